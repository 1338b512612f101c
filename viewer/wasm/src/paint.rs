//! What the GPU gets per vertex: `f32` positions and normals, an RGBA colour
//! and the highlight-line parameter, for one of the four shadings. The
//! colours and the parameter come from `capdiv_mesh::shade` — the CLI's
//! formulas:
//!
//! - **plain**: one base colour (the page lights it);
//! - **highlight**: the base colour, plus per vertex
//!   [`HighlightLines::parameter`] (where the normal line meets the light
//!   plane, in line spacings). The page's fragment shader draws the stripes
//!   from the interpolated parameter with the formula of
//!   [`HighlightLines::intensity`] (`1 − d/w` within `w` of an integer), so
//!   the stripes are per pixel while the geometry stays in WASM;
//! - **gaussian**, **mean**: [`diverging`]`(value / m)` with the symmetric
//!   scale `m` = [`symmetric_scale`]`(values, `[`QUANTILE`]`)`; hole-fan
//!   vertices get [`HOLE_COLOUR`], degenerate ones [`DEGENERATE_COLOUR`].

use crate::scene::Up;
use crate::tess::{Surface, DEGENERATE, HOLE};
use capdiv_mesh::shade::{diverging, symmetric_scale, HighlightLines};

/// Base colour of the plain and highlight shadings.
pub const BASE_COLOUR: [u8; 3] = [208, 208, 216];
/// Colour of the caps' last holes in the curvature maps.
pub const HOLE_COLOUR: [u8; 3] = [40, 170, 70];
/// Colour where the normal does not exist.
pub const DEGENERATE_COLOUR: [u8; 3] = [110, 110, 110];
/// Quantile of `|K|` or `|H|` that sets the colour scale (a few extreme
/// samples, as at a Catmull-Clark cap's centre, do not wash out the rest).
pub const QUANTILE: f64 = 0.98;
/// Light lines across the bounding box in the highlight shading.
pub const LINES_ACROSS: f64 = 5.0;
/// Highlight parameter given where the normal line misses the light plane:
/// half-way between two lines, so no stripe.
pub const NO_LINE: f32 = 0.5;

/// The shadings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Lit base colour.
    Plain,
    /// Highlight lines.
    Highlight,
    /// Gaussian curvature map.
    Gaussian,
    /// Mean curvature map.
    Mean,
}

impl Mode {
    /// From the page's code (0..=3).
    pub fn from_code(code: i32) -> Option<Self> {
        Some(match code {
            0 => Mode::Plain,
            1 => Mode::Highlight,
            2 => Mode::Gaussian,
            3 => Mode::Mean,
            _ => return None,
        })
    }
}

/// Vertex attributes for the GPU.
#[derive(Clone, Debug, Default)]
pub struct Paint {
    /// `x, y, z` per vertex.
    pub positions: Vec<f32>,
    /// Unit normal per vertex (zero where degenerate).
    pub normals: Vec<f32>,
    /// `r, g, b, a` per vertex.
    pub colors: Vec<u8>,
    /// Highlight-line parameter per vertex (highlight shading; else 0.5).
    pub stripes: Vec<f32>,
}

/// The colour scale `m` of a curvature map over the surface's samples
/// (hole fans and degenerate samples left out).
pub fn scale(surface: &Surface, mode: Mode) -> f64 {
    let values = match mode {
        Mode::Gaussian => &surface.gaussian,
        Mode::Mean => &surface.mean,
        _ => return 1.0,
    };
    let kept: Vec<f64> = values
        .iter()
        .zip(&surface.flags)
        .filter(|(_, &f)| f & (HOLE | DEGENERATE) == 0)
        .map(|(&v, _)| v)
        .collect();
    symmetric_scale(&kept, QUANTILE)
}

/// The light lines for a surface of bounding box `[lo, hi]` with `up` the
/// axis shown upward: [`HighlightLines::for_box`] with [`LINES_ACROSS`]
/// lines for `z` up; for `y` up the same lines turned with the model
/// (`z` up's `x, y, z` are `y` up's `x, −z, y`): the light plane a box
/// diagonal above the top face (`+y`), lines along `−z`.
pub fn lines(lo: [f64; 3], hi: [f64; 3], up: Up) -> Option<HighlightLines> {
    match up {
        Up::Z => HighlightLines::for_box(lo, hi, LINES_ACROSS),
        Up::Y => {
            let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
            let centre = [0.5 * (lo[0] + hi[0]), hi[1] + size, 0.5 * (lo[2] + hi[2])];
            HighlightLines::new(
                centre,
                [0.0, 0.0, -1.0],
                [1.0, 0.0, 0.0],
                size / LINES_ACROSS,
            )
        }
    }
}

/// Fills `out` for `surface` under `mode` (curvature scale `m`, light lines
/// `lines`; each only used by its shading).
pub fn paint(
    surface: &Surface,
    mode: Mode,
    m: f64,
    lines: Option<&HighlightLines>,
    out: &mut Paint,
) {
    paint_range(surface, mode, m, lines, (0, surface.len()), out);
}

