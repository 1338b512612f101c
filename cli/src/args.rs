//! The command line (clap derive). Option values are kept as small enums so
//! that EG can add `--scheme eg` and a `spectrum` subcommand without touching
//! the existing ones.

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// The command line of `capdiv`.
#[derive(Debug, Parser)]
#[command(
    name = "capdiv",
    version,
    about = "Smooth subdivision caps: C²PS polar subdivision (JSON in, JSON/OBJ/PNG out)",
    after_help = "Every failure prints one line 'error: …' on stderr and exits with status 2."
)]
pub struct Cli {
    /// The command to run.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Refine a configuration M steps and print the level-M configuration.
    Refine(RefineArgs),
    /// Print the limit point, eigencoefficients, normal and curvatures at the pole.
    Pole(PoleArgs),
    /// Print every Bézier patch from level 0 through ring M (JSON, OBJ or PNG).
    Patches(PatchesArgs),
    /// Refine built-in sample surfaces, write OBJ/PNG/JSON files, print a summary.
    Demo(DemoArgs),
}

/// Subdivision scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Scheme {
    /// C²PS, the valence doubles every step (spec C2PS.md §2).
    C2ps,
    /// RTS, the stationary auxiliary scheme, valence kept (spec C2PS.md §3).
    Rts,
}

/// Scalar type of the computation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Precision {
    /// 64-bit floating point.
    F64,
    /// 32-bit floating point.
    F32,
}

/// Rule for the 2-link in the first C²PS step (spec C2PS.md §2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FirstStepArg {
    /// The paper's §6 variant (the pole stands in for link 0).
    Uniform,
    /// Rules (1)–(3) in the first step too.
    Plain,
}

impl From<FirstStepArg> for capdiv::FirstStep {
    fn from(f: FirstStepArg) -> Self {
        match f {
            FirstStepArg::Uniform => capdiv::FirstStep::Uniform,
            FirstStepArg::Plain => capdiv::FirstStep::Plain,
        }
    }
}

/// Patch output format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum PatchFormat {
    /// `[{"level", "degree", "points"}]`.
    Json,
    /// A Wavefront OBJ mesh tessellated from the patches.
    Obj,
    /// A shaded PNG preview of that mesh (binary: use with `-o`).
    Png,
}

/// Where the input comes from and where the output goes.
#[derive(Clone, Debug, Args)]
pub struct Io {
    /// Input JSON file, `-` for standard input.
    #[arg(value_name = "FILE")]
    pub file: String,
    /// Write the output to this file (atomically) instead of standard output.
    #[arg(short, long, value_name = "PATH")]
    pub output: Option<PathBuf>,
}

/// `capdiv refine`.
#[derive(Clone, Debug, Args)]
pub struct RefineArgs {
    /// Subdivision scheme.
    #[arg(long, value_enum, default_value_t = Scheme::C2ps)]
    pub scheme: Scheme,
    /// Number of steps M.
    #[arg(long, default_value_t = 1, value_name = "M")]
    pub steps: u32,
    /// Scalar type of the computation and of the printed numbers.
    #[arg(long, value_enum, default_value_t = Precision::F64)]
    pub precision: Precision,
    /// First-step rule for the 2-link (C²PS only) [default: uniform].
    #[arg(long, value_enum)]
    pub first_step: Option<FirstStepArg>,
    /// Pretty-print the JSON.
    #[arg(long)]
    pub pretty: bool,
    /// Input and output.
    #[command(flatten)]
    pub io: Io,
}

/// `capdiv pole`.
#[derive(Clone, Debug, Args)]
pub struct PoleArgs {
    /// Scalar type of the computation and of the printed numbers.
    #[arg(long, value_enum, default_value_t = Precision::F64)]
    pub precision: Precision,
    /// Pretty-print the JSON.
    #[arg(long)]
    pub pretty: bool,
    /// Input and output.
    #[command(flatten)]
    pub io: Io,
}

/// `capdiv patches`.
#[derive(Clone, Debug, Args)]
pub struct PatchesArgs {
    /// Deepest ring level M (a ring needs 5 links: with 2 input links rings
    /// start at level 2, with 3 or 4 at level 1).
    #[arg(long, value_name = "M")]
    pub depth: u32,
    /// Output format.
    #[arg(long, value_enum, default_value_t = PatchFormat::Json)]
    pub format: PatchFormat,
    /// OBJ and PNG: grid segments per patch side.
    #[arg(long, default_value_t = 4, value_name = "G",
          value_parser = clap::value_parser!(u32).range(1..=64))]
    pub grid: u32,
    /// Scalar type of the computation and of the printed numbers.
    #[arg(long, value_enum, default_value_t = Precision::F64)]
    pub precision: Precision,
    /// First-step rule for the 2-link.
    #[arg(long, value_enum, default_value_t = FirstStepArg::Uniform)]
    pub first_step: FirstStepArg,
    /// Pretty-print the JSON.
    #[arg(long)]
    pub pretty: bool,
    /// Input and output.
    #[command(flatten)]
    pub io: Io,
}

/// `capdiv demo`.
#[derive(Clone, Debug, Args)]
pub struct DemoArgs {
    /// Directory for the OBJ and JSON files (created if missing).
    #[arg(long, default_value = "out", value_name = "DIR")]
    pub out: PathBuf,
}
