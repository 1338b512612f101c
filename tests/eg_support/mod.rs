//! Shared helpers of the EG kernel tests (docs/math/eg.md): random nets, the §1
//! frame change written independently of the kernel, and a second-order jet
//! evaluator for Bézier patches (the kernel's evaluator stops at first order).
#![allow(dead_code)]

use capdiv::bezier::TensorPatch;
use capdiv::Point3;

/// A deterministic xorshift generator (tests that are not proptests).
pub struct Rng(pub u64);
impl Rng {
    pub fn next_f64(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [-a, a].
    pub fn sym(&mut self, a: f64) -> f64 {
        a * (2.0 * self.next_f64() - 1.0)
    }
    pub fn point(&mut self, a: f64) -> [f64; 3] {
        [self.sym(a), self.sym(a), self.sym(a)]
    }
}

/// An extended c-net (the EG paper's §7: "a c-net extended by one ring
/// of quads"): center and, per sector, the points `(x, y)`, `x ∈ 1..=3`,
/// `y ∈ 0..=3`, stored `pts[s][x−1][y]`.
#[derive(Clone, Debug)]
pub struct ExtNet {
    pub n: usize,
    pub center: [f64; 3],
    pub pts: Vec<[[[f64; 3]; 4]; 3]>,
}

impl ExtNet {
    /// A bumpy, roughly radial net: `(x, y)` of sector `s` placed at the
    /// polar-like position of the lattice point, plus noise of size `noise`.
    pub fn random(n: usize, rng: &mut Rng, noise: f64) -> Self {
        let pos = |s: usize, x: f64, y: f64| -> [f64; 3] {
            // Sector s spans angle 2π/n; lattice (x, y) maps into it.
            let a = std::f64::consts::TAU / n as f64;
            let t = s as f64 * a + a * y.atan2(x) / std::f64::consts::FRAC_PI_2;
            let r = (x * x + y * y).sqrt();
            [r * t.cos(), r * t.sin(), 0.1 * r * r]
        };
        let mut pts = Vec::new();
        for s in 0..n {
            let mut sec = [[[0.0; 3]; 4]; 3];
            for (xi, col) in sec.iter_mut().enumerate() {
                for (y, p) in col.iter_mut().enumerate() {
                    let q = pos(s, (xi + 1) as f64, y as f64);
                    *p = [
                        q[0] + rng.sym(noise),
                        q[1] + rng.sym(noise),
                        q[2] + rng.sym(noise),
                    ];
                }
            }
            pts.push(sec);
        }
        ExtNet {
            n,
            center: rng.point(noise),
            pts,
        }
    }

    /// Point `(x, y)` of sector `s`, any `x, y ∈ −3..=3` reachable by the §1
    /// change of frame (independent re-implementation of docs/math/eg.md §1).
    pub fn at(&self, s: isize, x: i32, y: i32) -> [f64; 3] {
        let (mut s, mut x, mut y) = (s, x, y);
        loop {
            if x == 0 && y == 0 {
                return self.center;
            }
            if y < 0 {
                (x, y, s) = (-y, x, s - 1);
            } else if x <= 0 {
                (x, y, s) = (y, -x, s + 1);
            } else {
                break;
            }
        }
        let s = s.rem_euclid(self.n as isize) as usize;
        self.pts[s][(x - 1) as usize][y as usize]
    }

    /// The c-net part (§1 order per sector).
    pub fn cnet_nodes(&self) -> Vec<[f64; 3]> {
        let mut v = Vec::new();
        for s in 0..self.n {
            for (x, y) in [(1, 0), (2, 0), (1, 1), (2, 1), (1, 2), (2, 2)] {
                v.push(self.at(s as isize, x, y));
            }
        }
        v
    }

