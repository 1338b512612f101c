//! `capdiv patches --stream`: the same patches as without it, in
//! the same order and the same layout (JSON compact and pretty; OBJ: the same
//! welded tessellation, faces after their vertices), equal
//! to rounding — f64 within 1e-12 and f32 within 1e-6 of the input's size
//! (the kernel's streaming bounds, tests/polar_stream.rs) — checks before any
//! output, and memory that does not grow with the depth.

mod common;

use capdiv_cli::json::indent;
use common::*;
use serde_json::Value;
use std::io::Read;
use std::process::{Command, Stdio};

fn size(pole: [f64; 3], links: &[Vec<[f64; 3]>]) -> f64 {
    let mut lo = pole;
    let mut hi = pole;
    for p in links.iter().flatten() {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
}

/// The text with every number replaced by `#`: the layout.
fn shape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut in_num = false;
    for c in text.chars() {
        let num = c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '-' | '+');
        if num && !in_num {
            out.push('#');
        } else if !num {
            out.push(c);
        }
        in_num = num;
    }
    out
}

fn numbers(v: &Value, out: &mut Vec<f64>) {
    match v {
        Value::Number(x) => out.push(x.as_f64().unwrap()),
        Value::Array(a) => a.iter().for_each(|x| numbers(x, out)),
        Value::Object(o) => o.values().for_each(|x| numbers(x, out)),
        _ => {}
    }
}

#[test]
fn json_equals_the_in_place_output() {
    let dir = tempdir();
    for (n, k, depth) in [(6, 5, 4), (5, 7, 3), (3, 2, 4), (7, 4, 3)] {
        let (pole, links) = config(n, k, (n * k) as u64);
        let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
        let sz = size(pole, &links);
        for (precision, tol) in [("f64", 1e-12), ("f32", 1e-6)] {
            for first in ["uniform", "plain"] {
                let d = depth.to_string();
                let base = [
                    "patches",
                    "--depth",
                    &d,
                    "--precision",
                    precision,
                    "--first-step",
                    first,
                ];
                let with = |extra: &[&str]| {
                    let mut a: Vec<&str> = base.to_vec();
                    a.extend_from_slice(extra);
                    a.push(s(&file));
                    let r = capdiv(&a, None);
                    r.assert_ok();
                    r
                };
                let plain = with(&[]);
                let streamed = with(&["--stream"]);
                let (a, b) = (plain.json(), streamed.json());
                let (a, b) = (a.as_array().unwrap(), b.as_array().unwrap());
                assert_eq!(a.len(), b.len(), "n {n} k {k}: patch count");
                for (x, y) in a.iter().zip(b) {
                    assert_eq!(x["level"], y["level"]);
                    assert_eq!(x["degree"], y["degree"]);
                    let (mut u, mut v) = (Vec::new(), Vec::new());
                    numbers(&x["points"], &mut u);
                    numbers(&y["points"], &mut v);
                    assert_eq!(u.len(), v.len());
                    for (p, q) in u.iter().zip(&v) {
                        assert!((p - q).abs() <= tol * sz, "{p} vs {q} ({precision})");
                    }
                }
                // Pretty: the layout `indent` gives the whole list.
                let pretty = with(&["--pretty", "--stream"]);
                let compact = streamed.stdout_str();
                let mut want = indent(compact.trim_end().as_bytes());
                want.push(b'\n');
                assert_eq!(pretty.stdout_str(), String::from_utf8(want).unwrap());
                assert_eq!(
                    shape(&pretty.stdout_str()),
                    shape(&with(&["--pretty"]).stdout_str())
                );
            }
        }
    }
}

