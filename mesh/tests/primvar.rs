//! Per-vertex data other than positions through the plan's stencils
//! ([`SurfacePlan::refine_primvar`], [`capdiv_mesh::Primvar`]): colours equal
//! their components refined one by one, constants stay constant, and
//! positions refined as a primvar give the regular patches the evaluator
//! emits.

mod common;

use capdiv::bezier::bspline_to_bezier_cubic;
use capdiv::Point3;
use capdiv_mesh::tessellate::PatchGeometry;
use capdiv_mesh::{
    samples, CapRecord, Evaluator, MeshInput, PatchKind, PatchRecord, SurfacePlan, SurfaceSink,
    Unit,
};

/// Meshes whose plans have refinement steps (the triangle and pentagon
/// need one) and phantom points (open boundaries).
fn meshes() -> Vec<(&'static str, MeshInput)> {
    vec![
        (
            "triangle-and-pentagon",
            samples::triangle_and_pentagon_mesh(),
        ),
        ("feature-mix", samples::feature_mix(200)),
        ("grid", samples::grid(4, 3)),
        ("extraordinary-disk", samples::extraordinary_disk(5, 3)),
    ]
}

fn plan(m: &MeshInput) -> SurfacePlan<'static> {
    common::plan(m, 2)
}

/// A colour per vertex from its index: arbitrary, distinct values.
fn colour(v: usize) -> [f64; 3] {
    let x = v as f64;
    [
        (0.37 * x).sin().abs(),
        (0.11 * x + 0.5).cos().abs(),
        (x * 0.618).fract(),
    ]
}

#[test]
fn the_meshes_have_refinement_steps_and_phantoms() {
    let plans: Vec<SurfacePlan> = meshes().iter().map(|(_, m)| plan(m)).collect();
    assert!(plans.iter().any(|p| !p.steps.is_empty()));
    assert!(plans.iter().any(|p| !p.phantoms.is_empty()));
}

#[test]
fn colours_refine_component_by_component() {
    for (name, m) in meshes() {
        let p = plan(&m);
        let colours: Vec<[f64; 3]> = (0..m.vertices.len()).map(colour).collect();
        let refined = p.refine_primvar(&colours).expect("one colour per vertex");
        assert_eq!(refined.len(), p.working_points(), "{name}");
        for c in 0..3 {
            let channel: Vec<f64> = colours.iter().map(|x| x[c]).collect();
            let one = p.refine_primvar(&channel).unwrap();
            for (k, (a, b)) in refined.iter().zip(&one).enumerate() {
                // The same weights in the same order: bit-identical sums.
                assert_eq!(a[c].to_bits(), b.to_bits(), "{name}: point {k} channel {c}");
            }
        }
        // f32 colours follow the f64 ones within f32 rounding.
        let c32: Vec<[f32; 3]> = colours.iter().map(|c| c.map(|x| x as f32)).collect();
        let r32 = p.refine_primvar(&c32).unwrap();
        for (a, b) in refined.iter().zip(&r32) {
            for c in 0..3 {
                assert!((a[c] - f64::from(b[c])).abs() < 1e-5, "{name}");
            }
        }
        assert!(p.refine_primvar(&colours[1..]).is_none());
    }
}

#[test]
fn constant_data_stay_constant_and_rows_sum_to_one() {
    for (name, m) in meshes() {
        let p = plan(&m);
        // Each row is an affine combination: weights sum to 1 up to the
        // rounding of adding at most a few dozen weights of size ≤ 1
        // (≈ 30 · 2⁻⁵³ ≈ 3e-15; 1e-13 leaves room).
        for table in p.steps.iter().chain([&p.phantoms]) {
            for i in 0..table.len() {
                let sum: f64 = table.row(i).map(|(_, w)| w).sum();
                assert!((sum - 1.0).abs() < 1e-13, "{name}: row {i} sums to {sum}");
            }
        }
        let constant = vec![[0.7f64, -2.5]; m.vertices.len()];
        for q in p.refine_primvar(&constant).unwrap() {
            assert!(
                (q[0] - 0.7).abs() < 1e-13 && (q[1] + 2.5).abs() < 1e-13,
                "{name}: {q:?}"
            );
        }
    }
}

#[derive(Default)]
struct Regular(Vec<PatchRecord<f64>>);
impl SurfaceSink<f64> for Regular {
    fn patch(&mut self, p: &PatchRecord<f64>) {
        if p.kind == PatchKind::Regular {
            self.0.push(p.clone());
        }
    }
    fn cap(&mut self, _: &CapRecord<f64>) {}
}

#[test]
fn positions_as_a_primvar_make_the_evaluators_regular_patches() {
    for (name, m) in meshes() {
        let p = plan(&m);
        let mut sink = Regular::default();
        Evaluator::<f64>::new(&p)
            .unwrap()
            .evaluate(&m.vertices, &mut sink)
            .unwrap();
        let work = p.refine_primvar(&m.vertices).unwrap();
        assert_eq!(sink.0.len(), p.regular.len(), "{name}");
        // The evaluator gives them in the plan's emission order.
        let emitted = p.order.iter().filter_map(|u| match *u {
            Unit::Regular(i) => Some(&p.regular[i as usize]),
            Unit::Cap(_) => None,
        });
        for (r, rec) in emitted.zip(&sink.0) {
            let d: [[Point3<f64>; 4]; 4] = std::array::from_fn(|i| {
                std::array::from_fn(|j| Point3(work[r.gather[4 * i + j] as usize]))
            });
            let b = bspline_to_bezier_cubic(&d);
            let PatchGeometry::Cubic(g) = &rec.geometry else {
                panic!("{name}: a regular patch is bicubic");
            };
            // The record may be re-oriented to its input face: compare the
            // corner points as sets. Same arithmetic on the same points, so
            // equality is exact.
            let mut want: Vec<[u64; 3]> = [b[0][0], b[3][0], b[3][3], b[0][3]]
                .iter()
                .map(|q| q.0.map(f64::to_bits))
                .collect();
            let mut got: Vec<[u64; 3]> = [
                g.points[0][0],
                g.points[3][0],
                g.points[3][3],
                g.points[0][3],
            ]
            .iter()
            .map(|q| q.0.map(f64::to_bits))
            .collect();
            want.sort();
            got.sort();
            assert_eq!(want, got, "{name}");
        }
    }
}
