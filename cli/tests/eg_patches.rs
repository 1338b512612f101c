//! `capdiv patches` on EG inputs (docs/math/eg.md §9): the rings of steps 1..M,
//! `3n` bi-4 patches each, in the documented order, equal to the kernel's;
//! neighbouring patches share their edges (within a ring, across sectors,
//! between consecutive rings); the OBJ and PNG outputs.

mod common;

use capdiv::{CNet, EgSubdivision};
use common::*;
use serde_json::Value;

type Net = [[[f64; 3]; 5]; 5];

fn patches(args: &[&str]) -> Vec<Value> {
    capdiv(args, None)
        .ok_json()
        .as_array()
        .expect("an array of patches")
        .clone()
}

/// `points[i][j]` of a printed patch (`i` along `u`, `j` along `v`).
fn net(p: &Value) -> Net {
    let pts: Vec<[f64; 3]> = p["points"].as_array().unwrap().iter().map(p3).collect();
    assert_eq!(pts.len(), 25);
    std::array::from_fn(|i| std::array::from_fn(|j| pts[5 * i + j]))
}

/// A degree-4 Bézier curve at `t` (de Casteljau).
fn curve(b: [[f64; 3]; 5], t: f64) -> [f64; 3] {
    let mut b = b;
    for r in 1..5 {
        for k in 0..5 - r {
            let next = b[k + 1];
            for (x, y) in b[k].iter_mut().zip(next) {
                *x = (1.0 - t) * *x + t * y;
            }
        }
    }
    b[0]
}

fn row(n: &Net, i: usize) -> [[f64; 3]; 5] {
    n[i]
}
fn col(n: &Net, j: usize) -> [[f64; 3]; 5] {
    std::array::from_fn(|i| n[i][j])
}

#[test]
fn rings_of_steps_1_to_m_with_3n_patches_each() {
    let dir = tempdir();
    for n in [3, 4, 5] {
        let (center, sectors) = cnet(n, n as u64);
        let file = write_json(dir.path(), "c.json", &cnet_json(center, &sectors));
        for m in 0..=3u32 {
            let depth = m.to_string();
            let ps = patches(&["patches", "--depth", &depth, s(&file)]);
            assert_eq!(ps.len(), 3 * n * m as usize, "n={n} M={m}");
            for (k, p) in ps.iter().enumerate() {
                assert_eq!(p["degree"], 4);
                assert_eq!(p["points"].as_array().unwrap().len(), 25);
                // Ring of step 1 first, 3n patches a ring.
                assert_eq!(p["level"], 1 + k / (3 * n), "n={n} M={m} patch {k}");
                assert_eq!(p.as_object().unwrap().len(), 3, "level, degree, points");
            }
        }
    }
}

#[test]
fn patches_equal_the_kernel_bit_for_bit() {
    let dir = tempdir();
    for n in [3, 5] {
        let (center, sectors) = cnet(n, 20 + n as u64);
        let file = write_json(dir.path(), "c.json", &cnet_json(center, &sectors));
        let ps = patches(&["patches", "--depth", "3", s(&file)]);
        let mut eg =
            EgSubdivision::new(&CNet::from_sectors(center, &sectors).unwrap(), None).unwrap();
        let mut want = Vec::new();
        for _ in 0..3 {
            eg.step().unwrap();
            for p in eg.ring_patches() {
                want.push(p.points.map(|r| r.map(|q| q.0)));
            }
        }
        let got: Vec<Net> = ps.iter().map(net).collect();
        assert_eq!(got, want, "n={n}");
    }
}

#[test]
fn neighbouring_patches_share_their_edges() {
    // Patch 3s+p of a ring: p = 0 [½,1]×[0,½], 1 [0,½]×[½,1], 2 [½,1]² of
    // sector s's old hole; u along x (spoke s), v along y (spoke s+1).
    let dir = tempdir();
    for n in [3, 4, 5] {
        let (center, sectors) = cnet(n, 30 + n as u64);
        let scale = sectors
            .iter()
            .flatten()
            .flatten()
            .fold(0.0f64, |m, c| m.max(c.abs()));
        let tol = 1e-13 * scale;
        let file = write_json(dir.path(), "c.json", &cnet_json(center, &sectors));
        let depth = 4;
        let ps: Vec<Net> = patches(&["patches", "--depth", "4", s(&file)])
            .iter()
            .map(net)
            .collect();
        let at = |m: usize, s: usize, p: usize| &ps[(m - 1) * 3 * n + 3 * (s % n) + p];
        let same = |a: [[f64; 3]; 5], b: [[f64; 3]; 5], what: &str| {
            for (x, y) in a.iter().zip(&b) {
                assert!(diff(x, y) <= tol, "n={n} {what}: {x:?} vs {y:?}");
            }
        };
        for m in 1..=depth {
            for s in 0..n {
                // Within a sector: y = ½ and x = ½ of the old hole.
                same(col(at(m, s, 0), 4), col(at(m, s, 2), 0), "p0/p2");
                same(row(at(m, s, 1), 4), row(at(m, s, 2), 0), "p1/p2");
                // Across spoke s+1: sector s's p1 (x = 0) is sector s+1's p0 (y = 0).
                same(row(at(m, s, 1), 0), col(at(m, s + 1, 0), 0), "spoke");
                // Ring m+1's outer edge x = 2^-m lies on the first half of ring
                // m's inner edge (its p0 at u = 0, v ∈ [0, ½]).
                if m < depth {
                    let inner = row(at(m, s, 0), 0);
                    let outer = row(at(m + 1, s, 0), 4);
                    for t in [0.0, 0.25, 0.5, 0.75, 1.0] {
                        let (a, b) = (curve(inner, t / 2.0), curve(outer, t));
                        assert!(diff(&a, &b) <= tol, "n={n} rings {m}/{}: t={t}", m + 1);
                    }
                }
            }
        }
    }
}

