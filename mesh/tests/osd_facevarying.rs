//! Face-varying UVs ([`capdiv_mesh::FaceVarying`]) against OpenSubdiv 3.5
//! (tests/osd): its face-varying patch table with `FVAR_LINEAR_ALL`
//! evaluated at the same ptex points, on meshes with triangles, pentagons,
//! boundaries, extraordinary vertices and UV seams everywhere (every face
//! corner its own UV), and at sample points of every patch capdiv emits
//! (regular patches and EG / Catmull-Clark cap rings, through their
//! records' domains).
//!
//! Tolerance 1e-12 with UVs of size ≤ 1: both sides form the same bilinear
//! combinations of the same corner values; OpenSubdiv reaches them through
//! up to `isolation` levels of linear refinement (one midpoint or centroid
//! per level, each a few ulps of 1) and its patch basis, capdiv in one step,
//! so they differ by rounding only (≈ 1e-15 measured, see
//! `fvar_linear_all_matches_at_ptex_points`); a wrong sub-face, corner order
//! or orientation errs by ≥ 1e-2 on these UVs.

mod common;

#[path = "osd/mod.rs"]
mod osd;

use capdiv_mesh::{
    samples, CapRecord, Evaluator, FaceVarying, MeshInput, PatchKind, PatchRecord, SurfaceSink,
};
use osd::{Job, Query};

const TOL: f64 = 1e-12;

/// Deterministic pseudo-random numbers in [0, 1) (a small LCG).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `m` with a distinct random UV at every face corner: seams along every
/// edge, so any mix-up between faces, corners or sub-faces shows.
fn with_random_uvs(m: MeshInput, seed: u64) -> MeshInput {
    let mut rng = Rng(seed);
    let mut uvs = Vec::new();
    let mut uv_faces = Vec::new();
    for f in &m.faces {
        let mut list = Vec::new();
        for _ in f {
            list.push(uvs.len() as u32);
            uvs.push([rng.next(), rng.next()]);
        }
        uv_faces.push(list);
    }
    m.with_uvs(uvs, uv_faces)
}

fn meshes() -> Vec<(&'static str, MeshInput)> {
    vec![
        (
            "triangle-and-pentagon",
            with_random_uvs(samples::triangle_and_pentagon_mesh(), 1),
        ),
        ("feature-mix", with_random_uvs(samples::feature_mix(120), 2)),
        (
            "extraordinary-disk",
            with_random_uvs(samples::extraordinary_disk(5, 3), 3),
        ),
        ("cube", with_random_uvs(samples::cube(), 4)),
    ]
}

fn max_err(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).abs().max((a[1] - b[1]).abs())
}

#[test]
fn fvar_linear_all_matches_at_ptex_points() {
    let mut worst = 0.0f64;
    let mut compared = 0;
    for (name, m) in meshes() {
        let fv = FaceVarying::without_plan(&m).unwrap().unwrap();
        let mut rng = Rng(99);
        let mut queries = Vec::new();
        for (f, face) in m.faces.iter().enumerate() {
            let corners: Vec<Option<u8>> = if face.len() == 4 {
                vec![None]
            } else {
                (0..face.len() as u8).map(Some).collect()
            };
            for c in corners {
                for (u, v) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
                    .into_iter()
                    .chain((0..4).map(|_| (rng.next(), rng.next())))
                {
                    queries.push(Query {
                        face: f as u32,
                        corner: c,
                        u,
                        v,
                    });
                }
            }
        }
        let mut job = Job::new(&m);
        job.queries = queries.clone();
        let (_, _, uvs) = osd::run_with_uvs(&job);
        assert_eq!(uvs.len(), queries.len());
        for (q, want) in queries.iter().zip(&uvs) {
            let Some(want) = want else {
                panic!("{name}: OpenSubdiv has no patch at {q:?}");
            };
            let got = fv.at(q.face, q.corner, q.u, q.v);
            let e = max_err(got, *want);
            worst = worst.max(e);
            compared += 1;
            assert!(e < TOL, "{name} {q:?}: capdiv {got:?}, OpenSubdiv {want:?}");
        }
    }
    println!("fvar at ptex points: {compared} compared, max error {worst:e}");
}

