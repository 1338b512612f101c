//! Regular faces are the uniform bicubic B-spline of
//! their 4×4 neighbourhood, gathered here from the known vertex layout of the
//! sample meshes (never from the plan), evaluated with the literal B-spline
//! basis and compared through the patch's domain and the face's orientation
//! convention (first vertex (0,0), second (1,0), last (0,1)).
mod common;

use capdiv_mesh::{samples, PatchKind, PatchRecord};
use common::*;

/// Evaluates the emitted patch at face coordinates `(u, v)` (which must lie in
/// its domain).
fn at_face_uv(p: &PatchRecord<f64>, u: f64, v: f64) -> [f64; 3] {
    let [u0, u1, v0, v1] = p.domain;
    let s = (u - u0) / (u1 - u0);
    let t = (v - v0) / (v1 - v0);
    derivs(&control_grid(&p.geometry), s, t)[0]
}

/// Literal uniform bicubic B-spline of `d[i][j]` (`i` along u) at `(u, v)`.
fn bspline(d: &[[[f64; 3]; 4]; 4], u: f64, v: f64) -> [f64; 3] {
    let (bu, bv) = (bspline_basis(u), bspline_basis(v));
    let mut x = [0.0; 3];
    for i in 0..4 {
        for j in 0..4 {
            for c in 0..3 {
                x[c] += bu[i] * bv[j] * d[i][j][c];
            }
        }
    }
    x
}

const PARAMS: [f64; 5] = [0.0, 0.2, 0.5, 0.77, 1.0];

/// Torus: vertex (i, j) is `i·nv + j`, face (i, j) is `[(i,j), (i+1,j),
/// (i+1,j+1), (i,j+1)]` at index `i·nv + j` (samples::torus). Every face is
/// regular; its grid is `(i−1..i+2) × (j−1..j+2)` with `i` along the face's u.
#[test]
fn torus_regular_patches_are_the_bspline_of_their_neighbourhood() {
    let (nu, nv) = (7, 5);
    let m = samples::torus(nu, nv);
    let at = |i: isize, j: isize| {
        let (i, j) = (i.rem_euclid(nu as isize), j.rem_euclid(nv as isize));
        m.vertices[i as usize * nv + j as usize]
    };
    let (plan, out) = surface(&m, 3);
    assert!(plan.uncovered.is_empty() && plan.steps.is_empty());
    assert_eq!(out.patches.len(), nu * nv);
    let mut worst = 0.0f64;
    let mut worst_corner = 0.0f64;
    let mut seen = vec![false; nu * nv];
    for p in &out.patches {
        assert_eq!(p.kind, PatchKind::Regular);
        assert_eq!(p.domain, [0.0, 1.0, 0.0, 1.0]);
        assert_eq!(p.corner, None);
        let f = p.face as usize;
        assert!(!seen[f], "face {f} twice");
        seen[f] = true;
        let (i, j) = ((f / nv) as isize, (f % nv) as isize);
        let mut d = [[[0.0; 3]; 4]; 4];
        for (a, row) in d.iter_mut().enumerate() {
            for (b, x) in row.iter_mut().enumerate() {
                *x = at(i - 1 + a as isize, j - 1 + b as isize);
            }
        }
        for &u in &PARAMS {
            for &v in &PARAMS {
                worst = worst.max(dist(at_face_uv(p, u, v), bspline(&d, u, v)));
            }
        }
        // Corners: Catmull-Clark's limit position of a regular vertex,
        // (16 v + 4 Σ edge neighbours + Σ diagonal neighbours) / 36.
        for (ci, cj, u, v) in [
            (0, 0, 0.0, 0.0),
            (1, 0, 1.0, 0.0),
            (1, 1, 1.0, 1.0),
            (0, 1, 0.0, 1.0),
        ] {
            let (vi, vj) = (i + ci, j + cj);
            let mut lim = [0.0; 3];
            for (di, dj, w) in [
                (0, 0, 16.0),
                (1, 0, 4.0),
                (-1, 0, 4.0),
                (0, 1, 4.0),
                (0, -1, 4.0),
                (1, 1, 1.0),
                (1, -1, 1.0),
                (-1, 1, 1.0),
                (-1, -1, 1.0),
            ] {
                let q = at(vi + di, vj + dj);
                for c in 0..3 {
                    lim[c] += w * q[c] / 36.0;
                }
            }
            worst_corner = worst_corner.max(dist(at_face_uv(p, u, v), lim));
        }
    }
    println!(
        "torus: worst |patch − B-spline| {worst:.2e}, worst |corner − CC limit| {worst_corner:.2e}"
    );
    assert!(worst < 1e-14, "{worst}");
    assert!(worst_corner < 1e-14, "{worst_corner}");
}

