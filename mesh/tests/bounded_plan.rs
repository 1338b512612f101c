//! `BoundedPlan`: a surface refused above a patch limit, before evaluation,
//! and otherwise the same surface as planning and evaluating by hand.

mod common;

use capdiv_mesh::bounded::{BoundedPlan, SurfaceError};
use capdiv_mesh::sinks::CollectSurface;
use capdiv_mesh::{
    samples, CapRecord, EvalError, Evaluator, MeshError, MeshInput, PatchRecord, SurfacePlan,
    SurfaceSink,
};
use common::plan_options;

/// Meshes with every kind of patch: regular faces and C²PS caps (globe),
/// EG caps (cube), Catmull-Clark caps (icosphere: valence 5 and 6 under
/// `catmull_clark`), an open mesh with a polar disk.
fn meshes() -> Vec<(&'static str, MeshInput, bool)> {
    vec![
        ("globe", samples::globe(5, 8), false),
        ("cube", samples::cube(), false),
        ("icosphere cc", samples::icosphere(1), true),
        ("pole disk", samples::pole_disk(6, 4), false),
    ]
}

/// Counts every record it is given.
#[derive(Default)]
struct Seen {
    patches: usize,
    caps: usize,
}

impl SurfaceSink<f64> for Seen {
    fn patch(&mut self, _: &PatchRecord<f64>) {
        self.patches += 1;
    }
    fn cap(&mut self, _: &CapRecord<f64>) {
        self.caps += 1;
    }
}

/// The plan's patch count, planned by hand.
fn count(mesh: &MeshInput, depth: u32, cc: bool) -> u64 {
    SurfacePlan::for_mesh(mesh, plan_options(depth, cc))
        .expect("plan")
        .patch_count()
}

#[test]
fn accepts_at_the_limit_and_refuses_one_below_it() {
    for (name, mesh, cc) in meshes() {
        for depth in [1, 3] {
            let n = count(&mesh, depth, cc);
            assert!(n > 1, "{name}: {n} patches");
            let at = BoundedPlan::new(&mesh, plan_options(depth, cc), n, None);
            assert!(
                at.is_ok(),
                "{name} depth {depth}: refused at its own count {n}"
            );
            let above = BoundedPlan::new(&mesh, plan_options(depth, cc), u64::MAX, None);
            assert!(above.is_ok(), "{name}: refused under u64::MAX");
            let below = BoundedPlan::new(&mesh, plan_options(depth, cc), n - 1, None);
            assert_eq!(
                below.err(),
                Some(SurfaceError::TooLarge {
                    patches: n,
                    max: n - 1,
                    upper_bound: false,
                }),
                "{name} depth {depth}"
            );
        }
    }
}

#[test]
fn the_limit_counts_exactly_the_patches_emitted_without_a_tolerance() {
    // The bound is only as good as the count: with every cap at the depth,
    // the evaluation gives exactly `patch_count` patches, so a limit equal
    // to it is the smallest that lets the surface through.
    for (name, mesh, cc) in meshes() {
        for depth in [1, 2, 4] {
            let n = count(&mesh, depth, cc);
            let mut seen = Seen::default();
            BoundedPlan::evaluate_mesh::<f64>(&mesh, plan_options(depth, cc), n, None, &mut seen)
                .expect("accepted at its count");
            assert_eq!(seen.patches as u64, n, "{name} depth {depth}");
        }
    }
}

#[test]
fn a_tolerance_makes_the_count_an_upper_bound() {
    let mesh = samples::globe(6, 8);
    let depth = 6;
    let n = count(&mesh, depth, false);
    // A hole tolerance of a tenth of the globe's radius: caps stop early.
    let tolerance = Some(0.1);
    let refused = BoundedPlan::new(&mesh, plan_options(depth, false), n - 1, tolerance);
    assert_eq!(
        refused.err(),
        Some(SurfaceError::TooLarge {
            patches: n,
            max: n - 1,
            upper_bound: true,
        })
    );
    let mut seen = Seen::default();
    let plan = BoundedPlan::evaluate_mesh::<f64>(
        &mesh,
        plan_options(depth, false),
        n,
        tolerance,
        &mut seen,
    )
    .expect("accepted");
    assert_eq!(plan.hole_tolerance(), tolerance);
    // Early stops emit fewer patches than the bound, never more.
    assert!((seen.patches as u64) < n, "{} of at most {n}", seen.patches);
}

