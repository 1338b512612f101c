//! The CLI under a memory limit (`ulimit -v`): an allocation the system
//! refuses — in the output built whole, in the adaptive refinement, in the
//! streaming weld — is reported as one line `error: … out of memory …` with
//! exit status 2 and no output file, not an abort with a backtrace; output
//! written as it is made fits a limit far below its size.

mod common;

use common::{polar_json, s, tempdir, write_json};
use std::fmt::Write as _;
use std::process::Command;

/// Runs `capdiv ARGS -o OUTPUT` under `ulimit -v LIMIT_KB` and asserts
/// that it fails as [`run_under`] checks: exit status 2, nothing on stdout,
/// one line `error: … out of memory …` on stderr (no panic, no backtrace
/// though `RUST_BACKTRACE=1`), no `output`.
fn runs_out_of_memory(limit_kb: u64, args: &str, output: &std::path::Path) {
    assert_eq!(run_under(limit_kb, args, output), Ending::OutOfMemory);
}

/// The `n × n` vertices of a torus (radii 3 and 1) as OBJ `v` lines, row
/// after row.
fn torus_vertices(n: usize) -> String {
    let mut text = String::new();
    for i in 0..n {
        for j in 0..n {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let b = std::f64::consts::TAU * j as f64 / n as f64;
            let r = 3.0 + b.cos();
            let _ = writeln!(text, "v {} {} {}", r * a.cos(), r * a.sin(), b.sin());
        }
    }
    text
}

/// A torus of `n × n` quads, each split into two triangles, as OBJ text.
fn triangle_torus(n: usize) -> String {
    let mut text = torus_vertices(n);
    let id = |i: usize, j: usize| ((i % n) * n + (j % n) + 1).to_string();
    triangles(&mut text, n, id);
    text
}

/// The `f` lines of the torus' `n × n` quads, each split into two
/// triangles `(a, b, c)`, `(a, c, d)`; `corner(i, j)` is the text of the
/// corner at grid point `(i, j)` (`i`, `j` up to `n`).
fn triangles(text: &mut String, n: usize, corner: impl Fn(usize, usize) -> String) {
    for i in 0..n {
        for j in 0..n {
            let [a, b, c, d] =
                [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)].map(|(i, j)| corner(i, j));
            let _ = writeln!(text, "f {a} {b} {c}");
            let _ = writeln!(text, "f {a} {c} {d}");
        }
    }
}

#[test]
fn pretty_surface_json_is_written_in_less_memory_than_its_text() {
    // 1,800 triangles at the default depth: 123,120 patches, about 190 MB
    // of pretty-printed JSON (540 MB of memory when it was built whole).
    // Written as it is made, it fits a 60 MB limit: the input, its plan and
    // one patch's text. One thread: the evaluation threads' stacks would
    // count against the limit by the machine's core count.
    let dir = tempdir();
    let input = dir.path().join("torus.obj");
    std::fs::write(&input, triangle_torus(30)).unwrap();
    let bin = env!("CARGO_BIN_EXE_capdiv");
    let script = format!(
        "set -o pipefail; ulimit -v 60000 && '{bin}' surface '{}' --threads 1 --format json \
         --pretty | wc -c",
        s(&input)
    );
    let out = Command::new("bash")
        .args(["-c", &script])
        .output()
        .expect("run bash");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "stderr: {stderr}");
    let bytes: u64 = String::from_utf8_lossy(&out.stdout).trim().parse().unwrap();
    assert!(bytes > 150_000_000, "{bytes} bytes");
}

/// A torus of `n × n` quads with every edge creased at `sharpness`, as OBJ
/// text with OpenSubdiv's `t crease` tags.
fn creased_quad_torus(n: usize, sharpness: f64) -> String {
    let mut text = torus_vertices(n);
    let id = |i: usize, j: usize| (i % n) * n + (j % n);
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            let _ = writeln!(text, "f {} {} {} {}", a + 1, b + 1, c + 1, d + 1);
        }
    }
    for i in 0..n {
        for j in 0..n {
            let _ = writeln!(
                text,
                "t crease 2/1/0 {} {} {sharpness}",
                id(i, j),
                id(i + 1, j)
            );
            let _ = writeln!(
                text,
                "t crease 2/1/0 {} {} {sharpness}",
                id(i, j),
                id(i, j + 1)
            );
        }
    }
    text
}

