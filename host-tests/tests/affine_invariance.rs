//! Affine invariance of both schemes: refining the image of a configuration
//! under `x ↦ M x + t` gives the image of the refined configuration, for the
//! kernel's C²PS (either first step) and RTS steps. Every rule's weights sum
//! to 1 (docs/math/c2ps.md §2, §3), so this must hold to round-off.
//!
//! Tolerance: 1e-11 · S with S = max(|image coordinates|, ‖M‖∞ · size):
//! a few levels of round-off at ≤ 1e-15 S each, with margin for the sums of
//! up to 16384 terms.

mod common;

use capdiv::FirstStep;
use capdiv_reference::polar::Polar;
use common::*;
use proptest::prelude::*;

fn affine_map() -> impl Strategy<Value = ([[f64; 3]; 3], [f64; 3])> {
    let row = || [-2.0f64..2.0, -2.0f64..2.0, -2.0f64..2.0];
    (
        [row(), row(), row()],
        [-5.0f64..5.0, -5.0f64..5.0, -5.0f64..5.0],
    )
}

fn scale_of(cfg: &Polar, m: &[[f64; 3]; 3], t: &[f64; 3]) -> f64 {
    let norm_inf = m
        .iter()
        .map(|r| r.iter().map(|x| x.abs()).sum::<f64>())
        .fold(0.0, f64::max);
    cfg.affine(m, t).max_abs().max(norm_inf * cfg.max_abs())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn c2ps_refinement_commutes_with_affine_maps(
        cfg in config(3..=64, 2..=5),
        depth in 1u32..=8,
        (m, t) in affine_map(),
        first in prop_oneof![Just(FirstStep::Plain), Just(FirstStep::Uniform)],
    ) {
        let mut a: Box<Net> = Box::new(to_net(&cfg.affine(&m, &t)));
        let mut b: Box<Net> = Box::new(to_net(&cfg));
        for _ in 0..depth {
            a.step(first).unwrap();
            b.step(first).unwrap();
        }
        let err = max_diff(&from_net(&a), &from_net(&b).affine(&m, &t));
        prop_assert!(err <= 1e-11 * scale_of(&cfg, &m, &t), "{err:e}");
    }

    #[test]
    fn rts_refinement_commutes_with_affine_maps(
        cfg in config(3..=64, 2..=5),
        steps in 1usize..=8,
        (m, t) in affine_map(),
    ) {
        let mut a: Box<Net> = Box::new(to_net(&cfg.affine(&m, &t)));
        let mut b: Box<Net> = Box::new(to_net(&cfg));
        for _ in 0..steps {
            a.rts_step().unwrap();
            b.rts_step().unwrap();
        }
        let err = max_diff(&from_net(&a), &from_net(&b).affine(&m, &t));
        prop_assert!(err <= 1e-11 * scale_of(&cfg, &m, &t), "{err:e}");
    }
}
