//! `Level`: a face-vertex mesh of one refinement level with OpenSubdiv's
//! component tags — edge and vertex sharpness, holes — and the incidence
//! OpenSubdiv's `Vtr::Level` keeps (faces and edges of every vertex, faces of
//! every edge), without assuming a manifold: an edge may have any number of
//! faces, a vertex any number of fans.
//!
//! A level is either a whole base mesh or a *neighbourhood*: the children of
//! some faces of a parent neighbourhood. In a neighbourhood only the vertices
//! whose faces are all present ("complete") may be asked for rules, masks or
//! regularity; [`crate::adaptive`] keeps to those.

use super::crease::{is_semi_sharp, is_sharp, vertex_rule, Rule, INFINITE};
use crate::mem::{self, OutOfMemory};
use alloc::vec::Vec;
use hashbrown::HashMap;

/// One corner of a face: index into [`Level::corner_vertex`].
pub type Corner = u32;

/// A mesh level.
#[derive(Clone, Debug, Default)]
pub struct Level {
    /// `face_start[f]..face_start[f+1]` are face `f`'s corners.
    pub face_start: Vec<u32>,
    /// Vertex of each corner.
    pub corner_vertex: Vec<u32>,
    /// Edge of each corner: the edge from the corner to the next one.
    pub corner_edge: Vec<u32>,
    /// Face of each corner.
    pub corner_face: Vec<u32>,
    /// Per face: a hole (no surface over it).
    pub hole: Vec<bool>,
    /// Per vertex: the point it is (an index of the plan's working points).
    pub point: Vec<u32>,
    /// Per vertex: sharpness.
    pub vertex_sharpness: Vec<f32>,
    /// Per edge: its vertices (as made: the base level's from the face that
    /// made it, a refined level's from the parent's component).
    pub edge_vertices: Vec<[u32; 2]>,
    /// Per edge: sharpness.
    pub edge_sharpness: Vec<f32>,
    /// Per edge: OpenSubdiv's non-manifold tag (made at the base level,
    /// inherited by the children of an edge).
    pub edge_nonmanifold: Vec<bool>,
    /// Per edge: how many edges between the same two vertices were made
    /// before it (base level; 0 in a refined level, whose vertices are
    /// distinct points wherever their edges are).
    pub edge_instance: Vec<u32>,
    /// CSR: corners whose edge is this edge.
    edge_corner_start: Vec<u32>,
    edge_corners: Vec<Corner>,
    /// CSR: corners at this vertex.
    vertex_corner_start: Vec<u32>,
    vertex_corners: Vec<Corner>,
    /// CSR: edges at this vertex (a degenerate edge twice).
    vertex_edge_start: Vec<u32>,
    vertex_edges: Vec<u32>,
}

/// The faces of a level: corners face after face.
#[derive(Clone, Debug, Default)]
pub struct Faces {
    /// `face_start[f]..face_start[f+1]` are face `f`'s corners.
    pub face_start: Vec<u32>,
    /// Vertex of each corner.
    pub corner_vertex: Vec<u32>,
    /// Face of each corner.
    pub corner_face: Vec<u32>,
    /// Edge of each corner (from the corner to the next one).
    pub corner_edge: Vec<u32>,
}

/// The edges of a level.
#[derive(Clone, Debug, Default)]
pub struct Edges {
    /// Per edge: its two vertices.
    pub vertices: Vec<[u32; 2]>,
    /// Per edge: sharpness.
    pub sharpness: Vec<f32>,
    /// Per edge: OpenSubdiv's non-manifold tag.
    pub nonmanifold: Vec<bool>,
    /// Per edge: [`Level::edge_instance`] (empty: all 0).
    pub instance: Vec<u32>,
}

