//! `Evaluator`: runs a [`SurfacePlan`] on vertex positions and hands every
//! patch and cap to a [`SurfaceSink`]. All buffers and kernel nets are sized
//! once in [`Evaluator::new`]; [`Evaluator::evaluate`] allocates nothing, so a
//! caller repeats it whenever vertices move and the topology does not.
//!
//! Patches are given in their input face's own parameter square (see
//! [`crate::chart`]): `domain = [u0, u1, v0, v1]`, control point `[i][j]` with
//! `i` along `u`, `j` along `v`. Faces of a polar fan (triangles) use polar
//! coordinates instead: `u` is the distance from the pole in link units (0 at
//! the pole, 1 on the triangle's edge on the 1-link), `v` runs from the
//! triangle's first spoke (counter-clockwise order around the pole) to its
//! second.

use crate::chart::{Affine, FaceChart};
use crate::error::{Indices, Names};
use crate::facevarying::PatchUv;
use crate::mem;
use crate::plan::{ExtraordinaryCapPlan, PolarPlan, Scheme, SurfacePlan, Unit};
use crate::rings::{self, RingPatch};
use crate::tessellate::PatchGeometry;
use alloc::boxed::Box;
use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;
use capdiv::bezier::bspline_to_bezier_cubic;
use capdiv::eg::{CNet, EgSubdivision, FourierRule, PatchDomain, RuleTable};
use capdiv::{CcCap, Error, Point3, PolarNetBuf, PoleJet, Real, SliceStorage, TensorPatch};

/// What a patch is made by.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PatchKind {
    /// Uniform bicubic B-spline of a regular face.
    Regular,
    /// A C²PS ring patch.
    C2ps,
    /// An EG ring patch (bi-quartic).
    Eg,
    /// A Catmull-Clark ring patch.
    CatmullClark,
}

impl PatchKind {
    /// Every kind, in the order of the counts of
    /// [`crate::sinks::PatchCounts`].
    pub const ALL: [PatchKind; 4] = [
        PatchKind::Regular,
        PatchKind::C2ps,
        PatchKind::Eg,
        PatchKind::CatmullClark,
    ];

    /// Identifier used in JSON.
    pub fn id(self) -> &'static str {
        match self {
            PatchKind::Regular => "regular",
            PatchKind::C2ps => "c2ps",
            PatchKind::Eg => "eg",
            PatchKind::CatmullClark => "catmull-clark",
        }
    }
}

/// One patch of the surface.
#[derive(Clone, Debug)]
pub struct PatchRecord<R> {
    /// Its scheme.
    pub kind: PatchKind,
    /// Subdivision level relative to the input: the patch is `2^-level` of
    /// its input face across (refinement steps included).
    pub level: u32,
    /// The input face it lies in.
    pub face: u32,
    /// For input faces that are not quads (and not polar triangles): the
    /// corner whose sub-quad holds the patch ([`crate::chart`]).
    pub corner: Option<u8>,
    /// `[u0, u1, v0, v1]` in the face's (or sub-quad's) square.
    pub domain: [f64; 4],
    /// Bézier control points, oriented to the input face, relative to
    /// [`PatchRecord::origin`].
    pub geometry: PatchGeometry<R>,
    /// The point `geometry` is relative to: a control point is
    /// `origin + geometry`'s point. Zero (the control points absolute)
    /// unless the evaluator hands cap patches out relative to their cap's
    /// centre ([`Evaluator::set_relative_caps`]).
    pub origin: Point3<R>,
    /// Edges (bits as [`crate::tessellate::edge_bit`]) met by two patches of
    /// half this one's size: a tessellation samples them twice as finely.
    pub finer: u8,
    /// Edges (bits as [`crate::tessellate::edge_bit`]) bordering the cap's
    /// last hole, closed by triangles to [`PatchRecord::hole_point`].
    pub hole: u8,
    /// The cap's limit point, where `hole` edges are closed to (unused when
    /// `hole` is 0).
    pub hole_point: Point3<R>,
    /// Bit `k` (edges as [`crate::tessellate::edge_bit`] numbers them): edge
    /// `k` lies on the surface's boundary. Bit `4 + k`: corner
    /// `k` (where edge `k` starts) is a boundary vertex where exactly two
    /// patches meet. Set for regular patches of the analysed level (0
    /// elsewhere: unknown); a streaming welder lets go of samples there
    /// without waiting for the end ([`crate::tessellate::stream`]).
    pub boundary: u8,
    /// Index of the cap it belongs to (polar caps first, then EG and
    /// Catmull-Clark caps, in plan order), if any.
    pub cap: Option<u32>,
    /// Texture coordinates over the patch, for a surface that has them: the
    /// evaluator gives `None`; [`crate::FaceVarying::patch`] computes them
    /// from the record, and the tessellation carries them to its vertices.
    pub uv: Option<PatchUv>,
}

