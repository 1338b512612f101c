//! Shared helpers of the CLI integration tests: run the built binary, build
//! test configurations, parse outputs.
#![allow(dead_code)]

use serde_json::{json, Value};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// What one run of the binary produced.
pub struct Run {
    pub code: Option<i32>,
    pub stdout: Vec<u8>,
    pub stderr: String,
}

impl Run {
    pub fn stdout_str(&self) -> String {
        String::from_utf8(self.stdout.clone()).expect("stdout is UTF-8")
    }
    pub fn json(&self) -> Value {
        serde_json::from_slice(&self.stdout).unwrap_or_else(|e| {
            panic!(
                "stdout is not JSON ({e}); stderr: {}; code {:?}",
                self.stderr, self.code
            )
        })
    }
    /// Asserts success and returns the JSON on stdout.
    pub fn ok_json(&self) -> Value {
        self.assert_ok();
        self.json()
    }
    pub fn assert_ok(&self) {
        assert_eq!(self.code, Some(0), "stderr: {}", self.stderr);
        assert!(self.stderr.is_empty(), "stderr: {}", self.stderr);
    }
}

/// Runs `capdiv args…`, feeding `stdin` when given.
pub fn capdiv(args: &[&str], stdin: Option<&[u8]>) -> Run {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_capdiv"));
    cmd.args(args)
        .stdin(if stdin.is_some() {
            Stdio::piped()
        } else {
            Stdio::null()
        })
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = cmd.spawn().expect("spawn capdiv");
    if let Some(bytes) = stdin {
        let mut pipe = child.stdin.take().expect("stdin pipe");
        // A command that fails before reading its input (a usage error)
        // closes the pipe early: that is its right, not a test failure.
        if let Err(e) = pipe.write_all(bytes) {
            assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe, "write stdin: {e}");
        }
    }
    let out = child.wait_with_output().expect("wait capdiv");
    Run {
        code: out.status.code(),
        stdout: out.stdout,
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// A temporary directory for inputs and outputs.
pub fn tempdir() -> tempfile::TempDir {
    tempfile::tempdir().expect("tempdir")
}

/// Writes `value` as JSON to `dir/name` and returns the path.
pub fn write_json(dir: &Path, name: &str, value: &Value) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_vec(value).unwrap()).unwrap();
    path
}

/// Path as `&str` for the command line.
pub fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

/// Deterministic pseudo-random numbers in [-1, 1) (64-bit LCG).
pub struct Lcg(u64);
impl Lcg {
    pub fn new(seed: u64) -> Self {
        Lcg(seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407))
    }
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

/// A polar configuration of valence `n` with `k` links: link `i` near the
/// circle of radius `i`, counter-clockwise, with a bump and noise of size
/// `0.1` so that nothing is symmetric.
pub fn config(n: usize, k: usize, seed: u64) -> ([f64; 3], Vec<Vec<[f64; 3]>>) {
    let mut rng = Lcg::new(seed);
    let pole = [0.1 * rng.next(), 0.1 * rng.next(), 0.2 + 0.1 * rng.next()];
    let links = (1..=k)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / n as f64;
                    let r = i as f64;
                    [
                        r * t.cos() + 0.1 * rng.next(),
                        r * t.sin() + 0.1 * rng.next(),
                        0.3 * r * r * (1.0 + 0.5 * t.cos()) + 0.1 * rng.next(),
                    ]
                })
                .collect()
        })
        .collect();
    (pole, links)
}

/// The input JSON of a configuration.
pub fn polar_json(pole: [f64; 3], links: &[Vec<[f64; 3]>]) -> Value {
    json!({"kind": "polar", "pole": pole, "links": links})
}

/// A point `[x, y, z]` from JSON.
pub fn p3(v: &Value) -> [f64; 3] {
    let a = v.as_array().expect("point is an array");
    assert_eq!(a.len(), 3, "point has 3 coordinates");
    [0, 1, 2].map(|k| a[k].as_f64().expect("coordinate is a number"))
}

/// `(pole, links)` of a polar configuration printed by the CLI.
pub fn parse_polar(v: &Value) -> ([f64; 3], Vec<Vec<[f64; 3]>>) {
    assert_eq!(v["kind"], "polar");
    let obj = v.as_object().unwrap();
    assert_eq!(obj.len(), 3, "exactly kind, pole, links: {obj:?}");
    let links = v["links"]
        .as_array()
        .expect("links is an array")
        .iter()
        .map(|l| l.as_array().expect("link").iter().map(p3).collect())
        .collect();
    (p3(&v["pole"]), links)
}

