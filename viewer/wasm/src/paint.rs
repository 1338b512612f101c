//! What the GPU gets per vertex: `f32` positions and normals, an RGBA colour
//! and the highlight-line parameter, for one of the four shadings. The
//! colours and the parameter come from `capdiv_mesh::shade` — the CLI's
//! formulas:
//!
//! - **plain**: one base colour (the page lights it);
//! - **highlight**: the base colour, plus per vertex
//!   [`HighlightLines::parameter`] (where the normal line meets the light
//!   plane, in line spacings) for the light lines of [`lines`]: spaced
//!   relative to the [`View`], so that the page re-computes this parameter
//!   alone ([`restripe`]) when the zoom changes. The page's fragment shader
//!   draws the stripes from the interpolated parameter with the formula of
//!   [`HighlightLines::intensity`] (`1 − d/w` within `w` of an integer), so
//!   the stripes are per pixel while the geometry stays in WASM;
//! - **gaussian**, **mean**: [`diverging`]`(value / m)` with the symmetric
//!   scale `m` = [`symmetric_scale`]`(values, `[`QUANTILE`]`)`; hole-fan
//!   vertices get [`HOLE_COLOUR`], degenerate ones [`DEGENERATE_COLOUR`].

use crate::scene::Up;
use crate::tess::{Surface, DEGENERATE, HOLE};
use capdiv_mesh::shade::{diverging, symmetric_scale, HighlightLines, DEFAULT_LINES};

/// Base colour of the plain and highlight shadings.
pub const BASE_COLOUR: [u8; 3] = [208, 208, 216];
/// Colour of the caps' last holes in the curvature maps.
pub const HOLE_COLOUR: [u8; 3] = [40, 170, 70];
/// Colour where the normal does not exist.
pub const DEGENERATE_COLOUR: [u8; 3] = [110, 110, 110];
/// Quantile of `|K|` or `|H|` that sets the colour scale (a few extreme
/// samples, as at a Catmull-Clark cap's centre, do not wash out the rest).
pub const QUANTILE: f64 = 0.98;
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

/// What the light lines are relative to: the view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// The orbit target, at the picture's centre.
    pub target: [f64; 3],
    /// The world length the picture's height spans at the target's depth.
    pub height: f64,
    /// Light-line spacings across `height`.
    pub lines: f64,
}

impl View {
    /// A view of the bounding box `[lo, hi]` before the page gives its
    /// own: the box's centre, its largest side across the height,
    /// [`DEFAULT_LINES`] lines.
    pub fn of_box(lo: [f64; 3], hi: [f64; 3]) -> View {
        let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        View {
            target: [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k])),
            height: if size > 0.0 { size } else { 1.0 },
            lines: DEFAULT_LINES,
        }
    }

    /// `Err` unless the target is finite and the height and line count
    /// positive and finite.
    pub fn check(&self) -> Result<(), String> {
        if !self.target.iter().all(|c| c.is_finite()) {
            return Err(format!("view target {:?}: not finite", self.target));
        }
        if !(self.height > 0.0 && self.height.is_finite()) {
            return Err(format!("view height {}: positive and finite", self.height));
        }
        if !(self.lines > 0.0 && self.lines.is_finite()) {
            return Err(format!("lines {}: positive and finite", self.lines));
        }
        Ok(())
    }
}

/// The light lines for a surface of bounding box `[lo, hi]` with `up` the
/// axis shown upward, seen in `view`. For `z` up: the light plane
/// `z = hi_z + size` (`size` the box's largest side: a box size above the
/// top face), lines along `y` repeated along `x` every
/// `view.height / view.lines`, line 0 above the target; for `y` up the
/// same lines turned with the model (`z` up's `x, y, z` are `y` up's
/// `x, −z, y`): the plane a box size above the top face along `+y`, lines
/// along `−z`. A flat region facing the light, seen from the light's side,
/// thus shows `view.lines` stripes across the picture's height at any zoom,
/// and a zoom about the target leaves them where they are on the screen.
pub fn lines(lo: [f64; 3], hi: [f64; 3], up: Up, view: &View) -> Option<HighlightLines> {
    let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    // A world point in z up's coordinates, and back.
    type Map = fn([f64; 3]) -> [f64; 3];
    let (to_z_up, to_world): (Map, Map) = match up {
        Up::Z => (|v| v, |v| v),
        Up::Y => (|v| [v[0], -v[2], v[1]], |v| [v[0], v[2], -v[1]]),
    };
    let t = to_z_up(view.target);
    let top = to_z_up(hi)[2];
    HighlightLines::new(
        to_world([t[0], t[1], top + size]),
        to_world([0.0, 1.0, 0.0]),
        to_world([1.0, 0.0, 0.0]),
        view.height / view.lines,
    )
}

