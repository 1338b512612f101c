//! Meshes made in code, for the demo, tests and benchmarks.
//!
//! Every generator returns a [`MeshInput`] whose vertices are all used and
//! distinct, whose faces have no repeated vertex and non-zero area, and —
//! unless its doc says it is open — which is closed and consistently oriented,
//! faces counter-clockwise about the outward normal. Parameters below their
//! documented minimum are raised to it (no generator panics).
//!
//! The structures the surface code looks for:
//! - a *polar configuration*: a pole whose faces are all triangles (a fan of
//!   `n`), ringed by quads whose vertices are 4-valent (the 1-link vertices
//!   meet 2 triangles and 2 quads) — [`globe`], [`pole_disk`], [`mushroom`],
//!   [`hand`];
//! - an *extraordinary point*: a quad-mesh vertex of valence ≠ 4 —
//!   [`cube`], [`rounded_cube`], [`two_beam_corner`], [`extraordinary_disk`],
//!   and the finger junctions of [`hand`];
//! - regular quad meshes: [`torus`], [`grid`];
//! - a triangle mesh with valence-5 and -6 vertices: [`icosphere`];
//! - faces that need refinement first: [`triangle_and_pentagon_mesh`];
//! - benchmark tori of `16·base²` quads: isolated extraordinary points
//!   ([`ev_torus`]), and those with creases, corners and holes
//!   ([`feature_torus`]).
//!
//! Angles come from a local Taylor-series `sin`/`cos` (the crate has no
//! `libm` of its own); positions are only meant to be reasonable shapes.

use crate::input::{EdgeCrease, MeshInput, VertexCorner};
use alloc::collections::{BTreeMap, BTreeSet};
use alloc::vec;
use alloc::vec::Vec;
use capdiv::Point3;

const PI: f64 = core::f64::consts::PI;
const TAU: f64 = 2.0 * PI;

/// `(sin x, cos x)` to about 1e-15 absolute: reduction to `[-π, π]`, then
/// Taylor series.
fn sin_cos(x: f64) -> (f64, f64) {
    let mut r = x - ((x / TAU) as i64 as f64) * TAU;
    if r > PI {
        r -= TAU;
    } else if r < -PI {
        r += TAU;
    }
    let r2 = r * r;
    let (mut s, mut c) = (0.0, 0.0);
    let (mut ts, mut tc) = (r, 1.0);
    let mut k = 1.0;
    for _ in 0..20 {
        s += ts;
        c += tc;
        ts *= -r2 / ((k + 1.0) * (k + 2.0));
        tc *= -r2 / (k * (k + 1.0));
        k += 2.0;
    }
    (s, c)
}

fn sin(x: f64) -> f64 {
    sin_cos(x).0
}

fn cos(x: f64) -> f64 {
    sin_cos(x).1
}

fn axpy(p: [f64; 3], s: f64, d: [f64; 3]) -> [f64; 3] {
    [p[0] + s * d[0], p[1] + s * d[1], p[2] + s * d[2]]
}

/// `a / |a|` (not finite for a zero `a`).
fn normalized(a: [f64; 3]) -> [f64; 3] {
    let l = Point3(a).norm();
    [a[0] / l, a[1] / l, a[2] / l]
}

/// Collects vertices and faces; [`Builder::finish`] drops emptied faces and
/// unused vertices.
#[derive(Default)]
struct Builder {
    vertices: Vec<[f64; 3]>,
    faces: Vec<Vec<u32>>,
}

impl Builder {
    fn vertex(&mut self, p: [f64; 3]) -> u32 {
        self.vertices.push(p);
        (self.vertices.len() - 1) as u32
    }

    fn face(&mut self, f: &[u32]) -> usize {
        self.faces.push(f.to_vec());
        self.faces.len() - 1
    }

    /// Removes faces emptied by [`Builder::cut`] and renumbers the vertices
    /// still used, in their original order.
    fn finish(self) -> MeshInput {
        let mut used = vec![false; self.vertices.len()];
        for f in &self.faces {
            for &v in f {
                used[v as usize] = true;
            }
        }
        let mut new_index = vec![u32::MAX; self.vertices.len()];
        let mut vertices = Vec::new();
        for (v, p) in self.vertices.iter().enumerate() {
            if used[v] {
                new_index[v] = vertices.len() as u32;
                vertices.push(*p);
            }
        }
        let faces = self
            .faces
            .into_iter()
            .filter(|f| !f.is_empty())
            .map(|f| f.iter().map(|&v| new_index[v as usize]).collect())
            .collect();
        MeshInput::new(vertices, faces)
    }

    /// Removes `faces` (they must form one disk) and returns the boundary of
    /// the hole, in the direction the removed faces ran it.
    fn cut(&mut self, faces: &[usize]) -> Vec<u32> {
        let mut edges = BTreeSet::new();
        for &f in faces {
            let face = &self.faces[f];
            for k in 0..face.len() {
                edges.insert((face[k], face[(k + 1) % face.len()]));
            }
        }
        let next: BTreeMap<u32, u32> = edges
            .iter()
            .filter(|&&(a, b)| !edges.contains(&(b, a)))
            .copied()
            .collect();
        let mut ring = Vec::with_capacity(next.len());
        if let Some((&first, _)) = next.iter().next() {
            let mut v = first;
            loop {
                ring.push(v);
                v = next[&v];
                if v == first || ring.len() > next.len() {
                    break;
                }
            }
        }
        for &f in faces {
            self.faces[f].clear();
        }
        ring
    }

    /// Closes the boundary ring `base` (running the way the faces it
    /// replaces ran it) with a tube along `dir`: `straight` rings of quads
    /// tapering from `radius` to `0.9·radius`, a hemispherical tip of two
    /// more rings, and a pole at distance `length` from the ring's centroid.
    /// Returns the pole.
    fn tube(
        &mut self,
        base: &[u32],
        dir: [f64; 3],
        length: f64,
        radius: f64,
        straight: usize,
    ) -> u32 {
        let n = base.len();
        let d = normalized(dir);
        let mut c = [0.0; 3];
        for &v in base {
            c = axpy(c, 1.0 / n as f64, self.vertices[v as usize]);
        }
        let radial: Vec<[f64; 3]> = base
            .iter()
            .map(|&v| {
                let o = (Point3(self.vertices[v as usize]) - Point3(c)).0;
                normalized(axpy(o, -Point3(o).dot(Point3(d)), d))
            })
            .collect();
        let end = radius * 0.9;
        let mut rings: Vec<(f64, f64)> = (1..=straight)
            .map(|k| {
                let t = k as f64 / straight as f64;
                (t * (length - end), radius + t * (end - radius))
            })
            .collect();
        for deg in [30.0f64, 60.0] {
            let (s, c) = sin_cos(deg.to_radians());
            rings.push((length - end + end * s, end * c));
        }
        let mut prev: Vec<u32> = base.to_vec();
        for (along, r) in rings {
            let ring: Vec<u32> = radial
                .iter()
                .map(|&u| self.vertex(axpy(axpy(c, along, d), r, u)))
                .collect();
            for j in 0..n {
                let j1 = (j + 1) % n;
                self.face(&[prev[j], prev[j1], ring[j1], ring[j]]);
            }
            prev = ring;
        }
        let pole = self.vertex(axpy(c, length, d));
        for j in 0..n {
            self.face(&[prev[j], prev[(j + 1) % n], pole]);
        }
        pole
    }
}

