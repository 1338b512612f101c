//! Valence 4 (docs/math/eg.md §7: "n = 4 is regular"): no EG rule; the cap of a
//! regular c-net is its 2×2 bicubic patches around the center.

use super::layout::CAP4;
use super::net::CNet;
use crate::bezier::{bspline_to_bezier_cubic, BicubicPatch};
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;

impl<R: Real> CNet<R> {
    /// Valence 4 only: the cap `[0,1]²` of every sector as the bicubic Bézier
    /// patch of the uniform bicubic B-spline of the (regular) c-net, patch `s`
    /// in sector `s`'s frame (`u` along spoke `s`, `v` along spoke `s+1`; its
    /// 4×4 control points are the c-net points `(x, y) ∈ {−1..2}²`, §1).
    /// Together the 4 patches are the surface the EG rings of a valence-4 net
    /// converge to. [`Error::ValenceUnsupported`] for `n ≠ 4`.
    pub fn regular_cap(&self) -> Result<[BicubicPatch<R>; 4], Error> {
        if self.valence() != 4 {
            return Err(Error::ValenceUnsupported {
                valence: self.valence(),
            });
        }
        let mut out = [BicubicPatch {
            points: [[Point3::ZERO; 4]; 4],
        }; 4];
        for (s, patch) in out.iter_mut().enumerate() {
            let mut d = [[Point3::ZERO; 4]; 4];
            for (row, src) in d.iter_mut().zip(CAP4.iter()) {
                for (p, &(ds, node)) in row.iter_mut().zip(src.iter()) {
                    *p = self.node(s, ds, node)?;
                }
            }
            patch.points = bspline_to_bezier_cubic(&d);
        }
        Ok(out)
    }
}
