//! Streaming welded tessellation: each patch is sampled and triangulated as
//! it arrives and its vertices and faces go to a [`MeshSink`] at once, so the
//! memory held is the weld front, not the output.
//!
//! The output is the welded mesh [`super::tessellate`] makes of the same
//! patches in the same order: the same vertices (numbered in the order of
//! their first sample, same positions and normals) and the same faces in the
//! same order, whenever welding joins no chain of samples that are each
//! within the tolerance of the next but not of each other (then the
//! collected tessellation merges the chain, the stream keeps its first
//! vertex and joins the sample to the lowest-numbered close one).
//!
//! # What is kept
//!
//! A vertex stays in the weld table while more samples may still weld into
//! it. Each sample records the share of a full turn around it that its patch
//! covers (in quarter turns): 1 at a patch corner, 2 on an edge or at the
//! midpoint of a finer edge, 4 inside; a hole edge adds the 2 of the fan
//! beyond it to its inner samples. A vertex whose turns add up to 4 is
//! surrounded by the patches that sample it and leaves the table when the
//! patch completing it is done. What never adds up stays: samples on the
//! surface's boundary (until [`StreamTessellator::finish`]), and the
//! corners of a cap's last hole and the hole's point, whose fans span an
//! angle of the hole's shape: they stay until the group of patches they
//! belong to ends (a cap's patches, or a run of patches of no cap). A patch
//! whose record marks its boundary edges ([`PatchRecord::boundary`]) adds
//! the outside's 2 to the samples inside them, and 1 per boundary edge at a
//! corner marked as two patches' boundary corner: those leave too.
//!
//! So the table holds the open edges between the patches done and the
//! patches to come, and what the records do not mark of the surface's
//! boundary. A [`crate::Evaluator`]
//! gives the regular patches and caps by input face, the faces taken
//! breadth first ([`crate::SurfacePlan::order`]): the open edges are those
//! of a front of input faces (for a mesh of `F` faces about `√F` of them)
//! and one cap's rings, not the surface behind it. (The adaptive
//! refinement's patches, around tags and irregular points without a cap,
//! come after the rest, in one run, and its caps after them: the runs'
//! hole corners need every patch around them before their run ends.)
//!
//! A vertex is handed to the sink once its normal is final: at once when its
//! first sample has a normal (`∂u × ∂v` not zero), otherwise when it leaves
//! the table (a cap's limit point, made of hole points only, gets the
//! normalised area-weighted sum of its faces' normals, as in
//! [`super::Tessellation::normals`]). Vertices and faces are handed over in
//! order, so output behind a vertex waiting for its normal waits too: one
//! cap's last ring, or, for holes of patches of no cap (adaptive rings
//! around irregular points), what follows the first such hole among those
//! patches.
//!
//! The closedness check follows every edge of the output in order, except
//! the edges at a sample inside a patch's lattice whose vertex the patch
//! made, when no two of the patch's samples welded together: the patch's
//! own faces (an oriented disk) use each of those once each way, and no
//! other face can reach the vertex, so the verdict is the same.
//!
//! Limits: on a non-manifold surface (an edge of three patches, a corner of
//! more than four outside a hole) a vertex can leave the table before its
//! last sample, which then makes a second vertex; the closedness check sees
//! each edge in order and reports an edge used more than twice as unpaired
//! or as used twice in the same direction.

use super::sample::Raw;
use super::{BadEdge, EdgeFault, Face};
use crate::evaluate::{CapRecord, PatchRecord, SurfaceSink};
use crate::mem::{self, OutOfMemory};
use alloc::collections::VecDeque;
use alloc::vec::Vec;
use capdiv::{Point3, Real};
use core::fmt::{Display, LowerExp, Write};
use hashbrown::hash_map::Entry;
use hashbrown::HashMap;

/// Receives a streamed tessellation.
pub trait MeshSink<R> {
    /// The next vertex (numbered 0, 1, … in call order) and its unit normal
    /// (zero where every sample is degenerate).
    fn vertex(&mut self, position: Point3<R>, normal: Point3<R>);
    /// A face over vertices already given, with its patch's tag.
    fn face(&mut self, face: Face, tag: u32);
}

/// Collects a streamed tessellation into a [`super::Tessellation`] (its
/// `samples` and `degenerate_dropped` from [`StreamSummary`]).
impl<R> MeshSink<R> for super::Tessellation<R> {
    fn vertex(&mut self, position: Point3<R>, normal: Point3<R>) {
        self.positions.push(position);
        self.normals.push(normal);
    }
    fn face(&mut self, face: Face, tag: u32) {
        self.faces.push(face);
        self.tags.push(tag);
    }
}

