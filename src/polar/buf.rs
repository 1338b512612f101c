//! `PolarNetBuf`: a polar configuration (docs/math/c2ps.md §1) in caller-provided
//! storage — [`PolarNet`]'s operations, results and errors with a capacity
//! chosen at run time.
//!
//! [`PolarNet<R, CAP>`](PolarNet) holds its links and roots inline, so a large
//! `CAP` cannot be built on the heap without passing through the stack. This
//! net borrows two slices instead (a `Vec`, a `Box<[_]>`, a `static` array…):
//!
//! - link storage, [`PolarNetBuf::link_storage_len`]`(cap) = 5·cap` points:
//!   link `k` (1-based, `k ≤ 5`) at `[(k−1)·cap, (k−1)·cap + N)`;
//! - root storage, [`PolarNetBuf::root_storage_len`]`(cap) = cap` pairs
//!   `[cos, sin]`: the roots of unity of the current valence at `[0, N)`;
//!
//! where `cap` is the largest valence the net may reach (`n0·2^max_depth`):
//! `17·cap·size_of::<R>()` bytes, as for `PolarNet<R, cap>`. With storage of
//! other lengths the capacity is `min(links / 5, roots)`; the rest is unused.
//!
//! Every operation runs the same code as [`PolarNet`]'s (the step, the roots,
//! the rings and the jet are written once over plain slices), so both nets
//! give the same numbers bit for bit.

use super::net::{flat_links, held_after_step, validate, FirstStep, MAX_STORED_LINKS};
use super::ring::{Ring, RingPatchesView};
use super::rts::rts_in_place;
use super::step::{c2ps_in_place, check_step, step_fits};
use crate::bezier::BicubicPatch;
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;
use crate::trig::roots::{check_valence, double_ring, fill_ring, seed};

#[cfg(doc)]
use super::net::PolarNet;

/// A polar configuration of valence `n·2^level` whose links and roots live in
/// caller-provided slices (see the [module docs](self) for the layout).
///
/// `self` is a few words; every operation uses a fixed amount of stack,
/// whatever the capacity.
pub struct PolarNetBuf<'s, R> {
    pole: Point3<R>,
    /// Link `k` (1-based) at `[(k−1)·cap, (k−1)·cap + valence)` for `k ≤ held`.
    links: &'s mut [Point3<R>],
    /// The `valence`-th roots of unity at `[0, valence)`.
    roots: &'s mut [[R; 2]],
    /// Points per link and roots the storage has room for.
    cap: usize,
    /// Current valence `N` (0 for an empty net).
    valence: usize,
    held: usize,
    level: u32,
    base_valence: usize,
}

impl<'s, R: Real> PolarNetBuf<'s, R> {
    /// Points of link storage for capacity `cap`: `5·cap` (links 1..5).
    #[inline]
    pub const fn link_storage_len(cap: usize) -> usize {
        MAX_STORED_LINKS.saturating_mul(cap)
    }

    /// `[cos, sin]` pairs of root storage for capacity `cap`: `cap`.
    #[inline]
    pub const fn root_storage_len(cap: usize) -> usize {
        cap
    }

    /// The capacity `valence · 2^steps` a net of that valence needs to take
    /// `steps` C²PS steps; `None` on overflow.
    pub const fn capacity_for(valence: usize, steps: u32) -> Option<usize> {
        match 1usize.checked_shl(steps) {
            Some(p) if steps < usize::BITS => valence.checked_mul(p),
            _ => None,
        }
    }

    /// An empty net (valence 0, no links) over the given storage: fill it with
    /// [`Self::reset`]. Nothing is written to the storage. On an empty net
    /// [`Self::step`] returns [`Error::NotEnoughLinks`] and [`Self::rts_step`]
    /// does nothing.
    pub fn empty(link_storage: &'s mut [Point3<R>], root_storage: &'s mut [[R; 2]]) -> Self {
        let cap = (link_storage.len() / MAX_STORED_LINKS).min(root_storage.len());
        PolarNetBuf {
            pole: Point3::ZERO,
            links: link_storage,
            roots: root_storage,
            cap,
            valence: 0,
            held: 0,
            level: 0,
            base_valence: 0,
        }
    }

