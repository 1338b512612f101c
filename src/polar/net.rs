//! `PolarNet`: a polar configuration (docs/math/c2ps.md §1) in fixed capacity.
//!
//! The pole and links 1..5 are stored as heapless ring buffers of capacity `CAP`
//! (points `q[i][j]`, `j` taken mod the valence). `CAP = n0·2^max_depth` fixes
//! the deepest level reachable from valence `n0`. Beside them, the net keeps the
//! roots of unity of its current valence ([`RootsOfUnity`], 2·CAP scalars).
//!
//! Memory: `(15 + 2)·CAP·size_of::<R>()` bytes plus a few words, e.g. 104 KiB for
//! `PolarNet<f32, 1536>` (valence 6, depth 8).

use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;
use crate::trig::RootsOfUnity;
use heapless::Vec;

/// Links stored by a net: 1..5, what one surface ring needs (§5).
pub const MAX_STORED_LINKS: usize = 5;

/// How the first C²PS step computes the refined 2-link (docs/math/c2ps.md §2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FirstStep {
    /// The paper's §6 variant: in the first step the 2-link is the uniform rule
    /// with the pole standing in for link 0. The paper recommends it.
    #[default]
    Uniform,
    /// Rules (1)–(3) in the first step too.
    Plain,
}

/// A polar configuration of valence `n·2^level`, capacity `CAP` per link.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PolarNet<R, const CAP: usize> {
    pub(crate) pole: Point3<R>,
    /// Links 1..5 in slots 0..4; slots at and beyond `held` are empty.
    pub(crate) links: [Vec<Point3<R>, CAP>; MAX_STORED_LINKS],
    pub(crate) held: usize,
    pub(crate) roots: RootsOfUnity<R, CAP>,
    pub(crate) level: u32,
    pub(crate) base_valence: usize,
}

/// Checks a level-0 configuration (used by the net and the outer region).
/// Returns the valence.
pub(crate) fn validate<R: Real, L: AsRef<[[R; 3]]>>(
    pole: &[R; 3],
    links: &[L],
) -> Result<usize, Error> {
    if links.len() < 2 {
        return Err(Error::TooFewLinks { links: links.len() });
    }
    let n = links[0].as_ref().len();
    if n < 3 {
        return Err(Error::ValenceTooSmall { valence: n });
    }
    for (i, l) in links.iter().enumerate() {
        let len = l.as_ref().len();
        if len != n {
            return Err(Error::LinkLengthMismatch {
                link: i + 1,
                len,
                expected: n,
            });
        }
    }
    let finite = |p: &[R; 3]| p.iter().all(|c| c.is_finite());
    if !finite(pole) || !links.iter().all(|l| l.as_ref().iter().all(finite)) {
        return Err(Error::NonFinite);
    }
    Ok(n)
}

impl<R: Real, const CAP: usize> PolarNet<R, CAP> {
    /// An empty net (valence 0, no links), usable in a `static`: fill it in
    /// place with [`Self::reset`]. On an empty net [`Self::step`] returns
    /// [`Error::NotEnoughLinks`] and [`Self::rts_step`] does nothing.
    pub const fn empty() -> Self {
        PolarNet {
            pole: Point3([R::ZERO; 3]),
            links: [Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new()],
            held: 0,
            roots: RootsOfUnity::empty(),
            level: 0,
            base_valence: 0,
        }
    }

    /// Builds a net from the pole and links `links[0]` = 1-link, … (each a
    /// closed ring of `n ≥ 3` points, counter-clockwise). At least 2 links;
    /// links beyond the 5th are checked but not stored (they only shape the
    /// level-0 outer region, see [`crate::polar::OuterRegion`]).
    ///
    /// Errors, in this order of checking: [`Error::TooFewLinks`],
    /// [`Error::ValenceTooSmall`], [`Error::LinkLengthMismatch`],
    /// [`Error::NonFinite`], [`Error::CapacityExceeded`] (`n > CAP`),
    /// [`Error::ValenceUnsupported`] (odd part of `n` above
    /// [`crate::trig::MAX_ODD_PART`]).
    ///
    /// The net is returned by value: where stack is scarce (a microcontroller),
    /// keep an [`Self::empty`] net in a `static` and [`Self::reset`] it instead.
    pub fn new<L: AsRef<[[R; 3]]>>(pole: [R; 3], links: &[L]) -> Result<Self, Error> {
        let mut net = Self::empty();
        net.reset(pole, links)?;
        Ok(net)
    }