/// A surface of revolution about the z axis: a pole at `(0, 0, top)`, rings
/// of `n` points at the profile's `(radius, z)` (top to bottom, radii > 0),
/// a pole at `(0, 0, bottom)`. Triangle fans at the poles, quads between.
fn revolution(n: usize, top: f64, profile: &[[f64; 2]], bottom: f64) -> MeshInput {
    let mut b = Builder::default();
    let north = b.vertex([0.0, 0.0, top]);
    let mut rings: Vec<Vec<u32>> = Vec::with_capacity(profile.len());
    for &[r, z] in profile {
        rings.push(
            (0..n)
                .map(|j| {
                    let (s, c) = sin_cos(TAU * j as f64 / n as f64);
                    b.vertex([r * c, r * s, z])
                })
                .collect(),
        );
    }
    let south = b.vertex([0.0, 0.0, bottom]);
    for j in 0..n {
        let j1 = (j + 1) % n;
        b.face(&[north, rings[0][j], rings[0][j1]]);
    }
    for w in rings.windows(2) {
        let (up, down) = (&w[0], &w[1]);
        for j in 0..n {
            let j1 = (j + 1) % n;
            b.face(&[up[j], down[j], down[j1], up[j1]]);
        }
    }
    let last = &rings[rings.len() - 1];
    for j in 0..n {
        b.face(&[south, last[(j + 1) % n], last[j]]);
    }
    b.finish()
}

/// The unit sphere as a latitude-longitude grid: two poles (at `z = ±1`) of
/// valence `valence` (≥ 3), each a fan of triangles, and `rings` (≥ 7)
/// latitude rings of `valence` points at equal polar angles, joined by quads.
/// Each pole's links 1, 2, 3 … are its nearest rings; every vertex but the
/// poles is 4-valent.
///
/// `valence·rings + 2` vertices, `valence·(rings + 1)` faces (`2·valence`
/// triangles).
pub fn globe(valence: usize, rings: usize) -> MeshInput {
    let n = valence.max(3);
    let r = rings.max(7);
    let profile: Vec<[f64; 2]> = (1..=r)
        .map(|i| {
            let (s, c) = sin_cos(PI * i as f64 / (r + 1) as f64);
            [s, c]
        })
        .collect();
    revolution(n, 1.0, &profile, -1.0)
}

/// An OPEN polar disk: a pole of valence `valence` (≥ 3) at the centre, a fan
/// of triangles to link 1, then quads out to link `links` (≥ 2), which is
/// the boundary. Link `i` is a circle of radius `i/links` (points at equal
/// angles, counter-clockwise seen from +z, normals pointing up) lifted onto
/// the bumpy dome `z = 0.35·(1 − x² − y²) + 0.06·sin 3x·cos 2y + 0.04·x·y`.
/// Links 1..links−1 are 4-valent; boundary vertices have valence 3.
///
/// `valence·links + 1` vertices, `valence·links` faces; Euler characteristic 1.
pub fn pole_disk(valence: usize, links: usize) -> MeshInput {
    let n = valence.max(3);
    let l = links.max(2);
    let height = |x: f64, y: f64| {
        0.35 * (1.0 - x * x - y * y) + 0.06 * sin(3.0 * x) * cos(2.0 * y) + 0.04 * x * y
    };
    let mut b = Builder::default();
    let pole = b.vertex([0.0, 0.0, height(0.0, 0.0)]);
    let rings: Vec<Vec<u32>> = (1..=l)
        .map(|i| {
            let r = i as f64 / l as f64;
            (0..n)
                .map(|j| {
                    let (s, c) = sin_cos(TAU * j as f64 / n as f64);
                    let (x, y) = (r * c, r * s);
                    b.vertex([x, y, height(x, y)])
                })
                .collect()
        })
        .collect();
    for j in 0..n {
        b.face(&[pole, rings[0][j], rings[0][(j + 1) % n]]);
    }
    for w in rings.windows(2) {
        for j in 0..n {
            let j1 = (j + 1) % n;
            b.face(&[w[0][j], w[1][j], w[1][j1], w[0][j1]]);
        }
    }
    b.finish()
}

/// A mushroom: a closed surface of revolution about z with two poles of
/// valence 12, one at the top of the cap (`z = 2`), one at the centre of the
/// flat foot (`z = −0.07`). Profile, top to bottom (17 rings): a convex
/// elliptic dome, a rounded rim, the concave underside of the cap curving
/// into a thin stem, a stem bulging towards its foot, and a flat bottom whose
/// first three links are evenly spaced circles. Every vertex but the poles is
/// 4-valent.
///
/// 206 vertices, 216 faces (24 triangles, 192 quads).
pub fn mushroom() -> MeshInput {
    let mut profile: Vec<[f64; 2]> = [15.0f64, 30.0, 45.0, 60.0, 75.0]
        .iter()
        .map(|&deg| {
            let (s, c) = sin_cos(deg.to_radians());
            [1.3 * s, 1.3 + 0.7 * c]
        })
        .collect();
    profile.extend_from_slice(&[
        [1.34, 1.2], // rim
        [1.26, 1.07],
        [1.0, 1.08], // underside, concave towards the stem
        [0.7, 1.12],
        [0.42, 1.06],
        [0.31, 0.9], // stem
        [0.3, 0.62],
        [0.34, 0.34],
        [0.43, 0.08], // bulging foot
        [0.36, -0.06],
        [0.24, -0.07], // flat bottom: links 2 and 1 of the lower pole
        [0.12, -0.07],
    ]);
    revolution(12, 2.0, &profile, -0.07)
}