    /// Builds a net from the pole and links `links[0]` = 1-link, … as
    /// [`PolarNet::new`] does, in the given storage.
    ///
    /// Errors, in [`PolarNet::new`]'s order: [`Error::TooFewLinks`],
    /// [`Error::ValenceTooSmall`], [`Error::LinkLengthMismatch`],
    /// [`Error::NonFinite`], [`Error::CapacityExceeded`] (`n` above
    /// [`Self::capacity`], the storage is too small),
    /// [`Error::ValenceUnsupported`]. On error nothing has been written to the
    /// storage.
    pub fn new<L: AsRef<[[R; 3]]>>(
        pole: [R; 3],
        links: &[L],
        link_storage: &'s mut [Point3<R>],
        root_storage: &'s mut [[R; 2]],
    ) -> Result<Self, Error> {
        let mut net = Self::empty(link_storage, root_storage);
        net.reset(pole, links)?;
        Ok(net)
    }

    /// [`Self::new`] in place: loads a level-0 configuration, whatever the net
    /// held. Every check runs before anything is written, so on error the net
    /// and its storage are unchanged.
    pub fn reset<L: AsRef<[[R; 3]]>>(&mut self, pole: [R; 3], links: &[L]) -> Result<(), Error> {
        let n = validate(&pole, links)?;
        check_valence(n, self.cap)?;
        let base = seed(n)?;
        // Checked: from here on nothing fails.
        let held = links.len().min(MAX_STORED_LINKS);
        let slots = split_links(self.links, self.cap, n, held);
        for (slot, l) in slots.into_iter().zip(links) {
            for (dst, src) in slot.iter_mut().zip(l.as_ref()) {
                *dst = Point3(*src);
            }
        }
        let roots = self.roots.get_mut(..n).unwrap_or_default();
        fill_ring(roots, n, base);
        self.pole = Point3(pole);
        self.valence = n;
        self.held = held;
        self.level = 0;
        self.base_valence = n;
        Ok(())
    }

    /// Builds a net from flat coordinates as [`PolarNet::from_flat`] does
    /// (`links·valence` points as `x, y, z` triples, link by link).
    pub fn from_flat(
        pole: [R; 3],
        valence: usize,
        coords: &[R],
        link_storage: &'s mut [Point3<R>],
        root_storage: &'s mut [[R; 2]],
    ) -> Result<Self, Error> {
        let mut net = Self::empty(link_storage, root_storage);
        net.reset_flat(pole, valence, coords)?;
        Ok(net)
    }

    /// [`Self::from_flat`] in place; on error the net is unchanged.
    pub fn reset_flat(&mut self, pole: [R; 3], valence: usize, coords: &[R]) -> Result<(), Error> {
        let (links, stored) = flat_links(valence, coords)?;
        self.reset(pole, links.get(..stored).unwrap_or(&[]))
    }

    /// Gives the storage back (link storage, root storage).
    pub fn into_storage(self) -> (&'s mut [Point3<R>], &'s mut [[R; 2]]) {
        (self.links, self.roots)
    }

