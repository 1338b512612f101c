//! Eigencoefficients `p0..p5` and what is exactly known about them (spec
//! docs/math/c2ps.md §4), written from the spec's formulas with `std` `cos`/`sin`.
//!
//! `p0 = 2/3 q00 + 1/3 A`, `p1 = 2 C1`, `p2 = 2 S1`, `p3 = A − q00`,
//! `p4 = 3 C2`, `p5 = 3 S2` (the normalisation of the paper's Table 1).

use crate::polar::Polar;
use crate::vec3::{add, axpy, cross, dot, norm, scale, sub, P3, ZERO};
use std::f64::consts::TAU;

/// `λ = 1/2`, the subdominant eigenvalue.
pub const LAMBDA: f64 = 0.5;
/// `μ = 1/4`, the subsubdominant eigenvalue.
pub const MU: f64 = 0.25;
/// `λ_k` of `p_k`.
pub const EIGENVALUES: [f64; 6] = [1.0, LAMBDA, LAMBDA, MU, MU, MU];

/// `p0..p5` of a configuration at its own valence `n`, as the sums over the
/// 1-link: `A = (1/n) Σ q1h`, `C_k = (1/n) Σ c(kh/n) q1h`, `S_k = (1/n) Σ s(kh/n) q1h`.
pub fn coefficients(cfg: &Polar) -> [P3; 6] {
    let n = cfg.valence();
    let inv = 1.0 / n as f64;
    let (mut a, mut c1, mut s1, mut c2, mut s2) = (ZERO, ZERO, ZERO, ZERO, ZERO);
    for (h, &q) in cfg.links[0].iter().enumerate() {
        let t = TAU * h as f64 / n as f64;
        a = axpy(a, inv, q);
        c1 = axpy(c1, inv * t.cos(), q);
        s1 = axpy(s1, inv * t.sin(), q);
        c2 = axpy(c2, inv * (2.0 * t).cos(), q);
        s2 = axpy(s2, inv * (2.0 * t).sin(), q);
    }
    let q00 = cfg.pole;
    [
        add(scale(2.0 / 3.0, q00), scale(1.0 / 3.0, a)),
        scale(2.0, c1),
        scale(2.0, s1),
        sub(a, q00),
        scale(3.0, c2),
        scale(3.0, s2),
    ]
}

/// `p0 + λ^m v1 (p1 c + p2 s) + μ^m v3 (p3 + p4 c2 + p5 s2)` at angle `τ`,
/// the common shape of the closed forms (paper (28)/(30) with Table 1's
/// right eigenvectors, `v1 = (v̂1)_i`, `v3 = (v̂3)_i = (v̂4)_i` for `i ≥ 1`).
fn expansion(p: &[P3; 6], m: u32, tau: f64, v1: f64, v3: f64, v3_const: f64) -> P3 {
    let (c, s) = ((TAU * tau).cos(), (TAU * tau).sin());
    let (c2, s2) = ((2.0 * TAU * tau).cos(), (2.0 * TAU * tau).sin());
    let lm = LAMBDA.powi(m as i32);
    let mm = MU.powi(m as i32);
    let lin = axpy(scale(c, p[1]), s, p[2]);
    let quad = axpy(axpy(scale(v3_const, p[3]), v3 * c2, p[4]), v3 * s2, p[5]);
    axpy(axpy(p[0], lm * v1, lin), mm, quad)
}

/// The pole at level `m` (eq. (30), exact): `p0 − μ^m/3 · p3`.
pub fn pole_closed(p: &[P3; 6], m: u32) -> P3 {
    axpy(p[0], -MU.powi(m as i32) / 3.0, p[3])
}

/// `q[1][j]` at level `m`, `N = n·2^m` (eq. (30), exact):
/// `p0 + λ^m (p1 c + p2 s) + 2/3 μ^m (p3 + p4 c2 + p5 s2)` at `τ = j/N`.
pub fn link1_closed(p: &[P3; 6], m: u32, j: usize, big_n: usize) -> P3 {
    expansion(p, m, j as f64 / big_n as f64, 1.0, 2.0 / 3.0, 2.0 / 3.0)
}

/// The leading part of `q[2][j]` at level `m` (eq. (30)/(39), up to
/// `O(8^-m)`): `p0 + 2λ^m (p1 c + p2 s) + 11/3 μ^m (p3 + p4 c2 + p5 s2)`.
pub fn link2_leading(p: &[P3; 6], m: u32, j: usize, big_n: usize) -> P3 {
    expansion(p, m, j as f64 / big_n as f64, 2.0, 11.0 / 3.0, 11.0 / 3.0)
}

