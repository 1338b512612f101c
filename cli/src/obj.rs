//! Wavefront OBJ output: Bézier patches tessellated on a regular grid.
//!
//! Each patch is evaluated with the kernel's [`TensorPatch::evaluate`] at
//! `(grid+1)²` parameter pairs `(u, v) = (a/grid, b/grid)`, giving `v` (position)
//! and `vn` (unit normal `∂u × ∂v`) lines, and `grid²` quads `f a//a b//b c//c d//d`
//! ordered counter-clockwise about that normal.
//!
//! Patches do not share vertices: points on a common edge are emitted once per
//! patch (duplicated). Positions on shared edges agree to round-off, so the mesh
//! looks closed, but a tool that needs a welded mesh must merge by position.
//! Generic over the patch size `K`, so bi-quartic EG patches work unchanged.

use crate::Scalar;
use capdiv::{Point3, TensorPatch};
use std::fmt::Write;

/// Tessellation of a list of patches, as OBJ text.
#[derive(Clone, Debug, Default)]
pub struct ObjMesh {
    /// The OBJ text.
    pub text: String,
    /// `v` lines written.
    pub vertices: usize,
    /// `f` lines written.
    pub faces: usize,
}

/// Tessellates `patches` with `grid` segments per parameter direction
/// (`grid ≥ 1`). `header` lines are written as `#` comments first.
pub fn tessellate<'a, R: Scalar, const K: usize>(
    patches: impl IntoIterator<Item = &'a TensorPatch<R, K>>,
    grid: usize,
    header: &[String],
) -> ObjMesh {
    let grid = grid.max(1);
    let mut mesh = ObjMesh::default();
    for line in header {
        let _ = writeln!(mesh.text, "# {line}");
    }
    let side = grid + 1;
    let mut pts = vec![Point3::<R>::ZERO; side * side];
    let mut nrm = vec![Point3::<R>::ZERO; side * side];
    for patch in patches {
        sample(patch, grid, &mut pts, &mut nrm);
        for (p, n) in pts.iter().zip(&nrm) {
            let [x, y, z] = p.0;
            let [a, b, c] = n.0;
            let _ = writeln!(mesh.text, "v {x} {y} {z}");
            let _ = writeln!(mesh.text, "vn {a} {b} {c}");
        }
        // 1-based index of the patch's first vertex.
        let base = mesh.vertices + 1;
        for i in 0..grid {
            for j in 0..grid {
                let idx = |a: usize, b: usize| base + a * side + b;
                let q = [idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)];
                let _ = writeln!(
                    mesh.text,
                    "f {0}//{0} {1}//{1} {2}//{2} {3}//{3}",
                    q[0], q[1], q[2], q[3]
                );
            }
        }
        mesh.vertices += side * side;
        mesh.faces += grid * grid;
    }
    mesh
}

/// Positions and unit normals of one patch on the grid, row `a` (along `u`)
/// after row. Where the patch normal degenerates, the normal of the grid cell
/// (finite differences) stands in; failing that, the zero vector is written
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
