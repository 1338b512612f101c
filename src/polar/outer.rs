//! The level-0 outer region (docs/math/c2ps.md §5). The spec counts the pole as
//! link 0, so its `L` is the number of links plus one: with `K = L−1 ≥ 6` links
//! the level-0 configuration directly defines the regular bicubic surface
//! between the level-0 ring and the last links, `r ∈ [4, K−1]`, without
//! refinement.
//!
//! Span `k` (`r ∈ [k, k+1]`, `k = 4..=K−2`) uses links `k−1..k+2`; each span has
//! `n` periodic patches. Together with the rings of levels 0, 1, … it covers
//! everything but the shrinking hole around the pole.

use super::index::at;
use super::net::validate;
use crate::bezier::{bspline_to_bezier_cubic, BicubicPatch};
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;

/// The outer region of a level-0 configuration, borrowed from the caller.
#[derive(Clone, Copy, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct OuterRegion<'a, R, L> {
    links: &'a [L],
    valence: usize,
    _r: core::marker::PhantomData<R>,
}

impl<'a, R: Real, L: AsRef<[[R; 3]]>> OuterRegion<'a, R, L> {
    /// Validates the configuration like [`crate::polar::PolarNet::new`]
    /// (same errors, same order). With at most 5 links the region is empty.
    pub fn new(pole: [R; 3], links: &'a [L]) -> Result<Self, Error> {
        let valence = validate(&pole, links)?;
        Ok(OuterRegion {
            links,
            valence,
            _r: core::marker::PhantomData,
        })
    }

    /// Radial spans: `max(K − 5, 0)` for `K` links.
    #[inline]
    pub fn spans(&self) -> usize {
        self.links.len().saturating_sub(5)
    }

    /// Number of patches, `spans · n`.
    #[inline]
    pub fn len(&self) -> usize {
        self.spans() * self.valence
    }

    /// `true` when the configuration has at most 5 links.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Patch `i` (`span = i / n`, `column = i % n`): span `s` covers
    /// `r ∈ [4+s, 5+s]`. [`Error::OutOfDomain`] for `i ≥ len()`.
    pub fn patch(&self, i: usize) -> Result<BicubicPatch<R>, Error> {
        if i >= self.len() {
            return Err(Error::OutOfDomain);
        }
        let n = self.valence;
        // n >= 3 (validated); the checked forms only spare divide-by-zero paths.
        let (Some(span), Some(column)) = (i.checked_div(n), i.checked_rem(n)) else {
            return Err(Error::OutOfDomain);
        };
        // r in [k, k+1] with k = 4 + span uses links k-1..k+2 (1-based),
        // i.e. slice indices k-2..k+1.
        let first = span + 2;
        let mut d = [[Point3::ZERO; 4]; 4];
        for (k, row) in d.iter_mut().enumerate() {
            // first + k <= L - 2 for i < len(), and every link has n points.
            let link = self.links.get(first + k).map_or(&[][..], |l| l.as_ref());
            for (l, p) in row.iter_mut().enumerate() {
                let idx = (column + n + l - 1).checked_rem(n).unwrap_or(0);
                *p = Point3(at(link, idx, [R::ZERO; 3]));
            }
        }
        Ok(BicubicPatch {
            points: bspline_to_bezier_cubic(&d),
        })
    }

    /// All patches, span by span.
    pub fn patches(&self) -> impl Iterator<Item = BicubicPatch<R>> + '_ {
        (0..self.len()).filter_map(|i| self.patch(i).ok())
    }
}
