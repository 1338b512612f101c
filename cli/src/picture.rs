//! Pictures of [`Shape`]s shaded per pixel from the exact patches:
//! `capdiv render` and `capdiv compare`.
//!
//! 1. Every patch is tessellated on a `grid × grid` parameter grid by
//!    `capdiv_mesh::tessellate`; each vertex carries (patch index, `u`,
//!    `v`). Hole edges get a fan of triangles to the cap's limit point,
//!    tagged as hole.
//! 2. The triangles are rasterised ([`crate::raster`]: orthographic camera of
//!    [`crate::camera`], z-buffer, 2×2 supersampling); a pixel keeps the
//!    patch index and the barycentric interpolation of `(u, v)`.
//! 3. Each covered pixel evaluates its patch's jet at `(u, v)`
//!    ([`capdiv_mesh::tessellate::PatchGeometry::jet`]): the exact normal
//!    for Lambert shading and highlight lines
//!    ([`capdiv_mesh::shade::HighlightLines`], set up and anti-aliased by
//!    [`crate::stripes`]), the exact `K`, `H` for the
//!    colour maps ([`capdiv_mesh::shade::diverging`], scale
//!    [`capdiv_mesh::shade::symmetric_scale`] of the 98th percentile of
//!    `|value|` over every panel, so `compare` panels share it). The
//!    tessellation only decides which patch a pixel sees.
//! 4. Hole pixels (the cap's unrefined centre) are hatched magenta/white;
//!    curvature maps get a colour bar with its `−m`, `0`, `+m` values and
//!    its sign convention ([`sign_convention`]) printed ([`crate::glyphs`]);
//!    several panels get a label each (the shape's, clipped to the panel).

use crate::camera::{dot, Fit, V3};
pub use crate::camera::{Camera, Focus, Up};
use crate::raster::{downsample, ZBuffer};
use crate::shape::{geometry_at, Shape};
pub use crate::stripes::LightLines;
use capdiv_mesh::shade::{diverging, symmetric_scale, HighlightLines};
use capdiv_mesh::tessellate::{try_tessellate, Face};
use capdiv_mesh::PatchRecord;
use capdiv_mesh::PatchUv;
use capdiv_mesh::{mem, OutOfMemory};

/// What is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shading {
    /// Lambert, rings in alternating colours.
    Plain,
    /// Highlight lines of this light.
    Highlight(LightLines),
    /// Gaussian curvature map.
    Gauss,
    /// Mean curvature map.
    Mean,
}

/// Background colour.
pub const BACKGROUND: [u8; 3] = [246, 246, 246];
/// The two colours of the hole hatch.
pub const HATCH: [[u8; 3]; 2] = [[200, 0, 160], [255, 255, 255]];
/// Height of the legend strip under a curvature map, pixels.
pub const LEGEND_HEIGHT: usize = 44;
/// Height of the label strip above each panel, pixels.
pub const LABEL_HEIGHT: usize = 20;

const SS: usize = 2;
const NO_PATCH: u32 = u32::MAX;
const HOLE: u32 = u32::MAX - 1;

/// A tessellation vertex: position, patch, parameters.
#[derive(Clone, Copy, Debug)]
struct Vert {
    p: V3,
    patch: u32,
    uv: [f64; 2],
}

/// The parameters given to a cap's limit point, outside every patch's
/// square: they mark the triangles of the hole fans.
const HOLE_UV: [f64; 2] = [-1.0, -1.0];

