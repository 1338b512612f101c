//! The Catmull-Clark limit at the center: position, tangents, unit normal.
//!
//! Position: the left eigenvector of eigenvalue 1 of the subdivision matrix,
//! `(n² e + 4 Σ (1,0)_s + Σ (1,1)_s) / (n(n+5))` (Halstead, Kass & DeRose
//! 1993), for every valence, n = 3 included.
//!
//! Tangents: the projections on the subdominant eigenvector pair (Halstead et
//! al. 1993; OpenSubdiv's Catmark limit tangent masks, same ratio of edge to
//! face weights):
//! `t1 = Σ_s A_n cos θ_s (1,0)_s + (cos θ_s + cos θ_{s+1}) (1,1)_s`,
//! `t2` the same with `sin`, `θ_s = 2πs/n`,
//! `A_n = 1 + cos(2π/n) + cos(π/n) √(2(9 + cos(2π/n)))`. No trig call at run
//! time: `cos, sin (2π/n)` and `cos(π/n)` come from [`crate::trig::primitive_root`]
//! (its table of odd parts ≤ 127), the `θ_s` by repeated rotation in `f64`.

use super::cap::CcCap;
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;
use crate::trig::primitive_root;

impl<R: Real> CcCap<'_, R> {
    /// Node `(x, y)` of sector `s < n` of the current c-net (or the center).
    #[inline]
    fn c(&self, s: usize, x: i32, y: i32) -> Point3<R> {
        self.node(s, x, y).unwrap_or(self.center)
    }

    /// The Catmull-Clark limit position of the center,
    /// `(n² e + 4 Σ (1,0)_s + Σ (1,1)_s) / (n(n+5))`, written as
    /// `e + Σ w (c − e)` (the weights sum to 1; exact for translations).
    /// The same at every level.
    ///
    /// Not checked: it overflows only for nets with coordinates of opposite
    /// signs near `MAX/2` (`c − e` is formed first); [`Point3::finite`]
    /// checks (`cap.limit().finite()?`, [`Error::NonFinite`]), as
    /// [`crate::PoleJet::finite`] does for C²PS.
    pub fn limit(&self) -> Point3<R> {
        let nf = self.n as f64;
        let w6 = R::from_f64(4.0 / (nf * (nf + 5.0)));
        let w5 = R::from_f64(1.0 / (nf * (nf + 5.0)));
        let e = self.center;
        let mut acc = Point3::ZERO;
        for s in 0..self.n {
            acc += (self.c(s, 1, 0) - e) * w6 + (self.c(s, 1, 1) - e) * w5;
        }
        e + acc
    }

    /// The limit tangents `(t1, t2)` at the center (module doc): `t1` along
    /// spoke 0, `t2` a quarter turn counter-clockwise from it in the
    /// characteristic map, so `t1 × t2` points to the side of `∂u × ∂v` of
    /// the ring patches. Not normalized (their common scale depends on the
    /// net). [`Error::ValenceUnsupported`] when the odd part of `n` exceeds
    /// [`crate::trig::MAX_ODD_PART`]; [`Error::NonFinite`] when a tangent
    /// overflows (coordinates near `MAX/(4n)` and beyond).
    pub fn limit_tangents(&self) -> Result<(Point3<R>, Point3<R>), Error> {
        let n = self.n;
        let unsupported = Error::ValenceUnsupported { valence: n };
        let (c1, s1) = primitive_root(n).ok_or(unsupported)?;
        let (c_half, _) = n
            .checked_mul(2)
            .and_then(primitive_root)
            .ok_or(unsupported)?;
        let a_n = 1.0 + c1 + c_half * libm::sqrt(2.0 * (9.0 + c1));
        let e = self.center;
        let (mut t1, mut t2) = (Point3::ZERO, Point3::ZERO);
        // (cos, sin) θ_s, rotated by 2π/n per sector. Σ cos θ_s = Σ sin θ_s = 0,
        // so the weights of e sum to 0: take differences from e.
        let (mut c, mut sn) = (1.0f64, 0.0f64);
        for s in 0..n {
            let (cn, snn) = (c * c1 - sn * s1, sn * c1 + c * s1);
            let edge = self.c(s, 1, 0) - e;
            let face = self.c(s, 1, 1) - e;
            t1 += edge * R::from_f64(a_n * c) + face * R::from_f64(c + cn);
            t2 += edge * R::from_f64(a_n * sn) + face * R::from_f64(sn + snn);
            (c, sn) = (cn, snn);
        }
        if t1.is_finite() && t2.is_finite() {
            Ok((t1, t2))
        } else {
            Err(Error::NonFinite)
        }
    }

    /// The unit limit normal at the center, `t1 × t2 / |t1 × t2|`
    /// ([`CcCap::limit_tangents`]); [`Error::Degenerate`] if it vanishes (or
    /// `t1 × t2` under- or overflows), [`Error::ValenceUnsupported`] and
    /// [`Error::NonFinite`] as `limit_tangents`.
    pub fn normal(&self) -> Result<Point3<R>, Error> {
        let (t1, t2) = self.limit_tangents()?;
        let m = t1.cross(t2);
        let len = m.norm();
        let unit = m * (R::ONE / len);
        // `unit` is not finite when `len` is subnormal (its reciprocal overflows).
        if !(len > R::ZERO && len.is_finite() && unit.is_finite()) {
            return Err(Error::Degenerate);
        }
        // `|m|²` can be subnormal while `|m|` is not (f32 tangents near 1e-10):
        // `len` then has lost precision. Normalize `m` scaled by its largest
        // component instead (found by fuzz/kernel_eg_cc).
        let big =
            m.0.iter()
                .fold(R::ZERO, |a, c| if c.abs() > a { c.abs() } else { a });
        let s = Point3(m.0.map(|c| c / big));
        Ok(s * (R::ONE / s.norm()))
    }
}
