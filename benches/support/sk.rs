//! subdiv-kernels as a Catmull-Clark peer: a mesh from faces, the
//! stencils of one refinement, applied to `[f32; 3]` or `[f64; 3]` points.

use capdiv::Real;
use std::num::NonZeroU8;
use subdiv_kernels::{Mesh, Refiner, Scheme, SchemeOptions, StencilTable, UniformRefine};

/// A subdiv-kernels mesh from faces (`counts` corners each, `indices` flat);
/// its edge list derived from them; no creases or corners.
pub fn mesh(vertices: usize, counts: Vec<u32>, indices: Vec<u32>) -> Mesh {
    let mut edges = std::collections::BTreeSet::new();
    let mut start = 0;
    for &c in &counts {
        let f = &indices[start..start + c as usize];
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            edges.insert([a.min(b), a.max(b)]);
        }
        start += c as usize;
    }
    let edge_vertices: Vec<[u32; 2]> = edges.into_iter().collect();
    Mesh {
        vertex_count: vertices as u32,
        face_vertex_counts: counts,
        face_vertex_indices: indices,
        edge_creases: vec![0.0; edge_vertices.len()],
        edge_vertices,
        vertex_corners: vec![0.0; vertices],
    }
}

/// subdiv-kernels' stencils of one Catmull-Clark refinement of `mesh`
/// (topology and weights, computed once, like a rule table).
pub fn cc_stencils(mesh: Mesh) -> StencilTable {
    let refiner =
        Refiner::new(mesh, Scheme::CatmullClark, SchemeOptions::default()).expect("valid mesh");
    let one = UniformRefine::from(NonZeroU8::new(1).expect("1 level"));
    let mut result = refiner.refine_uniform(&one).expect("refinement");
    result.level_stencils.remove(0)
}

/// subdiv-kernels' positions type for `R` (`[f32; 3]` or `[f64; 3]`).
pub trait SkReal: Real {
    /// One refinement, the crate's one-shot path (a new `Vec`).
    fn interpolate(t: &StencilTable, input: &[[Self; 3]]) -> Vec<[Self; 3]>;
    /// One refinement into `out` (no allocation).
    fn interpolate_rows(t: &StencilTable, input: &[[Self; 3]], rows: &[u32], out: &mut [[Self; 3]]);
}
impl SkReal for f64 {
    fn interpolate(t: &StencilTable, input: &[[f64; 3]]) -> Vec<[f64; 3]> {
        t.interpolate(input)
    }
    fn interpolate_rows(t: &StencilTable, input: &[[f64; 3]], rows: &[u32], out: &mut [[f64; 3]]) {
        t.interpolate_rows(input, rows, out)
    }
}
impl SkReal for f32 {
    fn interpolate(t: &StencilTable, input: &[[f32; 3]]) -> Vec<[f32; 3]> {
        t.interpolate(input)
    }
    fn interpolate_rows(t: &StencilTable, input: &[[f32; 3]], rows: &[u32], out: &mut [[f32; 3]]) {
        t.interpolate_rows(input, rows, out)
    }
}
