//! RTS, the stationary auxiliary scheme (paper §5.2, rules (9)–(12); spec
//! docs/math/c2ps.md §3): the C²PS rules with the valence kept, `q̃ = q` and `b_{h−j}`,
//! `d_{h−j}` in place of `b_{h−j/2}`, `d_{h−j/2}`.
//!
//! Two independent forms: [`step`], the literal sums, and [`matrix`], the
//! dense subdivision matrix on the state `[q00, link 1, …, link 5]`
//! (`1 + 5n` rows), whose leading `1 + 3n` block [`state_matrix`] (pole and
//! links 1..3, which carry all the state) gives the spectrum.

use crate::c2ps::{b, d, radial_link, MAX_LINKS};
use crate::polar::Polar;
use crate::vec3::{axpy, scale, P3, ZERO};
use nalgebra::{Complex, DMatrix};

/// One RTS step as the literal sums (9)–(12). Links `K → min(2K−1, 5)`.
pub fn step(cfg: &Polar) -> Polar {
    let n = cfg.valence();
    let q00 = cfg.pole;
    let q1 = &cfg.links[0];
    let wsum = |w: &dyn Fn(f64) -> f64, j: usize| -> P3 {
        let mut acc = ZERO;
        for (h, &q) in q1.iter().enumerate() {
            acc = axpy(acc, w(h as f64 - j as f64), q);
        }
        acc
    };
    // (9)
    let mut pole = scale(0.75, q00);
    for &q in q1 {
        pole = axpy(pole, 1.0 / (4.0 * n as f64), q);
    }
    // (10), (11)
    let l1: Vec<P3> = (0..n)
        .map(|j| axpy(wsum(&|g| b(g, n), j), 0.5, q00))
        .collect();
    let l2: Vec<P3> = (0..n)
        .map(|j| {
            let base = axpy(scale(11.0 / 12.0, q1[j]), 1.0 / 12.0, cfg.links[1][j]);
            axpy(base, 1.0, wsum(&|g| d(g, n), j))
        })
        .collect();
    // (12): uniform radial refinement of the unrefined links.
    let mut links = vec![l1, l2];
    let target = (2 * cfg.links.len() - 1).min(MAX_LINKS);
    for i in 3..=target {
        match radial_link(&cfg.links, i) {
            Some(l) => links.push(l),
            None => break,
        }
    }
    Polar { pole, links }
}

/// Index of `q[i][j]` in the state vector (`i = 0` is the pole).
pub fn index(n: usize, i: usize, j: usize) -> usize {
    if i == 0 {
        0
    } else {
        1 + (i - 1) * n + j % n
    }
}

/// The dense RTS matrix on `[q00, link 1..5]`, `(1+5n)²`, row = new point,
/// column = old point; assembled entry by entry from (9)–(12).
pub fn matrix(n: usize) -> DMatrix<f64> {
    let dim = 1 + 5 * n;
    let mut a = DMatrix::<f64>::zeros(dim, dim);
    let ix = |i, j| index(n, i, j);
    a[(0, 0)] = 0.75;
    for h in 0..n {
        a[(0, ix(1, h))] += 0.25 / n as f64;
    }
    for j in 0..n {
        a[(ix(1, j), 0)] += 0.5;
        a[(ix(2, j), ix(1, j))] += 11.0 / 12.0;
        a[(ix(2, j), ix(2, j))] += 1.0 / 12.0;
        for h in 0..n {
            let g = h as f64 - j as f64;
            a[(ix(1, j), ix(1, h))] += b(g, n);
            a[(ix(2, j), ix(1, h))] += d(g, n);
        }
        a[(ix(3, j), ix(1, j))] += 0.5;
        a[(ix(3, j), ix(2, j))] += 0.5;
        a[(ix(4, j), ix(1, j))] += 1.0 / 8.0;
        a[(ix(4, j), ix(2, j))] += 6.0 / 8.0;
        a[(ix(4, j), ix(3, j))] += 1.0 / 8.0;
        a[(ix(5, j), ix(2, j))] += 0.5;
        a[(ix(5, j), ix(3, j))] += 0.5;
    }
    a
}

/// The leading `(1+3n)²` block of [`matrix`]: pole and links 1..3. No old
/// link 4 or 5 enters any new point, so the columns of links 4, 5 in
/// [`matrix`] are zero and its spectrum is this block's plus `2n` zeros.
pub fn state_matrix(n: usize) -> DMatrix<f64> {
    let dim = 1 + 3 * n;
    matrix(n).view((0, 0), (dim, dim)).into_owned()
}

/// Eigenvalues of a general real square matrix, sorted by decreasing
/// modulus ([`crate::eigen::eigenvalues`]). Panics if the QR iteration fails.
pub fn eigenvalues_by_modulus(a: &DMatrix<f64>) -> Vec<Complex<f64>> {
    crate::eigen::eigenvalues(a).expect("QR iteration converges")
}

/// Applies [`matrix`] to a configuration coordinate by coordinate. Links the
/// configuration lacks count as zero; the result keeps `min(2K−1, 5)` links,
/// like [`step`].
pub fn apply_matrix(a: &DMatrix<f64>, cfg: &Polar) -> Polar {
    let n = cfg.valence();
    let k = cfg.links.len();
    let mut out = Polar {
        pole: ZERO,
        links: vec![vec![ZERO; n]; (2 * k - 1).min(MAX_LINKS)],
    };
    for c in 0..3 {
        let mut x = nalgebra::DVector::<f64>::zeros(1 + 5 * n);
        x[0] = cfg.pole[c];
        for (i, l) in cfg.links.iter().take(MAX_LINKS).enumerate() {
            for (j, p) in l.iter().enumerate() {
                x[index(n, i + 1, j)] = p[c];
            }
        }
        let y = a * x;
        out.pole[c] = y[0];
        for (i, l) in out.links.iter_mut().enumerate() {
            for (j, p) in l.iter_mut().enumerate() {
                p[c] = y[index(n, i + 1, j)];
            }
        }
    }
    out
}
