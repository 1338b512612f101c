//! `PoleJet`: the eigencoefficients `p0..p5` at the pole and what follows from
//! them (docs/math/c2ps.md §4): limit point, unit normal, curvatures.
//!
//! Normalisation (the paper's Table 1, not its mistyped eq. (27)):
//! `p0 = 2/3 q00 + 1/3 A`, `p1 = 2 C1`, `p2 = 2 S1`, `p3 = A − q00`,
//! `p4 = 3 C2`, `p5 = 3 S2`, from the configuration's own valence. Near the pole
//! the limit surface is `p0 + p1 x + p2 y + p3 (x²+y²) + p4 (x²−y²) + p5 (2xy)`.

use super::fourier::Fourier;
use super::net::PolarNetInner;
use super::storage::NetStorage;
use crate::bezier::{SurfaceGeometry, SurfaceJet};
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;

/// The six eigencoefficients of a polar configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PoleJet<R> {
    /// `p0..p5`.
    pub p: [Point3<R>; 6],
}

/// Differential geometry of the limit surface at the pole: the same formulas
/// as at any surface point ([`SurfaceJet::geometry`]).
pub type PoleGeometry<R> = SurfaceGeometry<R>;

impl<R: Real> PoleJet<R> {
    /// The jet of a net at its current level, whatever its storage.
    ///
    /// The coefficients overflow only for nets with coordinates above
    /// `MAX/(3·N)` (every coefficient is below `3·m` for coordinates below
    /// `m`, the Fourier sums below `2·N·m`); [`Self::finite`] checks.
    ///
    /// ```
    /// use capdiv::{FirstStep, Point3, PolarNet, PoleJet};
    /// // A rotationally symmetric configuration (the paraboloid z = r²/10):
    /// // the limit lies on the axis, p0 = 2/3 q00 + 1/3 A (§4, Table 1).
    /// let links: Vec<Vec<[f64; 3]>> = (1..=5)
    ///     .map(|i| (0..6).map(|j| {
    ///         let t = core::f64::consts::TAU * j as f64 / 6.0;
    ///         let r = i as f64;
    ///         [r * t.cos(), r * t.sin(), 0.1 * r * r]
    ///     }).collect())
    ///     .collect();
    /// let mut net: PolarNet<f64, 12> = PolarNet::new([0.0; 3], &links)?;
    /// let jet = PoleJet::of(&net).finite()?;
    /// assert!(jet.limit().max_abs_diff(Point3([0.0, 0.0, 0.1 / 3.0])) < 1e-15);
    /// assert!(jet.geometry()?.normal.max_abs_diff(Point3([0.0, 0.0, 1.0])) < 1e-12);
    /// // A step does not move the limit.
    /// net.step(FirstStep::Uniform)?;
    /// assert!(PoleJet::of(&net).limit().max_abs_diff(jet.limit()) < 1e-15);
    /// # Ok::<(), capdiv::Error>(())
    /// ```
    pub fn of<S: NetStorage<R>>(net: &PolarNetInner<R, S>) -> Self {
        let v = net.view();
        Self::from_parts(v.head.pole, v.link(1).unwrap_or(&[]), v.roots())
    }

    /// The jet, or [`Error::NonFinite`] when a coefficient is not finite.
    pub fn finite(self) -> Result<Self, Error> {
        if self.p.iter().all(Point3::is_finite) {
            Ok(self)
        } else {
            Err(Error::NonFinite)
        }
    }

    /// The jet from the pole, the 1-link and the roots of its valence
    /// (`roots.len() = link1.len()`), compiled once per scalar type.
    fn from_parts(q00: Point3<R>, link1: &[Point3<R>], roots: &[[R; 2]]) -> Self {
        let f = Fourier::of(link1, roots, 1);
        let two = R::from_f64(2.0);
        let three = R::from_f64(3.0);
        PoleJet {
            p: [
                q00 * R::ratio(2, 3) + f.a * R::ratio(1, 3),
                f.c1 * two,
                f.s1 * two,
                f.a - q00,
                f.c2 * three,
                f.s2 * three,
            ],
        }
    }

    /// The limit point at the pole, `p0`.
    #[inline]
    pub fn limit(&self) -> Point3<R> {
        self.p[0]
    }

    /// Normal and curvatures; [`Error::Degenerate`] when `p1 × p2` vanishes
    /// (or under- or overflows: `|p1|·|p2|` outside about `[√MIN_POSITIVE,
    /// √MAX]`), [`Error::NonFinite`] when a curvature overflows (a net far
    /// smaller than its tangents) or the jet is not finite.
    pub fn geometry(&self) -> Result<PoleGeometry<R>, Error> {
        let [p0, p1, p2, p3, p4, p5] = self.p;
        let two = R::from_f64(2.0);
        SurfaceJet {
            position: p0,
            du: p1,
            dv: p2,
            duu: (p3 + p4) * two,
            duv: p5 * two,
            dvv: (p3 - p4) * two,
        }
        .geometry()
    }
}
