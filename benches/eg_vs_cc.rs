//! EG against Catmull-Clark on the same c-net, in one run ("switching
//! a cap from Catmull-Clark to EG at most doubles its cost", EG paper §8).
//!
//! For n = 3 and 5, f64 and f32, on one c-net (docs/math/eg.md §1: center and 6
//! nodes per sector, i.e. 4n quads):
//! - `eg_step`: one [`EgSubdivision::step`] (built-in §7 table, dense
//!   rule (7): the small-firmware path);
//! - `eg_fourier_step`: one [`EgSubdivision::step_fourier`] with the
//!   [`FourierRule`] of that table (built once, like the stencil tables);
//! - `cc_cap_step`: one [`CcCap::step`], the kernel's own Catmull-Clark cap;
//! - `sk_cc_step`: subdiv-kernels' Catmull-Clark refinement of the same 4n
//!   quads, refined once: its level-1 [`StencilTable`] (built once, like
//!   EG's table) applied to the positions with `interpolate` (returns a new
//!   `Vec`, the crate's one-shot path);
//! - `sk_cc_step_rows`: the same stencils with `interpolate_rows` into a
//!   buffer kept between runs (no allocation; the cheaper of its two paths).
//!
//! Stateful steps run on fresh copies, 8 per timed batch (setup untimed), so
//! every step starts from level 0. `python3 scripts/bench-table.py eg-vs-cc`
//! prints the times and the ratios EG / Catmull-Clark of this run.
//! `cargo bench --bench eg_vs_cc -- --probe REPS f64|f32 N` instead runs REPS
//! steps of each (for `valgrind --tool=callgrind`: instruction counts per step,
//! `scripts/eg-vs-cc-callgrind.sh`).

use capdiv::eg::{CNet, EgSubdivision, FourierRule};
use capdiv::{CcCap, Point3, Real};
use criterion::{BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use std::time::{Duration, Instant};
use subdiv_kernels::{Mesh, StencilTable};

#[path = "support/sk.rs"]
mod sk;
use sk::{cc_stencils, mesh, SkReal};

/// The §1 order of a sector's c-net nodes.
const GRID: [(i32, i32); 6] = [(1, 0), (2, 0), (1, 1), (2, 1), (1, 2), (2, 2)];

/// A c-net sampled from z = 0.3x² + 0.1xy around a node of valence n (the
/// net of `benches/eg_step.rs`), moved by (1, 2, 3) so that nothing tends to
/// zero: center and the 6n nodes.
fn cnet_nodes(n: usize) -> ([f64; 3], Vec<[f64; 3]>) {
    let mut nodes = Vec::new();
    for s in 0..n {
        for (x, y) in GRID.map(|(x, y)| (f64::from(x), f64::from(y))) {
            let a = std::f64::consts::TAU * (s as f64 + y.atan2(x) * 4.0 / std::f64::consts::TAU)
                / n as f64;
            let r = x.hypot(y);
            let (px, py) = (r * a.cos(), r * a.sin());
            nodes.push([px + 1.0, py + 2.0, 0.3 * px * px + 0.1 * px * py + 3.0]);
        }
    }
    ([1.0, 2.0, 3.0], nodes)
}

/// Vertex index of c-net position `(x, y)` of sector `s` (center 0, node `k`
/// of sector `s` at `1 + 6s + k`), after the §1 change of frame.
fn vertex(n: usize, s: usize, x: i32, y: i32) -> u32 {
    let (mut s, mut x, mut y) = (s, x, y);
    if (x, y) == (0, 0) {
        return 0;
    }
    if x == 0 {
        // (0, y)_s = (y, 0)_{s+1}.
        (x, y, s) = (y, 0, (s + 1) % n);
    }
    let k = GRID.iter().position(|&g| g == (x, y)).expect("c-net node");
    (1 + 6 * s + k) as u32
}

/// The c-net's 4n quads as a subdiv-kernels mesh (counter-clockwise faces,
/// edges derived from them, no creases or corners).
fn cnet_mesh(n: usize) -> Mesh {
    let mut faces = Vec::new();
    for s in 0..n {
        for (a, b) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            for (x, y) in [(a, b), (a + 1, b), (a + 1, b + 1), (a, b + 1)] {
                faces.push(vertex(n, s, x, y));
            }
        }
    }
    mesh(6 * n + 1, vec![4; 4 * n], faces)
}

