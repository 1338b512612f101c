//! The combined refinement step (Catmull-Clark, C²PS at polar vertices),
//! checked against independent computations: a textbook Catmull-Clark step
//! written here over plain face lists, uniform cubic B-spline knot insertion
//! on regular grids, the `capdiv` kernel's C²PS step at poles, and affine
//! reproduction for the charts.

use capdiv::{FirstStep, PolarNet};
use capdiv_mesh::chart::{Affine, FaceChart};
use capdiv_mesh::global_step::{global_step, PolarSeed, Refined};
use capdiv_mesh::topology::NONE;
use capdiv_mesh::Topology;
use std::collections::HashMap;

type P = [f64; 3];

fn add(a: P, b: P) -> P {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn scale(a: P, s: f64) -> P {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn dist(a: P, b: P) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max)
}
fn mean(ps: &[P]) -> P {
    let s = ps.iter().fold([0.0; 3], |acc, &p| add(acc, p));
    scale(s, 1.0 / ps.len() as f64)
}

/// Deterministic pseudo-random numbers in [-1, 1] (a small LCG).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

fn input_charts(nf: usize) -> Vec<FaceChart> {
    (0..nf as u32).map(FaceChart::input).collect()
}

/// Refined positions by applying every stencil row by hand.
fn positions(r: &Refined, old: &[P]) -> Vec<P> {
    (0..r.stencils.len())
        .map(|i| {
            r.stencils
                .row(i)
                .fold([0.0; 3], |acc, (j, w)| add(acc, scale(old[j as usize], w)))
        })
        .collect()
}

/// Every stencil row sums to 1 (affine invariance), one row per vertex.
fn assert_affine_rows(r: &Refined) {
    assert_eq!(r.stencils.len(), r.num_vertices);
    for i in 0..r.stencils.len() {
        let s: f64 = r.stencils.row(i).map(|(_, w)| w).sum();
        assert!((s - 1.0).abs() < 1e-13, "row {i} sums to {s}");
    }
}

/// Undirected edges numbered in the order first met walking the faces'
/// corners (= half-edges) in order.
fn edge_ids(faces: &[Vec<u32>]) -> HashMap<(u32, u32), u32> {
    let mut ids = HashMap::new();
    for f in faces {
        for c in 0..f.len() {
            let (a, b) = (f[c], f[(c + 1) % f.len()]);
            let n = ids.len() as u32;
            ids.entry((a.min(b), a.max(b))).or_insert(n);
        }
    }
    ids
}

