//! Regular faces of a level: where the limit surface over a face is one
//! uniform bicubic B-spline patch of the level's points, and its 16 control
//! points, with phantom points `2b − i` beyond infinitely sharp edges
//! (OpenSubdiv's boundary patches with `useInfSharpPatch`).
//!
//! A quad is regular when every corner is, and a corner is regular when no
//! edge at its vertex is semi-sharp, the vertex is not semi-sharp, and the
//! corner's *sector* — the faces reached from it across smooth manifold edges
//! — is all quads and fits its vertex's rule:
//! - a closed sector of 4 faces that are all the vertex's faces, rule smooth;
//! - a sector of 2 faces between two infinitely sharp edges, rule crease
//!   (a boundary vertex with two faces, or either side of an infinitely
//!   sharp crease, manifold or not);
//! - a sector of 1 face between two infinitely sharp edges, rule corner.
//!
//! In each case the rules that reach the face's points at every later level
//! are the uniform B-spline rules on the grid mirrored across the sharp
//! edges, so the patch is the limit surface exactly.

use super::crease::{is_sharp, Rule};
use super::level::{Corner, Level};
use super::points::{Key, Points};
use alloc::vec::Vec;

/// Grid position of face corner `k` in the 4×4 grid (`[i][j]`, `i` along the
/// face's first edge).
const CORNER: [(i32, i32); 4] = [(1, 1), (2, 1), (2, 2), (1, 2)];

/// Quarter turn counter-clockwise.
fn rot((a, b): (i32, i32)) -> (i32, i32) {
    (-b, a)
}

/// Whether corner `c` is regular (see the module doc), its sector returned
/// in `fan`: its own sector fits, and so does every other sector of its
/// vertex. (A sector that fits beside one that does not would put a level-0
/// patch against the rings of the other, more than one level apart along
/// the sharp edge between them.)
pub fn corner_is_regular(m: &Level, c: Corner, fan: &mut Vec<Corner>) -> bool {
    if !sector_is_regular(m, c, fan) {
        return false;
    }
    let v = m.corner_vertex[c as usize] as usize;
    let mut other = Vec::with_capacity(8);
    let own: Vec<Corner> = fan.clone();
    m.vertex_corners(v)
        .iter()
        .filter(|k| !own.contains(k))
        .all(|&k| sector_is_regular(m, k, &mut other))
}

/// Whether the sector of corner `c` fits its vertex's rule.
fn sector_is_regular(m: &Level, c: Corner, fan: &mut Vec<Corner>) -> bool {
    let v = m.corner_vertex[c as usize] as usize;
    if m.has_semi_sharp(v) {
        return false;
    }
    let closed = m.fan(c, fan);
    if fan
        .iter()
        .any(|&k| m.face(m.corner_face[k as usize] as usize).len() != 4)
    {
        return false;
    }
    let rule = m.rule(v);
    if closed {
        return fan.len() == 4 && rule == Rule::Smooth && m.vertex_corners(v).len() == 4;
    }
    match fan.len() {
        2 => rule == Rule::Crease,
        1 => rule == Rule::Corner,
        _ => false,
    }
}

