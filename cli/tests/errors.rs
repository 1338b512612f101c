//! Every failure: exit status 2, exactly one line on stderr naming the
//! problem, nothing on stdout, and no output file (a file already there is
//! left as it was).

mod common;

use common::*;
use std::path::Path;

/// Runs a failing command twice — to stdout, and with `-o FILE` when the
/// command takes one — and checks the failure contract. `needle` must occur
/// in the error line.
fn fails(args: &[&str], stdin: Option<&[u8]>, needle: &str, takes_output: bool) {
    let run = capdiv(args, stdin);
    check(&run, args, needle);
    if takes_output {
        let dir = tempdir();
        let out = dir.path().join("out.json");
        let mut with_o = args.to_vec();
        with_o.splice(1..1, ["-o", s(&out)]);
        let run = capdiv(&with_o, stdin);
        check(&run, &with_o, needle);
        assert!(!out.exists(), "{with_o:?} left an output file");
        assert_dir_empty(dir.path());
        // An existing file is not touched by a failing run.
        std::fs::write(&out, b"old").unwrap();
        let run = capdiv(&with_o, stdin);
        check(&run, &with_o, needle);
        assert_eq!(std::fs::read(&out).unwrap(), b"old");
    }
}

fn check(run: &Run, args: &[&str], needle: &str) {
    assert_eq!(run.code, Some(2), "{args:?}: stderr {}", run.stderr);
    assert!(run.stdout.is_empty(), "{args:?}: stdout not empty");
    let lines: Vec<&str> = run.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "{args:?}: stderr {:?}", run.stderr);
    assert!(run.stderr.ends_with('\n'));
    assert!(lines[0].starts_with("error: "), "{:?}", lines[0]);
    assert!(
        lines[0].contains(needle),
        "{args:?}: {:?} lacks {needle:?}",
        lines[0]
    );
}

fn assert_dir_empty(dir: &Path) {
    let left: Vec<_> = std::fs::read_dir(dir).unwrap().collect();
    assert!(left.is_empty(), "files left behind: {left:?}");
}

/// Every command that reads a configuration, with the given input on stdin.
fn fails_everywhere(input: &str, needle: &str) {
    for cmd in [
        &["refine", "-"][..],
        &["refine", "--precision", "f32", "--steps", "2", "-"],
        &["refine", "--scheme", "rts", "-"],
        &["pole", "-"],
        &["patches", "--depth", "2", "-"],
        &["patches", "--depth", "1", "--format", "obj", "-"],
    ] {
        fails(cmd, Some(input.as_bytes()), needle, true);
    }
}

fn valid_links(n: usize, k: usize) -> String {
    let (pole, links) = config(n, k, 1);
    serde_json::to_string(&links).unwrap() + &format!(", \"pole\": {:?}", pole)
}

#[test]
fn malformed_json() {
    fails_everywhere("{\"kind\": \"polar\", ", "malformed JSON");
    fails_everywhere("", "malformed JSON");
    fails_everywhere("[1, 2", "malformed JSON");
}

