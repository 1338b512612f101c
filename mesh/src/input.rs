//! `MeshInput`: a polygon mesh as the user gives it — vertex positions, faces
//! as lists of 0-based vertex indices (counter-clockwise about the outward
//! normal), OpenSubdiv's subdivision tags ([`SubdivTags`]) and, optionally,
//! face-varying texture coordinates (UVs: a pool of `(u, v)` pairs and, per
//! face corner, an index into it, as OBJ's `vt` lines and `f v/vt` corners
//! give them; interpolated by [`crate::facevarying`]).

use crate::error::MeshError;
use alloc::string::String;
use alloc::vec;
use alloc::vec::Vec;

/// A polygon mesh: positions, faces (0-based indices, any polygon size),
/// tags and optional face-varying UVs. Nothing is checked here; the analysis
/// validates ([`MeshInput::check_uvs`] for the UVs).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshInput {
    /// Vertex positions.
    pub vertices: Vec<[f64; 3]>,
    /// Faces, each a list of vertex indices, counter-clockwise.
    pub faces: Vec<Vec<u32>>,
    /// Creases, corners, holes and the boundary rule (none by default).
    pub tags: SubdivTags,
    /// Texture coordinates `(u, v)`, indexed by [`MeshInput::uv_faces`].
    pub uvs: Vec<[f64; 2]>,
    /// Per face, per corner (in the order of [`MeshInput::faces`]): an index
    /// into [`MeshInput::uvs`]. Empty: the mesh has no UVs. Two faces meeting
    /// at a vertex may give it different UVs (a seam).
    pub uv_faces: Vec<Vec<u32>>,
}

impl MeshInput {
    /// A mesh from its parts, without tags.
    pub fn new(vertices: Vec<[f64; 3]>, faces: Vec<Vec<u32>>) -> Self {
        MeshInput {
            vertices,
            faces,
            tags: SubdivTags::default(),
            uvs: Vec::new(),
            uv_faces: Vec::new(),
        }
    }

    /// The open disk a polar configuration spans (pole `q00` and links
    /// `1, 2, …`, each a closed ring of `n` points): vertex 0 the pole, point
    /// `j` of link `i` (0-based) vertex `1 + i·n + j`; faces the fan
    /// `(pole, l1[j], l1[j+1])` (faces `0..n`), then per pair of links
    /// `i, i+1` the quads `(li[j], li+1[j], li+1[j+1], li[j+1])` (faces
    /// `n·(i+1) .. n·(i+2)`), counter-clockwise as the links turn. `n` is the
    /// first link's length; the faces index the points as if every link had
    /// `n` (check the lengths first).
    pub fn polar_disk(pole: [f64; 3], links: &[Vec<[f64; 3]>]) -> Self {
        let n = links.first().map_or(0, Vec::len);
        let mut vertices = vec![pole];
        for l in links {
            vertices.extend_from_slice(l);
        }
        let at = |i: usize, j: usize| (1 + i * n + j % n) as u32;
        let mut faces: Vec<Vec<u32>> = (0..n).map(|j| vec![0, at(0, j), at(0, j + 1)]).collect();
        for i in 0..links.len().saturating_sub(1) {
            for j in 0..n {
                faces.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        MeshInput::new(vertices, faces)
    }

    /// The mesh with face-varying UVs: the pool `uvs` and, per face corner,
    /// an index into it (`uv_faces[f][k]` for corner `k` of face `f`).
    pub fn with_uvs(mut self, uvs: Vec<[f64; 2]>, uv_faces: Vec<Vec<u32>>) -> Self {
        self.uvs = uvs;
        self.uv_faces = uv_faces;
        self
    }

    /// Whether the mesh carries UVs ([`MeshInput::uv_faces`] is not empty).
    pub fn has_uvs(&self) -> bool {
        !self.uv_faces.is_empty()
    }

    /// Checks the UVs, if any: one list of UV indices per face, as long as
    /// the face ([`MeshError::UvCorners`]), every index in the pool
    /// ([`MeshError::UvOutOfRange`]), every used UV finite
    /// ([`MeshError::NonFiniteUv`]). The first offending face is named.
    pub fn check_uvs(&self) -> Result<(), MeshError> {
        if !self.has_uvs() {
            return Ok(());
        }
        for (face, f) in self.faces.iter().enumerate() {
            let corners = self.uv_faces.get(face).map_or(0, Vec::len);
            if corners != f.len() {
                return Err(MeshError::UvCorners {
                    face,
                    uv_corners: corners,
                    vertices: f.len(),
                });
            }
        }
        if self.uv_faces.len() > self.faces.len() {
            let face = self.faces.len();
            return Err(MeshError::UvCorners {
                face,
                uv_corners: self.uv_faces[face].len(),
                vertices: 0,
            });
        }
        for (face, f) in self.uv_faces.iter().enumerate() {
            for &index in f {
                match self.uvs.get(index as usize) {
                    None => {
                        return Err(MeshError::UvOutOfRange {
                            face,
                            index: i64::from(index),
                            uvs: self.uvs.len(),
                        })
                    }
                    Some(uv) if !uv.iter().all(|c| c.is_finite()) => {
                        return Err(MeshError::NonFiniteUv {
                            face,
                            uv: index as usize,
                        })
                    }
                    Some(_) => {}
                }
            }
        }
        Ok(())
    }
}

/// OpenSubdiv's boundary interpolation (`Sdc::Options::VtxBoundaryInterpolation`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum BoundaryInterpolation {
    /// `VTX_BOUNDARY_NONE`: faces with a boundary vertex are holes.
    None,
    /// `VTX_BOUNDARY_EDGE_ONLY`: boundary edges are infinitely sharp.
    EdgeOnly,
    /// `VTX_BOUNDARY_EDGE_AND_CORNER`: boundary edges infinitely sharp, and a
    /// vertex with one face an infinitely sharp corner (the default).
    #[default]
    EdgeAndCorner,
}

impl BoundaryInterpolation {
    /// The name used on the command line and in JSON.
    pub fn id(self) -> &'static str {
        match self {
            BoundaryInterpolation::None => "none",
            BoundaryInterpolation::EdgeOnly => "edge-only",
            BoundaryInterpolation::EdgeAndCorner => "edge-and-corner",
        }
    }

