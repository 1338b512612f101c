//! Crack-free, welded tessellation of a patchwork surface: bicubic and
//! bi-quartic Bézier patches that meet along whole edges, or — across the
//! rings of a subdivision cap, whose patches halve in size ring after ring —
//! one patch against two of half its size, each covering half of the edge.
//! Each cap leaves a last hole, closed by a fan of triangles to its limit
//! point.
//!
//! A patch to tessellate is the evaluator's [`PatchRecord`] — its geometry,
//! the edge bits [`PatchRecord::finer`] and [`PatchRecord::hole`], its
//! [`PatchRecord::hole_point`] and [`PatchRecord::uv`] — with a `u32` tag
//! given alongside, copied to every output face of the patch
//! ([`Tessellation::tags`]); [`PatchRecord::new`] makes one of a bare
//! Bézier patch.
//!
//! [`tessellate`] samples every patch on a `grid × grid` parameter grid
//! (`(u, v) = (a/grid, b/grid)`, [`capdiv::TensorPatch::evaluate`]), laid
//! out as [`layout`] says under [`layout::Sampling::Uniform`]:
//!
//! - an edge whose [`PatchRecord::finer`] bit is set is sampled at `2·grid`
//!   segments (the midpoints `(2c+1)/(2·grid)` added), so its points are
//!   exactly those of the two half-size neighbours' `grid`-segment edges. The
//!   cells along it become triangle fans from a midpoint (a cell with one
//!   midpoint: 3 triangles), so there is no T-junction;
//! - an edge whose [`PatchRecord::hole`] bit is set gets one triangle per
//!   segment, `(segment reversed, hole_point)`, oriented like the patch;
//! - samples that coincide within `weld_tolerance` (absolute, per
//!   coordinate: `max |Δx|, |Δy|, |Δz| ≤ tol`), directly or through a chain
//!   of such samples, are merged into one vertex (sorting on quantised
//!   coordinates, `O(N log N)`; see [`weld`]). Vertices are numbered in the
//!   order of their first sample;
//! - with texture coordinates ([`PatchRecord::uv`]), every sample gets its
//!   patch's bilinear UV, and a welded vertex whose samples carry different
//!   UVs (a UV seam) is split into one vertex per UV
//!   ([`weld::split_by_uv`]); nothing else changes. Without UVs the result
//!   is exactly what it is without this step.
//!
//! **Edge bits.** A patch's edges are numbered counter-clockwise around its
//! own square, `0`: `v = 0` ([`EDGE_V0`]), `1`: `u = 1`, `2`: `v = 1`, `3`:
//! `u = 0`; a set of edges is a `u8` with bit `e` ([`edge_bit`]) for edge
//! `e`. [`PatchRecord::finer`], [`PatchRecord::hole`] and
//! [`PatchRecord::boundary`] use them.
//!
//! The result is a [`Tessellation`]: a closed input surface gives a closed,
//! consistently oriented mesh ([`is_closed_and_oriented`]). Faces are
//! [`Face::Quad`] (interior cells) or [`Face::Tri`] (cells along a finer edge,
//! hole fans), counter-clockwise about `∂u × ∂v` of their patch; indices are
//! 0-based `u32`. [`write_obj`] writes Wavefront OBJ text.

mod check;
pub mod layout;
mod obj;
mod sample;
pub mod stream;
pub mod weld;

use crate::evaluate::PatchRecord;
use crate::mem::{self, OutOfMemory};
use alloc::vec::Vec;
use capdiv::{BicubicPatch, BiquarticPatch, Point3, Real};
use core::borrow::Borrow;

pub use check::{
    closed_in_order, is_closed_and_oriented, try_closed_and_oriented, BadEdge, EdgeFault,
};
pub use obj::{try_write_obj, write_number, write_obj, write_point};
pub use stream::{MeshSink, ObjWriter, StreamSummary, StreamTessellator, TessellatingSink};

/// Edge `v = 0` of a patch's own square, `u` running from 0 to 1.
pub const EDGE_V0: u8 = 0;
/// Edge `u = 1`, `v` from 0 to 1.
pub const EDGE_U1: u8 = 1;
/// Edge `v = 1`, `u` from 1 to 0.
pub const EDGE_V1: u8 = 2;
/// Edge `u = 0`, `v` from 1 to 0.
pub const EDGE_U0: u8 = 3;

/// The bit of edge `e` (one of `EDGE_*`) in [`PatchRecord::finer`] and
/// [`PatchRecord::hole`]: `1 << e`.
pub const fn edge_bit(e: u8) -> u8 {
    1 << e
}

