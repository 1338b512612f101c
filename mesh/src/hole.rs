//! The size of a cap's remaining hole, for caps that stop refining once the
//! hole is small enough ([`crate::Evaluator::set_hole_tolerance`]).
//!
//! After a ring, the hole is bounded by the inner edges of the ring's
//! patches. Each edge is a Bézier curve and lies in the convex hull of its
//! control points, so when every such control point lies within `r` of the
//! cap's limit point, the whole boundary does, and the hole's diameter is at
//! most `2r`.

use capdiv::{Point3, Real, TensorPatch};

pub(crate) use crate::tessellate::{EDGE_U0, EDGE_V0};

/// The largest distance from `center` to a control point of edge `edge`
/// ([`EDGE_V0`]: control points `[i][0]`, or [`EDGE_U0`]: `[0][j]`) of
/// `patch`, in `f64`.
pub(crate) fn edge_radius<R: Real, const K: usize>(
    patch: &TensorPatch<R, K>,
    edge: u8,
    center: Point3<R>,
) -> f64 {
    (0..K)
        .map(|k| {
            let p = if edge == EDGE_U0 {
                patch.points[0][k]
            } else {
                patch.points[k][0]
            };
            (p - center).norm().to_f64()
        })
        .fold(0.0, f64::max)
}

/// Whether a hole whose boundary lies within `radius` of its centre is
/// closed at `tolerance` (its diameter bound `2·radius` at most the
/// tolerance); a NaN radius never is.
pub(crate) fn small_enough(radius: f64, tolerance: Option<f64>) -> bool {
    tolerance.is_some_and(|t| 2.0 * radius <= t)
}
