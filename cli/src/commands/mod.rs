//! Command dispatch: one module per subcommand. Each command reads and parses
//! its input, runs the kernel in the precision asked for, and returns its whole
//! output as an [`Outcome`]; nothing is written before the command succeeded.
//!
//! `refine`, `pole` and `patches` dispatch on the input's `kind`: the polar
//! steps are in [`polar`], the EG ones in [`eg`]; `spectrum` takes no input
//! net (a valence and optionally a rule table); `surface` takes a whole mesh
//! (`kind: "mesh"` JSON or Wavefront OBJ) through `capdiv_mesh`.

pub mod compare;
pub mod curvature;
pub mod demo;
pub mod eg;
pub mod patches;
pub mod polar;
pub mod pole;
pub mod refine;
pub mod render;
pub mod spectrum;
pub mod surface;
pub mod surface_stream;

use crate::args::Command;
use crate::error::CliError;
use crate::output::Sink;

/// A command's complete output and where it goes.
#[derive(Debug)]
pub struct Outcome {
    /// The bytes to write.
    pub bytes: Vec<u8>,
    /// Where to write them.
    pub sink: Sink,
    /// A human-readable report for stderr, printed after the output has been
    /// written (empty: nothing is printed). Never starts with `error:`.
    pub report: String,
}

impl Outcome {
    /// An outcome without a report.
    pub fn new(bytes: Vec<u8>, sink: Sink) -> Self {
        Outcome {
            bytes,
            sink,
            report: String::new(),
        }
    }

    /// Writes the output in one piece, then the report (if any) on stderr.
    pub fn write(&self) -> Result<(), CliError> {
        self.sink.write(&self.bytes)?;
        if !self.report.is_empty() {
            use std::io::Write;
            let mut err = std::io::stderr().lock();
            let _ = err.write_all(self.report.as_bytes());
            let _ = err.flush();
        }
        Ok(())
    }
}

/// Runs one subcommand.
pub fn run(command: Command) -> Result<Outcome, CliError> {
    match command {
        Command::Refine(a) => refine::run(&a),
        Command::Pole(a) => pole::run(&a),
        Command::Patches(a) => patches::run(&a),
        Command::Spectrum(a) => spectrum::run(&a),
        Command::Surface(a) => surface::run(&a),
        Command::Demo(a) => demo::run(&a),
        Command::Curvature(a) => curvature::run(&a),
        Command::Render(a) => render::run(&a),
        Command::Compare(a) => compare::run(&a),
    }
}
