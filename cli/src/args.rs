//! The command line (clap derive). Option values are small enums; the scheme
//! is optional and defaults to the one the input's `kind` calls for (`polar` →
//! C²PS, `cnet`/`dnet` → EG).

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// The command line of `capdiv`.
#[derive(Debug, Parser)]
#[command(
    name = "capdiv",
    version,
    about = "Smooth subdivision caps: C²PS polar and EG (Evolving Guide) subdivision \
             (JSON in, JSON/OBJ/PNG out)",
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
    /// Print the limit point (polar: also eigencoefficients, normal, curvatures).
    Pole(PoleArgs),
    /// Print the Bézier patches through ring M (JSON, OBJ or PNG).
    Patches(PatchesArgs),
    /// Print the spectrum of the EG subdivision matrix of a valence.
    Spectrum(SpectrumArgs),
    /// Turn a whole mesh (OBJ or JSON) into a smooth surface: patches and caps
    /// as JSON, or a welded OBJ / PNG.
    Surface(SurfaceArgs),
    /// Refine built-in sample surfaces, write OBJ/PNG/JSON files, print a summary.
    Demo(DemoArgs),
    /// Draw the surface as a PNG: plain shading, highlight lines, or Gaussian
    /// or mean curvature maps computed per pixel from the exact patches.
    Render(RenderArgs),
    /// Draw the input under every scheme that applies, side by side, same
    /// view and colour scale (PNG).
    Compare(CompareArgs),
    /// Print per ring level the extremes of Gaussian and mean curvature and
    /// the limit values at the centre (JSON).
    Curvature(CurvatureArgs),
}

/// Subdivision scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Scheme {
    /// C²PS, the valence doubles every step (docs/math/c2ps.md §2).
    C2ps,
    /// RTS, the stationary auxiliary scheme, valence kept (docs/math/c2ps.md §3).
    Rts,
    /// EG, Evolving Guide subdivision of a c-net or d-net (docs/math/eg.md §5, §6).
    Eg,
}

impl Scheme {
    /// The name as written on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Scheme::C2ps => "c2ps",
            Scheme::Rts => "rts",
            Scheme::Eg => "eg",
        }
    }
}

/// Scheme of `render`, `compare`, `curvature`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ShapeScheme {
    /// C²PS (polar inputs; for meshes: the mesh pipeline's default, C²PS at
    /// poles and EG at extraordinary points).
    C2ps,
    /// RTS (polar inputs).
    Rts,
    /// EG (c-nets and d-nets; for meshes the same as c2ps).
    Eg,
    /// Catmull-Clark caps everywhere (polar, c-net and mesh inputs).
    CatmullClark,
}

impl ShapeScheme {
    /// The name as written on the command line.
    pub fn name(self) -> &'static str {
        match self {
            ShapeScheme::C2ps => "c2ps",
            ShapeScheme::Rts => "rts",
            ShapeScheme::Eg => "eg",
            ShapeScheme::CatmullClark => "catmull-clark",
        }
    }
}

/// Boundary rule of a mesh (OpenSubdiv's `VtxBoundaryInterpolation`),
/// overriding the one the mesh file gives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum BoundaryArg {
    /// Faces with a boundary vertex are holes.
    None,
    /// Boundary edges infinitely sharp.
    EdgeOnly,
    /// Boundary edges infinitely sharp, vertices with one face infinitely
    /// sharp corners.
    EdgeAndCorner,
}

impl From<BoundaryArg> for capdiv_mesh::BoundaryInterpolation {
    fn from(b: BoundaryArg) -> Self {
        match b {
            BoundaryArg::None => capdiv_mesh::BoundaryInterpolation::None,
            BoundaryArg::EdgeOnly => capdiv_mesh::BoundaryInterpolation::EdgeOnly,
            BoundaryArg::EdgeAndCorner => capdiv_mesh::BoundaryInterpolation::EdgeAndCorner,
        }
    }
}

/// Scheme of `surface`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SurfaceScheme {
    /// C²PS at poles, EG at extraordinary points of valence 3 and 5,
    /// Catmull-Clark caps elsewhere.
    Default,
    /// Catmull-Clark caps everywhere (`PlanOptions::catmull_clark`, as
    /// `render --scheme catmull-clark` on a mesh).
    CatmullClark,
}