impl<R: Real> PatchRecord<R> {
    /// A patch of `kind` that is not a piece of an input mesh's face (a
    /// kernel configuration's ring or outer-region patch, a test's patch):
    /// level 0, face 0, the whole unit square as its domain, no finer or
    /// hole edge, no boundary, no cap, no UVs.
    pub fn new(kind: PatchKind, geometry: PatchGeometry<R>) -> Self {
        PatchRecord {
            kind,
            level: 0,
            face: 0,
            corner: None,
            domain: [0.0, 1.0, 0.0, 1.0],
            geometry,
            origin: Point3::ZERO,
            finer: 0,
            hole: 0,
            hole_point: Point3::ZERO,
            boundary: 0,
            cap: None,
            uv: None,
        }
    }
}

/// One cap's centre.
#[derive(Clone, Debug)]
pub struct CapRecord<R> {
    /// Index (as in [`PatchRecord::cap`]).
    pub index: u32,
    /// The input vertex at its centre, if it is one.
    pub vertex: Option<u32>,
    /// The input face whose centre it is, otherwise.
    pub face: Option<u32>,
    /// The scheme.
    pub scheme: Scheme,
    /// Valence in the input (for a refined pole, before refinement).
    pub valence: usize,
    /// Limit point.
    pub limit: Point3<R>,
    /// Unit normal at the limit point (C²PS: from the pole jet; EG: from the
    /// last ring; Catmull-Clark: the limit tangents), if not degenerate.
    pub normal: Option<Point3<R>>,
    /// Principal curvatures at the limit point: C²PS only (exact, spec
    /// docs/math/c2ps.md §4); EG and Catmull-Clark caps report none.
    pub principal_curvatures: Option<[R; 2]>,
    /// Rings emitted: the plan's depth, or fewer when the hole tolerance
    /// ([`Evaluator::set_hole_tolerance`]) was met earlier.
    pub rings: u32,
}

/// Receives the surface.
pub trait SurfaceSink<R> {
    /// One patch.
    fn patch(&mut self, p: &PatchRecord<R>);
    /// One cap (after its patches).
    fn cap(&mut self, c: &CapRecord<R>);
}

/// Why an evaluation failed.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum EvalError {
    /// `positions` does not have one entry per input vertex.
    WrongLength {
        /// Entries needed.
        expected: usize,
        /// Entries given.
        found: usize,
    },
    /// A coordinate is NaN or infinite.
    NonFinite {
        /// The vertex.
        vertex: usize,
    },
    /// A polar cap would exceed the largest net capacity.
    CapacityExceeded {
        /// The pole (input vertex).
        vertex: u32,
        /// Valence needed at the deepest level.
        needed: usize,
        /// The largest capacity.
        max: usize,
    },
    /// A point of the refined mesh or a phantom point exceeds `MAX/2` in
    /// magnitude (or is not finite): the refinement overflowed, or the
    /// regular patches formed from it could. Checked before any patch is
    /// emitted. Input coordinates of at most `MAX/32` never fail here:
    /// refined points are convex combinations of the input, and a phantom
    /// point (`2b − i`, mirrored twice at a corner: `4a − 2b − 2c + d`) is at
    /// most 9 times its magnitude.
    Overflow,
    /// The kernel refused a cap.
    Kernel {
        /// The cap's index.
        cap: u32,
        /// The input vertex at the cap's centre (`None`: a face centre).
        vertex: Option<u32>,
        /// The input face whose centre is the cap's centre, when `vertex`
        /// is `None`.
        face: Option<u32>,
        /// The kernel's error.
        error: Error,
    },
    /// A buffer of the evaluation could not be allocated.
    OutOfMemory {
        /// The size asked for.
        bytes: usize,
    },
}

impl From<crate::mem::OutOfMemory> for EvalError {
    fn from(e: crate::mem::OutOfMemory) -> Self {
        EvalError::OutOfMemory { bytes: e.bytes }
    }
}

impl EvalError {
    /// The one-line message, naming vertices and faces by `names`.
    pub fn describe(&self, names: &dyn Names) -> String {
        match self {
            EvalError::WrongLength { expected, found } => {
                format!("{found} positions given, the mesh has {expected} vertices")
            }
            EvalError::NonFinite { vertex } => {
                format!("{} has a coordinate that is not finite", names.vertex(*vertex))
            }
            EvalError::CapacityExceeded {
                vertex,
                needed,
                max,
            } => format!(
                "the pole at {} needs valence {needed} at the requested depth, at most {max} is supported",
                names.vertex(*vertex as usize)
            ),
            EvalError::Overflow => String::from(
                "the refined mesh overflows the number type (coordinates too large)",
            ),
            EvalError::Kernel {
                vertex,
                face,
                error,
                ..
            } => match (vertex, face) {
                (Some(v), _) => format!("the cap at {}: {error}", names.vertex(*v as usize)),
                (None, Some(f)) => {
                    format!("the cap at the centre of {}: {error}", names.face(*f as usize))
                }
                (None, None) => format!("a cap: {error}"),
            },
            EvalError::OutOfMemory { bytes } => {
                crate::mem::OutOfMemory { bytes: *bytes }.message()
            }
        }
    }
}

