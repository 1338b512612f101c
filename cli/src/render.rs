//! PNG preview of a [`Tessellation`], rasterised by [`crate::raster`]
//! (orthographic view from above at an angle, z-buffer, per-pixel Lambert
//! shading of the interpolated normals, 2×2 supersampling), encoded with the
//! `png` crate.
//!
//! Faces are coloured by their tag (the level of their patch), alternating
//! warm (even levels, [`EVEN`]) and cool (odd levels, [`ODD`]), so the rings of the
//! subdivision show; the back side is grey. A legend in the bottom margin
//! says so ([`RING_LEGEND`]). Patch boundaries are drawn as thin dark lines
//! where the caller gives each vertex's patch parameters and a patch is
//! large enough on screen (more than [`MIN_LINE_PATCH`] pixels). Only for
//! looking at results: no claim of accuracy.

use crate::camera::{cross, dot, unit, Camera, Up, V3};
use crate::raster::{area, downsample, drawable, ZBuffer};
use crate::Scalar;
use capdiv_mesh::tessellate::{Face, Tessellation};
use capdiv_mesh::{mem, OutOfMemory};

/// Camera and image size.
#[derive(Clone, Copy, Debug)]
pub struct View {
    /// Image width in pixels.
    pub width: usize,
    /// Image height in pixels.
    pub height: usize,
    /// Direction to the camera around the up axis, degrees.
    pub azimuth: f64,
    /// Height of the camera above the plane normal to the up axis, degrees.
    pub elevation: f64,
    /// The up axis ([`crate::camera::Camera::frame`]).
    pub up: Up,
}

impl Default for View {
    fn default() -> Self {
        View {
            width: 800,
            height: 600,
            azimuth: -60.0,
            elevation: 50.0,
            up: Up::Z,
        }
    }
}

/// Albedo of even ring levels.
pub const EVEN: [u8; 3] = [235, 150, 90];
/// Albedo of odd ring levels.
pub const ODD: [u8; 3] = [95, 155, 215];
/// The legend's texts after the [`EVEN`] and [`ODD`] swatches, and the
/// last one.
pub const RING_LEGEND: [&str; 3] = [
    "even ring level",
    "odd ring level",
    "(a cap's rings alternate)  grey: back side",
];

/// An RGB image, 8 bits per channel, rows top to bottom.
#[derive(Clone, Debug)]
pub struct Image {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// `3·width·height` bytes.
    pub rgb: Vec<u8>,
}

/// Patches narrower than this many (output) pixels get no boundary lines.
pub const MIN_LINE_PATCH: f64 = 8.0;

/// Background colour.
pub const BACKGROUND: [u8; 3] = [246, 246, 246];

