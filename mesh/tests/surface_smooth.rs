//! Smoothness and coverage on generated meshes.
//!
//! Every patch edge (but the edges around a cap's last hole) is sampled at
//! t = k/16; samples of different patches are matched by position (a hash on
//! rounded coordinates, neighbouring cells searched too). An edge met by two
//! half-size patches: their samples at t = k/8 are the big edge's k/16, and
//! the big edge's k/16 up to 1/2 are the first small edge's k/8, so the
//! samples at eighths always find a partner across an interior edge. At every
//! match, position, unit normal, Gaussian and mean curvature must agree.
//!
//! Which joins are C² by construction: every patch edge on these meshes.
//! B-spline/B-spline (one uniform bicubic B-spline surface over the mesh);
//! C²PS ring/ring and ring/surround (each ring is the uniform bicubic
//! B-spline of the level's links 1..5, the level-0 ring being the regular
//! faces', docs/math/c2ps.md §5); EG ring/ring and ring/surround (docs/math/eg.md §9:
//! the rings are C² with each other and with the bicubic surround);
//! Catmull-Clark ring patches are uniform bicubic B-spline patches of the
//! refined grid, so C² across their edges too (with each other and with the
//! regular faces around the cap). The only point that is not C² is the
//! Catmull-Clark cap's centre (not an edge; it is the last hole's limit
//! point, never sampled here) — `catmull_clark_centre_*` looks at it.
//!
//! Mean and Gaussian curvature do not depend on the parametrization, so the
//! checks hold whatever the two patches' frames; normals are compared as
//! vectors, so they also check that both patches are oriented alike.
//!
//! Tolerances (measured worst values printed by each test, see the report in
//! the commit): positions 1e-9·size (the matching radius; measured ≤ 1e-14),
//! normals 1e-9, curvature relative to the local scale
//! `κ = max(|H|, √|K|, 1/size)`: |ΔH| ≤ 1e-6·κ, |ΔK| ≤ 1e-6·κ². The floor
//! 1/size keeps flat regions from dividing by zero. Deep C²PS rings of high
//! valence are the worst case: a level-m column of valence n·2^m is
//! ~2π·2^{-m}/(n·2^m) wide, and second derivatives of a patch of width h
//! carry rounding ~ε·|x|/h².
mod common;

use capdiv_mesh::{samples, MeshInput, PatchKind, PatchRecord};
use common::*;
use std::collections::HashMap;

struct Sample {
    patch: usize,
    edge: usize,
    k: usize,
    key: (u32, Option<u8>),
    uv: [f64; 2],
    x: [f64; 3],
    n: [f64; 3],
    gauss: f64,
    mean: f64,
}

#[derive(Default, Debug)]
struct Report {
    samples: usize,
    pairs: usize,
    position: f64,
    normal: f64,
    mean: f64,
    gauss: f64,
    uv: f64,
    boundary_edges: usize,
    partial_edges: usize,
}

fn bbox_size(m: &MeshInput) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &m.vertices {
        for c in 0..3 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    dist(lo, hi)
}

fn edge_param(edge: usize, t: f64) -> (f64, f64) {
    match edge {
        0 => (t, 0.0),
        1 => (1.0, t),
        2 => (t, 1.0),
        _ => (0.0, t),
    }
}

fn samples_of(patches: &[PatchRecord<f64>]) -> Vec<Sample> {
    let mut out = Vec::new();
    for (pi, p) in patches.iter().enumerate() {
        let g = control_grid(&p.geometry);
        let [u0, u1, v0, v1] = p.domain;
        for edge in 0..4 {
            if p.hole & (1 << edge) != 0 {
                continue;
            }
            for k in 0..=16 {
                let (s, t) = edge_param(edge, k as f64 / 16.0);
                let d = derivs(&g, s, t);
                let (n, gauss, mean) = geometry(&d);
                out.push(Sample {
                    patch: pi,
                    edge,
                    k,
                    key: (p.face, p.corner),
                    uv: [u0 + s * (u1 - u0), v0 + t * (v1 - v0)],
                    x: d[0],
                    n,
                    gauss,
                    mean,
                });
            }
        }
    }
    out
}

