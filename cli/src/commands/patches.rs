//! `capdiv patches`: the Bézier patches through ring M, as JSON, as an OBJ
//! mesh or as a PNG preview. The patch set, its mesh and its OBJ are generic
//! over the patch size `K` (bicubic C²PS, bi-quartic EG).
//!
//! **EG** (`cnet`/`dnet`, docs/math/eg.md §9): the rings of steps 1..M, `3n`
//! bi-4 patches each (`"degree": 4`, 25 points), `level` = the step that
//! emitted the ring: ring `m` covers the L-shape between the holes
//! `[0, 2^−(m−1)]²` and `[0, 2^−m]²` of every sector (level-0 c-units), patch
//! `3s + p` in sector `s` (`p`: 0 `[½,1]×[0,½]`, 1 `[0,½]×[½,1]`, 2 `[½,1]²`
//! of the old hole). Level 0 has no ring (the c-net alone defines no surface
//! outside the cap), so `--depth 0` prints `[]`; the hole `[0, 2^−M]²` around
//! `c0` stays open.
//!
//! **C²PS** (`polar`, docs/math/c2ps.md §5): bicubic patches from level 0.
//! Order: first the level-0 outer region (kernel `OuterRegion`, only when the
//! input has 6 or more links; `level` 0), then the rings of levels 0, 1, …, M,
//! each `2N` patches with `N = n·2^m` (span 0 columns 0..N, then span 1).
//!
//! A ring needs links 1..5. An input with K links has them at level 0 when
//! K ≥ 5, from level 1 when K is 3 or 4, and from level 2 when K = 2 (old links
//! up to K give new links up to 2K−1, §2). Rings before that do not exist and are
//! not emitted, so `--depth 1` on a 2-link input prints no patch at all.
//!
//! **`--stream`** (polar inputs, JSON or OBJ): the rings come from the
//! kernel's streaming sweep (`PolarStream`, docs/math/c2ps.md §4 eq. (30)) and are
//! written as they are computed, in the order above (one sweep per level and
//! span), so memory does not grow with the depth: the sweep's state is
//! fixed (depth ≤ [`STREAM_MAX_DEPTH`]) and nothing is collected. The patches
//! equal the in-place ones to rounding (f64: 1e-12 of the input's size; f32:
//! 1e-6). All checks run before the first byte is written; a file output is
//! written aside and renamed at the end, so an error leaves no partial file.

use super::eg::{read_table, subdivision};
use super::polar::Config;
use super::Outcome;
use crate::args::{FirstStepArg, PatchFormat, PatchesArgs, Precision};
use crate::camera::Up;
use crate::error::CliError;
use crate::input::{EgInput, Input, PolarInput, Source};
use crate::mesh::Mesh;
use crate::net::{valence_after, NetStorage};
use crate::obj::to_obj;
use crate::output::{indent, temporary_sibling, to_json, LeveledPatch, PatchOutput, Sink, Target};
use crate::render::{encode_png, render, View};
use crate::table::Table;
use crate::Scalar;
use capdiv::{FirstStep, OuterRegion, PolarStream, StreamOptions};
use std::io::Write;

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
        describe(self.patches.len(), self.outer, &self.rings, K)
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

/// [`PatchSet::describe`] from the counts: `total` patches of `K×K` points,
/// `outer` of them in the outer region, `rings` as `(level, patches)`.
fn describe(total: usize, outer: usize, rings: &[(u32, usize)], k: usize) -> String {
    let rings = match (rings.first(), rings.last()) {
        (Some(a), Some(b)) => format!("rings of levels {}..={}", a.0, b.0),
        _ => "no ring".to_string(),
    };
    let kind = format!("bi-{} Bézier patches", k - 1);
    if outer == 0 {
        return format!("{total} {kind} in {rings}");
    }
    format!(
        "{total} {kind}: {outer} in the level-0 outer region, {} in {rings}",
        total - outer
    )
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
            if args.stream {
                return match args.precision {
                    Precision::F64 => stream::<f64>(&name, &input, args, first),
                    Precision::F32 => stream::<f32>(&name, &input, args, first),
                };
            }
            match args.precision {
                Precision::F64 => {
                    format::<f64, 4>(&collect(&name, &input, args.depth, first)?, args, &name)?
                }
                Precision::F32 => {
                    format::<f32, 4>(&collect(&name, &input, args.depth, first)?, args, &name)?
                }
            }
        }
        _ if args.stream => {
            return Err(CliError::Usage(
                "--stream applies to polar inputs only".into(),
            ));
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
    Ok(match args.format() {
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
        PatchFormat::Png => png_bytes(&set.to_mesh(grid), Up::Z)?,
    })
}

/// The default view of a mesh, `up` pointing up, as PNG bytes.
pub fn png_bytes<R: Scalar>(mesh: &Mesh<R>, up: Up) -> Result<Vec<u8>, CliError> {
    let view = View {
        up,
        ..View::default()
    };
    encode_png(&render(mesh, &view)).map_err(|e| CliError::Io {
        path: "<png encoder>".into(),
        message: e.to_string(),
    })
}

