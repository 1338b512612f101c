//! One C²PS step, level m → m+1, valence n → 2n, written as the paper's
//! literal O(n²) sums (paper rules (1)–(5), (29); docs/math/c2ps.md §2), with
//! `std` `cos`.
//!
//! Rule (2) reads `q'[1][j] = ½ q00 + Σ_h b_{h−j/2} q[1][h]` and rule (3)
//! `q'[2][j] = 11/12 q̃1[j] + 1/12 q̃2[j] + Σ_h d_{h−j/2} q[1][h]` with the
//! weights of eq. (4):
//!
//! ```text
//! b_g = (1/n) (½ + c(g/n) + ½ c(2g/n)),      d_g = −1/(6n) c(g/n).
//! ```
//!
//! `g = h − j/2` is a multiple of ½ and the weights have period `n` in `g`, so
//! the `2n` distinct values `b_{k/2}`, `k = 0..2n`, are tabulated once and the
//! sum picks `k = (2h − j) mod 2n`: the same O(n²) sum, without `2n²` calls of
//! `cos`. (Expanding `c(a−b)` into `c(a)c(b) + s(a)s(b)` gives the spec's O(n)
//! form; this module deliberately does not.)

use crate::polar::Polar;
use crate::vec3::{axpy, scale, P3, ZERO};
use std::f64::consts::TAU;

/// Links a refined configuration keeps (links 1..5 define one surface ring).
pub const MAX_LINKS: usize = 5;

/// Which rule computes the new 2-link.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TwoLinkRule {
    /// Rule (3) with the weights `d_g` of eq. (4).
    Plain,
    /// The first-step variant (paper §6, docs/math/c2ps.md §2): the uniform radial rule with
    /// the pole standing in for link 0, `(q00 + 6 q̃1 + q̃2)/8`.
    Uniform,
}

/// `b_g` of eq. (4) for valence `n` (the old valence `n_m`).
pub fn b(g: f64, n: usize) -> f64 {
    let nf = n as f64;
    (0.5 + (TAU * g / nf).cos() + 0.5 * (TAU * 2.0 * g / nf).cos()) / nf
}

/// `d_g` of eq. (4) for valence `n`.
pub fn d(g: f64, n: usize) -> f64 {
    let nf = n as f64;
    -(TAU * g / nf).cos() / (6.0 * nf)
}

/// Uniform cubic periodic refinement of one link, paper rule (5):
/// `ũ[2j] = (u[j−1] + 6u[j] + u[j+1])/8`, `ũ[2j+1] = (u[j] + u[j+1])/2`.
pub fn refine_periodic(u: &[P3]) -> Vec<P3> {
    let n = u.len();
    let mut out = Vec::with_capacity(2 * n);
    for j in 0..n {
        let (prev, cur, next) = (u[(j + n - 1) % n], u[j], u[(j + 1) % n]);
        let even = scale(1.0 / 8.0, axpy(axpy(prev, 6.0, cur), 1.0, next));
        let odd = scale(0.5, axpy(cur, 1.0, next));
        out.push(even);
        out.push(odd);
    }
    out
}

/// New links `i ≥ 3`: uniform bi-3 refinement in the radial direction of the
/// periodically refined old links `qt[k-1]` = `q̃_k` (paper (29), generalised):
/// `i = 2k+1`: `(q̃_k + q̃_{k+1})/2`; `i = 2k`: `(q̃_{k−1} + 6 q̃_k + q̃_{k+1})/8`.
/// `None` when the old links needed are missing.
pub fn radial_link(qt: &[Vec<P3>], i: usize) -> Option<Vec<P3>> {
    let link = |k: usize| qt.get(k.checked_sub(1)?);
    let len = qt[0].len();
    if i % 2 == 1 {
        let k = (i - 1) / 2;
        let (a, b) = (link(k)?, link(k + 1)?);
        Some(
            (0..len)
                .map(|j| scale(0.5, axpy(a[j], 1.0, b[j])))
                .collect(),
        )
    } else {
        let k = i / 2;
        let (a, b, c) = (link(k - 1)?, link(k)?, link(k + 1)?);
        Some(
            (0..len)
                .map(|j| scale(1.0 / 8.0, axpy(axpy(a[j], 6.0, b[j]), 1.0, c[j])))
                .collect(),
        )
    }
}

