//! Instruction-count probe for callgrind (reproducible on a busy machine):
//! builds a generated mesh, analyses it once and evaluates it once in f64.
//!
//! `cost_probe regular|features FACES`; run under
//! `valgrind --tool=callgrind --toggle-collect='*SurfacePlan*new*'` (analysis)
//! or `--toggle-collect='*Evaluator*evaluate*'` (evaluation) and divide by the
//! faces or patches it prints. `regular`: a torus, every face a regular
//! patch; `features`: copies of a mushroom (two valence-12 poles), a rounded
//! cube (eight valence-3 EG caps) and a valence-7 extraordinary disk
//! (Catmull-Clark cap), caps to depth 3 (as `benches/surface.rs`).
use capdiv_mesh::sinks::PatchCounts;
use capdiv_mesh::{samples, Evaluator, PlanOptions, SurfacePlan, Topology};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let kind = args.get(1).map(String::as_str).unwrap_or("regular");
    let faces: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(10_000);
    let mesh = if kind == "features" {
        samples::feature_mix(faces)
    } else {
        let side = (faces as f64).sqrt().ceil() as usize;
        samples::torus(side, side)
    };
    let topo = Topology::new(&mesh).expect("valid mesh");
    let options = PlanOptions {
        depth: 3,
        ..Default::default()
    };
    let plan = SurfacePlan::new(&topo, options).expect("plan");
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    let mut count = PatchCounts::default();
    ev.evaluate(&mesh.vertices, &mut count).expect("evaluate");
    println!(
        "{kind}: {} faces, {} patches",
        mesh.faces.len(),
        count.total
    );
}
