//! `Points`: the points adaptive refinement makes, each a stencil row over
//! earlier points, made once however many neighbourhoods need it. A point is
//! named by what it is the child of (a vertex, an edge, a face of the level
//! above), so two neighbourhoods that refine the same component share the
//! point, and a patch edge can ask whether its neighbour is finer.

use super::NONE;
use crate::stencil::StencilTable;
use alloc::vec::Vec;
use hashbrown::HashMap;

/// What a point is.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Key {
    /// The child of a vertex (its point).
    Vertex(u32),
    /// The child of an edge (its end points, smaller first).
    Edge(u32, u32),
    /// The child of the `k`-th (`k ≥ 1`) other edge between the same two
    /// points (end points smaller first, then `k`): a base-level edge a face
    /// runs twice, or a further degenerate edge, as OpenSubdiv makes them.
    EdgeInstance(u32, u32, u32),
    /// The child of a face (its points in order, from the rotation that
    /// reads smallest).
    Face(Vec<u32>),
    /// `2·a − b`: a phantom point beyond an infinitely sharp edge.
    Mirror(u32, u32),
    /// The limit position of a vertex.
    Limit(u32),
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
}

impl Points {
    /// An empty set whose first point will be `base`.
    pub fn new(base: u32) -> Self {
        Points {
            base,
            keys: HashMap::new(),
            parent: Vec::new(),
            rows: StencilTable::new(),
        }
    }

    /// The point named `key`, if it was made.
    pub fn get(&self, key: &Key) -> Option<u32> {
        self.keys.get(key).copied()
    }

    /// The point named `key`, made from `row()` the first time.
    pub fn get_or_make(&mut self, key: Key, row: impl FnOnce() -> Vec<(u32, f64)>) -> u32 {
        if let Some(&p) = self.keys.get(&key) {
            return p;
        }
        let p = self.base + self.rows.push_row(row());
        self.parent.push(match key {
            Key::Vertex(v) => v,
            _ => NONE,
        });
        self.keys.insert(key, p);
        p
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
