//! Face-varying data (texture coordinates) over the surface, interpolated as
//! OpenSubdiv interpolates a face-varying channel with
//! `Sdc::Options::FVAR_LINEAR_ALL`: linearly everywhere, each input face on
//! its own, whatever the neighbouring faces give the same vertex (so UV seams
//! are kept exactly).
//!
//! In OpenSubdiv's parametrisation of an input face ([`crate::chart`]):
//!
//! - a quad's square `(s, t) ∈ [0, 1]²` carries the bilinear interpolation of
//!   its corner values (corner 0 at (0,0), 1 at (1,0), 2 at (1,1), 3 at (0,1));
//! - a face of `n ≠ 4` corners is `n` sub-quads, the one at corner `k` with
//!   corners: the value at corner `k`, the midpoint of edge `k→k+1`, the face's
//!   centroid (mean of its `n` values), the midpoint of edge `k−1→k` — the
//!   values a linear (bilinear-scheme) refinement step gives the child face —
//!   and bilinear in between.
//!
//! Every patch of the surface ([`PatchRecord`]) lies in one such square over
//! an axis-aligned rectangle, its `domain`; composing the affine map from the
//! patch's own square onto the rectangle with a bilinear function gives a
//! bilinear function again, so a patch's UVs are exactly the bilinear
//! interpolation of the UVs at its four domain corners ([`PatchUv`]). This
//! holds for the caps' patches as well (EG, C²PS beyond the 1-link,
//! Catmull-Clark caps): each sample takes the UV of the input face and
//! `(s, t)` it lies at.
//!
//! The patches of a C²PS cap inside the triangles around the pole are given in
//! polar coordinates instead ([`crate::evaluate`]): `r` from the pole (0) to
//! the triangle's edge on the 1-link (1), `v` from the triangle's first spoke
//! (the edge from the pole to the next corner) to its second (the edge from
//! the previous corner). The C²PS surface is not OpenSubdiv's there, so there
//! is no OpenSubdiv parameter to match; the triangle's UVs are interpolated
//! in the same coordinates, `uv(r, v) = uv_pole + r · ((1 − v) · uv_next +
//! v · uv_prev − uv_pole)`, which is bilinear in `(r, v)` too, covers the
//! triangle's UV triangle once and agrees with the bilinear rule along the
//! triangle's edges through the pole.

use crate::error::MeshError;
use crate::evaluate::{PatchKind, PatchRecord};
use crate::input::MeshInput;
use crate::plan::SurfacePlan;
use alloc::vec::Vec;

/// Texture coordinates over one patch: bilinear in the patch's own
/// parameters `(u, v) ∈ [0, 1]²` between its corner values, and the value
/// of the point its hole edges (if any) are closed to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchUv {
    /// UVs at `(u, v)` = (0,0), (1,0), (1,1), (0,1).
    pub corners: [[f64; 2]; 4],
    /// UV of the hole point ([`PatchRecord::hole_point`], the cap's centre);
    /// the first corner's value for a patch without hole edges.
    pub hole: [f64; 2],
}

impl PatchUv {
    /// The UV at `(u, v)` of the patch's own square. Terms with a zero
    /// weight add exactly zero, so two patches sharing an edge give equal
    /// values at the same points of that edge.
    pub fn at(&self, u: f64, v: f64) -> [f64; 2] {
        bilinear(&self.corners, u, v)
    }
}

/// `(1−s)(1−t)·c0 + s(1−t)·c1 + s·t·c2 + (1−s)·t·c3`, per component.
fn bilinear(c: &[[f64; 2]; 4], s: f64, t: f64) -> [f64; 2] {
    let w = [(1.0 - s) * (1.0 - t), s * (1.0 - t), s * t, (1.0 - s) * t];
    let mut out = [0.0; 2];
    for (d, o) in out.iter_mut().enumerate() {
        *o = w[0] * c[0][d] + w[1] * c[1][d] + w[2] * c[2][d] + w[3] * c[3][d];
    }
    out
}

