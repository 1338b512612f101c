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
use crate::mem::OutOfMemory;
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
    // The vertex's semi-sharpness and rule hold for all its sectors: read
    // once here, not once per sector (each is a pass over the vertex's
    // edges; per sector, a vertex of valence `n` would cost `n³`).
    let v = m.corner_vertex[c as usize] as usize;
    if m.has_semi_sharp(v) {
        return false;
    }
    let rule = m.rule(v);
    if !sector_fits(m, c, rule, fan) {
        return false;
    }
    if fan.len() == m.vertex_corners(v).len() {
        return true;
    }
    let mut other = Vec::with_capacity(8);
    m.vertex_corners(v)
        .iter()
        .filter(|k| !fan.contains(k))
        .all(|&k| sector_fits(m, k, rule, &mut other))
}

/// Whether the sector of corner `c` fits `rule`, its vertex's rule (a
/// vertex without semi-sharpness).
fn sector_fits(m: &Level, c: Corner, rule: Rule, fan: &mut Vec<Corner>) -> bool {
    let v = m.corner_vertex[c as usize] as usize;
    let closed = m.fan(c, fan);
    if fan
        .iter()
        .any(|&k| m.face(m.corner_face[k as usize] as usize).len() != 4)
    {
        return false;
    }
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
/// along the face's edge 0 (corner 0 → 1), `j` along corner 0 → 3. The
/// error is a refused allocation of a phantom point's row.
pub fn regular_grid(
    m: &Level,
    f: usize,
    points: &mut Points,
) -> Result<Option<[u32; 16]>, OutOfMemory> {
    if m.face(f).len() != 4 {
        return Ok(None);
    }
    if let Some(g) = smooth_interior_grid(m, f) {
        return Ok(Some(g));
    }
    let mut refused = None;
    let g = gathered_grid(m, f, points, &mut refused);
    match refused {
        Some(e) => Err(e),
        None => Ok(g),
    }
}

/// Outward direction of face side `k` (corner `k` → `k + 1`) in the grid.
const OUTWARD: [(i32, i32); 4] = [(0, -1), (1, 0), (0, 1), (-1, 0)];

/// [`regular_grid`] of a quad whose four corners are smooth 4-valent
/// vertices (no sharpness on them or their edges, manifold edges) with
/// nine distinct quads around, read straight off the corners: across side
/// `k` the neighbour's two far points, across corner `k` the diagonal
/// quad's far point. `None` where that shape is not there.
pub fn smooth_interior_grid(m: &Level, f: usize) -> Option<[u32; 16]> {
    let p = |k: Corner| m.point[m.corner_vertex[k as usize] as usize];
    let quad = |k: Corner| m.face(m.corner_face[k as usize] as usize).len() == 4;
    let mut g = [0u32; 16];
    let mut put = |(i, j): (i32, i32), x: u32| g[(4 * i + j) as usize] = x;
    let mut faces = [f as u32; 9];
    let mut beside = [0u32; 4];
    let first = m.face_start[f];
    for k in 0..4usize {
        let c = first + k as u32;
        let v = m.corner_vertex[c as usize] as usize;
        if m.vertex_sharpness[v] != 0.0
            || m.vertex_corners(v).len() != 4
            || m.vertex_edges(v)
                .iter()
                .any(|&e| m.edge_sharpness[e as usize] != 0.0)
        {
            return None;
        }
        let (at, next_at) = (CORNER[k], CORNER[(k + 1) % 4]);
        let (out, back) = (OUTWARD[k], OUTWARD[(k + 3) % 4]);
        put(at, p(c));
        // The neighbour across side k runs it from corner k+1 to corner k.
        let o = m.across(c).filter(|&o| quad(o))?;
        let here = m.next(o);
        put((at.0 + out.0, at.1 + out.1), p(m.next(here)));
        put(
            (next_at.0 + out.0, next_at.1 + out.1),
            p(m.next(m.next(here))),
        );
        // The diagonal quad runs the edge (corner k, neighbour's point) the
        // other way.
        let d = m.across(here).filter(|&d| quad(d))?;
        let centre = m.next(d);
        beside[k] = p(m.next(centre));
        put(
            (at.0 + out.0 + back.0, at.1 + out.1 + back.1),
            p(m.next(m.next(centre))),
        );
        faces[1 + 2 * k] = m.corner_face[o as usize];
        faces[2 + 2 * k] = m.corner_face[d as usize];
    }
    for (k, &b) in beside.iter().enumerate() {
        let (at, back) = (CORNER[k], OUTWARD[(k + 3) % 4]);
        if g[(4 * (at.0 + back.0) + at.1 + back.1) as usize] != b {
            return None;
        }
    }
    for i in 0..9 {
        if faces[i + 1..].contains(&faces[i]) {
            return None;
        }
    }
    Some(g)
}

/// [`regular_grid`] by gathering each corner's sector and mirroring across
/// infinitely sharp sides: every regular face. A phantom point whose row
/// cannot be allocated ends the gathering, its error in `refused`.
fn gathered_grid(
    m: &Level,
    f: usize,
    points: &mut Points,
    refused: &mut Option<OutOfMemory>,
) -> Option<[u32; 16]> {
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
    let mut mirror = |near: u32, far: u32| -> Option<u32> {
        let made = points.get_or_make(Key::Mirror(near, far), |row| {
            row.0.extend([(near, 2.0), (far, -1.0)]);
        });
        made.map_err(|e| *refused = Some(e)).ok()
    };
    // Edge rows first, then the corners of the grid across the cut side.
    #[allow(clippy::needless_range_loop)] // x indexes rows and columns alike
    for x in 1..3 {
        if cut[0] {
            g[x][0] = Some(mirror(g[x][1]?, g[x][2]?)?);
        }
        if cut[2] {
            g[x][3] = Some(mirror(g[x][2]?, g[x][1]?)?);
        }
        if cut[3] {
            g[0][x] = Some(mirror(g[1][x]?, g[2][x]?)?);
        }
        if cut[1] {
            g[3][x] = Some(mirror(g[2][x]?, g[1][x]?)?);
        }
    }
    for (i, j, side_j, side_i) in [(0, 0, 0, 3), (3, 0, 0, 1), (3, 3, 2, 1), (0, 3, 2, 3)] {
        let (jn, jf) = if j == 0 { (1, 2) } else { (2, 1) };
        let (in_, if_) = if i == 0 { (1, 2) } else { (2, 1) };
        if cut[side_j] {
            g[i][j] = Some(mirror(g[i][jn]?, g[i][jf]?)?);
        } else if cut[side_i] {
            g[i][j] = Some(mirror(g[in_][j]?, g[if_][j]?)?);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::adaptive::base::tagged_base;
    use crate::adaptive::subdivide::{subdivide, Rules};
    use crate::input::EdgeCrease;
    use crate::samples;

    #[test]
    fn corner_walk_grid_equals_the_gathered_grid() {
        // Small tori wrap around (faces repeat in a neighbourhood); the
        // crease and the boundary keep some faces off the corner walk; one
        // refinement of everything adds the levels below the base.
        let mut creased = samples::torus(6, 5);
        let f0 = creased.faces[7].clone();
        creased.tags.creases.push(EdgeCrease {
            vertices: [f0[0], f0[1]],
            sharpness: 1.5,
        });
        let meshes = [
            samples::torus(3, 3),
            samples::torus(4, 3),
            creased,
            samples::grid(5, 4),
            samples::extraordinary_disk(5, 2),
            samples::globe(8, 3),
        ];
        let (mut walked, mut gathered_only) = (0, 0);
        for mesh in &meshes {
            let base = tagged_base(mesh).unwrap().level;
            let mut points = Points::new(base.num_vertices() as u32);
            let all: Vec<u32> = (0..base.num_faces() as u32).collect();
            let child = subdivide(&base, &all, Rules::default(), &mut points)
                .unwrap()
                .level;
            for m in [&base, &child] {
                for f in 0..m.num_faces() {
                    let gathered = if m.face(f).len() == 4 {
                        gathered_grid(m, f, &mut points, &mut None)
                    } else {
                        None
                    };
                    match smooth_interior_grid(m, f) {
                        Some(g) => {
                            walked += 1;
                            assert_eq!(Some(g), gathered, "face {f}");
                        }
                        None => gathered_only += usize::from(gathered.is_some()),
                    }
                }
            }
        }
        assert!(
            walked > 100 && gathered_only > 10,
            "{walked} {gathered_only}"
        );
    }
}
