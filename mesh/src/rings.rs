//! The rings of patches of one cap, the same way for every scheme.
//!
//! A cap subdivides its configuration ring by ring: C²PS levels
//! `m = 1..=depth` (docs/math/c2ps.md §5: `2·n·2^m` bicubic patches, span 0
//! then span 1, column by column), EG steps (docs/math/eg.md §9: `3n`
//! bi-quartic patches, sector by sector, pieces `[½,1]×[0,½]`, `[0,½]×[½,1]`,
//! `[½,1]²` of the old hole) and Catmull-Clark steps (the same layout,
//! bicubic). Every ring patch gets its `(finer, hole)` edges from the one
//! rule [`ring_edge_flags`]: the inner edges meet the next ring on every ring
//! but the last, and border the hole on the last. A hole tolerance stops a
//! cap early, as [`crate::Evaluator::set_hole_tolerance`] describes.
//!
//! Two layers:
//!
//! - [`polar_net_rings`], [`eg_net_rings`], [`cc_cap_rings`]: the ring loops
//!   over a kernel net the caller owns (its storage, its centre), handing
//!   each [`RingPatch`] to a closure. [`crate::Evaluator`] runs its caps
//!   through them, placing each patch in its input face.
//! - [`polar_rings`], [`eg_rings`], [`catmull_clark_rings`]: one cap
//!   configuration given as points, all with the signature
//!   `(centre, around, &RingOptions, sink)`, giving a [`SurfaceSink`] the
//!   ring patches and then the cap, computed around the centre as the
//!   evaluator computes its caps, so the patches are the evaluator's for the
//!   same cap, bit for bit.
//!
//! `capdiv patches` keeps its own loop over the kernel's nets: it emits bare
//! kernel patches of every level from 0 (and, with `--stream`, from a
//! streaming sweep that never holds a whole ring), which these functions,
//! made for caps of a surface, do not.
//!
//! ```
//! use capdiv_mesh::rings::{catmull_clark_rings, RingOptions};
//! use capdiv_mesh::sinks::CollectSurface;
//!
//! // A c-net of valence 5 (6 nodes per sector) around the origin, lifted
//! // into a bowl.
//! let n = 5;
//! let mut nodes = Vec::new();
//! for s in 0..n {
//!     for (x, y) in [(1.0, 0.0), (2.0, 0.0), (1.0, 1.0), (2.0, 1.0), (1.0, 2.0), (2.0, 2.0)] {
//!         let (a, b) = (std::f64::consts::TAU * s as f64 / n as f64, std::f64::consts::TAU / n as f64);
//!         let p = [x * a.cos() + y * (a + b).cos(), x * a.sin() + y * (a + b).sin()];
//!         nodes.push([p[0], p[1], 0.1 * (p[0] * p[0] + p[1] * p[1])]);
//!     }
//! }
//! let mut out = CollectSurface::new();
//! let rings = catmull_clark_rings([0.0; 3], &nodes, &RingOptions::new(3), &mut out)?;
//! assert_eq!(rings, 3);
//! assert_eq!(out.patches.len(), 3 * 3 * n); // 3 patches per sector and ring
//! assert_eq!(out.caps.len(), 1);
//! # Ok::<(), capdiv_mesh::rings::RingError>(())
//! ```

use crate::chart::FaceChart;
use crate::evaluate::{moved, record, CapRecord, PatchKind, SurfaceSink, MAX_POLAR_VALENCE};
use crate::hole;
use crate::mem::{self, OutOfMemory};
use crate::plan::Scheme;
use crate::tessellate::{ring_edge_flags, PatchGeometry, RingLayout};
use capdiv::eg::{CNet, EgSubdivision, FourierRule, PatchDomain, RuleTable};
use capdiv::polar::{capacity_for, NetStorage, PolarNetInner};
use capdiv::{CcCap, Error, FirstStep, Point3, PolarNetBuf, PoleJet, Real, SliceStorage};
use core::fmt;

