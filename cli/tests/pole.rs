//! `capdiv pole`: the limit point against an independent computation, the
//! curvatures of sampled quadrics against hand-derived values, invariance
//! under refinement (docs/math/c2ps.md §4).

mod common;

use common::*;
use serde_json::Value;

fn pole_of(file: &str) -> Value {
    capdiv(&["pole", file], None).ok_json()
}

fn num(v: &Value) -> f64 {
    v.as_f64().expect("number")
}

#[test]
fn output_has_the_documented_fields() {
    let dir = tempdir();
    let (pole, links) = config(5, 2, 1);
    let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
    let out = pole_of(s(&file));
    let mut keys: Vec<&str> = out
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    keys.sort_unstable();
    assert_eq!(
        keys,
        [
            "gaussian_curvature",
            "limit",
            "mean_curvature",
            "normal",
            "p",
            "principal_curvatures"
        ]
    );
    assert_eq!(out["p"].as_array().unwrap().len(), 6);
    assert_eq!(p3(&out["p"][0]), p3(&out["limit"]), "limit is p0");
    let n = p3(&out["normal"]);
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    assert!((len - 1.0).abs() < 1e-15, "unit normal, |n| = {len}");
    // H = (k1 + k2)/2 and K = k1 k2 (a few ulps of the magnitudes involved).
    let k = &out["principal_curvatures"];
    let (k1, k2) = (num(&k[0]), num(&k[1]));
    let (h, g) = (num(&out["mean_curvature"]), num(&out["gaussian_curvature"]));
    let mag = k1.abs().max(k2.abs()).max(1.0);
    assert!(((k1 + k2) / 2.0 - h).abs() < 1e-12 * mag);
    assert!((k1 * k2 - g).abs() < 1e-12 * mag * mag);
}

#[test]
fn limit_is_two_thirds_pole_plus_one_third_mean_of_link_1() {
    let dir = tempdir();
    for (n, k, seed) in [(3, 2, 1), (5, 5, 2), (7, 3, 3), (16, 6, 4), (48, 2, 5)] {
        let (pole, links) = config(n, k, seed);
        let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
        let got = p3(&pole_of(s(&file))["limit"]);
        let mut mean = [0.0; 3];
        for p in &links[0] {
            for c in 0..3 {
                mean[c] += p[c] / n as f64;
            }
        }
        let want = [0, 1, 2].map(|c| 2.0 / 3.0 * pole[c] + mean[c] / 3.0);
        // Summation order differs from the kernel's: a few ulps of the scale.
        let tol = 8.0 * f64::EPSILON * scale(&pole, &links[..1]);
        assert!(diff(&got, &want) <= tol, "n={n}: {got:?} vs {want:?}");
    }
}

/// Sampled `z = a (x² + y²)` on circles of radius `i·h`: by hand (docs/math/c2ps.md §4),
/// `A = (0, 0, a h²)`, `C1 = (h/2, 0, 0)`, `S1 = (0, h/2, 0)`, `C2 = S2 = 0`
/// (n ≥ 4), so the limit surface is `z = a h²/3 + a (X² + Y²)` with `X = h x`:
/// K = 4a², H = 2a, both principal curvatures 2a, normal +z, limit `a h²/3`.
#[test]
fn sampled_paraboloid_has_the_analytic_curvature() {
    let dir = tempdir();
    for (n, a, h) in [(4, 1.0, 0.25), (6, 0.7, 0.5), (48, -0.3, 0.1)] {
        let links: Vec<Vec<[f64; 3]>> = (1..=5)
            .map(|i| {
                (0..n)
                    .map(|j| {
                        let t = std::f64::consts::TAU * j as f64 / n as f64;
                        let r = i as f64 * h;
                        [r * t.cos(), r * t.sin(), a * r * r]
                    })
                    .collect()
            })
            .collect();
        let file = write_json(dir.path(), "in.json", &polar_json([0.0; 3], &links));
        let out = pole_of(s(&file));
        let tol = 1e-12;
        assert!(
            (num(&out["gaussian_curvature"]) - 4.0 * a * a).abs() < tol,
            "{out}"
        );
        assert!((num(&out["mean_curvature"]) - 2.0 * a).abs() < tol, "{out}");
        // k = H ± √(H² − K) with H² − K = 0 up to round-off ε: the root
        // amplifies it to √ε, so only ~1e-7 agreement is meaningful.
        for k in 0..2 {
            assert!(
                (num(&out["principal_curvatures"][k]) - 2.0 * a).abs() < 1e-6,
                "{out}"
            );
        }
        assert!(diff(&p3(&out["normal"]), &[0.0, 0.0, 1.0]) < tol);
        assert!(diff(&p3(&out["limit"]), &[0.0, 0.0, a * h * h / 3.0]) < tol);
    }
}