#[test]
fn adaptive_refinement_out_of_memory_is_one_line_and_exit_2() {
    let dir = tempdir();
    let input = dir.path().join("creased.obj");
    // 1,600 quads, every edge creased at sharpness 6: every face goes to the
    // adaptive refinement, which refines along the creases until their
    // sharpness has decayed (about 1 GB of analysis, most of it the
    // refinement's levels, points and patches). The limit leaves room for
    // the input and its topology, not for the refinement: the refusal comes
    // from inside it.
    std::fs::write(&input, creased_quad_torus(40, 6.0)).unwrap();
    let output = dir.path().join("out.obj");
    let args = format!("surface '{}' --threads 1 --format obj", s(&input));
    runs_out_of_memory(400_000, &args, &output);
}

/// A valence-6 polar configuration (five links, a paraboloid) written to
/// `dir`; its path.
fn pole_file(dir: &std::path::Path) -> String {
    let links: Vec<Vec<[f64; 3]>> = (1..=5)
        .map(|k| {
            let r = 0.5 * k as f64;
            (0..6)
                .map(|j| {
                    let a = std::f64::consts::TAU * j as f64 / 6.0;
                    [r * a.cos(), r * a.sin(), 0.1 * (k * k) as f64]
                })
                .collect()
        })
        .collect();
    s(&write_json(dir, "pole.json", &polar_json([0.0; 3], &links))).to_string()
}

#[test]
fn streaming_weld_out_of_memory_is_one_line_and_exit_2() {
    let dir = tempdir();
    // A valence-6 pole streamed to depth 13: ring 13 has 6·2^14 patches,
    // and the weld holds the open edges between the rings written and
    // those to come (tens of MB at depth 13), the kernel's stream a few
    // KB: the limit leaves room for the stream, not for the weld.
    let input = pole_file(dir.path());
    let output = dir.path().join("out.obj");
    let args = format!("patches --depth 13 --stream --format obj '{input}'");
    runs_out_of_memory(80_000, &args, &output);
}

#[test]
fn collected_tessellation_out_of_memory_is_one_line_and_exit_2() {
    let dir = tempdir();
    // The same pole to depth 12, built whole: its patches fit the limit,
    // their collected tessellation (samples, weld, vertices) does not.
    let input = pole_file(dir.path());
    let output = dir.path().join("out.obj");
    let args = format!("patches --depth 12 --format obj '{input}'");
    runs_out_of_memory(100_000, &args, &output);
}

/// How a run under a memory limit ended.
#[derive(Debug, PartialEq)]
enum Ending {
    /// Exit 0, the output written.
    Done,
    /// Exit 2, one line `error: … out of memory …`, no output.
    OutOfMemory,
}

/// Runs `capdiv ARGS -o OUTPUT` under `ulimit -v LIMIT_KB`; panics unless
/// it succeeded (exit 0, `output` written) or failed as
/// [`runs_out_of_memory`] checks (exit 2, one line, nothing on stdout, no
/// `output`).
fn run_under(limit_kb: u64, args: &str, output: &std::path::Path) -> Ending {
    let _ = std::fs::remove_file(output);
    let bin = env!("CARGO_BIN_EXE_capdiv");
    let script = format!(
        "ulimit -v {limit_kb} && exec '{bin}' {args} -o '{}'",
        s(output)
    );
    let out = Command::new("sh")
        .args(["-c", &script])
        .env("RUST_BACKTRACE", "1")
        .output()
        .expect("run sh");
    let stderr = String::from_utf8_lossy(&out.stderr);
    let context = format!(
        "under {limit_kb} KB, capdiv {args}: {:?}\n{stderr}",
        out.status
    );
    match out.status.code() {
        Some(0) => {
            assert!(output.exists(), "{context}");
            Ending::Done
        }
        Some(2) => {
            let lines: Vec<&str> = stderr.lines().collect();
            assert_eq!(lines.len(), 1, "{context}");
            assert!(lines[0].starts_with("error: "), "{context}");
            assert!(lines[0].contains("out of memory"), "{context}");
            assert!(out.stdout.is_empty(), "{context}");
            assert!(!output.exists(), "{context}");
            Ending::OutOfMemory
        }
        _ => panic!("{context}"),
    }
}