#[derive(Default)]
struct Patches(Vec<PatchRecord<f64>>, Vec<CapRecord<f64>>);
impl SurfaceSink<f64> for Patches {
    fn patch(&mut self, p: &PatchRecord<f64>) {
        self.0.push(p.clone());
    }
    fn cap(&mut self, c: &CapRecord<f64>) {
        self.1.push(c.clone());
    }
}

/// The hole fans of the caps' last rings end at the cap's centre: its UV
/// in the patch's face is the face's UV at that input vertex (or, for the
/// centre of a face that is not a quad, the centroid of the face's UVs).
#[test]
fn hole_points_take_the_uv_of_the_caps_centre_in_the_patchs_face() {
    let mut checked = 0;
    for (name, m) in meshes() {
        for depth in [1, 3] {
            let plan = common::plan(&m, depth);
            let fv = FaceVarying::new(&m, &plan).unwrap().unwrap();
            let mut sink = Patches::default();
            Evaluator::<f64>::new(&plan)
                .unwrap()
                .evaluate(&m.vertices, &mut sink)
                .unwrap();
            for p in sink
                .0
                .iter()
                .filter(|p| p.hole != 0 && p.kind != PatchKind::C2ps)
            {
                let Some(cap) = p.cap.and_then(|c| sink.1.iter().find(|r| r.index == c)) else {
                    continue;
                };
                let f = p.face as usize;
                let face = &m.faces[f];
                let uv = |k: usize| m.uvs[m.uv_faces[f][k] as usize];
                let want = match cap.vertex {
                    Some(v) => uv(face.iter().position(|&x| x == v).expect("centre in face")),
                    None => {
                        let n = face.len() as f64;
                        let s = (0..face.len())
                            .fold([0.0, 0.0], |a, k| [a[0] + uv(k)[0], a[1] + uv(k)[1]]);
                        [s[0] / n, s[1] / n]
                    }
                };
                let got = fv.patch(p).hole;
                assert!(
                    max_err(got, want) < TOL,
                    "{name} depth {depth}: {got:?} vs {want:?}"
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 0);
}

#[test]
fn every_patch_carries_opensubdivs_uvs_over_its_domain() {
    let mut worst = 0.0f64;
    let mut kinds = std::collections::BTreeSet::new();
    for (name, m) in meshes() {
        let plan = common::plan(&m, 3);
        let fv = FaceVarying::new(&m, &plan).unwrap().unwrap();
        let mut sink = Patches::default();
        Evaluator::<f64>::new(&plan)
            .unwrap()
            .evaluate(&m.vertices, &mut sink)
            .unwrap();
        // Patch parameters: the corners and an inner point.
        let params = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.3, 0.7)];
        let mut queries = Vec::new();
        let mut ours = Vec::new();
        for p in sink.0.iter().filter(|p| p.kind != PatchKind::C2ps) {
            kinds.insert(p.kind);
            let uv = fv.patch(p);
            let [u0, u1, v0, v1] = p.domain;
            for &(a, b) in &params {
                let (s, t) = (u0 + a * (u1 - u0), v0 + b * (v1 - v0));
                let corner = if m.faces[p.face as usize].len() == 4 {
                    None
                } else {
                    Some(p.corner.unwrap_or(0))
                };
                queries.push(Query {
                    face: p.face,
                    corner,
                    u: s,
                    v: t,
                });
                ours.push(uv.at(a, b));
            }
        }
        let mut job = Job::new(&m);
        job.queries = queries.clone();
        let (_, _, uvs) = osd::run_with_uvs(&job);
        for ((q, got), want) in queries.iter().zip(&ours).zip(&uvs) {
            let want = want.unwrap_or_else(|| panic!("{name}: no OpenSubdiv patch at {q:?}"));
            let e = max_err(*got, want);
            worst = worst.max(e);
            assert!(e < TOL, "{name} {q:?}: capdiv {got:?}, OpenSubdiv {want:?}");
        }
    }
    // Regular patches and cap rings were both compared.
    assert!(
        kinds.contains(&PatchKind::Regular) && kinds.len() > 1,
        "{kinds:?}"
    );
    println!("fvar over patches: max error {worst:e}");
}

/// C²PS patches in the triangles around a pole carry the triangle's UVs in
/// polar coordinates (pole at r = 0, first spoke towards the triangle's next
/// corner at v = 0): with UVs equal to the vertices' `(x, y)` on a disk
/// around the pole, each polar patch corner's UV lies near the `(x, y)` of
/// the surface point there — far nearer than the neighbouring spoke.
#[test]
fn polar_patches_take_their_triangles_uvs_along_the_spokes() {
    let m = samples::pole_disk(8, 3);
    let uvs: Vec<[f64; 2]> = m.vertices.iter().map(|p| [p[0], p[1]]).collect();
    let faces = m.faces.clone();
    let m = m.with_uvs(uvs, faces);
    let plan = common::plan(&m, 3);
    assert!(!plan.polar.is_empty(), "the disk has a pole");
    let fv = FaceVarying::new(&m, &plan).unwrap().unwrap();
    let mut sink = Patches::default();
    Evaluator::<f64>::new(&plan)
        .unwrap()
        .evaluate(&m.vertices, &mut sink)
        .unwrap();
    let mut worst = 0.0f64;
    let mut swapped = 0.0f64;
    let mut polar = 0;
    for p in sink.0.iter().filter(|p| p.kind == PatchKind::C2ps) {
        let capdiv_mesh::tessellate::PatchGeometry::Cubic(g) = &p.geometry else {
            panic!("polar patches are bicubic");
        };
        let uv = fv.patch(p);
        let corners = [
            g.points[0][0],
            g.points[3][0],
            g.points[3][3],
            g.points[0][3],
        ];
        for (c, q) in uv.corners.iter().zip(corners) {
            worst = worst.max(max_err(*c, [q.0[0], q.0[1]]));
        }
        // The same corners with the spokes exchanged (v = 0 towards the
        // previous corner): what a wrong spoke order would give.
        {
            let f = &m.faces[p.face as usize];
            if f.len() == 3 {
                let pole = plan.polar[p.cap.unwrap() as usize].vertex;
                let k = f.iter().position(|&x| x == pole).unwrap();
                let at = |i: usize| [m.vertices[f[i] as usize][0], m.vertices[f[i] as usize][1]];
                let (pp, nx, pv) = (at(k), at((k + 1) % 3), at((k + 2) % 3));
                let [r0, r1, v0, v1] = p.domain;
                let sw = |r: f64, v: f64| {
                    [0, 1].map(|d| pp[d] + r * ((1.0 - v) * pv[d] + v * nx[d] - pp[d]))
                };
                let rect = [[r0, v0], [r1, v0], [r1, v1], [r0, v1]];
                for (c, q) in rect.iter().zip(corners) {
                    swapped = swapped.max(max_err(sw(c[0], c[1]), [q.0[0], q.0[1]]));
                }
            }
        }
        polar += 1;
    }
    assert!(polar > 0);
    // The C²PS surface is not the linear image of its polar domain (its
    // rings bulge towards the links' circles, its radii are not linear in
    // r), so UV and (x, y) differ by a fraction of the 1-link's radius 1/3
    // (measured 0.065); exchanged spokes put the UVs a spoke off (measured
    // 0.236; neighbouring spokes are 2·sin(π/8)/3 ≈ 0.255 apart).
    println!("polar: {polar} patches, max |uv − xy| {worst:e}, spokes exchanged {swapped:e}");
    assert!(worst < 0.1 && worst < swapped / 3.0, "{worst} vs {swapped}");
}
