//! The ring of bi-4 patches one step emits (docs/math/eg.md §9).
//!
//! Step m → m+1 emits, per sector, 3 bi-4 patches over the L-shape between the
//! old and the new hole: patch `3s + 0` over `[½,1]×[0,½]`, `3s + 1` over
//! `[0,½]×[½,1]`, `3s + 2` over `[½,1]²`, in sector `s`'s level-m frame
//! (level-0 c-units × 2⁻ᵐ; `x` along spoke `s`, `y` along spoke `s+1`). Patch
//! `u` runs along `x`, `v` along `y`, so `∂u × ∂v` points to the same side in
//! every sector. Each patch's 5×5 node block (index tables in `layout`) takes the
//! new d-net's nodes and, at positions 1 and 5/4 (×2⁻ᵐ), the regular
//! refinement (§5) of the old d-net; (5) tensored turns it into the BB-net.
//!
//! Cost: the regular nodes dominate (9 stencil terms each). A patch looks up
//! the sectors it reads once (not per term), and the ring iterator computes
//! the 18 regular nodes a sector's 3 patches share in that sector's frame
//! once per sector (`OwnNodes`) instead of 30 times; 6 more per sector lie in
//! a neighbour's frame and are computed where needed. Every patch is bit for
//! bit what the per-node construction gives (`tests/eg_ring_exact.rs`).

use super::layout::{Fine, OWN, OWN_REG, REGULAR, RING};
use super::net::{sector_at, DNet, DSector};
use crate::bezier::BiquarticPatch;
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;

/// Patches per sector and ring.
pub const PATCHES_PER_SECTOR: usize = 3;

/// (5) as a matrix, ×4: BB-coefficients `b0..b4` of a segment from its nodes
/// `d_{2s−2} … d_{2s+2}`.
const B_FROM_D: [[i32; 5]; 5] = [
    [1, 2, 1, 0, 0],
    [0, 2, 2, 0, 0],
    [0, 0, 4, 0, 0],
    [0, 0, 2, 2, 0],
    [0, 0, 1, 2, 1],
];

/// Sector offsets a patch reads: new-net nodes at `−1..=1`, the old net's
/// regular stencils at `−2..=2` (checked at compile time in `layout`).
const NEW_REACH: i8 = 1;
const OLD_REACH: i8 = 2;

/// The sectors `s − R ..= s + R` of a net, looked up once per patch (the
/// modular sector index is the costly part of a stencil term).
fn window<R: Real, const W: usize>(
    sectors: &[DSector<R>],
    s: usize,
    reach: i8,
) -> Result<[&DSector<R>; W], Error> {
    let first = sector_at(sectors, s, reach.wrapping_neg())?;
    let mut out = [first; W];
    let mut ds = reach.wrapping_neg();
    for slot in out.iter_mut() {
        *slot = sector_at(sectors, s, ds)?;
        ds = ds.wrapping_add(1);
    }
    Ok(out)
}

/// Node `(a, b)` of a patch's block: a new-net node, or the regular
/// refinement (§5) of the old net, `c0 + Σ w/256 (d − c0)` over the stencil
/// in its order (the same sum as the step's `gather`, bit for bit).
#[inline]
fn fine_node<R: Real>(
    old: &[&DSector<R>; 5],
    new: &[&DSector<R>; 3],
    c0: Point3<R>,
    f: &Fine,
) -> Option<Point3<R>> {
    if f.new_node != 255 {
        let sec = new.get(usize::try_from(f.ds.wrapping_add(NEW_REACH)).ok()?)?;
        return sec.get(usize::from(f.new_node)).copied();
    }
    let terms = REGULAR
        .get(usize::from(f.reg.0))?
        .get(usize::from(f.reg.1))?;
    let mut acc = Point3::ZERO;
    for t in terms.iter().filter(|t| t.w != 0) {
        let k = f.ds.wrapping_add(t.ds).wrapping_add(OLD_REACH);
        let p = old
            .get(usize::try_from(k).ok()?)?
            .get(usize::from(t.node))?;
        acc += (*p - c0) * R::ratio(i32::from(t.w), 256);
    }
    Some(c0 + acc)
}

/// The regular nodes of one sector's 3 ring patches in that sector's own
/// frame ([`OWN_REG`]): the ring iterator computes them once per sector
/// instead of once per patch (18 stencils instead of 30).
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct OwnNodes<R> {
    /// The sector they belong to (`usize::MAX`: none yet).
    sector: usize,
    nodes: [Point3<R>; OWN],
}

