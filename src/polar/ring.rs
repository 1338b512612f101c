//! The surface ring of the current level as bicubic Bézier patches (spec
//! docs/math/c2ps.md §5).
//!
//! The level-m ring is the uniform bicubic B-spline with control rows = links
//! 1..5 and `N` periodic columns, over `r ∈ [2, 4]` (level-m link units): two
//! radial spans × `N` columns = `2N` patches. Patch `k = span·N + column` has
//! the B-spline control points `q[span+1+a][column−1+b]`, `a, b = 0..3`, and
//! covers `r ∈ [2+span, 3+span]`, `τ ∈ [column/N, (column+1)/N]`; its `u` runs
//! outward, its `v` counter-clockwise.

use super::index::at;
use crate::bezier::{bspline_to_bezier_cubic, BicubicPatch};
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;
use core::iter::FusedIterator;

/// The current ring of a net over plain slices: links 1..5 and the valence.
/// The patch construction exists once per scalar type, whatever the storage.
#[derive(Clone, Copy, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Ring<'a, R> {
    /// Links 1..5, each at least `n` points long.
    links: [&'a [Point3<R>]; 5],
    n: usize,
}

impl<'a, R: Real> Ring<'a, R> {
    /// The ring of a net holding `link_count` links of valence `n`;
    /// [`Error::NotEnoughLinks`] below 5 links.
    pub(crate) fn new(
        links: [&'a [Point3<R>]; 5],
        link_count: usize,
        n: usize,
    ) -> Result<Self, Error> {
        if link_count < 5 {
            return Err(Error::NotEnoughLinks {
                needed: 5,
                present: link_count,
            });
        }
        Ok(Ring { links, n })
    }

    /// Patches in the ring, `2N`.
    pub(crate) fn len(&self) -> usize {
        self.n.saturating_mul(2)
    }

    /// Patch `k = span·N + column`; [`Error::OutOfDomain`] for `k ≥ 2N`.
    pub(crate) fn patch(&self, k: usize) -> Result<BicubicPatch<R>, Error> {
        let n = self.n;
        if k >= self.len() {
            return Err(Error::OutOfDomain);
        }
        // n >= 3 here (k < 2n); `max(1)` only spares a divide-by-zero path.
        let (span, column) = (k / n.max(1), k % n.max(1));
        let mut d = [[Point3::ZERO; 4]; 4];
        for (a, row) in d.iter_mut().enumerate() {
            // span + a <= 4 and every link has n points: in range.
            let link: &[Point3<R>] = self.links.get(span + a).map_or(&[], |l| l);
            for (b, p) in row.iter_mut().enumerate() {
                let idx = (column + n + b - 1).checked_rem(n).unwrap_or(0);
                *p = at(link, idx, Point3::ZERO);
            }
        }
        Ok(BicubicPatch {
            points: bspline_to_bezier_cubic(&d),
        })
    }

    /// An iterator over all `2N` patches.
    pub(crate) fn patches(self) -> PolarRingPatches<'a, R> {
        PolarRingPatches {
            ring: self,
            next: 0,
        }
    }
}

/// Iterator over the patches of a polar net's current ring, in ring order
/// (`k = span·N + column`):
/// [`PolarNetInner::ring_patches`](super::PolarNetInner::ring_patches).
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PolarRingPatches<'a, R> {
    ring: Ring<'a, R>,
    next: usize,
}

impl<R> PolarRingPatches<'_, R> {
    /// No patches (a net with fewer than 5 links).
    pub(crate) fn empty() -> Self {
        PolarRingPatches {
            ring: Ring {
                links: [&[]; 5],
                n: 0,
            },
            next: 0,
        }
    }
}

impl<R: Real> Iterator for PolarRingPatches<'_, R> {
    type Item = BicubicPatch<R>;
    fn next(&mut self) -> Option<Self::Item> {
        let p = self.ring.patch(self.next).ok()?;
        self.next = self.next.saturating_add(1);
        Some(p)
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.ring.len().saturating_sub(self.next);
        (left, Some(left))
    }
}

impl<R: Real> ExactSizeIterator for PolarRingPatches<'_, R> {}

impl<R: Real> FusedIterator for PolarRingPatches<'_, R> {}
