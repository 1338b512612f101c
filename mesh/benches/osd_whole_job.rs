//! The whole job side by side with OpenSubdiv 3.5, per input face and per
//! sample, in f64 and in f32, one thread: mesh in, positions and unit
//! normals out on a 5×5 grid of `(u, v) = ((2i+1)/10, (2j+1)/10)` per ptex
//! face (a quad; each corner's sub-quad of another face). Those parameters
//! are never on a patch boundary (patch domains are dyadic), so every sample
//! lies inside exactly one patch of either library.
//!
//! - capdiv: [`SurfacePlan::for_mesh`] at depth 4 (the analysis),
//!   [`Evaluator::new`], then one [`Evaluator::evaluate`] whose sink samples
//!   each patch as it arrives: a patch with domain `[u0, u1] × [v0, v1]` in
//!   its face's (or sub-quad's) square takes the grid points inside it, at
//!   its own `((u − u0)/(u1 − u0), (v − v0)/(v1 − v0))`
//!   ([`capdiv::TensorPatch::iso_v`] line by line: position and both
//!   partials, normal `∂u × ∂v` normalised; cap patches come relative to
//!   their cap's centre, [`Evaluator::set_relative_caps`], and the sink adds
//!   the origin to positions). This is how `tests/osd_surface.rs` puts capdiv's
//!   patches and OpenSubdiv's ptex faces side by side. Re-evaluation is
//!   [`Evaluator::evaluate`] with the sampling sink again, on moved
//!   vertices.
//! - OpenSubdiv: `osd/osd_bench.cpp --whole` (the analysis, stencil tables
//!   for the refined and local points, the points, then per sample
//!   `PatchMap::FindPatch`, `PatchTable::EvaluateBasis` and the sums; see
//!   there).
//!
//! Both sides time as `osd_side_by_side.rs` does (batches, then the median
//! of 5..21 samples of about 2 s in all), the stages of the whole job inside
//! the same timed runs. Re-evaluation alternates between the input positions
//! and the input scaled by 1.01 on both sides.
//!
//! Also: capdiv's f64 samples against OpenSubdiv's (the same on regular
//! faces; EG caps are not Gregory end caps), each library's f32 normals
//! against its own f64 normals, and capdiv's welded OBJ tessellation
//! streamed as `capdiv surface` writes it ([`StreamTessellator`] at the
//! CLI's default grid 4, welded within 1e-9 of the bounding box, into
//! [`ObjWriter`]) against evaluating the same patches.
//!
//! `cargo bench -p capdiv-mesh --bench osd_whole_job` prints markdown
//! tables (`-- --only NAME,NAME` for some meshes). For instruction counts
//! (`scripts/osd-whole-job.sh`): `-- --prepare NAME` writes the mesh's job
//! file and prints the helper's and the job's paths, `-- --once NAME f64|f32`
//! runs the whole job once inside `capdiv_whole_job_f64` or `_f32`,
//! `-- --stream NAME` one evaluation each inside `capdiv_stream_evaluate`
//! (patches to a sink that counts them), `capdiv_stream_count` (streamed
//! through the welded tessellation into a sink that counts) and
//! `capdiv_stream_obj` (into OBJ text). `-- --analyse NAME [ROUNDS]` times
//! capdiv's analysis alone, ROUNDS times (21 by default), and prints the
//! fastest and the median per face: a quick comparison of two builds, run
//! alternately (the analysis' time moves with the allocator's page faults:
//! see `docs/benchmarks.md`).

#[path = "osd/common.rs"]
mod common;
#[path = "../tests/osd/mod.rs"]
mod osd;

use capdiv::Point3;
use capdiv::Real;
use capdiv_mesh::samples::{ev_torus, feature_torus};
use capdiv_mesh::sinks::PatchCounts;
use capdiv_mesh::tessellate::{
    Face, MeshSink, ObjWriter, PatchGeometry, StreamTessellator, TessellatingSink,
};
use capdiv_mesh::{samples, CapRecord, Evaluator, MeshInput, PatchKind, PatchRecord};
use capdiv_mesh::{PlanOptions, SurfacePlan, SurfaceSink};
use common::{helper, job_file, time, DEPTH};
use std::collections::BTreeMap;
use std::hint::black_box;
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

/// Samples per ptex face side.
const GRID: usize = 5;