/// A hand: a flat palm with four fingers and a thumb, each finger ending in
/// a pole of valence 8 (the C²PS paper's Fig. 2 idea: a tube closed by a
/// polar fan), and the wrist closed by a pole of valence 26.
///
/// The palm is a tube along +y whose cross-section is the rim of an 11×2
/// quad grid (26 points; the palm is 2.2 wide and about 0.5 thick), closed
/// at the wrist (y ≈ −0.6) by the fan and at the top (y = 1.9) by that grid.
/// Each finger replaces a 2×2 block of the top grid (blocks at columns 0–1,
/// 3–4, 6–7, 9–10, one column left between neighbours) by a tube of 8-point
/// rings (5 rings: 3 straight, 2 for the round tip, so each tip pole has 5
/// quad links of its own); the thumb replaces a 2×2 block of the palm's side
/// wall at x = 1.1 and points up and out.
///
/// Valences: the 6 poles (one 26, five 8); 16 junction vertices of valence 5
/// (the 12 top-rim vertices beside the 3 gaps between fingers, and the 4
/// corners of the thumb's block); every other vertex is 4-valent.
///
/// 549 vertices, 580 faces (66 triangles, 514 quads).
pub fn hand() -> MeshInput {
    const A: usize = 11; // top grid: A×2 cells
    const W: f64 = 0.2; // cell width (x)
    const T: f64 = 0.25; // cell thickness (z)
    const RINGS: usize = 13; // palm rings, the last one the top grid's rim
    let shape = |i: usize, k: usize, y: f64, scale: f64| {
        let x = (i as f64 - A as f64 / 2.0) * W;
        let bulge = 1.0 + 0.25 * (1.0 - (x / 1.1) * (x / 1.1));
        let z = (k as f64 - 1.0) * T * bulge;
        [x * scale, y, z * scale]
    };
    let mut b = Builder::default();
    // The top grid (including the hole centres, dropped by `finish`).
    let top_y = -0.5 + 0.2 * (RINGS - 1) as f64;
    let mut grid = [[0u32; 3]; A + 1];
    for (i, column) in grid.iter_mut().enumerate() {
        for (k, v) in column.iter_mut().enumerate() {
            *v = b.vertex(shape(i, k, top_y, 1.0));
        }
    }
    // The rim, counter-clockwise about -y (the way the palm's quads run it).
    let mut rim: Vec<(usize, usize)> = Vec::new();
    rim.extend((0..A).map(|i| (i, 0)));
    rim.extend((0..2).map(|k| (A, k)));
    rim.extend((1..=A).rev().map(|i| (i, 2)));
    rim.extend((1..=2).rev().map(|k| (0, k)));
    let m = rim.len();
    let scales = [0.5, 0.8, 0.95];
    let mut rings: Vec<Vec<u32>> = (0..RINGS - 1)
        .map(|r| {
            let y = -0.5 + 0.2 * r as f64;
            let s = scales.get(r).copied().unwrap_or(1.0);
            rim.iter()
                .map(|&(i, k)| b.vertex(shape(i, k, y, s)))
                .collect()
        })
        .collect();
    rings.push(rim.iter().map(|&(i, k)| grid[i][k]).collect());
    let wrist = b.vertex([0.0, -0.62, 0.0]);
    for p in 0..m {
        b.face(&[wrist, rings[0][p], rings[0][(p + 1) % m]]);
    }
    // tube[r][p]: the quad between rings r and r+1 over rim edge p → p+1.
    let mut tube = vec![vec![0usize; m]; RINGS - 1];
    for r in 0..RINGS - 1 {
        for p in 0..m {
            let p1 = (p + 1) % m;
            tube[r][p] = b.face(&[rings[r][p1], rings[r][p], rings[r + 1][p], rings[r + 1][p1]]);
        }
    }
    let mut cell = [[0usize; 2]; A];
    for (i, column) in cell.iter_mut().enumerate() {
        for (k, f) in column.iter_mut().enumerate() {
            *f = b.face(&[
                grid[i][k],
                grid[i][k + 1],
                grid[i + 1][k + 1],
                grid[i + 1][k],
            ]);
        }
    }
    // Fingers: little, ring, middle, index (lengths from the top grid).
    for (s, length) in [(0usize, 0.75), (3, 0.95), (6, 1.05), (9, 0.95)] {
        let centre = (s as f64 + 1.0 - A as f64 / 2.0) * W;
        let hole = b.cut(&[cell[s][0], cell[s][1], cell[s + 1][0], cell[s + 1][1]]);
        b.tube(&hole, [0.15 * centre, 1.0, 0.0], length, 0.19, 3);
    }
    // Thumb: rings 4..6, rim edges (A,0)-(A,1)-(A,2) (rim positions A, A+1).
    let hole = b.cut(&[tube[4][A], tube[4][A + 1], tube[5][A], tube[5][A + 1]]);
    b.tube(&hole, [1.0, 0.8, 0.15], 0.85, 0.2, 3);
    b.finish()
}

/// The cube `[-1, 1]³`: 8 vertices of valence 3 (extraordinary points that
/// are each other's neighbours — it needs refinement before any cap), 6
/// quads, 12 edges.
pub fn cube() -> MeshInput {
    voxels(&|x, y, z| x == 0 && y == 0 && z == 0, [0; 3], [1; 3], |g| {
        [
            2.0 * g[0] as f64 - 1.0,
            2.0 * g[1] as f64 - 1.0,
            2.0 * g[2] as f64 - 1.0,
        ]
    })
}

/// A rounded cube: each face of `[-1, 1]³` a `k×k` quad grid (`k ≥ 1`), every
/// point then moved half-way towards its projection onto the sphere of
/// radius 1.2. The 8 corners are valence-3 extraordinary points separated
/// along each edge by `k − 1` regular vertices; all other vertices are
/// 4-valent.
///
/// `6k² + 2` vertices, `6k²` quads.
pub fn rounded_cube(k: usize) -> MeshInput {
    let k = k.max(1) as i32;
    voxels(
        &|x, y, z| (0..k).contains(&x) && (0..k).contains(&y) && (0..k).contains(&z),
        [0; 3],
        [k; 3],
        |g| {
            let p = [
                2.0 * g[0] as f64 / k as f64 - 1.0,
                2.0 * g[1] as f64 / k as f64 - 1.0,
                2.0 * g[2] as f64 / k as f64 - 1.0,
            ];
            let s = 0.5 + 0.5 * 1.2 / Point3(p).norm();
            [p[0] * s, p[1] * s, p[2] * s]
        },
    )
}

/// An L-shaped corner of two square beams (quad mesh), built from unit
/// cells scaled by 0.25: beam A runs along x (`[0,6]×[0,2]×[0,2]` cells),
/// beam B along y (`[0,2]×[0,6]×[0,2]`), sharing the corner block. Each
/// beam's cross-section is a 2×2 quad grid.
///
/// Where the beams meet, the two vertices at the ends of the inner (concave)
/// edge are valence-5 extraordinary points whose 1-rings are 4-valent; the
/// 10 outer corners (5 on top, 5 below) have valence 3; all other vertices
/// are 4-valent.
///
/// 90 vertices, 88 quads.
pub fn two_beam_corner() -> MeshInput {
    let inside = |x: i32, y: i32, z: i32| {
        (0..2).contains(&z)
            && (((0..6).contains(&x) && (0..2).contains(&y))
                || ((0..2).contains(&x) && (0..6).contains(&y)))
    };
    voxels(&inside, [0; 3], [6, 6, 2], |g| {
        [0.25 * g[0] as f64, 0.25 * g[1] as f64, 0.25 * g[2] as f64]
    })
}