impl core::fmt::Display for EvalError {
    /// [`EvalError::describe`] with 0-based [`Indices`].
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(&self.describe(&Indices))
    }
}

/// The message names the kernel's error of a [`EvalError::Kernel`] itself,
/// so no error is reported again as a source.
impl core::error::Error for EvalError {}

/// The largest valence a polar cap may reach at its deepest level (its net
/// then takes `17·2^20·size_of::<R>()` bytes: 142 MB in f64).
pub const MAX_POLAR_VALENCE: usize = 1 << 20;

/// Evaluation state: the plan it runs and buffers sized for it.
pub struct Evaluator<'p, R: Real> {
    /// The plan the buffers are sized for.
    plan: &'p SurfacePlan<'p>,
    /// Everything but the plan.
    pub(crate) buffers: EvalBuffers<R>,
}

/// An [`Evaluator`]'s buffers without its plan ([`Evaluator::into_buffers`]),
/// for a caller that owns the plan beside them (a struct cannot hold a plan
/// and an evaluator borrowing it): [`Evaluator::with_buffers`] takes them
/// back without allocating.
pub struct EvalBuffers<R: Real> {
    /// Points of each refinement level (level 0: the input positions).
    levels: Vec<Vec<Point3<R>>>,
    /// The analysed level's vertices followed by the phantom points.
    pub(crate) work: Vec<Point3<R>>,
    /// The caps' buffers.
    pub(crate) scratch: Scratch<R>,
    /// Rule (7) in the Fourier basis for each built-in EG valence the plan
    /// has (n = 3, 5), built once: the caps' fast step.
    pub(crate) eg_rules: Vec<FourierRule<'static, R>>,
    /// Further caps' buffers, one per extra thread of
    /// `Evaluator::evaluate_parallel` (empty until it runs).
    #[cfg_attr(not(feature = "parallel"), allow(dead_code))]
    pub(crate) extra: Vec<Scratch<R>>,
}

/// The buffers a cap is evaluated in, sized for the largest cap of a plan
/// and reused by every cap.
pub(crate) struct Scratch<R: Real> {
    /// Storage of the polar nets (links 1..5, roots).
    polar_links: Vec<Point3<R>>,
    polar_roots: Vec<[R; 2]>,
    links: Vec<[R; 3]>,
    cnet: Vec<[R; 3]>,
    cc: Vec<Point3<R>>,
    eg: Box<EgSubdivision<'static, R>>,
    /// A cap stops after the ring whose hole is at most this wide.
    pub(crate) hole_tolerance: Option<f64>,
    /// Cap patches relative to their cap's centre ([`PatchRecord::origin`]).
    pub(crate) relative_caps: bool,
}

/// The lengths of a [`Scratch`]'s buffers for `plan` (`need`: the largest
/// valence a polar cap reaches, [`polar_need`]): polar links, polar roots,
/// links, c-net, Catmull-Clark storage.
fn scratch_lens<R: Real>(plan: &SurfacePlan<'_>, need: usize) -> [usize; 5] {
    let max_n = plan.polar.iter().map(|p| p.valence).max().unwrap_or(0);
    let max_ev = plan
        .extraordinary
        .iter()
        .map(|e| e.sectors.len())
        .max()
        .unwrap_or(0);
    [
        SliceStorage::<R>::links_len(need),
        SliceStorage::<R>::roots_len(need),
        3 * max_n,
        6 * max_ev,
        CcCap::<R>::storage_len(max_ev.max(3)),
    ]
}

impl<R: Real> Scratch<R> {
    /// Buffers for the caps of `plan`; `need` is the largest valence a polar
    /// cap reaches (its storage capacity, [`SliceStorage::links_len`]).
    pub(crate) fn new(plan: &SurfacePlan<'_>, need: usize) -> Result<Self, EvalError> {
        let [polar_links, polar_roots, links, cnet, cc] = scratch_lens::<R>(plan, need);
        Ok(Scratch {
            polar_links: mem::filled(polar_links, Point3::ZERO)?,
            polar_roots: mem::filled(polar_roots, [R::ZERO; 2])?,
            links: mem::filled(links, [R::ZERO; 3])?,
            cnet: mem::filled(cnet, [R::ZERO; 3])?,
            cc: mem::filled(cc, Point3::ZERO)?,
            eg: Box::new(EgSubdivision::empty()),
            hole_tolerance: None,
            relative_caps: false,
        })
    }

