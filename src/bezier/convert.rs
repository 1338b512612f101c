//! Uniform cubic B-spline → Bézier conversion (docs/math/c2ps.md §5).

use crate::point::Point3;
use crate::real::Real;

/// Rows: the 4 Bézier coefficients of one uniform cubic span from its 4 B-spline
/// coefficients, times 6: `1/6 · [1 4 1 0; 0 4 2 0; 0 2 4 0; 0 1 4 1]`.
pub const BSPLINE_TO_BEZIER_CUBIC: [[i32; 4]; 4] =
    [[1, 4, 1, 0], [0, 4, 2, 0], [0, 2, 4, 0], [0, 1, 4, 1]];

/// The weights `k/6` of [`BSPLINE_TO_BEZIER_CUBIC`] that are not zero.
#[derive(Clone, Copy)]
struct Sixths<R> {
    one: R,
    two: R,
    four: R,
}

/// The 4 Bézier coefficients of one uniform cubic span: the rows of
/// [`BSPLINE_TO_BEZIER_CUBIC`]`/6` applied to `p`, the zero terms skipped and
/// the others summed in row order, so the result is bit for bit the dense
/// product's (adding a zero product is exact).
#[inline]
fn span<R: Real>(p: [Point3<R>; 4], w: Sixths<R>) -> [Point3<R>; 4] {
    [
        p[0] * w.one + p[1] * w.four + p[2] * w.one,
        p[1] * w.four + p[2] * w.two,
        p[1] * w.two + p[2] * w.four,
        p[1] * w.one + p[2] * w.four + p[3] * w.one,
    ]
}

/// The bicubic Bézier net of one uniform bicubic B-spline patch with control
/// points `d[k][l]`: `b = M d Mᵀ` with `M` = [`BSPLINE_TO_BEZIER_CUBIC`] / 6,
/// applied along `v` (each row), then along `u` (each column). The weights
/// are computed once per call (no division per term).
///
/// The product runs on `d − d[1][1]` (`d[1][1]`, the patch's first corner's
/// B-spline point, added back to each result): the weighted sums then round
/// relative to the patch's size, not to its distance from the origin, and
/// each Bézier point gets one rounding of that size (the final addition).
/// Differences of neighbouring Bézier points — the partials — keep `f32`
/// precision on small patches far from the origin. Where the points span
/// more than the scalar's range (a difference overflows) the product runs
/// about zero.
pub fn bspline_to_bezier_cubic<R: Real>(d: &[[Point3<R>; 4]; 4]) -> [[Point3<R>; 4]; 4] {
    let local = convert_about(d, d[1][1]);
    // One test for every coordinate: their sum is finite only if each is.
    let sum = local.iter().flatten().fold(Point3::ZERO, |s, &p| s + p);
    if (sum.0[0] + sum.0[1] + sum.0[2]).is_finite() {
        local
    } else {
        // The points span more than the scalar's range: about zero.
        convert_about(d, Point3::ZERO)
    }
}

/// `origin + M (d − origin) Mᵀ`.
fn convert_about<R: Real>(d: &[[Point3<R>; 4]; 4], origin: Point3<R>) -> [[Point3<R>; 4]; 4] {
    let w = Sixths {
        one: R::ratio(1, 6),
        two: R::ratio(2, 6),
        four: R::ratio(4, 6),
    };
    let mut half = [[Point3::ZERO; 4]; 4];
    for (h, row) in half.iter_mut().zip(d) {
        *h = span(row.map(|p| p - origin), w);
    }
    let mut out = [[Point3::ZERO; 4]; 4];
    for b in 0..4 {
        let col = span([half[0][b], half[1][b], half[2][b], half[3][b]], w);
        for (a, p) in col.into_iter().enumerate() {
            out[a][b] = p + origin;
        }
    }
    out
}
