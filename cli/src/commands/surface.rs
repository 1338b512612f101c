//! `capdiv surface`: a whole polygon mesh to a smooth surface through
//! `capdiv_mesh`.
//!
//! The mesh is Wavefront OBJ (with OpenSubdiv's `t` tag lines) or JSON
//! `{"kind": "mesh", "vertices", "faces"}` (with optional tag fields),
//! chosen by content ([`looks_like_json`]). It is validated and analysed
//! once with its tags ([`capdiv_mesh::SurfacePlan::for_mesh`]: regular
//! faces, polar fans, extraordinary points, adaptive refinement of the
//! rest), refused above `--max-patches` ([`BoundedPlan`]), and evaluated in
//! the precision asked for ([`capdiv_mesh::Evaluator`]). Output:
//!
//! - `json`: `{"patches": [...], "caps": [...], "summary": {...}}` (see
//!   [`PatchJson`], [`CapJson`], [`Summary`]);
//! - `obj`: the patches tessellated on a `G×G` grid by
//!   [`capdiv_mesh::tessellate`] (finer edges sampled twice as finely, each
//!   cap's last hole closed by a fan to its limit point) and welded with a
//!   tolerance relative to the input's bounding box ([`weld_tolerance`]), with
//!   normals; a closed, consistently oriented input gives a closed,
//!   consistently oriented OBJ (checked, and reported);
//! - `png`: a shaded preview of that tessellation (colours by level);
//! - `glb`, `gltf`: that tessellation as glTF 2.0, a node per OBJ object
//!   ([`crate::export::gltf`]);
//! - `step`: the exact patches as an ISO 10303-21 B-rep of B-spline faces,
//!   each cap's last hole closed by collapsed ruled patches
//!   ([`crate::export::step`]); the summary adds the face, edge and vertex
//!   counts, the shell, and for a closed shell the volume it encloses (Gauss
//!   quadrature over the faces).
//!
//! `obj` (f64, a consistently oriented manifold input) and `json` (compact
//! or pretty) of an input without UVs are written as they are produced
//! ([`super::surface_stream`]); the other outputs are built whole in memory
//! first.
//!
//! The summary is also printed as one block on stderr (unless `--quiet`),
//! after the output has been written; exit status 0.

use super::Outcome;
use crate::args::{
    Precision, SurfaceArgs, SurfaceFormat, SurfaceScheme, Tolerance, DEFAULT_MAX_PATCHES,
};
use crate::error::{CliError, Naming};
use crate::export::{gltf, step};
use crate::input::{parse, Input, Source};
use crate::json::{try_to_json, Lazy};
use crate::output::Sink;
use crate::table::Table;
use crate::text::{count, sig};
use crate::Scalar;
use capdiv::Point3;
use capdiv_mesh::obj::{looks_like_json, parse_obj_objects, ObjObject};
use capdiv_mesh::sinks::{CollectSurface, PatchCounts, SurfaceStats, Tee};
use capdiv_mesh::tessellate::{
    try_closed_and_oriented, try_tessellate, try_tessellate_guided, try_write_obj, BadEdge,
    EdgeFault, Face, Tessellation,
};
use capdiv_mesh::{
    BoundedPlan, CapRecord, FaceVarying, MeshInput, OutOfMemory, PatchKind, PatchRecord, PatchUv,
    PlanOptions, SurfaceSink, Topology,
};
use serde::Serialize;
use std::fmt::Write;
use std::io::IsTerminal;
use std::time::Instant;

/// Weld tolerance of `f64` output, relative to the bounding-box size.
pub const WELD_F64: f64 = 1e-9;
/// Weld tolerance of `f32` output when the f64 guide does not match (it
/// always does for `surface`), relative to the bounding-box size.
pub const WELD_F32: f64 = 1e-5;

/// What `surface` prints on a terminal instead of the surface.
pub const TERMINAL_HINT: &str =
    "  output       not printed to a terminal: give -o FILE (.obj, .json or \
     .png), or --format json|obj to print it\n";

/// Valences that take a user EG table.
pub const TABLE_VALENCES: std::ops::RangeInclusive<usize> = 6..=10;

/// Runs the command.
pub fn run(args: &SurfaceArgs) -> Result<Outcome, CliError> {
    let tables = read_tables(&args.eg_table)?;
    let source = Source::read_text(&args.file)?;
    let naming = Naming::of_text(&source.text);
    let (mut mesh, objects) = read_mesh_objects(&source).map_err(|e| e.named(&naming))?;
    if let Some(b) = args.boundary {
        mesh.tags.boundary = b.into();
    }
    let name = source.name.as_str();
    let to_terminal =
        args.output.is_none() && args.format.is_none() && std::io::stdout().is_terminal();
    if !to_terminal && super::surface_stream::streams(args, &mesh) {
        let streamed = match (args.format(), args.precision) {
            (SurfaceFormat::Obj, _) => {
                super::surface_stream::obj(name, &naming, &mesh, &tables, args)
            }
            (_, Precision::F64) => {
                super::surface_stream::json::<f64>(name, &naming, &mesh, &tables, args, "f64")
            }
            (_, Precision::F32) => {
                super::surface_stream::json::<f32>(name, &naming, &mesh, &tables, args, "f32")
            }
        };
        return streamed.map_err(|e| e.named(&naming));
    }
    let input = (&mesh, objects.as_slice());
    let (bytes, report) = match args.precision {
        Precision::F64 => produce::<f64>(name, &naming, input, &tables, args, "f64", WELD_F64),
        Precision::F32 => produce::<f32>(name, &naming, input, &tables, args, "f32", WELD_F32),
    }
    .map_err(|e| e.named(&naming))?;
    // A terminal gets the summary, not megabytes of patches, unless a
    // format was asked for.
    if to_terminal {
        let mut out = Outcome::new(Vec::new(), Sink::Stdout);
        out.report = if args.quiet { String::new() } else { report };
        out.report.push_str(TERMINAL_HINT);
        return Ok(out);
    }
    let mut out = Outcome::new(bytes, Sink::from_option(args.output.clone()));
    if !args.quiet {
        out.report = report;
    }
    Ok(out)
}

