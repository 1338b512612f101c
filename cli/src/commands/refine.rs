//! `capdiv refine`: M steps of C²PS (spec C2PS.md §2) or RTS (§3); prints the
//! level-M configuration in the input schema.
//!
//! The kernel keeps links 1..5 (what one surface ring needs, §5), so the
//! output holds at most 5 links; links beyond the 5th only shape the level-0
//! outer region. With 2 input links the output has 3 after one step and 5
//! after two (old links up to K give new links up to 2K−1, §2).

use super::polar::{read_polar, Config};
use super::Outcome;
use crate::args::{FirstStepArg, Precision, RefineArgs, Scheme};
use crate::capacity::{dispatch, valence_after, NetJob};
use crate::error::CliError;
use crate::input::PolarInput;
use crate::output::{to_json, PolarOutput, Sink};
use crate::Scalar;
use capdiv::{FirstStep, PolarNet};

/// Runs the command.
pub fn run(args: &RefineArgs) -> Result<Outcome, CliError> {
    if args.scheme == Scheme::Rts && args.first_step.is_some() {
        return Err(CliError::Usage(
            "--first-step applies to --scheme c2ps only".into(),
        ));
    }
    let first = args.first_step.unwrap_or(FirstStepArg::Uniform).into();
    let (name, input) = read_polar(&args.io.file)?;
    let bytes = match args.precision {
        Precision::F64 => to_json(
            &refine::<f64>(&name, &input, args.scheme, args.steps, first)?,
            args.pretty,
        ),
        Precision::F32 => to_json(
            &refine::<f32>(&name, &input, args.scheme, args.steps, first)?,
            args.pretty,
        ),
    };
    Ok(Outcome {
        bytes,
        sink: Sink::from_option(args.io.output.clone()),
    })
}

/// The level-`steps` configuration of `input` (`name` for messages).
pub fn refine<R: Scalar>(
    name: &str,
    input: &PolarInput,
    scheme: Scheme,
    steps: u32,
    first: FirstStep,
) -> Result<PolarOutput<R>, CliError> {
    let config = Config::<R>::of(input);
    let n = config.valence();
    let needed = match scheme {
        Scheme::C2ps => valence_after(n, steps),
        Scheme::Rts => Some(n),
    };
    let out = dispatch(
        needed,
        || format!("valence n·2^M = {n}·2^{steps}"),
        Job {
            name,
            config: &config,
            scheme,
            steps,
            first,
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
    scheme: Scheme,
    steps: u32,
    first: FirstStep,
}

impl<R: Scalar> NetJob<R> for Job<'_, R> {
    type Output = PolarOutput<R>;
    fn run<const CAP: usize>(self) -> Result<PolarOutput<R>, CliError> {
        let kernel = |e| CliError::kernel(self.name, e);
        let mut net =
            PolarNet::<R, CAP>::new(self.config.pole, &self.config.links).map_err(kernel)?;
        for _ in 0..self.steps {
            match self.scheme {
                Scheme::C2ps => net.step(self.first).map_err(kernel)?,
                Scheme::Rts => net.rts_step(),
            }
        }
        Ok(PolarOutput::of(&net))
    }
}
