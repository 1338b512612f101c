//! Per-vertex tessellation of the evaluated patches at exact parameters, on
//! the mesh crate's one patch layout (`capdiv_mesh::tessellate::layout`):
//! every patch is sampled where [`PatchLayout`] puts its samples under
//! [`Sampling::Halving`] — its own grid of `(u, v)` in its Bézier square,
//! `g` segments per side for the coarsest patches and half as many a level
//! finer (at least 1), so across a ring of a cap, where one patch meets two
//! of half its size, the coarse patch's edge samples are exactly the fine
//! patches' ones; a one-segment patch gets the midpoints of its finer edges
//! instead. Each sample carries what [`PatchGeometry::jet`] and
//! [`capdiv::SurfaceJet::geometry`] give there — position, unit normal,
//! Gaussian and mean curvature — the same formulas as the CLI's pictures
//! (`capdiv_mesh::shade`).
//!
//! Patches are not welded: samples on a shared edge are computed once per
//! patch, at the same parameters, so they coincide (up to rounding) and
//! carry the same normal and curvature (the surface is C² across patch
//! edges), and each patch's vertices are one range the page re-uploads
//! after an edit.
//!
//! The cap's last hole (edges flagged in [`PatchRecord::hole`]) is closed by
//! the layout's fan of triangles to the cap's limit point, on copies of the
//! fan's edge samples; those copies and the limit point are flagged
//! [`HOLE`] (the page marks them in the curvature maps: the hole is not part
//! of any patch).

