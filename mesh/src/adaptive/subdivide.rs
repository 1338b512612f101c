//! One Catmull-Clark refinement of some faces of a level with OpenSubdiv's
//! `Sdc` Catmark rules and creasing (`Sdc::Scheme::ComputeFaceVertexMask`,
//! `ComputeEdgeVertexMask`, `ComputeVertexVertexMask`, and the child
//! sharpness of `Vtr::Refinement`), and the limit masks
//! (`ComputeVertexLimitMask`).
//!
//! Refining faces `R` needs, for every vertex of `R`, all its faces and
//! edges; the caller ([`super::cover`]) refines the faces around the
//! corners of the faces it targets, inside a level that holds the faces
//! around their vertices, and the child level it gets back again holds the
//! faces around the corners' vertices of each child of a target (the
//! closure that lets the refinement go on).
//!
//! Masks, over the parent level's points:
//! - face point: centroid;
//! - edge point, sharpness `s`: smooth `(a + b)/4 + (f₁ + f₂)/4` (face
//!   centroids) when `s = 0`; the midpoint when both child edges are sharp;
//!   otherwise `s·midpoint + (1 − s)·smooth`;
//! - vertex point by the parent rule: smooth and dart `(n−2)/n·v + Σ ends/n²
//!   + Σ centroids/n²`, crease `¾ v + ⅛ (a + b)` (the sharp edges' ends),
//!   corner `v`; when the child's rule differs, `w·parent + (1 − w)·child`
//!   with `w` the fractional weight ([`super::crease::fractional_weight`]).

use super::crease::{child_edge_sharpness, decay, fractional_weight, is_sharp, vertex_rule, Rule};
use super::level::{Edges, Faces, Level};
use super::points::{Key, Points, Row};
use super::NONE;
use crate::mem::{self, OutOfMemory};
use alloc::vec::Vec;

/// Adds `w ×` face `f`'s centroid to `row`.
fn add_centroid(m: &Level, f: usize, w: f64, row: &mut Row) {
    let vs = m.face(f);
    let share = w / vs.len() as f64;
    for &v in vs {
        row.add(m.point[v as usize], share);
    }
}

/// The child level: the children of `faces` (each face's children in corner
/// order, face after face), and where each given face's children start.
pub struct Child {
    /// The child level.
    pub level: Level,
    /// `first[i]`: the child of `faces[i]` at its corner 0.
    pub first: Vec<u32>,
}

/// The rules of OpenSubdiv's `Sdc::Options` that change the masks.
#[derive(Clone, Copy, Debug, Default)]
pub struct Rules {
    /// `CREASE_CHAIKIN` (else `CREASE_UNIFORM`).
    pub chaikin: bool,
    /// `TRI_SUB_SMOOTH` (else `TRI_SUB_CATMARK`).
    pub smooth_triangles: bool,
}

