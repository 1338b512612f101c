//! Sampling and triangulation of one patch, before welding: every patch gets
//! its own samples (shared edges are sampled once per patch and merged later),
//! laid out as [`super::layout`] with [`Sampling::Uniform`].

use super::layout::{PatchLayout, SampleAt, Sampling};
use super::Face;
use super::PatchGeometry;
use crate::evaluate::PatchRecord;
use crate::facevarying::PatchUv;
use crate::mem::{self, OutOfMemory};
use alloc::vec::Vec;
use capdiv::{IsoCurve, Point3, Real, TensorPatch};

/// The samples and faces of the patches pushed so far.
pub(super) struct Raw<R> {
    /// `n`, segments per side.
    grid: usize,
    /// `t[k] = k / (2n)`, `k = 0..=2n` (grid parameters are `t[2a]`).
    params: Vec<R>,
    /// The layouts met so far, by `split << 4 | hole` (`n` is `grid`; a
    /// layout with no samples is not built yet): built once each, not once
    /// per patch.
    layouts: Vec<PatchLayout>,
    /// Sample positions.
    pub positions: Vec<Point3<R>>,
    /// Per sample: its unit normal (zero where degenerate), `None` for a hole point.
    pub normals: Vec<Option<Point3<R>>>,
    /// Faces in sample indices.
    pub faces: Vec<Face>,
    /// Per face: its patch's tag.
    pub tags: Vec<u32>,
    /// Per sample: its UV; empty until a patch with UVs comes, then as long
    /// as `positions` after each such patch (earlier samples (0, 0)).
    pub uvs: Vec<[f64; 2]>,
    /// `k / (2n)` in `f64`, for the UVs.
    uv_params: Vec<f64>,
}

impl<R: Real> Raw<R> {
    /// An empty set for `grid` segments per side (its tables of a layout
    /// per kind of patch, a few KB, aborting if the system refuses them).
    pub fn new(grid: usize) -> Self {
        mem::or_abort(Self::try_new(grid))
    }

    /// [`Self::new`], its tables reserved fallibly.
    pub fn try_new(grid: usize) -> Result<Self, OutOfMemory> {
        let uv_params: Vec<f64> =
            mem::collect((0..=2 * grid).map(|k| k as f64 / (2 * grid) as f64))?;
        let params = mem::collect(uv_params.iter().map(|&t| R::from_f64(t)))?;
        Ok(Raw {
            grid,
            params,
            layouts: mem::filled(256, PatchLayout::default())?,
            positions: Vec::new(),
            normals: Vec::new(),
            faces: Vec::new(),
            tags: Vec::new(),
            uvs: Vec::new(),
            uv_params,
        })
    }

    /// Samples and triangulates `p`, its faces tagged `tag`. The room for
    /// them is reserved fallibly first: on an error nothing is pushed.
    pub fn push(&mut self, p: &PatchRecord<R>, tag: u32) -> Result<(), OutOfMemory> {
        let sampling = Sampling::Uniform(self.grid);
        let split = sampling.split_edges(p.level, p.finer);
        let which = usize::from(split) << 4 | usize::from(p.hole & 0xf);
        let mut layout = core::mem::take(&mut self.layouts[which]);
        layout.set(&sampling, p);
        if let Err(e) = self.reserve(&layout, p.uv.is_some()) {
            self.layouts[which] = layout;
            return Err(e);
        }
        let start = self.positions.len();
        match &p.geometry {
            PatchGeometry::Cubic(g) => self.push_samples(g, p, &layout),
            PatchGeometry::Quartic(g) => self.push_samples(g, p, &layout),
        }
        let base = start as u32;
        for f in &layout.faces {
            self.faces.push(f.map(|k| base + k));
            self.tags.push(tag);
        }
        if let Some(uv) = &p.uv {
            self.push_uvs(uv, &layout, start);
        }
        self.layouts[which] = layout;
        Ok(())
    }

    /// Room for `layout`'s samples and faces (and their UVs).
    fn reserve(&mut self, layout: &PatchLayout, uvs: bool) -> Result<(), OutOfMemory> {
        let (samples, faces) = (layout.samples.len(), layout.faces.len());
        mem::reserve(&mut self.positions, samples)?;
        mem::reserve(&mut self.normals, samples)?;
        mem::reserve(&mut self.faces, faces)?;
        mem::reserve(&mut self.tags, faces)?;
        if uvs {
            let more = (self.positions.len() + samples).saturating_sub(self.uvs.len());
            mem::reserve(&mut self.uvs, more)?;
        }
        Ok(())
    }

    /// The positions and normals of `layout`'s samples of `g`, the lattice
    /// line by line ([`PatchLayout::lines`]: one reduction along `v` per
    /// line, each point bit for bit `g.evaluate(u, v)`), positions moved by
    /// the record's origin where it has one ([`PatchRecord::origin`]).
    fn push_samples<const K: usize>(
        &mut self,
        g: &TensorPatch<R, K>,
        p: &PatchRecord<R>,
        layout: &PatchLayout,
    ) {
        let start = self.positions.len();
        self.positions
            .resize(start + layout.samples.len(), p.hole_point);
        self.normals.resize(start + layout.samples.len(), None);
        let lines = g.lines();
        // Absolute records (zero origin) keep their positions' bits: no
        // `+ 0`, which would turn a −0 coordinate into +0.
        let origin = (p.origin != Point3::ZERO).then_some(p.origin);
        let mut line = None;
        for &k in &layout.lines {
            let SampleAt::Lattice(i, j) = layout.samples[k as usize] else {
                continue;
            };
            let v = self.params[j as usize];
            if line
                .as_ref()
                .is_none_or(|l: &IsoCurve<'_, R, K>| l.v() != v)
            {
                // v ∈ [0, 1]: iso_v and evaluate cannot fail with OutOfDomain.
                line = lines.iso_v(v).ok();
            }
            let point = line.as_ref().map(|l| l.evaluate(self.params[i as usize]));
            let (pos, n) = match point {
                Some(Ok(pp)) => (
                    origin.map_or(pp.position, |o| pp.position + o),
                    pp.normal().unwrap_or(Point3::ZERO),
                ),
                _ => (Point3::ZERO, Point3::ZERO),
            };
            self.positions[start + k as usize] = pos;
            self.normals[start + k as usize] = Some(n);
        }
    }

    /// The UVs of the samples `start..` just pushed, laid out as `layout`.
    fn push_uvs(&mut self, uv: &PatchUv, layout: &PatchLayout, start: usize) {
        self.uvs.resize(start, [0.0; 2]);
        let t = &self.uv_params;
        for &at in &layout.samples {
            self.uvs.push(match at {
                SampleAt::Lattice(i, j) => uv.at(t[i as usize], t[j as usize]),
                SampleAt::HolePoint => uv.hole,
            });
        }
        debug_assert_eq!(self.uvs.len(), self.positions.len());
    }
}
