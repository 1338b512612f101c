//! Uniform cubic B-spline → Bézier conversion (spec C2PS.md §5).

use crate::point::Point3;
use crate::real::Real;

/// Rows: the 4 Bézier coefficients of one uniform cubic span from its 4 B-spline
/// coefficients, times 6: `1/6 · [1 4 1 0; 0 4 2 0; 0 2 4 0; 0 1 4 1]`.
pub const BSPLINE_TO_BEZIER_CUBIC: [[i32; 4]; 4] =
    [[1, 4, 1, 0], [0, 4, 2, 0], [0, 2, 4, 0], [0, 1, 4, 1]];

/// The 4 Bézier coefficients of one uniform cubic span (the rows of
/// [`BSPLINE_TO_BEZIER_CUBIC`] written out, zeros skipped).
#[inline]
fn span<R: Real>(p: [Point3<R>; 4], third: R, sixth: R) -> [Point3<R>; 4] {
    let two = R::from_f64(2.0);
    let four = R::from_f64(4.0);
    [
        (p[0] + p[1] * four + p[2]) * sixth,
        (p[1] * two + p[2]) * third,
        (p[1] + p[2] * two) * third,
        (p[1] + p[2] * four + p[3]) * sixth,
    ]
}

/// The bicubic Bézier net of one uniform bicubic B-spline patch with control
/// points `d[k][l]`: `b = M d Mᵀ` with `M` = [`BSPLINE_TO_BEZIER_CUBIC`] / 6,
/// applied along `v` (each row), then along `u` (each column).
pub fn bspline_to_bezier_cubic<R: Real>(d: &[[Point3<R>; 4]; 4]) -> [[Point3<R>; 4]; 4] {
    let third = R::ratio(1, 3);
    let sixth = R::ratio(1, 6);
    let mut half = [[Point3::ZERO; 4]; 4];
    for (h, row) in half.iter_mut().zip(d) {
        *h = span(*row, third, sixth);
    }
    let mut out = [[Point3::ZERO; 4]; 4];
    for b in 0..4 {
        let col = span(
            [half[0][b], half[1][b], half[2][b], half[3][b]],
            third,
            sixth,
        );
        for (a, p) in col.into_iter().enumerate() {
            out[a][b] = p;
        }
    }
    out
}
