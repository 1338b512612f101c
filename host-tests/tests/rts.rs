//! docs/math/c2ps.md §3: RTS. The dense subdivision matrix assembled entry by entry
//! from the paper's (9)–(12) (`capdiv_reference::rts::matrix`) has the
//! dominant spectrum 1, ½, ½, ¼, ¼, ¼ (valence ≥ 5), and the kernel's
//! `rts_step` is that matrix's product with the configuration.

mod common;

use capdiv_reference::jet;
use capdiv_reference::polar::Polar;
use capdiv_reference::rts;
use capdiv_reference::vec3::{max_abs_diff, scale};
use common::*;
use nalgebra::Complex;
use proptest::prelude::*;

/// Eigenvalue tolerance 1e-10: the leading eigenvalues are semisimple and
/// well separated (next |λ| is 1/12), so the QR iteration gets them to a few
/// ulps times the matrix norm (~1); measured ≤ 2e-14 for n ≤ 64.
const EIG_TOL: f64 = 1e-10;

fn assert_leading(ev: &[Complex<f64>], want: &[f64], n: usize) {
    for (k, (z, w)) in ev.iter().zip(want).enumerate() {
        assert!(
            (z - Complex::new(*w, 0.0)).norm() < EIG_TOL,
            "n {n}: eigenvalue {k} is {z}, want {w}"
        );
    }
}

/// Valences 5..=64: the six largest eigenvalues of the `(1+3n)²` state matrix
/// (pole, links 1..3) are 1, ½, ½, ¼, ¼, ¼, and every other has modulus
/// `1/12 + 1e-10` at most (μ = ¼ strictly dominates the rest).
#[test]
fn rts_matrix_dominant_spectrum_is_1_half_half_quarter_quarter_quarter() {
    for n in 5..=64 {
        let ev = rts::eigenvalues_by_modulus(&rts::state_matrix(n));
        assert_eq!(ev.len(), 1 + 3 * n);
        assert_leading(&ev, &[1.0, 0.5, 0.5, 0.25, 0.25, 0.25], n);
        assert!(ev[6].norm() < 1.0 / 12.0 + EIG_TOL, "n {n}: λ6 = {}", ev[6]);
    }
}

/// The full `(1+5n)²` matrix adds only zeros (no new point reads links 4, 5):
/// same leading six eigenvalues, for a few valences (the full matrix is
/// larger; 5..64 is covered by the state matrix above).
#[test]
fn rts_full_matrix_has_the_state_matrix_spectrum_plus_zeros() {
    for n in [5, 6, 9, 16] {
        let full = rts::eigenvalues_by_modulus(&rts::matrix(n));
        let state = rts::eigenvalues_by_modulus(&rts::state_matrix(n));
        assert_leading(&full, &[1.0, 0.5, 0.5, 0.25, 0.25, 0.25], n);
        // Zero eigenvalues sit in Jordan blocks, so they come out as ε^(1/k)
        // for block size k (≈ 1e-5 for k = 3); every nonzero eigenvalue of RTS
        // has modulus ≥ 1/12 (Fourier symbols ½, ¼, 1/12 on the diagonal), so
        // 1e-3 separates them.
        let zeros = full.iter().filter(|z| z.norm() < 1e-3).count();
        let state_zeros = state.iter().filter(|z| z.norm() < 1e-3).count();
        assert_eq!(zeros, state_zeros + 2 * n, "n {n}");
    }
}

/// Where the spec's "1, ½, ½, ¼, ¼, ¼" does not hold: for n = 3 and 4 the
/// second harmonic aliases onto the first (n = 3: c(2h/3) = c(h/3)) or onto
/// itself (n = 4: c(2h/4) = (−1)^h, s(2h/4) = 0), and the Fourier symbols of
/// eq. (4) become b̂_1 = ½ + ¼ = ¾ (n = 3) and b̂_2 = ¼ + ¼ = ½ (n = 4). The
/// paper stipulates n ≥ 5 (§5.2). Expected values from that hand computation.
#[test]
fn rts_spectrum_for_valences_3_and_4_differs_by_aliasing() {
    let ev3 = rts::eigenvalues_by_modulus(&rts::state_matrix(3));
    assert_leading(&ev3, &[1.0, 0.75, 0.75, 0.25], 3);
    assert!(ev3[4].norm() < 1.0 / 12.0 + EIG_TOL);
    let ev4 = rts::eigenvalues_by_modulus(&rts::state_matrix(4));
    assert_leading(&ev4, &[1.0, 0.5, 0.5, 0.5, 0.25], 4);
    assert!(ev4[5].norm() < 1.0 / 12.0 + EIG_TOL);
}

