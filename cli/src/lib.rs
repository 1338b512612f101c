//! `capdiv-cli`: the command-line front end of the `capdiv` kernel.
//!
//! Data flows one way through small modules, one job each:
//!
//! - [`args`]: the command line (clap derive);
//! - [`input`]: reading a source (file or `-`) and parsing the JSON input,
//!   dispatched on its `kind` tag (`polar` for C²PS, `cnet` and `dnet` for
//!   EG, `mesh` for `capdiv surface`, which also reads Wavefront OBJ);
//! - [`table`]: user rule tables for EG (`--table FILE`);
//! - [`net`]: polar nets on heap storage sized for the valence a job
//!   reaches (docs/math/c2ps.md §1: level `m` has valence `n·2^m`);
//! - [`commands`]: one module per subcommand, each producing its output in
//!   memory;
//! - [`json`]: JSON text, compact or re-indented, into fallibly growing
//!   buffers, with lists serialised as they are made;
//! - [`output`]: the serialisable output types and the all-or-nothing writers
//!   (stdout, or a file written through a temporary file and a rename);
//! - [`export`]: exchange formats of a whole surface (glTF 2.0, STEP);
//! - [`render`]: a tessellation (`capdiv_mesh::tessellate`) as a shaded PNG
//!   preview;
//! - [`raster`]: the one triangle rasteriser (z-buffer, supersampling) of
//!   [`render`] and [`picture`];
//! - [`picture`]: shapes shaded per pixel from the exact patches (highlight
//!   lines, curvature maps with legends), one panel per scheme;
//! - [`camera`]: the pictures' view (azimuth, elevation, up axis) and its
//!   map to pixels, fitted or framed on a focus;
//! - [`focus`]: `--focus V`, the neighbourhood of a vertex's cap a zoomed
//!   picture frames;
//! - [`glyphs`]: text in pictures;
//! - [`stripes`]: highlight lines set up relative to the view and
//!   anti-aliased;
//! - [`samples`]: analytic sample configurations for `capdiv demo`;
//! - [`shape`]: every input under every scheme as ring patches with levels
//!   and hole edges (`render`, `compare`, `curvature`);
//! - [`text`]: counts and measured numbers in human-readable text;
//! - [`error`]: the one-line error type (every failure exits with status 2).

pub mod args;
pub mod camera;
pub mod commands;
pub mod error;
pub mod export;
pub mod focus;
pub mod glyphs;
pub mod input;
pub mod json;
pub mod net;
pub mod output;
pub mod picture;
pub mod raster;
pub mod render;
pub mod samples;
pub mod shape;
pub mod stripes;
pub mod table;
pub mod text;
pub mod threads;

pub use error::CliError;

/// Coordinates the CLI computes in and prints: `f32` or `f64`.
///
/// `Display`, `LowerExp` and `Serialize` of both print the shortest
/// representation that round-trips, so JSON and OBJ output can be read back
/// exactly.
pub trait Scalar:
    capdiv::Real + serde::Serialize + core::fmt::Display + core::fmt::LowerExp + Send + Sync
{
}
impl<T> Scalar for T where
    T: capdiv::Real + serde::Serialize + core::fmt::Display + core::fmt::LowerExp + Send + Sync
{
}