/// Largest absolute coordinate of a configuration (its scale).
pub fn scale(pole: &[f64; 3], links: &[Vec<[f64; 3]>]) -> f64 {
    links
        .iter()
        .flatten()
        .chain(std::iter::once(pole))
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, c| m.max(c.abs()))
}

/// Largest coordinate difference of two points.
pub fn diff(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max)
}

/// An 8-bit RGB picture read from a PNG file.
pub struct Png {
    pub w: usize,
    pub h: usize,
    pub rgb: Vec<u8>,
}

/// Reads the 8-bit RGB PNG at `path`.
pub fn read_png(path: &std::path::Path) -> Png {
    let (w, h, rgb) = decode_png(&std::fs::read(path).expect("read the PNG"));
    Png { w, h, rgb }
}

impl Png {
    /// The colour of pixel `(x, y)`.
    pub fn at(&self, x: usize, y: usize) -> [u8; 3] {
        let k = 3 * (y * self.w + x);
        [self.rgb[k], self.rgb[k + 1], self.rgb[k + 2]]
    }

    /// Pixels of `rows` whose colour passes `f`.
    pub fn count(&self, rows: std::ops::Range<usize>, f: impl Fn([u8; 3]) -> bool) -> usize {
        rows.flat_map(|y| (0..self.w).map(move |x| (x, y)))
            .filter(|&(x, y)| f(self.at(x, y)))
            .count()
    }
}

/// Width, height and RGB bytes of an 8-bit RGB PNG.
pub fn decode_png(bytes: &[u8]) -> (usize, usize, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().expect("PNG header");
    let mut buf = vec![0; reader.output_buffer_size().expect("buffer size")];
    let info = reader.next_frame(&mut buf).expect("PNG data");
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    buf.truncate(info.buffer_size());
    (info.width as usize, info.height as usize, buf)
}

/// A c-net of valence `n` (docs/math/eg.md §1): node `(x, y)` of sector `s` near
/// `x u_s + y u_{s+1}` in the plane (`u_s` the unit vector at angle 2πs/n),
/// lifted by a bump, plus noise of size 0.1 so that nothing is symmetric.
/// Returns `(center, sectors)` in the §1 order.
pub fn cnet(n: usize, seed: u64) -> ([f64; 3], Vec<[[f64; 3]; 6]>) {
    let mut rng = Lcg::new(seed);
    let center = [0.1 * rng.next(), 0.1 * rng.next(), 0.2 + 0.1 * rng.next()];
    let u = |s: usize| {
        let t = std::f64::consts::TAU * s as f64 / n as f64;
        [t.cos(), t.sin()]
    };
    let sectors = (0..n)
        .map(|s| {
            let (a, b) = (u(s), u(s + 1));
            [(1., 0.), (2., 0.), (1., 1.), (2., 1.), (1., 2.), (2., 2.)].map(|(x, y)| {
                let px = x * a[0] + y * b[0];
                let py = x * a[1] + y * b[1];
                [
                    px + 0.1 * rng.next(),
                    py + 0.1 * rng.next(),
                    0.3 * (px * px + py * py) * (1.0 + 0.3 * px) + 0.1 * rng.next(),
                ]
            })
        })
        .collect();
    (center, sectors)
}

/// The input JSON of a c-net.
pub fn cnet_json(center: [f64; 3], sectors: &[[[f64; 3]; 6]]) -> Value {
    json!({"kind": "cnet", "center": center, "sectors": sectors})
}

/// The input JSON of a d-net (`c0` omitted when `None`).
pub fn dnet_json(sectors: &[[[f64; 3]; 12]], c0: Option<[f64; 3]>) -> Value {
    match c0 {
        Some(c0) => json!({"kind": "dnet", "c0": c0, "sectors": sectors}),
        None => json!({"kind": "dnet", "sectors": sectors}),
    }
}

/// `(c0, sectors)` of a d-net printed by the CLI (exactly `kind`, `c0`,
/// `sectors`; 12 points a sector).
pub fn parse_dnet(v: &Value) -> ([f64; 3], Vec<[[f64; 3]; 12]>) {
    assert_eq!(v["kind"], "dnet");
    let obj = v.as_object().unwrap();
    assert_eq!(obj.len(), 3, "exactly kind, c0, sectors: {obj:?}");
    let sectors = v["sectors"]
        .as_array()
        .expect("sectors is an array")
        .iter()
        .map(|s| {
            let pts: Vec<[f64; 3]> = s.as_array().expect("sector").iter().map(p3).collect();
            pts.try_into().expect("12 points a sector")
        })
        .collect();
    (p3(&v["c0"]), sectors)
}