/// Table 1's right eigenvectors are eigenvectors of the assembled matrix:
/// `A v_k = λ_k v_k` (n ≥ 5), a check of the matrix entries independent of
/// the eigenvalue solver.
#[test]
fn table1_right_eigenvectors_are_eigenvectors_of_the_matrix() {
    for n in 5..=24 {
        let a = rts::matrix(n);
        for k in 0..6 {
            let mut p = [[0.0; 3]; 6];
            p[k] = [1.0, -0.5, 0.25];
            let v = jet::eigen_configuration(&p, n, 5);
            let av = rts::apply_matrix(&a, &v);
            let mut want = v.clone();
            // Scale v by λ_k (pole and every link).
            let l = jet::EIGENVALUES[k];
            want.pole = want.pole.map(|c| c * l);
            for link in &mut want.links {
                for q in link.iter_mut() {
                    *q = q.map(|c| c * l);
                }
            }
            let err = max_diff(&av, &want);
            assert!(err < 1e-12 * v.max_abs(), "n {n}, v{k}: {err:e}");
        }
    }
}

/// For n = 3, 4 Lemma 5 fails for RTS (not for C²PS, whose first step
/// doubles the valence before the aliasing matters): with `b̂_1 = ¾` (n = 3),
/// `p1, p2` shrink by ¾ per step; with `b̂_2 = ½` (n = 4), `p4` shrinks by ½.
/// Data: Table-1 eigen-configurations with one `p_k ≠ 0` (hand computation
/// above; the kernel's `rts_step` and `PoleJet`).
#[test]
fn rts_lemma5_fails_for_valences_3_and_4() {
    for (n, k, factor) in [(3usize, 1usize, 0.75), (3, 2, 0.75), (4, 4, 0.5)] {
        let mut p = [[0.0; 3]; 6];
        p[k] = [1.0, 2.0, -1.0];
        let cfg = jet::eigen_configuration(&p, n, 5);
        let mut net: Box<Net> = Box::new(to_net(&cfg));
        let p0 = capdiv::PoleJet::of(&*net).p[k].0;
        net.rts_step().unwrap();
        let p1 = capdiv::PoleJet::of(&*net).p[k].0;
        for c in 0..3 {
            assert!(
                (p1[c] - factor * p0[c]).abs() < 1e-12,
                "n {n}, p{k}: {p1:?} vs {factor}·{p0:?}"
            );
            assert!((p1[c] - jet::EIGENVALUES[k] * p0[c]).abs() > 0.1 * p0[c].abs());
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Lemma 5 for RTS (docs/math/c2ps.md §4), valences 5..64, up to 8 steps:
    /// `p_k` after m RTS steps is `λ_k^m p_k`, to 1e-12 · size.
    #[test]
    fn rts_eigencoefficients_scale_by_eigenvalue_powers(
        cfg in config(5..=64, 2..=5),
        steps in 1u32..=8,
    ) {
        let p = jet::coefficients(&cfg);
        let mut net: Box<Net> = Box::new(to_net(&cfg));
        for m in 1..=steps {
            net.rts_step().unwrap();
            let pm = capdiv::PoleJet::of(&*net).p;
            for k in 0..6 {
                let l = jet::EIGENVALUES[k].powi(m as i32);
                let err = max_abs_diff(pm[k].0, scale(l, p[k]));
                prop_assert!(err <= 1e-12 * cfg.max_abs(), "step {m}, p{k}: {err:e}");
            }
        }
    }

    /// The kernel's in-place O(n) `rts_step`, applied 1..3 times, equals the
    /// dense matrix product, and so does the literal O(n²) `rts::step`.
    /// Tolerance 1e-12 · size: ≤ 3 steps of sums of ≤ 321 terms of size ≤ 1
    /// per entry, round-off of order 1e-15 · size.
    #[test]
    fn kernel_rts_step_equals_dense_matrix_product(
        cfg in config(3..=64, 2..=5),
        steps in 1usize..=3,
    ) {
        let a = rts::matrix(cfg.valence());
        let size = cfg.max_abs();
        let mut net: Box<Net> = Box::new(to_net(&cfg));
        let mut by_matrix: Polar = cfg.clone();
        let mut literal: Polar = cfg.clone();
        for s in 1..=steps {
            net.rts_step().unwrap();
            by_matrix = rts::apply_matrix(&a, &by_matrix);
            literal = rts::step(&literal);
            let kernel = from_net(&net);
            prop_assert_eq!(kernel.valence(), cfg.valence());
            let err = max_diff(&kernel, &by_matrix);
            prop_assert!(err <= 1e-12 * size, "step {s}: kernel vs matrix {err:e}");
            let err = max_diff(&literal, &by_matrix);
            prop_assert!(err <= 1e-12 * size, "step {s}: literal vs matrix {err:e}");
        }
    }
}
