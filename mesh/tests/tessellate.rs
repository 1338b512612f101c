//! Welded tessellation of patchworks (`capdiv_mesh::tessellate`): closed,
//! consistently oriented cubes built from whole, split (one patch against two
//! halves) and holed (a fan to the cap's point) faces, mixed degrees, normals
//! against the kernel's evaluation, and welding tolerances. The properties
//! (edge counts, Euler characteristic, T-junctions, normals) are computed
//! here from the output, independently of the crate.

use capdiv::{BicubicPatch, BiquarticPatch, Point3, TensorPatch};
use capdiv_mesh::tessellate::{
    closed_in_order, edge_bit, is_closed_and_oriented, tessellate, weld, write_obj, BadEdge,
    EdgeFault, Face, PatchGeometry, Tessellation, EDGE_U0, EDGE_U1, EDGE_V0, EDGE_V1,
};
use capdiv_mesh::{PatchKind, PatchRecord};
use std::collections::BTreeSet;

type P = Point3<f64>;

fn p(x: f64, y: f64, z: f64) -> P {
    Point3::new(x, y, z)
}

/// A face of the cube `[-1, 1]³`: `point(u, v) = c + eu·(2u−1) + ev·(2v−1)`
/// with `eu × ev = c`, the outward normal.
#[derive(Clone, Copy)]
struct CubeFace {
    c: P,
    eu: P,
    ev: P,
}

impl CubeFace {
    fn point(&self, u: f64, v: f64) -> P {
        self.c + self.eu * (2.0 * u - 1.0) + self.ev * (2.0 * v - 1.0)
    }
    /// The flat bicubic patch of the sub-square `[u0,u1]×[v0,v1]`, mapped by `bulge`.
    fn patch(
        &self,
        (u0, u1): (f64, f64),
        (v0, v1): (f64, f64),
        bulge: fn(P) -> P,
    ) -> BicubicPatch<f64> {
        let mut pts = [[P::ZERO; 4]; 4];
        for (i, row) in pts.iter_mut().enumerate() {
            for (j, q) in row.iter_mut().enumerate() {
                let (s, t) = (i as f64 / 3.0, j as f64 / 3.0);
                *q = bulge(self.point(u0 + (u1 - u0) * s, v0 + (v1 - v0) * t));
            }
        }
        TensorPatch { points: pts }
    }
}

/// +x, −x, +y, −y, +z, −z.
fn cube_faces() -> [CubeFace; 6] {
    let (x, y, z) = (p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0), p(0.0, 0.0, 1.0));
    let f = |c: P, eu: P, ev: P| {
        assert_eq!(eu.cross(ev), c);
        CubeFace { c, eu, ev }
    };
    [
        f(x, y, z),
        f(-x, z, y),
        f(y, z, x),
        f(-y, x, z),
        f(z, x, y),
        f(-z, y, x),
    ]
}

fn flat(q: P) -> P {
    q
}

/// A smooth map of the cube: shared control points stay shared.
fn bulge(q: P) -> P {
    let r2 = q.dot(q);
    q * (1.0 + 0.3 * (3.0 - r2) / 3.0) + p(0.1 * q.0[1] * q.0[2], 0.0, 0.05 * q.0[0] * q.0[0])
}

/// de Casteljau split of a cubic row at 1/2: (left, right).
fn split4(c: [P; 4]) -> ([P; 4], [P; 4]) {
    let h = |a: P, b: P| (a + b) * 0.5;
    let (a1, b1, c1) = (h(c[0], c[1]), h(c[1], c[2]), h(c[2], c[3]));
    let (a2, b2) = (h(a1, b1), h(b1, c1));
    let m = h(a2, b2);
    ([c[0], a1, a2, m], [m, b2, c1, c[3]])
}

/// The four quarters of a bicubic patch, `[i][j]`: `i` the half along u.
#[allow(clippy::needless_range_loop)] // index algebra reads clearer
fn quarters(b: &BicubicPatch<f64>) -> [[BicubicPatch<f64>; 2]; 2] {
    // Split along v (rows), then along u (columns).
    let mut halves_v = [[[P::ZERO; 4]; 4]; 2];
    for i in 0..4 {
        let (l, r) = split4(b.points[i]);
        halves_v[0][i] = l;
        halves_v[1][i] = r;
    }
    let mut out = [[TensorPatch {
        points: [[P::ZERO; 4]; 4],
    }; 2]; 2];
    for (jv, hv) in halves_v.iter().enumerate() {
        for j in 0..4 {
            let (l, r) = split4([hv[0][j], hv[1][j], hv[2][j], hv[3][j]]);
            for i in 0..4 {
                out[0][jv].points[i][j] = l[i];
                out[1][jv].points[i][j] = r[i];
            }
        }
    }
    out
}

