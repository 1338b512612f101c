//! Evaluation time, one thread against `Evaluator::evaluate_parallel` on
//! pools of 2 (and more) threads: the median of repeated runs per mesh,
//! with a sink that only counts and one that keeps every record (as the
//! CLI does before writing).
//!
//! `cargo run --release -p capdiv-mesh --features parallel --example parallel_eval [REPEATS]`

use capdiv_mesh::{
    samples, CapRecord, Evaluator, MeshInput, PatchRecord, PlanOptions, SurfacePlan, SurfaceSink,
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

#[derive(Default)]
struct Keep(Vec<PatchRecord<f64>>, Vec<CapRecord<f64>>);

impl SurfaceSink<f64> for Keep {
    fn patch(&mut self, p: &PatchRecord<f64>) {
        self.0.push(p.clone());
    }
    fn cap(&mut self, c: &CapRecord<f64>) {
        self.1.push(c.clone());
    }
}

/// An icosahedron split `k` times into four (20·4^k triangles) on the unit
/// sphere.
fn icosphere(k: usize) -> MeshInput {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut v: Vec<[f64; 3]> = vec![
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let unit = |p: [f64; 3]| {
        let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        [p[0] / n, p[1] / n, p[2] / n]
    };
    v = v.into_iter().map(unit).collect();
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..k {
        let mut mid = std::collections::HashMap::new();
        let mut next = Vec::new();
        for [a, b, c] in f {
            let mut m = |x: u32, y: u32| {
                *mid.entry((x.min(y), x.max(y))).or_insert_with(|| {
                    let (p, q) = (v[x as usize], v[y as usize]);
                    v.push(unit([p[0] + q[0], p[1] + q[1], p[2] + q[2]]));
                    v.len() as u32 - 1
                })
            };
            let (ab, bc, ca) = (m(a, b), m(b, c), m(c, a));
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = next;
    }
    MeshInput::new(v, f.into_iter().map(|t| t.to_vec()).collect())
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
            ev.evaluate(plan, positions, &mut sink).unwrap();
        } else {
            pool.install(|| ev.evaluate_parallel(plan, positions, &mut sink))
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
        ("icosphere 20480", icosphere(5), 3),
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
                _ => time::<Keep>(repeats, threads, &plan, &mesh.vertices),
            };
            let (one, two) = (run(1), run(2));
            println!(
                "{name} | {patches} | {sink} | {one:.1} | {two:.1} | {:.2}",
                one / two
            );
        }
    }
}