#[test]
fn dnet_inputs_and_valence_4_have_rings_too() {
    let dir = tempdir();
    // The printed level-2 d-net continues where the c-net's refinement is:
    // its ring 1 is the c-net's ring 3.
    let (center, sectors) = cnet(5, 40);
    let file = write_json(dir.path(), "c.json", &cnet_json(center, &sectors));
    let level2 = capdiv(&["refine", "--steps", "2", s(&file)], None);
    level2.assert_ok();
    let d = dir.path().join("d.json");
    std::fs::write(&d, &level2.stdout).unwrap();
    let from_c = patches(&["patches", "--depth", "3", s(&file)]);
    let from_d = patches(&["patches", "--depth", "1", s(&d)]);
    assert_eq!(from_d.len(), 15);
    let want: Vec<Net> = from_c[30..].iter().map(net).collect();
    let got: Vec<Net> = from_d.iter().map(net).collect();
    assert_eq!(got, want);
    // n = 4: regular rules, 12 patches a ring.
    let (center, sectors) = cnet(4, 41);
    let file = write_json(dir.path(), "c4.json", &cnet_json(center, &sectors));
    assert_eq!(patches(&["patches", "--depth", "2", s(&file)]).len(), 24);
}

#[test]
fn obj_is_welded_interpolates_corners_and_faces_follow_the_normals() {
    let dir = tempdir();
    let (center, sectors) = cnet(3, 50);
    let file = write_json(dir.path(), "c.json", &cnet_json(center, &sectors));
    let ps: Vec<Net> = patches(&["patches", "--depth", "2", s(&file)])
        .iter()
        .map(net)
        .collect();
    for grid in [1usize, 4] {
        let g = grid.to_string();
        let run = capdiv(
            &[
                "patches",
                "--depth",
                "2",
                "--format",
                "obj",
                "--grid",
                &g,
                s(&file),
            ],
            None,
        );
        run.assert_ok();
        let text = run.stdout_str();
        assert!(text.contains("18 bi-4 Bézier patches in rings of levels 1..=2"));
        let obj = parse_obj(&text);
        assert_eq!(obj.vn.len(), obj.v.len());
        // Welded, ring meeting ring without a T-junction: an annulus whose
        // inner loop is the hole [0, 2^-2]² of each of the 3 sectors (two
        // edges of `grid` segments each).
        let loops = assert_welded_annulus(&obj, &format!("grid {grid}"));
        assert_eq!(loops[0], 3 * 2 * grid);
        // Ring 1's pieces 0 and 1 (2n patches) meet ring 2 along one edge
        // each: its `grid` cells become 3 triangles each (fans from the
        // midpoints); every other cell is a quad.
        let tris = obj.f.iter().filter(|f| f.len() == 3).count();
        let quads = obj.f.iter().filter(|f| f.len() == 4).count();
        assert_eq!(tris, 2 * 3 * grid * 3);
        assert_eq!(quads, ps.len() * grid * grid - 2 * 3 * grid);
        // A Bézier patch interpolates its corners; a welded vertex holds
        // the first of its samples (the patches sharing it agree to
        // rounding).
        for p in &ps {
            for corner in [p[0][0], p[4][0], p[4][4], p[0][4]] {
                assert!(has_vertex(&obj, &corner, 1e-12), "corner {corner:?}");
            }
        }
        for face in &obj.f {
            let v: Vec<[f64; 3]> = face.iter().map(|&(a, _)| obj.v[a - 1]).collect();
            let (a, b) = (sub(v[1], v[0]), sub(v[v.len() - 1], v[0]));
            let cr = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            let nrm = obj.vn[face[0].1 - 1];
            let dot: f64 = (0..3).map(|k| cr[k] * nrm[k]).sum();
            assert!(dot > 0.0, "face not counter-clockwise about its normal");
        }
    }
    let png = dir.path().join("c.png");
    capdiv(
        &[
            "patches",
            "--depth",
            "3",
            "--format",
            "png",
            "-o",
            s(&png),
            s(&file),
        ],
        None,
    )
    .assert_ok();
    let (w, h, _) = decode_png(&std::fs::read(&png).unwrap());
    assert_eq!((w, h), (800, 600));
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
