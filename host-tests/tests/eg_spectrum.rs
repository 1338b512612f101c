//! EG (docs/math/eg.md): the dense subdivision matrix assembled from §5–§7 by the
//! reference (`capdiv_reference::eg`) has the spectrum of §8; the limit-point
//! formulas agree, (4)∘R = (3) (§3–§4); the degree raising and the tables
//! are consistent. Expected values are the spec's table (§8) and calculus.

use capdiv_reference::eg;
use nalgebra::{DMatrix, DVector};

/// §8, per valence: λ (double), μ/λ² of the single and of the double μ.
const SPEC: [(usize, f64, f64, f64); 2] = [
    (3, 0.4100423, 1.000157, 0.998065),
    (5, 0.5499951, 1.000160, 1.000118),
];

/// Every row of A_n sums to 1 (affine invariance), so the vector "every node
/// = c0" (all ones) is fixed: A·1 = 1. Row sums to 1e-12: each row is at most
/// 12n + 1 terms of size ≤ 1.
#[test]
fn eg_matrix_rows_sum_to_one() {
    for n in [3, 5] {
        let a = eg::matrix(n, None).unwrap();
        let ones = DVector::from_element(12 * n + 1, 1.0);
        let err = (&a * &ones - &ones).amax();
        assert!(err < 1e-12, "n {n}: {err:e}");
    }
}

/// §8: eigenvalue 1 is simple and dominant with eigenvector "every node = c0"
/// (the null vector of A − I, from the SVD, is ∝ 1); then λ double, to 1e-6 of
/// the table (it gives 7 digits); μ/λ² of the single and the double μ to
/// 1e-5; λ within 1e-3 of Catmull-Clark's λ_CC(n).
#[test]
fn eg_spectrum_matches_spec_table() {
    for (n, lambda, mu_single, mu_double) in SPEC {
        let a = eg::matrix(n, None).unwrap();
        let ev = eg::eigenvalues(&a);
        assert_eq!(ev.len(), 12 * n + 1);
        assert!(
            (ev[0].re - 1.0).abs() < 1e-10 && ev[0].im.abs() < 1e-10,
            "n {n}: {}",
            ev[0]
        );
        assert!(
            ev[1].norm() < 0.9,
            "n {n}: eigenvalue 1 is not simple: {}",
            ev[1]
        );
        for z in &ev[1..3] {
            assert!(
                (z.re - lambda).abs() < 1e-6 && z.im.abs() < 1e-9,
                "n {n}: λ = {z}, want {lambda}"
            );
        }
        let l = 0.5 * (ev[1].re + ev[2].re);
        assert!(
            (l - eg::lambda_cc(n)).abs() < 1e-3,
            "n {n}: λ {l} vs λ_CC {}",
            eg::lambda_cc(n)
        );
        // μ: the next three, one single and one double (the pair that coincides).
        let mu: Vec<f64> = ev[3..6]
            .iter()
            .map(|z| {
                assert!(z.im.abs() < 1e-9, "n {n}: μ complex: {z}");
                z.re
            })
            .collect();
        let (single, double) = if (mu[1] - mu[2]).abs() < 1e-9 {
            (mu[0], mu[1])
        } else {
            assert!((mu[0] - mu[1]).abs() < 1e-9, "n {n}: no double μ in {mu:?}");
            (mu[2], mu[0])
        };
        let l2 = l * l;
        assert!(
            (single / l2 - mu_single).abs() < 1e-5,
            "n {n}: μ/λ² single {}",
            single / l2
        );
        assert!(
            (double / l2 - mu_double).abs() < 1e-5,
            "n {n}: μ/λ² double {}",
            double / l2
        );
        assert!(
            ev[6].norm() < double.min(single) - 1e-6,
            "n {n}: μ not subsubdominant"
        );

        // Eigenvector of 1: the right singular vector of A − I with the
        // smallest singular value; all its entries equal.
        let m = &a - DMatrix::identity(12 * n + 1, 12 * n + 1);
        let svd = m.svd(false, true);
        let (k, smin) = svd
            .singular_values
            .iter()
            .enumerate()
            .min_by(|x, y| x.1.total_cmp(y.1))
            .unwrap();
        assert!(*smin < 1e-12, "n {n}: A − I not singular: {smin:e}");
        let v = svd.v_t.unwrap().row(k).transpose();
        let v0 = v[12 * n];
        assert!(v0.abs() > 0.1 / ((12 * n + 1) as f64).sqrt());
        assert!(
            (v / v0 - DVector::from_element(12 * n + 1, 1.0)).amax() < 1e-10,
            "n {n}: not every node = c0"
        );
    }
}