impl SurfaceScheme {
    /// The name as written on the command line.
    pub fn name(self) -> &'static str {
        match self {
            SurfaceScheme::Default => "default",
            SurfaceScheme::CatmullClark => "catmull-clark",
        }
    }
}

/// Shading of `render` and `compare`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Shade {
    /// Lambert shading of the exact normal, rings in alternating colours.
    Plain,
    /// Highlight lines (Beier & Chen 1994) from the exact normal.
    Highlight,
    /// Gaussian curvature colour map with a legend.
    Gauss,
    /// Mean curvature colour map with a legend.
    Mean,
}

/// The default ring depth of `surface`, `render` and `compare`.
pub const DEFAULT_DEPTH: u32 = 4;

/// The default `--max-patches` of `surface` (also the limit of `render` and
/// `compare`): all patches are held in memory, a few KB each, so two
/// million is several GB.
pub const DEFAULT_MAX_PATCHES: u64 = 2_000_000;

/// The default `--max-patches` of `surface` output written as it is made
/// (OBJ in f64, compact JSON): memory does not grow with the patches, time
/// does (about a microsecond a patch, several for OBJ), and files by about
/// 1 KB a patch as JSON, 3 KB as OBJ at grid 4: 5e7 patches is an hour and
/// 50–150 GB.
pub const DEFAULT_MAX_STREAMED_PATCHES: u64 = 50_000_000;

/// The default picture size of `render` and `compare` (per panel), and of
/// `surface --format png`.
pub const DEFAULT_SIZE: &str = "800x600";

/// The world axis that points up in a picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum UpArg {
    /// `+z` up (azimuth in the xy-plane from `+x` towards `+y`).
    Z,
    /// `+y` up (azimuth in the zx-plane from `+x` towards `−z`).
    Y,
}

impl From<UpArg> for crate::camera::Up {
    fn from(u: UpArg) -> Self {
        match u {
            UpArg::Z => crate::camera::Up::Z,
            UpArg::Y => crate::camera::Up::Y,
        }
    }
}

/// Picture options shared by `render` and `compare`.
#[derive(Clone, Debug, Args)]
pub struct PictureArgs {
    /// Shading.
    #[arg(long, value_enum, default_value_t = Shade::Plain)]
    pub shade: Shade,
    /// Highlight lines: light-line spacings across the picture's height
    /// (a flat region facing the light shows this many stripes, whatever the
    /// zoom; curved regions more).
    #[arg(long, default_value_t = 10.0, value_name = "N", value_parser = parse_lines)]
    pub lines: f64,
    /// Highlight lines: direction from the surface to the light plane, `X,Y,Z`
    /// [default: towards the camera].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_light, allow_hyphen_values = true)]
    pub light: Option<[f64; 3]>,
    /// Frame the neighbourhood of vertex V's cap, V numbered as the input
    /// numbers it (OBJ: from 1; JSON mesh: from 0; polar net, c-net, d-net:
    /// 0, the pole or centre).
    #[arg(long, value_name = "V")]
    pub focus: Option<usize>,
    /// With --focus: magnification; at 1 the picture's shorter side spans
    /// the vertex's 1-ring (twice its longest edge).
    #[arg(long, default_value_t = crate::focus::DEFAULT_ZOOM, value_name = "Z",
          value_parser = parse_zoom, requires = "focus")]
    pub zoom: f64,
    /// The world axis pointing up in the picture; `--view`'s azimuth turns
    /// about it, its elevation rises towards it.
    #[arg(long, value_enum, default_value_t = UpArg::Z)]
    pub up: UpArg,
    /// Rings per cap (C²PS levels 0..M, EG/Catmull-Clark steps 1..M).
    #[arg(long, default_value_t = DEFAULT_DEPTH, value_name = "M",
          value_parser = clap::value_parser!(u32).range(0..=12))]
    pub depth: u32,
    /// Camera: azimuth and elevation in degrees, `AZ,EL`.
    #[arg(long, default_value = "-60,50", value_name = "AZ,EL",
          value_parser = parse_view, allow_hyphen_values = true)]
    pub view: (f64, f64),
    /// Image size in pixels (per panel for `compare`), `WxH`.
    #[arg(long, default_value = DEFAULT_SIZE, value_name = "WxH", value_parser = parse_size)]
    pub size: (usize, usize),
    /// Tessellation segments per patch side (shading is per pixel anyway).
    #[arg(long, default_value_t = 6, value_name = "G",
          value_parser = clap::value_parser!(u32).range(1..=32))]
    pub grid: u32,
    /// The input: polar, cnet, dnet or mesh JSON, or a Wavefront OBJ mesh;
    /// `-` for standard input.
    #[arg(value_name = "FILE")]
    pub file: String,
    /// The PNG file to write.
    #[arg(short, long, value_name = "PATH")]
    pub output: PathBuf,
    /// Meshes only: the boundary rule, overriding the file's [default: the
    /// file's, else edge-and-corner].
    #[arg(long, value_enum, value_name = "RULE")]
    pub boundary: Option<BoundaryArg>,
}

