//! The combined refinement step: one global Catmull-Clark (CC) step, except at
//! polar vertices, where the C²PS step (docs/math/c2ps.md §2, first-step variant
//! "Uniform") gives the new pole, new link 1 and new link 2. New links ≥ 3 of
//! C²PS are plain CC (docs/math/c2ps.md §2: uniform bi-3 refinement), so they come out of
//! the CC rules unchanged.
//!
//! The step of a mesh with tags ([`crate::tagged_step`]) is this step with
//! OpenSubdiv's rows in place of the Catmull-Clark rules below
//! (`try_step_with_rows`): the numbering, the C²PS rows and the faces are
//! this module's.
//!
//! Topology is computed once; every refined vertex is a fixed linear
//! combination of old vertices (a [`StencilTable`] row), so positions are
//! re-evaluated cheaply when the input vertices move.
//!
//! Numbering of the refined vertices: vertex point of old vertex `v` is `v`
//! (`0..V`), face point of old face `f` is `V + f`, edge point of undirected
//! old edge `e` is `V + F + e`, edges numbered in the order they are first met
//! walking the half-edges `0, 1, 2, …`.
//!
//! Faces: old face `f` with `k` corners gives `k` sub-quads, grouped per old
//! face in old-face order, corners in order; the sub-quad at corner `c` is
//! (vertex point of `c`, edge point of `c→c+1`, face point, edge point of
//! `c−1→c`). At a seed's pole corner, that sub-quad is replaced by two
//! triangles (new pole, edge point of pole→link1\[j\], face point) and (new
//! pole, face point, edge point of pole→link1\[j+1\]).
//!
//! CC rules (positions over old vertices):
//! - face point: centroid;
//! - interior edge point `(v + w + fp₁ + fp₂)/4`, boundary edge point `(v + w)/2`;
//! - interior vertex point of valence `n`:
//!   `(n−2)/n · v + 1/n² Σ neighbours + 1/n² Σ face points`;
//!   boundary vertex with two or more faces `(6v + a + b)/8` (`a`, `b` its
//!   boundary neighbours); boundary vertex with one face (a corner) `v`;
//!   a vertex no face uses: `v`.

use crate::chart::FaceChart;
use crate::mem::{self, OutOfMemory};
use crate::stencil::StencilTable;
use crate::topology::{Topology, NONE};
use alloc::vec;
use alloc::vec::Vec;

/// A polar vertex that the step refines by C²PS: pole, its 1-link and 2-link,
/// counter-clockwise. `triangles[j]` is the face (pole, link1\[j\],
/// link1\[j+1\]); `quads[j]` is the quad (link1\[j+1\], link1\[j\], link2\[j\],
/// link2\[j+1\]) (given as face indices; vertex order within the face may
/// start anywhere but is counter-clockwise).
#[derive(Clone, Debug, PartialEq)]
pub struct PolarSeed {
    /// The pole `q00`.
    pub pole: u32,
    /// The 1-link, counter-clockwise (`n ≥ 3` vertices).
    pub link1: Vec<u32>,
    /// The 2-link; `link2[j]` lies across `quads[j]` from `link1[j]`.
    pub link2: Vec<u32>,
    /// `triangles[j]`: the face (pole, link1\[j\], link1\[j+1\]).
    pub triangles: Vec<u32>,
    /// `quads[j]`: the face (link1\[j+1\], link1\[j\], link2\[j\], link2\[j+1\]).
    pub quads: Vec<u32>,
}

/// The result of one refinement step.
#[derive(Clone, Debug)]
pub struct Refined {
    /// Number of refined vertices (`V + F + E` of the old mesh).
    pub num_vertices: usize,
    /// Faces of the refined mesh, counter-clockwise (same orientation as the input).
    pub faces: Vec<Vec<u32>>,
    /// Refined vertex i = Σ w · old vertex (rows in refined vertex order).
    pub stencils: StencilTable,
    /// Per refined face: where it lies in the INPUT mesh (old charts composed).
    pub charts: Vec<FaceChart>,
    /// Per refined face: the old face it came from.
    pub parent: Vec<u32>,
    /// Refined vertex index of each seed's new pole (same order as `poles`).
    pub poles: Vec<u32>,
}

/// A stencil row under construction: `(old vertex, weight)`, one entry per
/// vertex.
pub(crate) type Row = Vec<(u32, f64)>;

