//! `MeshError`: every way a mesh can be unusable, one variant per cause, each
//! naming the face or vertex where it was found — 0-based indices into
//! [`crate::MeshInput`] by default, or as the file counts them through
//! [`Names`] (OBJ: 1-based, with the line, [`crate::obj::ObjLines`]).

use alloc::format;
use alloc::string::String;
use core::fmt;

/// How a message names the input's vertices and faces.
pub trait Names {
    /// Vertex `v` (0-based index into the mesh), e.g. `vertex 3`.
    fn vertex(&self, v: usize) -> String;
    /// Face `f` (0-based index into the mesh), e.g. `face 0`.
    fn face(&self, f: usize) -> String;
    /// A vertex index that is out of range, possibly negative (as the
    /// index list gives it).
    fn missing_vertex(&self, index: i64) -> String {
        match usize::try_from(index) {
            Ok(v) => self.vertex(v),
            Err(_) => format!("vertex {index}"),
        }
    }
    /// Texture coordinate `t` (0-based index into the UV pool).
    fn uv(&self, t: usize) -> String {
        format!("texture coordinate {t}")
    }
    /// A texture coordinate index that is out of range, possibly negative.
    fn missing_uv(&self, index: i64) -> String {
        match usize::try_from(index) {
            Ok(t) => self.uv(t),
            Err(_) => format!("texture coordinate {index}"),
        }
    }
}

/// 0-based indices, as in [`crate::MeshInput`] and the JSON mesh schema.
#[derive(Clone, Copy, Debug, Default)]
pub struct Indices;

impl Names for Indices {
    fn vertex(&self, v: usize) -> String {
        format!("vertex {v}")
    }
    fn face(&self, f: usize) -> String {
        format!("face {f}")
    }
}

/// Why a mesh was rejected. Display gives one line naming the face or vertex.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum MeshError {
    /// The mesh has no faces (or no vertices).
    Empty,
    /// A syntax error in the input text (OBJ), 1-based line.
    Parse {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A vertex coordinate is NaN or infinite.
    NonFinite {
        /// The vertex.
        vertex: usize,
    },
    /// A face refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The face.
        face: usize,
        /// The index as written (0-based; OBJ indices are converted first).
        index: i64,
        /// Number of vertices.
        vertices: usize,
    },
    /// A face with fewer than 3 vertices.
    FaceTooSmall {
        /// The face.
        face: usize,
        /// Its number of vertices.
        len: usize,
    },
    /// A face that lists one vertex twice ([`crate::Topology::new`] only;
    /// [`crate::SurfacePlan::for_mesh`] takes such faces, as OpenSubdiv does).
    RepeatedVertex {
        /// The face.
        face: usize,
        /// The repeated vertex.
        vertex: usize,
    },
    /// An edge shared by more than two faces.
    NonManifoldEdge {
        /// The third face found on the edge.
        face: usize,
        /// The edge's vertices.
        edge: [usize; 2],
    },
    /// Two faces run along a shared edge in the same direction.
    InconsistentOrientation {
        /// The second face found running the edge that way.
        face: usize,
        /// The edge's vertices, in that direction.
        edge: [usize; 2],
    },
    /// The faces around a vertex do not form one disk or half-disk (a bow-tie).
    NonManifoldVertex {
        /// The vertex.
        vertex: usize,
    },
    /// The mesh is larger than the indices can address (more than 2³¹ items).
    TooLarge,
    /// A tag names a vertex or face that does not exist.
    TagOutOfRange {
        /// "vertex" or "face".
        what: &'static str,
        /// The index (0-based).
        index: usize,
        /// How many there are.
        count: usize,
    },
    /// A face's list of UV indices is not as long as its list of vertices
    /// (or a face has no UV list while the mesh has UVs).
    UvCorners {
        /// The face.
        face: usize,
        /// Its number of UV indices.
        uv_corners: usize,
        /// Its number of vertices.
        vertices: usize,
    },
    /// A face refers to a UV that does not exist.
    UvOutOfRange {
        /// The face.
        face: usize,
        /// The UV index as written (0-based; OBJ indices are converted first).
        index: i64,
        /// Number of UVs.
        uvs: usize,
    },
    /// A UV used by a face is NaN or infinite.
    NonFiniteUv {
        /// The face.
        face: usize,
        /// The UV (0-based index into the pool).
        uv: usize,
    },
    /// An allocation of the analysis could not be made.
    OutOfMemory {
        /// The size asked for.
        bytes: usize,
    },
}

impl From<crate::mem::OutOfMemory> for MeshError {
    fn from(e: crate::mem::OutOfMemory) -> Self {
        MeshError::OutOfMemory { bytes: e.bytes }
    }
}

impl MeshError {
    /// The one-line message, naming vertices and faces by `names`.
    pub fn describe(&self, names: &dyn Names) -> String {
        let v = |i: usize| names.vertex(i);
        let f = |i: usize| names.face(i);
        match self {
            MeshError::Empty => String::from("the mesh has no faces"),
            MeshError::Parse { line, message } => format!("line {line}: {message}"),
            MeshError::NonFinite { vertex } => {
                format!("{} has a coordinate that is not finite", v(*vertex))
            }
            MeshError::IndexOutOfRange {
                face,
                index,
                vertices,
            } => {
                format!(
                    "{} refers to {}, the mesh has {vertices} vertices",
                    f(*face),
                    names.missing_vertex(*index)
                )
            }
            MeshError::FaceTooSmall { face, len } => {
                format!("{} has {len} vertices, at least 3 are needed", f(*face))
            }
            MeshError::RepeatedVertex { face, vertex } => {
                format!("{} lists {} more than once", f(*face), v(*vertex))
            }
            MeshError::NonManifoldEdge { face, edge } => format!(
                "{} is a third face on the edge from {} to {} (non-manifold edge)",
                f(*face),
                v(edge[0]),
                v(edge[1])
            ),
            MeshError::InconsistentOrientation { face, edge } => format!(
                "{} runs the edge from {} to {} in the same direction as another face \
                 (inconsistent orientation)",
                f(*face),
                v(edge[0]),
                v(edge[1])
            ),
            MeshError::NonManifoldVertex { vertex } => format!(
                "the faces around {} do not form one disk (non-manifold vertex)",
                v(*vertex)
            ),
            MeshError::TooLarge => {
                String::from("the mesh has more than 2^31 vertices, faces or corners")
            }
            MeshError::TagOutOfRange { what, index, count } => {
                format!("a tag names {what} {index}, but the mesh has {count} {what}s (0-based)")
            }
            MeshError::OutOfMemory { bytes } => crate::mem::OutOfMemory { bytes: *bytes }.message(),
            MeshError::UvCorners {
                face,
                uv_corners,
                vertices,
            } => format!(
                "{} has {uv_corners} texture coordinates for {vertices} vertices",
                f(*face)
            ),
            MeshError::UvOutOfRange { face, index, uvs } => format!(
                "{} refers to {}, the mesh has {uvs} texture coordinates",
                f(*face),
                names.missing_uv(*index)
            ),
            MeshError::NonFiniteUv { face, uv } => {
                format!("{} uses {}, which is not finite", f(*face), names.uv(*uv))
            }
        }
    }
}

impl fmt::Display for MeshError {
    /// [`MeshError::describe`] with 0-based [`Indices`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.describe(&Indices))
    }
}

impl core::error::Error for MeshError {}