/// Degree elevation 3 → 4 in both directions: `Q_i = i/4 P_{i−1} + (1 − i/4) P_i`.
fn elevate(b: &BicubicPatch<f64>) -> BiquarticPatch<f64> {
    let up = |c: [P; 4]| -> [P; 5] {
        let mut q = [P::ZERO; 5];
        for (i, qi) in q.iter_mut().enumerate() {
            let a = i as f64 / 4.0;
            let prev = if i > 0 { c[i - 1] * a } else { P::ZERO };
            let cur = if i < 4 { c[i] * (1.0 - a) } else { P::ZERO };
            *qi = prev + cur;
        }
        q
    };
    let rows: Vec<[P; 5]> = b.points.iter().map(|r| up(*r)).collect();
    let mut pts = [[P::ZERO; 5]; 5];
    for j in 0..5 {
        let col = up([rows[0][j], rows[1][j], rows[2][j], rows[3][j]]);
        for i in 0..5 {
            pts[i][j] = col[i];
        }
    }
    TensorPatch { points: pts }
}

/// A patch record of `geometry` whose face number is the tag its faces get
/// ([`by_face`]).
fn patch(geometry: PatchGeometry<f64>, tag: u32) -> PatchRecord<f64> {
    PatchRecord {
        face: tag,
        ..PatchRecord::new(PatchKind::Regular, geometry)
    }
}

fn cubic(b: BicubicPatch<f64>, tag: u32) -> PatchRecord<f64> {
    patch(PatchGeometry::Cubic(b), tag)
}

/// The patches to tessellate, each tagged with its face number.
fn by_face(
    patches: impl IntoIterator<Item = PatchRecord<f64>>,
) -> impl Iterator<Item = (PatchRecord<f64>, u32)> {
    patches.into_iter().map(|p| {
        let tag = p.face;
        (p, tag)
    })
}

fn corner_points(g: &PatchGeometry<f64>) -> [P; 4] {
    match g {
        PatchGeometry::Cubic(b) => [
            b.points[0][0],
            b.points[3][0],
            b.points[3][3],
            b.points[0][3],
        ],
        PatchGeometry::Quartic(b) => [
            b.points[0][0],
            b.points[4][0],
            b.points[4][4],
            b.points[0][4],
        ],
    }
}

/// Sets the `finer` bit of every edge of `patch` whose two end points
/// `corners` (the patch's corners before any bulging) lie on one of the cube
/// faces `planes` (outward normals `c`: `q·c = 1`).
fn mark_finer(patch: &mut PatchRecord<f64>, corners: [P; 4], planes: &[P]) {
    for e in [EDGE_V0, EDGE_U1, EDGE_V1, EDGE_U0] {
        let (a, b) = (corners[e as usize], corners[(e as usize + 1) % 4]);
        if planes.iter().any(|c| a.dot(*c) == 1.0 && b.dot(*c) == 1.0) {
            patch.finer |= edge_bit(e);
        }
    }
}

/// The cube with faces `split` cut into 2×2 quarter patches (de Casteljau), the
/// other faces whole with `finer` edges against them.
fn split_cube(split: &[usize], bulge: fn(P) -> P) -> Vec<PatchRecord<f64>> {
    let faces = cube_faces();
    let mut out = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        let whole = face.patch((0.0, 1.0), (0.0, 1.0), bulge);
        if split.contains(&f) {
            for row in quarters(&whole) {
                for q in row {
                    out.push(cubic(q, f as u32));
                }
            }
        } else {
            let mut t = cubic(whole, f as u32);
            let corners = corner_points(&PatchGeometry::Cubic(face.patch(
                (0.0, 1.0),
                (0.0, 1.0),
                flat,
            )));
            let planes: Vec<P> = split.iter().map(|&s| faces[s].c).collect();
            mark_finer(&mut t, corners, &planes);
            out.push(t);
        }
    }
    out
}

/// Undirected edges of the faces.
fn edges(faces: &[Face]) -> BTreeSet<(u32, u32)> {
    let mut e = BTreeSet::new();
    for f in faces {
        let c = f.corners();
        for i in 0..c.len() {
            let (a, b) = (c[i], c[(i + 1) % c.len()]);
            e.insert((a.min(b), a.max(b)));
        }
    }
    e
}

/// V − E + F, after checking every vertex is used.
fn euler(t: &Tessellation<f64>) -> i64 {
    let used: BTreeSet<u32> = t.faces.iter().flat_map(|f| f.corners().to_vec()).collect();
    assert_eq!(used.len(), t.positions.len(), "unused vertices");
    t.positions.len() as i64 - edges(&t.faces).len() as i64 + t.faces.len() as i64
}

/// No vertex lies on a face edge other than at its ends.
fn assert_no_t_junction(t: &Tessellation<f64>) {
    for (a, b) in edges(&t.faces) {
        let (pa, pb) = (t.positions[a as usize], t.positions[b as usize]);
        let d = pb - pa;
        let len2 = d.dot(d);
        for (k, q) in t.positions.iter().enumerate() {
            if k as u32 == a || k as u32 == b {
                continue;
            }
            let s = (*q - pa).dot(d) / len2;
            if s <= 0.0 || s >= 1.0 {
                continue;
            }
            let off = *q - (pa + d * s);
            assert!(off.norm() > 1e-9, "vertex {k} on edge {a}-{b}");
        }
    }
}