impl<R: Real> OwnNodes<R> {
    /// Nothing cached.
    pub(crate) const fn empty() -> Self {
        OwnNodes {
            sector: usize::MAX,
            nodes: [Point3([R::ZERO; 3]); OWN],
        }
    }
}

/// Patch `k` (`k < 3n`) of the ring between `old` and `new = step(old)`.
/// With `own`, the own-frame regular nodes come from (and, for a new
/// sector, go to) that cache; the patch is the same bit for bit.
pub(crate) fn ring_patch<R: Real>(
    old: &DNet<R>,
    new: &DNet<R>,
    k: usize,
    own: Option<&mut OwnNodes<R>>,
) -> Result<BiquarticPatch<R>, Error> {
    let n = old.valence();
    if k >= n.saturating_mul(PATCHES_PER_SECTOR) || new.valence() != n {
        return Err(Error::OutOfDomain);
    }
    let (s, p) = (k / PATCHES_PER_SECTOR, k % PATCHES_PER_SECTOR);
    let block = RING.get(p).ok_or(Error::OutOfDomain)?;
    let old_w = window::<R, 5>(&old.sectors, s, OLD_REACH)?;
    let new_w = window::<R, 3>(&new.sectors, s, NEW_REACH)?;
    let cached = match own {
        Some(c) => {
            if c.sector != s {
                c.sector = usize::MAX;
                for (slot, &(i, j)) in c.nodes.iter_mut().zip(OWN_REG.iter()) {
                    let f = Fine {
                        ds: 0,
                        new_node: 255,
                        reg: (i, j),
                        slot: 255,
                    };
                    *slot = fine_node(&old_w, &new_w, old.c0, &f).ok_or(Error::OutOfDomain)?;
                }
                c.sector = s;
            }
            Some(&c.nodes)
        }
        None => None,
    };
    let mut d = [[Point3::ZERO; 5]; 5];
    for (row, src) in d.iter_mut().zip(block.iter()) {
        for (pt, f) in row.iter_mut().zip(src.iter()) {
            let hit = cached.and_then(|c| c.get(usize::from(f.slot)));
            *pt = match hit {
                Some(q) => *q,
                None => fine_node(&old_w, &new_w, old.c0, f).ok_or(Error::OutOfDomain)?,
            };
        }
    }
    Ok(BiquarticPatch { points: bb_net(&d) })
}

/// `b = M d Mᵀ` with `M` = (5), on differences from the mid-mid node `d[2][2]`
/// (exact for translations, smaller rounding far from the origin): along `v`
/// (within a row of `d`) first, then along `u`, each sum from zero in index
/// order. `M`'s zero entries are skipped: for finite terms `p·0 = ±0` and a
/// sum started at `+0` is never `−0`, so adding them changes nothing (only a
/// patch whose differences overflow could tell: ±∞ where the full product
/// gave NaN).
fn bb_net<R: Real>(d: &[[Point3<R>; 5]; 5]) -> [[Point3<R>; 5]; 5] {
    let w: [[R; 5]; 5] = B_FROM_D.map(|row| row.map(|m| R::ratio(m, 4)));
    let o = d[2][2];
    // Along v: t[a][k] = Σ_b (d[a][b] − o) w[k][b].
    let mut t = [[Point3::ZERO; 5]; 5];
    for (trow, drow) in t.iter_mut().zip(d.iter()) {
        let rel = drow.map(|p| p - o);
        for (tk, (mk, wk)) in trow.iter_mut().zip(B_FROM_D.iter().zip(w.iter())) {
            *tk = combine(mk, wk, |b| rel.get(b).copied());
        }
    }
    // Along u: b[i][k] = o + Σ_a t[a][k] w[i][a].
    let mut b = [[o; 5]; 5];
    for (brow, (mi, wi)) in b.iter_mut().zip(B_FROM_D.iter().zip(w.iter())) {
        for (k, bk) in brow.iter_mut().enumerate() {
            *bk = o + combine(mi, wi, |a| t.get(a).and_then(|r| r.get(k)).copied());
        }
    }
    b
}

/// `Σ_j p(j) w[j]` over the `j` with `m[j] ≠ 0`, from `+0`, in order.
#[inline(always)]
fn combine<R: Real>(m: &[i32; 5], w: &[R; 5], p: impl Fn(usize) -> Option<Point3<R>>) -> Point3<R> {
    let mut acc = Point3::ZERO;
    for (j, (mj, wj)) in m.iter().zip(w.iter()).enumerate() {
        if *mj != 0 {
            if let Some(q) = p(j) {
                acc += q * *wj;
            }
        }
    }
    acc
}
