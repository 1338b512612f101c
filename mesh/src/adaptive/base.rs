//! The base level of a mesh with its tags, as OpenSubdiv's
//! `TopologyRefinerFactory` prepares it: user sharpness (read as `f32`,
//! later entries replacing earlier ones, creases on vertex pairs that are no
//! edge ignored as OpenSubdiv ignores them), holes, boundary faces made
//! holes under `VTX_BOUNDARY_NONE`, then [`Level::sharpen_base`].

use super::crease::is_infinite;
use super::level::Level;
use crate::input::{BoundaryInterpolation, CreaseMethod, MeshInput, TriangleSubdivision};
use crate::mem::{self, OutOfMemory};
use crate::topology::Topology;
use alloc::vec::Vec;

/// A base level and what the analysis needs to know of it.
#[derive(Clone, Debug)]
pub struct TaggedBase {
    /// The level, tags applied.
    pub level: Level,
    /// Per face: not a hole, and no tag or boundary rule other than
    /// OpenSubdiv's default reaches its corners (a face the fast path's
    /// regular patches and caps may take).
    pub clean: Vec<bool>,
    /// Chaikin's creasing method.
    pub chaikin: bool,
    /// The smooth-triangle edge rule.
    pub smooth_triangles: bool,
    /// Crease tags whose two vertices share no edge (ignored).
    pub creases_not_edges: usize,
    /// The boundary rule (what [`Self::clean`] allows at one-face corners).
    pub boundary: BoundaryInterpolation,
}

impl TaggedBase {
    /// Faces of the edge between `x` and `y` (none if there is no such edge).
    pub fn edge_faces(&self, x: u32, y: u32) -> impl Iterator<Item = usize> + '_ {
        let l = &self.level;
        let e = l
            .vertex_edges(x as usize)
            .iter()
            .copied()
            .find(|&e| l.other_end(e as usize, x) == y);
        e.into_iter().flat_map(move |e| {
            l.edge_corners(e as usize)
                .iter()
                .map(move |&c| l.corner_face[c as usize] as usize)
        })
    }
}

/// The base level of `mesh` with its tags (indices already validated),
/// every buffer reserved fallibly.
pub fn tagged_base(mesh: &MeshInput) -> Result<TaggedBase, OutOfMemory> {
    let tags = &mesh.tags;
    let nv = mesh.vertices.len();
    let faces: Vec<&[u32]> = mem::collect(mesh.faces.iter().map(|f| &f[..]))?;
    // Crease sharpness by vertex pair (smaller first), the last tag of a
    // pair winning: latest first, sorted by pair stably, the first of each
    // pair kept.
    let mut sharp: Vec<((u32, u32), f32)> = mem::collect(tags.creases.iter().rev().map(|c| {
        let [a, b] = c.vertices;
        ((a.min(b), a.max(b)), sanitize(c.sharpness))
    }))?;
    sharp.sort_by_key(|&(pair, _)| pair);
    sharp.dedup_by_key(|&mut (pair, _)| pair);
    let sharpness_of = |a: u32, b: u32| match sharp.binary_search_by_key(&(a, b), |&(p, _)| p) {
        Ok(i) => sharp[i].1,
        Err(_) => 0.0,
    };
    let mut vsharp = mem::filled(nv, 0.0f32)?;
    for c in &tags.corners {
        if let Some(s) = vsharp.get_mut(c.vertex as usize) {
            *s = sanitize(c.sharpness);
        }
    }
    let mut hole = mem::filled(faces.len(), false)?;
    for &f in &tags.holes {
        if let Some(h) = hole.get_mut(f as usize) {
            *h = true;
        }
    }
    let point = mem::collect(0..nv as u32)?;
    let mut level = Level::new(&faces, point, vsharp, hole, sharpness_of)?;
    let edges_found = sharp
        .iter()
        .filter(|&&((a, b), _)| {
            level
                .vertex_edges(a as usize)
                .iter()
                .any(|&e| level.other_end(e as usize, a) == b)
        })
        .count();
    if tags.boundary == BoundaryInterpolation::None {
        boundary_faces_to_holes(&mut level);
    }
    level.sharpen_base(tags.boundary == BoundaryInterpolation::EdgeAndCorner)?;
    let smooth_triangles = tags.triangles == TriangleSubdivision::Smooth;
    let clean = clean_faces(&level, tags.boundary, smooth_triangles)?;
    Ok(TaggedBase {
        level,
        clean,
        chaikin: tags.crease_method == CreaseMethod::Chaikin,
        smooth_triangles,
        creases_not_edges: sharp.len() - edges_found,
        boundary: tags.boundary,
    })
}

/// The base level of a mesh without tags.
pub fn plain_base(t: &Topology) -> Result<TaggedBase, OutOfMemory> {
    let faces: Vec<&[u32]> = mem::collect((0..t.num_faces()).map(|f| t.face(f)))?;
    let point = mem::collect(0..t.num_vertices() as u32)?;
    let mut level = Level::new(
        &faces,
        point,
        mem::filled(t.num_vertices(), 0.0)?,
        mem::filled(faces.len(), false)?,
        |_, _| 0.0,
    )?;
    level.sharpen_base(true)?;
    let clean = mem::filled(faces.len(), true)?;
    Ok(TaggedBase {
        level,
        clean,
        chaikin: false,
        smooth_triangles: false,
        creases_not_edges: 0,
        boundary: BoundaryInterpolation::EdgeAndCorner,
    })
}

