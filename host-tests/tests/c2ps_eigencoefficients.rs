//! docs/math/c2ps.md §4 and §6 item 2: Lemma 5 scaling of the eigencoefficients,
//! the exact closed forms of the pole and the 1-link, the `O(8^-m)` 2-link,
//! for C²PS with and without the first-step variant; the kernel's `PoleJet`
//! against the reference's independently written `p0..p5` and curvatures.
//!
//! Sizes: the kernel is O(n) per step, so every case runs the full range,
//! valences 3..64 and depths 0..8 (valence up to 16384).
//!
//! Tolerances are absolute, relative to the configuration's size `s` (largest
//! absolute coordinate, ≤ 1 here): "exact" identities hold to round-off, whose
//! worst case for sums of `N ≤ 16384` terms is about `N·ε·s ≈ 4e-12 s`;
//! measured ≤ 6e-15 s. We assert 1e-12 s.

// Parallel arrays p[k], want[k], λ_k are clearer indexed.
#![allow(clippy::needless_range_loop)]

mod common;

use capdiv::{FirstStep, PoleJet};
use capdiv_reference::jet::{self, EIGENVALUES};
use capdiv_reference::vec3::{max_abs_diff, scale, P3};
use common::*;
use proptest::prelude::*;

const TOL: f64 = 1e-12;

fn first_step() -> impl Strategy<Value = FirstStep> {
    prop_oneof![Just(FirstStep::Plain), Just(FirstStep::Uniform)]
}

fn kernel_jet(net: &Net) -> [P3; 6] {
    PoleJet::of(net).p.map(|q| q.0)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Lemma 5: `p_k(level m) = λ_k^m p_k(level 0)`, `λ = (1, ½, ½, ¼, ¼, ¼)`,
    /// for every level, either first step. The kernel's jet at level m is
    /// compared with λ^m times the reference's jet of the level-0 data.
    #[test]
    fn lemma5_eigencoefficients_scale_by_eigenvalue_powers(
        cfg in config(3..=64, 2..=5),
        depth in 0u32..=8,
        first in first_step(),
    ) {
        let p = jet::coefficients(&cfg);
        let size = cfg.max_abs();
        let mut net: Box<Net> = Box::new(to_net(&cfg));
        for m in 0..=depth {
            if m > 0 {
                net.step(first).unwrap();
            }
            let pm = kernel_jet(&net);
            for k in 0..6 {
                let want = scale(EIGENVALUES[k].powi(m as i32), p[k]);
                let err = max_abs_diff(pm[k], want);
                prop_assert!(err <= TOL * size, "level {m}, p{k}: {err:e}");
            }
        }
    }

    /// Eq. (30), exact for links 0 and 1: `q00 = p0 − μ^m/3 p3` and
    /// `q1[j] = p0 + λ^m (p1 c + p2 s) + 2/3 μ^m (p3 + p4 c2 + p5 s2)` at
    /// `τ = j/N`: the pole at every level, the 1-link from level 1 on, either
/// first step.
    #[test]
    fn pole_and_link1_equal_their_closed_forms_at_every_level(
        cfg in config(3..=64, 2..=5),
        depth in 0u32..=8,
        first in first_step(),
    ) {
        let p = jet::coefficients(&cfg);
        let size = cfg.max_abs();
        let mut net: Box<Net> = Box::new(to_net(&cfg));
        for m in 0..=depth {
            if m > 0 {
                net.step(first).unwrap();
            }
            let q = from_net(&net);
            let err = max_abs_diff(q.pole, jet::pole_closed(&p, m));
            prop_assert!(err <= TOL * size, "level {m}, pole: {err:e}");
            if m == 0 {
                // Level-0 data is arbitrary: its 1-link has every Fourier
                // mode. From level 1 on, rule (2) leaves only modes 0, 1, 2.
                continue;
            }
            let big_n = q.valence();
            for (j, &x) in q.links[0].iter().enumerate() {
                let err = max_abs_diff(x, jet::link1_closed(&p, m, j, big_n));
                prop_assert!(err <= TOL * size, "level {m}, q1[{j}]: {err:e}");
            }
        }
    }

    /// Eq. (30)/(39): the 2-link deviates from
    /// `p0 + 2λ^m (p1 c + p2 s) + 11/3 μ^m (p3 + p4 c2 + p5 s2)` by `O(8^-m)`.
    /// Bound: the spec's "≤ 70" for `deviation·8^m / size`; measured ≤ 22 over
    /// 600 random configurations (valences 3..64, 2..5 links, either first
    /// step). The bound is checked at every level 1..8, so a slower decay
    /// (e.g. `4^-m`) would exceed it by level 8.
    #[test]
    fn link2_deviation_times_8_to_the_m_stays_bounded(
        cfg in config(3..=64, 2..=5),
        first in first_step(),
    ) {
        let p = jet::coefficients(&cfg);
        let size = cfg.max_abs();
        let mut net: Box<Net> = Box::new(to_net(&cfg));
        for m in 1..=8u32 {
            net.step(first).unwrap();
            let q = from_net(&net);
            let big_n = q.valence();
            let dev = q.links[1]
                .iter()
                .enumerate()
                .map(|(j, &x)| max_abs_diff(x, jet::link2_leading(&p, m, j, big_n)))
                .fold(0.0, f64::max);
            let scaled = dev * 8f64.powi(m as i32) / size;
            prop_assert!(scaled <= 70.0, "level {m}: deviation·8^m/size = {scaled}");
        }
    }

    /// docs/math/c2ps.md §2: the first-step variant changes neither the eigencoefficients
    /// nor the pole and 1-link at any level (only links ≥ 2 differ).
    #[test]
    fn first_step_variant_changes_neither_jet_nor_links_0_and_1(
        cfg in config(3..=64, 2..=5),
        depth in 1u32..=8,
    ) {
        let size = cfg.max_abs();
        let mut plain: Box<Net> = Box::new(to_net(&cfg));
        let mut uniform: Box<Net> = Box::new(to_net(&cfg));
        for m in 1..=depth {
            plain.step(FirstStep::Plain).unwrap();
            uniform.step(FirstStep::Uniform).unwrap();
            let (a, b) = (kernel_jet(&plain), kernel_jet(&uniform));
            for k in 0..6 {
                prop_assert!(max_abs_diff(a[k], b[k]) <= TOL * size, "level {m}, p{k}");
            }
            let (qa, qb) = (from_net(&plain), from_net(&uniform));
            prop_assert!(max_abs_diff(qa.pole, qb.pole) <= TOL * size);
            for (x, y) in qa.links[0].iter().zip(&qb.links[0]) {
                prop_assert!(max_abs_diff(*x, *y) <= TOL * size, "level {m}, 1-link");
            }
        }
    }

    /// The kernel's `PoleJet::of` and `geometry()` equal the reference's
    /// `p0..p5` (std `cos`/`sin`) and its shape-operator curvatures.
    /// Curvatures are compared relative to `1 + |κ|` at tolerance 1e-9: they
    /// divide by `EG − F²`, which random data keeps away from 0 only loosely
    /// (cases with `EG − F² < 1e-3 |p1|²|p2|²` are skipped as ill-conditioned).
    #[test]
    fn kernel_jet_and_curvatures_equal_reference(cfg in config(3..=64, 2..=5)) {
        let net: Box<Net> = Box::new(to_net(&cfg));
        let kp = PoleJet::of(&*net);
        let p = jet::coefficients(&cfg);
        for k in 0..6 {
            prop_assert!(max_abs_diff(kp.p[k].0, p[k]) <= TOL * cfg.max_abs(), "p{k}");
        }
        let (e, f, g) = (p[1][0] * p[1][0] + p[1][1] * p[1][1] + p[1][2] * p[1][2],
            p[1][0] * p[2][0] + p[1][1] * p[2][1] + p[1][2] * p[2][2],
            p[2][0] * p[2][0] + p[2][1] * p[2][1] + p[2][2] * p[2][2]);
        prop_assume!(e * g - f * f > 1e-3 * e * g);
        let want = jet::geometry(&p).expect("non-degenerate");
        let got = kp.geometry().expect("non-degenerate");
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * (1.0 + b.abs());
        prop_assert!(max_abs_diff(got.normal.0, want.normal) <= 1e-12);
        prop_assert!(close(got.gaussian, want.gaussian), "K {} vs {}", got.gaussian, want.gaussian);
        prop_assert!(close(got.mean, want.mean), "H {} vs {}", got.mean, want.mean);
        // √(H²−K) turns a round-off δ into √δ near umbilics: √ε-level tolerance.
        let close_p = |a: f64, b: f64| (a - b).abs() <= 1e-6 * (1.0 + b.abs());
        prop_assert!(close_p(got.principal[0], want.principal[0]));
        prop_assert!(close_p(got.principal[1], want.principal[1]));
    }
}

