//! The ring of bi-4 patches one step emits (spec EG.md §9).
//!
//! Step m → m+1 emits, per sector, 3 bi-4 patches over the L-shape between the
//! old and the new hole: patch `3s + 0` over `[½,1]×[0,½]`, `3s + 1` over
//! `[0,½]×[½,1]`, `3s + 2` over `[½,1]²`, in sector `s`'s level-m frame
//! (level-0 c-units × 2⁻ᵐ; `x` along spoke `s`, `y` along spoke `s+1`). Patch
//! `u` runs along `x`, `v` along `y`, so `∂u × ∂v` points to the same side in
//! every sector. Each patch's 5×5 node block (index tables in `layout`) takes the
//! new d-net's nodes and, at positions 1 and 5/4 (×2⁻ᵐ), the regular
//! refinement (§5) of the old d-net; (5) tensored turns it into the BB-net.

use super::layout::{Fine, REGULAR, RING};
use super::net::{sector_at, DNet};
use super::refine::gather;
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

fn fine_node<R: Real>(
    old: &DNet<R>,
    new: &DNet<R>,
    s: usize,
    f: &Fine,
) -> Result<Point3<R>, Error> {
    if f.new_node != 255 {
        let sec = sector_at(&new.sectors, s, f.ds)?;
        sec.get(usize::from(f.new_node))
            .copied()
            .ok_or(Error::OutOfDomain)
    } else {
        let terms = REGULAR
            .get(usize::from(f.reg.0))
            .and_then(|r| r.get(usize::from(f.reg.1)))
            .ok_or(Error::OutOfDomain)?;
        gather(old, s, f.ds, terms, None)
    }
}

/// Patch `k` (`k < 3n`) of the ring between `old` and `new = step(old)`.
pub(crate) fn ring_patch<R: Real>(
    old: &DNet<R>,
    new: &DNet<R>,
    k: usize,
) -> Result<BiquarticPatch<R>, Error> {
    let n = old.valence();
    if k >= n.saturating_mul(PATCHES_PER_SECTOR) || new.valence() != n {
        return Err(Error::OutOfDomain);
    }
    let (s, p) = (k / PATCHES_PER_SECTOR, k % PATCHES_PER_SECTOR);
    let block = RING.get(p).ok_or(Error::OutOfDomain)?;
    let mut d = [[Point3::ZERO; 5]; 5];
    for (row, src) in d.iter_mut().zip(block.iter()) {
        for (pt, f) in row.iter_mut().zip(src.iter()) {
            *pt = fine_node(old, new, s, f)?;
        }
    }
    Ok(BiquarticPatch { points: bb_net(&d) })
}

/// (5) applied to one row of 5 nodes.
fn convert<R: Real>(v: &[Point3<R>; 5]) -> [Point3<R>; 5] {
    B_FROM_D.map(|m| {
        m.iter()
            .zip(v.iter())
            .fold(Point3::ZERO, |acc, (w, p)| acc + *p * R::ratio(*w, 4))
    })
}

fn transpose<R: Real>(m: &[[Point3<R>; 5]; 5]) -> [[Point3<R>; 5]; 5] {
    let mut out = [[Point3::ZERO; 5]; 5];
    for (i, row) in m.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            if let Some(o) = out.get_mut(j).and_then(|r| r.get_mut(i)) {
                *o = *v;
            }
        }
    }
    out
}

/// `b = M d Mᵀ` with `M` = (5), on differences from the mid-mid node `d[2][2]`
/// (exact for translations, smaller rounding far from the origin).
fn bb_net<R: Real>(d: &[[Point3<R>; 5]; 5]) -> [[Point3<R>; 5]; 5] {
    let o = d[2][2];
    let rel = d.map(|row| row.map(|p| p - o));
    let along_v = rel.map(|row| convert(&row));
    let both = transpose(&transpose(&along_v).map(|col| convert(&col)));
    both.map(|row| row.map(|p| o + p))
}