/// Refines `faces` of `m` (see the module doc for what `m` must hold).
/// Every buffer is reserved fallibly, up front from the bounds below.
pub fn subdivide(
    m: &Level,
    faces: &[u32],
    rules: Rules,
    points: &mut Points,
) -> Result<Child, OutOfMemory> {
    let chaikin = rules.chaikin;
    // Children by parent index (NONE: not made yet).
    let mut vchild = mem::filled(m.num_vertices(), NONE)?;
    let mut echild = mem::filled(m.edge_vertices.len(), NONE)?;
    // Bounds: a child face per corner; a point per face, vertex and edge
    // (at most one of each per corner); two half edges per parent edge and
    // one edge inside the face per corner.
    let corners: usize = faces.iter().map(|&f| m.face(f as usize).len()).sum();
    let max_points = faces.len() + 2 * corners;
    let mut point: Vec<u32> = mem::with_capacity(max_points)?;
    let mut vsharp: Vec<f32> = mem::with_capacity(max_points)?;
    let mut faces_out = Faces {
        face_start: mem::with_capacity(corners + 1)?,
        corner_vertex: mem::with_capacity(4 * corners)?,
        corner_face: mem::with_capacity(4 * corners)?,
        corner_edge: mem::with_capacity(4 * corners)?,
    };
    faces_out.face_start.push(0);
    // Face points of about 4 entries, edge and vertex points of about 6
    // and 9 (at valence 4), roughly a quarter and a half as many as
    // corners.
    points.reserve(max_points, corners, 4 * faces.len() + 6 * corners)?;
    let max_edges = 3 * corners;
    let mut edges_out = Edges {
        vertices: mem::with_capacity(max_edges)?,
        sharpness: mem::with_capacity(max_edges)?,
        nonmanifold: mem::with_capacity(max_edges)?,
        instance: Vec::new(),
    };
    // Child edges by origin: per parent edge, the halves at its two ends;
    // per parent corner, the edge from the face point to the edge point of
    // the corner's edge.
    let mut edge_child = mem::filled(m.edge_vertices.len(), [NONE; 2])?;
    let mut face_child = mem::filled(m.corner_vertex.len(), NONE)?;
    let mut holes = mem::with_capacity(corners)?;
    let mut first = mem::with_capacity(faces.len())?;

    let new_vertex = |p: u32, s: f32, point: &mut Vec<u32>, vsharp: &mut Vec<f32>| -> u32 {
        point.push(p);
        vsharp.push(s);
        (point.len() - 1) as u32
    };
    let new_edge = |ends: [u32; 2], s: f32, nm: bool, edges: &mut Edges| -> u32 {
        edges.vertices.push(ends);
        edges.sharpness.push(s);
        edges.nonmanifold.push(nm);
        (edges.vertices.len() - 1) as u32
    };
    for &f in faces {
        let f = f as usize;
        // Each face is given once: its point is new.
        let p = face_point(m, f, points)?;
        let face_fc = new_vertex(p, 0.0, &mut point, &mut vsharp);
        for c in m.face_corners(f) {
            let v = m.corner_vertex[c as usize] as usize;
            if vchild[v] == NONE {
                let p = vertex_point(m, v, chaikin, points)?;
                let s = decay(m.vertex_sharpness[v]);
                vchild[v] = new_vertex(p, s, &mut point, &mut vsharp);
            }
        }
        for c in m.face_corners(f) {
            let e = m.corner_edge[c as usize] as usize;
            if echild[e] == NONE {
                let p = edge_point(m, e, rules, points)?;
                echild[e] = new_vertex(p, 0.0, &mut point, &mut vsharp);
            }
        }
        // The child edge of parent edge `e` at its end `end` (both ends
        // are corners of f: their children exist).
        let mut half = |e: usize, end: usize, edges: &mut Edges| -> u32 {
            if edge_child[e][end] == NONE {
                let s = m.edge_sharpness[e];
                let v = m.edge_vertices[e][end] as usize;
                let cs = child_edge_sharpness(s, chaikin, around(m, v));
                let cs = if is_sharp(cs) { cs } else { 0.0 };
                edge_child[e][end] =
                    new_edge([echild[e], vchild[v]], cs, m.edge_nonmanifold[e], edges);
            }
            edge_child[e][end]
        };
        // Which end of edge `e` corner vertex `v` is (`OpenSubdiv`'s
        // `QuadRefinement::populateFaceEdgesFromParentFaces`: of a
        // degenerate edge, the end after the corner for the edge leaving
        // it, the one before for the edge reaching it).
        let end_at = |e: usize, v: u32, leaving: bool| -> usize {
            let [a, b] = m.edge_vertices[e];
            if a == b {
                usize::from(!leaving)
            } else {
                usize::from(a != v)
            }
        };
        first.push((faces_out.face_start.len() - 1) as u32);
        let n = m.face(f).len();
        let start = m.face_start[f] as usize;
        for j in 0..n {
            let c = (start + j) as u32;
            let v = m.corner_vertex[c as usize];
            let e_next = m.corner_edge[c as usize] as usize;
            let e_prev = m.corner_edge[m.prev(c) as usize] as usize;
            let jp = if j == 0 { n - 1 } else { j - 1 };
            let mut across = |k: usize, e: usize, edges: &mut Edges| -> u32 {
                let slot = &mut face_child[start + k];
                if *slot == NONE {
                    *slot = new_edge([face_fc, echild[e]], 0.0, false, edges);
                }
                *slot
            };
            let edges = [
                half(e_next, end_at(e_next, v, true), &mut edges_out),
                across(j, e_next, &mut edges_out),
                across(jp, e_prev, &mut edges_out),
                half(e_prev, end_at(e_prev, v, false), &mut edges_out),
            ];
            let verts = [vchild[v as usize], echild[e_next], face_fc, echild[e_prev]];
            let face = (faces_out.face_start.len() - 1) as u32;
            faces_out.corner_vertex.extend_from_slice(&verts);
            faces_out.corner_edge.extend_from_slice(&edges);
            faces_out.corner_face.extend([face; 4]);
            faces_out
                .face_start
                .push(faces_out.corner_vertex.len() as u32);
            holes.push(m.hole[f]);
        }
    }
    let level = Level::from_parts(faces_out, edges_out, point, vsharp, holes)?;
    Ok(Child { level, first })
}

