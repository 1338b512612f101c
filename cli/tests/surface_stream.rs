//! `capdiv surface` writes OBJ (f64) and compact JSON as it produces them:
//! the streamed files hold the collected surface — the OBJ the same vertex,
//! normal and face lines in the same order as the collected tessellation
//! (`build_scheme` + `tessellate_surface` + `obj_text`, which PNG and glTF
//! output still use), the JSON the same document as the collected `--pretty`
//! output.

mod common;

use capdiv_cli::commands::surface::{build_scheme, obj_text, tessellate_surface, WELD_F64};
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

/// The lines starting with one of `keys`, in order.
fn pick(text: &str, keys: &[&str]) -> Vec<String> {
    text.lines()
        .filter(|l| keys.iter().any(|k| l.starts_with(k)))
        .map(String::from)
        .collect()
}

#[test]
fn streamed_obj_is_the_collected_tessellation() {
    let dir = tempdir();
    for (name, mesh, depth, grid) in [
        ("hand", samples::hand(), 3, 4),
        ("globe", samples::globe(8, 6), 2, 3),
        ("cube", samples::cube(), 4, 2),
        ("grid", samples::grid(4, 3), 2, 4),
        ("pentagon", samples::triangle_and_pentagon_mesh(), 2, 1),
    ] {
        let path = dir.path().join(format!("{name}.obj"));
        std::fs::write(&path, obj_of(&mesh)).unwrap();
        let (d, g) = (depth.to_string(), grid.to_string());
        let out = dir.path().join(format!("{name}-out.obj"));
        let run = capdiv(
            &[
                "surface",
                "--depth",
                &d,
                "--grid",
                &g,
                "-o",
                s(&out),
                s(&path),
            ],
            None,
        );
        assert_eq!(run.code, Some(0), "{}", run.stderr);
        let streamed = std::fs::read_to_string(&out).unwrap();

        // The collected surface from the same (parsed) mesh.
        let parsed = capdiv_mesh::obj::parse_obj(&obj_of(&mesh)).unwrap();
        let surface =
            build_scheme::<f64>(name, &parsed, depth, &[], "f64", false, u64::MAX).unwrap();
        let tess = tessellate_surface(&surface, &parsed, grid as usize, WELD_F64, None).unwrap();
        let collected = obj_text(&tess, &surface.summary, "title").unwrap();

        assert_eq!(
            pick(&streamed, &["v ", "vn "]),
            pick(&collected, &["v ", "vn "]),
            "{name}"
        );
        assert_eq!(
            pick(&streamed, &["f "]),
            pick(&collected, &["f "]),
            "{name}"
        );
        // Every face after its vertices.
        let mut vertices = 0;
        for line in pick(&streamed, &["v ", "f "]) {
            if line.starts_with("v ") {
                vertices += 1;
            } else {
                for c in line.split_whitespace().skip(1) {
                    let i: usize = c.split("//").next().unwrap().parse().unwrap();
                    assert!(i <= vertices, "{name}: {line} before its vertex");
                }
            }
        }
        // The header's counts, closedness and weld lines, at the top or the end.
        let comments = pick(&streamed, &["# "]);
        for line in pick(&collected, &["# "]).iter().skip(1) {
            assert!(comments.contains(line), "{name}: missing {line}");
        }
        // The summary on stderr counts the same.
        assert!(
            run.stderr
                .contains(&format!("tessellation {} vertices", tess.info.vertices)),
            "{name}: {}",
            run.stderr
        );
    }
}

/// The document without its times (they differ from run to run).
fn untimed(text: &str) -> Value {
    let mut v: Value = serde_json::from_str(text).expect("JSON");
    v["summary"]
        .as_object_mut()
        .expect("summary")
        .remove("times_ms");
    v
}

#[test]
fn streamed_json_is_the_collected_document() {
    let dir = tempdir();
    for (name, mesh) in [
        ("mushroom", samples::mushroom()),
        ("globe", samples::globe(6, 5)),
        ("two-beam", samples::two_beam_corner()),
    ] {
        let path = dir.path().join(format!("{name}.obj"));
        std::fs::write(&path, obj_of(&mesh)).unwrap();
        for precision in ["f64", "f32"] {
            let args = |pretty: bool| {
                let mut a = vec![
                    "surface",
                    "--quiet",
                    "--depth",
                    "2",
                    "--format",
                    "json",
                    "--precision",
                    precision,
                ];
                if pretty {
                    a.push("--pretty");
                }
                a.push(s(&path));
                a
            };
            let streamed = capdiv(&args(false), None);
            streamed.assert_ok();
            let collected = capdiv(&args(true), None);
            collected.assert_ok();
            let text = streamed.stdout_str();
            // Compact: one line.
            assert!(text.ends_with("}\n") && text.lines().count() == 1);
            assert_eq!(
                untimed(&text),
                untimed(&collected.stdout_str()),
                "{name} {precision}"
            );
        }
    }
}

/// A surface that fails after the analysis leaves no output file behind.
#[test]
fn a_refused_stream_writes_no_file() {
    let dir = tempdir();
    let path = dir.path().join("cube.obj");
    std::fs::write(&path, obj_of(&samples::cube())).unwrap();
    for format in ["obj", "json"] {
        let out = dir.path().join(format!("out.{format}"));
        let run = capdiv(
            &["surface", "--max-patches", "10", "-o", s(&out), s(&path)],
            None,
        );
        assert_eq!(run.code, Some(2), "{format}");
        assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
        assert!(!out.exists(), "{format}");
        let leftovers: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(leftovers.len(), 1, "{leftovers:?}");
    }
}

/// An empty surface (every face a hole) is refused before any byte of a
/// streamed output reaches stdout.
#[test]
fn an_empty_streamed_surface_writes_nothing() {
    let mesh = serde_json::json!({
        "kind": "mesh",
        "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
        "faces": [[0, 1, 2, 3]],
        "holes": [0]
    });
    let text = serde_json::to_vec(&mesh).unwrap();
    for format in ["obj", "json"] {
        let run = capdiv(&["surface", "--format", format, "-"], Some(&text));
        assert_eq!(run.code, Some(2), "{format}: {}", run.stderr);
        assert!(run.stdout.is_empty(), "{format}: {}", run.stdout_str());
        assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    }
}