    /// Whether these buffers are the ones [`Scratch::new`] makes for `plan`.
    fn fits(&self, plan: &SurfacePlan<'_>, need: usize) -> bool {
        let lens = [
            self.polar_links.len(),
            self.polar_roots.len(),
            self.links.len(),
            self.cnet.len(),
            self.cc.len(),
        ];
        lens == scratch_lens::<R>(plan, need)
    }
}

/// The built-in EG valences (3, 5) of `plan`'s EG caps, whose rules an
/// evaluator holds in the Fourier basis.
fn eg_valences<'a>(plan: &'a SurfacePlan<'_>) -> impl Iterator<Item = usize> + 'a {
    [3, 5].into_iter().filter(|&n| {
        plan.extraordinary
            .iter()
            .any(|e| e.scheme == Scheme::Eg && e.sectors.len() == n)
    })
}

impl<R: Real> EvalBuffers<R> {
    /// Whether these buffers are the ones [`Evaluator::new`] makes for
    /// `plan` (`need`: its largest polar capacity); extra thread buffers
    /// that are not are dropped.
    fn fit(&mut self, plan: &SurfacePlan<'_>, need: usize) -> bool {
        self.extra.retain(|s| s.fits(plan, need));
        self.levels.len() == plan.steps.len() + 1
            && self.levels.first().map(Vec::len) == Some(plan.input_vertices)
            && self.levels[1..]
                .iter()
                .zip(&plan.steps)
                .all(|(l, s)| l.len() == s.len())
            && self.work.len() == plan.working_points()
            && self.scratch.fits(plan, need)
            && self
                .eg_rules
                .iter()
                .map(|r| r.valence())
                .eq(eg_valences(plan))
    }
}

impl<'p, R: Real> Evaluator<'p, R> {
    /// Sizes every buffer for `plan`. [`EvalError::CapacityExceeded`] when a
    /// polar cap's deepest valence exceeds the largest tier,
    /// [`EvalError::OutOfMemory`] when a buffer cannot be allocated.
    pub fn new(plan: &'p SurfacePlan<'p>) -> Result<Self, EvalError> {
        let need = polar_need(plan)?;
        let mut levels = mem::with_capacity(plan.steps.len() + 1)?;
        levels.push(mem::filled(plan.input_vertices, Point3::ZERO)?);
        for s in &plan.steps {
            levels.push(mem::filled(s.len(), Point3::ZERO)?);
        }
        let buffers = EvalBuffers {
            levels,
            work: mem::filled(plan.working_points(), Point3::ZERO)?,
            scratch: Scratch::new(plan, need)?,
            extra: Vec::new(),
            eg_rules: eg_valences(plan)
                .filter_map(|n| FourierRule::new(&RuleTable::builtin(n)?).ok())
                .collect(),
        };
        Ok(Evaluator { plan, buffers })
    }

    /// An evaluator for `plan` on `buffers` taken from an evaluator of the
    /// same plan ([`Self::into_buffers`]), allocating nothing; buffers sized
    /// for another plan are replaced by new ones, as [`Self::new`] sizes
    /// them. The hole tolerance ([`Self::set_hole_tolerance`]) and
    /// [`Self::set_relative_caps`] are kept.
    pub fn with_buffers(
        plan: &'p SurfacePlan<'p>,
        mut buffers: EvalBuffers<R>,
    ) -> Result<Self, EvalError> {
        let need = polar_need(plan)?;
        if buffers.fit(plan, need) {
            return Ok(Evaluator { plan, buffers });
        }
        let tolerance = buffers.scratch.hole_tolerance;
        let relative = buffers.scratch.relative_caps;
        let mut fresh = Self::new(plan)?;
        fresh.set_hole_tolerance(tolerance);
        fresh.set_relative_caps(relative);
        Ok(fresh)
    }

    /// The buffers, to keep beside the plan ([`Self::with_buffers`]).
    pub fn into_buffers(self) -> EvalBuffers<R> {
        self.buffers
    }

    /// The plan it evaluates.
    pub fn plan(&self) -> &'p SurfacePlan<'p> {
        self.plan
    }

    /// Each cap emits rings until the hole left inside its last ring is at
    /// most `tolerance` across (absolute, in the positions' units), and at
    /// most the plan's depth; `None` (the default): always the plan's depth.
    /// The hole's width is bounded by twice the largest distance from the
    /// limit point to a control point of the ring's inner edges (the edges
    /// lie in their control points' convex hull). The rings of the adaptive
    /// refinement around irregular points keep the plan's depth.
    pub fn set_hole_tolerance(&mut self, tolerance: Option<f64>) {
        let b = &mut self.buffers;
        for s in core::iter::once(&mut b.scratch).chain(&mut b.extra) {
            s.hole_tolerance = tolerance;
        }
    }

