//! One level of the streaming sweep ([`super::stream`]): a window of the last
//! [`WINDOW`] columns of level `m` and the level's closed-form data (spec
//! docs/math/c2ps.md §2, §4).
//!
//! A *column* `k` of level `m` is the five points `q[1..=5][k]` plus the root
//! `(c, s)(k/N)` its rules need (the doubled angle's follows from it). Columns are produced in
//! order of a *virtual* index `k = −2, −1, 0, …, N+1` (`k` taken mod `N` for
//! the data), so the periodic wrap-around needs no stored first or last
//! columns: the few columns at both ends are simply computed twice.
//!
//! New column `k' ∈ {2j, 2j+1}` of level `m+1` needs old columns `j−1, j, j+1`
//! (the periodic refinement of §2) and the pole and 1-link Fourier sums of
//! level `m`. For `m ≥ 1` the sums are not summed: links 0 and 1 of every
//! level are closed forms of the level-0 eigencoefficients (§4, eq. (30)), so
//! level `m`'s sums follow from level `m−1`'s: `A ← (q00 + A)/2`,
//! `C1, S1 ← ½·(C1, S1)`, `C2, S2 ← ¼·(C2, S2)`, `q00 ← ¾ q00 + ¼ A`
//! (Lemma 5 scaling, exact for the valences `N ≥ 6` of levels ≥ 1).

use super::column::{column, refine_even, refine_odd};
use crate::point::Point3;
use crate::real::Real;

/// Columns kept per level: a ring patch needs 4 consecutive columns (§5), a
/// refinement 3.
pub(crate) const WINDOW: usize = 4;

/// Columns produced per level beyond its valence: virtual `−2, −1` and
/// `N, N+1`.
pub(crate) const EXTRA: usize = 4;

/// One column of a level.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Column<R> {
    /// `q[1..=5][k]` (zero for links the level does not hold).
    pub q: [Point3<R>; 5],
    /// `(c, s)(k/N)`.
    pub r: [R; 2],
}

impl<R: Real> Column<R> {
    pub(crate) const ZERO: Self = Column {
        q: [Point3([R::ZERO; 3]); 5],
        r: [R::ZERO; 2],
    };
}

/// The pole and the Fourier sums `A, C1, S1, C2, S2` of a level's 1-link
/// (docs/math/c2ps.md §2): what the next level is computed from.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sums<R> {
    pub pole: Point3<R>,
    pub a: Point3<R>,
    pub c1: Point3<R>,
    pub s1: Point3<R>,
    pub c2: Point3<R>,
    pub s2: Point3<R>,
}

impl<R: Real> Sums<R> {
    pub(crate) const ZERO: Self = Sums {
        pole: Point3([R::ZERO; 3]),
        a: Point3([R::ZERO; 3]),
        c1: Point3([R::ZERO; 3]),
        s1: Point3([R::ZERO; 3]),
        c2: Point3([R::ZERO; 3]),
        s2: Point3([R::ZERO; 3]),
    };

    /// The next level's pole and sums (docs/math/c2ps.md §2 rule (1) for the pole; §4 eq.
    /// (30) / Lemma 5 for the 1-link's sums).
    pub(crate) fn next(&self) -> Self {
        Sums {
            pole: self.pole * R::ratio(3, 4) + self.a * R::ratio(1, 4),
            a: (self.pole + self.a) * R::ratio(1, 2),
            c1: self.c1 * R::ratio(1, 2),
            s1: self.s1 * R::ratio(1, 2),
            c2: self.c2 * R::ratio(1, 4),
            s2: self.s2 * R::ratio(1, 4),
        }
    }

    /// First harmonic `C1 c + S1 s` at the angle `(c, s)`.
    #[inline]
    pub(crate) fn h1(&self, [c, s]: [R; 2]) -> Point3<R> {
        self.c1 * c + self.s1 * s
    }

    /// Second harmonic `C2 c2 + S2 s2` at the doubled angle `(c2, s2)`.
    #[inline]
    pub(crate) fn h2(&self, [c, s]: [R; 2]) -> Point3<R> {
        self.c2 * c + self.s2 * s
    }
}

