//! `PlanOptions::catmull_clark` (the papers' baseline): every cap is
//! a Catmull-Clark cap. Checked (1) on extraordinary points of valence 3 and
//! 5, whose CC caps must equal the literal reference's Catmull-Clark step on
//! the c-net the test reads off `extraordinary_disk` by construction (as
//! `surface_caps.rs` does for n ≥ 6 without the option); (2) on poles: no
//! C²PS cap is left, the pole is a CC cap of the same valence after the
//! refinement step(s); (3) the surfaces stay closed and smooth: every patch
//! edge sample at t = k/8 (hole edges excluded) of a closed mesh is met by
//! another patch's sample at sixteenths (closed: an edge met by two
//! half-size patches has their eighths at its sixteenths and its eighths
//! at theirs), with the same unit normal to 1e-9 and
//! the same H, K to 1e-6 of the local curvature scale (CC ring patches are
//! B-spline patches of the refined grid: C² across their edges; the same
//! tolerances as `surface_smooth.rs`, whose measured worst values are
//! ~1e-12 and ~1e-9).
mod common;

use capdiv_mesh::{samples, Evaluator, MeshInput, PatchKind, Scheme, SurfacePlan, Topology};
use capdiv_reference::{bezier, catmull_clark as cc};
use common::*;

type Grid = Vec<Vec<[f64; 3]>>;

fn surface_with(
    m: &MeshInput,
    depth: u32,
    catmull_clark: bool,
) -> (SurfacePlan<'static>, Collect<f64>) {
    let t = Topology::new(m).expect("valid mesh");
    let plan = SurfacePlan::new(&t, common::plan_options(depth, catmull_clark)).expect("plan");
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    let mut c = Collect::default();
    ev.evaluate(&m.vertices, &mut c).expect("evaluate");
    (plan, c)
}

/// Centre and c-net of `extraordinary_disk(n, r)` by construction (see
/// `surface_caps.rs::disk_cnet`): centre 0, spoke `s` point `a` is
/// `1 + s·r + a − 1`, sector `s` inner point `(a, c)` is
/// `1 + n·r + s·r² + (a−1)·r + c − 1`.
fn disk_cnet(m: &MeshInput, n: usize, r: usize) -> Vec<[f64; 3]> {
    let at = |s: usize, a: usize, c: usize| -> usize {
        match (a, c) {
            (0, 0) => 0,
            (a, 0) => 1 + s * r + a - 1,
            (0, c) => 1 + ((s + 1) % n) * r + c - 1,
            (a, c) => 1 + n * r + s * r * r + (a - 1) * r + c - 1,
        }
    };
    let mut nodes = Vec::new();
    for s in 0..n {
        for (x, y) in [(1, 0), (2, 0), (1, 1), (2, 1), (1, 2), (2, 2)] {
            nodes.push(m.vertices[at(s, x, y)]);
        }
    }
    nodes.push(m.vertices[0]);
    nodes
}

#[test]
fn valence_3_and_5_get_catmull_clark_caps_equal_to_the_reference() {
    let depth = 3;
    for n in [3, 5] {
        let m = samples::extraordinary_disk(n, 3);
        // Without the option: EG.
        let (_, eg) = surface_with(&m, depth, false);
        assert!(eg.caps.iter().all(|c| c.scheme == Scheme::Eg));
        let (plan, out) = surface_with(&m, depth, true);
        assert!(plan.steps.is_empty() && plan.uncovered.is_empty());
        assert_eq!(plan.extraordinary.len(), 1);
        let cap = &out.caps[0];
        assert_eq!(
            (cap.scheme, cap.valence, cap.vertex),
            (Scheme::CatmullClark, n, Some(0))
        );
        assert!(out.patches.iter().all(|p| p.kind != PatchKind::Eg));
        let mut cnet = disk_cnet(&m, n, 3);
        let mut worst = 0.0f64;
        for level in 1..=depth {
            let ext = cc::refine_extended(n, &cnet);
            let mut want: Vec<Grid> = Vec::new();
            for s in 0..n {
                for piece in 0..3 {
                    let b = bezier::bspline_to_bezier(&cc::ring_grid(n, &ext, s, piece));
                    want.push(b.iter().map(|r| r.to_vec()).collect());
                }
            }
            let got: Vec<Grid> = out
                .patches
                .iter()
                .filter(|p| p.cap == Some(cap.index) && p.level == level)
                .inspect(|p| assert_eq!(p.kind, PatchKind::CatmullClark))
                .map(|p| control_grid(&p.geometry))
                .collect();
            worst = worst.max(match_patch_sets(&want, &got));
            cnet = cc::ext_to_cnet(n, &ext);
        }
        println!("CC option n={n}: rings 1..{depth} worst {worst:.2e}");
        assert!(worst < 1e-14, "n={n}: {worst}");
    }
}

#[test]
fn poles_become_catmull_clark_caps_and_closed_meshes_stay_closed_and_smooth() {
    let depth = 3;
    for (name, m, poles) in [
        ("globe(5, 8)", samples::globe(5, 8), vec![5usize, 5]),
        ("globe(20, 8)", samples::globe(20, 8), vec![20, 20]),
        ("mushroom", samples::mushroom(), vec![12, 12]),
        ("rounded_cube(3)", samples::rounded_cube(3), vec![]),
    ] {
        let (default_plan, _) = surface_with(&m, depth, false);
        assert_eq!(
            default_plan.polar.len(),
            poles.len(),
            "{name}: poles by default"
        );
        let (plan, out) = surface_with(&m, depth, true);
        assert!(plan.uncovered.is_empty(), "{name}: {:?}", plan.uncovered);
        assert!(plan.polar.is_empty(), "{name}: a C²PS cap is left");
        assert!(!plan.extraordinary.is_empty());
        assert!(out.caps.iter().all(|c| c.scheme == Scheme::CatmullClark));
        assert!(out
            .patches
            .iter()
            .all(|p| matches!(p.kind, PatchKind::Regular | PatchKind::CatmullClark)));
        // Each pole: a CC cap of its valence at the input vertex.
        let mut pole_valences: Vec<usize> = out
            .caps
            .iter()
            .filter(|c| {
                c.vertex.is_some_and(|v| {
                    m.faces
                        .iter()
                        .filter(|f| f.contains(&v))
                        .all(|f| f.len() == 3)
                })
            })
            .map(|c| c.valence)
            .collect();
        pole_valences.sort_unstable();
        assert_eq!(pole_valences, poles, "{name}");
        if poles.is_empty() {
            // No triangles: no refinement, the valence-3 points are EG's.
            assert!(plan.steps.is_empty());
            assert!(out.caps.iter().all(|c| c.valence == 3));
        }
        let (pairs, normal, mean, gauss) = closed_and_smooth(name, &out.patches);
        assert!(pairs > 0);
        assert!(normal < 1e-9, "{name}: normal {normal}");
        assert!(mean < 1e-6 && gauss < 1e-6, "{name}: ΔH {mean} ΔK {gauss}");
    }
}
