//! Regular neighbourhoods: the 3×3 vertices around a 4-valent vertex, and the
//! 4×4 B-spline control grid of a regular face, with phantom points at the
//! boundary (mirror `2b − i`, Catmull-Clark's edge-only boundary).

use crate::topology::{Topology, NONE};

/// A grid entry: a linear combination of mesh vertices (a vertex itself has
/// one term of weight 1; a phantom point two, or four at a corner). Fixed
/// size, so gathering a face allocates nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridPoint {
    terms: [(u32, f64); 4],
    len: u8,
}

impl GridPoint {
    /// The vertex `v` itself.
    pub fn vertex(v: u32) -> Self {
        GridPoint {
            terms: [(v, 1.0), (0, 0.0), (0, 0.0), (0, 0.0)],
            len: 1,
        }
    }

    /// `Σ w·v` over `terms` (at most 4; `None` beyond).
    pub fn from_terms(terms: &[(u32, f64)]) -> Option<Self> {
        let mut c = GridPoint {
            terms: [(0, 0.0); 4],
            len: 0,
        };
        for &t in terms {
            *c.terms.get_mut(c.len as usize)? = t;
            c.len += 1;
        }
        Some(c)
    }

    /// The terms `(vertex, weight)`.
    pub fn terms(&self) -> &[(u32, f64)] {
        &self.terms[..self.len as usize]
    }

    /// The vertex, when the entry is one vertex with weight 1.
    pub fn as_vertex(&self) -> Option<u32> {
        match self.terms() {
            [(v, w)] if *w == 1.0 => Some(*v),
            _ => None,
        }
    }

    /// The mirror `2·near − far` (`None` if it would need more than 4 terms).
    pub fn mirror(near: &GridPoint, far: &GridPoint) -> Option<Self> {
        let mut c = GridPoint {
            terms: [(0, 0.0); 4],
            len: 0,
        };
        let terms = near
            .terms()
            .iter()
            .map(|&(v, w)| (v, 2.0 * w))
            .chain(far.terms().iter().map(|&(v, w)| (v, -w)));
        for t in terms {
            *c.terms.get_mut(c.len as usize)? = t;
            c.len += 1;
        }
        Some(c)
    }
}

/// The vertices around `origin(h)` in local coordinates `(a, b) ∈ {−1,0,1}²`
/// (entry `[a+1][b+1]`): `+x` along `h`, `+y` along the next edge
/// counter-clockwise. `None` entries lie beyond the boundary.
///
/// Returns `None` unless the vertex is *regular*: every face around it is a
/// quad, and it has 4 faces (interior) or at most 2 (boundary: an edge vertex
/// of valence 3, or a corner of valence 2); also `None` if the faces do not
/// fit one grid (possible only on tiny closed meshes).
pub fn corner_grid(t: &Topology, h: u32) -> Option<[[Option<u32>; 3]; 3]> {
    let v = t.origin(h) as usize;
    let faces = t.vertex_face_count(v);
    if t.is_boundary(v) {
        if faces > 2 {
            return None;
        }
    } else if faces != 4 {
        return None;
    }
    let mut g = [[None; 3]; 3];
    put(&mut g, (0, 0), v as u32)?;
    // Counter-clockwise from h, then (at a boundary) clockwise.
    let mut e = h;
    let mut d = (1, 0);
    for _ in 0..4 {
        cell(t, e, d, &mut g)?;
        e = t.rotate_ccw(e);
        d = rot90(d);
        if e == NONE || e == h {
            break;
        }
    }
    if e == NONE {
        let mut e = t.rotate_cw(h);
        let mut d = (0, -1);
        while e != NONE && e != h {
            cell(t, e, d, &mut g)?;
            e = t.rotate_cw(e);
            d = rot90(rot90(rot90(d)));
        }
    }
    Some(g)
}

/// Counter-clockwise quarter turn.
fn rot90((a, b): (i32, i32)) -> (i32, i32) {
    (-b, a)
}

/// Writes the quad to the left of `e` (leaving the centre in direction `d`)
/// into the local grid.
fn cell(t: &Topology, e: u32, d: (i32, i32), g: &mut [[Option<u32>; 3]; 3]) -> Option<()> {
    if t.face_len(t.face_of(e) as usize) != 4 {
        return None;
    }
    let r = rot90(d);
    let n1 = t.next(e);
    let n2 = t.next(n1);
    put(g, d, t.dest(e))?;
    put(g, (d.0 + r.0, d.1 + r.1), t.dest(n1))?;
    put(g, r, t.dest(n2))
}

