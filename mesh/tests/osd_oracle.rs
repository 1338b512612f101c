//! The OpenSubdiv oracle (tests/osd) against truths computed here from the
//! textbook: uniform bicubic B-spline patches on regular grids, cubic B-spline
//! curves along infinitely sharp creases, holes leaving their neighbours
//! unchanged, the Catmull-Clark vertex limit mask, and the ptex layout of a
//! non-quad face.

#[path = "osd/mod.rs"]
mod osd;

use capdiv_mesh::{EdgeCrease, MeshInput};
use osd::{Answer, Job, Query};

type P = [f64; 3];

const N: u32 = 6;

fn idx(i: u32, j: u32) -> u32 {
    j * N + i
}

/// A 6×6 vertex grid, gently wavy in x and y and bumpy in z.
fn grid() -> MeshInput {
    let mut vertices = Vec::new();
    for j in 0..N {
        for i in 0..N {
            let (x, y) = (f64::from(i), f64::from(j));
            vertices.push([
                x + 0.13 * (1.7 * y + 0.3).sin(),
                y + 0.11 * (1.3 * x - 0.2).cos(),
                0.7 * (0.9 * x).sin() * (1.1 * y + 0.4).cos() + 0.05 * x * y,
            ]);
        }
    }
    let mut faces = Vec::new();
    for j in 0..N - 1 {
        for i in 0..N - 1 {
            faces.push(vec![
                idx(i, j),
                idx(i + 1, j),
                idx(i + 1, j + 1),
                idx(i, j + 1),
            ]);
        }
    }
    MeshInput::new(vertices, faces)
}

fn face(i: u32, j: u32) -> u32 {
    j * (N - 1) + i
}