/// The state of one level during a sweep.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Level<R> {
    /// The last columns produced: column number `i` (0-based, in production
    /// order, virtual index `i − 2`) in slot `i mod WINDOW`.
    pub win: [Column<R>; WINDOW],
    /// Columns produced so far.
    pub count: usize,
    /// The level's valence `N = n·2^m`.
    pub n: usize,
    /// Links at this level (§2: `2K−1` after a step, at most 5).
    pub link_count: usize,
    /// This level's pole and 1-link sums.
    pub sums: Sums<R>,
    /// `(c, s)(1/N)`: turns the root of column `k` of the level below into
    /// this level's column `2k+1` (unused at level 0).
    pub w: [R; 2],
}

impl<R: Real> Level<R> {
    pub(crate) const EMPTY: Self = Level {
        win: [Column::ZERO; WINDOW],
        count: 0,
        n: 0,
        link_count: 0,
        sums: Sums::ZERO,
        w: [R::ZERO; 2],
    };

    /// Column number `i` (must be one of the last [`WINDOW`] produced).
    #[inline]
    pub(crate) fn col(&self, i: usize) -> &Column<R> {
        // i % 4 < 4: no bounds check.
        &self.win[i % WINDOW]
    }

    /// `true` once all `N + EXTRA` columns are produced.
    #[inline]
    pub(crate) fn finished(&self) -> bool {
        self.count >= self.n.saturating_add(EXTRA)
    }
}

/// `(c, s)` rotated by the angle whose `(c, s)` is `w` (one complex product,
/// as the in-place root doubling computes it).
#[inline]
pub(crate) fn rotate<R: Real>([c, s]: [R; 2], [hc, hs]: [R; 2]) -> [R; 2] {
    [c * hc - s * hs, s * hc + c * hs]
}

/// `w^k` in `f64` by repeated squaring (`O(log k)` products).
pub(crate) fn power(w: (f64, f64), mut k: usize) -> (f64, f64) {
    let (mut rc, mut rs) = (1.0f64, 0.0f64);
    let (mut bc, mut bs) = w;
    while k > 0 {
        if k & 1 == 1 {
            let c = rc * bc - rs * bs;
            rs = rs * bc + rc * bs;
            rc = c;
        }
        let c = bc * bc - bs * bs;
        bs *= 2.0 * bc;
        bc = c;
        k >>= 1;
    }
    (rc, rs)
}

/// Computes column number `i` of level `hi` from the level below, `lo`
/// (which must have produced columns `⌊i/2⌋ … ⌊i/2⌋+2`), by the rules of
/// docs/math/c2ps.md §2 with the sums of `lo`. `uniform_first`: this is level 1 and the first step
/// uses the §2 first-step variant.
pub(crate) fn next_column<R: Real>(
    lo: &Level<R>,
    hi: &Level<R>,
    i: usize,
    uniform_first: bool,
) -> Column<R> {
    let base = i / 2;
    let (prev, cur, next) = (lo.col(base), lo.col(base + 1), lo.col(base + 2));
    let even = i.is_multiple_of(2);
    // Periodic refinement of old links 1..3 (§2), `ũ[2j]` or `ũ[2j+1]`.
    let t: [Point3<R>; 3] = core::array::from_fn(|k| {
        if even {
            refine_even(prev.q[k], cur.q[k], next.q[k])
        } else {
            refine_odd(cur.q[k], next.q[k])
        }
    });
    let r = if even { cur.r } else { rotate(cur.r, hi.w) };
    let f = &lo.sums;
    let h = [f.h1(r), f.h2(double(r))];
    let outer = lo.link_count >= 3 && hi.link_count >= 5;
    let q = column(t, f.pole, f.a, h, uniform_first, outer);
    Column { q, r }
}

/// `(c, s)` of the doubled angle: `(c² − s², 2cs)`.
#[inline]
pub(crate) fn double<R: Real>([c, s]: [R; 2]) -> [R; 2] {
    [c * c - s * s, (c + c) * s]
}
