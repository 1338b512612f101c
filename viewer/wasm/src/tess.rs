//! Per-vertex tessellation of the evaluated patches at exact parameters:
//! every patch is sampled on its own `g × g` grid of `(u, v)` in its Bézier
//! square, and each sample carries what [`PatchGeometry::jet`] and
//! [`capdiv::SurfaceJet::geometry`] give there — position, unit normal,
//! Gaussian and mean curvature — the same formulas as the CLI's pictures
//! (`capdiv_mesh::shade`).
//!
//! Patches are not welded: samples on a shared edge are computed once per
//! patch, at the same parameters, so they coincide (up to rounding) and
//! carry the same normal and curvature (the surface is C² across patch
//! edges). A patch `k` levels finer than the surface's coarsest patches gets
//! `g >> k` segments (at least 1), so across a ring of a cap, where one patch
//! meets two of half its size, the coarse patch's edge samples are exactly
//! the fine patches' ones. Patches of one segment (rings under `1/g` of a face)
//! whose edge meets two half-size patches get that edge's midpoint and a fan
//! from their centre: no crack either.
//!
//! The cap's last hole (edges flagged in [`PatchRecord::hole`]) is closed by
//! a fan of triangles to the cap's limit point; those triangles' vertices are
//! flagged [`HOLE`] (the page marks them in the curvature maps: the hole is
//! not part of any patch).

use capdiv_mesh::evaluate::{CapRecord, PatchKind, PatchRecord, SurfaceSink};
use capdiv_mesh::tessellate::PatchGeometry;

/// Flag: the vertex belongs to a hole fan.
pub const HOLE: u8 = 1;
/// Flag: the normal and curvature do not exist there (`x_u × x_v = 0`).
pub const DEGENERATE: u8 = 2;

/// The sampled surface.
#[derive(Clone, Debug, Default)]
pub struct Surface {
    /// Positions.
    pub position: Vec<[f64; 3]>,
    /// Unit normals (`x_u × x_v` normalised; zero where [`DEGENERATE`]).
    pub normal: Vec<[f64; 3]>,
    /// Gaussian curvature (NaN where [`DEGENERATE`]).
    pub gaussian: Vec<f64>,
    /// Mean curvature, positive where the surface bends towards the normal
    /// (NaN where [`DEGENERATE`]).
    pub mean: Vec<f64>,
    /// [`HOLE`], [`DEGENERATE`] bits.
    pub flags: Vec<u8>,
    /// Triangles, counter-clockwise about their patch's `x_u × x_v`.
    pub indices: Vec<u32>,
    /// Bounding box of the positions (`lo > hi` when empty).
    pub lo: [f64; 3],
    /// See `lo`.
    pub hi: [f64; 3],
}

impl Surface {
    /// Vertices.
    pub fn len(&self) -> usize {
        self.position.len()
    }

    /// No vertex.
    pub fn is_empty(&self) -> bool {
        self.position.is_empty()
    }

    fn clear(&mut self) {
        self.position.clear();
        self.normal.clear();
        self.gaussian.clear();
        self.mean.clear();
        self.flags.clear();
        self.indices.clear();
        self.lo = [f64::INFINITY; 3];
        self.hi = [f64::NEG_INFINITY; 3];
    }

    fn push(&mut self, p: [f64; 3], n: [f64; 3], k: f64, h: f64, flags: u8) -> u32 {
        let i = self.position.len() as u32;
        for (c, &x) in p.iter().enumerate() {
            widen(&mut self.lo, &mut self.hi, c, x);
        }
        self.position.push(p);
        self.normal.push(n);
        self.gaussian.push(k);
        self.mean.push(h);
        self.flags.push(flags);
        i
    }

    /// Sets vertex `i`.
    fn set(&mut self, i: usize, p: [f64; 3], n: [f64; 3], k: f64, h: f64, flags: u8) {
        for (c, &x) in p.iter().enumerate() {
            widen(&mut self.lo, &mut self.hi, c, x);
        }
        self.position[i] = p;
        self.normal[i] = n;
        self.gaussian[i] = k;
        self.mean[i] = h;
        self.flags[i] = flags;
    }