/// [`paint`] for the vertices `range.0..range.1` only (the rest of `out`
/// kept; `out` is resized to the surface first).
pub fn paint_range(
    surface: &Surface,
    mode: Mode,
    m: f64,
    lines: Option<&HighlightLines>,
    range: (usize, usize),
    out: &mut Paint,
) {
    let n = surface.len();
    out.positions.resize(3 * n, 0.0);
    out.normals.resize(3 * n, 0.0);
    out.colors.resize(4 * n, 0);
    out.stripes.resize(n, NO_LINE);
    for i in range.0..range.1.min(n) {
        let (p, nrm, flags) = (surface.position[i], surface.normal[i], surface.flags[i]);
        for c in 0..3 {
            out.positions[3 * i + c] = p[c] as f32;
            out.normals[3 * i + c] = nrm[c] as f32;
        }
        let colour = match mode {
            Mode::Plain | Mode::Highlight => BASE_COLOUR,
            Mode::Gaussian | Mode::Mean if flags & HOLE != 0 => HOLE_COLOUR,
            Mode::Gaussian | Mode::Mean if flags & DEGENERATE != 0 => DEGENERATE_COLOUR,
            Mode::Gaussian => diverging(surface.gaussian[i] / m),
            Mode::Mean => diverging(surface.mean[i] / m),
        };
        out.colors[4 * i..4 * i + 4].copy_from_slice(&[colour[0], colour[1], colour[2], 255]);
        out.stripes[i] = match (mode, lines) {
            (Mode::Highlight, Some(l)) if flags & DEGENERATE == 0 => {
                l.parameter(p, nrm).map_or(NO_LINE, |s| s as f32)
            }
            _ => NO_LINE,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn surface(values: &[(f64, f64, u8)]) -> Surface {
        let mut s = Surface::default();
        for (i, &(k, h, f)) in values.iter().enumerate() {
            s.position.push([i as f64, 0.0, 0.0]);
            s.normal.push([0.0, 0.0, 1.0]);
            s.gaussian.push(k);
            s.mean.push(h);
            s.flags.push(f);
        }
        s.lo = [0.0; 3];
        s.hi = [values.len() as f64, 1.0, 1.0];
        s
    }

    #[test]
    fn curvature_maps_use_the_shared_colour_map_and_scale() {
        let s = surface(&[
            (-2.0, 1.0, 0),
            (2.0, -1.0, 0),
            (0.0, 0.0, 0),
            (1e9, 1e9, HOLE),
            (f64::NAN, f64::NAN, DEGENERATE),
        ]);
        // The hole and degenerate samples do not enter the scale.
        let m = scale(&s, Mode::Gaussian);
        assert_eq!(m, symmetric_scale(&[-2.0, 2.0, 0.0], QUANTILE));
        let mut p = Paint::default();
        paint(&s, Mode::Gaussian, m, None, &mut p);
        assert_eq!(p.positions.len(), 15);
        assert_eq!(&p.colors[0..3], &diverging(-2.0 / m));
        assert_eq!(&p.colors[4..7], &diverging(2.0 / m));
        assert_eq!(&p.colors[12..15], &HOLE_COLOUR);
        assert_eq!(&p.colors[16..19], &DEGENERATE_COLOUR);
        assert!(p.stripes.iter().all(|&t| t == NO_LINE));
        let mh = scale(&s, Mode::Mean);
        paint(&s, Mode::Mean, mh, None, &mut p);
        assert_eq!(&p.colors[0..3], &diverging(1.0 / mh));
        assert_eq!(scale(&s, Mode::Plain), 1.0);
    }

    #[test]
    fn highlight_parameter_is_the_shared_one() {
        let s = surface(&[(0.0, 0.0, 0), (0.0, 0.0, 0), (0.0, 0.0, DEGENERATE)]);
        let l = lines(s.lo, s.hi, Up::Z).unwrap();
        let mut p = Paint::default();
        paint(&s, Mode::Highlight, 1.0, Some(&l), &mut p);
        for i in 0..2 {
            let want = l.parameter(s.position[i], s.normal[i]).unwrap() as f32;
            assert_eq!(p.stripes[i], want);
        }
        assert_eq!(p.stripes[2], NO_LINE);
        // Points one spacing apart across the lines (x), upward normals:
        // parameters one apart (the spacing is the box size / LINES_ACROSS).
        let spacing = 3.0 / LINES_ACROSS;
        let a = l.parameter([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]).unwrap();
        let b = l.parameter([spacing, 0.0, 0.0], [0.0, 0.0, 1.0]).unwrap();
        assert!(((b - a).abs() - 1.0).abs() < 1e-12);
        assert!(p.colors.chunks(4).all(|c| c[..3] == BASE_COLOUR));
    }

    #[test]
    fn modes_have_codes() {
        assert_eq!(Mode::from_code(0), Some(Mode::Plain));
        assert_eq!(Mode::from_code(3), Some(Mode::Mean));
        assert_eq!(Mode::from_code(4), None);
        assert_eq!(Mode::from_code(-1), None);
    }
}