/// `capdiv render`.
#[derive(Clone, Debug, Args)]
pub struct RenderArgs {
    /// Scheme [default: c2ps for polar inputs and meshes, eg for c-nets and
    /// d-nets].
    #[arg(long, value_enum)]
    pub scheme: Option<ShapeScheme>,
    /// Picture options.
    #[command(flatten)]
    pub picture: PictureArgs,
}

/// `capdiv compare`.
#[derive(Clone, Debug, Args)]
pub struct CompareArgs {
    /// Picture options.
    #[command(flatten)]
    pub picture: PictureArgs,
}

/// `capdiv curvature`.
#[derive(Clone, Debug, Args)]
pub struct CurvatureArgs {
    /// Scheme [default: c2ps for polar inputs and meshes, eg for c-nets and
    /// d-nets].
    #[arg(long, value_enum)]
    pub scheme: Option<ShapeScheme>,
    /// Deepest ring level M.
    #[arg(long, default_value_t = 6, value_name = "M",
          value_parser = clap::value_parser!(u32).range(0..=14))]
    pub depth: u32,
    /// Samples per patch side (the extremes are taken over `(S+1)²` samples
    /// of every ring patch).
    #[arg(long, default_value_t = 8, value_name = "S",
          value_parser = clap::value_parser!(u32).range(1..=64))]
    pub samples: u32,
    /// Pretty-print the JSON.
    #[arg(long)]
    pub pretty: bool,
    /// Input and output.
    #[command(flatten)]
    pub io: Io,
}

fn parse_view(s: &str) -> Result<(f64, f64), String> {
    let bad = || format!("'{s}' is not AZIMUTH,ELEVATION in degrees (e.g. -60,50)");
    let (a, e) = s.split_once(',').ok_or_else(bad)?;
    let a: f64 = a.trim().parse().map_err(|_| bad())?;
    let e: f64 = e.trim().parse().map_err(|_| bad())?;
    if !a.is_finite() || !(-90.0..=90.0).contains(&e) {
        return Err(bad());
    }
    Ok((a, e))
}

fn parse_zoom(s: &str) -> Result<f64, String> {
    let bad = || format!("'{s}' is not a magnification in 0.1..=100000 (e.g. 4)");
    let z: f64 = s.trim().parse().map_err(|_| bad())?;
    if !(0.1..=100000.0).contains(&z) {
        return Err(bad());
    }
    Ok(z)
}

/// `surface --tolerance`: when a cap stops emitting rings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tolerance {
    /// Every cap emits `--depth` rings.
    None,
    /// Rings until the hole is at most this wide (the input's units).
    Absolute(f64),
    /// Rings until the hole is at most this fraction of the input's
    /// bounding-box diagonal.
    Relative(f64),
}

impl Tolerance {
    /// The absolute tolerance for a bounding-box diagonal `diagonal`.
    pub fn absolute(self, diagonal: f64) -> Option<f64> {
        match self {
            Tolerance::None => None,
            Tolerance::Absolute(t) => Some(t),
            Tolerance::Relative(r) => Some(r * diagonal),
        }
    }
}

impl std::fmt::Display for Tolerance {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Tolerance::None => f.write_str("none"),
            Tolerance::Absolute(t) => write!(f, "{t}"),
            Tolerance::Relative(r) => write!(f, "{r}rel"),
        }
    }
}

/// The default `surface --tolerance`: a cap's hole closes at 0.3 % of the
/// bounding-box diagonal (a fan over it deviates from the surface by about
/// the hole's curvature times its width, far below a pixel of a picture of
/// the whole mesh).
pub const DEFAULT_TOLERANCE: &str = "3e-3rel";

