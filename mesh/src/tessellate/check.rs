//! Closedness and orientation of a polygon mesh.

use super::Face;
use crate::mem::{self, OutOfMemory};
use alloc::vec::Vec;
use hashbrown::HashMap;

/// What is wrong with an edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeFault {
    /// The edge joins a vertex to itself.
    Degenerate,
    /// Only one face uses the edge (a boundary, crack or T-junction).
    Unpaired,
    /// Two faces use the edge in the same direction (orientation flips).
    SameDirection,
    /// More than two faces use the edge (non-manifold).
    Overused,
}

/// The first offending edge found by [`is_closed_and_oriented`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BadEdge {
    /// The edge's first corner, as the face `face` runs it.
    pub from: u32,
    /// Its second corner.
    pub to: u32,
    /// The first face (in `faces` order) that uses the edge.
    pub face: usize,
    /// The fault.
    pub fault: EdgeFault,
}

/// The verdict of following the edges of `faces` one by one, as the
/// streaming weld reports it on its own output
/// ([`super::StreamSummary::closed`]): an edge's second use pairs it (a
/// [`EdgeFault::SameDirection`] fault where it runs the same way as the
/// first), a third use opens it again, and an edge left open is
/// [`EdgeFault::Unpaired`]; of the faults, the one whose edge use came
/// first in face order is returned. Unlike [`is_closed_and_oriented`] it
/// does not see an edge used four times, twice each way. A hash map of the
/// open edges, `O(E)`.
pub fn closed_in_order(faces: &[Face]) -> Result<(), BadEdge> {
    let mut open: HashMap<(u32, u32), (u32, u32, u64, usize)> = HashMap::new();
    let mut first: Option<(u64, BadEdge)> = None;
    let blame = |first: &mut Option<(u64, BadEdge)>, at: u64, bad: BadEdge| {
        if first.is_none_or(|(t, _)| at < t) {
            *first = Some((at, bad));
        }
    };
    let mut seq = 0u64;
    for (index, f) in faces.iter().enumerate() {
        let c = f.corners();
        for i in 0..c.len() {
            let (a, b) = (c[i], c[(i + 1) % c.len()]);
            let key = (a.min(b), a.max(b));
            match open.remove(&key) {
                None => {
                    open.insert(key, (a, b, seq, index));
                }
                Some((from, _, at, face)) if from == a => {
                    let fault = EdgeFault::SameDirection;
                    let bad = BadEdge {
                        from: a,
                        to: b,
                        face,
                        fault,
                    };
                    blame(&mut first, at, bad);
                }
                Some(_) => {}
            }
            seq += 1;
        }
    }
    for (from, to, at, face) in open.into_values() {
        let fault = EdgeFault::Unpaired;
        blame(
            &mut first,
            at,
            BadEdge {
                from,
                to,
                face,
                fault,
            },
        );
    }
    first.map_or(Ok(()), |(_, bad)| Err(bad))
}

/// Checks that every undirected edge of `faces` is used by exactly two
/// faces, in opposite directions (a closed, consistently oriented mesh).
/// Otherwise returns the offending edge that comes first in face order
/// (faces in order, each face's edges `c[i] → c[i+1]` in order). Sorting,
/// `O(E log E)`. Aborts, as a `Vec` does, when its edge lists cannot be
/// allocated: [`try_closed_and_oriented`] returns the error instead.
pub fn is_closed_and_oriented(faces: &[Face]) -> Result<(), BadEdge> {
    crate::mem::or_abort(try_closed_and_oriented(faces))
}

/// [`is_closed_and_oriented`], or the error when its edge lists (two
/// entries per face corner) cannot be allocated.
pub fn try_closed_and_oriented(faces: &[Face]) -> Result<Result<(), BadEdge>, OutOfMemory> {
    // Directed edges in face order; their sequence number is the position here.
    let corners = faces.iter().map(|f| f.corners().len()).sum();
    let mut directed: Vec<(u32, u32, usize)> = mem::with_capacity(corners)?;
    for (f, face) in faces.iter().enumerate() {
        let c = face.corners();
        for i in 0..c.len() {
            directed.push((c[i], c[(i + 1) % c.len()], f));
        }
    }
    let key = |&(a, b, _): &(u32, u32, usize)| ((a.min(b) as u64) << 32) | a.max(b) as u64;
    let mut sorted: Vec<(u64, u32)> =
        mem::collect(directed.iter().enumerate().map(|(s, e)| (key(e), s as u32)))?;
    sorted.sort_unstable();

    let mut first: Option<(u32, EdgeFault)> = None;
    let mut blame = |s: u32, fault: EdgeFault| {
        if first.is_none_or(|(t, _)| s < t) {
            first = Some((s, fault));
        }
    };
    let mut g = 0;
    while g < sorted.len() {
        let mut h = g + 1;
        while h < sorted.len() && sorted[h].0 == sorted[g].0 {
            h += 1;
        }
        let s = sorted[g].1;
        let (a, b, _) = directed[s as usize];
        if a == b {
            blame(s, EdgeFault::Degenerate);
        } else {
            match h - g {
                1 => blame(s, EdgeFault::Unpaired),
                2 => {
                    if directed[sorted[g + 1].1 as usize].0 == a {
                        blame(s, EdgeFault::SameDirection);
                    }
                }
                _ => blame(s, EdgeFault::Overused),
            }
        }
        g = h;
    }
    Ok(match first {
        None => Ok(()),
        Some((s, fault)) => {
            let (from, to, face) = directed[s as usize];
            Err(BadEdge {
                from,
                to,
                face,
                fault,
            })
        }
    })
}
