//! Finding the caps' configurations in a mesh: polar configurations (spec
//! docs/math/c2ps.md §1) and the c-nets of extraordinary points (docs/math/eg.md §1).

use crate::grid::{corner_grid, GridPoint};
use crate::topology::{Topology, NONE};
use alloc::vec;
use alloc::vec::Vec;

/// Why a face is left without a patch, or a vertex without a cap.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Reason {
    /// A face that is neither a quad nor part of a polar fan.
    NotQuad,
    /// A quad next to more than one irregular vertex, or an extraordinary
    /// point whose 1-ring vertices are not all regular.
    CrowdedIrregular,
    /// A fan of triangles whose links 1..3 are not rings of regular quads.
    PolarIncomplete,
    /// An irregular vertex on the boundary, or a cap reaching the boundary.
    Boundary,
    /// Two caps claim the face.
    Overlap,
    /// A crease, corner, hole or boundary rule reaches the configuration:
    /// Catmull-Clark with OpenSubdiv's rules there.
    Feature,
    /// An interior vertex of two faces: no cap scheme has valence 2, and
    /// refinement keeps it; Catmull-Clark rings with the valence-2 smooth
    /// rule converge to it.
    ValenceTwo,
}

impl Reason {
    /// Whether one refinement step (Catmull-Clark, C²PS at poles) can fix it.
    pub fn refinement_helps(self) -> bool {
        matches!(
            self,
            Reason::NotQuad | Reason::CrowdedIrregular | Reason::PolarIncomplete
        )
    }

    /// A short explanation, for summaries.
    pub fn describe(self) -> &'static str {
        match self {
            Reason::NotQuad => "not a quad and not in a polar fan",
            Reason::CrowdedIrregular => "next to more than one irregular vertex",
            Reason::PolarIncomplete => "polar fan without three rings of regular quads",
            Reason::Boundary => "irregular vertex or cap at the boundary",
            Reason::Overlap => "claimed by two caps",
            Reason::Feature => "a crease, corner, hole or boundary rule reaches it",
            Reason::ValenceTwo => "interior vertex of valence 2",
        }
    }

    /// A stable identifier (JSON).
    pub fn id(self) -> &'static str {
        match self {
            Reason::NotQuad => "not-quad",
            Reason::CrowdedIrregular => "crowded-irregular",
            Reason::PolarIncomplete => "polar-incomplete",
            Reason::Boundary => "boundary",
            Reason::Overlap => "overlap",
            Reason::Feature => "feature",
            Reason::ValenceTwo => "valence-two",
        }
    }
}

/// A polar configuration found in the mesh: pole, links 1..3 (link 3 may be
/// phantom points `2 q2 − q1` when link 2 is the boundary), the fan's
/// triangles and the quads between links 1 and 2.
#[derive(Clone, Debug, PartialEq)]
pub struct PolarConfig {
    /// The pole.
    pub pole: u32,
    /// Links 1 and 2, counter-clockwise; `links[1][j]` is across the quad
    /// `quads[j]` from `links[0][j]`.
    pub links: [Vec<u32>; 2],
    /// Link 3 as combinations (phantoms at a boundary), empty if unknown.
    pub link3: Vec<GridPoint>,
    /// `triangles[j]` = face `(pole, link1[j], link1[j+1])`.
    pub triangles: Vec<u32>,
    /// `quads[j]` = face `(link1[j+1], link1[j], link2[j], link2[j+1])`.
    pub quads: Vec<u32>,
    /// Corner of `quads[j]` at which `links[0][j]` sits.
    pub quad_corner: Vec<u8>,
}

/// A vertex whose faces are all triangles (interior, at least 3): the
/// candidate poles.
pub fn is_fan(t: &Topology, v: usize) -> bool {
    t.vertex_first(v) != NONE
        && !t.is_boundary(v)
        && t.vertex_face_count(v) >= 3
        && t.outgoing(v)
            .all(|h| t.face_len(t.face_of(h) as usize) == 3)
}

