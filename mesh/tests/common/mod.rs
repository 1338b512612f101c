//! Test helpers written independently of the crate: Bernstein evaluation of a
//! tensor Bézier patch with derivatives to second order, the curvatures they
//! give, and a literal uniform cubic B-spline basis.
#![allow(dead_code)]

/// Binomial coefficient.
fn binom(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// Bernstein polynomials of degree `d` at `t` and their first and second
/// derivatives, by the textbook formula.
fn bernstein(d: usize, t: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let b = |d: usize, i: isize| -> f64 {
        if i < 0 || i as usize > d {
            0.0
        } else {
            let i = i as usize;
            binom(d, i) * t.powi(i as i32) * (1.0 - t).powi((d - i) as i32)
        }
    };
    let df = d as f64;
    let v: Vec<f64> = (0..=d).map(|i| b(d, i as isize)).collect();
    let d1: Vec<f64> = (0..=d as isize)
        .map(|i| {
            if d == 0 {
                0.0
            } else {
                df * (b(d - 1, i - 1) - b(d - 1, i))
            }
        })
        .collect();
    let d2: Vec<f64> = (0..=d as isize)
        .map(|i| {
            if d < 2 {
                0.0
            } else {
                df * (df - 1.0) * (b(d - 2, i - 2) - 2.0 * b(d - 2, i - 1) + b(d - 2, i))
            }
        })
        .collect();
    (v, d1, d2)
}

/// Position and derivatives `[x, xu, xv, xuu, xuv, xvv]` of the Bézier patch
/// `pts[i][j]` (`i` along u) at `(u, v)`.
pub fn derivs(pts: &[Vec<[f64; 3]>], u: f64, v: f64) -> [[f64; 3]; 6] {
    let d = pts.len() - 1;
    let (bu, du, ddu) = bernstein(d, u);
    let (bv, dv, ddv) = bernstein(d, v);
    let mut out = [[0.0; 3]; 6];
    for i in 0..=d {
        for j in 0..=d {
            let w = [
                bu[i] * bv[j],
                du[i] * bv[j],
                bu[i] * dv[j],
                ddu[i] * bv[j],
                du[i] * dv[j],
                bu[i] * ddv[j],
            ];
            for (o, wk) in out.iter_mut().zip(w) {
                for c in 0..3 {
                    o[c] += wk * pts[i][j][c];
                }
            }
        }
    }
    out
}

pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}
pub fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    norm(sub(a, b))
}

/// Unit normal, Gaussian and mean curvature from the derivatives.
pub fn geometry(d: &[[f64; 3]; 6]) -> ([f64; 3], f64, f64) {
    let n = cross(d[1], d[2]);
    let l = norm(n);
    let n = [n[0] / l, n[1] / l, n[2] / l];
    let (e, f, g) = (dot(d[1], d[1]), dot(d[1], d[2]), dot(d[2], d[2]));
    let (l2, m2, n2) = (dot(n, d[3]), dot(n, d[4]), dot(n, d[5]));
    let det = e * g - f * f;
    let k = (l2 * n2 - m2 * m2) / det;
    let h = (e * n2 - 2.0 * f * m2 + g * l2) / (2.0 * det);
    (n, k, h)
}

/// Uniform cubic B-spline basis on [0, 1] (literal polynomials).
pub fn bspline_basis(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [
        s * s * s / 6.0,
        (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
        (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
        t * t * t / 6.0,
    ]
}