fn key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// Textbook Catmull-Clark (no poles) over plain face lists: the new position
/// of every old vertex, face and edge, keyed as the refined numbering.
/// Vertex points: Q/n + 2R/n + (n−3)S/n inside; (6v+a+b)/8 on a boundary
/// with two or more faces; v at a one-face corner.
fn textbook_cc(pos: &[P], faces: &[Vec<u32>]) -> Vec<P> {
    let ids = edge_ids(faces);
    let (nv, nf, ne) = (pos.len(), faces.len(), ids.len());
    let fps: Vec<P> = faces
        .iter()
        .map(|f| mean(&f.iter().map(|&v| pos[v as usize]).collect::<Vec<_>>()))
        .collect();
    let mut edge_faces: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (fi, f) in faces.iter().enumerate() {
        for c in 0..f.len() {
            edge_faces
                .entry(key(f[c], f[(c + 1) % f.len()]))
                .or_default()
                .push(fi);
        }
    }
    let mut out = vec![[0.0; 3]; nv + nf + ne];
    for v in 0..nv as u32 {
        let vf: Vec<usize> = (0..nf).filter(|&f| faces[f].contains(&v)).collect();
        let ve: Vec<(u32, u32)> = edge_faces
            .keys()
            .copied()
            .filter(|&(a, b)| a == v || b == v)
            .collect();
        let other = |e: (u32, u32)| if e.0 == v { e.1 } else { e.0 };
        let p = pos[v as usize];
        out[v as usize] = if vf.is_empty() || vf.len() == 1 {
            p
        } else if ve.iter().any(|e| edge_faces[e].len() == 1) {
            let bn: Vec<u32> = ve
                .iter()
                .filter(|e| edge_faces[e].len() == 1)
                .map(|&e| other(e))
                .collect();
            assert_eq!(bn.len(), 2);
            scale(
                add(scale(p, 6.0), add(pos[bn[0] as usize], pos[bn[1] as usize])),
                1.0 / 8.0,
            )
        } else {
            let n = ve.len() as f64;
            let q = mean(&vf.iter().map(|&f| fps[f]).collect::<Vec<_>>());
            let r = mean(
                &ve.iter()
                    .map(|&e| scale(add(pos[e.0 as usize], pos[e.1 as usize]), 0.5))
                    .collect::<Vec<_>>(),
            );
            add(
                add(scale(q, 1.0 / n), scale(r, 2.0 / n)),
                scale(p, (n - 3.0) / n),
            )
        };
    }
    out[nv..nv + nf].copy_from_slice(&fps);
    for (e, &id) in &ids {
        let fs = &edge_faces[e];
        let mid = add(pos[e.0 as usize], pos[e.1 as usize]);
        out[nv + nf + id as usize] = if fs.len() == 2 {
            scale(add(mid, add(fps[fs[0]], fps[fs[1]])), 0.25)
        } else {
            scale(mid, 0.5)
        };
    }
    out
}

/// The refined faces the numbering rule gives without poles.
fn expected_faces(nv: usize, faces: &[Vec<u32>]) -> Vec<Vec<u32>> {
    let ids = edge_ids(faces);
    let (nv, nf) = (nv as u32, faces.len() as u32);
    let ep = |a: u32, b: u32| nv + nf + ids[&key(a, b)];
    let mut out = Vec::new();
    for (fi, f) in faces.iter().enumerate() {
        let k = f.len();
        for c in 0..k {
            let (p, v, n) = (f[(c + k - 1) % k], f[c], f[(c + 1) % k]);
            out.push(vec![v, ep(v, n), nv + fi as u32, ep(p, v)]);
        }
    }
    out
}

/// Euler characteristic V − E + F of a face list.
fn euler(nv: usize, faces: &[Vec<u32>]) -> i64 {
    nv as i64 - edge_ids(faces).len() as i64 + faces.len() as i64
}