/// The rings of steps 1..=`depth` of an EG input (docs/math/eg.md §9), `3n`
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
    let set = Job {
        name,
        config: &config,
        depth,
        first,
    }
    .run(NetStorage::for_valence(valence_after(n, depth), || {
        format!("valence n·2^M = {n}·2^{depth}")
    })?)?;
    check_finite(name, set)
}

struct Job<'a, R> {
    name: &'a str,
    config: &'a Config<R>,
    depth: u32,
    first: FirstStep,
}

impl<R: Scalar> Job<'_, R> {
    fn run(self, mut storage: NetStorage<R>) -> Result<PatchSet<R, 4>, CliError> {
        let kernel = |e| CliError::kernel(self.name, e);
        let (pole, links) = (self.config.pole, &self.config.links);
        let mut net = storage.net(pole, links).map_err(kernel)?;
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

/// Deepest level `--stream` reaches: the sweep's state holds one window of
/// 4 columns per level (`PolarStream<R, 30>`: 21 KiB in f64).
pub const STREAM_MAX_DEPTH: usize = 30;

/// `--stream`: validates, then writes the patches of `input` through ring
/// `args.depth` as the sweeps produce them (see the module docs).
fn stream<R: Scalar>(
    name: &str,
    input: &PolarInput,
    args: &PatchesArgs,
    first: FirstStep,
) -> Result<Outcome, CliError> {
    if args.format() == PatchFormat::Png {
        return Err(CliError::Usage(
            "--stream writes json or obj (a png needs the whole mesh)".into(),
        ));
    }
    let kernel = |e| CliError::kernel(name, e);
    let config = Config::<R>::of(input);
    let (pole, links) = (config.pole, &config.links);
    let outer = OuterRegion::new(pole, links).map_err(kernel)?;
    let mut state = Box::new(PolarStream::<R, STREAM_MAX_DEPTH>::empty());
    // Every check before the first byte: the whole sweep's, then the rings'
    // sizes (a level's ring has N patches per span, or none below 5 links).
    state
        .sweep(pole, links, StreamOptions::depth(args.depth))
        .map_err(kernel)?;
    let mut rings = Vec::new();
    for level in 0..=args.depth {
        let one = StreamOptions::depth(level).only(level, Some(0));
        let len = state.sweep(pole, links, one).map_err(kernel)?.len();
        if len > 0 {
            rings.push((level, 2 * len));
        }
    }
    let total = outer.len() + rings.iter().map(|r| r.1).sum::<usize>();
    let mut out = StreamOut::open(args.io.output.as_deref())?;
    let io = |e: std::io::Error| CliError::Io {
        path: args
            .io
            .output
            .as_ref()
            .map_or("<stdout>".into(), |p| p.display().to_string()),
        message: e.to_string(),
    };
    let grid = args.grid as usize;
    let mut writer = match args.format() {
        PatchFormat::Obj => {
            let side = grid.max(1) + 1;
            let title = format!("capdiv patches --depth {} {name}", args.depth);
            let header = [
                title,
                describe(total, outer.len(), &rings, 4),
                format!(
                    "each patch sampled on a {grid}x{grid} grid: {} vertices, {} quads; \
                     vertices on shared patch edges are duplicated (not welded)",
                    total * side * side,
                    total * grid.max(1) * grid.max(1)
                ),
            ];
            for line in header {
                writeln!(out, "# {line}").map_err(io)?;
            }
            PatchWriter::Obj { grid }
        }
        _ => PatchWriter::Json {
            pretty: args.pretty,
            count: 0,
        },
    };
    for patch in outer.patches() {
        writer.patch(&mut out, 0, &patch).map_err(io)?;
    }
    for &(level, _) in &rings {
        for span in [0u8, 1] {
            let opts = StreamOptions::depth(level)
                .first(first)
                .only(level, Some(span));
            let sweep = state.sweep(pole, links, opts).map_err(kernel)?;
            for p in sweep {
                writer.patch(&mut out, level, &p.patch).map_err(io)?;
            }
        }
    }
    writer.finish(&mut out, total).map_err(io)?;
    out.commit().map_err(io)?;
    // Everything is written: nothing left for the caller to write.
    Ok(Outcome::new(Vec::new(), Sink::Stdout))
}

/// How `--stream` formats patches: the bytes `format` writes for the whole
/// set, piece by piece.
enum PatchWriter {
    /// `to_json` of the list: compact elements joined by `,` (pretty: each
    /// element indented as `indent` does inside the array).
    Json { pretty: bool, count: usize },
    /// `to_obj` of the tessellated patches: `v`/`vn` lines per patch as they
    /// come, the quads (pure index arithmetic) at the end.
    Obj { grid: usize },
}

impl PatchWriter {
    fn patch<R: Scalar>(
        &mut self,
        out: &mut impl std::io::Write,
        level: u32,
        patch: &capdiv::BicubicPatch<R>,
    ) -> std::io::Result<()> {
        match self {
            PatchWriter::Json { pretty, count } => {
                let compact = serde_json::to_vec(&PatchOutput::new(level, patch))
                    .map_err(std::io::Error::other)?;
                out.write_all(if *count == 0 { b"[" } else { b"," })?;
                if *pretty {
                    // indent("[e]") = "[" + "\n  E" + "\n]": keep the middle.
                    let mut one = Vec::with_capacity(compact.len() + 2);
                    one.push(b'[');
                    one.extend_from_slice(&compact);
                    one.push(b']');
                    let text = indent(&one);
                    out.write_all(text.get(1..text.len().saturating_sub(2)).unwrap_or(&[]))?;
                } else {
                    out.write_all(&compact)?;
                }
                *count += 1;
            }
            PatchWriter::Obj { grid } => {
                let mesh = Mesh::from_patches([(level, patch)], *grid);
                for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
                    let [x, y, z] = p.0;
                    let [a, b, c] = n.0;
                    writeln!(out, "v {x} {y} {z}")?;
                    writeln!(out, "vn {a} {b} {c}")?;
                }
            }
        }
        Ok(())
    }

    fn finish(&self, out: &mut impl std::io::Write, total: usize) -> std::io::Result<()> {
        match *self {
            PatchWriter::Json { pretty, count } => {
                if count == 0 {
                    out.write_all(&to_json(&Vec::<PatchOutput<f64>>::new(), pretty))
                } else {
                    out.write_all(if pretty { b"\n]\n" } else { b"]\n" })
                }
            }
            PatchWriter::Obj { grid } => {
                let grid = grid.max(1);
                let side = grid + 1;
                for k in 0..total {
                    let base = k * side * side + 1; // OBJ indices are 1-based
                    for a in 0..grid {
                        for b in 0..grid {
                            let idx = |a: usize, b: usize| base + a * side + b;
                            let [a, b, c, d] =
                                [idx(a, b), idx(a + 1, b), idx(a + 1, b + 1), idx(a, b + 1)];
                            writeln!(out, "f {a}//{a} {b}//{b} {c}//{c} {d}//{d}")?;
                        }
                    }
                }
                Ok(())
            }
        }
    }
}