/// Adds `w · old vertex i` to `row`.
fn add(row: &mut Row, i: u32, w: f64) {
    if let Some(e) = row.iter_mut().find(|e| e.0 == i) {
        e.1 += w;
    } else {
        row.push((i, w));
    }
}

/// Adds `w · row` to `acc`.
fn add_row(acc: &mut Row, row: &[(u32, f64)], w: f64) {
    for &(i, x) in row {
        add(acc, i, w * x);
    }
}

/// `cos(2π t)`.
fn c(t: f64) -> f64 {
    libm::cos(2.0 * core::f64::consts::PI * t)
}

/// One refinement step of `topo`: Catmull-Clark everywhere, C²PS (first-step
/// variant "Uniform") for the pole, link 1 and link 2 of every seed in
/// `poles`. `charts[f]` is where old face `f` lies in the input mesh.
///
/// Seeds are applied in order; a vertex shared by two seeds' rings takes the
/// later seed's rule (the analysis never produces such seeds).
///
/// # Panics
/// If `charts` does not have one entry per face, or a seed does not describe
/// its faces as documented on [`PolarSeed`] (a caller's logic error).
pub fn global_step(topo: &Topology, charts: &[FaceChart], poles: &[PolarSeed]) -> Refined {
    match try_global_step(topo, charts, poles) {
        Ok(r) => r,
        Err(e) => panic!("global_step: {e}"),
    }
}

/// [`global_step`], with [`OutOfMemory`] when a buffer whose size depends on the
/// mesh (edges, stencil rows, faces) cannot be allocated.
///
/// # Panics
/// As [`global_step`], on a caller's logic error.
pub fn try_global_step(
    topo: &Topology,
    charts: &[FaceChart],
    poles: &[PolarSeed],
) -> Result<Refined, OutOfMemory> {
    let numbering = StepNumbering::new(topo)?;
    let rows = catmull_clark_rows(topo, &numbering)?;
    try_step_with_rows(topo, charts, poles, &numbering, rows)
}

/// The numbering of a step's refined vertices (the module doc's): vertex
/// points first, then face points, then edge points, edges numbered as
/// first met along the half-edges.
pub(crate) struct StepNumbering {
    /// Per half-edge: its undirected edge.
    edge: Vec<u32>,
    /// Per edge: the half-edge that first met it.
    edge_he: Vec<u32>,
    /// Vertices and faces of the old mesh.
    nv: usize,
    nf: usize,
}

impl StepNumbering {
    /// The numbering of one step of `topo`.
    pub(crate) fn new(topo: &Topology) -> Result<Self, OutOfMemory> {
        let nh = topo.num_half_edges();
        let mut edge = mem::filled(nh, NONE)?;
        // At most one edge per half-edge.
        let mut edge_he: Vec<u32> = mem::with_capacity(nh)?;
        for h in 0..nh {
            if edge[h] == NONE {
                let e = edge_he.len() as u32;
                edge[h] = e;
                let t = topo.twin(h as u32);
                if t != NONE {
                    edge[t as usize] = e;
                }
                edge_he.push(h as u32);
            }
        }
        Ok(StepNumbering {
            edge,
            edge_he,
            nv: topo.num_vertices(),
            nf: topo.num_faces(),
        })
    }

    /// Refined vertices: `V + F + E`.
    pub(crate) fn len(&self) -> usize {
        self.nv + self.nf + self.edge_he.len()
    }

    /// The face point of old face `f`.
    pub(crate) fn face_point(&self, f: usize) -> u32 {
        (self.nv + f) as u32
    }

    /// The edge point of the edge of half-edge `h`.
    pub(crate) fn edge_point(&self, h: u32) -> u32 {
        (self.nv + self.nf) as u32 + self.edge[h as usize]
    }
}

