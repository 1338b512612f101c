//! Time per output point of one C²PS step, valence 6·2^k → 6·2^(k+1), for
//! k = 0..13 (up to valence 49152), in f64 and f32, and the independent
//! reference's literal O(n²) step (`capdiv_reference::c2ps::step`, rules
//! (1)–(5) as the paper writes them) for k = 0..9. The kernel's step is O(n),
//! so its time per point must stay flat; the literal one grows with n.
//!
//! Output points are counted as points: a step to valence n writes 5 links
//! of n points and the pole, `5n + 1` (the reference: `n` columns, counted
//! per column). Side by side, in the same run: subdiv-kernels'
//! Catmull-Clark refinement of the same polar net (the net the C²PS step
//! starts from, as a mesh: a fan of triangles around the pole, quads between
//! links), its stencils applied once with `interpolate_rows`, per output
//! vertex. `scripts/bench-table.py c2ps-vs-cc` and
//! `scripts/bench-table.py GROUP…` turn the results into the tables of docs/benchmarks.md.

use capdiv::{FirstStep, PolarNet, Real};
use criterion::{BatchSize, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use std::time::Duration;

// Shared with benches/eg_vs_cc.rs, which uses all of it.
#[allow(dead_code)]
#[path = "support/sk.rs"]
mod sk;
use sk::{cc_stencils, mesh, SkReal};

/// The polar net `pole, links` as a subdiv-kernels mesh: vertex 0 the pole,
/// point `j` of link `i` (1-based) at `1 + (i−1)·n + j`; a fan of triangles
/// around the pole and quads between consecutive links, counter-clockwise.
fn polar_mesh(n: usize, links: usize) -> subdiv_kernels::Mesh {
    let v = |i: usize, j: usize| (1 + (i - 1) * n + j % n) as u32;
    let (mut counts, mut idx) = (Vec::new(), Vec::new());
    for j in 0..n {
        counts.push(3);
        idx.extend([0, v(1, j), v(1, j + 1)]);
    }
    for i in 1..links {
        for j in 0..n {
            counts.push(4);
            idx.extend([v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    mesh(1 + links * n, counts, idx)
}

/// A paraboloid-like valence-6 configuration with 5 links.
fn sample<R: Real>() -> ([R; 3], Vec<Vec<[R; 3]>>) {
    let links = (1..=5)
        .map(|i| {
            (0..6)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / 6.0;
                    let r = i as f64;
                    [r * t.cos(), r * t.sin(), 0.2 * r * r + 0.05 * (j as f64)].map(R::from_f64)
                })
                .collect()
        })
        .collect();
    ([R::ZERO; 3], links)
}

/// Refines to valence `6·2^k` (stored with room for one more step) and
/// benchmarks that one more step,
/// then subdiv-kernels' Catmull-Clark refinement of the same net (group
/// `c2ps_step_sk_cc_{prec}`, same parameter), per output vertex.
fn bench_level<R: SkReal, const CAP: usize>(c: &mut Criterion, prec: &str, k: u32) {
    let (pole, links) = sample::<R>();
    let mut net: Box<PolarNet<R, CAP>> = Box::new(PolarNet::new(pole, &links).unwrap());
    for _ in 0..k {
        net.step(FirstStep::Uniform).unwrap();
    }
    let n_out = 2 * net.valence();
    let held = net.link_count();
    let mut g = c.benchmark_group(format!("c2ps_step_{prec}"));
    // Points written: `held` links of n_out points and the pole.
    g.throughput(Throughput::Elements((held * n_out + 1) as u64));
    g.bench_with_input(BenchmarkId::from_parameter(n_out), &net, |b, net| {
        b.iter_batched_ref(
            || net.clone(),
            |n| black_box(n.step(FirstStep::Uniform)),
            BatchSize::LargeInput,
        )
    });
    g.finish();

    let n = net.valence();
    let mut points = vec![net.pole().0];
    for i in 1..=held {
        points.extend(net.link(i).expect("held link").iter().map(|p| p.0));
    }
    let table = cc_stencils(polar_mesh(n, held));
    let rows: Vec<u32> = (0..table.output_count() as u32).collect();
    let mut out = vec![[R::ZERO; 3]; rows.len()];
    let mut g = c.benchmark_group(format!("c2ps_step_sk_cc_{prec}"));
    g.throughput(Throughput::Elements(rows.len() as u64));
    g.bench_function(BenchmarkId::from_parameter(n_out), |b| {
        b.iter(|| {
            R::interpolate_rows(&table, black_box(&points), &rows, &mut out);
            black_box(&out);
        })
    });
    g.finish();
}

/// The reference's literal step at the same valence (its time per output
/// point grows linearly with n: every new point sums over the whole 1-link).
fn bench_reference(c: &mut Criterion, k: u32) {
    let (pole, links) = sample::<f64>();
    let mut cfg = capdiv_reference::polar::Polar::new(pole, links);
    for _ in 0..k {
        cfg = capdiv_reference::c2ps::step_first_uniform(&cfg);
    }
    let n_out = 2 * cfg.valence();
    let mut g = c.benchmark_group("c2ps_step_reference");
    g.throughput(Throughput::Elements(n_out as u64));
    g.bench_with_input(BenchmarkId::from_parameter(n_out), &cfg, |b, cfg| {
        b.iter(|| black_box(capdiv_reference::c2ps::step(cfg)))
    });
    g.finish();
}

macro_rules! levels {
    ($c:expr, $r:ty, $prec:expr; $($k:literal),*) => {
        $( bench_level::<$r, { 6 << ($k + 1) }>($c, $prec, $k); )*
    };
}

fn benches(c: &mut Criterion) {
    levels!(c, f64, "f64"; 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13);
    levels!(c, f32, "f32"; 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13);
    for k in 0..=9 {
        bench_reference(c, k);
    }
}

fn main() {
    // Nets of valence 98304 are tens of MiB; give them room.
    std::thread::Builder::new()
        .stack_size(1 << 30)
        .spawn(|| {
            let mut c = Criterion::default()
                .warm_up_time(Duration::from_millis(500))
                .measurement_time(Duration::from_secs(2))
                .sample_size(20)
                .configure_from_args();
            benches(&mut c);
            c.final_summary();
        })
        .expect("bench thread")
        .join()
        .expect("bench thread panicked");
}
