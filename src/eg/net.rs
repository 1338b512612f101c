//! The two input nets of EG (docs/math/eg.md §1, §2) in fixed capacity, and the
//! conversions between them: degree raising R (§3) and the limit point `c0`
//! (§4, formulas (3) and (4)).
//!
//! Memory: a [`DNet`] holds `12·MAX_VALENCE + 1` points (2.9 KiB for `f64`,
//! 1.5 KiB for `f32`), a [`CNet`] `6·MAX_VALENCE + 1`; both independent of the
//! valence actually used.

use super::layout::{Term, CENTER, RAISE};
use super::MAX_VALENCE;
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;
use core::num::NonZeroUsize;
use heapless::Vec;

/// Nodes per sector of a c-net (§1).
pub const C_SECTOR: usize = 6;
/// Nodes per sector of a d-net (§2).
pub const D_SECTOR: usize = 12;

/// One c-net sector, in the §1 order `(1,0) (2,0) (1,1) (2,1) (1,2) (2,2)`.
pub type CSector<R> = [Point3<R>; C_SECTOR];
/// One d-net sector, in the §2 order `00 10 20 30 01 11 21 31 02 12 22 32`
/// (`d_ij` at index `i + 4j`).
pub type DSector<R> = [Point3<R>; D_SECTOR];

/// Validates a valence for EG: 3..=[`MAX_VALENCE`].
pub(crate) fn check_valence(n: usize) -> Result<(), Error> {
    if n < 3 {
        Err(Error::ValenceTooSmall { valence: n })
    } else if n > MAX_VALENCE {
        Err(Error::ValenceUnsupported { valence: n })
    } else {
        Ok(())
    }
}

/// The number of `PER`-point sectors in `len` points (a positive multiple).
/// `PER` is a constant, so the divisions cannot divide by zero.
fn sector_count<const PER: usize>(len: usize) -> Result<usize, Error> {
    let n = len / PER;
    if n.saturating_mul(PER) != len {
        return Err(Error::WrongLength {
            expected: n.saturating_add(1).saturating_mul(PER),
            found: len,
        });
    }
    check_valence(n)?;
    Ok(n)
}

/// `coords` as points; [`Error::WrongLength`] unless a multiple of 3.
fn triples<R>(coords: &[R]) -> Result<&[[R; 3]], Error> {
    let (pts, rest) = coords.as_chunks::<3>();
    if rest.is_empty() {
        Ok(pts)
    } else {
        Err(Error::WrongLength {
            expected: coords.len().saturating_sub(rest.len()).saturating_add(3),
            found: coords.len(),
        })
    }
}

fn finite<R: Real>(p: &[R; 3]) -> bool {
    p.iter().all(|c| c.is_finite())
}

/// Sector `s + ds` (mod `n`) of `sectors`.
#[inline]
pub(crate) fn sector_at<T>(sectors: &[T], s: usize, ds: i8) -> Result<&T, Error> {
    let n = NonZeroUsize::new(sectors.len()).ok_or(Error::ValenceTooSmall { valence: 0 })?;
    // s < n ≤ 10 and ds ≥ −8: no wrap-around in practice; wrapping keeps it panic-free.
    let k = s
        .wrapping_add(n.get().wrapping_mul(2))
        .wrapping_add_signed(isize::from(ds))
        % n;
    sectors.get(k).ok_or(Error::OutOfDomain)
}

/// A Catmull-Clark c-net (§1): center `e` of valence `n ∈ 3..=10` and `n`
/// counter-clockwise sectors of 6 nodes.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CNet<R> {
    center: Point3<R>,
    sectors: Vec<CSector<R>, MAX_VALENCE>,
}

impl<R: Real> CNet<R> {
    /// An empty c-net (valence 0), usable in a `static` (all-zero bytes, so
    /// it lands in `.bss`): fill it in place with [`CNet::reset`].
    pub const fn empty() -> Self {
        CNet {
            center: Point3([R::ZERO; 3]),
            sectors: Vec::new(),
        }
    }

    /// A c-net from its center and `6n` nodes, sector by sector in the §1
    /// order. Errors, in this order: [`Error::WrongLength`] (not a multiple of
    /// 6), [`Error::ValenceTooSmall`] (`n < 3`), [`Error::ValenceUnsupported`]
    /// (`n > 10`), [`Error::NonFinite`].
    pub fn new(center: [R; 3], nodes: &[[R; 3]]) -> Result<Self, Error> {
        let mut net = Self::empty();
        net.reset(center, nodes)?;
        Ok(net)
    }

    /// A c-net from flat coordinates: `coords` holds the `6n` nodes as `x, y, z`
    /// triples (the layout of the C ABI and WASM). Errors as [`CNet::new`],
    /// with [`Error::WrongLength`] counted in coordinates (a multiple of 18).
    pub fn from_flat(center: [R; 3], coords: &[R]) -> Result<Self, Error> {
        let mut net = Self::empty();
        net.reset_flat(center, coords)?;
        Ok(net)
    }

