//! `capdiv patches`: the Bézier patches through ring M, as JSON, as an OBJ
//! mesh or as a PNG preview. The patch set, its mesh and its OBJ are generic
//! over the patch size `K` (bicubic C²PS, bi-quartic EG).
//!
//! **EG** (`cnet`/`dnet`, spec EG.md §9): the rings of steps 1..M, `3n`
//! bi-4 patches each (`"degree": 4`, 25 points), `level` = the step that
//! emitted the ring: ring `m` covers the L-shape between the holes
//! `[0, 2^−(m−1)]²` and `[0, 2^−m]²` of every sector (level-0 c-units), patch
//! `3s + p` in sector `s` (`p`: 0 `[½,1]×[0,½]`, 1 `[0,½]×[½,1]`, 2 `[½,1]²`
//! of the old hole). Level 0 has no ring (the c-net alone defines no surface
//! outside the cap), so `--depth 0` prints `[]`; the hole `[0, 2^−M]²` around
//! `c0` stays open.
//!
//! **C²PS** (`polar`, spec C2PS.md §5): bicubic patches from level 0.
//! Order: first the level-0 outer region (kernel `OuterRegion`, only when the
//! input has 6 or more links; `level` 0), then the rings of levels 0, 1, …, M,
//! each `2N` patches with `N = n·2^m` (span 0 columns 0..N, then span 1).
//!
//! A ring needs links 1..5. An input with K links has them at level 0 when
//! K ≥ 5, from level 1 when K is 3 or 4, and from level 2 when K = 2 (old links
//! up to K give new links up to 2K−1, §2). Rings before that do not exist and are
//! not emitted, so `--depth 1` on a 2-link input prints no patch at all.

use super::eg::{read_table, subdivision};
use super::polar::Config;
use super::Outcome;
use crate::args::{FirstStepArg, PatchFormat, PatchesArgs, Precision};
use crate::capacity::{dispatch, valence_after, NetJob};
use crate::error::CliError;
use crate::input::{EgInput, Input, PolarInput, Source};
use crate::mesh::Mesh;
use crate::obj::to_obj;
use crate::output::{to_json, LeveledPatch, PatchOutput, Sink};
use crate::render::{encode_png, render, View};
use crate::table::Table;
use crate::Scalar;
use capdiv::{FirstStep, OuterRegion, PolarNet};

/// The patches of a configuration through some depth, `K×K` control points
/// each.
#[derive(Clone, Debug)]
pub struct PatchSet<R, const K: usize> {
    /// Outer region first (C²PS only), then ring by ring.
    pub patches: Vec<LeveledPatch<R, K>>,
    /// Patches of the level-0 outer region (0 for EG).
    pub outer: usize,
    /// `(level, patches)` of each ring emitted.
    pub rings: Vec<(u32, usize)>,
    /// Valence at the deepest level.
    pub valence: usize,
}

impl<R: Scalar, const K: usize> PatchSet<R, K> {
    /// One-line description for OBJ headers and the demo.
    pub fn describe(&self) -> String {
        let rings = match (self.rings.first(), self.rings.last()) {
            (Some(a), Some(b)) => format!("rings of levels {}..={}", a.0, b.0),
            _ => "no ring".to_string(),
        };
        let kind = format!("bi-{} Bézier patches", K - 1);
        if self.outer == 0 {
            return format!("{} {kind} in {rings}", self.patches.len());
        }
        format!(
            "{} {kind}: {} in the level-0 outer region, {} in {rings}",
            self.patches.len(),
            self.outer,
            self.patches.len() - self.outer
        )
    }

    /// Tessellates the patches, `grid` segments per side, tagged by level.
    pub fn to_mesh(&self, grid: usize) -> Mesh<R> {
        Mesh::from_patches(self.patches.iter().map(|p| (p.level, &p.patch)), grid)
    }

    /// OBJ text of the tessellated patches.
    pub fn to_obj(&self, mesh: &Mesh<R>, grid: usize, title: &str) -> String {
        let header = [
            title.to_string(),
            self.describe(),
            format!(
                "each patch sampled on a {grid}x{grid} grid: {} vertices, {} quads; \
                 vertices on shared patch edges are duplicated (not welded)",
                mesh.positions.len(),
                mesh.quads.len()
            ),
        ];
        to_obj(mesh, &header)
    }
}

/// Runs the command.
pub fn run(args: &PatchesArgs) -> Result<Outcome, CliError> {
    let source = Source::read(&args.io.file)?;
    let name = source.name.clone();
    let bytes = match source.parse()? {
        Input::Polar(input) => {
            if args.table.is_some() {
                return Err(CliError::Usage(
                    "--table applies to EG inputs (cnet, dnet) only".into(),
                ));
            }
            let first = args.first_step.unwrap_or(FirstStepArg::Uniform).into();
            match args.precision {
                Precision::F64 => {
                    format::<f64, 4>(&collect(&name, &input, args.depth, first)?, args, &name)?
                }
                Precision::F32 => {
                    format::<f32, 4>(&collect(&name, &input, args.depth, first)?, args, &name)?
                }
            }
        }
        other => {
            if args.first_step.is_some() {
                return Err(CliError::Usage(
                    "--first-step applies to polar inputs only".into(),
                ));
            }
            let input = other.into_eg(&name, "patches")?;
            let table = read_table(args.table.as_deref())?;
            let table = table.as_ref();
            match args.precision {
                Precision::F64 => {
                    format::<f64, 5>(&collect_eg(&name, &input, args.depth, table)?, args, &name)?
                }
                Precision::F32 => {
                    format::<f32, 5>(&collect_eg(&name, &input, args.depth, table)?, args, &name)?
                }
            }
        }
    };
    Ok(Outcome::new(
        bytes,
        Sink::from_option(args.io.output.clone()),
    ))
}

