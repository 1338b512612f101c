//! The c-net of an extraordinary vertex of a refinement level
//! (docs/math/eg.md §1): where the adaptive refinement has separated an
//! extraordinary point from every other irregular feature, its EG cap can
//! take over from Catmull-Clark rings.
//!
//! A vertex has its c-net at a level when it is smooth (no sharp or
//! semi-sharp edge, no vertex sharpness), its faces are one closed fan of
//! `n ≠ 4` quads, none of them or of the faces around its 1-ring vertices is
//! a hole, and every 1-ring vertex is regular ([`corner_is_regular`]: four
//! quads, smooth, no sharpness). Then the surface just outside the cap's
//! faces has, along their edges, the uniform B-spline jet of the c-net's
//! rows (the rules that reach it are the uniform ones of the 1-ring's
//! vertices and of the edges between the 1-ring and the 2-ring), which is
//! what the EG cap joins with (docs/math/eg.md §1).

use super::level::{Corner, Level};
use super::regular::corner_is_regular;
use crate::adaptive::crease::Rule;
use alloc::vec::Vec;

/// The c-net of a vertex of a level.
#[derive(Clone, Debug, PartialEq)]
pub struct LevelCNet {
    /// Valence `n`.
    pub valence: usize,
    /// `6n` nodes (points), sector by sector in the §1 order (1,0) (2,0)
    /// (1,1) (2,1) (1,2) (2,2), sectors counter-clockwise.
    pub nodes: Vec<u32>,
    /// Per sector: its face's corners as points, from the centre:
    /// (0,0) (1,0) (1,1) (0,1).
    pub faces: Vec<[u32; 4]>,
}

/// The c-net of the vertex at corner `c` of `m`, if it has one (see the
/// module doc). `c`'s vertex must be complete in `m` with its 2-ring.
pub fn level_cnet(m: &Level, c: Corner) -> Option<LevelCNet> {
    let v = m.corner_vertex[c as usize] as usize;
    if m.has_semi_sharp(v) || m.rule(v) != Rule::Smooth {
        return None;
    }
    let mut fan = Vec::with_capacity(8);
    if !m.fan(c, &mut fan) {
        return None;
    }
    let n = fan.len();
    if n < 3 || n == 4 || n != m.vertex_corners(v).len() {
        return None;
    }
    let p = |k: Corner| m.point[m.corner_vertex[k as usize] as usize];
    let quad = |k: Corner| m.face(m.corner_face[k as usize] as usize).len() == 4;
    let mut scratch = Vec::with_capacity(8);
    let mut clean = |k: Corner| -> bool {
        corner_is_regular(m, k, &mut scratch)
            && m.vertex_corners(m.corner_vertex[k as usize] as usize)
                .iter()
                .all(|&x| !m.hole[m.corner_face[x as usize] as usize])
    };
    let mut nodes = Vec::with_capacity(6 * n);
    let mut faces = Vec::with_capacity(n);
    for &k in &fan {
        if !quad(k) || m.hole[m.corner_face[k as usize] as usize] {
            return None;
        }
        // The sector's face: k at (0,0), a at (1,0), d at (1,1), b at (0,1).
        let a = m.next(k);
        let d = m.next(a);
        let b = m.next(d);
        if !clean(a) || !clean(d) {
            return None;
        }
        // Across edge (1,0)–(1,1): the quad (1,1) (1,0) (2,0) (2,1).
        let q1 = m.across(a)?;
        let q1_20 = m.next(m.next(q1));
        let q1_21 = m.next(q1_20);
        // Across edge (1,1)–(0,1): the quad (0,1) (1,1) (1,2) (0,2).
        let q3 = m.across(d)?;
        let q3_12 = m.next(m.next(q3));
        // Across edge (2,1)–(1,1): the quad (1,1) (2,1) (2,2) (1,2).
        let q2 = m.across(q1_21)?;
        let q2_22 = m.next(m.next(q2));
        let q2_12 = m.next(q2_22);
        if !(quad(q1) && quad(q2) && quad(q3))
            || p(m.next(q1)) != p(a)
            || p(q1) != p(d)
            || p(q3) != p(b)
            || p(q2) != p(d)
            || p(q2_12) != p(q3_12)
        {
            return None;
        }
        nodes.extend([p(a), p(q1_20), p(d), p(q1_21), p(q3_12), p(q2_22)]);
        faces.push([p(k), p(a), p(d), p(b)]);
    }
    // A c-net must not wrap onto itself.
    let mut all = nodes.clone();
    all.push(p(c));
    all.sort_unstable();
    if all.windows(2).any(|w| w[0] == w[1]) {
        return None;
    }
    Some(LevelCNet {
        valence: n,
        nodes,
        faces,
    })
}