/// A face list re-ordered so that every face starts at another corner: the
/// patch must follow the face's own first vertex.
#[test]
fn rotated_faces_rotate_their_patches() {
    let (nu, nv) = (6, 5);
    let mut m = samples::torus(nu, nv);
    for (f, face) in m.faces.iter_mut().enumerate() {
        face.rotate_left(f % 4);
    }
    let (_, out) = surface(&m, 2);
    let mut worst = 0.0f64;
    for p in &out.patches {
        let face = &m.faces[p.face as usize];
        // Corner k of the face's square is face vertex k; its limit point is
        // the B-spline's value there, so compare the patch with its own
        // corner vertices' CC limit positions via the torus layout.
        let ij = |v: u32| ((v as usize / nv) as isize, (v as usize % nv) as isize);
        let at = |i: isize, j: isize| {
            let (i, j) = (i.rem_euclid(nu as isize), j.rem_euclid(nv as isize));
            m.vertices[i as usize * nv + j as usize]
        };
        for (k, (u, v)) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
            .into_iter()
            .enumerate()
        {
            let (i, j) = ij(face[k]);
            let mut lim = [0.0; 3];
            for di in -1..=1isize {
                for dj in -1..=1isize {
                    let w = [1.0, 4.0, 1.0][(di + 1) as usize] * [1.0, 4.0, 1.0][(dj + 1) as usize];
                    let q = at(i + di, j + dj);
                    for c in 0..3 {
                        lim[c] += w * q[c] / 36.0;
                    }
                }
            }
            worst = worst.max(dist(at_face_uv(p, u, v), lim));
        }
    }
    assert!(worst < 1e-14, "{worst}");
}

/// Open grid: vertex (i, j) is `j·(nu+1) + i`, face (i, j) has index
/// `j·nu + i`, u along i. Interior faces: B-spline of the 4×4 block.
/// Boundary faces: the boundary curve is the cubic B-spline of the boundary
/// vertices (ends: the curve interpolates the corner vertex, as the mirrored
/// phantom `2b − i` gives); every boundary vertex's limit is `(a + 4b + c)/6`.
#[test]
fn grid_patches_interior_and_boundary() {
    let (nu, nv) = (6, 5);
    let m = samples::grid(nu, nv);
    let at = |i: usize, j: usize| m.vertices[j * (nu + 1) + i];
    let (plan, out) = surface(&m, 2);
    assert!(plan.uncovered.is_empty());
    assert_eq!(out.patches.len(), nu * nv);
    let (mut interior, mut curve, mut corner) = (0.0f64, 0.0f64, 0.0f64);
    // Boundary vertex sequence along a side, extended by the mirror rule at
    // both ends, as a uniform cubic B-spline curve.
    let curve_at = |pts: &[[f64; 3]], k: usize, t: f64| -> [f64; 3] {
        // Span k (between pts[k] and pts[k+1]), control points k−1..k+2,
        // mirrored beyond the ends.
        let get = |i: isize| -> [f64; 3] {
            let n = pts.len() as isize;
            if i < 0 {
                let (b, f) = (pts[0], pts[1]);
                [2.0 * b[0] - f[0], 2.0 * b[1] - f[1], 2.0 * b[2] - f[2]]
            } else if i >= n {
                let (b, f) = (pts[(n - 1) as usize], pts[(n - 2) as usize]);
                [2.0 * b[0] - f[0], 2.0 * b[1] - f[1], 2.0 * b[2] - f[2]]
            } else {
                pts[i as usize]
            }
        };
        let b = bspline_basis(t);
        let mut x = [0.0; 3];
        for (a, w) in b.iter().enumerate() {
            let q = get(k as isize - 1 + a as isize);
            for c in 0..3 {
                x[c] += w * q[c];
            }
        }
        x
    };
    let bottom: Vec<[f64; 3]> = (0..=nu).map(|i| at(i, 0)).collect();
    let top: Vec<[f64; 3]> = (0..=nu).map(|i| at(i, nv)).collect();
    let left: Vec<[f64; 3]> = (0..=nv).map(|j| at(0, j)).collect();
    let right: Vec<[f64; 3]> = (0..=nv).map(|j| at(nu, j)).collect();
    for p in &out.patches {
        assert_eq!(p.kind, PatchKind::Regular);
        let f = p.face as usize;
        let (i, j) = (f % nu, f / nu);
        if i > 0 && j > 0 && i + 1 < nu && j + 1 < nv {
            let mut d = [[[0.0; 3]; 4]; 4];
            for (a, row) in d.iter_mut().enumerate() {
                for (b, x) in row.iter_mut().enumerate() {
                    *x = at(i - 1 + a, j - 1 + b);
                }
            }
            for &u in &PARAMS {
                for &v in &PARAMS {
                    interior = interior.max(dist(at_face_uv(p, u, v), bspline(&d, u, v)));
                }
            }
        }
        for &t in &PARAMS {
            if j == 0 {
                curve = curve.max(dist(at_face_uv(p, t, 0.0), curve_at(&bottom, i, t)));
            }
            if j + 1 == nv {
                curve = curve.max(dist(at_face_uv(p, t, 1.0), curve_at(&top, i, t)));
            }
            if i == 0 {
                curve = curve.max(dist(at_face_uv(p, 0.0, t), curve_at(&left, j, t)));
            }
            if i + 1 == nu {
                curve = curve.max(dist(at_face_uv(p, 1.0, t), curve_at(&right, j, t)));
            }
        }
        for (ci, cj) in [(0, 0), (1, 0), (1, 1), (0, 1)] {
            let (vi, vj) = (i + ci, j + cj);
            let x = at_face_uv(p, ci as f64, cj as f64);
            let on_u = vi == 0 || vi == nu;
            let on_v = vj == 0 || vj == nv;
            if on_u && on_v {
                corner = corner.max(dist(x, at(vi, vj)));
            }
        }
    }
    println!("grid: interior {interior:.2e}, boundary curve {curve:.2e}, corner {corner:.2e}");
    assert!(interior < 1e-14, "{interior}");
    assert!(curve < 1e-14, "{curve}");
    assert!(corner < 1e-15, "{corner}");
}
