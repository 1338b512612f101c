//! Test helpers written independently of the crate: Bernstein evaluation of a
//! tensor Bézier patch with derivatives to second order, the curvatures they
//! give, and a literal uniform cubic B-spline basis.
#![allow(dead_code)]

/// Binomial coefficient.
fn binom(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// Bernstein polynomials of degree `d` at `t` and their first and second
/// derivatives, by the textbook formula.
fn bernstein(d: usize, t: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let b = |d: usize, i: isize| -> f64 {
        if i < 0 || i as usize > d {
            0.0
        } else {
            let i = i as usize;
            binom(d, i) * t.powi(i as i32) * (1.0 - t).powi((d - i) as i32)
        }
    };
    let df = d as f64;
    let v: Vec<f64> = (0..=d).map(|i| b(d, i as isize)).collect();
    let d1: Vec<f64> = (0..=d as isize)
        .map(|i| {
            if d == 0 {
                0.0
            } else {
                df * (b(d - 1, i - 1) - b(d - 1, i))
            }
        })
        .collect();
    let d2: Vec<f64> = (0..=d as isize)
        .map(|i| {
            if d < 2 {
                0.0
            } else {
                df * (df - 1.0) * (b(d - 2, i - 2) - 2.0 * b(d - 2, i - 1) + b(d - 2, i))
            }
        })
        .collect();
    (v, d1, d2)
}

/// Position and derivatives `[x, xu, xv, xuu, xuv, xvv]` of the Bézier patch
/// `pts[i][j]` (`i` along u) at `(u, v)`.
pub fn derivs(pts: &[Vec<[f64; 3]>], u: f64, v: f64) -> [[f64; 3]; 6] {
    let d = pts.len() - 1;
    let (bu, du, ddu) = bernstein(d, u);
    let (bv, dv, ddv) = bernstein(d, v);
    let mut out = [[0.0; 3]; 6];
    for i in 0..=d {
        for j in 0..=d {
            let w = [
                bu[i] * bv[j],
                du[i] * bv[j],
                bu[i] * dv[j],
                ddu[i] * bv[j],
                du[i] * dv[j],
                bu[i] * ddv[j],
            ];
            for (o, wk) in out.iter_mut().zip(w) {
                for c in 0..3 {
                    o[c] += wk * pts[i][j][c];
                }
            }
        }
    }
    out
}

pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}
pub fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    norm(sub(a, b))
}

/// Unit normal, Gaussian and mean curvature from the derivatives.
pub fn geometry(d: &[[f64; 3]; 6]) -> ([f64; 3], f64, f64) {
    let n = cross(d[1], d[2]);
    let l = norm(n);
    let n = [n[0] / l, n[1] / l, n[2] / l];
    let (e, f, g) = (dot(d[1], d[1]), dot(d[1], d[2]), dot(d[2], d[2]));
    let (l2, m2, n2) = (dot(n, d[3]), dot(n, d[4]), dot(n, d[5]));
    let det = e * g - f * f;
    let k = (l2 * n2 - m2 * m2) / det;
    let h = (e * n2 - 2.0 * f * m2 + g * l2) / (2.0 * det);
    (n, k, h)
}

/// Uniform cubic B-spline basis on [0, 1] (literal polynomials).
pub fn bspline_basis(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [
        s * s * s / 6.0,
        (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
        (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
        t * t * t / 6.0,
    ]
}

// ---------------------------------------------------------------------------
// Surface collection and evaluation helpers (mesh/tests/surface_*.rs).

use capdiv_mesh::tessellate::PatchGeometry;
use capdiv_mesh::{Evaluator, MeshInput, PatchRecord, PlanOptions, SurfacePlan, Topology};

/// A sink that keeps every patch and cap.
pub type Collect<R> = capdiv_mesh::sinks::CollectSurface<R>;

/// The options of a plan to `depth`: every cap Catmull-Clark when
/// `catmull_clark`, no EG tables.
pub fn plan_options(depth: u32, catmull_clark: bool) -> PlanOptions<'static> {
    PlanOptions {
        depth,
        catmull_clark,
        ..Default::default()
    }
}

/// `SurfacePlan::for_mesh` at `depth` with the default caps (the test fails
/// when the mesh is refused).
pub fn plan(mesh: &MeshInput, depth: u32) -> SurfacePlan<'static> {
    plan_with(mesh, depth, false)
}

