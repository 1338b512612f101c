//! `capdiv refine`: M steps of C²PS (docs/math/c2ps.md §2), RTS (§3) or EG
//! (docs/math/eg.md §5, §6); prints the level-M configuration in the input schema
//! (EG: always as a `dnet`, with its `c0`).
//!
//! The scheme defaults to the input's kind: `polar` → C²PS, `cnet`/`dnet` →
//! EG; a scheme that does not fit the kind is an error. EG keeps the valence;
//! see [`super::eg`] for the rules per valence (n = 4: regular rules).
//!
//! The kernel keeps links 1..5 (what one surface ring needs, §5), so the
//! output holds at most 5 links; links beyond the 5th only shape the level-0
//! outer region. With 2 input links the output has 3 after one step and 5
//! after two (old links up to K give new links up to 2K−1, §2).

use super::eg::{dnet, read_table, subdivision};
use super::polar::Config;
use super::Outcome;
use crate::args::{FirstStepArg, Precision, RefineArgs, Scheme};
use crate::error::CliError;
use crate::input::{EgInput, Input, PolarInput, Source};
use crate::json::to_json;
use crate::net::{valence_after, HeapStorage};
use crate::output::{DnetOutput, PolarOutput, Sink};
use crate::table::Table;
use crate::Scalar;
use capdiv::FirstStep;

/// The option combinations a scheme refuses (checked before and after the
/// input decides the default scheme).
fn check_options(args: &RefineArgs, scheme: Scheme) -> Result<(), CliError> {
    if scheme != Scheme::C2ps && args.first_step.is_some() {
        return Err(CliError::Usage(
            "--first-step applies to --scheme c2ps only".into(),
        ));
    }
    if scheme != Scheme::Eg && args.table.is_some() {
        return Err(CliError::Usage(
            "--table applies to --scheme eg only".into(),
        ));
    }
    Ok(())
}

/// Runs the command.
pub fn run(args: &RefineArgs) -> Result<Outcome, CliError> {
    if let Some(scheme) = args.scheme {
        check_options(args, scheme)?;
    }
    let source = Source::read(&args.io.file)?;
    let name = source.name.clone();
    let input = source.parse()?;
    let scheme = args.scheme.unwrap_or(match input {
        Input::Polar(_) => Scheme::C2ps,
        Input::Cnet(_) | Input::Dnet(_) | Input::Mesh(_) => Scheme::Eg,
    });
    check_options(args, scheme)?;
    let who = format!("--scheme {}", scheme.name());
    let bytes = if scheme == Scheme::Eg {
        let input = input.into_eg(&name, &who)?;
        let table = read_table(args.table.as_deref())?;
        let table = table.as_ref();
        match args.precision {
            Precision::F64 => to_json(
                &refine_eg::<f64>(&name, &input, args.steps, table)?,
                args.pretty,
            ),
            Precision::F32 => to_json(
                &refine_eg::<f32>(&name, &input, args.steps, table)?,
                args.pretty,
            ),
        }
    } else {
        let input = input.into_polar(&name, &who)?;
        let first = args.first_step.unwrap_or(FirstStepArg::Uniform).into();
        match args.precision {
            Precision::F64 => to_json(
                &refine::<f64>(&name, &input, scheme, args.steps, first)?,
                args.pretty,
            ),
            Precision::F32 => to_json(
                &refine::<f32>(&name, &input, scheme, args.steps, first)?,
                args.pretty,
            ),
        }
    };
    Ok(Outcome::new(
        bytes,
        Sink::from_option(args.io.output.clone()),
    ))
}

/// The level-`steps` d-net of an EG input (docs/math/eg.md §5, §6; `c0` fixed),
/// with the user's table when given. `steps = 0` without a table needs no
/// rule: it prints the d-net (a c-net's degree raising, §3) for any valence
/// 3..=10.
pub fn refine_eg<R: Scalar>(
    name: &str,
    input: &EgInput,
    steps: u32,
    table: Option<&Table>,
) -> Result<DnetOutput<R>, CliError> {
    let out = if steps == 0 && table.is_none() {
        // No step, no rule needed: the d-net itself (any valence 3..=10).
        DnetOutput::of(&dnet::<R>(name, input)?)
    } else {
        let mut eg = subdivision::<R>(name, input, table)?;
        for _ in 0..steps {
            eg.step().map_err(|e| CliError::kernel(name, e))?;
        }
        DnetOutput::of(eg.net())
    };
    if !out.is_finite() {
        return Err(CliError::NonFiniteResult {
            source: name.to_string(),
        });
    }
    Ok(out)
}

/// The level-`steps` configuration of `input` (`name` for messages).
pub fn refine<R: Scalar>(
    name: &str,
    input: &PolarInput,
    scheme: Scheme,
    steps: u32,
    first: FirstStep,
) -> Result<PolarOutput<R>, CliError> {
    if scheme == Scheme::Eg {
        return Err(CliError::WrongKind {
            source: name.to_string(),
            kind: "polar",
            need: "--scheme eg needs a 'cnet' or 'dnet' input".into(),
        });
    }
    let config = Config::<R>::of(input);
    let n = config.valence();
    let needed = match scheme {
        Scheme::C2ps => valence_after(n, steps),
        Scheme::Rts | Scheme::Eg => Some(n),
    };
    let out = Job {
        name,
        config: &config,
        scheme,
        steps,
        first,
    }
    .run(HeapStorage::for_valence(needed, || {
        format!("valence n·2^M = {n}·2^{steps}")
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
    scheme: Scheme,
    steps: u32,
    first: FirstStep,
}

impl<R: Scalar> Job<'_, R> {
    fn run(self, storage: HeapStorage<R>) -> Result<PolarOutput<R>, CliError> {
        let kernel = |e| CliError::kernel(self.name, e);
        let mut net = storage
            .net(self.config.pole, &self.config.links)
            .map_err(kernel)?;
        for _ in 0..self.steps {
            match self.scheme {
                Scheme::C2ps => net.step(self.first).map_err(kernel)?,
                // Eg is refused by `refine` before the job starts.
                Scheme::Rts | Scheme::Eg => net.rts_step().map_err(kernel)?,
            }
        }
        Ok(PolarOutput::of(&net))
    }
}