/// A configuration built from Table 1's right eigenvectors with
/// `p = (0, e_x, e_y, a e_z, b e_z, 0)` has the limit surface
/// `z = (a+b) x² + (a−b) y² + o(r²)` at the pole, so `K = 4(a+b)(a−b)`,
/// `H = 2a`, principal curvatures `2(a+b)`, `2(a−b)` and normal `e_z`:
/// values from calculus, not from either implementation. Valences ≥ 5 (for
/// n = 3, 4 the second harmonic aliases, see the RTS spectrum tests).
#[test]
fn quadric_eigen_configuration_has_its_analytic_jet_and_curvatures() {
    for n in 5..=64 {
        for (a, b) in [(0.5, 0.25), (-0.3, 0.7), (1.0, 0.0)] {
            let p: [P3; 6] = [
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, a],
                [0.0, 0.0, b],
                [0.0; 3],
            ];
            let cfg = jet::eigen_configuration(&p, n, 5);
            let net: Box<Net> = Box::new(to_net(&cfg));
            let kp = PoleJet::of(&*net);
            for k in 0..6 {
                assert!(max_abs_diff(kp.p[k].0, p[k]) < 1e-13, "n {n}: p{k}");
                assert!(max_abs_diff(jet::coefficients(&cfg)[k], p[k]) < 1e-13);
            }
            let g = kp.geometry().unwrap();
            let r = jet::geometry(&p).unwrap();
            let (k_want, h_want) = (4.0 * (a + b) * (a - b), 2.0 * a);
            let (k1, k2) = (2.0 * (a + b), 2.0 * (a - b));
            let (hi, lo) = (k1.max(k2), k1.min(k2));
            for (kk, hh, pr, nr) in [
                (g.gaussian, g.mean, g.principal, g.normal.0),
                (r.gaussian, r.mean, r.principal, r.normal),
            ] {
                assert!((kk - k_want).abs() < 1e-12 && (hh - h_want).abs() < 1e-12);
                // Principal curvatures are `H ± √(H²−K)`: a round-off δ in
                // `H²−K` moves them by √δ at an umbilic (a = 1, b = 0), so
                // they get √ε-level tolerance: 1e-7.
                assert!(
                    (pr[0] - hi).abs() < 1e-7 && (pr[1] - lo).abs() < 1e-7,
                    "n {n}, a {a}, b {b}: principal {pr:?}, want {hi}, {lo}"
                );
                assert!(max_abs_diff(nr, [0.0, 0.0, 1.0]) < 1e-13, "normal {nr:?}");
            }
        }
    }
}
