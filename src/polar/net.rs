//! The polar net: a polar configuration (docs/math/c2ps.md §1) refined in
//! place, over any [`NetStorage`].
//!
//! One type, [`PolarNetInner<R, S>`], holds the pole, the valence, the level and
//! the number of links; its links 1..5 (points `q[i][j]`, `j` taken mod
//! the valence) and the roots of unity of its current valence live in the
//! storage `S`. As `heapless` does with `VecInner` and its `Vec`/`VecView`
//! aliases, two aliases name the usual storages:
//!
//! - [`PolarNet<R, CAP>`]: storage inline ([`ArrayStorage`]), capacity `CAP`
//!   fixed at compile time — a `static`, a `Box`, the stack;
//! - [`PolarNetBuf<'s, R>`]: storage borrowed from the caller
//!   ([`SliceStorage`]), capacity chosen at run time.
//!
//! `CAP = n0·2^max_depth` fixes the deepest level reachable from valence `n0`.
//! Memory: `17·CAP·size_of::<R>()` bytes of storage plus a few words, e.g.
//! 104 KiB for `PolarNet<f32, 1536>` (valence 6, depth 8).
//!
//! Every method is written once, for any storage; its work is done by
//! functions over the storage's two slices, compiled once per scalar type
//! whatever the storage or the capacity (one copy of the step in flash for
//! nets of any capacities), so every storage gives the same numbers bit for
//! bit.

use super::ring::{PolarRingPatches, Ring};
use super::rts::rts_step;
use super::step::c2ps_step;
use super::storage::{ArrayStorage, NetStorage, SliceStorage};
use crate::bezier::BicubicPatch;
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;
use crate::trig::roots::{check_valence, fill_ring, seed};

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

/// A polar configuration of valence `n·2^level` over the storage `S`; see
/// the [module docs](self). Use it through [`PolarNet`] (inline storage) or
/// [`PolarNetBuf`] (borrowed storage), or over a [`NetStorage`] of your own.
#[derive(Clone)]
pub struct PolarNetInner<R, S> {
    pub(crate) head: Head<R>,
    storage: S,
}

/// A polar net with its storage inline: capacity `CAP` per link.
pub type PolarNet<R, const CAP: usize> = PolarNetInner<R, ArrayStorage<R, CAP>>;

/// A polar net in caller-provided storage (a `Vec`, a `Box<[_]>`, a
/// `static` array…), capacity chosen at run time: see [`SliceStorage`].
pub type PolarNetBuf<'s, R> = PolarNetInner<R, SliceStorage<'s, R>>;

/// A net's state besides its storage.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Head<R> {
    /// The polar vertex `q00`.
    pub(crate) pole: Point3<R>,
    /// Current valence `N` (0 for an empty net).
    pub(crate) valence: usize,
    /// Links; link `k` (1-based, `k ≤ link_count`) is at
    /// `[(k−1)·cap, (k−1)·cap + valence)` of the link storage.
    pub(crate) link_count: usize,
    pub(crate) level: u32,
    pub(crate) base_valence: usize,
}

impl<R: Real> Head<R> {
    const EMPTY: Self = Head {
        pole: Point3([R::ZERO; 3]),
        valence: 0,
        link_count: 0,
        level: 0,
        base_valence: 0,
    };
}

/// The capacity of storage with `links` points of link storage and `roots`
/// pairs of root storage: `min(links / 5, roots)`.
#[inline]
pub(crate) fn capacity(links: usize, roots: usize) -> usize {
    (links / MAX_STORED_LINKS).min(roots)
}

/// A net's head and storage as slices: what every read runs on.
#[derive(Clone, Copy)]
pub(crate) struct NetRef<'a, R> {
    pub(crate) head: &'a Head<R>,
    links: &'a [Point3<R>],
    roots: &'a [[R; 2]],
}

impl<'a, R: Real> NetRef<'a, R> {
    fn cap(self) -> usize {
        capacity(self.links.len(), self.roots.len())
    }

    /// Link `i` (1-based, `1..=link_count`), or `None`.
    pub(crate) fn link(self, i: usize) -> Option<&'a [Point3<R>]> {
        link_of(self.links, self.cap(), self.head, i)
    }

    /// The roots of unity of the current valence.
    pub(crate) fn roots(self) -> &'a [[R; 2]] {
        self.roots.get(..self.head.valence).unwrap_or_default()
    }

    /// The current ring; [`Error::NotEnoughLinks`] below 5 links.
    pub(crate) fn ring(self) -> Result<Ring<'a, R>, Error> {
        let link = |k: usize| self.link(k).unwrap_or(&[]);
        Ring::new(
            [link(1), link(2), link(3), link(4), link(5)],
            self.head.link_count,
            self.head.valence,
        )
    }
}