fn parse_tolerance(s: &str) -> Result<Tolerance, String> {
    let bad = || {
        format!(
            "'{s}' is not a tolerance: 'none', a width T > 0 (e.g. 0.01) or a fraction of the \
             bounding-box diagonal Trel (e.g. 3e-3rel)"
        )
    };
    let s = s.trim();
    if s == "none" {
        return Ok(Tolerance::None);
    }
    let (number, relative) = match s.strip_suffix("rel") {
        Some(n) => (n, true),
        None => (s, false),
    };
    let t: f64 = number.trim().parse().map_err(|_| bad())?;
    if !(t.is_finite() && t > 0.0) {
        return Err(bad());
    }
    Ok(if relative {
        Tolerance::Relative(t)
    } else {
        Tolerance::Absolute(t)
    })
}

fn parse_lines(s: &str) -> Result<f64, String> {
    let bad = || format!("'{s}' is not a number of light lines in 0.5..=2000 (e.g. 10)");
    let n: f64 = s.trim().parse().map_err(|_| bad())?;
    if !(0.5..=2000.0).contains(&n) {
        return Err(bad());
    }
    Ok(n)
}

fn parse_light(s: &str) -> Result<[f64; 3], String> {
    let bad =
        || format!("'{s}' is not a direction X,Y,Z of finite numbers, not all 0 (e.g. 0,-1,1)");
    let parts: Vec<&str> = s.split(',').collect();
    let [x, y, z] = parts.as_slice() else {
        return Err(bad());
    };
    let mut v = [0.0f64; 3];
    for (c, t) in v.iter_mut().zip([x, y, z]) {
        *c = t.trim().parse().map_err(|_| bad())?;
    }
    let big = v.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    if v.iter().any(|c| !c.is_finite()) || big == 0.0 {
        return Err(bad());
    }
    // Only the direction counts; scaled so its length is finite.
    Ok(v.map(|c| c / big))
}

fn parse_size(s: &str) -> Result<(usize, usize), String> {
    let bad = || format!("'{s}' is not WIDTHxHEIGHT with sides 64..=4096 (e.g. 800x600)");
    let (w, h) = s.split_once('x').ok_or_else(bad)?;
    let w: usize = w.trim().parse().map_err(|_| bad())?;
    let h: usize = h.trim().parse().map_err(|_| bad())?;
    if !(64..=4096).contains(&w) || !(64..=4096).contains(&h) {
        return Err(bad());
    }
    Ok((w, h))
}

/// Scalar type of the computation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Precision {
    /// 64-bit floating point.
    F64,
    /// 32-bit floating point.
    F32,
}

/// Rule for the 2-link in the first C²PS step (docs/math/c2ps.md §2).
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
    /// A shaded PNG preview of that mesh (binary: refused on a terminal,
    /// use `-o` or a redirection).
    Png,
}

impl PatchFormat {
    /// The format asked for, else the one `-o`'s extension names (`.json`,
    /// `.obj`, `.png`, any case), else JSON.
    pub fn resolve(explicit: Option<PatchFormat>, output: Option<&std::path::Path>) -> Self {
        explicit
            .or_else(|| {
                let ext = output?.extension()?.to_str()?.to_ascii_lowercase();
                match ext.as_str() {
                    "json" => Some(PatchFormat::Json),
                    "obj" => Some(PatchFormat::Obj),
                    "png" => Some(PatchFormat::Png),
                    _ => None,
                }
            })
            .unwrap_or(PatchFormat::Json)
    }
}

/// `capdiv surface` output format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SurfaceFormat {
    /// `{"patches", "caps", "summary"}`.
    Json,
    /// The welded tessellation as Wavefront OBJ.
    Obj,
    /// A shaded PNG preview of that mesh (binary: use with `-o`).
    Png,
    /// The welded tessellation as binary glTF 2.0 (use with `-o`).
    Glb,
    /// The welded tessellation as glTF 2.0 JSON, buffer embedded (base64).
    Gltf,
    /// The exact patches as a STEP (ISO 10303-21, AP214) B-rep for CAD.
    Step,
}

