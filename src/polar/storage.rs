//! Where a polar net (docs/math/c2ps.md §1) keeps its links and roots: owned
//! arrays or borrowed slices, behind one trait, as `heapless` keeps a `Vec`'s
//! buffer behind `VecStorage`.
//!
//! A net of capacity `cap` (the largest valence it may reach, `n0·2^max_depth`)
//! needs two slices:
//!
//! - link storage, [`SliceStorage::links_len`]`(cap) = 5·cap` points: link `k`
//!   (1-based, `k ≤ 5`) at `[(k−1)·cap, (k−1)·cap + N)`;
//! - root storage, [`SliceStorage::roots_len`]`(cap) = cap` pairs
//!   `[cos, sin]`: the roots of unity of the current valence at `[0, N)`;
//!
//! `17·cap·size_of::<R>()` bytes in all. With slices of other lengths the
//! capacity is `min(links / 5, roots)`; the rest is unused.
//!
//! [`ArrayStorage<R, CAP>`] holds both inline (a `static`, a `Box`, the
//! stack); [`SliceStorage`] borrows them from the caller (a `Vec`, a
//! `Box<[_]>`, part of a work buffer), for a capacity chosen at run time. Any
//! other type may implement [`NetStorage`] (a net that owns heap storage, say:
//! the CLI's `HeapStorage`).
//! Every operation of the net runs the same code over the two slices, compiled
//! once per scalar type whatever the storage, so all storages give the same
//! numbers bit for bit.

use super::net::MAX_STORED_LINKS;
use crate::point::Point3;
use crate::real::Real;

/// The link and root storage of a polar net (see the [module docs](self) for
/// the layout).
///
/// The net reads the lengths on every call; an implementation must return
/// slices of the same lengths each time (other lengths give wrong numbers,
/// never a panic).
pub trait NetStorage<R> {
    /// Link storage (`5·cap` points) and root storage (`cap` pairs).
    fn parts(&self) -> (&[Point3<R>], &[[R; 2]]);
    /// The same, writable.
    fn parts_mut(&mut self) -> (&mut [Point3<R>], &mut [[R; 2]]);
}

/// Link and root storage held inline: room for valence `CAP`,
/// `17·CAP·size_of::<R>()` bytes.
#[derive(Clone)]
pub struct ArrayStorage<R, const CAP: usize> {
    links: [[Point3<R>; CAP]; MAX_STORED_LINKS],
    roots: [[R; 2]; CAP],
}

impl<R: Real, const CAP: usize> ArrayStorage<R, CAP> {
    /// All-zero storage: a `const fn`, so a `static` net lands in `.bss`.
    pub const fn new() -> Self {
        ArrayStorage {
            links: [[Point3([R::ZERO; 3]); CAP]; MAX_STORED_LINKS],
            roots: [[R::ZERO; 2]; CAP],
        }
    }
}

impl<R: Real, const CAP: usize> Default for ArrayStorage<R, CAP> {
    fn default() -> Self {
        Self::new()
    }
}

impl<R, const CAP: usize> NetStorage<R> for ArrayStorage<R, CAP> {
    #[inline]
    fn parts(&self) -> (&[Point3<R>], &[[R; 2]]) {
        (self.links.as_flattened(), &self.roots)
    }
    #[inline]
    fn parts_mut(&mut self) -> (&mut [Point3<R>], &mut [[R; 2]]) {
        (self.links.as_flattened_mut(), &mut self.roots)
    }
}

/// Link and root storage borrowed from the caller.
#[derive(Debug)]
pub struct SliceStorage<'s, R> {
    links: &'s mut [Point3<R>],
    roots: &'s mut [[R; 2]],
}

impl<'s, R> SliceStorage<'s, R> {
    /// Storage over the caller's link and root slices; their contents are
    /// not read, and not written until a net is loaded into them.
    #[inline]
    pub fn new(links: &'s mut [Point3<R>], roots: &'s mut [[R; 2]]) -> Self {
        SliceStorage { links, roots }
    }

    /// Points of link storage for capacity `cap`: `5·cap` (links 1..5).
    #[inline]
    pub const fn links_len(cap: usize) -> usize {
        MAX_STORED_LINKS.saturating_mul(cap)
    }

    /// `[cos, sin]` pairs of root storage for capacity `cap`: `cap`.
    #[inline]
    pub const fn roots_len(cap: usize) -> usize {
        cap
    }

    /// Gives the slices back (link storage, root storage).
    #[inline]
    pub fn into_parts(self) -> (&'s mut [Point3<R>], &'s mut [[R; 2]]) {
        (self.links, self.roots)
    }
}

impl<R> NetStorage<R> for SliceStorage<'_, R> {
    #[inline]
    fn parts(&self) -> (&[Point3<R>], &[[R; 2]]) {
        (self.links, self.roots)
    }
    #[inline]
    fn parts_mut(&mut self) -> (&mut [Point3<R>], &mut [[R; 2]]) {
        (self.links, self.roots)
    }
}

/// The capacity `valence · 2^steps` a net of that valence needs to take
/// `steps` C²PS steps; `None` on overflow.
pub const fn capacity_for(valence: usize, steps: u32) -> Option<usize> {
    match 1usize.checked_shl(steps) {
        Some(p) if steps < usize::BITS => valence.checked_mul(p),
        _ => None,
    }
}
