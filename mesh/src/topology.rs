//! `Topology`: a validated, oriented 2-manifold polygon mesh (with or without
//! boundary) as half-edges, built once from the face lists.
//!
//! Half-edge `h` is corner `h` of the face list: it runs from the corner's
//! vertex to the next corner's vertex of the same face, and its face lies to
//! its left (faces are counter-clockwise about the outward normal). Around a
//! vertex, the next outgoing half-edge counter-clockwise after `h` is
//! `twin(prev(h))`.
//!
//! Validation (in this order, the first offence reported): no faces
//! ([`MeshError::Empty`]), more than 2³¹ items ([`MeshError::TooLarge`]), a
//! non-finite coordinate, then per face in order: fewer than 3 vertices, an
//! index out of range, a repeated vertex; then per edge: more than two faces,
//! or two faces running it the same way; then per vertex: faces that do not
//! form one disk or half-disk. Vertices that no face uses are allowed (OBJ
//! files often carry them) and ignored.

use crate::error::MeshError;
use crate::input::MeshInput;
use crate::mem;
use alloc::vec::Vec;

/// "No half-edge" (a boundary edge has no twin).
pub const NONE: u32 = u32::MAX;

/// The first checks of every mesh, in this order: no faces or vertices
/// ([`MeshError::Empty`]), more than 2³¹ items ([`MeshError::TooLarge`]), a
/// non-finite coordinate ([`MeshError::NonFinite`]).
pub fn check_sizes_and_positions(mesh: &MeshInput) -> Result<(), MeshError> {
    let nv = mesh.vertices.len();
    let nf = mesh.faces.len();
    if nf == 0 || nv == 0 {
        return Err(MeshError::Empty);
    }
    let corners: usize = mesh.faces.iter().map(|f| f.len()).sum();
    let limit = (i32::MAX as usize) - 1;
    if nv > limit || nf > limit || corners > limit {
        return Err(MeshError::TooLarge);
    }
    if let Some(vertex) = mesh
        .vertices
        .iter()
        .position(|p| !p.iter().all(|c| c.is_finite()))
    {
        return Err(MeshError::NonFinite { vertex });
    }
    Ok(())
}

/// The half-edge structure of a validated mesh.
#[derive(Clone, Debug)]
pub struct Topology {
    /// `face_start[f]..face_start[f+1]` are face `f`'s corners (= half-edges).
    face_start: Vec<u32>,
    /// Vertex of each corner.
    corner_vertex: Vec<u32>,
    /// Face of each corner.
    corner_face: Vec<u32>,
    /// Opposite half-edge, or [`NONE`] on the boundary.
    twin: Vec<u32>,
    /// Per vertex: the first outgoing half-edge of its counter-clockwise fan
    /// (on the boundary, the one whose edge is a boundary edge), or [`NONE`]
    /// for an unused vertex.
    vertex_start: Vec<u32>,
    /// Per vertex: number of incident faces.
    vertex_faces: Vec<u32>,
    /// Per vertex: on the boundary.
    vertex_boundary: Vec<bool>,
}

impl Topology {
    /// Validates `mesh` and builds its half-edges. See the module doc for the
    /// checks and their order.
    ///
    /// # Example
    ///
    /// ```
    /// use capdiv_mesh::{samples, Topology};
    ///
    /// let topo = Topology::new(&samples::cube())?;
    /// assert_eq!((topo.num_vertices(), topo.num_faces()), (8, 6));
    /// assert_eq!(topo.num_half_edges(), 24);
    /// assert!(topo.is_closed());
    /// assert!((0..8).all(|v| topo.vertex_face_count(v) == 3));
    /// # Ok::<(), capdiv_mesh::MeshError>(())
    /// ```
    pub fn new(mesh: &MeshInput) -> Result<Self, MeshError> {
        check_sizes_and_positions(mesh)?;
        Self::from_faces(mesh.vertices.len(), &mesh.faces)
    }

