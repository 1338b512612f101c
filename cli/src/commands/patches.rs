//! `capdiv patches`: the Bézier patches through ring M, as JSON, as an OBJ
//! mesh or as a PNG preview. The patch set is generic over the patch size
//! `K` (bicubic C²PS, bi-quartic EG); OBJ and PNG are its welded
//! tessellation by `capdiv_mesh::tessellate` (the edges a ring shares with
//! the next ring marked finer: [`inner_edges`]), as `surface` makes them.
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
//! 1e-6); OBJ goes through the streaming weld ([`StreamTessellator`]): the
//! in-place output's vertices and faces in the same order, each face after
//! its vertices, the counts as the last comment line. All checks run before the first byte is written; a file output is
//! written aside and renamed at the end, so an error leaves no partial file.
//!
//! The rings are made here from the kernel's nets, not by
//! [`capdiv_mesh::rings`]: that module gives a surface cap's rings `1..=M`
//! as placed records with their cap, while this command emits bare kernel
//! patches from level 0 (with the outer region, RTS steps and any number of
//! input links) and, with `--stream`, from a sweep that never holds a whole
//! ring. The edge flags follow the same rule ([`inner_edges`]).

use super::eg::{read_table, subdivision};
use super::polar::Config;
use super::surface::{WELD_F32, WELD_F64};
use super::surface_stream::IoText;
use super::Outcome;
use crate::args::{FirstStepArg, PatchFormat, PatchesArgs, Precision};
use crate::camera::Up;
use crate::error::CliError;
use crate::input::{EgInput, Input, PolarInput, Source};
use crate::json::{indent, to_json, try_to_json, Lazy};
use crate::net::{valence_after, HeapStorage};
use crate::output::{temporary_sibling, LeveledPatch, PatchOutput, Sink, Target};
use crate::render::{encode_png, render, View};
use crate::table::Table;
use crate::text::{count, sig};
use crate::Scalar;
use capdiv::{FirstStep, OuterRegion, PolarStream, StreamOptions, TensorPatch};
use capdiv_mesh::tessellate::{
    ring_inner_edges, try_tessellate, try_write_obj, ObjWriter, PatchGeometry, RingLayout,
    StreamTessellator, Tessellation,
};
use capdiv_mesh::{PatchKind, PatchRecord, PatchUv};
use std::io::Write;

/// The record of a kernel configuration's patch of `level` with `finer`
/// edges: a C²PS (or RTS) patch if bicubic, an EG patch if bi-quartic.
fn record<R: Scalar, const K: usize>(
    level: u32,
    patch: TensorPatch<R, K>,
    finer: u8,
) -> PatchRecord<R>
where
    TensorPatch<R, K>: Into<PatchGeometry<R>>,
{
    let kind = if K == 5 {
        PatchKind::Eg
    } else {
        PatchKind::C2ps
    };
    PatchRecord {
        level,
        finer,
        ..PatchRecord::new(kind, patch.into())
    }
}

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
    /// The largest extent of the input net's bounding box, which holds
    /// every patch (the weld tolerance is relative to it).
    pub size: f64,
}

impl<R: Scalar, const K: usize> PatchSet<R, K>
where
    TensorPatch<R, K>: Into<PatchGeometry<R>>,
{
    /// One-line description for OBJ headers and the demo.
    pub fn describe(&self) -> String {
        describe(self.patches.len(), self.outer, &self.rings, K)
    }

    /// The patches as the tessellator takes them, each with its level (the
    /// tag of its faces), each ring's edges that the next ring meets marked
    /// finer ([`inner_edges`]): made one by one as they are taken.
    pub fn tess_patches(&self) -> impl Iterator<Item = (PatchRecord<R>, u32)> + '_ {
        let last = self.rings.len().saturating_sub(1);
        let finer =
            core::iter::repeat_n(0u8, self.outer).chain(self.rings.iter().enumerate().flat_map(
                move |(r, &(_, len))| {
                    (0..len).map(move |j| if r == last { 0 } else { inner_edges(K, j, len) })
                },
            ));
        self.patches
            .iter()
            .zip(finer)
            .map(|(p, finer)| (record(p.level, p.patch, finer), p.level))
    }

    /// The welded tessellation, `grid` segments per patch side, samples
    /// within `factor ×` [`PatchSet::size`] merged; an allocation refused is
    /// the out-of-memory error of input `name`.
    pub fn tessellate(
        &self,
        name: &str,
        grid: usize,
        factor: f64,
    ) -> Result<Tessellation<R>, CliError> {
        try_tessellate(self.tess_patches(), grid, R::from_f64(factor * self.size))
            .map_err(CliError::out_of_memory_in(name))
    }

    /// The tessellation with each patch's own parameters `(u, v)` as texture
    /// coordinates, so vertices are split along patch edges and carry the
    /// parameters of their patch (the PNG preview draws patch boundaries
    /// from them).
    pub fn tessellate_with_parameters(
        &self,
        name: &str,
        grid: usize,
        factor: f64,
    ) -> Result<Tessellation<R>, CliError> {
        let square = PatchUv {
            corners: [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            hole: [0.0, 0.0],
        };
        let patches = self.tess_patches().map(|(p, tag)| {
            let record = PatchRecord {
                uv: Some(square),
                ..p
            };
            (record, tag)
        });
        try_tessellate(patches, grid, R::from_f64(factor * self.size))
            .map_err(CliError::out_of_memory_in(name))
    }

    /// OBJ text of the welded tessellation `tess`; an allocation refused
    /// is the out-of-memory error of input `name`.
    pub fn to_obj(
        &self,
        name: &str,
        tess: &Tessellation<R>,
        grid: usize,
        factor: f64,
        title: &str,
    ) -> Result<String, CliError> {
        let mut header = obj_header(title, self.describe(), grid, factor, self.size).to_vec();
        let triangles = tess.faces.iter().filter(|f| f.corners().len() == 3).count();
        header.push(counts_line(
            tess.positions.len(),
            triangles,
            tess.faces.len() - triangles,
        ));
        try_write_obj(tess, &header).map_err(CliError::out_of_memory_in(name))
    }
}