/// [`plan`], every cap Catmull-Clark when `catmull_clark`.
pub fn plan_with(mesh: &MeshInput, depth: u32, catmull_clark: bool) -> SurfacePlan<'static> {
    SurfacePlan::for_mesh(mesh, plan_options(depth, catmull_clark)).expect("plan")
}

/// Plan (at `depth`) and evaluate a mesh in f64.
pub fn surface(mesh: &MeshInput, depth: u32) -> (SurfacePlan<'static>, Collect<f64>) {
    let t = Topology::new(mesh).expect("valid mesh");
    let plan = SurfacePlan::new(&t, plan_options(depth, false)).expect("plan");
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    let mut c = Collect::default();
    ev.evaluate(&mesh.vertices, &mut c).expect("evaluate");
    (plan, c)
}

/// The Bézier control grid of a patch as plain f64 rows (`[i][j]`, `i` along u).
pub fn control_grid(g: &PatchGeometry<f64>) -> Vec<Vec<[f64; 3]>> {
    match g {
        PatchGeometry::Cubic(p) => p
            .points
            .iter()
            .map(|r| r.iter().map(|q| q.0).collect())
            .collect(),
        PatchGeometry::Quartic(p) => p
            .points
            .iter()
            .map(|r| r.iter().map(|q| q.0).collect())
            .collect(),
    }
}

/// Same for an f32 patch, widened.
pub fn control_grid32(g: &PatchGeometry<f32>) -> Vec<Vec<[f64; 3]>> {
    let w = |q: &capdiv::Point3<f32>| [q.0[0] as f64, q.0[1] as f64, q.0[2] as f64];
    match g {
        PatchGeometry::Cubic(p) => p.points.iter().map(|r| r.iter().map(w).collect()).collect(),
        PatchGeometry::Quartic(p) => p.points.iter().map(|r| r.iter().map(w).collect()).collect(),
    }
}

/// A Bézier control grid seen under the 8 symmetries of the square
/// (transposition and reversals): every way the same patch can be stored.
pub fn orientations(g: &[Vec<[f64; 3]>]) -> Vec<Vec<Vec<[f64; 3]>>> {
    let k = g.len();
    let mut out = Vec::new();
    for swap in [false, true] {
        for ri in [false, true] {
            for rj in [false, true] {
                let mut h = vec![vec![[0.0; 3]; k]; k];
                for (i, row) in h.iter_mut().enumerate() {
                    for (j, p) in row.iter_mut().enumerate() {
                        let a = if ri { k - 1 - i } else { i };
                        let b = if rj { k - 1 - j } else { j };
                        *p = if swap { g[b][a] } else { g[a][b] };
                    }
                }
                out.push(h);
            }
        }
    }
    out
}

/// Largest distance between corresponding control points (∞ on a size
/// mismatch).
pub fn grid_distance(a: &[Vec<[f64; 3]>], b: &[Vec<[f64; 3]>]) -> f64 {
    if a.len() != b.len() {
        return f64::INFINITY;
    }
    a.iter()
        .zip(b)
        .flat_map(|(r, s)| r.iter().zip(s).map(|(p, q)| dist(*p, *q)))
        .fold(0.0, f64::max)
}

/// Centroid of a control grid (the same under every orientation).
pub fn grid_centroid(g: &[Vec<[f64; 3]>]) -> [f64; 3] {
    let mut c = [0.0; 3];
    let mut k = 0.0;
    for p in g.iter().flatten() {
        for a in 0..3 {
            c[a] += p[a];
        }
        k += 1.0;
    }
    [c[0] / k, c[1] / k, c[2] / k]
}

