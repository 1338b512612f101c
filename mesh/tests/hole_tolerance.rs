//! Caps that stop at a hole tolerance (`Evaluator::set_hole_tolerance`):
//! a cap that stops before the plan's depth leaves a hole at most the
//! tolerance across (measured here on the output's hole edges, sampled
//! densely); a smaller tolerance never gives fewer rings; no tolerance is the
//! fixed-depth surface, patch for patch.

mod common;

use capdiv::Point3;
use capdiv_mesh::samples;
use capdiv_mesh::sinks::CollectSurface;
use capdiv_mesh::tessellate::PatchGeometry;
use capdiv_mesh::{Evaluator, MeshInput, PatchRecord};

type Collect = CollectSurface<f64>;

fn evaluate(mesh: &MeshInput, depth: u32, tolerance: Option<f64>) -> Collect {
    let plan = common::plan(mesh, depth);
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    ev.set_hole_tolerance(tolerance);
    let mut c = Collect::default();
    ev.evaluate(&mesh.vertices, &mut c).expect("evaluate");
    c
}

/// Caps of every scheme: C²PS (globe), EG n = 3 (cube) and n = 5,
/// Catmull-Clark n = 6 (the triangle mesh's refined vertices), mixed (hand).
fn meshes() -> Vec<(&'static str, MeshInput)> {
    vec![
        ("globe", samples::globe(8, 6)),
        ("cube", samples::cube()),
        ("rounded cube", samples::rounded_cube(2)),
        (
            "triangle and pentagon",
            samples::triangle_and_pentagon_mesh(),
        ),
        ("hand", samples::hand()),
    ]
}

fn position(g: &PatchGeometry<f64>, u: f64, v: f64) -> Point3<f64> {
    match g {
        PatchGeometry::Cubic(p) => p.evaluate(u, v).unwrap().position,
        PatchGeometry::Quartic(p) => p.evaluate(u, v).unwrap().position,
    }
}

/// Points of every hole edge of `cap`'s patches, 65 per edge.
fn hole_boundary(patches: &[PatchRecord<f64>], cap: u32) -> Vec<Point3<f64>> {
    let mut pts = Vec::new();
    for p in patches.iter().filter(|p| p.cap == Some(cap) && p.hole != 0) {
        for e in 0..4 {
            if p.hole & (1 << e) == 0 {
                continue;
            }
            for k in 0..=64 {
                let t = k as f64 / 64.0;
                let (u, v) = match e {
                    0 => (t, 0.0),
                    1 => (1.0, t),
                    2 => (t, 1.0),
                    _ => (0.0, t),
                };
                pts.push(position(&p.geometry, u, v));
            }
        }
    }
    pts
}

fn diameter(pts: &[Point3<f64>]) -> f64 {
    let mut d: f64 = 0.0;
    for (i, a) in pts.iter().enumerate() {
        for b in &pts[i + 1..] {
            d = d.max((*a - *b).norm());
        }
    }
    d
}

fn size(mesh: &MeshInput) -> f64 {
    let mut d2 = 0.0;
    for k in 0..3 {
        let lo = mesh
            .vertices
            .iter()
            .map(|p| p[k])
            .fold(f64::INFINITY, f64::min);
        let hi = mesh
            .vertices
            .iter()
            .map(|p| p[k])
            .fold(f64::NEG_INFINITY, f64::max);
        d2 += (hi - lo) * (hi - lo);
    }
    f64::sqrt(d2)
}

#[test]
fn a_cap_stopped_early_leaves_a_hole_within_the_tolerance() {
    let depth = 7;
    for (name, mesh) in meshes() {
        let diag = size(&mesh);
        let mut early = 0;
        for rel in [3e-2, 3e-3, 1e-3] {
            let t = rel * diag;
            let s = evaluate(&mesh, depth, Some(t));
            assert!(!s.caps.is_empty(), "{name}");
            for c in &s.caps {
                assert!((1..=depth).contains(&c.rings), "{name}: {} rings", c.rings);
                // The hole edges are the last ring's: the cap's deepest level.
                let levels: Vec<u32> = s
                    .patches
                    .iter()
                    .filter(|p| p.cap == Some(c.index))
                    .map(|p| p.level)
                    .collect();
                let (lo, hi) = (*levels.iter().min().unwrap(), *levels.iter().max().unwrap());
                assert_eq!(hi - lo + 1, c.rings, "{name}: cap {}", c.index);
                for p in s.patches.iter().filter(|p| p.cap == Some(c.index)) {
                    assert_eq!(p.hole != 0, p.hole != 0 && p.level == hi, "{name}");
                }
                let boundary = hole_boundary(&s.patches, c.index);
                assert!(!boundary.is_empty(), "{name}: cap {} has no hole", c.index);
                if c.rings < depth {
                    early += 1;
                    // The bound is exact (convex hulls); 1e-12 covers rounding.
                    let d = diameter(&boundary);
                    assert!(
                        d <= t * (1.0 + 1e-12),
                        "{name}: cap {} stopped at {} rings with a hole {d} across > {t}",
                        c.index,
                        c.rings
                    );
                }
            }
        }
        assert!(early > 0, "{name}: no cap stopped early");
    }
}

#[test]
fn a_smaller_tolerance_never_gives_fewer_rings() {
    for (name, mesh) in meshes() {
        let diag = size(&mesh);
        let mut previous: Option<Vec<u32>> = None;
        // Decreasing tolerances: rings per cap never decrease.
        for rel in [1.0, 1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 3e-4, 1e-5] {
            let rings: Vec<u32> = evaluate(&mesh, 6, Some(rel * diag))
                .caps
                .iter()
                .map(|c| c.rings)
                .collect();
            if let Some(prev) = &previous {
                assert_eq!(prev.len(), rings.len(), "{name}");
                for (a, b) in prev.iter().zip(&rings) {
                    assert!(b >= a, "{name} at {rel}: {b} rings after {a}");
                }
            }
            previous = Some(rings);
        }
        // A tolerance as large as the mesh stops every cap after one ring.
        assert!(evaluate(&mesh, 6, Some(10.0 * diag))
            .caps
            .iter()
            .all(|c| c.rings == 1));
    }
}

#[test]
fn no_tolerance_is_the_fixed_depth_surface() {
    for (name, mesh) in meshes() {
        for depth in [0, 1, 3] {
            let fixed = evaluate(&mesh, depth, None);
            // A tolerance no hole meets (0: a hole has a width) changes nothing.
            let zero = evaluate(&mesh, depth, Some(0.0));
            for other in [&zero] {
                assert_eq!(other.patches.len(), fixed.patches.len(), "{name}");
                for (a, b) in other.patches.iter().zip(&fixed.patches) {
                    assert_eq!(a.geometry, b.geometry, "{name}");
                    assert_eq!(
                        (a.level, a.face, a.finer, a.hole, a.cap),
                        (b.level, b.face, b.finer, b.hole, b.cap),
                        "{name}"
                    );
                    assert_eq!(a.domain, b.domain, "{name}");
                }
            }
            assert!(fixed.caps.iter().all(|c| c.rings == depth), "{name}");
        }
    }
}