/// Counts of a finished stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StreamSummary {
    /// Vertices handed over.
    pub vertices: usize,
    /// Triangles handed over.
    pub triangles: usize,
    /// Quads handed over.
    pub quads: usize,
    /// Samples taken (grid points, edge midpoints, hole points).
    pub samples: usize,
    /// Faces dropped because welding made two of their corners equal.
    pub degenerate_dropped: usize,
    /// The closedness check ([`super::is_closed_and_oriented`] on a
    /// manifold output; see the module doc).
    pub closed: Result<(), BadEdge>,
    /// The most vertices the weld table held at once.
    pub peak_weld: usize,
    /// The most vertices and faces waiting at once for a vertex's normal.
    pub peak_waiting: usize,
}

/// No slot.
const NONE: u32 = u32::MAX;
/// A full turn, in quarter turns.
const WHOLE: u8 = 4;
/// Cell size in tolerances (as [`super::weld`]).
const CELL: f64 = 32.0;

/// A vertex in the weld table (its weld coordinates and cell are those of
/// `position`: [`weld_coordinates`]).
struct Slot<R> {
    /// The next slot of its cell.
    next: u32,
    /// Its cell's name in the table ([`cell_name`]).
    cell: u64,
    vertex: u32,
    /// Quarter turns covered so far (saturating).
    turns: u8,
    /// Kept until its group ends (a hole's point or corner).
    pinned: bool,
    live: bool,
    position: Point3<R>,
    normal: Point3<R>,
    /// Some patch sample (not only hole points) went into it.
    sampled: bool,
    /// Its normal is final (handed over, or set in the waiting queue).
    done: bool,
    /// Its place in the waiting queue (absolute), when not handed over.
    seq: u64,
    /// The last patch that sampled it ([`StreamTessellator::patches`]).
    patch: u64,
}

/// Output waiting for a vertex's normal.
enum Waiting<R> {
    Vertex(Point3<R>, Option<Point3<R>>),
    Face(Face, u32),
}

/// A point's coordinates in `f64`, `−0` made `+0`: what welding compares.
fn weld_coordinates<R: Real>(p: Point3<R>) -> [f64; 3] {
    p.0.map(|c| c.to_f64() + 0.0)
}

/// `floor(q)` as an `i64`, saturating, NaN taken as 0: what
/// `libm::floor(q) as i64` gives, without the bit-level `floor` (a truncating
/// cast and one comparison).
#[inline]
fn floor_to_i64(q: f64) -> i64 {
    let t = q as i64;
    if t as f64 > q {
        t.saturating_sub(1)
    } else {
        t
    }
}