/// The edges of ring patch `j` (of `len` in its ring) that the next ring
/// meets: [`ring_inner_edges`] of the C²PS layout for bicubic sets
/// (`k = 4`), of the EG one for bi-quartic sets (`k = 5`).
pub fn inner_edges(k: usize, j: usize, len: usize) -> u8 {
    let layout = if k == 5 {
        RingLayout::Sectors
    } else {
        RingLayout::Polar
    };
    ring_inner_edges(layout, j, len)
}

/// The OBJ header of a patch set: title, description, grid and weld
/// tolerance (the counts follow: [`counts_line`]).
fn obj_header(title: &str, describe: String, grid: usize, factor: f64, size: f64) -> [String; 3] {
    [
        title.to_string(),
        describe,
        format!(
            "grid {grid}x{grid} per patch; welded within {} ({} x bounding-box size {}); \
             the hole around the centre stays open",
            sig(factor * size, 3),
            sig(factor, 3),
            sig(size, 6)
        ),
    ]
}

/// The OBJ comment line with the welded mesh's counts.
fn counts_line(vertices: usize, triangles: usize, quads: usize) -> String {
    format!(
        "{}, {} ({}, {})",
        count(vertices, "vertex", "vertices"),
        count(triangles + quads, "face", "faces"),
        count(triangles, "triangle", "triangles"),
        count(quads, "quad", "quads"),
    )
}

/// The weld tolerance factor of a precision.
fn weld_factor(precision: Precision) -> f64 {
    match precision {
        Precision::F64 => WELD_F64,
        Precision::F32 => WELD_F32,
    }
}

/// The largest extent of the bounding box of `points` (0 when empty or not
/// finite).
pub fn extent<'a>(points: impl IntoIterator<Item = &'a [f64; 3]>) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0f64, f64::max);
    if size.is_finite() {
        size
    } else {
        0.0
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
) -> Result<Vec<u8>, CliError>
where
    TensorPatch<R, K>: Into<PatchGeometry<R>>,
{
    let grid = args.grid as usize;
    let factor = weld_factor(args.precision);
    Ok(match args.format() {
        PatchFormat::Json => {
            // Serialised as they are made.
            let out = Lazy(|| (set.patches.iter()).map(|p| PatchOutput::new(p.level, &p.patch)));
            try_to_json(&out, args.pretty).map_err(CliError::out_of_memory_in(name))?
        }
        PatchFormat::Obj => {
            let title = format!("capdiv patches --depth {} {name}", args.depth);
            let tess = set.tessellate(name, grid, factor)?;
            set.to_obj(name, &tess, grid, factor, &title)?.into_bytes()
        }
        PatchFormat::Png => {
            let tess = set.tessellate_with_parameters(name, grid, factor)?;
            png_bytes(name, &tess, Some(&tess.uvs), Up::Z)?
        }
    })
}

/// The default view of a tessellation of input `name`, `up` pointing up,
/// as PNG bytes; patch boundaries drawn where `params` gives each vertex's
/// patch parameters ([`PatchSet::tessellate_with_parameters`]).
pub fn png_bytes<R: Scalar>(
    name: &str,
    tess: &Tessellation<R>,
    params: Option<&[[f64; 2]]>,
    up: Up,
) -> Result<Vec<u8>, CliError> {
    let view = View {
        up,
        ..View::default()
    };
    let image = render(tess, params, &view).map_err(CliError::out_of_memory_in(name))?;
    encode_png(&image).map_err(|e| CliError::Io {
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
        size: extent(eg_points(input)),
    };
    check_finite(name, set)
}

/// The points of a polar input: pole and links.
fn polar_points(input: &PolarInput) -> impl Iterator<Item = &[f64; 3]> {
    std::iter::once(&input.pole).chain(input.links.iter().flatten())
}

/// The points of an EG input: the c-net's centre and sectors, or the
/// d-net's sectors and `c0`.
fn eg_points(input: &EgInput) -> Box<dyn Iterator<Item = &[f64; 3]> + '_> {
    match input {
        EgInput::Cnet(c) => Box::new(std::iter::once(&c.center).chain(c.sectors.iter().flatten())),
        EgInput::Dnet(d) => Box::new(d.sectors.iter().flatten().chain(&d.c0)),
    }
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
        size: extent(polar_points(input)),
        config: &config,
        depth,
        first,
    }
    .run(HeapStorage::for_valence(valence_after(n, depth), || {
        format!("valence n·2^M = {n}·2^{depth}")
    })?)?;
    check_finite(name, set)
}