    /// Appends a copy of vertex `src` flagged [`HOLE`]. The box already
    /// holds its position.
    fn push_copy(&mut self, src: usize) -> u32 {
        let i = self.position.len() as u32;
        self.position.push(self.position[src]);
        self.normal.push(self.normal[src]);
        self.gaussian.push(self.gaussian[src]);
        self.mean.push(self.mean[src]);
        self.flags.push(self.flags[src] | HOLE);
        i
    }

    /// Vertex `dst` becomes a copy of `src` flagged [`HOLE`].
    fn copy_sample(&mut self, src: usize, dst: usize) {
        let (p, n, k, h) = (
            self.position[src],
            self.normal[src],
            self.gaussian[src],
            self.mean[src],
        );
        let f = self.flags[src] | HOLE;
        self.set(dst, p, n, k, h, f);
    }

    /// The sample `(u, v)` of `g`: position, normal, curvatures.
    fn jet(g: &PatchGeometry<f64>, u: f64, v: f64) -> ([f64; 3], [f64; 3], f64, f64, u8) {
        match g.jet(u, v) {
            Ok(jet) => {
                let p = jet.position.0;
                match jet.geometry() {
                    Ok(geo) => (p, geo.normal.0, geo.gaussian, geo.mean, 0),
                    Err(_) => (p, [0.0; 3], f64::NAN, f64::NAN, DEGENERATE),
                }
            }
            // (u, v) ∈ [0, 1]² always: not reached.
            Err(_) => ([0.0; 3], [0.0; 3], f64::NAN, f64::NAN, DEGENERATE),
        }
    }

    /// Appends the sample `(u, v)` of `g`.
    fn sample(&mut self, g: &PatchGeometry<f64>, u: f64, v: f64) -> u32 {
        let (p, n, k, h, f) = Self::jet(g, u, v);
        self.push(p, n, k, h, f)
    }

    /// Rewrites vertex `i` with the sample `(u, v)` of `g`.
    fn resample(&mut self, i: usize, g: &PatchGeometry<f64>, u: f64, v: f64) {
        let (p, n, k, h, f) = Self::jet(g, u, v);
        self.set(i, p, n, k, h, f);
    }

    /// The bounding box from scratch (after points moved inwards).
    pub fn recompute_bounds(&mut self) {
        self.lo = [f64::INFINITY; 3];
        self.hi = [f64::NEG_INFINITY; 3];
        for p in &self.position {
            for (c, &x) in p.iter().enumerate() {
                widen(&mut self.lo, &mut self.hi, c, x);
            }
        }
    }
}

/// Widens the box `[lo, hi]` along `c` to hold `x` (plain comparisons:
/// `f64::min` is a libm call on wasm32).
#[inline]
fn widen(lo: &mut [f64; 3], hi: &mut [f64; 3], c: usize, x: f64) {
    if x < lo[c] {
        lo[c] = x;
    }
    if x > hi[c] {
        hi[c] = x;
    }
}

/// Segments per side of a patch `level` levels below `base` (see the module
/// doc): `grid >> (level − base)`, at least 1.
pub fn segments(grid: usize, base: u32, level: u32) -> usize {
    let k = level.saturating_sub(base);
    if k >= usize::BITS {
        1
    } else {
        (grid >> k).max(1)
    }
}

/// Where one patch's samples are, and what they were computed from.
#[derive(Clone, Debug)]
struct Slot {
    geometry: PatchGeometry<f64>,
    level: u32,
    finer: u8,
    hole: u8,
    hole_point: [f64; 3],
    /// First vertex, and one past its last (hole fans included).
    first: u32,
    end: u32,
}

/// The samples of an evaluation, as a [`SurfaceSink`]: the first evaluation
/// of a plan builds the whole [`Surface`] ([`Tessellator::begin`] with
/// `rebuild`); the following ones, with the same plan, re-sample only the
/// patches whose control points changed — an edit of a control point moves
/// only the patches in its support — in place, so the triangles stay as they
/// are. [`Tessellator::dirty`] is the range of vertices rewritten.
#[derive(Clone, Debug, Default)]
pub struct Tessellator {
    grid: usize,
    base: u32,
    rebuild: bool,
    cursor: usize,
    /// A patch did not match the layout (another plan): rebuild.
    mismatch: bool,
    slots: Vec<Slot>,
    /// The sampled surface.
    pub surface: Surface,
    /// Vertices rewritten by the last evaluation: `dirty.0..dirty.1`.
    pub dirty: (usize, usize),
    /// Patches per kind (regular, polar, EG, Catmull-Clark) of the layout.
    pub kinds: [usize; 4],
    /// The caps of the last evaluation.
    pub caps: Vec<CapRecord<f64>>,
}

