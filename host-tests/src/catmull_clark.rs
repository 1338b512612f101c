//! Catmull-Clark subdivision (Catmull & Clark 1978), literally, on an explicit
//! polygon mesh, and what the kernel's `cc` module is checked against: the
//! refined neighbourhood of a c-net (docs/math/eg.md §1), its dense subdivision
//! matrix, the limit weights as the matrix's left eigenvector, and the uniform
//! bicubic B-spline patch from its literal basis functions. Shares no code
//! with the kernel.
//!
//! Indexing. c-net (`6n+1`): sector `s` node `(x, y)` in the §1 order
//! `(1,0) (2,0) (1,1) (2,1) (1,2) (2,2)` at `6s + k`, the center last.
//! Extended ring (`12n+1`): sector `s` node `(x, y)`, `x ∈ 1..=3`,
//! `y ∈ 0..=3`, at `12s + 4(x−1) + y` (note: x-major, unlike the kernel),
//! the center last.

use crate::vec3::{add, axpy, scale, P3, ZERO};
use nalgebra::{DMatrix, DVector};
use std::collections::HashMap;

/// A polygon mesh: points and faces (counter-clockwise index lists).
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// The points.
    pub verts: Vec<P3>,
    /// The faces, each a counter-clockwise list of point indices.
    pub faces: Vec<Vec<usize>>,
}

/// One Catmull-Clark step of a [`Mesh`], and where each new point came from.
#[derive(Clone, Debug)]
pub struct Refined {
    /// The new mesh (quads).
    pub mesh: Mesh,
    /// New index of the vertex point of old vertex `v`.
    pub vertex_point: Vec<usize>,
    /// New index of the edge point of old edge `{a, b}` (key `(min, max)`).
    pub edge_point: HashMap<(usize, usize), usize>,
    /// New index of the face point of old face `f`.
    pub face_point: Vec<usize>,
}

fn edge_key(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

fn average(pts: impl Iterator<Item = P3>) -> P3 {
    let mut sum = ZERO;
    let mut k = 0usize;
    for p in pts {
        sum = add(sum, p);
        k += 1;
    }
    scale(1.0 / k as f64, sum)
}

/// One Catmull-Clark step, by the paper's rules for interior points:
/// - face point `F` = average of the face's points;
/// - edge point = average of the edge's two ends and the two adjacent face points;
/// - vertex point = `Q/k + 2R/k + (k−3)S/k`, `Q` the average of the adjacent
///   face points, `R` the average of the midpoints of the `k` incident edges,
///   `S` the old point.
///
/// Boundary edges (one face) and boundary vertices have no rule here: their
/// new points are NaN, so any use of them shows.
pub fn step(mesh: &Mesh) -> Refined {
    let nv = mesh.verts.len();
    let face_pts: Vec<P3> = mesh
        .faces
        .iter()
        .map(|f| average(f.iter().map(|&i| mesh.verts[i])))
        .collect();
    // Edge → adjacent faces; vertex → incident faces and edges.
    let mut edge_faces: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    let mut vert_faces: Vec<Vec<usize>> = vec![Vec::new(); nv];
    for (fi, f) in mesh.faces.iter().enumerate() {
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            edge_faces.entry(edge_key(a, b)).or_default().push(fi);
            vert_faces[a].push(fi);
        }
    }
    let mut vert_edges: Vec<Vec<(usize, usize)>> = vec![Vec::new(); nv];
    let mut edges: Vec<(usize, usize)> = edge_faces.keys().copied().collect();
    edges.sort();
    for &(a, b) in &edges {
        vert_edges[a].push((a, b));
        vert_edges[b].push((a, b));
    }
    let nan = [f64::NAN; 3];
    let mut verts = Vec::new();
    let mut face_point = Vec::new();
    for &p in &face_pts {
        face_point.push(verts.len());
        verts.push(p);
    }
    let mut edge_point = HashMap::new();
    for &(a, b) in &edges {
        let fs = &edge_faces[&(a, b)];
        let p = if fs.len() == 2 {
            average(
                [
                    mesh.verts[a],
                    mesh.verts[b],
                    face_pts[fs[0]],
                    face_pts[fs[1]],
                ]
                .into_iter(),
            )
        } else {
            nan
        };
        edge_point.insert((a, b), verts.len());
        verts.push(p);
    }
    let mut vertex_point = Vec::new();
    for v in 0..nv {
        let k = vert_edges[v].len();
        let interior = k >= 3
            && k == vert_faces[v].len()
            && vert_edges[v].iter().all(|e| edge_faces[e].len() == 2);
        let p = if interior {
            let q = average(vert_faces[v].iter().map(|&f| face_pts[f]));
            let r = average(
                vert_edges[v]
                    .iter()
                    .map(|&(a, b)| scale(0.5, add(mesh.verts[a], mesh.verts[b]))),
            );
            let kf = k as f64;
            axpy(
                axpy(scale(1.0 / kf, q), 2.0 / kf, r),
                (kf - 3.0) / kf,
                mesh.verts[v],
            )
        } else {
            nan
        };
        vertex_point.push(verts.len());
        verts.push(p);
    }
    // New faces: per old face and corner, (vertex, next edge, face, previous edge).
    let mut faces = Vec::new();
    for (fi, f) in mesh.faces.iter().enumerate() {
        let m = f.len();
        for k in 0..m {
            let (prev, cur, next) = (f[(k + m - 1) % m], f[k], f[(k + 1) % m]);
            faces.push(vec![
                vertex_point[cur],
                edge_point[&edge_key(cur, next)],
                face_point[fi],
                edge_point[&edge_key(prev, cur)],
            ]);
        }
    }
    Refined {
        mesh: Mesh { verts, faces },
        vertex_point,
        edge_point,
        face_point,
    }
}