/// Matches two lists of patches as sets, up to orientation: for each patch of
/// `want`, the closest patch of `got` (by centroid, then the best of its 8
/// orientations). Returns the worst control-point distance; panics if the
/// sizes differ. Each `got` patch is used at most once.
pub fn match_patch_sets(want: &[Vec<Vec<[f64; 3]>>], got: &[Vec<Vec<[f64; 3]>>]) -> f64 {
    assert_eq!(want.len(), got.len(), "patch counts differ");
    let centroids: Vec<[f64; 3]> = got.iter().map(|g| grid_centroid(g)).collect();
    let mut used = vec![false; got.len()];
    let mut worst = 0.0f64;
    for w in want {
        let c = grid_centroid(w);
        // Candidates: the few closest centroids not yet used.
        let mut order: Vec<usize> = (0..got.len()).filter(|&i| !used[i]).collect();
        order.sort_by(|&a, &b| dist(centroids[a], c).total_cmp(&dist(centroids[b], c)));
        let mut best = (f64::INFINITY, usize::MAX);
        for &i in order.iter().take(4) {
            for o in orientations(&got[i]) {
                let d = grid_distance(w, &o);
                if d < best.0 {
                    best = (d, i);
                }
            }
        }
        used[best.1] = true;
        worst = worst.max(best.0);
    }
    worst
}

/// Number of faces around each vertex of a mesh.
pub fn face_counts(m: &MeshInput) -> Vec<usize> {
    let mut c = vec![0; m.vertices.len()];
    for f in &m.faces {
        for &v in f {
            c[v as usize] += 1;
        }
    }
    c
}

/// Closedness and smoothness across patch edges: every patch edge sample at
/// t = k/8 (hole edges excluded) is met by another patch's sample at
/// sixteenths (an edge met by two half-size patches has their eighths at its
/// sixteenths); over all pairs, the worst difference of unit normals, of H
/// relative to the local curvature scale κ and of K relative to κ².
/// Returns (pairs, worst normal, worst ΔH/κ, worst ΔK/κ²).
pub fn closed_and_smooth(name: &str, patches: &[PatchRecord<f64>]) -> (usize, f64, f64, f64) {
    use std::collections::HashMap;
    struct S {
        patch: usize,
        x: [f64; 3],
        n: [f64; 3],
        k: f64,
        h: f64,
        eighth: bool,
    }
    let mut samples = Vec::new();
    for (pi, p) in patches.iter().enumerate() {
        let g = control_grid(&p.geometry);
        for edge in 0..4 {
            if p.hole & (1 << edge) != 0 {
                continue;
            }
            for i in 0..=16u32 {
                let t = i as f64 / 16.0;
                let (u, v) = match edge {
                    0 => (t, 0.0),
                    1 => (1.0, t),
                    2 => (t, 1.0),
                    _ => (0.0, t),
                };
                let d = derivs(&g, u, v);
                let (n, k, h) = geometry(&d);
                samples.push(S {
                    patch: pi,
                    x: d[0],
                    n,
                    k,
                    h,
                    eighth: i.is_multiple_of(2) && (1..16).contains(&i),
                });
            }
        }
    }
    let cell = 1e-6;
    let key = |x: [f64; 3]| x.map(|c| (c / cell).floor() as i64);
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (i, s) in samples.iter().enumerate() {
        grid.entry(key(s.x)).or_default().push(i);
    }
    let (mut pairs, mut wn, mut wh, mut wk) = (0, 0.0f64, 0.0f64, 0.0f64);
    for a in &samples {
        let c = key(a.x);
        let mut found = false;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for &j in grid
                        .get(&[c[0] + dx, c[1] + dy, c[2] + dz])
                        .into_iter()
                        .flatten()
                    {
                        let b = &samples[j];
                        if b.patch == a.patch || dist(a.x, b.x) > 1e-9 {
                            continue;
                        }
                        found = true;
                        pairs += 1;
                        let kappa = a.h.abs().max(b.h.abs()).max(a.k.abs().sqrt()).max(1.0);
                        wn = wn.max(dist(a.n, b.n));
                        wh = wh.max((a.h - b.h).abs() / kappa);
                        wk = wk.max((a.k - b.k).abs() / (kappa * kappa));
                    }
                }
            }
        }
        assert!(
            found || !a.eighth,
            "{name}: edge sample {:?} has no partner: not closed",
            a.x
        );
    }
    println!("{name}: {pairs} pairs, worst normal {wn:.1e}, ΔH/κ {wh:.1e}, ΔK/κ² {wk:.1e}");
    (pairs, wn, wh, wk)
}

