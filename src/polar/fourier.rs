//! The five Fourier sums of the 1-link (docs/math/c2ps.md §2):
//! `A = mean q1[h]`, `C_k = mean c(kh/n) q1[h]`, `S_k = mean s(kh/n) q1[h]`, k = 1, 2.
//!
//! The sums run over up to `CAP` terms (8192 and more at depth 8). Plain
//! running sums would lose accuracy in proportion to `n`; instead blocks of
//! [`BLOCK`] terms are summed plainly and the block sums are accumulated with
//! Kahan's compensated summation. The error is then bounded by the block length,
//! not by `n` — this keeps the f32 kernel's deviation independent of the
//! valence (docs/accuracy.md: 2.1e-7 of the level-0 bounding box at depth 8
//! over random nets up to n = 64, against 8.6e-6 with plain running sums) for
//! +0.4 % instructions per step (callgrind; Kahan on every term: +28 %).

use super::index::{add_mod, at};
use crate::point::Point3;
use crate::real::Real;

/// Terms summed plainly before a compensated addition.
const BLOCK: usize = 32;

/// `A, C1, S1, C2, S2` of a 1-link.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fourier<R> {
    pub a: Point3<R>,
    pub c1: Point3<R>,
    pub s1: Point3<R>,
    pub c2: Point3<R>,
    pub s2: Point3<R>,
}

/// A compensated (Kahan) running sum of points.
#[derive(Clone, Copy)]
struct Sum<R> {
    sum: Point3<R>,
    carry: Point3<R>,
}

impl<R: Real> Sum<R> {
    const ZERO: Self = Sum {
        sum: Point3([R::ZERO; 3]),
        carry: Point3([R::ZERO; 3]),
    };

    #[inline]
    fn add(&mut self, x: Point3<R>) {
        // Kahan: `carry` holds the negated low-order part lost so far.
        let y = x - self.carry;
        let t = self.sum + y;
        self.carry = (t - self.sum) - y;
        self.sum = t;
    }

    #[inline]
    fn total(&self) -> Point3<R> {
        self.sum - self.carry
    }
}

impl<R: Real> Fourier<R> {
    /// Sums over `link` (length `n`), with `roots[stride·h]` = `(c, s)(h/n)`;
    /// `roots.len() = stride·n`.
    pub fn of(link: &[Point3<R>], roots: &[[R; 2]], stride: usize) -> Self {
        let n = link.len();
        let len = roots.len();
        let mut sums = [Sum::ZERO; 5];
        let none = [R::ZERO; 2];
        // Plain sums within blocks of BLOCK terms, compensated across blocks.
        let mut h = 0usize;
        for block in link.chunks(BLOCK) {
            let mut part = [Point3::ZERO; 5];
            for q in block {
                // stride·h < len; (2·stride·h) mod len by one conditional subtraction.
                let k = stride.wrapping_mul(h);
                let [c, s] = at(roots, k, none);
                let [c2, s2] = at(roots, add_mod(k, k, len), none);
                part[0] += *q;
                part[1] += *q * c;
                part[2] += *q * s;
                part[3] += *q * c2;
                part[4] += *q * s2;
                h += 1;
            }
            for (sum, p) in sums.iter_mut().zip(part) {
                sum.add(p);
            }
        }
        let [a, c1, s1, c2, s2] = sums.map(|x| x.total());
        let mut f = Fourier { a, c1, s1, c2, s2 };
        if n == 0 {
            return f; // an empty net: all sums zero
        }
        let inv = R::ONE / R::from_usize(n);
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
