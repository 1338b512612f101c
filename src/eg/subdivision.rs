//! `EgSubdivision`: the state of an EG cap — the current d-net, the previous
//! one (for the last ring, §9), the rule, the level.

use super::net::{CNet, DNet};
use super::refine::{refine, Rule};
use super::ring::{ring_patch, PATCHES_PER_SECTOR};
use super::rule::RuleTable;
use crate::bezier::BiquarticPatch;
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;

/// An EG subdivision in progress (spec EG.md §5–§9).
///
/// Memory: two [`DNet`]s and a borrowed table, independent of the valence
/// (≈ 2.9 KiB for `f32`, 5.8 KiB for `f64`). [`EgSubdivision::step`] builds
/// the new net in one more `DNet` on the stack, so a failing step leaves the
/// state untouched.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EgSubdivision<'t, R> {
    table: Option<RuleTable<'t>>,
    prev: DNet<R>,
    cur: DNet<R>,
    level: u32,
}

impl<R: Real> EgSubdivision<'static, R> {
    /// Starts from a d-net with the built-in rule of its valence: the §7
    /// table for n = 3, 5; the regular rules for n = 4 (see
    /// [`EgSubdivision::step`]). [`Error::ValenceUnsupported`] for n = 6..10,
    /// whose rules must come from the caller ([`EgSubdivision::with_table`]);
    /// [`Error::NonFinite`] for a net with a non-finite node (only
    /// [`CNet::to_dnet`] of a c-net whose coordinate differences overflow can
    /// make one).
    pub fn new(net: DNet<R>) -> Result<Self, Error> {
        if !net.is_finite() {
            return Err(Error::NonFinite);
        }
        let n = net.valence();
        let table = RuleTable::builtin(n);
        if table.is_none() && n != 4 {
            return Err(Error::ValenceUnsupported { valence: n });
        }
        Ok(Self::start(net, table))
    }

    /// [`EgSubdivision::new`] of the c-net's degree-raised d-net (§3), `c0` by (3).
    pub fn from_cnet(net: &CNet<R>) -> Result<Self, Error> {
        Self::new(net.to_dnet())
    }
}

impl<'t, R: Real> EgSubdivision<'t, R> {
    /// Starts from a d-net with a checked table of the same valence
    /// ([`RuleTable::new`] or [`RuleTable::builtin`]); [`Error::TableShape`]
    /// when the valences differ, [`Error::NonFinite`] as in [`EgSubdivision::new`].
    pub fn with_table(net: DNet<R>, table: RuleTable<'t>) -> Result<Self, Error> {
        if !net.is_finite() {
            return Err(Error::NonFinite);
        }
        if table.valence() != net.valence() {
            return Err(Error::TableShape);
        }
        Ok(Self::start(net, Some(table)))
    }

    fn start(net: DNet<R>, table: Option<RuleTable<'t>>) -> Self {
        EgSubdivision {
            table,
            prev: net.clone(),
            cur: net,
            level: 0,
        }
    }

    /// One step `d → d̃` (§5, §6): outer nodes by the regular bi-4 rules, inner
    /// nodes by the EG rule (7); `c0` is unchanged.
    ///
    /// Valence 4 has no EG rule: every node, inner ones included, follows the
    /// regular rules, with the lattice node at the center (absent from the
    /// d-net) set so that the spline's value there is `c0`. For a d-net raised
    /// from a regular c-net this is exact bi-4 refinement of the degree-raised
    /// bicubic, and `c0` stays its value at the center.
    ///
    /// [`Error::NonFinite`] if a coordinate overflows; the state is then unchanged.
    pub fn step(&mut self) -> Result<(), Error> {
        let rule = match &self.table {
            Some(t) => Rule::Eg(t),
            None => Rule::Regular,
        };
        let mut next = self.cur.clone();
        refine(&self.cur, rule, &mut next)?;
        if !next.is_finite() {
            return Err(Error::NonFinite);
        }
        self.prev = core::mem::replace(&mut self.cur, next);
        self.level = self.level.saturating_add(1);
        Ok(())
    }

