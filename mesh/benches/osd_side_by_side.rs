//! capdiv's analysis side by side with OpenSubdiv 3.5's, on the same meshes
//! with the same tags, per input face; and the patches each makes per face.
//!
//! - capdiv: [`SurfacePlan::for_mesh`] at depth 4 (validation, topology, tags,
//!   caps, feature-adaptive refinement); patches counted from one
//!   [`Evaluator::evaluate`].
//! - OpenSubdiv: `TopologyRefinerFactory::Create`, `RefineAdaptive` to
//!   isolation level 4, `PatchTableFactory::Create` (Gregory basis end caps,
//!   infinitely sharp patches) and a `PatchMap`, in `osd/osd_bench.cpp`,
//!   built here with `g++ … -losdCPU` and run on a job file of each mesh
//!   (the format of `tests/osd/oracle.cpp`).
//!
//! Both sides time the same way: batches of analyses (doubled until a batch
//! takes 2 ms), then 5..21 batches (about 2 s), the median time per analysis;
//! a result is dropped inside the timed batch on both sides.
//!
//! `cargo bench -p capdiv-mesh --bench osd_side_by_side` prints markdown
//! tables (`-- --only NAME,NAME` for some meshes). For instruction counts
//! (`scripts/osd-side-by-side.sh`): `-- --prepare NAME` writes the mesh's job
//! file and prints the helper's and the job's paths, `-- --once NAME` runs
//! the analysis once inside `capdiv_analyse` (callgrind's
//! `--toggle-collect=capdiv_analyse`).

#[path = "../tests/osd/mod.rs"]
mod osd;

use capdiv_mesh::{samples, CapRecord, EdgeCrease, Evaluator, MeshInput, PatchRecord};
use capdiv_mesh::{PlanOptions, SurfacePlan, SurfaceSink, Topology, VertexCorner};
use std::collections::{BTreeMap, HashMap};
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// capdiv's cap depth and OpenSubdiv's isolation level.
const DEPTH: u32 = 4;

/// A named benchmark mesh.
struct Case {
    name: &'static str,
    mesh: MeshInput,
}

/// Catmull-Clark's topological split (positions averaged, not smoothed):
/// every k-gon becomes k quads, its children contiguous and in corner order.
/// Tags follow: a crease edge's two halves keep its sharpness, a hole's
/// children are holes, corners stay on their vertex.
fn split(m: &MeshInput) -> MeshInput {
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
fn feature_torus(base: usize) -> MeshInput {
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

/// The unit icosahedron's triangles split `levels` times into four (edge
/// midpoints pushed to the sphere): `20·4^levels` triangles, twelve
/// valence-5 vertices, all others valence 6.
fn icosphere(levels: u32) -> MeshInput {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
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
    let unit = |p: [f64; 3]| {
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        [p[0] / r, p[1] / r, p[2] / r]
    };
    for p in &mut vertices {
        *p = unit(*p);
    }
    for _ in 0..levels {
        let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
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
            next.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
        }
        faces = next;
    }
    MeshInput::new(vertices, faces.iter().map(|f| f.to_vec()).collect())
}

/// Builds one benchmark mesh.
type Make = fn() -> MeshInput;

/// The meshes, in table order; only those `keep` accepts are built.
fn cases(keep: &dyn Fn(&str) -> bool) -> Vec<Case> {
    let makers: [(&'static str, Make); 14] = [
        ("torus-features-1e4", || feature_torus(25)),
        ("torus-features-1e5", || feature_torus(79)),
        ("grid-1e4", || samples::grid(100, 100)),
        ("grid-1e5", || samples::grid(316, 316)),
        ("feature-mix-1e4", || samples::feature_mix(10_000)),
        ("icosphere-1280", || icosphere(3)),
        ("icosphere-5120", || icosphere(4)),
        ("globe(8,12)", || samples::globe(8, 12)),
        ("mushroom", samples::mushroom),
        ("hand", samples::hand),
        ("rounded_cube(6)", || samples::rounded_cube(6)),
        ("cube", samples::cube),
        ("two_beam_corner", samples::two_beam_corner),
        ("triangle_and_pentagon", samples::triangle_and_pentagon_mesh),
    ];
    makers
        .into_iter()
        .filter(|(name, _)| keep(name))
        .map(|(name, make)| Case { name, mesh: make() })
        .collect()
}

fn options() -> PlanOptions<'static> {
    PlanOptions {
        depth: DEPTH,
        ..Default::default()
    }
}

/// The measured analysis, under a fixed symbol for callgrind.
#[no_mangle]
#[inline(never)]
fn capdiv_analyse(mesh: &MeshInput) -> SurfacePlan<'static> {
    SurfacePlan::for_mesh(mesh, options()).expect("capdiv analyses the mesh")
}