/// The uniform cubic B-spline basis.
fn bspline(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [
        s * s * s / 6.0,
        (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
        (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
        t * t * t / 6.0,
    ]
}

fn dist(a: P, b: P) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

#[track_caller]
fn close(a: P, b: P, tol: f64, what: &str) {
    assert!(
        dist(a, b) <= tol,
        "{what}: {a:?} vs {b:?} (distance {:e})",
        dist(a, b)
    );
}

const PARAMS: [f64; 6] = [0.0, 0.125, 0.3, 0.5, 0.77, 1.0];

#[test]
fn regular_interior_face_is_the_bicubic_bspline_patch() {
    let mesh = grid();
    let mut job = Job::new(&mesh);
    let mut expected = Vec::new();
    for (fi, fj) in [(1, 1), (2, 2), (3, 1), (2, 3)] {
        for &u in &PARAMS {
            for &v in &PARAMS {
                job.queries.push(Query::quad(face(fi, fj), u, v));
                let (bu, bv) = (bspline(u), bspline(v));
                let mut p = [0.0; 3];
                for (b, wv) in bv.iter().enumerate() {
                    for (a, wu) in bu.iter().enumerate() {
                        let q = mesh.vertices[idx(fi + a as u32 - 1, fj + b as u32 - 1) as usize];
                        for c in 0..3 {
                            p[c] += wu * wv * q[c];
                        }
                    }
                }
                expected.push(p);
            }
        }
    }
    let (answers, _) = osd::run(&job);
    for ((q, a), e) in job.queries.iter().zip(&answers).zip(&expected) {
        assert!(matches!(a, Answer::Exact(_, 0)), "{q:?}: {a:?}");
        close(a.exact(), *e, 1e-12, &format!("{q:?}"));
    }
}

#[test]
fn infinitely_sharp_crease_is_the_bspline_curve_of_its_vertices() {
    let mut mesh = grid();
    let j = 2;
    for i in 0..N - 1 {
        mesh.tags.creases.push(EdgeCrease {
            vertices: [idx(i, j), idx(i + 1, j)],
            sharpness: 10.0,
        });
    }
    let mut job = Job::new(&mesh);
    let mut expected = Vec::new();
    for i in 1..=3 {
        for &t in &PARAMS {
            // The face above the crease has it at v = 0, the face below at v = 1.
            job.queries.push(Query::quad(face(i, j), t, 0.0));
            job.queries.push(Query::quad(face(i, j - 1), t, 1.0));
            let w = bspline(t);
            let mut p = [0.0; 3];
            for (a, wa) in w.iter().enumerate() {
                let q = mesh.vertices[idx(i + a as u32 - 1, j) as usize];
                for c in 0..3 {
                    p[c] += wa * q[c];
                }
            }
            expected.push(p);
            expected.push(p);
        }
    }
    let (answers, _) = osd::run(&job);
    for ((q, a), e) in job.queries.iter().zip(&answers).zip(&expected) {
        close(a.exact(), *e, 1e-12, &format!("{q:?}"));
    }
}

#[test]
fn hole_has_no_patch_and_leaves_its_neighbours_unchanged() {
    let plain = grid();
    let mut holed = grid();
    let hole = face(2, 2);
    holed.tags.holes.push(hole);
    let mut queries = Vec::new();
    for f in [
        face(1, 2),
        face(3, 2),
        face(2, 1),
        face(2, 3),
        face(1, 1),
        face(3, 3),
    ] {
        for &u in &PARAMS {
            for &v in &PARAMS {
                queries.push(Query::quad(f, u, v));
            }
        }
    }
    let mut job = Job::new(&plain);
    job.queries = queries.clone();
    let (expected, _) = osd::run(&job);
    let mut job = Job::new(&holed);
    job.queries = queries.clone();
    job.queries.push(Query::quad(hole, 0.5, 0.5));
    job.queries.push(Query::quad(hole, 0.1, 0.9));
    let (answers, _) = osd::run(&job);
    assert_eq!(answers[queries.len()..], [Answer::NoPatch, Answer::NoPatch]);
    for ((q, a), e) in queries.iter().zip(&answers).zip(&expected) {
        close(a.exact(), e.exact(), 1e-12, &format!("{q:?}"));
    }
}

/// A fan of `n` quads around vertex 0: edge neighbours 1, 3, …, diagonal
/// neighbours 2, 4, …, positions somewhat irregular.
fn fan(n: u32) -> MeshInput {
    let mut vertices = vec![[0.1, -0.05, 0.3]];
    let mut faces = Vec::new();
    for k in 0..n {
        let t = std::f64::consts::TAU * f64::from(k) / f64::from(n);
        let h = std::f64::consts::PI / f64::from(n);
        let r = 1.0 + 0.1 * f64::from(k % 3);
        vertices.push([r * t.cos(), r * t.sin(), 0.2 * (3.0 * t).sin()]);
        vertices.push([
            1.6 * (t + h).cos(),
            1.6 * (t + h).sin(),
            0.3 * (2.0 * t + 0.5).cos(),
        ]);
        let e = 1 + 2 * k;
        faces.push(vec![0, e, e + 1, 1 + (2 * k + 2) % (2 * n)]);
    }
    MeshInput::new(vertices, faces)
}

#[test]
fn vertex_limit_is_the_catmull_clark_limit_mask() {
    for n in [3u32, 4, 5, 6] {
        let mesh = fan(n);
        let v = &mesh.vertices;
        let nf = f64::from(n);
        let mut p = [0.0; 3];
        for c in 0..3 {
            let edges: f64 = (0..n).map(|k| v[1 + 2 * k as usize][c]).sum();
            let diagonals: f64 = (0..n).map(|k| v[2 + 2 * k as usize][c]).sum();
            p[c] = (nf * nf * v[0][c] + 4.0 * edges + diagonals) / (nf * (nf + 5.0));
        }
        let mut job = Job::new(&mesh);
        job.limits = vec![0];
        let (_, limits) = osd::run(&job);
        close(limits[0], p, 1e-12, &format!("valence {n}"));
    }
}

/// A pentagon a0..a4 (vertices 0..4) ringed by quads so that each a_k is a
/// regular interior vertex: per corner k, outer vertices r_k, c_k, s_k.
fn ringed_pentagon() -> MeshInput {
    let n = 5u32;
    let r = |k: u32| n + 3 * (k % n);
    let c = |k: u32| n + 3 * (k % n) + 1;
    let s = |k: u32| n + 3 * (k % n) + 2;
    let polar = |radius: f64, t: f64, z: f64| [radius * t.cos(), radius * t.sin(), z];
    let angle = |k: u32| std::f64::consts::TAU * f64::from(k) / f64::from(n);
    let mut vertices = Vec::new();
    for k in 0..n {
        vertices.push(polar(
            1.0 + 0.07 * f64::from(k),
            angle(k),
            0.1 * f64::from(k),
        ));
    }
    for k in 0..n {
        let t = angle(k);
        vertices.push(polar(2.0, t - 0.3, 0.2 * t.sin()));
        vertices.push(polar(2.5, t, 0.3 * t.cos()));
        vertices.push(polar(2.0, t + 0.3, -0.1 * t.sin()));
    }
    let mut faces = vec![(0..n).collect::<Vec<u32>>()];
    for k in 0..n {
        let k1 = (k + 1) % n;
        faces.push(vec![k1, k, s(k), r(k1)]);
        faces.push(vec![k, r(k), c(k), s(k)]);
    }
    MeshInput::new(vertices, faces)
}

#[test]
fn non_quad_subface_k_starts_at_corner_k_and_runs_to_edge_k_midpoint() {
    let mesh = ringed_pentagon();
    let mut job = Job::new(&mesh);
    for k in 0..5u8 {
        job.queries.push(Query::sub(0, k, 0.0, 0.0));
        job.queries.push(Query::sub(0, k, 1.0, 0.0));
        job.queries.push(Query::sub(0, (k + 1) % 5, 0.0, 1.0));
        job.queries.push(Query::sub(0, k, 1.0, 1.0));
    }
    job.limits = (0..5).collect();
    let (answers, limits) = osd::run(&job);
    let v = &mesh.vertices;
    let mid = |k: usize| {
        let (a, b) = (v[k], v[(k + 1) % 5]);
        [
            (a[0] + b[0]) / 2.0,
            (a[1] + b[1]) / 2.0,
            (a[2] + b[2]) / 2.0,
        ]
    };
    let centre = answers[3].point().unwrap();
    for k in 0..5 {
        let a = &answers[4 * k..4 * k + 4];
        // (0,0) is corner k's limit position.
        close(a[0].exact(), limits[k], 1e-12, &format!("corner {k}"));
        // (1,0) of sub-face k and (0,1) of sub-face k+1 are one point, the
        // limit of edge k→k+1's midpoint, nearer that midpoint than any other.
        let e = a[1].exact();
        close(e, a[2].exact(), 1e-12, &format!("edge {k}"));
        let nearest = (0..5)
            .min_by(|&i, &j| dist(e, mid(i)).total_cmp(&dist(e, mid(j))))
            .unwrap();
        assert_eq!(nearest, k, "sub-face {k} (1,0) is near edge {nearest}");
        // (1,1) is the centre, shared by all sub-faces (an end-cap point
        // at the extraordinary centre, so only approximately equal).
        close(a[3].point().unwrap(), centre, 1e-9, &format!("centre {k}"));
    }
}

#[test]
fn an_out_of_range_vertex_fails_with_the_oracles_message() {
    let mesh = MeshInput::new(vec![[0.0; 3]; 3], vec![vec![0, 1, 7]]);
    let job = Job::new(&mesh);
    let err = std::panic::catch_unwind(|| osd::run(&job)).expect_err("the oracle must fail");
    let message = err
        .downcast_ref::<String>()
        .expect("panic message is a String");
    assert!(message.contains("vertex 7 out of range"), "{message}");
}