/// Sets `g` at local `(a, b)`; `None` on a conflict.
fn put(g: &mut [[Option<u32>; 3]; 3], (a, b): (i32, i32), v: u32) -> Option<()> {
    let slot = g.get_mut((a + 1) as usize)?.get_mut((b + 1) as usize)?;
    match *slot {
        Some(w) if w != v => None,
        _ => {
            *slot = Some(v);
            Some(())
        }
    }
}

/// The 4×4 uniform bicubic B-spline control grid of quad face `f`, `[i][j]`
/// with `i` along the face's `u` (first → second vertex) and `j` along `v`
/// (first → last vertex); the face's corners sit at (1,1), (2,1), (2,2),
/// (1,2). Points beyond a boundary are phantom points: `2b − i` across an
/// edge, mirrored twice at a corner.
///
/// `None` unless the face is regular: a quad whose four corners are regular
/// (see [`corner_grid`]) and whose neighbourhood fits one grid.
pub fn face_grid(t: &Topology, f: usize) -> Option<[[GridPoint; 4]; 4]> {
    if t.face_len(f) != 4 {
        return None;
    }
    if let Some(g) = interior_face_grid(t, f) {
        return Some(g.map(|row| row.map(GridPoint::vertex)));
    }
    gathered_face_grid(t, f)
}

/// [`face_grid`] by gathering each corner's 3×3 neighbourhood
/// ([`corner_grid`]) and mirroring at the boundary: every regular face.
fn gathered_face_grid(t: &Topology, f: usize) -> Option<[[GridPoint; 4]; 4]> {
    if t.face_len(f) != 4 {
        return None;
    }
    let mut grid: [[Option<u32>; 4]; 4] = [[None; 4]; 4];
    const CORNER: [(i32, i32); 4] = [(1, 1), (2, 1), (2, 2), (1, 2)];
    for (k, &(ci, cj)) in CORNER.iter().enumerate() {
        let local = corner_grid(t, t.face_half_edge(f, k))?;
        for (a, row) in local.iter().enumerate() {
            for (b, entry) in row.iter().enumerate() {
                let Some(v) = *entry else { continue };
                let (a, b) = (a as i32 - 1, b as i32 - 1);
                // Local axes of corner k in the face's (u, v): +x runs along
                // the face edge k → k+1, +y along the next edge ccw.
                let (di, dj) = match k {
                    0 => (a, b),
                    1 => (-b, a),
                    2 => (-a, -b),
                    _ => (b, -a),
                };
                let (i, j) = ((ci + di) as usize, (cj + dj) as usize);
                let slot = &mut grid[i][j];
                match *slot {
                    Some(w) if w != v => return None,
                    _ => *slot = Some(v),
                }
            }
        }
    }
    let mut out: [[Option<GridPoint>; 4]; 4] = [[None; 4]; 4];
    let mut complete = true;
    for (o_row, g_row) in out.iter_mut().zip(&grid) {
        for (o, g) in o_row.iter_mut().zip(g_row) {
            *o = g.map(GridPoint::vertex);
            complete &= g.is_some();
        }
    }
    if !complete {
        mirror(&mut out)?;
    }
    let mut full = [[GridPoint::vertex(0); 4]; 4];
    for (f_row, o_row) in full.iter_mut().zip(&out) {
        for (f, o) in f_row.iter_mut().zip(o_row) {
            *f = (*o)?;
        }
    }
    Some(full)
}

/// Grid position of face corner `k` (`[i][j]`).
const GRID_CORNER: [(usize, usize); 4] = [(1, 1), (2, 1), (2, 2), (1, 2)];

/// The outward direction of face side `k` (corner `k` → `k + 1`).
const OUTWARD: [(isize, isize); 4] = [(0, -1), (1, 0), (0, 1), (-1, 0)];

/// `p + a + b` on the 4×4 grid.
fn step(p: (usize, usize), a: (isize, isize), b: (isize, isize)) -> (usize, usize) {
    (
        p.0.wrapping_add_signed(a.0 + b.0),
        p.1.wrapping_add_signed(a.1 + b.1),
    )
}

