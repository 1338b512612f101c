//! The pictures' one triangle rasteriser: screen-space triangles into a
//! z-buffer, pixel centres `(x + ½, y + ½)`, larger depth nearer. It only
//! decides which triangle each pixel sees and where in it (barycentric
//! coordinates); what the pixel shows is the caller's (Lambert shading of
//! interpolated normals in [`crate::render`], the exact patch geometry in
//! [`crate::picture`]).

use capdiv_mesh::{mem, OutOfMemory};

/// A screen point: `x`, `y` in pixels (`y` down), depth (larger = nearer).
pub type Screen = [f64; 3];

/// A z-buffer of `w × h` pixels.
pub struct ZBuffer {
    w: usize,
    h: usize,
    depth: Vec<f64>,
}

impl ZBuffer {
    /// An empty buffer: every pixel infinitely far; the error when its
    /// `8·w·h` bytes cannot be allocated.
    pub fn new(w: usize, h: usize) -> Result<Self, OutOfMemory> {
        Ok(ZBuffer {
            w,
            h,
            depth: mem::filled(w.saturating_mul(h), f64::NEG_INFINITY)?,
        })
    }

    /// Draws triangle `s`: every pixel whose centre lies in it (or within
    /// `overlap` pixels outside it, measured relative to the triangle's
    /// size: barycentric coordinates down to `−overlap / max(1, √|area|)`)
    /// and whose interpolated depth is nearer than the pixel's so far takes
    /// that depth and is passed to `hit` with its index `y·w + x` and its
    /// barycentric coordinates. Nothing is drawn of a triangle that is not
    /// [`drawable`].
    pub fn triangle(&mut self, s: [Screen; 3], overlap: f64, mut hit: impl FnMut(usize, [f64; 3])) {
        if !drawable(&s) {
            return;
        }
        let area = area(&s);
        let eps = overlap / area.abs().sqrt().max(1.0);
        let xs = s.map(|p| p[0]);
        let ys = s.map(|p| p[1]);
        // One pixel beyond the box: the pixels an overlap reaches.
        let x0 = (xs.iter().cloned().fold(f64::INFINITY, f64::min) - 1.0).max(0.0) as usize;
        let x1 =
            ((xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max) + 1.0) as usize).min(self.w);
        let y0 = (ys.iter().cloned().fold(f64::INFINITY, f64::min) - 1.0).max(0.0) as usize;
        let y1 =
            ((ys.iter().cloned().fold(f64::NEG_INFINITY, f64::max) + 1.0) as usize).min(self.h);
        for y in y0..y1 {
            for x in x0..x1 {
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                let edge = |a: Screen, b: Screen| {
                    (b[0] - a[0]) * (py - a[1]) - (px - a[0]) * (b[1] - a[1])
                };
                let l = [
                    edge(s[1], s[2]) / area,
                    edge(s[2], s[0]) / area,
                    edge(s[0], s[1]) / area,
                ];
                if l.iter().any(|&c| c < -eps) {
                    continue;
                }
                let z = l[0] * s[0][2] + l[1] * s[1][2] + l[2] * s[2][2];
                let k = y * self.w + x;
                if z <= self.depth[k] {
                    continue;
                }
                self.depth[k] = z;
                hit(k, l);
            }
        }
    }
}

/// Twice the signed area of a screen triangle (positive when it turns
/// clockwise on screen, i.e. counter-clockwise with `y` up).
pub fn area(s: &[Screen; 3]) -> f64 {
    (s[1][0] - s[0][0]) * (s[2][1] - s[0][1]) - (s[2][0] - s[0][0]) * (s[1][1] - s[0][1])
}

/// Whether a screen triangle is drawn: finite coordinates and an [`area`]
/// of at least `1e-12` square pixels.
pub fn drawable(s: &[Screen; 3]) -> bool {
    let a = area(s);
    s.iter().flatten().all(|c| c.is_finite()) && a.is_finite() && a.abs() >= 1e-12
}

/// The mean of each `ss × ss` block of the top left `(w·ss) × (h·ss)`
/// pixels of a supersampled colour buffer `stride` pixels wide, rounded to 8
/// bits: `3·w·h` bytes, rows top to bottom (or the error when they cannot
/// be allocated).
pub fn downsample(
    color: &[[f64; 3]],
    stride: usize,
    w: usize,
    h: usize,
    ss: usize,
) -> Result<Vec<u8>, OutOfMemory> {
    let mut rgb = mem::with_capacity(w.saturating_mul(h).saturating_mul(3))?;
    for y in 0..h {
        for x in 0..w {
            let mut acc = [0.0; 3];
            for dy in 0..ss {
                for dx in 0..ss {
                    let c = color[(y * ss + dy) * stride + x * ss + dx];
                    for d in 0..3 {
                        acc[d] += c[d];
                    }
                }
            }
            rgb.extend(acc.map(|c| (c / (ss * ss) as f64).round().clamp(0.0, 255.0) as u8));
        }
    }
    Ok(rgb)
}
