//! Uniform cubic B-spline → Bézier conversion (spec C2PS.md §5).

use crate::point::Point3;
use crate::real::Real;

/// Rows: the 4 Bézier coefficients of one uniform cubic span from its 4 B-spline
/// coefficients, times 6: `1/6 · [1 4 1 0; 0 4 2 0; 0 2 4 0; 0 1 4 1]`.
pub const BSPLINE_TO_BEZIER_CUBIC: [[i32; 4]; 4] =
    [[1, 4, 1, 0], [0, 4, 2, 0], [0, 2, 4, 0], [0, 1, 4, 1]];

/// The bicubic Bézier net of one uniform bicubic B-spline patch with control
/// points `d[k][l]`: `b = M d Mᵀ`.
pub fn bspline_to_bezier_cubic<R: Real>(d: &[[Point3<R>; 4]; 4]) -> [[Point3<R>; 4]; 4] {
    let m = |a: usize, k: usize| R::ratio(BSPLINE_TO_BEZIER_CUBIC[a][k], 6);
    // Columns first (along v), then rows (along u).
    let mut half = [[Point3::ZERO; 4]; 4];
    for (k, row) in d.iter().enumerate() {
        for (b, h) in half[k].iter_mut().enumerate() {
            let mut acc = Point3::ZERO;
            for (l, p) in row.iter().enumerate() {
                acc += *p * m(b, l);
            }
            *h = acc;
        }
    }
    let mut out = [[Point3::ZERO; 4]; 4];
    for (a, out_row) in out.iter_mut().enumerate() {
        for (b, o) in out_row.iter_mut().enumerate() {
            let mut acc = Point3::ZERO;
            for (k, h) in half.iter().enumerate() {
                acc += h[b] * m(a, k);
            }
            *o = acc;
        }
    }
    out
}
