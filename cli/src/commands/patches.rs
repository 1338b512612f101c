//! `capdiv patches`: every bicubic Bézier patch from level 0 through ring M
//! (spec C2PS.md §5), as JSON or as an OBJ mesh.
//!
//! Order: first the level-0 outer region (kernel `OuterRegion`, only when the
//! input has 6 or more links; `level` 0), then the rings of levels 0, 1, …, M,
//! each `2N` patches with `N = n·2^m` (span 0 columns 0..N, then span 1).
//!
//! A ring needs links 1..5. An input with K links has them at level 0 when
//! K ≥ 5, from level 1 when K is 3 or 4, and from level 2 when K = 2 (old links
//! up to K give new links up to 2K−1, §2). Rings before that do not exist and are
//! not emitted, so `--depth 1` on a 2-link input prints no patch at all.

use super::polar::{read_polar, Config};
use super::Outcome;
use crate::args::{PatchFormat, PatchesArgs, Precision};
use crate::capacity::{dispatch, valence_after, NetJob};
use crate::error::CliError;
use crate::input::PolarInput;
use crate::mesh::Mesh;
use crate::obj::to_obj;
use crate::output::{to_json, LeveledPatch, PatchOutput, Sink};
use crate::render::{encode_png, render, View};
use crate::Scalar;
use capdiv::{FirstStep, OuterRegion, PolarNet};

/// The patches of a configuration through some depth.
#[derive(Clone, Debug)]
pub struct PatchSet<R> {
    /// Outer region first, then ring by ring.
    pub patches: Vec<LeveledPatch<R>>,
    /// Patches of the level-0 outer region.
    pub outer: usize,
    /// `(level, patches)` of each ring emitted.
    pub rings: Vec<(u32, usize)>,
    /// Valence at the deepest level.
    pub valence: usize,
}

impl<R: Scalar> PatchSet<R> {
    /// One-line description for OBJ headers and the demo.
    pub fn describe(&self) -> String {
        let rings = match (self.rings.first(), self.rings.last()) {
            (Some(a), Some(b)) => format!("rings of levels {}..={}", a.0, b.0),
            _ => "no ring".to_string(),
        };
        format!(
            "{} patches: {} in the level-0 outer region, {} in {rings}",
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
    let (name, input) = read_polar(&args.io.file)?;
    let first = args.first_step.into();
    let bytes = match args.precision {
        Precision::F64 => format::<f64>(&collect(&name, &input, args.depth, first)?, args, &name)?,
        Precision::F32 => format::<f32>(&collect(&name, &input, args.depth, first)?, args, &name)?,
    };
    Ok(Outcome {
        bytes,
        sink: Sink::from_option(args.io.output.clone()),
    })
}

fn format<R: Scalar>(
    set: &PatchSet<R>,
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

/// All patches of `input` through ring `depth`.
pub fn collect<R: Scalar>(
    name: &str,
    input: &PolarInput,
    depth: u32,
    first: FirstStep,
) -> Result<PatchSet<R>, CliError> {
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

struct Job<'a, R> {
    name: &'a str,
    config: &'a Config<R>,
    depth: u32,
    first: FirstStep,
}

impl<R: Scalar> NetJob<R> for Job<'_, R> {
    type Output = PatchSet<R>;
    fn run<const CAP: usize>(self) -> Result<PatchSet<R>, CliError> {
        let kernel = |e| CliError::kernel(self.name, e);
        let (pole, links) = (self.config.pole, &self.config.links);
        let mut net = PolarNet::<R, CAP>::new(pole, links).map_err(kernel)?;
        let outer = OuterRegion::new(pole, links).map_err(kernel)?;
        let mut patches: Vec<LeveledPatch<R>> = outer
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
