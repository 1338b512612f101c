//! `TensorPatch`: a `K×K` Bézier patch (degree `K−1` in each direction) and its
//! evaluation by de Casteljau's algorithm: position, both first partials and the
//! unit normal. Index `[i][j]`: `i` runs along `u` (for polar rings: radially
//! outward), `j` along `v` (counter-clockwise), so `∂u × ∂v` is the normal.
//!
//! A grid is sampled line by line: [`TensorPatch::lines`] makes the points
//! relative once, [`PatchLines::iso_v`] reduces the rows along `v` once per
//! line ([`IsoCurve`]), and each point on the line is then two curve
//! evaluations along `u`, bit for bit what [`TensorPatch::evaluate`] gives.

use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;

/// A tensor-product Bézier patch with `K×K` control points.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TensorPatch<R, const K: usize> {
    /// Control points, `points[i][j]`, `i` along `u`, `j` along `v`.
    pub points: [[Point3<R>; K]; K],
}

/// A bicubic patch (C²PS rings).
pub type BicubicPatch<R> = TensorPatch<R, 4>;
/// A bi-quartic patch (EG rings).
pub type BiquarticPatch<R> = TensorPatch<R, 5>;

/// Position and first partial derivatives at one parameter pair.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PatchPoint<R> {
    /// `x(u, v)`.
    pub position: Point3<R>,
    /// `∂x/∂u`.
    pub du: Point3<R>,
    /// `∂x/∂v`.
    pub dv: Point3<R>,
}

impl<R: Real> PatchPoint<R> {
    /// Unit normal `∂u × ∂v / |∂u × ∂v|`; [`Error::Degenerate`] where it vanishes.
    pub fn normal(&self) -> Result<Point3<R>, Error> {
        let n = self.du.cross(self.dv);
        let len = n.norm();
        if len > R::ZERO && len.is_finite() {
            Ok(n * (R::ONE / len))
        } else {
            Err(Error::Degenerate)
        }
    }
}

/// de Casteljau on `K` points at `t`: value and derivative.
#[inline]
fn casteljau<R: Real, const K: usize>(pts: &[Point3<R>; K], t: R) -> (Point3<R>, Point3<R>) {
    let mut b = *pts;
    let s = R::ONE - t;
    // Reduce to two points, then value and derivative from them.
    let mut len = K;
    while len > 2 {
        for i in 0..len - 1 {
            b[i] = b[i] * s + b[i + 1] * t;
        }
        len -= 1;
    }
    if K == 1 {
        return (b[0], Point3::ZERO);
    }
    let deg = R::from_f64((K - 1) as f64);
    (b[0] * s + b[1] * t, (b[1] - b[0]) * deg)
}

impl<R: Real, const K: usize> TensorPatch<R, K> {
    /// The first control point: evaluation runs on the points relative to
    /// it, so every de Casteljau step rounds relative
    /// to the patch's size instead of to its distance from the origin and
    /// the partials (differences of nearby points) keep the precision of
    /// the control points. For a patch of size `h` at distance `|x|` the
    /// partials' rounding drops from about `ε|x|/h` to `ε`, which is what
    /// makes `f32` normals of small patches usable; the position gets one
    /// more rounding (`origin + local`). Where a difference overflows (the
    /// points span more than the scalar's range) evaluation runs about zero.
    pub(crate) fn origin(&self) -> Point3<R> {
        match self.points.first().and_then(|row| row.first()) {
            Some(&p) => p,
            None => Point3::ZERO,
        }
    }

    /// Position and partials at `(u, v) ∈ [0,1]²`; [`Error::OutOfDomain`] otherwise.
    /// de Casteljau's algorithm on the control points relative to the first
    /// one (`origin`), the position shifted back at the end: the rows are
    /// reduced along `v` ([`TensorPatch::iso_v`]), then the curve along `u`.
    pub fn evaluate(&self, u: R, v: R) -> Result<PatchPoint<R>, Error> {
        if !in_unit(u) || !in_unit(v) {
            return Err(Error::OutOfDomain);
        }
        Ok(IsoCurve::about(self, self.origin(), v).at_or_about_zero(u))
    }

    /// The patch along the line `v = const` (`v ∈ [0,1]`, else
    /// [`Error::OutOfDomain`]): the `K` rows reduced by de Casteljau along
    /// `v` once, so each [`IsoCurve::evaluate`] on it costs two curve
    /// evaluations instead of `K + 2`. Sampling a grid line by line this
    /// way gives, bit for bit, what [`TensorPatch::evaluate`] gives at each
    /// point (it is the same sequence of operations).
    #[inline]
    pub fn iso_v(&self, v: R) -> Result<IsoCurve<'_, R, K>, Error> {
        if !in_unit(v) {
            return Err(Error::OutOfDomain);
        }
        Ok(IsoCurve::about(self, self.origin(), v))
    }

    /// The control points relative to the first one, subtracted once for
    /// sampling many lines of the patch ([`PatchLines::iso_v`]: the same
    /// [`IsoCurve`], bit for bit, as [`TensorPatch::iso_v`], without
    /// subtracting the origin again on every line).
    pub fn lines(&self) -> PatchLines<'_, R, K> {
        let origin = self.origin();
        PatchLines {
            patch: self,
            origin,
            relative: self.points.map(|row| row.map(|p| p - origin)),
        }
    }

    /// Position at `(u, v)`.
    pub fn position(&self, u: R, v: R) -> Result<Point3<R>, Error> {
        Ok(self.evaluate(u, v)?.position)
    }

    /// Unit normal at `(u, v)`.
    pub fn normal(&self, u: R, v: R) -> Result<Point3<R>, Error> {
        self.evaluate(u, v)?.normal()
    }
}

