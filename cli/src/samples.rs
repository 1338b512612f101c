//! Sample polar configurations for `capdiv demo`: points of an analytic
//! surface `z = f(x, y)` over concentric circles.
//!
//! Link `i` (1-based) samples the circle of radius `i·h` at the angles
//! `τ_j = j/n` (counter-clockwise seen from +z, so the surface normal
//! `∂r × ∂τ` points up); the pole is `(0, 0, f(0, 0))`. The analytic
//! curvatures at the origin are those of the sampled surface with the upward
//! normal: `K = f_xx f_yy − f_xy²`, `H = (f_xx + f_yy)/2` (the gradient vanishes
//! there).
//!
//! What the C²PS limit reproduces (docs/math/c2ps.md §4, `p3 = A − q00`,
//! `p4 = 3 C2`): the rotationally symmetric part `x² + y²` exactly, so a
//! sampled paraboloid has the analytic curvature at the pole; the `cos 2τ` part
//! of the 1-link enters with the factor 3/2 (`C2` of `h² cos 2τ` is `h²/2`), so
//! a sampled saddle `x² − y²` limits to `1.5 (x² − y²)`: `K` is 2.25× the
//! sampled surface's. Control points on a surface are not points of the limit.

//!
//! EG samples ([`eg_samples`]): c-nets (docs/math/eg.md §1) of valence 3 and 5,
//! node `(x, y)` of sector `s` placed at `h (x u_s + y u_{s+1})` in the plane,
//! `u_s = (cos 2πs/n, sin 2πs/n)` (sectors counter-clockwise seen from +z),
//! lifted to `z = f(x, y)`; the center is `(0, 0, f(0, 0))`.

use crate::input::{CnetInput, PolarInput};
use std::f64::consts::TAU;

/// Curvatures of the sampled surface at the origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Analytic {
    /// Gaussian curvature.
    pub gaussian: f64,
    /// Mean curvature (upward normal).
    pub mean: f64,
}

/// A named sample for the demo.
#[derive(Clone, Debug)]
pub struct Sample {
    /// File stem and label.
    pub name: &'static str,
    /// The surface in words.
    pub surface: &'static str,
    /// The level-0 configuration.
    pub input: PolarInput,
    /// Ring depth the demo refines to.
    pub depth: u32,
    /// Curvatures of the sampled surface at the pole.
    pub analytic: Analytic,
    /// What to expect of the comparison.
    pub note: &'static str,
}

/// Samples `f` on `links` circles of radius `i·h`, `n` points each.
pub fn sample_surface(n: usize, links: usize, h: f64, f: impl Fn(f64, f64) -> f64) -> PolarInput {
    let links = (1..=links)
        .map(|i| {
            let r = i as f64 * h;
            (0..n)
                .map(|j| {
                    let t = TAU * j as f64 / n as f64;
                    let (x, y) = (r * t.cos(), r * t.sin());
                    [x, y, f(x, y)]
                })
                .collect()
        })
        .collect();
    PolarInput {
        pole: [0.0, 0.0, f(0.0, 0.0)],
        links,
    }
}

/// The demo's samples: a convex paraboloid, a saddle, and a sphere cap of
/// valence 48.
pub fn demo_samples() -> Vec<Sample> {
    let radius = 2.0f64;
    vec![
        Sample {
            name: "paraboloid",
            surface: "z = (x^2 + y^2)/2",
            input: sample_surface(6, 7, 0.25, |x, y| 0.5 * (x * x + y * y)),
            depth: 6,
            analytic: Analytic {
                gaussian: 1.0,
                mean: 1.0,
            },
            note: "rotationally symmetric quadratic: reproduced exactly (docs/math/c2ps.md §4)",
        },
        Sample {
            name: "saddle",
            surface: "z = (x^2 - y^2)/2",
            input: sample_surface(8, 5, 0.25, |x, y| 0.5 * (x * x - y * y)),
            depth: 6,
            analytic: Analytic {
                gaussian: -1.0,
                mean: 0.0,
            },
            note: "expected: the cos 2t part of link 1 enters as p4 = 3 C2, so the limit \
                   near the pole is 1.5 z and K = 2.25 x the sampled surface's",
        },
        Sample {
            name: "sphere-n48",
            surface: "sphere cap of radius 2, z = 2 - sqrt(4 - x^2 - y^2)",
            input: sample_surface(48, 8, 0.2, move |x, y| {
                radius - (radius * radius - x * x - y * y).sqrt()
            }),
            depth: 4,
            analytic: Analytic {
                gaussian: 1.0 / (radius * radius),
                mean: 1.0 / radius,
            },
            note: "not quadratic: p3 = z(h) gives curvature 2 z(h)/h^2 = 1/R + O(h^2)",
        },
    ]
}