    /// The bicubic patch over `[a, a+1] × [b, b+1]` of sector `s` (a regular
    /// 4×4 sub-grid), as Bézier control points.
    pub fn bicubic(&self, s: usize, a: i32, b: i32) -> TensorPatch<f64, 4> {
        let mut d = [[Point3::ZERO; 4]; 4];
        for (k, row) in d.iter_mut().enumerate() {
            for (l, p) in row.iter_mut().enumerate() {
                *p = Point3(self.at(s as isize, a - 1 + k as i32, b - 1 + l as i32));
            }
        }
        TensorPatch {
            points: capdiv::bezier::bspline_to_bezier_cubic(&d),
        }
    }
}

/// Position and all partials up to order 2 with respect to `(x, y)`.
#[derive(Clone, Copy, Debug)]
pub struct Jet {
    pub d: [[f64; 3]; 6], // f, fx, fy, fxx, fxy, fyy
}

impl Jet {
    pub fn max_abs(&self) -> f64 {
        self.d.iter().flatten().fold(0.0f64, |m, c| m.max(c.abs()))
    }
    pub fn max_diff(&self, o: &Jet) -> f64 {
        self.d
            .iter()
            .flatten()
            .zip(o.d.iter().flatten())
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
    }
    /// Re-expresses a jet of `g` in the frame where `f(x, y) = g(−y, x)`
    /// (neighbor s−1 seen from s).
    pub fn from_prev(g: &Jet) -> Jet {
        let [v, gx, gy, gxx, gxy, gyy] = g.d;
        Jet {
            d: [v, gy, neg(gx), gyy, neg(gxy), gxx],
        }
    }
    /// Same for `f(x, y) = g(y, −x)` (neighbor s+1 seen from s).
    pub fn from_next(g: &Jet) -> Jet {
        let [v, gx, gy, gxx, gxy, gyy] = g.d;
        Jet {
            d: [v, neg(gy), gx, gyy, neg(gxy), gxx],
        }
    }
}

fn neg(a: [f64; 3]) -> [f64; 3] {
    a.map(|c| -c)
}

fn binom(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// Bernstein basis of degree `d` and its first two derivatives at `t`.
fn bernstein(d: usize, t: f64) -> [Vec<f64>; 3] {
    let b = |deg: usize, i: isize| -> f64 {
        if i < 0 || i as usize > deg {
            0.0
        } else {
            let i = i as usize;
            binom(deg, i) * t.powi(i as i32) * (1.0 - t).powi((deg - i) as i32)
        }
    };
    let df = d as f64;
    let v: Vec<f64> = (0..=d as isize).map(|i| b(d, i)).collect();
    let d1: Vec<f64> = (0..=d as isize)
        .map(|i| {
            if d >= 1 {
                df * (b(d - 1, i - 1) - b(d - 1, i))
            } else {
                0.0
            }
        })
        .collect();
    let d2: Vec<f64> = (0..=d as isize)
        .map(|i| {
            if d >= 2 {
                df * (df - 1.0) * (b(d - 2, i - 2) - 2.0 * b(d - 2, i - 1) + b(d - 2, i))
            } else {
                0.0
            }
        })
        .collect();
    [v, d1, d2]
}

/// The jet of a patch over the square `[x0, x0+w] × [y0, y0+w]` (u along x).
pub fn patch_jet<const K: usize>(
    p: &TensorPatch<f64, K>,
    x0: f64,
    y0: f64,
    w: f64,
    x: f64,
    y: f64,
) -> Jet {
    let (u, v) = ((x - x0) / w, (y - y0) / w);
    let bu = bernstein(K - 1, u);
    let bv = bernstein(K - 1, v);
    let combos = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)];
    let mut d = [[0.0; 3]; 6];
    for (slot, &(a, b)) in d.iter_mut().zip(combos.iter()) {
        let scale = w.powi(-((a + b) as i32));
        for (bi, row) in bu[a].iter().zip(p.points.iter()) {
            for (bj, q) in bv[b].iter().zip(row.iter()) {
                let wgt = bi * bj * scale;
                for (o, c) in slot.iter_mut().zip(q.0.iter()) {
                    *o += wgt * c;
                }
            }
        }
    }
    Jet { d }
}

/// Points of a d-net/c-net as `f64` triples.
pub fn max_dist(a: &[Point3<f64>], b: &[Point3<f64>]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (p, q)| m.max(p.max_abs_diff(*q)))
}
