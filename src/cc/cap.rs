//! `CcCap`: the state of a Catmull-Clark cap — center, valence, level and the
//! current net in caller-provided storage — construction, node access and the
//! ring of bicubic patches each step emits.
//!
//! Layout. Per sector the cap keeps the *extended* ring: the nodes
//! `(x, y)`, `x ∈ 1..=3`, `y ∈ 0..=3`, of that sector's frame (docs/math/eg.md §1)
//! at index `(x − 1) + 3y` (12 per sector, sector `s` at `12s`). Its part with
//! `x, y ≤ 2` is the c-net of the current level; the nodes at `x = 3` or
//! `y = 3` (set by every step from the previous c-net, see [`super::step`])
//! are what the ring patches reach beyond it. Level 0 holds only the c-net.
//! The storage holds two such nets: the current one, and the one the next
//! step writes (its neighbours' old nodes are read while it is written).

use crate::bezier::{bspline_to_bezier_cubic, BicubicPatch};
use crate::eg::PatchDomain;
use crate::error::Error;
use crate::point::Point3;
use crate::polar::index::{at, next_mod, put};
use crate::real::Real;
use core::iter::FusedIterator;

/// Points per sector of the kept extended ring (`x ∈ 1..=3`, `y ∈ 0..=3`).
pub const EXT_SECTOR: usize = 12;
/// Patches per sector and ring.
pub const PATCHES_PER_SECTOR: usize = 3;
/// Nodes per sector of the input c-net (docs/math/eg.md §1).
const C_SECTOR: usize = 6;
/// Where the §1 order `(1,0) (2,0) (1,1) (2,1) (1,2) (2,2)` lands in the
/// extended layout `(x − 1) + 3y`.
const C_SLOTS: [usize; C_SECTOR] = [0, 1, 3, 4, 6, 7];

/// A Catmull-Clark cap of valence `n ≥ 3` in caller-provided storage.
///
/// Memory: `self` is a few words plus the borrowed storage of
/// [`CcCap::storage_len`]`(n) = 24n` points (two nets of 12 points per
/// sector). Every operation works sector by sector with a fixed amount of
/// stack, whatever the valence.
///
/// ```
/// use capdiv::{CcCap, Error, Point3};
/// // Valence 6, symmetric under a turn by 2π/6 about the z axis (the c-net
/// // of docs/math/eg.md §1: center and 6 nodes per sector).
/// let n = 6;
/// let mut nodes = Vec::new();
/// for s in 0..n {
///     let a = s as f64 * core::f64::consts::TAU / n as f64;
///     for (x, y) in [(1.0, 0.0), (2.0, 0.0), (1.0, 1.0), (2.0, 1.0), (1.0, 2.0), (2.0, 2.0)] {
///         let (t, r) = (a + f64::atan2(y, x) * 4.0 / n as f64, f64::hypot(x, y));
///         nodes.push([r * t.cos(), r * t.sin(), 0.1 * r * r]);
///     }
/// }
/// let mut storage = vec![Point3::ZERO; CcCap::<f64>::storage_len(n)];
/// let mut cap = CcCap::new([0.0; 3], &nodes, &mut storage)?;
/// // The limit (checked) lies on the axis, by symmetry; a step keeps it.
/// let p = cap.limit().finite()?;
/// assert!(p.0[0].abs() < 1e-14 && p.0[1].abs() < 1e-14);
/// cap.step()?;
/// assert!(cap.limit().max_abs_diff(p) < 1e-14);
/// // The ring: 3 bicubic patches per sector, k = 3·sector + piece.
/// assert_eq!(cap.ring_patches().len(), 3 * n);
/// for (k, patch) in cap.ring_patches().enumerate() {
///     assert_eq!(cap.ring_patch(k), Ok(patch));
/// }
/// assert_eq!(cap.ring_patch(3 * n), Err(Error::OutOfDomain));
/// # Ok::<(), capdiv::Error>(())
/// ```
#[derive(Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CcCap<'s, R> {
    /// The extraordinary vertex of the current level.
    pub(super) center: Point3<R>,
    /// The valence (≥ 3).
    pub(super) n: usize,
    /// Steps taken.
    pub(super) level: u32,
    /// The current net is the second half of `storage` when set, else the first.
    pub(super) flip: bool,
    /// Two nets of `12n` points each (at least [`CcCap::storage_len`] points).
    pub(super) storage: &'s mut [Point3<R>],
}

/// Where a position of a sector's frame lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Loc {
    /// The center `(0, 0)`.
    Center,
    /// Index into a net (`12·sector + (x − 1) + 3y`).
    Node(usize),
    /// Beyond the ring held (`x` or `y` above `reach` after the change of frame).
    Outside,
}

/// Sector `s + ds` (mod `n`), for `s < n` and small `|ds|`, without a
/// division (so no divide-by-zero path).
#[inline]
fn shift(s: usize, ds: i32, n: usize) -> usize {
    let mut k = s;
    for _ in 0..ds.unsigned_abs() {
        k = if ds > 0 {
            next_mod(k, n)
        } else if k == 0 {
            n.saturating_sub(1)
        } else {
            k - 1
        };
    }
    k
}