/// The CLI's default tessellation grid (`capdiv surface --grid`).
const TESS_GRID: usize = 4;

/// The CLI's f64 weld tolerance, relative to the bounding box.
const WELD: f64 = 1e-9;

struct Case {
    name: &'static str,
    mesh: MeshInput,
}

type Make = fn() -> MeshInput;

/// The meshes, in table order; only those `keep` accepts are built.
fn cases(keep: &dyn Fn(&str) -> bool) -> Vec<Case> {
    let makers: [(&'static str, Make); 6] = [
        ("torus-300x300", || samples::torus(300, 300)),
        ("torus-ev-9e4", || ev_torus(75)),
        ("torus-features-1e5", || feature_torus(79)),
        ("torus-100x100", || samples::torus(100, 100)),
        ("torus-ev-1e4", || ev_torus(25)),
        ("torus-features-1e4", || feature_torus(25)),
    ];
    makers
        .into_iter()
        .filter(|(name, _)| keep(name))
        .map(|(name, make)| Case { name, mesh: make() })
        .collect()
}

fn options() -> PlanOptions<'static> {
    PlanOptions {
        depth: DEPTH,
        ..Default::default()
    }
}

/// Each input face's first ptex face (a quad has one, a k-gon k).
fn ptex_bases(mesh: &MeshInput) -> (Vec<u32>, usize) {
    let mut next = 0u32;
    let bases = mesh
        .faces
        .iter()
        .map(|f| {
            let b = next;
            next += if f.len() == 4 { 1 } else { f.len() as u32 };
            b
        })
        .collect();
    (bases, next as usize)
}

/// The grid indices `i` with `lo ≤ (2i+1)/10 ≤ hi`: a sample on an edge two
/// patches share is written by both (the surface is continuous there).
fn inside(lo: f64, hi: f64) -> std::ops::Range<usize> {
    let n = 2.0 * GRID as f64;
    let first = ((n * lo - 1.0) / 2.0).ceil().max(0.0) as usize;
    let end = (((n * hi - 1.0) / 2.0).floor() + 1.0).clamp(0.0, GRID as f64) as usize;
    first..end.max(first)
}

/// Samples every patch it receives on its share of its ptex face's grid:
/// position and unit normal (zero where degenerate) into `out[ptex·25 +
/// 5i + j]`.
struct GridSink<'a, R> {
    bases: &'a [u32],
    out: &'a mut [[R; 6]],
    /// C²PS patches (polar coordinates, no ptex counterpart): not sampled.
    c2ps: usize,
}

impl<R: Real> GridSink<'_, R> {
    fn sample<const K: usize>(&mut self, g: &capdiv::TensorPatch<R, K>, p: &PatchRecord<R>) {
        let ptex = (self.bases[p.face as usize] + u32::from(p.corner.unwrap_or(0))) as usize;
        let [u0, u1, v0, v1] = p.domain;
        let n = 2.0 * GRID as f64;
        let base = ptex * GRID * GRID;
        let rows = inside(u0, u1);
        let mut s = [R::ZERO; GRID];
        for i in rows.clone() {
            s[i] = R::from_f64(((2 * i + 1) as f64 / n - u0) / (u1 - u0));
        }
        // Line by line: one reduction along v per grid column.
        let lines = g.lines();
        for j in inside(v0, v1) {
            let t = R::from_f64(((2 * j + 1) as f64 / n - v0) / (v1 - v0));
            let Ok(line) = lines.iso_v(t) else { continue };
            for i in rows.clone() {
                if let Ok(x) = line.evaluate(s[i]) {
                    let nrm = x.normal().map_or([R::ZERO; 3], |n| n.0);
                    let q = (x.position + p.origin).0;
                    self.out[base + GRID * i + j] = [q[0], q[1], q[2], nrm[0], nrm[1], nrm[2]];
                }
            }
        }
    }
}

impl<R: Real> SurfaceSink<R> for GridSink<'_, R> {
    fn patch(&mut self, p: &PatchRecord<R>) {
        if p.kind == PatchKind::C2ps {
            self.c2ps += 1;
            return;
        }
        match &p.geometry {
            PatchGeometry::Cubic(g) => self.sample(g, p),
            PatchGeometry::Quartic(g) => self.sample(g, p),
        }
    }
    fn cap(&mut self, _: &CapRecord<R>) {}
}