    /// [`Self::new`] without positions: `nv` vertices and the face lists
    /// (every check but finiteness). Used for refined meshes.
    pub fn from_faces(nv: usize, faces: &[Vec<u32>]) -> Result<Self, MeshError> {
        let nf = faces.len();
        if nf == 0 || nv == 0 {
            return Err(MeshError::Empty);
        }
        let corners: usize = faces.iter().map(|f| f.len()).sum();
        let limit = (i32::MAX as usize) - 1;
        if nv > limit || nf > limit || corners > limit {
            return Err(MeshError::TooLarge);
        }
        let mut face_start = mem::with_capacity(nf + 1)?;
        let mut corner_vertex = mem::with_capacity(corners)?;
        let mut corner_face = mem::with_capacity(corners)?;
        face_start.push(0u32);
        for (f, face) in faces.iter().enumerate() {
            if face.len() < 3 {
                return Err(MeshError::FaceTooSmall {
                    face: f,
                    len: face.len(),
                });
            }
            for &v in face {
                if v as usize >= nv {
                    return Err(MeshError::IndexOutOfRange {
                        face: f,
                        index: v as i64,
                        vertices: nv,
                    });
                }
            }
            for (k, &v) in face.iter().enumerate() {
                if face[..k].contains(&v) {
                    return Err(MeshError::RepeatedVertex {
                        face: f,
                        vertex: v as usize,
                    });
                }
            }
            corner_vertex.extend_from_slice(face);
            corner_face.extend(core::iter::repeat_n(f as u32, face.len()));
            face_start.push(corner_vertex.len() as u32);
        }
        let mut topo = Topology {
            face_start,
            corner_vertex,
            corner_face,
            twin: mem::filled(corners, NONE)?,
            vertex_start: mem::filled(nv, NONE)?,
            vertex_faces: mem::filled(nv, 0)?,
            vertex_boundary: mem::filled(nv, false)?,
        };
        topo.link_twins(nv)?;
        topo.link_vertices()?;
        Ok(topo)
    }

    /// Pairs half-edges `v→w` and `w→v` through the outgoing half-edges of
    /// every vertex (a CSR by origin; valences are small, so the partner is
    /// found by a short scan).
    fn link_twins(&mut self, nv: usize) -> Result<(), MeshError> {
        let nh = self.corner_vertex.len();
        let mut start = mem::filled(nv + 1, 0u32)?;
        for &v in &self.corner_vertex {
            start[v as usize + 1] += 1;
        }
        for v in 0..nv {
            start[v + 1] += start[v];
        }
        let mut fill = mem::to_vec(&start)?;
        let mut out = mem::filled(nh, 0u32)?;
        for h in 0..nh {
            let v = self.corner_vertex[h] as usize;
            out[fill[v] as usize] = h as u32;
            fill[v] += 1;
        }
        // Destinations looked up once: the scans below read each several times.
        let dest: Vec<u32> = mem::collect((0..nh as u32).map(|h| self.dest(h)))?;
        // In face order, so the error names the first offending face. An
        // edge is checked from its first half-edge: its twin's check would
        // count the same half-edges (its `same` is this one's `opposite`
        // less itself, and the other way round), so it would pass too, and
        // the twin is linked here.
        for h in 0..nh {
            if self.twin[h] != NONE {
                continue;
            }
            let v = self.corner_vertex[h] as usize;
            let w = dest[h] as usize;
            // Other half-edges v→w (same direction) and w→v (opposite).
            let same = out[start[v] as usize..start[v + 1] as usize]
                .iter()
                .filter(|&&g| g != h as u32 && dest[g as usize] as usize == w)
                .count();
            let mut opposite = 0;
            let mut twin = NONE;
            for &g in &out[start[w] as usize..start[w + 1] as usize] {
                if dest[g as usize] as usize == v {
                    twin = g;
                    opposite += 1;
                }
            }
            if 1 + same + opposite > 2 {
                return Err(self.non_manifold_edge(&out, &start, v, w));
            }
            if same > 0 {
                return Err(MeshError::InconsistentOrientation {
                    face: self.second_face_on(&out, &start, v, w),
                    edge: [v, w],
                });
            }
            if twin != NONE {
                self.twin[h] = twin;
                self.twin[twin as usize] = h as u32;
            }
        }
        Ok(())
    }