/// Where `(x, y)` of sector `s` lies after the §1 change of frame:
/// `None` for the center, else `(sector, x, y)` with `x ≥ 1`, `y ≥ 0`.
pub fn owner(n: usize, s: usize, x: i64, y: i64) -> Option<(usize, i64, i64)> {
    let (mut s, mut x, mut y) = (s as i64, x, y);
    loop {
        if x == 0 && y == 0 {
            return None;
        }
        if y < 0 {
            (s, x, y) = (s - 1, -y, x);
        } else if x <= 0 {
            (s, x, y) = (s + 1, y, -x);
        } else {
            return Some((s.rem_euclid(n as i64) as usize, x, y));
        }
    }
}

/// Index of c-net node `(x, y)` of sector `s` (any frame, `|x|, |y| ≤ 2`).
pub fn cnet_index(n: usize, s: usize, x: i64, y: i64) -> usize {
    match owner(n, s, x, y) {
        None => 6 * n,
        Some((t, x, y)) => {
            assert!(
                (1..=2).contains(&x) && (0..=2).contains(&y),
                "outside c-net"
            );
            6 * t + (x - 1) as usize + 2 * y as usize
        }
    }
}

/// Index of extended-ring node `(x, y)` of sector `s` (any frame, `|x|, |y| ≤ 3`).
pub fn ext_index(n: usize, s: usize, x: i64, y: i64) -> usize {
    match owner(n, s, x, y) {
        None => 12 * n,
        Some((t, x, y)) => {
            assert!((1..=3).contains(&x) && (0..=3).contains(&y), "outside ring");
            12 * t + 4 * (x - 1) as usize + y as usize
        }
    }
}

/// The c-net as an explicit quad mesh: its points (the `6n+1` of the c-net
/// indexing) and the `4n` faces `[a,a+1]×[b,b+1]`, `a, b ∈ {0, 1}`, of each
/// sector, counter-clockwise.
pub fn cnet_mesh(n: usize, cnet: &[P3]) -> Mesh {
    assert_eq!(cnet.len(), 6 * n + 1);
    let mut faces = Vec::new();
    for s in 0..n {
        for (a, b) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            faces.push(vec![
                cnet_index(n, s, a, b),
                cnet_index(n, s, a + 1, b),
                cnet_index(n, s, a + 1, b + 1),
                cnet_index(n, s, a, b + 1),
            ]);
        }
    }
    Mesh {
        verts: cnet.to_vec(),
        faces,
    }
}