    /// A c-net from its center and `n` sectors of 6 nodes (§1 order).
    /// Errors as [`CNet::new`].
    pub fn from_sectors(center: [R; 3], sectors: &[[[R; 3]; C_SECTOR]]) -> Result<Self, Error> {
        let mut net = Self::empty();
        net.reset_sectors(center, sectors)?;
        Ok(net)
    }

    /// [`CNet::new`] in place: loads the c-net into `self`, whatever it held.
    /// Every check runs before anything is written, so on error `self` is
    /// unchanged; stack use is a few words.
    pub fn reset(&mut self, center: [R; 3], nodes: &[[R; 3]]) -> Result<(), Error> {
        sector_count::<C_SECTOR>(nodes.len())?;
        let (chunks, _) = nodes.as_chunks::<C_SECTOR>();
        self.reset_sectors(center, chunks)
    }

    /// [`CNet::from_flat`] in place; on error `self` is unchanged.
    pub fn reset_flat(&mut self, center: [R; 3], coords: &[R]) -> Result<(), Error> {
        sector_count::<{ 3 * C_SECTOR }>(coords.len())?;
        self.reset(center, triples(coords)?)
    }

    /// [`CNet::from_sectors`] in place; on error `self` is unchanged.
    pub fn reset_sectors(
        &mut self,
        center: [R; 3],
        sectors: &[[[R; 3]; C_SECTOR]],
    ) -> Result<(), Error> {
        check_valence(sectors.len())?;
        if !finite(&center) || !sectors.iter().flatten().all(finite) {
            return Err(Error::NonFinite);
        }
        self.center = Point3(center);
        fill(&mut self.sectors, sectors)
    }

    /// The valence `n`.
    #[inline]
    pub fn valence(&self) -> usize {
        self.sectors.len()
    }
    /// The extraordinary node `e`.
    #[inline]
    pub fn center(&self) -> Point3<R> {
        self.center
    }
    /// Sector `s` (`s < n`), or `None`.
    #[inline]
    pub fn sector(&self, s: usize) -> Option<&CSector<R>> {
        self.sectors.get(s)
    }
    /// All sectors.
    #[inline]
    pub fn sectors(&self) -> &[CSector<R>] {
        &self.sectors
    }

    /// Node `(x, y)` of sector `s` (c-units, any frame reachable by §1), or the center.
    pub(crate) fn node(&self, s: usize, ds: i8, node: u8) -> Result<Point3<R>, Error> {
        if node == CENTER {
            return Ok(self.center);
        }
        let sec = sector_at(&self.sectors, s, ds)?;
        sec.get(usize::from(node))
            .copied()
            .ok_or(Error::OutOfDomain)
    }

    /// The limit point `c0` by formula (3) (§4): the Catmull-Clark limit point,
    /// corrected for n = 3.
    pub fn limit(&self) -> Point3<R> {
        let n = self.valence();
        // n ≠ 3: e weighs n/(n+5); n = 3: 11/32. Written as c0 = e + Σ w (c − e),
        // exact because the weights sum to 1.
        let (w6, w5) = if n == 3 {
            (R::ratio(1, 6), R::ratio(5, 96))
        } else {
            // n ≤ MAX_VALENCE: n(n + 5) is a small integer.
            let g = (n * (n + 5)) as i32;
            (R::ratio(4, g), R::ratio(1, g))
        };
        let e = self.center;
        let mut acc = Point3::ZERO;
        for [c6, _, c5, ..] in self.sectors.iter() {
            acc += (*c6 - e) * w6 + (*c5 - e) * w5;
        }
        e + acc
    }

    /// The d-net `R c` (§3) with `c0` by (3). Convex combinations of the
    /// c-net, so finite unless differences of coordinates overflow (|c| near
    /// the type's maximum); [`EgSubdivision::new`](super::EgSubdivision::new)
    /// rejects such a net with [`Error::NonFinite`].
    pub fn to_dnet(&self) -> DNet<R> {
        let mut out = DNet::empty();
        self.raise_into(&mut out);
        out
    }

    /// Sector `s` of [`CNet::to_dnet`].
    pub(crate) fn raised_sector(&self, s: usize) -> DSector<R> {
        let e = self.center;
        let mut d = [e; D_SECTOR];
        for (out, stencil) in d.iter_mut().zip(RAISE.iter()) {
            *out = e + self.apply(s, stencil);
        }
        d
    }

    /// `true` when [`CNet::to_dnet`] would be finite (computed, not stored).
    pub(crate) fn raises_finite(&self) -> bool {
        self.limit().is_finite()
            && (0..self.valence()).all(|s| self.raised_sector(s).iter().all(Point3::is_finite))
    }

