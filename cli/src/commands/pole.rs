//! `capdiv pole`: the eigencoefficients `p0..p5` of the input configuration,
//! the limit point `p0`, the unit normal and the curvatures at the pole (spec
//! C2PS.md §4; kernel `PoleJet::of` and `PoleJet::geometry`).

use super::polar::{read_polar, Config};
use super::Outcome;
use crate::args::{PoleArgs, Precision};
use crate::capacity::{dispatch, NetJob};
use crate::error::CliError;
use crate::input::PolarInput;
use crate::output::{to_json, PoleOutput, Sink};
use crate::Scalar;
use capdiv::{PolarNet, PoleJet};

/// Runs the command.
pub fn run(args: &PoleArgs) -> Result<Outcome, CliError> {
    let (name, input) = read_polar(&args.io.file)?;
    let bytes = match args.precision {
        Precision::F64 => to_json(&pole::<f64>(&name, &input)?, args.pretty),
        Precision::F32 => to_json(&pole::<f32>(&name, &input)?, args.pretty),
    };
    Ok(Outcome {
        bytes,
        sink: Sink::from_option(args.io.output.clone()),
    })
}

/// Jet and geometry at the pole of `input`. A degenerate tangent plane
/// (`p1 × p2 = 0`) is the kernel's `Degenerate` error.
pub fn pole<R: Scalar>(name: &str, input: &PolarInput) -> Result<PoleOutput<R>, CliError> {
    let config = Config::<R>::of(input);
    let n = config.valence();
    let out = dispatch(
        Some(n),
        || format!("valence {n}"),
        Job {
            name,
            config: &config,
        },
    )?;
    if !out.is_finite() {
        return Err(CliError::NonFiniteResult {
            source: name.to_string(),
        });
    }
    Ok(out)
}

struct Job<'a, R> {
    name: &'a str,
    config: &'a Config<R>,
}

impl<R: Scalar> NetJob<R> for Job<'_, R> {
    type Output = PoleOutput<R>;
    fn run<const CAP: usize>(self) -> Result<PoleOutput<R>, CliError> {
        let kernel = |e| CliError::kernel(self.name, e);
        let net = PolarNet::<R, CAP>::new(self.config.pole, &self.config.links).map_err(kernel)?;
        let jet = PoleJet::of(&net);
        let geometry = jet.geometry().map_err(kernel)?;
        Ok(PoleOutput::new(&jet, &geometry))
    }
}