struct Job<'a, R> {
    name: &'a str,
    size: f64,
    config: &'a Config<R>,
    depth: u32,
    first: FirstStep,
}

impl<R: Scalar> Job<'_, R> {
    fn run(self, storage: HeapStorage<R>) -> Result<PatchSet<R, 4>, CliError> {
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
            if net.link_count() >= 5 {
                let ring = net.ring_patches();
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
            size: self.size,
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
    let factor = weld_factor(args.precision);
    let size = extent(polar_points(input));
    let last = rings.last().map(|r| r.0);
    let mut writer = match args.format() {
        PatchFormat::Obj => {
            let title = format!("capdiv patches --depth {} {name}", args.depth);
            let describe = describe(total, outer.len(), &rings, 4);
            let header = obj_header(&title, describe, grid, factor, size);
            let text = IoText {
                w: &mut out,
                header: String::new(),
                error: None,
            };
            let header: Vec<&str> = header.iter().map(String::as_str).collect();
            PatchWriter::Obj {
                tess: Box::new(StreamTessellator::new(grid, R::from_f64(factor * size))),
                obj: ObjWriter::new(text, &header),
            }
        }
        _ => PatchWriter::Json {
            out: &mut out,
            pretty: args.pretty,
            count: 0,
        },
    };
    for patch in outer.patches() {
        writer.patch(0, &patch, 0).map_err(io)?;
    }
    for &(level, len) in &rings {
        for span in [0u8, 1] {
            let opts = StreamOptions::depth(level)
                .first(first)
                .only(level, Some(span));
            let sweep = state.sweep(pole, links, opts).map_err(kernel)?;
            // Span 0 comes first in a ring: its column `j` is patch `j`.
            let finer = match (span, Some(level) == last) {
                (0, false) => inner_edges(4, 0, len),
                _ => 0,
            };
            for p in sweep {
                writer.patch(level, &p.patch, finer).map_err(io)?;
            }
        }
    }
    writer.finish().map_err(io)?;
    out.commit().map_err(io)?;
    // Everything is written: nothing left for the caller to write.
    Ok(Outcome::new(Vec::new(), Sink::Stdout))
}

/// How `--stream` formats patches: the bytes `format` writes for the whole
/// set, piece by piece.
enum PatchWriter<'a, R> {
    /// `to_json` of the list: compact elements joined by `,` (pretty: each
    /// element indented as `indent` does inside the array).
    Json {
        out: &'a mut StreamOut,
        pretty: bool,
        count: usize,
    },
    /// [`PatchSet::to_obj`]'s lines: the welded tessellation as it comes
    /// (faces after their vertices instead of all at the end), the counts
    /// as the last comment line.
    Obj {
        tess: Box<StreamTessellator<R>>,
        obj: ObjWriter<IoText<'a, StreamOut>>,
    },
}

impl<R: Scalar> PatchWriter<'_, R> {
    /// One patch of `level`, with its finer edges.
    fn patch(
        &mut self,
        level: u32,
        patch: &capdiv::BicubicPatch<R>,
        finer: u8,
    ) -> std::io::Result<()> {
        match self {
            PatchWriter::Json { out, pretty, count } => {
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
                Ok(())
            }
            PatchWriter::Obj { tess, obj } => {
                tess.push(&record(level, *patch, finer), level, obj);
                obj_error(obj)
            }
        }
    }

    fn finish(self) -> std::io::Result<()> {
        match self {
            PatchWriter::Json { out, pretty, count } => {
                if count == 0 {
                    out.write_all(&to_json(&Vec::<PatchOutput<f64>>::new(), pretty))
                } else {
                    out.write_all(if pretty { b"\n]\n" } else { b"]\n" })
                }
            }
            PatchWriter::Obj { mut tess, mut obj } => {
                let s = tess.finish(&mut obj);
                if let Some(e) = tess.refused() {
                    return Err(std::io::Error::new(
                        std::io::ErrorKind::OutOfMemory,
                        e.message(),
                    ));
                }
                obj_error(&mut obj)?;
                let counts = counts_line(s.vertices, s.triangles, s.quads);
                writeln!(obj.out.w, "# {counts}")
            }
        }
    }
}

/// The first write error of a streamed OBJ, if any.
fn obj_error(obj: &mut ObjWriter<IoText<'_, StreamOut>>) -> std::io::Result<()> {
    match obj.out.error.take() {
        Some(e) => Err(e),
        None => Ok(()),
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
