//! Sampling and triangulation of one patch, before welding: every patch gets
//! its own samples (shared edges are sampled once per patch and merged later).

use super::{Face, PatchGeometry};
use crate::evaluate::PatchRecord;
use crate::facevarying::PatchUv;
use alloc::vec::Vec;
use capdiv::{Point3, Real, TensorPatch};

/// The samples and faces of the patches pushed so far.
pub(super) struct Raw<R> {
    /// `n`, segments per side.
    grid: usize,
    /// `t[k] = k / (2n)`, `k = 0..=2n` (grid parameters are `t[2a]`).
    params: Vec<R>,
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
    pub fn new(grid: usize) -> Self {
        let uv_params: Vec<f64> = (0..=2 * grid)
            .map(|k| k as f64 / (2 * grid) as f64)
            .collect();
        let params = uv_params.iter().map(|&t| R::from_f64(t)).collect();
        Raw {
            grid,
            params,
            positions: Vec::new(),
            normals: Vec::new(),
            faces: Vec::new(),
            tags: Vec::new(),
            uvs: Vec::new(),
            uv_params,
        }
    }

    /// Samples and triangulates `p`, its faces tagged `tag`.
    pub fn push(&mut self, p: &PatchRecord<R>, tag: u32) {
        let start = self.positions.len();
        match &p.geometry {
            PatchGeometry::Cubic(g) => self.push_patch(g, p, tag),
            PatchGeometry::Quartic(g) => self.push_patch(g, p, tag),
        }
        if let Some(uv) = &p.uv {
            self.push_uvs(uv, p, start);
        }
    }

    /// The UVs of the samples `start..` just pushed for `p`, in the order
    /// [`Raw::push_patch`] takes them.
    fn push_uvs(&mut self, uv: &PatchUv, p: &PatchRecord<R>, start: usize) {
        self.uvs.resize(start, [0.0; 2]);
        let n = self.grid;
        let t = &self.uv_params;
        for a in 0..=n {
            for b in 0..=n {
                self.uvs.push(uv.at(t[2 * a], t[2 * b]));
            }
        }
        for e in 0..4u8 {
            if p.finer & (1 << e) == 0 {
                continue;
            }
            for c in 0..n {
                let m = 2 * c + 1;
                let (i, j) = match e {
                    0 => (m, 0),
                    1 => (2 * n, m),
                    2 => (m, 2 * n),
                    _ => (0, m),
                };
                self.uvs.push(uv.at(t[i], t[j]));
            }
        }
        if p.hole & 0xf != 0 {
            self.uvs.push(uv.hole);
        }
        debug_assert_eq!(self.uvs.len(), self.positions.len());
    }

    fn sample<const K: usize>(&mut self, g: &TensorPatch<R, K>, i: usize, j: usize) {
        let (u, v) = (self.params[i], self.params[j]);
        // (u, v) ∈ [0, 1]²: evaluate cannot fail with OutOfDomain.
        let (pos, n) = match g.evaluate(u, v) {
            Ok(pp) => (pp.position, pp.normal().unwrap_or(Point3::ZERO)),
            Err(_) => (Point3::ZERO, Point3::ZERO),
        };
        self.positions.push(pos);
        self.normals.push(Some(n));
    }

    fn push_patch<const K: usize>(&mut self, g: &TensorPatch<R, K>, p: &PatchRecord<R>, tag: u32) {
        let n = self.grid;
        let base = self.positions.len();
        let side = n + 1;
        // Grid points, a (along u) after a.
        for a in 0..side {
            for b in 0..side {
                self.sample(g, 2 * a, 2 * b);
            }
        }
        // Midpoints of finer edges, cell c of the edge between grid points c, c+1
        // (along u for edges 0 and 2, along v for 1 and 3).
        let finer = |e: u8| p.finer & (1 << e) != 0;
        let mut mid_base = [usize::MAX; 4];
        for e in 0..4u8 {
            if !finer(e) {
                continue;
            }
            mid_base[e as usize] = self.positions.len();
            for c in 0..n {
                let m = 2 * c + 1;
                let (i, j) = match e {
                    0 => (m, 0),
                    1 => (2 * n, m),
                    2 => (m, 2 * n),
                    _ => (0, m),
                };
                self.sample(g, i, j);
            }
        }
        let idx = |a: usize, b: usize| (base + a * side + b) as u32;
        let mid = |e: usize, c: usize| (mid_base[e] + c) as u32;

        // Cells: the square's corners counter-clockwise in (u, v), with the
        // midpoints of the finer sides it has between them.
        for a in 0..n {
            for b in 0..n {
                let mut poly = [0u32; 8];
                let mut len = 0;
                let mut first_mid = None;
                let mut put = |v: u32, is_mid: bool| {
                    if is_mid && first_mid.is_none() {
                        first_mid = Some(len);
                    }
                    poly[len] = v;
                    len += 1;
                };
                put(idx(a, b), false);
                if b == 0 && finer(0) {
                    put(mid(0, a), true);
                }
                put(idx(a + 1, b), false);
                if a + 1 == n && finer(1) {
                    put(mid(1, b), true);
                }
                put(idx(a + 1, b + 1), false);
                if b + 1 == n && finer(2) {
                    put(mid(2, a), true);
                }
                put(idx(a, b + 1), false);
                if a == 0 && finer(3) {
                    put(mid(3, b), true);
                }
                match first_mid {
                    None => self
                        .faces
                        .push(Face::Quad([poly[0], poly[1], poly[2], poly[3]])),
                    Some(s) => {
                        // Fan from a midpoint: never two collinear sides in
                        // one triangle (the cell is a convex square in (u, v)).
                        let at = |k: usize| poly[(s + k) % len];
                        for k in 1..len - 1 {
                            self.faces.push(Face::Tri([at(0), at(k), at(k + 1)]));
                        }
                    }
                }
                self.tags.extend(core::iter::repeat_n(
                    tag,
                    self.faces.len() - self.tags.len(),
                ));
            }
        }

        // Hole edges: the edge's samples in the patch's counter-clockwise
        // boundary order s0, s1, …; triangles (s[k+1], s[k], hole point).
        if p.hole & 0xf != 0 {
            let h = self.positions.len() as u32;
            self.positions.push(p.hole_point);
            self.normals.push(None);
            let mut run: Vec<u32> = Vec::with_capacity(2 * n + 1);
            for e in 0..4u8 {
                if p.hole & (1 << e) == 0 {
                    continue;
                }
                run.clear();
                for c in 0..n {
                    let (start, m) = match e {
                        0 => (idx(c, 0), c),
                        1 => (idx(n, c), c),
                        2 => (idx(n - c, n), n - 1 - c),
                        _ => (idx(0, n - c), n - 1 - c),
                    };
                    run.push(start);
                    if finer(e) {
                        run.push(mid(e as usize, m));
                    }
                }
                run.push(match e {
                    0 => idx(n, 0),
                    1 => idx(n, n),
                    2 => idx(0, n),
                    _ => idx(0, 0),
                });
                for w in run.windows(2) {
                    self.faces.push(Face::Tri([w[1], w[0], h]));
                    self.tags.push(tag);
                }
            }
        }
    }
}