/// The boundary of a union of unit cells `c` (`lo ≤ c < hi`, `inside(c)`):
/// one quad per cell face with no cell behind it, counter-clockwise about
/// the outward normal, vertices shared through their integer coordinates
/// and placed by `place`. The union must be a manifold solid (no cells
/// touching along an edge or at a corner only).
fn voxels(
    inside: &dyn Fn(i32, i32, i32) -> bool,
    lo: [i32; 3],
    hi: [i32; 3],
    place: impl Fn([i32; 3]) -> [f64; 3],
) -> MeshInput {
    let mut b = Builder::default();
    let mut index: BTreeMap<[i32; 3], u32> = BTreeMap::new();
    let solid = |c: [i32; 3]| inside(c[0], c[1], c[2]);
    for x in lo[0]..hi[0] {
        for y in lo[1]..hi[1] {
            for z in lo[2]..hi[2] {
                let c = [x, y, z];
                if !solid(c) {
                    continue;
                }
                for a in 0..3 {
                    let (u, v) = ((a + 1) % 3, (a + 2) % 3);
                    for outward in [true, false] {
                        let mut n = c;
                        n[a] += if outward { 1 } else { -1 };
                        if solid(n) {
                            continue;
                        }
                        // (u, v) offsets, counter-clockwise about +a.
                        let mut quad = [(0, 0), (1, 0), (1, 1), (0, 1)];
                        if !outward {
                            quad.reverse();
                        }
                        let mut face = [0u32; 4];
                        for (slot, &(du, dv)) in face.iter_mut().zip(&quad) {
                            let mut g = c;
                            g[a] += i32::from(outward);
                            g[u] += du;
                            g[v] += dv;
                            *slot = *index.entry(g).or_insert_with(|| b.vertex(place(g)));
                        }
                        b.face(&face);
                    }
                }
            }
        }
    }
    b.finish()
}

