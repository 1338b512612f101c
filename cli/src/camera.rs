//! The pictures' camera: an orthographic view from azimuth and elevation
//! around an up axis (`z` or `y`), and the map from space to a panel's
//! (supersampled) pixels — fitted to everything drawn, or framed on a focus
//! point at a given radius.

use capdiv::Point3;

/// A point or direction: the coordinates of a `Point3<f64>`, whose
/// operations [`dot`](fn@dot), [`cross`](fn@cross) and [`unit`](fn@unit) apply to it.
pub type V3 = [f64; 3];

/// [`Point3::dot`] of two `V3`.
pub fn dot(a: V3, b: V3) -> f64 {
    Point3(a).dot(Point3(b))
}

/// [`Point3::cross`] of two `V3`.
pub fn cross(a: V3, b: V3) -> V3 {
    Point3(a).cross(Point3(b)).0
}

/// [`Point3::unit`] of a `V3`: `a` scaled to unit length, `None` when it is
/// zero or not finite.
pub fn unit(a: V3) -> Option<V3> {
    Point3(a).unit().map(|u| u.0)
}

/// The world axis that points up in a picture.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Up {
    /// `+z` up; azimuth measured in the xy-plane from `+x` towards `+y`.
    #[default]
    Z,
    /// `+y` up; azimuth measured in the zx-plane from `+x` towards `−z`
    /// (the z-up view turned so that its `z` becomes `y`).
    Y,
}

/// The region a zoomed picture frames: the shorter side of a panel spans
/// the sphere of `radius` about `centre`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Focus {
    /// The point at the panel's centre.
    pub centre: V3,
    /// Half the world length across the panel's shorter side.
    pub radius: f64,
}

/// Camera and size of one panel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Panel width in pixels.
    pub width: usize,
    /// Panel height in pixels.
    pub height: usize,
    /// Azimuth of the direction to the camera, degrees.
    pub azimuth: f64,
    /// Elevation above the plane normal to the up axis, degrees.
    pub elevation: f64,
    /// Tessellation segments per patch side.
    pub grid: usize,
    /// The up axis.
    pub up: Up,
    /// The framed region; `None`: everything drawn, fitted with a margin.
    pub focus: Option<Focus>,
}

impl Default for Camera {
    /// The command line's defaults: 800×600, view `-60,50`, grid 6, z up,
    /// everything in view.
    fn default() -> Self {
        Camera {
            width: 800,
            height: 600,
            azimuth: -60.0,
            elevation: 50.0,
            grid: 6,
            up: Up::Z,
            focus: None,
        }
    }
}

/// The screen axes in space: `right`, `up` and `toward` (from the scene to
/// the camera), orthonormal and right-handed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Screen right.
    pub right: V3,
    /// Screen up.
    pub up: V3,
    /// Towards the camera.
    pub toward: V3,
}

impl Camera {
    /// The camera's frame.
    pub fn frame(&self) -> Frame {
        let (az, el) = (self.azimuth.to_radians(), self.elevation.to_radians());
        let toward = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
        let right = unit(cross([0.0, 0.0, 1.0], toward)).unwrap_or([1.0, 0.0, 0.0]);
        let up = cross(toward, right);
        // y up: the z-up frame turned by −90° about x, (x, y, z) → (x, z, −y).
        let turn = |v: V3| match self.up {
            Up::Z => v,
            Up::Y => [v[0], v[2], -v[1]],
        };
        Frame {
            right: turn(right),
            up: turn(up),
            toward: turn(toward),
        }
    }
}

/// How space maps to a panel of `w × h` (supersampled) pixels: `x` right,
/// `y` down, and a depth that grows towards the camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// The camera's frame.
    pub frame: Frame,
    /// Width in pixels.
    pub w: usize,
    /// Height in pixels.
    pub h: usize,
    lo: [f64; 2],
    scale: f64,
    depth_mid: f64,
}

impl Fit {
    /// The fit of `cam` at `ss` pixels per picture pixel for a scene whose
    /// points are `points` (non-finite ones skipped): framed on the focus
    /// when there is one, else the union of the points' screen extents with a
    /// 4 % margin.
    pub fn new(cam: &Camera, ss: usize, points: impl Iterator<Item = V3>) -> Fit {
        let frame = cam.frame();
        let (w, h) = (cam.width.max(1) * ss, cam.height.max(1) * ss);
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in points {
            let s = [dot(p, frame.right), dot(p, frame.up), dot(p, frame.toward)];
            if s.iter().all(|c| c.is_finite()) {
                for k in 0..3 {
                    lo[k] = lo[k].min(s[k]);
                    hi[k] = hi[k].max(s[k]);
                }
            }
        }
        let depth_mid = if lo[2] <= hi[2] {
            0.5 * (lo[2] + hi[2])
        } else {
            0.0
        };
        let (wf, hf) = (w as f64, h as f64);
        let focus = cam
            .focus
            .filter(|f| f.radius > 0.0 && f.radius.is_finite())
            .filter(|f| f.centre.iter().all(|c| c.is_finite()));
        let (centre, scale) = match focus {
            Some(f) => (
                [dot(f.centre, frame.right), dot(f.centre, frame.up)],
                wf.min(hf) / (2.0 * f.radius),
            ),
            None if lo[0] <= hi[0] => {
                let margin = 0.04 * wf.min(hf);
                let span = [(hi[0] - lo[0]).max(1e-300), (hi[1] - lo[1]).max(1e-300)];
                let scale = ((wf - 2.0 * margin) / span[0]).min((hf - 2.0 * margin) / span[1]);
                ([0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])], scale)
            }
            None => ([0.0, 0.0], 1.0),
        };
        Fit {
            frame,
            w,
            h,
            lo: [centre[0] - 0.5 * wf / scale, centre[1] - 0.5 * hf / scale],
            scale,
            depth_mid,
        }
    }

    /// Pixel coordinates (`x`, `y`) and depth of a point.
    pub fn screen(&self, p: V3) -> V3 {
        let f = &self.frame;
        [
            (dot(p, f.right) - self.lo[0]) * self.scale,
            self.h as f64 - (dot(p, f.up) - self.lo[1]) * self.scale,
            dot(p, f.toward),
        ]
    }

    /// The world length the panel's height spans.
    pub fn visible_height(&self) -> f64 {
        self.h as f64 / self.scale
    }

    /// The world point at the panel's centre, halfway through the scene's
    /// depth.
    pub fn centre(&self) -> V3 {
        let f = &self.frame;
        let r = self.lo[0] + 0.5 * self.w as f64 / self.scale;
        let u = self.lo[1] + 0.5 * self.h as f64 / self.scale;
        [0, 1, 2].map(|k| r * f.right[k] + u * f.up[k] + self.depth_mid * f.toward[k])
    }
}