/// Reads the `--eg-table N=FILE` options: `N` in 6..=10, each once, the file's
/// valence `N`, the table accepted by the kernel ([`Table::rule`]).
pub fn read_tables(specs: &[String]) -> Result<Vec<Table>, CliError> {
    let mut tables: Vec<Table> = Vec::new();
    for spec in specs {
        let bad = || {
            CliError::Usage(format!(
                "--eg-table expects N=FILE with N in 6..10, got '{spec}'"
            ))
        };
        let (n, file) = spec.split_once('=').ok_or_else(bad)?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        if !TABLE_VALENCES.contains(&n) || file.is_empty() {
            return Err(bad());
        }
        if tables.iter().any(|t| t.valence == n) {
            return Err(CliError::Usage(format!(
                "--eg-table gives valence {n} more than once"
            )));
        }
        let table = Table::read(file)?;
        if table.valence != n {
            return Err(CliError::Usage(format!(
                "{}: the rule table is for valence {}, --eg-table names valence {n}",
                table.name, table.valence
            )));
        }
        table.rule()?;
        tables.push(table);
    }
    Ok(tables)
}

/// The mesh of a source: JSON (`kind: "mesh"`) when it looks like JSON, OBJ
/// otherwise.
pub fn read_mesh(source: &Source) -> Result<MeshInput, CliError> {
    read_mesh_objects(source).map(|(mesh, _)| mesh)
}

/// [`read_mesh`] and the OBJ's named objects ([`parse_obj_objects`]; none
/// for JSON).
pub fn read_mesh_objects(source: &Source) -> Result<(MeshInput, Vec<ObjObject>), CliError> {
    let mesh_err = |error| CliError::mesh(&source.name, error);
    if looks_like_json(&source.text) {
        match parse(&source.name, &source.text)? {
            Input::Mesh(m) => m.to_mesh(&source.name).map(|m| (m, Vec::new())),
            other => Err(CliError::WrongKind {
                source: source.name.clone(),
                kind: other.kind(),
                need: "surface needs a 'mesh' input (or a Wavefront OBJ)".into(),
            }),
        }
    } else {
        parse_obj_objects(&source.text).map_err(mesh_err)
    }
}

fn produce<R: Scalar>(
    name: &str,
    naming: &Naming,
    (mesh, objects): (&MeshInput, &[ObjObject]),
    tables: &[Table],
    args: &SurfaceArgs,
    precision: &str,
    weld: f64,
) -> Result<(Vec<u8>, String), CliError> {
    let options = SchemeOptions {
        depth: args.depth,
        tables,
        precision,
        catmull_clark: args.scheme == SurfaceScheme::CatmullClark,
        max_patches: args.max_patches.unwrap_or(DEFAULT_MAX_PATCHES),
        tolerance: args.tolerance,
        threads: args.threads.map(|t| t as usize),
    };
    let surface = build_with::<R>(name, mesh, &options)?;
    // The f64 surface that f32 output is joined and welded by.
    let f64_guide = || -> Result<Option<Surface<f64>>, CliError> {
        if precision != "f32" {
            return Ok(None);
        }
        let options = SchemeOptions {
            precision: "f64",
            ..options
        };
        build_with::<f64>(name, mesh, &options).map(Some)
    };
    let grid = args.grid as usize;
    let format = args.format();
    Ok(match format {
        SurfaceFormat::Json => {
            // The patches and caps are serialised as they are made.
            let out = SurfaceJson {
                patches: Lazy(|| {
                    let uv = |k| surface.uvs.get(k);
                    (surface.patches.iter().enumerate())
                        .map(move |(k, p)| PatchJson::new(p).with_uv(uv(k)))
                }),
                caps: Lazy(|| surface.caps.iter().map(CapJson::new)),
                summary: &surface.summary,
            };
            let report = report(name, &surface.summary, None, naming);
            let text = try_to_json(&out, args.pretty).map_err(CliError::out_of_memory_in(name))?;
            (text, report)
        }
        SurfaceFormat::Step => {
            // f32 patches are joined where the f64 ones are (see
            // `step::brep_guided`).
            let guide = f64_guide()?;
            let mut report = report(name, &surface.summary, None, naming);
            let (text, line) = step_text(&surface, guide.as_ref(), mesh, name, args, precision)?;
            report.push_str(&line);
            (text.into_bytes(), report)
        }
        SurfaceFormat::Obj | SurfaceFormat::Png | SurfaceFormat::Glb | SurfaceFormat::Gltf => {
            // f32 output is welded where the f64 surface welds (see
            // `tessellate_surface`); f64 output needs no guide.
            let guide = f64_guide()?;
            // glTF groups faces by input face (its objects); the others colour
            // them by level.
            let tag = match format {
                SurfaceFormat::Glb | SurfaceFormat::Gltf => |p: &PatchRecord<_>| p.face,
                _ => |p: &PatchRecord<_>| p.level,
            };
            let tess = tessellate_surface_tagged(&surface, mesh, grid, weld, guide.as_ref(), tag)
                .map_err(CliError::out_of_memory_in(name))?;
            let mut report = report(name, &surface.summary, Some(&tess.info), naming);
            let bytes = match format {
                SurfaceFormat::Obj => {
                    let title = format!(
                        "capdiv surface --depth {} --tolerance {} --grid {grid} --precision \
                         {precision} {name}",
                        args.depth, args.tolerance
                    );
                    obj_text(&tess, &surface.summary, &title)
                        .map_err(CliError::out_of_memory_in(name))?
                        .into_bytes()
                }
                SurfaceFormat::Png => {
                    super::patches::png_bytes(name, &tess.mesh, None, args.up.into())?
                }
                _ => {
                    let memory = CliError::out_of_memory_in(name);
                    let groups = gltf::groups(&tess.mesh.tags, objects).map_err(&memory)?;
                    let doc = gltf::document(&tess.mesh, &groups).map_err(&memory)?;
                    let _ = writeln!(
                        report,
                        "  gltf         {}, {}, {}",
                        count(doc.nodes, "node", "nodes"),
                        count(doc.vertices, "vertex", "vertices"),
                        count(doc.triangles, "triangle", "triangles")
                    );
                    if format == SurfaceFormat::Glb {
                        gltf::glb(&doc).map_err(&memory)?
                    } else {
                        gltf::gltf_text(&doc).map_err(&memory)?
                    }
                }
            };
            (bytes, report)
        }
    })
}