impl SurfaceFormat {
    /// The format asked for, else the one `-o`'s extension names (`.json`,
    /// `.obj`, `.png`, `.glb`, `.gltf`, `.step`, `.stp`, any case), else JSON.
    pub fn resolve(explicit: Option<SurfaceFormat>, output: Option<&std::path::Path>) -> Self {
        explicit
            .or_else(|| {
                let ext = output?.extension()?.to_str()?.to_ascii_lowercase();
                match ext.as_str() {
                    "json" => Some(SurfaceFormat::Json),
                    "obj" => Some(SurfaceFormat::Obj),
                    "png" => Some(SurfaceFormat::Png),
                    "glb" => Some(SurfaceFormat::Glb),
                    "gltf" => Some(SurfaceFormat::Gltf),
                    "step" | "stp" => Some(SurfaceFormat::Step),
                    _ => None,
                }
            })
            .unwrap_or(SurfaceFormat::Json)
    }
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
    /// Subdivision scheme [default: c2ps for a polar input, eg for a cnet or
    /// dnet input].
    #[arg(long, value_enum)]
    pub scheme: Option<Scheme>,
    /// Number of steps M.
    #[arg(long, default_value_t = 1, value_name = "M")]
    pub steps: u32,
    /// Scalar type of the computation and of the printed numbers.
    #[arg(long, value_enum, default_value_t = Precision::F64)]
    pub precision: Precision,
    /// First-step rule for the 2-link (C²PS only) [default: uniform].
    #[arg(long, value_enum)]
    pub first_step: Option<FirstStepArg>,
    /// EG only: rule table of the input's valence (JSON, see `capdiv spectrum`);
    /// needed for valences 6..10.
    #[arg(long, value_name = "TABLE")]
    pub table: Option<String>,
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

impl PatchesArgs {
    /// The output format ([`PatchFormat::resolve`]).
    pub fn format(&self) -> PatchFormat {
        PatchFormat::resolve(self.format, self.io.output.as_deref())
    }
}

impl SurfaceArgs {
    /// The output format ([`SurfaceFormat::resolve`]).
    pub fn format(&self) -> SurfaceFormat {
        SurfaceFormat::resolve(self.format, self.output.as_deref())
    }
}

/// `capdiv patches`.
#[derive(Clone, Debug, Args)]
pub struct PatchesArgs {
    /// Deepest ring level M (polar: a ring needs 5 links, with 2 input links
    /// rings start at level 2, with 3 or 4 at level 1; EG: the rings of steps
    /// 1..M).
    #[arg(long, value_name = "M")]
    pub depth: u32,
    /// Output format [default: from the `-o` extension (.json, .obj, .png),
    /// else json].
    #[arg(long, value_enum)]
    pub format: Option<PatchFormat>,
    /// OBJ and PNG: grid segments per patch side.
    #[arg(long, default_value_t = 4, value_name = "G",
          value_parser = clap::value_parser!(u32).range(1..=64))]
    pub grid: u32,
    /// Scalar type of the computation and of the printed numbers.
    #[arg(long, value_enum, default_value_t = Precision::F64)]
    pub precision: Precision,
    /// First-step rule for the 2-link (polar inputs only) [default: uniform].
    #[arg(long, value_enum)]
    pub first_step: Option<FirstStepArg>,
    /// EG only: rule table of the input's valence (needed for 6..10).
    #[arg(long, value_name = "TABLE")]
    pub table: Option<String>,
    /// Pretty-print the JSON.
    #[arg(long)]
    pub pretty: bool,
    /// Polar inputs, JSON or OBJ: stream the rings (kernel `PolarStream`) and
    /// write the patches as they are computed — the same patches in the same
    /// order (to rounding), in memory that does not grow with the depth.
    #[arg(long)]
    pub stream: bool,
    /// Input and output.
    #[command(flatten)]
    pub io: Io,
}

