//! Instruction-count probe for callgrind: evaluates a 100×100 torus (10⁴
//! regular faces) 20 times in f64. `valgrind --tool=callgrind` on the release
//! build, divided by 2·10⁵ patches, is the cost of one regular patch.
use capdiv_mesh::{samples, CapRecord, Evaluator, PatchRecord, PlanOptions, SurfacePlan};
use capdiv_mesh::{SurfaceSink, Topology};

struct Sum(f64);
impl SurfaceSink<f64> for Sum {
    fn patch(&mut self, p: &PatchRecord<f64>) {
        self.0 += p.domain[1];
    }
    fn cap(&mut self, _: &CapRecord<f64>) {}
}

fn main() {
    let mesh = samples::torus(100, 100);
    let topo = Topology::new(&mesh).expect("torus");
    let plan = SurfacePlan::new(&topo, PlanOptions::default()).expect("plan");
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    let mut sum = Sum(0.0);
    for _ in 0..20 {
        ev.evaluate(&plan, &mesh.vertices, &mut sum)
            .expect("evaluate");
    }
    println!("{}", sum.0);
}
