//! Subdivision tags of `capdiv surface` inputs: OpenSubdiv `t` lines in OBJ,
//! the tag fields of JSON meshes, `--boundary` and `--scheme`, and how the
//! summary (JSON and stderr) reports them; `render` and `compare` take
//! `--boundary` too.

mod common;

use common::*;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// A 2×2 grid of quads (vertices 0..9 row by row, faces 0..3) with one tag of
/// every kind applied and one ignored. Tag lines are lines 14..=19.
const GRID: &str = "\
v 0 0 0
v 1 0 0
v 2 0 0
v 0 1 0
v 1 1 0
v 2 1 0
v 0 2 0
v 1 2 0
v 2 2 0
f 1 2 5 4
f 2 3 6 5
f 4 5 8 7
f 5 6 9 8
t crease 4/1/0 1 4 4 7 2.0
t corner 1/1/0 0 10
t hole 1/0/0 3
t interpolateboundary 1/0/0 2
t creasemethod 0/0/1 chaikin
t smoothtriangles 0/0/1 smooth
t facevaryingpropagatecorners 1/0/0 1
";

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn summary_tags(json: &Value) -> &Value {
    &json["summary"]["tags"]
}

#[test]
fn obj_tags_are_read_and_reported() {
    let dir = tempdir();
    let path = write(dir.path(), "grid.obj", GRID);
    let run = capdiv(&["surface", "--depth", "2", s(&path)], None);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let json = run.json();
    assert_eq!(
        summary_tags(&json),
        &json!({
            "creases": 2, "corners": 1, "holes": 1,
            "boundary": "edge-only", "crease_method": "chaikin", "triangles": "smooth",
            "ignored": [{"name": "facevaryingpropagatecorners", "line": 20}]
        })
    );
    assert_eq!(json["summary"]["scheme"], "default");
    let tags = run
        .stderr
        .lines()
        .find(|l| l.trim_start().starts_with("tags"))
        .unwrap_or_else(|| panic!("no tags line: {}", run.stderr));
    for part in [
        "2 creases",
        "1 corner,",
        "1 hole;",
        "boundary edge-only",
        "creasing chaikin",
        "triangles smooth",
        "scheme default",
        "ignored tags: facevaryingpropagatecorners (line 20)",
    ] {
        assert!(tags.contains(part), "{tags:?} lacks {part:?}");
    }
}

#[test]
fn an_untagged_mesh_reports_the_defaults() {
    let dir = tempdir();
    let text: String = GRID
        .lines()
        .filter(|l| !l.starts_with('t'))
        .map(|l| format!("{l}\n"))
        .collect();
    let path = write(dir.path(), "plain.obj", &text);
    let json = capdiv(&["surface", "--quiet", "--depth", "1", s(&path)], None).ok_json();
    assert_eq!(
        summary_tags(&json),
        &json!({
            "creases": 0, "corners": 0, "holes": 0,
            "boundary": "edge-and-corner", "crease_method": "normal", "triangles": "catmark",
            "ignored": []
        })
    );
}

#[test]
fn boundary_and_scheme_flags_are_accepted_and_reported() {
    let dir = tempdir();
    let path = write(dir.path(), "grid.obj", GRID);
    // Every face of this grid touches the boundary: `none` makes them all
    // holes, an empty surface (an error, checked in surface.rs).
    for (boundary, scheme) in [
        ("edge-and-corner", "default"),
        ("edge-only", "catmull-clark"),
    ] {
        let run = capdiv(
            &[
                "surface",
                "--depth",
                "2",
                "--boundary",
                boundary,
                "--scheme",
                scheme,
                s(&path),
            ],
            None,
        );
        assert_eq!(run.code, Some(0), "{boundary} {scheme}: {}", run.stderr);
        let json = run.json();
        assert_eq!(summary_tags(&json)["boundary"], boundary);
        assert_eq!(json["summary"]["scheme"], scheme);
        // The other tags stay as the file gives them.
        assert_eq!(summary_tags(&json)["creases"], 2);
        assert!(run.stderr.contains(&format!("boundary {boundary}")));
        assert!(run.stderr.contains(&format!("scheme {scheme}")));
    }
    // Without --boundary the file's rule holds; the default scheme by name.
    let json = capdiv(
        &["surface", "--quiet", "--scheme", "default", s(&path)],
        None,
    )
    .ok_json();
    assert_eq!(summary_tags(&json)["boundary"], "edge-only");
    for bad in [["--boundary", "edge"], ["--scheme", "c2ps"]] {
        let run = capdiv(&["surface", bad[0], bad[1], s(&path)], None);
        assert_eq!(run.code, Some(2), "{bad:?}");
        assert!(run.stdout.is_empty());
    }
}