/// One patch of a cap's ring, as the ring loops give it (in the frame of
/// the net they run on).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RingPatch<R> {
    /// The ring: the C²PS level or EG / Catmull-Clark step that made it,
    /// `1..=depth`.
    pub ring: u32,
    /// Its place in the ring: C²PS `span·cols + column`, EG and
    /// Catmull-Clark `3·sector + piece`.
    pub index: usize,
    /// Patches in the ring (`2·cols`, or `3n`).
    pub len: usize,
    /// Whether this is the cap's last ring.
    pub last: bool,
    /// The scheme's patch kind.
    pub kind: PatchKind,
    /// The Bézier patch.
    pub geometry: PatchGeometry<R>,
    /// Inner edges that meet the next ring ([`ring_edge_flags`]).
    pub finer: u8,
    /// Inner edges that border the hole ([`ring_edge_flags`]).
    pub hole: u8,
    /// EG and Catmull-Clark: the patch's square in its sector, in level-0
    /// c-units; C²PS: `None`.
    pub domain: Option<PatchDomain>,
}

/// How many rings a cap emits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RingOptions {
    /// Rings at most (C²PS levels, EG and Catmull-Clark steps).
    pub depth: u32,
    /// Stop once the hole inside the last ring is at most this across
    /// (absolute); `None`: always `depth` rings.
    pub hole_tolerance: Option<f64>,
    /// The first C²PS step's rule (docs/math/c2ps.md §2); unused by the
    /// other schemes.
    pub first: FirstStep,
}

impl RingOptions {
    /// `depth` rings, no tolerance, the uniform first step.
    pub fn new(depth: u32) -> Self {
        RingOptions {
            depth,
            hole_tolerance: None,
            first: FirstStep::Uniform,
        }
    }
}

/// Why a cap's rings could not be made.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum RingError {
    /// The points around the centre are not whole links or sectors.
    Length {
        /// Points given.
        found: usize,
        /// Points per link (C²PS: 3 links) or sector (c-net: 6 nodes) times
        /// valence must give it: this is the multiple.
        multiple: usize,
    },
    /// A C²PS cap of this valence would exceed the largest net at the depth.
    Capacity {
        /// Valence at the deepest level (`None`: it overflows).
        needed: Option<usize>,
        /// The largest supported.
        max: usize,
    },
    /// The kernel refused the configuration (too small a valence, a point
    /// not finite, ...).
    Kernel(Error),
    /// A net's storage could not be allocated.
    OutOfMemory {
        /// The size asked for.
        bytes: usize,
    },
}

impl From<Error> for RingError {
    fn from(e: Error) -> Self {
        RingError::Kernel(e)
    }
}

impl From<OutOfMemory> for RingError {
    fn from(e: OutOfMemory) -> Self {
        RingError::OutOfMemory { bytes: e.bytes }
    }
}

impl fmt::Display for RingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RingError::Length { found, multiple } => write!(
                f,
                "{found} points around the centre, a multiple of {multiple} is needed"
            ),
            RingError::Capacity {
                needed: Some(n),
                max,
            } => write!(
                f,
                "the cap needs valence {n} at the requested depth, at most {max} is supported"
            ),
            RingError::Capacity { needed: None, max } => write!(
                f,
                "the cap's valence at the requested depth overflows, at most {max} is supported"
            ),
            RingError::Kernel(e) => fmt::Display::fmt(e, f),
            RingError::OutOfMemory { bytes } => {
                fmt::Display::fmt(&OutOfMemory { bytes: *bytes }, f)
            }
        }
    }
}

/// The kernel's error is the message itself.
impl core::error::Error for RingError {}