/// A Wavefront OBJ file as parsed: `v`, `vn`, faces of `(v, vn)` indices.
pub struct Obj {
    pub v: Vec<[f64; 3]>,
    pub vn: Vec<[f64; 3]>,
    pub f: Vec<Vec<(usize, usize)>>,
}

/// Parses the OBJ subset the CLI writes (panics on anything else).
pub fn parse_obj(text: &str) -> Obj {
    let mut obj = Obj {
        v: vec![],
        vn: vec![],
        f: vec![],
    };
    for line in text.lines() {
        let mut it = line.split_whitespace();
        let nums = |it: std::str::SplitWhitespace| -> [f64; 3] {
            let v: Vec<f64> = it.map(|x| x.parse().expect("number")).collect();
            assert_eq!(v.len(), 3, "{line}");
            [v[0], v[1], v[2]]
        };
        match it.next() {
            Some("v") => obj.v.push(nums(it)),
            Some("vn") => obj.vn.push(nums(it)),
            Some("f") => obj.f.push(
                it.map(|c| {
                    let (a, b) = c.split_once("//").expect("v//vn");
                    (a.parse().unwrap(), b.parse().unwrap())
                })
                .collect(),
            ),
            Some(t) if t.starts_with('#') => {}
            None => {}
            Some(other) => panic!("unexpected OBJ line {other}: {line}"),
        }
    }
    obj
}

/// The §7 arrays of docs/math/eg.md for n = 3, typed from the spec (A11, A22,
/// A21, A31, A32).
pub const SPEC_N3: [&[[i64; 12]]; 5] = [
    &[
        [
            -1, -13, -37, 42, -13, 1671, 10243, 2049, -37, 10243, 50096, 5073,
        ],
        [0, 0, 38, 35, -4, 20, -169, -859, -77, -272, -1886, -2793],
    ],
    &[
        [0, 6, -49, -96, 6, -87, 2309, 1776, -49, 2309, 15760, 6979],
        [0, 0, 87, 57, -11, 39, -330, -1928, -58, -793, -3253, -5925],
    ],
    &[
        [0, -10, 2, 1, -5, 153, 8101, 7372, -173, 2036, 32183, 20229],
        [0, 3, 46, -11, -7, -3, 98, -966, -118, 328, 1736, -2329],
        [0, -8, -3, -128, 0, 16, -709, 307, 55, -198, -2703, 4434],
    ],
    &[
        [0, -3, 0, 76, 16, -125, 3642, 9873, 79, -370, 4902, 23927],
        [0, 16, 79, 79, -3, -125, -370, -1761, 0, 3642, 4902, -6789],
        [
            0, -7, 113, 79, -7, 80, -1088, -1761, 113, -1088, -6828, -6789,
        ],
    ],
    &[
        [0, -3, -30, 63, 9, -28, 792, 2658, 14, -402, 341, 7126],
        [0, 9, 14, 44, -3, -28, -402, -1866, -30, 792, 341, -6175],
        [0, -4, 63, 44, -4, 62, -1112, -1866, 63, -1112, -6536, -6175],
    ],
];

/// The §7 arrays for n = 5 (with the spec's corrected A21 r=4 column 01 = −59).
pub const SPEC_N5: [&[[i64; 12]]; 5] = [
    &[
        [
            -129, 221, 50, -28, 221, 2629, 6368, 2877, 50, 6368, 61638, 6916,
        ],
        [-26, 68, -27, 2, 36, -65, -111, -16, 2, -177, -10, -388],
        [28, -41, -27, 21, -57, -73, 278, -17, 4, 306, -692, -676],
    ],
    &[
        [
            -491, 973, 57, -205, 973, -322, -4931, 1147, 57, -4931, 41825, 11869,
        ],
        [
            -74, 217, -103, 27, 68, -164, -225, -200, 76, -94, 2039, -3059,
        ],
        [
            165, -264, -112, 114, -332, -210, 1422, -150, 34, 1591, -5064, -3801,
        ],
    ],
    &[
        [
            -256, 482, 14, -132, 582, -379, 5085, 5035, 70, -3009, 48736, 23656,
        ],
        [
            -143, 317, -74, -16, 243, -143, -857, -44, -67, 434, 5702, -564,
        ],
        [
            89, -140, -48, 53, -195, -107, 773, -48, 67, 874, -2602, -1630,
        ],
        [
            57, -96, -42, 35, -83, -172, 625, -107, -74, 552, -1421, -2015,
        ],
        [
            49, -135, 104, -135, -59, -88, 456, 957, -37, 538, -1701, 3402,
        ],
    ],
    &[
        [
            -269, 492, -13, -197, 541, -115, -84, 9355, -192, -1203, 16754, 43563,
        ],
        [
            -269, 541, -192, -10, 492, -115, -1203, -313, -13, -84, 16754, 641,
        ],
        [
            103, -154, -54, 62, -243, -113, 944, -117, 118, 951, -2635, -2601,
        ],
        [
            79, -125, -80, 62, -125, -219, 800, -117, -80, 800, -2081, -2601,
        ],
    ],
    &[
        [
            -433, 772, -48, -208, 910, -235, -3106, 1327, -264, -2342, 12285, 25197,
        ],
        [
            -433, 910, -264, -41, 772, -235, -2342, -207, -48, -3106, 12285, -542,
        ],
        [
            220, -354, -73, 125, -509, -69, 1859, -299, 263, 1600, -6314, -5478,
        ],
        [
            169, -285, -124, 125, -285, -260, 1544, -299, -124, 1544, -5418, -5478,
        ],
    ],
];