// ---------------------------------------------------------------------------
// Coverage of input faces by a surface's patches and holes
// (mesh/tests/adaptive_surface.rs, mesh/tests/tagged_step.rs).

/// Plans `m` with its tags (`SurfacePlan::for_mesh`, at `depth`, every cap
/// Catmull-Clark when `catmull_clark`), checks that no face is uncovered and
/// evaluates it in f64.
pub fn plan_and_evaluate(
    m: &MeshInput,
    depth: u32,
    catmull_clark: bool,
) -> (SurfacePlan<'static>, Collect<f64>) {
    let plan = plan_with(m, depth, catmull_clark);
    assert!(plan.uncovered.is_empty(), "uncovered {:?}", plan.uncovered);
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    let mut c = Collect::default();
    ev.evaluate(&m.vertices, &mut c).expect("evaluate");
    (plan, c)
}

/// Area scale of an affine chart map.
pub fn det(m: &capdiv_mesh::chart::Affine) -> f64 {
    (m.du[0] * m.dv[1] - m.du[1] * m.dv[0]).abs()
}

/// Per input face (per corner of a face that is neither a quad nor a polar
/// triangle), the patches' domains plus the holes left for the last rings
/// of caps and of the adaptive refinement add up to the face (0 for a hole:
/// a tagged one, or one of `holes`). An EG or Catmull-Clark cap's hole is
/// the central `2^-depth` square of each sector; a C²PS cap's hole is
/// `u < 2^(1 − depth − prior_steps)` of each triangle's polar square.
pub fn check_coverage(
    name: &str,
    m: &MeshInput,
    holes: &[u32],
    plan: &SurfacePlan<'_>,
    c: &Collect<f64>,
) {
    let mut area: std::collections::HashMap<(u32, Option<u8>), f64> = Default::default();
    for p in &c.patches {
        let [u0, u1, v0, v1] = p.domain;
        *area.entry((p.face, p.corner)).or_default() += (u1 - u0) * (v1 - v0);
    }
    for h in &plan.last_holes {
        *area.entry((h.face, h.corner)).or_default() += det(&h.map);
    }
    let depth = plan.options.depth as i32;
    let side = 0.5f64.powi(depth);
    for e in &plan.extraordinary {
        for s in &e.sectors {
            *area.entry((s.face, s.corner)).or_default() += det(&s.map) * side * side;
        }
    }
    for p in &plan.polar {
        let mut tri = p.triangles.clone();
        tri.sort_unstable();
        tri.dedup();
        for t in tri {
            *area.entry((t, None)).or_default() += 0.5f64.powi(depth + p.prior_steps as i32 - 1);
        }
    }
    let polar: Vec<u32> = plan
        .polar
        .iter()
        .flat_map(|p| p.triangles.clone())
        .collect();
    for (f, face) in m.faces.iter().enumerate() {
        let want = if m.tags.holes.contains(&(f as u32)) || holes.contains(&(f as u32)) {
            0.0
        } else {
            1.0
        };
        let parts: Vec<Option<u8>> = if face.len() == 4 || polar.contains(&(f as u32)) {
            vec![None]
        } else {
            (0..face.len() as u8).map(Some).collect()
        };
        for corner in parts {
            let a = area.get(&(f as u32, corner)).copied().unwrap_or(0.0);
            assert!(
                (a - want).abs() <= 1e-12,
                "{name}: face {f} corner {corner:?} covered {a}, want {want}"
            );
        }
    }
}