use capdiv_mesh::evaluate::{CapRecord, PatchRecord, SurfaceSink};
use capdiv_mesh::sinks::PatchCounts;
use capdiv_mesh::tessellate::layout::{PatchLayout, SampleAt, Sampling};
use capdiv_mesh::tessellate::{Face, PatchGeometry};

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

    /// Appends `count` vertices to be [`Surface::set`] (the box is not
    /// widened for them).
    fn grow(&mut self, count: usize) {
        let len = self.len() + count;
        self.position.resize(len, [0.0; 3]);
        self.normal.resize(len, [0.0; 3]);
        self.gaussian.resize(len, 0.0);
        self.mean.resize(len, 0.0);
        self.flags.resize(len, 0);
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

    /// Sets vertex `i` to the sample `(u, v)` of `g`.
    fn sample(&mut self, i: usize, g: &PatchGeometry<f64>, u: f64, v: f64) {
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

/// Where one patch's vertices are, and what they were computed from.
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

/// One patch's vertices: its layout's samples, then copies of the samples
/// its hole fans use.
#[derive(Clone, Debug, Default)]
struct PatchVertices {
    layout: PatchLayout,
    /// The samples the hole fans use, in the order of their first use.
    fan_samples: Vec<u32>,
}

impl PatchVertices {
    /// The vertices of `p` under `sampling`.
    fn set(&mut self, sampling: &Sampling, p: &PatchRecord<f64>) {
        self.layout.set(sampling, p);
        self.fan_samples.clear();
        let Some(h) = self.hole_sample() else {
            return;
        };
        for f in &self.layout.faces {
            let c = f.corners();
            if c.contains(&h) {
                for &s in c.iter().filter(|&&s| s != h) {
                    if !self.fan_samples.contains(&s) {
                        self.fan_samples.push(s);
                    }
                }
            }
        }
    }

    /// The hole point's sample, if the patch has hole edges.
    fn hole_sample(&self) -> Option<u32> {
        let last = self.layout.samples.len().checked_sub(1)?;
        (self.layout.samples[last] == SampleAt::HolePoint).then_some(last as u32)
    }

    /// Vertices per patch.
    fn len(&self) -> usize {
        self.layout.samples.len() + self.fan_samples.len()
    }

    /// Writes the vertices of `p` from vertex `first` on.
    fn write(&self, p: &PatchRecord<f64>, first: usize, s: &mut Surface) {
        for (k, &at) in self.layout.samples.iter().enumerate() {
            if let Some((u, v)) = self.layout.parameters(at) {
                s.sample(first + k, &p.geometry, u, v);
            }
        }
        let copies = first + self.layout.samples.len();
        for (c, &src) in self.fan_samples.iter().enumerate() {
            s.copy_sample(first + src as usize, copies + c);
        }
        if let Some(h) = self.hole_sample() {
            let (n, k, mean, f) = hole_centre(s, copies..copies + self.fan_samples.len());
            s.set(first + h as usize, p.hole_point.0, n, k, mean, f);
        }
    }

    /// Appends the triangles, on vertices from `first` on: a quad's as
    /// `(a, b, c), (a, c, d)`, a fan triangle's on the copies.
    fn triangles(&self, first: u32, out: &mut Vec<u32>) {
        let h = self.hole_sample();
        let copies = first + self.layout.samples.len() as u32;
        for f in &self.layout.faces {
            let fan = h.is_some_and(|h| f.corners().contains(&h));
            let vertex = |s: u32| {
                let copy = fan
                    .then(|| self.fan_samples.iter().position(|&c| c == s))
                    .flatten();
                copy.map_or(first + s, |c| copies + c as u32)
            };
            match *f {
                Face::Quad([a, b, c, d]) => {
                    let [a, b, c, d] = [a, b, c, d].map(vertex);
                    out.extend_from_slice(&[a, b, c, a, c, d]);
                }
                Face::Tri(t) => out.extend_from_slice(&t.map(vertex)),
            }
        }
    }
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
    /// The current patch's vertices.
    vertices: PatchVertices,
    /// The sampled surface.
    pub surface: Surface,
    /// Vertices rewritten by the last evaluation: `dirty.0..dirty.1`.
    pub dirty: (usize, usize),
    /// Patches per kind of the layout.
    pub kinds: PatchCounts,
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
            self.kinds = PatchCounts::default();
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

    /// The sampling of the current plan.
    fn sampling(&self) -> Sampling {
        Sampling::Halving {
            grid: self.grid,
            base: self.base,
        }
    }

    fn push_patch(&mut self, p: &PatchRecord<f64>) {
        let first = self.surface.len();
        self.vertices.set(&self.sampling(), p);
        self.surface.grow(self.vertices.len());
        self.vertices.write(p, first, &mut self.surface);
        self.vertices
            .triangles(first as u32, &mut self.surface.indices);
        self.kinds.add(p.kind);
        self.slots.push(Slot {
            geometry: p.geometry,
            level: p.level,
            finer: p.finer,
            hole: p.hole,
            hole_point: p.hole_point.0,
            first: first as u32,
            end: self.surface.len() as u32,
        });
    }

    /// Re-samples slot `k` in place from `p` (same level and edges, so the
    /// same layout).
    fn update_patch(&mut self, k: usize, p: &PatchRecord<f64>) {
        let (first, end) = (self.slots[k].first as usize, self.slots[k].end as usize);
        self.vertices.set(&self.sampling(), p);
        debug_assert_eq!(first + self.vertices.len(), end);
        self.vertices.write(p, first, &mut self.surface);
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

/// The hole point's attributes: the mean of the fan's edge samples' normals
/// and curvatures (vertices `copies`; the limit point has none of a patch).
fn hole_centre(s: &Surface, copies: core::ops::Range<usize>) -> ([f64; 3], f64, f64, u8) {
    let mut n = [0.0; 3];
    let (mut k, mut h) = (0.0, 0.0);
    let count = copies.len() as f64;
    for i in copies {
        for (acc, x) in n.iter_mut().zip(s.normal[i]) {
            *acc += x;
        }
        k += s.gaussian[i];
        h += s.mean[i];
    }
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
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
    use capdiv_mesh::PatchKind;

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
            level,
            hole,
            hole_point: Point3([-1.0, -1.0, 0.0]),
            ..PatchRecord::new(PatchKind::Regular, paraboloid())
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
    fn one_segment_patches_take_the_midpoints_of_finer_edges() {
        let mut r = record(3, 0);
        r.finer = 0b0011; // edges v = 0 and u = 1
        let mut s = Surface::default();
        // Level 3 at grid 8: 8 >> 3 = 1 segment, against two one-segment
        // patches along each finer edge.
        tessellate(&[r], 0, 8, &mut s);
        // 4 corners (a along u after a: (0,0), (0,1), (1,0), (1,1)) and the
        // midpoints of edges 0 and 1; the cell is the hexagon
        // 0, m0, 2, m1, 3, 1 fanned from its first midpoint m0 (vertex 4):
        // 6 − 2 = 4 triangles.
        assert_eq!(s.len(), 6);
        // z = x² + y² at (½, 0), (1, ½), to rounding.
        let near = |p: [f64; 3], q: [f64; 3]| (0..3).all(|c| (p[c] - q[c]).abs() < 1e-15);
        assert!(near(s.position[4], [0.5, 0.0, 0.25]));
        assert!(near(s.position[5], [1.0, 0.5, 1.25]));
        assert_eq!(s.indices.len(), 4 * 3);
        for tri in s.indices.chunks(3) {
            assert_eq!(tri[0], 4);
            let p: Vec<[f64; 3]> = tri.iter().map(|&i| s.position[i as usize]).collect();
            let area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
            assert!(area > 0.0, "{p:?}");
        }
        // With two or more segments the grid already has them: level 2 is
        // 2 segments, 3 × 3 samples, no midpoint.
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
        // 3 × 3 grid samples and the hole point; the fans over edge v = 0
        // ((0,0), (1,0), (2,0) in grid steps) and edge u = 0 ((0,2), (0,1),
        // (0,0)) use 5 distinct samples, each copied once.
        let grid = 9;
        assert_eq!(s.len(), grid + 1 + 5);
        // 2 × 2 cells of 2 triangles, and 2 fan triangles per hole edge.
        assert_eq!(s.indices.len(), 2 * 2 * 6 + 2 * 2 * 3);
        // The copies and the hole point.
        let holes = s.flags.iter().filter(|&&f| f & HOLE != 0).count();
        assert_eq!(holes, 6);
        assert_eq!(s.flags[grid], HOLE);
        let fans = &s.indices[24..];
        for tri in fans.chunks(3) {
            assert_eq!(s.position[tri[2] as usize], [-1.0, -1.0, 0.0]);
            // Fan triangles lie on the copies, oriented like the patch seen
            // from +z (the hole point is outside the square, below-left).
            assert!(tri.iter().all(|&i| s.flags[i as usize] & HOLE != 0));
            let p: Vec<[f64; 3]> = tri.iter().map(|&i| s.position[i as usize]).collect();
            let area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
            assert!(area > 0.0, "{p:?}");
        }
        // The patch's own triangles keep the unflagged samples.
        for tri in s.indices[..24].chunks(3) {
            assert!(tri.iter().all(|&i| s.flags[i as usize] & HOLE == 0));
        }
    }
}
