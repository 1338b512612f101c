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
use alloc::vec;
use alloc::vec::Vec;

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
    /// Per edge: its vertices (the smaller index first).
    pub edge_vertices: Vec<[u32; 2]>,
    /// Per edge: sharpness.
    pub edge_sharpness: Vec<f32>,
    /// CSR: corners whose edge is this edge.
    edge_corner_start: Vec<u32>,
    edge_corners: Vec<Corner>,
    /// CSR: corners at this vertex.
    vertex_corner_start: Vec<u32>,
    vertex_corners: Vec<Corner>,
    /// CSR: edges at this vertex.
    vertex_edge_start: Vec<u32>,
    vertex_edges: Vec<u32>,
}

impl Level {
    /// A level from faces (`faces[f]` = vertex indices), the point of each
    /// vertex, vertex sharpness, hole flags and an edge sharpness lookup
    /// (`sharp(a, b)` with `a < b`).
    pub fn new(
        faces: &[&[u32]],
        point: Vec<u32>,
        vertex_sharpness: Vec<f32>,
        hole: Vec<bool>,
        mut sharp: impl FnMut(u32, u32) -> f32,
    ) -> Level {
        let nv = point.len();
        let mut face_start = Vec::with_capacity(faces.len() + 1);
        let mut corner_vertex = Vec::new();
        let mut corner_face = Vec::new();
        face_start.push(0);
        for (f, vs) in faces.iter().enumerate() {
            corner_vertex.extend_from_slice(vs);
            corner_face.extend(core::iter::repeat_n(f as u32, vs.len()));
            face_start.push(corner_vertex.len() as u32);
        }
        let nc = corner_vertex.len();
        // Edges: corners sorted by their (min, max) vertex pair.
        let next = |c: usize| -> usize {
            let f = corner_face[c] as usize;
            let (a, b) = (face_start[f] as usize, face_start[f + 1] as usize);
            if c + 1 == b {
                a
            } else {
                c + 1
            }
        };
        let pair = |c: usize| -> [u32; 2] {
            let (a, b) = (corner_vertex[c], corner_vertex[next(c)]);
            if a <= b {
                [a, b]
            } else {
                [b, a]
            }
        };
        let mut order: Vec<([u32; 2], u32)> = (0..nc).map(|c| (pair(c), c as u32)).collect();
        order.sort_unstable();
        let mut corner_edge = vec![0u32; nc];
        let mut edge_vertices: Vec<[u32; 2]> = Vec::new();
        let mut edge_corner_start = vec![0u32];
        let mut edge_corners = Vec::with_capacity(nc);
        for &(p, c) in &order {
            if edge_vertices.last() != Some(&p) {
                if !edge_vertices.is_empty() {
                    edge_corner_start.push(edge_corners.len() as u32);
                }
                edge_vertices.push(p);
            }
            corner_edge[c as usize] = (edge_vertices.len() - 1) as u32;
            edge_corners.push(c);
        }
        edge_corner_start.push(edge_corners.len() as u32);
        let edge_sharpness = edge_vertices.iter().map(|&[a, b]| sharp(a, b)).collect();
        // Vertex incidence.
        let csr = |keys: &mut dyn Iterator<Item = (u32, u32)>, n: usize| {
            let items: Vec<(u32, u32)> = keys.collect();
            let mut start = vec![0u32; n + 1];
            for &(k, _) in &items {
                start[k as usize + 1] += 1;
            }
            for i in 0..n {
                start[i + 1] += start[i];
            }
            let mut fill = start.clone();
            let mut out = vec![0u32; items.len()];
            for &(k, x) in &items {
                out[fill[k as usize] as usize] = x;
                fill[k as usize] += 1;
            }
            (start, out)
        };
        let (vertex_corner_start, vertex_corners) = csr(
            &mut corner_vertex
                .iter()
                .enumerate()
                .map(|(c, &v)| (v, c as u32)),
            nv,
        );
        let (vertex_edge_start, vertex_edges) = csr(
            &mut edge_vertices.iter().enumerate().flat_map(|(e, &[a, b])| {
                let e = e as u32;
                // A degenerate edge (a = b) is listed once.
                [(a, e)].into_iter().chain((a != b).then_some((b, e)))
            }),
            nv,
        );
        Level {
            face_start,
            corner_vertex,
            corner_edge,
            corner_face,
            hole,
            point,
            vertex_sharpness,
            edge_vertices,
            edge_sharpness,
            edge_corner_start,
            edge_corners,
            vertex_corner_start,
            vertex_corners,
            vertex_edge_start,
            vertex_edges,
        }
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.face_start.len() - 1
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.point.len()
    }

    /// Face `f`'s corners.
    pub fn face_corners(&self, f: usize) -> core::ops::Range<u32> {
        self.face_start[f]..self.face_start[f + 1]
    }