#[test]
fn catmull_clark_scheme_gives_catmull_clark_caps() {
    // A cube: eight valence-3 corners, EG caps by default, CC with the flag.
    let cube = capdiv_mesh::samples::cube();
    let mesh = json!({"kind": "mesh", "vertices": cube.vertices, "faces": cube.faces});
    let text = serde_json::to_vec(&mesh).unwrap();
    let caps = |scheme: &str| {
        let json = capdiv(
            &[
                "surface", "--quiet", "--depth", "2", "--scheme", scheme, "-",
            ],
            Some(&text),
        )
        .ok_json();
        let list: Vec<String> = json["caps"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["scheme"].as_str().unwrap().to_string())
            .collect();
        list
    };
    let default = caps("default");
    assert!(
        !default.is_empty() && default.iter().all(|c| c == "eg"),
        "{default:?}"
    );
    let cc = caps("catmull-clark");
    assert_eq!(cc.len(), default.len());
    assert!(cc.iter().all(|c| c == "catmull-clark"), "{cc:?}");
}

#[test]
fn json_mesh_tags_are_read_like_obj_tags() {
    let dir = tempdir();
    let obj = write(dir.path(), "grid.obj", GRID);
    let from_obj = capdiv(&["surface", "--quiet", "--depth", "2", s(&obj)], None).ok_json();
    let vertices: Vec<[f64; 3]> = (0..9)
        .map(|k| [(k % 3) as f64, (k / 3) as f64, 0.0])
        .collect();
    let mesh = json!({
        "kind": "mesh",
        "vertices": vertices,
        "faces": [[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6], [4, 5, 8, 7]],
        "creases": [[1, 4, 2.0], [4, 7, 2]],
        "corners": [[0, 10]],
        "holes": [3],
        "boundary": "edge-only",
        "crease_method": "chaikin",
        "triangles": "smooth"
    });
    let path = write_json(dir.path(), "grid.json", &mesh);
    let from_json = capdiv(&["surface", "--quiet", "--depth", "2", s(&path)], None).ok_json();
    let mut want = summary_tags(&from_obj).clone();
    want["ignored"] = json!([]);
    assert_eq!(summary_tags(&from_json), &want);
    assert_eq!(from_json["patches"], from_obj["patches"]);
    // Every field is optional.
    for (field, value) in [
        ("boundary", json!("edge-only")),
        ("crease_method", json!("normal")),
        ("triangles", json!("catmark")),
        ("holes", json!([])),
    ] {
        let mut m = json!({"kind": "mesh", "vertices": vertices,
                           "faces": [[0, 1, 4, 3]]});
        m[field] = value;
        let p = write_json(dir.path(), &format!("{field}.json"), &m);
        capdiv(&["surface", "--quiet", "--depth", "1", s(&p)], None).ok_json();
    }
}

/// Runs `surface` on `content`, expects exit 2, no stdout and one line
/// `error: …` containing every needle.
fn expect_error(dir: &Path, label: &str, content: &str, needles: &[&str]) {
    let path = write(dir, label, content);
    let run = capdiv(&["surface", s(&path)], None);
    assert_eq!(run.code, Some(2), "{label}: {}", run.stderr);
    assert!(run.stdout.is_empty(), "{label}");
    assert_eq!(run.stderr.lines().count(), 1, "{label}: {}", run.stderr);
    assert!(run.stderr.starts_with("error: "), "{label}: {}", run.stderr);
    for needle in needles {
        assert!(
            run.stderr.contains(needle),
            "{label}: {:?} lacks {needle:?}",
            run.stderr
        );
    }
}