/// The shape's triangles, by `capdiv_mesh::tessellate` (`grid` segments per
/// patch side, hole edges fanned to the limit point), each corner with its
/// patch and parameters (its patch's own `(u, v)` as texture coordinates,
/// so the tessellation keeps every patch's vertices apart); the fans'
/// corners belong to [`HOLE`]. The error when the tessellation or the
/// triangle list cannot be allocated.
fn tessellate(shape: &Shape, grid: usize) -> Result<Vec<[Vert; 3]>, OutOfMemory> {
    let square = PatchUv {
        corners: [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        hole: HOLE_UV,
    };
    let patches = shape.patches.iter().enumerate().map(|(k, sp)| {
        let record = PatchRecord {
            uv: Some(square),
            ..sp.patch.clone()
        };
        (record, k as u32)
    });
    let t = try_tessellate(patches, grid, 0.0)?;
    // At most two triangles a face: the pushes stay within the reservation.
    let mut tris = mem::with_capacity(2 * t.faces.len())?;
    for (face, &patch) in t.faces.iter().zip(&t.tags) {
        let hole = face.corners().iter().any(|&v| t.uvs[v as usize] == HOLE_UV);
        let vert = |v: u32| Vert {
            p: t.positions[v as usize].0,
            patch: if hole { HOLE } else { patch },
            uv: t.uvs[v as usize],
        };
        match *face {
            Face::Tri([a, b, c]) => tris.push([vert(a), vert(b), vert(c)]),
            Face::Quad([a, b, c, d]) => {
                tris.push([vert(a), vert(b), vert(c)]);
                tris.push([vert(a), vert(c), vert(d)]);
            }
        }
    }
    Ok(tris)
}

/// What each supersample of a panel sees.
struct Hits {
    w: usize,
    patch: Vec<u32>,
    uv: Vec<[f64; 2]>,
}

/// Rasterises the shapes' tessellations into panels sharing one fit (the
/// union of their screen extents, or the camera's focus). The error when
/// a tessellation or a panel's buffers cannot be allocated.
fn rasterise(shapes: &[&Shape], cam: &Camera) -> Result<(Fit, Vec<Hits>), OutOfMemory> {
    let tris: Vec<Vec<[Vert; 3]>> = shapes
        .iter()
        .map(|s| tessellate(s, cam.grid))
        .collect::<Result<_, _>>()?;
    let fit = Fit::new(cam, SS, tris.iter().flatten().flatten().map(|v| v.p));
    let (w, h) = (fit.w, fit.h);
    let screen = |p: V3| fit.screen(p);
    let hits = tris
        .iter()
        .map(|list| {
            let mut z = ZBuffer::new(w, h)?;
            let mut hits = Hits {
                w,
                patch: mem::filled(w * h, NO_PATCH)?,
                uv: mem::filled(w * h, [0.0; 2])?,
            };
            for t in list {
                // A little overlap (1/8 supersample) closes rounding gaps between
                // the triangles of neighbouring patches.
                z.triangle(t.map(|v| screen(v.p)), 0.125, |k, l| {
                    hits.patch[k] = t[0].patch;
                    let uv = [
                        l[0] * t[0].uv[0] + l[1] * t[1].uv[0] + l[2] * t[2].uv[0],
                        l[0] * t[0].uv[1] + l[1] * t[1].uv[1] + l[2] * t[2].uv[1],
                    ];
                    hits.uv[k] = uv.map(|c| c.clamp(0.0, 1.0));
                });
            }
            Ok(hits)
        })
        .collect::<Result<_, _>>()?;
    Ok((fit, hits))
}

/// An RGB image, rows top to bottom.
#[derive(Clone, Debug)]
pub struct Picture {
    /// Width.
    pub width: usize,
    /// Height.
    pub height: usize,
    /// `3·width·height` bytes.
    pub rgb: Vec<u8>,
    /// The colour scale `m` of a curvature map (`[−m, m]`), if any.
    pub scale: Option<f64>,
    /// Per panel, how many supersamples show a patch (not the background
    /// or the hatched hole).
    pub patch_samples: Vec<usize>,
}

impl Picture {
    /// A picture of the background colour, or the error when its bytes
    /// cannot be allocated.
    fn new(width: usize, height: usize) -> Result<Self, OutOfMemory> {
        let pixels = width.saturating_mul(height);
        let mut rgb = mem::with_capacity(pixels.saturating_mul(3))?;
        for _ in 0..pixels {
            rgb.extend_from_slice(&BACKGROUND);
        }
        Ok(Picture {
            width,
            height,
            rgb,
            scale: None,
            patch_samples: Vec::new(),
        })
    }
    fn put(&mut self, x: usize, y: usize, c: [u8; 3]) {
        if x < self.width && y < self.height {
            let k = 3 * (y * self.width + x);
            self.rgb[k..k + 3].copy_from_slice(&c);
        }
    }
    /// Text in the 8×8 font at `(x, y)` (top left), `size` pixels per font
    /// pixel.
    pub fn text(&mut self, x: usize, y: usize, s: &str, size: usize, c: [u8; 3]) {
        let (w, h) = (self.width, self.height);
        crate::glyphs::text(&mut self.rgb, w, h, (x, y), s, size, c);
    }
}

/// The exact geometry one supersample sees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Surface point.
    pub point: V3,
    /// Unit normal `∂u × ∂v` normalised.
    pub normal: V3,
    /// Gaussian curvature.
    pub k: f64,
    /// Mean curvature.
    pub h: f64,
    /// Ring level of its patch.
    pub level: u32,
}