/// The STEP file of a surface ([`step`]; with a `guide`, the same surface
/// in f64, joined where the guide's faces join) and its summary line
/// `  step         F faces (P patches, H hole fills), E edges, V vertices;
/// closed shell; volume X; T ms` (or `open shell (N free edges); T ms`);
/// the one-line out-of-memory error when the B-rep or its text cannot be
/// allocated.
pub fn step_text<R: Scalar>(
    surface: &Surface<R>,
    guide: Option<&Surface<f64>>,
    mesh: &MeshInput,
    name: &str,
    args: &SurfaceArgs,
    precision: &str,
) -> Result<(String, String), CliError> {
    let oom = CliError::out_of_memory_in(name);
    let start = Instant::now();
    let faces = step::faces(&surface.patches).map_err(&oom)?;
    let (tol, _) = weld_tolerance(mesh, WELD_F64);
    let size = step::model_size(&faces);
    let b = match guide {
        Some(g) => step::brep_guided(
            faces,
            &step::faces(&g.patches).map_err(&oom)?,
            tol,
            step::UNCERTAINTY * size,
        ),
        None => step::brep(faces, tol, step::UNCERTAINTY * size),
    }
    .map_err(&oom)?;
    let file_name = args
        .output
        .as_ref()
        .and_then(|p| p.file_name())
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_else(|| "capdiv.step".into());
    let header = step::Header {
        file_name,
        product: name.to_string(),
        time_stamp: step::time_stamp(std::time::SystemTime::now()),
        description: format!(
            "capdiv surface --depth {} --tolerance {} --precision {} {name}",
            args.depth, args.tolerance, precision
        ),
    };
    let text = step::write(&b, &header).map_err(&oom)?;
    let patches = surface.patches.len();
    let shell = if b.is_closed().map_err(&oom)? {
        format!("closed shell; volume {}", step::volume(&b.faces))
    } else {
        format!(
            "open shell ({})",
            count(b.free_edges(), "free edge", "free edges")
        )
    };
    let line = format!(
        "  step         {} ({} patches, {} hole fills), {}, {}; {shell}; {:.1} ms\n",
        count(b.faces.len(), "face", "faces"),
        patches,
        b.faces.len() - patches,
        count(b.edges.len(), "edge", "edges"),
        count(b.vertices.len(), "vertex", "vertices"),
        start.elapsed().as_secs_f64() * 1e3
    );
    Ok((text, line))
}

/// A surface: every patch and cap the evaluator gave, and the summary.
#[derive(Clone, Debug)]
pub struct Surface<R> {
    /// Patches in the evaluator's order (regular faces, then cap by cap).
    pub patches: Vec<PatchRecord<R>>,
    /// Caps in the evaluator's order (polar first, then EG / Catmull-Clark).
    pub caps: Vec<CapRecord<R>>,
    /// Per patch, its texture coordinates ([`FaceVarying`]) when the input
    /// has UVs; empty otherwise.
    pub uvs: Vec<PatchUv>,
    /// Counts, reasons, times.
    pub summary: Summary,
}

/// Validates, analyses and evaluates `mesh` in `R` (positions cast), the
/// default scheme.
pub fn build<R: Scalar>(
    name: &str,
    mesh: &MeshInput,
    depth: u32,
    tables: &[Table],
    precision: &str,
) -> Result<Surface<R>, CliError> {
    build_scheme(
        name,
        mesh,
        depth,
        tables,
        precision,
        false,
        DEFAULT_MAX_PATCHES,
    )
}

/// [`build`], with Catmull-Clark caps everywhere when `catmull_clark`
/// (`--scheme catmull-clark`), refusing a surface of more than
/// `max_patches` patches before making any.
pub fn build_scheme<R: Scalar>(
    name: &str,
    mesh: &MeshInput,
    depth: u32,
    tables: &[Table],
    precision: &str,
    catmull_clark: bool,
    max_patches: u64,
) -> Result<Surface<R>, CliError> {
    let options = SchemeOptions {
        depth,
        tables,
        precision,
        catmull_clark,
        max_patches,
        tolerance: Tolerance::None,
        threads: None,
    };
    build_with(name, mesh, &options)
}

/// [`build_scheme`] with all of `surface`'s options.
pub fn build_with<R: Scalar>(
    name: &str,
    mesh: &MeshInput,
    options: &SchemeOptions<'_>,
) -> Result<Surface<R>, CliError> {
    let mut sink = CollectSurface::new();
    let (summary, facevarying) = run_scheme::<R>(name, mesh, options, &mut sink)?;
    let (patches, caps) = sink.finish().map_err(CliError::out_of_memory_in(name))?;
    let uvs = match facevarying {
        Some(fv) => capdiv_mesh::mem::collect(patches.iter().map(|p| fv.patch(p)))
            .map_err(CliError::out_of_memory_in(name))?,
        None => Vec::new(),
    };
    Ok(Surface {
        patches,
        caps,
        uvs,
        summary,
    })
}