fn mid(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [(a[0] + b[0]) * 0.5, (a[1] + b[1]) * 0.5]
}

/// A mesh's UVs, per face corner, ready to be evaluated at any point of the
/// surface (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct FaceVarying {
    /// `starts[f]..starts[f+1]`: face `f`'s corners.
    starts: Vec<u32>,
    /// Per corner: its UV.
    values: Vec<[f64; 2]>,
    /// Per corner: its vertex.
    vertices: Vec<u32>,
    /// Per C²PS cap of the plan (in plan order): its pole.
    poles: Vec<u32>,
}

impl FaceVarying {
    /// The UVs of `mesh` for patches of `plan` (made from `mesh`): `None`
    /// when the mesh has none, an error when they are malformed
    /// ([`MeshInput::check_uvs`]).
    pub fn new(mesh: &MeshInput, plan: &SurfacePlan<'_>) -> Result<Option<Self>, MeshError> {
        Self::without_plan(mesh).map(|fv| {
            fv.map(|mut fv| {
                fv.poles = plan.polar.iter().map(|p| p.vertex).collect();
                fv
            })
        })
    }

    /// [`FaceVarying::new`] for evaluating at face parameters only
    /// ([`FaceVarying::at`]); C²PS patches are not recognised.
    pub fn without_plan(mesh: &MeshInput) -> Result<Option<Self>, MeshError> {
        mesh.check_uvs()?;
        if !mesh.has_uvs() {
            return Ok(None);
        }
        let corners: usize = mesh.faces.iter().map(Vec::len).sum();
        if u32::try_from(corners).is_err() {
            return Err(MeshError::TooLarge);
        }
        let mut starts = Vec::with_capacity(mesh.faces.len() + 1);
        let mut values = Vec::with_capacity(corners);
        let mut vertices = Vec::with_capacity(corners);
        starts.push(0);
        for (f, uv) in mesh.faces.iter().zip(&mesh.uv_faces) {
            vertices.extend_from_slice(f);
            // check_uvs: every index is in the pool.
            values.extend(uv.iter().map(|&t| mesh.uvs[t as usize]));
            starts.push(values.len() as u32);
        }
        Ok(Some(FaceVarying {
            starts,
            values,
            vertices,
            poles: Vec::new(),
        }))
    }

    /// Face `face`'s corner values (empty for a face that does not exist).
    fn face(&self, face: u32) -> &[[f64; 2]] {
        let f = face as usize;
        match (self.starts.get(f), self.starts.get(f + 1)) {
            (Some(&a), Some(&b)) => &self.values[a as usize..b as usize],
            _ => &[],
        }
    }

    /// The UV at `(s, t)` of input face `face`'s square (`corner: None`, a
    /// quad) or of its sub-quad at `corner` (a face of `n ≠ 4` corners),
    /// OpenSubdiv's `FVAR_LINEAR_ALL` value there. A quad asked with a
    /// corner is read as its quadrant at that corner; a non-quad asked
    /// without one, as its sub-quad 0. A face that does not exist gives
    /// (0, 0).
    pub fn at(&self, face: u32, corner: Option<u8>, s: f64, t: f64) -> [f64; 2] {
        let c = self.face(face);
        let n = c.len();
        if n == 0 {
            return [0.0; 2];
        }
        if n == 4 && corner.is_none() {
            return bilinear(&[c[0], c[1], c[2], c[3]], s, t);
        }
        let k = corner.map_or(0, usize::from) % n;
        let mut centroid = [0.0; 2];
        for v in c {
            centroid[0] += v[0];
            centroid[1] += v[1];
        }
        let centroid = [centroid[0] / n as f64, centroid[1] / n as f64];
        let sub = [
            c[k],
            mid(c[k], c[(k + 1) % n]),
            centroid,
            mid(c[(k + n - 1) % n], c[k]),
        ];
        bilinear(&sub, s, t)
    }