/// The Catmull-Clark rows of every refined vertex (the module doc's rules),
/// in the refined numbering.
fn catmull_clark_rows(topo: &Topology, numbering: &StepNumbering) -> Result<Vec<Row>, OutOfMemory> {
    let nv = topo.num_vertices();
    let nf = topo.num_faces();
    // Face points.
    let face_rows: Vec<Row> = mem::collect((0..nf).map(|f| {
        let vs = topo.face(f);
        let w = 1.0 / vs.len() as f64;
        vs.iter().map(|&v| (v, w)).collect()
    }))?;

    let mut rows: Vec<Row> = mem::with_capacity(numbering.len())?;
    // Vertex points.
    for v in 0..nv {
        let mut row = Row::new();
        let first = topo.vertex_first(v);
        if first == NONE || (topo.is_boundary(v) && topo.vertex_face_count(v) == 1) {
            row.push((v as u32, 1.0));
        } else if topo.is_boundary(v) {
            // `first` runs along the boundary to `a`; the last outgoing
            // half-edge's face comes in along the boundary from `b`.
            let a = topo.dest(first);
            let last = topo.outgoing(v).last().unwrap_or(first);
            let b = topo.origin(topo.prev(last));
            row.push((v as u32, 0.75));
            add(&mut row, a, 0.125);
            add(&mut row, b, 0.125);
        } else {
            let n = topo.valence(v) as f64;
            let nn = 1.0 / (n * n);
            row.push((v as u32, (n - 2.0) / n));
            for h in topo.outgoing(v) {
                add(&mut row, topo.dest(h), nn);
                add_row(&mut row, &face_rows[topo.face_of(h) as usize], nn);
            }
        }
        rows.push(row);
    }
    rows.extend(face_rows.iter().cloned());
    // Edge points.
    for &h in &numbering.edge_he {
        let mut row = Row::new();
        let t = topo.twin(h);
        let (v, w) = (topo.origin(h), topo.dest(h));
        if t == NONE {
            row.push((v, 0.5));
            add(&mut row, w, 0.5);
        } else {
            row.push((v, 0.25));
            add(&mut row, w, 0.25);
            add_row(&mut row, &face_rows[topo.face_of(h) as usize], 0.25);
            add_row(&mut row, &face_rows[topo.face_of(t) as usize], 0.25);
        }
        rows.push(row);
    }
    Ok(rows)
}

/// One refinement step of `topo` whose refined vertices outside the seeds'
/// C²PS points are `rows` (one per refined vertex, in `numbering`): the
/// seeds' pole, link 1 and link 2 rows replaced by C²PS's, the faces (two
/// triangles at each seed's pole corners), their charts and parents.
///
/// # Panics
/// As [`global_step`], on a caller's logic error.
pub(crate) fn try_step_with_rows(
    topo: &Topology,
    charts: &[FaceChart],
    poles: &[PolarSeed],
    numbering: &StepNumbering,
    mut rows: Vec<Row>,
) -> Result<Refined, OutOfMemory> {
    let nf = topo.num_faces();
    let nh = topo.num_half_edges();
    assert_eq!(charts.len(), nf, "global_step: one chart per face");
    assert_eq!(
        rows.len(),
        numbering.len(),
        "global_step: one row per vertex"
    );
    // Per face: the corner holding a seed's pole (or NONE).
    let mut pole_corner = mem::filled(nf, NONE)?;
    let mut new_poles = mem::with_capacity(poles.len())?;
    for seed in poles {
        polar_rows(topo, numbering, seed, &mut rows, &mut pole_corner);
        new_poles.push(seed.pole);
    }

    let mut stencils = StencilTable::new();
    stencils.try_reserve(rows.len(), rows.iter().map(|r| r.len()).sum())?;
    for row in rows {
        stencils.push_row(row);
    }

    // Faces, charts, parents.
    let out_faces = nh + poles.len() * 3;
    let mut faces = mem::with_capacity(out_faces)?;
    let mut out_charts = mem::with_capacity(out_faces)?;
    let mut parent = mem::with_capacity(out_faces)?;
    for f in 0..nf {
        let k = topo.face_len(f);
        let fp = numbering.face_point(f);
        let chart = charts[f];
        for corner in 0..k {
            let h = topo.face_half_edge(f, corner);
            let vp = topo.origin(h);
            let e_next = numbering.edge_point(h);
            let e_prev = numbering.edge_point(topo.prev(h));
            if pole_corner[f] == corner as u32 {
                faces.push(vec![vp, e_next, fp]);
                faces.push(vec![vp, fp, e_prev]);
                for _ in 0..2 {
                    out_charts.push(FaceChart::input(chart.face));
                    parent.push(f as u32);
                }
                continue;
            }
            faces.push(vec![vp, e_next, fp, e_prev]);
            out_charts.push(chart.child(corner, k));
            parent.push(f as u32);
        }
    }

    Ok(Refined {
        num_vertices: numbering.len(),
        faces,
        stencils,
        charts: out_charts,
        parent,
        poles: new_poles,
    })
}