fn assert_closed_sphere(t: &Tessellation<f64>) {
    assert_eq!(is_closed_and_oriented(&t.faces), Ok(()));
    assert_eq!(euler(t), 2);
    assert_eq!(t.degenerate_dropped, 0);
    assert_eq!(t.faces.len(), t.tags.len());
    assert_eq!(t.positions.len(), t.normals.len());
}

/// Every face's normal (Newell) points away from the origin (convex, star-shaped input).
fn assert_outward(t: &Tessellation<f64>) {
    for f in &t.faces {
        let c: Vec<P> = f
            .corners()
            .iter()
            .map(|&i| t.positions[i as usize])
            .collect();
        let mut n = P::ZERO;
        let mut centre = P::ZERO;
        for i in 0..c.len() {
            n += c[i].cross(c[(i + 1) % c.len()]);
            centre += c[i];
        }
        assert!(n.dot(centre) > 0.0, "face {f:?} points inward");
    }
}

#[test]
fn whole_cube_is_closed_oriented_sphere() {
    for grid in [1, 2, 5] {
        let faces = cube_faces();
        let patches = faces
            .iter()
            .enumerate()
            .map(|(f, face)| cubic(face.patch((0.0, 1.0), (0.0, 1.0), flat), f as u32));
        let t = tessellate(by_face(patches), grid, 1e-9);
        assert_closed_sphere(&t);
        assert_outward(&t);
        // 6 faces of grid² quads; vertices of the cube's surface lattice.
        assert_eq!(t.faces.len(), 6 * grid * grid);
        assert!(t.faces.iter().all(|f| matches!(f, Face::Quad(_))));
        assert_eq!(t.positions.len(), 6 * grid * grid + 2);
        assert_eq!(t.samples, 6 * (grid + 1) * (grid + 1));
        assert_no_t_junction(&t);
    }
}

#[test]
fn split_face_against_finer_edges_is_closed_without_t_junctions() {
    // One face split; then two opposite faces split (the ring between has
    // finer edges on opposite sides: at grid 1 one cell with two).
    for split in [&[4usize][..], &[4, 5][..], &[0, 2, 4][..]] {
        for grid in [1, 2, 5] {
            let patches = split_cube(split, flat);
            let finer: u32 = patches.iter().map(|p| p.finer.count_ones()).sum();
            assert_eq!(finer as usize, 4 * split.len() - shared(split));
            let t = tessellate(by_face(patches), grid, 1e-9);
            assert_closed_sphere(&t);
            assert_outward(&t);
            assert_no_t_junction(&t);
            // The lattice of a cube whose split faces have 2·grid segments:
            // every sample point of the surface once.
            assert_eq!(t.positions.len(), lattice_points(split, grid));
        }
    }
}

/// Ordered pairs of adjacent split faces: each split face has 4 neighbours,
/// those split themselves have no finer edge against it.
fn shared(split: &[usize]) -> usize {
    let faces = cube_faces();
    let mut n = 0;
    for &a in split {
        for &b in split {
            if a != b && faces[a].c.dot(faces[b].c) == 0.0 {
                n += 1;
            }
        }
    }
    n
}

/// Distinct points of the sample lattices, counted by brute force.
fn lattice_points(split: &[usize], grid: usize) -> usize {
    let mut set = BTreeSet::new();
    for (f, face) in cube_faces().iter().enumerate() {
        let n = if split.contains(&f) { 2 * grid } else { grid };
        for a in 0..=n {
            for b in 0..=n {
                let q = face.point(a as f64 / n as f64, b as f64 / n as f64);
                set.insert(q.0.map(|c| (c * 1e6).round() as i64));
            }
        }
    }
    set.len()
}

/// The cube with faces +x, +y, +z each an L of 3 half-size patches around the
/// corner (1,1,1); the corner's three quarters form one hole, closed by a fan
/// to the corner from the 6 ring edges around it. The other faces are whole,
/// finer against the L faces.
fn holed_cube(quartic: bool) -> Vec<PatchRecord<f64>> {
    let faces = cube_faces();
    let corner = p(1.0, 1.0, 1.0);
    let mut out = Vec::new();
    let geometry = |b: BicubicPatch<f64>, odd: bool| {
        if quartic && odd {
            PatchGeometry::Quartic(elevate(&b))
        } else {
            PatchGeometry::Cubic(b)
        }
    };
    for (f, face) in faces.iter().enumerate() {
        if face.c.dot(corner) > 0.0 {
            // Face coordinates of the corner are (1, 1): the hole is [½,1]².
            assert_eq!(face.point(1.0, 1.0), corner);
            let a = face.patch((0.0, 0.5), (0.0, 0.5), flat);
            let b = face.patch((0.5, 1.0), (0.0, 0.5), flat);
            let c = face.patch((0.0, 0.5), (0.5, 1.0), flat);
            out.push(patch(geometry(a, false), f as u32));
            let mut tb = patch(geometry(b, true), f as u32);
            tb.hole = edge_bit(EDGE_V1);
            tb.hole_point = corner;
            out.push(tb);
            let mut tc = patch(geometry(c, f % 2 == 0), f as u32);
            tc.hole = edge_bit(EDGE_U1);
            tc.hole_point = corner;
            out.push(tc);
        } else {
            let whole = face.patch((0.0, 1.0), (0.0, 1.0), flat);
            let corners = corner_points(&PatchGeometry::Cubic(whole));
            let mut t = patch(geometry(whole, f % 2 == 1), f as u32);
            let planes: Vec<P> = faces
                .iter()
                .map(|g| g.c)
                .filter(|c| c.dot(corner) > 0.0)
                .collect();
            mark_finer(&mut t, corners, &planes);
            assert_eq!(t.finer.count_ones(), 2);
            out.push(t);
        }
    }
    out
}