impl Level {
    /// A base level from faces (`faces[f]` = vertex indices), the point of
    /// each vertex, vertex sharpness, hole flags and an edge sharpness lookup
    /// (`sharp(a, b)` with `a ≤ b`). Edges are made as OpenSubdiv's
    /// `Vtr::Level::completeTopologyFromFaceVertices` makes them, face after
    /// face: a face's edge from `a` to `b ≠ a` joins the first edge made
    /// between them unless that edge's last face is this face (a face
    /// running it twice), which makes a new edge, both then non-manifold;
    /// an edge already with two faces, or with one face running it the same
    /// way, becomes non-manifold; every degenerate edge (`a = b`) is a new,
    /// non-manifold edge. Every buffer is reserved fallibly
    /// ([`crate::mem`]).
    pub fn new(
        faces: &[&[u32]],
        point: Vec<u32>,
        vertex_sharpness: Vec<f32>,
        hole: Vec<bool>,
        mut sharp: impl FnMut(u32, u32) -> f32,
    ) -> Result<Level, OutOfMemory> {
        let nc: usize = faces.iter().map(|f| f.len()).sum();
        let mut face_start = mem::with_capacity(faces.len() + 1)?;
        let mut corner_vertex = mem::with_capacity(nc)?;
        let mut corner_face = mem::with_capacity(nc)?;
        face_start.push(0);
        for (f, vs) in faces.iter().enumerate() {
            corner_vertex.extend_from_slice(vs);
            corner_face.extend(core::iter::repeat_n(f as u32, vs.len()));
            face_start.push(corner_vertex.len() as u32);
        }
        let mut corner_edge = mem::filled(nc, 0u32)?;
        // Per edge (a closed mesh has an edge per two corners; an open one
        // grows the lists past that): its vertices, non-manifold tag, face
        // count, last face and instance.
        let edges = nc / 2;
        let mut edge_vertices: Vec<[u32; 2]> = mem::with_capacity(edges)?;
        let mut nonmanifold: Vec<bool> = mem::with_capacity(edges)?;
        let mut face_count: Vec<u32> = mem::with_capacity(edges)?;
        let mut last_face: Vec<u32> = mem::with_capacity(edges)?;
        let mut instance: Vec<u32> = mem::with_capacity(edges)?;
        // The first edge made between two vertices, and how many.
        let mut first: HashMap<(u32, u32), (u32, u32)> = HashMap::new();
        mem::reserve_map(&mut first, edges)?;
        for (f, vs) in faces.iter().enumerate() {
            let f = f as u32;
            let base = face_start[f as usize] as usize;
            for i in 0..vs.len() {
                let (a, b) = (vs[i], vs[(i + 1) % vs.len()]);
                let mut found = None;
                let mut new_nonmanifold = a == b;
                if a != b {
                    if let Some(&(e, _)) = first.get(&(a.min(b), a.max(b))) {
                        let e = e as usize;
                        if last_face[e] == f {
                            nonmanifold[e] = true;
                            new_nonmanifold = true;
                        } else {
                            if face_count[e] > 1 || edge_vertices[e][0] == a {
                                nonmanifold[e] = true;
                            }
                            found = Some(e);
                        }
                    }
                }
                let e = match found {
                    Some(e) => e,
                    None => {
                        mem::push(&mut edge_vertices, [a, b])?;
                        mem::push(&mut nonmanifold, new_nonmanifold)?;
                        mem::push(&mut face_count, 0)?;
                        mem::push(&mut last_face, f)?;
                        let e = edge_vertices.len() - 1;
                        mem::reserve_map(&mut first, 1)?;
                        let made = first.entry((a.min(b), a.max(b))).or_insert((e as u32, 0));
                        mem::push(&mut instance, made.1)?;
                        made.1 += 1;
                        e
                    }
                };
                face_count[e] += 1;
                last_face[e] = f;
                corner_edge[base + i] = e as u32;
            }
        }
        let edge_sharpness = mem::collect(
            edge_vertices
                .iter()
                .map(|&[a, b]| sharp(a.min(b), a.max(b))),
        )?;
        Level::from_parts(
            Faces {
                face_start,
                corner_vertex,
                corner_face,
                corner_edge,
            },
            Edges {
                vertices: edge_vertices,
                sharpness: edge_sharpness,
                nonmanifold,
                instance,
            },
            point,
            vertex_sharpness,
            hole,
        )
    }