fn cube() -> (Vec<P>, Vec<Vec<u32>>) {
    let pos = vec![
        [-1.0, -1.0, -1.0],
        [1.0, -1.0, -1.0],
        [1.0, 1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
        [1.0, -1.0, 1.0],
        [1.0, 1.0, 1.0],
        [-1.0, 1.0, 1.0],
    ];
    let faces = vec![
        vec![0, 3, 2, 1],
        vec![4, 5, 6, 7],
        vec![0, 1, 5, 4],
        vec![1, 2, 6, 5],
        vec![2, 3, 7, 6],
        vec![3, 0, 4, 7],
    ];
    (pos, faces)
}

fn check_against_textbook(pos: &[P], faces: &[Vec<u32>]) -> Refined {
    let topo = Topology::from_faces(pos.len(), faces).unwrap();
    let r = global_step(&topo, &input_charts(faces.len()), &[]);
    assert_affine_rows(&r);
    assert_eq!(r.faces, expected_faces(pos.len(), faces));
    let got = positions(&r, pos);
    let want = textbook_cc(pos, faces);
    assert_eq!(got.len(), want.len());
    for (i, (g, w)) in got.iter().zip(&want).enumerate() {
        assert!(dist(*g, *w) < 1e-14, "refined vertex {i}: {g:?} vs {w:?}");
    }
    r
}

#[test]
fn cube_refines_to_the_textbook_catmull_clark_cube() {
    let (pos, faces) = cube();
    let r = check_against_textbook(&pos, &faces);
    assert_eq!(r.num_vertices, 26);
    assert_eq!(r.faces.len(), 24);
    assert!(r.faces.iter().all(|f| f.len() == 4));
    let t = Topology::from_faces(r.num_vertices, &r.faces).unwrap();
    assert!(t.is_closed());
    assert_eq!(euler(r.num_vertices, &r.faces), 2);
    assert_eq!(r.parent, (0..6).flat_map(|f| [f; 4]).collect::<Vec<u32>>());
    // Closed forms by hand: corner (±1,±1,±1), n = 3: Q = (1,1,1)/3 (mean of
    // the three face centres), R = 2/3 (1,1,1) (mean of the edge midpoints),
    // (Q + 2R + 0·S)/3 = 5/9 (1,1,1). Face points: the face centres; edge
    // points: (v + w + two face centres)/4, e.g. edge (1,1,±1) → (3/4, 3/4, 0).
    let got = positions(&r, &pos);
    for v in 0..8 {
        assert!(dist(got[v], scale(pos[v], 5.0 / 9.0)) < 1e-15);
    }
    for f in 0..6 {
        let c = mean(
            &faces[f]
                .iter()
                .map(|&v| pos[v as usize])
                .collect::<Vec<_>>(),
        );
        assert!(dist(got[8 + f], c) < 1e-15);
        assert_eq!(c.iter().map(|x| x.abs()).sum::<f64>(), 1.0);
    }
    for p in &got[14..] {
        let mut a: Vec<f64> = p.iter().map(|x| x.abs()).collect();
        a.sort_by(f64::total_cmp);
        assert_eq!(a, vec![0.0, 0.75, 0.75]);
    }
}

#[test]
fn perturbed_mixed_polygon_meshes_match_the_textbook_step() {
    let mut rng = Rng(7);
    // Perturbed cube.
    let (mut pos, faces) = cube();
    for p in &mut pos {
        for x in p.iter_mut() {
            *x += 0.3 * rng.next();
        }
    }
    check_against_textbook(&pos, &faces);
    // Pentagonal prism whose top is a fan of 5 triangles around a centre
    // (valence 5 of triangles, valence 4 mixed at the top rim), bottom a pentagon.
    let mut pos: Vec<P> = Vec::new();
    for z in [0.0, 1.0] {
        for j in 0..5 {
            let a = 2.0 * std::f64::consts::PI * j as f64 / 5.0;
            pos.push([
                a.cos() + 0.1 * rng.next(),
                a.sin() + 0.1 * rng.next(),
                z + 0.1 * rng.next(),
            ]);
        }
    }
    pos.push([0.0, 0.0, 1.3]);
    let mut faces: Vec<Vec<u32>> = vec![vec![0, 4, 3, 2, 1]];
    for j in 0..5u32 {
        let k = (j + 1) % 5;
        faces.push(vec![j, k, 5 + k, 5 + j]);
        faces.push(vec![10, 5 + j, 5 + k]);
    }
    let r = check_against_textbook(&pos, &faces);
    assert_eq!(euler(r.num_vertices, &r.faces), 2);
    assert!(Topology::from_faces(r.num_vertices, &r.faces)
        .unwrap()
        .is_closed());
}

/// An `n × n` vertex grid (vertex (i, j) = j·n + i), quads counter-clockwise
/// in the (i, j) plane.
fn grid(n: usize, mut pos_of: impl FnMut(usize, usize) -> P) -> (Vec<P>, Vec<Vec<u32>>) {
    let id = |i: usize, j: usize| (j * n + i) as u32;
    let mut pos = vec![[0.0; 3]; n * n];
    for j in 0..n {
        for i in 0..n {
            pos[id(i, j) as usize] = pos_of(i, j);
        }
    }
    let mut faces = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (pos, faces)
}

#[test]
fn regular_grid_interior_is_cubic_b_spline_knot_insertion() {
    let n = 7;
    let mut rng = Rng(11);
    let (pos, faces) = grid(n, |i, j| {
        [
            i as f64 + 0.2 * rng.next(),
            j as f64 + 0.2 * rng.next(),
            rng.next(),
        ]
    });
    let topo = Topology::from_faces(pos.len(), &faces).unwrap();
    let r = global_step(&topo, &input_charts(faces.len()), &[]);
    assert_affine_rows(&r);
    let got = positions(&r, &pos);
    let p = |i: usize, j: usize| pos[j * n + i];
    let w = [1.0, 6.0, 1.0];
    let fidx = |i: usize, j: usize| j * (n - 1) + i;
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let sub = &r.faces[4 * fidx(i, j)..4 * fidx(i, j) + 4];
            // Face point: 1/4 of the four corners.
            let fp = scale(
                add(add(p(i, j), p(i + 1, j)), add(p(i + 1, j + 1), p(i, j + 1))),
                0.25,
            );
            assert!(dist(got[sub[0][2] as usize], fp) < 1e-14);
            // Vertex point of (i, j): (1/64) [1 6 1] ⊗ [1 6 1].
            if i >= 1 && j >= 1 {
                let mut vp = [0.0; 3];
                for a in 0..3 {
                    for b in 0..3 {
                        vp = add(vp, scale(p(i + a - 1, j + b - 1), w[a] * w[b] / 64.0));
                    }
                }
                assert_eq!(sub[0][0] as usize, j * n + i);
                assert!(dist(got[j * n + i], vp) < 1e-14, "vertex ({i},{j})");
            }
            // Edge point of (i, j)–(i+1, j): (1/16) [1 1] ⊗ [1 6 1].
            if j >= 1 {
                let mut ep = [0.0; 3];
                for a in 0..2 {
                    for (b, wb) in w.iter().enumerate() {
                        ep = add(ep, scale(p(i + a, j + b - 1), wb / 16.0));
                    }
                }
                assert!(dist(got[sub[0][1] as usize], ep) < 1e-14, "edge ({i},{j})→");
            }
            // Edge point of (i, j+1)–(i, j): (1/16) [1 6 1] ⊗ [1 1].
            if i >= 1 {
                let mut ep = [0.0; 3];
                for (a, wa) in w.iter().enumerate() {
                    for b in 0..2 {
                        ep = add(ep, scale(p(i + a - 1, j + b), wa / 16.0));
                    }
                }
                assert!(dist(got[sub[0][3] as usize], ep) < 1e-14, "edge ({i},{j})↑");
            }
        }
    }
}

