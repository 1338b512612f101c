//! What a surface looks like to a designer, per sample point: exact curvature
//! from a patch's derivatives, highlight lines, and the colour maps that show
//! them. One set of formulas for every front end (the CLI's `render`,
//! `compare` and `curvature`, the browser viewer's WASM module), so a picture
//! and a number always mean the same thing.
//!
//! - Curvature: [`PatchGeometry::jet`] gives position and first and second
//!   partials of a ring or regular patch by de Casteljau's algorithm
//!   ([`capdiv::TensorPatch::jet`]); [`capdiv::SurfaceJet::geometry`] turns
//!   them into the unit normal, `K` and `H` — exact, not estimated from a
//!   tessellation.
//! - Highlight lines (Beier & Chen, *Highlight-line algorithm for realtime
//!   surface-quality assessment*, CAD 26(4), 1994; used as the shape test in
//!   the EG paper): a family of parallel light lines in a plane; a surface
//!   point lies on the highlight of a light line when its normal line meets
//!   that light line. [`HighlightLines::parameter`] is the position, across
//!   the family, at which the normal line meets the light plane; its integer
//!   crossings are the highlight lines. A flaw in curvature shows as a kink
//!   or a wobble of the stripes.

use capdiv::{Error, Point3, SurfaceJet};

use crate::tessellate::PatchGeometry;

impl<R: capdiv::Real> PatchGeometry<R> {
    /// Position and first and second partials at `(u, v) ∈ [0,1]²` in the
    /// patch's own parameters.
    pub fn jet(&self, u: R, v: R) -> Result<SurfaceJet<R>, Error> {
        match self {
            PatchGeometry::Cubic(p) => p.jet(u, v),
            PatchGeometry::Quartic(p) => p.jet(u, v),
        }
    }
}

/// Default number of light-line spacings across a picture's visible height:
/// the CLI's `--lines`, the browser viewer's *lines*. A flat region facing
/// the light shows that many stripes across the picture whatever the
/// object's size or zoom.
pub const DEFAULT_LINES: f64 = 10.0;

/// A family of parallel light lines `A + t·E + k·s·D` (`k` integer) in the
/// light plane through `A` spanned by `E` and `D`, `D ⟂ E` unit vectors,
/// spacing `s`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HighlightLines {
    origin: [f64; 3],
    across: [f64; 3],
    plane_normal: [f64; 3],
    spacing: f64,
}

impl HighlightLines {
    /// Light lines through `origin` along `direction`, repeated every
    /// `spacing` along `across` (made perpendicular to `direction`). `None`
    /// when the directions are parallel, zero or not finite, or the spacing
    /// is not positive and finite.
    pub fn new(
        origin: [f64; 3],
        direction: [f64; 3],
        across: [f64; 3],
        spacing: f64,
    ) -> Option<Self> {
        let e = Point3(direction).unit()?;
        let plane_normal = e.cross(Point3(across)).unit()?;
        let d = plane_normal.cross(e);
        if !(spacing > 0.0 && spacing.is_finite() && origin.iter().all(|c| c.is_finite())) {
            return None;
        }
        Some(HighlightLines {
            origin,
            across: d.0,
            plane_normal: plane_normal.0,
            spacing,
        })
    }

    /// Where the normal line `p + μ·n` meets the light plane, measured across
    /// the family in units of the spacing: integers are light lines. `None`
    /// where the normal is parallel to the plane (the normal line never
    /// meets it) or the input is not finite.
    pub fn parameter(&self, point: [f64; 3], normal: [f64; 3]) -> Option<f64> {
        let w = Point3(self.plane_normal);
        let nw = Point3(normal).dot(w);
        if nw.abs() < 1e-12 {
            return None;
        }
        let rel = [
            self.origin[0] - point[0],
            self.origin[1] - point[1],
            self.origin[2] - point[2],
        ];
        let mu = Point3(rel).dot(w) / nw;
        let q = [
            point[0] + mu * normal[0] - self.origin[0],
            point[1] + mu * normal[1] - self.origin[1],
            point[2] + mu * normal[2] - self.origin[2],
        ];
        let s = Point3(q).dot(Point3(self.across)) / self.spacing;
        s.is_finite().then_some(s)
    }

    /// Stripe intensity at a point: 1 on a highlight line, falling to 0 at
    /// `width` (in units of the spacing, e.g. 0.15) away from it.
    pub fn intensity(&self, point: [f64; 3], normal: [f64; 3], width: f64) -> f64 {
        match self.parameter(point, normal) {
            Some(s) => {
                let dist = (s - libm::round(s)).abs();
                if dist >= width {
                    0.0
                } else {
                    1.0 - dist / width
                }
            }
            None => 0.0,
        }
    }
}

/// Diverging colour map for a signed quantity: `t ∈ [−1, 1]` (clamped) from
/// blue (−1) through white (0) to red (+1), linear in each half. Used for
/// Gaussian and mean curvature scaled by a symmetric range `[−m, m]`.
pub fn diverging(t: f64) -> [u8; 3] {
    let t = if t.is_nan() { 0.0 } else { t.clamp(-1.0, 1.0) };
    let fade = |x: f64| libm::round(255.0 * (1.0 - x)) as u8;
    if t >= 0.0 {
        [255, fade(t), fade(t)]
    } else {
        [fade(-t), fade(-t), 255]
    }
}

/// A symmetric colour scale `[−m, m]` for `values`: `m` is the
/// `quantile`-th quantile of `|value|` (e.g. 0.98, so a few extreme samples —
/// the centre of a Catmull-Clark cap, where curvature diverges — do not wash
/// out the rest), never 0. Non-finite values are skipped.
pub fn symmetric_scale(values: &[f64], quantile: f64) -> f64 {
    let mut mags: alloc::vec::Vec<f64> = values
        .iter()
        .filter(|v| v.is_finite())
        .map(|v| v.abs())
        .collect();
    if mags.is_empty() {
        return 1.0;
    }
    mags.sort_unstable_by(f64::total_cmp);
    let q = quantile.clamp(0.0, 1.0);
    let idx = libm::round((mags.len() - 1) as f64 * q) as usize;
    let m = mags[idx.min(mags.len() - 1)];
    if m > 0.0 {
        m
    } else {
        mags[mags.len() - 1].max(f64::MIN_POSITIVE)
    }
}