    /// A level from its faces and edges as they are (a refined level, whose
    /// edges its parent's make), with the incidence derived from them
    /// (reserved fallibly).
    pub fn from_parts(
        faces: Faces,
        edges: Edges,
        point: Vec<u32>,
        vertex_sharpness: Vec<f32>,
        hole: Vec<bool>,
    ) -> Result<Level, OutOfMemory> {
        let nv = point.len();
        let ne = edges.vertices.len();
        let (edge_corner_start, edge_corners) = csr(
            faces
                .corner_edge
                .iter()
                .enumerate()
                .map(|(c, &e)| (e, c as u32)),
            ne,
        )?;
        let (vertex_corner_start, vertex_corners) = csr(
            faces
                .corner_vertex
                .iter()
                .enumerate()
                .map(|(c, &v)| (v, c as u32)),
            nv,
        )?;
        // Each edge at each of its ends: a degenerate edge twice, as
        // OpenSubdiv lists it.
        let (vertex_edge_start, vertex_edges) = csr(
            edges
                .vertices
                .iter()
                .enumerate()
                .flat_map(|(e, &[a, b])| [(a, e as u32), (b, e as u32)]),
            nv,
        )?;
        Ok(Level {
            face_start: faces.face_start,
            corner_vertex: faces.corner_vertex,
            corner_edge: faces.corner_edge,
            corner_face: faces.corner_face,
            hole,
            point,
            vertex_sharpness,
            edge_vertices: edges.vertices,
            edge_sharpness: edges.sharpness,
            edge_nonmanifold: edges.nonmanifold,
            edge_instance: if edges.instance.is_empty() {
                mem::filled(ne, 0)?
            } else {
                edges.instance
            },
            edge_corner_start,
            edge_corners,
            vertex_corner_start,
            vertex_corners,
            vertex_edge_start,
            vertex_edges,
        })
    }

    /// Number of faces.
    #[inline]
    pub fn num_faces(&self) -> usize {
        self.face_start.len() - 1
    }

    /// Number of vertices.
    #[inline]
    pub fn num_vertices(&self) -> usize {
        self.point.len()
    }

    /// Face `f`'s corners.
    #[inline]
    pub fn face_corners(&self, f: usize) -> core::ops::Range<u32> {
        self.face_start[f]..self.face_start[f + 1]
    }

    /// Face `f`'s vertices.
    #[inline]
    pub fn face(&self, f: usize) -> &[u32] {
        &self.corner_vertex[self.face_start[f] as usize..self.face_start[f + 1] as usize]
    }

    /// The next corner of the same face.
    #[inline]
    pub fn next(&self, c: Corner) -> Corner {
        let f = self.corner_face[c as usize] as usize;
        if c + 1 == self.face_start[f + 1] {
            self.face_start[f]
        } else {
            c + 1
        }
    }

    /// The previous corner of the same face.
    #[inline]
    pub fn prev(&self, c: Corner) -> Corner {
        let f = self.corner_face[c as usize] as usize;
        if c == self.face_start[f] {
            self.face_start[f + 1] - 1
        } else {
            c - 1
        }
    }

    /// Corners at vertex `v`.
    #[inline]
    pub fn vertex_corners(&self, v: usize) -> &[Corner] {
        let (a, b) = (
            self.vertex_corner_start[v] as usize,
            self.vertex_corner_start[v + 1] as usize,
        );
        &self.vertex_corners[a..b]
    }

    /// Edges at vertex `v`.
    #[inline]
    pub fn vertex_edges(&self, v: usize) -> &[u32] {
        let (a, b) = (
            self.vertex_edge_start[v] as usize,
            self.vertex_edge_start[v + 1] as usize,
        );
        &self.vertex_edges[a..b]
    }

    /// Corners whose edge is `e`.
    #[inline]
    pub fn edge_corners(&self, e: usize) -> &[Corner] {
        let (a, b) = (
            self.edge_corner_start[e] as usize,
            self.edge_corner_start[e + 1] as usize,
        );
        &self.edge_corners[a..b]
    }

    /// The other end of edge `e` from `v`.
    #[inline]
    pub fn other_end(&self, e: usize, v: u32) -> u32 {
        let [a, b] = self.edge_vertices[e];
        if a == v {
            b
        } else {
            a
        }
    }