#[test]
fn boundary_rules_and_open_grid_counts() {
    let n = 5;
    let mut rng = Rng(3);
    let (pos, faces) = grid(n, |i, j| {
        [
            i as f64 + 0.2 * rng.next(),
            j as f64 + 0.2 * rng.next(),
            rng.next(),
        ]
    });
    let r = check_against_textbook(&pos, &faces);
    let (nv, nf) = (pos.len(), faces.len());
    let ne = 2 * n * (n - 1);
    assert_eq!(r.num_vertices, nv + nf + ne);
    assert_eq!(r.faces.len(), 4 * nf);
    let t = Topology::from_faces(r.num_vertices, &r.faces).unwrap();
    assert!(!t.is_closed());
    let boundary_he = |t: &Topology| {
        (0..t.num_half_edges() as u32)
            .filter(|&h| t.twin(h) == NONE)
            .count()
    };
    let old = Topology::from_faces(nv, &faces).unwrap();
    assert_eq!(boundary_he(&old), 4 * (n - 1));
    assert_eq!(boundary_he(&t), 8 * (n - 1));
    assert_eq!(euler(r.num_vertices, &r.faces), 1);
    let got = positions(&r, &pos);
    let p = |i: usize, j: usize| pos[j * n + i];
    // Corners fixed.
    for (i, j) in [(0, 0), (n - 1, 0), (0, n - 1), (n - 1, n - 1)] {
        assert_eq!(got[j * n + i], p(i, j));
    }
    // Boundary vertex on the bottom row: (6v + a + b)/8.
    for i in 1..n - 1 {
        let want = scale(
            add(scale(p(i, 0), 6.0), add(p(i - 1, 0), p(i + 1, 0))),
            0.125,
        );
        assert!(dist(got[i], want) < 1e-15);
        // Boundary edge (i,0)–(i+1,0): the midpoint.
        let f = i; // face (i, 0)
        let ep = r.faces[4 * f][1] as usize;
        assert!(dist(got[ep], scale(add(p(i, 0), p(i + 1, 0)), 0.5)) < 1e-15);
    }
    // Mixed polygons with a boundary: a pentagon, a triangle and quads.
    let pos2: Vec<P> = (0..8)
        .map(|_| [rng.next(), rng.next(), rng.next()])
        .collect();
    let faces2 = vec![
        vec![0, 1, 2, 3, 4],
        vec![1, 5, 6, 2],
        vec![2, 6, 7],
        vec![3, 2, 7],
    ];
    let r2 = check_against_textbook(&pos2, &faces2);
    assert!(!Topology::from_faces(r2.num_vertices, &r2.faces)
        .unwrap()
        .is_closed());
}