/// Where `--stream` writes: standard output; a new or regular file written
/// aside and renamed over the target at the end (as `Sink::File` does in one
/// piece); or a FIFO, device or dangling link written through
/// ([`Target::of`]).
pub(crate) enum StreamOut {
    /// Unlocked (each buffered chunk takes the lock): the writer may be
    /// handed to an evaluation thread, and a lock guard cannot move.
    Stdout(std::io::BufWriter<std::io::Stdout>),
    File {
        w: std::io::BufWriter<std::fs::File>,
        tmp: std::path::PathBuf,
        path: std::path::PathBuf,
        permissions: Option<std::fs::Permissions>,
        committed: bool,
    },
    Through(std::io::BufWriter<std::fs::File>),
}

impl StreamOut {
    pub(crate) fn open(path: Option<&std::path::Path>) -> Result<Self, CliError> {
        let Some(path) = path else {
            return Ok(StreamOut::Stdout(
                std::io::BufWriter::new(std::io::stdout()),
            ));
        };
        let io_err = |e: std::io::Error| CliError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        };
        match Target::of(path)? {
            Target::Replace { path, permissions } => {
                let tmp = temporary_sibling(&path, "stream.");
                let file = std::fs::File::create(&tmp).map_err(io_err)?;
                Ok(StreamOut::File {
                    w: std::io::BufWriter::new(file),
                    tmp,
                    path,
                    permissions,
                    committed: false,
                })
            }
            Target::Through { path, create } => Ok(StreamOut::Through(std::io::BufWriter::new(
                Target::open_through(&path, create).map_err(io_err)?,
            ))),
        }
    }

    pub(crate) fn commit(&mut self) -> std::io::Result<()> {
        match self {
            StreamOut::Stdout(w) => w.flush(),
            StreamOut::Through(w) => w.flush(),
            StreamOut::File {
                w,
                tmp,
                path,
                permissions,
                committed,
            } => {
                w.flush()?;
                w.get_ref().sync_all()?;
                if let Some(p) = permissions.take() {
                    std::fs::set_permissions(&*tmp, p)?;
                }
                std::fs::rename(&*tmp, &*path)?;
                *committed = true;
                Ok(())
            }
        }
    }
}

impl Drop for StreamOut {
    /// An unfinished file output (an error midway) is removed.
    fn drop(&mut self) {
        if let StreamOut::File {
            tmp,
            committed: false,
            ..
        } = self
        {
            let _ = std::fs::remove_file(tmp);
        }
    }
}

impl std::io::Write for StreamOut {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self {
            StreamOut::Stdout(w) => w.write(buf),
            StreamOut::File { w, .. } | StreamOut::Through(w) => w.write(buf),
        }
    }
    fn flush(&mut self) -> std::io::Result<()> {
        match self {
            StreamOut::Stdout(w) => w.flush(),
            StreamOut::File { w, .. } | StreamOut::Through(w) => w.flush(),
        }
    }
}