/// One Catmull-Clark step of a c-net (`6n+1` points, c-net indexing): the
/// extended ring (`12n+1`, x-major indexing) read off the refined mesh. New
/// `(X, Y)` is the vertex point of old `(X/2, Y/2)`, the edge point of the
/// old edge through `(X/2, Y/2)`, or the face point of the old face around it.
pub fn refine_extended(n: usize, cnet: &[P3]) -> Vec<P3> {
    let mesh = cnet_mesh(n, cnet);
    let r = step(&mesh);
    // Old face [a,a+1]×[b,b+1] of sector s, found by its corner set.
    let face_of = |s: usize, a: i64, b: i64| -> usize {
        let mut want = [
            cnet_index(n, s, a, b),
            cnet_index(n, s, a + 1, b),
            cnet_index(n, s, a + 1, b + 1),
            cnet_index(n, s, a, b + 1),
        ];
        want.sort();
        let fi = mesh
            .faces
            .iter()
            .position(|f| {
                let mut g = f.clone();
                g.sort();
                g == want
            })
            .expect("a face of the c-net");
        r.face_point[fi]
    };
    let mut out = vec![ZERO; 12 * n + 1];
    for s in 0..n {
        for x in 1..=3i64 {
            for y in 0..=3i64 {
                let (a, b) = (x.div_euclid(2), y.div_euclid(2));
                let idx = match (x % 2, y % 2) {
                    (0, 0) => r.vertex_point[cnet_index(n, s, a, b)],
                    (1, 0) => {
                        r.edge_point[&edge_key(cnet_index(n, s, a, b), cnet_index(n, s, a + 1, b))]
                    }
                    (0, 1) => {
                        r.edge_point[&edge_key(cnet_index(n, s, a, b), cnet_index(n, s, a, b + 1))]
                    }
                    _ => face_of(s, a, b),
                };
                out[ext_index(n, s, x, y)] = r.mesh.verts[idx];
            }
        }
    }
    out[12 * n] = r.mesh.verts[r.vertex_point[6 * n]];
    out
}

/// The c-net part (`x, y ≤ 2`) of an extended ring, in c-net indexing.
pub fn ext_to_cnet(n: usize, ext: &[P3]) -> Vec<P3> {
    let mut c = vec![ZERO; 6 * n + 1];
    for s in 0..n {
        for x in 1..=2 {
            for y in 0..=2 {
                c[cnet_index(n, s, x, y)] = ext[ext_index(n, s, x, y)];
            }
        }
    }
    c[6 * n] = ext[12 * n];
    c
}

/// The dense matrix `E` (`(12n+1) × (6n+1)`) of [`refine_extended`]: column
/// `j` is the literal step applied to the `j`-th unit c-net (in `x`).
pub fn extended_matrix(n: usize) -> DMatrix<f64> {
    let dim = 6 * n + 1;
    let mut m = DMatrix::zeros(12 * n + 1, dim);
    for j in 0..dim {
        let mut c = vec![ZERO; dim];
        c[j] = [1.0, 0.0, 0.0];
        let ext = refine_extended(n, &c);
        for (i, p) in ext.iter().enumerate() {
            m[(i, j)] = p[0];
        }
    }
    m
}

/// The c-net's subdivision matrix `S` (`(6n+1)²`): the rows of
/// [`extended_matrix`] of the new c-net.
pub fn cnet_matrix(n: usize) -> DMatrix<f64> {
    let e = extended_matrix(n);
    let mut s = DMatrix::zeros(6 * n + 1, 6 * n + 1);
    for t in 0..n {
        for x in 1..=2 {
            for y in 0..=2 {
                s.set_row(cnet_index(n, t, x, y), &e.row(ext_index(n, t, x, y)));
            }
        }
    }
    s.set_row(6 * n, &e.row(12 * n));
    s
}

/// The left eigenvector `l` of eigenvalue 1 of `S`, normalized to `Σ l = 1`:
/// `lᵀ S^m c → lᵀ c`, the limit position of the center. Solved from
/// `(Sᵀ − I) l = 0` with one equation replaced by `Σ l = 1`.
pub fn limit_weights(n: usize) -> DVector<f64> {
    let s = cnet_matrix(n);
    let dim = s.nrows();
    let mut a = s.transpose() - DMatrix::identity(dim, dim);
    a.row_mut(dim - 1).fill(1.0);
    let mut rhs = DVector::zeros(dim);
    rhs[dim - 1] = 1.0;
    a.lu().solve(&rhs).expect("eigenvalue 1 is simple")
}

