//! Output meant for files stays off a terminal: PNG bytes are refused with a
//! hint, `surface` prints only its summary there unless a format is asked
//! for; `-o`'s extension chooses the format. A terminal is a pseudo-terminal
//! from util-linux's `script`, which runs the command with its standard
//! output (and error) on the terminal and copies what appears there to ours.

mod common;

use common::{capdiv, s, tempdir};
use std::process::Command;

/// A one-quad OBJ mesh in `dir`.
fn quad(dir: &std::path::Path) -> String {
    let path = dir.join("quad.obj");
    std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
    s(&path).to_string()
}

/// Runs `capdiv args…` with a terminal as standard output: (exit status,
/// what the terminal showed).
fn on_terminal(args: &[&str]) -> (Option<i32>, String) {
    let line: Vec<String> = std::iter::once(env!("CARGO_BIN_EXE_capdiv"))
        .chain(args.iter().copied())
        .map(|a| format!("'{a}'"))
        .collect();
    let out = Command::new("script")
        .args(["-qec", &line.join(" "), "/dev/null"])
        .stdin(std::process::Stdio::null())
        .output()
        .expect("run script (util-linux)");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
    )
}

#[test]
fn png_is_refused_on_a_terminal_with_a_hint() {
    let dir = tempdir();
    let mesh = quad(dir.path());
    let (code, shown) = on_terminal(&["surface", "--format", "png", &mesh]);
    assert_eq!(code, Some(2), "{shown}");
    assert!(
        !shown.contains("PNG\r\n") && !shown.contains("IHDR"),
        "{shown}"
    );
    assert!(shown.contains("error: refusing to write binary output (PNG, GLB) to a terminal"));
    assert!(shown.contains("give -o FILE"), "{shown}");
    // The same bytes through a pipe are a PNG.
    let run = capdiv(&["surface", "--quiet", "--format", "png", &mesh], None);
    run.assert_ok();
    assert_eq!(&run.stdout[..4], b"\x89PNG");
}

#[test]
fn surface_on_a_terminal_prints_the_summary_only() {
    let dir = tempdir();
    let mesh = quad(dir.path());
    let (code, shown) = on_terminal(&["surface", &mesh]);
    assert_eq!(code, Some(0), "{shown}");
    assert!(shown.contains("1 face (open)"), "{shown}");
    assert!(shown.contains("not printed to a terminal"), "{shown}");
    assert!(!shown.contains("\"patches\""), "{shown}");
    // An explicit format prints the surface there.
    let (code, shown) = on_terminal(&["surface", "--quiet", "--format", "json", &mesh]);
    assert_eq!(code, Some(0));
    assert!(shown.contains("\"patches\""), "{shown}");
}

#[test]
fn the_output_extension_chooses_the_format() {
    let dir = tempdir();
    let mesh = quad(dir.path());
    for (name, starts) in [
        ("out.obj", &b"# capdiv surface"[..]),
        ("out.PNG", &b"\x89PNG"[..]),
        ("out.json", &b"{\"patches\""[..]),
        ("out.txt", &b"{\"patches\""[..]),
    ] {
        let path = dir.path().join(name);
        let run = capdiv(&["surface", "--quiet", &mesh, "-o", s(&path)], None);
        run.assert_ok();
        let bytes = std::fs::read(&path).unwrap();
        assert!(bytes.starts_with(starts), "{name}");
    }
}