/// How a cap's ring patches are ordered, for [`ring_inner_edges`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RingLayout {
    /// C²PS: two spans of `N` columns, span 0 (patches `0..N`) the inner
    /// one, `u` running outwards.
    Polar,
    /// EG and Catmull-Clark: per sector `s` three pieces `3s + p` of the
    /// previous ring's hole `[0, 1]²`: `p = 0` over `[½,1]×[0,½]`, 1 over
    /// `[0,½]×[½,1]`, 2 over `[½,1]²`.
    Sectors,
}

/// The edges (bits as [`edge_bit`]) of ring patch `j` (of `len` in its
/// ring, laid out as `layout`) that face the cap's centre: the next ring
/// meets each of them with two patches of half the size
/// ([`PatchRecord::finer`]), or, on the last ring, the hole borders them
/// ([`PatchRecord::hole`]). Polar: edge `u = 0` of span 0; sectors: edge
/// `u = 0` of piece 0 and edge `v = 0` of piece 1.
pub fn ring_inner_edges(layout: RingLayout, j: usize, len: usize) -> u8 {
    match layout {
        RingLayout::Polar if j < len / 2 => edge_bit(EDGE_U0),
        RingLayout::Polar => 0,
        RingLayout::Sectors => match j % 3 {
            0 => edge_bit(EDGE_U0),
            1 => edge_bit(EDGE_V0),
            _ => 0,
        },
    }
}

/// `(finer, hole)` ([`PatchRecord::finer`], [`PatchRecord::hole`]) of ring
/// patch `j` of a cap's rings: its inner edges ([`ring_inner_edges`]) meet
/// the next ring's half-size patches on every ring but the `last`, and
/// border the last ring's hole there.
///
/// ```
/// use capdiv_mesh::tessellate::{edge_bit, ring_edge_flags, RingLayout, EDGE_U0, EDGE_V0};
///
/// // A C²PS ring of 2·6 patches: span 0 (patches 0..6) faces the pole.
/// let u0 = edge_bit(EDGE_U0);
/// assert_eq!(ring_edge_flags(RingLayout::Polar, 2, 12, false), (u0, 0));
/// assert_eq!(ring_edge_flags(RingLayout::Polar, 2, 12, true), (0, u0));
/// assert_eq!(ring_edge_flags(RingLayout::Polar, 8, 12, true), (0, 0));
/// // EG / Catmull-Clark: piece 1 of a sector faces the centre along v = 0,
/// // piece 2 not at all.
/// assert_eq!(ring_edge_flags(RingLayout::Sectors, 4, 9, true), (0, edge_bit(EDGE_V0)));
/// assert_eq!(ring_edge_flags(RingLayout::Sectors, 5, 9, false), (0, 0));
/// ```
pub fn ring_edge_flags(layout: RingLayout, j: usize, len: usize, last: bool) -> (u8, u8) {
    let inner = ring_inner_edges(layout, j, len);
    if last {
        (0, inner)
    } else {
        (inner, 0)
    }
}

/// The geometry of one patch to tessellate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PatchGeometry<R> {
    /// A bicubic patch (C²PS rings, B-spline faces, Catmull-Clark caps).
    Cubic(BicubicPatch<R>),
    /// A bi-quartic patch (EG rings).
    Quartic(BiquarticPatch<R>),
}

impl<R> From<BicubicPatch<R>> for PatchGeometry<R> {
    fn from(p: BicubicPatch<R>) -> Self {
        PatchGeometry::Cubic(p)
    }
}

impl<R> From<BiquarticPatch<R>> for PatchGeometry<R> {
    fn from(p: BiquarticPatch<R>) -> Self {
        PatchGeometry::Quartic(p)
    }
}

/// One output face: 0-based vertex indices, counter-clockwise about
/// `∂u × ∂v` of the patch it comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Face {
    /// A triangle (a cell along a finer edge, or a hole fan triangle).
    Tri([u32; 3]),
    /// A quad (a grid cell).
    Quad([u32; 4]),
}

impl Face {
    /// The corners in order (3 or 4).
    #[inline]
    pub fn corners(&self) -> &[u32] {
        match self {
            Face::Tri(c) => c,
            Face::Quad(c) => c,
        }
    }

    #[inline]
    fn map(self, f: impl Fn(u32) -> u32) -> Self {
        match self {
            Face::Tri(c) => Face::Tri(c.map(f)),
            Face::Quad(c) => Face::Quad(c.map(f)),
        }
    }

    /// Two corners equal.
    #[inline]
    fn is_degenerate(&self) -> bool {
        match *self {
            Face::Tri([a, b, c]) => (a == b) | (b == c) | (a == c),
            Face::Quad([a, b, c, d]) => {
                (a == b) | (a == c) | (a == d) | (b == c) | (b == d) | (c == d)
            }
        }
    }
}