/// Renders `mesh` as seen from `view`; with `params`, per vertex the
/// parameters `(u, v)` of its patch, patch boundaries are drawn. The error
/// when a buffer (per vertex of `mesh`, or per supersample of the image)
/// cannot be allocated.
pub fn render<R: Scalar>(
    mesh: &Tessellation<R>,
    params: Option<&[[f64; 2]]>,
    view: &View,
) -> Result<Image, OutOfMemory> {
    const SS: usize = 2;
    let (w, h) = (view.width.max(1) * SS, view.height.max(1) * SS);
    // `toward`: from the scene to the camera; `right`, `up`: screen axes.
    let frame = Camera {
        azimuth: view.azimuth,
        elevation: view.elevation,
        up: view.up,
        ..Camera::default()
    }
    .frame();
    let (right, up, toward) = (frame.right, frame.up, frame.toward);
    let light = unit([
        toward[0] + 0.4 * right[0] + 0.6 * up[0],
        toward[1] + 0.4 * right[1] + 0.6 * up[1],
        toward[2] + 0.4 * right[2] + 0.6 * up[2],
    ])
    .unwrap_or(toward);

    let pos: Vec<V3> = mem::collect(mesh.positions.iter().map(|p| p.0.map(|c| c.to_f64())))?;
    let nrm: Vec<V3> = mem::collect(mesh.normals.iter().map(|p| p.0.map(|c| c.to_f64())))?;
    // Screen coordinates before fitting, and depth (larger = nearer).
    let proj: Vec<V3> = mem::collect(
        pos.iter()
            .map(|&p| [dot(p, right), dot(p, up), dot(p, toward)]),
    )?;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in proj.iter().filter(|p| p.iter().all(|c| c.is_finite())) {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let margin = 0.05 * w.min(h) as f64;
    let span = [(hi[0] - lo[0]).max(1e-300), (hi[1] - lo[1]).max(1e-300)];
    let scale = ((w as f64 - 2.0 * margin) / span[0]).min((h as f64 - 2.0 * margin) / span[1]);
    let off = [
        0.5 * (w as f64 - scale * span[0]),
        0.5 * (h as f64 - scale * span[1]),
    ];
    let screen: Vec<V3> = mem::collect(proj.iter().map(|p| {
        [
            off[0] + (p[0] - lo[0]) * scale,
            h as f64 - (off[1] + (p[1] - lo[1]) * scale),
            p[2],
        ]
    }))?;

    let mut z = ZBuffer::new(w, h)?;
    let mut color = mem::filled(w * h, BACKGROUND.map(f64::from))?;
    for (f, &tag) in mesh.faces.iter().zip(&mesh.tags) {
        let base = if tag % 2 == 0 { EVEN } else { ODD }.map(f64::from);
        let tris = match *f {
            Face::Tri(t) => [Some(t), None],
            Face::Quad(q) => [Some([q[0], q[1], q[2]]), Some([q[0], q[2], q[3]])],
        };
        for tri in tris.into_iter().flatten() {
            let tri = tri.map(|i| i as usize);
            let sub = |a: V3, b: V3| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
            let face = unit(cross(
                sub(pos[tri[1]], pos[tri[0]]),
                sub(pos[tri[2]], pos[tri[0]]),
            ));
            let Some(face) = face else { continue };
            let s = tri.map(|i| screen[i]);
            if !drawable(&s) {
                continue;
            }
            let area = area(&s);
            // Screen-space gradients of u and v (constant on the triangle),
            // for boundary lines of constant width in pixels.
            let uv = tri.map(|i| params.and_then(|p| p.get(i)).copied().unwrap_or([0.5; 2]));
            let grad = |c: usize| {
                let (d1, d2) = (uv[1][c] - uv[0][c], uv[2][c] - uv[0][c]);
                let gx = (d1 * (s[2][1] - s[0][1]) - d2 * (s[1][1] - s[0][1])) / area;
                let gy = (d2 * (s[1][0] - s[0][0]) - d1 * (s[2][0] - s[0][0])) / area;
                (gx * gx + gy * gy).sqrt()
            };
            let (gu, gv) = (grad(0), grad(1));
            z.triangle(s, 0.0, |k, l| {
                let mut n = [0.0; 3];
                for (c, &i) in l.iter().zip(&tri) {
                    for d in 0..3 {
                        n[d] += c * nrm[i][d];
                    }
                }
                let mut n = unit(n).unwrap_or(face);
                let front = dot(face, toward) >= 0.0;
                if dot(n, toward) < 0.0 {
                    n = n.map(|c| -c);
                }
                let shade = 0.25 + 0.75 * dot(n, light).max(0.0);
                let albedo = if front { base } else { [170.0, 170.0, 170.0] };
                // Distance to the patch boundary in (supersampled) pixels.
                let (u, v) = (
                    l[0] * uv[0][0] + l[1] * uv[1][0] + l[2] * uv[2][0],
                    l[0] * uv[0][1] + l[1] * uv[1][1] + l[2] * uv[2][1],
                );
                let line = |t: f64, g: f64| {
                    g > 0.0
                        && 1.0 / g > MIN_LINE_PATCH * SS as f64
                        && t.min(1.0 - t) / g < 0.6 * SS as f64
                };
                let ink = if line(u, gu) || line(v, gv) {
                    0.45
                } else {
                    1.0
                };
                color[k] = albedo.map(|c| c * shade * ink);
            });
        }
    }

    let (ow, oh) = (w / SS, h / SS);
    let rgb = downsample(&color, w, ow, oh, SS)?;
    let mut image = Image {
        width: ow,
        height: oh,
        rgb,
    };
    ring_legend(&mut image);
    Ok(image)
}

/// The ring colours' legend along the bottom margin: a swatch and a text per
/// colour, then [`RING_LEGEND`]'s last text.
fn ring_legend(image: &mut Image) {
    let (w, h) = (image.width, image.height);
    let y = h.saturating_sub(14);
    let ink = [60, 60, 60];
    let mut x = 8;
    for (colour, label) in [(EVEN, RING_LEGEND[0]), (ODD, RING_LEGEND[1])] {
        for py in y..(y + 8).min(h) {
            for px in x..(x + 12).min(w) {
                let k = 3 * (py * w + px);
                image.rgb[k..k + 3].copy_from_slice(&colour);
            }
        }
        crate::glyphs::text(&mut image.rgb, w, h, (x + 16, y), label, 1, ink);
        x += 16 + 8 * label.len() + 16;
    }
    crate::glyphs::text(&mut image.rgb, w, h, (x, y), RING_LEGEND[2], 1, ink);
}

/// PNG bytes of an image.
pub fn encode_png(image: &Image) -> Result<Vec<u8>, png::EncodingError> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, image.width as u32, image.height as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header()?;
        writer.write_image_data(&image.rgb)?;
        writer.finish()?;
    }
    Ok(out)
}