    /// With `true`, every cap's patches come relative to the cap's centre
    /// (the input vertex or face centre it surrounds): the record's
    /// [`PatchRecord::origin`] is the centre and its control points are
    /// what the kernel computed about it, not yet moved back. A consumer
    /// adds the origin to positions (partials and normals need nothing):
    /// [`crate::tessellate`]'s tessellations do; a sink that reads control
    /// points as absolute (the CLI's patch and CAD writers) wants `false`.
    /// Caps are computed about their centre either way; relative records
    /// skip the last rounding of every control point to the size of its
    /// distance from the coordinate origin, which is what limits `f32`
    /// normals of small caps far from it. `false` (the default): absolute
    /// control points and a zero origin, for every patch.
    pub fn set_relative_caps(&mut self, on: bool) {
        let b = &mut self.buffers;
        for s in core::iter::once(&mut b.scratch).chain(&mut b.extra) {
            s.relative_caps = on;
        }
    }

    /// Evaluates the surface for `positions` (one per input vertex): the
    /// regular patches and caps in [`SurfacePlan::order`], each cap's
    /// patches followed by its record.
    pub fn evaluate(
        &mut self,
        positions: &[[R; 3]],
        sink: &mut dyn SurfaceSink<R>,
    ) -> Result<(), EvalError> {
        self.prepare(positions, |s, src, out| s.apply(src, out))?;
        let plan = self.plan;
        let b = &mut self.buffers;
        for &unit in &plan.order {
            match unit {
                Unit::Regular(i) => emit_regular(plan, &b.work, i as usize, sink),
                Unit::Cap(index) => {
                    b.scratch.cap(&b.work, &b.eg_rules, plan, index, sink)?;
                }
            }
        }
        Ok(())
    }

    /// Checks `positions` and computes the working points (refinement
    /// steps through `apply`, phantom points) that every patch and cap
    /// gathers from.
    pub(crate) fn prepare(
        &mut self,
        positions: &[[R; 3]],
        apply: impl Fn(&crate::StencilTable, &[Point3<R>], &mut [Point3<R>]),
    ) -> Result<(), EvalError> {
        let plan = self.plan;
        let b = &mut self.buffers;
        if positions.len() != plan.input_vertices || b.levels[0].len() != positions.len() {
            return Err(EvalError::WrongLength {
                expected: plan.input_vertices,
                found: positions.len(),
            });
        }
        if let Some(vertex) = positions
            .iter()
            .position(|p| !p.iter().all(|c| c.is_finite()))
        {
            return Err(EvalError::NonFinite { vertex });
        }
        for (d, s) in b.levels[0].iter_mut().zip(positions) {
            *d = Point3(*s);
        }
        for (k, s) in plan.steps.iter().enumerate() {
            let (src, dst) = b.levels.split_at_mut(k + 1);
            apply(s, &src[k], &mut dst[0]);
        }
        let last = b.levels.last().map(Vec::as_slice).unwrap_or(&[]);
        let split = plan.vertices.min(b.work.len());
        let (verts, phantoms) = b.work.split_at_mut(split);
        verts.copy_from_slice(&last[..verts.len()]);
        plan.phantoms.apply_chained(verts, phantoms);
        // Regular patches are convex combinations of these points: below
        // MAX/2 they are finite. `(p + p)·0` is zero unless a coordinate is
        // above MAX/2 or not finite (then NaN, which the sum keeps).
        let mut probe = Point3::ZERO;
        for p in &b.work {
            probe += (*p + *p) * R::ZERO;
        }
        if !probe.is_finite() {
            return Err(EvalError::Overflow);
        }
        Ok(())
    }
}

/// The largest polar net capacity the caps of `plan` need.
pub(crate) fn polar_need(plan: &SurfacePlan<'_>) -> Result<usize, EvalError> {
    let depth = plan.options.depth;
    let mut need = 0usize;
    for p in &plan.polar {
        match capdiv::polar::capacity_for(p.valence, depth) {
            Some(x) if x <= MAX_POLAR_VALENCE => need = need.max(x),
            other => {
                return Err(EvalError::CapacityExceeded {
                    vertex: p.vertex,
                    needed: other.unwrap_or(usize::MAX),
                    max: MAX_POLAR_VALENCE,
                })
            }
        }
    }
    Ok(need)
}

