//! The surface ring of a configuration (docs/math/c2ps.md §5): the uniform bicubic
//! B-spline with control rows = links 1..5 and `N` periodic columns over
//! `r ∈ [2, 4]` (the configuration's own link units), as `2N` Bézier patches.
//!
//! Patch `(span, col)` covers `r ∈ [2+span, 3+span]` (`u = r − 2 − span`) and
//! `τ ∈ [col/N, (col+1)/N]` (`v = N τ − col`); its B-spline control points are
//! `q[span+1+k][col−1+l]`, `k, l = 0..3` (link `i` has Greville abscissa
//! `r = i`, column `j` has `τ = j/N`).

use crate::bezier::{bspline_to_bezier, eval, Patch};
use crate::polar::Polar;
use crate::vec3::{P3, ZERO};

/// The Bézier net of patch `(span, col)`; needs 5 links.
pub fn patch(cfg: &Polar, span: usize, col: usize) -> Patch<4> {
    let n = cfg.valence();
    let mut d = [[ZERO; 4]; 4];
    for (k, row) in d.iter_mut().enumerate() {
        for (l, p) in row.iter_mut().enumerate() {
            *p = cfg.links[span + k][(col + n + l - 1) % n];
        }
    }
    bspline_to_bezier(&d)
}

/// `(x, ∂x/∂r, ∂²x/∂r²)` of the ring at `r ∈ [2, 4]`, `τ ∈ [0, 1)`, `r` in the
/// configuration's link units (one unit = one patch in `u`).
pub fn radial_jet(cfg: &Polar, r: f64, tau: f64) -> [P3; 3] {
    let n = cfg.valence();
    let span = if r < 3.0 { 0 } else { 1 };
    let u = r - 2.0 - span as f64;
    let t = tau.rem_euclid(1.0) * n as f64;
    let col = (t.floor() as usize).min(n - 1);
    let v = t - col as f64;
    let p = patch(cfg, span, col);
    [
        eval(&p, u, v, 0, 0),
        eval(&p, u, v, 1, 0),
        eval(&p, u, v, 2, 0),
    ]
}
