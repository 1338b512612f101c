//! Evaluation time, one thread against `Evaluator::evaluate_parallel` on
//! pools of 2 (and more) threads: the median of repeated runs per mesh,
//! with a sink that only counts and one that keeps every record (as the
//! CLI does before writing).
//!
//! `cargo run --release -p capdiv-mesh --features parallel --example parallel_eval [REPEATS]`

use capdiv_mesh::sinks::CollectSurface;
use capdiv_mesh::{
    samples, CapRecord, Evaluator, PatchRecord, PlanOptions, SurfacePlan, SurfaceSink,
};
use std::time::Instant;

#[derive(Default)]
struct Count(usize);

impl SurfaceSink<f64> for Count {
    fn patch(&mut self, p: &PatchRecord<f64>) {
        self.0 += p.level as usize;
    }
    fn cap(&mut self, _: &CapRecord<f64>) {}
}

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

fn time<S: SurfaceSink<f64> + Default + Send>(
    repeats: usize,
    threads: usize,
    plan: &SurfacePlan<'_>,
    positions: &[[f64; 3]],
) -> f64 {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let mut ev = Evaluator::<f64>::new(plan).unwrap();
    let mut times = Vec::new();
    for _ in 0..repeats {
        let mut sink = S::default();
        let start = Instant::now();
        if threads == 1 {
            ev.evaluate(positions, &mut sink).unwrap();
        } else {
            pool.install(|| ev.evaluate_parallel(positions, &mut sink))
                .unwrap();
        }
        times.push(start.elapsed().as_secs_f64() * 1e3);
        drop(sink);
    }
    median(times)
}

fn main() {
    let repeats: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(7);
    let meshes = [
        ("torus 300x300", samples::torus(300, 300), 3),
        ("icosphere 20480", samples::icosphere(5), 3),
        ("feature mix 20k", samples::feature_mix(20_000), 3),
    ];
    println!("mesh | patches | sink | 1 thread ms | 2 threads ms | speed-up");
    for (name, mesh, depth) in meshes {
        let plan = SurfacePlan::for_mesh(
            &mesh,
            PlanOptions {
                depth,
                ..Default::default()
            },
        )
        .unwrap();
        let patches = plan.patch_count();
        for sink in ["count", "keep"] {
            let run = |threads| match sink {
                "count" => time::<Count>(repeats, threads, &plan, &mesh.vertices),
                _ => time::<CollectSurface<f64>>(repeats, threads, &plan, &mesh.vertices),
            };
            let (one, two) = (run(1), run(2));
            println!(
                "{name} | {patches} | {sink} | {one:.1} | {two:.1} | {:.2}",
                one / two
            );
        }
    }
}
