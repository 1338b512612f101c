//! `Points`: the points adaptive refinement makes, each a stencil row over
//! earlier points. A vertex's or an edge's child is named by the points it
//! is the child of (and phantom and limit points by theirs), so it is made
//! once however many faces need it, and a patch edge can ask whether its
//! neighbour is finer; a face's child is made once by the refinement of its
//! level and needs no name.

use super::NONE;
use crate::mem::{self, OutOfMemory};
use crate::stencil::StencilTable;
use alloc::vec::Vec;
use hashbrown::hash_map::Entry;
use hashbrown::HashMap;

/// What a point is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Key {
    /// The child of a vertex (its point).
    Vertex(u32),
    /// The child of an edge (its end points, smaller first).
    Edge(u32, u32),
    /// The child of the `k`-th (`k ≥ 1`) other edge between the same two
    /// points (end points smaller first, then `k`): a base-level edge a face
    /// runs twice, or a further degenerate edge, as OpenSubdiv makes them.
    EdgeInstance(u32, u32, u32),
    /// `2·a − b`: a phantom point beyond an infinitely sharp edge.
    Mirror(u32, u32),
    /// The limit position of a vertex.
    Limit(u32),
}

/// A stencil row being built: `(point, weight)`, one entry per point.
#[derive(Clone, Debug, Default)]
pub struct Row(pub Vec<(u32, f64)>);

impl Row {
    /// An empty row.
    pub fn new() -> Self {
        Row(Vec::with_capacity(16))
    }

    /// Adds `w ×` point `p` (to its entry, if it has one).
    pub fn add(&mut self, p: u32, w: f64) {
        if let Some(e) = self.0.iter_mut().find(|e| e.0 == p) {
            e.1 += w;
        } else {
            self.0.push((p, w));
        }
    }

    /// Every weight times `s`.
    pub fn scaled(mut self, s: f64) -> Self {
        for e in &mut self.0 {
            e.1 *= s;
        }
        self
    }

    /// `other`'s entries added, one by one.
    pub fn plus(mut self, other: Row) -> Self {
        for (p, w) in other.0 {
            self.add(p, w);
        }
        self
    }
}

/// Points numbered from `base` on, each a row over earlier points.
#[derive(Clone, Debug)]
pub struct Points {
    base: u32,
    keys: HashMap<Key, u32>,
    /// Per point made: the point it is the vertex child of ([`NONE`] for
    /// the other kinds).
    parent: Vec<u32>,
    /// Row `i` is point `base + i`.
    pub rows: StencilTable,
    /// The row being built (kept, so that building one does not allocate).
    scratch: Row,
}

impl Points {
    /// An empty set whose first point will be `base`.
    pub fn new(base: u32) -> Self {
        Points {
            base,
            keys: HashMap::new(),
            parent: Vec::new(),
            rows: StencilTable::new(),
            scratch: Row::new(),
        }
    }

    /// Room for `points` more points, `named` of them named, `entries`
    /// row entries in all, without growing the tables on the way (a
    /// refinement knows bounds: a point per face, and one vertex and one
    /// edge child per corner of the faces it refines). Fallible, as every
    /// growth of the tables: an allocation the system refuses is an error.
    pub fn reserve(
        &mut self,
        points: usize,
        named: usize,
        entries: usize,
    ) -> Result<(), OutOfMemory> {
        mem::reserve_map(&mut self.keys, named)?;
        mem::reserve(&mut self.parent, points)?;
        self.rows.try_reserve(points, entries)
    }

    /// The point named `key`, if it was made.
    #[inline]
    pub fn get(&self, key: &Key) -> Option<u32> {
        self.keys.get(key).copied()
    }

    /// A new point without a name (a face's child: made once), its row
    /// written by `build` into an empty row.
    #[inline]
    pub fn make(&mut self, build: impl FnOnce(&mut Row)) -> Result<u32, OutOfMemory> {
        self.scratch.0.clear();
        build(&mut self.scratch);
        room_for_one(&mut self.parent, &mut self.rows, self.scratch.0.len())?;
        self.parent.push(NONE);
        Ok(self.base + self.rows.push_slice(&self.scratch.0))
    }

    /// The point named `key`, its row written by `build` into an empty row
    /// the first time.
    pub fn get_or_make(
        &mut self,
        key: Key,
        build: impl FnOnce(&mut Row),
    ) -> Result<u32, OutOfMemory> {
        // Room for a new name first: the look-up's slot is then filled
        // without growing the table.
        mem::reserve_map(&mut self.keys, 1)?;
        match self.keys.entry(key) {
            Entry::Occupied(made) => Ok(*made.get()),
            Entry::Vacant(slot) => {
                self.scratch.0.clear();
                build(&mut self.scratch);
                room_for_one(&mut self.parent, &mut self.rows, self.scratch.0.len())?;
                let p = self.base + self.rows.push_slice(&self.scratch.0);
                self.parent.push(match key {
                    Key::Vertex(v) => v,
                    _ => NONE,
                });
                Ok(*slot.insert(p))
            }
        }
    }

    /// The point `p` descends from as a vertex child, child of a child…:
    /// a point below `base` (a vertex of the level the refinement started
    /// from), or `None` when the chain starts at an edge or face point.
    pub fn vertex_origin(&self, mut p: u32) -> Option<u32> {
        while p >= self.base {
            p = *self.parent.get((p - self.base) as usize)?;
            if p == NONE {
                return None;
            }
        }
        Some(p)
    }
}

/// Room for one more point, of a row of `entries` entries, in `parent` and
/// `rows` (no allocation when they have room: the check [`Vec::push`]
/// makes).
#[inline]
fn room_for_one(
    parent: &mut Vec<u32>,
    rows: &mut StencilTable,
    entries: usize,
) -> Result<(), OutOfMemory> {
    if parent.len() == parent.capacity() {
        mem::reserve(parent, 1)?;
    }
    if rows.has_room(1, entries) {
        return Ok(());
    }
    rows.try_reserve(1, entries)
}