    /// For a C²PS patch in polar coordinates: the triangle's UVs at the
    /// pole, the next and the previous corner.
    fn polar_triangle(&self, p: &PatchRecord<impl Copy>) -> Option<[[f64; 2]; 3]> {
        if p.kind != PatchKind::C2ps {
            return None;
        }
        let pole = *self.poles.get(p.cap? as usize)?;
        let (a, b) = (
            *self.starts.get(p.face as usize)? as usize,
            *self.starts.get(p.face as usize + 1)? as usize,
        );
        if b - a != 3 {
            return None;
        }
        let k = self.vertices[a..b].iter().position(|&v| v == pole)?;
        let c = &self.values[a..b];
        Some([c[k], c[(k + 1) % 3], c[(k + 2) % 3]])
    }

    /// The UVs over patch `p` (see the module doc). A patch with hole edges
    /// gets the UV of its cap's centre as [`PatchUv::hole`]: the corner of
    /// its face's (or sub-quad's) square beyond its first hole edge that is
    /// nearest to that edge's midpoint (a cap's centre is an input vertex,
    /// a square corner, or the centre of a face that is not a quad, corner
    /// (1,1) of each sub-quad; the last hole is at most the patch's own
    /// size across, the other corners are further).
    pub fn patch<R: Copy>(&self, p: &PatchRecord<R>) -> PatchUv {
        let [u0, u1, v0, v1] = p.domain;
        let rect = [[u0, v0], [u1, v0], [u1, v1], [u0, v1]];
        if let Some([pole, next, prev]) = self.polar_triangle(p) {
            let at = |r: f64, v: f64| {
                let mut out = [0.0; 2];
                for (d, o) in out.iter_mut().enumerate() {
                    *o = pole[d] + r * ((1.0 - v) * next[d] + v * prev[d] - pole[d]);
                }
                out
            };
            return PatchUv {
                corners: rect.map(|[r, v]| at(r, v)),
                hole: pole,
            };
        }
        let corners = rect.map(|[s, t]| self.at(p.face, p.corner, s, t));
        let hole = match (0..4u8).find(|e| p.hole & (1 << e) != 0) {
            None => corners[0],
            Some(e) => {
                // Edge e's midpoint, and how far beyond the edge a point is.
                let m = match e {
                    0 => [(u0 + u1) / 2.0, v0],
                    1 => [u1, (v0 + v1) / 2.0],
                    2 => [(u0 + u1) / 2.0, v1],
                    _ => [u0, (v0 + v1) / 2.0],
                };
                let beyond = |c: [f64; 2]| match e {
                    0 => v0 - c[1],
                    1 => c[0] - u1,
                    2 => c[1] - v1,
                    _ => u0 - c[0],
                };
                let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
                let dist = |c: [f64; 2]| {
                    let (x, y) = (c[0] - m[0], c[1] - m[1]);
                    x * x + y * y
                };
                let best = square
                    .iter()
                    .filter(|&&c| beyond(c) >= 0.0)
                    .min_by(|a, b| dist(**a).total_cmp(&dist(**b)));
                match best {
                    Some(c) => self.at(p.face, p.corner, c[0], c[1]),
                    None => self.at(p.face, p.corner, m[0], m[1]),
                }
            }
        };
        PatchUv { corners, hole }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

    fn pentagon_and_quad() -> MeshInput {
        let v = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [3.0, 1.5, 0.0],
            [1.0, 3.0, 0.0],
            [-1.0, 1.5, 0.0],
            [3.0, -2.0, 0.0],
            [0.0, -2.0, 0.0],
        ];
        MeshInput::new(v, vec![vec![0, 1, 2, 3, 4], vec![0, 6, 5, 1]]).with_uvs(
            vec![
                [0.1, 0.2],
                [0.9, 0.1],
                [1.0, 0.7],
                [0.5, 1.0],
                [0.0, 0.6],
                [0.9, -0.5],
                [0.1, -0.6],
            ],
            vec![vec![0, 1, 2, 3, 4], vec![0, 6, 5, 1]],
        )
    }

