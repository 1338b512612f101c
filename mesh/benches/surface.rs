//! Whole-mesh surfaces: analysis (topology + plan, once per mesh)
//! and evaluation (positions → every patch and cap) on generated meshes of
//! 10³ to 10⁶ faces, per input face and per emitted patch, f64.
//!
//! - `features`: disjoint copies of a mushroom (two valence-12 poles), a
//!   rounded cube (eight valence-3 points: EG) and an extraordinary disk
//!   (valence 7: Catmull-Clark), 1,077 faces per copy; cap depth 3.
//! - `regular`: a torus, every face a regular bicubic patch (the cost of one
//!   regular patch).
//!
//! `cargo bench -p capdiv-mesh --bench surface`; the sink only counts.

use capdiv_mesh::sinks::PatchCounts;
use capdiv_mesh::{samples, Evaluator, MeshInput, PlanOptions, SurfacePlan, Topology};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;

fn torus(faces: usize) -> MeshInput {
    let side = (faces as f64).sqrt().ceil() as usize;
    samples::torus(side, side)
}

fn bench(c: &mut Criterion, name: &str, make: fn(usize) -> MeshInput, depth: u32) {
    let mut analysis = c.benchmark_group(format!("{name}/analysis"));
    analysis.sample_size(10);
    for faces in [1_000usize, 10_000, 100_000, 1_000_000] {
        let mesh = make(faces);
        analysis.throughput(Throughput::Elements(mesh.faces.len() as u64));
        analysis.bench_with_input(
            BenchmarkId::from_parameter(mesh.faces.len()),
            &mesh,
            |b, m| {
                b.iter(|| {
                    let t = Topology::new(m).expect("valid mesh");
                    let plan = SurfacePlan::new(
                        &t,
                        PlanOptions {
                            depth,
                            ..Default::default()
                        },
                    );
                    black_box(plan.expect("plan").regular.len())
                })
            },
        );
    }
    analysis.finish();
    let mut evaluation = c.benchmark_group(format!("{name}/evaluation"));
    evaluation.sample_size(10);
    for faces in [1_000usize, 10_000, 100_000, 1_000_000] {
        let mesh = make(faces);
        let t = Topology::new(&mesh).expect("valid mesh");
        let plan = SurfacePlan::new(
            &t,
            PlanOptions {
                depth,
                ..Default::default()
            },
        )
        .expect("plan");
        let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
        let mut count = PatchCounts::default();
        ev.evaluate(&mesh.vertices, &mut count).expect("evaluate");
        // Throughput in emitted patches; faces are in the id.
        evaluation.throughput(Throughput::Elements(count.total as u64));
        let id = format!("{}f/{}p", mesh.faces.len(), count.total);
        evaluation.bench_function(BenchmarkId::from_parameter(id), |b| {
            b.iter(|| {
                let mut count = PatchCounts::default();
                ev.evaluate(&mesh.vertices, &mut count).expect("evaluate");
                black_box(count.total)
            })
        });
    }
    evaluation.finish();
}

fn all(c: &mut Criterion) {
    bench(c, "features", samples::feature_mix, 3);
    bench(c, "regular", torus, 3);
}

criterion_group!(benches, all);
criterion_main!(benches);