#[test]
fn cap_hole_fan_closes_the_surface() {
    for grid in [1, 2, 5] {
        let t = tessellate(by_face(holed_cube(false)), grid, 1e-9);
        assert_closed_sphere(&t);
        assert_outward(&t);
        assert_no_t_junction(&t);
        // 6 hole edges of grid segments each: 6·grid fan triangles at the corner.
        let corner = t
            .positions
            .iter()
            .position(|q| *q == p(1.0, 1.0, 1.0))
            .unwrap() as u32;
        let fan = t
            .faces
            .iter()
            .filter(|f| f.corners().contains(&corner))
            .count();
        assert_eq!(fan, 6 * grid);
        assert!(t
            .faces
            .iter()
            .filter(|f| f.corners().contains(&corner))
            .all(|f| matches!(f, Face::Tri(_))));
        // Its normal (no patch samples it): the fan's, symmetric about (1,1,1).
        let n = t.normals[corner as usize];
        let d = (1.0f64 / 3.0).sqrt();
        assert!(n.max_abs_diff(p(d, d, d)) < 1e-12, "{n:?}");
    }
}

#[test]
fn biquartic_and_bicubic_patches_mix() {
    // Degree elevation keeps the surface.
    let b = cube_faces()[4].patch((0.0, 1.0), (0.0, 1.0), bulge);
    let e = elevate(&b);
    for (u, v) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.25), (0.5, 1.0)] {
        let (x, y) = (b.evaluate(u, v).unwrap(), e.evaluate(u, v).unwrap());
        assert!(x.position.max_abs_diff(y.position) < 1e-14);
        assert!(x.du.max_abs_diff(y.du) < 1e-13 && x.dv.max_abs_diff(y.dv) < 1e-13);
    }
    // The holed cube, half its patches bi-quartic.
    for grid in [1, 2, 5] {
        let cubic_only = tessellate(by_face(holed_cube(false)), grid, 1e-9);
        let mixed = tessellate(by_face(holed_cube(true)), grid, 1e-9);
        assert_closed_sphere(&mixed);
        assert_outward(&mixed);
        assert_eq!(mixed.positions.len(), cubic_only.positions.len());
        assert_eq!(mixed.faces, cubic_only.faces);
    }
    // A curved (bulged) cube, one face split by de Casteljau, every other
    // patch elevated: shared edges agree only to round-off.
    for grid in [1, 2, 5] {
        let patches: Vec<_> = split_cube(&[4], bulge)
            .into_iter()
            .enumerate()
            .map(|(k, mut t)| {
                if k % 2 == 1 {
                    if let PatchGeometry::Cubic(b) = t.geometry {
                        t.geometry = PatchGeometry::Quartic(elevate(&b));
                    }
                }
                t
            })
            .collect();
        assert!(patches
            .iter()
            .any(|t| matches!(t.geometry, PatchGeometry::Quartic(_))));
        let t = tessellate(by_face(patches), grid, 1e-9);
        assert_closed_sphere(&t);
        assert_outward(&t);
        assert_eq!(t.positions.len(), lattice_points(&[4], grid));
    }
}