/// [`face_grid`] of an interior quad with four 4-valent interior corners
/// and nine distinct quads around, read straight off the half-edges: across
/// side `k` the neighbour's two far vertices, across corner `k` the diagonal
/// quad's far vertex. `None` where that shape is not there (the general
/// path decides).
pub fn interior_face_grid(t: &Topology, f: usize) -> Option<[[u32; 4]; 4]> {
    if t.face_len(f) != 4 {
        return None;
    }
    let mut g = [[0u32; 4]; 4];
    let mut faces = [f as u32; 9];
    // Per corner: the diagonal quad's vertex next to the corner on the
    // previous side's neighbour (checked against that neighbour below).
    let mut beside = [0u32; 4];
    for k in 0..4 {
        let h = t.face_half_edge(f, k);
        let v = t.origin(h) as usize;
        if t.is_boundary(v) || t.vertex_face_count(v) != 4 {
            return None;
        }
        let (p, q) = (GRID_CORNER[k], GRID_CORNER[(k + 1) % 4]);
        let out = OUTWARD[k];
        let back = OUTWARD[(k + 3) % 4];
        g[p.0][p.1] = t.origin(h);
        // The neighbour across side k runs it from corner k+1 to corner k.
        let across = t.twin(h);
        if across == NONE || t.face_len(t.face_of(across) as usize) != 4 {
            return None;
        }
        let to_a = t.next(across);
        let a = step(p, out, (0, 0));
        let b = step(q, out, (0, 0));
        g[a.0][a.1] = t.dest(to_a);
        g[b.0][b.1] = t.dest(t.next(to_a));
        // The diagonal quad runs the edge (a, corner k) the other way.
        let diagonal = t.twin(to_a);
        if diagonal == NONE || t.face_len(t.face_of(diagonal) as usize) != 4 {
            return None;
        }
        let to_c = t.next(diagonal);
        beside[k] = t.dest(to_c);
        let d = step(p, out, back);
        g[d.0][d.1] = t.dest(t.next(to_c));
        faces[1 + 2 * k] = t.face_of(across);
        faces[2 + 2 * k] = t.face_of(diagonal);
    }
    for k in 0..4 {
        let c = step(GRID_CORNER[k], OUTWARD[(k + 3) % 4], (0, 0));
        if g[c.0][c.1] != beside[k] {
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

/// Fills missing border entries by mirroring (`2·near − far` along a row or
/// column), repeatedly, so that corners are mirrored twice. `None` if some
/// entry cannot be filled.
///
/// Each pass reads only entries known before it (a snapshot): an entry beside
/// an edge is the mirror of its own row or column's real points (`2b − i`
/// across the edge), never an extrapolation along a row of phantoms filled
/// in the same pass (which differs unless the grid is affine, and is not
/// what the neighbouring face computes for the same point).
fn mirror(g: &mut [[Option<GridPoint>; 4]; 4]) -> Option<()> {
    loop {
        let mut changed = false;
        let mut missing = false;
        let known = *g;
        for i in 0..4 {
            for j in 0..4 {
                if known[i][j].is_some() {
                    continue;
                }
                let pairs = [
                    (i == 0).then_some(((1, j), (2, j))),
                    (i == 3).then_some(((2, j), (1, j))),
                    (j == 0).then_some(((i, 1), (i, 2))),
                    (j == 3).then_some(((i, 2), (i, 1))),
                ];
                let mut filled = None;
                for ((ni, nj), (fi, fj)) in pairs.into_iter().flatten() {
                    if let (Some(near), Some(far)) = (&known[ni][nj], &known[fi][fj]) {
                        filled = Some(GridPoint::mirror(near, far)?);
                        break;
                    }
                }
                match filled {
                    Some(c) => {
                        g[i][j] = Some(c);
                        changed = true;
                    }
                    None => missing = true,
                }
            }
        }
        if !missing {
            return Some(());
        }
        if !changed {
            return None;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::MeshInput;
    use alloc::vec::Vec;

    /// An `nu × nv` quad grid of vertices `(i, j) ↦ i + (nu+1)·j`.
    fn grid_mesh(nu: usize, nv: usize) -> MeshInput {
        let w = nu + 1;
        let verts = (0..=nv)
            .flat_map(|j| (0..=nu).map(move |i| [i as f64, j as f64, 0.0]))
            .collect();
        let mut faces = Vec::new();
        for j in 0..nv {
            for i in 0..nu {
                let v = |a: usize, b: usize| (a + w * b) as u32;
                faces.push(alloc::vec![
                    v(i, j),
                    v(i + 1, j),
                    v(i + 1, j + 1),
                    v(i, j + 1)
                ]);
            }
        }
        MeshInput::new(verts, faces)
    }

    #[test]
    fn half_edge_grid_equals_the_gathered_grid() {
        // Tori (small ones wrap around: faces repeat in a neighbourhood),
        // a grid with its boundary, an extraordinary disk and a globe.
        let meshes = [
            crate::samples::torus(3, 3),
            crate::samples::torus(4, 3),
            crate::samples::torus(7, 5),
            grid_mesh(5, 4),
            crate::samples::extraordinary_disk(5, 2),
            crate::samples::globe(8, 3),
        ];
        let mut fast = 0;
        for m in &meshes {
            let t = Topology::new(m).unwrap();
            for f in 0..t.num_faces() {
                let gathered = gathered_face_grid(&t, f);
                if let Some(g) = interior_face_grid(&t, f) {
                    fast += 1;
                    assert_eq!(
                        Some(g.map(|r| r.map(GridPoint::vertex))),
                        gathered,
                        "face {f}"
                    );
                }
            }
        }
        assert!(fast > 40, "{fast} faces took the half-edge path");
    }

    #[test]
    fn interior_face_grid_is_the_4x4_block() {
        let m = grid_mesh(5, 5);
        let t = Topology::new(&m).unwrap();
        // Face (2, 2): vertices (2..=3, 2..=3); grid (1..=4, 1..=4).
        let f = 2 + 5 * 2;
        let g = face_grid(&t, f).unwrap();
        for (i, row) in g.iter().enumerate() {
            for (j, c) in row.iter().enumerate() {
                assert_eq!(c.terms(), &[((1 + i + 6 * (1 + j)) as u32, 1.0)]);
            }
        }
    }

    #[test]
    fn corner_face_grid_mirrors_twice() {
        let m = grid_mesh(3, 3);
        let t = Topology::new(&m).unwrap();
        let g = face_grid(&t, 0).unwrap();
        // Evaluate combos on the positions: phantoms continue the grid
        // linearly, so entry (i, j) sits at (i − 1, j − 1).
        for (i, row) in g.iter().enumerate() {
            for (j, c) in row.iter().enumerate() {
                let p = c.terms().iter().fold([0.0; 2], |acc, &(v, w)| {
                    let q = m.vertices[v as usize];
                    [acc[0] + w * q[0], acc[1] + w * q[1]]
                });
                assert_eq!(p, [i as f64 - 1.0, j as f64 - 1.0]);
            }
        }
    }

    #[test]
    fn edge_phantoms_mirror_their_own_column() {
        // Bottom face (1, 0) of a 4×4 grid: every entry of the phantom row
        // j = 0 is 2·(its column's boundary vertex) − (the vertex above), in
        // particular the last one, which a row-wise extrapolation of phantoms
        // filled first would get wrong on a non-affine grid.
        let m = grid_mesh(4, 4);
        let t = Topology::new(&m).unwrap();
        let g = face_grid(&t, 1).unwrap();
        let v = |a: usize, b: usize| (a + 5 * b) as u32;
        for (i, column) in g.iter().enumerate() {
            assert_eq!(
                column[0].terms(),
                &[(v(i, 0), 2.0), (v(i, 1), -1.0)],
                "i={i}"
            );
        }
    }

    #[test]
    fn rotated_face_orders_its_grid_from_its_first_vertex() {
        let mut m = grid_mesh(4, 4);
        let f = 1 + 4;
        m.faces[f].rotate_left(1); // first vertex is now the old second one
        let t = Topology::new(&m).unwrap();
        let g = face_grid(&t, f).unwrap();
        // Grid (1,1) is the face's first vertex, (2,1) its second, (1,2) its last.
        assert_eq!(g[1][1].terms()[0].0, m.faces[f][0]);
        assert_eq!(g[2][1].terms()[0].0, m.faces[f][1]);
        assert_eq!(g[2][2].terms()[0].0, m.faces[f][2]);
        assert_eq!(g[1][2].terms()[0].0, m.faces[f][3]);
    }
}