    /// [`CNet::to_dnet`] written into `out` (one sector at a time, no
    /// net-sized temporary).
    pub(crate) fn raise_into(&self, out: &mut DNet<R>) {
        out.c0 = self.limit();
        out.sectors.clear();
        for s in 0..self.valence() {
            // Cannot fail: as many sectors as the c-net, which fits.
            let _ = out.sectors.push(self.raised_sector(s));
        }
    }

    /// `Σ w/144 (c − e)` over a degree-raising stencil.
    fn apply(&self, s: usize, stencil: &[Term; 9]) -> Point3<R> {
        let e = self.center;
        let mut acc = Point3::ZERO;
        for t in stencil.iter().filter(|t| t.w != 0) {
            // The stencils only read sectors s..s+2 and the center (layout tests).
            if let Ok(c) = self.node(s, t.ds, t.node) {
                acc += (c - e) * R::ratio(i32::from(t.w), 144);
            }
        }
        acc
    }
}

/// A d-net (§2): `n ∈ 3..=10` sectors of 12 bi-4 C² spline nodes, and the
/// limit point `c0`, fixed for all steps (§4).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DNet<R> {
    pub(crate) c0: Point3<R>,
    pub(crate) sectors: Vec<DSector<R>, MAX_VALENCE>,
}

impl<R: Real> DNet<R> {
    /// An empty d-net (valence 0), usable in a `static` (all-zero bytes, so
    /// it lands in `.bss`): fill it in place with [`DNet::reset`] or
    /// [`DNet::reset_from_cnet`].
    pub const fn empty() -> Self {
        DNet {
            c0: Point3([R::ZERO; 3]),
            sectors: Vec::new(),
        }
    }

    /// A d-net from `12n` nodes, sector by sector in the §2 order. `c0`: the
    /// limit point if known, else computed by formula (4).
    /// Errors, in this order: [`Error::WrongLength`] (not a multiple of 12),
    /// [`Error::ValenceTooSmall`], [`Error::ValenceUnsupported`], [`Error::NonFinite`].
    pub fn new(nodes: &[[R; 3]], c0: Option<[R; 3]>) -> Result<Self, Error> {
        let mut net = Self::empty();
        net.reset(nodes, c0)?;
        Ok(net)
    }

    /// A d-net from flat coordinates (`12n` nodes as `x, y, z` triples).
    /// Errors as [`DNet::new`], with [`Error::WrongLength`] counted in
    /// coordinates (a multiple of 36).
    pub fn from_flat(coords: &[R], c0: Option<[R; 3]>) -> Result<Self, Error> {
        let mut net = Self::empty();
        net.reset_flat(coords, c0)?;
        Ok(net)
    }

    /// A d-net from `n` sectors of 12 nodes; `c0` as in [`DNet::new`].
    pub fn from_sectors(sectors: &[[[R; 3]; D_SECTOR]], c0: Option<[R; 3]>) -> Result<Self, Error> {
        let mut net = Self::empty();
        net.reset_sectors(sectors, c0)?;
        Ok(net)
    }

    /// [`DNet::new`] in place: loads the d-net into `self`, whatever it held.
    /// Every check runs before anything is written, so on error `self` is
    /// unchanged; stack use is a few words.
    pub fn reset(&mut self, nodes: &[[R; 3]], c0: Option<[R; 3]>) -> Result<(), Error> {
        sector_count::<D_SECTOR>(nodes.len())?;
        let (chunks, _) = nodes.as_chunks::<D_SECTOR>();
        self.reset_sectors(chunks, c0)
    }

    /// [`DNet::from_flat`] in place; on error `self` is unchanged.
    pub fn reset_flat(&mut self, coords: &[R], c0: Option<[R; 3]>) -> Result<(), Error> {
        sector_count::<{ 3 * D_SECTOR }>(coords.len())?;
        self.reset(triples(coords)?, c0)
    }

    /// [`DNet::from_sectors`] in place; on error `self` is unchanged.
    pub fn reset_sectors(
        &mut self,
        sectors: &[[[R; 3]; D_SECTOR]],
        c0: Option<[R; 3]>,
    ) -> Result<(), Error> {
        check_valence(sectors.len())?;
        if !sectors.iter().flatten().all(finite) || !c0.as_ref().is_none_or(finite) {
            return Err(Error::NonFinite);
        }
        let c0 = match c0 {
            Some(p) => Point3(p),
            None => fitted_limit(sectors.iter().map(|s| s.map(Point3))),
        };
        if !c0.is_finite() {
            return Err(Error::NonFinite);
        }
        self.c0 = c0;
        fill(&mut self.sectors, sectors)
    }