/// A named EG sample for the demo: a c-net around an extraordinary node.
#[derive(Clone, Debug)]
pub struct EgSample {
    /// File stem and label.
    pub name: &'static str,
    /// The surface in words.
    pub surface: &'static str,
    /// The level-0 c-net.
    pub input: CnetInput,
    /// Steps the demo takes (rings of levels 1..=depth).
    pub depth: u32,
    /// What to expect.
    pub note: &'static str,
}

/// The c-net of valence `n` sampling `f` (module docs), node spacing `h`.
pub fn sample_cnet(n: usize, h: f64, f: impl Fn(f64, f64) -> f64) -> CnetInput {
    let spoke = |s: usize| {
        let t = TAU * s as f64 / n as f64;
        (t.cos(), t.sin())
    };
    let sectors = (0..n)
        .map(|s| {
            let (a, b) = (spoke(s), spoke(s + 1));
            // §1 order: (1,0) (2,0) (1,1) (2,1) (1,2) (2,2).
            [(1, 0), (2, 0), (1, 1), (2, 1), (1, 2), (2, 2)].map(|(x, y)| {
                let (x, y) = (f64::from(x), f64::from(y));
                let (px, py) = (h * (x * a.0 + y * b.0), h * (x * a.1 + y * b.1));
                [px, py, f(px, py)]
            })
        })
        .collect();
    CnetInput {
        center: [0.0, 0.0, f(0.0, 0.0)],
        sectors,
    }
}

/// The demo's EG samples: a monkey saddle around a valence-3 node and a
/// paraboloid with a ripple around a valence-5 node.
pub fn eg_samples() -> Vec<EgSample> {
    vec![
        EgSample {
            name: "eg-n3",
            surface: "monkey saddle z = (x^3 - 3xy^2)/4 over a valence-3 c-net",
            input: sample_cnet(3, 0.5, |x, y| 0.25 * (x * x * x - 3.0 * x * y * y)),
            depth: 8,
            note: "cos 3t: spoke nodes at +1/32, diagonal nodes at -1/32; (3) weighs them 1/6 and 5/96: c0 z = 11/1024",
        },
        EgSample {
            name: "eg-n5",
            surface: "z = (x^2 + y^2)/2 + x y^2/4 over a valence-5 c-net",
            input: sample_cnet(5, 0.5, |x, y| 0.5 * (x * x + y * y) + 0.25 * x * y * y),
            depth: 8,
            note: "c0 by (3) averages the nodes around the center: above the sampled f(0,0) = 0",
        },
    ]
}

/// The papers' kinds of test nets, built in code and read by
/// `render`, `compare` and `curvature` as `sample:NAME`:
///
/// - `c2ps-convex-n20`: a convex polar configuration of valence 20 (as in
///   C²PS Fig. 4), the paraboloid `z = (x² + y²)/2` sampled on 5 links of
///   spacing 0.2 (analytic K = H = 1 at the pole, reproduced by C²PS);
/// - `c2ps-saddle-n8`: the saddle `z = (x² − y²)/2`, valence 8, 5 links of
///   spacing 0.25 (C²PS limit `1.5 (x² − y²)`: K = −2.25, H = 0);
/// - `eg-convex-n3`, `eg-convex-n5`: c-nets of `z = (x² + y²)/2`, spacing
///   0.5;
/// - `eg-saddle-n3`, `eg-saddle-n5`: c-nets of `z = (x² − y²)/2` rotated so
///   that no spoke is an axis of symmetry (`x, y` turned by 0.3 rad).
pub fn shape_samples() -> Vec<(&'static str, crate::input::Input)> {
    use crate::input::Input;
    let convex = |x: f64, y: f64| 0.5 * (x * x + y * y);
    let saddle = |x: f64, y: f64| {
        let (s, c) = 0.3f64.sin_cos();
        let (a, b) = (c * x - s * y, s * x + c * y);
        0.5 * (a * a - b * b)
    };
    vec![
        (
            "c2ps-convex-n20",
            Input::Polar(sample_surface(20, 5, 0.2, convex)),
        ),
        (
            "c2ps-saddle-n8",
            Input::Polar(sample_surface(8, 5, 0.25, |x, y| 0.5 * (x * x - y * y))),
        ),
        ("eg-convex-n3", Input::Cnet(sample_cnet(3, 0.5, convex))),
        ("eg-convex-n5", Input::Cnet(sample_cnet(5, 0.5, convex))),
        ("eg-saddle-n3", Input::Cnet(sample_cnet(3, 0.5, saddle))),
        ("eg-saddle-n5", Input::Cnet(sample_cnet(5, 0.5, saddle))),
    ]
}
