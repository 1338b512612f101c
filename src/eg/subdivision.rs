//! `EgSubdivision`: the state of an EG cap — the current d-net, the previous
//! one (for the last ring, §9), the rule, the level.

use super::fourier::FourierRule;
use super::net::{check_valence, CNet, DNet};
use super::ring::{ring_patch, OwnNodes, PATCHES_PER_SECTOR};
use super::rule::RuleTable;
use super::step::{cannot_overflow, step_into, step_is_finite, Rule};
use crate::bezier::BiquarticPatch;
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;
use core::iter::FusedIterator;

/// An EG subdivision in progress (docs/math/eg.md §5–§9).
///
/// Memory: two [`DNet`]s (the current one and the previous one, which the
/// last ring needs, §9) and a borrowed table, independent of the valence
/// (≈ 2.9 KiB for `f32`, 5.8 KiB for `f64`). [`EgSubdivision::step`] writes
/// the new net over the previous one, so it needs no net-sized temporary;
/// where stack is scarce, keep an [`EgSubdivision::empty`] in a `static` and
/// load it with [`EgSubdivision::reset`].
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EgSubdivision<'t, R> {
    table: Option<RuleTable<'t>>,
    /// The current net is `nets[1]` when `flip`, else `nets[0]`; the other
    /// one is the previous net (meaningful for `level > 0`).
    nets: [DNet<R>; 2],
    flip: bool,
    level: u32,
}

/// What an EG subdivision starts from: a [`CNet`] (degree-raised to its
/// d-net, §3, `c0` by (3), written in place without a d-net temporary) or a
/// [`DNet`] (copied). Sealed.
pub trait EgStart<R>: sealed::Start<R> {}

mod sealed {
    use super::{CNet, DNet};
    use crate::real::Real;

    pub trait Start<R> {
        fn valence(&self) -> usize;
        /// The level-0 d-net is finite (checked before anything is written).
        fn finite(&self) -> bool;
        fn write(&self, out: &mut DNet<R>);
    }

    impl<R: Real> Start<R> for CNet<R> {
        fn valence(&self) -> usize {
            CNet::valence(self)
        }
        fn finite(&self) -> bool {
            self.raises_finite()
        }
        fn write(&self, out: &mut DNet<R>) {
            self.raise_into(out)
        }
    }

    impl<R: Real> Start<R> for DNet<R> {
        fn valence(&self) -> usize {
            DNet::valence(self)
        }
        fn finite(&self) -> bool {
            self.is_finite()
        }
        fn write(&self, out: &mut DNet<R>) {
            out.assign(self)
        }
    }
}

impl<R: Real> EgStart<R> for CNet<R> {}
impl<R: Real> EgStart<R> for DNet<R> {}

/// The built-in rule of valence `n` (`None`: n = 4, regular).
fn builtin_rule(n: usize) -> Result<Option<RuleTable<'static>>, Error> {
    let table = RuleTable::builtin(n);
    if table.is_none() && n != 4 {
        return Err(Error::ValenceUnsupported { valence: n });
    }
    Ok(table)
}

impl<'t, R: Real> EgSubdivision<'t, R> {
    /// An empty subdivision (valence 0, no rule), usable in a `static`
    /// (all-zero bytes, so it lands in `.bss`): load it in place with
    /// [`EgSubdivision::reset`]. Its [`EgSubdivision::step`]
    /// returns [`Error::ValenceTooSmall`]; its ring is empty.
    pub const fn empty() -> Self {
        EgSubdivision {
            table: None,
            nets: [DNet::empty(), DNet::empty()],
            flip: false,
            level: 0,
        }
    }

