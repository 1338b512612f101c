//! `Point3`: a point or vector in 3-space, the unit every net stores.

use crate::error::Error;
use crate::real::Real;
use core::ops::{Add, AddAssign, Mul, Neg, Sub};

/// A point (or vector) with coordinates `[x, y, z]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Point3<R>(pub [R; 3]);

impl<R: Real> Point3<R> {
    /// The origin.
    pub const ZERO: Self = Point3([R::ZERO; 3]);

    /// A point from its coordinates.
    #[inline]
    pub const fn new(x: R, y: R, z: R) -> Self {
        Point3([x, y, z])
    }
    /// `true` when all three coordinates are finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.0.iter().all(|c| c.is_finite())
    }
    /// The point, or [`Error::NonFinite`] when a coordinate is not finite:
    /// the one check of a computed limit, as [`crate::PoleJet::finite`] is
    /// of a jet (`cap.limit().finite()?`).
    #[inline]
    pub fn finite(self) -> Result<Self, Error> {
        if self.is_finite() {
            Ok(self)
        } else {
            Err(Error::NonFinite)
        }
    }
    /// Dot product.
    #[inline]
    pub fn dot(self, o: Self) -> R {
        self.0[0] * o.0[0] + self.0[1] * o.0[1] + self.0[2] * o.0[2]
    }
    /// Cross product.
    #[inline]
    pub fn cross(self, o: Self) -> Self {
        let [a, b, c] = self.0;
        let [d, e, f] = o.0;
        Point3([b * f - c * e, c * d - a * f, a * e - b * d])
    }
    /// Euclidean length.
    #[inline]
    pub fn norm(self) -> R {
        self.dot(self).sqrt()
    }
    /// `self` divided by its length ([`Point3::norm`]), `None` when the
    /// length is zero or not finite.
    ///
    /// ```
    /// use capdiv::Point3;
    /// assert_eq!(Point3::new(3.0, 0.0, 4.0).unit(), Some(Point3::new(0.6, 0.0, 0.8)));
    /// assert_eq!(Point3::<f64>::ZERO.unit(), None);
    /// assert_eq!(Point3::new(f64::INFINITY, 0.0, 0.0).unit(), None);
    /// ```
    #[inline]
    pub fn unit(self) -> Option<Self> {
        let len = self.norm();
        (len > R::ZERO && len.is_finite()).then(|| Point3(self.0.map(|c| c / len)))
    }
    /// Converts the coordinate type (through `f64`).
    #[inline]
    pub fn cast<S: Real>(self) -> Point3<S> {
        Point3(self.0.map(|c| S::from_f64(c.to_f64())))
    }
    /// Largest absolute coordinate difference to `o`.
    #[inline]
    pub fn max_abs_diff(self, o: Self) -> R {
        let mut m = R::ZERO;
        for k in 0..3 {
            let d = (self.0[k] - o.0[k]).abs();
            if d > m {
                m = d;
            }
        }
        m
    }
}

impl<R: Real> Add for Point3<R> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Point3([self.0[0] + o.0[0], self.0[1] + o.0[1], self.0[2] + o.0[2]])
    }
}
impl<R: Real> AddAssign for Point3<R> {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl<R: Real> Sub for Point3<R> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Point3([self.0[0] - o.0[0], self.0[1] - o.0[1], self.0[2] - o.0[2]])
    }
}
impl<R: Real> Neg for Point3<R> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Point3([-self.0[0], -self.0[1], -self.0[2]])
    }
}
impl<R: Real> Mul<R> for Point3<R> {
    type Output = Self;
    #[inline]
    fn mul(self, s: R) -> Self {
        // Written out like `add`: `array::map` is not inlined at opt-level
        // "z" (the firmware's), and each product became a call.
        Point3([self.0[0] * s, self.0[1] * s, self.0[2] * s])
    }
}

impl<R> From<[R; 3]> for Point3<R> {
    #[inline]
    fn from(a: [R; 3]) -> Self {
        Point3(a)
    }
}
impl<R> From<Point3<R>> for [R; 3] {
    #[inline]
    fn from(p: Point3<R>) -> Self {
        p.0
    }
}
