//! Double-single arithmetic: a value as the unevaluated sum `hi + lo` of two
//! `f32` (`|lo| ≤ ½ ulp(hi)`), about 48 significant bits, from `f32`
//! operations only. The `f32` roots of unity are derived in it ([`super::angles`]),
//! so an `f32` build needs no `f64` arithmetic, which a Cortex-M4F has only in
//! software (~4 KiB of flash for the soft-float routines, ~100 instructions
//! per operation).
//!
//! Error-free transformations of Knuth (two-sum) and Dekker (two-product by
//! splitting at 2^12 + 1, no fused multiply-add: `core` has none for `f32`);
//! addition and multiplication as in the QD library (Hida, Li, Bailey,
//! "Library for double-double and quad-double arithmetic", 2007), with `f32`
//! in place of `f64`. Relative error of `add`, `mul`: a few units of 2^-48.
//! Only for the small magnitudes of angles, sines and cosines (no overflow
//! handling). `add`, `mul`, `div_int` are kept out of line: they run a few
//! hundred times per net, and inlined they cost ~1 KiB of Cortex-M flash.

/// `hi + lo`, `|lo| ≤ ½ ulp(hi)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ds {
    pub hi: f32,
    pub lo: f32,
}

/// `s + e = a + b` exactly (Knuth).
#[inline]
fn two_sum(a: f32, b: f32) -> Ds {
    let s = a + b;
    let bb = s - a;
    Ds {
        hi: s,
        lo: (a - (s - bb)) + (b - bb),
    }
}

/// `s + e = a + b` exactly, for `|a| ≥ |b|` (or `a = 0`).
#[inline]
fn quick_two_sum(a: f32, b: f32) -> Ds {
    let s = a + b;
    Ds {
        hi: s,
        lo: b - (s - a),
    }
}

/// `a = hi + lo` with 12 significant bits each (Dekker's split).
#[inline]
fn split(a: f32) -> (f32, f32) {
    let c = 4097.0 * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `p + e = a·b` exactly (Dekker).
#[inline]
fn two_prod(a: f32, b: f32) -> Ds {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    Ds {
        hi: p,
        lo: ((ah * bh - p) + ah * bl + al * bh) + al * bl,
    }
}

impl Ds {
    pub const ZERO: Ds = Ds { hi: 0.0, lo: 0.0 };
    pub const ONE: Ds = Ds { hi: 1.0, lo: 0.0 };

    /// `v` to about 48 bits (for constants: evaluated at compile time).
    pub const fn from_f64(v: f64) -> Ds {
        let hi = v as f32;
        Ds {
            hi,
            lo: (v - hi as f64) as f32,
        }
    }

    /// `self + b`.
    #[inline(never)]
    pub fn add(self, b: Ds) -> Ds {
        let s = two_sum(self.hi, b.hi);
        let t = two_sum(self.lo, b.lo);
        let s = quick_two_sum(s.hi, s.lo + t.hi);
        quick_two_sum(s.hi, s.lo + t.lo)
    }

    /// `−self`.
    #[inline]
    pub fn neg(self) -> Ds {
        Ds {
            hi: -self.hi,
            lo: -self.lo,
        }
    }

    /// `self − b`.
    #[inline]
    pub fn sub(self, b: Ds) -> Ds {
        self.add(b.neg())
    }

    /// `self · b`.
    #[inline(never)]
    pub fn mul(self, b: Ds) -> Ds {
        let p = two_prod(self.hi, b.hi);
        quick_two_sum(p.hi, p.lo + (self.hi * b.lo + self.lo * b.hi))
    }

    /// `self / m` for an integer `m` exact in `f32` (`0 < m ≤ 2^24`).
    #[inline(never)]
    pub fn div_int(self, m: f32) -> Ds {
        let q1 = self.hi / m;
        let p = two_prod(q1, m);
        let r = ((self.hi - p.hi) - p.lo) + self.lo;
        quick_two_sum(q1, r / m)
    }

    /// `self / 2`, exact (no underflow at the magnitudes used here).
    #[inline]
    pub fn half(self) -> Ds {
        Ds {
            hi: self.hi * 0.5,
            lo: self.lo * 0.5,
        }
    }

    /// Rounded to `f32` (`lo` is below half an ulp of `hi`, so `hi` is the
    /// nearest `f32` except for ties, which `hi + lo` settles).
    #[inline]
    pub fn round(self) -> f32 {
        self.hi + self.lo
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    fn val(d: Ds) -> f64 {
        d.hi as f64 + d.lo as f64
    }

    fn pseudo(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
    }

    /// Random operands per test (under Miri, ~10⁴× slower, 500).
    const RUNS: usize = if cfg!(miri) { 500 } else { 20_000 };

    /// Each operation is within a few units of 2^-48 (relative to the
    /// operands' magnitude) of the `f64` result of the same operation on the
    /// same (double-single) operands; `f64` is 5 bits finer, so it serves as
    /// the reference.
    #[test]
    fn operations_carry_about_48_bits() {
        let mut seed = 7;
        let tol = 8.0 * 2f64.powi(-48);
        for _ in 0..RUNS {
            let (x, y) = (pseudo(&mut seed), pseudo(&mut seed));
            let (a, b) = (Ds::from_f64(x), Ds::from_f64(y));
            let (va, vb) = (val(a), val(b));
            assert!((va - x).abs() <= 2f64.powi(-48) * x.abs());
            let scale = va.abs() + vb.abs();
            assert!((val(a.add(b)) - (va + vb)).abs() <= tol * scale);
            assert!((val(a.sub(b)) - (va - vb)).abs() <= tol * scale);
            assert!((val(a.mul(b)) - va * vb).abs() <= tol * (va * vb).abs());
            for m in [3.0f32, 7.0, 127.0, 600.0] {
                let q = val(a.div_int(m)) - va / m as f64;
                assert!(q.abs() <= tol * (va / m as f64).abs(), "{x} / {m}");
            }
            assert_eq!(val(a.half()), va / 2.0);
        }
    }

    /// Two-sum and two-product are exact: `f64` holds every sum and product
    /// of two `f32` exactly (sums: when exponents are within 29 of each
    /// other, as here).
    #[test]
    fn error_free_transformations_are_exact() {
        let mut seed = 11;
        for _ in 0..RUNS {
            let (a, b) = (pseudo(&mut seed) as f32, pseudo(&mut seed) as f32);
            let s = two_sum(a, b);
            assert_eq!(val(s), a as f64 + b as f64);
            let p = two_prod(a, b);
            assert_eq!(val(p), a as f64 * b as f64);
        }
    }

    /// `round` is the nearest `f32` of `hi + lo`.
    #[test]
    fn round_is_nearest() {
        let mut seed = 13;
        for _ in 0..RUNS {
            let x = pseudo(&mut seed);
            let d = Ds::from_f64(x);
            assert_eq!(d.round(), val(d) as f32);
        }
    }
}