/// A triangle fan of valence `n` around a pole plus `rings − 1` rings of
/// quads; if `closed`, capped by a second fan (a spindle) and two seeds.
/// Triangle and quad vertex lists start at varying corners.
fn polar_mesh(
    n: usize,
    rings: usize,
    closed: bool,
    rng: &mut Rng,
) -> (Vec<P>, Vec<Vec<u32>>, Vec<PolarSeed>) {
    let ring = |r: usize, j: usize| (1 + (r - 1) * n + j % n) as u32;
    let mut pos = vec![[0.1 * rng.next(), 0.1 * rng.next(), 0.5 + 0.1 * rng.next()]];
    for r in 1..=rings {
        for j in 0..n {
            let a = 2.0 * std::f64::consts::PI * (j as f64 + 0.2 * rng.next()) / n as f64;
            let rad = r as f64 * (1.0 + 0.15 * rng.next());
            pos.push([
                rad * a.cos(),
                rad * a.sin(),
                0.2 * rng.next() - 0.05 * (r * r) as f64,
            ]);
        }
    }
    let rot = |f: Vec<u32>, s: usize| -> Vec<u32> {
        let k = f.len();
        (0..k).map(|i| f[(i + s) % k]).collect()
    };
    let mut faces = Vec::new();
    let mut seed = PolarSeed {
        pole: 0,
        link1: (0..n).map(|j| ring(1, j)).collect(),
        link2: (0..n).map(|j| ring(2, j)).collect(),
        triangles: Vec::new(),
        quads: Vec::new(),
    };
    for j in 0..n {
        seed.triangles.push(faces.len() as u32);
        faces.push(rot(vec![0, ring(1, j), ring(1, j + 1)], j % 3));
    }
    for r in 1..rings {
        for j in 0..n {
            if r == 1 {
                seed.quads.push(faces.len() as u32);
            }
            faces.push(rot(
                vec![
                    ring(r, j + 1),
                    ring(r, j),
                    ring(r + 1, j),
                    ring(r + 1, j + 1),
                ],
                (j + r) % 4,
            ));
        }
    }
    let mut seeds = vec![seed];
    if closed {
        let south = pos.len() as u32;
        pos.push([0.0, 0.0, -((rings * rings) as f64) * 0.05 - 0.7]);
        let m = |k: usize| (n - k) % n;
        let mut s = PolarSeed {
            pole: south,
            link1: (0..n).map(|k| ring(rings, m(k))).collect(),
            link2: (0..n).map(|k| ring(rings - 1, m(k))).collect(),
            triangles: Vec::new(),
            quads: Vec::new(),
        };
        // quads[k] = the quad between rings R−1 and R at j = m(k) − 1.
        let first_outer = (n + (rings - 2) * n) as u32;
        for k in 0..n {
            let j = (m(k) + n - 1) % n;
            s.quads.push(first_outer + j as u32);
        }
        for k in 0..n {
            s.triangles.push(faces.len() as u32);
            faces.push(rot(
                vec![south, s.link1[k], s.link1[(k + 1) % n]],
                (k + 1) % 3,
            ));
        }
        seeds.push(s);
    }
    (pos, faces, seeds)
}

