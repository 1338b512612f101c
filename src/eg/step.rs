//! One EG step `d → d̃` (docs/math/eg.md §5, §6): the 6 outer new nodes of every
//! sector by the regular bi-4 rules, the 6 inner ones by the EG rule (7),
//! `c0` unchanged. Written out of place (`old` → `out`, both fixed-size nets).

use super::layout::{Term, CENTER, CENTER_RING, REGULAR};
use super::net::{sector_at, DNet, DSector};
use super::rule::{InnerNode, RuleTable, WEIGHT_SCALE};
use super::MAX_VALENCE;
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;

/// Which rule computes the inner nodes.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Rule<'r, 't> {
    /// Valence 4: the regular rules everywhere (see [`center_node`]).
    Regular,
    /// The EG rule (7) with this table.
    Eg(&'r RuleTable<'t>),
}

/// The six outer new nodes `(i', j', i' + 4j')` with `i' = 0` or `j' = 0`.
const OUTER: [(usize, usize, usize); 6] = [
    (0, 0, 0),
    (1, 0, 1),
    (2, 0, 2),
    (3, 0, 3),
    (0, 1, 4),
    (0, 2, 8),
];

/// `c0 + Σ w/256 (d − c0)` over a §5 stencil centred on sector `s`.
/// `center` stands in for the lattice node at the center (valence 4 only).
pub(crate) fn gather<R: Real>(
    old: &DNet<R>,
    s: usize,
    ds: i8,
    terms: &[Term; 9],
    center: Option<Point3<R>>,
) -> Result<Point3<R>, Error> {
    let c0 = old.c0;
    let mut acc = Point3::ZERO;
    for t in terms.iter().filter(|t| t.w != 0) {
        let p = if t.node == CENTER {
            center.ok_or(Error::OutOfDomain)?
        } else {
            let sec = sector_at(&old.sectors, s, ds.wrapping_add(t.ds))?;
            *sec.get(usize::from(t.node)).ok_or(Error::OutOfDomain)?
        };
        acc += (p - c0) * R::ratio(i32::from(t.w), 256);
    }
    Ok(c0 + acc)
}

/// Valence 4: the d-lattice node at the center, absent from the d-net, is the
/// one that makes the spline's value at the center `c0`: its corner
/// BB-coefficient `b00 = (4 d00 + Σ w d)/16` (§9 tensored) must equal `c0`,
/// so `d00 = c0 + Σ w (c0 − d)/4` over its 8 neighbors (weights 2 and 1).
/// For a d-net raised from a regular c-net this is exactly the raised node.
pub(crate) fn center_node<R: Real>(old: &DNet<R>) -> Result<Point3<R>, Error> {
    let c0 = old.c0;
    let mut acc = Point3::ZERO;
    for t in CENTER_RING.iter() {
        let sec = sector_at(&old.sectors, 0, t.ds)?;
        let p = *sec.get(usize::from(t.node)).ok_or(Error::OutOfDomain)?;
        acc += (c0 - p) * R::ratio(i32::from(t.w), 4);
    }
    Ok(c0 + acc)
}

/// The §5 stencil of new node `(i', j')`.
fn regular_stencil(i: usize, j: usize) -> Result<&'static [Term; 9], Error> {
    REGULAR
        .get(i.wrapping_add(2))
        .and_then(|row| row.get(j.wrapping_add(2)))
        .ok_or(Error::OutOfDomain)
}

/// One step from `old` into `out` (resized to `old`'s valence, `c0` copied).
pub(crate) fn step_into<R: Real>(
    old: &DNet<R>,
    rule: Rule<'_, '_>,
    out: &mut DNet<R>,
) -> Result<(), Error> {
    let n = old.valence();
    out.c0 = old.c0;
    out.sectors.clear();
    for _ in 0..n {
        out.sectors
            .push([old.c0; 12])
            .map_err(|_| Error::ValenceUnsupported { valence: n })?;
    }
    new_nodes(old, rule, &mut |s, k, p| {
        if let Some(q) = out.sectors.get_mut(s).and_then(|sec| sec.get_mut(k)) {
            *q = p;
        }
        true
    })?;
    Ok(())
}

/// `true` when [`step_into`] of `old` would give a finite net: the same
/// computation (so bit-identical values), each new node checked and dropped.
pub(crate) fn step_is_finite<R: Real>(old: &DNet<R>, rule: Rule<'_, '_>) -> Result<bool, Error> {
    new_nodes(old, rule, &mut |_, _, p| p.is_finite())
}

/// Computes every node of the step from `old` and hands it to
/// `emit(sector, node index, value)`; stops early (returning `false`) when
/// `emit` does. One routine for [`step_into`] and [`step_is_finite`], so the
/// step's pre-check sees exactly the values the step stores.
fn new_nodes<R: Real>(
    old: &DNet<R>,
    rule: Rule<'_, '_>,
    emit: &mut dyn FnMut(usize, usize, Point3<R>) -> bool,
) -> Result<bool, Error> {
    let n = old.valence();
    match rule {
        Rule::Regular => {
            let center = Some(center_node(old)?);
            for s in 0..n {
                for k in 0..12 {
                    if !emit(
                        s,
                        k,
                        gather(old, s, 0, regular_stencil(k % 4, k / 4)?, center)?,
                    ) {
                        return Ok(false);
                    }
                }
            }
            Ok(true)
        }
        Rule::Eg(table) => {
            if table.valence() != n {
                return Err(Error::TableShape);
            }
            for s in 0..n {
                for (i, j, k) in OUTER {
                    if !emit(s, k, gather(old, s, 0, regular_stencil(i, j)?, None)?) {
                        return Ok(false);
                    }
                }
            }
            eg_inner(old, table, emit)
        }
    }
}