/// Median seconds per call of `f`, timed as `osd_bench.cpp` times.
fn time(mut f: impl FnMut()) -> (f64, usize) {
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

/// Counts the patches of one evaluation by level.
#[derive(Default)]
struct Count {
    by_level: BTreeMap<u32, usize>,
    acc: f64,
}

impl SurfaceSink<f64> for Count {
    fn patch(&mut self, p: &PatchRecord<f64>) {
        *self.by_level.entry(p.level).or_default() += 1;
        self.acc += p.domain[0];
    }
    fn cap(&mut self, c: &CapRecord<f64>) {
        self.acc += c.limit.0[0];
    }
}

/// The OpenSubdiv helper, built into the bench's target directory when its
/// source is newer.
fn helper() -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/osd/osd_bench.cpp");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let bin = dir.join("osd-bench");
    let modified = |p: &Path| std::fs::metadata(p).and_then(|m| m.modified()).ok();
    if modified(&bin).is_some_and(|b| modified(&src).is_some_and(|s| b >= s)) {
        return bin;
    }
    std::fs::create_dir_all(dir).expect("create CARGO_TARGET_TMPDIR");
    let tmp = dir.join(format!("osd-bench.{}.tmp", std::process::id()));
    let out = Command::new("g++")
        .args(["-O2", "-std=c++14"])
        .arg(&src)
        .arg("-o")
        .arg(&tmp)
        .arg("-losdCPU")
        .output()
        .expect("run g++ (install g++ and libosd-dev)");
    assert!(
        out.status.success(),
        "building osd_bench.cpp failed (install libosd-dev):\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::rename(&tmp, &bin).expect("rename the helper");
    bin
}

/// Writes the mesh's job file (isolation [`DEPTH`]) and returns its path.
fn job_file(case: &Case) -> PathBuf {
    let mut job = osd::Job::new(&case.mesh);
    job.isolation = DEPTH;
    let name: String = case
        .name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}.osdjob"));
    std::fs::write(&path, osd::job_text(&job)).expect("write the job file");
    path
}

/// The helper's `key value` lines.
fn run_helper(helper: &Path, job: &Path) -> BTreeMap<String, f64> {
    let out = Command::new(helper)
        .arg(job)
        .output()
        .expect("run the OpenSubdiv helper");
    assert!(
        out.status.success(),
        "OpenSubdiv helper failed on {}:\n{}",
        job.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| {
            let (k, v) = l.split_once(' ')?;
            Some((k.to_string(), v.trim().parse().ok()?))
        })
        .collect()
}

struct Row {
    name: &'static str,
    faces: usize,
    capdiv_ns: f64,
    capdiv_samples: usize,
    topology_ns: f64,
    osd: BTreeMap<String, f64>,
    patches: BTreeMap<u32, usize>,
    uncovered: usize,
    steps: usize,
}

fn levels(total: f64, by: impl Iterator<Item = (u32, f64)>) -> String {
    by.filter(|&(_, n)| n > 0.0)
        .map(|(l, n)| format!("{l}: {:.0}%", 100.0 * n / total))
        .collect::<Vec<_>>()
        .join(", ")
}

