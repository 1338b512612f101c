//! `EgSubdivision::step_fourier` (the fast EG step, `FourierRule`):
//! the same subdivision as `step` over many steps, its errors, and the
//! overflow contract (state unchanged on `NonFinite`). The matrix comparison
//! is in `host-tests/tests/eg_kernel_vs_matrix.rs`, the f32 bound in
//! `tests/eg_precision.rs`.

use capdiv::eg::{DNet, EgSubdivision, FourierRule, RuleTable};
use capdiv::Error;

fn next(seed: &mut u64) -> f64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    (*seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
}

fn dnet(n: usize, scale: f64, seed: &mut u64) -> DNet<f64> {
    let sectors: Vec<[[f64; 3]; 12]> = (0..n)
        .map(|_| std::array::from_fn(|_| [next(seed), next(seed), next(seed)].map(|c| c * scale)))
        .collect();
    DNet::from_sectors(&sectors, Some([0.1 * scale, -0.2 * scale, 0.3 * scale])).unwrap()
}

/// Ten steps of both paths from one net: every node and ring patch agrees to
/// 1e-13 of the net's size (each step's rounding, a few 1e-16, over steps
/// that contract towards c0; measured below 1e-15).
#[test]
fn fourier_steps_follow_the_dense_steps() {
    let mut seed = 0x1234_5678_9abc_def1u64;
    for n in [3usize, 5] {
        for _ in 0..if cfg!(miri) { 1 } else { 10 } {
            let net = dnet(n, 10.0, &mut seed);
            let mut dense = EgSubdivision::new(&net, None).unwrap();
            let mut fast = EgSubdivision::new(&net, None).unwrap();
            let rule = FourierRule::new(fast.table().unwrap()).unwrap();
            assert_eq!(rule.valence(), n);
            for _ in 0..if cfg!(miri) { 2 } else { 10 } {
                dense.step().unwrap();
                fast.step_fourier(&rule).unwrap();
                assert_eq!(dense.level(), fast.level());
                let nodes = dense.net().sectors().iter().flatten();
                for (p, q) in nodes.zip(fast.net().sectors().iter().flatten()) {
                    assert!(p.max_abs_diff(*q) < 1e-13 * 10.0);
                }
                for (a, b) in dense.ring_patches().zip(fast.ring_patches()) {
                    for (ra, rb) in a.points.iter().zip(b.points.iter()) {
                        for (p, q) in ra.iter().zip(rb) {
                            assert!(p.max_abs_diff(*q) < 1e-13 * 10.0);
                        }
                    }
                }
            }
        }
    }
}

/// A rule of another valence, a valence-4 subdivision (no EG rule) and an
/// empty one: typed errors, state unchanged.
#[test]
fn wrong_valence_is_refused_and_nothing_changes() {
    let mut seed = 7u64;
    let rule5 = FourierRule::new(&RuleTable::builtin(5).unwrap()).unwrap();
    for n in [3usize, 4] {
        let mut sub = EgSubdivision::new(&dnet(n, 1.0, &mut seed), None).unwrap();
        let before = sub.clone();
        assert_eq!(sub.step_fourier(&rule5), Err(Error::TableShape));
        assert_eq!(sub.net(), before.net());
        assert_eq!(sub.level(), 0);
    }
    let mut empty = EgSubdivision::<f64>::empty();
    assert_eq!(
        empty.step_fourier(&rule5),
        Err(Error::ValenceTooSmall { valence: 0 })
    );
}

/// Beyond `MAX/1024` the Fourier step takes the dense step's check-first
/// path: a net that would overflow gives `NonFinite` with the state
/// unchanged, one that does not gives the dense step's nodes bit for bit.
/// Nets at 0.002, 0.25 and 0.9 of `MAX`: both outcomes occur.
#[test]
fn huge_nets_take_the_dense_path() {
    let mut seed = 99u64;
    let (mut ok, mut overflowed) = (0, 0);
    for _ in 0..if cfg!(miri) { 1 } else { 10 } {
        for scale in [f64::MAX / 512.0, f64::MAX / 4.0, f64::MAX * 0.9] {
            let net = dnet(5, scale, &mut seed);
            let mut dense = EgSubdivision::new(&net, None).unwrap();
            let mut fast = EgSubdivision::new(&net, None).unwrap();
            let rule = FourierRule::new(fast.table().unwrap()).unwrap();
            let before = fast.clone();
            let (a, b) = (dense.step(), fast.step_fourier(&rule));
            assert_eq!(a, b);
            if b.is_err() {
                assert_eq!(b, Err(Error::NonFinite));
                assert_eq!(fast.net(), before.net());
                assert_eq!(fast.level(), 0);
                overflowed += 1;
            } else {
                assert_eq!(fast.net(), dense.net());
                ok += 1;
            }
        }
    }
    assert!(
        ok > 0 && (overflowed > 0 || cfg!(miri)),
        "{ok} {overflowed}"
    );
}
