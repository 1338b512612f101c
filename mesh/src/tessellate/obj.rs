//! Wavefront OBJ text of a [`Tessellation`].

use super::Tessellation;
use alloc::string::String;
use capdiv::Real;
use core::fmt::{Display, Write};

/// OBJ text: `header` lines as `#` comments, then one `v x y z` and one
/// `vn x y z` line per vertex, then one `f a//a b//b c//c[ d//d]` line per
/// face (1-based, counter-clockwise about the normals, tags not written).
pub fn write_obj<R: Real + Display>(t: &Tessellation<R>, header: &[String]) -> String {
    let mut text = String::with_capacity(t.positions.len() * 96 + t.faces.len() * 40);
    for line in header {
        let _ = writeln!(text, "# {line}");
    }
    for (p, n) in t.positions.iter().zip(&t.normals) {
        let [x, y, z] = p.0;
        let [a, b, c] = n.0;
        let _ = writeln!(text, "v {x} {y} {z}");
        let _ = writeln!(text, "vn {a} {b} {c}");
    }
    for f in &t.faces {
        text.push('f');
        for &i in f.corners() {
            let i = i as u64 + 1;
            let _ = write!(text, " {i}//{i}");
        }
        text.push('\n');
    }
    text
}