/// The polar configuration around `v` (a fan, [`is_fan`]), starting its
/// columns at outgoing half-edge `start` (or the vertex's first).
/// `need_link3`: also require link 3 (a cap needs it; the refinement step
/// needs links 1 and 2 only).
pub fn polar_config(
    t: &Topology,
    v: usize,
    start: Option<u32>,
    need_link3: bool,
) -> Result<PolarConfig, Reason> {
    if !is_fan(t, v) {
        return Err(Reason::PolarIncomplete);
    }
    let first = start.unwrap_or(t.vertex_first(v));
    let spokes: Vec<u32> = {
        let mut s = vec![first];
        let mut h = t.rotate_ccw(first);
        while h != first && h != NONE {
            s.push(h);
            h = t.rotate_ccw(h);
        }
        s
    };
    let n = spokes.len();
    let link1: Vec<u32> = spokes.iter().map(|&h| t.dest(h)).collect();
    let triangles: Vec<u32> = spokes.iter().map(|&h| t.face_of(h)).collect();
    // Link-1 vertices: interior, 2 triangles + 2 quads.
    for &q in &link1 {
        let q = q as usize;
        if t.is_boundary(q) {
            return Err(Reason::Boundary);
        }
        if t.vertex_face_count(q) != 4 {
            return Err(Reason::PolarIncomplete);
        }
    }
    // Ring walk: e[j] runs link_i[j] → link_i[j+1] with the inner face on its left.
    let mut edges: Vec<u32> = spokes.iter().map(|&h| t.next(h)).collect();
    let mut rings: Vec<Vec<u32>> = Vec::new();
    let mut quads = Vec::with_capacity(n);
    let mut quad_corner = Vec::with_capacity(n);
    let mut boundary_at = None;
    for ring in 0..2 {
        if ring == 1 && !need_link3 {
            break;
        }
        let mut next_ring = vec![0u32; n];
        let mut next_edges = vec![0u32; n];
        for j in 0..n {
            let tw = t.twin(edges[j]);
            if tw == NONE {
                if ring == 0 {
                    return Err(Reason::Boundary);
                }
                boundary_at = Some(ring);
                break;
            }
            let f = t.face_of(tw) as usize;
            if t.face_len(f) != 4 {
                return Err(Reason::PolarIncomplete);
            }
            let a = t.next(tw);
            let b = t.next(a);
            next_ring[j] = t.dest(a);
            next_edges[j] = b;
            if ring == 0 {
                quads.push(f as u32);
                quad_corner.push(t.corner_of(a) as u8);
            }
        }
        if boundary_at.is_some() {
            break;
        }
        // Consistency: the quad j's far edge ends where quad j+1's starts.
        for j in 0..n {
            if t.dest(next_edges[j]) != next_ring[(j + 1) % n] {
                return Err(Reason::PolarIncomplete);
            }
        }
        rings.push(next_ring);
        edges = next_edges;
    }
    let link2 = rings.first().cloned().ok_or(Reason::PolarIncomplete)?;
    // Link-2 vertices: 4 quads (interior) or, when link 2 is the boundary,
    // 2 quads (the phantom link 3 completes the configuration).
    for &q in &link2 {
        let q = q as usize;
        let ok = if boundary_at.is_some() {
            t.is_boundary(q) && t.vertex_face_count(q) == 2
        } else {
            !t.is_boundary(q) && t.vertex_face_count(q) == 4
        };
        if !ok {
            return Err(if t.is_boundary(q) {
                Reason::Boundary
            } else {
                Reason::PolarIncomplete
            });
        }
    }
    let link3: Vec<GridPoint> = if !need_link3 {
        Vec::new()
    } else if boundary_at.is_some() {
        (0..n)
            .filter_map(|j| GridPoint::from_terms(&[(link2[j], 2.0), (link1[j], -1.0)]))
            .collect()
    } else {
        rings[1].iter().map(|&q| GridPoint::vertex(q)).collect()
    };
    // All vertices distinct (a configuration must not wrap onto itself).
    let mut all: Vec<u32> = link1.iter().chain(&link2).copied().collect();
    all.push(v as u32);
    if rings.len() > 1 {
        all.extend_from_slice(&rings[1]);
    }
    all.sort_unstable();
    if all.windows(2).any(|w| w[0] == w[1]) {
        return Err(Reason::PolarIncomplete);
    }
    Ok(PolarConfig {
        pole: v as u32,
        links: [link1, link2],
        link3,
        triangles,
        quads,
        quad_corner,
    })
}

/// The c-net of an extraordinary point (docs/math/eg.md §1) found in the mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct ExtraordinaryConfig {
    /// The center `e`.
    pub center: u32,
    /// `6n` nodes, sector by sector in the §1 order (1,0) (2,0) (1,1) (2,1) (1,2) (2,2).
    pub nodes: Vec<u32>,
    /// Per sector: the face `[0,1]²` of the sector and the corner of that
    /// face at which `e` sits.
    pub sectors: Vec<(u32, u8)>,
}