/// `capdiv surface`.
#[derive(Clone, Debug, Args)]
pub struct SurfaceArgs {
    /// Most rings a cap emits (C²PS levels, EG and Catmull-Clark steps);
    /// fewer when `--tolerance` is met first.
    #[arg(long, default_value_t = DEFAULT_DEPTH, value_name = "M",
          value_parser = clap::value_parser!(u32).range(0..=16))]
    pub depth: u32,
    /// Each cap emits rings until the hole inside its last ring is at most
    /// T across (closed by a fan to the limit point), and at most `--depth`:
    /// `T` in the mesh's units, `Trel` a fraction of the bounding-box
    /// diagonal, `none` always `--depth` rings. The summary gives the rings
    /// used (fewest–most per cap). Rings of the adaptive refinement around
    /// irregular points keep `--depth`.
    #[arg(long, value_name = "T", default_value = DEFAULT_TOLERANCE,
          value_parser = parse_tolerance)]
    pub tolerance: Tolerance,
    /// Output format: `json` — `{"patches", "caps", "summary"}` (every
    /// Bézier patch with its kind, level, face and domain; every cap with its
    /// centre, scheme, valence, limit point and normal; the summary); `obj` —
    /// the tessellated surface, welded, with normals; `png` — a shaded
    /// preview; glTF 2.0 (binary `glb`, or `gltf` with the buffer embedded);
    /// `step` — the exact patches as a STEP B-rep of B-spline faces [default: from the `-o` extension, else json; on a terminal without
    /// `-o`, only the summary is printed].
    #[arg(long, value_enum)]
    pub format: Option<SurfaceFormat>,
    /// OBJ, PNG, glb and gltf: grid segments per patch side.
    #[arg(long, default_value_t = 4, value_name = "G",
          value_parser = clap::value_parser!(u32).range(1..=64))]
    pub grid: u32,
    /// Scalar type of the evaluation and of the printed numbers.
    #[arg(long, value_enum, default_value_t = Precision::F64)]
    pub precision: Precision,
    /// Caps: the default pipeline, or Catmull-Clark caps everywhere.
    #[arg(long, value_enum, default_value_t = SurfaceScheme::Default)]
    pub scheme: SurfaceScheme,
    /// PNG: the world axis pointing up in the picture.
    #[arg(long, value_enum, default_value_t = UpArg::Z)]
    pub up: UpArg,
    /// The boundary rule, overriding the file's [default: the file's, else
    /// edge-and-corner].
    #[arg(long, value_enum, value_name = "RULE")]
    pub boundary: Option<BoundaryArg>,
    /// EG rule table for valence N (6..10), in the `spectrum --table` format;
    /// repeatable. Valences without a table get Catmull-Clark caps.
    #[arg(long = "eg-table", value_name = "N=FILE")]
    pub eg_table: Vec<String>,
    /// Refuse, after the analysis and before making any patch, a surface
    /// that would have more patches than this: every cap at `--depth` rings
    /// (exact with `--tolerance none`, an upper bound otherwise) [default:
    /// 50000000 for output written as it is made (obj in f64, compact
    /// json), 2000000 for output built whole in memory (png, glb, gltf,
    /// step, f32 obj, --pretty json)].
    #[arg(long, value_name = "N")]
    pub max_patches: Option<u64>,
    /// Threads that evaluate the surface [default: the available
    /// parallelism]; 1 evaluates on the calling thread. The output is the
    /// same, bit for bit, for every count.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub threads: Option<u32>,
    /// Do not print the summary on stderr.
    #[arg(long)]
    pub quiet: bool,
    /// Pretty-print the JSON.
    #[arg(long)]
    pub pretty: bool,
    /// The mesh: Wavefront OBJ or JSON `{"kind": "mesh", ...}` (chosen by
    /// content), `-` for standard input.
    #[arg(value_name = "MESH")]
    pub file: String,
    /// Write the output to this file (atomically) instead of standard output.
    #[arg(short, long, value_name = "PATH")]
    pub output: Option<PathBuf>,
}

/// `capdiv spectrum`.
#[derive(Clone, Debug, Args)]
pub struct SpectrumArgs {
    /// The valence n (built-in rules: 3, 5; 4 is regular; others need --table).
    #[arg(long, value_name = "N")]
    pub valence: usize,
    /// A rule table `{"valence", "A11", "A22", "A21", "A31", "A32"}` (spec
    /// docs/math/eg.md §7 format) instead of the built-in one; `-` reads stdin.
    #[arg(long, value_name = "FILE")]
    pub table: Option<String>,
    /// Pretty-print the JSON.
    #[arg(long)]
    pub pretty: bool,
    /// Write the output to this file (atomically) instead of standard output.
    #[arg(short, long, value_name = "PATH")]
    pub output: Option<PathBuf>,
}

/// `capdiv demo`.
#[derive(Clone, Debug, Args)]
pub struct DemoArgs {
    /// Directory for the OBJ and JSON files (created if missing).
    #[arg(long, default_value = "out", value_name = "DIR")]
    pub out: PathBuf,
}