/// One number naming a cell of the weld grid. Two cells may share a name:
/// their slots then share a chain, which only lengthens the search (every
/// candidate's distance is checked), never changes what it finds.
#[inline]
fn cell_name(key: [i64; 3]) -> u64 {
    (key[0] as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (key[1] as u64)
            .wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
            .rotate_left(21)
        ^ (key[2] as u64)
            .wrapping_mul(0x1656_67B1_9E37_79F9)
            .rotate_left(42)
}

/// `|x / cell|` below which the fraction of `x / cell` is meaningful to
/// well within `1 / CELL`: the quotient's rounding error is then at most
/// `2⁻¹³` of a cell.
const FRACTION_MEANINGFUL: f64 = (1u64 << 40) as f64;

/// A point's weld cell and the cells a search covers: per axis (bit `d`),
/// whether the neighbour below and the one above are searched too.
struct Near {
    key: [i64; 3],
    below: u8,
    above: u8,
}

impl Near {
    /// Only the point's own cell is searched.
    #[inline]
    fn single(&self) -> bool {
        self.below | self.above == 0
    }

    /// The first cell searched along axis `d`.
    #[inline]
    fn lo(&self, d: usize) -> i64 {
        self.key[d].saturating_sub(i64::from(self.below >> d & 1))
    }

    /// The last cell searched along axis `d` (`lo(d) ≤ key[d] ≤ hi(d)`).
    #[inline]
    fn hi(&self, d: usize) -> i64 {
        self.key[d].saturating_add(i64::from(self.above >> d & 1))
    }
}

/// Among the slots chained from `s` within `tol` of `x` (per coordinate)
/// and `best`, the one of the lowest-numbered vertex, into `best`.
#[inline]
fn closest_in_chain<R: Real>(
    slots: &[Slot<R>],
    mut s: u32,
    x: &[f64; 3],
    tol: f64,
    best: &mut Option<u32>,
) {
    while s != NONE {
        let slot = &slots[s as usize];
        let y = weld_coordinates(slot.position);
        if (0..3).all(|d| libm::fabs(x[d] - y[d]) <= tol)
            && best.is_none_or(|b| slot.vertex < slots[b as usize].vertex)
        {
            *best = Some(s);
        }
        s = slot.next;
    }
}

/// An edge used by one face so far.
struct OpenEdge {
    from: u32,
    to: u32,
    seq: u64,
    face: usize,
}

/// Streaming welded tessellator (see the module doc).
pub struct StreamTessellator<R> {
    raw: Raw<R>,
    grid: usize,
    tol: f64,
    /// The first slot of each cell, by [`cell_name`].
    cells: HashMap<u64, u32>,
    slots: Vec<Slot<R>>,
    free: Vec<u32>,
    /// Per slot of hole points only: twice the vector area of its faces.
    areas: HashMap<u32, Point3<R>>,
    live: usize,
    /// Per sample of the current patch: its slot, turns, pinned.
    local: Vec<u32>,
    turns: Vec<u8>,
    pin: Vec<bool>,
    /// Per sample of the current patch: inside its lattice (not on the
    /// square's sides).
    interior: Vec<bool>,
    /// What `turns`, `pin` and `interior` were classified for: the sample
    /// count and the record's boundary, hole and finer bits.
    classified: Option<(usize, u8, u8, u8)>,
    /// Per sample of the current patch: its edges need no closedness check
    /// (see `push`).
    paired_here: Vec<bool>,
    /// Patches pushed so far.
    patches: u64,
    /// No two samples of the current patch welded into one vertex.
    injective: bool,
    /// The current group (`None` before the first patch).
    group: Option<Option<u32>>,
    pins: Vec<u32>,
    queue: VecDeque<Waiting<R>>,
    queue_front: u64,
    edges: HashMap<u64, OpenEdge>,
    edge_seq: u64,
    blame: Option<(u64, BadEdge)>,
    summary: StreamSummary,
    /// The allocation refused, after which the stream takes no more.
    refused: Option<OutOfMemory>,
}

impl<R: Real> StreamTessellator<R> {
    /// A tessellator with `grid` segments per patch side (`0` taken as 1)
    /// that welds samples within `weld_tolerance` (per coordinate; negative
    /// or NaN taken as 0: equal coordinates only), as [`super::tessellate`].
    pub fn new(grid: usize, weld_tolerance: R) -> Self {
        let tol = weld_tolerance.to_f64();
        StreamTessellator {
            raw: Raw::new(grid.max(1)),
            grid: grid.max(1),
            tol: if tol > 0.0 { tol } else { 0.0 },
            cells: HashMap::new(),
            slots: Vec::new(),
            free: Vec::new(),
            areas: HashMap::new(),
            live: 0,
            local: Vec::new(),
            turns: Vec::new(),
            pin: Vec::new(),
            interior: Vec::new(),
            classified: None,
            paired_here: Vec::new(),
            patches: 0,
            injective: true,
            group: None,
            pins: Vec::new(),
            queue: VecDeque::new(),
            queue_front: 0,
            edges: HashMap::new(),
            edge_seq: 0,
            blame: None,
            summary: StreamSummary {
                vertices: 0,
                triangles: 0,
                quads: 0,
                samples: 0,
                degenerate_dropped: 0,
                closed: Ok(()),
                peak_weld: 0,
                peak_waiting: 0,
            },
            refused: None,
        }
    }

    /// The allocation the system refused, if it refused one: the stream
    /// then stopped taking patches (what was handed to the sink before is
    /// a prefix of the output, and [`Self::finish`] hands over nothing
    /// more; its summary then counts that prefix, and its `closed` speaks
    /// of the prefix's edges, not of the surface). Every table whose size
    /// depends on the input (the weld
    /// table, the waiting output, the open edges, a patch's samples) is
    /// reserved fallibly before it grows.
    pub fn refused(&self) -> Option<OutOfMemory> {
        self.refused
    }

    /// Tessellates one patch, its faces tagged `tag`, and hands what is
    /// final to `sink`. The patch's group is its cap ([`PatchRecord::cap`];
    /// `None`: no cap): a patch of another group than the previous one ends
    /// that group ([`Self::end_group`]). Samples inside the edges that
    /// [`PatchRecord::boundary`] marks, and at a boundary corner of two
    /// patches once both are done, leave the table at once instead of at
    /// [`Self::finish`]; wrong bits make a vertex leave before its last
    /// sample, which then makes a second vertex. The streaming weld carries
    /// positions and normals only: [`PatchRecord::uv`] is not used.
    ///
    /// After a refused allocation ([`Self::refused`]) it does nothing.
    ///
    /// # Panics
    ///
    /// If the vertices outnumber `u32::MAX`.
    pub fn push(&mut self, p: &PatchRecord<R>, tag: u32, sink: &mut dyn MeshSink<R>) {
        if self.refused.is_some() {
            return;
        }
        if self.group != Some(p.cap) {
            self.end_group(sink);
            if self.refused.is_some() {
                return;
            }
            self.group = Some(p.cap);
        }
        self.raw.positions.clear();
        self.raw.normals.clear();
        self.raw.faces.clear();
        self.raw.tags.clear();
        self.raw.uvs.clear();
        // The room for the patch first (then nothing below grows).
        if let Err(e) = self.raw.push(p, tag).and_then(|()| self.reserve_patch()) {
            self.refused = Some(e);
            return;
        }
        self.raw.uvs.clear();
        self.classify(p, p.boundary);
        let count = self.raw.positions.len();
        self.summary.samples += count;
        self.local.clear();
        self.patches += 1;
        self.injective = true;
        let first_vertex = self.summary.vertices;
        for k in 0..count {
            let s = self.weld(k);
            self.local.push(s);
        }
        // An interior sample whose vertex this patch made, in a patch whose
        // samples all have vertices of their own: its faces are those of the
        // layout around it, which pair each of its edges once each way
        // (an oriented disk), and no other patch reaches the vertex (it
        // leaves the table after this patch).
        self.paired_here.clear();
        for k in 0..count {
            let here = self.interior[k]
                && self.injective
                && self.slots[self.local[k] as usize].vertex as usize >= first_vertex;
            self.paired_here.push(here);
        }
        for f in 0..self.raw.faces.len() {
            let (face, tag) = (self.raw.faces[f], self.raw.tags[f]);
            self.face(face, tag);
        }
        for k in 0..count {
            let s = self.local[k];
            let slot = &self.slots[s as usize];
            if slot.live && !slot.pinned && slot.turns >= WHOLE {
                self.evict(s);
            }
        }
        self.flush(sink);
    }

    /// Room for what the patch in `raw` can add: a slot, a cell, a pin, a
    /// freed slot and a waiting vertex per sample, a waiting face and four
    /// open edges and hole areas per face, and the per-sample lists. Within
    /// it nothing grows while the patch is taken in. (Kept out of line: the
    /// checks cost less than the code they would add to `push`.)
    #[inline(never)]
    fn reserve_patch(&mut self) -> Result<(), OutOfMemory> {
        let (samples, faces) = (self.raw.positions.len(), self.raw.faces.len());
        for list in [&mut self.local, &mut self.pins, &mut self.free] {
            mem::reserve(list, samples)?;
        }
        mem::reserve(&mut self.turns, samples)?;
        mem::reserve(&mut self.pin, samples)?;
        mem::reserve(&mut self.interior, samples)?;
        mem::reserve(&mut self.paired_here, samples)?;
        mem::reserve(&mut self.slots, samples)?;
        mem::reserve_map(&mut self.cells, samples)?;
        mem::reserve_map(&mut self.areas, faces)?;
        mem::reserve_map(&mut self.edges, 4 * faces)?;
        self.reserve_queue(samples + faces)
    }

    /// Room for `more` waiting vertices and faces.
    fn reserve_queue(&mut self, more: usize) -> Result<(), OutOfMemory> {
        self.queue
            .try_reserve(more)
            .map_err(|_| OutOfMemory::of::<Waiting<R>>(self.queue.len().saturating_add(more)))
    }

    /// Ends the current group: its holes' points and corners leave the
    /// table, their vertices get their normals, and what waited for them is
    /// handed over.
    pub fn end_group(&mut self, sink: &mut dyn MeshSink<R>) {
        if self.refused.is_some() {
            return;
        }
        if let Err(e) = self.try_end_group(sink) {
            self.refused = Some(e);
        }
    }

    /// [`Self::end_group`], the room for the slots it frees reserved first.
    fn try_end_group(&mut self, sink: &mut dyn MeshSink<R>) -> Result<(), OutOfMemory> {
        mem::reserve(&mut self.free, self.pins.len())?;
        let pins = core::mem::take(&mut self.pins);
        for &s in &pins {
            if self.slots[s as usize].live {
                self.slots[s as usize].pinned = false;
                self.evict(s);
            }
        }
        self.pins = pins;
        self.pins.clear();
        self.flush(sink);
        Ok(())
    }

    /// Ends the stream: every vertex still held gets its normal and is handed
    /// over with the faces waiting for it. Returns the counts.
    pub fn finish(&mut self, sink: &mut dyn MeshSink<R>) -> StreamSummary {
        self.end_group(sink);
        if self.refused.is_none() {
            match mem::reserve(&mut self.free, self.slots.len()) {
                Ok(()) => {
                    for s in 0..self.slots.len() {
                        if self.slots[s].live {
                            self.evict(s as u32);
                        }
                    }
                    self.flush(sink);
                }
                Err(e) => self.refused = Some(e),
            }
        }
        let mut first = self.blame;
        for e in self.edges.values() {
            if first.is_none_or(|(t, _)| e.seq < t) {
                first = Some((
                    e.seq,
                    BadEdge {
                        from: e.from,
                        to: e.to,
                        face: e.face,
                        fault: EdgeFault::Unpaired,
                    },
                ));
            }
        }
        self.summary.closed = match first {
            None => Ok(()),
            Some((_, b)) => Err(b),
        };
        self.summary
    }

    /// The counts so far.
    pub fn summary(&self) -> StreamSummary {
        self.summary
    }

    /// Turns and pins of the current patch's samples, from their layout
    /// ([`super::layout`]): `(n+1)²` grid points (`a` along `u` after `a`), then
    /// `n` midpoints per finer edge in edge order, then the hole point. A
    /// boundary edge adds the 2 of the outside to its inner samples, and 1 to
    /// each end that is a boundary corner of two patches (whose other
    /// boundary edge adds the other 1).
    fn classify(&mut self, p: &PatchRecord<R>, boundary: u8) {
        let n = self.grid;
        let side = n + 1;
        let count = self.raw.positions.len();
        let key = (count, boundary, p.hole & 0xf, p.finer & 0xf);
        if self.classified == Some(key) {
            return;
        }
        self.classified = Some(key);
        self.turns.clear();
        self.pin.clear();
        self.interior.clear();
        for k in 0..count {
            let t = if k < side * side {
                let (a, b) = (k / side, k % side);
                match (a == 0 || a == n, b == 0 || b == n) {
                    (true, true) => 1,
                    (true, false) | (false, true) => 2,
                    _ => WHOLE,
                }
            } else {
                2
            };
            self.turns.push(t);
            self.pin.push(false);
            self.interior.push(t == WHOLE);
        }
        let idx = |a: usize, b: usize| a * side + b;
        // Corner `e` of the square (edge `e` runs from corner `e` to `e + 1`)
        // and the `c`-th sample inside edge `e`.
        let corner = [idx(0, 0), idx(n, 0), idx(n, n), idx(0, n)];
        let inside = |e: usize, c: usize| match e {
            0 => idx(c, 0),
            1 => idx(n, c),
            2 => idx(c, n),
            _ => idx(0, c),
        };
        if boundary & 0xf != 0 {
            for e in (0..4).filter(|e| boundary & (1 << e) != 0) {
                for c in 1..n {
                    let k = inside(e, c);
                    self.turns[k] = self.turns[k].saturating_add(2);
                }
                for end in [e, (e + 1) % 4] {
                    if boundary & (1 << (4 + end)) != 0 {
                        let k = corner[end];
                        self.turns[k] = self.turns[k].saturating_add(1);
                    }
                }
            }
        }
        if p.hole & 0xf == 0 {
            return;
        }
        // The hole point.
        self.turns[count - 1] = 0;
        self.pin[count - 1] = true;
        let mut mid = side * side;
        for e in 0..4u8 {
            let finer = p.finer & (1 << e) != 0;
            if p.hole & (1 << e) != 0 {
                let e = usize::from(e);
                let (from, to) = (corner[e], corner[(e + 1) % 4]);
                for c in 1..n {
                    let k = inside(e, c);
                    self.turns[k] = self.turns[k].saturating_add(2);
                }
                if finer {
                    for k in mid..mid + n {
                        self.turns[k] = self.turns[k].saturating_add(2);
                    }
                }
                self.pin[from] = true;
                self.pin[to] = true;
            }
            if finer {
                mid += n;
            }
        }
    }

    /// Welds sample `k` of the current patch; returns its slot.
    fn weld(&mut self, k: usize) -> u32 {
        let position = self.raw.positions[k];
        let x = weld_coordinates(position);
        let near = self.near(&x);
        let s = if near.single() {
            // One cell to search: the search and the insertion share a
            // look-up.
            self.insert(cell_name(near.key), position, Some(&x))
        } else {
            match self.find(&x, &near) {
                Some(s) => s,
                None => self.insert(cell_name(near.key), position, None),
            }
        };
        let new = self.slots[s as usize].vertex == NONE;
        if self.slots[s as usize].patch == self.patches {
            self.injective = false;
        }
        self.slots[s as usize].patch = self.patches;
        {
            let slot = &mut self.slots[s as usize];
            slot.turns = slot.turns.saturating_add(self.turns[k]);
            if let Some(nrm) = self.raw.normals[k] {
                slot.sampled = true;
                if slot.normal == Point3::ZERO {
                    slot.normal = nrm;
                }
            }
        }
        if self.pin[k] && !self.slots[s as usize].pinned {
            self.slots[s as usize].pinned = true;
            self.pins.push(s);
        }
        if new {
            let vertex = u32::try_from(self.summary.vertices)
                .expect("tessellate: more than u32::MAX vertices");
            self.summary.vertices += 1;
            let seq = self.queue_front + self.queue.len() as u64;
            let slot = &mut self.slots[s as usize];
            slot.vertex = vertex;
            slot.seq = seq;
            let known = (slot.sampled && slot.normal != Point3::ZERO).then_some(slot.normal);
            slot.done = known.is_some();
            self.queue.push_back(Waiting::Vertex(slot.position, known));
        } else {
            let slot = &self.slots[s as usize];
            if !slot.done && slot.sampled && slot.normal != Point3::ZERO {
                self.finalize(s);
            }
        }
        s
    }

    /// The slot of the lowest-numbered vertex within the tolerance of `x`,
    /// searched in the cells `near` names ([`Self::near`]).
    fn find(&self, x: &[f64; 3], near: &Near) -> Option<u32> {
        let tol = self.tol;
        let mut best: Option<u32> = None;
        let lo = [near.lo(0), near.lo(1), near.lo(2)];
        let hi = [near.hi(0), near.hi(1), near.hi(2)];
        // `lo[d] ..= hi[d]` (never empty: `lo ≤ key ≤ hi`), counted by hand:
        // a `RangeInclusive` checks its own exhaustion on every step.
        let mut i = lo[0];
        loop {
            let mut j = lo[1];
            loop {
                let mut l = lo[2];
                loop {
                    let name = cell_name([i, j, l]);
                    let head = self.cells.get(&name).copied().unwrap_or(NONE);
                    closest_in_chain(&self.slots, head, x, tol, &mut best);
                    if l >= hi[2] {
                        break;
                    }
                    l += 1;
                }
                if j >= hi[1] {
                    break;
                }
                j += 1;
            }
            if i >= hi[0] {
                break;
            }
            i += 1;
        }
        best
    }

    /// The cell of `x` and the cells around it that may hold a point within
    /// the tolerance. A cell is [`CELL`] tolerances wide, so a point within
    /// the tolerance lies in the cell of `x` or, when `x` is within a
    /// tolerance of a cell face, in the neighbour across it; the neighbour is
    /// searched whenever `x` is within two tolerances of the face (room for
    /// the rounding of `x / cell`), and both neighbours where `x / cell` is
    /// too large for its fraction to mean anything. Searching more cells
    /// than hold candidates finds the same vertex. With a zero tolerance the
    /// cell is the exact coordinates.
    fn near(&self, x: &[f64; 3]) -> Near {
        if self.tol == 0.0 {
            return Near {
                key: x.map(|c| c.to_bits() as i64),
                below: 0,
                above: 0,
            };
        }
        let cell = CELL * self.tol;
        let mut near = Near {
            key: [0; 3],
            below: 0,
            above: 0,
        };
        for (d, &c) in x.iter().enumerate() {
            let q = c / cell;
            // Saturating; NaN gives 0.
            let k = floor_to_i64(q);
            // Both neighbours where the fraction means nothing (NaN too,
            // hence the negated comparison).
            #[allow(clippy::neg_cmp_op_on_partial_ord)]
            let wide = !(libm::fabs(q) < FRACTION_MEANINGFUL);
            let f = q - k as f64;
            near.key[d] = k;
            near.below |= u8::from(wide | (f < 2.0 / CELL)) << d;
            near.above |= u8::from(wide | (f > 1.0 - 2.0 / CELL)) << d;
        }
        near
    }

    /// A new slot for a new vertex in cell `cell` (its number set by the
    /// caller), chained in front of the cell's others. With `search`, first
    /// the lowest-numbered vertex of that cell within the tolerance of the
    /// point, as [`Self::find`] of that one cell gives it, if there is one:
    /// one look-up in the cell table for the search and the insertion.
    fn insert(&mut self, cell: u64, position: Point3<R>, search: Option<&[f64; 3]>) -> u32 {
        let tol = self.tol;
        let s = self.free.last().copied().unwrap_or(self.slots.len() as u32);
        let head = match self.cells.entry(cell) {
            Entry::Occupied(mut first) => {
                if let Some(x) = search {
                    let mut best: Option<u32> = None;
                    closest_in_chain(&self.slots, *first.get(), x, tol, &mut best);
                    if let Some(b) = best {
                        return b;
                    }
                }
                core::mem::replace(first.get_mut(), s)
            }
            Entry::Vacant(none) => {
                none.insert(s);
                NONE
            }
        };
        let slot = Slot {
            next: head,
            cell,
            vertex: NONE,
            turns: 0,
            pinned: false,
            live: true,
            position,
            normal: Point3::ZERO,
            sampled: false,
            done: false,
            seq: 0,
            patch: 0,
        };
        let s = match self.free.pop() {
            Some(s) => {
                self.slots[s as usize] = slot;
                s
            }
            None => {
                self.slots.push(slot);
                (self.slots.len() - 1) as u32
            }
        };
        self.live += 1;
        self.summary.peak_weld = self.summary.peak_weld.max(self.live);
        s
    }

    /// Takes a slot out of the table; its vertex's normal becomes final.
    fn evict(&mut self, s: u32) {
        self.finalize(s);
        if !self.areas.is_empty() {
            self.areas.remove(&s);
        }
        let key = self.slots[s as usize].cell;
        let next = self.slots[s as usize].next;
        if let Entry::Occupied(mut first) = self.cells.entry(key) {
            let head = *first.get();
            if head == s {
                if next == NONE {
                    first.remove();
                } else {
                    *first.get_mut() = next;
                }
            } else {
                let mut t = head;
                while t != NONE {
                    if self.slots[t as usize].next == s {
                        self.slots[t as usize].next = next;
                        break;
                    }
                    t = self.slots[t as usize].next;
                }
            }
        }
        let slot = &mut self.slots[s as usize];
        slot.live = false;
        slot.pinned = false;
        slot.vertex = NONE;
        self.free.push(s);
        self.live -= 1;
    }

    /// Sets the waiting vertex's normal: the first sample normal, or the
    /// normalised area of its faces for a vertex of hole points only.
    fn finalize(&mut self, s: u32) {
        let slot = &mut self.slots[s as usize];
        if slot.done {
            return;
        }
        slot.done = true;
        let normal = if slot.sampled {
            slot.normal
        } else {
            let area = self.areas.get(&s).copied().unwrap_or(Point3::ZERO);
            let len = area.norm();
            if len > R::ZERO && len.is_finite() {
                area * (R::ONE / len)
            } else {
                Point3::ZERO
            }
        };
        let at = (slot.seq - self.queue_front) as usize;
        if let Some(Waiting::Vertex(_, n)) = self.queue.get_mut(at) {
            *n = Some(normal);
        }
    }

    /// One face of the current patch, in sample indices.
    fn face(&mut self, f: Face, tag: u32) {
        let slots: Face = f.map(|k| self.local[k as usize]);
        let face = slots.map(|s| self.slots[s as usize].vertex);
        if face.is_degenerate() {
            self.summary.degenerate_dropped += 1;
            return;
        }
        let c = slots.corners();
        // Hole points only: the face's twice vector area (Newell), about its
        // first corner, as `super::tessellate` sums it.
        if c.iter().any(|&s| !self.slots[s as usize].sampled) {
            let p0 = self.slots[c[0] as usize].position;
            let mut area = Point3::ZERO;
            for i in 1..c.len() - 1 {
                let a = self.slots[c[i] as usize].position - p0;
                let b = self.slots[c[i + 1] as usize].position - p0;
                area += a.cross(b);
            }
            for &s in c {
                if !self.slots[s as usize].sampled {
                    *self.areas.entry(s).or_insert(Point3::ZERO) += area;
                }
            }
        }
        let index = self.summary.triangles + self.summary.quads;
        match face {
            Face::Tri(_) => self.summary.triangles += 1,
            Face::Quad(_) => self.summary.quads += 1,
        }
        let v = face.corners();
        // Per corner: its edges are paired inside this patch (see `push`).
        let mut here = [false; 4];
        for (h, &k) in here.iter_mut().zip(f.corners()) {
            *h = self.paired_here[k as usize];
        }
        if here[..v.len()].iter().all(|&h| h) {
            self.edge_seq += v.len() as u64;
        } else {
            for i in 0..v.len() {
                let j = if i + 1 == v.len() { 0 } else { i + 1 };
                if here[i] || here[j] {
                    // Numbered all the same.
                    self.edge_seq += 1;
                } else {
                    self.edge(v[i], v[j], index);
                }
            }
        }
        self.queue.push_back(Waiting::Face(face, tag));
    }

    /// One directed edge of face `face`, for the closedness check.
    fn edge(&mut self, a: u32, b: u32, face: usize) {
        let seq = self.edge_seq;
        self.edge_seq += 1;
        let key = ((a.min(b) as u64) << 32) | a.max(b) as u64;
        let mut blame = |seq: u64, from: u32, to: u32, face: usize, fault: EdgeFault| {
            if self.blame.is_none_or(|(t, _)| seq < t) {
                self.blame = Some((
                    seq,
                    BadEdge {
                        from,
                        to,
                        face,
                        fault,
                    },
                ));
            }
        };
        let first = match self.edges.entry(key) {
            Entry::Occupied(first) => first.remove(),
            Entry::Vacant(none) => {
                none.insert(OpenEdge {
                    from: a,
                    to: b,
                    seq,
                    face,
                });
                return;
            }
        };
        if first.from == a {
            blame(first.seq, a, b, first.face, EdgeFault::SameDirection);
        }
    }

    /// Hands over the waiting output up to the first vertex without a normal.
    fn flush(&mut self, sink: &mut dyn MeshSink<R>) {
        self.summary.peak_waiting = self.summary.peak_waiting.max(self.queue.len());
        while let Some(front) = self.queue.front() {
            match *front {
                Waiting::Vertex(p, Some(n)) => sink.vertex(p, n),
                Waiting::Vertex(_, None) => break,
                Waiting::Face(f, tag) => sink.face(f, tag),
            }
            self.queue.pop_front();
            self.queue_front += 1;
        }
    }
}

/// A [`SurfaceSink`] that tessellates the evaluator's patches as they come
/// ([`StreamTessellator::push`], each face tagged `tag(its patch)`)
/// and ends each cap's group at its record. Call
/// [`StreamTessellator::finish`] after the evaluation.
pub struct TessellatingSink<'a, R, S> {
    /// The tessellator.
    pub tess: &'a mut StreamTessellator<R>,
    /// Where the vertices and faces go.
    pub out: &'a mut S,
    /// The tag of a patch's faces.
    pub tag: fn(&PatchRecord<R>) -> u32,
}