#[test]
fn poles_follow_the_c2ps_kernel_and_everything_else_catmull_clark() {
    let mut rng = Rng(2024);
    for n in 3..=12 {
        for (rings, closed) in [(3, false), (4, true), (5, true)] {
            let (pos, faces, seeds) = polar_mesh(n, rings, closed, &mut rng);
            let topo = Topology::from_faces(pos.len(), &faces).unwrap();
            assert_eq!(topo.is_closed(), closed);
            let r = global_step(&topo, &input_charts(faces.len()), &seeds);
            assert_affine_rows(&r);
            assert_eq!(r.poles, seeds.iter().map(|s| s.pole).collect::<Vec<_>>());
            let got = positions(&r, &pos);
            let ids = edge_ids(&faces);
            let (nv, nf) = (pos.len() as u32, faces.len() as u32);
            let ep = |a: u32, b: u32| nv + nf + ids[&key(a, b)];
            for s in &seeds {
                let p = |v: u32| pos[v as usize];
                let link = |l: &[u32]| l.iter().map(|&v| p(v)).collect::<Vec<P>>();
                // Links 1..3 of the old net: link 3 across quads from link 2.
                let link3: Vec<u32> = s
                    .link2
                    .iter()
                    .map(|&v| {
                        let t = topo.outgoing(v as usize).map(|h| topo.dest(h));
                        let across: Vec<u32> = t
                            .filter(|w| !s.link1.contains(w) && !s.link2.contains(w))
                            .collect();
                        assert_eq!(across.len(), 1);
                        across[0]
                    })
                    .collect();
                let mut net = PolarNet::<f64, 4096>::new(
                    p(s.pole),
                    &[link(&s.link1), link(&s.link2), link(&link3)],
                )
                .unwrap();
                net.step(FirstStep::Uniform).unwrap();
                let q = |x: capdiv::Point3<f64>| x.0;
                let tol = 1e-12 * rings as f64 * rings as f64;
                assert!(
                    dist(got[s.pole as usize], q(net.pole())) < tol,
                    "pole n={n}"
                );
                let m = s.link1.len();
                for jp in 0..2 * m {
                    let j = jp / 2;
                    let (a, b) = (s.link1[j], s.link1[(j + 1) % m]);
                    let ids_of_link = [
                        if jp.is_multiple_of(2) {
                            ep(s.pole, a)
                        } else {
                            nv + s.triangles[j]
                        },
                        if jp.is_multiple_of(2) { a } else { ep(a, b) },
                        if jp.is_multiple_of(2) {
                            ep(a, s.link2[j])
                        } else {
                            nv + s.quads[j]
                        },
                        if jp.is_multiple_of(2) {
                            s.link2[j]
                        } else {
                            ep(s.link2[j], s.link2[(j + 1) % m])
                        },
                        if jp.is_multiple_of(2) {
                            ep(s.link2[j], link3[j])
                        } else {
                            // The quad between links 2 and 3 at j: its face point.
                            let f = faces
                                .iter()
                                .position(|f| {
                                    f.len() == 4
                                        && [s.link2[j], s.link2[(j + 1) % m], link3[j]]
                                            .iter()
                                            .all(|v| f.contains(v))
                                })
                                .unwrap();
                            nv + f as u32
                        },
                    ];
                    for (i, &id) in ids_of_link.iter().enumerate() {
                        let want = q(net.link(i + 1).unwrap()[jp]);
                        assert!(
                            dist(got[id as usize], want) < tol,
                            "n={n} rings={rings} link {} j'={jp}: {:?} vs {want:?}",
                            i + 1,
                            got[id as usize]
                        );
                    }
                }
            }
            // Faces: triangles at the pole corners, sub-quads elsewhere, in
            // old-face order.
            let pole_of: HashMap<u32, u32> = seeds
                .iter()
                .flat_map(|s| s.triangles.iter().map(move |&t| (t, s.pole)))
                .collect();
            let mut want_faces = Vec::new();
            for (fi, f) in faces.iter().enumerate() {
                let k = f.len();
                for c in 0..k {
                    let (pv, v, nx) = (f[(c + k - 1) % k], f[c], f[(c + 1) % k]);
                    let fp = nv + fi as u32;
                    if pole_of.get(&(fi as u32)) == Some(&v) {
                        want_faces.push(vec![v, ep(v, nx), fp]);
                        want_faces.push(vec![v, fp, ep(pv, v)]);
                    } else {
                        want_faces.push(vec![v, ep(v, nx), fp, ep(pv, v)]);
                    }
                }
            }
            assert_eq!(r.faces, want_faces);
            assert_eq!(r.parent.len(), r.faces.len());
            let t = Topology::from_faces(r.num_vertices, &r.faces).unwrap();
            assert_eq!(t.is_closed(), closed);
            assert_eq!(euler(r.num_vertices, &r.faces), euler(pos.len(), &faces));
            for s in &seeds {
                let pole = s.pole as usize;
                assert_eq!(t.outgoing(pole).count(), 2 * n);
                assert!(t
                    .outgoing(pole)
                    .all(|h| t.face_len(t.face_of(h) as usize) == 3));
                // Each new link-1 vertex: two pole triangles, then quads.
                for h in t.outgoing(pole) {
                    let v = t.dest(h) as usize;
                    let sizes: Vec<usize> = t
                        .outgoing(v)
                        .map(|g| t.face_len(t.face_of(g) as usize))
                        .collect();
                    assert_eq!(sizes.len(), 4);
                    assert_eq!(sizes.iter().filter(|&&k| k == 3).count(), 2);
                }
                // The pole triangles report the input face itself.
                for h in t.outgoing(pole) {
                    let g = t.face_of(h) as usize;
                    assert_eq!(r.charts[g], FaceChart::input(r.parent[g]));
                    assert!(s.triangles.contains(&r.parent[g]));
                }
            }
        }
    }
}