/// Lemma 5 (docs/math/c2ps.md §4): at level m, p1, p2 scale by 2^-m and p3..p5 by 4^-m
/// while link i sits at r = i·2^-m, so normal and curvatures at the pole are
/// the same at every level, and the limit point too.
#[test]
fn pole_geometry_is_invariant_under_refinement() {
    let dir = tempdir();
    let (pole, links) = config(6, 4, 21);
    let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
    let base = pole_of(s(&file));
    for m in ["1", "3", "6"] {
        for scheme in ["c2ps", "rts"] {
            let refined = capdiv(
                &["refine", "--scheme", scheme, "--steps", m, s(&file)],
                None,
            );
            let mid = write_json(dir.path(), "mid.json", &refined.ok_json());
            let got = pole_of(s(&mid));
            let tol = 1e-9;
            assert!(
                diff(&p3(&got["limit"]), &p3(&base["limit"])) < tol,
                "{scheme} {m}"
            );
            assert!(
                diff(&p3(&got["normal"]), &p3(&base["normal"])) < tol,
                "{scheme} {m}"
            );
            for key in ["gaussian_curvature", "mean_curvature"] {
                let (a, b) = (num(&got[key]), num(&base[key]));
                assert!(
                    (a - b).abs() < tol * b.abs().max(1.0),
                    "{scheme} {m} {key}: {a} vs {b}"
                );
            }
        }
    }
}

#[test]
fn f32_precision_agrees_with_f64() {
    let dir = tempdir();
    let (pole, links) = config(5, 3, 8);
    let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
    let a = pole_of(s(&file));
    let b = capdiv(&["pole", "--precision", "f32", s(&file)], None).ok_json();
    // Inputs rounded to f32 (relative 6e-8), a handful of operations: 1e-5.
    assert!(diff(&p3(&a["limit"]), &p3(&b["limit"])) < 1e-5);
    let (ka, kb) = (num(&a["gaussian_curvature"]), num(&b["gaussian_curvature"]));
    assert!((ka - kb).abs() < 1e-4 * ka.abs().max(1.0), "{ka} vs {kb}");
}

/// Sampled `z = b (x² − y²)` (n ≥ 5): by hand, `C2 = (0, 0, b h²/2)` so
/// `p4 = 3 C2 = (0, 0, 1.5 b h²)` and the limit near the pole is
/// `z = 1.5 b (X² − Y²)`: K = −(3b)², H = 0 — not the sampled surface's
/// K = −(2b)². The patches (geometry, not the jet) agree: on the ray τ = 0 at
/// r = 3·2^-m (the corner u = 1, v = 0 of ring-m span-0 column 0),
/// z / X² → 1.5 b as m grows.
#[test]
fn sampled_saddle_limits_to_one_and_a_half_times_the_saddle() {
    let dir = tempdir();
    let (n, b, h) = (8usize, 0.5, 0.25);
    let links: Vec<Vec<[f64; 3]>> = (1..=5)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / n as f64;
                    let r = i as f64 * h;
                    let (x, y) = (r * t.cos(), r * t.sin());
                    [x, y, b * (x * x - y * y)]
                })
                .collect()
        })
        .collect();
    let file = write_json(dir.path(), "in.json", &polar_json([0.0; 3], &links));
    let out = pole_of(s(&file));
    assert!(
        (num(&out["gaussian_curvature"]) + 9.0 * b * b).abs() < 1e-12,
        "{out}"
    );
    assert!(num(&out["mean_curvature"]).abs() < 1e-12, "{out}");

    let ps = capdiv(&["patches", "--depth", "8", s(&file)], None).ok_json();
    let ps = ps.as_array().unwrap();
    let mut errs = vec![];
    for m in [4u64, 6, 8] {
        let first = ps.iter().position(|p| p["level"] == m).unwrap();
        let corner = p3(&ps[first]["points"][12]);
        assert!(corner[1].abs() < 1e-12, "on the ray τ = 0");
        errs.push((corner[2] / (corner[0] * corner[0]) - 1.5 * b).abs());
    }
    // o(r²) remainder: the error shrinks with r = 3·2^-m and ends small.
    assert!(errs[0] > errs[1] && errs[1] > errs[2], "{errs:?}");
    assert!(errs[2] < 0.01 * b, "{errs:?}");
}