impl<R: Real, S: MeshSink<R>> SurfaceSink<R> for TessellatingSink<'_, R, S> {
    fn patch(&mut self, p: &PatchRecord<R>) {
        self.tess.push(p, (self.tag)(p), self.out);
    }
    fn cap(&mut self, _: &CapRecord<R>) {
        self.tess.end_group(self.out);
    }
}

/// A [`MeshSink`] that writes Wavefront OBJ text as it comes: a `v` and a
/// `vn` line per vertex and an `f a//a b//b c//c` line per face (1-based),
/// numbers as [`super::write_number`]. The lines are those of
/// [`super::write_obj`] for the same tessellation, faces interleaved with
/// the vertices (every face after its vertices). The first write error is
/// kept in [`ObjWriter::error`] and later output dropped.
pub struct ObjWriter<W> {
    /// The text output.
    pub out: W,
    /// The first write error.
    pub error: core::fmt::Result,
    vertices: u64,
    line: alloc::string::String,
}

impl<W: Write> ObjWriter<W> {
    /// A writer that first writes `header` lines as `#` comments.
    pub fn new(mut out: W, header: &[&str]) -> Self {
        let mut error = Ok(());
        for line in header {
            if error.is_ok() {
                error = writeln!(out, "# {line}");
            }
        }
        ObjWriter {
            out,
            error,
            vertices: 0,
            line: alloc::string::String::new(),
        }
    }

