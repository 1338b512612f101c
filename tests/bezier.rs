//! Bézier patch evaluation (de Casteljau) against the Bernstein-sum definition.

use capdiv::bezier::BSPLINE_TO_BEZIER_CUBIC;
use capdiv::{Error, Point3, TensorPatch};

fn binom(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}
fn bern(n: usize, k: usize, t: f64) -> f64 {
    binom(n, k) * t.powi(k as i32) * (1.0 - t).powi((n - k) as i32)
}
fn dbern(n: usize, k: usize, t: f64) -> f64 {
    let a = if k > 0 { bern(n - 1, k - 1, t) } else { 0.0 };
    let b = if k < n { bern(n - 1, k, t) } else { 0.0 };
    n as f64 * (a - b)
}

fn patch<const K: usize>(seed: u64) -> TensorPatch<f64, K> {
    let mut s = seed;
    let mut rnd = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    let mut points = [[Point3::ZERO; K]; K];
    for (i, row) in points.iter_mut().enumerate() {
        for (j, p) in row.iter_mut().enumerate() {
            *p = Point3::new(i as f64 + 0.2 * rnd(), j as f64 + 0.2 * rnd(), rnd());
        }
    }
    TensorPatch { points }
}

fn check<const K: usize>() {
    let d = K - 1;
    // Under Miri (~1000x slower) two patches.
    let seeds = if cfg!(miri) { 2 } else { 20 };
    for seed in 0..seeds {
        let p = patch::<K>(seed);
        for &(u, v) in &[
            (0.0, 0.0),
            (1.0, 1.0),
            (0.3, 0.7),
            (0.5, 0.5),
            (0.9, 0.1),
            (1.0, 0.25),
        ] {
            let got = p.evaluate(u, v).unwrap();
            // The same point sampled along the line v = const.
            assert_eq!(p.iso_v(v).unwrap().evaluate(u), Ok(got));
            let (mut x, mut xu, mut xv) = (Point3::ZERO, Point3::ZERO, Point3::ZERO);
            for i in 0..K {
                for j in 0..K {
                    let q = p.points[i][j];
                    x += q * (bern(d, i, u) * bern(d, j, v));
                    xu += q * (dbern(d, i, u) * bern(d, j, v));
                    xv += q * (bern(d, i, u) * dbern(d, j, v));
                }
            }
            // Values are O(K); de Casteljau and the Bernstein sum differ by rounding only.
            assert!(got.position.max_abs_diff(x) < 1e-13);
            assert!(got.du.max_abs_diff(xu) < 1e-12);
            assert!(got.dv.max_abs_diff(xv) < 1e-12);
            let n = got.normal().unwrap();
            assert!((n.norm() - 1.0).abs() < 1e-14);
            assert!(n.dot(xu).abs() < 1e-12 && n.dot(xv).abs() < 1e-12);
            assert!(n.dot(xu.cross(xv)) > 0.0);
        }
    }
}

#[test]
fn bicubic_evaluation_matches_bernstein_sums() {
    check::<4>();
}

#[test]
fn biquartic_evaluation_matches_bernstein_sums() {
    check::<5>();
}

#[test]
fn evaluation_rejects_parameters_outside_the_domain() {
    let p = patch::<4>(1);
    for (u, v) in [
        (-0.1, 0.5),
        (0.5, 1.1),
        (f64::NAN, 0.5),
        (0.5, f64::INFINITY),
    ] {
        assert_eq!(p.evaluate(u, v), Err(Error::OutOfDomain));
    }
}

#[test]
fn iso_curves_sample_a_grid_as_pointwise_evaluation_does() {
    // A grid sampled line by line (one reduction along v per line) is the
    // documented fast path for tessellation; it must give what `evaluate`
    // gives at every point, bit for bit, in both precisions.
    let params = [0.0, 0.125, 1.0 / 3.0, 0.5, 0.8, 1.0];
    for seed in 0..4 {
        let p = patch::<5>(seed);
        let p32 = TensorPatch::<f32, 5> {
            points: p
                .points
                .map(|row| row.map(|q| Point3(q.0.map(|x| (x * 1e3 + 7e3) as f32)))),
        };
        let (lines, lines32) = (p.lines(), p32.lines());
        for &v in &params {
            let line = p.iso_v(v).unwrap();
            let line32 = p32.iso_v(v as f32).unwrap();
            // The same lines from points made relative once per patch.
            let (again, again32) = (lines.iso_v(v).unwrap(), lines32.iso_v(v as f32).unwrap());
            assert_eq!(line.v(), v);
            for &u in &params {
                assert_eq!(line.evaluate(u), p.evaluate(u, v));
                assert_eq!(line32.evaluate(u as f32), p32.evaluate(u as f32, v as f32));
                assert_eq!(again.evaluate(u), p.evaluate(u, v));
                assert_eq!(again32.evaluate(u as f32), p32.evaluate(u as f32, v as f32));
            }
        }
    }
}