    /// Starts from a c-net or a d-net ([`EgStart`]) at level 0 with the rule
    /// `table`: a checked table of the net's valence ([`RuleTable::new`] or
    /// [`RuleTable::builtin`]), or `None` for the built-in rule of the
    /// valence — the §7 table for n = 3, 5, the regular rules for n = 4 (see
    /// [`EgSubdivision::step`]).
    ///
    /// Errors, in this order: [`Error::ValenceTooSmall`] for an empty net;
    /// [`Error::NonFinite`] when the level-0 d-net has a non-finite node (a
    /// c-net whose raised net would overflow, checked by computing it once
    /// without storing it; a d-net from [`CNet::to_dnet`] of such a c-net);
    /// with `None`, [`Error::ValenceUnsupported`] for n = 6..10, whose rules
    /// must come from the caller; with a table, [`Error::TableShape`] when
    /// its valence is not the net's.
    ///
    /// ```
    /// use capdiv::eg::{CNet, EgSubdivision};
    /// use capdiv::Error;
    /// // Valence 5, symmetric under a turn by 2π/5: sector s is sector 0
    /// // turned by 2πs/5; 6 nodes per sector in the §1 order.
    /// let n = 5;
    /// let mut nodes = Vec::new();
    /// for s in 0..n {
    ///     let a = s as f64 * core::f64::consts::TAU / n as f64;
    ///     for (x, y) in [(1.0, 0.0), (2.0, 0.0), (1.0, 1.0), (2.0, 1.0), (1.0, 2.0), (2.0, 2.0)] {
    ///         let (t, r) = (a + f64::atan2(y, x) * 4.0 / n as f64, f64::hypot(x, y));
    ///         nodes.push([r * t.cos(), r * t.sin(), 0.1 * r * r]);
    ///     }
    /// }
    /// let net = CNet::new([0.0; 3], &nodes)?;
    /// let eg = EgSubdivision::new(&net, None)?; // the built-in §7 rule of valence 5
    /// assert_eq!((eg.valence(), eg.level(), eg.ring_len()), (5, 0, 0));
    /// assert_eq!(eg.limit(), net.limit()); // c0 by (3)
    /// // Valence 6 has no built-in rule: the caller must pass a table.
    /// let six = CNet::new([0.0; 3], &[[1.0, 0.0, 0.0]; 36])?;
    /// assert_eq!(
    ///     EgSubdivision::new(&six, None).unwrap_err(),
    ///     Error::ValenceUnsupported { valence: 6 }
    /// );
    /// # Ok::<(), capdiv::Error>(())
    /// ```
    pub fn new<N: EgStart<R>>(net: &N, table: Option<RuleTable<'t>>) -> Result<Self, Error> {
        let mut sub = Self::empty();
        sub.reset(net, table)?;
        Ok(sub)
    }

    /// [`EgSubdivision::new`] in place: restarts at level 0, whatever `self`
    /// held. Errors as `new`; every check runs before anything is written, so
    /// on error `self` is unchanged. Stack use is a few words.
    pub fn reset<N: EgStart<R>>(
        &mut self,
        net: &N,
        table: Option<RuleTable<'t>>,
    ) -> Result<(), Error> {
        let n = net.valence();
        check_valence(n)?;
        if !net.finite() {
            return Err(Error::NonFinite);
        }
        let table = match table {
            Some(t) if t.valence() != n => return Err(Error::TableShape),
            Some(t) => Some(t),
            None => builtin_rule(n)?,
        };
        self.install(table, |cur| net.write(cur));
        Ok(())
    }

    /// Level 0 with `table` and the net `write` puts in the current slot.
    fn install(&mut self, table: Option<RuleTable<'t>>, write: impl FnOnce(&mut DNet<R>)) {
        self.table = table;
        self.flip = false;
        self.level = 0;
        let [cur, prev] = &mut self.nets;
        write(cur);
        // No previous net at level 0 (the first step overwrites this one).
        prev.c0 = cur.c0;
        prev.sectors.clear();
    }