    /// Vertices written so far.
    pub fn vertices(&self) -> u64 {
        self.vertices
    }
}

impl<R: Real + Display + LowerExp, W: Write> MeshSink<R> for ObjWriter<W> {
    fn vertex(&mut self, position: Point3<R>, normal: Point3<R>) {
        self.vertices += 1;
        if self.error.is_err() {
            return;
        }
        self.line.clear();
        super::write_point(&mut self.line, "v", position.0);
        super::write_point(&mut self.line, "vn", normal.0);
        self.error = self.out.write_str(&self.line);
    }
    fn face(&mut self, face: Face, _tag: u32) {
        if self.error.is_err() {
            return;
        }
        self.line.clear();
        super::obj::write_face(&mut self.line, face.corners(), false);
        self.error = self.out.write_str(&self.line);
    }
}

#[cfg(test)]
mod tests {
    use super::{floor_to_i64, StreamTessellator, CELL};
    use alloc::vec;

    #[test]
    fn floor_to_i64_is_libm_floor_cast_saturating() {
        let big = libm::exp2(63.0);
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            -1.0 - f64::EPSILON,
            1.0 - f64::EPSILON / 2.0,
            -(1.0 - f64::EPSILON / 2.0),
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
            big,
            -big,
            big - 1024.0,
            -(big - 1024.0),
            2.0 * big,
            -2.0 * big,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        // A spread of magnitudes and fractions, both signs.
        for e in -40..70 {
            for f in [0.1, 0.25, 0.999_999, 1.0, 1.5, 3.7] {
                let x = f * libm::exp2(f64::from(e));
                values.push(x);
                values.push(-x);
            }
        }
        for x in values {
            assert_eq!(floor_to_i64(x), libm::floor(x) as i64, "x = {x:e}");
        }
    }