    /// The largest valence the storage has room for:
    /// `min(link storage / 5, root storage)`.
    #[inline]
    pub fn capacity(&self) -> usize {
        self.cap
    }
    /// Current valence `N = n·2^level`.
    #[inline]
    pub fn valence(&self) -> usize {
        self.valence
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
            let start = (i - 1) * self.cap;
            self.links.get(start..start + self.valence)
        } else {
            None
        }
    }
    /// The roots of unity of the current valence, `(c(j/N), s(j/N))` for
    /// `j < N` (as [`PolarNet::roots`]`().as_slice()`).
    #[inline]
    pub fn roots(&self) -> &[[R; 2]] {
        self.roots.get(..self.valence).unwrap_or_default()
    }

    /// One C²PS step, as [`PolarNet::step`]. [`Error::CapacityExceeded`] when
    /// `2N` is above [`Self::capacity`], [`Error::NotEnoughLinks`] on an
    /// [`Self::empty`] net, [`Error::NonFinite`] when the step could overflow
    /// (as [`PolarNet::step`]); the net is then unchanged.
    pub fn step(&mut self, first: FirstStep) -> Result<(), Error> {
        let n = self.valence;
        // 2n <= cap <= root storage: the roots double in place.
        check_step(self.held, n, self.cap)?;
        step_fits(self.pole, [1, 2, 3].map(|i| self.link(i).unwrap_or(&[])), n)?;
        let roots = self.roots.get_mut(..2 * n).unwrap_or_default();
        double_ring(roots, n);
        let new_held = held_after_step(self.held);
        c2ps_in_place(
            &mut self.pole,
            split_links(self.links, self.cap, 2 * n, new_held),
            n,
            self.held,
            new_held,
            self.roots.get(..2 * n).unwrap_or_default(),
            self.level == 0 && first == FirstStep::Uniform,
        );
        self.valence = 2 * n;
        self.held = new_held;
        self.level += 1;
        Ok(())
    }

    /// One RTS step, as [`PolarNet::rts_step`]: valence and level unchanged,
    /// the links held grow as for C²PS. [`Error::NonFinite`] when the step
    /// could overflow (as [`PolarNet::rts_step`]); the net is then unchanged.
    /// On an [`Self::empty`] net: `Ok`, nothing done.
    pub fn rts_step(&mut self) -> Result<(), Error> {
        if self.held < 2 {
            return Ok(()); // an empty net: nothing to refine
        }
        let n = self.valence;
        step_fits(self.pole, [1, 2, 3].map(|i| self.link(i).unwrap_or(&[])), n)?;
        let new_held = held_after_step(self.held);
        rts_in_place(
            &mut self.pole,
            split_links(self.links, self.cap, n, new_held),
            n,
            self.held,
            self.roots.get(..n).unwrap_or_default(),
        );
        self.held = new_held;
        Ok(())
    }

    /// Number of patches in the current ring, `2N`.
    #[inline]
    pub fn ring_len(&self) -> usize {
        2 * self.valence
    }

    /// Patch `(span, column)` of the current ring, as [`PolarNet::ring_patch`]:
    /// [`Error::NotEnoughLinks`] below 5 links, [`Error::OutOfDomain`] for an
    /// index outside the ring.
    pub fn ring_patch(&self, span: usize, column: usize) -> Result<BicubicPatch<R>, Error> {
        self.ring()?.patch(span, column)
    }

    /// All `2N` patches of the current ring, as [`PolarNet::ring_patches`].
    pub fn ring_patches(&self) -> Result<RingPatchesView<'_, R>, Error> {
        Ok(self.ring()?.patches())
    }

    fn ring(&self) -> Result<Ring<'_, R>, Error> {
        let link = |k: usize| self.link(k).unwrap_or(&[]);
        Ring::new(
            [link(1), link(2), link(3), link(4), link(5)],
            self.held,
            self.valence,
        )
    }
}

/// Links 1..5 of `storage` (`cap` points each), the first `count` of them cut
/// to `len` points, the others empty.
fn split_links<R>(
    storage: &mut [Point3<R>],
    cap: usize,
    len: usize,
    count: usize,
) -> [&mut [Point3<R>]; MAX_STORED_LINKS] {
    let mut out: [&mut [Point3<R>]; MAX_STORED_LINKS] = Default::default();
    let mut rest = storage;
    for (k, slot) in out.iter_mut().enumerate() {
        let (head, tail) = rest.split_at_mut_checked(cap).unwrap_or_default();
        rest = tail;
        if k < count {
            *slot = head.get_mut(..len).unwrap_or_default();
        }
    }
    out
}

impl<R: Real> core::fmt::Debug for PolarNetBuf<'_, R> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("PolarNetBuf")
            .field("pole", &self.pole)
            .field("valence", &self.valence)
            .field("level", &self.level)
            .field("links_held", &self.held)
            .field("base_valence", &self.base_valence)
            .field("capacity", &self.cap)
            .finish_non_exhaustive()
    }
}

#[cfg(feature = "defmt")]
impl<R: Real + defmt::Format> defmt::Format for PolarNetBuf<'_, R> {
    fn format(&self, f: defmt::Formatter) {
        defmt::write!(
            f,
            "PolarNetBuf {{ pole: {}, valence: {}, level: {}, links_held: {}, capacity: {} }}",
            self.pole,
            self.valence,
            self.level,
            self.held,
            self.cap
        )
    }
}
