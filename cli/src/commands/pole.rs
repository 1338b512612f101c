//! `capdiv pole`: the limit point at the center of the input.
//!
//! - `polar`: the eigencoefficients `p0..p5`, the limit point `p0`, the unit
//!   normal and the curvatures at the pole (docs/math/c2ps.md §4; kernel
//!   `PoleJet::of` and `PoleJet::geometry`);
//! - `cnet`: `{"limit"}`, `c0` by formula (3) (docs/math/eg.md §4, kernel
//!   `CNet::limit`);
//! - `dnet`: `{"limit"}`, its `c0` when given, else formula (4) (kernel
//!   `DNet::fitted_limit`). `c0` is the same at every level (EG keeps it).

use super::eg::{cnet, dnet_of};
use super::polar::Config;
use super::Outcome;
use crate::args::{PoleArgs, Precision};
use crate::error::CliError;
use crate::input::{Input, PolarInput, Source};
use crate::json::to_json;
use crate::net::HeapStorage;
use crate::output::{EgPoleOutput, PoleOutput, Sink};
use crate::Scalar;
use capdiv::PoleJet;

/// Runs the command.
pub fn run(args: &PoleArgs) -> Result<Outcome, CliError> {
    let source = Source::read(&args.io.file)?;
    let name = &source.name;
    let input = source.parse()?;
    let bytes = match (&input, args.precision) {
        (Input::Polar(p), Precision::F64) => to_json(&pole::<f64>(name, p)?, args.pretty),
        (Input::Polar(p), Precision::F32) => to_json(&pole::<f32>(name, p)?, args.pretty),
        (_, Precision::F64) => to_json(&eg_limit::<f64>(name, &input)?, args.pretty),
        (_, Precision::F32) => to_json(&eg_limit::<f32>(name, &input)?, args.pretty),
    };
    Ok(Outcome::new(
        bytes,
        Sink::from_option(args.io.output.clone()),
    ))
}

/// The limit point `c0` of a `cnet` (formula (3)) or `dnet` (given `c0`, else
/// formula (4)) input (docs/math/eg.md §4).
pub fn eg_limit<R: Scalar>(name: &str, input: &Input) -> Result<EgPoleOutput<R>, CliError> {
    let limit = match input {
        Input::Cnet(c) => cnet::<R>(name, c)?.limit(),
        Input::Dnet(d) => dnet_of::<R>(name, d)?.c0(),
        Input::Polar(_) | Input::Mesh(_) => {
            return Err(CliError::WrongKind {
                source: name.to_string(),
                kind: input.kind(),
                need: "the EG limit point needs a 'cnet' or 'dnet' input".into(),
            })
        }
    };
    if !limit.is_finite() {
        return Err(CliError::NonFiniteResult {
            source: name.to_string(),
        });
    }
    Ok(EgPoleOutput { limit: limit.0 })
}

/// Jet and geometry at the pole of `input`. A degenerate tangent plane
/// (`p1 × p2 = 0`) is the kernel's `Degenerate` error.
pub fn pole<R: Scalar>(name: &str, input: &PolarInput) -> Result<PoleOutput<R>, CliError> {
    let config = Config::<R>::of(input);
    let n = config.valence();
    let out = Job {
        name,
        config: &config,
    }
    .run(HeapStorage::for_valence(Some(n), || {
        format!("valence {n}")
    })?)?;
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

impl<R: Scalar> Job<'_, R> {
    fn run(self, storage: HeapStorage<R>) -> Result<PoleOutput<R>, CliError> {
        let kernel = |e| CliError::kernel(self.name, e);
        let net = storage
            .net(self.config.pole, &self.config.links)
            .map_err(kernel)?;
        let jet = PoleJet::of(&net);
        let geometry = jet.geometry().map_err(kernel)?;
        Ok(PoleOutput::new(&jet, &geometry))
    }
}