/// The 16 control points of face `f` if it is regular: `[4·i + j]`, `i`
/// along the face's edge 0 (corner 0 → 1), `j` along corner 0 → 3.
pub fn regular_grid(m: &Level, f: usize, points: &mut Points) -> Option<[u32; 16]> {
    if m.face(f).len() != 4 {
        return None;
    }
    let mut g: [[Option<u32>; 4]; 4] = [[None; 4]; 4];
    let mut fan = Vec::with_capacity(8);
    let first = m.face_start[f];
    for k in 0..4u32 {
        let c = first + k;
        if !corner_is_regular(m, c, &mut fan) {
            return None;
        }
        let (ci, cj) = CORNER[k as usize];
        // Direction of this corner's outgoing edge in the face's frame.
        let mut d0 = (1, 0);
        for _ in 0..k {
            d0 = rot(d0);
        }
        put(
            &mut g,
            (ci, cj),
            m.point[m.corner_vertex[c as usize] as usize],
        )?;
        // Counter-clockwise from c: directions turn by +90° per face.
        let at = fan.iter().position(|&x| x == c)?;
        for (step, &o) in fan[at..].iter().enumerate() {
            let mut d = d0;
            for _ in 0..step {
                d = rot(d);
            }
            cell(m, o, d, (ci, cj), &mut g)?;
        }
        for (step, &o) in fan[..at].iter().rev().enumerate() {
            let mut d = d0;
            for _ in 0..=step {
                d = rot(rot(rot(d)));
            }
            cell(m, o, d, (ci, cj), &mut g)?;
        }
    }
    // Sides cut by an infinitely sharp edge (side k: corner k → k + 1).
    let cut: [bool; 4] = core::array::from_fn(|k| {
        is_sharp(m.edge_sharpness[m.corner_edge[first as usize + k] as usize])
    });
    let mut mirror = |near: u32, far: u32| -> u32 {
        points.get_or_make(Key::Mirror(near, far), || {
            alloc::vec![(near, 2.0), (far, -1.0)]
        })
    };
    // Edge rows first, then the corners of the grid across the cut side.
    #[allow(clippy::needless_range_loop)] // x indexes rows and columns alike
    for x in 1..3 {
        if cut[0] {
            g[x][0] = Some(mirror(g[x][1]?, g[x][2]?));
        }
        if cut[2] {
            g[x][3] = Some(mirror(g[x][2]?, g[x][1]?));
        }
        if cut[3] {
            g[0][x] = Some(mirror(g[1][x]?, g[2][x]?));
        }
        if cut[1] {
            g[3][x] = Some(mirror(g[2][x]?, g[1][x]?));
        }
    }
    for (i, j, side_j, side_i) in [(0, 0, 0, 3), (3, 0, 0, 1), (3, 3, 2, 1), (0, 3, 2, 3)] {
        let (jn, jf) = if j == 0 { (1, 2) } else { (2, 1) };
        let (in_, if_) = if i == 0 { (1, 2) } else { (2, 1) };
        if cut[side_j] {
            g[i][j] = Some(mirror(g[i][jn]?, g[i][jf]?));
        } else if cut[side_i] {
            g[i][j] = Some(mirror(g[in_][j]?, g[if_][j]?));
        }
    }
    let mut out = [0u32; 16];
    for i in 0..4 {
        for j in 0..4 {
            out[4 * i + j] = g[i][j]?;
        }
    }
    Some(out)
}

/// Writes the quad of corner `c` (its outgoing edge in direction `d` from
/// the centre `o`) into the grid.
fn cell(
    m: &Level,
    c: Corner,
    d: (i32, i32),
    o: (i32, i32),
    g: &mut [[Option<u32>; 4]; 4],
) -> Option<()> {
    let r = rot(d);
    let n1 = m.next(c);
    let n2 = m.next(n1);
    let n3 = m.next(n2);
    let p = |k: Corner| m.point[m.corner_vertex[k as usize] as usize];
    put(g, (o.0 + d.0, o.1 + d.1), p(n1))?;
    put(g, (o.0 + d.0 + r.0, o.1 + d.1 + r.1), p(n2))?;
    put(g, (o.0 + r.0, o.1 + r.1), p(n3))
}

/// Sets grid entry `(i, j)`; `None` when it holds another point or lies
/// outside the grid (a neighbourhood that does not fit one grid).
fn put(g: &mut [[Option<u32>; 4]; 4], (i, j): (i32, i32), p: u32) -> Option<()> {
    let slot = g
        .get_mut(usize::try_from(i).ok()?)?
        .get_mut(usize::try_from(j).ok()?)?;
    match *slot {
        Some(q) if q != p => None,
        _ => {
            *slot = Some(p);
            Some(())
        }
    }
}