impl Tessellator {
    /// Starts an evaluation: `rebuild` for a new plan (or grid), where `base`
    /// is the level of the coarsest patches (the plan's refinement steps)
    /// and `grid` their segments per side (a power of two, so that halving
    /// stays exact).
    pub fn begin(&mut self, rebuild: bool, base: u32, grid: usize) {
        self.rebuild = rebuild || self.grid != grid || self.base != base;
        self.grid = grid;
        self.base = base;
        self.cursor = 0;
        self.mismatch = false;
        self.caps.clear();
        if self.rebuild {
            self.slots.clear();
            self.surface.clear();
            self.kinds = [0; 4];
        }
        self.dirty = (usize::MAX, 0);
    }

    /// Ends an evaluation. `false`: the patches did not fit the layout of
    /// the previous evaluation — evaluate again after `begin(true, ..)`.
    pub fn finish(&mut self) -> bool {
        if !self.rebuild && (self.mismatch || self.cursor != self.slots.len()) {
            return false;
        }
        if self.rebuild {
            self.dirty = (0, self.surface.len());
        } else {
            self.surface.recompute_bounds();
        }
        if self.dirty.0 > self.dirty.1 {
            self.dirty = (0, 0);
        }
        true
    }

    fn push_patch(&mut self, p: &PatchRecord<f64>) {
        let first = self.surface.len() as u32;
        let g = segments(self.grid, self.base, p.level);
        let side = g as u32 + 1;
        for a in 0..=g {
            for b in 0..=g {
                self.surface
                    .sample(&p.geometry, a as f64 / g as f64, b as f64 / g as f64);
            }
        }
        let at = |a: u32, b: u32| first + a * side + b;
        let extra = extra_samples(g, p.finer);
        if extra.is_empty() {
            for a in 0..g as u32 {
                for b in 0..g as u32 {
                    self.surface.indices.extend_from_slice(&[
                        at(a, b),
                        at(a + 1, b),
                        at(a + 1, b + 1),
                        at(a, b),
                        at(a + 1, b + 1),
                        at(a, b + 1),
                    ]);
                }
            }
        } else {
            // One cell with midpoints on its finer edges: a fan from the
            // centre over its boundary, counter-clockwise.
            let base = self.surface.len() as u32;
            for &(u, v) in &extra {
                self.surface.sample(&p.geometry, u, v);
            }
            let centre = base + extra.len() as u32 - 1;
            let mut ring = Vec::with_capacity(8);
            let mut mid = base;
            for (e, corner) in [at(0, 0), at(1, 0), at(1, 1), at(0, 1)]
                .into_iter()
                .enumerate()
            {
                ring.push(corner);
                if p.finer & (1 << e) != 0 {
                    ring.push(mid);
                    mid += 1;
                }
            }
            for k in 0..ring.len() {
                let next = ring[(k + 1) % ring.len()];
                self.surface
                    .indices
                    .extend_from_slice(&[ring[k], next, centre]);
            }
        }
        if p.hole != 0 {
            hole_fans(p, g, at, &mut self.surface);
        }
        self.kinds[match p.kind {
            PatchKind::Regular => 0,
            PatchKind::Polar => 1,
            PatchKind::Eg => 2,
            PatchKind::CatmullClark => 3,
        }] += 1;
        self.slots.push(Slot {
            geometry: p.geometry,
            level: p.level,
            finer: p.finer,
            hole: p.hole,
            hole_point: p.hole_point.0,
            first,
            end: self.surface.len() as u32,
        });
    }

