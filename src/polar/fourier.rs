//! The five Fourier sums of the 1-link (spec C2PS.md §2):
//! `A = mean q1[h]`, `C_k = mean c(kh/n) q1[h]`, `S_k = mean s(kh/n) q1[h]`, k = 1, 2.

use super::index::{add_mod, at};
use crate::point::Point3;
use crate::real::Real;

/// `A, C1, S1, C2, S2` of a 1-link.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fourier<R> {
    pub a: Point3<R>,
    pub c1: Point3<R>,
    pub s1: Point3<R>,
    pub c2: Point3<R>,
    pub s2: Point3<R>,
}

impl<R: Real> Fourier<R> {
    /// Sums over `link` (length `n`), with `roots[stride·h]` = `(c, s)(h/n)`;
    /// `roots.len() = stride·n`.
    pub fn of(link: &[Point3<R>], roots: &[[R; 2]], stride: usize) -> Self {
        let n = link.len();
        let len = roots.len();
        let mut f = Fourier {
            a: Point3::ZERO,
            c1: Point3::ZERO,
            s1: Point3::ZERO,
            c2: Point3::ZERO,
            s2: Point3::ZERO,
        };
        let none = [R::ZERO; 2];
        for (h, q) in link.iter().enumerate() {
            // stride·h < len; (2·stride·h) mod len by one conditional subtraction.
            let k = stride.wrapping_mul(h);
            let [c, s] = at(roots, k, none);
            let [c2, s2] = at(roots, add_mod(k, k, len), none);
            f.a += *q;
            f.c1 += *q * c;
            f.s1 += *q * s;
            f.c2 += *q * c2;
            f.s2 += *q * s2;
        }
        if n == 0 {
            return f; // an empty net: all sums zero
        }
        let inv = R::ONE / R::from_f64(n as f64);
        f.a = f.a * inv;
        f.c1 = f.c1 * inv;
        f.s1 = f.s1 * inv;
        f.c2 = f.c2 * inv;
        f.s2 = f.s2 * inv;
        f
    }

    /// First harmonic `C1 c + S1 s` at the angle whose `(c, s)` is given.
    #[inline]
    pub fn h1(&self, [c, s]: [R; 2]) -> Point3<R> {
        self.c1 * c + self.s1 * s
    }

    /// Second harmonic `C2 c2 + S2 s2`, given `(c, s)` of the doubled angle.
    #[inline]
    pub fn h2(&self, [c2, s2]: [R; 2]) -> Point3<R> {
        self.c2 * c2 + self.s2 * s2
    }
}
