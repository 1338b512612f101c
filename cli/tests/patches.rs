//! `capdiv patches`: patch counts (2N per ring level plus the outer region),
//! which rings exist, exact agreement with the kernel, the outer region
//! meeting ring 0, and a well-formed OBJ mesh.

mod common;

use capdiv::{FirstStep, OuterRegion, PolarNet};
use common::*;
use serde_json::Value;
use std::collections::BTreeMap;

fn patches(args: &[&str]) -> Vec<Value> {
    let out = capdiv(args, None).ok_json();
    out.as_array().expect("a JSON array").clone()
}

/// Patches per level.
fn per_level(ps: &[Value]) -> BTreeMap<u64, usize> {
    let mut m = BTreeMap::new();
    for p in ps {
        assert_eq!(p["degree"], 3);
        assert_eq!(p["points"].as_array().unwrap().len(), 16);
        *m.entry(p["level"].as_u64().unwrap()).or_default() += 1;
    }
    m
}

#[test]
fn counts_are_2n_per_ring_level_plus_the_outer_region() {
    let dir = tempdir();
    for (n, k) in [(5, 5), (5, 8), (3, 9), (6, 6)] {
        let (pole, links) = config(n, k, k as u64);
        let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
        let depth = 3u32;
        let ps = patches(&["patches", "--depth", "3", s(&file)]);
        // Outer region: as many patches as the kernel's OuterRegion has,
        // whole spans of n, at least one span per link beyond the 6th.
        let outer = OuterRegion::new(pole, &links).unwrap().len();
        assert_eq!(outer % n, 0);
        assert!(outer >= k.saturating_sub(6) * n);
        let rings: usize = (0..=depth).map(|m| 2 * (n << m)).sum();
        assert_eq!(ps.len(), outer + rings, "n={n} k={k}");
        let levels = per_level(&ps);
        assert_eq!(levels[&0], outer + 2 * n);
        for m in 1..=depth {
            assert_eq!(levels[&(m as u64)], 2 * (n << m));
        }
    }
}

/// A ring needs links 1..5: K input links give 2K−1 after a step (docs/math/c2ps.md §2),
/// so K ≥ 5 has ring 0, K = 3, 4 start at level 1, K = 2 at level 2.
#[test]
fn rings_exist_from_the_level_with_five_links() {
    let dir = tempdir();
    for (k, first_level) in [(2u64, 2u64), (3, 1), (4, 1), (5, 0)] {
        let (pole, links) = config(4, k as usize, k);
        let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
        let ps = patches(&["patches", "--depth", "3", s(&file)]);
        let levels: Vec<u64> = per_level(&ps).keys().copied().collect();
        let want: Vec<u64> = (first_level..=3).collect();
        assert_eq!(levels, want, "k={k}");
    }
    // Before that: no patch at all, still a valid (empty) answer.
    let (pole, links) = config(4, 2, 1);
    let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
    assert!(patches(&["patches", "--depth", "1", s(&file)]).is_empty());
}

#[test]
fn json_equals_the_kernel_bit_for_bit() {
    let dir = tempdir();
    let (pole, links) = config(5, 7, 3);
    let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
    let ps = patches(&["patches", "--depth", "2", "--first-step", "plain", s(&file)]);
    let mut want: Vec<[f64; 3]> = Vec::new();
    for p in OuterRegion::new(pole, &links).unwrap().patches() {
        want.extend(p.points.iter().flatten().map(|q| q.0));
    }
    let mut net: PolarNet<f64, 1024> = PolarNet::new(pole, &links).unwrap();
    for m in 0..=2 {
        for p in net.ring_patches() {
            want.extend(p.points.iter().flatten().map(|q| q.0));
        }
        if m < 2 {
            net.step(FirstStep::Plain).unwrap();
        }
    }
    let got: Vec<[f64; 3]> = ps
        .iter()
        .flat_map(|p| p["points"].as_array().unwrap().iter().map(p3))
        .collect();
    assert_eq!(got, want);
}