/// How `surface` plans and evaluates.
#[derive(Clone, Copy, Debug)]
pub struct SchemeOptions<'a> {
    /// Rings every cap emits at most.
    pub depth: u32,
    /// `--eg-table` rules.
    pub tables: &'a [Table],
    /// `f64` or `f32` (for the summary).
    pub precision: &'a str,
    /// Catmull-Clark caps everywhere.
    pub catmull_clark: bool,
    /// Refuse a plan of more patches.
    pub max_patches: u64,
    /// When caps stop emitting rings.
    pub tolerance: Tolerance,
    /// Threads that evaluate (`None`: [`crate::threads::default_threads`]).
    pub threads: Option<usize>,
}

/// Validates, analyses and evaluates `mesh` in `R` into `sink`, refusing a
/// surface of more than `options.max_patches` patches before making any;
/// returns the summary and, when the mesh has UVs, their face-varying
/// interpolation over the plan. A surface that is not finite or has no patch is an
/// error after the evaluation (a streaming sink has then written part of it).
pub fn run_scheme<R: Scalar>(
    name: &str,
    mesh: &MeshInput,
    options: &SchemeOptions<'_>,
    sink: &mut (dyn SurfaceSink<R> + Send),
) -> Result<(Summary, Option<FaceVarying>), CliError> {
    let mesh_err = |error| CliError::mesh(name, error);
    let eval_err = |error| CliError::eval(name, error);
    let surface_err = |error| CliError::surface(name, error);
    let start = Instant::now();
    let eg_tables = options
        .tables
        .iter()
        .map(Table::rule)
        .collect::<Result<_, _>>()?;
    let catmull_clark = options.catmull_clark;
    // Some exactly when `--tolerance` is given: the patch count is then an
    // upper bound.
    let tolerance = options.tolerance.absolute(diagonal(mesh));
    let bounded = BoundedPlan::new(
        mesh,
        PlanOptions {
            depth: options.depth,
            eg_tables,
            catmull_clark,
        },
        options.max_patches,
        tolerance,
    )
    .map_err(surface_err)?;
    let plan = bounded.plan();
    let analysis = start.elapsed();

    let start = Instant::now();
    let memory = CliError::out_of_memory_in(name);
    let positions: Vec<[R; 3]> =
        capdiv_mesh::mem::collect(mesh.vertices.iter().map(|p| p.map(R::from_f64)))
            .map_err(&memory)?;
    let mut evaluator = bounded.evaluator::<R>().map_err(surface_err)?;
    let mut stats = SurfaceStats::new();
    crate::threads::evaluate(
        options.threads,
        &mut evaluator,
        &positions,
        &mut Tee(&mut stats, &mut *sink),
    )
    .map_err(eval_err)?;
    let evaluation = start.elapsed();

    if let Some(e) = stats.refused() {
        return Err(CliError::out_of_memory(name, e.bytes));
    }
    if !stats.finite {
        return Err(CliError::NonFiniteResult {
            source: name.to_string(),
        });
    }
    if stats.patches.total == 0 {
        return Err(CliError::EmptySurface {
            source: name.to_string(),
        });
    }
    let mut caps: Vec<CapCount> = stats.caps.iter().map(CapCount::from).collect();
    caps.sort_by_key(|k| (k.scheme, k.valence));
    let reasons = |list: &[capdiv_mesh::plan::UncoveredFace]| {
        capdiv_mesh::mem::collect(list.iter().map(|u| FaceReason {
            face: u.face,
            reason: u.reason.id(),
            description: u.reason.describe(),
        }))
        .map_err(&memory)
    };
    // An input whose topology cannot be built for want of memory is an
    // error, not an open surface.
    let closed = mesh.tags.holes.is_empty()
        && match Topology::new(mesh) {
            Ok(t) => t.is_closed(),
            Err(capdiv_mesh::MeshError::OutOfMemory { bytes }) => {
                return Err(CliError::out_of_memory(name, bytes))
            }
            Err(_) => false,
        };
    let mut levels = stats.levels;
    if levels.is_empty() {
        levels.push(0);
    }
    let summary = Summary {
        input: InputSummary {
            vertices: plan.input_vertices,
            faces: plan.input_faces,
            closed,
        },
        depth: options.depth,
        tolerance,
        rings: stats.rings,
        precision: options.precision.to_string(),
        scheme: if catmull_clark {
            SurfaceScheme::CatmullClark
        } else {
            SurfaceScheme::Default
        }
        .name(),
        tags: TagSummary::of(&mesh.tags),
        patches: stats.patches,
        caps,
        refinement_steps: plan.steps.len(),
        needed_refinement: reasons(&plan.needed_refinement)?,
        uncovered: reasons(&plan.uncovered)?,
        patches_per_level: levels,
        last_holes: plan.last_holes.len(),
        fallbacks: capdiv_mesh::mem::collect(plan.input_fallbacks().map(|(vertex, r)| Fallback {
            vertex: vertex + 1,
            reason: r.id(),
            description: r.describe(),
        }))
        .map_err(&memory)?,
        times_ms: Times {
            analysis: analysis.as_secs_f64() * 1e3,
            evaluation: evaluation.as_secs_f64() * 1e3,
        },
    };
    let facevarying = FaceVarying::new(mesh, plan).map_err(mesh_err)?;
    Ok((summary, facevarying))
}

/// `{"patches", "caps", "summary"}`: the patches' and caps' arrays
/// ([`Lazy`]) of [`PatchJson`] and [`CapJson`].
#[derive(Serialize)]
#[serde(bound = "Lazy<P>: Serialize, Lazy<C>: Serialize")]
struct SurfaceJson<'a, P, C> {
    patches: Lazy<P>,
    caps: Lazy<C>,
    summary: &'a Summary,
}

