//! Tessellation of Bézier patches into a quad mesh, the common input of the
//! OBJ writer ([`crate::obj`]) and the PNG preview ([`crate::render`]).
//!
//! Each patch is evaluated with the kernel's [`TensorPatch::evaluate`] at
//! `(grid+1)²` parameter pairs `(u, v) = (a/grid, b/grid)`: position and unit
//! normal `∂u × ∂v`. Its `grid²` quads list their corners counter-clockwise
//! about that normal. Patches do not share vertices: points on a common edge
//! are stored once per patch (duplicated; they agree to round-off). Generic over
//! the patch size `K`, so bi-quartic EG patches work unchanged.

use crate::Scalar;
use capdiv::{Point3, TensorPatch};

/// A tessellated set of patches.
#[derive(Clone, Debug, Default)]
pub struct Mesh<R> {
    /// Vertex positions.
    pub positions: Vec<Point3<R>>,
    /// Unit normals, one per vertex (zero where none could be found).
    pub normals: Vec<Point3<R>>,
    /// Patch parameters `(u, v)` of each vertex.
    pub uv: Vec<[f64; 2]>,
    /// Quads as 0-based vertex indices, counter-clockwise about the normal.
    pub quads: Vec<[usize; 4]>,
    /// Per quad: the tag of its patch (the subdivision level).
    pub tags: Vec<u32>,
}

impl<R: Scalar> Mesh<R> {
    /// Tessellates `(tag, patch)` pairs with `grid ≥ 1` segments per side.
    pub fn from_patches<'a, const K: usize>(
        patches: impl IntoIterator<Item = (u32, &'a TensorPatch<R, K>)>,
        grid: usize,
    ) -> Self {
        let grid = grid.max(1);
        let side = grid + 1;
        let mut mesh = Mesh::default();
        let mut pts = vec![Point3::<R>::ZERO; side * side];
        let mut nrm = vec![Point3::<R>::ZERO; side * side];
        for (tag, patch) in patches {
            sample(patch, grid, &mut pts, &mut nrm);
            let base = mesh.positions.len();
            mesh.positions.extend_from_slice(&pts);
            mesh.normals.extend_from_slice(&nrm);
            for a in 0..side {
                for b in 0..side {
                    mesh.uv
                        .push([a as f64 / grid as f64, b as f64 / grid as f64]);
                }
            }
            for a in 0..grid {
                for b in 0..grid {
                    let idx = |a: usize, b: usize| base + a * side + b;
                    mesh.quads
                        .push([idx(a, b), idx(a + 1, b), idx(a + 1, b + 1), idx(a, b + 1)]);
                    mesh.tags.push(tag);
                }
            }
        }
        mesh
    }
}

/// Positions and unit normals of one patch on the grid, row `a` (along `u`)
/// after row. Where the patch normal degenerates, the normal of the grid cell
/// (finite differences) stands in; failing that, the zero vector is kept
/// rather than a made-up direction.
fn sample<R: Scalar, const K: usize>(
    patch: &TensorPatch<R, K>,
    grid: usize,
    pts: &mut [Point3<R>],
    nrm: &mut [Point3<R>],
) {
    let side = grid + 1;
    let t = |k: usize| R::from_f64(k as f64 / grid as f64);
    let mut missing = false;
    for a in 0..side {
        for b in 0..side {
            let k = a * side + b;
            // (u, v) lie in [0, 1]: evaluate cannot fail with OutOfDomain.
            match patch.evaluate(t(a), t(b)) {
                Ok(pp) => {
                    pts[k] = pp.position;
                    nrm[k] = pp.normal().unwrap_or_else(|_| {
                        missing = true;
                        Point3::ZERO
                    });
                }
                Err(_) => {
                    pts[k] = Point3::ZERO;
                    nrm[k] = Point3::ZERO;
                    missing = true;
                }
            }
        }
    }
    if !missing {
        return;
    }
    for a in 0..side {
        for b in 0..side {
            let k = a * side + b;
            if nrm[k] != Point3::ZERO {
                continue;
            }
            let (a0, a1) = (a.saturating_sub(1), (a + 1).min(grid));
            let (b0, b1) = (b.saturating_sub(1), (b + 1).min(grid));
            let du = pts[a1 * side + b] - pts[a0 * side + b];
            let dv = pts[a * side + b1] - pts[a * side + b0];
            let n = du.cross(dv);
            let len = n.norm();
            if len > R::ZERO && len.is_finite() {
                nrm[k] = n * (R::ONE / len);
            }
        }
    }
}