/// The level a whole-mesh step makes of `parent`'s level
/// ([`crate::tagged_step`]): `faces` over `vertex_sharpness.len()`
/// vertices, each vertex its own point, `face_parent[f]` the face of
/// `parent` that face `f` lies in (a hole's children are holes), the
/// sharpness its refinement gave each vertex and edge (`sharp(a, b)` with
/// `a ≤ b`, 0 for an edge it did not make). Boundary and non-manifold
/// sharpness came down from `parent` with the rest (infinite stays
/// infinite), so nothing is sharpened again; the options and
/// [`TaggedBase::clean`]'s rule are `parent`'s.
pub fn stepped_base(
    parent: &TaggedBase,
    faces: &[Vec<u32>],
    face_parent: &[u32],
    vertex_sharpness: Vec<f32>,
    sharp: impl FnMut(u32, u32) -> f32,
) -> Result<TaggedBase, OutOfMemory> {
    let faces: Vec<&[u32]> = mem::collect(faces.iter().map(|f| &f[..]))?;
    let point = mem::collect(0..vertex_sharpness.len() as u32)?;
    let hole = mem::collect(
        face_parent
            .iter()
            .map(|&f| parent.level.hole.get(f as usize).copied().unwrap_or(false)),
    )?;
    let level = Level::new(&faces, point, vertex_sharpness, hole, sharp)?;
    let clean = clean_faces(&level, parent.boundary, parent.smooth_triangles)?;
    Ok(TaggedBase {
        level,
        clean,
        chaikin: parent.chaikin,
        smooth_triangles: parent.smooth_triangles,
        creases_not_edges: parent.creases_not_edges,
        boundary: parent.boundary,
    })
}

/// Negative and NaN sharpness are smooth.
fn sanitize(s: f32) -> f32 {
    if s > 0.0 {
        s
    } else {
        0.0
    }
}

/// `VTX_BOUNDARY_NONE`: every face at a vertex that has a boundary edge not
/// made infinitely sharp by a tag is a hole.
fn boundary_faces_to_holes(level: &mut Level) {
    for v in 0..level.num_vertices() {
        let open = level.vertex_edges(v).iter().any(|&e| {
            level.edge_corners(e as usize).len() == 1
                && !is_infinite(level.edge_sharpness[e as usize])
        });
        if open {
            // (Whether a vertex is open does not depend on holes.)
            for k in 0..level.vertex_corners(v).len() {
                let f = level.corner_face[level.vertex_corners(v)[k] as usize];
                level.hole[f as usize] = true;
            }
        }
    }
}

/// Faces whose corners see only OpenSubdiv's defaults: no sharp edge but
/// boundary edges, no sharp vertex but corners of one face sharpened by the
/// edge-and-corner rule, no hole, and (under the smooth-triangle rule) no
/// triangle.
fn clean_faces(
    level: &Level,
    boundary: BoundaryInterpolation,
    smooth_triangles: bool,
) -> Result<Vec<bool>, OutOfMemory> {
    let vertex_clean: Vec<bool> = mem::collect((0..level.num_vertices()).map(|v| {
        let edges = level.vertex_edges(v);
        let corner = level.vertex_corners(v).len() == 1 && edges.len() == 2;
        let vs = level.vertex_sharpness[v];
        let vertex_ok = if corner {
            boundary == BoundaryInterpolation::EdgeAndCorner
        } else {
            vs == 0.0
        };
        let triangle_free = !smooth_triangles
            || level
                .vertex_corners(v)
                .iter()
                .all(|&c| level.face(level.corner_face[c as usize] as usize).len() != 3);
        vertex_ok
            && triangle_free
            && edges.iter().all(|&e| {
                let e = e as usize;
                level.edge_sharpness[e] == 0.0
                    || (level.edge_corners(e).len() == 1 && is_infinite(level.edge_sharpness[e]))
            })
    }))?;
    mem::collect(
        (0..level.num_faces())
            .map(|f| !level.hole[f] && level.face(f).iter().all(|&v| vertex_clean[v as usize])),
    )
}

#[cfg(test)]
mod tests {
    use super::tagged_base;
    use crate::input::EdgeCrease;
    use crate::samples;
    use alloc::vec;

    /// A vertex pair tagged more than once takes its last tag's sharpness,
    /// whichever way round the pair is written, as OpenSubdiv's factory
    /// takes it; other pairs keep their own.
    #[test]
    fn the_last_crease_tag_of_a_pair_wins() {
        let mut mesh = samples::grid(3, 3);
        let f = mesh.faces[4].clone();
        let crease = |a: u32, b: u32, sharpness: f32| EdgeCrease {
            vertices: [a, b],
            sharpness,
        };
        mesh.tags.creases = vec![
            crease(f[0], f[1], 1.0),
            crease(f[1], f[2], 2.0),
            crease(f[1], f[0], 3.0),
            crease(f[0], f[1], 4.0),
            crease(f[2], f[1], 5.0),
        ];
        let level = tagged_base(&mesh).unwrap().level;
        let sharpness = |a: u32, b: u32| {
            let mut edges = level.vertex_edges(a as usize).iter().copied();
            let e = edges.find(|&e| level.other_end(e as usize, a) == b);
            level.edge_sharpness[e.expect("an edge") as usize]
        };
        assert_eq!(sharpness(f[0], f[1]), 4.0);
        assert_eq!(sharpness(f[1], f[2]), 5.0);
        assert_eq!(sharpness(f[2], f[3]), 0.0);
    }
}