#[test]
fn iso_curves_reject_parameters_outside_the_domain() {
    let p = patch::<4>(2);
    for t in [-0.1, 1.1, f64::NAN, f64::INFINITY] {
        assert_eq!(p.iso_v(t).err(), Some(Error::OutOfDomain));
        assert_eq!(p.lines().iso_v(t).err(), Some(Error::OutOfDomain));
        assert_eq!(p.iso_v(0.5).unwrap().evaluate(t), Err(Error::OutOfDomain));
    }
}

#[test]
fn iso_curves_of_a_patch_spanning_more_than_f32_take_the_evaluation_about_zero() {
    // Differences of ±3e38 overflow f32: evaluation relative to the first
    // point is not finite, so the point is evaluated again about zero, the
    // same way as `evaluate` does, and is finite (the Bernstein weights
    // keep every partial sum within range at the corner u = v = 0).
    let mut points = [[Point3::new(0.0f32, 0.0, 0.0); 4]; 4];
    points[0][0] = Point3::new(-3e38, 0.0, 0.0);
    points[3][3] = Point3::new(3e38, 1.0, 1.0);
    let p = TensorPatch::<f32, 4> { points };
    let line = p.iso_v(0.0).unwrap();
    let got = line.evaluate(0.0).unwrap();
    assert_eq!(Ok(got), p.evaluate(0.0, 0.0));
    assert_eq!(p.lines().iso_v(0.0).unwrap().evaluate(0.0), Ok(got));
    assert_eq!(got.position, Point3::new(-3e38, 0.0, 0.0));
}

#[test]
fn collapsed_patch_has_no_normal() {
    let p = TensorPatch::<f64, 4> {
        points: [[Point3::new(1.0, 2.0, 3.0); 4]; 4],
    };
    assert_eq!(p.normal(0.5, 0.5), Err(Error::Degenerate));
}

/// The conversion is bit for bit `d[1][1] + M (d − d[1][1]) Mᵀ` with the
/// weights `k/6` (written here as the literal double sum, zeros included),
/// in f32 and f64: the firmware's logged sums are compared with tolerances
/// of a few ulps, so the kernel's rounding must not drift.
#[test]
fn bspline_to_bezier_is_bit_for_bit_the_dense_product() {
    // Literal indices on purpose: this is the textbook double sum.
    #[allow(clippy::needless_range_loop)]
    fn dense<R: capdiv::Real>(d: &[[Point3<R>; 4]; 4]) -> [[Point3<R>; 4]; 4] {
        let m = |a: usize, k: usize| R::ratio(BSPLINE_TO_BEZIER_CUBIC[a][k], 6);
        let o = d[1][1];
        let mut half = [[Point3::ZERO; 4]; 4];
        for k in 0..4 {
            for b in 0..4 {
                let mut acc = Point3::ZERO;
                for l in 0..4 {
                    acc += (d[k][l] - o) * m(b, l);
                }
                half[k][b] = acc;
            }
        }
        let mut out = [[Point3::ZERO; 4]; 4];
        for a in 0..4 {
            for b in 0..4 {
                let mut acc = Point3::ZERO;
                for k in 0..4 {
                    acc += half[k][b] * m(a, k);
                }
                out[a][b] = acc + o;
            }
        }
        out
    }
    fn check<R: capdiv::Real + core::fmt::Debug>(seed: u64) {
        let mut x = seed;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            R::from_f64((x % 20001) as f64 / 997.0 - 10.0)
        };
        let mut d = [[Point3::ZERO; 4]; 4];
        for row in d.iter_mut() {
            for p in row.iter_mut() {
                *p = Point3::new(next(), next(), next());
            }
        }
        let got = capdiv::bezier::bspline_to_bezier_cubic(&d);
        let want = dense(&d);
        for a in 0..4 {
            for b in 0..4 {
                for c in 0..3 {
                    assert_eq!(
                        got[a][b].0[c].to_f64().to_bits(),
                        want[a][b].0[c].to_f64().to_bits(),
                        "seed {seed} [{a}][{b}]"
                    );
                }
            }
        }
    }
    let seeds = if cfg!(miri) { 8 } else { 2000u64 };
    for seed in 1..seeds {
        check::<f32>(seed);
        check::<f64>(seed);
    }
}

