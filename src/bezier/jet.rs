//! `SurfaceJet`: position and first and second partial derivatives of a
//! surface at one point, and what follows from them exactly: unit normal,
//! Gaussian, mean and principal curvatures ([`SurfaceGeometry`]).
//!
//! One formula serves the pole of a C²PS cap (docs/math/c2ps.md §4: the jet
//! `p0 + p1 x + p2 y + p3 (x²+y²) + p4 (x²−y²) + p5 (2xy)` has
//! `x_u = p1`, `x_v = p2`, `x_uu = 2(p3+p4)`, `x_uv = 2 p5`, `x_vv = 2(p3−p4)`)
//! and every point of a Bézier ring patch (docs/math/c2ps.md §5, docs/math/eg.md §9), whose
//! partials [`TensorPatch::jet`] computes by de Casteljau's algorithm.
//!
//! Fundamental forms: `E = x_u·x_u`, `F = x_u·x_v`, `G = x_v·x_v`;
//! `e = n·x_uu`, `f = n·x_uv`, `g = n·x_vv` with `n = x_u×x_v/|x_u×x_v|`;
//! `K = (eg − f²)/(EG − F²)`, `H = (Eg − 2Ff + Ge)/(2(EG − F²))` (do Carmo,
//! *Differential Geometry of Curves and Surfaces*, §3-3). With this sign `H`
//! is positive where the surface bends towards `n`.

use super::patch::TensorPatch;
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;

/// Position and first and second partial derivatives at one parameter pair.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SurfaceJet<R> {
    /// `x(u, v)`.
    pub position: Point3<R>,
    /// `∂x/∂u`.
    pub du: Point3<R>,
    /// `∂x/∂v`.
    pub dv: Point3<R>,
    /// `∂²x/∂u²`.
    pub duu: Point3<R>,
    /// `∂²x/∂u∂v`.
    pub duv: Point3<R>,
    /// `∂²x/∂v²`.
    pub dvv: Point3<R>,
}

/// Differential geometry of a surface at a point.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SurfaceGeometry<R> {
    /// Unit normal `x_u×x_v/|x_u×x_v|`.
    pub normal: Point3<R>,
    /// Gaussian curvature `K = (eg − f²)/(EG − F²)`.
    pub gaussian: R,
    /// Mean curvature `H = (Eg − 2Ff + Ge)/(2(EG − F²))`.
    pub mean: R,
    /// Principal curvatures `H + √(H²−K)`, `H − √(H²−K)`.
    pub principal: [R; 2],
}

impl<R: Real> SurfaceJet<R> {
    /// Normal and curvatures; [`Error::Degenerate`] when `x_u × x_v`
    /// vanishes (or under- or overflows: `|x_u|·|x_v|` outside about
    /// `[√MIN_POSITIVE, √MAX]`), [`Error::NonFinite`] when a curvature
    /// overflows or the jet is not finite.
    pub fn geometry(&self) -> Result<SurfaceGeometry<R>, Error> {
        let (du, dv) = (self.du, self.dv);
        let cross = du.cross(dv);
        let len = cross.norm();
        let (e1, f1, g1) = (du.dot(du), du.dot(dv), dv.dot(dv));
        let det = e1 * g1 - f1 * f1;
        if len <= R::ZERO || det <= R::ZERO || !len.is_finite() || !det.is_finite() {
            return Err(Error::Degenerate);
        }
        let normal = cross * (R::ONE / len);
        if !normal.is_finite() {
            // `len` subnormal: its reciprocal overflows.
            return Err(Error::Degenerate);
        }
        let two = R::from_f64(2.0);
        let e2 = normal.dot(self.duu);
        let g2 = normal.dot(self.dvv);
        let f2 = normal.dot(self.duv);
        let gaussian = (e2 * g2 - f2 * f2) / det;
        let mean = (e1 * g2 - two * f1 * f2 + g1 * e2) / (two * det);
        let disc = mean * mean - gaussian;
        let root = if disc > R::ZERO { disc.sqrt() } else { R::ZERO };
        let principal = [mean + root, mean - root];
        if ![gaussian, mean, principal[0], principal[1]]
            .iter()
            .all(|c| c.is_finite())
        {
            return Err(Error::NonFinite);
        }
        Ok(SurfaceGeometry {
            normal,
            gaussian,
            mean,
            principal,
        })
    }
}

/// de Casteljau on `K` points at `t`: value, first and second derivative.
fn casteljau2<R: Real, const K: usize>(pts: &[Point3<R>; K], t: R) -> [Point3<R>; 3] {
    let mut b = *pts;
    let s = R::ONE - t;
    let mut len = K;
    while len > 3 {
        for i in 0..len - 1 {
            b[i] = b[i] * s + b[i + 1] * t;
        }
        len -= 1;
    }
    let d = R::from_f64(K.saturating_sub(1) as f64);
    match K {
        0 => [Point3::ZERO; 3],
        1 => [b[0], Point3::ZERO, Point3::ZERO],
        2 => [b[0] * s + b[1] * t, (b[1] - b[0]) * d, Point3::ZERO],
        _ => {
            // Three points of degree 2 left: blend them, differentiate once
            // and twice (the factors d and d(d−1) of the reduced degree).
            let (a, c) = (b[0] * s + b[1] * t, b[1] * s + b[2] * t);
            let second = (b[2] - b[1] * R::from_f64(2.0) + b[0]) * (d * (d - R::ONE));
            [a * s + c * t, (c - a) * d, second]
        }
    }
}

impl<R: Real, const K: usize> TensorPatch<R, K> {
    /// Position and first and second partials at `(u, v) ∈ [0,1]²`;
    /// [`Error::OutOfDomain`] otherwise. `u` runs along `i` of
    /// `points[i][j]`, `v` along `j`, as in [`TensorPatch::evaluate`].
    pub fn jet(&self, u: R, v: R) -> Result<SurfaceJet<R>, Error> {
        let inside = |t: R| t.is_finite() && t >= R::ZERO && t <= R::ONE;
        if !inside(u) || !inside(v) {
            return Err(Error::OutOfDomain);
        }
        // Relative to the first control point, as in `evaluate`: the
        // derivatives round relative to the patch's size.
        let local = self.jet_about(self.origin(), u, v);
        // One test for every coordinate: their sum is finite only if each is.
        let sum = local.position + local.du + local.dv + local.duu + local.duv + local.dvv;
        Ok(if (sum.0[0] + sum.0[1] + sum.0[2]).is_finite() {
            local
        } else {
            self.jet_about(Point3::ZERO, u, v)
        })
    }

    /// de Casteljau (two derivatives) on the points relative to `origin`,
    /// the position shifted back.
    fn jet_about(&self, origin: Point3<R>, u: R, v: R) -> SurfaceJet<R> {
        let mut rows = [[Point3::ZERO; K]; 3];
        for (i, points) in self.points.iter().enumerate() {
            let [p, pv, pvv] = casteljau2(&points.map(|p| p - origin), v);
            rows[0][i] = p;
            rows[1][i] = pv;
            rows[2][i] = pvv;
        }
        let [position, du, duu] = casteljau2(&rows[0], u);
        let [dv, duv, _] = casteljau2(&rows[1], u);
        let [dvv, _, _] = casteljau2(&rows[2], u);
        SurfaceJet {
            position: position + origin,
            du,
            dv,
            duu,
            duv,
            dvv,
        }
    }
}