    /// Whether edge `e` is manifold: not tagged non-manifold, two faces
    /// running it in opposite directions, two distinct ends.
    ///
    /// An edge with two corners that is not tagged runs between two vertices
    /// in opposite directions: [`Level::new`] tags a degenerate edge, a
    /// face running an edge twice and a second face running it the same
    /// way, and a refined level's edges inherit the tag or lie inside a
    /// parent face (two child faces, opposite ways), so the tag and the
    /// corner count tell.
    pub fn edge_is_manifold(&self, e: usize) -> bool {
        // The corner count from the offsets (not `edge_corners`, whose slice
        // bounds checks cost 2 % of a tagged mesh's analysis here).
        let two = self.edge_corner_start[e + 1] - self.edge_corner_start[e] == 2;
        let manifold = two && !self.edge_nonmanifold[e];
        debug_assert!(
            !manifold || {
                let cs = self.edge_corners(e);
                let [a, b] = self.edge_vertices[e];
                a != b && self.corner_vertex[cs[0] as usize] != self.corner_vertex[cs[1] as usize]
            }
        );
        manifold
    }

    /// Across edge `corner_edge[c]` from corner `c`'s face: the corner of the
    /// other face at the same edge (`None` unless the edge is manifold).
    #[inline]
    pub fn across(&self, c: Corner) -> Option<Corner> {
        let e = self.corner_edge[c as usize] as usize;
        if !self.edge_is_manifold(e) {
            return None;
        }
        let cs = self.edge_corners(e);
        Some(if cs[0] == c { cs[1] } else { cs[0] })
    }

    /// Vertex `v`'s rule from its sharpness and sharp edges.
    pub fn rule(&self, v: usize) -> Rule {
        let sharp = self
            .vertex_edges(v)
            .iter()
            .filter(|&&e| is_sharp(self.edge_sharpness[e as usize]))
            .count();
        vertex_rule(self.vertex_sharpness[v], sharp)
    }

    /// A semi-sharp vertex or edge at `v`: its rule will change.
    pub fn has_semi_sharp(&self, v: usize) -> bool {
        is_semi_sharp(self.vertex_sharpness[v])
            || self
                .vertex_edges(v)
                .iter()
                .any(|&e| is_semi_sharp(self.edge_sharpness[e as usize]))
    }

    /// The corners at `v` reachable from `c` across manifold edges that are
    /// not sharp (one sector of one sheet), in counter-clockwise order, and
    /// whether the walk came back to `c`.
    pub fn fan(&self, c: Corner, out: &mut Vec<Corner>) -> bool {
        out.clear();
        out.push(c);
        let limit = self
            .vertex_corners(self.corner_vertex[c as usize] as usize)
            .len();
        let crossable =
            |k: Corner| !is_sharp(self.edge_sharpness[self.corner_edge[k as usize] as usize]);
        // Counter-clockwise: across the edge from prev(k) to k.
        let mut k = c;
        loop {
            let p = self.prev(k);
            if !crossable(p) {
                break;
            }
            let Some(o) = self.across(p) else { break };
            if o == c {
                return true;
            }
            if out.len() > limit {
                break;
            }
            out.push(o);
            k = o;
        }
        // Clockwise: across the edge from k to next(k).
        let mut k = c;
        loop {
            if !crossable(k) {
                break;
            }
            let Some(o) = self.across(k) else { break };
            let o = self.next(o);
            if o == c || out.len() > limit {
                break;
            }
            out.insert(0, o);
            k = o;
        }
        false
    }

    /// Applies OpenSubdiv's base-level sharpening
    /// (`TopologyRefinerFactoryBase::prepareComponentTagsAndSharpness`):
    /// boundary and non-manifold edges infinitely sharp; a vertex of one face
    /// and two edges an infinitely sharp corner when `sharpen_corners`;
    /// otherwise a non-manifold vertex (at a non-manifold edge, or whose
    /// faces and edges [`Self::orders_around`] cannot order) infinitely sharp
    /// unless it lies on an interior non-manifold crease (two non-manifold
    /// edges, no boundary edge, more faces than edges).
    pub fn sharpen_base(&mut self, sharpen_corners: bool) -> Result<(), OutOfMemory> {
        let ne = self.edge_vertices.len();
        for e in 0..ne {
            if self.edge_corners(e).len() < 2 || self.edge_nonmanifold[e] {
                self.edge_sharpness[e] = INFINITE;
            }
        }
        let mut nonmanifold = mem::filled(self.num_vertices(), false)?;
        for e in (0..ne).filter(|&e| self.edge_nonmanifold[e]) {
            for v in self.edge_vertices[e] {
                nonmanifold[v as usize] = true;
            }
        }
        for v in 0..self.num_vertices() {
            let edges = self.vertex_edges(v);
            let faces = self.vertex_corners(v).len();
            let boundary = edges
                .iter()
                .filter(|&&e| self.edge_corners(e as usize).len() < 2)
                .count();
            let nm_edges = edges
                .iter()
                .filter(|&&e| self.edge_nonmanifold[e as usize])
                .count();
            if faces == 1 && edges.len() == 2 && sharpen_corners {
                self.vertex_sharpness[v] = INFINITE;
                continue;
            }
            let nonmanifold = nonmanifold[v] || !self.orders_around(v);
            if nonmanifold && !(nm_edges == 2 && boundary == 0 && faces > edges.len()) {
                self.vertex_sharpness[v] = INFINITE;
            }
        }
        Ok(())
    }