#[test]
fn normals_are_the_patch_normals() {
    // One curved patch alone, welding only equal points: every grid sample
    // is a vertex whose normal is the kernel's ∂u × ∂v, normalised.
    let b = cube_faces()[2].patch((0.0, 1.0), (0.0, 1.0), bulge);
    for (geometry, name) in [
        (PatchGeometry::Cubic(b), "cubic"),
        (PatchGeometry::Quartic(elevate(&b)), "quartic"),
    ] {
        let grid = 4;
        let t = tessellate(by_face([patch(geometry, 0)]), grid, 0.0);
        assert_eq!(t.positions.len(), 25, "{name}");
        for a in 0..=grid {
            for c in 0..=grid {
                let (u, v) = (a as f64 / grid as f64, c as f64 / grid as f64);
                let pp = b.evaluate(u, v).unwrap();
                let n = pp.du.cross(pp.dv);
                let n = n * (1.0 / n.norm());
                let k = t
                    .positions
                    .iter()
                    .position(|q| q.max_abs_diff(pp.position) < 1e-14)
                    .unwrap_or_else(|| panic!("{name}: no vertex at ({u}, {v})"));
                let got = t.normals[k];
                assert!((got.norm() - 1.0).abs() < 1e-14);
                assert!(
                    got.max_abs_diff(n) < 1e-13,
                    "{name} ({u}, {v}): {got:?} vs {n:?}"
                );
            }
        }
    }
    // The cube: unit, outward; inside a face, the face's normal.
    let t = tessellate(by_face(split_cube(&[4], flat)), 3, 1e-9);
    for (q, n) in t.positions.iter().zip(&t.normals) {
        assert!((n.norm() - 1.0).abs() < 1e-14);
        assert!(n.dot(*q) > 0.0);
        let on_face: Vec<usize> = (0..3).filter(|&k| q.0[k].abs() == 1.0).collect();
        if on_face.len() == 1 {
            let k = on_face[0];
            let mut axis = P::ZERO;
            axis.0[k] = q.0[k];
            assert!(n.max_abs_diff(axis) < 1e-15, "{q:?}: {n:?}");
        }
    }
    // A degenerate patch (all points equal): zero normals, and its faces
    // collapse to one vertex and are dropped.
    let d = TensorPatch {
        points: [[p(1.0, 2.0, 3.0); 4]; 4],
    };
    let t = tessellate(by_face([cubic(d, 7)]), 2, 1e-9);
    assert_eq!(t.positions.len(), 1);
    assert_eq!(t.normals[0], P::ZERO);
    assert!(t.faces.is_empty());
    assert_eq!(t.degenerate_dropped, 4);
}

/// Two unit squares side by side in z = 0; the second's shared edge moved by `eps` in x.
fn two_squares(eps: f64) -> [PatchRecord<f64>; 2] {
    let sq = |x0: f64, shift_left: f64| {
        let mut pts = [[P::ZERO; 4]; 4];
        for (i, row) in pts.iter_mut().enumerate() {
            for (j, q) in row.iter_mut().enumerate() {
                let x = x0 + i as f64 / 3.0 + if i == 0 { shift_left } else { 0.0 };
                *q = p(x, j as f64 / 3.0, 0.0);
            }
        }
        TensorPatch { points: pts }
    };
    [cubic(sq(0.0, 0.0), 0), cubic(sq(1.0, eps), 1)]
}

#[test]
fn weld_tolerance_decides_merging() {
    let grid = 3;
    let welded = tessellate(by_face(two_squares(1e-12)), grid, 1e-9);
    assert_eq!(welded.positions.len(), (2 * grid + 1) * (grid + 1));
    let apart = tessellate(by_face(two_squares(1e-12)), grid, 1e-14);
    assert_eq!(apart.positions.len(), 2 * (grid + 1) * (grid + 1));
    assert_eq!(welded.faces.len(), apart.faces.len());
    // The welded pair is an open sheet: its boundary shows.
    let bad = is_closed_and_oriented(&welded.faces).unwrap_err();
    assert_eq!(bad.fault, EdgeFault::Unpaired);
    // Interior edges of the welded sheet all pair up: boundary edges = 2·(3·grid).
    let open: usize = {
        let mut count = std::collections::BTreeMap::new();
        for f in &welded.faces {
            let c = f.corners();
            for i in 0..c.len() {
                let (a, b) = (c[i], c[(i + 1) % c.len()]);
                *count.entry((a.min(b), a.max(b))).or_insert(0) += 1;
            }
        }
        count.values().filter(|&&n| n == 1).count()
    };
    assert_eq!(open, 6 * grid);
}

/// Brute force: classes of the "close" relation (all pairs, union-find by
/// relabelling); each point mapped to the smallest index of its class.
fn brute_weld(pts: &[P], tol: f64) -> Vec<u32> {
    let mut class: Vec<usize> = (0..pts.len()).collect();
    for a in 0..pts.len() {
        for b in 0..a {
            if pts[a].max_abs_diff(pts[b]) <= tol && class[a] != class[b] {
                let (keep, drop) = (class[a].min(class[b]), class[a].max(class[b]));
                for c in class.iter_mut() {
                    if *c == drop {
                        *c = keep;
                    }
                }
            }
        }
    }
    class.into_iter().map(|c| c as u32).collect()
}