/// Position `(x, y)` of sector `s` (`s < n`), moved by the §1 change of
/// frame until owned (`x ≥ 1, y ≥ 0`): `(x, y)_s` with `y < 0` is
/// `(−y, x)_{s−1}`; otherwise, with `x ≤ 0`, `(y, −x)_{s+1}`. At most two
/// changes are ever needed. `reach`: the largest `x`, `y` held (2 or 3).
#[inline]
pub(super) fn locate(s: usize, x: i32, y: i32, n: usize, reach: i32) -> Loc {
    if x.unsigned_abs() > reach.unsigned_abs() || y.unsigned_abs() > reach.unsigned_abs() {
        // A change of frame keeps the coordinates' magnitudes.
        return Loc::Outside;
    }
    let (mut x, mut y, mut ds) = (x, y, 0i32);
    for _ in 0..4 {
        if x == 0 && y == 0 {
            return Loc::Center;
        }
        if y < 0 {
            (x, y, ds) = (-y, x, ds - 1);
        } else if x <= 0 {
            (x, y, ds) = (y, -x, ds + 1);
        } else {
            break;
        }
    }
    match (usize::try_from(x - 1), usize::try_from(y)) {
        (Ok(i), Ok(j)) if x <= reach && y <= reach => {
            Loc::Node(shift(s, ds, n) * EXT_SECTOR + i + 3 * j)
        }
        _ => Loc::Outside,
    }
}

/// Node `(x, y)` of sector `s` of `net` (center `e`), or `None` outside.
#[inline]
pub(super) fn node_of<R: Real>(
    net: &[Point3<R>],
    e: Point3<R>,
    n: usize,
    s: usize,
    x: i32,
    y: i32,
    reach: i32,
) -> Option<Point3<R>> {
    match locate(s, x, y, n, reach) {
        Loc::Center => Some(e),
        Loc::Node(i) => net.get(i).copied(),
        Loc::Outside => None,
    }
}

impl<'s, R: Real> CcCap<'s, R> {
    /// Points of storage a cap of valence `n` needs: `24n` — two nets (the
    /// current one and the one a step writes) of 12 points per sector (the
    /// extended ring `x ∈ 1..=3`, `y ∈ 0..=3`). Saturates instead of overflowing.
    pub const fn storage_len(n: usize) -> usize {
        n.saturating_mul(2 * EXT_SECTOR)
    }

    /// A cap from a c-net: center `e` and `6n` nodes, sector by sector in the
    /// §1 order `(1,0) (2,0) (1,1) (2,1) (1,2) (2,2)`, stored in the first
    /// `12n` points of `storage` (which must hold [`CcCap::storage_len`]`(n)`).
    /// Any `n ≥ 3` is accepted (`n = 4` is the regular case).
    ///
    /// Errors, in this order, all before anything is written:
    /// [`Error::WrongLength`] (not a multiple of 6), [`Error::ValenceTooSmall`]
    /// (`n < 3`), [`Error::CapacityExceeded`] (storage too short),
    /// [`Error::NonFinite`].
    pub fn new(
        center: [R; 3],
        nodes: &[[R; 3]],
        storage: &'s mut [Point3<R>],
    ) -> Result<Self, Error> {
        let n = nodes.len() / C_SECTOR;
        if n.saturating_mul(C_SECTOR) != nodes.len() {
            return Err(Error::WrongLength {
                expected: n.saturating_add(1).saturating_mul(C_SECTOR),
                found: nodes.len(),
            });
        }
        if n < 3 {
            return Err(Error::ValenceTooSmall { valence: n });
        }
        let needed = Self::storage_len(n);
        if storage.len() < needed {
            return Err(Error::CapacityExceeded {
                needed,
                capacity: storage.len(),
            });
        }
        let finite = |p: &[R; 3]| p.iter().all(|c| c.is_finite());
        if !finite(&center) || !nodes.iter().all(finite) {
            return Err(Error::NonFinite);
        }
        let e = Point3(center);
        let (sectors, _) = nodes.as_chunks::<C_SECTOR>();
        for (s, sector) in sectors.iter().enumerate() {
            let base = s * EXT_SECTOR;
            // The nodes at x = 3 or y = 3 are not part of a level-0 net (never
            // read before the first step writes them); keep them defined.
            for k in 0..EXT_SECTOR {
                put(storage, base + k, e);
            }
            for (p, slot) in sector.iter().zip(C_SLOTS) {
                put(storage, base + slot, Point3(*p));
            }
        }
        Ok(CcCap {
            center: e,
            n,
            level: 0,
            flip: false,
            storage,
        })
    }

    /// The valence `n`.
    #[inline]
    pub fn valence(&self) -> usize {
        self.n
    }
    /// Steps taken.
    #[inline]
    pub fn level(&self) -> u32 {
        self.level
    }
    /// The extraordinary vertex of the current level.
    #[inline]
    pub fn center(&self) -> Point3<R> {
        self.center
    }

