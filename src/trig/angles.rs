//! [`UnitRoots`]: how each scalar type derives the roots of unity the C²PS
//! rules need (docs/math/c2ps.md §2, §4: `c(j/N)`, `s(j/N)`).
//!
//! - `f64`: from the compile-time table [`super::ODD_ROOTS`] by a product
//!   chain (base ring) and half-angle steps ([`super::primitive_root`]), all
//!   in `f64`.
//! - `f32`: from the angle `2π/n` in double-single arithmetic
//!   (`double_single`, ~48 bits) by Taylor series, with `f32`
//!   operations only — no soft-float `f64` on an FPU-less or single-precision
//!   chip — then rounded to `f32`. Over every supported odd part and 30
//!   doublings the rounded values equal the `f64` route's rounded to `f32`,
//!   bit for bit (`f32_roots_are_the_f64_roots_rounded`), so `f32` results do
//!   not depend on the route.

use super::double_single::Ds;
use super::table::{primitive_root, MAX_ODD_PART};

/// Derives the `n`-th roots of unity `(cos, sin)(2πj/n)` in a scalar type.
/// Implemented for `f32` and `f64`; a supertrait of [`crate::Real`].
pub trait UnitRoots: Sized {
    /// Writes the `base`-th roots to `ring[..base]` (entries beyond
    /// `ring.len()` are skipped), `base` the odd part `3 ≤ o ≤ 127` of a
    /// valence or 4; nothing for other `base`.
    fn fill_base(ring: &mut [[Self; 2]], base: usize);
    /// `(cos, sin)(2π/n)` for a valence `n ≥ 3` whose odd part is at most
    /// [`MAX_ODD_PART`]; `[1, 0]` for any other `n`.
    fn unit_root(n: usize) -> [Self; 2];
}

/// `(odd part, number of factors 2)` of `n > 0`.
#[inline]
fn odd_part(n: usize) -> (usize, u32) {
    let f = n.trailing_zeros();
    (n >> f, f)
}

impl UnitRoots for f64 {
    /// The powers `ω^j`, `j ≤ base/2`, by repeated multiplication (at most
    /// 63 products), the rest by symmetry `ω^(n−j) = conj ω^j`.
    fn fill_base(ring: &mut [[f64; 2]], base: usize) {
        let Some(w) = primitive_root(base) else {
            return;
        };
        let (mut c, mut s) = (1.0f64, 0.0f64);
        for j in 0..=base / 2 {
            put(ring, j, [c, s]);
            if j > 0 {
                put(ring, base - j, [c, -s]);
            }
            let c2 = c * w.0 - s * w.1;
            s = s * w.0 + c * w.1;
            c = c2;
        }
    }

    fn unit_root(n: usize) -> [f64; 2] {
        primitive_root(n).map_or([1.0, 0.0], |(c, s)| [c, s])
    }
}

/// `2π`, `π/2`, `π/4` to ~48 bits.
const TAU: Ds = Ds::from_f64(core::f64::consts::TAU);
const FRAC_PI_2: Ds = Ds::from_f64(core::f64::consts::FRAC_PI_2);
const FRAC_PI_4: f32 = core::f64::consts::FRAC_PI_4 as f32;

/// `(sin x, cos x)` for `|x| ≤ π/4 (+ rounding)`: Taylor series, summed until
/// the terms fall below 2^-50 (at most 11 terms each at `π/4`).
fn sin_cos_small(x: Ds) -> (Ds, Ds) {
    let x2 = x.mul(x).neg();
    let (mut s, mut c) = (Ds::ZERO, Ds::ZERO);
    let (mut ts, mut tc) = (x, Ds::ONE); // x^(2k+1)/(2k+1)!, x^(2k)/(2k)! with signs
    let mut k = 0.0f32;
    while k < 24.0 {
        s = s.add(ts);
        c = c.add(tc);
        if tc.hi.abs() < 1e-15 {
            break;
        }
        let (a, b) = (2.0 * k + 2.0, 2.0 * k + 3.0);
        ts = ts.mul(x2).div_int(a * b);
        tc = tc.mul(x2).div_int((2.0 * k + 1.0) * a);
        k += 1.0;
    }
    (s, c)
}

/// `(cos θ, sin θ)` for `0 ≤ θ ≤ 3π/4`: directly for `θ ≤ π/4`, else from
/// the complement `π/2 − θ ∈ [−π/4, π/4)` with sine and cosine swapped (as
/// [`super::table`] does in `f64`).
fn cos_sin(theta: Ds) -> (Ds, Ds) {
    if theta.hi <= FRAC_PI_4 {
        let (s, c) = sin_cos_small(theta);
        (c, s)
    } else {
        sin_cos_small(FRAC_PI_2.sub(theta))
    }
}