fn positions<R: Real>(mesh: &MeshInput, scale: f64) -> Vec<[R; 3]> {
    mesh.vertices
        .iter()
        .map(|p| p.map(|x| R::from_f64(x * scale)))
        .collect()
}

/// The analysis stage, under a fixed symbol for callgrind.
#[no_mangle]
#[inline(never)]
fn capdiv_job_analyse(mesh: &MeshInput) -> SurfacePlan<'static> {
    SurfacePlan::for_mesh(mesh, options()).expect("capdiv analyses the mesh")
}

/// The evaluator [`GridSink`] samples from: cap patches relative to their
/// cap's centre (the sink adds the origin), for `f32` normals at the
/// precision of the cap's size.
fn sampling_evaluator<'p, R: Real>(plan: &'p SurfacePlan<'p>) -> Evaluator<'p, R> {
    let mut ev = Evaluator::<R>::new(plan).expect("evaluator");
    ev.set_relative_caps(true);
    ev
}

/// Evaluation and sampling: one [`Evaluator::evaluate`] into a [`GridSink`].
#[inline(never)]
fn evaluate_sampled<R: Real>(
    ev: &mut Evaluator<'_, R>,
    at: &[[R; 3]],
    bases: &[u32],
    out: &mut [[R; 6]],
) -> usize {
    let mut sink = GridSink {
        bases,
        out,
        c2ps: 0,
    };
    ev.evaluate(at, &mut sink).expect("evaluate");
    sink.c2ps
}

/// The whole job, its three stages' durations added to `stages`: the
/// samples (NaN where no patch) and the C²PS patches left unsampled.
fn whole_job<R: Real>(mesh: &MeshInput, stages: &mut [Duration; 3]) -> (Vec<[R; 6]>, usize) {
    let t = Instant::now();
    let plan = capdiv_job_analyse(mesh);
    let t1 = Instant::now();
    let mut ev = sampling_evaluator::<R>(&plan);
    let t2 = Instant::now();
    let (bases, ptex) = ptex_bases(mesh);
    let at = positions::<R>(mesh, 1.0);
    let mut out = vec![[R::from_f64(f64::NAN); 6]; ptex * GRID * GRID];
    let c2ps = evaluate_sampled(&mut ev, &at, &bases, &mut out);
    let t3 = Instant::now();
    stages[0] += t1 - t;
    stages[1] += t2 - t1;
    stages[2] += t3 - t2;
    (out, c2ps)
}

/// The whole job once in f64, for callgrind's `--toggle-collect`.
#[no_mangle]
#[inline(never)]
fn capdiv_whole_job_f64(mesh: &MeshInput) -> (Vec<[f64; 6]>, usize) {
    whole_job::<f64>(mesh, &mut [Duration::ZERO; 3])
}

/// The whole job once in f32, for callgrind's `--toggle-collect`.
#[no_mangle]
#[inline(never)]
fn capdiv_whole_job_f32(mesh: &MeshInput) -> (Vec<[f32; 6]>, usize) {
    whole_job::<f32>(mesh, &mut [Duration::ZERO; 3])
}

/// Median seconds per call of `f` and of each of its stages (`f` adds
/// each stage's time to its argument), timed as [`time`].
fn time_stages<const N: usize>(mut f: impl FnMut(&mut [Duration; N])) -> ([f64; N], f64) {
    let mut stages = [Duration::ZERO; N];
    let mut batch_of = |n: usize, stages: &mut [Duration; N]| {
        *stages = [Duration::ZERO; N];
        let t = Instant::now();
        for _ in 0..n {
            f(stages);
        }
        t.elapsed()
    };
    let mut batch = 1;
    let mut took;
    loop {
        took = batch_of(batch, &mut stages);
        if took >= Duration::from_millis(2) || batch >= 1 << 20 {
            break;
        }
        batch *= 2;
    }
    let samples = ((2.0 / took.as_secs_f64()) as usize).clamp(5, 21);
    let mut per: Vec<[f64; N]> = Vec::new();
    let mut total = Vec::new();
    for _ in 0..samples {
        let all = batch_of(batch, &mut stages);
        total.push(all.as_secs_f64() / batch as f64);
        per.push(stages.map(|d| d.as_secs_f64() / batch as f64));
    }
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let each = std::array::from_fn(|k| median(per.iter().map(|p| p[k]).collect()));
    (each, median(total))
}