/// The `r`-th derivative of the uniform cubic B-spline basis function `i`
/// (`i = 0..3`) on one span, `t ∈ [0, 1]`: `N0 = (1−t)³/6`,
/// `N1 = (3t³ − 6t² + 4)/6`, `N2 = (−3t³ + 3t² + 3t + 1)/6`, `N3 = t³/6`.
pub fn bspline_basis(i: usize, r: usize, t: f64) -> f64 {
    let poly: [f64; 4] = match i {
        0 => [1.0, -3.0, 3.0, -1.0],
        1 => [4.0, 0.0, -6.0, 3.0],
        2 => [1.0, 3.0, 3.0, -3.0],
        _ => [0.0, 0.0, 0.0, 1.0],
    }; // coefficients of 1, t, t², t³, ×6
    let mut c = poly.map(|v| v / 6.0);
    for _ in 0..r {
        c = [c[1], 2.0 * c[2], 3.0 * c[3], 0.0];
    }
    c[0] + t * (c[1] + t * (c[2] + t * c[3]))
}

/// `∂^(ru+rv)/∂u^ru ∂v^rv` of the uniform bicubic B-spline patch of the 4×4
/// grid `d[i][j]` (`i` along `u`) at `(u, v) ∈ [0, 1]²`.
pub fn bspline_eval(d: &[[P3; 4]; 4], u: f64, v: f64, ru: usize, rv: usize) -> P3 {
    let mut acc = ZERO;
    for (i, row) in d.iter().enumerate() {
        for (j, &p) in row.iter().enumerate() {
            acc = axpy(acc, bspline_basis(i, ru, u) * bspline_basis(j, rv, v), p);
        }
    }
    acc
}

/// The 4×4 B-spline grid of ring patch `piece` of sector `s` of an extended
/// ring: the face `[1,2]×[0,1]` (piece 0), `[0,1]×[1,2]` (1) or `[1,2]²` (2),
/// nodes `(a−1+i, b−1+j)` for the face's lower-left corner `(a, b)`.
pub fn ring_grid(n: usize, ext: &[P3], s: usize, piece: usize) -> [[P3; 4]; 4] {
    let (a, b) = [(1, 0), (0, 1), (1, 1)][piece];
    let mut d = [[ZERO; 4]; 4];
    for (i, row) in d.iter_mut().enumerate() {
        for (j, p) in row.iter_mut().enumerate() {
            *p = ext[ext_index(n, s, a - 1 + i as i64, b - 1 + j as i64)];
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The basis is a partition of unity, C² across spans (N_{i+1}(1) = N_i(0)
    /// with derivatives), and the derivative matches a central difference.
    #[test]
    fn bspline_basis_properties() {
        for t in [0.0, 0.3, 0.5, 1.0] {
            let s: f64 = (0..4).map(|i| bspline_basis(i, 0, t)).sum();
            assert!((s - 1.0).abs() < 1e-15);
            for i in 0..4 {
                let h = 1e-6;
                let fd = (bspline_basis(i, 0, t + h) - bspline_basis(i, 0, t - h)) / (2.0 * h);
                assert!((fd - bspline_basis(i, 1, t)).abs() < 1e-8);
            }
        }
        for r in 0..3 {
            for i in 0..3 {
                assert!((bspline_basis(i, r, 0.0) - bspline_basis(i + 1, r, 1.0)).abs() < 1e-15);
            }
        }
    }

    /// A closed cube: every vertex valence 3, the step keeps 8 + 12 + 6 points,
    /// and the vertex rule gives the known value for the unit cube's corner.
    #[test]
    fn cube_step() {
        let verts: Vec<P3> = (0..8)
            .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
            .collect();
        let faces = vec![
            vec![0, 2, 3, 1],
            vec![4, 5, 7, 6],
            vec![0, 1, 5, 4],
            vec![2, 6, 7, 3],
            vec![0, 4, 6, 2],
            vec![1, 3, 7, 5],
        ];
        let r = step(&Mesh { verts, faces });
        assert_eq!(r.mesh.verts.len(), 26);
        assert_eq!(r.mesh.faces.len(), 24);
        // Corner 0: Q = avg of 3 face centers (¼,¼,¼)·... = (1/3)(½,½,0)+... = (1/3,1/3,1/3);
        // R = (1/6,1/6,1/6); S = 0: V = Q/3 + 2R/3 = (2/9,2/9,2/9).
        let v = r.mesh.verts[r.vertex_point[0]];
        for c in v {
            assert!((c - 2.0 / 9.0).abs() < 1e-15);
        }
    }
}