/// Under 32 memory limits evenly spaced from 32 MB to one the command fits
/// in (found by doubling), `capdiv ARGS` either succeeds or fails as one
/// line out of memory, never aborts; at least one limit refuses it. The
/// refusals come from wherever the work has got to at that limit —
/// reading, analysis, evaluation, tessellation, the exporter's own buffers
/// — so the limits meet the command at many of its stages.
fn every_limit_succeeds_or_fails_as_one_line(args: &str, output: &std::path::Path) {
    const LOW: u64 = 32 * 1024;
    let mut high = 2 * LOW;
    while run_under(high, args, output) == Ending::OutOfMemory {
        high *= 2;
        assert!(high <= 1 << 24, "capdiv {args} does not fit 16 GB");
    }
    let refused = (0..32)
        .map(|k| LOW + (high - LOW) * k / 32)
        .filter(|&limit| run_under(limit, args, output) == Ending::OutOfMemory)
        .count();
    assert!(refused > 0, "no limit refused capdiv {args}");
}

/// A triangle torus of 288 faces written to `dir`; its path. (`surface`
/// runs on one thread in these tests: the evaluation threads' stacks and
/// arenas would count against the limit by the machine's core count.)
fn small_torus(dir: &std::path::Path) -> String {
    let input = dir.join("torus.obj");
    std::fs::write(&input, triangle_torus(12)).unwrap();
    s(&input).to_string()
}

#[test]
fn surface_png_under_any_memory_limit_succeeds_or_fails_as_one_line() {
    let dir = tempdir();
    let input = small_torus(dir.path());
    let args = format!("surface '{input}' --threads 1 --format png");
    every_limit_succeeds_or_fails_as_one_line(&args, &dir.path().join("out.png"));
}

#[test]
fn surface_gltf_under_any_memory_limit_succeeds_or_fails_as_one_line() {
    let dir = tempdir();
    let input = small_torus(dir.path());
    for format in ["glb", "gltf"] {
        let args = format!("surface '{input}' --threads 1 --format {format}");
        every_limit_succeeds_or_fails_as_one_line(&args, &dir.path().join("out.glb"));
    }
}

#[test]
fn surface_step_under_any_memory_limit_succeeds_or_fails_as_one_line() {
    let dir = tempdir();
    let input = small_torus(dir.path());
    // f32 takes the B-rep guided by the f64 surface's.
    for precision in ["f64", "f32"] {
        let args = format!(
            "surface '{input}' --threads 1 --depth 2 --precision {precision} --format step"
        );
        every_limit_succeeds_or_fails_as_one_line(&args, &dir.path().join("out.step"));
    }
}

#[test]
fn surface_f32_obj_under_any_memory_limit_succeeds_or_fails_as_one_line() {
    let dir = tempdir();
    let input = small_torus(dir.path());
    let args = format!("surface '{input}' --threads 1 --precision f32 --format obj");
    every_limit_succeeds_or_fails_as_one_line(&args, &dir.path().join("out.obj"));
}

/// [`triangle_torus`] of `n × n` quads with texture coordinates (the
/// torus' parameters) at every corner, as OBJ text.
fn textured_triangle_torus(n: usize) -> String {
    let mut text = torus_vertices(n);
    for i in 0..=n {
        for j in 0..=n {
            let _ = writeln!(text, "vt {} {}", i as f64 / n as f64, j as f64 / n as f64);
        }
    }
    let v = |i: usize, j: usize| (i % n) * n + (j % n) + 1;
    let t = |i: usize, j: usize| i * (n + 1) + j + 1;
    triangles(&mut text, n, |i, j| format!("{}/{}", v(i, j), t(i, j)));
    text
}

#[test]
fn surface_json_built_whole_under_any_memory_limit_succeeds_or_fails_as_one_line() {
    // Texture coordinates take the collected path: the JSON built whole.
    let dir = tempdir();
    let input = dir.path().join("textured.obj");
    std::fs::write(&input, textured_triangle_torus(12)).unwrap();
    let args = format!("surface '{}' --threads 1 --format json --pretty", s(&input));
    every_limit_succeeds_or_fails_as_one_line(&args, &dir.path().join("out.json"));
}

#[test]
fn pictures_under_any_memory_limit_succeed_or_fail_as_one_line() {
    let dir = tempdir();
    let input = small_torus(dir.path());
    for args in [
        format!("render '{input}' --size 320x240 --shade highlight"),
        format!("compare '{input}' --size 320x240 --shade mean"),
    ] {
        every_limit_succeeds_or_fails_as_one_line(&args, &dir.path().join("out.png"));
    }
}

#[test]
fn patches_under_any_memory_limit_succeed_or_fail_as_one_line() {
    let dir = tempdir();
    let input = pole_file(dir.path());
    for format in ["json --pretty", "obj", "png"] {
        let args = format!("patches --depth 9 --format {format} '{input}'");
        every_limit_succeeds_or_fails_as_one_line(&args, &dir.path().join("out"));
    }
}