    /// Face `f`'s vertices.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.corner_vertex[self.face_start[f] as usize..self.face_start[f + 1] as usize]
    }

    /// The next corner of the same face.
    pub fn next(&self, c: Corner) -> Corner {
        let f = self.corner_face[c as usize] as usize;
        if c + 1 == self.face_start[f + 1] {
            self.face_start[f]
        } else {
            c + 1
        }
    }

    /// The previous corner of the same face.
    pub fn prev(&self, c: Corner) -> Corner {
        let f = self.corner_face[c as usize] as usize;
        if c == self.face_start[f] {
            self.face_start[f + 1] - 1
        } else {
            c - 1
        }
    }

    /// Corners at vertex `v`.
    pub fn vertex_corners(&self, v: usize) -> &[Corner] {
        let (a, b) = (
            self.vertex_corner_start[v] as usize,
            self.vertex_corner_start[v + 1] as usize,
        );
        &self.vertex_corners[a..b]
    }

    /// Edges at vertex `v`.
    pub fn vertex_edges(&self, v: usize) -> &[u32] {
        let (a, b) = (
            self.vertex_edge_start[v] as usize,
            self.vertex_edge_start[v + 1] as usize,
        );
        &self.vertex_edges[a..b]
    }

    /// Corners whose edge is `e`.
    pub fn edge_corners(&self, e: usize) -> &[Corner] {
        let (a, b) = (
            self.edge_corner_start[e] as usize,
            self.edge_corner_start[e + 1] as usize,
        );
        &self.edge_corners[a..b]
    }

    /// The other end of edge `e` from `v`.
    pub fn other_end(&self, e: usize, v: u32) -> u32 {
        let [a, b] = self.edge_vertices[e];
        if a == v {
            b
        } else {
            a
        }
    }

    /// Whether edge `e` is manifold: two faces running it in opposite
    /// directions, two distinct ends.
    pub fn edge_is_manifold(&self, e: usize) -> bool {
        let cs = self.edge_corners(e);
        cs.len() == 2 && {
            let [a, b] = self.edge_vertices[e];
            a != b && self.corner_vertex[cs[0] as usize] != self.corner_vertex[cs[1] as usize]
        }
    }

    /// Across edge `corner_edge[c]` from corner `c`'s face: the corner of the
    /// other face at the same edge (`None` unless the edge is manifold).
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
        self.walk(c, true, out)
    }

    /// [`Self::fan`], crossing sharp edges too when `stop_at_sharp` is false
    /// (one fan of the vertex's faces).
    fn walk(&self, c: Corner, stop_at_sharp: bool, out: &mut Vec<Corner>) -> bool {
        out.clear();
        out.push(c);
        let limit = self
            .vertex_corners(self.corner_vertex[c as usize] as usize)
            .len();
        let crossable = |k: Corner| {
            !(stop_at_sharp && is_sharp(self.edge_sharpness[self.corner_edge[k as usize] as usize]))
        };
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
    /// and two edges an infinitely sharp corner when `sharpen_corners`; a
    /// non-manifold vertex infinitely sharp unless it lies on an interior
    /// non-manifold crease.
    pub fn sharpen_base(&mut self, sharpen_corners: bool) {
        let ne = self.edge_vertices.len();
        let nonmanifold_edge: Vec<bool> = (0..ne)
            .map(|e| self.edge_corners(e).len() > 1 && !self.edge_is_manifold(e))
            .collect();
        for (e, nm) in nonmanifold_edge.iter().enumerate() {
            if self.edge_corners(e).len() < 2 || *nm {
                self.edge_sharpness[e] = INFINITE;
            }
        }
        let mut fan = Vec::new();
        for v in 0..self.num_vertices() {
            let corners = self.vertex_corners(v);
            if corners.is_empty() {
                continue;
            }
            let edges = self.vertex_edges(v);
            let boundary = edges
                .iter()
                .filter(|&&e| self.edge_corners(e as usize).len() < 2)
                .count();
            let nm_edges = edges
                .iter()
                .filter(|&&e| nonmanifold_edge[e as usize])
                .count();
            let faces = corners.len();
            if faces == 1 && edges.len() == 2 {
                if sharpen_corners {
                    self.vertex_sharpness[v] = INFINITE;
                }
                continue;
            }
            // Non-manifold: a non-manifold edge, or more than one fan (fans
            // cut only at boundary and non-manifold edges here).
            let first = corners[0];
            let mut one_fan = true;
            if nm_edges == 0 {
                self.walk(first, false, &mut fan);
                one_fan = fan.len() == faces;
            }
            let nonmanifold = nm_edges > 0 || !one_fan;
            if nonmanifold && !(nm_edges == 2 && boundary == 0 && faces > edges.len()) {
                self.vertex_sharpness[v] = INFINITE;
            }
        }
    }
}