    /// Re-samples slot `k` in place from `p` (same layout).
    fn update_patch(&mut self, k: usize, p: &PatchRecord<f64>) {
        let slot = &self.slots[k];
        let (first, end) = (slot.first as usize, slot.end as usize);
        let g = segments(self.grid, self.base, p.level);
        let s = &mut self.surface;
        let mut i = first;
        for a in 0..=g {
            for b in 0..=g {
                s.resample(i, &p.geometry, a as f64 / g as f64, b as f64 / g as f64);
                i += 1;
            }
        }
        for (u, v) in extra_samples(g, p.finer) {
            s.resample(i, &p.geometry, u, v);
            i += 1;
        }
        if p.hole != 0 {
            // The fans' vertices follow the grid: per hole edge, copies of
            // its g + 1 samples and the hole point (as `hole_fans` made them).
            let side = g + 1;
            let at = |a: usize, b: usize| first + a * side + b;
            for e in (0..4u8).filter(|e| p.hole & (1 << e) != 0) {
                let edge: Vec<usize> = edge_samples(e, g).map(|(a, b)| at(a, b)).collect();
                for &src in &edge {
                    s.copy_sample(src, i);
                    i += 1;
                }
                let (n, k, h, f) = hole_centre(s, &edge);
                s.set(i, p.hole_point.0, n, k, h, f);
                i += 1;
            }
        }
        debug_assert_eq!(i, end);
        let slot = &mut self.slots[k];
        slot.geometry = p.geometry;
        slot.hole_point = p.hole_point.0;
        self.dirty = (self.dirty.0.min(first), self.dirty.1.max(end));
    }
}

impl SurfaceSink<f64> for Tessellator {
    fn patch(&mut self, p: &PatchRecord<f64>) {
        if self.rebuild {
            self.push_patch(p);
        } else if !self.mismatch {
            match self.slots.get(self.cursor) {
                Some(s) if s.level == p.level && s.finer == p.finer && s.hole == p.hole => {
                    if s.geometry != p.geometry || s.hole_point != p.hole_point.0 {
                        self.update_patch(self.cursor, p);
                    }
                }
                _ => self.mismatch = true,
            }
        }
        self.cursor += 1;
    }

    fn cap(&mut self, c: &CapRecord<f64>) {
        self.caps.push(c.clone());
    }
}

/// Samples beyond the grid: a patch of one segment whose edge `e` is met
/// by two patches of half its size (bit `e` of `finer`) gets that edge's
/// midpoint — where the two meet — and then its centre, so that it can be
/// triangulated without a T-junction. (With `g ≥ 2` segments the
/// neighbours' samples are already among the patch's, `g/2` each.)
fn extra_samples(g: usize, finer: u8) -> Vec<(f64, f64)> {
    if g != 1 || finer == 0 {
        return Vec::new();
    }
    let mut out: Vec<(f64, f64)> = [(0.5, 0.0), (1.0, 0.5), (0.5, 1.0), (0.0, 0.5)]
        .into_iter()
        .enumerate()
        .filter(|(e, _)| finer & (1 << e) != 0)
        .map(|(_, uv)| uv)
        .collect();
    out.push((0.5, 0.5));
    out
}

/// Grid coordinates `(a, b)` of edge `e`'s samples, in the patch's
/// counter-clockwise boundary order.
fn edge_samples(e: u8, g: usize) -> impl Iterator<Item = (usize, usize)> {
    (0..=g).map(move |i| match e {
        0 => (i, 0),
        1 => (g, i),
        2 => (g - i, g),
        _ => (0, g - i),
    })
}

/// The hole point's attributes: the mean of the edge samples' normals and
/// curvatures (the limit point has none of a patch).
fn hole_centre(s: &Surface, edge: &[usize]) -> ([f64; 3], f64, f64, u8) {
    let mut n = [0.0; 3];
    let (mut k, mut h) = (0.0, 0.0);
    for &i in edge {
        for (acc, x) in n.iter_mut().zip(s.normal[i]) {
            *acc += x;
        }
        k += s.gaussian[i];
        h += s.mean[i];
    }
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let count = edge.len() as f64;
    if len > 0.0 && len.is_finite() {
        (
            [n[0] / len, n[1] / len, n[2] / len],
            k / count,
            h / count,
            HOLE,
        )
    } else {
        ([0.0; 3], k / count, h / count, HOLE | DEGENERATE)
    }
}