fn measure(case: &Case, helper: &Path) -> Row {
    let faces = case.mesh.faces.len();
    let (capdiv, capdiv_samples) = time(|| {
        black_box(capdiv_analyse(black_box(&case.mesh)));
    });
    let (topology, _) = time(|| {
        black_box(Topology::new(black_box(&case.mesh)).ok());
    });
    let plan = capdiv_analyse(&case.mesh);
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    let mut count = Count::default();
    ev.evaluate(&plan, &case.mesh.vertices, &mut count)
        .expect("evaluate");
    black_box(count.acc);
    let osd = run_helper(helper, &job_file(case));
    Row {
        name: case.name,
        faces,
        capdiv_ns: capdiv * 1e9,
        capdiv_samples,
        topology_ns: topology * 1e9,
        osd,
        patches: count.by_level,
        uncovered: plan.uncovered.len(),
        steps: plan.steps.len(),
    }
}

fn print_tables(rows: &[Row]) {
    println!("### Analysis per input face (wall clock, median)\n");
    println!(
        "| mesh | faces | capdiv `for_mesh` ns/face | (its `Topology::new`) | OSD Create | \
         OSD RefineAdaptive | OSD PatchTable | OSD PatchMap | OSD total ns/face | \
         capdiv / OSD |"
    );
    println!("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
    for r in rows {
        let f = r.faces as f64;
        let o = |k: &str| r.osd.get(k).copied().unwrap_or(f64::NAN) / f;
        println!(
            "| {} | {} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.2} |",
            r.name,
            r.faces,
            r.capdiv_ns / f,
            r.topology_ns / f,
            o("create_ns"),
            o("refine_ns"),
            o("table_ns"),
            o("map_ns"),
            o("total_ns"),
            r.capdiv_ns / r.osd["total_ns"],
        );
    }
    println!("\n### Patches per input face\n");
    println!(
        "| mesh | faces | capdiv patches/face | OSD patches/face | capdiv by level | \
         OSD by depth | OSD end caps/face | capdiv steps, uncovered |"
    );
    println!("|---|--:|--:|--:|---|---|--:|---|");
    for r in rows {
        let f = r.faces as f64;
        let capdiv: usize = r.patches.values().sum();
        let osd = r.osd["patches"];
        let osd_levels = (0..=20u32).filter_map(|d| Some((d, *r.osd.get(&format!("depth{d}"))?)));
        println!(
            "| {} | {} | {:.2} | {:.2} | {} | {} | {:.3} | {}, {} |",
            r.name,
            r.faces,
            capdiv as f64 / f,
            osd / f,
            levels(
                capdiv as f64,
                r.patches.iter().map(|(&l, &n)| (l, n as f64))
            ),
            levels(osd, osd_levels),
            r.osd["endcap"] / f,
            r.steps,
            r.uncovered,
        );
    }
    let samples: Vec<String> = rows
        .iter()
        .map(|r| format!("{}/{}", r.capdiv_samples, r.osd["samples"]))
        .collect();
    println!(
        "\nSamples (capdiv/OSD) per mesh: {}. Ratio > 1: capdiv's analysis is slower.",
        samples.join(", ")
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1).cloned())
    };
    if let Some(name) = value("--once") {
        let case = cases(&|n| n == name).pop().expect("unknown mesh");
        let plan = capdiv_analyse(&case.mesh);
        println!("faces {}", case.mesh.faces.len());
        println!("regular {}", plan.regular.len());
        return;
    }
    if let Some(name) = value("--prepare") {
        let case = cases(&|n| n == name).pop().expect("unknown mesh");
        println!("helper {}", helper().display());
        println!("job {}", job_file(&case).display());
        println!("faces {}", case.mesh.faces.len());
        return;
    }
    let only = value("--only");
    let keep = |n: &str| only.as_ref().is_none_or(|o| o.split(',').any(|x| x == n));
    let helper = helper();
    let mut rows = Vec::new();
    for case in cases(&keep) {
        eprintln!("measuring {} ({} faces)", case.name, case.mesh.faces.len());
        rows.push(measure(&case, &helper));
    }
    print_tables(&rows);
}