/// The C²PS rings of `net` (levels `1..=depth`, each step with `first` at
/// level 1), stopping early at `tolerance` around `limit` (the pole's limit
/// point in the net's frame). Returns the rings emitted.
pub fn polar_net_rings<R: Real, S: NetStorage<R>>(
    net: &mut PolarNetInner<R, S>,
    first: FirstStep,
    (depth, tolerance): (u32, Option<f64>),
    limit: Point3<R>,
    emit: &mut dyn FnMut(RingPatch<R>),
) -> Result<u32, Error> {
    for m in 1..=depth {
        net.step(if m == 1 { first } else { FirstStep::Plain })?;
        let cols = net.valence();
        let last = m == depth || {
            let mut radius = 0.0f64;
            if tolerance.is_some() {
                for c in 0..cols {
                    let inner = net.ring_patch(c)?;
                    radius = radius.max(hole::edge_radius(&inner, hole::EDGE_U0, limit));
                }
            }
            hole::small_enough(radius, tolerance)
        };
        let len = 2 * cols;
        for index in 0..len {
            let patch = net.ring_patch(index)?;
            let (finer, hole) = ring_edge_flags(RingLayout::Polar, index, len, last);
            emit(RingPatch {
                ring: m,
                index,
                len,
                last,
                kind: PatchKind::C2ps,
                geometry: PatchGeometry::Cubic(patch),
                finer,
                hole,
                domain: None,
            });
        }
        if last {
            return Ok(m);
        }
    }
    Ok(0)
}

/// The EG rings of `eg` (steps `1..=depth`, through `rule`, the Fourier
/// form of its table, when given), stopping early at `tolerance`. Returns
/// the rings emitted and the cap's normal: the mean of the last ring's
/// normals at the corners nearest the centre, one per sector.
pub fn eg_net_rings<R: Real>(
    eg: &mut EgSubdivision<'_, R>,
    rule: Option<&FourierRule<'_, R>>,
    (depth, tolerance): (u32, Option<f64>),
    emit: &mut dyn FnMut(RingPatch<R>),
) -> Result<(u32, Option<Point3<R>>), Error> {
    let limit = eg.limit();
    let mut normal_sum = Point3::ZERO;
    let mut rings = 0;
    for m in 1..=depth {
        match rule {
            Some(rule) => eg.step_fourier(rule),
            None => eg.step(),
        }?;
        let last = m == depth || {
            let mut radius = 0.0f64;
            if tolerance.is_some() {
                for (k, inner) in eg.ring_patches().enumerate().filter(|(k, _)| k % 3 < 2) {
                    let edge = [hole::EDGE_U0, hole::EDGE_V0][k % 3];
                    radius = radius.max(hole::edge_radius(&inner, edge, limit));
                }
            }
            hole::small_enough(radius, tolerance)
        };
        let len = 3 * eg.valence();
        for (index, patch) in eg.ring_patches().enumerate() {
            let domain = eg.ring_patch_domain(index)?;
            if last && index % 3 == 0 {
                if let Ok(nrm) = patch.normal(R::ZERO, R::ZERO) {
                    normal_sum += nrm;
                }
            }
            let (finer, hole) = ring_edge_flags(RingLayout::Sectors, index, len, last);
            emit(RingPatch {
                ring: m,
                index,
                len,
                last,
                kind: PatchKind::Eg,
                geometry: PatchGeometry::Quartic(patch),
                finer,
                hole,
                domain: Some(domain),
            });
        }
        if last {
            rings = m;
            break;
        }
    }
    let norm = normal_sum.norm();
    let normal = (norm > R::ZERO && norm.is_finite()).then(|| normal_sum * (R::ONE / norm));
    Ok((rings, normal))
}

/// The Catmull-Clark rings of `cap` (steps `1..=depth`), stopping early at
/// `tolerance`. Returns the rings emitted.
pub fn cc_cap_rings<R: Real>(
    cap: &mut CcCap<'_, R>,
    (depth, tolerance): (u32, Option<f64>),
    emit: &mut dyn FnMut(RingPatch<R>),
) -> Result<u32, Error> {
    let limit = cap.limit();
    for m in 1..=depth {
        cap.step()?;
        let last = m == depth || {
            let mut radius = 0.0f64;
            if tolerance.is_some() {
                for k in (0..cap.ring_len()).filter(|k| k % 3 < 2) {
                    let inner = cap.ring_patch(k)?;
                    let edge = [hole::EDGE_U0, hole::EDGE_V0][k % 3];
                    radius = radius.max(hole::edge_radius(&inner, edge, limit));
                }
            }
            hole::small_enough(radius, tolerance)
        };
        let len = cap.ring_len();
        for index in 0..len {
            let patch = cap.ring_patch(index)?;
            let domain = cap.ring_patch_domain(index)?;
            let (finer, hole) = ring_edge_flags(RingLayout::Sectors, index, len, last);
            emit(RingPatch {
                ring: m,
                index,
                len,
                last,
                kind: PatchKind::CatmullClark,
                geometry: PatchGeometry::Cubic(patch),
                finer,
                hole,
                domain: Some(domain),
            });
        }
        if last {
            return Ok(m);
        }
    }
    Ok(0)
}