/// capdiv's figures in one precision, seconds per mesh.
struct Side<R> {
    analysis: f64,
    evaluator: f64,
    evaluate_sampled: f64,
    total: f64,
    /// [`Evaluator::evaluate`] alone (patches, no sampling).
    patches: f64,
    reeval: f64,
    out: Vec<[R; 6]>,
    c2ps: usize,
}

fn measure_side<R: Real>(mesh: &MeshInput) -> Side<R> {
    let ([analysis, evaluator, sampled], total) = time_stages(|s| {
        black_box(whole_job::<R>(black_box(mesh), s));
    });
    let plan = capdiv_job_analyse(mesh);
    let mut ev = sampling_evaluator::<R>(&plan);
    let (bases, ptex) = ptex_bases(mesh);
    let moved = [positions::<R>(mesh, 1.0), positions::<R>(mesh, 1.01)];
    let mut out = vec![[R::from_f64(f64::NAN); 6]; ptex * GRID * GRID];
    let mut flip = 0;
    let (patches, _) = time(|| {
        flip += 1;
        // Only counted (the evaluation alone).
        let mut d = PatchCounts::default();
        ev.evaluate(&moved[flip & 1], &mut d).expect("evaluate");
        black_box(d.total);
    });
    let (reeval, _) = time(|| {
        flip += 1;
        black_box(evaluate_sampled(
            &mut ev,
            &moved[flip & 1],
            &bases,
            &mut out,
        ));
    });
    let (out, c2ps) = whole_job::<R>(mesh, &mut [Duration::ZERO; 3]);
    Side {
        analysis,
        evaluator,
        evaluate_sampled: sampled,
        total,
        patches,
        reeval,
        out,
        c2ps,
    }
}

/// Counts what a streamed tessellation hands over.
#[derive(Default)]
struct CountMesh(usize, usize);

impl MeshSink<f64> for CountMesh {
    fn vertex(&mut self, _: Point3<f64>, _: Point3<f64>) {
        self.0 += 1;
    }
    fn face(&mut self, _: Face, _: u32) {
        self.1 += 1;
    }
}

/// Counts patches.
#[derive(Default)]
struct CountPatches(usize);

impl SurfaceSink<f64> for CountPatches {
    fn patch(&mut self, p: &PatchRecord<f64>) {
        black_box(p);
        self.0 += 1;
    }
    fn cap(&mut self, _: &CapRecord<f64>) {}
}

/// One evaluation of the patches, handed to a sink that only counts them:
/// what the streamed tessellation adds to.
#[no_mangle]
#[inline(never)]
fn capdiv_stream_evaluate(ev: &mut Evaluator<f64>, mesh: &MeshInput) -> usize {
    let mut count = CountPatches::default();
    ev.evaluate(&mesh.vertices, &mut count).expect("evaluate");
    count.0
}

/// One evaluation streamed through the CLI's welded tessellation (grid
/// [`TESS_GRID`], welded within `tol`, faces tagged by level) into `out`.
#[inline(always)]
fn stream_tessellate<S: MeshSink<f64>>(
    ev: &mut Evaluator<f64>,
    mesh: &MeshInput,
    tol: f64,
    out: &mut S,
) {
    let mut tess = StreamTessellator::new(TESS_GRID, tol);
    let mut sink = TessellatingSink {
        tess: &mut tess,
        out,
        tag: |p| p.level,
    };
    ev.evaluate(&mesh.vertices, &mut sink).expect("evaluate");
    tess.finish(out);
}

/// [`stream_tessellate`] into a counting sink, for callgrind: vertices and
/// faces.
#[no_mangle]
#[inline(never)]
fn capdiv_stream_count(ev: &mut Evaluator<f64>, mesh: &MeshInput, tol: f64) -> (usize, usize) {
    let mut out = CountMesh::default();
    stream_tessellate(ev, mesh, tol, &mut out);
    (out.0, out.1)
}

/// [`stream_tessellate`] into OBJ text, for callgrind: its length.
#[no_mangle]
#[inline(never)]
fn capdiv_stream_obj(ev: &mut Evaluator<f64>, mesh: &MeshInput, tol: f64) -> usize {
    let mut out = ObjWriter::new(String::new(), &[]);
    stream_tessellate(ev, mesh, tol, &mut out);
    out.out.len()
}