/// Input parameter `(s, t)` of a point of grid face `(i, j)`: the grid's
/// (i + s, j + t).
fn grid_param(n: usize, chart: &FaceChart, st: [f64; 2]) -> [f64; 2] {
    let (i, j) = (chart.face as usize % (n - 1), chart.face as usize / (n - 1));
    [i as f64 + st[0], j as f64 + st[1]]
}

#[test]
fn quad_charts_compose_quadrants_and_reproduce_affine_positions() {
    // An affine image of the integer grid: Catmull-Clark (boundary rules
    // included) reproduces affine functions, so every refined vertex sits at
    // the affine image of its chart parameter — at both levels.
    let n = 5;
    let aff = |x: f64, y: f64| -> P {
        [
            0.3 + 1.1 * x + 0.4 * y,
            -0.2 + 0.3 * x + 0.9 * y,
            0.5 * x - 0.7 * y,
        ]
    };
    let (pos, faces) = grid(n, |i, j| aff(i as f64, j as f64));
    let topo = Topology::from_faces(pos.len(), &faces).unwrap();
    let r1 = global_step(&topo, &input_charts(faces.len()), &[]);
    // Level 1, explicitly: corner c of the input quad's square at (0,0), the
    // centre at (1,1), edge midpoints at (1,0) and (0,1).
    let sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
    for (g, ch) in r1.charts.iter().enumerate() {
        let c = g % 4;
        assert_eq!(ch.face as usize, g / 4);
        assert_eq!(ch.corner, None);
        assert_eq!(ch.map.apply(0.0, 0.0), sq[c]);
        assert_eq!(ch.map.apply(1.0, 1.0), [0.5, 0.5]);
        assert_eq!(ch.map.apply(1.0, 0.0), mid(sq[c], sq[(c + 1) % 4]));
        assert_eq!(ch.map.apply(0.0, 1.0), mid(sq[c], sq[(c + 3) % 4]));
    }
    let p1 = positions(&r1, &pos);
    let t1 = Topology::from_faces(r1.num_vertices, &r1.faces).unwrap();
    let r2 = global_step(&t1, &r1.charts, &[]);
    assert_affine_rows(&r2);
    let p2 = positions(&r2, &p1);
    for (r, p) in [(&r1, &p1), (&r2, &p2)] {
        for (g, f) in r.faces.iter().enumerate() {
            let ch = &r.charts[g];
            for (k, &v) in f.iter().enumerate() {
                let uv = grid_param(n, ch, ch.map.apply(sq[k][0], sq[k][1]));
                assert!(
                    dist(p[v as usize], aff(uv[0], uv[1])) < 1e-13,
                    "face {g} vertex {k}"
                );
            }
        }
    }
    // Level 2 parents are level-1 faces; the chart's face is the input face.
    for (g, ch) in r2.charts.iter().enumerate() {
        assert_eq!(r2.parent[g] as usize, g / 4);
        assert_eq!(ch.face, r1.charts[g / 4].face);
        let side = ch.map.du[0].abs() + ch.map.du[1].abs();
        assert_eq!(side, 0.25);
    }
}

