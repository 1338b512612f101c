//! Texture coordinates through the surface on generated checkerboard-textured
//! meshes: a torus whose UVs tile `[0, 1]²` one input face per checker
//! square (seams where u and v wrap), and a cube whose faces are the six
//! squares of a 3×2 atlas (every edge a seam; EG caps at the corners).
//!
//! Checked: every patch's corner UVs are the bilinear interpolation of its
//! input face's corner UVs at the patch's domain corners; the tessellation
//! keeps the seams (a position on a seam is two vertices, with different
//! UVs) and changes nothing else (merged across the seams it is the
//! tessellation without UVs); each output face lies in its input face's
//! checker square; the OBJ text carries the same UVs.

mod common;

use capdiv_mesh::tessellate::{tessellate, write_obj, Tessellation};
use capdiv_mesh::{
    samples, CapRecord, Evaluator, FaceVarying, MeshInput, PatchKind, PatchRecord, SurfaceSink,
};

const NU: usize = 8;
const NV: usize = 6;

/// The torus with UV `(i/NU, j/NV)` at grid corner `(i, j)`, `i = NU` and
/// `j = NV` kept apart from 0 (the wrap seams).
fn checker_torus() -> MeshInput {
    let m = samples::torus(NU, NV);
    let uv_at = |i: usize, j: usize| (i * (NV + 1) + j) as u32;
    let mut uvs = Vec::new();
    for i in 0..=NU {
        for j in 0..=NV {
            uvs.push([i as f64 / NU as f64, j as f64 / NV as f64]);
        }
    }
    // samples::torus: face (i, j) is [at(i,j), at(i+1,j), at(i+1,j+1), at(i,j+1)].
    let mut uv_faces = Vec::new();
    for i in 0..NU {
        for j in 0..NV {
            uv_faces.push(vec![
                uv_at(i, j),
                uv_at(i + 1, j),
                uv_at(i + 1, j + 1),
                uv_at(i, j + 1),
            ]);
        }
    }
    m.with_uvs(uvs, uv_faces)
}

/// The cube with face `f` on square `(f mod 3, f div 3)` of a 3×2 atlas.
fn atlas_cube() -> MeshInput {
    let m = samples::cube();
    let mut uvs = Vec::new();
    let mut uv_faces = Vec::new();
    for (f, face) in m.faces.iter().enumerate() {
        assert_eq!(face.len(), 4);
        let (x, y) = ((f % 3) as f64, (f / 3) as f64);
        let mut list = Vec::new();
        for c in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
            list.push(uvs.len() as u32);
            uvs.push([(x + c[0]) / 3.0, (y + c[1]) / 2.0]);
        }
        uv_faces.push(list);
    }
    m.with_uvs(uvs, uv_faces)
}

/// Face `f`'s checker square `[u0, u1] × [v0, v1]` (the box of its UVs).
fn square(m: &MeshInput, f: usize) -> [f64; 4] {
    let mut b = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    for &t in &m.uv_faces[f] {
        let uv = m.uvs[t as usize];
        b = [
            b[0].min(uv[0]),
            b[1].max(uv[0]),
            b[2].min(uv[1]),
            b[3].max(uv[1]),
        ];
    }
    b
}

#[derive(Default)]
struct Collect(Vec<PatchRecord<f64>>);
impl SurfaceSink<f64> for Collect {
    fn patch(&mut self, p: &PatchRecord<f64>) {
        self.0.push(p.clone());
    }
    fn cap(&mut self, _: &CapRecord<f64>) {}
}

fn surface(m: &MeshInput) -> (Vec<PatchRecord<f64>>, FaceVarying) {
    let plan = common::plan(m, 3);
    let fv = FaceVarying::new(m, &plan).unwrap().unwrap();
    let mut c = Collect::default();
    Evaluator::<f64>::new(&plan)
        .unwrap()
        .evaluate(&m.vertices, &mut c)
        .unwrap();
    (c.0, fv)
}

fn tess(patches: &[PatchRecord<f64>], fv: Option<&FaceVarying>) -> Tessellation<f64> {
    tessellate(
        patches.iter().map(|p| {
            let record = PatchRecord {
                uv: fv.map(|fv| fv.patch(p)),
                ..p.clone()
            };
            (record, p.face)
        }),
        3,
        1e-9,
    )
}

