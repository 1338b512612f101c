//! `MeshInput`: a polygon mesh as the user gives it — vertex positions and
//! faces as lists of 0-based vertex indices, counter-clockwise about the
//! outward normal.

use alloc::vec::Vec;

/// A polygon mesh: positions and faces (0-based indices, any polygon size).
/// Nothing is checked here; [`crate::Topology::new`] validates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshInput {
    /// Vertex positions.
    pub vertices: Vec<[f64; 3]>,
    /// Faces, each a list of vertex indices, counter-clockwise.
    pub faces: Vec<Vec<u32>>,
}

impl MeshInput {
    /// A mesh from its parts.
    pub fn new(vertices: Vec<[f64; 3]>, faces: Vec<Vec<u32>>) -> Self {
        MeshInput { vertices, faces }
    }
}