/// One of the compared steps, ready to run on fresh copies.
struct Case<R: Real> {
    n: usize,
    center: [R; 3],
    nodes: Vec<[R; 3]>,
    eg: EgSubdivision<'static, R>,
    fourier: FourierRule<'static, R>,
    table: StencilTable,
    positions: Vec<[R; 3]>,
}

impl<R: SkReal> Case<R> {
    fn new(n: usize) -> Self {
        let (c, nodes) = cnet_nodes(n);
        let center = c.map(R::from_f64);
        let nodes: Vec<[R; 3]> = nodes.iter().map(|p| p.map(R::from_f64)).collect();
        let net = CNet::new(center, &nodes).expect("valid c-net");
        let eg = EgSubdivision::new(&net, None).expect("built-in rule");
        let fourier = FourierRule::new(eg.table().expect("EG table")).expect("rule");
        let positions: Vec<[R; 3]> = std::iter::once(center)
            .chain(nodes.iter().copied())
            .collect();
        let table = cc_stencils(cnet_mesh(n));
        // The two Catmull-Clark steps agree: the new center (the vertex point
        // of the extraordinary vertex) is among subdiv-kernels' outputs.
        let mut storage = vec![Point3::ZERO; CcCap::<R>::storage_len(n)];
        let mut cap = CcCap::new(center, &nodes, &mut storage).expect("valid c-net");
        cap.step().expect("step");
        let e = cap.center().0.map(|c| c.to_f64());
        let close = |p: &[R; 3]| (0..3).all(|k| (p[k].to_f64() - e[k]).abs() < 1e-5);
        assert!(R::interpolate(&table, &positions).iter().any(close));
        Case {
            n,
            center,
            nodes,
            eg,
            fourier,
            table,
            positions,
        }
    }

    /// `iters` EG steps, each on a fresh copy, timed in batches of `B`.
    fn time_eg(&self, iters: u64) -> Duration {
        batches(iters, |k| {
            let mut subs: Vec<_> = (0..k).map(|_| self.eg.clone()).collect();
            let t = Instant::now();
            for s in subs.iter_mut() {
                black_box(s.step()).expect("step");
            }
            t.elapsed()
        })
    }

    /// `iters` EG steps through the Fourier rule, as [`Case::time_eg`].
    fn time_eg_fourier(&self, iters: u64) -> Duration {
        batches(iters, |k| {
            let mut subs: Vec<_> = (0..k).map(|_| self.eg.clone()).collect();
            let t = Instant::now();
            for s in subs.iter_mut() {
                black_box(s.step_fourier(&self.fourier)).expect("step");
            }
            t.elapsed()
        })
    }

    /// `iters` `CcCap` steps, each on a fresh cap, timed in batches of `B`.
    fn time_cc(&self, iters: u64) -> Duration {
        let mut storage = vec![vec![Point3::ZERO; CcCap::<R>::storage_len(self.n)]; B];
        batches(iters, |k| {
            let mut caps: Vec<_> = storage
                .iter_mut()
                .take(k)
                .map(|st| CcCap::new(self.center, &self.nodes, st).expect("valid c-net"))
                .collect();
            let t = Instant::now();
            for c in caps.iter_mut() {
                black_box(c.step()).expect("step");
            }
            t.elapsed()
        })
    }
}

/// Steps per timed batch of the stateful steps (their copies stay in cache).
const B: usize = 4;

fn batches(iters: u64, mut batch: impl FnMut(usize) -> Duration) -> Duration {
    let mut left = iters as usize;
    let mut total = Duration::ZERO;
    while left > 0 {
        let k = left.min(B);
        total += batch(k);
        left -= k;
    }
    total
}