/// The highlight parameter of vertex `i` under `mode` ([`NO_LINE`] outside
/// the highlight shading, without lines, where the normal does not exist or
/// its line misses the light plane).
fn stripe(surface: &Surface, i: usize, mode: Mode, lines: Option<&HighlightLines>) -> f32 {
    match (mode, lines) {
        (Mode::Highlight, Some(l)) if surface.flags[i] & DEGENERATE == 0 => l
            .parameter(surface.position[i], surface.normal[i])
            .map_or(NO_LINE, |s| s as f32),
        _ => NO_LINE,
    }
}

/// Rewrites only the highlight parameters of `out` (all vertices; `out`
/// already painted for `surface`): the cheap update when the light lines
/// move with the view.
pub fn restripe(surface: &Surface, mode: Mode, lines: Option<&HighlightLines>, out: &mut Paint) {
    out.stripes.resize(surface.len(), NO_LINE);
    for (i, s) in out.stripes.iter_mut().enumerate() {
        *s = stripe(surface, i, mode, lines);
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
        out.stripes[i] = stripe(surface, i, mode, lines);
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
        let view = View::of_box(s.lo, s.hi);
        let l = lines(s.lo, s.hi, Up::Z, &view).unwrap();
        let mut p = Paint::default();
        paint(&s, Mode::Highlight, 1.0, Some(&l), &mut p);
        for i in 0..2 {
            let want = l.parameter(s.position[i], s.normal[i]).unwrap() as f32;
            assert_eq!(p.stripes[i], want);
        }
        assert_eq!(p.stripes[2], NO_LINE);
        assert!(p.colors.chunks(4).all(|c| c[..3] == BASE_COLOUR));
        // Re-striping alone gives what a full paint gives.
        let l2 = lines(s.lo, s.hi, Up::Z, &View { lines: 3.0, ..view }).unwrap();
        let mut q = p.clone();
        restripe(&s, Mode::Highlight, Some(&l2), &mut q);
        paint(&s, Mode::Highlight, 1.0, Some(&l2), &mut p);
        assert_eq!(q.stripes, p.stripes);
        restripe(&s, Mode::Plain, Some(&l2), &mut q);
        assert!(q.stripes.iter().all(|&t| t == NO_LINE));
    }

    /// The parameter of a flat region facing the light (normal `up`) at
    /// `p`.
    fn flat(l: &HighlightLines, p: [f64; 3], up: Up) -> f64 {
        let n = match up {
            Up::Z => [0.0, 0.0, 1.0],
            Up::Y => [0.0, 1.0, 0.0],
        };
        l.parameter(p, n).unwrap()
    }

    #[test]
    fn the_lines_are_spaced_relative_to_the_view() {
        // A box of size 3, seen with 2 or 0.2 units across the picture's
        // height: on a flat region facing the light, `lines` spacings fit
        // in the visible height whatever the zoom; the line through the
        // target stays there; the box only places the plane.
        let (lo, hi) = ([0.0, 0.0, 0.0], [3.0, 1.0, 1.0]);
        for up in [Up::Z, Up::Y] {
            for (height, lines_across) in [(2.0, 10.0), (0.2, 10.0), (0.2, 4.0)] {
                let target = [1.2, 0.4, 0.7];
                let view = View {
                    target,
                    height,
                    lines: lines_across,
                };
                let l = lines(lo, hi, up, &view).unwrap();
                assert!(flat(&l, target, up).abs() < 1e-12);
                // The lines run along y (z up) or z (y up) and repeat
                // along x.
                let step = [height, 0.0, 0.0];
                let moved = |p: [f64; 3], d: [f64; 3]| [0, 1, 2].map(|k| p[k] + d[k]);
                let across = flat(&l, moved(target, step), up) - flat(&l, target, up);
                assert!((across.abs() - lines_across).abs() < 1e-9, "{across}");
                let along = [0.0, 0.5 * height, 0.5 * height];
                assert!((flat(&l, moved(target, along), up)).abs() < 1e-9);
            }
        }
        let bad = |v: View| v.check().is_err();
        let v = View::of_box(lo, hi);
        assert_eq!((v.height, v.lines), (3.0, DEFAULT_LINES));
        assert!(v.check().is_ok());
        assert!(bad(View { height: 0.0, ..v }));
        assert!(bad(View { lines: -1.0, ..v }));
        assert!(bad(View {
            lines: f64::INFINITY,
            ..v
        }));
        assert!(bad(View {
            target: [f64::NAN, 0.0, 0.0],
            ..v
        }));
    }

    #[test]
    fn modes_have_codes() {
        assert_eq!(Mode::from_code(0), Some(Mode::Plain));
        assert_eq!(Mode::from_code(3), Some(Mode::Mean));
        assert_eq!(Mode::from_code(4), None);
        assert_eq!(Mode::from_code(-1), None);
    }
}