/// C²PS at one seed (docs/math/c2ps.md §2, first-step variant "Uniform"):
/// the rows of its new pole, new link 1 and new link 2 in `rows`, and the
/// corner of each of its triangles that holds the pole in `pole_corner`.
///
/// # Panics
/// If the seed does not describe its faces as documented on [`PolarSeed`].
fn polar_rows(
    topo: &Topology,
    numbering: &StepNumbering,
    seed: &PolarSeed,
    rows: &mut [Row],
    pole_corner: &mut [u32],
) {
    let n = seed.link1.len();
    assert!(
        n >= 3 && seed.link2.len() == n && seed.triangles.len() == n && seed.quads.len() == n,
        "global_step: PolarSeed of pole {} has inconsistent lengths",
        seed.pole
    );
    // h[j]: the half-edge pole → link1[j] in triangles[j].
    let spokes: Vec<u32> = (0..n)
        .map(|j| {
            let f = seed.triangles[j] as usize;
            let vs = topo.face(f);
            let k = vs.iter().position(|&x| x == seed.pole);
            let ok = vs.len() == 3
                && k.is_some_and(|k| {
                    vs[(k + 1) % 3] == seed.link1[j] && vs[(k + 2) % 3] == seed.link1[(j + 1) % n]
                });
            assert!(
                ok,
                "global_step: face {f} is not triangle {j} of pole {}",
                seed.pole
            );
            let k = k.unwrap_or(0);
            pole_corner[f] = k as u32;
            topo.face_half_edge(f, k)
        })
        .collect();
    for j in 0..n {
        let f = seed.quads[j] as usize;
        let vs = topo.face(f);
        let want = [
            seed.link1[(j + 1) % n],
            seed.link1[j],
            seed.link2[j],
            seed.link2[(j + 1) % n],
        ];
        let ok = vs.len() == 4 && (0..4).any(|s| (0..4).all(|i| vs[(s + i) % 4] == want[i]));
        assert!(
            ok,
            "global_step: face {f} is not quad {j} of pole {}",
            seed.pole
        );
    }
    let (q00, q1, q2) = (seed.pole, &seed.link1, &seed.link2);
    let nf64 = n as f64;
    // (1): new pole = 3/4 q00 + 1/4 A.
    let mut row = vec![(q00, 0.75)];
    for &v in q1 {
        add(&mut row, v, 0.25 / nf64);
    }
    rows[q00 as usize] = row;
    // Periodic cubic refinement of a link as weights: ũ[j'].
    let tilde = |u: &[u32], jp: usize, w: f64, row: &mut Row| {
        let j = jp / 2;
        if jp.is_multiple_of(2) {
            add(row, u[(j + n - 1) % n], w / 8.0);
            add(row, u[j], 6.0 * w / 8.0);
            add(row, u[(j + 1) % n], w / 8.0);
        } else {
            add(row, u[j], w / 2.0);
            add(row, u[(j + 1) % n], w / 2.0);
        }
    };
    for jp in 0..2 * n {
        let j = jp / 2;
        let h = spokes[j];
        // (2): new link 1.
        let tau = jp as f64 / (2.0 * nf64);
        let mut row = vec![(q00, 0.5)];
        for (hh, &v) in q1.iter().enumerate() {
            let d = hh as f64 / nf64 - tau;
            add(&mut row, v, (0.5 + c(d) + 0.5 * c(2.0 * d)) / nf64);
        }
        let id = if jp.is_multiple_of(2) {
            numbering.edge_point(h)
        } else {
            numbering.face_point(seed.triangles[j] as usize)
        };
        rows[id as usize] = row;
        // First-step variant: new link 2 = (q00 + 6 q̃1 + q̃2)/8.
        let mut row = vec![(q00, 0.125)];
        tilde(q1, jp, 0.75, &mut row);
        tilde(q2, jp, 0.125, &mut row);
        let id = if jp.is_multiple_of(2) {
            q1[j]
        } else {
            numbering.edge_point(topo.next(h))
        };
        rows[id as usize] = row;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

    fn charts(nf: u32) -> Vec<FaceChart> {
        (0..nf).map(FaceChart::input).collect()
    }

    #[test]
    fn edges_are_numbered_as_first_met_along_the_half_edges() {
        // Half-edges: 0→1 (e0), 1→2 (e1), 2→0 (e2), 2→1 (= e1), 1→3 (e3), 3→2 (e4).
        let faces = vec![vec![0, 1, 2], vec![2, 1, 3]];
        let t = Topology::from_faces(4, &faces).unwrap();
        let r = global_step(&t, &charts(2), &[]);
        assert_eq!(r.num_vertices, 4 + 2 + 5);
        let e = |i: u32| 6 + i;
        assert_eq!(
            r.faces,
            vec![
                vec![0, e(0), 4, e(2)],
                vec![1, e(1), 4, e(0)],
                vec![2, e(2), 4, e(1)],
                vec![2, e(1), 5, e(4)],
                vec![1, e(3), 5, e(1)],
                vec![3, e(4), 5, e(3)],
            ]
        );
        assert_eq!(r.parent, vec![0, 0, 0, 1, 1, 1]);
        // Interior edge 1–2: (v + w)/4 + both centroids/4.
        let row: Vec<(u32, f64)> = r.stencils.row(e(1) as usize).collect();
        let w = |i: u32| row.iter().filter(|x| x.0 == i).map(|x| x.1).sum::<f64>();
        let third = 1.0 / 12.0;
        assert!((w(1) - (0.25 + 2.0 * third)).abs() < 1e-15);
        assert!((w(2) - (0.25 + 2.0 * third)).abs() < 1e-15);
        assert!((w(0) - third).abs() < 1e-15 && (w(3) - third).abs() < 1e-15);
        // A one-face corner keeps its position.
        assert_eq!(r.stencils.row(0).collect::<Vec<_>>(), vec![(0, 1.0)]);
    }

    /// A closed fan of valence `n` around vertex 0 with one ring of quads and
    /// a second pole closing it: vertices 0, link1 1..=n, link2 n+1..=2n, 2n+1.
    fn bipyramid_seed(n: u32) -> (Topology, PolarSeed) {
        let l1 = |j: u32| 1 + j % n;
        let l2 = |j: u32| 1 + n + j % n;
        let mut faces = Vec::new();
        let mut seed = PolarSeed {
            pole: 0,
            link1: (0..n).map(l1).collect(),
            link2: (0..n).map(l2).collect(),
            triangles: Vec::new(),
            quads: Vec::new(),
        };
        for j in 0..n {
            seed.triangles.push(faces.len() as u32);
            faces.push(vec![0, l1(j), l1(j + 1)]);
        }
        for j in 0..n {
            seed.quads.push(faces.len() as u32);
            faces.push(vec![l1(j + 1), l1(j), l2(j), l2(j + 1)]);
        }
        for j in 0..n {
            faces.push(vec![2 * n + 1, l2(j + 1), l2(j)]);
        }
        let t = Topology::from_faces(2 * n as usize + 2, &faces).unwrap();
        (t, seed)
    }

    #[test]
    fn pole_row_is_three_quarters_pole_plus_quarter_link_mean() {
        for n in 3..9 {
            let (t, seed) = bipyramid_seed(n);
            let r = global_step(&t, &charts(t.num_faces() as u32), &[seed]);
            assert_eq!(r.poles, vec![0]);
            let row: Vec<(u32, f64)> = r.stencils.row(0).collect();
            assert_eq!(row.len(), n as usize + 1);
            for (i, w) in row {
                let want = if i == 0 { 0.75 } else { 0.25 / n as f64 };
                assert!((w - want).abs() < 1e-15);
            }
            for i in 0..r.stencils.len() {
                let s: f64 = r.stencils.row(i).map(|e| e.1).sum();
                assert!((s - 1.0).abs() < 1e-13, "n={n} row {i}");
            }
            // Each fan triangle (pole at corner 0): the two pole triangles,
            // then the sub-quads at its other two corners.
            for j in 0..n as usize {
                let sizes: Vec<usize> = r.faces[4 * j..4 * j + 4].iter().map(|f| f.len()).collect();
                assert_eq!(sizes, vec![3, 3, 4, 4]);
                assert!(r.faces[4 * j][0] == 0 && r.faces[4 * j + 1][0] == 0);
            }
            assert_eq!(
                r.faces.iter().filter(|f| f.len() == 3).count(),
                2 * n as usize
            );
        }
    }

    #[test]
    #[should_panic(expected = "is not triangle")]
    fn a_seed_naming_the_wrong_faces_panics() {
        let (t, mut seed) = bipyramid_seed(5);
        seed.triangles.swap(0, 1);
        let _ = global_step(&t, &charts(t.num_faces() as u32), &[seed]);
    }
}
