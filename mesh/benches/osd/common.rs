//! What the OpenSubdiv side-by-side benchmarks share: the benchmark meshes,
//! the timing loop (the same as `osd_bench.cpp`'s), the OpenSubdiv helper's
//! build and its job files. Included by each bench with `#[path]`; each uses
//! a part of it.
#![allow(dead_code)]

use super::osd;
use capdiv_mesh::{samples, EdgeCrease, MeshInput, VertexCorner};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// capdiv's cap depth and OpenSubdiv's isolation level.
pub const DEPTH: u32 = 4;

/// Catmull-Clark's topological split (positions averaged, not smoothed):
/// every k-gon becomes k quads, its children contiguous and in corner order.
/// Tags follow: a crease edge's two halves keep its sharpness, a hole's
/// children are holes, corners stay on their vertex.
pub fn split(m: &MeshInput) -> MeshInput {
    let mut vertices = m.vertices.clone();
    let mut edge_point: HashMap<(u32, u32), u32> = HashMap::new();
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

/// `samples::torus(base, base)` with, for i ≡ 0 (mod 4) and j even, the
/// edge shared by faces (i, j) and (i+1, j) turned by one step in their
/// hexagon: two valence-3 and two valence-5 points per turned edge.
fn turned_torus(base: usize) -> MeshInput {
    let n = base;
    let mut m = samples::torus(n, n);
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
/// tags: [`turned_torus`] split twice, so the extraordinary points are 4
/// edges apart.
pub fn ev_torus(base: usize) -> MeshInput {
    split(&split(&turned_torus(base)))
}

/// A torus of `16·base²` quads with features, from `samples::torus(base,
/// base)` split twice ([`split`]):
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
    split(&split(&m))
}

/// Median seconds per call of `f`, timed as `osd_bench.cpp` times.
pub fn time(mut f: impl FnMut()) -> (f64, usize) {
    let batch_of = |f: &mut dyn FnMut(), n: usize| {
        let t = Instant::now();
        for _ in 0..n {
            f();
        }
        t.elapsed()
    };
    let mut batch = 1;
    let mut took;
    loop {
        took = batch_of(&mut f, batch);
        if took >= Duration::from_millis(2) || batch >= 1 << 20 {
            break;
        }
        batch *= 2;
    }
    let samples = ((2.0 / took.as_secs_f64()) as usize).clamp(5, 21);
    let mut per: Vec<f64> = (0..samples)
        .map(|_| batch_of(&mut f, batch).as_secs_f64() / batch as f64)
        .collect();
    per.sort_by(f64::total_cmp);
    (per[samples / 2], samples)
}

/// The OpenSubdiv helper, built into the bench's target directory when its
/// source is newer.
pub fn helper() -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/osd/osd_bench.cpp");
    osd::compile(&src, "osd-bench")
}

/// Writes the job file of mesh `name` (isolation [`DEPTH`]) and returns its
/// path.
pub fn job_file(name: &str, mesh: &MeshInput) -> PathBuf {
    let mut job = osd::Job::new(mesh);
    job.isolation = DEPTH;
    let name: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}.osdjob"));
    std::fs::write(&path, osd::job_text(&job)).expect("write the job file");
    path
}
