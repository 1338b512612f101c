//! Closedness and orientation of a polygon mesh.

use super::Face;
use alloc::vec::Vec;

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

/// Checks that every undirected edge of `faces` is used by exactly two
/// faces, in opposite directions (a closed, consistently oriented mesh).
/// Otherwise returns the offending edge that comes first in face order
/// (faces in order, each face's edges `c[i] → c[i+1]` in order). Sorting,
/// `O(E log E)`.
pub fn is_closed_and_oriented(faces: &[Face]) -> Result<(), BadEdge> {
    // Directed edges in face order; their sequence number is the position here.
    let mut directed: Vec<(u32, u32, usize)> = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        let c = face.corners();
        for i in 0..c.len() {
            directed.push((c[i], c[(i + 1) % c.len()], f));
        }
    }
    let key = |&(a, b, _): &(u32, u32, usize)| ((a.min(b) as u64) << 32) | a.max(b) as u64;
    let mut sorted: Vec<(u64, u32)> = directed
        .iter()
        .enumerate()
        .map(|(s, e)| (key(e), s as u32))
        .collect();
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
    match first {
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
    }
}
