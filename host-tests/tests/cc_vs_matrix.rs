//! The kernel's Catmull-Clark cap (`capdiv::CcCap`) against the dense
//! subdivision matrix the reference builds from its literal mesh step
//! (`capdiv_reference::catmull_clark`, no code shared with `src/cc`):
//! steps, limit point (left eigenvector of eigenvalue 1) and limit tangent
//! masks (left eigenvectors of the subdominant eigenvalue).

use capdiv::{CcCap, Point3};
use capdiv_reference::catmull_clark::{
    cnet_index, cnet_matrix, ext_index, extended_matrix, limit_weights,
};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;
use std::sync::OnceLock;

/// `(E, S)` of valence `n`, built once per test binary.
fn matrices(n: usize) -> &'static (DMatrix<f64>, DMatrix<f64>) {
    static CACHE: OnceLock<Vec<(DMatrix<f64>, DMatrix<f64>)>> = OnceLock::new();
    &CACHE.get_or_init(|| {
        (0..=12)
            .map(|n| {
                if n < 3 {
                    (DMatrix::zeros(0, 0), DMatrix::zeros(0, 0))
                } else {
                    (extended_matrix(n), cnet_matrix(n))
                }
            })
            .collect()
    })[n]
}

fn cnet_strategy() -> impl Strategy<Value = (usize, Vec<[f64; 3]>)> {
    (3usize..=12).prop_flat_map(|n| {
        let coord = -10.0f64..10.0;
        (
            Just(n),
            proptest::collection::vec([coord.clone(), coord.clone(), coord], 6 * n + 1),
        )
    })
}

/// Worst |kernel − E S^(m−1) c| over the extended ring and the center after
/// each of `steps` steps, relative to the net's size.
fn deviation(n: usize, c: &[[f64; 3]], steps: usize) -> f64 {
    let (e, s) = matrices(n);
    let mut storage = vec![Point3::ZERO; CcCap::<f64>::storage_len(n)];
    let mut cap = CcCap::new(c[6 * n], &c[..6 * n], &mut storage).unwrap();
    let size = c.iter().flatten().fold(1e-300f64, |m, v| m.max(v.abs()));
    let mut x: Vec<DVector<f64>> = (0..3)
        .map(|k| DVector::from_iterator(6 * n + 1, c.iter().map(|p| p[k])))
        .collect();
    let mut worst = 0.0f64;
    for _ in 0..steps {
        cap.step().unwrap();
        for (k, xk) in x.iter_mut().enumerate() {
            let y = e * &*xk;
            for t in 0..n {
                for px in 1..=3 {
                    for py in 0..=3 {
                        let got = cap.node(t, px, py).unwrap().0[k];
                        worst = worst.max((got - y[ext_index(n, t, px.into(), py.into())]).abs());
                    }
                }
            }
            worst = worst.max((cap.center().0[k] - y[12 * n]).abs());
            *xk = s * &*xk;
        }
    }
    worst / size
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Kernel steps equal the dense matrix product, n = 3..=12, 4 steps.
    /// Tolerance 1e-12 of the net size: every new node is a convex
    /// combination (weights ≥ 0, sum 1) of at most 2n + 1 old ones, so each
    /// step adds a few roundings of the net size (measured worst: 3.6e-16).
    #[test]
    fn cc_step_equals_matrix_product((n, c) in cnet_strategy()) {
        let d = deviation(n, &c, 4);
        prop_assert!(d <= 1e-12, "n = {}: {:e}", n, d);
    }
}

