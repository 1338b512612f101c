//! The kernel's EG step against the reference's dense subdivision matrix
//! (docs/math/eg.md §5–§7): for random d-nets, `step()` equals `A_n · (d, c0)`.
//!
//! The matrix is assembled in `capdiv_reference::eg` from the spec's arrays
//! and frame rules, sharing no code with `src/eg`. Tolerance 1e-12 of the net's
//! size: each new node is a combination of at most 12n + 1 old ones with
//! weights of L1 norm below 4 (largest |a| sum over a row, n ≤ 5), so
//! round-off stays far below it (measured: a few 1e-16).

use capdiv::eg::{DNet, EgSubdivision, FourierRule, RuleTable};
use capdiv_reference::eg::{d_index, matrix};
use nalgebra::DVector;
use proptest::prelude::*;

fn dnet_strategy(n: usize) -> impl Strategy<Value = (Vec<[[f64; 3]; 12]>, [f64; 3])> {
    let coord = -10.0f64..10.0;
    let point = [coord.clone(), coord.clone(), coord.clone()];
    (
        proptest::collection::vec(proptest::array::uniform12(point.clone()), n),
        point,
    )
}

/// Worst |kernel − matrix| over all nodes after one step, relative to the net size.
fn deviation(n: usize, sectors: &[[[f64; 3]; 12]], c0: [f64; 3], user_table: bool) -> f64 {
    deviation_by(n, sectors, c0, user_table, false)
}

/// [`deviation`] of `step` or, with `fourier`, of `step_fourier` (the
/// Fourier rule of the subdivision's table).
fn deviation_by(
    n: usize,
    sectors: &[[[f64; 3]; 12]],
    c0: [f64; 3],
    user_table: bool,
    fourier: bool,
) -> f64 {
    let a = matrix(n, None).expect("built-in table");
    let net = DNet::from_sectors(sectors, Some(c0)).expect("valid d-net");
    let mut eg = if user_table {
        EgSubdivision::new(&net, Some(RuleTable::builtin(n).expect("built-in"))).unwrap()
    } else {
        EgSubdivision::new(&net, None).unwrap()
    };
    if fourier {
        let rule = FourierRule::new(eg.table().expect("EG table")).unwrap();
        eg.step_fourier(&rule).unwrap();
    } else {
        eg.step().unwrap();
    }

    let dim = 12 * n + 1;
    let mut worst = 0.0f64;
    let mut size = 0.0f64;
    for k in 0..3 {
        let mut x = DVector::zeros(dim);
        for (s, sector) in sectors.iter().enumerate() {
            for i in 0..4 {
                for j in 0..3 {
                    x[d_index(s, i, j)] = sector[i + 4 * j][k];
                }
            }
        }
        x[12 * n] = c0[k];
        size = size.max(x.amax());
        let y = &a * &x;
        for s in 0..n {
            for i in 0..4 {
                for j in 0..3 {
                    let got = eg.net().node(s, i, j).unwrap().0[k];
                    worst = worst.max((got - y[d_index(s, i, j)]).abs());
                }
            }
        }
        worst = worst.max((eg.limit().0[k] - y[12 * n]).abs());
    }
    worst / size.max(1e-300)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn eg_step_equals_matrix_product_n3((sectors, c0) in dnet_strategy(3)) {
        prop_assert!(deviation(3, &sectors, c0, false) <= 1e-12);
    }

    #[test]
    fn eg_step_equals_matrix_product_n5((sectors, c0) in dnet_strategy(5)) {
        prop_assert!(deviation(5, &sectors, c0, false) <= 1e-12);
    }

    #[test]
    fn eg_step_with_builtin_as_user_table_equals_matrix((sectors, c0) in dnet_strategy(5)) {
        prop_assert!(deviation(5, &sectors, c0, true) <= 1e-12);
    }

    /// The Fourier path against the same matrix, same
    /// tolerance: the transform's sums have at most 2n terms of weight ≤ 2
    /// per product, so its round-off stays at a few 1e-16 as well.
    #[test]
    fn eg_step_fourier_equals_matrix_product_n3((sectors, c0) in dnet_strategy(3)) {
        prop_assert!(deviation_by(3, &sectors, c0, false, true) <= 1e-12);
    }

    #[test]
    fn eg_step_fourier_equals_matrix_product_n5((sectors, c0) in dnet_strategy(5)) {
        prop_assert!(deviation_by(5, &sectors, c0, false, true) <= 1e-12);
    }

    #[test]
    fn eg_step_fourier_with_user_table_equals_matrix((sectors, c0) in dnet_strategy(5)) {
        prop_assert!(deviation_by(5, &sectors, c0, true, true) <= 1e-12);
    }
}

/// The measured worst case, printed for the record (`--nocapture`).
#[test]
fn eg_step_matrix_deviation_report() {
    let mut worst = 0.0f64;
    let mut fourier = 0.0f64;
    for n in [3usize, 5] {
        for seed in 0..50u64 {
            let mut s = seed.wrapping_add(n as u64 * 1000);
            let mut rnd = || {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                ((s >> 11) as f64 / (1u64 << 53) as f64) * 20.0 - 10.0
            };
            let sectors: Vec<[[f64; 3]; 12]> = (0..n)
                .map(|_| std::array::from_fn(|_| [rnd(), rnd(), rnd()]))
                .collect();
            let c0 = [rnd(), rnd(), rnd()];
            worst = worst.max(deviation(n, &sectors, c0, false));
            fourier = fourier.max(deviation_by(n, &sectors, c0, false, true));
        }
    }
    println!("EG kernel step vs reference matrix: worst relative deviation {worst:.2e}");
    println!("EG kernel step_fourier vs reference matrix: worst relative deviation {fourier:.2e}");
    assert!(fourier <= 1e-12);
    assert!(worst <= 1e-12);
}