/// What every supersample of every panel sees: per panel, row-major
/// `(2·width) × (2·height)` entries, `None` for background, hole pixels and
/// degenerate points — the numbers the pictures are made of (or the error
/// when they cannot be allocated).
pub fn probe(shapes: &[&Shape], cam: &Camera) -> Result<Vec<Vec<Option<Sample>>>, OutOfMemory> {
    samples_of(shapes, &rasterise(shapes, cam)?.1)
}

fn samples_of(shapes: &[&Shape], hits: &[Hits]) -> Result<Vec<Vec<Option<Sample>>>, OutOfMemory> {
    hits.iter()
        .zip(shapes)
        .map(|(hit, shape)| {
            mem::collect(hit.patch.iter().zip(&hit.uv).map(|(&p, uv)| {
                let sp = shape.patches.get(p as usize)?;
                let (point, normal, k, h) = geometry_at(sp.geometry(), uv[0], uv[1])?;
                Some(Sample {
                    point,
                    normal,
                    k,
                    h,
                    level: sp.level,
                })
            }))
        })
        .collect()
}

/// The light lines a highlight picture of `shapes` seen by `cam` uses
/// ([`crate::stripes::family`] of the panels' fit), or the error when the
/// rasterisation that fits the panels cannot be allocated.
pub fn highlight_lines(
    shapes: &[&Shape],
    cam: &Camera,
    light: &LightLines,
) -> Result<Option<HighlightLines>, OutOfMemory> {
    Ok(crate::stripes::family(light, &rasterise(shapes, cam)?.0))
}

/// Draws `shapes` side by side, labelled when there are several (or
/// `labels` is set), with one colour scale and one view; the error when a
/// tessellation or a buffer of the picture (per supersample) cannot be
/// allocated.
pub fn draw(
    shapes: &[&Shape],
    cam: &Camera,
    shading: Shading,
    labels: bool,
) -> Result<Picture, OutOfMemory> {
    let (fit, hits) = rasterise(shapes, cam)?;
    let (right, up, toward) = (fit.frame.right, fit.frame.up, fit.frame.toward);
    let light = crate::camera::unit([0, 1, 2].map(|k| toward[k] + 0.4 * right[k] + 0.6 * up[k]))
        .unwrap_or(toward);
    let samples = samples_of(shapes, &hits)?;
    let value = |s: &Sample| match shading {
        Shading::Gauss => s.k,
        _ => s.h,
    };
    let scale = match shading {
        Shading::Gauss | Shading::Mean => {
            let all = mem::collect(samples.iter().flatten().flatten().map(value))?;
            Some(symmetric_scale(&all, 0.98))
        }
        _ => None,
    };
    // Per panel, each supersample's stripe intensity.
    let stripes: Vec<Vec<f64>> = match shading {
        Shading::Highlight(opts) => {
            let lines = crate::stripes::family(&opts, &fit);
            hits.iter()
                .zip(&samples)
                .map(|(hit, samples)| {
                    let params = mem::collect(
                        samples
                            .iter()
                            .map(|s| lines?.parameter(s.as_ref()?.point, s.as_ref()?.normal)),
                    )?;
                    crate::stripes::intensities(&params, hit.w, SS)
                })
                .collect::<Result<_, _>>()?
        }
        _ => Vec::new(),
    };
    let top = if labels || shapes.len() > 1 {
        LABEL_HEIGHT
    } else {
        0
    };
    let bottom = if scale.is_some() { LEGEND_HEIGHT } else { 0 };
    let gap = 8;
    let n = shapes.len().max(1);
    let width = n * cam.width + (n - 1) * gap;
    let mut pic = Picture::new(width, top + cam.height + bottom)?;
    pic.scale = scale;
    pic.patch_samples = hits
        .iter()
        .map(|h| {
            h.patch
                .iter()
                .filter(|&&p| p != NO_PATCH && p != HOLE)
                .count()
        })
        .collect();
    for (panel, (hit, samples)) in hits.iter().zip(&samples).enumerate() {
        let stripes = stripes.get(panel);
        let x0 = panel * (cam.width + gap);
        let color = mem::collect((0..hit.patch.len()).map(|k| {
            match (hit.patch[k], &samples[k]) {
                (NO_PATCH, _) => BACKGROUND.map(f64::from),
                (HOLE, _) => {
                    // Hatched by output pixel.
                    let (x, y) = ((k % hit.w) / SS, (k / hit.w) / SS);
                    HATCH[((x + y) / 3) % 2].map(f64::from)
                }
                (_, None) => [90.0, 90.0, 90.0],
                (_, Some(s)) => {
                    let mut nrm = s.normal;
                    if dot(nrm, toward) < 0.0 {
                        nrm = nrm.map(|c| -c);
                    }
                    let lambert = dot(nrm, light).max(0.0);
                    match shading {
                        Shading::Plain => {
                            let base = if s.level % 2 == 0 {
                                [235.0, 150.0, 90.0]
                            } else {
                                [95.0, 155.0, 215.0]
                            };
                            base.map(|c| c * (0.25 + 0.75 * lambert))
                        }
                        Shading::Highlight(_) => {
                            let i = stripes.map_or(0.0, |st| st[k]);
                            let g = 120.0 + 125.0 * lambert;
                            [g * (1.0 - i), g * (1.0 - i), g * (1.0 - 0.6 * i)]
                        }
                        Shading::Gauss | Shading::Mean => {
                            let m = scale.unwrap_or(1.0);
                            diverging(value(s) / m).map(|c| f64::from(c) * (0.6 + 0.4 * lambert))
                        }
                    }
                }
            }
        }))?;
        let rgb = downsample(&color, hit.w, cam.width, cam.height, SS)?;
        for (i, c) in rgb.chunks(3).enumerate() {
            let (x, y) = (i % cam.width.max(1), i / cam.width.max(1));
            pic.put(x0 + x, top + y, [c[0], c[1], c[2]]);
        }
        if top > 0 {
            // Clipped to the panel.
            let room = cam.width.saturating_sub(12) / 8;
            let label: String = shapes[panel].label.chars().take(room).collect();
            pic.text(x0 + 6, 4, &label, 1, [20, 20, 20]);
        }
    }
    if let Some(m) = scale {
        legend(&mut pic, top + cam.height, m, shading);
    }
    Ok(pic)
}

