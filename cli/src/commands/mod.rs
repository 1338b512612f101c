//! Command dispatch: one module per subcommand. Each command reads and parses
//! its input, runs the kernel in the precision asked for, and returns its whole
//! output as an [`Outcome`]; nothing is written before the command succeeded.
//!
//! `refine`, `pole` and `patches` dispatch on the input's `kind`: the polar
//! steps are in [`polar`], the EG ones in [`eg`]; `spectrum` takes no input
//! net (a valence and optionally a rule table).

pub mod demo;
pub mod eg;
pub mod patches;
pub mod polar;
pub mod pole;
pub mod refine;
pub mod spectrum;

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
}

impl Outcome {
    /// Writes the output in one piece.
    pub fn write(&self) -> Result<(), CliError> {
        self.sink.write(&self.bytes)
    }
}

/// Runs one subcommand.
pub fn run(command: Command) -> Result<Outcome, CliError> {
    match command {
        Command::Refine(a) => refine::run(&a),
        Command::Pole(a) => pole::run(&a),
        Command::Patches(a) => patches::run(&a),
        Command::Spectrum(a) => spectrum::run(&a),
        Command::Demo(a) => demo::run(&a),
    }
}