    #[test]
    fn quads_are_bilinear_and_sub_quads_meet_at_midpoints_and_centroid() {
        let m = pentagon_and_quad();
        let fv = FaceVarying::without_plan(&m).unwrap().unwrap();
        // Quad corners.
        let q = [[0.1, 0.2], [0.1, -0.6], [0.9, -0.5], [0.9, 0.1]];
        for (k, st) in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
            .iter()
            .enumerate()
        {
            assert_eq!(fv.at(1, None, st[0], st[1]), q[k]);
        }
        // The quad's centre is the mean of its corners (exact in binary here
        // up to one rounding per operation).
        let c = fv.at(1, None, 0.5, 0.5);
        assert!((c[0] - 0.5).abs() < 1e-15 && (c[1] + 0.2).abs() < 1e-15);
        // Pentagon: sub-quad k's (1,0) is sub-quad k+1's (0,1); every (1,1)
        // is the centroid.
        let centroid = [2.5 / 5.0, 2.6 / 5.0];
        for k in 0..5u8 {
            let a = fv.at(0, Some(k), 1.0, 0.0);
            let b = fv.at(0, Some((k + 1) % 5), 0.0, 1.0);
            assert_eq!(a, b);
            let c = fv.at(0, Some(k), 1.0, 1.0);
            assert!((c[0] - centroid[0]).abs() < 1e-15 && (c[1] - centroid[1]).abs() < 1e-15);
        }
    }

    #[test]
    fn patch_uvs_are_the_face_values_at_the_domain_corners() {
        let m = pentagon_and_quad();
        let fv = FaceVarying::without_plan(&m).unwrap().unwrap();
        let geometry = crate::tessellate::PatchGeometry::Cubic(capdiv::TensorPatch {
            points: [[capdiv::Point3::<f64>::ZERO; 4]; 4],
        });
        let p = PatchRecord {
            level: 2,
            face: 1,
            domain: [0.25, 0.5, 0.5, 0.75],
            hole: crate::tessellate::edge_bit(crate::tessellate::EDGE_U0),
            ..PatchRecord::new(PatchKind::Regular, geometry)
        };
        let uv = fv.patch(&p);
        for (u, v) in [(0.0, 0.0), (0.3, 0.9), (1.0, 0.5)] {
            let want = fv.at(1, None, 0.25 + 0.25 * u, 0.5 + 0.25 * v);
            let got = uv.at(u, v);
            assert!((want[0] - got[0]).abs() < 1e-15 && (want[1] - got[1]).abs() < 1e-15);
        }
        // The hole lies beyond u = 0.25: the nearest square corner there is (0, 1).
        assert_eq!(uv.hole, fv.at(1, None, 0.0, 1.0));
    }

    #[test]
    fn malformed_uvs_are_errors() {
        let m = pentagon_and_quad();
        let mut bad = m.clone();
        bad.uv_faces[1].pop();
        assert_eq!(
            FaceVarying::without_plan(&bad),
            Err(MeshError::UvCorners {
                face: 1,
                uv_corners: 3,
                vertices: 4
            })
        );
        let mut bad = m.clone();
        bad.uv_faces[0][2] = 7;
        assert_eq!(
            FaceVarying::without_plan(&bad),
            Err(MeshError::UvOutOfRange {
                face: 0,
                index: 7,
                uvs: 7
            })
        );
        let mut bad = m.clone();
        bad.uvs[5][1] = f64::NAN;
        assert_eq!(
            FaceVarying::without_plan(&bad),
            Err(MeshError::NonFiniteUv { face: 1, uv: 5 })
        );
        let mut bad = m;
        bad.uv_faces.truncate(1);
        assert!(matches!(
            FaceVarying::without_plan(&bad),
            Err(MeshError::UvCorners { face: 1, .. })
        ));
    }
}