/// What the sign of a curvature map's value means, as its legend states it.
/// The normal is the patches' `∂u × ∂v`, which points out of a closed mesh
/// whose faces run counter-clockwise seen from outside; `H` is positive
/// where the surface bends towards that normal, so an outward unit sphere
/// has `H = −1` (and the paraboloid `z = (x² + y²)/2` with its normal up
/// `H = +1`). `K`'s sign does not depend on the normal.
pub fn sign_convention(shading: Shading) -> Option<&'static str> {
    match shading {
        Shading::Mean => {
            Some("H > 0: bends towards the normal (du x dv). Outward unit sphere: H = -1")
        }
        Shading::Gauss => Some("K > 0: dome or bowl, K < 0: saddle (either normal)"),
        _ => None,
    }
}

/// The colour bar under a curvature map: `−m … 0 … +m` with the numbers,
/// and the sign convention ([`sign_convention`]) below.
fn legend(pic: &mut Picture, y0: usize, m: f64, shading: Shading) {
    let (x0, x1) = (16usize, pic.width.saturating_sub(16).max(17));
    let bar = 10;
    for x in x0..x1 {
        let t = 2.0 * (x - x0) as f64 / (x1 - 1 - x0) as f64 - 1.0;
        let c = diverging(t);
        for y in y0 + 6..y0 + 6 + bar {
            pic.put(x, y, c);
        }
    }
    let name = match shading {
        Shading::Gauss => "K",
        _ => "H",
    };
    let ty = y0 + 6 + bar + 4;
    let ink = [20, 20, 20];
    let lo = format!("{:.3e}", -m);
    let hi = format!("{:.3e}", m);
    pic.text(x0, ty, &lo, 1, ink);
    let mid = (x0 + x1) / 2;
    pic.text(mid.saturating_sub(4), ty, "0", 1, ink);
    pic.text(x1.saturating_sub(8 * hi.len()), ty, &hi, 1, ink);
    let title = format!("{name} (clamped beyond)");
    pic.text(mid + 24, ty, &title, 1, ink);
    if let Some(rule) = sign_convention(shading) {
        pic.text(x0, ty + 12, rule, 1, ink);
    }
    // Tick marks at both ends and the middle.
    for x in [x0, mid, x1 - 1] {
        for y in y0 + 2..y0 + 6 {
            pic.put(x, y, ink);
        }
    }
}

/// PNG bytes of a picture.
pub fn png(pic: &Picture) -> Result<Vec<u8>, png::EncodingError> {
    crate::render::encode_png(&crate::render::Image {
        width: pic.width,
        height: pic.height,
        rgb: pic.rgb.clone(),
    })
}