    /// [`CNet::to_dnet`] in place: the degree-raised d-net (§3), `c0` by (3).
    /// Infallible like `to_dnet` (see there for when it is not finite).
    pub fn reset_from_cnet(&mut self, net: &CNet<R>) {
        net.raise_into(self);
    }

    /// Copies `other` into `self` sector by sector (no net-sized temporary,
    /// unlike `*self = other.clone()`).
    pub(crate) fn assign(&mut self, other: &DNet<R>) {
        self.c0 = other.c0;
        self.sectors.clear();
        for sec in other.sectors.iter() {
            // Cannot fail: both nets have the same capacity.
            let _ = self.sectors.push(*sec);
        }
    }

    /// The valence `n`.
    #[inline]
    pub fn valence(&self) -> usize {
        self.sectors.len()
    }
    /// The limit point `c0` (fixed by construction, unchanged by every step).
    #[inline]
    pub fn c0(&self) -> Point3<R> {
        self.c0
    }
    /// Sector `s` (`s < n`), or `None`.
    #[inline]
    pub fn sector(&self, s: usize) -> Option<&DSector<R>> {
        self.sectors.get(s)
    }
    /// All sectors.
    #[inline]
    pub fn sectors(&self) -> &[DSector<R>] {
        &self.sectors
    }
    /// Node `d_ij` of sector `s` (`i ≤ 3`, `j ≤ 2`), or `None`.
    #[inline]
    pub fn node(&self, s: usize, i: usize, j: usize) -> Option<Point3<R>> {
        if i > 3 || j > 2 {
            return None;
        }
        self.sectors.get(s)?.get(i + 4 * j).copied()
    }
    /// `true` when every node and `c0` are finite.
    pub fn is_finite(&self) -> bool {
        self.c0.is_finite() && self.sectors.iter().flatten().all(|p| p.is_finite())
    }

    /// The limit point fitted to this d-net by formula (4) (§4). For a d-net
    /// made by [`CNet::to_dnet`] it equals (3) of that c-net (up to rounding).
    pub fn fitted_limit(&self) -> Point3<R> {
        fitted_limit(self.sectors.iter().copied())
    }
}

/// Formula (4) over `n` sectors of nodes (`n` = the iterator's length).
fn fitted_limit<R: Real>(sectors: impl ExactSizeIterator<Item = DSector<R>>) -> Point3<R> {
    let w = limit_weights(sectors.len());
    let mut origin = None;
    let mut acc = Point3::ZERO;
    for sec in sectors {
        let o = *origin.get_or_insert(sec[10]);
        for (p, wk) in sec.iter().zip(w.iter()) {
            acc += (*p - o) * *wk;
        }
    }
    origin.unwrap_or(Point3::ZERO) + acc
}

/// Replaces the points of `out` by `sectors` (at most [`MAX_VALENCE`], checked
/// by the caller; [`Error::ValenceUnsupported`] otherwise, `out` then cleared).
fn fill<R: Real, const K: usize>(
    out: &mut Vec<[Point3<R>; K], MAX_VALENCE>,
    sectors: &[[[R; 3]; K]],
) -> Result<(), Error> {
    out.clear();
    for s in sectors {
        out.push(s.map(Point3))
            .map_err(|_| Error::ValenceUnsupported {
                valence: sectors.len(),
            })?;
    }
    Ok(())
}

/// The per-sector weights `e_ij / γ_n` of formula (4), node order `i + 4j`.
fn limit_weights<R: Real>(n: usize) -> [R; D_SECTOR] {
    // Integers (n ≤ 10: |e| < 4·10^6 < 2^24). γ = 16·γ' with γ' < 2^24, so
    // e/γ = (e/γ')/16 is one rounding of an exact rational (`Real::ratio`)
    // scaled exactly by 1/16.
    // Callers check n ≤ MAX_VALENCE; the clamp keeps i32 in range regardless.
    let nn = n.min(MAX_VALENCE) as i32;
    let (g16, e00, e20, e22, e30, e31, e32) = if n == 3 {
        (5_820, 11, -73, 10_643, -66, 396, 19_062)
    } else {
        let e30 = 336 * (153 * nn - 448);
        (
            11_155 * nn * (nn + 5),
            2587 * nn - 8377,
            19_339 * nn - 53_929,
            157_051 * nn + 50_279,
            e30,
            -6 * e30,
            48 * (8483 * nn - 5008),
        )
    };
    let (e10, e11, e21) = (-6 * e00, 36 * e00, -6 * e20);
    // 00 10 20 30 01 11 21 31 02 12 22 32
    let e: [i32; D_SECTOR] = [e00, e10, e20, e30, e10, e11, e21, e31, e20, e21, e22, e32];
    let sixteenth = R::ratio(1, 16);
    e.map(|x| R::ratio(x, g16) * sixteenth)
}
