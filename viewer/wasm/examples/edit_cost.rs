//! Native cost of one control-point edit per stage (evaluate, sample, paint)
//! for each sample: `cargo run --release --example edit_cost`. The browser's
//! numbers (WASM, plus the buffer upload) are measured by the page's test.
use capdiv_mesh::{Evaluator, PlanOptions, SurfacePlan, Topology};
use capdiv_viewer::samples::SAMPLES;
use capdiv_viewer::scene::{Options, Scene};
use std::time::Instant;

struct Null;
impl capdiv_mesh::SurfaceSink<f64> for Null {
    fn patch(&mut self, _: &capdiv_mesh::PatchRecord<f64>) {}
    fn cap(&mut self, _: &capdiv_mesh::CapRecord<f64>) {}
}

fn median(mut t: Vec<f64>) -> f64 {
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn main() {
    let depth = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(4);
    let reps = 20;
    println!("depth {depth}, median of {reps} edits, ms");
    println!(
        "{:<24} {:>9} {:>9} {:>9} {:>9}",
        "sample", "evaluate", "edit", "vertices", "rewritten"
    );
    for s in SAMPLES {
        let mesh = (s.build)();
        let topo = Topology::new(&mesh).unwrap();
        let plan = SurfacePlan::new(
            &topo,
            PlanOptions {
                depth,
                ..Default::default()
            },
        )
        .unwrap();
        let mut ev = Evaluator::<f64>::new(&plan).unwrap();
        let mut pos = mesh.vertices.clone();
        // A point in the middle of the list (vertex 0 is often a pole).
        let v = mesh.vertices.len() / 2;
        let eval: Vec<f64> = (0..reps)
            .map(|r| {
                pos[v][0] = mesh.vertices[v][0] + 0.01 * (r % 2) as f64;
                let t = Instant::now();
                ev.evaluate(&pos, &mut Null).unwrap();
                t.elapsed().as_secs_f64() * 1e3
            })
            .collect();
        let o = Options {
            depth,
            ..Options::default()
        };
        let mut sc = Scene::new(
            s.name,
            mesh.clone(),
            o,
            capdiv_viewer::paint::Mode::Gaussian,
        )
        .unwrap();
        let edit: Vec<f64> = (0..reps)
            .map(|r| {
                let p = [
                    mesh.vertices[0][0] + 0.01 * (r % 2) as f64,
                    mesh.vertices[0][1],
                    mesh.vertices[0][2],
                ];
                let t = Instant::now();
                sc.move_vertex(v, p).unwrap();
                t.elapsed().as_secs_f64() * 1e3
            })
            .collect();
        let (a, b) = sc.dirty();
        println!(
            "{:<24} {:>9.2} {:>9.2} {:>9} {:>9}",
            s.name,
            median(eval),
            median(edit),
            sc.surface().len(),
            b - a
        );
    }
}