/// Sharpness of the edges at `v`.
fn around(m: &Level, v: usize) -> impl Iterator<Item = f32> + '_ {
    m.vertex_edges(v)
        .iter()
        .map(move |&e| m.edge_sharpness[e as usize])
}

/// The face point of `f` (a new point: [`subdivide`] makes each face's once).
pub fn face_point(m: &Level, f: usize, points: &mut Points) -> Result<u32, OutOfMemory> {
    points.make(|row| add_centroid(m, f, 1.0, row))
}

/// The edge point of `e`.
pub fn edge_point(
    m: &Level,
    e: usize,
    rules: Rules,
    points: &mut Points,
) -> Result<u32, OutOfMemory> {
    let chaikin = rules.chaikin;
    let [a, b] = m.edge_vertices[e];
    let (pa, pb) = (m.point[a as usize], m.point[b as usize]);
    let key = match m.edge_instance[e] {
        0 => Key::Edge(pa.min(pb), pa.max(pb)),
        k => Key::EdgeInstance(pa.min(pb), pa.max(pb), k),
    };
    points.get_or_make(key, |row| {
        let s = m.edge_sharpness[e];
        let mid = |r: &mut Row| {
            r.add(pa, 0.5);
            r.add(pb, 0.5);
        };
        let smooth = |r: &mut Row| {
            let corners = m.edge_corners(e);
            let triangle = |c: u32| m.face(m.corner_face[c as usize] as usize).len() == 3;
            let (wv, wf) = if rules.smooth_triangles
                && corners.len() == 2
                && corners.iter().any(|&c| triangle(c))
            {
                // `assignSmoothMaskForEdge` with `TRI_SUB_SMOOTH`, in its
                // order of operations.
                let fw = |c: u32| if triangle(c) { 0.470 } else { 0.25 };
                let wf = 0.5 * (fw(corners[0]) + fw(corners[1]));
                (0.5 * (1.0 - 2.0 * wf), wf)
            } else {
                (0.25, 0.25)
            };
            r.add(pa, wv);
            r.add(pb, wv);
            for &c in corners {
                add_centroid(m, m.corner_face[c as usize] as usize, wf, r);
            }
        };
        if !is_sharp(s) {
            return smooth(row);
        }
        let both_sharp = m.edge_vertices[e]
            .iter()
            .all(|&end| is_sharp(child_edge_sharpness(s, chaikin, around(m, end as usize))));
        if both_sharp {
            return mid(row);
        }
        let w = f64::from(s);
        let (mut sharp, mut smoothed) = (Row::new(), Row::new());
        mid(&mut sharp);
        smooth(&mut smoothed);
        *row = sharp.scaled(w).plus(smoothed.scaled(1.0 - w));
    })
}

/// Adds the mask of rule `rule` at `v` to `r` (`sharp[i]`: whether edge `i`
/// of `v` counts as sharp for the crease pair).
fn vertex_mask(m: &Level, v: usize, rule: Rule, sharp: &[bool], r: &mut Row) {
    let pv = m.point[v];
    match rule {
        Rule::Smooth | Rule::Dart => {
            let edges = m.vertex_edges(v);
            let n = edges.len() as f64;
            r.add(pv, (n - 2.0) / n);
            for &e in edges {
                r.add(
                    m.point[m.other_end(e as usize, v as u32) as usize],
                    1.0 / (n * n),
                );
            }
            for &c in m.vertex_corners(v) {
                add_centroid(m, m.corner_face[c as usize] as usize, 1.0 / (n * n), r);
            }
        }
        Rule::Crease => {
            r.add(pv, 0.75);
            let edges = m.vertex_edges(v);
            for (i, &e) in edges.iter().enumerate().filter(|(i, _)| sharp[*i]).take(2) {
                let _ = i;
                r.add(m.point[m.other_end(e as usize, v as u32) as usize], 0.125);
            }
        }
        Rule::Corner => r.add(pv, 1.0),
    }
}