#[test]
fn non_quad_faces_report_their_corner() {
    let mut rng = Rng(5);
    let pos: Vec<P> = (0..8)
        .map(|_| [rng.next(), rng.next(), rng.next()])
        .collect();
    let faces = vec![vec![0, 1, 2, 3, 4], vec![1, 5, 6, 2], vec![2, 6, 7]];
    let topo = Topology::from_faces(pos.len(), &faces).unwrap();
    // Input face 1 is given with a non-trivial chart, to see composition.
    let mut charts = input_charts(3);
    charts[1].map = Affine::quadrant(2);
    let r1 = global_step(&topo, &charts, &[]);
    assert_eq!(r1.parent, vec![0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2]);
    for c in 0..5 {
        assert_eq!(
            r1.charts[c],
            FaceChart {
                face: 0,
                corner: Some(c as u8),
                map: Affine::IDENTITY
            }
        );
    }
    for c in 0..4 {
        assert_eq!(
            r1.charts[5 + c],
            FaceChart {
                face: 1,
                corner: None,
                map: Affine::quadrant(2).compose(&Affine::quadrant(c))
            }
        );
    }
    for c in 0..3 {
        assert_eq!(
            r1.charts[9 + c],
            FaceChart {
                face: 2,
                corner: Some(c as u8),
                map: Affine::IDENTITY
            }
        );
    }
    // One more level: sub-quads of a pentagon's corner keep the corner and
    // take the quadrant of its sub-square.
    let t1 = Topology::from_faces(r1.num_vertices, &r1.faces).unwrap();
    let r2 = global_step(&t1, &r1.charts, &[]);
    for (g, ch) in r2.charts.iter().enumerate() {
        let (parent, c) = (g / 4, g % 4);
        assert_eq!(r2.parent[g] as usize, parent);
        let pc = r1.charts[parent];
        assert_eq!(ch.face, pc.face);
        assert_eq!(ch.corner, pc.corner);
        assert_eq!(ch.map, pc.map.compose(&Affine::quadrant(c)));
        // (0,0) ↦ the parent's own corner c, (1,1) ↦ the parent's centre.
        let sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(ch.map.apply(0.0, 0.0), pc.map.apply(sq[c][0], sq[c][1]));
        assert_eq!(ch.map.apply(1.0, 1.0), pc.map.apply(0.5, 0.5));
    }
}