/// Median seconds of three calls of `f` (the tessellation takes seconds on
/// the larger meshes).
fn median_of_3(mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..3)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[1]
}

/// capdiv's welded OBJ tessellation streamed from the evaluation, seconds
/// per mesh: (evaluating the patches only, the evaluation streamed through
/// the tessellation into a counting sink, the same into OBJ text, patches,
/// output vertices).
fn measure_tessellation(mesh: &MeshInput) -> (f64, f64, f64, usize, usize) {
    let plan = capdiv_job_analyse(mesh);
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    let tol = WELD * size(mesh);
    let mut patches = 0;
    let evaluate = median_of_3(|| patches = capdiv_stream_evaluate(&mut ev, mesh));
    let mut vertices = 0;
    let count = median_of_3(|| vertices = capdiv_stream_count(&mut ev, mesh, tol).0);
    let obj = median_of_3(|| {
        black_box(capdiv_stream_obj(&mut ev, mesh, tol));
    });
    (evaluate, count, obj, patches, vertices)
}

/// The largest side of the bounding box.
fn size(m: &MeshInput) -> f64 {
    let mut lo = [f64::MAX; 3];
    let mut hi = [f64::MIN; 3];
    for p in &m.vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
}

/// Largest |n32 − n64| (normals) and |p32 − p64| (coordinates) over the
/// samples both cover.
fn f32_error(s64: &[[f64; 6]], s32: &[[f32; 6]]) -> (f64, f64) {
    let mut normal = 0.0f64;
    let mut position = 0.0f64;
    for (a, b) in s64.iter().zip(s32) {
        if a[0].is_nan() || b[0].is_nan() {
            continue;
        }
        let d: f64 = (3..6).map(|k| (a[k] - b[k] as f64).powi(2)).sum();
        normal = normal.max(d.sqrt());
        for k in 0..3 {
            position = position.max((a[k] - b[k] as f64).abs());
        }
    }
    (normal, position)
}

/// The helper's `key value` lines of `--whole`, and its f64 samples.
fn run_helper(helper: &Path, job: &Path) -> (BTreeMap<String, f64>, Vec<[f64; 6]>) {
    let dump = job.with_extension("samples");
    let out = Command::new(helper)
        .arg("--whole")
        .arg(job)
        .arg(&dump)
        .output()
        .expect("run the OpenSubdiv helper");
    assert!(
        out.status.success(),
        "OpenSubdiv helper failed on {}:\n{}",
        job.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    let keys = String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| {
            let (k, v) = l.split_once(' ')?;
            Some((k.to_string(), v.trim().parse().ok()?))
        })
        .collect();
    let bytes = std::fs::read(&dump).expect("read the helper's samples");
    let samples = bytes
        .chunks_exact(48)
        .map(|c| {
            std::array::from_fn(|k| f64::from_ne_bytes(c[8 * k..8 * k + 8].try_into().unwrap()))
        })
        .collect();
    (keys, samples)
}

struct Row {
    name: &'static str,
    faces: usize,
    samples: usize,
    covered: [usize; 2],
    c64: Side<f64>,
    c32: Side<f32>,
    osd: BTreeMap<String, f64>,
    /// capdiv against OpenSubdiv, f64: largest |Δp| / size, largest |Δn|,
    /// samples with |Δp| > 1e-9 of the size.
    cross: (f64, f64, usize),
    /// Evaluate only, streamed tessellation, the same to OBJ text; patches,
    /// vertices ([`measure_tessellation`]).
    tess: (f64, f64, f64, usize, usize),
}