    /// `(current, previous)`.
    #[inline]
    fn pair(&self) -> (&DNet<R>, &DNet<R>) {
        let [a, b] = &self.nets;
        if self.flip {
            (b, a)
        } else {
            (a, b)
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
    /// The new net is written over the previous one (which becomes the
    /// current one's predecessor), so no net-sized temporary is needed.
    /// [`Error::NonFinite`] if a coordinate would overflow: decided before
    /// anything is written (nets whose coordinates are all below `MAX/1024`
    /// cannot overflow; others are first refined without storing), so the
    /// state is then unchanged. [`Error::ValenceTooSmall`] on an
    /// [`EgSubdivision::empty`] one.
    ///
    /// ```
    /// # use capdiv::eg::{CNet, EgSubdivision};
    /// # let n = 5;
    /// # let mut nodes = Vec::new();
    /// # for s in 0..n {
    /// #     let a = s as f64 * core::f64::consts::TAU / n as f64;
    /// #     for (x, y) in [(1.0, 0.0), (2.0, 0.0), (1.0, 1.0), (2.0, 1.0), (1.0, 2.0), (2.0, 2.0)] {
    /// #         let (t, r) = (a + f64::atan2(y, x) * 4.0 / n as f64, f64::hypot(x, y));
    /// #         nodes.push([r * t.cos(), r * t.sin(), 0.1 * r * r]);
    /// #     }
    /// # }
    /// # let net = CNet::new([0.0; 3], &nodes)?;
    /// let mut eg = EgSubdivision::new(&net, None)?;
    /// let c0 = eg.limit();
    /// eg.step()?;
    /// assert_eq!((eg.level(), eg.ring_len()), (1, 3 * 5));
    /// assert_eq!(eg.limit(), c0); // c0 is fixed (§5)
    /// assert_eq!(eg.previous().unwrap(), &net.to_dnet()); // the level-0 d-net (§3)
    /// # Ok::<(), capdiv::Error>(())
    /// ```
    pub fn step(&mut self) -> Result<(), Error> {
        let n = self.valence();
        check_valence(n)?;
        let rule = match &self.table {
            Some(t) if t.valence() != n => return Err(Error::TableShape),
            Some(t) => Rule::Eg(t),
            None => Rule::Regular,
        };
        let [a, b] = &mut self.nets;
        let (cur, out) = if self.flip { (&*b, a) } else { (&*a, b) };
        if !cannot_overflow(cur) && !step_is_finite(cur, rule)? {
            return Err(Error::NonFinite);
        }
        // Finite by the check above (the unit tests of `step` pin both
        // checks to the values `step_into` stores).
        step_into(cur, rule, out)?;
        self.flip = !self.flip;
        self.level = self.level.saturating_add(1);
        Ok(())
    }

    /// [`EgSubdivision::step`] with rule (7) applied through the Fourier
    /// transform over the sectors ([`FourierRule`], built once per table and
    /// shared by every cap of its valence): about half the operations, the
    /// same result up to rounding (the kernel-vs-matrix tests hold both).
    /// The table applied is `rule`'s, normally the one this subdivision was
    /// set up with ([`FourierRule::new`] of [`EgSubdivision::table`]).
    ///
    /// Errors as [`EgSubdivision::step`], and [`Error::TableShape`] when
    /// `rule`'s valence is not the net's (always for valence 4, which has no
    /// EG rule), before anything is written. A net with a coordinate beyond
    /// `MAX/1024` takes the dense step with `rule`'s table (whose check-first
    /// path decides overflow without writing).
    pub fn step_fourier(&mut self, rule: &FourierRule<'_, R>) -> Result<(), Error> {
        let n = self.valence();
        check_valence(n)?;
        if rule.valence() != n || self.table.is_none() {
            return Err(Error::TableShape);
        }
        let [a, b] = &mut self.nets;
        let (cur, out) = if self.flip { (&*b, a) } else { (&*a, b) };
        if cannot_overflow(cur) {
            rule.step_into(cur, out)?;
        } else {
            // As `step`: decided without writing, with `rule`'s table.
            let table = Rule::Eg(rule.table());
            if !step_is_finite(cur, table)? {
                return Err(Error::NonFinite);
            }
            step_into(cur, table, out)?;
        }
        self.flip = !self.flip;
        self.level = self.level.saturating_add(1);
        Ok(())
    }

    /// The current d-net.
    #[inline]
    pub fn net(&self) -> &DNet<R> {
        self.pair().0
    }
    /// The d-net before the last step (`None` before the first step).
    #[inline]
    pub fn previous(&self) -> Option<&DNet<R>> {
        (self.level > 0).then_some(self.pair().1)
    }
    /// The limit point at the center, `c0` (§4), fixed for all steps. Always
    /// finite ([`EgSubdivision::new`] checks the net, and a step that would
    /// overflow is refused), so it needs no [`Point3::finite`] check, unlike
    /// [`crate::CcCap::limit`] and [`crate::PoleJet`].
    ///
    /// ```
    /// # use capdiv::eg::{CNet, EgSubdivision};
    /// # let n = 5;
    /// # let mut nodes = Vec::new();
    /// # for s in 0..n {
    /// #     let a = s as f64 * core::f64::consts::TAU / n as f64;
    /// #     for (x, y) in [(1.0, 0.0), (2.0, 0.0), (1.0, 1.0), (2.0, 1.0), (1.0, 2.0), (2.0, 2.0)] {
    /// #         let (t, r) = (a + f64::atan2(y, x) * 4.0 / n as f64, f64::hypot(x, y));
    /// #         nodes.push([r * t.cos(), r * t.sin(), 0.1 * r * r]);
    /// #     }
    /// # }
    /// # let net = CNet::new([0.0; 3], &nodes)?;
    /// // The net is symmetric under a turn by 2π/5 about the z axis: so is its
    /// // limit, which therefore lies on the axis.
    /// let eg = EgSubdivision::new(&net, None)?;
    /// let [x, y, z] = eg.limit().0;
    /// assert!(x.abs() < 1e-14 && y.abs() < 1e-14 && z > 0.0);
    /// # Ok::<(), capdiv::Error>(())
    /// ```
    #[inline]
    pub fn limit(&self) -> Point3<R> {
        self.net().c0
    }
    /// The valence.
    #[inline]
    pub fn valence(&self) -> usize {
        self.net().valence()
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
    /// level-0 c-units × 2^−(level−1)); `u` along `x`, `v` along `y`.
    /// [`Error::OutOfDomain`] for `k ≥ ring_len()` (every `k` before the
    /// first step).
    pub fn ring_patch(&self, k: usize) -> Result<BiquarticPatch<R>, Error> {
        if k >= self.ring_len() {
            return Err(Error::OutOfDomain);
        }
        let (cur, prev) = self.pair();
        ring_patch(prev, cur, k, None)
    }

    /// Where patch `k` of the last step's ring lies: its sector and square in
    /// that sector's level-0 c-units (patch `u` along `x`, `v` along `y`).
    /// [`Error::OutOfDomain`] for `k ≥ ring_len()`.
    pub fn ring_patch_domain(&self, k: usize) -> Result<PatchDomain, Error> {
        if k >= self.ring_len() {
            return Err(Error::OutOfDomain);
        }
        Ok(PatchDomain::of_ring_patch(self.level, k))
    }

    /// All [`Self::ring_len`] patches of the last step's ring, in ring order
    /// ([`Self::ring_patch`]: `k = 3·sector + piece`); none before the first
    /// step.
    ///
    /// ```
    /// # use capdiv::eg::{CNet, EgSubdivision};
    /// # let n = 5;
    /// # let mut nodes = Vec::new();
    /// # for s in 0..n {
    /// #     let a = s as f64 * core::f64::consts::TAU / n as f64;
    /// #     for (x, y) in [(1.0, 0.0), (2.0, 0.0), (1.0, 1.0), (2.0, 1.0), (1.0, 2.0), (2.0, 2.0)] {
    /// #         let (t, r) = (a + f64::atan2(y, x) * 4.0 / n as f64, f64::hypot(x, y));
    /// #         nodes.push([r * t.cos(), r * t.sin(), 0.1 * r * r]);
    /// #     }
    /// # }
    /// # let net = CNet::new([0.0; 3], &nodes)?;
    /// let mut eg = EgSubdivision::new(&net, None)?;
    /// eg.step()?;
    /// let ring: Vec<_> = eg.ring_patches().collect();
    /// assert_eq!(ring.len(), eg.ring_len());
    /// for (k, patch) in ring.iter().enumerate() {
    ///     assert_eq!(eg.ring_patch(k).as_ref(), Ok(patch));
    /// }
    /// // A sector's pieces join: piece 0 ([½,1]×[0,½]) meets piece 2 ([½,1]²)
    /// // along y = ½, piece 1 ([0,½]×[½,1]) meets piece 2 along x = ½.
    /// for s in 0..5 {
    ///     let [p0, p1, p2] = [&ring[3 * s], &ring[3 * s + 1], &ring[3 * s + 2]];
    ///     for t in [0.0, 0.3, 1.0] {
    ///         assert!(p0.position(t, 1.0)?.max_abs_diff(p2.position(t, 0.0)?) < 1e-12);
    ///         assert!(p1.position(1.0, t)?.max_abs_diff(p2.position(0.0, t)?) < 1e-12);
    ///     }
    /// }
    /// # Ok::<(), capdiv::Error>(())
    /// ```
    pub fn ring_patches(&self) -> EgRingPatches<'_, 't, R> {
        EgRingPatches {
            sub: self,
            next: 0,
            own: OwnNodes::empty(),
        }
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

impl PatchDomain {
    /// Patch `k` of the ring emitted by step `level` (sector `k / 3`, piece
    /// `k % 3`, §9): the level-(m−1) hole is `[0, 2^−(m−1)]²` and the ring's
    /// pieces have half its size. Shared by EG and Catmull-Clark caps.
    pub(crate) fn of_ring_patch(level: u32, k: usize) -> Self {
        // 2^−level exactly (0 past the subnormals), by exponent arithmetic.
        let exponent = i32::try_from(level).unwrap_or(i32::MAX);
        let size = libm::scalbn(1.0, -exponent);
        let (x0, y0) = match k % PATCHES_PER_SECTOR {
            0 => (size, 0.0),
            1 => (0.0, size),
            _ => (size, size),
        };
        PatchDomain {
            sector: k / PATCHES_PER_SECTOR,
            x0,
            y0,
            size,
        }
    }
}

/// Iterator over the last ring's patches, in ring order (`k = 3·sector +
/// piece`): [`EgSubdivision::ring_patches`].
/// Faster than [`EgSubdivision::ring_patch`] for every `k` (it shares the
/// regular nodes of a sector's 3 patches, 18 points of scratch), same patches.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EgRingPatches<'a, 't, R> {
    sub: &'a EgSubdivision<'t, R>,
    next: usize,
    /// The current sector's own-frame regular nodes, shared by its 3 patches.
    own: OwnNodes<R>,
}

impl<R: Real> Iterator for EgRingPatches<'_, '_, R> {
    type Item = BiquarticPatch<R>;
    fn next(&mut self) -> Option<Self::Item> {
        if self.next >= self.sub.ring_len() {
            return None;
        }
        let (cur, prev) = self.sub.pair();
        let p = ring_patch(prev, cur, self.next, Some(&mut self.own)).ok()?;
        self.next = self.next.saturating_add(1);
        Some(p)
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.sub.ring_len().saturating_sub(self.next);
        (left, Some(left))
    }
}

impl<R: Real> ExactSizeIterator for EgRingPatches<'_, '_, R> {}

impl<R: Real> FusedIterator for EgRingPatches<'_, '_, R> {}

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
        step_into(self, rule, &mut next)?;
        if !next.is_finite() {
            return Err(Error::NonFinite);
        }
        Ok(next)
    }
}