/// Matches samples of different patches and measures the jumps.
fn smoothness(m: &MeshInput, patches: &[PatchRecord<f64>]) -> Report {
    let size = bbox_size(m);
    let samples = samples_of(patches);
    let cell = 1e-6 * size;
    let radius = POS_TOL * size;
    let key = |x: [f64; 3]| x.map(|c| (c / cell).floor() as i64);
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (i, s) in samples.iter().enumerate() {
        grid.entry(key(s.x)).or_default().push(i);
    }
    let mut matched = vec![false; samples.len()];
    let mut r = Report {
        samples: samples.len(),
        ..Default::default()
    };
    for (i, a) in samples.iter().enumerate() {
        let c = key(a.x);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(list) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) else {
                        continue;
                    };
                    for &j in list {
                        let b = &samples[j];
                        if b.patch == a.patch || dist(a.x, b.x) > radius {
                            continue;
                        }
                        matched[i] = true;
                        if j < i {
                            continue;
                        }
                        r.pairs += 1;
                        r.position = r.position.max(dist(a.x, b.x));
                        r.normal = r.normal.max(dist(a.n, b.n));
                        let kappa = a
                            .mean
                            .abs()
                            .max(b.mean.abs())
                            .max(a.gauss.abs().sqrt())
                            .max(b.gauss.abs().sqrt())
                            .max(1.0 / size);
                        r.mean = r.mean.max((a.mean - b.mean).abs() / kappa);
                        r.gauss = r.gauss.max((a.gauss - b.gauss).abs() / (kappa * kappa));
                        if a.key == b.key {
                            let d = (a.uv[0] - b.uv[0]).abs().max((a.uv[1] - b.uv[1]).abs());
                            r.uv = r.uv.max(d);
                        }
                    }
                }
            }
        }
    }
    // Edges: the inner samples at t = k/8 (k = 1..7) all matched (interior),
    // none (boundary of the surface), or some (a crack: fail). The samples at
    // odd sixteenths of a half-size patch's edge have no partner on the big
    // edge; those at eighths always do.
    let mut per_edge: HashMap<(usize, usize), (usize, usize)> = HashMap::new();
    for (i, s) in samples.iter().enumerate() {
        if s.k % 2 == 0 && (1..16).contains(&s.k) {
            let e = per_edge.entry((s.patch, s.edge)).or_default();
            e.0 += 1;
            e.1 += usize::from(matched[i]);
        }
    }
    if std::env::var("DEBUG_EDGES").is_ok() {
        for (&(pi, e), &(total, hit)) in &per_edge {
            if hit != 0 && hit != total {
                let p = &patches[pi];
                eprintln!("patch {pi} {:?} level {} face {} dom {:?} edge {e} hole {} finer {}: {hit}/{total}", p.kind, p.level, p.face, p.domain, p.hole, p.finer);
            }
        }
    }
    for &(total, hit) in per_edge.values() {
        if hit == 0 {
            r.boundary_edges += 1;
        } else if hit != total {
            r.partial_edges += 1;
            if std::env::var("DEBUG_EDGES").is_ok() {
                eprintln!("partial: {hit}/{total}");
            }
        }
    }
    r
}

/// Sum of domain areas per (input face, corner).
fn areas(patches: &[PatchRecord<f64>]) -> HashMap<(u32, Option<u8>), f64> {
    let mut a: HashMap<(u32, Option<u8>), f64> = HashMap::new();
    for p in patches {
        let [u0, u1, v0, v1] = p.domain;
        assert!(
            u0 < u1 && v0 < v1 && u0 >= 0.0 && v0 >= 0.0 && u1 <= 1.0 && v1 <= 1.0,
            "domain {:?}",
            p.domain
        );
        *a.entry((p.face, p.corner)).or_default() += (u1 - u0) * (v1 - v0);
    }
    a
}

/// Matching radius (relative to the mesh's size): positions closer than
/// this are the same point.
const POS_TOL: f64 = 1e-9;
const NORMAL_TOL: f64 = 1e-9;
const CURV_TOL: f64 = 1e-6;

