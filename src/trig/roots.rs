//! `RootsOfUnity`: the ring `(c(j/N), s(j/N))`, `j < N`, of the current valence.
//!
//! Built once per net from [`super::table`] and doubled in place by each C²PS
//! step: `new[2j] = old[j]`, `new[2j+1] = old[j]·ω_{2N}` (one complex product,
//! `ω_{2N}` from a half-angle step kept in `f64`). The error therefore grows by
//! one rounding per level, not per entry. Storage: `2·CAP` scalars.
//!
//! The ring algorithms (`fill_ring`, `double_ring`) work on plain slices, once
//! per scalar type; [`RootsOfUnity`] and [`crate::polar::PolarNetBuf`] (roots in
//! caller storage) both call them.

use crate::error::Error;
use crate::polar::index::{at, put};
use crate::real::Real;
use heapless::{Vec, VecView};

/// The `N`-th roots of unity as `[cos, sin]` pairs, capacity `CAP`.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RootsOfUnity<R, const CAP: usize> {
    ring: Vec<[R; 2], CAP>,
    /// `(cos, sin)(2π/N)` in `f64`, the seed of the next doubling.
    primitive: (f64, f64),
}

impl<R: Real, const CAP: usize> RootsOfUnity<R, CAP> {
    /// An empty ring (valence 0), for statics; fill it with [`Self::reset`].
    pub const fn empty() -> Self {
        RootsOfUnity {
            ring: Vec::new(),
            // All-zero bytes, so a static net lands in .bss; never read before
            // `reset` (doubling an empty ring is a no-op).
            primitive: (0.0, 0.0),
        }
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
        let seed = seed(n)?;
        self.ring.clear();
        // Cannot fail: n <= CAP was checked above.
        let _ = self.ring.resize(n, [R::ZERO; 2]);
        self.primitive = fill_ring(&mut self.ring, n, seed);
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
        self.primitive = double_ring(&mut self.ring, n, self.primitive);
        Ok(())
    }
}

// The ring algorithms below work on plain slices and are shared by every
// capacity: `RootsOfUnity<R, CAP>` (a heapless `Vec`) and
// `crate::polar::PolarNetBuf` (caller storage) both call them.

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
    super::primitive_root(n).ok_or(Error::ValenceUnsupported { valence: n })?;
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
/// powers of two) and its primitive root. Fails for an unsupported odd part.
pub(crate) fn seed(n: usize) -> Result<(usize, (f64, f64)), Error> {
    let odd = n >> n.trailing_zeros();
    let base = if odd == 1 { 4 } else { odd };
    let primitive = super::primitive_root(base).ok_or(Error::ValenceUnsupported { valence: n })?;
    Ok((base, primitive))
}

/// Writes the `n`-th roots to `ring[..n]` (`ring.len() >= n`, `n` checked by
/// [`check_valence`], `seed` from [`seed`]): the base ring by a short product
/// chain, then doublings in place. Returns `(cos, sin)(2π/n)` in `f64`.
pub(crate) fn fill_ring<R: Real>(
    ring: &mut [[R; 2]],
    n: usize,
    (base, mut primitive): (usize, (f64, f64)),
) -> (f64, f64) {
    fill(ring, base, primitive);
    let mut len = base;
    while len < n && len > 0 {
        primitive = double_ring(ring, len, primitive);
        len *= 2;
    }
    primitive
}

/// Fills `ring[..n]` with the `n`-th roots: the powers `ω^j` for `j <= n/2` by
/// repeated multiplication in `f64` (at most 63 products for the odd part),
/// the rest by symmetry `ω^(n-j) = conj ω^j`.
fn fill<R: Real>(ring: &mut [[R; 2]], n: usize, w: (f64, f64)) {
    let (mut c, mut s) = (1.0f64, 0.0f64);
    for j in 0..=n / 2 {
        put(ring, j, [R::from_f64(c), R::from_f64(s)]);
        if j > 0 {
            put(ring, n - j, [R::from_f64(c), R::from_f64(-s)]);
        }
        let c2 = c * w.0 - s * w.1;
        s = s * w.0 + c * w.1;
        c = c2;
    }
}

/// Doubles the ring `ring[..n]` of `n`-th roots in place into `ring[..2n]`
/// (`ring.len() >= 2n`, checked by the caller): `new[2j] = old[j]`,
/// `new[2j+1] = old[j]·ω_{2n}`. `w = (cos, sin)(2π/n)`; returns that of `2n`.
pub(crate) fn double_ring<R: Real>(ring: &mut [[R; 2]], n: usize, w: (f64, f64)) -> (f64, f64) {
    let ch = libm::sqrt(0.5 * (1.0 + w.0));
    let half = (ch, w.1 / (2.0 * ch));
    let (hc, hs) = (R::from_f64(half.0), R::from_f64(half.1));
    for j in (0..n).rev() {
        let [c, s] = at(ring, j, [R::ZERO; 2]);
        put(ring, 2 * j, [c, s]);
        put(ring, 2 * j + 1, [c * hc - s * hs, s * hc + c * hs]);
    }
    half
}