/// The triangles from each hole edge of `p` to its hole point, on copies of
/// the edge's samples (flagged [`HOLE`]).
fn hole_fans(p: &PatchRecord<f64>, g: usize, at: impl Fn(u32, u32) -> u32, out: &mut Surface) {
    for e in (0..4u8).filter(|e| p.hole & (1 << e) != 0) {
        let edge: Vec<usize> = edge_samples(e, g)
            .map(|(a, b)| at(a as u32, b as u32) as usize)
            .collect();
        let copies: Vec<u32> = edge.iter().map(|&s| out.push_copy(s)).collect();
        let (n, k, h, f) = hole_centre(out, &edge);
        let centre = out.push(p.hole_point.0, n, k, h, f);
        for w in copies.windows(2) {
            out.indices.extend_from_slice(&[w[1], w[0], centre]);
        }
    }
}

/// Samples `patches` into `out` in one go (what a [`Tessellator`]'s first
/// evaluation builds).
pub fn tessellate(patches: &[PatchRecord<f64>], base: u32, grid: usize, out: &mut Surface) {
    let mut t = Tessellator::default();
    t.begin(true, base, grid);
    for p in patches {
        t.patch(p);
    }
    t.finish();
    *out = t.surface;
}

#[cfg(test)]
mod tests {
    use super::*;
    use capdiv::{Point3, TensorPatch};

    /// The bicubic Bézier patch of `z = x² + y²` over `[0,1]²`, exact
    /// (degree elevation of the quadratic: `z` control values
    /// `b_i + b_j` with `b = [0, 0, 1/3, 1]`).
    fn paraboloid() -> PatchGeometry<f64> {
        let b = [0.0, 0.0, 1.0 / 3.0, 1.0];
        let mut points = [[Point3::ZERO; 4]; 4];
        for (i, row) in points.iter_mut().enumerate() {
            for (j, p) in row.iter_mut().enumerate() {
                *p = Point3([i as f64 / 3.0, j as f64 / 3.0, b[i] + b[j]]);
            }
        }
        PatchGeometry::Cubic(TensorPatch { points })
    }

    fn record(level: u32, hole: u8) -> PatchRecord<f64> {
        PatchRecord {
            kind: PatchKind::Regular,
            level,
            face: 0,
            corner: None,
            domain: [0.0, 1.0, 0.0, 1.0],
            geometry: paraboloid(),
            finer: 0,
            hole,
            hole_point: Point3([-1.0, -1.0, 0.0]),
            boundary: 0,
            cap: None,
            uv: None,
        }
    }

    #[test]
    fn samples_carry_the_analytic_curvature_of_the_patch() {
        let mut s = Surface::default();
        tessellate(&[record(0, 0)], 0, 4, &mut s);
        assert_eq!(s.len(), 25);
        assert_eq!(s.indices.len(), 4 * 4 * 6);
        for i in 0..s.len() {
            let [x, y, z] = s.position[i];
            // z = x² + y²: K = 4/(1+4x²+4y²)², H = 2(1+2x²+2y²)/(1+4x²+4y²)^{3/2}
            // with the upward normal (x_u × x_v has +z).
            let w = 1.0 + 4.0 * x * x + 4.0 * y * y;
            assert!((z - x * x - y * y).abs() < 1e-14);
            assert!((s.gaussian[i] - 4.0 / (w * w)).abs() < 1e-12);
            let h = 2.0 * (1.0 + 2.0 * x * x + 2.0 * y * y) / w.powf(1.5);
            assert!((s.mean[i] - h).abs() < 1e-12, "{} {h}", s.mean[i]);
            let n = [-2.0 * x, -2.0 * y, 1.0].map(|c| c / w.sqrt());
            for (got, want) in s.normal[i].iter().zip(n) {
                assert!((got - want).abs() < 1e-12);
            }
            assert_eq!(s.flags[i], 0);
        }
        assert_eq!((s.lo, s.hi), ([0.0, 0.0, 0.0], [1.0, 1.0, 2.0]));
    }