/// A welded polygon mesh of a patchwork surface.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tessellation<R> {
    /// Vertex positions, in the order of their first sample.
    pub positions: Vec<Point3<R>>,
    /// Per vertex: the unit normal `∂u × ∂v / |∂u × ∂v|` of the first sample
    /// welded into it whose normal exists (the zero vector where every sample
    /// is degenerate). A vertex made of hole points only (a cap's limit
    /// point, which no patch samples) gets the normalised, area-weighted sum
    /// of its faces' normals instead.
    pub normals: Vec<Point3<R>>,
    /// The faces, patch after patch in input order.
    pub faces: Vec<Face>,
    /// Per face: the tag its patch was given with.
    pub tags: Vec<u32>,
    /// Per vertex: its texture coordinates, when the patches have them
    /// ([`PatchRecord::uv`]; a patch without them gives (0, 0)); empty
    /// otherwise.
    pub uvs: Vec<[f64; 2]>,
    /// With UVs: per vertex, the first vertex of its position class (itself
    /// unless a UV seam split the class), so that checks of the surface's
    /// connectivity ([`is_closed_and_oriented`] of faces mapped through it)
    /// see through the seams; empty without UVs.
    pub seam_origin: Vec<u32>,
    /// Samples taken before welding (grid points, edge midpoints, hole points).
    pub samples: usize,
    /// Faces dropped because welding made two of their corners equal (none
    /// for good input).
    pub degenerate_dropped: usize,
}

/// Tessellates `patches` — each a [`PatchRecord`] (borrowed or owned) and
/// the tag of its faces — with `grid` segments per patch side (`grid = 0`
/// is taken as 1) and welds samples within `weld_tolerance` (a negative or
/// NaN tolerance is taken as 0: only equal coordinates weld). See the
/// module doc.
///
/// # Panics
///
/// If the samples outnumber `u32::MAX` (`u32` indices).
pub fn tessellate<R: Real, P: Borrow<PatchRecord<R>>>(
    patches: impl IntoIterator<Item = (P, u32)>,
    grid: usize,
    weld_tolerance: R,
) -> Tessellation<R> {
    mem::or_abort(try_tessellate(patches, grid, weld_tolerance))
}

/// [`tessellate`], every buffer reserved fallibly: a refused allocation is
/// an error instead of an abort.
pub fn try_tessellate<R: Real, P: Borrow<PatchRecord<R>>>(
    patches: impl IntoIterator<Item = (P, u32)>,
    grid: usize,
    weld_tolerance: R,
) -> Result<Tessellation<R>, OutOfMemory> {
    let raw = sample_all(patches, grid)?;
    let rep = weld::representatives(&raw.positions, weld_tolerance)?;
    assemble(raw, rep)
}

/// [`tessellate`] of `patches`, welded where the samples of `guide` weld:
/// `guide` is the same patchwork in a higher precision (e.g. `f64` beside an
/// `f32` evaluation). Near a deep cap the samples of an `f32` surface are
/// closer together than `f32` rounding lets any one tolerance tell apart;
/// the connectivity of the `f64` surface does not depend on that. If the
/// two patchworks do not have the same samples, `patches` are welded on their
/// own with `fallback_tolerance`.
pub fn tessellate_guided<R: Real, S: Real, P: Borrow<PatchRecord<R>>, G: Borrow<PatchRecord<S>>>(
    patches: impl IntoIterator<Item = (P, u32)>,
    guide: impl IntoIterator<Item = (G, u32)>,
    grid: usize,
    guide_tolerance: S,
    fallback_tolerance: R,
) -> Tessellation<R> {
    mem::or_abort(try_tessellate_guided(
        patches,
        guide,
        grid,
        guide_tolerance,
        fallback_tolerance,
    ))
}

/// [`tessellate_guided`], every buffer reserved fallibly.
pub fn try_tessellate_guided<
    R: Real,
    S: Real,
    P: Borrow<PatchRecord<R>>,
    G: Borrow<PatchRecord<S>>,
>(
    patches: impl IntoIterator<Item = (P, u32)>,
    guide: impl IntoIterator<Item = (G, u32)>,
    grid: usize,
    guide_tolerance: S,
    fallback_tolerance: R,
) -> Result<Tessellation<R>, OutOfMemory> {
    let raw = sample_all(patches, grid)?;
    let guide = sample_all(guide, grid)?;
    let rep = if guide.positions.len() == raw.positions.len() && guide.faces == raw.faces {
        weld::representatives(&guide.positions, guide_tolerance)?
    } else {
        weld::representatives(&raw.positions, fallback_tolerance)?
    };
    assemble(raw, rep)
}

