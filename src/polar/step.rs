//! One C²PS step, level m → m+1, valence n → 2n (docs/math/c2ps.md §2), in place.
//!
//! O(n): the Fourier sums of the old 1-link are taken once, then every new
//! point is a fixed combination of them and of the periodic refinements of old
//! links 1..3. The new links are written over the old ones in one backward sweep
//! `j = n−1 … 0` that reads old entries `j−1, j, j+1` and writes new entries
//! `2j, 2j+1`: an entry is never overwritten before its last read (only the
//! wrap-around entry `n−1`, read again at `j = 0`, is saved beforehand). No
//! second copy of the net; stack use is a fixed number of points.

use super::column::{column, refine_even, refine_odd};
use super::fourier::Fourier;
use super::index::{add_mod, at, next_mod, put};
use super::net::{capacity, link_count_after_step, link_of, split_links, FirstStep, Head};
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;
use crate::trig::roots::double_ring;

/// One C²PS step of a net (`PolarNetInner::step`), over its storage's
/// slices: compiled once per scalar type, whatever the storage.
pub(crate) fn c2ps_step<R: Real>(
    head: &mut Head<R>,
    (links, roots): (&mut [Point3<R>], &mut [[R; 2]]),
    first: FirstStep,
) -> Result<(), Error> {
    let n = head.valence;
    let cap = capacity(links.len(), roots.len());
    // 2n <= cap <= root storage: the roots double in place.
    check_step(head.link_count, n, cap)?;
    step_fits(
        head.pole,
        [1, 2, 3].map(|i| link_of(links, cap, head, i).unwrap_or(&[])),
        n,
    )?;
    let roots = roots.get_mut(..2 * n).unwrap_or_default();
    double_ring(roots, n);
    let new_link_count = link_count_after_step(head.link_count);
    c2ps_in_place(
        &mut head.pole,
        split_links(links, cap, 2 * n, new_link_count),
        n,
        head.link_count,
        new_link_count,
        roots,
        head.level == 0 && first == FirstStep::Uniform,
    );
    head.valence = 2 * n;
    head.link_count = new_link_count;
    head.level += 1;
    Ok(())
}

/// The errors of a C²PS step from valence `n` with `link_count` links in room for
/// `cap` points per link, in the order checked: [`Error::NotEnoughLinks`],
/// [`Error::CapacityExceeded`].
pub(crate) fn check_step(link_count: usize, n: usize, cap: usize) -> Result<(), Error> {
    if link_count < 2 {
        return Err(Error::NotEnoughLinks {
            needed: 2,
            present: link_count,
        });
    }
    if 2 * n > cap {
        return Err(Error::CapacityExceeded {
            needed: 2 * n,
            capacity: cap,
        });
    }
    Ok(())
}

/// [`Error::NonFinite`] unless a C²PS or RTS step from valence `n` is sure
/// not to overflow: every coordinate of the pole and of links 1..3 (the only
/// inputs a step reads) at most `MAX/(16·n)` in magnitude. With `m` that
/// bound, the Fourier sums of the 1-link stay below `2·n·m` before their
/// division by `n` (plain sums of up to 32 terms, compensated across blocks),
/// and every other intermediate (`prev + 6·cur + next`, `q00 + 6·t1 + t2`, the
/// harmonics) below `8·m`; new points are below `4·m`. Checked before
/// anything is written.
pub(crate) fn step_fits<R: Real>(
    pole: Point3<R>,
    links: [&[Point3<R>]; 3],
    n: usize,
) -> Result<(), Error> {
    // Plain loops: the iterator chain (`flat_map` + `chain([&pole])`) cost a
    // 1.5 KiB `memmove` on Cortex-M for moving the array iterator.
    let mut m = R::ZERO;
    let mut widen = |p: &Point3<R>| {
        for c in p.0 {
            let a = c.abs();
            if a > m {
                m = a;
            }
        }
    };
    widen(&pole);
    for l in links {
        for p in l.get(..n).unwrap_or(l) {
            widen(p);
        }
    }
    // 16·n rounds as in f64: scaling by 16 is exact.
    if (m * (R::from_usize(n) * R::from_f64(16.0))).is_finite() {
        Ok(())
    } else {
        Err(Error::NonFinite)
    }
}

/// Uniform cubic periodic refinement of `u` at old index `j`: `(ũ[2j], ũ[2j+1])`.
#[inline]
fn refine<R: Real>(prev: Point3<R>, cur: Point3<R>, next: Point3<R>) -> (Point3<R>, Point3<R>) {
    (refine_even(prev, cur, next), refine_odd(cur, next))
}

/// The step over plain slices. `n` is the old valence: on entry
/// `links[k][..n]` holds link `k+1` for `k < link_count`, and every link that will be
/// written (`k < new_link_count`) has room for `2n` points (more is left alone);
/// `roots` are already the `2n`-th roots.
pub(crate) fn c2ps_in_place<R: Real>(
    pole: &mut Point3<R>,
    links: [&mut [Point3<R>]; 5],
    n: usize,
    link_count: usize,
    new_link_count: usize,
    roots: &[[R; 2]],
    uniform_first: bool,
) {
    let [l1, l2, l3, l4, l5] = links;
    let n2 = 2 * n;
    let f = Fourier::of(l1.get(..n).unwrap_or(&[]), roots, 2);
    let q00 = *pole;
    let has3 = link_count >= 3;

    // Every link that will be written has room for 2n (checked by the caller;
    // a short one would only make the sweep below do nothing).
    if l1.len() < n2 || l2.len() < n2 || l3.len() < n2 {
        return;
    }
    let z = Point3::ZERO;
    let jl = n.wrapping_sub(1);
    let last = [
        at(l1, jl, z),
        at(l2, jl, z),
        if has3 { at(l3, jl, z) } else { z },
    ];
    let write45 = has3 && new_link_count >= 5 && l4.len() >= n2 && l5.len() >= n2;
    let no_root = [R::ZERO; 2];

    for j in (0..n).rev() {
        let (jm, jp) = (if j == 0 { jl } else { j - 1 }, next_mod(j, n));
        let get = |l: &[Point3<R>], k: usize, i: usize| {
            if j == 0 && i == jm {
                at(&last, k, z)
            } else {
                at(l, i, z)
            }
        };
        let r1 = refine(get(l1, 0, jm), at(l1, j, z), at(l1, jp, z));
        let r2 = refine(get(l2, 1, jm), at(l2, j, z), at(l2, jp, z));
        let r3 = if has3 {
            refine(get(l3, 2, jm), at(l3, j, z), at(l3, jp, z))
        } else {
            (z, z)
        };
        for (jj, t1, t2, t3) in [(2 * j, r1.0, r2.0, r3.0), (2 * j + 1, r1.1, r2.1, r3.1)] {
            let h1 = f.h1(at(roots, jj, no_root));
            // (2·jj) mod 2n, for jj < 2n.
            let h2 = f.h2(at(roots, add_mod(jj, jj, n2), no_root));
            let [q1, q2, q3, q4, q5] =
                column([t1, t2, t3], q00, f.a, [h1, h2], uniform_first, write45);
            if write45 {
                put(l5, jj, q5);
                put(l4, jj, q4);
            }
            put(l3, jj, q3);
            put(l2, jj, q2);
            put(l1, jj, q1);
        }
    }
    *pole = q00 * R::ratio(3, 4) + f.a * R::ratio(1, 4);
}