/// The outer region starts where ring 0 ends (r = 4, docs/math/c2ps.md §5): the inner
/// boundary row of outer patch `c` equals the outer boundary row of ring-0
/// span-1 patch `c` (the same B-spline curve from links 3..5).
#[test]
fn outer_region_meets_ring_zero() {
    let dir = tempdir();
    let n = 6;
    let (pole, links) = config(n, 8, 17);
    let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
    let ps = patches(&["patches", "--depth", "0", s(&file)]);
    let outer = OuterRegion::new(pole, &links).unwrap().len();
    assert!(outer >= n);
    let pts =
        |p: &Value| -> Vec<[f64; 3]> { p["points"].as_array().unwrap().iter().map(p3).collect() };
    let tol = 1e-12 * scale(&pole, &links);
    for c in 0..n {
        let inner_row = &pts(&ps[c])[0..4];
        let ring_span1 = &ps[outer + n + c];
        let outer_row = &pts(ring_span1)[12..16];
        for (a, b) in inner_row.iter().zip(outer_row) {
            assert!(diff(a, b) <= tol, "column {c}: {a:?} vs {b:?}");
        }
    }
}

#[test]
fn obj_is_welded_and_interpolates_patch_corners() {
    let dir = tempdir();
    let (pole, links) = config(5, 7, 2);
    let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
    let ps = patches(&["patches", "--depth", "2", s(&file)]);
    let n = 5;
    for grid in [1usize, 3, 4] {
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
        let obj = parse_obj(&run.stdout_str());
        assert_eq!(obj.vn.len(), obj.v.len());
        for face in &obj.f {
            assert!(face.len() == 3 || face.len() == 4);
            for &(a, b) in face {
                assert!(a >= 1 && a <= obj.v.len() && a == b, "index {a}//{b}");
            }
        }
        for n in &obj.vn {
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            assert!((len - 1.0).abs() < 1e-12, "unit normal {n:?}");
        }
        // Welded: shared patch edges are one, ring meets ring without a
        // T-junction. The open boundary is the outer region's edge and the
        // hole's: the inner edges of ring 2's span 0, n·2^2 patches of
        // `grid` segments.
        let loops = assert_welded_annulus(&obj, &format!("grid {grid}"));
        assert!(loops.contains(&(n * 4 * grid)), "boundary loops {loops:?}");
        // Fewer vertices than samples: every shared edge is stored once.
        let side = grid + 1;
        assert!(obj.v.len() < ps.len() * side * side);
        // A Bézier patch interpolates its corner control points.
        for p in &ps {
            let pts: Vec<[f64; 3]> = p["points"].as_array().unwrap().iter().map(p3).collect();
            for c in [0, 3, 12, 15] {
                assert!(has_vertex(&obj, &pts[c], 1e-12), "corner {:?}", pts[c]);
            }
        }
    }
}

#[test]
fn obj_faces_turn_counter_clockwise_about_the_normals() {
    // Paraboloid z = x² + y², links counter-clockwise from +z: every face's
    // geometric normal (by its vertex order) must point up, like its vn.
    let dir = tempdir();
    let n = 8;
    let links: Vec<Vec<[f64; 3]>> = (1..=5)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / n as f64;
                    let r = i as f64;
                    [r * t.cos(), r * t.sin(), 0.2 * r * r]
                })
                .collect()
        })
        .collect();
    let file = write_json(dir.path(), "in.json", &polar_json([0.0; 3], &links));
    let run = capdiv(
        &["patches", "--depth", "1", "--format", "obj", s(&file)],
        None,
    );
    run.assert_ok();
    let obj = parse_obj(&run.stdout_str());
    for face in &obj.f {
        let p = |k: usize| obj.v[face[k].0 - 1];
        let (a, b, c) = (p(0), p(1), p(2));
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let z = u[0] * w[1] - u[1] * w[0];
        assert!(z > 0.0, "face turns clockwise from +z");
        assert!(obj.vn[face[0].1 - 1][2] > 0.0, "vn points down");
    }
}

#[test]
fn png_preview_decodes() {
    let dir = tempdir();
    let (pole, links) = config(5, 5, 2);
    let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
    let out = dir.path().join("p.png");
    let run = capdiv(
        &[
            "patches",
            "--depth",
            "2",
            "--format",
            "png",
            "-o",
            s(&out),
            s(&file),
        ],
        None,
    );
    run.assert_ok();
    assert!(run.stdout.is_empty());
    let (w, h, rgb) = decode_png(&std::fs::read(&out).unwrap());
    assert_eq!((w, h), (800, 600));
    assert_eq!(rgb.len(), 3 * w * h);
    let drawn = rgb.chunks(3).filter(|p| p != &[246, 246, 246]).count();
    assert!(drawn > w * h / 10, "only {drawn} pixels drawn");
}
