//! The surface ring of the current level as bicubic Bézier patches (spec
//! docs/math/c2ps.md §5).
//!
//! The level-m ring is the uniform bicubic B-spline with control rows = links
//! 1..5 and `N` periodic columns, over `r ∈ [2, 4]` (level-m link units): two
//! radial spans × `N` columns = `2N` patches. Patch `(span, column)` has the
//! B-spline control points `q[span+1+k][column−1+l]`, `k, l = 0..3`, and covers
//! `r ∈ [2+span, 3+span]`, `τ ∈ [column/N, (column+1)/N]`; its `u` runs outward,
//! its `v` counter-clockwise.

use super::index::at;
use crate::bezier::{bspline_to_bezier_cubic, BicubicPatch};
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;

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
    /// The ring of a net holding `held` links of valence `n`;
    /// [`Error::NotEnoughLinks`] below 5 links.
    pub(crate) fn new(links: [&'a [Point3<R>]; 5], held: usize, n: usize) -> Result<Self, Error> {
        if held < 5 {
            return Err(Error::NotEnoughLinks { needed: 5, held });
        }
        Ok(Ring { links, n })
    }

    /// Patch `(span, column)`; [`Error::OutOfDomain`] outside the ring.
    pub(crate) fn patch(&self, span: usize, column: usize) -> Result<BicubicPatch<R>, Error> {
        let n = self.n;
        if span > 1 || column >= n {
            return Err(Error::OutOfDomain);
        }
        let mut d = [[Point3::ZERO; 4]; 4];
        for (k, row) in d.iter_mut().enumerate() {
            // span + k <= 4 and every link has n points: in range.
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

    /// An iterator over all `2N` patches.
    pub(crate) fn patches(self) -> RingPatches<'a, R> {
        RingPatches {
            ring: self,
            next: 0,
        }
    }
}

/// Iterator over the patches of one ring:
/// [`PolarNetInner::ring_patches`](super::PolarNetInner::ring_patches).
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RingPatches<'a, R> {
    ring: Ring<'a, R>,
    next: usize,
}

impl<R: Real> Iterator for RingPatches<'_, R> {
    type Item = BicubicPatch<R>;
    fn next(&mut self) -> Option<Self::Item> {
        let n = self.ring.n;
        if self.next >= 2 * n {
            return None;
        }
        let i = self.next;
        self.next += 1;
        // n >= 3 here; the checked forms only spare a divide-by-zero path.
        let (span, column) = (i.checked_div(n)?, i.checked_rem(n)?);
        self.ring.patch(span, column).ok()
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = (2 * self.ring.n).saturating_sub(self.next);
        (left, Some(left))
    }
}

impl<R: Real> ExactSizeIterator for RingPatches<'_, R> {}