/// `Σ_ij w_ij (d_ij − c0)` over one sector, in node order (rule (7), one row).
#[inline]
fn row_dot<R: Real>(src: &DSector<R>, c0: Point3<R>, w: &[R; 12]) -> Point3<R> {
    let mut acc = Point3::ZERO;
    for (d, wk) in src.iter().zip(w.iter()) {
        acc += (*d - c0) * *wk;
    }
    acc
}

/// Rule (7): `d̃_hk^s = c0 + Σ_r Σ_ij a_ij^{r,hk} (d_ij^{s+r} − c0)`, which is the
/// spec's `a0 c0 + Σ a d` with `a0 = 1 − Σ a`. Each expanded row is built once
/// and applied to all sectors (sums per sector in `acc`).
fn eg_inner<R: Real>(
    old: &DNet<R>,
    table: &RuleTable<'_>,
    emit: &mut dyn FnMut(usize, usize, Point3<R>) -> bool,
) -> Result<bool, Error> {
    let n = old.valence();
    let c0 = old.c0;
    for node in InnerNode::ALL {
        // Sums of (d − c0) start at zero; c0 is added at the end.
        let mut acc = [Point3::ZERO; MAX_VALENCE];
        for r in 0..n {
            let row = table.row(node, r).ok_or(Error::TableShape)?;
            let w = row.map(|a| R::ratio(a, WEIGHT_SCALE));
            let dr = i8::try_from(r).map_err(|_| Error::OutOfDomain)?;
            for (s, p) in acc.iter_mut().enumerate().take(n) {
                *p += row_dot(sector_at(&old.sectors, s, dr)?, c0, &w);
            }
        }
        for (s, p) in acc.iter().enumerate().take(n) {
            if !emit(s, node.index(), c0 + *p) {
                return Ok(false);
            }
        }
    }
    Ok(true)
}

/// `true` when every coordinate of `net` (nodes and `c0`) is at most
/// `MAX/1024` in magnitude (`MAX` the type's largest finite value). Then no
/// step can overflow: with `m` that bound, `|d − c0| ≤ 2m`; the weights of a
/// new node sum in absolute value to 1 (§5, positive) or below `12n ≤ 120`
/// (rule (7): every table entry is below 10⁵ in magnitude, checked by
/// [`RuleTable::new`]); the n = 4 center node is within `6m` of `c0`; so every
/// partial sum and every new node stays below `~250 m < MAX`. The Fourier
/// step ([`super::fourier`]) stays within the same bound (its sums have at
/// most `2n` terms of weight below 2 per product, `12n` per row).
///
/// Lane-wise maxima in two independent chains (one per half of each
/// sector's nodes), not one serial chain: on a wide core the serial chain
/// was a quarter of the Fourier step's wall time.
pub(crate) fn cannot_overflow<R: Real>(net: &DNet<R>) -> bool {
    let mut even = net.c0.0.map(|c| c.abs());
    let mut odd = even;
    for sec in &net.sectors {
        for pair in sec.chunks_exact(2) {
            if let [a, b] = pair {
                for ((e, o), (x, y)) in even.iter_mut().zip(&mut odd).zip(a.0.iter().zip(&b.0)) {
                    let (x, y) = (x.abs(), y.abs());
                    if x > *e {
                        *e = x;
                    }
                    if y > *o {
                        *o = y;
                    }
                }
            }
        }
    }
    let scale = R::from_f64(1024.0);
    // Scaling by a power of two is exact unless it overflows.
    even.iter().chain(&odd).all(|m| (*m * scale).is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A d-net of valence `n` with pseudo-random nodes of magnitude up to
    /// `amp`, each coordinate of sign chosen at random, and `c0`.
    fn net(n: usize, amp: f64, c0: f64, seed: &mut u64) -> DNet<f64> {
        let mut next = || {
            *seed ^= *seed << 13;
            *seed ^= *seed >> 7;
            *seed ^= *seed << 17;
            (*seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut sectors = heapless::Vec::new();
        for _ in 0..n {
            let sec = core::array::from_fn(|_| Point3([next() * amp, next() * amp, next() * amp]));
            let _ = sectors.push(sec);
        }
        DNet {
            c0: Point3([c0, -c0, 0.0]),
            sectors,
        }
    }

    /// The step's check-first path is exact: `step_is_finite` says `true`
    /// exactly when `step_into` gives a finite net, and a net within `MAX/1024`
    /// never overflows (the bound of `cannot_overflow`).
    #[test]
    fn finiteness_checks_agree_with_the_step() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        // Under Miri (float-heavy, ~10⁴× slower) one net of each amplitude.
        const NETS: usize = if cfg!(miri) { 6 } else { 600 };
        let (mut finite, mut infinite) = (0, 0);
        for k in 0..NETS {
            let n = 3 + k % 3;
            let amp = f64::MAX * [1e-4, 1e-3, 0.05, 0.2, 0.5, 0.9][k % 6];
            let c0 = amp * [0.0, -0.5, 0.9][k % 3];
            let old = net(n, amp, c0, &mut seed);
            let table = RuleTable::builtin(n);
            let rule = match &table {
                Some(t) => Rule::Eg(t),
                None => Rule::Regular,
            };
            let mut out = old.clone();
            step_into(&old, rule, &mut out).unwrap();
            assert_eq!(step_is_finite(&old, rule), Ok(out.is_finite()));
            if cannot_overflow(&old) {
                assert!(out.is_finite());
            }
            if out.is_finite() {
                finite += 1;
            } else {
                infinite += 1;
            }
        }
        assert!(
            finite > NETS / 12 && infinite > NETS / 12,
            "{finite} {infinite}"
        );
    }
}