/// Plans, evaluates, checks smoothness, the boundary edge count, coverage
/// (no uncovered face, every key's area as `expected` says, every input face
/// present).
fn check(
    name: &str,
    m: &MeshInput,
    depth: u32,
    boundary_edges: usize,
    expected: &dyn Fn(u32, Option<u8>) -> f64,
) -> Report {
    let (plan, out) = surface(m, depth);
    assert!(
        plan.uncovered.is_empty(),
        "{name}: uncovered {:?}",
        plan.uncovered
    );
    let r = smoothness(m, &out.patches);
    println!(
        "{name} (depth {depth}, {} patches, {} steps): {} samples, {} pairs; worst position {:.1e}, normal {:.1e}, ΔH/κ {:.1e}, ΔK/κ² {:.1e}, Δuv {:.1e}; boundary edges {}",
        out.patches.len(),
        plan.steps.len(),
        r.samples,
        r.pairs,
        r.position,
        r.normal,
        r.mean,
        r.gauss,
        r.uv,
        r.boundary_edges
    );
    assert_eq!(
        r.partial_edges, 0,
        "{name}: edges matched only in part (a crack)"
    );
    assert_eq!(r.boundary_edges, boundary_edges, "{name}: unmatched edges");
    assert!(r.normal < NORMAL_TOL, "{name}: normal {}", r.normal);
    assert!(r.mean < CURV_TOL, "{name}: mean curvature {}", r.mean);
    assert!(r.gauss < CURV_TOL, "{name}: Gaussian curvature {}", r.gauss);
    assert!(
        r.uv < 1e-12,
        "{name}: samples of one face disagree on (u, v): {}",
        r.uv
    );
    let a = areas(&out.patches);
    let mut faces_seen = vec![false; m.faces.len()];
    let mut worst = 0.0f64;
    for (&(f, c), &area) in &a {
        faces_seen[f as usize] = true;
        let want = expected(f, c);
        worst = worst.max((area - want).abs());
        assert!(
            (area - want).abs() < 1e-12,
            "{name}: face {f} corner {c:?}: area {area}, expected {want}"
        );
    }
    assert!(
        faces_seen.iter().all(|&s| s),
        "{name}: a face without patches"
    );
    // Non-quads are tiled per corner: every corner present.
    for (f, face) in m.faces.iter().enumerate() {
        let polar = a.contains_key(&(f as u32, None));
        if face.len() != 4 && !polar {
            for c in 0..face.len() {
                assert!(
                    a.contains_key(&(f as u32, Some(c as u8))),
                    "{name}: face {f} corner {c}"
                );
            }
        }
    }
    r
}

fn quarter(depth: u32) -> f64 {
    0.25f64.powi(depth as i32)
}

/// Extraordinary vertices of a closed quad mesh (or the given set).
fn ev_holes(m: &MeshInput, ev: &[bool], depth: u32) -> impl Fn(u32, Option<u8>) -> f64 {
    let faces = m.faces.clone();
    let ev = ev.to_vec();
    move |f, c| {
        assert_eq!(c, None);
        let holes = faces[f as usize]
            .iter()
            .filter(|&&v| ev[v as usize])
            .count();
        1.0 - holes as f64 * quarter(depth)
    }
}

#[test]
fn extraordinary_disks_n3_to_12() {
    let depth = 4;
    for n in 3..=12 {
        let m = samples::extraordinary_disk(n, 3);
        let mut ev = vec![false; m.vertices.len()];
        ev[0] = n != 4;
        check(
            &format!("extraordinary_disk({n}, 3)"),
            &m,
            depth,
            2 * n * 3,
            &ev_holes(&m, &ev, depth),
        );
    }
}

#[test]
fn closed_quad_meshes_with_extraordinary_points() {
    let depth = 4;
    for (name, m) in [
        ("rounded_cube(3)", samples::rounded_cube(3)),
        ("two_beam_corner", samples::two_beam_corner()),
    ] {
        let ev: Vec<bool> = face_counts(&m).iter().map(|&c| c != 4).collect();
        check(name, &m, depth, 0, &ev_holes(&m, &ev, depth));
    }
}

/// The cube: adjacent valence-3 points, separated one level in by the
/// adaptive refinement; each input face holds 4 sector faces (its
/// quadrants), each with a hole of (2^-depth/2)².
#[test]
fn cube_after_refinement() {
    let depth = 4;
    let m = samples::cube();
    check("cube", &m, depth, 0, &|_, c| {
        assert_eq!(c, None);
        1.0 - 4.0 * quarter(depth + 1)
    });
}

/// Triangles and pentagons: caps two levels in. A non-quad face is tiled
/// per corner sub-quad (its own square); at the second level its sector
/// faces are the sub-quad's quadrants: a hole of (2^-depth/2)² at the face centre (valence
/// = face size ≠ 4) and one at the input vertex if its valence ≠ 4. An input
/// quad's sector faces are 1/4 of its side: holes (2^-depth/4)² at its
/// extraordinary corners.
#[test]
fn triangles_and_pentagons_caps_two_levels_in() {
    let depth = 3;
    let m = samples::triangle_and_pentagon_mesh();
    let val = face_counts(&m);
    let faces = m.faces.clone();
    let r = check("triangle_and_pentagon_mesh", &m, depth, 0, &|f, c| {
        let face = &faces[f as usize];
        match c {
            None => {
                assert_eq!(face.len(), 4);
                let holes = face.iter().filter(|&&v| val[v as usize] != 4).count();
                1.0 - holes as f64 * quarter(depth + 2)
            }
            Some(c) => {
                assert_ne!(face.len(), 4);
                let holes = 1 + usize::from(val[face[c as usize] as usize] != 4);
                1.0 - holes as f64 * quarter(depth + 1)
            }
        }
    });
    assert!(r.pairs > 0);
}