    /// Largest coordinate held per direction: the c-net (2) at level 0, the
    /// extended ring (3) after a step.
    #[inline]
    pub(super) fn reach(&self) -> i32 {
        if self.level == 0 {
            2
        } else {
            3
        }
    }

    /// The current net (`12n` points).
    #[inline]
    pub(super) fn current(&self) -> &[Point3<R>] {
        let len = self.n.saturating_mul(EXT_SECTOR);
        let start = if self.flip { len } else { 0 };
        self.storage
            .get(start..start.saturating_add(len))
            .unwrap_or(&[])
    }

    /// Node `(x, y)` of sector `s` (taken mod `n`) of the current c-net, in
    /// any frame reachable by the §1 change of frame, or the center at
    /// `(0, 0)`. After a step the extended ring (`x, y ≤ 3`) is available,
    /// at level 0 the c-net (`x, y ≤ 2`); `None` beyond.
    pub fn node(&self, s: usize, x: i32, y: i32) -> Option<Point3<R>> {
        let s = s.checked_rem(self.n)?;
        node_of(self.current(), self.center, self.n, s, x, y, self.reach())
    }

    /// Patches in the last step's ring: `3n`, or 0 before the first step.
    #[inline]
    pub fn ring_len(&self) -> usize {
        if self.level == 0 {
            0
        } else {
            self.n.saturating_mul(PATCHES_PER_SECTOR)
        }
    }

    /// Patch `k` of the last step's ring, in the EG convention
    /// ([`crate::eg::EgSubdivision::ring_patch`], docs/math/eg.md §9): sector
    /// `k / 3`, piece `k % 3` (0: `[½,1]×[0,½]`, 1: `[0,½]×[½,1]`, 2: `[½,1]²`
    /// of that sector, in level-0 c-units × 2^−(level−1)); `u` along `x`, `v`
    /// along `y`, so `∂u × ∂v` has the same orientation in every sector.
    ///
    /// In the current grid these are the faces `[1,2]×[0,1]`, `[0,1]×[1,2]`,
    /// `[1,2]²`, all of whose corners are regular: the patch is the uniform
    /// bicubic B-spline of the face's 4×4 nodes, in Bézier form
    /// ([`bspline_to_bezier_cubic`]). [`Error::OutOfDomain`] for `k ≥ ring_len()`
    /// (every `k` before the first step).
    pub fn ring_patch(&self, k: usize) -> Result<BicubicPatch<R>, Error> {
        if k >= self.ring_len() {
            return Err(Error::OutOfDomain);
        }
        let (s, piece) = (k / PATCHES_PER_SECTOR, k % PATCHES_PER_SECTOR);
        // Lower-left corner of the face in the sector's current grid.
        let (a, b) = at(&[(1, 0), (0, 1), (1, 1)], piece, (1, 1));
        let net = self.current();
        let mut d = [[Point3::ZERO; 4]; 4];
        for (i, row) in (-1i32..).zip(d.iter_mut()) {
            for (j, p) in (-1i32..).zip(row.iter_mut()) {
                *p = node_of(net, self.center, self.n, s, a + i, b + j, 3)
                    .ok_or(Error::OutOfDomain)?;
            }
        }
        Ok(BicubicPatch {
            points: bspline_to_bezier_cubic(&d),
        })
    }

    /// Where patch `k` of the last step's ring lies: its sector and square in
    /// that sector's level-0 c-units (the same values as
    /// [`crate::eg::EgSubdivision::ring_patch_domain`] at the same level).
    /// [`Error::OutOfDomain`] for `k ≥ ring_len()`.
    pub fn ring_patch_domain(&self, k: usize) -> Result<PatchDomain, Error> {
        if k >= self.ring_len() {
            return Err(Error::OutOfDomain);
        }
        Ok(PatchDomain::of_ring_patch(self.level, k))
    }

    /// All [`Self::ring_len`] patches of the last step's ring, in ring order
    /// ([`Self::ring_patch`]: `k = 3·sector + piece`, as
    /// [`crate::eg::EgSubdivision::ring_patches`]); none before the first
    /// step.
    pub fn ring_patches(&self) -> CcRingPatches<'_, 's, R> {
        CcRingPatches { cap: self, next: 0 }
    }
}

/// Iterator over the patches of a [`CcCap`]'s last ring, in ring order
/// (`k = 3·sector + piece`): [`CcCap::ring_patches`].
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CcRingPatches<'a, 's, R> {
    cap: &'a CcCap<'s, R>,
    next: usize,
}

impl<R: Real> Iterator for CcRingPatches<'_, '_, R> {
    type Item = BicubicPatch<R>;
    fn next(&mut self) -> Option<Self::Item> {
        if self.next >= self.cap.ring_len() {
            return None;
        }
        let p = self.cap.ring_patch(self.next).ok()?;
        self.next = self.next.saturating_add(1);
        Some(p)
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.cap.ring_len().saturating_sub(self.next);
        (left, Some(left))
    }
}

impl<R: Real> ExactSizeIterator for CcRingPatches<'_, '_, R> {}

impl<R: Real> FusedIterator for CcRingPatches<'_, '_, R> {}
