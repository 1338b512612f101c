//! Command dispatch: one module per subcommand. Each command reads and parses
//! its input, runs the kernel in the precision asked for, and returns its whole
//! output as an [`Outcome`]; nothing is written before the command succeeded.
//!
//! Adding EG: a `cnet`/`dnet` arm in the commands that take a configuration
//! (today they call [`crate::input::Input::into_polar`], which refuses other
//! kinds), `Scheme::Eg` in [`crate::args`], and a `spectrum` module here.

pub mod demo;
pub mod patches;
pub mod polar;
pub mod pole;
pub mod refine;

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
        Command::Demo(a) => demo::run(&a),
    }
}