fn bench_case<R: SkReal>(c: &mut Criterion, prec: &str, n: usize) {
    let case = Case::<R>::new(n);
    let rows: Vec<u32> = (0..case.table.output_count() as u32).collect();
    let mut out = vec![[R::ZERO; 3]; rows.len()];
    let mut g = c.benchmark_group(format!("eg_vs_cc_{prec}"));
    g.throughput(Throughput::Elements(1));
    g.bench_function(BenchmarkId::new("eg_step", n), |b| {
        b.iter_custom(|iters| case.time_eg(iters))
    });
    g.bench_function(BenchmarkId::new("eg_fourier_step", n), |b| {
        b.iter_custom(|iters| case.time_eg_fourier(iters))
    });
    g.bench_function(BenchmarkId::new("cc_cap_step", n), |b| {
        b.iter_custom(|iters| case.time_cc(iters))
    });
    g.bench_function(BenchmarkId::new("sk_cc_step", n), |b| {
        b.iter(|| black_box(R::interpolate(&case.table, black_box(&case.positions))))
    });
    g.bench_function(BenchmarkId::new("sk_cc_step_rows", n), |b| {
        b.iter(|| {
            R::interpolate_rows(&case.table, black_box(&case.positions), &rows, &mut out);
            black_box(&out);
        })
    });
    g.finish();
}

/// `--probe REPS PREC N`: REPS steps of each kind for one valence and type,
/// each in a function of its own (the copies made beforehand), for
/// callgrind's inclusive per-function instruction counts.
#[inline(never)]
fn probe_eg<R: SkReal>(subs: &mut [EgSubdivision<'static, R>]) {
    for s in subs.iter_mut() {
        black_box(s.step()).expect("step");
    }
}
#[inline(never)]
fn probe_eg_fourier<R: SkReal>(subs: &mut [EgSubdivision<'static, R>], rule: &FourierRule<'_, R>) {
    for s in subs.iter_mut() {
        black_box(s.step_fourier(rule)).expect("step");
    }
}
#[inline(never)]
fn probe_cc<R: SkReal>(caps: &mut [CcCap<'_, R>]) {
    for c in caps.iter_mut() {
        black_box(c.step()).expect("step");
    }
}
#[inline(never)]
fn probe_sk<R: SkReal>(case: &Case<R>, reps: usize) {
    for _ in 0..reps {
        black_box(R::interpolate(&case.table, black_box(&case.positions)));
    }
}
#[inline(never)]
fn probe_sk_rows<R: SkReal>(case: &Case<R>, reps: usize, rows: &[u32], out: &mut [[R; 3]]) {
    for _ in 0..reps {
        R::interpolate_rows(&case.table, black_box(&case.positions), rows, out);
        black_box(&*out);
    }
}

fn probe<R: SkReal>(n: usize, reps: usize) {
    let case = Case::<R>::new(n);
    let rows: Vec<u32> = (0..case.table.output_count() as u32).collect();
    let mut out = vec![[R::ZERO; 3]; rows.len()];
    let mut subs = vec![case.eg.clone(); reps];
    let mut fast = vec![case.eg.clone(); reps];
    let mut storage = vec![vec![Point3::ZERO; CcCap::<R>::storage_len(n)]; reps];
    let mut caps: Vec<_> = storage
        .iter_mut()
        .map(|st| CcCap::new(case.center, &case.nodes, st).expect("valid c-net"))
        .collect();
    probe_eg(&mut subs);
    probe_eg_fourier(&mut fast, &case.fourier);
    // Both paths: the same net up to rounding.
    for (a, b) in subs.iter().zip(&fast).take(1) {
        for (p, q) in a
            .net()
            .sectors()
            .iter()
            .flatten()
            .zip(b.net().sectors().iter().flatten())
        {
            assert!(p.max_abs_diff(*q).to_f64() < 1e-4, "EG paths disagree");
        }
    }
    probe_cc(&mut caps);
    probe_sk(&case, reps);
    probe_sk_rows(&case, reps, &rows, &mut out);
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(k) = args.iter().position(|a| a == "--probe") {
        let arg = |i: usize| args.get(k + i).map(String::as_str);
        let reps = arg(1).and_then(|s| s.parse().ok()).unwrap_or(1000);
        let n = arg(3).and_then(|s| s.parse().ok()).unwrap_or(5);
        match arg(2) {
            Some("f32") => probe::<f32>(n, reps),
            _ => probe::<f64>(n, reps),
        }
        return;
    }
    let mut c = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .sample_size(20)
        .configure_from_args();
    for n in [3, 5] {
        bench_case::<f64>(&mut c, "f64", n);
        bench_case::<f32>(&mut c, "f32", n);
    }
    c.final_summary();
}