    /// Every point within the tolerance of `x` (per coordinate) lies in a
    /// cell the search from `x` covers, and a search of one cell covers
    /// `x`'s own: the property that makes the weld find the same vertex
    /// whatever cells it skips. Points on and near cell faces, at several
    /// tolerances and magnitudes (past `FRACTION_MEANINGFUL` cells too).
    #[test]
    fn a_search_covers_every_cell_within_the_tolerance() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let (mut checked, mut single, mut spread) = (0usize, 0usize, 0usize);
        for tol in [1e-9, 1e-3, 0.25, 7.0] {
            let t = StreamTessellator::<f64>::new(4, tol);
            let cell = CELL * tol;
            for _ in 0..4000 {
                let mut x = [0.0; 3];
                for c in &mut x {
                    let r = next();
                    // A cell index of up to 2^44 (past the meaningful
                    // fraction), then a place in the cell: anywhere, or
                    // within a few tolerances of either face.
                    let k = (r % (1 << 44)) as i64 >> (r >> 58);
                    let k = if r & (1 << 57) != 0 { -k } else { k };
                    let f = match (r >> 44) % 3 {
                        0 => ((r >> 20) % 1000) as f64 / 1000.0,
                        1 => ((r >> 20) % 300) as f64 / 100.0 / CELL,
                        _ => 1.0 - ((r >> 20) % 300) as f64 / 100.0 / CELL,
                    };
                    *c = (k as f64 + f) * cell;
                }
                let near = t.near(&x);
                if near.single() {
                    single += 1;
                } else {
                    spread += 1;
                }
                for d in 0..3 {
                    assert!(near.lo(d) <= near.key[d] && near.key[d] <= near.hi(d));
                }
                for corner in 0..27 {
                    let mut y = x;
                    let mut c = corner;
                    for v in &mut y {
                        *v += [-tol, 0.0, tol][c % 3];
                        c /= 3;
                    }
                    let other = t.near(&y);
                    for d in 0..3 {
                        assert!(
                            (near.lo(d)..=near.hi(d)).contains(&other.key[d]),
                            "tol {tol}, x {x:?}, y {y:?}, axis {d}"
                        );
                    }
                    checked += 1;
                }
            }
        }
        assert!(single > 1000 && spread > 1000, "{single} {spread}");
        assert_eq!(checked, 4 * 4000 * 27);
    }
}
