//! OpenSubdiv 3.5 (Debian `libosd-dev`) as a test oracle for the Catmull-Clark
//! limit surface with creases, corners, holes and boundary rules.
//!
//! `oracle.cpp` (next to this file) is compiled once per test binary with
//! `g++ … -losdCPU` into `CARGO_TARGET_TMPDIR` and run with a plain-text job
//! on stdin: the mesh and its [`capdiv_mesh::SubdivTags`], ptex points to
//! evaluate on the limit surface, and input vertices whose limit positions
//! are wanted. A missing OpenSubdiv installation is a test failure, never a
//! skip.
//!
//! Use from an integration test with `#[path = "osd/mod.rs"] mod osd;`.
#![allow(dead_code)]

use capdiv_mesh::{BoundaryInterpolation, CreaseMethod, MeshInput};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;

/// A point of the limit surface in OpenSubdiv's ptex parametrisation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Query {
    /// The input face.
    pub face: u32,
    /// `None` for a quad; for a face with k ≠ 4 vertices, its sub-quad at
    /// corner `0..k` (OpenSubdiv's ptex sub-face: origin at that corner,
    /// u towards the midpoint of the edge to the next corner, v towards the
    /// midpoint of the edge from the previous corner, (1,1) the centroid).
    pub corner: Option<u8>,
    /// Ptex coordinates in [0, 1]².
    pub u: f64,
    pub v: f64,
}

impl Query {
    /// A point of quad face `face`.
    pub fn quad(face: u32, u: f64, v: f64) -> Self {
        Query {
            face,
            corner: None,
            u,
            v,
        }
    }

    /// A point of the sub-quad at `corner` of a non-quad face.
    pub fn sub(face: u32, corner: u8, u: f64, v: f64) -> Self {
        Query {
            face,
            corner: Some(corner),
            u,
            v,
        }
    }
}

/// What to ask OpenSubdiv about one mesh.
#[derive(Clone, Debug)]
pub struct Job<'a> {
    /// The control mesh with its tags.
    pub mesh: &'a MeshInput,
    /// Adaptive isolation level (1..=10).
    pub isolation: u32,
    /// Points of the limit surface.
    pub queries: Vec<Query>,
    /// Input vertices whose limit positions are wanted.
    pub limits: Vec<u32>,
}

impl<'a> Job<'a> {
    /// A job without queries, isolation level 8.
    pub fn new(mesh: &'a MeshInput) -> Self {
        Job {
            mesh,
            isolation: 8,
            queries: Vec::new(),
            limits: Vec::new(),
        }
    }
}

/// OpenSubdiv's answer to one [`Query`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Answer {
    /// On a regular B-spline patch of refined vertices (boundary and
    /// infinitely sharp rules included): the exact limit surface. The `u32`
    /// is the patch's refinement depth.
    Exact([f64; 3], u32),
    /// On an end-cap (Gregory) patch around an irregular feature at the
    /// isolation level: an approximation only.
    Irregular([f64; 3]),
    /// No patch there (a hole, or a face dropped by the boundary rule).
    NoPatch,
}

impl Answer {
    /// The point of an [`Answer::Exact`]; panics otherwise.
    #[track_caller]
    pub fn exact(&self) -> [f64; 3] {
        match self {
            Answer::Exact(p, _) => *p,
            other => panic!("OpenSubdiv answer is not exact: {other:?}"),
        }
    }

    /// The point of an exact or irregular answer; `None` for no patch.
    pub fn point(&self) -> Option<[f64; 3]> {
        match self {
            Answer::Exact(p, _) | Answer::Irregular(p) => Some(*p),
            Answer::NoPatch => None,
        }
    }
}

const INSTALL: &str = "install libosd-dev: apt-get install libosd-dev";

/// The source of the oracle program.
pub fn source() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/osd/oracle.cpp")
}

/// The compiled oracle, built on first use (and again when the source is
/// newer than the binary). Panics when OpenSubdiv is not installed.
pub fn oracle() -> &'static Path {
    static BINARY: OnceLock<PathBuf> = OnceLock::new();
    BINARY.get_or_init(|| compile(&source(), "osd-oracle"))
}