/// The limit weights (left eigenvector of eigenvalue 1 of the reference's
/// dense matrix, solved by LU) are the closed form the kernel uses,
/// `n/(n+5)` on e, `4/(n(n+5))` on each (1,0), `1/(n(n+5))` on each (1,1),
/// 0 on the rest — for every n = 3..=12, n = 3 included (measured worst
/// 6.7e-16; bound 1e-12) — and the kernel's `limit()` equals `lᵀ c` on random
/// nets at levels 0..6 (measured 3.6e-16 of the net size; bound 1e-12).
#[test]
fn limit_is_left_eigenvector_of_eigenvalue_1() {
    let mut worst_w = 0.0f64;
    let mut worst_p = 0.0f64;
    for n in 3..=12 {
        let l = limit_weights(n);
        let nf = n as f64;
        for t in 0..n {
            for x in 1..=2 {
                for y in 0..=2 {
                    let want = match (x, y) {
                        (1, 0) => 4.0 / (nf * (nf + 5.0)),
                        (1, 1) => 1.0 / (nf * (nf + 5.0)),
                        _ => 0.0,
                    };
                    worst_w = worst_w.max((l[cnet_index(n, t, x, y)] - want).abs());
                }
            }
        }
        worst_w = worst_w.max((l[6 * n] - nf / (nf + 5.0)).abs());

        let mut rng = 0x2545_F491_4F6C_DD1Du64 ^ n as u64;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            20.0 * ((rng >> 11) as f64 / (1u64 << 53) as f64) - 10.0
        };
        let c: Vec<[f64; 3]> = (0..=6 * n).map(|_| [next(), next(), next()]).collect();
        let mut storage = vec![Point3::ZERO; CcCap::<f64>::storage_len(n)];
        let mut cap = CcCap::new(c[6 * n], &c[..6 * n], &mut storage).unwrap();
        let want: Vec<f64> = (0..3)
            .map(|k| (0..=6 * n).map(|i| l[i] * c[i][k]).sum())
            .collect();
        for _ in 0..6 {
            for (k, w) in want.iter().enumerate() {
                worst_p = worst_p.max((cap.limit().0[k] - w).abs() / 10.0);
            }
            cap.step().unwrap();
        }
    }
    println!("limit weights: worst {worst_w:.1e}; limit(): worst {worst_p:.1e}");
    assert!(worst_w < 1e-12, "{worst_w:e}");
    assert!(worst_p < 1e-12, "{worst_p:e}");
}

/// The kernel's tangent masks are left eigenvectors of the reference's
/// matrix for the subdominant eigenvalue λ_CC(n) = (5 + cos(2π/n) +
/// cos(π/n)√(2(9 + cos(2π/n))))/16: `t(S c) = λ t(c)` for the masks `w`
/// read off the kernel (limit_tangents is linear in the net: applied to the
/// unit nets), i.e. `Sᵀ w = λ w`. Measured worst |Sᵀw − λw| / |w|: 7.2e-16
/// (n = 3..=12); bound 1e-12.
#[test]
fn tangent_masks_are_subdominant_left_eigenvectors() {
    let mut worst = 0.0f64;
    for n in 3..=12 {
        let (_, s) = matrices(n);
        let dim = 6 * n + 1;
        let mut w1 = DVector::zeros(dim);
        let mut w2 = DVector::zeros(dim);
        let mut storage = vec![Point3::ZERO; CcCap::<f64>::storage_len(n)];
        for j in 0..dim {
            let mut c = vec![[0.0f64; 3]; dim];
            c[j][0] = 1.0;
            let cap = CcCap::new(c[6 * n], &c[..6 * n], &mut storage).unwrap();
            let (t1, t2) = cap.limit_tangents().unwrap();
            w1[j] = t1.0[0];
            w2[j] = t2.0[0];
        }
        let t = std::f64::consts::PI / n as f64;
        let c2 = (2.0 * t).cos();
        let lambda = (5.0 + c2 + t.cos() * (2.0 * (9.0 + c2)).sqrt()) / 16.0;
        for w in [&w1, &w2] {
            let r = s.transpose() * w - w * lambda;
            worst = worst.max(r.amax() / w.amax());
        }
    }
    println!("tangent masks: worst {worst:.1e}");
    assert!(worst < 1e-12, "{worst:e}");
}
