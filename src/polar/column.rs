//! The C²PS column rule, docs/math/c2ps.md §2 rules (1)–(5): the new links
//! 1..5 at one column from the periodically refined old links 1..3 there,
//! the old pole and 1-link mean and the Fourier terms at the column's
//! angle. Both sweeps call it: the in-place step ([`super::step`], a whole
//! level at once) and the stream ([`super::stream_level`], one column at a
//! time), so the rules are written once.

use crate::point::Point3;
use crate::real::Real;

/// Uniform cubic periodic refinement (§2) of an old link at old index `j`
/// from its points at `j − 1`, `j`, `j + 1`: the new point `2j`.
#[inline]
pub(crate) fn refine_even<R: Real>(prev: Point3<R>, cur: Point3<R>, next: Point3<R>) -> Point3<R> {
    (prev + cur * R::from_f64(6.0) + next) * R::ratio(1, 8)
}

/// The new point `2j + 1` of the same refinement, from the points at `j`
/// and `j + 1`.
#[inline]
pub(crate) fn refine_odd<R: Real>(cur: Point3<R>, next: Point3<R>) -> Point3<R> {
    (cur + next) * R::ratio(1, 2)
}

/// Rules (1)–(5) at one new column. `t`: the refined old links 1..3 there;
/// `q00`, `a`: the old pole and the old 1-link's mean; `h1`, `h2`: the
/// Fourier terms at the column's angle (`h2` at the doubled angle);
/// `uniform_first`: rule (2) of the first step's "Uniform" variant; `outer`:
/// also links 4 and 5 (rules (4), (5)), else they are zero.
#[inline]
pub(crate) fn column<R: Real>(
    [t1, t2, t3]: [Point3<R>; 3],
    q00: Point3<R>,
    a: Point3<R>,
    [h1, h2]: [Point3<R>; 2],
    uniform_first: bool,
    outer: bool,
) -> [Point3<R>; 5] {
    let half = R::ratio(1, 2);
    let six = R::from_f64(6.0);
    let eighth = R::ratio(1, 8);
    let q1 = (q00 + a) * half + h1 + h2 * half;
    let q2 = if uniform_first {
        (q00 + t1 * six + t2) * eighth
    } else {
        t1 * R::ratio(11, 12) + t2 * R::ratio(1, 12) - h1 * R::ratio(1, 6)
    };
    let q3 = (t1 + t2) * half;
    let (q4, q5) = if outer {
        ((t1 + t2 * six + t3) * eighth, (t2 + t3) * half)
    } else {
        (Point3::ZERO, Point3::ZERO)
    };
    [q1, q2, q3, q4, q5]
}
