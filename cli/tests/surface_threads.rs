//! `capdiv surface --threads N`: the output is the same, byte for byte, for
//! one thread and for several (OBJ, and JSON but for the timings).

mod common;

use capdiv_mesh::{samples, MeshInput};
use common::{capdiv, s, tempdir};
use std::fmt::Write as _;
use std::path::Path;

fn obj_text(mesh: &MeshInput) -> String {
    let mut t = String::new();
    for v in &mesh.vertices {
        let _ = writeln!(t, "v {} {} {}", v[0], v[1], v[2]);
    }
    for f in &mesh.faces {
        let ids: Vec<String> = f.iter().map(|i| (i + 1).to_string()).collect();
        let _ = writeln!(t, "f {}", ids.join(" "));
    }
    t
}

/// The output file of `surface` on `input` with `--threads threads`.
fn output(input: &Path, dir: &Path, format: &str, precision: &str, threads: &str) -> Vec<u8> {
    let out = dir.join(format!("out-{threads}-{precision}.{format}"));
    let run = capdiv(
        &[
            "surface",
            s(input),
            "--depth",
            "3",
            "--format",
            format,
            "--precision",
            precision,
            "--threads",
            threads,
            "--quiet",
            "-o",
            s(&out),
        ],
        None,
    );
    run.assert_ok();
    std::fs::read(&out).unwrap()
}

/// The JSON text without its `"times_ms":{…}` member (wall-clock times).
fn without_times(json: &[u8]) -> Vec<u8> {
    let text = String::from_utf8(json.to_vec()).unwrap();
    let start = text.find("\"times_ms\":{").expect("times_ms");
    let end = start + text[start..].find('}').unwrap() + 1;
    format!("{}{}", &text[..start], &text[end..]).into_bytes()
}

#[test]
fn one_and_two_threads_write_the_same_bytes() {
    let dir = tempdir();
    // Poles (C²PS), valence-3 and -5 points (EG), valence-7 points
    // (Catmull-Clark), boundaries, and enough patches for many pieces.
    let mut mesh = samples::feature_mix(6_000);
    let hand = samples::hand();
    let base = mesh.vertices.len() as u32;
    mesh.vertices
        .extend(hand.vertices.iter().map(|p| [p[0], p[1] + 20.0, p[2]]));
    mesh.faces.extend(
        hand.faces
            .iter()
            .map(|f| f.iter().map(|v| v + base).collect()),
    );
    let input = dir.path().join("mix.obj");
    std::fs::write(&input, obj_text(&mesh)).unwrap();
    for precision in ["f64", "f32"] {
        let one = output(&input, dir.path(), "obj", precision, "1");
        assert!(one.len() > 1_000_000);
        assert!(one == output(&input, dir.path(), "obj", precision, "2"));
        let one = output(&input, dir.path(), "json", precision, "1");
        let two = output(&input, dir.path(), "json", precision, "2");
        assert!(
            without_times(&one) == without_times(&two),
            "{precision} JSON"
        );
    }
}

#[test]
fn zero_threads_is_a_usage_error() {
    let dir = tempdir();
    let input = dir.path().join("cube.obj");
    std::fs::write(&input, obj_text(&samples::cube())).unwrap();
    let run = capdiv(&["surface", s(&input), "--threads", "0"], None);
    assert_eq!(run.code, Some(2));
    assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    assert!(run.stderr.contains("--threads"), "{}", run.stderr);
}
