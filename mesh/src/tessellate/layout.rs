//! Where a patch is sampled and how its samples are joined into faces: the
//! one layout of every tessellation here. [`super::tessellate`] and the
//! streaming weld evaluate its samples' positions and normals; a caller
//! that wants other per-sample values (the browser viewer's curvatures from
//! the patch's jet) evaluates them itself at [`PatchLayout::parameters`].
//!
//! A patch of `n` segments per side has, in this order:
//!
//! 1. the `(n+1)²` grid samples `(u, v) = (a/n, b/n)`, `a` (along `u`)
//!    after `a`: sample `a·(n+1) + b`;
//! 2. for each edge `e` in `split` (bits as [`super::edge_bit`]), in edge
//!    order, its `n` midpoints `(2c+1)/(2n)` along the edge, cell `c`
//!    between grid samples `c` and `c+1` (along `u` for edges 0 and 2,
//!    along `v` for 1 and 3);
//! 3. with a hole edge, one hole point (not a point of the patch: the
//!    record's [`PatchRecord::hole_point`]).
//!
//! Faces: a grid cell is a [`Face::Quad`], or, with midpoints on its sides,
//! a fan of [`Face::Tri`]s from its first midpoint (never two collinear
//! sides in one triangle); each hole edge adds one triangle per segment,
//! `(s[k+1], s[k], hole point)` over its samples `s` in the patch's
//! counter-clockwise boundary order. Every face is counter-clockwise in
//! `(u, v)`.
//!
//! How many segments a patch gets is its [`Sampling`]: the same for every
//! patch, or halving level by level.

use super::Face;
use crate::evaluate::PatchRecord;
use alloc::vec::Vec;

/// Where one sample of a patch lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SampleAt {
    /// `(u, v) = (i, j) / (2n)` in the patch's own square, `n` its segments
    /// per side (grid samples have even `i` and `j`).
    Lattice(u32, u32),
    /// The hole point ([`PatchRecord::hole_point`]).
    HolePoint,
}

/// How many segments per side each patch gets, and so which of its finer
/// edges need midpoints.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sampling {
    /// `grid` segments for every patch (0 taken as 1): a finer edge is met
    /// by two patches of `grid` segments over its halves, so it gets
    /// midpoints ([`super::tessellate`]'s sampling).
    Uniform(usize),
    /// `grid >> (level − base)` segments (at least 1) for a patch of
    /// `level`: a patch a level finer has half the segments over half the
    /// size, so the samples along an edge are spaced alike on both sides. A
    /// finer edge gets midpoints only where that halving stops (a patch of
    /// one segment against two of one segment each). `grid` is a power of
    /// two (another is taken as the next power of two below it; 0 as 1),
    /// `base` the level of the coarsest patches.
    Halving {
        /// Segments per side at `base`.
        grid: usize,
        /// The level of the coarsest patches.
        base: u32,
    },
}

impl Sampling {
    /// Segments per side of a patch of `level`.
    pub fn segments(&self, level: u32) -> usize {
        match *self {
            Sampling::Uniform(grid) => grid.max(1),
            Sampling::Halving { grid, base } => {
                let grid = power_of_two_at_most(grid);
                let k = level.saturating_sub(base);
                if k >= usize::BITS {
                    1
                } else {
                    (grid >> k).max(1)
                }
            }
        }
    }

    /// The edges of a patch of `level` with `finer` edges that get
    /// midpoints: those whose two half-size neighbours have as many
    /// segments each as the patch.
    pub fn split_edges(&self, level: u32, finer: u8) -> u8 {
        if self.segments(level.saturating_add(1)) == self.segments(level) {
            finer & 0xf
        } else {
            0
        }
    }
}

/// The largest power of two at most `n` (1 for 0).
fn power_of_two_at_most(n: usize) -> usize {
    if n <= 1 {
        1
    } else {
        1 << (usize::BITS - 1 - n.leading_zeros())
    }
}

/// One patch's samples and faces (see the module doc); rebuilt in place
/// patch after patch, its buffers reused.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PatchLayout {
    /// `n`, segments per side.
    pub segments: usize,
    /// The edges with midpoints (bits as [`super::edge_bit`]).
    pub split: u8,
    /// The hole edges.
    pub hole: u8,
    /// Where each sample lies, in sample order.
    pub samples: Vec<SampleAt>,
    /// The faces, in indices into `samples`.
    pub faces: Vec<Face>,
    /// The [`SampleAt::Lattice`] samples' indices ordered by their `j` (and
    /// in sample order within one `j`): sampled in this order, a patch is
    /// reduced along `v` once per line ([`capdiv::TensorPatch::iso_v`]).
    pub lines: Vec<u32>,
}

impl PatchLayout {
    /// The layout of `p` under `sampling`.
    pub fn of<R>(sampling: &Sampling, p: &PatchRecord<R>) -> Self {
        let mut layout = PatchLayout::default();
        layout.set(sampling, p);
        layout
    }