    #[test]
    fn the_box_holds_only_the_samples_far_from_the_origin() {
        // The paraboloid moved by 1000 along every axis, two hole edges and
        // its hole point next to it: the box is exactly that of the samples,
        // nowhere near the origin.
        let mut r = record(0, 0b1001);
        let PatchGeometry::Cubic(mut t) = r.geometry else {
            unreachable!()
        };
        for p in t.points.iter_mut().flatten() {
            *p = Point3([p.0[0] + 1000.0, p.0[1] + 1000.0, p.0[2] + 1000.0]);
        }
        r.geometry = PatchGeometry::Cubic(t);
        r.hole_point = Point3([999.0, 999.0, 1000.0]);
        let mut s = Surface::default();
        tessellate(&[r], 0, 4, &mut s);
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in &s.position {
            for c in 0..3 {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
        }
        assert_eq!((s.lo, s.hi), (lo, hi));
        assert_eq!(
            (s.lo, s.hi),
            ([999.0, 999.0, 1000.0], [1001.0, 1001.0, 1002.0])
        );
    }

    #[test]
    fn finer_levels_halve_the_grid_and_keep_edge_samples_shared() {
        assert_eq!(segments(8, 0, 0), 8);
        assert_eq!(segments(8, 1, 2), 4);
        assert_eq!(segments(8, 0, 3), 1);
        assert_eq!(segments(8, 0, 9), 1);
        assert_eq!(segments(8, 0, 200), 1);
        assert_eq!(segments(8, 3, 0), 8);
        // Level-1 patch halves: the coarse edge v = 0 has samples at
        // u = a/8; the two half patches [0,½] and [½,1] (4 segments each) at
        // ½·b/4 and ½ + ½·b/4 — the same parameters.
        let coarse: Vec<f64> = (0..=8).map(|a| a as f64 / 8.0).collect();
        let fine: Vec<f64> = (0..2)
            .flat_map(|h| (0..=4).map(move |b| 0.5 * h as f64 + 0.5 * b as f64 / 4.0))
            .collect();
        for f in fine {
            assert!(coarse.contains(&f));
        }
    }

    #[test]
    fn one_segment_patches_take_the_midpoints_of_finer_edges() {
        let mut r = record(3, 0);
        r.finer = 0b0011; // edges v = 0 and u = 1
        let mut s = Surface::default();
        tessellate(&[r], 0, 8, &mut s);
        // 4 corners, 2 midpoints, the centre; a fan of 6 triangles.
        assert_eq!(s.len(), 7);
        // z = x² + y² at (½, 0), (1, ½), (½, ½), to rounding.
        let near = |p: [f64; 3], q: [f64; 3]| (0..3).all(|c| (p[c] - q[c]).abs() < 1e-15);
        assert!(near(s.position[4], [0.5, 0.0, 0.25]));
        assert!(near(s.position[5], [1.0, 0.5, 1.25]));
        assert!(near(s.position[6], [0.5, 0.5, 0.5]));
        assert_eq!(s.indices.len(), 6 * 3);
        for tri in s.indices.chunks(3) {
            assert_eq!(tri[2], 6);
            let p: Vec<[f64; 3]> = tri.iter().map(|&i| s.position[i as usize]).collect();
            let area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
            assert!(area > 0.0, "{p:?}");
        }
        // With two or more segments the grid already has them.
        let mut r = record(2, 0);
        r.finer = 0b0011;
        tessellate(&[r], 0, 8, &mut s);
        assert_eq!(s.len(), 9);
    }

    #[test]
    fn hole_edges_get_a_fan_to_the_hole_point() {
        let mut s = Surface::default();
        // Edges u = 0 (bit 3) and v = 0 (bit 0).
        tessellate(&[record(0, 0b1001)], 0, 2, &mut s);
        let grid = 9;
        // Per hole edge: 3 copies and the hole point.
        assert_eq!(s.len(), grid + 2 * 4);
        assert_eq!(s.indices.len(), 2 * 2 * 6 + 2 * 2 * 3);
        let holes = s.flags.iter().filter(|&&f| f & HOLE != 0).count();
        assert_eq!(holes, 8);
        let fans = &s.indices[24..];
        for tri in fans.chunks(3) {
            assert_eq!(s.position[tri[2] as usize], [-1.0, -1.0, 0.0]);
            // Fan triangles lie on the copies, oriented like the patch seen
            // from +z (the hole point is outside the square, below-left).
            let p: Vec<[f64; 3]> = tri.iter().map(|&i| s.position[i as usize]).collect();
            let area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
            assert!(area > 0.0, "{p:?}");
        }
    }
}