/// `src` (a C++ program over OpenSubdiv) compiled by `g++ -O2 -losdCPU` to
/// `CARGO_TARGET_TMPDIR/name`, unless that binary is newer than `src`.
/// Panics when OpenSubdiv or g++ is not installed. The oracle and the
/// benches' helper are built this way.
pub fn compile(src: &Path, name: &str) -> PathBuf {
    let headers = ["/usr/include/opensubdiv", "/usr/local/include/opensubdiv"];
    assert!(
        headers
            .iter()
            .any(|h| Path::new(h).join("far/patchTable.h").exists()),
        "OpenSubdiv headers not found in {headers:?}; {INSTALL}"
    );
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let bin = dir.join(name);
    let modified = |p: &Path| std::fs::metadata(p).and_then(|m| m.modified()).ok();
    let src_time = modified(src).unwrap_or_else(|| panic!("cannot read {}", src.display()));
    if modified(&bin).is_some_and(|t| t >= src_time) {
        return bin;
    }
    std::fs::create_dir_all(dir).expect("create CARGO_TARGET_TMPDIR");
    // Build under a private name and rename: other test binaries may be
    // building or running the same program at the same time.
    let tmp = dir.join(format!("{name}.{}.tmp", std::process::id()));
    let out = Command::new("g++")
        .args(["-O2", "-std=c++14"])
        .arg(src)
        .arg("-o")
        .arg(&tmp)
        .arg("-losdCPU")
        .output()
        .unwrap_or_else(|e| panic!("cannot run g++ ({e}); install g++ and libosd-dev"));
    assert!(
        out.status.success(),
        "building {} failed ({INSTALL}):\n{}",
        src.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::rename(&tmp, &bin).expect("rename the compiled program");
    bin
}

fn sharpness(s: f32) -> String {
    assert!(!s.is_nan(), "NaN sharpness cannot be given to OpenSubdiv");
    // OpenSubdiv reads f32 text; ≥ 10 is infinitely sharp already.
    if s.is_infinite() && s > 0.0 {
        "10".into()
    } else {
        format!("{s}")
    }
}

/// The job as the oracle reads it on stdin.
pub fn job_text(job: &Job) -> String {
    let mesh = job.mesh;
    let tags = &mesh.tags;
    let mut t = String::new();
    writeln!(t, "vertices {}", mesh.vertices.len()).unwrap();
    for p in &mesh.vertices {
        writeln!(t, "{:e} {:e} {:e}", p[0], p[1], p[2]).unwrap();
    }
    writeln!(t, "faces {}", mesh.faces.len()).unwrap();
    for f in &mesh.faces {
        write!(t, "{}", f.len()).unwrap();
        for v in f {
            write!(t, " {v}").unwrap();
        }
        t.push('\n');
    }
    writeln!(t, "creases {}", tags.creases.len()).unwrap();
    for c in &tags.creases {
        let [a, b] = c.vertices;
        writeln!(t, "{a} {b} {}", sharpness(c.sharpness)).unwrap();
    }
    writeln!(t, "corners {}", tags.corners.len()).unwrap();
    for c in &tags.corners {
        writeln!(t, "{} {}", c.vertex, sharpness(c.sharpness)).unwrap();
    }
    writeln!(t, "holes {}", tags.holes.len()).unwrap();
    for h in &tags.holes {
        writeln!(t, "{h}").unwrap();
    }
    let boundary = match tags.boundary {
        BoundaryInterpolation::None => "none",
        BoundaryInterpolation::EdgeOnly => "edge-only",
        BoundaryInterpolation::EdgeAndCorner => "edge-and-corner",
    };
    let creasing = match tags.crease_method {
        CreaseMethod::Uniform => "uniform",
        CreaseMethod::Chaikin => "chaikin",
    };
    writeln!(t, "boundary {boundary}").unwrap();
    writeln!(t, "creasing {creasing}").unwrap();
    writeln!(t, "triangles {}", tags.triangles.id()).unwrap();
    writeln!(t, "isolation {}", job.isolation).unwrap();
    writeln!(t, "queries {}", job.queries.len()).unwrap();
    for q in &job.queries {
        let corner = q.corner.map_or(-1, i32::from);
        writeln!(t, "{} {corner} {:e} {:e}", q.face, q.u, q.v).unwrap();
    }
    writeln!(t, "limits {}", job.limits.len()).unwrap();
    for v in &job.limits {
        writeln!(t, "{v}").unwrap();
    }
    // Face-varying UVs (none unless the mesh has them).
    let uv = mesh.has_uvs();
    writeln!(t, "uvs {}", if uv { mesh.uvs.len() } else { 0 }).unwrap();
    if uv {
        for p in &mesh.uvs {
            writeln!(t, "{:e} {:e}", p[0], p[1]).unwrap();
        }
        for f in &mesh.uv_faces {
            let line: Vec<String> = f.iter().map(|i| i.to_string()).collect();
            writeln!(t, "{}", line.join(" ")).unwrap();
        }
    }
    t
}

fn point(words: &[&str], line: &str) -> [f64; 3] {
    let mut p = [0.0; 3];
    for (c, w) in p.iter_mut().zip(words) {
        *c = w
            .parse()
            .unwrap_or_else(|_| panic!("bad number in oracle output line {line:?}"));
    }
    p
}

/// Runs OpenSubdiv on the job: one [`Answer`] per query, one limit position
/// per entry of `limits`. Panics (with the oracle's stderr) on any failure,
/// including topology OpenSubdiv rejects.
#[track_caller]
pub fn run(job: &Job) -> (Vec<Answer>, Vec<[f64; 3]>) {
    let (answers, limits, _) = run_with_uvs(job);
    (answers, limits)
}

/// Per query, OpenSubdiv's face-varying UV (`None` where no patch is).
pub type UvAnswers = Vec<Option<[f64; 2]>>;

/// [`run`], and, when the mesh has UVs, per query OpenSubdiv's
/// face-varying UV there (`FVAR_LINEAR_ALL`).
#[track_caller]
pub fn run_with_uvs(job: &Job) -> (Vec<Answer>, Vec<[f64; 3]>, UvAnswers) {
    let input = job_text(job);
    let mut child = Command::new(oracle())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start the OpenSubdiv oracle");
    let mut stdin = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()));
    let out = child.wait_with_output().expect("run the OpenSubdiv oracle");
    let written = writer.join().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "OpenSubdiv oracle failed ({}):\n{stderr}",
        out.status
    );
    written.expect("write the job to the oracle");
    let stdout = String::from_utf8(out.stdout).expect("oracle output is UTF-8");
    let mut lines = stdout.lines();
    let mut next = || {
        lines
            .next()
            .unwrap_or_else(|| panic!("oracle output too short:\n{stdout}\nstderr:\n{stderr}"))
    };
    let answers = (0..job.queries.len())
        .map(|_| {
            let line = next();
            let words: Vec<&str> = line.split_whitespace().collect();
            assert_eq!(words.len(), 5, "bad oracle answer {line:?}");
            let p = point(&words[1..4], line);
            match words[0] {
                "ok" => Answer::Exact(p, words[4].parse().expect("depth")),
                "irregular" => Answer::Irregular(p),
                "none" => Answer::NoPatch,
                _ => panic!("bad oracle answer {line:?}"),
            }
        })
        .collect();
    let limits = (0..job.limits.len())
        .map(|_| {
            let line = next();
            let words: Vec<&str> = line.split_whitespace().collect();
            assert_eq!(words.len(), 3, "bad oracle limit {line:?}");
            point(&words, line)
        })
        .collect();
    let uvs = if job.mesh.has_uvs() {
        (0..job.queries.len())
            .map(|_| {
                let line = next();
                let words: Vec<&str> = line.split_whitespace().collect();
                assert!(
                    words.len() == 4 && words[0] == "uv",
                    "bad oracle uv {line:?}"
                );
                let uv = [words[2], words[3]].map(|w| {
                    w.parse::<f64>()
                        .unwrap_or_else(|_| panic!("bad number in oracle uv {line:?}"))
                });
                (words[1] == "ok").then_some(uv)
            })
            .collect()
    } else {
        Vec::new()
    };
    (answers, limits, uvs)
}