    /// Whether the faces and edges of vertex `v` order into one
    /// counter-clockwise fan, closed or between two boundary edges
    /// (OpenSubdiv's `Vtr::Level::orderVertexFacesAndEdges`, whose failure
    /// makes a vertex non-manifold): walking from the first face (interior)
    /// or from the leading boundary edge, across the edge before the vertex
    /// in each face, every edge is met once before the walk closes.
    pub fn orders_around(&self, v: usize) -> bool {
        let corners = self.vertex_corners(v);
        let edges = self.vertex_edges(v);
        let (nf, ne) = (corners.len(), edges.len());
        if nf == 0 || ne < 2 || ne > nf + 1 {
            return false;
        }
        let face_edge = |f: usize, k: usize| self.corner_edge[self.face_start[f] as usize + k];
        let position = |f: usize| self.face(f).iter().position(|&x| x as usize == v);
        let edge_faces = |e: u32| {
            self.edge_corners(e as usize)
                .iter()
                .map(|&c| self.corner_face[c as usize] as usize)
        };
        let (mut f, mut k, mut e_start);
        if ne == nf {
            f = self.corner_face[corners[0] as usize] as usize;
            k = position(f).unwrap_or(0);
            e_start = face_edge(f, k);
        } else {
            let mut start = None;
            for &e in edges {
                let mut faces = edge_faces(e);
                if let (Some(g), None) = (faces.next(), faces.next()) {
                    let kg = position(g).unwrap_or(0);
                    start = Some((g, kg, e));
                    if face_edge(g, kg) == e {
                        break;
                    }
                }
            }
            let Some(s) = start else { return false };
            (f, k, e_start) = s;
        }
        let e_first = e_start;
        let (mut e_count, mut f_count) = (1, 1);
        while e_count < ne {
            let n = self.face(f).len();
            let e_next = face_edge(f, if k == 0 { n - 1 } else { k - 1 });
            if e_next == e_start || e_next == e_first {
                return false;
            }
            e_count += 1;
            if f_count < nf {
                // The edge's other face: its second if its first is `f`.
                let mut faces = edge_faces(e_next);
                f = match (faces.next(), faces.next()) {
                    (Some(g), Some(h)) if g == f => h,
                    (Some(g), _) if g != f => g,
                    _ => return false,
                };
                k = (0..self.face(f).len())
                    .position(|i| face_edge(f, i) == e_next)
                    .unwrap_or(0);
                f_count += 1;
            }
            e_start = e_next;
        }
        true
    }
}

/// Compressed rows of `(key, item)` pairs over keys `0..n`: `(start, items)`,
/// the items of key `k` at `items[start[k]..start[k + 1]]` in the pairs'
/// order. Two passes over the pairs, no intermediate list; reserved
/// fallibly.
fn csr(
    pairs: impl Iterator<Item = (u32, u32)> + Clone,
    n: usize,
) -> Result<(Vec<u32>, Vec<u32>), OutOfMemory> {
    let mut start = mem::filled(n + 1, 0u32)?;
    let mut len = 0usize;
    for (k, _) in pairs.clone() {
        start[k as usize + 1] += 1;
        len += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = mem::to_vec(&start)?;
    let mut out = mem::filled(len, 0u32)?;
    for (k, x) in pairs {
        out[fill[k as usize] as usize] = x;
        fill[k as usize] += 1;
    }
    Ok((start, out))
}
