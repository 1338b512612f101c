//! One EG step `d → d̃` (spec EG.md §5, §6): the 6 outer new nodes of every
//! sector by the regular bi-4 rules, the 6 inner ones by the EG rule (7),
//! `c0` unchanged. Written out of place (`old` → `out`, both fixed-size nets).

use super::layout::{Term, CENTER, CENTER_RING, REGULAR};
use super::net::{sector_at, DNet, DSector};
use super::rule::{InnerNode, RuleTable, WEIGHT_SCALE};
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
pub(crate) fn refine<R: Real>(
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
    match rule {
        Rule::Regular => {
            let center = Some(center_node(old)?);
            for (s, sec) in out.sectors.iter_mut().enumerate() {
                for (k, p) in sec.iter_mut().enumerate() {
                    *p = gather(old, s, 0, regular_stencil(k % 4, k / 4)?, center)?;
                }
            }
        }
        Rule::Eg(table) => {
            if table.valence() != n {
                return Err(Error::TableShape);
            }
            for (s, sec) in out.sectors.iter_mut().enumerate() {
                for (i, j, k) in OUTER {
                    if let Some(p) = sec.get_mut(k) {
                        *p = gather(old, s, 0, regular_stencil(i, j)?, None)?;
                    }
                }
            }
            eg_inner(old, table, out)?;
        }
    }
    Ok(())
}

/// Rule (7): `d̃_hk^s = c0 + Σ_r Σ_ij a_ij^{r,hk} (d_ij^{s+r} − c0)`, which is the
/// spec's `a0 c0 + Σ a d` with `a0 = 1 − Σ a`. Each expanded row is built once
/// and applied to all sectors.
fn eg_inner<R: Real>(old: &DNet<R>, table: &RuleTable<'_>, out: &mut DNet<R>) -> Result<(), Error> {
    let n = old.valence();
    let c0 = old.c0;
    for node in InnerNode::ALL {
        let k = node.index();
        // Sums of (d − c0) start at zero; c0 is added at the end.
        for sec in out.sectors.iter_mut() {
            if let Some(p) = sec.get_mut(k) {
                *p = Point3::ZERO;
            }
        }
        for r in 0..n {
            let row = table.row(node, r).ok_or(Error::TableShape)?;
            let w = row.map(|a| R::ratio(a, WEIGHT_SCALE));
            let dr = i8::try_from(r).map_err(|_| Error::OutOfDomain)?;
            for (s, sec) in out.sectors.iter_mut().enumerate() {
                let src: &DSector<R> = sector_at(&old.sectors, s, dr)?;
                let mut acc = Point3::ZERO;
                for (d, wk) in src.iter().zip(w.iter()) {
                    acc += (*d - c0) * *wk;
                }
                if let Some(p) = sec.get_mut(k) {
                    *p += acc;
                }
            }
        }
        for sec in out.sectors.iter_mut() {
            if let Some(p) = sec.get_mut(k) {
                *p = c0 + *p;
            }
        }
    }
    Ok(())
}