/// Polar caps (no refinement): a fan triangle is covered in polar
/// coordinates `u ∈ [2·2^-depth, 1]`, `v ∈ [0, 1]` (the last hole is
/// `u < 2·2^-depth`), the quads between links 1 and 2 by the level-1 ring
/// entirely, every other face by its B-spline patch.
fn polar_area(m: &MeshInput, depth: u32) -> impl Fn(u32, Option<u8>) -> f64 {
    let tri: Vec<bool> = m.faces.iter().map(|f| f.len() == 3).collect();
    move |f, c| {
        assert_eq!(c, None);
        if tri[f as usize] {
            1.0 - 2.0 * 0.5f64.powi(depth as i32)
        } else {
            1.0
        }
    }
}

#[test]
fn poles_of_valence_3_to_64() {
    for (n, depth) in [(3, 6), (5, 6), (8, 6), (16, 5), (64, 4)] {
        let g = samples::globe(n, 9);
        check(
            &format!("globe({n}, 9)"),
            &g,
            depth,
            0,
            &polar_area(&g, depth),
        );
        let d = samples::pole_disk(n, 4);
        check(
            &format!("pole_disk({n}, 4)"),
            &d,
            depth,
            n,
            &polar_area(&d, depth),
        );
    }
}

/// A pole whose link 2 is the boundary (link 3 made of phantom points).
#[test]
fn pole_disk_with_phantom_link3() {
    let depth = 4;
    for n in [4, 7] {
        let d = samples::pole_disk(n, 2);
        // The boundary quads are the cap's level-1 ring: two columns each.
        check(
            &format!("pole_disk({n}, 2)"),
            &d,
            depth,
            2 * n,
            &polar_area(&d, depth),
        );
    }
}

#[test]
fn regular_meshes_open_and_closed() {
    check(
        "grid(5, 4)",
        &samples::grid(5, 4),
        2,
        2 * (5 + 4),
        &|_, _| 1.0,
    );
    check("torus(6, 5)", &samples::torus(6, 5), 2, 0, &|_, _| 1.0);
}

/// The Catmull-Clark cap's centre is only G¹: the normal at the ring corners
/// nearest the centre converges to the cap's normal (the limit tangents'
/// normal), at the subdominant eigenvalue's rate, while the curvature there
/// does not settle (for n > 4 it grows without bound: the subsubdominant
/// eigenvalue exceeds λ²).
#[test]
fn catmull_clark_centre_normal_converges_curvature_does_not() {
    for n in [6, 7, 11] {
        let m = samples::extraordinary_disk(n, 3);
        let mut angles = Vec::new();
        let mut curv = Vec::new();
        for depth in 1..=8 {
            let (_, out) = surface(&m, depth);
            let cap = out.caps.iter().find(|c| c.vertex == Some(0)).unwrap();
            let nrm = cap.normal.expect("normal").0;
            let (mut angle, mut hmin, mut hmax) = (0.0f64, f64::INFINITY, 0.0f64);
            for p in out
                .patches
                .iter()
                .filter(|p| p.kind == PatchKind::CatmullClark && p.level == depth && p.hole != 0)
            {
                let g = control_grid(&p.geometry);
                let k = g.len() - 1;
                // The corner nearest the limit point.
                let (s, t) = [(0, 0), (k, 0), (0, k), (k, k)]
                    .into_iter()
                    .min_by(|a, b| {
                        dist(g[a.0][a.1], cap.limit.0).total_cmp(&dist(g[b.0][b.1], cap.limit.0))
                    })
                    .unwrap();
                let d = derivs(&g, (s / k) as f64, (t / k) as f64);
                let (pn, _, h) = geometry(&d);
                angle = angle.max(dist(pn, nrm));
                hmin = hmin.min(h.abs());
                hmax = hmax.max(h.abs());
            }
            angles.push(angle);
            curv.push((hmin, hmax));
        }
        println!(
            "CC centre n={n}: |normal − cap normal| by depth {:?}",
            angles
                .iter()
                .map(|a| format!("{a:.1e}"))
                .collect::<Vec<_>>()
        );
        println!(
            "CC centre n={n}: |H| range over the nearest corners {:?}",
            curv.iter()
                .map(|(a, b)| format!("{a:.2}..{b:.2}"))
                .collect::<Vec<_>>()
        );
        assert!(angles.windows(2).all(|w| w[1] < w[0]), "n={n}: {angles:?}");
        // Slowly for high valence (ratio per level measured 0.70 at n = 6,
        // 0.77 at n = 7, 0.89 at n = 11).
        assert!(angles[7] < 0.4 * angles[0], "n={n}: {angles:?}");
        // The largest |H| among the nearest corners keeps growing.
        assert!(curv[7].1 > 1.3 * curv[3].1, "n={n}: {curv:?}");
    }
}