#[test]
fn hash_grid_weld_matches_brute_force() {
    // Points on a lattice of spacing 3·tol spanning more than a cell (32·tol)
    // each way, jittered by up to 1.2·tol, some repeated exactly, some with a
    // neighbour up to 0.6·tol away per axis: many close pairs straddle cell
    // faces, some chains, many near-misses just beyond tol.
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for tol in [1e-3, 0.37, 1e-9] {
        let mut pts: Vec<P> = Vec::new();
        for _ in 0..2000 {
            let base = [(); 3].map(|_| ((rnd() * 24.0).floor() - 12.0) * 3.0 * tol);
            let jit = [(); 3].map(|_| (rnd() - 0.5) * 2.4 * tol);
            let q = p(base[0] + jit[0], base[1] + jit[1], base[2] + jit[2]);
            pts.push(q);
            if rnd() < 0.3 {
                pts.push(q);
            }
            if rnd() < 0.3 {
                let d = [(); 3].map(|_| (rnd() - 0.5) * 1.2 * tol);
                pts.push(q + p(d[0], d[1], d[2]));
            }
        }
        let fast = weld::representatives(&pts, tol).unwrap();
        assert_eq!(fast, brute_weld(&pts, tol), "tol {tol}");
        assert!(fast.iter().enumerate().any(|(k, &r)| r as usize != k));
    }
    // Tolerance 0: equal coordinates only, −0 equal to +0, NaN never.
    let pts = [
        p(0.0, 1.0, 2.0),
        p(-0.0, 1.0, 2.0),
        p(f64::NAN, 0.0, 0.0),
        p(f64::NAN, 0.0, 0.0),
        p(0.0, 1.0, 2.0 + 1e-16),
    ];
    assert_eq!(
        weld::representatives(&pts, 0.0).unwrap(),
        vec![0, 0, 2, 3, 0]
    );
    assert_eq!(
        weld::representatives(&pts, -1.0).unwrap(),
        vec![0, 0, 2, 3, 0]
    );
    assert_eq!(
        weld::representatives(&pts[..2], f64::NAN).unwrap(),
        vec![0, 0]
    );
    // Infinite tolerance: everything finite is one vertex.
    assert_eq!(
        weld::representatives(&[pts[0], pts[4], p(1e300, 0.0, 0.0)], f64::INFINITY).unwrap(),
        vec![0, 0, 0]
    );
}

/// A tetrahedron's faces, counter-clockwise seen from outside.
fn tetrahedron() -> [Face; 4] {
    [
        Face::Tri([0, 2, 1]),
        Face::Tri([0, 1, 3]),
        Face::Tri([1, 2, 3]),
        Face::Tri([2, 0, 3]),
    ]
}

#[test]
fn closedness_check_reports_the_first_bad_edge() {
    let tet = tetrahedron();
    assert_eq!(is_closed_and_oriented(&tet), Ok(()));
    let mut flipped = tet;
    flipped[2] = Face::Tri([1, 3, 2]);
    assert_eq!(
        is_closed_and_oriented(&flipped),
        // Face 0 runs 2 → 1, and so does the flipped face 2.
        Err(BadEdge {
            from: 2,
            to: 1,
            face: 0,
            fault: EdgeFault::SameDirection
        })
    );
    assert_eq!(
        is_closed_and_oriented(&tet[1..]),
        Err(BadEdge {
            from: 0,
            to: 1,
            face: 0,
            fault: EdgeFault::Unpaired
        })
    );
    let mut doubled = tet.to_vec();
    doubled.push(Face::Tri([0, 1, 3]));
    assert_eq!(
        is_closed_and_oriented(&doubled).unwrap_err().fault,
        EdgeFault::Overused
    );
    assert_eq!(
        is_closed_and_oriented(&[Face::Quad([1, 1, 0, 2])])
            .unwrap_err()
            .fault,
        EdgeFault::Degenerate
    );
}

#[test]
fn in_order_check_pairs_edges_as_they_come() {
    let tet = tetrahedron();
    assert_eq!(closed_in_order(&tet), Ok(()));
    let mut flipped = tet;
    flipped[2] = Face::Tri([1, 3, 2]);
    // Edge uses in order: 0→2, 2→1, 1→0 (face 0); 0→1, 1→3, 3→0 (face 1);
    // 1→3, 3→2, 2→1 (face 2); 2→0, 0→3, 3→2 (face 3). Faults: 1→3 against
    // use 4, 2→1 against use 1, 3→2 against use 7; the earliest is use 1.
    assert_eq!(
        closed_in_order(&flipped),
        Err(BadEdge {
            from: 2,
            to: 1,
            face: 0,
            fault: EdgeFault::SameDirection
        })
    );
    // Face 0 missing: 0→1, 1→2 and 2→0 stay open; 0→1 (use 0, face 0 of
    // the rest) is the first.
    assert_eq!(
        closed_in_order(&tet[1..]),
        Err(BadEdge {
            from: 0,
            to: 1,
            face: 0,
            fault: EdgeFault::Unpaired
        })
    );
    // Twice the tetrahedron: every edge used four times, twice each way,
    // pairs up in order, where the sorting check sees the overuse.
    let twice: Vec<Face> = tet.iter().chain(tet.iter()).copied().collect();
    assert_eq!(closed_in_order(&twice), Ok(()));
    assert_eq!(
        is_closed_and_oriented(&twice).unwrap_err().fault,
        EdgeFault::Overused
    );
}

