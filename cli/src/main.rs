//! The `capdiv` binary: parses the command line, runs the command, then
//! writes the output in one piece.
//!
//! Every failure prints exactly one line `error: …` on stderr, nothing on
//! stdout, and exits with status 2.

use capdiv_cli::args::Cli;
use capdiv_cli::commands;
use capdiv_cli::error::{CliError, EXIT_FAILURE};
use clap::error::ErrorKind;
use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage(e),
    };
    // A panic would be a bug; keep even that to one line.
    std::panic::set_hook(Box::new(|info| {
        let msg = info.to_string().replace('\n', " ");
        eprintln!("error: internal error: {msg}");
    }));
    let outcome = commands::run(cli.command);
    match outcome.and_then(|o| o.write()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{}", e.line());
            ExitCode::from(EXIT_FAILURE as u8)
        }
    }
}

/// Help and version go to stdout (status 0); a bare `capdiv` prints the help
/// on stderr; every other command-line error is one line.
fn usage(e: clap::Error) -> ExitCode {
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = e.print();
            ExitCode::SUCCESS
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            ExitCode::from(EXIT_FAILURE as u8)
        }
        _ => {
            // clap's message runs up to the first blank line (then usage and
            // tips follow); fold it into one line.
            let rendered = e.render().to_string();
            let message: Vec<&str> = rendered
                .lines()
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            let message = message.join(" ");
            let message = message.strip_prefix("error: ").unwrap_or(&message);
            let err = CliError::Usage(format!("{message} (see 'capdiv --help')"));
            eprintln!("{}", err.line());
            ExitCode::from(EXIT_FAILURE as u8)
        }
    }
}