/// The vertex point of `v`.
pub fn vertex_point(
    m: &Level,
    v: usize,
    chaikin: bool,
    points: &mut Points,
) -> Result<u32, OutOfMemory> {
    points.get_or_make(Key::Vertex(m.point[v]), |row| {
        let edges = m.vertex_edges(v);
        if m.vertex_sharpness[v] == 0.0
            && edges
                .iter()
                .all(|&e| !is_sharp(m.edge_sharpness[e as usize]))
        {
            // Smooth or dart now, and so in the child: no sharp edge pair.
            return vertex_mask(m, v, Rule::Smooth, &[], row);
        }
        let parent: Vec<f32> = edges
            .iter()
            .map(|&e| m.edge_sharpness[e as usize])
            .collect();
        let p_sharp: Vec<bool> = parent.iter().map(|&s| is_sharp(s)).collect();
        let p_rule = vertex_rule(
            m.vertex_sharpness[v],
            p_sharp.iter().filter(|&&s| s).count(),
        );
        vertex_mask(m, v, p_rule, &p_sharp, row);
        if matches!(p_rule, Rule::Smooth | Rule::Dart) {
            return;
        }
        let child: Vec<f32> = parent
            .iter()
            .map(|&s| child_edge_sharpness(s, chaikin, parent.iter().copied()))
            .collect();
        let c_sharp: Vec<bool> = child.iter().map(|&s| is_sharp(s)).collect();
        let cv = decay(m.vertex_sharpness[v]);
        let c_rule = vertex_rule(cv, c_sharp.iter().filter(|&&s| s).count());
        if c_rule == p_rule {
            return;
        }
        let p_mask = core::mem::take(row);
        let mut c_mask = Row::new();
        vertex_mask(m, v, c_rule, &c_sharp, &mut c_mask);
        let w = fractional_weight(
            m.vertex_sharpness[v],
            cv,
            parent.iter().copied().zip(child.iter().copied()),
        );
        *row = p_mask.scaled(w).plus(c_mask.scaled(1.0 - w));
    })
}

/// The limit position of `v` (`Sdc::Scheme::ComputeVertexLimitMask`): smooth
/// and dart `(n² v + 4 Σ ends + Σ opposite corners)/(n(n+5))` over quads
/// (`v` at valence 2), crease `(4v + a + b)/6`, corner `v`. Exact where the
/// rule stays the same at every level and is smooth, crease or corner; at a
/// dart (and valence 2) it is OpenSubdiv's approximation, so it differs a
/// little from level to level (the adaptive holes of one vertex share one). `None` for a smooth vertex with a
/// face that is not a quad (its limit mask needs face centroids; the
/// refinement never stops there).
pub fn limit_point(m: &Level, v: usize, points: &mut Points) -> Result<Option<u32>, OutOfMemory> {
    let rule = m.rule(v);
    let pv = m.point[v];
    let mut row = Row::new();
    match rule {
        // OpenSubdiv's smooth mask of a valence-2 vertex is the corner mask.
        Rule::Smooth | Rule::Dart if m.vertex_corners(v).len() == 2 => row.add(pv, 1.0),
        Rule::Smooth | Rule::Dart => {
            let edges = m.vertex_edges(v);
            let n = edges.len() as f64;
            let w = 1.0 / (n * (n + 5.0));
            row.add(pv, n / (n + 5.0));
            for &e in edges {
                row.add(m.point[m.other_end(e as usize, v as u32) as usize], 4.0 * w);
            }
            for &c in m.vertex_corners(v) {
                let f = m.corner_face[c as usize] as usize;
                if m.face(f).len() != 4 {
                    return Ok(None);
                }
                let opposite = m.next(m.next(c));
                row.add(m.point[m.corner_vertex[opposite as usize] as usize], w);
            }
        }
        Rule::Crease => {
            row.add(pv, 2.0 / 3.0);
            let sharp: Vec<u32> = m
                .vertex_edges(v)
                .iter()
                .copied()
                .filter(|&e| is_sharp(m.edge_sharpness[e as usize]))
                .take(2)
                .collect();
            for e in sharp {
                row.add(
                    m.point[m.other_end(e as usize, v as u32) as usize],
                    1.0 / 6.0,
                );
            }
        }
        Rule::Corner => row.add(pv, 1.0),
    }
    points
        .get_or_make(Key::Limit(pv), |made| *made = row)
        .map(Some)
}