fn format<R: Scalar, const K: usize>(
    set: &PatchSet<R, K>,
    args: &PatchesArgs,
    name: &str,
) -> Result<Vec<u8>, CliError> {
    let grid = args.grid as usize;
    Ok(match args.format {
        PatchFormat::Json => {
            let out: Vec<PatchOutput<R>> = set
                .patches
                .iter()
                .map(|p| PatchOutput::new(p.level, &p.patch))
                .collect();
            to_json(&out, args.pretty)
        }
        PatchFormat::Obj => {
            let title = format!("capdiv patches --depth {} {name}", args.depth);
            set.to_obj(&set.to_mesh(grid), grid, &title).into_bytes()
        }
        PatchFormat::Png => png_bytes(&set.to_mesh(grid))?,
    })
}

/// The default view of a mesh as PNG bytes.
pub fn png_bytes<R: Scalar>(mesh: &Mesh<R>) -> Result<Vec<u8>, CliError> {
    encode_png(&render(mesh, &View::default())).map_err(|e| CliError::Io {
        path: "<png encoder>".into(),
        message: e.to_string(),
    })
}

/// The rings of steps 1..=`depth` of an EG input (spec EG.md §9), `3n`
/// bi-4 patches each, with the user's table when given.
pub fn collect_eg<R: Scalar>(
    name: &str,
    input: &EgInput,
    depth: u32,
    table: Option<&Table>,
) -> Result<PatchSet<R, 5>, CliError> {
    let mut eg = subdivision::<R>(name, input, table)?;
    let kernel = |e| CliError::kernel(name, e);
    let mut patches = Vec::new();
    let mut rings = Vec::new();
    for _ in 0..depth {
        eg.step().map_err(kernel)?;
        let level = eg.level();
        let ring = eg.ring_patches();
        rings.push((level, ring.len()));
        patches.extend(ring.map(|patch| LeveledPatch { level, patch }));
    }
    let set = PatchSet {
        patches,
        outer: 0,
        rings,
        valence: eg.valence(),
    };
    check_finite(name, set)
}

fn check_finite<R: Scalar, const K: usize>(
    name: &str,
    set: PatchSet<R, K>,
) -> Result<PatchSet<R, K>, CliError> {
    let finite = set
        .patches
        .iter()
        .all(|p| p.patch.points.iter().flatten().all(|q| q.is_finite()));
    if !finite {
        return Err(CliError::NonFiniteResult {
            source: name.to_string(),
        });
    }
    Ok(set)
}

/// All patches of `input` through ring `depth`.
pub fn collect<R: Scalar>(
    name: &str,
    input: &PolarInput,
    depth: u32,
    first: FirstStep,
) -> Result<PatchSet<R, 4>, CliError> {
    let config = Config::<R>::of(input);
    let n = config.valence();
    let set = dispatch(
        valence_after(n, depth),
        || format!("valence n·2^M = {n}·2^{depth}"),
        Job {
            name,
            config: &config,
            depth,
            first,
        },
    )?;
    check_finite(name, set)
}

struct Job<'a, R> {
    name: &'a str,
    config: &'a Config<R>,
    depth: u32,
    first: FirstStep,
}

impl<R: Scalar> NetJob<R> for Job<'_, R> {
    type Output = PatchSet<R, 4>;
    fn run<const CAP: usize>(self) -> Result<PatchSet<R, 4>, CliError> {
        let kernel = |e| CliError::kernel(self.name, e);
        let (pole, links) = (self.config.pole, &self.config.links);
        let mut net = PolarNet::<R, CAP>::new(pole, links).map_err(kernel)?;
        let outer = OuterRegion::new(pole, links).map_err(kernel)?;
        let mut patches: Vec<LeveledPatch<R, 4>> = outer
            .patches()
            .map(|patch| LeveledPatch { level: 0, patch })
            .collect();
        let outer = patches.len();
        let mut rings = Vec::new();
        for level in 0..=self.depth {
            if net.links_held() >= 5 {
                let ring = net.ring_patches().map_err(kernel)?;
                rings.push((level, ring.len()));
                patches.extend(ring.map(|patch| LeveledPatch { level, patch }));
            }
            if level < self.depth {
                net.step(self.first).map_err(kernel)?;
            }
        }
        Ok(PatchSet {
            patches,
            outer,
            rings,
            valence: net.valence(),
        })
    }
}