/// Link `i` (1-based, `1..=head.link_count`) of link storage of capacity `cap`.
#[inline]
pub(crate) fn link_of<'a, R>(
    links: &'a [Point3<R>],
    cap: usize,
    head: &Head<R>,
    i: usize,
) -> Option<&'a [Point3<R>]> {
    if i >= 1 && i <= head.link_count {
        let start = (i - 1) * cap;
        links.get(start..start + head.valence)
    } else {
        None
    }
}

/// Links 1..5 of link storage (`cap` points each), the first `count` of them
/// cut to `len` points, the others empty.
pub(crate) fn split_links<R>(
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

/// Loads a level-0 configuration into `head` and the storage; every check
/// runs before anything is written.
fn reset<R: Real, L: AsRef<[[R; 3]]>>(
    head: &mut Head<R>,
    (links_storage, roots_storage): (&mut [Point3<R>], &mut [[R; 2]]),
    pole: [R; 3],
    links: &[L],
) -> Result<(), Error> {
    let n = validate(&pole, links)?;
    let cap = capacity(links_storage.len(), roots_storage.len());
    check_valence(n, cap)?;
    let base = seed(n)?;
    // Checked: from here on nothing fails.
    let link_count = links.len().min(MAX_STORED_LINKS);
    let slots = split_links(links_storage, cap, n, link_count);
    for (slot, l) in slots.into_iter().zip(links) {
        for (dst, &[x, y, z]) in slot.iter_mut().zip(l.as_ref()) {
            // Coordinate by coordinate: a whole-point copy here became a
            // call to a 1.5 KiB `memmove` per point on Cortex-M.
            dst.0[0] = x;
            dst.0[1] = y;
            dst.0[2] = z;
        }
    }
    fill_ring(roots_storage.get_mut(..n).unwrap_or_default(), n, base);
    *head = Head {
        pole: Point3(pole),
        valence: n,
        link_count,
        level: 0,
        base_valence: n,
    };
    Ok(())
}

impl<R: Real, const CAP: usize> PolarNet<R, CAP> {
    /// An empty net (valence 0, no links), a `const fn` usable in a `static`
    /// (all-zero bytes: `.bss`): fill it in place with [`Self::reset`].
    pub const fn empty() -> Self {
        PolarNetInner {
            head: Head::EMPTY,
            storage: ArrayStorage::new(),
        }
    }

    /// [`PolarNetInner::new_in`] with inline storage. The net is returned by
    /// value: where stack is scarce (a microcontroller), keep an
    /// [`Self::empty`] net in a `static` and [`Self::reset`] it instead.
    ///
    /// ```
    /// use capdiv::{Error, PolarNet};
    /// // Valence 6: link i (1..=5) is the circle of radius i at height i²/10.
    /// let links: Vec<Vec<[f64; 3]>> = (1..=5)
    ///     .map(|i| (0..6).map(|j| {
    ///         let t = core::f64::consts::TAU * j as f64 / 6.0;
    ///         let r = i as f64;
    ///         [r * t.cos(), r * t.sin(), 0.1 * r * r]
    ///     }).collect())
    ///     .collect();
    /// // Capacity 12: valence 6 and one step.
    /// let net: PolarNet<f64, 12> = PolarNet::new([0.0; 3], &links)?;
    /// assert_eq!((net.valence(), net.level(), net.link_count()), (6, 0, 5));
    /// assert_eq!(net.link(2).unwrap()[0].0, [2.0, 0.0, 0.4]);
    /// // Valence 13 does not fit: a typed error, nothing built.
    /// let too_big: Vec<Vec<[f64; 3]>> = vec![vec![[1.0, 0.0, 0.0]; 13]; 2];
    /// assert_eq!(
    ///     PolarNet::<f64, 12>::new([0.0; 3], &too_big).unwrap_err(),
    ///     Error::CapacityExceeded { needed: 13, capacity: 12 }
    /// );
    /// # Ok::<(), capdiv::Error>(())
    /// ```
    pub fn new<L: AsRef<[[R; 3]]>>(pole: [R; 3], links: &[L]) -> Result<Self, Error> {
        Self::new_in(pole, links, ArrayStorage::new())
    }

    /// [`PolarNetInner::from_flat_in`] with inline storage.
    pub fn from_flat(pole: [R; 3], valence: usize, coords: &[R]) -> Result<Self, Error> {
        Self::from_flat_in(pole, valence, coords, ArrayStorage::new())
    }
}

impl<R: Real, S: NetStorage<R>> PolarNetInner<R, S> {
    /// An empty net (valence 0, no links) over `storage`: fill it with
    /// [`Self::reset`]. Nothing is written to the storage. On an empty net
    /// [`Self::step`] returns [`Error::NotEnoughLinks`] and [`Self::rts_step`]
    /// does nothing.
    pub fn empty_in(storage: S) -> Self {
        PolarNetInner {
            head: Head::EMPTY,
            storage,
        }
    }

    /// Builds a net in `storage` from the pole and links `links[0]` = 1-link,
    /// … (each a closed ring of `n ≥ 3` points, counter-clockwise). At least
    /// 2 links; links beyond the 5th are checked but not stored (they only
    /// shape the level-0 outer region, see [`crate::polar::OuterRegion`]).
    ///
    /// Errors, in this order of checking: [`Error::TooFewLinks`],
    /// [`Error::ValenceTooSmall`], [`Error::LinkLengthMismatch`],
    /// [`Error::NonFinite`], [`Error::CapacityExceeded`] (`n` above
    /// [`Self::capacity`]), [`Error::ValenceUnsupported`] (odd part of `n`
    /// above [`crate::trig::MAX_ODD_PART`]). On error nothing has been written
    /// to the storage.
    ///
    /// A [`PolarNetBuf`] over the caller's slices, sized at run time, gives
    /// the numbers of a [`PolarNet`] bit for bit:
    ///
    /// ```
    /// use capdiv::{polar::capacity_for, FirstStep, Point3, PolarNet, PolarNetBuf, SliceStorage};
    /// # let links: Vec<Vec<[f64; 3]>> = (1..=5)
    /// #     .map(|i| (0..6).map(|j| {
    /// #         let t = core::f64::consts::TAU * j as f64 / 6.0;
    /// #         let r = i as f64;
    /// #         [r * t.cos(), r * t.sin(), 0.1 * r * r]
    /// #     }).collect())
    /// #     .collect();
    /// let cap = capacity_for(6, 1).unwrap(); // valence 6, one step: 12
    /// let mut ls = vec![Point3::ZERO; SliceStorage::<f64>::links_len(cap)];
    /// let mut rs = vec![[0.0; 2]; SliceStorage::<f64>::roots_len(cap)];
    /// let mut buf = PolarNetBuf::new_in([0.0; 3], &links, SliceStorage::new(&mut ls, &mut rs))?;
    /// let mut inline: PolarNet<f64, 12> = PolarNet::new([0.0; 3], &links)?;
    /// buf.step(FirstStep::Uniform)?;
    /// inline.step(FirstStep::Uniform)?;
    /// assert_eq!(buf.capacity(), 12);
    /// assert!(buf.ring_patches().eq(inline.ring_patches()));
    /// # Ok::<(), capdiv::Error>(())
    /// ```
    pub fn new_in<L: AsRef<[[R; 3]]>>(
        pole: [R; 3],
        links: &[L],
        storage: S,
    ) -> Result<Self, Error> {
        let mut net = Self::empty_in(storage);
        net.reset(pole, links)?;
        Ok(net)
    }

    /// Builds a net in `storage` from flat coordinates: `coords` holds
    /// `links·valence` points as `x, y, z` triples, link by link (the layout
    /// of the C ABI). Errors as [`Self::new_in`], with
    /// [`Error::WrongLength`] for a length not a multiple of `3·valence`.
    pub fn from_flat_in(
        pole: [R; 3],
        valence: usize,
        coords: &[R],
        storage: S,
    ) -> Result<Self, Error> {
        let mut net = Self::empty_in(storage);
        net.reset_flat(pole, valence, coords)?;
        Ok(net)
    }

    /// [`Self::new_in`] in place: loads a level-0 configuration, whatever the
    /// net held. Every check runs before anything is written, so on error
    /// the net and its storage are unchanged. Stack use is a few words,
    /// whatever the capacity.
    pub fn reset<L: AsRef<[[R; 3]]>>(&mut self, pole: [R; 3], links: &[L]) -> Result<(), Error> {
        reset(&mut self.head, self.storage.parts_mut(), pole, links)
    }

    /// [`Self::from_flat_in`] in place; on error the net is unchanged.
    pub fn reset_flat(&mut self, pole: [R; 3], valence: usize, coords: &[R]) -> Result<(), Error> {
        let (links, stored) = flat_links(valence, coords)?;
        self.reset(pole, links.get(..stored).unwrap_or(&[]))
    }

    /// Gives the storage back.
    pub fn into_storage(self) -> S {
        self.storage
    }

    #[inline]
    pub(crate) fn view(&self) -> NetRef<'_, R> {
        let (links, roots) = self.storage.parts();
        NetRef {
            head: &self.head,
            links,
            roots,
        }
    }

    /// The largest valence the storage has room for:
    /// `min(link storage / 5, root storage)` (`CAP` for a [`PolarNet`]).
    #[inline]
    pub fn capacity(&self) -> usize {
        let (links, roots) = self.storage.parts();
        capacity(links.len(), roots.len())
    }
    /// Current valence `N = n·2^level`.
    #[inline]
    pub fn valence(&self) -> usize {
        self.head.valence
    }
    /// Valence of the level-0 configuration.
    #[inline]
    pub fn base_valence(&self) -> usize {
        self.head.base_valence
    }
    /// Number of C²PS steps applied.
    #[inline]
    pub fn level(&self) -> u32 {
        self.head.level
    }
    /// The polar vertex `q00`.
    #[inline]
    pub fn pole(&self) -> Point3<R> {
        self.head.pole
    }
    /// Number of links (2..=5).
    #[inline]
    pub fn link_count(&self) -> usize {
        self.head.link_count
    }
    /// Link `i` (1-based, `1..=link_count()`), or `None`.
    #[inline]
    pub fn link(&self, i: usize) -> Option<&[Point3<R>]> {
        self.view().link(i)
    }
    /// The roots of unity of the current valence, `[c(j/N), s(j/N)]` for
    /// `j < N`.
    #[inline]
    pub fn roots(&self) -> &[[R; 2]] {
        self.view().roots()
    }

    /// One C²PS step (§2). `first` selects the first-step variant; it only
    /// matters on the net's first step (level 0), later steps always use
    /// rules (1)–(3).
    ///
    /// [`Error::CapacityExceeded`] when `2N` is above [`Self::capacity`],
    /// [`Error::NotEnoughLinks`] on an [`Self::empty_in`] net,
    /// [`Error::NonFinite`] when a coordinate of the pole or links 1..3
    /// exceeds `MAX/(16·N)` in magnitude (the step could overflow); the net
    /// is then unchanged.
    ///
    /// ```
    /// use capdiv::{Error, FirstStep, PolarNet};
    /// # let links: Vec<Vec<[f64; 3]>> = (1..=5)
    /// #     .map(|i| (0..6).map(|j| {
    /// #         let t = core::f64::consts::TAU * j as f64 / 6.0;
    /// #         let r = i as f64;
    /// #         [r * t.cos(), r * t.sin(), 0.1 * r * r]
    /// #     }).collect())
    /// #     .collect();
    /// let mut net: PolarNet<f64, 12> = PolarNet::new([0.0; 3], &links)?;
    /// net.step(FirstStep::Uniform)?;
    /// assert_eq!((net.valence(), net.level()), (12, 1));
    /// // Rule (1) of docs/math/c2ps.md §2: the new pole is 3/4 q00 + 1/4 A,
    /// // A the 1-link's average, here (0, 0, 0.1).
    /// assert!(net.pole().max_abs_diff(capdiv::Point3([0.0, 0.0, 0.025])) < 1e-15);
    /// // Valence 24 would exceed the capacity: an error, the net unchanged.
    /// let before = net.link(1).unwrap().to_vec();
    /// assert_eq!(
    ///     net.step(FirstStep::Uniform),
    ///     Err(Error::CapacityExceeded { needed: 24, capacity: 12 })
    /// );
    /// assert_eq!((net.valence(), net.link(1).unwrap()), (12, &before[..]));
    /// # Ok::<(), capdiv::Error>(())
    /// ```
    #[inline]
    pub fn step(&mut self, first: FirstStep) -> Result<(), Error> {
        c2ps_step(&mut self.head, self.storage.parts_mut(), first)
    }

    /// One RTS step (§3). Valence and level are unchanged; the links grow
    /// as for C²PS (old links up to `K` give new links up to `2K−1`, at most
    /// 5).
    ///
    /// [`Error::NonFinite`] when a coordinate of the pole or links 1..3
    /// exceeds `MAX/(16·N)` in magnitude (as for [`Self::step`]); the net is
    /// then unchanged. On an empty net: `Ok`, nothing done.
    #[inline]
    pub fn rts_step(&mut self) -> Result<(), Error> {
        rts_step(&mut self.head, self.storage.parts_mut())
    }

    /// Number of patches in the current ring: `2N` once the net holds 5
    /// links (§5), 0 before (a net built from 2 links has its first ring
    /// after 2 steps).
    #[inline]
    pub fn ring_len(&self) -> usize {
        self.view().ring().map_or(0, |r| r.len())
    }

    /// Patch `k` of the current ring (§5), `k < ring_len()`, in ring order:
    /// span `k / N` (0: `r ∈ [2, 3]`, 1: `r ∈ [3, 4]` in level-m link
    /// units), column `k % N` (`τ ∈ [column/N, (column+1)/N]`); `u` runs
    /// outward, `v` counter-clockwise. [`Error::NotEnoughLinks`] while the
    /// net holds fewer than 5 links, [`Error::OutOfDomain`] for
    /// `k ≥ ring_len()`.
    ///
    /// ```
    /// use capdiv::{PolarNet, Point3};
    /// // Valence 4, 5 flat links on circles of radius 1..5.
    /// let ring = |r: f64| [[r, 0.0, 0.0], [0.0, r, 0.0], [-r, 0.0, 0.0], [0.0, -r, 0.0]];
    /// let links = [ring(1.0), ring(2.0), ring(3.0), ring(4.0), ring(5.0)];
    /// let net: PolarNet<f64, 4> = PolarNet::new([0.0; 3], &links)?;
    /// assert_eq!(net.ring_len(), 2 * 4);
    /// // Patch 1 is span 0, column 1: its corner b00 is the B-spline's value
    /// // at link 2, column 1, the (1, 4, 1)/6 average over links 1..3 and
    /// // columns 0..2: (0, 4/3, 0).
    /// let corner = net.ring_patch(1)?.points[0][0];
    /// assert!(corner.max_abs_diff(Point3([0.0, 4.0 / 3.0, 0.0])) < 1e-15);
    /// assert!(net.ring_patch(net.ring_len()).is_err());
    /// # Ok::<(), capdiv::Error>(())
    /// ```
    #[inline]
    pub fn ring_patch(&self, k: usize) -> Result<BicubicPatch<R>, Error> {
        self.view().ring()?.patch(k)
    }

    /// All [`Self::ring_len`] patches of the current ring, in ring order
    /// ([`Self::ring_patch`]: span 0 columns `0..N`, then span 1); none
    /// while the net holds fewer than 5 links.
    ///
    /// ```
    /// use capdiv::{FirstStep, PolarNet};
    /// # let links: Vec<Vec<[f64; 3]>> = (1..=5)
    /// #     .map(|i| (0..6).map(|j| {
    /// #         let t = core::f64::consts::TAU * j as f64 / 6.0;
    /// #         let r = i as f64;
    /// #         [r * t.cos(), r * t.sin(), 0.1 * r * r]
    /// #     }).collect())
    /// #     .collect();
    /// // From the 1- and 2-link only: no ring until 5 links are reached.
    /// let mut net: PolarNet<f64, 24> = PolarNet::new([0.0; 3], &links[..2])?;
    /// assert_eq!((net.ring_len(), net.ring_patches().len()), (0, 0));
    /// net.step(FirstStep::Uniform)?; // 3 links
    /// net.step(FirstStep::Uniform)?; // 5 links, valence 24
    /// let ring = net.ring_patches();
    /// assert_eq!(ring.len(), 2 * 24);
    /// for (k, patch) in ring.enumerate() {
    ///     assert_eq!(net.ring_patch(k), Ok(patch));
    /// }
    /// # Ok::<(), capdiv::Error>(())
    /// ```
    #[inline]
    pub fn ring_patches(&self) -> PolarRingPatches<'_, R> {
        match self.view().ring() {
            Ok(ring) => ring.patches(),
            Err(_) => PolarRingPatches::empty(),
        }
    }
}

impl<R: Real, S> core::fmt::Debug for PolarNetInner<R, S> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let h = &self.head;
        f.debug_struct("PolarNet")
            .field("pole", &h.pole)
            .field("valence", &h.valence)
            .field("level", &h.level)
            .field("link_count", &h.link_count)
            .field("base_valence", &h.base_valence)
            .finish_non_exhaustive()
    }
}

#[cfg(feature = "defmt")]
impl<R: Real + defmt::Format, S> defmt::Format for PolarNetInner<R, S> {
    fn format(&self, f: defmt::Formatter) {
        let h = &self.head;
        defmt::write!(
            f,
            "PolarNet {{ pole: {}, valence: {}, level: {}, link_count: {}, base_valence: {} }}",
            h.pole,
            h.valence,
            h.level,
            h.link_count,
            h.base_valence
        )
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

/// Links after one step: with old links up to `K`, new links up to `2K−1`
/// (at most [`MAX_STORED_LINKS`]).
#[inline]
pub(crate) fn link_count_after_step(link_count: usize) -> usize {
    (2 * link_count).saturating_sub(1).min(MAX_STORED_LINKS)
}