/// The patch of regular face `index` of `plan`.
pub(crate) fn emit_regular<R: Real>(
    plan: &SurfacePlan<'_>,
    work: &[Point3<R>],
    index: usize,
    sink: &mut dyn SurfaceSink<R>,
) {
    let level0 = plan.steps.len() as u32;
    if let Some(r) = plan.regular.get(index) {
        let mut d = [[Point3::ZERO; 4]; 4];
        for (i, row) in d.iter_mut().enumerate() {
            for (j, p) in row.iter_mut().enumerate() {
                *p = work[r.gather[4 * i + j] as usize];
            }
        }
        let patch = TensorPatch {
            points: bspline_to_bezier_cubic(&d),
        };
        let hole_point = if r.hole != 0 {
            work[r.hole_point as usize]
        } else {
            Point3::ZERO
        };
        let mut rec = record(
            PatchKind::Regular,
            level0 + r.level,
            &r.chart,
            [0.0, 1.0, 0.0, 1.0],
            patch,
            r.finer,
            r.hole,
            hole_point,
            None,
        );
        if r.boundary != 0 {
            let map = &r.chart.map;
            rec.boundary =
                map_edges(map, r.boundary & 0xf) | map_corners(map, r.boundary >> 4) << 4;
        }
        sink.patch(&rec);
    }
}