    /// The current d-net.
    #[inline]
    pub fn net(&self) -> &DNet<R> {
        &self.cur
    }
    /// The d-net before the last step (`None` before the first step).
    #[inline]
    pub fn previous(&self) -> Option<&DNet<R>> {
        (self.level > 0).then_some(&self.prev)
    }
    /// The limit point `c0` (§4), fixed for all steps.
    #[inline]
    pub fn c0(&self) -> Point3<R> {
        self.cur.c0
    }
    /// The valence.
    #[inline]
    pub fn valence(&self) -> usize {
        self.cur.valence()
    }
    /// Steps taken.
    #[inline]
    pub fn level(&self) -> u32 {
        self.level
    }
    /// The rule table in use (`None`: valence 4, regular rules).
    #[inline]
    pub fn table(&self) -> Option<&RuleTable<'t>> {
        self.table.as_ref()
    }

    /// Patches in the last step's ring: `3n`, or 0 before the first step.
    #[inline]
    pub fn ring_len(&self) -> usize {
        if self.level == 0 {
            0
        } else {
            self.valence().saturating_mul(PATCHES_PER_SECTOR)
        }
    }

    /// Patch `k` of the last step's ring (§9): sector `k / 3`, piece `k % 3`
    /// (0: `[½,1]×[0,½]`, 1: `[0,½]×[½,1]`, 2: `[½,1]²` of that sector, in
    /// level-0 c-units × 2^−(level−1)). [`Error::OutOfDomain`] for `k ≥ ring_len()`.
    pub fn ring_patch(&self, k: usize) -> Result<BiquarticPatch<R>, Error> {
        if k >= self.ring_len() {
            return Err(Error::OutOfDomain);
        }
        ring_patch(&self.prev, &self.cur, k)
    }

    /// Where patch `k` of the last step's ring lies: its sector and square in
    /// that sector's level-0 c-units (patch `u` along `x`, `v` along `y`).
    /// [`Error::OutOfDomain`] for `k ≥ ring_len()`.
    pub fn ring_patch_domain(&self, k: usize) -> Result<PatchDomain, Error> {
        if k >= self.ring_len() {
            return Err(Error::OutOfDomain);
        }
        // Level-(m−1) hole [0, 2^−(m−1)]²; the ring's pieces have half its size.
        let exponent = i32::try_from(self.level).unwrap_or(i32::MAX);
        let size = libm::pow(0.5, f64::from(exponent));
        let (x0, y0) = match k % PATCHES_PER_SECTOR {
            0 => (size, 0.0),
            1 => (0.0, size),
            _ => (size, size),
        };
        Ok(PatchDomain {
            sector: k / PATCHES_PER_SECTOR,
            x0,
            y0,
            size,
        })
    }

    /// All patches of the last step's ring, in index order.
    pub fn ring_patches(&self) -> EgRingPatches<'_, 't, R> {
        EgRingPatches { sub: self, next: 0 }
    }
}

/// The square `[x0, x0+size] × [y0, y0+size]` of a ring patch in its sector's
/// level-0 c-units (§9: the hole of the level-m d-net is `[0, 2⁻ᵐ]²`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PatchDomain {
    /// The sector.
    pub sector: usize,
    /// Lower `x` (along spoke `sector`).
    pub x0: f64,
    /// Lower `y` (along spoke `sector + 1`).
    pub y0: f64,
    /// Side length.
    pub size: f64,
}

/// Iterator over the last ring's patches ([`EgSubdivision::ring_patches`]).
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EgRingPatches<'a, 't, R> {
    sub: &'a EgSubdivision<'t, R>,
    next: usize,
}

impl<R: Real> Iterator for EgRingPatches<'_, '_, R> {
    type Item = BiquarticPatch<R>;
    fn next(&mut self) -> Option<Self::Item> {
        let p = self.sub.ring_patch(self.next).ok()?;
        self.next = self.next.saturating_add(1);
        Some(p)
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.sub.ring_len().saturating_sub(self.next);
        (left, Some(left))
    }
}

impl<R: Real> ExactSizeIterator for EgRingPatches<'_, '_, R> {}

impl<R: Real> DNet<R> {
    /// One step of this net, returned as a new net (stateless form of
    /// [`EgSubdivision::step`]). `table`: `None` for the built-in rule
    /// (n = 3, 5; regular for n = 4; [`Error::ValenceUnsupported`] for 6..10),
    /// or a checked table of the same valence ([`Error::TableShape`] otherwise).
    pub fn refined(&self, table: Option<&RuleTable<'_>>) -> Result<DNet<R>, Error> {
        let n = self.valence();
        let builtin = RuleTable::builtin(n);
        let rule = match (table, builtin.as_ref()) {
            (Some(t), _) if t.valence() != n => return Err(Error::TableShape),
            (Some(t), _) => Rule::Eg(t),
            (None, Some(t)) => Rule::Eg(t),
            (None, None) if n == 4 => Rule::Regular,
            (None, None) => return Err(Error::ValenceUnsupported { valence: n }),
        };
        let mut next = self.clone();
        refine(self, rule, &mut next)?;
        if !next.is_finite() {
            return Err(Error::NonFinite);
        }
        Ok(next)
    }
}