/// The points around `centre` made relative to it (as the evaluator
/// computes its caps: rounding relative to the cap's size).
fn relative<R: Real>(
    centre: [R; 3],
    around: &[[R; 3]],
) -> Result<alloc::vec::Vec<[R; 3]>, RingError> {
    let origin = Point3(centre);
    let mut out = mem::with_capacity(around.len())?;
    out.extend(around.iter().map(|&p| (Point3(p) - origin).0));
    Ok(out)
}

/// `p`'s record for the sink: moved back by `origin`, placed over
/// `rect` of face `face` (the cap's triangle or sector), cap 0.
fn placed<R: Real>(
    p: RingPatch<R>,
    face: u32,
    rect: [f64; 4],
    origin: Point3<R>,
    hole_point: Point3<R>,
) -> crate::PatchRecord<R> {
    let chart = FaceChart::input(face);
    match p.geometry {
        PatchGeometry::Cubic(t) => record(
            p.kind,
            p.ring,
            &chart,
            rect,
            moved(t, origin),
            p.finer,
            p.hole,
            hole_point,
            Some(0),
        ),
        PatchGeometry::Quartic(t) => record(
            p.kind,
            p.ring,
            &chart,
            rect,
            moved(t, origin),
            p.finer,
            p.hole,
            hole_point,
            Some(0),
        ),
    }
}

/// The C²PS cap of a polar configuration: `pole` and `around`, its links
/// 1, 2 and 3 of `n` points each, one after the other. The sink gets the
/// rings (level = ring; face = the pole triangle `column >> ring`; domain =
/// `[u0, u1, v0, v1]` with `u` the distance from the pole in link units and
/// `v` across the triangle) and then the cap (index 0, its limit point,
/// normal and principal curvatures). Returns the rings emitted.
pub fn polar_rings<R: Real>(
    pole: [R; 3],
    around: &[[R; 3]],
    options: &RingOptions,
    sink: &mut dyn SurfaceSink<R>,
) -> Result<u32, RingError> {
    let n = around.len() / 3;
    if !around.len().is_multiple_of(3) || n == 0 {
        return Err(RingError::Length {
            found: around.len(),
            multiple: 3,
        });
    }
    let depth = options.depth;
    let cap = match capacity_for(n, depth) {
        Some(c) if c <= MAX_POLAR_VALENCE => c,
        needed => {
            return Err(RingError::Capacity {
                needed,
                max: MAX_POLAR_VALENCE,
            })
        }
    };
    let origin = Point3(pole);
    let links = relative(pole, around)?;
    let mut ls = mem::filled(SliceStorage::<R>::links_len(cap), Point3::ZERO)?;
    let mut rs = mem::filled(SliceStorage::<R>::roots_len(cap), [R::ZERO; 2])?;
    let (l1, rest) = links.split_at(n);
    let (l2, l3) = rest.split_at(n);
    let mut net = PolarNetBuf::new_in(
        [R::ZERO; 3],
        &[l1, l2, l3],
        SliceStorage::new(&mut ls, &mut rs),
    )?;
    let jet = PoleJet::of(&net);
    let limit = jet.limit();
    let geometry = jet.geometry().ok();
    let hole_point = limit + origin;
    let rings = polar_net_rings(
        &mut net,
        options.first,
        (depth, options.hole_tolerance),
        limit,
        &mut |p| {
            let cols = p.len / 2;
            let (span, c) = (p.index / cols, p.index % cols);
            let per = cols / n;
            let scale = 1.0 / (1u64 << p.ring) as f64;
            let rect = [
                (2 + span) as f64 * scale,
                (3 + span) as f64 * scale,
                (c % per) as f64 / per as f64,
                ((c % per) + 1) as f64 / per as f64,
            ];
            sink.patch(&placed(p, (c >> p.ring) as u32, rect, origin, hole_point));
        },
    )?;
    sink.cap(&CapRecord {
        index: 0,
        vertex: None,
        face: None,
        scheme: Scheme::C2ps,
        valence: n,
        limit: hole_point,
        normal: geometry.map(|g| g.normal),
        principal_curvatures: geometry.map(|g| g.principal),
        rings,
    });
    Ok(rings)
}

