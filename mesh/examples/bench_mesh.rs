//! Writes a benchmark mesh as Wavefront OBJ to stdout, for
//! `scripts/surface-scaling.sh`:
//!
//! - `mixed FACES`: the parts of [`samples::feature_mix`] (a mushroom with
//!   two valence-12 poles, a rounded cube with eight valence-3 points, a
//!   valence-7 disk; 1,077 faces a copy of the three) copied until there
//!   are at least `FACES` faces, on a cubic lattice 10 units apart (a row,
//!   as `feature_mix` lays them, makes the bounding box and with it the
//!   CLI's weld tolerance, 1e-9 of its size, grow with the count: at 10⁶
//!   faces it exceeds the sample spacing around a depth-6 pole);
//! - `triangles FACES`: a torus of about `FACES` triangles (a `k × k` quad
//!   torus with every quad split along a diagonal: every vertex of
//!   valence 6, so every vertex and every face centre is a cap);
//! - `icosphere LEVELS`: the icosahedron split `LEVELS` times into four on
//!   the unit sphere (`20·4^LEVELS` triangles);
//! - `features FACES`: [`samples::feature_torus`] with `16·base²` quads,
//!   `base` the nearest to `√(FACES/16)`: isolated valence-3 and -5
//!   points, creases of sharpness 2.5 and 10, eight corners and holes,
//!   written as OpenSubdiv's tag lines (`t crease`, `t corner`, `t hole`):
//!   the adaptive refinement's mesh.
//!
//! `cargo run --release -p capdiv-mesh --example bench_mesh -- mixed 10000 > mixed-1e4.obj`

use capdiv_mesh::{samples, MeshInput};
use std::io::{BufWriter, Write};

/// Copies of the parts of [`samples::feature_mix`], at least `faces`
/// faces, on a cubic lattice 10 units apart.
fn mixed(faces: usize) -> MeshInput {
    let parts = [
        samples::mushroom(),
        samples::rounded_cube(6),
        samples::extraordinary_disk(7, 5),
    ];
    let per: usize = parts.iter().map(|m| m.faces.len()).sum();
    let count = parts.len() * faces.div_ceil(per).max(1);
    let side = (1..).find(|s| s * s * s >= count).unwrap_or(1);
    let mut out = MeshInput::default();
    for k in 0..count {
        let m = &parts[k % parts.len()];
        let base = out.vertices.len() as u32;
        let at = [k % side, (k / side) % side, k / (side * side)].map(|c| 10.0 * c as f64);
        out.vertices.extend(
            m.vertices
                .iter()
                .map(|p| [p[0] + at[0], p[1] + at[1], p[2] + at[2]]),
        );
        out.faces.extend(
            m.faces
                .iter()
                .map(|f| f.iter().map(|&v| v + base).collect()),
        );
    }
    out
}

/// A torus of `2·k²` triangles (`k ≥ 3`).
fn triangle_torus(k: usize) -> MeshInput {
    let k = k.max(3);
    let (big, small) = (3.0, 1.0);
    let mut vertices = Vec::with_capacity(k * k);
    for i in 0..k {
        let a = std::f64::consts::TAU * i as f64 / k as f64;
        for j in 0..k {
            let b = std::f64::consts::TAU * j as f64 / k as f64;
            let r = big + small * b.cos();
            vertices.push([r * a.cos(), r * a.sin(), small * b.sin()]);
        }
    }
    let at = |i: usize, j: usize| ((i % k) * k + j % k) as u32;
    let mut faces = Vec::with_capacity(2 * k * k);
    for i in 0..k {
        for j in 0..k {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            faces.push(vec![a, b, c]);
            faces.push(vec![a, c, d]);
        }
    }
    MeshInput::new(vertices, faces)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let number = |i: usize| -> usize {
        args.get(i)
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| usage())
    };
    let mesh = match args.first().map(String::as_str) {
        Some("mixed") => mixed(number(1)),
        Some("triangles") => {
            let k = ((number(1) as f64 / 2.0).sqrt().round()) as usize;
            triangle_torus(k)
        }
        Some("icosphere") => samples::icosphere(number(1) as u32),
        Some("features") => {
            let base = ((number(1) as f64 / 16.0).sqrt().round() as usize).max(3);
            samples::feature_torus(base)
        }
        _ => usage(),
    };
    let mut out = BufWriter::new(std::io::stdout().lock());
    for p in &mesh.vertices {
        writeln!(out, "v {} {} {}", p[0], p[1], p[2]).expect("stdout");
    }
    for f in &mesh.faces {
        write!(out, "f").expect("stdout");
        for v in f {
            write!(out, " {}", v + 1).expect("stdout");
        }
        writeln!(out).expect("stdout");
    }
    // Tags, 0-based as OpenSubdiv's shape files have them.
    for c in &mesh.tags.creases {
        let [a, b] = c.vertices;
        writeln!(out, "t crease 2/1/0 {a} {b} {}", c.sharpness).expect("stdout");
    }
    for c in &mesh.tags.corners {
        writeln!(out, "t corner 1/1/0 {} {}", c.vertex, c.sharpness).expect("stdout");
    }
    for h in &mesh.tags.holes {
        writeln!(out, "t hole 1/0/0 {h}").expect("stdout");
    }
    out.flush().expect("stdout");
}

fn usage() -> ! {
    eprintln!(
        "usage: bench_mesh (mixed FACES | triangles FACES | icosphere LEVELS | features FACES)"
    );
    std::process::exit(2)
}
