//! [`SurfaceStats`]: a sink that counts what an evaluation gives — patches
//! per kind and per level, caps per scheme and valence, the rings the caps
//! emitted — and whether every point was finite; [`PatchCounts`]: a sink
//! that counts only patches per kind (no allocation, nothing else read).

use crate::evaluate::{CapRecord, PatchKind, PatchRecord, SurfaceSink};
use crate::mem::{self, OutOfMemory};
use crate::plan::Scheme;
use crate::tessellate::PatchGeometry;
use alloc::vec::Vec;
use capdiv::Real;

/// Patches per kind; as a [`SurfaceSink`] it counts each patch it is given
/// by its [`PatchRecord::kind`] and ignores caps.
///
/// ```
/// use capdiv_mesh::sinks::PatchCounts;
/// use capdiv_mesh::{samples, Evaluator, PlanOptions, SurfacePlan};
///
/// // A cube: eight EG caps of 3 sectors, 3 patches per sector and ring.
/// let cube = samples::cube();
/// let plan = SurfacePlan::for_mesh(&cube, PlanOptions { depth: 2, ..Default::default() })?;
/// let mut counts = PatchCounts::default();
/// Evaluator::<f64>::new(&plan).unwrap().evaluate(&cube.vertices, &mut counts).unwrap();
/// assert_eq!(counts.eg, 8 * 3 * 3 * 2);
/// assert_eq!(counts.total as u64, plan.patch_count());
/// # Ok::<(), capdiv_mesh::MeshError>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PatchCounts {
    /// B-spline patches of regular faces ([`PatchKind::Regular`]).
    pub regular: usize,
    /// C²PS ring patches ([`PatchKind::C2ps`]).
    pub c2ps: usize,
    /// EG ring patches ([`PatchKind::Eg`]).
    pub eg: usize,
    /// Catmull-Clark ring patches ([`PatchKind::CatmullClark`]).
    pub catmull_clark: usize,
    /// All.
    pub total: usize,
}

impl PatchCounts {
    /// Counts one patch of `kind`.
    pub fn add(&mut self, kind: PatchKind) {
        match kind {
            PatchKind::Regular => self.regular += 1,
            PatchKind::C2ps => self.c2ps += 1,
            PatchKind::Eg => self.eg += 1,
            PatchKind::CatmullClark => self.catmull_clark += 1,
        }
        self.total += 1;
    }

    /// The patches of `kind` counted.
    pub fn of(&self, kind: PatchKind) -> usize {
        match kind {
            PatchKind::Regular => self.regular,
            PatchKind::C2ps => self.c2ps,
            PatchKind::Eg => self.eg,
            PatchKind::CatmullClark => self.catmull_clark,
        }
    }
}

impl<R> SurfaceSink<R> for PatchCounts {
    fn patch(&mut self, p: &PatchRecord<R>) {
        self.add(p.kind);
    }
    fn cap(&mut self, _: &CapRecord<R>) {}
}

/// Caps of one scheme and valence.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CapCount {
    /// The scheme.
    pub scheme: Scheme,
    /// Valence in the input ([`CapRecord::valence`]).
    pub valence: usize,
    /// How many.
    pub count: usize,
}

/// Counts of a surface, taken as its records pass.
#[derive(Clone, Debug)]
pub struct SurfaceStats {
    /// Patches per kind.
    pub patches: PatchCounts,
    /// Patches per level ([`PatchRecord::level`] is the index), to the
    /// deepest level met.
    pub levels: Vec<usize>,
    /// Caps per scheme and valence, in the order first met.
    pub caps: Vec<CapCount>,
    /// Fewest and most rings a cap emitted (`None`: no cap).
    pub rings: Option<[u32; 2]>,
    /// Whether every control point and every cap's limit point was finite.
    pub finite: bool,
    /// The first growth the allocator refused.
    refused: Option<OutOfMemory>,
}

impl Default for SurfaceStats {
    fn default() -> Self {
        Self::new()
    }
}

impl SurfaceStats {
    /// No record counted yet (and nothing not finite).
    pub fn new() -> Self {
        SurfaceStats {
            patches: PatchCounts::default(),
            levels: Vec::new(),
            caps: Vec::new(),
            rings: None,
            finite: true,
            refused: None,
        }
    }

    /// Caps of every scheme and valence.
    pub fn cap_total(&self) -> usize {
        self.caps.iter().map(|c| c.count).sum()
    }

    /// The first allocation refused, if any (the level and cap counts are
    /// then incomplete; the patch counts are not).
    pub fn refused(&self) -> Option<OutOfMemory> {
        self.refused
    }

    fn count_level(&mut self, level: usize) -> Result<(), OutOfMemory> {
        if self.levels.len() <= level {
            let len = level
                .checked_add(1)
                .ok_or(OutOfMemory::of::<usize>(usize::MAX))?;
            let more = len - self.levels.len();
            mem::reserve(&mut self.levels, more)?;
            self.levels.resize(len, 0);
        }
        self.levels[level] += 1;
        Ok(())
    }

    fn count_cap(&mut self, scheme: Scheme, valence: usize) -> Result<(), OutOfMemory> {
        match self
            .caps
            .iter_mut()
            .find(|k| k.scheme == scheme && k.valence == valence)
        {
            Some(k) => k.count += 1,
            None => mem::push(
                &mut self.caps,
                CapCount {
                    scheme,
                    valence,
                    count: 1,
                },
            )?,
        }
        Ok(())
    }
}

/// Whether every control point of `g` is finite.
fn finite_geometry<R: Real>(g: &PatchGeometry<R>) -> bool {
    match g {
        PatchGeometry::Cubic(t) => t.points.iter().flatten().all(|q| q.is_finite()),
        PatchGeometry::Quartic(t) => t.points.iter().flatten().all(|q| q.is_finite()),
    }
}

impl<R: Real> SurfaceSink<R> for SurfaceStats {
    fn patch(&mut self, p: &PatchRecord<R>) {
        self.finite &= finite_geometry(&p.geometry);
        self.patches.add(p.kind);
        if self.refused.is_none() {
            self.refused = self.count_level(p.level as usize).err();
        }
    }
    fn cap(&mut self, c: &CapRecord<R>) {
        self.finite &= c.limit.is_finite();
        self.rings = Some(match self.rings {
            None => [c.rings; 2],
            Some([lo, hi]) => [lo.min(c.rings), hi.max(c.rings)],
        });
        if self.refused.is_none() {
            self.refused = self.count_cap(c.scheme, c.valence).err();
        }
    }
}