/// One C²PS step with the given 2-link rule: valence `n → 2n`, links `K →
/// min(2K−1, 5)`. Needs at least the 1- and 2-link.
pub fn step_with(cfg: &Polar, two: TwoLinkRule) -> Polar {
    let n = cfg.valence();
    let n2 = 2 * n;
    let q00 = cfg.pole;
    let q1 = &cfg.links[0];
    let qt: Vec<Vec<P3>> = cfg.links.iter().map(|l| refine_periodic(l)).collect();
    // b_{k/2}, d_{k/2} for k = 0..2n: every weight rules (2), (3) use.
    let bw: Vec<f64> = (0..n2).map(|k| b(k as f64 / 2.0, n)).collect();
    let dw: Vec<f64> = (0..n2).map(|k| d(k as f64 / 2.0, n)).collect();
    let wsum = |w: &[f64], j: usize| -> P3 {
        let mut acc = ZERO;
        for (h, &q) in q1.iter().enumerate() {
            acc = axpy(acc, w[(2 * h + n2 - j) % n2], q);
        }
        acc
    };

    // (1): q00' = 3/4 q00 + 1/(4n) Σ_h q[1][h].
    let mut pole = scale(0.75, q00);
    for &q in q1 {
        pole = axpy(pole, 1.0 / (4.0 * n as f64), q);
    }
    // (2): q'[1][j] = ½ q00 + Σ_h b_{h−j/2} q[1][h].
    let l1: Vec<P3> = (0..n2).map(|j| axpy(wsum(&bw, j), 0.5, q00)).collect();
    // (3), or the first-step variant.
    let l2: Vec<P3> = (0..n2)
        .map(|j| match two {
            TwoLinkRule::Plain => {
                let base = axpy(scale(11.0 / 12.0, qt[0][j]), 1.0 / 12.0, qt[1][j]);
                axpy(base, 1.0, wsum(&dw, j))
            }
            TwoLinkRule::Uniform => scale(1.0 / 8.0, axpy(axpy(q00, 6.0, qt[0][j]), 1.0, qt[1][j])),
        })
        .collect();
    let mut links = vec![l1, l2];
    let target = (2 * cfg.links.len() - 1).min(MAX_LINKS);
    for i in 3..=target {
        match radial_link(&qt, i) {
            Some(l) => links.push(l),
            None => break,
        }
    }
    Polar { pole, links }
}

/// One plain C²PS step: rules (1)–(5), (29). The function benchmarks compare
/// the kernel's `PolarNet::step` (at level ≥ 1, or with `FirstStep::Plain`) to.
pub fn step(cfg: &Polar) -> Polar {
    step_with(cfg, TwoLinkRule::Plain)
}

/// One step with the first-step variant for the 2-link (docs/math/c2ps.md §2).
pub fn step_first_uniform(cfg: &Polar) -> Polar {
    step_with(cfg, TwoLinkRule::Uniform)
}

/// Levels `0..=depth`: `out[m]` is the m-times refined configuration; the
/// first step uses `first`, later steps the plain rules.
pub fn refine(cfg: &Polar, depth: u32, first: TwoLinkRule) -> Vec<Polar> {
    let mut out = vec![cfg.clone()];
    for m in 0..depth {
        let rule = if m == 0 { first } else { TwoLinkRule::Plain };
        let next = step_with(out.last().expect("level 0 is there"), rule);
        out.push(next);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The spec's O(n) form (§2) follows from eq. (4) by the addition theorem:
    /// check `Σ_h b_{h−j/2} q_h = ½A + H1(τ) + ½H2(2τ)` on scalar data.
    #[test]
    fn weights_of_eq4_expand_to_the_fourier_form() {
        for n in 3..20 {
            let q: Vec<f64> = (0..n).map(|h| ((h * 7 + 3) % 11) as f64 - 5.0).collect();
            let mean =
                |f: &dyn Fn(usize) -> f64| (0..n).map(|h| f(h) * q[h]).sum::<f64>() / n as f64;
            let a = mean(&|_| 1.0);
            let c = |k: f64, h: usize| (TAU * k * h as f64 / n as f64).cos();
            let s = |k: f64, h: usize| (TAU * k * h as f64 / n as f64).sin();
            let (c1, s1) = (mean(&|h| c(1.0, h)), mean(&|h| s(1.0, h)));
            let (c2, s2) = (mean(&|h| c(2.0, h)), mean(&|h| s(2.0, h)));
            for j in 0..2 * n {
                let tau = j as f64 / (2 * n) as f64;
                let lit: f64 = (0..n).map(|h| b(h as f64 - j as f64 / 2.0, n) * q[h]).sum();
                let h1 = c1 * (TAU * tau).cos() + s1 * (TAU * tau).sin();
                let h2 = c2 * (TAU * 2.0 * tau).cos() + s2 * (TAU * 2.0 * tau).sin();
                assert!((lit - (0.5 * a + h1 + 0.5 * h2)).abs() < 1e-13);
                let litd: f64 = (0..n).map(|h| d(h as f64 - j as f64 / 2.0, n) * q[h]).sum();
                assert!((litd + h1 / 6.0).abs() < 1e-13);
            }
        }
    }
}