#[test]
fn malformed_obj_tags_fail_naming_the_line() {
    let dir = tempdir();
    let cases = [
        (
            "t crease 2/1/0 1 4",
            "line 14: tag crease: 2/1/0 announces 3 values",
        ),
        (
            "t crease 2/1/0 1 4 -2",
            "line 14: tag crease: sharpness -2 is negative",
        ),
        (
            "t crease 2/1/0 0 4 1",
            "line 14: tag crease: vertices 0 and 4 are not joined",
        ),
        (
            "t crease 2/1/0 1 x 1",
            "line 14: tag crease: `x` is not an integer",
        ),
        (
            "t crease 2/1/0 1 9 1",
            "line 14: tag crease: vertex 9 out of range (9 vertices)",
        ),
        (
            "t corner 1/1/0 0 nan",
            "line 14: tag corner: sharpness is NaN",
        ),
        (
            "t hole 1/0/0 4",
            "line 14: tag hole: face 4 out of range (4 faces)",
        ),
        (
            "t interpolateboundary 1/0/0 5",
            "line 14: tag interpolateboundary: 5 is not 0",
        ),
        (
            "t creasemethod 0/0/1 smooth",
            "line 14: tag creasemethod: `smooth` is not",
        ),
        (
            "t smoothtriangles 0/0/2 smooth",
            "line 14: tag smoothtriangles: 0/0/2 announces 2",
        ),
    ];
    for (k, (tag, needle)) in cases.iter().enumerate() {
        // The bad tag replaces the first tag line (line 14).
        let text = GRID.replacen("t crease 4/1/0 1 4 4 7 2.0", tag, 1);
        expect_error(dir.path(), &format!("bad{k}.obj"), &text, &[needle, "bad"]);
    }
}

#[test]
fn malformed_json_tags_fail_naming_the_entry() {
    let dir = tempdir();
    let base =
        r#""kind": "mesh", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "faces": [[0,1,2,3]]"#;
    let cases = [
        (
            r#""creases": [[0, 1, 1], [0, 2, 1]]"#,
            "creases[1]: vertices 0 and 2 are not joined",
        ),
        (
            r#""creases": [[0, 1, -1]]"#,
            "creases[0]: sharpness -1 is negative",
        ),
        (r#""creases": [[0, 1]]"#, "wrong schema"),
        (r#""creases": [[0, 1.5, 1]]"#, "wrong schema"),
        (
            r#""corners": [[4, 1]]"#,
            "corners[0]: vertex 4 out of range (4 vertices)",
        ),
        (
            r#""corners": [[-1, 1]]"#,
            "corners[0]: vertex -1 out of range",
        ),
        (
            r#""holes": [0, 1]"#,
            "holes[1]: face 1 out of range (1 faces)",
        ),
        (r#""boundary": "edge""#, "unknown variant `edge`"),
        (r#""crease_method": "uniform""#, "unknown variant `uniform`"),
        (
            r#""creases": [[0, 1, 1]], "sharpness": 2"#,
            "unknown field `sharpness`",
        ),
    ];
    for (k, (extra, needle)) in cases.iter().enumerate() {
        let text = format!("{{{base}, {extra}}}");
        expect_error(dir.path(), &format!("bad{k}.json"), &text, &[needle]);
    }
}

#[test]
fn render_and_compare_take_boundary() {
    let dir = tempdir();
    let path = write(dir.path(), "grid.obj", GRID);
    for (command, boundary) in [("render", "edge-only"), ("compare", "edge-and-corner")] {
        let png = dir.path().join(format!("{command}.png"));
        let run = capdiv(
            &[
                command,
                "--depth",
                "2",
                "--size",
                "64x64",
                "--boundary",
                boundary,
                "-o",
                s(&png),
                s(&path),
            ],
            None,
        );
        assert_eq!(run.code, Some(0), "{command}: {}", run.stderr);
        assert!(png.exists());
    }
    // A malformed tag fails render as it fails surface.
    let bad = write(
        dir.path(),
        "bad.obj",
        &GRID.replacen("t hole 1/0/0 3", "t hole 1/0/0 7", 1),
    );
    let png = dir.path().join("bad.png");
    let run = capdiv(&["render", "-o", s(&png), s(&bad)], None);
    assert_eq!(run.code, Some(2));
    assert!(
        run.stderr.contains("line 16: tag hole: face 7"),
        "{}",
        run.stderr
    );
    // --boundary on an input that is not a mesh is refused.
    let run = capdiv(
        &[
            "render",
            "--boundary",
            "none",
            "-o",
            s(&png),
            "sample:c2ps-convex-n20",
        ],
        None,
    );
    assert_eq!(run.code, Some(2));
    assert_eq!(run.stderr.lines().count(), 1);
    assert!(
        run.stderr.contains("--boundary needs a 'mesh' input"),
        "{}",
        run.stderr
    );
}