/// One patch as printed.
#[derive(Clone, Debug, Serialize)]
#[serde(bound = "R: Copy + Serialize")]
pub struct PatchJson<'a, R> {
    /// `regular`, `c2ps`, `eg` or `catmull-clark`.
    pub kind: &'static str,
    /// 3 (bicubic) or 4 (bi-quartic, EG).
    pub degree: usize,
    /// The patch is `2^-level` of its input face across.
    pub level: u32,
    /// The input face it lies in.
    pub face: u32,
    /// Non-quad faces: the corner whose sub-quad holds the patch.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub corner: Option<u8>,
    /// `[u0, u1, v0, v1]` in the face's (or sub-quad's) square.
    pub domain: [f64; 4],
    /// `(d+1)²` points, `points[(d+1)·j + i]` = `b_ij`, `i` along `u`.
    pub points: ControlPoints<'a, R>,
    /// With input UVs: the texture coordinates at the patch's corners
    /// `(u, v)` = (0,0), (1,0), (1,1), (0,1), bilinear in between.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub uv: Option<[[f64; 2]; 4]>,
}

impl<'a, R: Scalar> PatchJson<'a, R> {
    /// From an evaluator record (its control points are written from the
    /// record itself, no copy is made).
    pub fn new(p: &'a PatchRecord<R>) -> Self {
        use capdiv_mesh::tessellate::PatchGeometry;
        let degree = match &p.geometry {
            PatchGeometry::Cubic(_) => 3,
            PatchGeometry::Quartic(_) => 4,
        };
        PatchJson {
            kind: p.kind.id(),
            degree,
            level: p.level,
            face: p.face,
            corner: p.corner,
            domain: p.domain,
            points: ControlPoints(&p.geometry),
            uv: None,
        }
    }

    /// The patch with its texture coordinates, if given.
    pub fn with_uv(mut self, uv: Option<&PatchUv>) -> Self {
        self.uv = uv.map(|u| u.corners);
        self
    }
}

/// A patch's control points as printed: `(d+1)²` points, row `j` (along
/// `v`) after row, `i` (along `u`) within a row.
#[derive(Clone, Copy, Debug)]
pub struct ControlPoints<'a, R>(pub &'a capdiv_mesh::tessellate::PatchGeometry<R>);

impl<R: Copy + Serialize> Serialize for ControlPoints<'_, R> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use capdiv_mesh::tessellate::PatchGeometry;
        fn by_rows<R: Copy + Serialize, S: serde::Serializer, const K: usize>(
            pts: &[[Point3<R>; K]; K],
            serializer: S,
        ) -> Result<S::Ok, S::Error> {
            serializer.collect_seq((0..K).flat_map(|j| (0..K).map(move |i| pts[i][j].0)))
        }
        match self.0 {
            PatchGeometry::Cubic(t) => by_rows(&t.points, serializer),
            PatchGeometry::Quartic(t) => by_rows(&t.points, serializer),
        }
    }
}

/// One cap as printed.
#[derive(Clone, Debug, Serialize)]
pub struct CapJson<R> {
    /// The input vertex at its centre (`null` for a face centre).
    pub vertex: Option<u32>,
    /// The input face whose centre it is (only when `vertex` is `null`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub face: Option<u32>,
    /// `c2ps`, `eg` or `catmull-clark`.
    pub scheme: &'static str,
    /// Valence in the input.
    pub valence: usize,
    /// Limit point.
    pub limit: [R; 3],
    /// Unit normal, `null` if degenerate.
    pub normal: Option<[R; 3]>,
    /// C²PS only: principal curvatures, else `null`.
    pub principal_curvatures: Option<[R; 2]>,
}

impl<R: Scalar> CapJson<R> {
    /// From an evaluator record.
    pub fn new(c: &CapRecord<R>) -> Self {
        CapJson {
            vertex: c.vertex,
            face: if c.vertex.is_none() { c.face } else { None },
            scheme: c.scheme.id(),
            valence: c.valence,
            limit: c.limit.0,
            normal: c.normal.filter(|n| n.is_finite()).map(|n| n.0),
            principal_curvatures: c
                .principal_curvatures
                .filter(|k| k.iter().all(|v| v.is_finite())),
        }
    }
}

/// The summary (JSON `summary`, and the stderr block).
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// Counts of the input.
    pub input: InputSummary,
    /// `--depth`.
    pub depth: u32,
    /// The hole tolerance applied (absolute; `None`: every cap `depth` rings).
    pub tolerance: Option<f64>,
    /// Fewest and most rings a cap emitted (`None`: no cap).
    pub rings: Option<[u32; 2]>,
    /// `f64` or `f32`.
    pub precision: String,
    /// `--scheme`: `default` or `catmull-clark`.
    pub scheme: &'static str,
    /// The subdivision tags the analysis was given.
    pub tags: TagSummary,
    /// Patches per kind.
    #[serde(serialize_with = "patch_counts_json")]
    pub patches: PatchCounts,
    /// Caps per scheme and valence.
    pub caps: Vec<CapCount>,
    /// Whole-mesh refinement steps taken (0..=2; only when every face needs
    /// refinement, or for a polar fan whose C²PS configuration a step
    /// completes).
    pub refinement_steps: usize,
    /// Input faces that needed refinement: those that made the first
    /// whole-mesh step necessary, else those refined adaptively.
    pub needed_refinement: Vec<FaceReason>,
    /// Input faces left without a patch.
    pub uncovered: Vec<FaceReason>,
    /// Patches per subdivision level relative to the input (index = level).
    pub patches_per_level: Vec<usize>,
    /// Faces of the adaptive refinement left as the last hole around an
    /// irregular vertex (closed by fans in the OBJ).
    pub last_holes: usize,
    /// Vertices where a C²PS or EG configuration type is but the cap fell
    /// back to Catmull-Clark, and why (1-based vertex numbers, as in OBJ).
    pub fallbacks: Vec<Fallback>,
    /// Wall-clock times (vary from run to run).
    pub times_ms: Times,
}

