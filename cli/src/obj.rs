//! Wavefront OBJ output of a [`Mesh`]: `v` (position) and `vn` (unit normal)
//! lines, one pair per vertex, and `f a//a b//b c//c d//d` quads ordered
//! counter-clockwise about the normals. Numbers as
//! [`capdiv_mesh::tessellate::write_number`]: exact, in a compact form.
//!
//! Vertices on shared patch edges are duplicated (see [`crate::mesh`]): the
//! mesh looks closed, but a tool that needs a welded mesh must merge by
//! position.

use crate::mesh::Mesh;
use crate::Scalar;
use capdiv_mesh::tessellate::write_point;
use std::fmt::Write;

/// OBJ text of a mesh, with `header` lines as `#` comments first.
pub fn to_obj<R: Scalar>(mesh: &Mesh<R>, header: &[String]) -> String {
    let mut text = String::with_capacity(mesh.positions.len() * 96);
    for line in header {
        let _ = writeln!(text, "# {line}");
    }
    for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
        write_point(&mut text, "v", p.0);
        write_point(&mut text, "vn", n.0);
    }
    for q in &mesh.quads {
        // OBJ indices are 1-based.
        let [a, b, c, d] = q.map(|i| i + 1);
        let _ = writeln!(text, "f {a}//{a} {b}//{b} {c}//{c} {d}//{d}");
    }
    text
}