/// `t ∈ [0, 1]` (and not NaN).
fn in_unit<R: Real>(t: R) -> bool {
    t.is_finite() && t >= R::ZERO && t <= R::ONE
}

/// A [`TensorPatch`]'s control points relative to its first one, made by
/// [`TensorPatch::lines`] for sampling a grid line by line.
#[derive(Clone, Copy, Debug)]
pub struct PatchLines<'a, R, const K: usize> {
    patch: &'a TensorPatch<R, K>,
    origin: Point3<R>,
    relative: [[Point3<R>; K]; K],
}

impl<'a, R: Real, const K: usize> PatchLines<'a, R, K> {
    /// [`TensorPatch::iso_v`] from the points already relative to the
    /// origin: `v ∈ [0, 1]`, else [`Error::OutOfDomain`].
    #[inline]
    pub fn iso_v(&self, v: R) -> Result<IsoCurve<'a, R, K>, Error> {
        if !in_unit(v) {
            return Err(Error::OutOfDomain);
        }
        Ok(IsoCurve::of_rows(self.patch, self.origin, v, |i| {
            self.relative[i]
        }))
    }
}

/// A [`TensorPatch`] along one line `v = const`, made by
/// [`TensorPatch::iso_v`]: the curve in `u` through the line and the curve
/// of its `∂/∂v`, each `K` points relative to the patch's origin.
#[derive(Clone, Copy, Debug)]
pub struct IsoCurve<'a, R, const K: usize> {
    patch: &'a TensorPatch<R, K>,
    origin: Point3<R>,
    v: R,
    rows: [Point3<R>; K],
    rows_dv: [Point3<R>; K],
}

impl<'a, R: Real, const K: usize> IsoCurve<'a, R, K> {
    /// de Casteljau along `v` on each row of points relative to `origin`.
    fn about(patch: &'a TensorPatch<R, K>, origin: Point3<R>, v: R) -> Self {
        Self::of_rows(patch, origin, v, |i| patch.points[i].map(|p| p - origin))
    }

    /// de Casteljau along `v` on each row `row(i)` of points relative to
    /// `origin` (the patch's rows minus `origin`).
    #[inline]
    fn of_rows(
        patch: &'a TensorPatch<R, K>,
        origin: Point3<R>,
        v: R,
        row: impl Fn(usize) -> [Point3<R>; K],
    ) -> Self {
        let mut rows = [Point3::ZERO; K];
        let mut rows_dv = [Point3::ZERO; K];
        for i in 0..K {
            let (p, d) = casteljau(&row(i), v);
            rows[i] = p;
            rows_dv[i] = d;
        }
        IsoCurve {
            patch,
            origin,
            v,
            rows,
            rows_dv,
        }
    }

    /// The line's `v`.
    pub fn v(&self) -> R {
        self.v
    }

    /// Position and partials at `(u, v)`, `u ∈ [0, 1]` (else
    /// [`Error::OutOfDomain`]): bit for bit [`TensorPatch::evaluate`]`(u, v)`.
    #[inline]
    pub fn evaluate(&self, u: R) -> Result<PatchPoint<R>, Error> {
        if !in_unit(u) {
            return Err(Error::OutOfDomain);
        }
        Ok(self.at_or_about_zero(u))
    }

    /// de Casteljau along `u` about the origin; where a coordinate is not
    /// finite (the differences overflowed: the points span more than the
    /// scalar's range), the whole evaluation again about zero. One test for
    /// the nine coordinates: their sum is finite only if each is (a sum
    /// that overflows merely takes the slower way).
    #[inline]
    fn at_or_about_zero(&self, u: R) -> PatchPoint<R> {
        let local = self.at(u);
        let sum = local.position + local.du + local.dv;
        if (sum.0[0] + sum.0[1] + sum.0[2]).is_finite() {
            local
        } else {
            IsoCurve::about(self.patch, Point3::ZERO, self.v).at(u)
        }
    }

    /// de Casteljau along `u`, the position shifted back by the origin.
    #[inline]
    fn at(&self, u: R) -> PatchPoint<R> {
        let (position, du) = casteljau(&self.rows, u);
        let (dv, _) = casteljau(&self.rows_dv, u);
        PatchPoint {
            position: position + self.origin,
            du,
            dv,
        }
    }
}
