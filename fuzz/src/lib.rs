//! Helpers shared by the fuzz targets: scalars from raw bytes (every bit
//! pattern reachable, plus a bias towards small and special values so that
//! mutations find interesting nets quickly) and bitwise snapshots of state.

use arbitrary::{Result, Unstructured};
use capdiv::{Point3, Real};

/// A kernel scalar the targets can draw from bytes.
pub trait FuzzReal: Real + core::fmt::Debug + core::fmt::Display + 'static {
    /// Any bit pattern, or a value from a biased distribution.
    fn arb(u: &mut Unstructured<'_>) -> Result<Self>;
    /// The bits (for bitwise comparison, NaN-safe).
    fn bits(self) -> u64;
    /// The type's largest finite value.
    const MAX_F: Self;
    /// The name for messages.
    const NAME: &'static str;
}

/// Values worth hitting on purpose.
const SPECIAL_F64: [f64; 16] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    f64::MAX,
    -f64::MAX,
    f64::MIN_POSITIVE,
    5e-324,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NAN,
    f64::MAX / 1024.0,
    1e-300,
    1e300,
    3.0e38,
];

fn small(u: &mut Unstructured<'_>) -> Result<f64> {
    let k: i16 = u.arbitrary()?;
    Ok(f64::from(k) / 256.0)
}

fn scaled(u: &mut Unstructured<'_>) -> Result<f64> {
    let m: i16 = u.arbitrary()?;
    let e: i16 = u.arbitrary()?;
    Ok(f64::from(m) * libm_pow2(i32::from(e) % 1100))
}

fn libm_pow2(e: i32) -> f64 {
    // 2^e by repeated halving/doubling in range (no overflow to NaN).
    let mut x = 1.0f64;
    if e >= 0 {
        for _ in 0..e {
            x *= 2.0;
        }
    } else {
        for _ in 0..(-e) {
            x *= 0.5;
        }
    }
    x
}

impl FuzzReal for f64 {
    fn arb(u: &mut Unstructured<'_>) -> Result<Self> {
        let tag: u8 = u.arbitrary()?;
        Ok(match tag % 8 {
            0..=3 => small(u)?,
            4 => f64::from_bits(u.arbitrary()?),
            5 => SPECIAL_F64[usize::from(tag >> 4)],
            _ => scaled(u)?,
        })
    }
    fn bits(self) -> u64 {
        self.to_bits()
    }
    const MAX_F: Self = f64::MAX;
    const NAME: &'static str = "f64";
}

impl FuzzReal for f32 {
    fn arb(u: &mut Unstructured<'_>) -> Result<Self> {
        let tag: u8 = u.arbitrary()?;
        Ok(match tag % 8 {
            0..=3 => small(u)? as f32,
            4 => f32::from_bits(u.arbitrary()?),
            5 => [
                0.0f32,
                -0.0,
                1.0,
                -1.0,
                0.5,
                f32::MAX,
                -f32::MAX,
                f32::MIN_POSITIVE,
                1e-45,
                f32::INFINITY,
                f32::NEG_INFINITY,
                f32::NAN,
                f32::MAX / 1024.0,
                1e-30,
                1e30,
                3.0e38,
            ][usize::from(tag >> 4)],
            _ => scaled(u)? as f32,
        })
    }
    fn bits(self) -> u64 {
        u64::from(self.to_bits())
    }
    const MAX_F: Self = f32::MAX;
    const NAME: &'static str = "f32";
}

/// A point from bytes.
pub fn arb_point<R: FuzzReal>(u: &mut Unstructured<'_>) -> Result<[R; 3]> {
    Ok([R::arb(u)?, R::arb(u)?, R::arb(u)?])
}

/// A pool of 1..=`max` arbitrary points; the targets cycle through it to fill
/// large nets from few bytes.
pub fn arb_pool<R: FuzzReal>(u: &mut Unstructured<'_>, max: usize) -> Result<Vec<[R; 3]>> {
    let k = u.int_in_range(1..=max)?;
    (0..k).map(|_| arb_point(u)).collect()
}

/// Largest absolute coordinate (NaN counts as infinite).
pub fn max_abs<R: FuzzReal>(points: impl IntoIterator<Item = [R; 3]>) -> f64 {
    let mut m = 0.0f64;
    for p in points {
        for c in p {
            let a = c.to_f64().abs();
            if a.is_nan() {
                return f64::INFINITY;
            }
            m = m.max(a);
        }
    }
    m
}

/// Coordinates at most `MAX / 2^k`.
pub fn bounded<R: FuzzReal>(points: impl IntoIterator<Item = [R; 3]>, k: i32) -> bool {
    max_abs(points) <= R::MAX_F.to_f64() / libm_pow2(k)
}

/// Bits of a point.
pub fn point_bits<R: FuzzReal>(p: Point3<R>, out: &mut Vec<u64>) {
    out.extend(p.0.iter().map(|c| c.bits()));
}

/// All coordinates finite.
pub fn all_finite<R: FuzzReal>(points: impl IntoIterator<Item = Point3<R>>) -> bool {
    points.into_iter().all(|p| p.is_finite())
}