    /// Makes this the layout of `p` under `sampling` (kept if it already is).
    pub fn set<R>(&mut self, sampling: &Sampling, p: &PatchRecord<R>) {
        let n = sampling.segments(p.level);
        let split = sampling.split_edges(p.level, p.finer);
        self.build(n, split, p.hole & 0xf);
    }

    /// Makes this the layout of a patch of `n ≥ 1` segments per side with
    /// midpoints on the edges `split` and hole edges `hole` (kept if it
    /// already is).
    pub fn build(&mut self, n: usize, split: u8, hole: u8) {
        let n = n.max(1);
        let (split, hole) = (split & 0xf, hole & 0xf);
        if !self.samples.is_empty() && (self.segments, self.split, self.hole) == (n, split, hole) {
            return;
        }
        self.segments = n;
        self.split = split;
        self.hole = hole;
        self.samples.clear();
        self.faces.clear();
        self.lines.clear();
        let side = n + 1;
        let lattice = |i: usize, j: usize| SampleAt::Lattice(i as u32, j as u32);
        for a in 0..side {
            for b in 0..side {
                self.samples.push(lattice(2 * a, 2 * b));
            }
        }
        let has = |bits: u8, e: u8| bits & (1 << e) != 0;
        let mut mid_base = [usize::MAX; 4];
        for e in 0..4u8 {
            if !has(split, e) {
                continue;
            }
            mid_base[e as usize] = self.samples.len();
            for c in 0..n {
                let m = 2 * c + 1;
                self.samples.push(match e {
                    0 => lattice(m, 0),
                    1 => lattice(2 * n, m),
                    2 => lattice(m, 2 * n),
                    _ => lattice(0, m),
                });
            }
        }
        let idx = |a: usize, b: usize| (a * side + b) as u32;
        let mid = |e: usize, c: usize| (mid_base[e] + c) as u32;

        // Cells: the square's corners counter-clockwise in (u, v), with the
        // midpoints of the split sides it has between them.
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
                if b == 0 && has(split, 0) {
                    put(mid(0, a), true);
                }
                put(idx(a + 1, b), false);
                if a + 1 == n && has(split, 1) {
                    put(mid(1, b), true);
                }
                put(idx(a + 1, b + 1), false);
                if b + 1 == n && has(split, 2) {
                    put(mid(2, a), true);
                }
                put(idx(a, b + 1), false);
                if a == 0 && has(split, 3) {
                    put(mid(3, b), true);
                }
                match first_mid {
                    None => self
                        .faces
                        .push(Face::Quad([poly[0], poly[1], poly[2], poly[3]])),
                    Some(s) => {
                        let at = |k: usize| poly[(s + k) % len];
                        for k in 1..len - 1 {
                            self.faces.push(Face::Tri([at(0), at(k), at(k + 1)]));
                        }
                    }
                }
            }
        }

        // Hole edges: the edge's samples in the patch's counter-clockwise
        // boundary order s0, s1, …; triangles (s[k+1], s[k], hole point).
        if hole != 0 {
            let h = self.samples.len() as u32;
            self.samples.push(SampleAt::HolePoint);
            let mut run: Vec<u32> = Vec::with_capacity(2 * n + 1);
            for e in 0..4u8 {
                if !has(hole, e) {
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
                    if has(split, e) {
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
                }
            }
        }
        self.lines.extend(
            self.samples
                .iter()
                .enumerate()
                .filter(|(_, at)| matches!(at, SampleAt::Lattice(..)))
                .map(|(k, _)| k as u32),
        );
        let samples = &self.samples;
        self.lines.sort_by_key(|&k| match samples[k as usize] {
            SampleAt::Lattice(_, j) => j,
            SampleAt::HolePoint => u32::MAX,
        });
    }

    /// The parameters `(u, v)` of a [`SampleAt::Lattice`] sample, in `f64`
    /// (`i / (2n)`, correctly rounded: a grid sample's `2a / (2n)` is
    /// `a / n`); `None` for the hole point.
    pub fn parameters(&self, at: SampleAt) -> Option<(f64, f64)> {
        match at {
            SampleAt::Lattice(i, j) => {
                let d = (2 * self.segments) as f64;
                Some((i as f64 / d, j as f64 / d))
            }
            SampleAt::HolePoint => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_hold_every_lattice_sample_once_ordered_by_v() {
        for (n, split, hole) in [
            (1, 0, 0),
            (4, 0b1111, 0),
            (3, 0b0101, 0b0010),
            (2, 0b1010, 0b1001),
        ] {
            let mut layout = PatchLayout::default();
            layout.build(n, split, hole);
            let lattice: Vec<u32> = (0..layout.samples.len() as u32)
                .filter(|&k| matches!(layout.samples[k as usize], SampleAt::Lattice(..)))
                .collect();
            let mut seen = layout.lines.clone();
            seen.sort_unstable();
            assert_eq!(seen, lattice, "n {n} split {split:04b} hole {hole:04b}");
            let j = |k: &u32| match layout.samples[*k as usize] {
                SampleAt::Lattice(_, j) => j,
                SampleAt::HolePoint => unreachable!("hole points are not on lines"),
            };
            assert!(layout.lines.windows(2).all(|w| j(&w[0]) <= j(&w[1])));
        }
    }

    #[test]
    fn halving_sampling_halves_the_segments_level_by_level_down_to_one() {
        let at = |grid, base, level| Sampling::Halving { grid, base }.segments(level);
        assert_eq!(at(8, 0, 0), 8);
        assert_eq!(at(8, 1, 2), 4);
        assert_eq!(at(8, 0, 3), 1);
        assert_eq!(at(8, 0, 9), 1);
        assert_eq!(at(8, 0, 200), 1);
        assert_eq!(at(8, 3, 0), 8);
        // Not a power of two: the one below; 0: 1.
        assert_eq!(at(12, 0, 0), 8);
        assert_eq!(at(0, 0, 0), 1);
        assert_eq!(Sampling::Uniform(5).segments(7), 5);
        assert_eq!(Sampling::Uniform(0).segments(0), 1);
    }

    #[test]
    fn finer_edges_get_midpoints_where_the_neighbours_have_as_many_segments() {
        let halving = Sampling::Halving { grid: 8, base: 0 };
        // Level 2: 2 segments against 1 + 1: no midpoint. Level 3: 1
        // against 1 + 1: midpoints.
        assert_eq!(halving.split_edges(2, 0b0011), 0);
        assert_eq!(halving.split_edges(3, 0b0011), 0b0011);
        assert_eq!(Sampling::Uniform(4).split_edges(0, 0b1010), 0b1010);
    }

    #[test]
    fn halved_patches_share_the_coarse_edge_parameters() {
        // A level-0 patch of 8 segments and the two level-1 halves of its
        // edge v = 0 (4 segments each, over [0, ½] and [½, 1]): the same
        // points of the edge.
        let halving = Sampling::Halving { grid: 8, base: 0 };
        let edge = |level: u32| {
            let mut l = PatchLayout::default();
            l.build(halving.segments(level), 0, 0);
            let on_edge: Vec<f64> = l
                .samples
                .iter()
                .filter_map(|&s| l.parameters(s))
                .filter(|&(_, v)| v == 0.0)
                .map(|(u, _)| u)
                .collect();
            on_edge
        };
        let coarse = edge(0);
        assert_eq!(coarse.len(), 9);
        let fine: Vec<f64> = edge(1)
            .iter()
            .flat_map(|&u| [0.5 * u, 0.5 + 0.5 * u])
            .collect();
        assert_eq!(fine.len(), 10);
        for u in fine {
            assert!(coarse.contains(&u), "{u}");
        }
    }

    #[test]
    fn a_one_segment_cell_with_midpoints_is_a_fan_from_its_first_midpoint() {
        let mut l = PatchLayout::default();
        l.build(1, 0b0011, 0);
        // 4 grid samples, then the midpoints of edges 0 and 1.
        assert_eq!(
            l.samples,
            [
                SampleAt::Lattice(0, 0),
                SampleAt::Lattice(0, 2),
                SampleAt::Lattice(2, 0),
                SampleAt::Lattice(2, 2),
                SampleAt::Lattice(1, 0),
                SampleAt::Lattice(2, 1),
            ]
        );
        assert_eq!(l.parameters(l.samples[5]), Some((1.0, 0.5)));
        // The hexagon (0,0), m0, (1,0), m1, (1,1), (0,1) = samples 0, 4, 2,
        // 5, 3, 1 fanned from m0.
        assert_eq!(
            l.faces,
            [
                Face::Tri([4, 2, 5]),
                Face::Tri([4, 5, 3]),
                Face::Tri([4, 3, 1]),
                Face::Tri([4, 1, 0]),
            ]
        );
    }

    #[test]
    fn hole_edges_fan_their_samples_to_one_hole_point() {
        let mut l = PatchLayout::default();
        // 2 segments, edge v = 0 split and a hole edge.
        l.build(2, 0b0001, 0b0001);
        // 9 grid samples, 2 midpoints, the hole point.
        assert_eq!(l.samples.len(), 12);
        assert_eq!(l.samples[11], SampleAt::HolePoint);
        assert_eq!(l.parameters(SampleAt::HolePoint), None);
        // Edge v = 0 in boundary order: (0,0), m, (1,0), m, (2,0) = samples
        // 0, 9, 3, 10, 6: four triangles (s[k+1], s[k], hole).
        let fan: Vec<Face> = l.faces[l.faces.len() - 4..].to_vec();
        assert_eq!(
            fan,
            [
                Face::Tri([9, 0, 11]),
                Face::Tri([3, 9, 11]),
                Face::Tri([10, 3, 11]),
                Face::Tri([6, 10, 11]),
            ]
        );
        // Rebuilding with other edges replaces it.
        l.build(2, 0, 0);
        assert_eq!((l.samples.len(), l.faces.len()), (9, 4));
    }
}
