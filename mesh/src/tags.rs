//! Checks of subdivision tags ([`crate::SubdivTags`]) against the mesh they
//! belong to, shared by the OBJ reader ([`crate::obj`]) and the CLI's JSON
//! reader, so that both reject the same tags with the same words.
//!
//! An index is checked as written (any `i64`, so that a negative or huge
//! one is reported rather than wrapped): a crease's two vertices must exist,
//! differ and be joined by an edge of some face (OpenSubdiv's
//! `findBaseEdge` fails otherwise); a corner's vertex must exist; a hole's
//! face must exist. A sharpness must be a number ≥ 0 (OpenSubdiv's
//! regression tools clamp a negative one to 0; here it is an error).

use alloc::collections::BTreeSet;
use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;

/// The vertex and face counts and the edges of a mesh, to check tags with.
#[derive(Clone, Debug)]
pub struct TagCheck {
    vertices: usize,
    faces: usize,
    edges: BTreeSet<(u32, u32)>,
}

impl TagCheck {
    /// From the mesh's vertex count and faces (edges are read from the faces
    /// as given, either direction).
    pub fn new(vertices: usize, faces: &[Vec<u32>]) -> Self {
        let mut edges = BTreeSet::new();
        for f in faces {
            for (k, &a) in f.iter().enumerate() {
                let b = f[(k + 1) % f.len()];
                edges.insert((a.min(b), a.max(b)));
            }
        }
        TagCheck {
            vertices,
            faces: faces.len(),
            edges,
        }
    }

    /// A sharpness: not NaN, not negative (`+∞` is accepted: infinitely sharp).
    pub fn sharpness(s: f64) -> Result<f32, String> {
        if s.is_nan() {
            Err(String::from("sharpness is NaN"))
        } else if s < 0.0 {
            Err(format!("sharpness {s} is negative"))
        } else {
            Ok(s as f32)
        }
    }

    fn vertex(&self, v: i64) -> Result<u32, String> {
        if v < 0 || v as u64 >= self.vertices as u64 || v > i64::from(u32::MAX) {
            Err(format!(
                "vertex {v} out of range ({} vertices)",
                self.vertices
            ))
        } else {
            Ok(v as u32)
        }
    }

    /// A crease's edge: both vertices exist and an edge joins them.
    pub fn crease(&self, a: i64, b: i64) -> Result<[u32; 2], String> {
        let (x, y) = (self.vertex(a)?, self.vertex(b)?);
        if !self.edges.contains(&(x.min(y), x.max(y))) {
            return Err(format!("vertices {a} and {b} are not joined by an edge"));
        }
        Ok([x, y])
    }

    /// A corner's vertex exists.
    pub fn corner(&self, v: i64) -> Result<u32, String> {
        self.vertex(v)
    }

    /// A hole's face exists.
    pub fn hole(&self, f: i64) -> Result<u32, String> {
        if f < 0 || f as u64 >= self.faces as u64 || f > i64::from(u32::MAX) {
            Err(format!("face {f} out of range ({} faces)", self.faces))
        } else {
            Ok(f as u32)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

    #[test]
    fn indices_edges_and_sharpness_are_checked() {
        let c = TagCheck::new(4, &[vec![0, 1, 2, 3]]);
        assert_eq!(c.crease(0, 1), Ok([0, 1]));
        assert_eq!(c.crease(0, 3), Ok([0, 3]));
        assert_eq!(c.crease(1, 0), Ok([1, 0]));
        assert!(c.crease(0, 2).unwrap_err().contains("not joined"));
        assert!(c.crease(1, 1).unwrap_err().contains("not joined"));
        assert!(c
            .crease(0, 4)
            .unwrap_err()
            .contains("vertex 4 out of range"));
        assert!(c.crease(-1, 0).unwrap_err().contains("vertex -1"));
        assert_eq!(c.corner(3), Ok(3));
        assert!(c.corner(i64::MAX).is_err());
        assert_eq!(c.hole(0), Ok(0));
        assert!(c
            .hole(1)
            .unwrap_err()
            .contains("face 1 out of range (1 faces)"));
        assert_eq!(TagCheck::sharpness(2.5), Ok(2.5));
        assert_eq!(TagCheck::sharpness(0.0), Ok(0.0));
        assert_eq!(TagCheck::sharpness(f64::INFINITY), Ok(f32::INFINITY));
        assert!(TagCheck::sharpness(-0.5).is_err());
        assert!(TagCheck::sharpness(f64::NAN).is_err());
    }
}