    /// Inverse of [`Self::id`].
    pub fn from_id(s: &str) -> Option<Self> {
        match s {
            "none" => Some(BoundaryInterpolation::None),
            "edge-only" => Some(BoundaryInterpolation::EdgeOnly),
            "edge-and-corner" => Some(BoundaryInterpolation::EdgeAndCorner),
            _ => None,
        }
    }
}

/// OpenSubdiv's creasing method (`Sdc::Options::CreasingMethod`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CreaseMethod {
    /// `CREASE_UNIFORM` ("normal" in shape files): sharpness − 1 per level.
    #[default]
    Uniform,
    /// `CREASE_CHAIKIN`: a child edge's sharpness blends in the mean of the
    /// other semi-sharp edges at its end vertex.
    Chaikin,
}

impl CreaseMethod {
    /// The name used on the command line, in JSON and in shape files.
    pub fn id(self) -> &'static str {
        match self {
            CreaseMethod::Uniform => "normal",
            CreaseMethod::Chaikin => "chaikin",
        }
    }
}

/// OpenSubdiv's rule for the edges of triangles
/// (`Sdc::Options::TriangleSubdivision`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TriangleSubdivision {
    /// `TRI_SUB_CATMARK`: Catmull-Clark's edge rule for every face.
    #[default]
    Catmark,
    /// `TRI_SUB_SMOOTH`: an edge of one or two triangles between two faces
    /// weighs each triangle's centroid 0.47 instead of 0.25
    /// (`Sdc::Scheme<SCHEME_CATMARK>::assignSmoothMaskForEdge`), which brings
    /// the surface over triangles closer to Loop's.
    Smooth,
}

impl TriangleSubdivision {
    /// The name used on the command line, in JSON and in shape files.
    pub fn id(self) -> &'static str {
        match self {
            TriangleSubdivision::Catmark => "catmark",
            TriangleSubdivision::Smooth => "smooth",
        }
    }

    /// The rule named `s` (see [`TriangleSubdivision::id`]).
    pub fn from_id(s: &str) -> Option<Self> {
        match s {
            "catmark" => Some(TriangleSubdivision::Catmark),
            "smooth" => Some(TriangleSubdivision::Smooth),
            _ => None,
        }
    }
}

/// An edge sharpness: the edge between two vertices (either order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeCrease {
    /// The edge's vertices (0-based).
    pub vertices: [u32; 2],
    /// Sharpness (OpenSubdiv reads it as `f32`; ≥ 10 is infinitely sharp).
    pub sharpness: f32,
}

/// A vertex sharpness (a corner).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexCorner {
    /// The vertex (0-based).
    pub vertex: u32,
    /// Sharpness (`f32`; ≥ 10 is infinitely sharp).
    pub sharpness: f32,
}

/// OpenSubdiv's subdivision tags: what its shape files give as `t` lines and
/// `Far::TopologyDescriptor` as creases, corners and holes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SubdivTags {
    /// Edge sharpness. A later entry for the same edge replaces an earlier one.
    pub creases: Vec<EdgeCrease>,
    /// Vertex sharpness. A later entry for the same vertex replaces an earlier one.
    pub corners: Vec<VertexCorner>,
    /// Faces that are holes (0-based): no surface over them; their
    /// neighbours' surface is unchanged.
    pub holes: Vec<u32>,
    /// The boundary rule.
    pub boundary: BoundaryInterpolation,
    /// The creasing method.
    pub crease_method: CreaseMethod,
    /// The edge rule next to triangles.
    pub triangles: TriangleSubdivision,
    /// Tags read but not applied (name and 1-based line), for the summary.
    pub ignored: Vec<(String, usize)>,
}

impl SubdivTags {
    /// No crease, corner or hole and the default boundary and triangle
    /// rules: the mesh is a plain
    /// Catmull-Clark control mesh.
    pub fn is_plain(&self) -> bool {
        self.creases
            .iter()
            .all(|c| c.sharpness.is_nan() || c.sharpness <= 0.0)
            && self
                .corners
                .iter()
                .all(|c| c.sharpness.is_nan() || c.sharpness <= 0.0)
            && self.holes.is_empty()
            && self.boundary == BoundaryInterpolation::EdgeAndCorner
            && self.triangles == TriangleSubdivision::Catmark
    }
}