/// A torus (fully regular quad mesh, every vertex 4-valent): `nu` (≥ 3)
/// points around the major circle (radius 1, in the xy plane), `nv` (≥ 3)
/// around the tube (radius 0.35). `nu·nv` vertices and quads; Euler
/// characteristic 0.
pub fn torus(nu: usize, nv: usize) -> MeshInput {
    let (nu, nv) = (nu.max(3), nv.max(3));
    let mut b = Builder::default();
    for i in 0..nu {
        let (su, cu) = sin_cos(TAU * i as f64 / nu as f64);
        for j in 0..nv {
            let (sv, cv) = sin_cos(TAU * j as f64 / nv as f64);
            let r = 1.0 + 0.35 * cv;
            b.vertex([r * cu, r * su, 0.35 * sv]);
        }
    }
    let at = |i: usize, j: usize| ((i % nu) * nv + j % nv) as u32;
    for i in 0..nu {
        for j in 0..nv {
            b.face(&[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    b.finish()
}

/// The unit icosahedron's triangles split `levels` times into four (edge
/// midpoints pushed to the unit sphere): `20·4^levels` triangles, twelve
/// valence-5 vertices, every other vertex valence 6. Closed, Euler
/// characteristic 2.
pub fn icosphere(levels: u32) -> MeshInput {
    let t = (1.0 + libm::sqrt(5.0)) / 2.0;
    let unit = |p: [f64; 3]| {
        let r = libm::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        [p[0] / r, p[1] / r, p[2] / r]
    };
    let mut vertices: Vec<[f64; 3]> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .map(unit)
    .to_vec();
    let mut faces: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut mid: BTreeMap<(u32, u32), u32> = BTreeMap::new();
        let mut next = Vec::with_capacity(4 * faces.len());
        for [a, b, c] in faces {
            let mut m = |x: u32, y: u32| {
                *mid.entry((x.min(y), x.max(y))).or_insert_with(|| {
                    let (p, q) = (vertices[x as usize], vertices[y as usize]);
                    vertices.push(unit([p[0] + q[0], p[1] + q[1], p[2] + q[2]]));
                    (vertices.len() - 1) as u32
                })
            };
            let (ab, bc, ca) = (m(a, b), m(b, c), m(c, a));
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = next;
    }
    MeshInput::new(vertices, faces.into_iter().map(|f| f.to_vec()).collect())
}

/// An OPEN regular quad patch over `[-1, 1]²`: `nu×nv` quads (each ≥ 1),
/// `(nu+1)(nv+1)` vertices on the bumpy height field
/// `z = 0.15·sin(πx)·cos(πy/2) + 0.05·x·y`, normals pointing up. Interior
/// vertices are 4-valent, boundary ones 3-valent, the 4 corners 2-valent.
/// Euler characteristic 1.
pub fn grid(nu: usize, nv: usize) -> MeshInput {
    let (nu, nv) = (nu.max(1), nv.max(1));
    let mut b = Builder::default();
    for j in 0..=nv {
        for i in 0..=nu {
            let x = 2.0 * i as f64 / nu as f64 - 1.0;
            let y = 2.0 * j as f64 / nv as f64 - 1.0;
            b.vertex([x, y, 0.15 * sin(PI * x) * cos(PI * y / 2.0) + 0.05 * x * y]);
        }
    }
    let at = |i: usize, j: usize| (j * (nu + 1) + i) as u32;
    for j in 0..nv {
        for i in 0..nu {
            b.face(&[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    b.finish()
}

/// An OPEN quad mesh around one extraordinary point of valence `n` (≥ 3):
/// `n` sectors, sector `s` a `rings×rings` quad grid (`rings ≥ 2`) spanned
/// by spokes `s` and `s+1` (unit vectors at angles `2πs/n`), which it shares
/// with its neighbours. Point `(a, b)` of sector `s` sits at
/// `(a·e_s + b·e_{s+1})/rings`, lifted to the bumpy height
/// `z = 0.1·(x² − y²) + 0.04·sin 4x + 0.03·cos 3y`; normals point up.
/// The centre has valence `n`; all other interior vertices (in particular
/// the centre's whole 1-ring) are 4-valent.
///
/// `1 + n·rings·(rings + 1)` vertices, `n·rings²` quads; Euler
/// characteristic 1.
pub fn extraordinary_disk(n: usize, rings: usize) -> MeshInput {
    let n = n.max(3);
    let r = rings.max(2);
    let mut b = Builder::default();
    let spoke_dir: Vec<[f64; 2]> = (0..n)
        .map(|s| {
            let (sn, cs) = sin_cos(TAU * s as f64 / n as f64);
            [cs, sn]
        })
        .collect();
    let place = |s: usize, a: usize, c: usize| {
        let (e, f) = (spoke_dir[s], spoke_dir[(s + 1) % n]);
        let x = (a as f64 * e[0] + c as f64 * f[0]) / r as f64;
        let y = (a as f64 * e[1] + c as f64 * f[1]) / r as f64;
        [
            x,
            y,
            0.1 * (x * x - y * y) + 0.04 * sin(4.0 * x) + 0.03 * cos(3.0 * y),
        ]
    };
    let centre = b.vertex(place(0, 0, 0));
    // spokes[s][a-1]: point a on spoke s; inner[s][(a-1)*r + (c-1)].
    let spokes: Vec<Vec<u32>> = (0..n)
        .map(|s| (1..=r).map(|a| b.vertex(place(s, a, 0))).collect())
        .collect();
    let inner: Vec<Vec<u32>> = (0..n)
        .map(|s| {
            let mut v = Vec::with_capacity(r * r);
            for a in 1..=r {
                for c in 1..=r {
                    v.push(b.vertex(place(s, a, c)));
                }
            }
            v
        })
        .collect();
    let at = |s: usize, a: usize, c: usize| match (a, c) {
        (0, 0) => centre,
        (a, 0) => spokes[s][a - 1],
        (0, c) => spokes[(s + 1) % n][c - 1],
        (a, c) => inner[s][(a - 1) * r + (c - 1)],
    };
    for s in 0..n {
        for a in 0..r {
            for c in 0..r {
                b.face(&[
                    at(s, a, c),
                    at(s, a + 1, c),
                    at(s, a + 1, c + 1),
                    at(s, a, c + 1),
                ]);
            }
        }
    }
    b.finish()
}

/// A closed pentagonal prism (pentagons of circumradius 1 at `z = ±1`, the
/// top one turned by 12° so the sides are not planar) whose side faces 0 and
/// 2 are each split into two triangles: 2 pentagons, 3 quads, 4 triangles.
/// No vertex has only triangles around it (none is a pole), so the surface
/// code must refine it first. 10 vertices (valences 3 and 4), 9 faces,
/// 17 edges.
pub fn triangle_and_pentagon_mesh() -> MeshInput {
    let mut b = Builder::default();
    let bottom: Vec<u32> = (0..5)
        .map(|j| {
            let (s, c) = sin_cos(TAU * j as f64 / 5.0);
            b.vertex([c, s, -1.0])
        })
        .collect();
    let top: Vec<u32> = (0..5)
        .map(|j| {
            let (s, c) = sin_cos(TAU * j as f64 / 5.0 + 12f64.to_radians());
            b.vertex([c, s, 1.0])
        })
        .collect();
    b.face(&top);
    let reversed: Vec<u32> = bottom.iter().rev().copied().collect();
    b.face(&reversed);
    for j in 0..5 {
        let j1 = (j + 1) % 5;
        if j == 0 || j == 2 {
            b.face(&[bottom[j], bottom[j1], top[j1]]);
            b.face(&[bottom[j], top[j1], top[j]]);
        } else {
            b.face(&[bottom[j], bottom[j1], top[j1], top[j]]);
        }
    }
    b.finish()
}

/// A benchmark mesh of about `faces` faces (at least one copy): disjoint
/// copies of a [`mushroom`] (two valence-12 poles), a [`rounded_cube`]`(6)`
/// (eight valence-3 points) and an [`extraordinary_disk`]`(7, 5)` (one
/// valence-7 point), 1,077 faces per copy, each copy shifted along x.
pub fn feature_mix(faces: usize) -> MeshInput {
    let parts = [mushroom(), rounded_cube(6), extraordinary_disk(7, 5)];
    let per: usize = parts.iter().map(|m| m.faces.len()).sum();
    let mut out = MeshInput::default();
    for k in 0..faces.div_ceil(per).max(1) {
        for (i, m) in parts.iter().enumerate() {
            let base = out.vertices.len() as u32;
            let dx = 10.0 * (k * parts.len() + i) as f64;
            out.vertices
                .extend(m.vertices.iter().map(|p| [p[0] + dx, p[1], p[2]]));
            out.faces.extend(
                m.faces
                    .iter()
                    .map(|f| f.iter().map(|&v| v + base).collect()),
            );
        }
    }
    out
}

/// Catmull-Clark's topological split (positions averaged, not smoothed):
/// every k-gon becomes k quads, its children contiguous and in corner order.
/// Tags follow: a crease edge's two halves keep its sharpness, a hole's
/// children are holes, corners stay on their vertex.
pub fn split_into_quads(m: &MeshInput) -> MeshInput {
    let mut vertices = m.vertices.clone();
    let mut edge_point: BTreeMap<(u32, u32), u32> = BTreeMap::new();
    let mut edge = |vertices: &mut Vec<[f64; 3]>, a: u32, b: u32| {
        *edge_point.entry((a.min(b), a.max(b))).or_insert_with(|| {
            let (p, q) = (m.vertices[a as usize], m.vertices[b as usize]);
            vertices.push([
                (p[0] + q[0]) / 2.0,
                (p[1] + q[1]) / 2.0,
                (p[2] + q[2]) / 2.0,
            ]);
            (vertices.len() - 1) as u32
        })
    };
    let mut faces = Vec::with_capacity(4 * m.faces.len());
    let mut children = Vec::with_capacity(m.faces.len());
    for f in &m.faces {
        let k = f.len();
        let mut c = [0.0; 3];
        for &v in f {
            for (c, x) in c.iter_mut().zip(m.vertices[v as usize]) {
                *c += x / k as f64;
            }
        }
        vertices.push(c);
        let centre = (vertices.len() - 1) as u32;
        let mids: Vec<u32> = (0..k)
            .map(|i| edge(&mut vertices, f[i], f[(i + 1) % k]))
            .collect();
        children.push(faces.len() as u32..(faces.len() + k) as u32);
        for i in 0..k {
            faces.push(vec![f[i], mids[i], centre, mids[(i + k - 1) % k]]);
        }
    }
    let mut out = MeshInput::new(vertices, faces);
    out.tags = m.tags.clone();
    out.tags.creases = m
        .tags
        .creases
        .iter()
        .flat_map(|c| {
            let [a, b] = c.vertices;
            let e = edge(&mut out.vertices, a, b);
            [[a, e], [e, b]].map(|vertices| EdgeCrease {
                vertices,
                sharpness: c.sharpness,
            })
        })
        .collect();
    out.tags.holes = m
        .tags
        .holes
        .iter()
        .flat_map(|&h| children[h as usize].clone())
        .collect();
    out
}

/// `torus(base, base)` with, for i ≡ 0 (mod 4) and j even, the
/// edge shared by faces (i, j) and (i+1, j) turned by one step in their
/// hexagon: two valence-3 and two valence-5 points per turned edge.
fn turned_torus(base: usize) -> MeshInput {
    let n = base;
    let mut m = torus(n, n);
    let at = |i: usize, j: usize| ((i % n) * n + j % n) as u32;
    let face = |i: usize, j: usize| (i % n) * n + j % n;
    for i in (0..n.saturating_sub(3)).step_by(4) {
        for j in (0..n - 1).step_by(2) {
            let p = [
                at(i, j),
                at(i + 1, j),
                at(i + 2, j),
                at(i + 2, j + 1),
                at(i + 1, j + 1),
                at(i, j + 1),
            ];
            m.faces[face(i, j)] = vec![p[0], p[1], p[2], p[3]];
            m.faces[face(i + 1, j)] = vec![p[0], p[3], p[4], p[5]];
        }
    }
    m
}

/// A torus of `16·base²` quads with isolated extraordinary points and no
/// tags: [`torus`]`(base, base)` with, for i ≡ 0 (mod 4) and j even, the
/// edge shared by faces (i, j) and (i+1, j) turned by one step in their
/// hexagon (two valence-3 and two valence-5 points), split twice
/// ([`split_into_quads`]), so the extraordinary points are 4 edges apart.
pub fn ev_torus(base: usize) -> MeshInput {
    split_into_quads(&split_into_quads(&turned_torus(base)))
}

/// A torus of `16·base²` quads with features, from `torus(base,
/// base)` split twice ([`split_into_quads`]):
/// - isolated extraordinary points: before the splits, the edge shared by
///   faces (i, j) and (i+1, j) for i ≡ 0 (mod 4), j even, turned by one
///   step in their hexagon (two valence-3 and two valence-5 points), so
///   after the splits they are 4 edges apart;
/// - creases along whole grid lines: sharpness 2.5 around the tube at
///   columns ≡ 3 (mod 8) (no turned edge there), 10 around the major circle
///   at rows ≡ 1 (mod 8) (through turned hexagons);
/// - corners at the first eight crossings of those lines (sharpness 10 and
///   2.5, alternating);
/// - holes: the 16 children of base faces (i, j) with i ≡ 5, j ≡ 12 (mod 16).
pub fn feature_torus(base: usize) -> MeshInput {
    let n = base;
    let mut m = turned_torus(n);
    let at = |i: usize, j: usize| ((i % n) * n + j % n) as u32;
    let face = |i: usize, j: usize| (i % n) * n + j % n;
    let columns: Vec<usize> = (3..n).step_by(8).collect();
    let rows: Vec<usize> = (1..n).step_by(8).collect();
    for &c in &columns {
        for j in 0..n {
            m.tags.creases.push(EdgeCrease {
                vertices: [at(c, j), at(c, j + 1)],
                sharpness: 2.5,
            });
        }
    }
    for &r in &rows {
        for i in 0..n {
            m.tags.creases.push(EdgeCrease {
                vertices: [at(i, r), at(i + 1, r)],
                sharpness: 10.0,
            });
        }
    }
    let crossings = columns
        .iter()
        .flat_map(|&c| rows.iter().map(move |&r| (c, r)));
    for (k, (c, r)) in crossings.take(8).enumerate() {
        m.tags.corners.push(VertexCorner {
            vertex: at(c, r),
            sharpness: if k % 2 == 0 { 10.0 } else { 2.5 },
        });
    }
    for i in (5..n).step_by(16) {
        for j in (12..n).step_by(16) {
            m.tags.holes.push(face(i, j) as u32);
        }
    }
    split_into_quads(&split_into_quads(&m))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Undirected edges with the directed half-edges found on each.
    fn edges(m: &MeshInput) -> BTreeMap<(u32, u32), Vec<(u32, u32)>> {
        let mut e: BTreeMap<(u32, u32), Vec<(u32, u32)>> = BTreeMap::new();
        for f in &m.faces {
            for k in 0..f.len() {
                let (a, b) = (f[k], f[(k + 1) % f.len()]);
                e.entry((a.min(b), a.max(b))).or_default().push((a, b));
            }
        }
        e
    }

    fn euler(m: &MeshInput) -> i64 {
        m.vertices.len() as i64 - edges(m).len() as i64 + m.faces.len() as i64
    }

    /// Number of edges at each vertex.
    fn valences(m: &MeshInput) -> Vec<usize> {
        let mut val = vec![0; m.vertices.len()];
        for &(a, b) in edges(m).keys() {
            val[a as usize] += 1;
            val[b as usize] += 1;
        }
        val
    }

    /// Vertices whose faces are all triangles, with their valence.
    fn poles(m: &MeshInput) -> Vec<(usize, usize)> {
        let mut only_tri = vec![true; m.vertices.len()];
        for f in &m.faces {
            if f.len() != 3 {
                for &v in f {
                    only_tri[v as usize] = false;
                }
            }
        }
        let val = valences(m);
        (0..m.vertices.len())
            .filter(|&v| only_tri[v])
            .map(|v| (v, val[v]))
            .collect()
    }

    /// Signed volume (divergence theorem over fan triangles).
    fn volume(m: &MeshInput) -> f64 {
        let mut vol = 0.0;
        for f in &m.faces {
            let p0 = m.vertices[f[0] as usize];
            for k in 1..f.len() - 1 {
                let (p1, p2) = (m.vertices[f[k] as usize], m.vertices[f[k + 1] as usize]);
                vol += (p0[0] * (p1[1] * p2[2] - p1[2] * p2[1])
                    - p0[1] * (p1[0] * p2[2] - p1[2] * p2[0])
                    + p0[2] * (p1[0] * p2[1] - p1[1] * p2[0]))
                    / 6.0;
            }
        }
        vol
    }

    /// Indices valid, faces ≥ 3 distinct vertices with non-zero area and
    /// edges, every vertex used, no two vertices at the same place, no
    /// directed edge twice, no edge on more than two faces.
    fn check_basic(m: &MeshInput) {
        let nv = m.vertices.len();
        let mut used = vec![false; nv];
        for f in &m.faces {
            assert!(f.len() >= 3, "face {f:?}");
            for (k, &v) in f.iter().enumerate() {
                assert!((v as usize) < nv);
                assert!(!f[..k].contains(&v), "repeated vertex in {f:?}");
                used[v as usize] = true;
                let w = f[(k + 1) % f.len()];
                let d = Point3(m.vertices[w as usize]) - Point3(m.vertices[v as usize]);
                assert!(d.dot(d) > 1e-12, "zero-length edge in {f:?}");
            }
            // Newell normal.
            let mut nrm = [0.0; 3];
            for k in 0..f.len() {
                let p = m.vertices[f[k] as usize];
                let q = m.vertices[f[(k + 1) % f.len()] as usize];
                nrm[0] += (p[1] - q[1]) * (p[2] + q[2]);
                nrm[1] += (p[2] - q[2]) * (p[0] + q[0]);
                nrm[2] += (p[0] - q[0]) * (p[1] + q[1]);
            }
            assert!(
                Point3(nrm).dot(Point3(nrm)) > 1e-12,
                "degenerate face {f:?}"
            );
        }
        assert!(used.iter().all(|&u| u), "unused vertex");
        let mut sorted: Vec<[u64; 3]> = m
            .vertices
            .iter()
            .map(|p| [p[0].to_bits(), p[1].to_bits(), p[2].to_bits()])
            .collect();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), nv, "duplicate vertex positions");
        for (e, hs) in edges(m) {
            assert!(hs.len() <= 2, "edge {e:?} on {} faces", hs.len());
            if hs.len() == 2 {
                assert_ne!(hs[0], hs[1], "edge {e:?} run twice the same way");
            }
        }
    }

    /// `check_basic`, every edge on exactly two faces in opposite directions,
    /// outward orientation, and the Euler characteristic.
    fn check_closed(m: &MeshInput, chi: i64) {
        check_basic(m);
        for (e, hs) in edges(m) {
            assert_eq!(hs.len(), 2, "boundary edge {e:?}");
        }
        assert_eq!(euler(m), chi);
        assert!(volume(m) > 0.0, "inward orientation: {}", volume(m));
    }

    /// `check_basic`, one boundary loop, Euler characteristic 1, normals
    /// mostly up (signed projected area > 0).
    fn check_open_disk(m: &MeshInput) {
        check_basic(m);
        assert_eq!(euler(m), 1);
        let boundary: Vec<(u32, u32)> = edges(m)
            .values()
            .filter(|h| h.len() == 1)
            .map(|h| h[0])
            .collect();
        assert!(!boundary.is_empty());
        // One loop: follow it from any boundary half-edge.
        let next: BTreeMap<u32, u32> = boundary.iter().copied().collect();
        assert_eq!(next.len(), boundary.len(), "boundary vertex twice");
        let (mut v, mut steps) = (boundary[0].0, 0);
        loop {
            v = next[&v];
            steps += 1;
            if v == boundary[0].0 {
                break;
            }
        }
        assert_eq!(steps, boundary.len(), "more than one boundary loop");
        let mut area = 0.0;
        for f in &m.faces {
            for k in 0..f.len() {
                let p = m.vertices[f[k] as usize];
                let q = m.vertices[f[(k + 1) % f.len()] as usize];
                area += p[0] * q[1] - q[0] * p[1];
            }
        }
        assert!(area > 0.0);
    }

    fn count(val: &[usize], v: usize) -> usize {
        val.iter().filter(|&&x| x == v).count()
    }

    #[test]
    fn trig_is_accurate() {
        for k in -40..40 {
            let x = k as f64 * 0.37;
            let (s, c) = sin_cos(x);
            assert!((s * s + c * c - 1.0).abs() < 1e-14, "{x}");
            assert!((s - std_sin(x)).abs() < 1e-14, "{x}");
        }
        let (s, c) = sin_cos(PI / 6.0);
        assert!((s - 0.5).abs() < 1e-15 && (c - 0.75f64.sqrt()).abs() < 1e-15);
    }

    /// std's sine (tests link std).
    fn std_sin(x: f64) -> f64 {
        extern crate std;
        std::primitive::f64::sin(x)
    }

    #[test]
    fn globe_has_two_poles_and_regular_rings() {
        for (n, r) in [(3, 7), (6, 7), (8, 9), (17, 12)] {
            let m = globe(n, r);
            check_closed(&m, 2);
            assert_eq!(m.vertices.len(), n * r + 2);
            assert_eq!(m.faces.len(), n * (r + 1));
            let val = valences(&m);
            assert_eq!(poles(&m).iter().map(|p| p.1).collect::<Vec<_>>(), [n, n]);
            assert_eq!(count(&val, 4), n * r);
            // Close to the unit sphere (inscribed polyhedron).
            if n >= 6 {
                let ball = 4.0 / 3.0 * PI;
                assert!(volume(&m) < ball && volume(&m) > 0.6 * ball);
            }
        }
        // Parameters below the minimum are raised.
        assert_eq!(globe(1, 2), globe(3, 7));
    }

    #[test]
    fn pole_disk_is_an_open_polar_configuration() {
        for (n, l) in [(3, 2), (5, 4), (12, 6)] {
            let m = pole_disk(n, l);
            check_open_disk(&m);
            assert_eq!(m.vertices.len(), n * l + 1);
            assert_eq!(m.faces.len(), n * l);
            let val = valences(&m);
            assert_eq!(poles(&m), [(0, n)]);
            assert_eq!(count(&val, 4), n * (l - 1));
            assert_eq!(count(&val[1..], 3), n);
        }
    }

    #[test]
    fn mushroom_has_two_valence_12_poles() {
        let m = mushroom();
        check_closed(&m, 2);
        assert_eq!((m.vertices.len(), m.faces.len()), (206, 216));
        assert_eq!(poles(&m).iter().map(|p| p.1).collect::<Vec<_>>(), [12, 12]);
        assert_eq!(count(&valences(&m), 4), 204);
        // The profile (ring k's first point is vertex 1 + 12k): the underside
        // of the cap rises between rim and stem (concave), the stem narrows
        // then bulges at the foot.
        let ring = |k: usize| m.vertices[1 + 12 * k];
        assert!(ring(7)[2] < ring(8)[2] && ring(8)[2] > ring(9)[2]);
        assert!(ring(11)[0] < ring(13)[0] && ring(13)[0] > ring(14)[0]);
    }

    #[test]
    fn hand_has_six_poles_and_valence_5_junctions() {
        let m = hand();
        check_closed(&m, 2);
        assert_eq!((m.vertices.len(), m.faces.len()), (549, 580));
        assert_eq!(m.faces.iter().filter(|f| f.len() == 3).count(), 66);
        let mut pole_valences: Vec<usize> = poles(&m).iter().map(|p| p.1).collect();
        pole_valences.sort_unstable();
        assert_eq!(pole_valences, [8, 8, 8, 8, 8, 26]);
        let val = valences(&m);
        assert_eq!(count(&val, 5), 16);
        assert_eq!(count(&val, 4), 549 - 6 - 16);
        // Every 1-link vertex of a pole is 4-valent (2 triangles + 2 quads),
        // and so are links 2 and 3 (the pole's 2- and 3-neighbourhood).
        let e = edges(&m);
        let mut adj = vec![Vec::new(); m.vertices.len()];
        for &(a, b) in e.keys() {
            adj[a as usize].push(b as usize);
            adj[b as usize].push(a as usize);
        }
        for (p, _) in poles(&m) {
            let mut frontier = vec![p];
            let mut seen = vec![p];
            for _ in 0..3 {
                let mut next = Vec::new();
                for &v in &frontier {
                    for &w in &adj[v] {
                        if !seen.contains(&w) {
                            seen.push(w);
                            next.push(w);
                            assert_eq!(val[w], 4, "pole {p}: vertex {w}");
                        }
                    }
                }
                frontier = next;
            }
        }
    }

    #[test]
    fn cubes_have_eight_valence_3_corners() {
        let m = cube();
        check_closed(&m, 2);
        assert_eq!((m.vertices.len(), m.faces.len()), (8, 6));
        assert!(valences(&m).iter().all(|&v| v == 3));
        assert!((volume(&m) - 8.0).abs() < 1e-12);
        for k in [1, 2, 3, 5] {
            let m = rounded_cube(k);
            check_closed(&m, 2);
            assert_eq!(m.vertices.len(), 6 * k * k + 2);
            assert_eq!(m.faces.len(), 6 * k * k);
            let val = valences(&m);
            assert_eq!(count(&val, 3), 8);
            assert_eq!(count(&val, 4), 6 * k * k - 6);
            assert!(m.faces.iter().all(|f| f.len() == 4));
        }
    }

    #[test]
    fn two_beam_corner_has_valence_5_where_the_beams_meet() {
        let m = two_beam_corner();
        check_closed(&m, 2);
        assert_eq!((m.vertices.len(), m.faces.len()), (90, 88));
        let val = valences(&m);
        assert_eq!(count(&val, 3), 10);
        assert_eq!(count(&val, 5), 2);
        assert_eq!(count(&val, 4), 78);
        for (v, p) in m.vertices.iter().enumerate() {
            if val[v] == 5 {
                assert_eq!([p[0], p[1]], [0.5, 0.5]);
            }
        }
        // The valence-5 points' 1-rings are regular.
        for (a, b) in edges(&m).into_keys() {
            let (a, b) = (a as usize, b as usize);
            if val[a] == 5 {
                assert_eq!(val[b], 4);
            }
            if val[b] == 5 {
                assert_eq!(val[a], 4);
            }
        }
        assert!((volume(&m) - 40.0 / 64.0).abs() < 1e-12);
    }

    #[test]
    fn torus_and_grid_are_regular() {
        for (nu, nv) in [(3, 3), (8, 5), (24, 12)] {
            let m = torus(nu, nv);
            check_closed(&m, 0);
            assert_eq!((m.vertices.len(), m.faces.len()), (nu * nv, nu * nv));
            assert!(valences(&m).iter().all(|&v| v == 4));
        }
        for (nu, nv) in [(1, 1), (4, 3), (10, 10)] {
            let m = grid(nu, nv);
            check_open_disk(&m);
            assert_eq!(m.vertices.len(), (nu + 1) * (nv + 1));
            assert_eq!(m.faces.len(), nu * nv);
            let val = valences(&m);
            assert_eq!(count(&val, 2), 4);
            if nu > 1 && nv > 1 {
                assert_eq!(count(&val, 4), (nu - 1) * (nv - 1));
                assert_eq!(count(&val, 3), 2 * (nu - 1) + 2 * (nv - 1));
            }
        }
    }

    #[test]
    fn extraordinary_disk_has_one_irregular_centre() {
        for (n, r) in [(3, 2), (5, 3), (6, 2), (10, 4)] {
            let m = extraordinary_disk(n, r);
            check_open_disk(&m);
            assert_eq!(m.vertices.len(), 1 + n * r * (r + 1));
            assert_eq!(m.faces.len(), n * r * r);
            let val = valences(&m);
            assert_eq!(val[0], n);
            // Interior vertices other than the centre are 4-valent.
            let boundary: BTreeSet<u32> = edges(&m)
                .values()
                .filter(|h| h.len() == 1)
                .map(|h| h[0].0)
                .collect();
            for (v, &valence) in val.iter().enumerate().skip(1) {
                if !boundary.contains(&(v as u32)) {
                    assert_eq!(valence, 4, "vertex {v}");
                }
            }
            assert!(m.faces.iter().all(|f| f.len() == 4));
        }
    }

    #[test]
    fn triangle_and_pentagon_mesh_has_no_pole() {
        let m = triangle_and_pentagon_mesh();
        check_closed(&m, 2);
        assert_eq!((m.vertices.len(), m.faces.len()), (10, 9));
        let sizes: Vec<usize> = m.faces.iter().map(|f| f.len()).collect();
        assert_eq!(sizes.iter().filter(|&&s| s == 3).count(), 4);
        assert_eq!(sizes.iter().filter(|&&s| s == 4).count(), 3);
        assert_eq!(sizes.iter().filter(|&&s| s == 5).count(), 2);
        assert!(poles(&m).is_empty());
    }

    #[test]
    fn icosphere_is_a_closed_outward_sphere_of_valence_5_and_6() {
        for levels in 0..3 {
            let m = icosphere(levels);
            check_closed(&m, 2);
            assert_eq!(m.faces.len(), 20 << (2 * levels));
            let v = valences(&m);
            assert_eq!(v.iter().filter(|&&k| k == 5).count(), 12);
            assert!(v.iter().all(|&k| k == 5 || k == 6));
            assert!(volume(&m) > 0.0);
        }
    }

    #[test]
    fn every_sample_passes_the_topology() {
        let closed = [
            globe(6, 8),
            mushroom(),
            hand(),
            cube(),
            rounded_cube(3),
            two_beam_corner(),
            torus(8, 6),
            triangle_and_pentagon_mesh(),
            icosphere(2),
        ];
        for m in &closed {
            assert!(crate::Topology::new(m).unwrap().is_closed());
        }
        for m in [pole_disk(5, 3), grid(3, 4), extraordinary_disk(5, 3)] {
            assert!(!crate::Topology::new(&m).unwrap().is_closed());
        }
    }

    #[test]
    fn benchmark_tori_have_isolated_valence_3_and_5_points_and_their_tags() {
        // base 16: edges turned at i = 0, 4, 8, 12 and j = 0, 2, …, 14 → 32
        // hexagons, each with two valence-3 and two valence-5 points, which
        // the splits keep and move 4 edges apart.
        for (m, tagged) in [(ev_torus(16), false), (feature_torus(16), true)] {
            check_closed(&m, 0);
            assert_eq!(m.faces.len(), 16 * 16 * 16);
            assert!(m.faces.iter().all(|f| f.len() == 4));
            let val = valences(&m);
            assert_eq!((count(&val, 3), count(&val, 5)), (64, 64));
            assert_eq!(val.len(), count(&val, 3) + count(&val, 4) + count(&val, 5));
            let t = &m.tags;
            assert_eq!(!t.creases.is_empty(), tagged);
            assert_eq!(!t.corners.is_empty(), tagged);
            let edge_set: BTreeSet<(u32, u32)> = edges(&m).into_keys().collect();
            for c in &t.creases {
                let [a, b] = c.vertices;
                assert!(
                    edge_set.contains(&(a.min(b), a.max(b))),
                    "crease on an edge"
                );
            }
        }
        // One base face, (5, 12), is a hole: its 16 grandchildren are holes.
        // Both crease sharpnesses survive the splits on both halves.
        let f = feature_torus(16);
        assert_eq!(f.tags.holes.len(), 16);
        assert!(f.tags.holes.iter().all(|&h| (h as usize) < f.faces.len()));
        assert!(f.tags.creases.iter().any(|c| c.sharpness == 2.5));
        assert!(f.tags.creases.iter().any(|c| c.sharpness == 10.0));
    }
}