#[test]
fn obj_and_output_file_equal_the_in_place_output() {
    let dir = tempdir();
    let (pole, links) = config(6, 6, 11);
    let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
    let sz = size(pole, &links);
    let args = ["patches", "--depth", "3", "--format", "obj", "--grid", "3"];
    let run = |extra: &[&str]| {
        let mut a = args.to_vec();
        a.extend_from_slice(extra);
        a.push(s(&file));
        let r = capdiv(&a, None);
        r.assert_ok();
        r.stdout_str()
    };
    let (plain, streamed) = (run(&[]), run(&["--stream"]));
    // The same welded tessellation: the same vertex, normal and face lines
    // in the same order (the stream writes each face after its vertices,
    // the in-place output all faces last), the same comment lines (the
    // stream's counts come last).
    let pick = |text: &str, keys: &[&str]| -> Vec<String> {
        text.lines()
            .filter(|l| keys.iter().any(|k| l.starts_with(k)))
            .map(String::from)
            .collect()
    };
    let mut comments = (pick(&plain, &["#"]), pick(&streamed, &["#"]));
    comments.0.sort();
    comments.1.sort();
    assert_eq!(comments.0, comments.1);
    assert_eq!(pick(&plain, &["f "]), pick(&streamed, &["f "]));
    let (pl, sl) = (
        pick(&plain, &["v ", "vn "]),
        pick(&streamed, &["v ", "vn "]),
    );
    assert_eq!(pl.len(), sl.len());
    for (a, b) in pl.iter().zip(&sl) {
        assert_eq!(shape(a), shape(b));
        let nums = |l: &str| -> Vec<f64> {
            l.split_whitespace()
                .skip(1)
                .map(|x| x.parse().unwrap())
                .collect()
        };
        // Positions within the f64 bound; unit normals of nearly equal
        // patches within 1e-9.
        let tol = if a.starts_with("vn") {
            1e-9
        } else {
            1e-12 * sz
        };
        for (x, y) in nums(a).iter().zip(nums(b)) {
            assert!((x - y).abs() <= tol, "{a} vs {b}");
        }
    }
    // -o: the same bytes as standard output, no temporary left behind.
    let out = dir.path().join("out.obj");
    let mut a = args.to_vec();
    a.extend_from_slice(&["--stream", "-o", s(&out), s(&file)]);
    let r = capdiv(&a, None);
    r.assert_ok();
    assert!(r.stdout.is_empty());
    assert_eq!(std::fs::read_to_string(&out).unwrap(), streamed);
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left.len(), 2, "{left:?}");
}

#[test]
fn errors_come_before_any_output() {
    let dir = tempdir();
    let (pole, mut links) = config(6, 5, 3);
    let good = write_json(dir.path(), "good.json", &polar_json(pole, &links));
    links[1].pop();
    let bad = write_json(dir.path(), "bad.json", &polar_json(pole, &links));
    let out = dir.path().join("out.json");
    for args in [
        vec!["patches", "--depth", "3", "--stream", s(&bad)],
        vec![
            "patches",
            "--depth",
            "3",
            "--stream",
            "-o",
            s(&out),
            s(&bad),
        ],
        vec![
            "patches",
            "--depth",
            "3",
            "--stream",
            "--format",
            "png",
            s(&good),
        ],
        vec!["patches", "--depth", "31", "--stream", s(&good)],
    ] {
        let r = capdiv(&args, None);
        assert_eq!(r.code, Some(2), "{args:?}: {}", r.stderr);
        assert!(r.stdout.is_empty(), "{args:?}");
        assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
    }
    assert!(!out.exists());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
    let cnet = serde_json::json!({
        "kind": "cnet", "center": [0.0, 0.0, 0.0],
        "sectors": (0..3).map(|_| vec![[1.0, 0.0, 0.0]; 6]).collect::<Vec<_>>()
    });
    let cnet = write_json(dir.path(), "cnet.json", &cnet);
    let r = capdiv(&["patches", "--depth", "2", "--stream", s(&cnet)], None);
    assert_eq!(r.code, Some(2));
    assert!(r.stdout.is_empty());
}

/// Peak resident memory (VmHWM, KiB) of `capdiv patches --stream --depth d`
/// and the bytes it wrote, sampled while its output is read.
fn streamed_peak(file: &str, depth: u32) -> (u64, usize) {
    let d = depth.to_string();
    let mut child = Command::new(env!("CARGO_BIN_EXE_capdiv"))
        .args(["patches", "--depth", &d, "--stream", file])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let status = format!("/proc/{}/status", child.id());
    let hwm = || -> Option<u64> {
        let text = std::fs::read_to_string(&status).ok()?;
        let line = text.lines().find(|l| l.starts_with("VmHWM:"))?;
        line.split_whitespace().nth(1)?.parse().ok()
    };
    let mut out = child.stdout.take().unwrap();
    let mut buf = vec![0u8; 1 << 20];
    let (mut total, mut peak) = (0usize, 0u64);
    loop {
        let k = out.read(&mut buf).unwrap();
        if k == 0 {
            break;
        }
        total += k;
        peak = peak.max(hwm().unwrap_or(0));
    }
    assert!(child.wait().unwrap().success());
    (peak, total)
}

#[test]
fn memory_does_not_grow_with_the_depth() {
    if !std::path::Path::new("/proc/self/status").exists() {
        return; // VmHWM is Linux's
    }
    let dir = tempdir();
    let (pole, links) = config(6, 5, 8);
    let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
    let (small, small_bytes) = streamed_peak(s(&file), 6);
    let (large, large_bytes) = streamed_peak(s(&file), 11);
    eprintln!(
        "--stream peak RSS: depth 6 {small} KiB ({small_bytes} bytes out), \
         depth 11 {large} KiB ({large_bytes} bytes out)"
    );
    // 32× the output (~30 MB more), the same memory to within 2 MiB (the
    // in-place path would hold every patch and the whole JSON text).
    assert!(large_bytes > 30 * small_bytes);
    assert!(large < small + 2048, "{small} KiB -> {large} KiB");
}