/// `2π/n` for `n = o·2^f`: `2π/o`, then halved `f` times (exact).
fn angle(o: usize, f: u32) -> Ds {
    let mut t = TAU.div_int(o as f32);
    for _ in 0..f {
        t = t.half();
    }
    t
}

impl UnitRoots for f32 {
    /// The powers `ω^j`, `j ≤ base/2`, by repeated multiplication in
    /// double-single (at most 63 products), the rest by symmetry.
    fn fill_base(ring: &mut [[f32; 2]], base: usize) {
        if base != 4 && (base.is_multiple_of(2) || !(3..=MAX_ODD_PART).contains(&base)) {
            return;
        }
        let (wc, ws) = cos_sin(angle(base, 0));
        let (mut c, mut s) = (Ds::ONE, Ds::ZERO);
        for j in 0..=base / 2 {
            let (rc, rs) = (c.round(), s.round());
            put(ring, j, [rc, rs]);
            if j > 0 {
                put(ring, base - j, [rc, -rs]);
            }
            let c2 = c.mul(wc).sub(s.mul(ws));
            s = s.mul(wc).add(c.mul(ws));
            c = c2;
        }
    }

    fn unit_root(n: usize) -> [f32; 2] {
        if n < 3 {
            return [1.0, 0.0];
        }
        let (o, f) = odd_part(n);
        if o > MAX_ODD_PART {
            return [1.0, 0.0];
        }
        let (c, s) = cos_sin(angle(o, f));
        [c.round(), s.round()]
    }
}

/// `ring[j] = v` when `j` is in range.
#[inline]
fn put<R>(ring: &mut [[R; 2]], j: usize, v: [R; 2]) {
    if let Some(slot) = ring.get_mut(j) {
        *slot = v;
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// The `f64` ring of the odd part or 4, then `doublings` doublings'
    /// primitive roots: every value the `f64` route produces before rounding.
    fn f64_route(
        base: usize,
        doublings: u32,
    ) -> (std::vec::Vec<[f64; 2]>, std::vec::Vec<[f64; 2]>) {
        let mut ring = std::vec![[0.0f64; 2]; base];
        f64::fill_base(&mut ring, base);
        let halves = (1..=doublings).map(|k| f64::unit_root(base << k)).collect();
        (ring, halves)
    }

    /// Bit for bit: the `f32` route gives the `f64` route's values rounded to
    /// `f32`, for every supported odd part (and 4) and 30 doublings each.
    #[test]
    fn f32_roots_are_the_f64_roots_rounded() {
        let rounded = |v: [f64; 2]| v.map(|x| x as f32);
        // Under Miri (~10⁴× slower) every 8th odd part: 3, 19, .., 115.
        let every = if cfg!(miri) { 16 } else { 2 };
        let mut bases: std::vec::Vec<usize> = (3..=MAX_ODD_PART).step_by(every).collect();
        bases.push(4);
        let mut checked = 0;
        for base in bases {
            let (ring64, halves64) = f64_route(base, 30);
            let mut ring32 = std::vec![[0.0f32; 2]; base];
            f32::fill_base(&mut ring32, base);
            for (j, (a, b)) in ring32.iter().zip(&ring64).enumerate() {
                assert_eq!(*a, rounded(*b), "base {base}, j {j}");
                checked += 1;
            }
            for (k, h) in halves64.iter().enumerate() {
                let n = base << (k + 1);
                assert_eq!(f32::unit_root(n), rounded(*h), "n {n}");
                checked += 1;
            }
        }
        assert!(checked > if cfg!(miri) { 700 } else { 3000 });
    }

    /// Within 2^-46 of `f64`'s `cos`, `sin` before rounding (double-single
    /// carries ~48 bits; the reductions and series add a few units).
    #[test]
    fn double_single_cos_sin_are_accurate() {
        for o in (3..=MAX_ODD_PART).step_by(2).chain([1]) {
            for f in 0..12 {
                if o == 1 && f < 2 {
                    continue;
                }
                let n = (o << f) as f64;
                let (c, s) = cos_sin(angle(o, f));
                let t = core::f64::consts::TAU / n;
                let tol = 2f64.powi(-46);
                assert!(
                    (c.hi as f64 + c.lo as f64 - t.cos()).abs() < tol,
                    "cos 2π/{n}"
                );
                assert!(
                    (s.hi as f64 + s.lo as f64 - t.sin()).abs() < tol,
                    "sin 2π/{n}"
                );
            }
        }
    }

    #[test]
    fn unsupported_valences_give_one() {
        assert_eq!(f32::unit_root(2), [1.0, 0.0]);
        assert_eq!(f32::unit_root(129), [1.0, 0.0]);
        assert_eq!(f64::unit_root(129), [1.0, 0.0]);
        let mut ring = [[7.0f32; 2]; 8];
        f32::fill_base(&mut ring, 6);
        assert_eq!(ring, [[7.0f32; 2]; 8]);
    }
}