/// The quadratic Taylor expansion at the pole (eq. (32)) at `x = r c(τ)`,
/// `y = r s(τ)`: `p0 + p1 x + p2 y + p3 (x²+y²) + p4 (x²−y²) + p5 (2xy)`.
pub fn quadratic(p: &[P3; 6], r: f64, tau: f64) -> P3 {
    let (x, y) = (r * (TAU * tau).cos(), r * (TAU * tau).sin());
    let mut out = p[0];
    for (k, w) in [x, y, x * x + y * y, x * x - y * y, 2.0 * x * y]
        .into_iter()
        .enumerate()
    {
        out = axpy(out, w, p[k + 1]);
    }
    out
}

/// A configuration of valence `n` with `links` links built from the right
/// eigenvectors of Table 1, `q = Σ_k p_k v_k`, `(v_k)_{ij} = (v̂_k)_i op_k(j/n)`,
/// `v̂_0 = 1`, `v̂_1 = v̂_2 = i`, `v̂_3 = (3i²−1)/3`... i.e. `[−1,2,11,26,47,74]/3`,
/// `v̂_4 = v̂_5 = [0,2,11,26,47,74]/3`. For `n ≥ 5` its eigencoefficients are `p`.
pub fn eigen_configuration(p: &[P3; 6], n: usize, links: usize) -> Polar {
    let v3 = [-1.0, 2.0, 11.0, 26.0, 47.0, 74.0].map(|x: f64| x / 3.0);
    let v4 = [0.0, 2.0, 11.0, 26.0, 47.0, 74.0].map(|x: f64| x / 3.0);
    let point = |i: usize, j: usize| -> P3 {
        let t = TAU * j as f64 / n as f64;
        let mut q = p[0];
        q = axpy(q, i as f64 * t.cos(), p[1]);
        q = axpy(q, i as f64 * t.sin(), p[2]);
        q = axpy(q, v3[i], p[3]);
        q = axpy(q, v4[i] * (2.0 * t).cos(), p[4]);
        axpy(q, v4[i] * (2.0 * t).sin(), p[5])
    };
    Polar {
        pole: point(0, 0),
        links: (1..=links)
            .map(|i| (0..n).map(|j| point(i, j)).collect())
            .collect(),
    }
}

/// Differential geometry at the pole.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Geometry {
    /// Unit normal `p1 × p2 / |p1 × p2|`.
    pub normal: P3,
    /// Gaussian curvature.
    pub gaussian: f64,
    /// Mean curvature.
    pub mean: f64,
    /// Principal curvatures, larger first.
    pub principal: [f64; 2],
}

/// Normal and curvatures from the jet, through the shape operator
/// `W = I⁻¹ II` (first fundamental form `I = [[E, F], [F, G]]` from
/// `x_x = p1`, `x_y = p2`; second `II = [[e, f], [f, g]]` from
/// `x_xx = 2(p3+p4)`, `x_xy = 2p5`, `x_yy = 2(p3−p4)`): `K = det W`,
/// `H = tr W / 2`, principal curvatures = eigenvalues of `W`.
/// `None` for a degenerate tangent plane.
pub fn geometry(p: &[P3; 6]) -> Option<Geometry> {
    let nrm = cross(p[1], p[2]);
    let len = norm(nrm);
    if len.is_nan() || len <= 0.0 {
        return None;
    }
    let normal = scale(1.0 / len, nrm);
    let first = [
        [dot(p[1], p[1]), dot(p[1], p[2])],
        [dot(p[1], p[2]), dot(p[2], p[2])],
    ];
    let xxx = scale(2.0, add(p[3], p[4]));
    let xyy = scale(2.0, sub(p[3], p[4]));
    let xxy = scale(2.0, p[5]);
    let second = [
        [dot(normal, xxx), dot(normal, xxy)],
        [dot(normal, xxy), dot(normal, xyy)],
    ];
    let det1 = first[0][0] * first[1][1] - first[0][1] * first[1][0];
    let inv = [
        [first[1][1] / det1, -first[0][1] / det1],
        [-first[1][0] / det1, first[0][0] / det1],
    ];
    let mut w = [[0.0; 2]; 2];
    for (r, row) in w.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = inv[r][0] * second[0][c] + inv[r][1] * second[1][c];
        }
    }
    let gaussian = w[0][0] * w[1][1] - w[0][1] * w[1][0];
    let mean = 0.5 * (w[0][0] + w[1][1]);
    // Eigenvalues of the 2×2 W: ½ tr ± √((½(w00 − w11))² + w01 w10).
    let half_diff = 0.5 * (w[0][0] - w[1][1]);
    let disc = (half_diff * half_diff + w[0][1] * w[1][0]).max(0.0).sqrt();
    Some(Geometry {
        normal,
        gaussian,
        mean,
        principal: [mean + disc, mean - disc],
    })
}
