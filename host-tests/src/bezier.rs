//! Bézier patches by Bernstein sums (docs/math/c2ps.md §5): the uniform cubic
//! B-spline → Bézier conversion and the evaluation of a tensor patch of degree
//! `K−1` with its partial derivatives, `Σ_ij b_ij B_i(u) B_j(v)`. No de
//! Casteljau here (the kernel uses de Casteljau).

use crate::vec3::{axpy, P3, ZERO};

/// A tensor Bézier patch, `points[i][j]`, `i` along `u`, `j` along `v`.
pub type Patch<const K: usize> = [[P3; K]; K];

/// The uniform cubic B-spline → Bézier matrix, `1/6 · [1 4 1 0; 0 4 2 0;
/// 0 2 4 0; 0 1 4 1]`: row `a` gives Bézier point `a` of a span from its 4
/// B-spline coefficients.
pub const BSPLINE_TO_BEZIER: [[f64; 4]; 4] = [
    [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0],
    [0.0, 4.0 / 6.0, 2.0 / 6.0, 0.0],
    [0.0, 2.0 / 6.0, 4.0 / 6.0, 0.0],
    [0.0, 1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0],
];

/// The bicubic Bézier net of a uniform bicubic B-spline patch with control
/// points `d[k][l]`: `b[a][c] = Σ_{k,l} M[a][k] M[c][l] d[k][l]`.
pub fn bspline_to_bezier(d: &[[P3; 4]; 4]) -> Patch<4> {
    let m = &BSPLINE_TO_BEZIER;
    let mut out = [[ZERO; 4]; 4];
    for (a, row) in out.iter_mut().enumerate() {
        for (c, o) in row.iter_mut().enumerate() {
            for (k, dk) in d.iter().enumerate() {
                for (l, &p) in dk.iter().enumerate() {
                    *o = axpy(*o, m[a][k] * m[c][l], p);
                }
            }
        }
    }
    out
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// The `r`-th derivative of the Bernstein polynomial `B_i^deg` at `t`, from
/// the explicit form `C(deg,i) t^i (1−t)^(deg−i)` differentiated by the
/// product rule: `Σ_s C(r,s) (d/dt)^s t^i · (d/dt)^(r−s) (1−t)^(deg−i)`.
pub fn bernstein(deg: usize, i: usize, r: usize, t: f64) -> f64 {
    // (d/dt)^s t^a = a!/(a−s)! t^(a−s); (d/dt)^s (1−t)^a = (−1)^s a!/(a−s)! (1−t)^(a−s).
    let falling = |a: usize, s: usize| (0..s).fold(1.0, |acc, x| acc * (a - x) as f64);
    let mut sum = 0.0;
    let (a, b) = (i, deg - i);
    for s in 0..=r {
        if s > a || r - s > b {
            continue;
        }
        let left = falling(a, s) * t.powi((a - s) as i32);
        let sign = if (r - s).is_multiple_of(2) { 1.0 } else { -1.0 };
        let right = sign * falling(b, r - s) * (1.0 - t).powi((b - (r - s)) as i32);
        sum += binomial(r, s) * left * right;
    }
    binomial(deg, i) * sum
}

/// `∂^(ru+rv) x / ∂u^ru ∂v^rv` of a patch at `(u, v)`.
pub fn eval<const K: usize>(p: &Patch<K>, u: f64, v: f64, ru: usize, rv: usize) -> P3 {
    let deg = K - 1;
    let mut acc = ZERO;
    for (i, row) in p.iter().enumerate() {
        let bu = bernstein(deg, i, ru, u);
        for (j, &q) in row.iter().enumerate() {
            acc = axpy(acc, bu * bernstein(deg, j, rv, v), q);
        }
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bernstein polynomials sum to 1 and their derivatives to 0; the first
    /// derivative matches a central difference.
    #[test]
    fn bernstein_partition_of_unity_and_derivatives() {
        for deg in 1..6 {
            for t in [0.0, 0.1, 0.5, 0.77, 1.0] {
                let s: f64 = (0..=deg).map(|i| bernstein(deg, i, 0, t)).sum();
                assert!((s - 1.0).abs() < 1e-14);
                for r in 1..3 {
                    let s: f64 = (0..=deg).map(|i| bernstein(deg, i, r, t)).sum();
                    assert!(s.abs() < 1e-12);
                }
                let h = 1e-6;
                for i in 0..=deg {
                    let fd =
                        (bernstein(deg, i, 0, t + h) - bernstein(deg, i, 0, t - h)) / (2.0 * h);
                    assert!((fd - bernstein(deg, i, 1, t)).abs() < 1e-7);
                }
            }
        }
    }
}