/// A vertex whose cap fell back to Catmull-Clark.
#[derive(Clone, Debug, Serialize)]
pub struct Fallback {
    /// The vertex, 1-based.
    pub vertex: u32,
    /// Reason identifier.
    pub reason: &'static str,
    /// What it means.
    pub description: &'static str,
}

/// The subdivision tags of the input (after `--boundary`).
#[derive(Clone, Debug, Serialize)]
pub struct TagSummary {
    /// Edge sharpness entries.
    pub creases: usize,
    /// Vertex sharpness entries.
    pub corners: usize,
    /// Hole faces.
    pub holes: usize,
    /// `none`, `edge-only` or `edge-and-corner`.
    pub boundary: &'static str,
    /// `normal` or `chaikin`.
    pub crease_method: &'static str,
    /// `catmark` or `smooth`: the edge rule next to triangles.
    pub triangles: &'static str,
    /// OBJ tags read but not applied, with their 1-based line.
    pub ignored: Vec<IgnoredTag>,
}

/// An OBJ tag not applied.
#[derive(Clone, Debug, Serialize)]
pub struct IgnoredTag {
    /// Its name.
    pub name: String,
    /// Its 1-based line.
    pub line: usize,
}

impl TagSummary {
    /// Counts and rules of `tags`.
    pub fn of(tags: &capdiv_mesh::SubdivTags) -> Self {
        TagSummary {
            creases: tags.creases.len(),
            corners: tags.corners.len(),
            holes: tags.holes.len(),
            boundary: tags.boundary.id(),
            crease_method: tags.crease_method.id(),
            triangles: tags.triangles.id(),
            ignored: tags
                .ignored
                .iter()
                .map(|(name, line)| IgnoredTag {
                    name: name.clone(),
                    line: *line,
                })
                .collect(),
        }
    }

    /// The summary line after `  tags         `.
    fn text(&self, scheme: &str) -> String {
        let ignored: Vec<String> = self
            .ignored
            .iter()
            .map(|t| format!("{} (line {})", t.name, t.line))
            .collect();
        format!(
            "{}, {}, {}; boundary {}, creasing {}, triangles {}; scheme {}; ignored tags: {}",
            count(self.creases, "crease", "creases"),
            count(self.corners, "corner", "corners"),
            count(self.holes, "hole", "holes"),
            self.boundary,
            self.crease_method,
            self.triangles,
            scheme,
            if ignored.is_empty() {
                "none".to_string()
            } else {
                ignored.join(", ")
            }
        )
    }
}

/// Input counts.
#[derive(Clone, Debug, Serialize)]
pub struct InputSummary {
    /// Vertices.
    pub vertices: usize,
    /// Faces.
    pub faces: usize,
    /// Whether the input has no boundary edge.
    pub closed: bool,
}

/// `patches` of the JSON summary: the count of each kind under its id
/// ([`PatchKind::id`]), then `total`.
fn patch_counts_json<S: serde::Serializer>(p: &PatchCounts, s: S) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeStruct;
    let mut fields = s.serialize_struct("PatchCounts", PatchKind::ALL.len() + 1)?;
    for kind in PatchKind::ALL {
        fields.serialize_field(kind.id(), &p.of(kind))?;
    }
    fields.serialize_field("total", &p.total)?;
    fields.end()
}

/// Caps of one scheme and valence, as printed
/// ([`capdiv_mesh::sinks::CapCount`]).
#[derive(Clone, Debug, Serialize)]
pub struct CapCount {
    /// Scheme id.
    pub scheme: &'static str,
    /// Valence in the input.
    pub valence: usize,
    /// How many.
    pub count: usize,
}

impl From<&capdiv_mesh::sinks::CapCount> for CapCount {
    fn from(c: &capdiv_mesh::sinks::CapCount) -> Self {
        CapCount {
            scheme: c.scheme.id(),
            valence: c.valence,
            count: c.count,
        }
    }
}

/// An input face with a reason.
#[derive(Clone, Debug, Serialize)]
pub struct FaceReason {
    /// The input face.
    pub face: u32,
    /// Reason id.
    pub reason: &'static str,
    /// In words.
    pub description: &'static str,
}

/// Times in milliseconds.
#[derive(Clone, Debug, Serialize)]
pub struct Times {
    /// Topology, plan (with refinement).
    pub analysis: f64,
    /// Evaluation of every patch and cap.
    pub evaluation: f64,
}

/// The length of the input's bounding-box diagonal (0 for an empty or
/// non-finite box).
pub fn diagonal(mesh: &MeshInput) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &mesh.vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let d = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    if d.is_finite() {
        d
    } else {
        0.0
    }
}

/// The weld tolerance: `factor ×` the largest side of the input's bounding
/// box (0 for an empty or degenerate box).
pub fn weld_tolerance(mesh: &MeshInput, factor: f64) -> (f64, f64) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &mesh.vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0f64, f64::max);
    let size = if size.is_finite() { size } else { 0.0 };
    (factor * size, size)
}

/// What the tessellation gave.
#[derive(Clone, Debug)]
pub struct TessInfo {
    /// Grid segments per patch side.
    pub grid: usize,
    /// Weld tolerance used (absolute).
    pub tolerance: f64,
    /// Its factor and the bounding-box size.
    pub factor: f64,
    /// Bounding-box size of the input.
    pub size: f64,
    /// Welded vertices.
    pub vertices: usize,
    /// Triangles.
    pub triangles: usize,
    /// Quads.
    pub quads: usize,
    /// Faces dropped by welding.
    pub degenerate_dropped: usize,
    /// The closedness check.
    pub closed: Result<(), BadEdge>,
    /// Milliseconds.
    pub time_ms: f64,
}