fn meshes() -> [(&'static str, MeshInput); 2] {
    [("torus", checker_torus()), ("cube", atlas_cube())]
}

#[test]
fn patch_corners_carry_the_bilinear_interpolation_of_their_faces_uvs() {
    for (name, m) in meshes() {
        let (patches, fv) = surface(&m);
        let mut kinds = std::collections::BTreeSet::new();
        for p in &patches {
            kinds.insert(p.kind);
            let f = p.face as usize;
            let c: Vec<[f64; 2]> = m.uv_faces[f].iter().map(|&t| m.uvs[t as usize]).collect();
            let [u0, u1, v0, v1] = p.domain;
            let uv = fv.patch(p);
            for (k, (s, t)) in [(u0, v0), (u1, v0), (u1, v1), (u0, v1)]
                .into_iter()
                .enumerate()
            {
                let want: [f64; 2] = std::array::from_fn(|d| {
                    (1.0 - s) * (1.0 - t) * c[0][d]
                        + s * (1.0 - t) * c[1][d]
                        + s * t * c[2][d]
                        + (1.0 - s) * t * c[3][d]
                });
                // Same products, possibly summed in another order: a few ulps.
                for (got, want) in uv.corners[k].iter().zip(want) {
                    assert!(
                        (got - want).abs() < 1e-15,
                        "{name}: face {f} domain {:?} corner {k}",
                        p.domain
                    );
                }
            }
        }
        assert_ne!(
            kinds.contains(&PatchKind::Eg),
            name == "torus",
            "{name}: {kinds:?}"
        );
    }
}

#[test]
fn seams_split_vertices_and_nothing_else_changes() {
    for (name, m) in meshes() {
        let (patches, fv) = surface(&m);
        let with = tess(&patches, Some(&fv));
        let without = tess(&patches, None);
        assert_eq!(with.uvs.len(), with.positions.len());
        assert_eq!(with.seam_origin.len(), with.positions.len());
        assert!(without.uvs.is_empty() && without.seam_origin.is_empty());
        assert_eq!(with.faces.len(), without.faces.len(), "{name}");
        assert_eq!(with.tags, without.tags);

        // Merged across the seams, it is the tessellation without UVs: the
        // same faces over the same positions and normals.
        let origins: std::collections::BTreeSet<u32> = with.seam_origin.iter().copied().collect();
        assert_eq!(origins.len(), without.positions.len(), "{name}");
        for (a, b) in with.faces.iter().zip(&without.faces) {
            let pa: Vec<_> = a
                .corners()
                .iter()
                .map(|&i| with.positions[i as usize])
                .collect();
            let pb: Vec<_> = b
                .corners()
                .iter()
                .map(|&i| without.positions[i as usize])
                .collect();
            assert_eq!(pa, pb, "{name}");
            let na: Vec<_> = a
                .corners()
                .iter()
                .map(|&i| with.normals[i as usize])
                .collect();
            let nb: Vec<_> = b
                .corners()
                .iter()
                .map(|&i| without.normals[i as usize])
                .collect();
            assert_eq!(na, nb, "{name}");
        }

        // Split vertices share their position and differ in UV by a seam's
        // jump, never by rounding: on the torus a whole period (u or v wraps
        // from 1 to 0), on the cube the distance between two atlas squares'
        // edges (measured ≥ 0.04; rounding would be ≈ 1e-16).
        let least = if name == "torus" { 1.0 - 1e-12 } else { 1e-3 };
        let mut split = 0;
        for (v, &o) in with.seam_origin.iter().enumerate() {
            let o = o as usize;
            if o != v {
                split += 1;
                assert_eq!(with.positions[v], with.positions[o]);
                assert_eq!(with.normals[v], with.normals[o]);
                let (a, b) = (with.uvs[v], with.uvs[o]);
                let jump = (a[0] - b[0]).abs().max((a[1] - b[1]).abs());
                assert!(jump >= least, "{name}: vertex {v} {a:?} vs {o} {b:?}");
            }
        }
        assert!(split > 0, "{name} has seams");

        // Every output face lies in its input face's checker square (its
        // UV centroid strictly inside): no face straddles a seam.
        for (face, &f) in with.faces.iter().zip(&with.tags) {
            let c = face.corners();
            let mut centroid = [0.0; 2];
            for &i in c {
                centroid[0] += with.uvs[i as usize][0] / c.len() as f64;
                centroid[1] += with.uvs[i as usize][1] / c.len() as f64;
            }
            let b = square(&m, f as usize);
            assert!(
                b[0] < centroid[0]
                    && centroid[0] < b[1]
                    && b[2] < centroid[1]
                    && centroid[1] < b[3],
                "{name}: a face of input face {f} has UV centroid {centroid:?} outside {b:?}"
            );
        }
    }
}

#[test]
fn obj_text_carries_one_uv_per_vertex() {
    let m = checker_torus();
    let (patches, fv) = surface(&m);
    let t = tess(&patches, Some(&fv));
    let text = write_obj(&t, &[]);
    let vt: Vec<[f64; 2]> = text
        .lines()
        .filter_map(|l| l.strip_prefix("vt "))
        .map(|l| {
            let x: Vec<f64> = l.split(' ').map(|w| w.parse().unwrap()).collect();
            [x[0], x[1]]
        })
        .collect();
    // Numbers are written to read back exactly.
    assert_eq!(vt, t.uvs);
    let faces: Vec<&str> = text.lines().filter(|l| l.starts_with("f ")).collect();
    assert_eq!(faces.len(), t.faces.len());
    for (line, f) in faces.iter().zip(&t.faces) {
        let want: Vec<String> = f
            .corners()
            .iter()
            .map(|&i| format!("{0}/{0}/{0}", i + 1))
            .collect();
        assert_eq!(line[2..], want.join(" "));
    }
    // Without UVs: the `v//vn` form, no `vt`.
    let plain = write_obj(&tess(&patches, None), &[]);
    assert!(!plain.contains("vt ") && plain.contains("//"));
}