#[test]
fn obj_text_lists_vertices_normals_and_faces() {
    let t = tessellate(by_face(holed_cube(false)), 1, 1e-9);
    let text = write_obj(&t, &["holed cube".to_string()]);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "# holed cube");
    assert_eq!(
        lines.iter().filter(|l| l.starts_with("v ")).count(),
        t.positions.len()
    );
    assert_eq!(
        lines.iter().filter(|l| l.starts_with("vn ")).count(),
        t.positions.len()
    );
    let f: Vec<&&str> = lines.iter().filter(|l| l.starts_with("f ")).collect();
    assert_eq!(f.len(), t.faces.len());
    let corners = |l: &str| -> Vec<u32> {
        l.split_whitespace()
            .skip(1)
            .map(|c| {
                let (a, b) = c.split_once("//").unwrap();
                assert_eq!(a, b);
                a.parse::<u32>().unwrap() - 1
            })
            .collect()
    };
    for (l, face) in f.iter().zip(&t.faces) {
        assert_eq!(corners(l), face.corners());
    }
    // f32 works the same way.
    let t32 = tessellate(
        holed_cube(false).into_iter().map(|t| {
            let geometry = match t.geometry {
                PatchGeometry::Cubic(b) => PatchGeometry::Cubic(TensorPatch {
                    points: b.points.map(|r| r.map(|q| q.cast())),
                }),
                PatchGeometry::Quartic(b) => PatchGeometry::Quartic(TensorPatch {
                    points: b.points.map(|r| r.map(|q| q.cast())),
                }),
            };
            let record = PatchRecord {
                finer: t.finer,
                hole: t.hole,
                hole_point: t.hole_point.cast(),
                ..PatchRecord::new(t.kind, geometry)
            };
            (record, t.face)
        }),
        1,
        1e-5f32,
    );
    assert_eq!(t32.faces, t.faces);
    let text32 = write_obj(&t32, &[]);
    let v32: Vec<f32> = text32
        .lines()
        .filter(|l| l.starts_with("v "))
        .flat_map(|l| {
            l.split_whitespace()
                .skip(1)
                .map(|c| c.parse::<f32>().unwrap())
        })
        .collect();
    assert_eq!(v32.len(), 3 * t.positions.len());
    assert!(v32.iter().all(|c| c.abs() <= 1.0));
}

/// A cube of `6·m²` flat patches at `grid` 4; `cargo test --release -p
/// capdiv-mesh --test tessellate -- --ignored --nocapture`.
#[test]
#[ignore]
fn timing_large_patchwork() {
    let m = 129;
    let grid = 4;
    let mut patches = Vec::new();
    for (f, face) in cube_faces().iter().enumerate() {
        for a in 0..m {
            for b in 0..m {
                let (u0, v0) = (a as f64 / m as f64, b as f64 / m as f64);
                let (u1, v1) = ((a + 1) as f64 / m as f64, (b + 1) as f64 / m as f64);
                patches.push(cubic(face.patch((u0, u1), (v0, v1), bulge), f as u32));
            }
        }
    }
    let count = patches.len();
    let start = std::time::Instant::now();
    let t = tessellate(by_face(patches), grid, 1e-9);
    let secs = start.elapsed().as_secs_f64();
    println!(
        "{count} patches, grid {grid}: {} samples -> {} vertices, {} faces in {secs:.3} s ({:.2e} samples/s, {:.2e} vertices/s)",
        t.samples,
        t.positions.len(),
        t.faces.len(),
        t.samples as f64 / secs,
        t.positions.len() as f64 / secs
    );
    let start = std::time::Instant::now();
    assert_eq!(is_closed_and_oriented(&t.faces), Ok(()));
    println!("closedness check: {:.3} s", start.elapsed().as_secs_f64());
    let mut pts = t.positions.clone();
    pts.extend_from_slice(&t.positions);
    let start = std::time::Instant::now();
    let _ = weld::representatives(&pts, 1e-9).unwrap();
    println!(
        "weld of {} points: {:.3} s",
        pts.len(),
        start.elapsed().as_secs_f64()
    );
    assert_eq!(t.positions.len(), 6 * (m * grid) * (m * grid) + 2);
}

/// A real C²PS cap from the kernel: rings of levels 0..5 (each ring's inner
/// edge against two patches of the next, valence doubling), the last ring's
/// inner edge fanned to the pole's limit point. The result is a disk: every
/// edge paired in opposite directions except the outer boundary, one loop.
#[test]
fn c2ps_cap_rings_weld_into_a_disk() {
    use capdiv::{FirstStep, PolarNet, PoleJet};
    let n = 6;
    // An uneven surface around the pole.
    let links: Vec<Vec<[f64; 3]>> = (1..=5)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / n as f64;
                    let r = i as f64 * (1.0 + 0.1 * (j % 3) as f64);
                    let (x, y) = (r * t.cos(), r * t.sin());
                    [x, y, 0.25 * x * x - 0.1 * y * y + 0.05 * x * y * y]
                })
                .collect()
        })
        .collect();
    let mut net: PolarNet<f64, 512> = PolarNet::new([0.0, 0.0, 0.1], &links).unwrap();
    let levels = 5;
    let mut patches = Vec::new();
    for level in 0..levels {
        let last = level + 1 == levels;
        let valence = net.valence();
        let limit = PoleJet::of(&net).limit();
        for (k, b) in net.ring_patches().enumerate() {
            let mut t = patch(PatchGeometry::Cubic(b), level as u32);
            if k < valence {
                // Span 0: its inner edge u = 0 faces the next ring, or the hole.
                if last {
                    t.hole = edge_bit(EDGE_U0);
                    t.hole_point = limit;
                } else {
                    t.finer = edge_bit(EDGE_U0);
                }
            }
            patches.push(t);
        }
        net.step(FirstStep::Uniform).unwrap();
    }
    for grid in [1, 3] {
        let t = tessellate(by_face(patches.iter().cloned()), grid, 1e-9);
        assert_disk(&t, n * grid);
    }
}