/// The EG cap of a c-net: `centre` and `around`, its `6n` nodes sector by
/// sector in the order `(1,0) (2,0) (1,1) (2,1) (1,2) (2,2)`
/// (docs/math/eg.md §1), with the built-in rules (valences 3, 4, 5). The
/// sink gets the rings (level = ring; face = the sector; domain = the
/// patch's square in the sector, level-0 c-units) and then the cap.
/// Returns the rings emitted.
pub fn eg_rings<R: Real>(
    centre: [R; 3],
    around: &[[R; 3]],
    options: &RingOptions,
    sink: &mut dyn SurfaceSink<R>,
) -> Result<u32, RingError> {
    let nodes = sector_nodes(centre, around)?;
    let origin = Point3(centre);
    let net = CNet::new([R::ZERO; 3], &nodes)?;
    let mut eg = EgSubdivision::empty();
    eg.reset(&net, None)?;
    let n = eg.valence();
    let rule = RuleTable::builtin(n).and_then(|t| FourierRule::new(&t).ok());
    let hole_point = eg.limit() + origin;
    let (rings, normal) = eg_net_rings(
        &mut eg,
        rule.as_ref(),
        (options.depth, options.hole_tolerance),
        &mut |p| sink.patch(&sector_record(p, origin, hole_point)),
    )?;
    sink.cap(&CapRecord {
        index: 0,
        vertex: None,
        face: None,
        scheme: Scheme::Eg,
        valence: n,
        limit: hole_point,
        normal,
        principal_curvatures: None,
        rings,
    });
    Ok(rings)
}

/// The Catmull-Clark cap of a c-net (any valence ≥ 3), laid out as
/// [`eg_rings`]; the cap's normal is the limit normal.
pub fn catmull_clark_rings<R: Real>(
    centre: [R; 3],
    around: &[[R; 3]],
    options: &RingOptions,
    sink: &mut dyn SurfaceSink<R>,
) -> Result<u32, RingError> {
    let nodes = sector_nodes(centre, around)?;
    let n = nodes.len() / 6;
    let origin = Point3(centre);
    let mut storage = mem::filled(CcCap::<R>::storage_len(n), Point3::ZERO)?;
    let mut cap = CcCap::new([R::ZERO; 3], &nodes, &mut storage)?;
    let hole_point = cap.limit() + origin;
    let rings = cc_cap_rings(
        &mut cap,
        (options.depth, options.hole_tolerance),
        &mut |p| sink.patch(&sector_record(p, origin, hole_point)),
    )?;
    sink.cap(&CapRecord {
        index: 0,
        vertex: None,
        face: None,
        scheme: Scheme::CatmullClark,
        valence: n,
        limit: hole_point,
        normal: cap.normal().ok(),
        principal_curvatures: None,
        rings,
    });
    Ok(rings)
}

/// A c-net's nodes relative to its centre, checked to be whole sectors.
fn sector_nodes<R: Real>(
    centre: [R; 3],
    around: &[[R; 3]],
) -> Result<alloc::vec::Vec<[R; 3]>, RingError> {
    if !around.len().is_multiple_of(6) || around.is_empty() {
        return Err(RingError::Length {
            found: around.len(),
            multiple: 6,
        });
    }
    relative(centre, around)
}

/// An EG or Catmull-Clark ring patch's record: face = its sector.
fn sector_record<R: Real>(
    p: RingPatch<R>,
    origin: Point3<R>,
    hole_point: Point3<R>,
) -> crate::PatchRecord<R> {
    let (face, rect) = match p.domain {
        Some(d) => (d.sector as u32, [d.x0, d.x0 + d.size, d.y0, d.y0 + d.size]),
        None => (0, [0.0, 1.0, 0.0, 1.0]),
    };
    placed(p, face, rect, origin, hole_point)
}