/// A tessellated surface.
pub struct Tess<R> {
    /// The welded mesh.
    pub mesh: Tessellation<R>,
    /// Counts and the closedness check.
    pub info: TessInfo,
}

/// Tessellates and welds the surface's patches (see the module doc). With a
/// `guide` (the same surface in f64, for f32 output), samples weld where the
/// guide's samples weld within [`WELD_F64`] of the size: near a deep pole the
/// f32 samples lie closer together than f32 rounding lets any single
/// tolerance separate (measured: the hand at depth 4 does not close with any
/// f32 tolerance from 1e-4 to 1e-6), while the f64 connectivity is exact.
pub fn tessellate_surface<R: Scalar>(
    surface: &Surface<R>,
    mesh: &MeshInput,
    grid: usize,
    factor: f64,
    guide: Option<&Surface<f64>>,
) -> Result<Tess<R>, OutOfMemory> {
    tessellate_surface_tagged(surface, mesh, grid, factor, guide, |p| p.level)
}

/// [`tessellate_surface`] with each face tagged `tag(its patch)` (there: the
/// patch's level).
pub fn tessellate_surface_tagged<R: Scalar>(
    surface: &Surface<R>,
    mesh: &MeshInput,
    grid: usize,
    factor: f64,
    guide: Option<&Surface<f64>>,
    tag: fn(&PatchRecord<R>) -> u32,
) -> Result<Tess<R>, OutOfMemory> {
    let start = Instant::now();
    let (tolerance, size) = weld_tolerance(mesh, factor);
    fn tess_patches<S: capdiv::Real>(
        s: &Surface<S>,
        tag: fn(&PatchRecord<S>) -> u32,
    ) -> impl Iterator<Item = (PatchRecord<S>, u32)> + '_ {
        s.patches.iter().enumerate().map(move |(k, p)| {
            let record = PatchRecord {
                uv: s.uvs.get(k).copied(),
                ..p.clone()
            };
            (record, tag(p))
        })
    }
    let t = match guide {
        Some(g) => {
            let (guide_tolerance, _) = weld_tolerance(mesh, WELD_F64);
            try_tessellate_guided(
                tess_patches(surface, tag),
                tess_patches(g, |p| p.level),
                grid,
                guide_tolerance,
                R::from_f64(tolerance),
            )?
        }
        None => try_tessellate(tess_patches(surface, tag), grid, R::from_f64(tolerance))?,
    };
    // Report the tolerance that decided the welding.
    let (tolerance, factor) = match guide {
        Some(_) => (weld_tolerance(mesh, WELD_F64).0, WELD_F64),
        None => (tolerance, factor),
    };
    let triangles = t.faces.iter().filter(|f| matches!(f, Face::Tri(_))).count();
    let info = TessInfo {
        grid,
        tolerance,
        factor,
        size,
        vertices: t.positions.len(),
        triangles,
        quads: t.faces.len() - triangles,
        degenerate_dropped: t.degenerate_dropped,
        closed: closed_through_seams(&t)?,
        time_ms: start.elapsed().as_secs_f64() * 1e3,
    };
    Ok(Tess { mesh: t, info })
}

/// [`try_closed_and_oriented`] of the tessellation, UV seams joined (a
/// seam splits vertices for the texture, not the surface).
fn closed_through_seams<R>(t: &Tessellation<R>) -> Result<Result<(), BadEdge>, OutOfMemory> {
    if t.seam_origin.is_empty() {
        return try_closed_and_oriented(&t.faces);
    }
    let origin = |i: &u32| t.seam_origin.get(*i as usize).copied().unwrap_or(*i);
    let faces: Vec<Face> = capdiv_mesh::mem::collect(t.faces.iter().map(|f| match f {
        Face::Tri(c) => Face::Tri([origin(&c[0]), origin(&c[1]), origin(&c[2])]),
        Face::Quad(c) => Face::Quad(c.each_ref().map(origin)),
    }))?;
    try_closed_and_oriented(&faces)
}

/// The closedness check in words.
pub fn closed_text(closed: &Result<(), BadEdge>) -> String {
    match closed {
        Ok(()) => "closed and consistently oriented".into(),
        Err(b) => {
            let what = match b.fault {
                EdgeFault::Degenerate => "degenerate",
                EdgeFault::Unpaired => "used by one face only",
                EdgeFault::SameDirection => "used twice in the same direction",
                EdgeFault::Overused => "used by more than two faces",
            };
            format!(
                "not closed: the edge from vertex {} to vertex {} of face {} (1-based, as in \
                 the OBJ written) is {what}",
                b.from as u64 + 1,
                b.to as u64 + 1,
                b.face as u64 + 1
            )
        }
    }
}

/// OBJ text with a header describing the surface.
pub fn obj_text<R: Scalar>(
    tess: &Tess<R>,
    summary: &Summary,
    title: &str,
) -> Result<String, OutOfMemory> {
    let i = &tess.info;
    let header = [
        title.to_string(),
        format!(
            "{} ({} regular, {} c2ps, {} eg, {} catmull-clark), {}",
            count(summary.patches.total, "patch", "patches"),
            summary.patches.regular,
            summary.patches.c2ps,
            summary.patches.eg,
            summary.patches.catmull_clark,
            count(
                summary.caps.iter().map(|c| c.count).sum::<usize>(),
                "cap",
                "caps"
            )
        ),
        format!(
            "grid {}x{} per patch; welded within {} ({} x bounding-box size {})",
            i.grid,
            i.grid,
            sig(i.tolerance, 3),
            sig(i.factor, 3),
            sig(i.size, 6)
        ),
        format!(
            "{}, {} ({}, {}); {}",
            count(i.vertices, "vertex", "vertices"),
            count(i.triangles + i.quads, "face", "faces"),
            count(i.triangles, "triangle", "triangles"),
            count(i.quads, "quad", "quads"),
            closed_text(&i.closed)
        ),
    ];
    try_write_obj(&tess.mesh, &header)
}