/// A real EG cap from the kernel: per step and sector 3 bi-4 patches over the
/// L between the old hole `[0,1]²` and the new `[0,½]²` (docs/math/eg.md §9): patch
/// `3s` over `[½,1]×[0,½]` has its edge `u = 0`, patch `3s+1` over
/// `[0,½]×[½,1]` its edge `v = 0` on the new hole — against two patches of
/// the next ring, or, after the last step, fanned to the limit point `c0`.
#[test]
fn eg_cap_rings_weld_into_a_disk() {
    use capdiv::eg::{CNet, EgSubdivision};
    for n in [3usize, 5] {
        // §1 order per sector: (x, y) = (1,0), (2,0), (1,1), (2,1), (1,2), (2,2),
        // sector s's quarter-plane squeezed into the angle 2π/n, a bumpy paraboloid.
        let mut nodes = Vec::new();
        for s in 0..n {
            for (x, y) in [
                (1.0f64, 0.0f64),
                (2.0, 0.0),
                (1.0, 1.0),
                (2.0, 1.0),
                (1.0, 2.0),
                (2.0, 2.0),
            ] {
                let a = std::f64::consts::TAU / n as f64;
                let t = s as f64 * a + a * y.atan2(x) / std::f64::consts::FRAC_PI_2;
                let r = (x * x + y * y).sqrt();
                let bump = 0.05 * ((s * 7 + (x as usize) * 3 + y as usize) % 5) as f64;
                nodes.push([r * t.cos(), r * t.sin(), 0.1 * r * r + bump]);
            }
        }
        let c = CNet::new([0.0, 0.0, 0.02], &nodes).unwrap();
        let limit = c.limit();
        let mut sub = EgSubdivision::new(&c, None).unwrap();
        let steps = 4;
        let mut patches = Vec::new();
        for m in 0..steps {
            sub.step().unwrap();
            let last = m + 1 == steps;
            for (k, b) in sub.ring_patches().enumerate() {
                let mut t = patch(PatchGeometry::Quartic(b), m as u32);
                let inner = match k % 3 {
                    0 => edge_bit(EDGE_U0),
                    1 => edge_bit(EDGE_V0),
                    _ => 0,
                };
                if last {
                    t.hole = inner;
                    t.hole_point = limit;
                } else {
                    t.finer = inner;
                }
                patches.push(t);
            }
        }
        for grid in [1, 4] {
            let t = tessellate(by_face(patches.iter().cloned()), grid, 1e-9);
            // Outer boundary: per sector x = 1 and y = 1, two patch edges each.
            assert_disk(&t, 4 * n * grid);
        }
    }
}

/// A disk: every edge used once in each direction except `boundary_edges`
/// boundary edges forming one loop; Euler characteristic 1.
fn assert_disk(t: &Tessellation<f64>, boundary_edges: usize) {
    assert_eq!(t.degenerate_dropped, 0);
    let mut uses = std::collections::BTreeMap::new();
    for f in &t.faces {
        let c = f.corners();
        for i in 0..c.len() {
            *uses.entry((c[i], c[(i + 1) % c.len()])).or_insert(0) += 1;
        }
    }
    let mut boundary = Vec::new();
    for (&(a, b), &k) in &uses {
        assert_eq!(k, 1, "edge {a}->{b} used {k} times in one direction");
        if !uses.contains_key(&(b, a)) {
            boundary.push((a, b));
        }
    }
    assert_eq!(boundary.len(), boundary_edges);
    // One loop.
    let next: std::collections::BTreeMap<u32, u32> = boundary.iter().copied().collect();
    let (mut v, mut steps) = (boundary[0].0, 0);
    loop {
        v = next[&v];
        steps += 1;
        if v == boundary[0].0 {
            break;
        }
    }
    assert_eq!(steps, boundary.len());
    assert_eq!(euler_open(t), 1);
}

/// V − E + F of a mesh that may have a boundary.
fn euler_open(t: &Tessellation<f64>) -> i64 {
    t.positions.len() as i64 - edges(&t.faces).len() as i64 + t.faces.len() as i64
}
