//! `MeshError`: every way a mesh can be unusable, one variant per cause, each
//! naming the face or vertex (0-based, as in the input) where it was found.

use alloc::string::String;
use core::fmt;

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
    /// A face that lists one vertex twice.
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
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshError::Empty => write!(f, "the mesh has no faces"),
            MeshError::Parse { line, message } => write!(f, "line {line}: {message}"),
            MeshError::NonFinite { vertex } => {
                write!(f, "vertex {vertex} has a coordinate that is not finite")
            }
            MeshError::IndexOutOfRange {
                face,
                index,
                vertices,
            } => write!(
                f,
                "face {face} refers to vertex {index}, the mesh has {vertices} vertices"
            ),
            MeshError::FaceTooSmall { face, len } => {
                write!(f, "face {face} has {len} vertices, at least 3 are needed")
            }
            MeshError::RepeatedVertex { face, vertex } => {
                write!(f, "face {face} lists vertex {vertex} more than once")
            }
            MeshError::NonManifoldEdge { face, edge } => write!(
                f,
                "face {face} is a third face on edge {}-{} (non-manifold edge)",
                edge[0], edge[1]
            ),
            MeshError::InconsistentOrientation { face, edge } => write!(
                f,
                "face {face} runs edge {}-{} in the same direction as another face (inconsistent orientation)",
                edge[0], edge[1]
            ),
            MeshError::NonManifoldVertex { vertex } => write!(
                f,
                "the faces around vertex {vertex} do not form one disk (non-manifold vertex)"
            ),
            MeshError::TooLarge => write!(f, "the mesh has more than 2^31 vertices, faces or corners"),
            MeshError::TagOutOfRange { what, index, count } => write!(
                f,
                "a tag names {what} {index}, but the mesh has {count} {what}s (0-based)"
            ),
        }
    }
}

impl core::error::Error for MeshError {}