    /// The later of the two faces running `v→w`.
    fn second_face_on(&self, out: &[u32], start: &[u32], v: usize, w: usize) -> usize {
        out[start[v] as usize..start[v + 1] as usize]
            .iter()
            .filter(|&&g| self.dest(g) as usize == w)
            .map(|&g| self.corner_face[g as usize] as usize)
            .nth(1)
            .unwrap_or(0)
    }

    /// The error for edge `{v, w}` used by three or more faces: names the
    /// third face in face order.
    fn non_manifold_edge(&self, out: &[u32], start: &[u32], v: usize, w: usize) -> MeshError {
        let mut faces: Vec<u32> = Vec::new();
        for (a, b) in [(v, w), (w, v)] {
            for &g in &out[start[a] as usize..start[a + 1] as usize] {
                if self.dest(g) as usize == b {
                    faces.push(self.corner_face[g as usize]);
                }
            }
        }
        faces.sort_unstable();
        MeshError::NonManifoldEdge {
            face: faces.get(2).copied().unwrap_or(0) as usize,
            edge: [v.min(w), v.max(w)],
        }
    }

    /// Finds each vertex's fan start and checks that its faces form one disk
    /// (interior) or one half-disk (boundary).
    fn link_vertices(&mut self) -> Result<(), MeshError> {
        let nh = self.corner_vertex.len();
        let nv = self.vertex_start.len();
        let mut boundary_out = mem::filled(nv, 0u32)?;
        for h in 0..nh {
            let v = self.corner_vertex[h] as usize;
            self.vertex_faces[v] += 1;
            if self.vertex_start[v] == NONE {
                self.vertex_start[v] = h as u32;
            }
            if self.twin[h] == NONE {
                boundary_out[v] += 1;
                self.vertex_start[v] = h as u32;
                self.vertex_boundary[v] = true;
            }
        }
        for (v, &out) in boundary_out.iter().enumerate() {
            if self.vertex_start[v] == NONE {
                continue;
            }
            if out > 1 {
                return Err(MeshError::NonManifoldVertex { vertex: v });
            }
            // Walk the fan counter-clockwise; it must visit every face once.
            let first = self.vertex_start[v];
            let mut h = first;
            let mut seen = 0u32;
            loop {
                seen += 1;
                if seen > self.vertex_faces[v] {
                    return Err(MeshError::NonManifoldVertex { vertex: v });
                }
                let t = self.twin[self.prev(h) as usize];
                if t == NONE || t == first {
                    break;
                }
                h = t;
            }
            if seen != self.vertex_faces[v] {
                return Err(MeshError::NonManifoldVertex { vertex: v });
            }
        }
        Ok(())
    }