/// The human-readable summary block (stderr); faces and vertices numbered
/// as the input counts them (`naming`).
pub fn report(name: &str, s: &Summary, tess: Option<&TessInfo>, naming: &Naming) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "capdiv surface: {name}: {}, {} ({}); depth {}, {}",
        count(s.input.vertices, "vertex", "vertices"),
        count(s.input.faces, "face", "faces"),
        if s.input.closed { "closed" } else { "open" },
        s.depth,
        s.precision
    );
    let _ = writeln!(t, "  tags         {}", s.tags.text(s.scheme));
    if let Some([lo, hi]) = s.rings {
        let range = if lo == hi {
            format!("{lo}")
        } else {
            format!("{lo}-{hi}")
        };
        let _ = writeln!(
            t,
            "  rings        {range} per cap (--depth {}; {})",
            s.depth,
            match s.tolerance {
                Some(tol) => format!("holes closed at width {}", sig(tol, 3)),
                None => "no tolerance".to_string(),
            }
        );
    }
    let p = &s.patches;
    let _ = writeln!(
        t,
        "  patches      {} ({} regular, {} c2ps, {} eg, {} catmull-clark)",
        p.total, p.regular, p.c2ps, p.eg, p.catmull_clark
    );
    let caps: Vec<String> = s
        .caps
        .iter()
        .map(|c| format!("{} x{} n={}", c.scheme, c.count, c.valence))
        .collect();
    let _ = writeln!(
        t,
        "  caps         {}",
        if caps.is_empty() {
            "none".to_string()
        } else {
            caps.join(", ")
        }
    );
    let _ = writeln!(
        t,
        "  refinement   {}",
        if s.refinement_steps > 0 {
            format!(
                "{}{}",
                count(s.refinement_steps, "whole-mesh step", "whole-mesh steps"),
                faces_by_reason(&s.needed_refinement, " needed by", naming)
            )
        } else if s.needed_refinement.is_empty() {
            "none".to_string()
        } else {
            format!(
                "adaptive{}",
                faces_by_reason(&s.needed_refinement, ",", naming)
            )
        }
    );
    let _ = writeln!(
        t,
        "  uncovered    {}{}",
        s.uncovered.len(),
        faces_by_reason(&s.uncovered, ":", naming)
    );
    let levels: Vec<String> = s
        .patches_per_level
        .iter()
        .enumerate()
        .filter(|(_, &n)| n > 0)
        .map(|(l, n)| format!("{l}: {n}"))
        .collect();
    let _ = writeln!(
        t,
        "  levels       patches per level {}; {} closed by fans",
        levels.join(", "),
        count(s.last_holes, "last hole", "last holes")
    );
    if !s.fallbacks.is_empty() {
        let mut by: Vec<(&str, Vec<u32>)> = Vec::new();
        for f in &s.fallbacks {
            match by.iter_mut().find(|(d, _)| *d == f.description) {
                Some((_, v)) => v.push(f.vertex),
                None => by.push((f.description, vec![f.vertex])),
            }
        }
        let text: Vec<String> = by
            .iter()
            .map(|(d, vs)| {
                // `Fallback::vertex` is 1-based; shown as the input counts.
                let shown: Vec<String> = vs
                    .iter()
                    .take(8)
                    .map(|&v| naming.number(v as usize - 1).to_string())
                    .collect();
                let more = if vs.len() > 8 {
                    format!(" and {} more", vs.len() - 8)
                } else {
                    String::new()
                };
                format!(
                    "{} ({}{more}): {d}",
                    count(vs.len(), "vertex", "vertices"),
                    shown.join(", ")
                )
            })
            .collect();
        let _ = writeln!(t, "  fallback     Catmull-Clark at {}", text.join("; "));
    }
    if let Some(i) = tess {
        let _ = writeln!(
            t,
            "  tessellation {}, {}, {} (grid {}, weld {}); {}",
            count(i.vertices, "vertex", "vertices"),
            count(i.triangles, "triangle", "triangles"),
            count(i.quads, "quad", "quads"),
            i.grid,
            sig(i.tolerance, 3),
            closed_text(&i.closed)
        );
    }
    let _ = write!(
        t,
        "  time         analysis {:.1} ms, evaluation {:.1} ms",
        s.times_ms.analysis, s.times_ms.evaluation
    );
    if let Some(i) = tess {
        let _ = write!(t, ", tessellation {:.1} ms", i.time_ms);
    }
    t.push('\n');
    t
}

/// ` needed by N faces (reason: faces …; …)`, faces listed up to 8 a reason,
/// numbered as the input counts them.
fn faces_by_reason(list: &[FaceReason], lead: &str, naming: &Naming) -> String {
    if list.is_empty() {
        return String::new();
    }
    let mut ids: Vec<&str> = list.iter().map(|f| f.reason).collect();
    ids.sort_unstable();
    ids.dedup();
    let parts: Vec<String> = ids
        .iter()
        .map(|id| {
            let faces: Vec<u32> = list
                .iter()
                .filter(|f| f.reason == *id)
                .map(|f| f.face)
                .collect();
            let shown: Vec<String> = faces
                .iter()
                .take(8)
                .map(|&f| naming.number(f as usize).to_string())
                .collect();
            let more = if faces.len() > 8 { ", …" } else { "" };
            format!("{id}: faces {}{more}", shown.join(", "))
        })
        .collect();
    format!(
        "{lead} {} ({})",
        count(list.len(), "input face", "input faces"),
        parts.join("; ")
    )
}