/// The c-net around `v`: an interior vertex of valence `n ≠ 4` (n ≥ 3) whose
/// faces are quads and whose 1-ring vertices are all regular (4 quads).
pub fn extraordinary_config(t: &Topology, v: usize) -> Result<ExtraordinaryConfig, Reason> {
    if t.vertex_first(v) == NONE {
        return Err(Reason::NotQuad);
    }
    if t.is_boundary(v) {
        return Err(Reason::Boundary);
    }
    let n = t.vertex_face_count(v);
    let mut nodes = Vec::with_capacity(6 * n);
    let mut sectors = Vec::with_capacity(n);
    for h in t.outgoing(v) {
        let f = t.face_of(h);
        if t.face_len(f as usize) != 4 {
            return Err(Reason::NotQuad);
        }
        let spoke = t.next(h); // starts at (1,0)
        let diag = t.next(spoke); // starts at (1,1)
        for e in [spoke, diag] {
            let q = t.origin(e) as usize;
            if t.is_boundary(q) {
                return Err(Reason::Boundary);
            }
        }
        corner_grid(t, spoke).ok_or(Reason::CrowdedIrregular)?;
        // Around (1,1): local +x toward (0,1), +y toward (1,0); sector
        // coordinates (x, y) = (1 − a, 1 − b).
        let g = corner_grid(t, diag).ok_or(Reason::CrowdedIrregular)?;
        let at = |x: i32, y: i32| g[(2 - x) as usize][(2 - y) as usize];
        if at(0, 0) != Some(v as u32) {
            return Err(Reason::CrowdedIrregular);
        }
        for (x, y) in [(1, 0), (2, 0), (1, 1), (2, 1), (1, 2), (2, 2)] {
            nodes.push(at(x, y).ok_or(Reason::Boundary)?);
        }
        sectors.push((f, t.corner_of(h) as u8));
    }
    Ok(ExtraordinaryConfig {
        center: v as u32,
        nodes,
        sectors,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::MeshInput;

    /// A flat open disk: pole at the origin, `rings` rings of `n` points.
    fn pole_disk(n: usize, rings: usize) -> MeshInput {
        let mut v = vec![[0.0, 0.0, 0.0]];
        for r in 1..=rings {
            for j in 0..n {
                let a = core::f64::consts::TAU * j as f64 / n as f64;
                v.push([r as f64 * libm::cos(a), r as f64 * libm::sin(a), 0.0]);
            }
        }
        let id = |r: usize, j: usize| (1 + (r - 1) * n + j % n) as u32;
        let mut f = Vec::new();
        for j in 0..n {
            f.push(vec![0, id(1, j), id(1, j + 1)]);
        }
        for r in 1..rings {
            for j in 0..n {
                f.push(vec![id(r, j + 1), id(r, j), id(r + 1, j), id(r + 1, j + 1)]);
            }
        }
        MeshInput::new(v, f)
    }

    #[test]
    fn pole_disk_gives_links_in_order() {
        for n in [3, 5, 8] {
            let m = pole_disk(n, 4);
            let t = Topology::new(&m).unwrap();
            let c = polar_config(&t, 0, None, true).unwrap();
            // Link i, column j is a point at radius i; consecutive columns ccw.
            for (i, l) in c.links.iter().enumerate() {
                for j in 0..n {
                    let p = m.vertices[l[j] as usize];
                    let q = m.vertices[l[(j + 1) % n] as usize];
                    assert!((libm::hypot(p[0], p[1]) - (i + 1) as f64).abs() < 1e-12);
                    assert!(p[0] * q[1] - p[1] * q[0] > 0.0, "ccw");
                }
            }
            for j in 0..n {
                let p = m.vertices[c.link3[j].terms()[0].0 as usize];
                assert!((libm::hypot(p[0], p[1]) - 3.0).abs() < 1e-12);
                // Link 2 column j lies on the ray of link 1 column j.
                let a = m.vertices[c.links[0][j] as usize];
                let b = m.vertices[c.links[1][j] as usize];
                assert!((a[0] * b[1] - a[1] * b[0]).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn pole_with_link2_on_the_boundary_gets_phantom_link3() {
        let m = pole_disk(6, 2);
        let t = Topology::new(&m).unwrap();
        let c = polar_config(&t, 0, None, true).unwrap();
        assert_eq!(
            c.link3[0].terms(),
            &[(c.links[1][0], 2.0), (c.links[0][0], -1.0)]
        );
        // Links 1 only: no configuration.
        let m = pole_disk(6, 1);
        let t = Topology::new(&m).unwrap();
        assert_eq!(polar_config(&t, 0, None, true), Err(Reason::Boundary));
    }
}
