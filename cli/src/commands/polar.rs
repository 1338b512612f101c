//! Shared steps of the commands on polar configurations: converting the
//! parsed input to the working precision and reading an input file.

use crate::error::CliError;
use crate::input::{PolarInput, Source};
use crate::Scalar;

/// A polar configuration in the working precision.
#[derive(Clone, Debug)]
pub struct Config<R> {
    /// The pole.
    pub pole: [R; 3],
    /// Links 1, 2, ….
    pub links: Vec<Vec<[R; 3]>>,
}

impl<R: Scalar> Config<R> {
    /// Rounds the input to `R` (`f64` → `f32` rounds once per coordinate;
    /// values beyond the `f32` range become infinite and are refused by the
    /// kernel as non-finite).
    pub fn of(input: &PolarInput) -> Self {
        let p = |q: &[f64; 3]| q.map(R::from_f64);
        Config {
            pole: p(&input.pole),
            links: input
                .links
                .iter()
                .map(|l| l.iter().map(p).collect())
                .collect(),
        }
    }

    /// The valence `n` (length of the 1-link; 0 when there is none).
    pub fn valence(&self) -> usize {
        self.links.first().map_or(0, Vec::len)
    }
}

/// Reads and parses `file` (`-` = stdin) and takes its polar configuration
/// (`who` names the command in the error for other kinds). Returns the
/// input's display name with it.
pub fn read_polar(file: &str, who: &str) -> Result<(String, PolarInput), CliError> {
    let source = Source::read(file)?;
    let input = source.parse()?.into_polar(&source.name, who)?;
    Ok((source.name, input))
}
