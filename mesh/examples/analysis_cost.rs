//! Instruction-count probe for callgrind: analyses a 300×300 torus (9·10⁴
//! regular faces) once. `valgrind --tool=callgrind` on the release build,
//! divided by the faces, is the analysis cost per face.
use capdiv_mesh::{samples, PlanOptions, SurfacePlan, Topology};

fn main() {
    let mesh = samples::torus(300, 300);
    let topo = Topology::new(&mesh).expect("torus");
    let plan = SurfacePlan::new(&topo, PlanOptions::default()).expect("plan");
    println!("{} regular faces", plan.regular.len());
}
