//! The whole-mesh step of a mesh with tags (docs/adaptive.md, "Whole-mesh
//! steps"): every face refined once with OpenSubdiv's `Sdc` rules — creases
//! and their decay, Chaikin, fractional sharpness, corners, holes, the
//! boundary rules, the smooth-triangle rule — by [`subdivide`], the one
//! place those rules are written; then, at each seed (a polar fan no tag
//! reaches, see [`crate::plan`]'s rule 4), the C²PS rows of the new pole,
//! link 1 and link 2 and the two triangles at each pole corner, by
//! [`crate::global_step`], as in the step of a mesh without tags. No tag
//! reaches a seed's faces or the faces around their vertices, so the rows
//! C²PS replaces are the smooth rule's there, as in that step.
//!
//! The result is numbered as [`crate::global_step`] numbers its refined
//! vertices (vertex points first, so an old vertex keeps its index) and
//! comes with the level's [`TaggedBase`]: the sharpness the refinement gave
//! each vertex and edge, the holes' children, and the faces no tag reaches,
//! for the next analysis and for the adaptive refinement of what no patch
//! or cap covers.

use crate::adaptive::base::{stepped_base, TaggedBase};
use crate::adaptive::points::Points;
use crate::adaptive::subdivide::{subdivide, Rules};
use crate::adaptive::NONE;
use crate::chart::FaceChart;
use crate::error::MeshError;
use crate::global_step::{try_step_with_rows, PolarSeed, Refined, Row, StepNumbering};
use crate::mem;
use crate::topology::Topology;
use alloc::vec::Vec;
use hashbrown::HashMap;

/// One step of `topo` (a mesh with tags, `base` its level: the same faces,
/// corners in the same order, each vertex its own point): OpenSubdiv's
/// refinement of every face, C²PS at `poles` (which no tag may reach).
/// `charts[f]` is where face `f` lies in the input. `None` when `base` is
/// not `topo`'s level (nothing is refined then).
///
/// # Panics
/// As [`crate::global_step::global_step`], if a seed does not describe its
/// faces as documented on [`PolarSeed`] (a caller's logic error).
pub fn tagged_step(
    topo: &Topology,
    base: &TaggedBase,
    charts: &[FaceChart],
    poles: &[PolarSeed],
) -> Result<Option<(Refined, TaggedBase)>, MeshError> {
    let m = &base.level;
    let nv = topo.num_vertices();
    let nf = topo.num_faces();
    let same = m.num_faces() == nf
        && m.num_vertices() == nv
        && charts.len() == nf
        && (0..nf).all(|f| m.face(f) == topo.face(f))
        && m.point.iter().enumerate().all(|(v, &p)| p as usize == v);
    if !same {
        return Ok(None);
    }
    let numbering = StepNumbering::new(topo)?;
    let faces: Vec<u32> = mem::collect(0..nf as u32)?;
    let rules = Rules {
        chaikin: base.chaikin,
        smooth_triangles: base.smooth_triangles,
    };
    let mut points = Points::new(nv as u32);
    let child = subdivide(m, &faces, rules, &mut points)?;
    let c = &child.level;
    // Per vertex of the child level: its index in the step's numbering.
    // The child of face f at its corner k is (vertex point of corner k,
    // edge point of the edge k → k+1, face point, edge point of the edge
    // k−1 → k), as the step's sub-quad there.
    let mut index = mem::filled(c.num_vertices(), NONE)?;
    for f in 0..nf {
        for k in 0..topo.face_len(f) {
            let h = topo.face_half_edge(f, k);
            let sub = c.face((child.first[f] + k as u32) as usize);
            let ids = [
                topo.origin(h),
                numbering.edge_point(h),
                numbering.face_point(f),
                numbering.edge_point(topo.prev(h)),
            ];
            for (&cv, id) in sub.iter().zip(ids) {
                index[cv as usize] = id;
            }
        }
    }
    // Rows over the old vertices: the child level's points are rows of
    // `points` over the old level's points, which are its vertices. A
    // vertex no face uses stays where it is.
    let mut rows: Vec<Row> = mem::with_capacity(numbering.len())?;
    rows.extend((0..numbering.len()).map(|i| {
        if i < nv {
            alloc::vec![(i as u32, 1.0)]
        } else {
            Row::new()
        }
    }));
    let mut vertex_sharpness = mem::filled(numbering.len(), 0.0f32)?;
    for (cv, &id) in index.iter().enumerate() {
        let made = (c.point[cv] as usize).checked_sub(nv);
        let (Some(row), Some(s), Some(p)) = (
            rows.get_mut(id as usize),
            c.vertex_sharpness.get(cv),
            made.filter(|&p| p < points.rows.len()),
        ) else {
            continue;
        };
        *row = points.rows.row(p).collect();
        vertex_sharpness[id as usize] = *s;
    }
    let mut edge_sharpness: HashMap<(u32, u32), f32> = HashMap::new();
    for (e, &[a, b]) in c.edge_vertices.iter().enumerate() {
        let s = c.edge_sharpness[e];
        let (a, b) = (index[a as usize], index[b as usize]);
        if s > 0.0 && a != NONE && b != NONE {
            mem::reserve_map(&mut edge_sharpness, 1)?;
            edge_sharpness.insert((a.min(b), a.max(b)), s);
        }
    }
    let refined = try_step_with_rows(topo, charts, poles, &numbering, rows)?;
    let level = stepped_base(
        base,
        &refined.faces,
        &refined.parent,
        vertex_sharpness,
        |a, b| edge_sharpness.get(&(a, b)).copied().unwrap_or(0.0),
    )?;
    Ok(Some((refined, level)))
}