    /// [`Self::new`] in place: loads a level-0 configuration into this net,
    /// whatever it held. Every check runs before anything is written, so on
    /// error the net is unchanged. Stack use is a few words, whatever `CAP` is.
    pub fn reset<L: AsRef<[[R; 3]]>>(&mut self, pole: [R; 3], links: &[L]) -> Result<(), Error> {
        let n = validate(&pole, links)?;
        // The first write: `RootsOfUnity::reset` checks `n` (capacity, table
        // support) before touching anything, so an error leaves the net as it was.
        self.roots.reset(n)?;
        for (k, slot) in self.links.iter_mut().enumerate() {
            slot.clear();
            if let Some(l) = links.get(k) {
                for p in l.as_ref() {
                    // Cannot fail: n <= CAP was checked above.
                    slot.push(Point3(*p)).map_err(|_| Error::CapacityExceeded {
                        needed: n,
                        capacity: CAP,
                    })?;
                }
            }
        }
        self.pole = Point3(pole);
        self.held = links.len().min(MAX_STORED_LINKS);
        self.level = 0;
        self.base_valence = n;
        Ok(())
    }

    /// Builds a net from flat coordinates: `coords` holds `links·valence` points
    /// as `x, y, z` triples, link by link (the layout of the C ABI).
    pub fn from_flat(pole: [R; 3], valence: usize, coords: &[R]) -> Result<Self, Error> {
        let mut net = Self::empty();
        net.reset_flat(pole, valence, coords)?;
        Ok(net)
    }

    /// [`Self::from_flat`] in place; on error the net is unchanged.
    pub fn reset_flat(&mut self, pole: [R; 3], valence: usize, coords: &[R]) -> Result<(), Error> {
        let (links, stored) = flat_links(valence, coords)?;
        self.reset(pole, links.get(..stored).unwrap_or(&[]))
    }

    /// Current valence `N = n·2^level`.
    #[inline]
    pub fn valence(&self) -> usize {
        self.roots.len()
    }
    /// Valence of the level-0 configuration.
    #[inline]
    pub fn base_valence(&self) -> usize {
        self.base_valence
    }
    /// Number of C²PS steps applied.
    #[inline]
    pub fn level(&self) -> u32 {
        self.level
    }
    /// The polar vertex `q00`.
    #[inline]
    pub fn pole(&self) -> Point3<R> {
        self.pole
    }
    /// Number of links held (2..=5).
    #[inline]
    pub fn links_held(&self) -> usize {
        self.held
    }
    /// Link `i` (1-based, `1..=links_held()`), or `None`.
    #[inline]
    pub fn link(&self, i: usize) -> Option<&[Point3<R>]> {
        if i >= 1 && i <= self.held {
            // held <= MAX_STORED_LINKS: `get` never fails, but spares the
            // bounds-check panic path the optimiser cannot remove.
            self.links.get(i - 1).map(|l| l.as_slice())
        } else {
            None
        }
    }
    /// The roots of unity of the current valence.
    #[inline]
    pub fn roots(&self) -> &RootsOfUnity<R, CAP> {
        &self.roots
    }
}

/// Splits flat coordinates (`links·valence` points as `x, y, z` triples, link
/// by link) into the links to store: `(links, stored)`, `links[..stored]`.
/// Errors, in this order: [`Error::ValenceTooSmall`], [`Error::WrongLength`],
/// [`Error::TooFewLinks`], [`Error::NonFinite`].
#[allow(clippy::type_complexity)]
pub(crate) fn flat_links<R: Real>(
    valence: usize,
    coords: &[R],
) -> Result<([&[[R; 3]]; MAX_STORED_LINKS], usize), Error> {
    if valence < 3 {
        return Err(Error::ValenceTooSmall { valence });
    }
    let per_link = 3 * valence;
    if !coords.len().is_multiple_of(per_link) {
        return Err(Error::WrongLength {
            expected: (coords.len() / per_link + 1) * per_link,
            found: coords.len(),
        });
    }
    let count = coords.len() / per_link;
    if count < 2 {
        return Err(Error::TooFewLinks { links: count });
    }
    if !coords.iter().all(|c| c.is_finite()) {
        return Err(Error::NonFinite);
    }
    let (pts, _) = coords.as_chunks::<3>();
    let stored = count.min(MAX_STORED_LINKS);
    let mut links: [&[[R; 3]]; MAX_STORED_LINKS] = [&[]; MAX_STORED_LINKS];
    for (i, l) in links.iter_mut().enumerate().take(stored) {
        // In range: i < stored <= count = pts.len() / valence. `get` only
        // spares the slice-index panic path (an empty link would be
        // rejected by `reset` as a length mismatch).
        *l = pts.get(i * valence..(i + 1) * valence).unwrap_or(&[]);
    }
    Ok((links, stored))
}

/// Links held after one step: with old links up to `K`, new links up to `2K−1`
/// (at most [`MAX_STORED_LINKS`]).
#[inline]
pub(crate) fn held_after_step(held: usize) -> usize {
    (2 * held).saturating_sub(1).min(MAX_STORED_LINKS)
}