fn measure(case: &Case, helper: &Path) -> Row {
    let mesh = &case.mesh;
    let c64 = measure_side::<f64>(mesh);
    let c32 = measure_side::<f32>(mesh);
    let tess = measure_tessellation(mesh);
    let (osd, theirs) = run_helper(helper, &job_file(case.name, mesh));
    let scale = size(mesh);
    let mut cross = (0.0f64, 0.0f64, 0usize);
    assert_eq!(theirs.len(), c64.out.len(), "{}: sample counts", case.name);
    for (a, b) in c64.out.iter().zip(&theirs) {
        if a[0].is_nan() || b[0].is_nan() {
            continue;
        }
        let dp = (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max) / scale;
        let dn = (3..6).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt();
        cross.0 = cross.0.max(dp);
        cross.1 = cross.1.max(dn);
        cross.2 += usize::from(dp > 1e-9);
    }
    let covered = |o: &[[f64; 6]]| o.iter().filter(|s| !s[0].is_nan()).count();
    Row {
        name: case.name,
        faces: mesh.faces.len(),
        samples: c64.out.len(),
        covered: [covered(&c64.out), covered(&theirs)],
        c64,
        c32,
        osd,
        cross,
        tess,
    }
}

fn print_tables(rows: &[Row]) {
    for r in rows {
        let f = r.faces as f64;
        let n = r.covered[1] as f64;
        let o = |k: &str| r.osd.get(k).copied().unwrap_or(f64::NAN);
        let (e64, _) = f32_error(&r.c64.out, &r.c32.out);
        println!(
            "### {} ({} faces, {} samples; covered: capdiv {}, OSD {})\n",
            r.name, r.faces, r.samples, r.covered[0], r.covered[1]
        );
        println!(
            "| stage | OpenSubdiv f64 | capdiv f64 | ratio | OpenSubdiv f32 | capdiv f32 | ratio |"
        );
        println!("|---|--:|--:|--:|--:|--:|--:|");
        let line = |stage: &str, osd: [f64; 2], cap: [f64; 2], unit: &str| {
            let cell = |x: f64| {
                if x.is_nan() {
                    "—".to_string()
                } else {
                    format!("{x:.1} {unit}")
                }
            };
            let ratio = |a: f64, b: f64| {
                if a.is_nan() || b.is_nan() {
                    "—".to_string()
                } else {
                    format!("{:.2}×", a / b)
                }
            };
            println!(
                "| {stage} | {} | {} | {} | {} | {} | {} |",
                cell(osd[0]),
                cell(cap[0]),
                ratio(osd[0], cap[0]),
                cell(osd[1]),
                cell(cap[1]),
                ratio(osd[1], cap[1]),
            );
        };
        let osd2 = |k: &str, per: f64| [o(&format!("f64_{k}")) / per, o(&format!("f32_{k}")) / per];
        line(
            "analysis (OSD: Create + RefineAdaptive + PatchTable + PatchMap; capdiv: `SurfacePlan::for_mesh`)",
            osd2("analysis_ns", f),
            [r.c64.analysis * 1e9 / f, r.c32.analysis * 1e9 / f],
            "ns/face",
        );
        line(
            "stencil tables (OSD: refined + local points) / `Evaluator::new` (capdiv)",
            osd2("stencils_ns", f),
            [r.c64.evaluator * 1e9 / f, r.c32.evaluator * 1e9 / f],
            "ns/face",
        );
        line(
            "points (OSD: `UpdateValues`) / patches (capdiv: `evaluate`, no sampling)",
            osd2("points_ns", f),
            [r.c64.patches * 1e9 / f, r.c32.patches * 1e9 / f],
            "ns/face",
        );
        line(
            "sampling (OSD: FindPatch + EvaluateBasis + sums; capdiv: sink, = evaluate with sampling − evaluate)",
            osd2("sample_ns", n),
            [
                (r.c64.evaluate_sampled - r.c64.patches) * 1e9 / n,
                (r.c32.evaluate_sampled - r.c32.patches) * 1e9 / n,
            ],
            "ns/sample",
        );
        line(
            "**whole job**",
            osd2("total_ns", f),
            [r.c64.total * 1e9 / f, r.c32.total * 1e9 / f],
            "ns/face",
        );
        line(
            "(OSD whole job with `PrimvarRefiner::Interpolate` + local point stencils instead of stencil tables)",
            osd2("total_primvar_ns", f),
            [r.c64.total * 1e9 / f, r.c32.total * 1e9 / f],
            "ns/face",
        );
        line(
            "re-evaluation after vertices move (points/patches + sampling)",
            osd2("reeval_ns", f),
            [r.c64.reeval * 1e9 / f, r.c32.reeval * 1e9 / f],
            "ns/face",
        );
        line(
            "(OSD re-evaluation with `PrimvarRefiner::Interpolate` + local point stencils instead)",
            osd2("reeval_primvar_ns", f),
            [r.c64.reeval * 1e9 / f, r.c32.reeval * 1e9 / f],
            "ns/face",
        );
        let (evaluate, count, obj, patches, verts) = r.tess;
        println!(
            "| capdiv's welded OBJ streamed as `capdiv surface` writes it, f64, grid {TESS_GRID} \
             ({patches} patches, {verts} vertices): sampling, weld and assembly + text | — | \
             {:.0} + {:.0} ns/face | {:.1}× evaluating the patches ({:.0} ns/face; {:.1}× without \
             the text), {:.1}× the whole job | | | |",
            (count - evaluate) * 1e9 / f,
            (obj - count) * 1e9 / f,
            (obj - evaluate) / evaluate,
            evaluate * 1e9 / f,
            (count - evaluate) / evaluate,
            (obj - evaluate) / r.c64.total,
        );
        println!(
            "| f32 normals vs own f64 normals, max \\|n32 − n64\\| | {:.1e} | {:.1e} | | | | |",
            o("f32_normal_err"),
            e64,
        );
        println!(
            "\ncapdiv vs OpenSubdiv, f64 samples: max |Δp| {:.1e} of the size, max |Δn| {:.1e}, \
             {} samples with |Δp| > 1e-9 of the size (EG caps vs Gregory end caps). \
             OSD whole-job timing samples f64/f32: {}/{}. \
             C²PS patches not sampled: {}. Ratio > 1: capdiv is faster.\n",
            r.cross.0,
            r.cross.1,
            r.cross.2,
            o("f64_samples"),
            o("f32_samples"),
            r.c64.c2ps,
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1).cloned())
    };
    if let Some(name) = value("--once") {
        let case = cases(&|n| n == name).pop().expect("unknown mesh");
        let covered = match value(&name).as_deref() {
            Some("f32") => capdiv_whole_job_f32(&case.mesh)
                .0
                .iter()
                .filter(|s| !s[0].is_nan())
                .count(),
            _ => capdiv_whole_job_f64(&case.mesh)
                .0
                .iter()
                .filter(|s| !s[0].is_nan())
                .count(),
        };
        println!("faces {}", case.mesh.faces.len());
        println!("covered {covered}");
        return;
    }
    if let Some(name) = value("--stream") {
        let case = cases(&|n| n == name).pop().expect("unknown mesh");
        let plan = capdiv_job_analyse(&case.mesh);
        let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
        let tol = WELD * size(&case.mesh);
        println!("faces {}", case.mesh.faces.len());
        println!("patches {}", capdiv_stream_evaluate(&mut ev, &case.mesh));
        let (vertices, faces) = capdiv_stream_count(&mut ev, &case.mesh, tol);
        println!("output vertices {vertices}");
        println!("output faces {faces}");
        println!("bytes {}", capdiv_stream_obj(&mut ev, &case.mesh, tol));
        return;
    }
    if let Some(name) = value("--analyse") {
        let case = cases(&|n| n == name).pop().expect("unknown mesh");
        let rounds: usize = value(&name).and_then(|r| r.parse().ok()).unwrap_or(21);
        let mut ns: Vec<f64> = (0..rounds)
            .map(|_| {
                let t = Instant::now();
                let plan = capdiv_job_analyse(&case.mesh);
                let d = t.elapsed().as_nanos() as f64;
                drop(black_box(plan));
                d / case.mesh.faces.len() as f64
            })
            .collect();
        ns.sort_by(f64::total_cmp);
        println!(
            "analysis ns/face: min {:.1} median {:.1}",
            ns[0],
            ns[rounds / 2]
        );
        return;
    }
    if let Some(name) = value("--prepare") {
        let case = cases(&|n| n == name).pop().expect("unknown mesh");
        println!("helper {}", helper().display());
        println!("job {}", job_file(case.name, &case.mesh).display());
        println!("faces {}", case.mesh.faces.len());
        return;
    }
    let only = value("--only");
    let keep = |n: &str| only.as_ref().is_none_or(|o| o.split(',').any(|x| x == n));
    let helper = helper();
    let mut rows = Vec::new();
    for case in cases(&keep) {
        eprintln!("measuring {} ({} faces)", case.name, case.mesh.faces.len());
        rows.push(measure(&case, &helper));
    }
    print_tables(&rows);
}