/// §3–§4: applying the d-net formula (4) to the degree-raised c-net is the
/// c-net formula (3), for n = 3..12 (the spec verified this in exact
/// arithmetic; here to 1e-14, a few ulps of weights ≤ 1). Also both weight
/// rows sum to 1, and every row of R sums to 1.
#[test]
fn c0_formula_4_after_degree_raising_equals_formula_3() {
    for n in 3..=12 {
        let r = eg::degree_raising(n);
        let w4 = eg::c0_from_dnet_weights(n);
        let w3 = eg::c0_from_cnet_weights(n);
        let composed = r.transpose() * &w4;
        let err = (&composed - &w3).amax();
        assert!(err < 1e-14, "n {n}: (4)∘R − (3) = {err:e}");
        assert!(
            (w4.sum() - 1.0).abs() < 1e-14 && (w3.sum() - 1.0).abs() < 1e-14,
            "n {n}"
        );
        let rows = &r * DVector::from_element(6 * n + 1, 1.0);
        assert!((rows.add_scalar(-1.0)).amax() < 1e-15, "n {n}: R rows");
    }
}

/// §1–§3 geometry: for the regular valence 4, a c-net at its grid positions
/// (sector s rotated by s·90°) degree-raises to d-nodes at their positions
/// ((3−i)/2, (3−j)/2) in the same frames; R reproduces linear functions.
#[test]
fn degree_raising_places_d_nodes_of_a_regular_grid() {
    let n = 4;
    let rot = |s: usize, x: f64, y: f64| -> (f64, f64) {
        match s % 4 {
            0 => (x, y),
            1 => (-y, x),
            2 => (-x, -y),
            _ => (y, -x),
        }
    };
    let mut cx = DVector::zeros(6 * n + 1);
    let mut cy = DVector::zeros(6 * n + 1);
    for s in 0..n {
        for (x, y) in [(1, 0), (2, 0), (1, 1), (2, 1), (1, 2), (2, 2)] {
            let k = eg::c_index(n, s as isize, x, y);
            let (wx, wy) = rot(s, x as f64, y as f64);
            cx[k] = wx;
            cy[k] = wy;
        }
    }
    let r = eg::degree_raising(n);
    let (dx, dy) = (&r * cx, &r * cy);
    for s in 0..n {
        for j in 0..3 {
            for i in 0..4 {
                let (wx, wy) = rot(s, (3 - i) as f64 / 2.0, (3 - j) as f64 / 2.0);
                let k = eg::d_index(s, i, j);
                assert!(
                    (dx[k] - wx).abs() < 1e-14 && (dy[k] - wy).abs() < 1e-14,
                    "s {s}, d{i}{j}"
                );
            }
        }
    }
}

/// §5: the regular rules reproduce linear functions on the d-grid (new node
/// at half the old position) — checked on the outer rows of A_n through a
/// regular-grid d-net of valence 4 assembled with the n = 4 frames.
#[test]
fn regular_rules_halve_positions() {
    for big_i in 0..8usize {
        // Old regular index k sits at (3 − k)/2; new index I at (3 − (I − 2))/4.
        let pos: f64 = eg::regular_rule(big_i)
            .iter()
            .map(|&(k, w)| w * (3.0 - k as f64) / 2.0)
            .sum();
        let sum: f64 = eg::regular_rule(big_i).iter().map(|&(_, w)| w).sum();
        assert!((sum - 1.0).abs() < 1e-15);
        assert!(
            (pos - (5.0 - big_i as f64) / 4.0).abs() < 1e-15,
            "I {big_i}: {pos}"
        );
    }
}

/// §6: the listed rows of the built-in tables agree with the symmetries
/// wherever both a row and its mirror are listed.
#[test]
fn listed_table_rows_are_consistent_with_the_symmetries() {
    for n in [3usize, 5] {
        let t = eg::builtin_table(n).unwrap();
        let m = |r: isize| r.rem_euclid(n as isize) as usize;
        for (rows, name) in [(&t.a11, "A11"), (&t.a22, "A22")] {
            for r in 0..rows.len() {
                for j in 0..3 {
                    for i in 0..4 {
                        let w = rows[r][i + 4 * j];
                        let mirror = if i == 3 {
                            rows.get(m(-(r as isize) - 1)).map(|row| row[3 + 4 * j])
                        } else if j <= 2 && i <= 2 {
                            rows.get(m(-(r as isize))).map(|row| row[j + 4 * i])
                        } else {
                            None
                        };
                        if let Some(v) = mirror {
                            assert_eq!(w, v, "n {n} {name} r {r} d{i}{j}");
                        }
                    }
                }
            }
        }
        for (rows, name) in [(&t.a31, "A31"), (&t.a32, "A32")] {
            for r in 0..rows.len() {
                for j in 0..3 {
                    for i in 0..4 {
                        let w = rows[r][i + 4 * j];
                        let mirror = if i == 3 {
                            rows.get(m(-(r as isize))).map(|row| row[3 + 4 * j])
                        } else {
                            rows.get(m(1 - r as isize)).map(|row| row[j + 4 * i])
                        };
                        if let Some(v) = mirror {
                            assert_eq!(w, v, "n {n} {name} r {r} d{i}{j}");
                        }
                    }
                }
            }
        }
        // The full rule, with unlisted rows filled in, is a (12n+1)² matrix.
        assert_eq!(eg::matrix(n, Some(&t)).unwrap().nrows(), 12 * n + 1);
    }
    assert!(eg::matrix(4, None).is_none() && eg::matrix(6, None).is_none());
}
