//! EG (docs/math/eg.md §5–§9): time of one step and of emitting one ring of 3n
//! bi-4 patches, per valence, f64 and f32. Valences 3 and 5 use the built-in
//! §7 tables, 4 the regular rules. `scripts/bench-table.py` makes the table.

use capdiv::eg::{CNet, EgSubdivision};
use capdiv::Real;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;

/// A c-net sampled from z = 0.3x² + 0.1xy around a node of valence n.
fn cnet<R: Real>(n: usize) -> CNet<R> {
    let sectors: Vec<[[R; 3]; 6]> = (0..n)
        .map(|s| {
            let grid = [
                (1.0, 0.0),
                (2.0, 0.0),
                (1.0, 1.0),
                (2.0, 1.0),
                (1.0, 2.0),
                (2.0, 2.0),
            ];
            grid.map(|(x, y): (f64, f64)| {
                // Sector s spans the angle [s, s+1]·2π/n; (x, y) maps onto it.
                let a = std::f64::consts::TAU
                    * (s as f64 + y.atan2(x) * 4.0 / std::f64::consts::TAU)
                    / n as f64;
                let r = x.hypot(y);
                let (px, py) = (r * a.cos(), r * a.sin());
                [px, py, 0.3 * px * px + 0.1 * px * py].map(R::from_f64)
            })
        })
        .collect();
    CNet::from_sectors([R::ZERO; 3], &sectors).expect("valid c-net")
}

fn bench_valence<R: Real>(c: &mut Criterion, prec: &str, n: usize) {
    let start = EgSubdivision::new(&cnet::<R>(n), None).expect("supported valence");
    let mut stepped = start.clone();
    stepped.step().expect("step");

    let mut g = c.benchmark_group(format!("eg_step_{prec}"));
    g.throughput(Throughput::Elements(1));
    g.bench_with_input(BenchmarkId::from_parameter(n), &start, |b, s| {
        b.iter_batched_ref(
            || s.clone(),
            |s| black_box(s.step()),
            criterion::BatchSize::SmallInput,
        )
    });
    g.finish();

    let mut g = c.benchmark_group(format!("eg_ring_{prec}"));
    g.throughput(Throughput::Elements((3 * n) as u64));
    g.bench_with_input(BenchmarkId::from_parameter(n), &stepped, |b, s| {
        b.iter(|| {
            let mut acc = R::ZERO;
            for p in s.ring_patches() {
                acc += p.points[2][2].0[2];
            }
            black_box(acc)
        })
    });
    g.finish();
}

fn benches(c: &mut Criterion) {
    for n in [3, 4, 5] {
        bench_valence::<f64>(c, "f64", n);
        bench_valence::<f32>(c, "f32", n);
    }
}

criterion_group! {
    name = eg;
    config = Criterion::default()
        .warm_up_time(std::time::Duration::from_millis(500))
        .measurement_time(std::time::Duration::from_secs(2))
        .sample_size(20);
    targets = benches
}
criterion_main!(eg);