    /// Number of vertices (used or not).
    #[inline]
    pub fn num_vertices(&self) -> usize {
        self.vertex_start.len()
    }
    /// Number of faces.
    #[inline]
    pub fn num_faces(&self) -> usize {
        self.face_start.len() - 1
    }
    /// Number of half-edges (= corners).
    #[inline]
    pub fn num_half_edges(&self) -> usize {
        self.corner_vertex.len()
    }
    /// The vertices of face `f`, counter-clockwise.
    #[inline]
    pub fn face(&self, f: usize) -> &[u32] {
        &self.corner_vertex[self.face_start[f] as usize..self.face_start[f + 1] as usize]
    }
    /// Half-edge of face `f` starting at its corner `k`.
    #[inline]
    pub fn face_half_edge(&self, f: usize, k: usize) -> u32 {
        self.face_start[f] + k as u32
    }
    /// First half-edge of face `f` (its corner 0).
    #[inline]
    pub fn face_first(&self, f: usize) -> u32 {
        self.face_start[f]
    }
    /// Number of vertices of face `f`.
    #[inline]
    pub fn face_len(&self, f: usize) -> usize {
        (self.face_start[f + 1] - self.face_start[f]) as usize
    }
    /// The vertex half-edge `h` leaves.
    #[inline]
    pub fn origin(&self, h: u32) -> u32 {
        self.corner_vertex[h as usize]
    }
    /// The vertex half-edge `h` enters.
    #[inline]
    pub fn dest(&self, h: u32) -> u32 {
        self.corner_vertex[self.next(h) as usize]
    }
    /// The face to the left of `h`.
    #[inline]
    pub fn face_of(&self, h: u32) -> u32 {
        self.corner_face[h as usize]
    }
    /// Corner index of `h` within its face.
    #[inline]
    pub fn corner_of(&self, h: u32) -> usize {
        (h - self.face_start[self.corner_face[h as usize] as usize]) as usize
    }
    /// The next half-edge of the same face.
    #[inline]
    pub fn next(&self, h: u32) -> u32 {
        let f = self.corner_face[h as usize] as usize;
        if h + 1 == self.face_start[f + 1] {
            self.face_start[f]
        } else {
            h + 1
        }
    }
    /// The previous half-edge of the same face.
    #[inline]
    pub fn prev(&self, h: u32) -> u32 {
        let f = self.corner_face[h as usize] as usize;
        if h == self.face_start[f] {
            self.face_start[f + 1] - 1
        } else {
            h - 1
        }
    }
    /// The opposite half-edge, or [`NONE`] on the boundary.
    #[inline]
    pub fn twin(&self, h: u32) -> u32 {
        self.twin[h as usize]
    }
    /// Next outgoing half-edge counter-clockwise around `origin(h)`, or
    /// [`NONE`] past the boundary.
    #[inline]
    pub fn rotate_ccw(&self, h: u32) -> u32 {
        self.twin[self.prev(h) as usize]
    }
    /// Next outgoing half-edge clockwise around `origin(h)`, or [`NONE`].
    #[inline]
    pub fn rotate_cw(&self, h: u32) -> u32 {
        let t = self.twin[h as usize];
        if t == NONE {
            NONE
        } else {
            self.next(t)
        }
    }
    /// The first outgoing half-edge of vertex `v`'s fan (for a boundary
    /// vertex, the one on the boundary), or [`NONE`] for an unused vertex.
    #[inline]
    pub fn vertex_first(&self, v: usize) -> u32 {
        self.vertex_start[v]
    }
    /// Number of faces around `v`.
    #[inline]
    pub fn vertex_face_count(&self, v: usize) -> usize {
        self.vertex_faces[v] as usize
    }
    /// Number of edges at `v`: faces, plus one on the boundary.
    #[inline]
    pub fn valence(&self, v: usize) -> usize {
        self.vertex_faces[v] as usize + usize::from(self.vertex_boundary[v])
    }
    /// Whether `v` lies on the boundary.
    #[inline]
    pub fn is_boundary(&self, v: usize) -> bool {
        self.vertex_boundary[v]
    }
    /// Whether the mesh has no boundary edge.
    pub fn is_closed(&self) -> bool {
        self.twin.iter().all(|&t| t != NONE)
    }
    /// The outgoing half-edges of `v`, counter-clockwise, starting at
    /// [`Self::vertex_first`].
    pub fn outgoing(&self, v: usize) -> Outgoing<'_> {
        let first = self.vertex_start[v];
        Outgoing {
            topo: self,
            first,
            next: first,
        }
    }
}

/// Iterator over a vertex's outgoing half-edges, counter-clockwise.
#[derive(Clone, Debug)]
pub struct Outgoing<'a> {
    topo: &'a Topology,
    first: u32,
    next: u32,
}