#[test]
fn a_refused_surface_emits_nothing() {
    for (name, mesh, cc) in meshes() {
        let n = count(&mesh, 3, cc);
        let mut seen = Seen::default();
        let e =
            BoundedPlan::evaluate_mesh::<f64>(&mesh, plan_options(3, cc), n - 1, None, &mut seen)
                .expect_err("refused");
        assert!(matches!(e, SurfaceError::TooLarge { patches, .. } if patches == n));
        assert_eq!((seen.patches, seen.caps), (0, 0), "{name}");
    }
}

/// Every record as its exact text (Debug prints each float so that it
/// reads back to the same bits, and tells −0 from +0).
fn bits(c: &CollectSurface<f64>) -> (Vec<String>, Vec<String>) {
    (
        c.patches.iter().map(|p| format!("{p:?}")).collect(),
        c.caps.iter().map(|k| format!("{k:?}")).collect(),
    )
}

#[test]
fn the_surface_is_the_hand_planned_one_bit_for_bit() {
    for (name, mesh, cc) in meshes() {
        for tolerance in [None, Some(0.05)] {
            let plan = SurfacePlan::for_mesh(&mesh, plan_options(3, cc)).expect("plan");
            let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
            ev.set_hole_tolerance(tolerance);
            let mut by_hand = CollectSurface::new();
            ev.evaluate(&mesh.vertices, &mut by_hand).expect("evaluate");

            let mut bounded = CollectSurface::new();
            BoundedPlan::evaluate_mesh(
                &mesh,
                plan_options(3, cc),
                u64::MAX,
                tolerance,
                &mut bounded,
            )
            .expect("bounded");
            assert!(!by_hand.patches.is_empty(), "{name}");
            assert_eq!(bits(&bounded), bits(&by_hand), "{name} {tolerance:?}");

            // Again through a kept evaluator, as a caller whose vertices move.
            let kept =
                BoundedPlan::new(&mesh, plan_options(3, cc), u64::MAX, tolerance).expect("ok");
            let mut again = CollectSurface::new();
            kept.evaluator::<f64>()
                .expect("evaluator")
                .evaluate(&mesh.vertices, &mut again)
                .expect("evaluate");
            assert_eq!(bits(&again), bits(&by_hand), "{name} {tolerance:?} kept");
        }
    }
}

#[test]
fn f32_positions_are_the_cast_vertices() {
    let mesh = samples::cube();
    let plan = SurfacePlan::for_mesh(&mesh, plan_options(2, false)).expect("plan");
    let cast: Vec<[f32; 3]> = mesh.vertices.iter().map(|p| p.map(|c| c as f32)).collect();
    let mut by_hand = CollectSurface::<f32>::new();
    Evaluator::<f32>::new(&plan)
        .expect("evaluator")
        .evaluate(&cast, &mut by_hand)
        .expect("evaluate");
    let mut bounded = CollectSurface::<f32>::new();
    BoundedPlan::evaluate_mesh(&mesh, plan_options(2, false), u64::MAX, None, &mut bounded)
        .expect("bounded");
    let text = |c: &CollectSurface<f32>| format!("{:?} {:?}", c.patches, c.caps);
    assert_eq!(text(&bounded), text(&by_hand));
}

#[test]
fn mesh_and_evaluation_errors_pass_through() {
    let empty = MeshInput::new(Vec::new(), Vec::new());
    let e = BoundedPlan::new(&empty, plan_options(2, false), u64::MAX, None).err();
    assert_eq!(e, Some(SurfaceError::Mesh(MeshError::Empty)));

    let mesh = samples::cube();
    let plan = BoundedPlan::new(&mesh, plan_options(2, false), u64::MAX, None).expect("plan");
    let mut seen = Seen::default();
    let e = plan.evaluate::<f64>(&mesh.vertices[1..], &mut seen).err();
    assert_eq!(
        e,
        Some(SurfaceError::Eval(EvalError::WrongLength {
            expected: 8,
            found: 7,
        }))
    );
    assert_eq!((seen.patches, seen.caps), (0, 0));
}

#[test]
fn the_refusal_says_the_count_the_limit_and_whether_it_is_a_bound() {
    let e = SurfaceError::TooLarge {
        patches: 1234,
        max: 1000,
        upper_bound: false,
    };
    assert_eq!(
        e.to_string(),
        "the surface would have 1234 patches, more than 1000"
    );
    let e = SurfaceError::TooLarge {
        patches: 1234,
        max: 1000,
        upper_bound: true,
    };
    assert_eq!(
        e.to_string(),
        "the surface would have up to 1234 patches, more than 1000"
    );
    // The wrapped errors keep their own messages.
    let mesh = SurfaceError::Mesh(MeshError::Empty);
    assert_eq!(mesh.to_string(), MeshError::Empty.to_string());
    let source: &dyn core::error::Error = &mesh;
    assert!(source.source().is_none());
}