/// A small B-spline patch far from the origin, as `f32` control points.
fn far_small_bspline() -> [[Point3<f32>; 4]; 4] {
    let (h, far) = (1e-2f64, [1000.0f64, -900.0, 1100.0]);
    core::array::from_fn(|k| {
        core::array::from_fn(|l| {
            let (x, y) = (k as f64 * h, l as f64 * h);
            let z = 3.0 * (x * x - 0.5 * y * y) + 0.1 * x * y;
            Point3::new(
                (far[0] + x) as f32,
                (far[1] + y) as f32,
                (far[2] + z) as f32,
            )
        })
    })
}

fn widen<const K: usize>(p: &[[Point3<f32>; K]; K]) -> [[Point3<f64>; K]; K] {
    p.map(|row| row.map(|q| Point3(q.0.map(f64::from))))
}

/// The f32 conversion of a small patch far from the origin rounds each
/// Bézier point once, at the end: within 0.5 ulp of the coordinate (plus the
/// local sums' rounding, ~ε of the patch's size) of the f64 conversion of
/// the same points. Summing the coordinates themselves rounds three or four
/// times at their size (measured: 0.41 ulp; 1.33 about zero). Bound: 0.6 ulp.
#[test]
fn f32_bspline_to_bezier_rounds_once_at_the_coordinates_size() {
    let d32 = far_small_bspline();
    let b32 = capdiv::bezier::bspline_to_bezier_cubic(&d32);
    let b64 = capdiv::bezier::bspline_to_bezier_cubic(&widen(&d32));
    let mut worst = 0.0f64;
    for (r32, r64) in b32.iter().zip(&b64) {
        for (p32, p64) in r32.iter().zip(r64) {
            for c in 0..3 {
                let ulp = f64::from(p32.0[c].abs()) * f64::from(f32::EPSILON);
                worst = worst.max((f64::from(p32.0[c]) - p64.0[c]).abs() / ulp);
            }
        }
    }
    assert!(worst <= 0.6, "f32 Bézier points off by {worst:.2} ulp");
}

/// A small Bézier patch far from the origin, evaluated in `f32`: its unit
/// normals and second partials stay within `f32` precision of the `f64`
/// results from the same (exactly widened) control points. The patch is
/// 1e-2 across at distance ~1.7e3, where one ulp of a coordinate is 1e-2 of
/// the patch: de Casteljau on the coordinates would round the partials at
/// that size (measured 3.7e-2 about zero); relative to the first control point
/// the rounding is a few `ε` (measured 8.5e-8). Bound: 1e-5 for unit
/// normals, 1e-4 relative for the second partials (one more difference).
#[test]
fn f32_partials_of_a_small_patch_far_from_the_origin_keep_f32_precision() {
    let b32 = TensorPatch {
        points: capdiv::bezier::bspline_to_bezier_cubic(&far_small_bspline()),
    };
    let b64 = TensorPatch {
        points: widen(&b32.points),
    };
    let (mut normal, mut second) = (0.0f64, 0.0f64);
    for a in 0..=4 {
        for b in 0..=4 {
            let (u, v) = (a as f64 / 4.0, b as f64 / 4.0);
            let n32 = b32.normal(u as f32, v as f32).unwrap();
            let n64 = b64.normal(u, v).unwrap();
            for c in 0..3 {
                normal = normal.max((f64::from(n32.0[c]) - n64.0[c]).abs());
            }
            let j32 = b32.jet(u as f32, v as f32).unwrap();
            let j64 = b64.jet(u, v).unwrap();
            for (p32, p64) in [(j32.duu, j64.duu), (j32.duv, j64.duv), (j32.dvv, j64.dvv)] {
                let scale = p64.norm().max(1e-300);
                for c in 0..3 {
                    second = second.max((f64::from(p32.0[c]) - p64.0[c]).abs() / scale);
                }
            }
        }
    }
    assert!(normal < 1e-5, "f32 normals off by {normal:.2e}");
    assert!(
        second < 1e-4,
        "f32 second partials off by {second:.2e} (relative)"
    );
}