impl<R: Real> Scratch<R> {
    /// Emits cap `index` (numbered as in [`PatchRecord::cap`]), gathering
    /// from the working points.
    pub(crate) fn cap(
        &mut self,
        work: &[Point3<R>],
        eg_rules: &[FourierRule<'static, R>],
        plan: &SurfacePlan<'_>,
        index: u32,
        sink: &mut dyn SurfaceSink<R>,
    ) -> Result<(), EvalError> {
        let polar = plan.polar.len();
        match plan.polar.get(index as usize) {
            Some(p) => self.polar_cap(work, plan, p, index, sink),
            None => match plan.extraordinary.get(index as usize - polar) {
                Some(e) => self.ev_cap(work, eg_rules, plan, e, index, sink),
                None => Ok(()),
            },
        }
    }

    /// Whether cap records are relative, and the origin the records of a
    /// cap computed about `centre` carry: `centre` if so, zero otherwise
    /// ([`PatchRecord::origin`]).
    fn record_origin(&self, centre: Point3<R>) -> (bool, Point3<R>) {
        if self.relative_caps {
            (true, centre)
        } else {
            (false, Point3::ZERO)
        }
    }

    /// Emits polar cap `index` (`p`), gathering from the working points.
    pub(crate) fn polar_cap(
        &mut self,
        work: &[Point3<R>],
        plan: &SurfacePlan<'_>,
        p: &PolarPlan,
        index: u32,
        sink: &mut dyn SurfaceSink<R>,
    ) -> Result<(), EvalError> {
        let n = p.valence;
        let kernel = |error| EvalError::Kernel {
            cap: index,
            vertex: Some(p.vertex),
            face: None,
            error,
        };
        // The net relative to its pole, the rings moved back (`moved`).
        let origin = work[p.pole as usize];
        for (d, &i) in self.links.iter_mut().zip(&p.links) {
            *d = (work[i as usize] - origin).0;
        }
        let pole = [R::ZERO; 3];
        let (relative, at) = self.record_origin(origin);
        let depth = plan.options.depth;
        let n_in = n >> p.prior_steps;
        let (l1, rest) = self.links.split_at(n.min(self.links.len()));
        let (l2, l3) = rest.split_at(n.min(rest.len()));
        let mut net = PolarNetBuf::new_in(
            pole,
            &[l1, l2, &l3[..n.min(l3.len())]],
            SliceStorage::new(&mut self.polar_links, &mut self.polar_roots),
        )
        .map_err(kernel)?;
        let jet = PoleJet::of(&net);
        let limit = jet.limit();
        let geometry = jet.geometry().ok();
        let rings = rings::polar_net_rings(
            &mut net,
            p.first,
            (depth, self.hole_tolerance),
            limit,
            &mut |ring| {
                let m = ring.ring;
                let cols = ring.len / 2;
                let (span, c) = (ring.index / cols, ring.index % cols);
                // Columns of this level per input triangle.
                let per = cols / n_in.max(1);
                let scale = 1.0 / (1u64 << (m + p.prior_steps)) as f64;
                let (r0, r1) = ((2 + span) as f64 * scale, (3 + span) as f64 * scale);
                let tri = p.triangles.get(c >> m).copied().unwrap_or(0);
                let (v0, v1) = (
                    ((c % per) as f64) / per as f64,
                    ((c % per) + 1) as f64 / per as f64,
                );
                let chart = if r1 <= 1.0 || p.quads.is_empty() {
                    FaceChart {
                        face: tri,
                        corner: None,
                        map: Affine::IDENTITY,
                    }
                } else {
                    p.quads
                        .get(c >> m)
                        .copied()
                        .unwrap_or(FaceChart::input(tri))
                };
                let rect = if r1 <= 1.0 {
                    [r0, r1, v0, v1]
                } else {
                    [r0 - 1.0, r1 - 1.0, v0, v1]
                };
                if let PatchGeometry::Cubic(patch) = ring.geometry {
                    let mut rec = record(
                        PatchKind::C2ps,
                        m + p.prior_steps,
                        &chart,
                        rect,
                        placed(patch, origin, relative),
                        ring.finer,
                        ring.hole,
                        limit + origin,
                        Some(index),
                    );
                    rec.origin = at;
                    sink.patch(&rec);
                }
            },
        )
        .map_err(kernel)?;
        sink.cap(&CapRecord {
            index,
            vertex: Some(p.vertex),
            face: None,
            scheme: Scheme::C2ps,
            valence: n_in,
            limit: limit + origin,
            normal: geometry.map(|g| g.normal),
            principal_curvatures: geometry.map(|g| g.principal),
            rings,
        });
        Ok(())
    }

    /// Emits EG or Catmull-Clark cap `index` (`e`), gathering from the
    /// working points.
    pub(crate) fn ev_cap(
        &mut self,
        work: &[Point3<R>],
        eg_rules: &[FourierRule<'static, R>],
        plan: &SurfacePlan<'_>,
        e: &ExtraordinaryCapPlan,
        index: u32,
        sink: &mut dyn SurfaceSink<R>,
    ) -> Result<(), EvalError> {
        let n = e.sectors.len();
        let kernel = |error| EvalError::Kernel {
            cap: index,
            vertex: e.vertex,
            face: e.face,
            error,
        };
        // The c-net relative to its centre, the rings moved back (`moved`).
        let origin = work[e.center as usize];
        for (d, &i) in self.cnet.iter_mut().zip(&e.nodes) {
            *d = (work[i as usize] - origin).0;
        }
        let center = [R::ZERO; 3];
        let (relative, at) = self.record_origin(origin);
        let nodes = &self.cnet[..6 * n];
        let depth = plan.options.depth;
        let level0 = e.level;
        // A ring patch placed in its sector's face.
        let place = |ring: RingPatch<R>, limit: Point3<R>| {
            let dom = ring.domain.unwrap_or(PatchDomain {
                sector: 0,
                x0: 0.0,
                y0: 0.0,
                size: 1.0,
            });
            let chart = e
                .sectors
                .get(dom.sector)
                .copied()
                .unwrap_or(FaceChart::input(0));
            let rect = [dom.x0, dom.x0 + dom.size, dom.y0, dom.y0 + dom.size];
            let level = ring.ring + level0;
            let (finer, hole) = (ring.finer, ring.hole);
            let hole_point = limit + origin;
            let mut rec = match ring.geometry {
                PatchGeometry::Cubic(p) => record(
                    ring.kind,
                    level,
                    &chart,
                    rect,
                    placed(p, origin, relative),
                    finer,
                    hole,
                    hole_point,
                    Some(index),
                ),
                PatchGeometry::Quartic(p) => record(
                    ring.kind,
                    level,
                    &chart,
                    rect,
                    placed(p, origin, relative),
                    finer,
                    hole,
                    hole_point,
                    Some(index),
                ),
            };
            rec.origin = at;
            rec
        };
        let stop = (depth, self.hole_tolerance);
        let (scheme, limit, rings, normal) = match e.scheme {
            Scheme::Eg => {
                let net = CNet::new(center, nodes).map_err(kernel)?;
                match e.table.and_then(|i| plan.options.eg_tables.get(i)) {
                    // The user's table borrows from the plan; run on a local
                    // subdivision (about 6 KiB in f64).
                    Some(table) => {
                        let mut eg = EgSubdivision::empty();
                        eg.reset(&net, Some(*table)).map_err(kernel)?;
                        let limit = eg.limit();
                        let (rings, normal) = rings::eg_net_rings(&mut eg, None, stop, &mut |r| {
                            sink.patch(&place(r, limit))
                        })
                        .map_err(kernel)?;
                        (Scheme::Eg, limit, rings, normal)
                    }
                    None => {
                        self.eg.reset(&net, None).map_err(kernel)?;
                        let n = self.eg.valence();
                        let rule = eg_rules.iter().find(|r| r.valence() == n);
                        let limit = self.eg.limit();
                        let (rings, normal) =
                            rings::eg_net_rings(&mut self.eg, rule, stop, &mut |r| {
                                sink.patch(&place(r, limit))
                            })
                            .map_err(kernel)?;
                        (Scheme::Eg, limit, rings, normal)
                    }
                }
            }
            _ => {
                let mut cap = CcCap::new(center, nodes, &mut self.cc).map_err(kernel)?;
                let limit = cap.limit();
                let rings =
                    rings::cc_cap_rings(&mut cap, stop, &mut |r| sink.patch(&place(r, limit)))
                        .map_err(kernel)?;
                (Scheme::CatmullClark, limit, rings, cap.normal().ok())
            }
        };
        sink.cap(&CapRecord {
            index,
            vertex: e.vertex,
            face: e.face,
            scheme,
            valence: n,
            limit: limit + origin,
            normal,
            principal_curvatures: None,
            rings,
        });
        Ok(())
    }
}

/// `patch` moved by `by`.
///
/// A cap is computed around its centre: the kernel gets the polar net or
/// c-net minus its pole or centre point, and every ring patch, hole point
/// and limit is moved back by this. The schemes are affine invariant, so in
/// exact arithmetic nothing changes; in floating point the rounding of every
/// subdivision step is then relative to the cap's size rather than to its
/// distance from the origin, which matters in `f32` for a small cap far from
/// the origin (the last ring's normals of a 10⁴-face torus's EG caps come
/// out about 1.5× closer to the f64 surface; `mesh/tests/cap_precision.rs`).
#[inline]
pub(crate) fn moved<R: Real, const K: usize>(
    mut patch: TensorPatch<R, K>,
    by: Point3<R>,
) -> TensorPatch<R, K> {
    patch.points.iter_mut().flatten().for_each(|q| *q += by);
    patch
}

/// A cap's ring patch computed about `origin` as its record carries it:
/// moved back; or, `relative`, as computed (the record's origin is then
/// `origin`: [`Scratch::record_origin`]).
#[inline]
fn placed<R: Real, const K: usize>(
    patch: TensorPatch<R, K>,
    origin: Point3<R>,
    relative: bool,
) -> TensorPatch<R, K> {
    if relative {
        patch
    } else {
        moved(patch, origin)
    }
}

/// Which edge of the image square edge `k` of the own square maps to.
fn edge_image(map: &Affine, k: u8) -> u8 {
    let mid = match k {
        0 => (0.5, 0.0),
        1 => (1.0, 0.5),
        2 => (0.5, 1.0),
        _ => (0.0, 0.5),
    };
    let p = map.apply(mid.0, mid.1);
    let c = map.apply(0.5, 0.5);
    let (dx, dy) = (p[0] - c[0], p[1] - c[1]);
    if dx.abs() > dy.abs() {
        if dx > 0.0 {
            1
        } else {
            3
        }
    } else if dy > 0.0 {
        2
    } else {
        0
    }
}

/// Edge bits re-expressed in the image frame.
fn map_edges(map: &Affine, bits: u8) -> u8 {
    (0..4u8)
        .filter(|k| bits & (1 << k) != 0)
        .fold(0, |acc, k| acc | (1 << edge_image(map, k)))
}

/// Corner bits (bit `k`: corner `k`, where edge `k` starts) re-expressed in
/// the image frame.
fn map_corners(map: &Affine, bits: u8) -> u8 {
    let c = map.apply(0.5, 0.5);
    (0..4u8).filter(|k| bits & (1 << k) != 0).fold(0, |acc, k| {
        let (s, t) = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)][k as usize];
        let p = map.apply(s, t);
        let image = match (p[0] > c[0], p[1] > c[1]) {
            (false, false) => 0,
            (true, false) => 1,
            (true, true) => 2,
            (false, true) => 3,
        };
        acc | (1 << image)
    })
}

/// A patch given over `rect` of a face-local frame, placed through `chart`.
#[inline]
#[allow(clippy::too_many_arguments)]
pub(crate) fn record<R: Real, const K: usize>(
    kind: PatchKind,
    level: u32,
    chart: &FaceChart,
    rect: [f64; 4],
    patch: TensorPatch<R, K>,
    finer: u8,
    hole: u8,
    hole_point: Point3<R>,
    cap: Option<u32>,
) -> PatchRecord<R>
where
    TensorPatch<R, K>: Into<PatchGeometry<R>>,
{
    let map = &chart.map;
    // Most faces are input faces in their own frame: nothing to re-express.
    let identity = *map == Affine::IDENTITY;
    PatchRecord {
        kind,
        level,
        face: chart.face,
        corner: chart.corner,
        domain: if identity { rect } else { map.rect(rect) },
        geometry: if identity {
            patch.into()
        } else {
            TensorPatch {
                points: map.orient(&patch.points),
            }
            .into()
        },
        origin: Point3::ZERO,
        finer: if identity {
            finer
        } else {
            map_edges(map, finer)
        },
        hole: if identity { hole } else { map_edges(map, hole) },
        hole_point,
        boundary: 0,
        cap,
        uv: None,
    }
}