#[test]
fn wrong_schema() {
    let links = serde_json::to_string(&config(4, 2, 1).1).unwrap();
    fails_everywhere(
        r#"{"pole": [0, 0, 0], "links": []}"#,
        "missing field `kind`",
    );
    fails_everywhere(r#"{"kind": "polar", "links": []}"#, "missing field `pole`");
    fails_everywhere(r#"{"kind": "polygon"}"#, "unknown variant `polygon`");
    fails_everywhere(
        &format!(r#"{{"kind": "polar", "pole": [0, 0, 0], "links": {links}, "extra": 1}}"#),
        "unknown field `extra`",
    );
    fails_everywhere(
        r#"{"kind": "polar", "pole": [0, 0], "links": []}"#,
        "wrong schema",
    );
    fails_everywhere(
        r#"{"kind": "polar", "pole": [0, 0, "x"], "links": []}"#,
        "wrong schema",
    );
    fails_everywhere("[]", "wrong schema");
    // JSON has no NaN or infinity; a number beyond f64 is a parse error.
    fails_everywhere(
        r#"{"kind": "polar", "pole": [0, 0, 1e999], "links": []}"#,
        "number out of range",
    );
}

#[test]
fn eg_kinds_are_recognised_but_not_supported_yet() {
    let p = "[0, 0, 0]";
    let six = [p; 6].join(", ");
    let twelve = [p; 12].join(", ");
    fails_everywhere(
        &format!(r#"{{"kind": "cnet", "center": {p}, "sectors": [[{six}], [{six}], [{six}]]}}"#),
        "kind 'cnet' is not supported yet",
    );
    fails_everywhere(
        &format!(r#"{{"kind": "dnet", "sectors": [[{twelve}], [{twelve}], [{twelve}]]}}"#),
        "kind 'dnet' is not supported yet",
    );
    fails_everywhere(
        &format!(r#"{{"kind": "dnet", "c0": {p}, "sectors": []}}"#),
        "kind 'dnet' is not supported yet",
    );
}

#[test]
fn kernel_errors() {
    let ring = |n: usize, r: f64| -> String {
        let pts: Vec<String> = (0..n)
            .map(|j| {
                let t = std::f64::consts::TAU * j as f64 / n as f64;
                format!("[{}, {}, 0]", r * t.cos(), r * t.sin())
            })
            .collect();
        format!("[{}]", pts.join(", "))
    };
    let polar = |links: &[String]| {
        format!(
            r#"{{"kind": "polar", "pole": [0, 0, 0], "links": [{}]}}"#,
            links.join(", ")
        )
    };
    fails_everywhere(
        &polar(&[ring(5, 1.0), ring(4, 2.0)]),
        "link 2 has 4 points, the 1-link has 5",
    );
    fails_everywhere(
        &polar(&[ring(2, 1.0), ring(2, 2.0)]),
        "valence 2 is below 3",
    );
    fails_everywhere(
        &polar(&[ring(5, 1.0)]),
        "1 link(s) given, at least 2 are needed",
    );
    fails_everywhere(&polar(&[]), "0 link(s) given");
    // Odd part of the valence beyond the kernel's root table (127).
    fails_everywhere(
        &polar(&[ring(131, 1.0), ring(131, 2.0)]),
        "valence 131 is not supported",
    );
}

#[test]
fn degenerate_pole_has_no_normal() {
    // All points at the origin: p1 = p2 = 0.
    let zero = ["[0, 0, 0]"; 4].join(", ");
    let input = format!(r#"{{"kind": "polar", "pole": [0, 0, 0], "links": [[{zero}], [{zero}]]}}"#);
    fails(
        &["pole", "-"],
        Some(input.as_bytes()),
        "degenerate tangent plane",
        true,
    );
    // refine and patches do not need the tangent plane.
    capdiv(&["refine", "-"], Some(input.as_bytes())).assert_ok();
}

#[test]
fn f32_overflow_is_not_finite() {
    let (_, links) = config(4, 2, 3);
    let mut links = links;
    links[1][2][0] = 1e39; // finite in f64, infinite in f32
    let input = serde_json::to_string(&polar_json([0.0; 3], &links)).unwrap();
    for cmd in [
        &["refine", "--precision", "f32", "-"][..],
        &["pole", "--precision", "f32", "-"],
        &["patches", "--precision", "f32", "--depth", "2", "-"],
    ] {
        fails(
            cmd,
            Some(input.as_bytes()),
            "a coordinate is not finite",
            true,
        );
    }
    capdiv(&["refine", "-"], Some(input.as_bytes())).assert_ok();
    // Overflow during refinement in f64.
    let mut big = links.clone();
    big[0][0] = [1.7e308, 0.0, 0.0];
    big[0][1] = [-1.7e308, 0.0, 0.0];
    let input = serde_json::to_string(&polar_json([1.7e308, 0.0, 0.0], &big)).unwrap();
    fails(
        &["refine", "--steps", "2", "-"],
        Some(input.as_bytes()),
        "not finite",
        true,
    );
}

#[test]
fn capacity_exceeded() {
    let (pole, links) = config(6, 3, 4);
    let input = serde_json::to_string(&polar_json(pole, &links)).unwrap();
    // 6·2^15 = 196608 > 131072 = largest tier; 6·2^14 = 98304 fits.
    let msg = "exceeds the largest supported capacity 131072";
    fails(
        &["refine", "--steps", "15", "-"],
        Some(input.as_bytes()),
        msg,
        true,
    );
    fails(
        &["patches", "--depth", "15", "-"],
        Some(input.as_bytes()),
        msg,
        true,
    );
    fails(
        &["refine", "--steps", "4000000000", "-"],
        Some(input.as_bytes()),
        msg,
        true,
    );
    let ok = capdiv(&["refine", "--steps", "14", "-"], Some(input.as_bytes()));
    ok.assert_ok();
    let (_, got) = parse_polar(&ok.json());
    assert_eq!(got[0].len(), 6 << 14);
}

#[test]
fn io_and_usage_errors() {
    let dir = tempdir();
    let missing = dir.path().join("missing.json");
    fails(&["refine", s(&missing)], None, "missing.json", true);
    fails(&["pole", s(&missing)], None, "missing.json", true);
    fails(
        &["refine", "--bogus", "x.json"],
        None,
        "unexpected argument '--bogus'",
        false,
    );
    fails(
        &["refine", "--scheme", "eg", "x.json"],
        None,
        "invalid value 'eg'",
        false,
    );
    fails(&["patches", "x.json"], None, "--depth", false);
    fails(
        &["patches", "--depth", "1", "--grid", "0", "x.json"],
        None,
        "--grid",
        false,
    );
    fails(&["frobnicate"], None, "unrecognized subcommand", false);
    let input = valid_links(4, 2);
    let input = format!(r#"{{"kind": "polar", "links": {input}}}"#);
    fails(
        &["refine", "--scheme", "rts", "--first-step", "plain", "-"],
        Some(input.as_bytes()),
        "--first-step applies to --scheme c2ps only",
        true,
    );
    // Output into a directory that does not exist: an I/O error, no file.
    let nowhere = dir.path().join("no/such/dir/out.json");
    fails(
        &["pole", "-o", s(&nowhere), "-"],
        Some(input.as_bytes()),
        "out.json",
        false,
    );
    assert!(!dir.path().join("no").exists());
    // The same input succeeds where the options are right.
    capdiv(&["refine", "--scheme", "rts", "-"], Some(input.as_bytes())).assert_ok();
}

#[test]
fn help_and_version_succeed() {
    let help = capdiv(&["--help"], None);
    help.assert_ok();
    for cmd in ["refine", "pole", "patches", "demo"] {
        assert!(help.stdout_str().contains(cmd));
    }
    capdiv(&["--version"], None).assert_ok();
    capdiv(&["refine", "--help"], None).assert_ok();
}