/// Checks that `obj` is a welded, consistently oriented surface with the
/// topology of an annulus (the rings of a cap around its open hole, with the
/// outer region or the outer boundary): every vertex used, every edge used by
/// one face or by two in opposite directions (no crack, no T-junction, no
/// flip), Euler characteristic `V − E + F = 0`, and its boundary edges
/// (used once) forming exactly two closed loops. Returns the loops' lengths
/// in edges, shorter first.
pub fn assert_welded_annulus(obj: &Obj, name: &str) -> [usize; 2] {
    use std::collections::HashMap;
    let mut used = vec![false; obj.v.len()];
    // Directed edge -> uses; undirected edge -> uses.
    let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
    for f in &obj.f {
        for k in 0..f.len() {
            let (a, b) = (f[k].0, f[(k + 1) % f.len()].0);
            assert!(a >= 1 && a <= obj.v.len(), "{name}: index {a}");
            assert_ne!(a, b, "{name}: degenerate edge");
            used[a - 1] = true;
            *directed.entry((a, b)).or_default() += 1;
        }
    }
    assert!(used.iter().all(|&u| u), "{name}: unused vertex");
    let mut boundary: HashMap<usize, usize> = HashMap::new();
    let mut edges = 0;
    for (&(a, b), &n) in &directed {
        assert_eq!(
            n, 1,
            "{name}: edge {a}->{b} used {n} times in one direction"
        );
        match directed.get(&(b, a)) {
            Some(_) => edges += 1, // counted from both sides: halved below
            None => {
                edges += 2;
                assert!(
                    boundary.insert(a, b).is_none(),
                    "{name}: two boundary edges leave vertex {a}"
                );
            }
        }
    }
    let edges = edges / 2;
    let euler = obj.v.len() as i64 - edges as i64 + obj.f.len() as i64;
    assert_eq!(euler, 0, "{name}: Euler characteristic");
    // Boundary loops: each boundary vertex has one outgoing boundary edge.
    let mut seen: HashMap<usize, bool> = HashMap::new();
    let mut loops = Vec::new();
    for &start in boundary.keys() {
        if seen.contains_key(&start) {
            continue;
        }
        let (mut v, mut len) = (start, 0);
        while seen.insert(v, true).is_none() {
            v = *boundary
                .get(&v)
                .unwrap_or_else(|| panic!("{name}: boundary ends at vertex {v}"));
            len += 1;
        }
        assert_eq!(v, start, "{name}: boundary loops cross");
        loops.push(len);
    }
    loops.sort_unstable();
    assert_eq!(loops.len(), 2, "{name}: boundary loops {loops:?}");
    [loops[0], loops[1]]
}

/// Whether `p` is one of `obj`'s vertices, within `tol` per coordinate.
pub fn has_vertex(obj: &Obj, p: &[f64; 3], tol: f64) -> bool {
    obj.v.iter().any(|v| diff(v, p) <= tol)
}

/// A rule-table file `{"valence", "A11", "A22", "A21", "A31", "A32"}`.
pub fn table_json(n: usize, arrays: [&[[i64; 12]]; 5]) -> Value {
    json!({
        "valence": n,
        "A11": arrays[0], "A22": arrays[1], "A21": arrays[2],
        "A31": arrays[3], "A32": arrays[4],
    })
}
