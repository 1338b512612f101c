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
fn collapsed_patch_has_no_normal() {
    let p = TensorPatch::<f64, 4> {
        points: [[Point3::new(1.0, 2.0, 3.0); 4]; 4],
    };
    assert_eq!(p.normal(0.5, 0.5), Err(Error::Degenerate));
}

/// The conversion is bit for bit the dense product `M d Mᵀ` with the
/// weights `k/6` (written here as the literal double sum, zeros included),
/// in f32 and f64: the firmware's logged sums are compared with tolerances
/// of a few ulps, so the kernel's rounding must not drift.
#[test]
fn bspline_to_bezier_is_bit_for_bit_the_dense_product() {
    // Literal indices on purpose: this is the textbook double sum.
    #[allow(clippy::needless_range_loop)]
    fn dense<R: capdiv::Real>(d: &[[Point3<R>; 4]; 4]) -> [[Point3<R>; 4]; 4] {
        let m = |a: usize, k: usize| R::ratio(BSPLINE_TO_BEZIER_CUBIC[a][k], 6);
        let mut half = [[Point3::ZERO; 4]; 4];
        for k in 0..4 {
            for b in 0..4 {
                let mut acc = Point3::ZERO;
                for l in 0..4 {
                    acc += d[k][l] * m(b, l);
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
                out[a][b] = acc;
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