/// Every patch's samples and faces, unwelded.
fn sample_all<R: Real, P: Borrow<PatchRecord<R>>>(
    patches: impl IntoIterator<Item = (P, u32)>,
    grid: usize,
) -> Result<sample::Raw<R>, OutOfMemory> {
    let mut raw = sample::Raw::try_new(grid.max(1))?;
    for (p, tag) in patches {
        raw.push(p.borrow(), tag)?;
    }
    Ok(raw)
}

/// Welds `raw` into the tessellation: sample `k` becomes the vertex of its
/// representative `rep[k] ≤ k` (as [`weld::representatives`] returns them),
/// split across UV seams when the samples have UVs.
fn assemble<R: Real>(raw: sample::Raw<R>, rep: Vec<u32>) -> Result<Tessellation<R>, OutOfMemory> {
    let sample::Raw {
        positions: raw_pos,
        normals: raw_nrm,
        faces: raw_faces,
        tags: raw_tags,
        uvs: mut raw_uvs,
        ..
    } = raw;
    let samples = raw_pos.len();
    let (rep, by_position) = if raw_uvs.is_empty() {
        (rep, Vec::new())
    } else {
        let more = samples.saturating_sub(raw_uvs.len());
        mem::reserve(&mut raw_uvs, more)?;
        raw_uvs.resize(samples, [0.0; 2]);
        (weld::split_by_uv(&rep, &raw_uvs, weld::UV_TOLERANCE)?, rep)
    };
    let rep = rep.as_slice();
    assert!(
        u32::try_from(samples).is_ok(),
        "tessellate: more than u32::MAX samples"
    );

    // Welding: raw sample → representative sample → compact vertex index.
    // A vertex split off by a UV seam takes everything but its UV from the
    // first vertex of its position class (its seam origin): position, normal
    // and the faces' connectivity are those of the tessellation without UVs.
    let mut index = mem::filled(samples, u32::MAX)?;
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    // Whether some patch sample (not only hole points) went into the vertex.
    let mut sampled = Vec::new();
    let mut uvs = Vec::new();
    let mut seam_origin = Vec::new();
    for k in 0..samples {
        let r = rep[k] as usize;
        // The position class's first sample started a vertex first.
        let origin = by_position.get(k).map(|&p| p as usize);
        if r == k {
            let v = positions.len() as u32;
            index[k] = v;
            mem::push(&mut positions, raw_pos[origin.unwrap_or(k)])?;
            if let Some(uv) = raw_uvs.get(k) {
                mem::push(&mut uvs, *uv)?;
            }
            if let Some(o) = origin {
                mem::push(&mut seam_origin, index[o])?;
            }
            mem::push(&mut normals, Point3::ZERO)?;
            mem::push(&mut sampled, false)?;
        }
        let w = index[origin.map_or(r, |o| o)] as usize;
        if let Some(n) = raw_nrm[k] {
            sampled[w] = true;
            if normals[w] == Point3::ZERO {
                normals[w] = n;
            }
        }
    }
    let origin_of = |v: u32| seam_origin.get(v as usize).copied().unwrap_or(v);

    let mut faces = mem::with_capacity(raw_faces.len())?;
    let mut tags = mem::with_capacity(raw_faces.len())?;
    let mut degenerate_dropped = 0;
    for (f, tag) in raw_faces.into_iter().zip(raw_tags) {
        let f = f.map(|k| index[rep[k as usize] as usize]);
        if f.map(origin_of).is_degenerate() {
            degenerate_dropped += 1;
        } else {
            faces.push(f);
            tags.push(tag);
        }
    }

    // Hole points only: area-weighted face normals.
    if sampled.iter().any(|s| !s) {
        for f in &faces {
            let f = f.map(origin_of);
            let c = f.corners();
            // Twice the vector area of the polygon (Newell), about its first corner.
            let p0 = positions[c[0] as usize];
            let mut area = Point3::ZERO;
            for i in 1..c.len() - 1 {
                let a = positions[c[i] as usize] - p0;
                let b = positions[c[i + 1] as usize] - p0;
                area += a.cross(b);
            }
            for &v in c {
                if !sampled[v as usize] {
                    normals[v as usize] += area;
                }
            }
        }
        for (n, s) in normals.iter_mut().zip(&sampled) {
            if !s {
                let len = n.norm();
                *n = if len > R::ZERO && len.is_finite() {
                    *n * (R::ONE / len)
                } else {
                    Point3::ZERO
                };
            }
        }
    }
    // Split vertices: their origin's normal.
    for (v, &o) in seam_origin.iter().enumerate() {
        if o as usize != v {
            normals[v] = normals[o as usize];
        }
    }

    Ok(Tessellation {
        positions,
        normals,
        faces,
        tags,
        uvs,
        seam_origin,
        samples,
        degenerate_dropped,
    })
}
