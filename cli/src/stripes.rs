//! Highlight lines that stay readable at any size: the family of light
//! lines is set up relative to the view, and the stripe profile is
//! averaged over each sample's footprint (anti-aliasing).
//!
//! - The light plane faces the direction `light` (default: the camera's,
//!   so the plane is a light box behind the viewer); its lines run along the
//!   screen's horizontal as seen in that plane (the screen's vertical when
//!   the light is along the horizontal); `lines` spacings fit in the
//!   panel's visible height, and the plane lies one visible height from the
//!   panel's centre. A flat region facing the light thus shows `lines`
//!   stripes across the panel's height whatever the object's size or zoom;
//!   curved regions show more.
//! - The stripe at parameter `s` ([`HighlightLines::parameter`]) is a
//!   triangle pulse, 1 on a line and 0 from [`STRIPE_WIDTH`] spacings away.
//!   Each sample shows the pulse averaged over `[s − f/2, s + f/2]`, `f` the
//!   change of `s` across one picture pixel there (its footprint, from the
//!   neighbouring samples), so stripes narrower than a pixel are drawn with
//!   their true share; and as the footprint nears half a period (stripes
//!   closer than 2 pixels, which no picture can resolve: near silhouettes,
//!   or a density too high for the size) the stripes fade to their mean,
//!   [`STRIPE_WIDTH`], instead of folding into moiré.

use crate::camera::{cross, dot, unit, Fit, V3};
use capdiv_mesh::shade::HighlightLines;

pub use capdiv_mesh::shade::DEFAULT_LINES;

/// Half-width of a stripe's pulse, in light-line spacings.
pub const STRIPE_WIDTH: f64 = 0.12;

/// The user's light-line options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightLines {
    /// Direction from the scene towards the light plane (any length);
    /// `None`: towards the camera.
    pub direction: Option<V3>,
    /// Light-line spacings across the panel's visible height.
    pub lines: f64,
}

impl Default for LightLines {
    fn default() -> Self {
        LightLines {
            direction: None,
            lines: DEFAULT_LINES,
        }
    }
}

/// The light-line family of `opts` for a panel mapped by `fit`; `None` when
/// the direction is zero or the density not positive and finite.
pub fn family(opts: &LightLines, fit: &Fit) -> Option<HighlightLines> {
    if !(opts.lines > 0.0 && opts.lines.is_finite()) {
        return None;
    }
    let f = &fit.frame;
    let l = unit(opts.direction.unwrap_or(f.toward))?;
    // A screen axis's part in the light plane, if it has one.
    let along = |a: V3| {
        let p = [0, 1, 2].map(|k| a[k] - dot(a, l) * l[k]);
        (dot(p, p) > 1e-12).then(|| unit(p)).flatten()
    };
    let e = along(f.right).or_else(|| along(f.up))?;
    let height = fit.visible_height();
    let c = fit.centre();
    let origin = [0, 1, 2].map(|k| c[k] + height * l[k]);
    HighlightLines::new(origin, e, cross(l, e), height / opts.lines)
}

/// The stripe pulse at `s`: 1 on an integer, falling linearly to 0 at
/// `width` (at most ½) from it.
pub fn pulse(s: f64, width: f64) -> f64 {
    let d = (s - s.round()).abs();
    (1.0 - d / width).max(0.0)
}

/// `∫₀ˣ pulse`.
fn integral(x: f64, w: f64) -> f64 {
    let k = x.floor();
    let y = x - k;
    let part = if y < w {
        y - y * y / (2.0 * w)
    } else if y <= 1.0 - w {
        0.5 * w
    } else {
        let r = 1.0 - y;
        w - (r - r * r / (2.0 * w))
    };
    k * w + part
}

/// Footprints (in periods) from which the stripes fade to their mean, and
/// at which they are gone: a period of 2.9 pixels, and of 2 (Nyquist).
pub const FADE: [f64; 2] = [0.35, 0.5];

/// The pulse averaged over `[s − f/2, s + f/2]` (`f` the footprint of one
/// pixel), blended into its mean `width` as `f` goes through [`FADE`]:
/// [`pulse`] for a zero footprint, exactly `width` from half a period on.
pub fn filtered(s: f64, footprint: f64, width: f64) -> f64 {
    let w = width.clamp(1e-6, 0.5);
    let f = footprint.abs();
    if !s.is_finite() || !f.is_finite() || f >= FADE[1] || s.abs() > 1e12 {
        return w;
    }
    let boxed = if f < 1e-9 {
        pulse(s, w)
    } else {
        ((integral(s + 0.5 * f, w) - integral(s - 0.5 * f, w)) / f).clamp(0.0, 1.0)
    };
    let t = ((f - FADE[0]) / (FADE[1] - FADE[0])).clamp(0.0, 1.0);
    let t = t * t * (3.0 - 2.0 * t);
    boxed + t * (w - boxed)
}

/// Stripe intensity of every sample of a row-major grid `w` wide with `ss`
/// samples per picture pixel along each side, from each sample's parameter
/// (`None`: no stripe there, intensity 0). The footprint is `ss` times the
/// length of the parameter's change per sample: in `x` the smaller change
/// to the left or right neighbour, in `y` to the one above or below
/// (one-sided where a neighbour has none, and the smaller of two, so that
/// silhouettes do not blur). The error when the intensities cannot be
/// allocated.
pub fn intensities(
    params: &[Option<f64>],
    w: usize,
    ss: usize,
) -> Result<Vec<f64>, capdiv_mesh::OutOfMemory> {
    let h = params.len().checked_div(w).unwrap_or(0);
    let at = |x: isize, y: isize| -> Option<f64> {
        if x < 0 || y < 0 || x as usize >= w || y as usize >= h {
            return None;
        }
        params[y as usize * w + x as usize]
    };
    let change = |s: f64, a: Option<f64>, b: Option<f64>| {
        [a, b]
            .into_iter()
            .flatten()
            .map(|t| (t - s).abs())
            .fold(None, |m: Option<f64>, d| Some(m.map_or(d, |m| m.min(d))))
            .unwrap_or(0.0)
    };
    capdiv_mesh::mem::collect(params.iter().enumerate().map(|(k, p)| {
        let Some(s) = *p else { return 0.0 };
        let (x, y) = ((k % w) as isize, (k / w) as isize);
        let fx = change(s, at(x - 1, y), at(x + 1, y));
        let fy = change(s, at(x, y - 1), at(x, y + 1));
        filtered(s, ss as f64 * fx.hypot(fy), STRIPE_WIDTH)
    }))
}
