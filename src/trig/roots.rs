//! `RootsOfUnity`: the ring `(c(j/N), s(j/N))`, `j < N`, of the current valence.
//!
//! Built once per net ([`fill_base`](super::UnitRoots::fill_base) for the odd part, then
//! doublings) and doubled in place by each C²PS step: `new[2j] = old[j]`,
//! `new[2j+1] = old[j]·ω_{2N}` (one complex product, `ω_{2N}` from
//! [`unit_root`](super::UnitRoots::unit_root), rounded once from ~48 bits or more). The error
//! therefore grows by one rounding per level, not per entry. Storage: `2·CAP`
//! scalars.
//!
//! The ring algorithms (`fill_ring`, `double_ring`) work on plain slices, once
//! per scalar type; [`RootsOfUnity`] and the polar net (roots in its
//! [`crate::polar::NetStorage`]) both call them.

use super::table::MAX_ODD_PART;
use crate::error::Error;
use crate::polar::index::{at, put};
use crate::real::Real;
use heapless::{Vec, VecView};

/// The `N`-th roots of unity as `[cos, sin]` pairs, capacity `CAP`.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RootsOfUnity<R, const CAP: usize> {
    ring: Vec<[R; 2], CAP>,
}

impl<R: Real, const CAP: usize> RootsOfUnity<R, CAP> {
    /// An empty ring (valence 0), for statics; fill it with [`Self::reset`].
    pub const fn empty() -> Self {
        RootsOfUnity { ring: Vec::new() }
    }

    /// The ring for valence `n`.
    pub fn new(n: usize) -> Result<Self, Error> {
        let mut ring = Self::empty();
        ring.reset(n)?;
        Ok(ring)
    }

    /// Refills the ring in place for valence `n`; on error it is unchanged.
    pub fn reset(&mut self, n: usize) -> Result<(), Error> {
        check_valence(n, CAP)?;
        let base = seed(n)?;
        self.ring.clear();
        // Cannot fail: n <= CAP was checked above.
        let _ = self.ring.resize(n, [R::ZERO; 2]);
        fill_ring(&mut self.ring, n, base);
        Ok(())
    }

    /// The errors [`Self::reset`] would return for valence `n`, without
    /// touching anything.
    pub fn check(n: usize) -> Result<(), Error> {
        check_valence(n, CAP)
    }

    /// Valence `N` of the ring.
    #[inline]
    pub fn len(&self) -> usize {
        self.ring.len()
    }

    /// Never true for a constructed ring (valence ≥ 3).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.ring.is_empty()
    }

    /// `(c(j/N), s(j/N))` for any `j` (taken mod `N`).
    #[inline]
    pub fn get(&self, j: usize) -> [R; 2] {
        // A constructed ring is never empty; `checked_rem` and `at` only spare
        // the divide-by-zero and bounds-check panic paths.
        let k = j.checked_rem(self.ring.len()).unwrap_or(0);
        at(&self.ring, k, [R::ZERO; 2])
    }

    /// All entries, `j = 0..N`.
    #[inline]
    pub fn as_slice(&self) -> &[[R; 2]] {
        &self.ring
    }

    /// The ring as a capacity-erased view.
    #[inline]
    pub fn view(&self) -> &VecView<[R; 2]> {
        self.ring.as_view()
    }

    /// Doubles the valence in place: afterwards the ring holds the `2N`-th roots.
    /// Fails, unchanged, when `2N > CAP`.
    pub fn double(&mut self) -> Result<(), Error> {
        let n = self.ring.len();
        check_double(n, CAP)?;
        // Cannot fail: 2n <= CAP was checked above.
        let _ = self.ring.resize(2 * n, [R::ZERO; 2]);
        double_ring(&mut self.ring, n);
        Ok(())
    }
}

// The ring algorithms below work on plain slices and are shared by every
// capacity: `RootsOfUnity<R, CAP>` (a heapless `Vec`) and the polar net
// (any storage) both call them.

/// The errors of building the ring of valence `n` in room for `cap` roots, in
/// the order checked: [`Error::ValenceTooSmall`], [`Error::CapacityExceeded`],
/// [`Error::ValenceUnsupported`].
pub(crate) fn check_valence(n: usize, cap: usize) -> Result<(), Error> {
    if n < 3 {
        return Err(Error::ValenceTooSmall { valence: n });
    }
    if n > cap {
        return Err(Error::CapacityExceeded {
            needed: n,
            capacity: cap,
        });
    }
    seed(n)?;
    Ok(())
}

/// [`Error::CapacityExceeded`] when a ring of valence `n` cannot double in
/// room for `cap` roots.
#[inline]
pub(crate) fn check_double(n: usize, cap: usize) -> Result<(), Error> {
    if 2 * n > cap {
        return Err(Error::CapacityExceeded {
            needed: 2 * n,
            capacity: cap,
        });
    }
    Ok(())
}

/// Where [`fill_ring`] starts for valence `n`: the odd part of `n` (or 4 for
/// powers of two). [`Error::ValenceUnsupported`] for an odd part above
/// [`MAX_ODD_PART`] (or `n < 3`).
pub(crate) fn seed(n: usize) -> Result<usize, Error> {
    let odd = n.checked_shr(n.trailing_zeros()).unwrap_or(0);
    if n < 3 || odd > MAX_ODD_PART {
        return Err(Error::ValenceUnsupported { valence: n });
    }
    Ok(if odd == 1 { 4 } else { odd })
}

/// Writes the `n`-th roots to `ring[..n]` (`ring.len() >= n`, `n` checked by
/// [`check_valence`], `base` from [`seed`]): the base ring by a short product
/// chain, then doublings in place.
pub(crate) fn fill_ring<R: Real>(ring: &mut [[R; 2]], n: usize, base: usize) {
    R::fill_base(ring, base);
    let mut len = base;
    while len < n && len > 0 {
        double_ring(ring, len);
        len *= 2;
    }
}

/// Doubles the ring `ring[..n]` of `n`-th roots in place into `ring[..2n]`
/// (`ring.len() >= 2n`, checked by the caller): `new[2j] = old[j]`,
/// `new[2j+1] = old[j]·ω_{2n}`.
pub(crate) fn double_ring<R: Real>(ring: &mut [[R; 2]], n: usize) {
    let [hc, hs] = R::unit_root(n.wrapping_mul(2));
    for j in (0..n).rev() {
        let [c, s] = at(ring, j, [R::ZERO; 2]);
        put(ring, 2 * j, [c, s]);
        put(ring, 2 * j + 1, [c * hc - s * hs, s * hc + c * hs]);
    }
}
