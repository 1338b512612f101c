//! `capdiv surface --tolerance`: caps stop emitting rings once their hole is
//! small enough; `none` is the fixed-depth surface of the library's
//! `build_scheme`, patch for patch; the summary says the rings used.

mod common;

use capdiv_cli::commands::surface::{build_scheme, PatchJson};
use capdiv_mesh::samples;
use capdiv_mesh::MeshInput;
use common::*;
use serde_json::Value;

fn obj_of(m: &MeshInput) -> String {
    let mut obj = String::new();
    for v in &m.vertices {
        obj += &format!("v {:?} {:?} {:?}\n", v[0], v[1], v[2]);
    }
    for f in &m.faces {
        let ids: Vec<String> = f.iter().map(|i| (i + 1).to_string()).collect();
        obj += &format!("f {}\n", ids.join(" "));
    }
    obj
}

#[test]
fn tolerance_none_is_the_fixed_depth_surface() {
    let dir = tempdir();
    let mesh = samples::hand();
    let path = dir.path().join("hand.obj");
    std::fs::write(&path, obj_of(&mesh)).unwrap();
    let run = capdiv(
        &[
            "surface",
            "--depth",
            "3",
            "--tolerance",
            "none",
            "--format",
            "json",
            s(&path),
        ],
        None,
    );
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(
        run.stderr
            .contains("rings        3 per cap (--depth 3; no tolerance)"),
        "{}",
        run.stderr
    );
    let got = run.json();
    let parsed = capdiv_mesh::obj::parse_obj(&obj_of(&mesh)).unwrap();
    let fixed = build_scheme::<f64>("hand", &parsed, 3, &[], "f64", false, u64::MAX).unwrap();
    let want: Vec<Value> = fixed
        .patches
        .iter()
        .map(|p| serde_json::to_value(PatchJson::new(p)).unwrap())
        .collect();
    assert_eq!(got["patches"].as_array().unwrap(), &want);
    assert_eq!(got["summary"]["rings"], serde_json::json!([3, 3]));
    assert_eq!(got["summary"]["tolerance"], Value::Null);
}

/// Rings used, from the summary's `rings` line.
fn rings(stderr: &str) -> (u32, u32) {
    let line = stderr
        .lines()
        .find(|l| l.trim_start().starts_with("rings"))
        .unwrap_or_else(|| panic!("no rings line: {stderr}"));
    let range = line.split_whitespace().nth(1).unwrap();
    match range.split_once('-') {
        Some((a, b)) => (a.parse().unwrap(), b.parse().unwrap()),
        None => (range.parse().unwrap(), range.parse().unwrap()),
    }
}

#[test]
fn the_summary_gives_the_rings_used_and_the_default_stops_early() {
    let dir = tempdir();
    // A fine mesh: its caps' first rings are already small.
    let mesh = samples::rounded_cube(6);
    let path = dir.path().join("rc.obj");
    std::fs::write(&path, obj_of(&mesh)).unwrap();
    let run_with = |tol: Option<&str>| {
        let mut args = vec!["surface", "--depth", "6", "--format", "json"];
        if let Some(t) = tol {
            args.extend(["--tolerance", t]);
        }
        args.push(s(&path));
        let run = capdiv(&args, None);
        assert_eq!(run.code, Some(0), "{}", run.stderr);
        let json = run.json();
        let summary = &json["summary"];
        let r = rings(&run.stderr);
        assert_eq!(summary["rings"], serde_json::json!([r.0, r.1]));
        (r, summary["patches"]["total"].as_u64().unwrap())
    };
    let (default, n_default) = run_with(None);
    let (rel, n_rel) = run_with(Some("3e-3rel"));
    assert_eq!((default, n_default), (rel, n_rel), "the default is 3e-3rel");
    assert!(default.1 < 6, "{default:?}");
    let (none, n_none) = run_with(Some("none"));
    assert_eq!(none, (6, 6));
    assert!(n_default < n_none);
    // An absolute tolerance as wide as the mesh: one ring everywhere.
    let (wide, _) = run_with(Some("100"));
    assert_eq!(wide, (1, 1));
}

#[test]
fn a_bad_tolerance_is_one_line() {
    for bad in ["0", "-1", "abc", "nan", "1e-3relx", "inf"] {
        let arg = format!("--tolerance={bad}");
        let run = capdiv(&["surface", &arg, "mesh.obj"], None);
        assert_eq!(run.code, Some(2), "{bad}");
        assert_eq!(run.stderr.lines().count(), 1, "{bad}: {}", run.stderr);
        assert!(run.stderr.contains("tolerance"), "{bad}: {}", run.stderr);
    }
}

/// With a tolerance, `--max-patches` refuses by the count with every cap at
/// `--depth` (an upper bound: "up to"), the count `--tolerance none` makes.
#[test]
fn max_patches_counts_every_cap_at_the_depth() {
    let dir = tempdir();
    let path = dir.path().join("rc.obj");
    std::fs::write(&path, obj_of(&samples::rounded_cube(6))).unwrap();
    let total = |tol: &str| {
        let run = capdiv(
            &[
                "surface",
                "--depth",
                "6",
                "--tolerance",
                tol,
                "--format",
                "json",
                s(&path),
            ],
            None,
        );
        assert_eq!(run.code, Some(0), "{}", run.stderr);
        run.json()["patches"].as_array().unwrap().len()
    };
    let (fixed, early) = (total("none"), total("3e-3rel"));
    assert!(early < fixed);
    let limit = (fixed - 1).to_string();
    let run = capdiv(
        &[
            "surface",
            "--depth",
            "6",
            "--max-patches",
            &limit,
            "--format",
            "json",
            s(&path),
        ],
        None,
    );
    assert_eq!(run.code, Some(2));
    assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    assert!(
        run.stderr
            .contains(&format!("would have up to {fixed} patches")),
        "{}",
        run.stderr
    );
}