impl Iterator for Outgoing<'_> {
    type Item = u32;
    fn next(&mut self) -> Option<u32> {
        if self.next == NONE {
            return None;
        }
        let h = self.next;
        let r = self.topo.rotate_ccw(h);
        self.next = if r == self.first { NONE } else { r };
        Some(h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(v: usize, faces: &[&[u32]]) -> MeshInput {
        MeshInput::new(
            (0..v).map(|i| [i as f64, 0.0, 0.0]).collect(),
            faces.iter().map(|f| f.to_vec()).collect(),
        )
    }

    /// The cube: 8 vertices of valence 3, closed.
    fn cube() -> MeshInput {
        mesh(
            8,
            &[
                &[0, 3, 2, 1],
                &[4, 5, 6, 7],
                &[0, 1, 5, 4],
                &[1, 2, 6, 5],
                &[2, 3, 7, 6],
                &[3, 0, 4, 7],
            ],
        )
    }

    #[test]
    fn cube_is_closed_with_valence_three() {
        let t = Topology::new(&cube()).unwrap();
        assert!(t.is_closed());
        for v in 0..8 {
            assert_eq!(t.valence(v), 3);
            assert_eq!(t.outgoing(v).count(), 3);
            // Every outgoing half-edge starts at v; twins run back.
            for h in t.outgoing(v) {
                assert_eq!(t.origin(h) as usize, v);
                assert_eq!(t.dest(t.twin(h)) as usize, v);
            }
        }
    }

    #[test]
    fn open_grid_has_boundary_fans() {
        // 2x2 quads on a 3x3 vertex grid.
        let m = mesh(
            9,
            &[&[0, 1, 4, 3], &[1, 2, 5, 4], &[3, 4, 7, 6], &[4, 5, 8, 7]],
        );
        let t = Topology::new(&m).unwrap();
        assert!(!t.is_closed());
        assert_eq!(t.valence(4), 4);
        assert!(!t.is_boundary(4));
        assert_eq!((t.valence(1), t.is_boundary(1)), (3, true));
        assert_eq!((t.valence(0), t.is_boundary(0)), (2, true));
        // A boundary fan starts at its boundary edge and visits all faces.
        let h = t.vertex_first(1);
        assert_eq!(t.twin(h), NONE);
        assert_eq!(t.outgoing(1).count(), 2);
    }

    #[test]
    fn each_bad_mesh_gives_its_error() {
        assert_eq!(Topology::new(&mesh(3, &[])).unwrap_err(), MeshError::Empty);
        let mut m = mesh(3, &[&[0, 1, 2]]);
        m.vertices[1][2] = f64::NAN;
        assert_eq!(
            Topology::new(&m).unwrap_err(),
            MeshError::NonFinite { vertex: 1 }
        );
        assert_eq!(
            Topology::new(&mesh(3, &[&[0, 1]])).unwrap_err(),
            MeshError::FaceTooSmall { face: 0, len: 2 }
        );
        assert_eq!(
            Topology::new(&mesh(3, &[&[0, 1, 3]])).unwrap_err(),
            MeshError::IndexOutOfRange {
                face: 0,
                index: 3,
                vertices: 3
            }
        );
        assert_eq!(
            Topology::new(&mesh(3, &[&[0, 1, 2], &[0, 2, 1, 0]])).unwrap_err(),
            MeshError::RepeatedVertex { face: 1, vertex: 0 }
        );
        // Two triangles running edge 0-1 the same way.
        assert_eq!(
            Topology::new(&mesh(4, &[&[0, 1, 2], &[0, 1, 3]])).unwrap_err(),
            MeshError::InconsistentOrientation {
                face: 1,
                edge: [0, 1]
            }
        );
        // Three triangles on edge 0-1.
        assert_eq!(
            Topology::new(&mesh(5, &[&[0, 1, 2], &[1, 0, 3], &[1, 0, 4]])).unwrap_err(),
            MeshError::NonManifoldEdge {
                face: 2,
                edge: [0, 1]
            }
        );
        // Two triangles touching at vertex 0 only (a bow-tie).
        assert_eq!(
            Topology::new(&mesh(5, &[&[0, 1, 2], &[0, 3, 4]])).unwrap_err(),
            MeshError::NonManifoldVertex { vertex: 0 }
        );
    }

    #[test]
    fn closed_cone_of_two_fans_sharing_a_vertex_is_non_manifold() {
        // Two closed tetrahedra glued at vertex 0 only: every edge is fine,
        // vertex 0's faces form two disks.
        let m = mesh(
            7,
            &[
                &[0, 2, 1],
                &[0, 1, 3],
                &[0, 3, 2],
                &[1, 2, 3],
                &[0, 5, 4],
                &[0, 4, 6],
                &[0, 6, 5],
                &[4, 5, 6],
            ],
        );
        assert_eq!(
            Topology::new(&m).unwrap_err(),
            MeshError::NonManifoldVertex { vertex: 0 }
        );
    }
}
