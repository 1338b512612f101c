//! The scalar trait: one code path for `f32` and `f64`.
//!
//! Every formula in the kernel is written once over [`Real`]. Constants are
//! written as exact rationals in `f64` and rounded once to the target type by
//! [`Real::from_f64`] (constant operands: folded by the compiler). Values known
//! only at run time — valences, table weights — reach the type through
//! [`Real::ratio`] and [`Real::from_usize`], which never compute in `f64` for
//! `f32`: an `f32` build needs no soft-float `f64` routines (on a Cortex-M4F
//! they are ~4 KiB of flash and ~100 instructions per operation).
//!
//! Square roots go through `libm` (`sqrt`, `sqrtf`), correctly rounded. With the
//! `micromath` feature, `f32::sqrt` is micromath's bit-manipulation estimate
//! (about 5 % relative error, see that crate's `sqrt` module). It only affects the
//! operations that need a square root — unit normals, principal curvatures,
//! vector lengths — never the refinement rules, whose angles are derived in `f64`
//! (see [`crate::trig`]). The README states the accuracy measured with it.

use crate::trig::UnitRoots;
use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A floating-point scalar the kernel can compute in (`f32` or `f64`).
pub trait Real:
    Copy
    + Debug
    + Default
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + UnitRoots
    + 'static
{
    /// Additive identity.
    const ZERO: Self;
    /// Multiplicative identity.
    const ONE: Self;
    /// Machine epsilon of the type.
    const EPSILON: Self;

    /// Rounds an `f64` to this type.
    fn from_f64(v: f64) -> Self;
    /// Widens to `f64` (exact for both implementors).
    fn to_f64(self) -> f64;
    /// The exact rational `num / den`, rounded once to this type when
    /// `|num|, |den| ≤ 2^24` (every caller: weights ≤ 10⁵, valences; `f32`
    /// divides the exactly converted integers, which rounds the same as
    /// rounding the `f64` quotient again, since 53 ≥ 2·24 + 2).
    #[inline]
    fn ratio(num: i32, den: i32) -> Self {
        Self::from_f64(num as f64 / den as f64)
    }
    /// `n` rounded to this type (exact below 2^24 for `f32`, 2^53 for `f64`).
    fn from_usize(n: usize) -> Self;
    /// Square root (libm, or micromath's estimate for `f32` with that feature).
    fn sqrt(self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// `true` unless NaN or ±∞.
    fn is_finite(self) -> bool;
}

impl Real for f64 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const EPSILON: Self = f64::EPSILON;
    #[inline]
    fn from_f64(v: f64) -> Self {
        v
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn from_usize(n: usize) -> Self {
        n as f64
    }
    #[inline]
    fn sqrt(self) -> Self {
        libm::sqrt(self)
    }
    #[inline]
    fn abs(self) -> Self {
        libm::fabs(self)
    }
    #[inline]
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
}

impl Real for f32 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const EPSILON: Self = f32::EPSILON;
    #[inline]
    fn from_f64(v: f64) -> Self {
        v as f32
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline]
    fn ratio(num: i32, den: i32) -> Self {
        num as f32 / den as f32
    }
    #[inline]
    fn from_usize(n: usize) -> Self {
        n as f32
    }
    #[cfg(not(feature = "micromath"))]
    #[inline]
    fn sqrt(self) -> Self {
        libm::sqrtf(self)
    }
    #[cfg(feature = "micromath")]
    #[inline]
    fn sqrt(self) -> Self {
        micromath::F32Ext::sqrt(self)
    }
    #[inline]
    fn abs(self) -> Self {
        libm::fabsf(self)
    }
    #[inline]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
}
