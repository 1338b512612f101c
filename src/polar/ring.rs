//! The surface ring of the current level as bicubic Bézier patches (spec
//! C2PS.md §5).
//!
//! The level-m ring is the uniform bicubic B-spline with control rows = links
//! 1..5 and `N` periodic columns, over `r ∈ [2, 4]` (level-m link units): two
//! radial spans × `N` columns = `2N` patches. Patch `(span, column)` has the
//! B-spline control points `q[span+1+k][column−1+l]`, `k, l = 0..3`, and covers
//! `r ∈ [2+span, 3+span]`, `τ ∈ [column/N, (column+1)/N]`; its `u` runs outward,
//! its `v` counter-clockwise.

use super::index::at;
use super::net::PolarNet;
use crate::bezier::{bspline_to_bezier_cubic, BicubicPatch};
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;

impl<R: Real, const CAP: usize> PolarNet<R, CAP> {
    /// Number of patches in the current ring, `2N`.
    #[inline]
    pub fn ring_len(&self) -> usize {
        2 * self.valence()
    }

    /// Patch `(span, column)` of the current ring, `span ∈ {0, 1}`,
    /// `column < N`. Needs all 5 links ([`Error::NotEnoughLinks`]);
    /// [`Error::OutOfDomain`] for an index outside the ring.
    pub fn ring_patch(&self, span: usize, column: usize) -> Result<BicubicPatch<R>, Error> {
        if self.held < 5 {
            return Err(Error::NotEnoughLinks {
                needed: 5,
                held: self.held,
            });
        }
        let n = self.valence();
        if span > 1 || column >= n {
            return Err(Error::OutOfDomain);
        }
        let mut d = [[Point3::ZERO; 4]; 4];
        for (k, row) in d.iter_mut().enumerate() {
            // span + k <= 4 and every stored link has n points: in range.
            let link: &[Point3<R>] = self.links.get(span + k).map_or(&[], |l| l);
            for (l, p) in row.iter_mut().enumerate() {
                // n >= 3 here; checked_rem only spares a divide-by-zero path.
                let idx = (column + n + l - 1).checked_rem(n).unwrap_or(0);
                *p = at(link, idx, Point3::ZERO);
            }
        }
        Ok(BicubicPatch {
            points: bspline_to_bezier_cubic(&d),
        })
    }

    /// All `2N` patches of the current ring: span 0 (columns 0..N), then span 1.
    pub fn ring_patches(&self) -> Result<RingPatches<'_, R, CAP>, Error> {
        if self.held < 5 {
            return Err(Error::NotEnoughLinks {
                needed: 5,
                held: self.held,
            });
        }
        Ok(RingPatches { net: self, next: 0 })
    }
}

/// Iterator over the patches of one ring.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RingPatches<'a, R, const CAP: usize> {
    net: &'a PolarNet<R, CAP>,
    next: usize,
}

impl<R: Real, const CAP: usize> Iterator for RingPatches<'_, R, CAP> {
    type Item = BicubicPatch<R>;
    fn next(&mut self) -> Option<Self::Item> {
        let n = self.net.valence();
        if self.next >= 2 * n {
            return None;
        }
        let i = self.next;
        self.next += 1;
        // n >= 3 here; the checked forms only spare a divide-by-zero path.
        let (span, column) = (i.checked_div(n)?, i.checked_rem(n)?);
        self.net.ring_patch(span, column).ok()
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = (2 * self.net.valence()).saturating_sub(self.next);
        (left, Some(left))
    }
}

impl<R: Real, const CAP: usize> ExactSizeIterator for RingPatches<'_, R, CAP> {}
