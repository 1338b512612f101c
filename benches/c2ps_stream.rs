//! Streaming C²PS against the in-place path: all ring patches of
//! levels 0..=M of a valence-6 configuration (5 links), time per patch, f64
//! and f32, M = 6, 8, 10, 12. Both workloads build every patch and hand it
//! to `black_box`:
//!
//! - `stream-*`: one `PolarStream::sweep` (state: `(M+1)` windows of 4
//!   columns, a few KiB);
//! - `in-place-*`: a `PolarNetBuf` (whole levels, `17·6·2^M` scalars)
//!   stepped M times, its `ring_patches` read at every level.
//!
//! `cargo bench --bench c2ps_stream`; `python3 scripts/bench-table.py
//! stream-f64 in-place-f64 stream-f32 in-place-f32` makes the README table.
//! The bench also prints the memory of both paths for M = 8, 12, 16, 20.
//!
//! Instruction counts (reproducible on a shared machine): run the bench
//! binary with `--probe stream|in-place DEPTH [f32]` under
//! `valgrind --tool=callgrind --collect-atstart=no --toggle-collect='*probe_*'`;
//! it runs one workload once (f64, or f32).

use capdiv::{
    BicubicPatch, FirstStep, Point3, PolarNetBuf, PolarStream, Real, SliceStorage, StreamOptions,
};
use criterion::{BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use std::time::Duration;

/// Deepest level benchmarked (and the state's maximum depth).
const MAX: usize = 12;

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

fn consume<R: Real>(p: &BicubicPatch<R>) {
    black_box(p);
}

/// All patches of levels 0..=depth by one sweep; returns their number.
#[inline(never)]
fn probe_stream<R: Real>(
    state: &mut PolarStream<R, MAX>,
    pole: [R; 3],
    links: &[Vec<[R; 3]>],
    depth: u32,
) -> usize {
    let mut count = 0;
    let sweep = state
        .sweep(pole, links, StreamOptions::depth(depth))
        .unwrap();
    for p in sweep {
        consume(&p.patch);
        count += 1;
    }
    count
}

/// All patches of levels 0..=depth in place; returns their number.
#[inline(never)]
fn probe_in_place<R: Real>(
    ls: &mut [Point3<R>],
    rs: &mut [[R; 2]],
    pole: [R; 3],
    links: &[Vec<[R; 3]>],
    depth: u32,
) -> usize {
    let mut net = PolarNetBuf::new_in(pole, links, SliceStorage::new(ls, rs)).unwrap();
    let mut count = 0;
    for level in 0..=depth {
        for p in net.ring_patches() {
            consume(&p);
            count += 1;
        }
        if level < depth {
            net.step(FirstStep::Uniform).unwrap();
        }
    }
    count
}

fn patches(depth: u32) -> usize {
    (0..=depth).map(|m| 2 * (6usize << m)).sum()
}

fn bench<R: Real>(c: &mut Criterion, name: &str) {
    let (pole, links) = sample::<R>();
    let mut state = Box::new(PolarStream::<R, MAX>::empty());
    let cap = 6 << MAX;
    let mut ls = vec![Point3::<R>::ZERO; SliceStorage::<R>::links_len(cap)];
    let mut rs = vec![[R::ZERO; 2]; SliceStorage::<R>::roots_len(cap)];
    for depth in [6u32, 8, 10, 12] {
        let n = patches(depth);
        let mut g = c.benchmark_group(format!("stream-{name}"));
        g.throughput(Throughput::Elements(n as u64));
        g.bench_function(BenchmarkId::from_parameter(depth), |b| {
            b.iter(|| probe_stream(&mut state, pole, &links, black_box(depth)))
        });
        g.finish();
        let mut g = c.benchmark_group(format!("in-place-{name}"));
        g.throughput(Throughput::Elements(n as u64));
        g.bench_function(BenchmarkId::from_parameter(depth), |b| {
            b.iter(|| probe_in_place(&mut ls, &mut rs, pole, &links, black_box(depth)))
        });
        g.finish();
    }
}

fn memory() {
    use std::mem::size_of;
    println!("| depth M | stream f32 (bytes) | stream f64 (bytes) | in place f32 (bytes) | in place f64 (bytes) |");
    println!("|---:|---:|---:|---:|---:|");
    let row = |m: usize, s32: usize, s64: usize| {
        let cap = 6usize << m;
        println!(
            "| {m} | {s32} | {s64} | {} | {} |",
            17 * cap * 4,
            17 * cap * 8
        );
    };
    row(
        8,
        size_of::<PolarStream<f32, 8>>(),
        size_of::<PolarStream<f64, 8>>(),
    );
    row(
        12,
        size_of::<PolarStream<f32, 12>>(),
        size_of::<PolarStream<f64, 12>>(),
    );
    row(
        16,
        size_of::<PolarStream<f32, 16>>(),
        size_of::<PolarStream<f64, 16>>(),
    );
    row(
        20,
        size_of::<PolarStream<f32, 20>>(),
        size_of::<PolarStream<f64, 20>>(),
    );
}

/// One workload once (for callgrind).
fn probe<R: Real>(which: &str, depth: u32) -> usize {
    let (pole, links) = sample::<R>();
    if which == "stream" {
        let mut state = Box::new(PolarStream::<R, MAX>::empty());
        probe_stream(&mut state, pole, &links, depth)
    } else {
        let cap = 6 << depth;
        let mut ls = vec![Point3::ZERO; SliceStorage::<R>::links_len(cap)];
        let mut rs = vec![[R::ZERO; 2]; SliceStorage::<R>::roots_len(cap)];
        probe_in_place(&mut ls, &mut rs, pole, &links, depth)
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--probe") {
        let which = args.get(i + 1).map(String::as_str).unwrap_or("stream");
        let depth: u32 = args.get(i + 2).and_then(|d| d.parse().ok()).unwrap_or(10);
        let f32 = args.get(i + 3).is_some_and(|t| t == "f32");
        let count = if f32 {
            probe::<f32>(which, depth)
        } else {
            probe::<f64>(which, depth)
        };
        println!("{which} depth {depth}: {count} patches");
        return;
    }
    memory();
    let mut c = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .configure_from_args();
    bench::<f64>(&mut c, "f64");
    bench::<f32>(&mut c, "f32");
    c.final_summary();
}
