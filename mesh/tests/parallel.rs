//! `Evaluator::evaluate_parallel` (feature `parallel`) gives the sink the
//! same records as `Evaluator::evaluate`, bit for bit and in the same order,
//! for meshes with caps of every kind (C²PS poles, EG and Catmull-Clark
//! caps, adaptive refinement, refinement steps, boundaries), in f64 and f32,
//! on pools of 2 to 5 threads.
#![cfg(feature = "parallel")]

mod common;

use capdiv::Real;
use capdiv_mesh::samples;
use capdiv_mesh::{
    CapRecord, EvalError, Evaluator, MeshInput, PatchRecord, PlanOptions, Scheme, SurfacePlan,
    SurfaceSink,
};

/// Every record in the order received. `Debug` prints each float in its
/// shortest round-trip form (and -0.0 as such), so equal texts are equal
/// bits.
#[derive(Default)]
struct Log {
    lines: Vec<String>,
    patches: usize,
    schemes: Vec<Scheme>,
}

impl<R: std::fmt::Debug> SurfaceSink<R> for Log {
    fn patch(&mut self, p: &PatchRecord<R>) {
        self.patches += 1;
        self.lines.push(format!("{p:?}"));
    }
    fn cap(&mut self, c: &CapRecord<R>) {
        self.schemes.push(c.scheme);
        self.lines.push(format!("{c:?}"));
    }
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
}

/// Serial and parallel logs of `mesh` in `R` (each parallel run on a new
/// evaluator and again on the same one, as when vertices move).
fn compare<R: Real + Send + Sync + std::fmt::Debug>(
    name: &str,
    mesh: &MeshInput,
    options: PlanOptions<'static>,
) -> Log {
    let plan = SurfacePlan::for_mesh(mesh, options).expect("plan");
    let positions: Vec<[R; 3]> = mesh.vertices.iter().map(|p| p.map(R::from_f64)).collect();
    let mut serial = Log::default();
    Evaluator::<R>::new(&plan)
        .unwrap()
        .evaluate(&positions, &mut serial)
        .unwrap();
    assert!(serial.patches > 0, "{name}");
    for threads in [2, 3, 5] {
        let mut ev = Evaluator::<R>::new(&plan).unwrap();
        for round in 0..2 {
            let mut par = Log::default();
            pool(threads)
                .install(|| ev.evaluate_parallel(&positions, &mut par))
                .unwrap();
            assert_eq!(
                par.lines.len(),
                serial.lines.len(),
                "{name}: {threads} threads, round {round}"
            );
            for (i, (a, b)) in serial.lines.iter().zip(&par.lines).enumerate() {
                assert_eq!(a, b, "{name}: record {i}, {threads} threads, round {round}");
            }
        }
    }
    serial
}

fn depth(depth: u32) -> PlanOptions<'static> {
    common::plan_options(depth, false)
}

fn meshes() -> Vec<(&'static str, MeshInput, PlanOptions<'static>)> {
    vec![
        ("globe", samples::globe(6, 8), depth(4)),
        ("hand", samples::hand(), depth(3)),
        ("cube", samples::cube(), depth(5)),
        ("rounded cube", samples::rounded_cube(4), depth(3)),
        (
            "extraordinary disk",
            samples::extraordinary_disk(7, 5),
            depth(3),
        ),
        ("grid", samples::grid(9, 7), depth(3)),
        (
            "triangle and pentagon",
            samples::triangle_and_pentagon_mesh(),
            depth(3),
        ),
        ("feature mix", samples::feature_mix(12_000), depth(3)),
        ("torus", samples::torus(100, 100), depth(3)),
        (
            "catmull-clark",
            samples::feature_mix(2_000),
            common::plan_options(3, true),
        ),
    ]
}

#[test]
fn parallel_output_is_the_serial_output_f64() {
    let mut schemes = Vec::new();
    for (name, mesh, options) in meshes() {
        schemes.extend(compare::<f64>(name, &mesh, options).schemes);
    }
    for s in [Scheme::C2ps, Scheme::Eg, Scheme::CatmullClark] {
        assert!(schemes.contains(&s), "no {s:?} cap among the meshes");
    }
}

#[test]
fn parallel_output_is_the_serial_output_f32() {
    for (name, mesh, options) in meshes() {
        compare::<f32>(name, &mesh, options);
    }
}

#[test]
fn parallel_errors_are_the_serial_errors() {
    let mesh = samples::hand();
    let plan = SurfacePlan::for_mesh(&mesh, depth(3)).unwrap();
    let mut ev = Evaluator::<f64>::new(&plan).unwrap();
    let mut short = mesh.vertices.clone();
    short.pop();
    let run = |ev: &mut Evaluator<f64>, v: &[[f64; 3]]| {
        pool(2).install(|| ev.evaluate_parallel(v, &mut Log::default()))
    };
    assert_eq!(
        run(&mut ev, &short),
        Err(EvalError::WrongLength {
            expected: mesh.vertices.len(),
            found: mesh.vertices.len() - 1,
        })
    );
    let mut bad = mesh.vertices.clone();
    bad[3][1] = f64::NAN;
    assert_eq!(run(&mut ev, &bad), Err(EvalError::NonFinite { vertex: 3 }));
    let mut huge = mesh.vertices.clone();
    huge[5][0] = f64::MAX;
    assert_eq!(run(&mut ev, &huge), ev.evaluate(&huge, &mut Log::default()));
}
