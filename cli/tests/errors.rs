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

/// Every command that reads an EG input, with the given input on stdin.
fn fails_eg_everywhere(input: &str, needle: &str) {
    for cmd in [
        &["refine", "-"][..],
        &["refine", "--precision", "f32", "--steps", "2", "-"],
        &["refine", "--scheme", "eg", "--steps", "0", "-"],
        &["pole", "-"],
        &["pole", "--precision", "f32", "-"],
        &["patches", "--depth", "2", "-"],
        &["patches", "--depth", "1", "--format", "obj", "-"],
    ] {
        fails(cmd, Some(input.as_bytes()), needle, true);
    }
}

fn cnet_text(n: usize) -> String {
    let (center, sectors) = cnet(n, 1);
    cnet_json(center, &sectors).to_string()
}

#[test]
fn scheme_and_options_must_fit_the_kind() {
    let (pole, links) = config(5, 3, 1);
    let polar = polar_json(pole, &links).to_string();
    let cnet = cnet_text(3);
    let (center, sectors) = common::cnet(5, 2);
    let dnet_out = capdiv(
        &["refine", "--steps", "0", "-"],
        Some(cnet_json(center, &sectors).to_string().as_bytes()),
    );
    dnet_out.assert_ok();
    let dnet = dnet_out.stdout_str();
    fails(
        &["refine", "--scheme", "eg", "-"],
        Some(polar.as_bytes()),
        "<stdin>: --scheme eg needs a 'cnet' or 'dnet' input, got kind 'polar'",
        true,
    );
    for (input, kind) in [(&cnet, "cnet"), (&dnet, "dnet")] {
        for scheme in ["c2ps", "rts"] {
            fails(
                &["refine", "--scheme", scheme, "-"],
                Some(input.as_bytes()),
                &format!("--scheme {scheme} needs a 'polar' input, got kind '{kind}'"),
                true,
            );
        }
        fails(
            &["refine", "--first-step", "plain", "-"],
            Some(input.as_bytes()),
            "--first-step applies to --scheme c2ps only",
            true,
        );
        fails(
            &["patches", "--depth", "1", "--first-step", "plain", "-"],
            Some(input.as_bytes()),
            "--first-step applies to polar inputs only",
            true,
        );
    }
    fails(
        &["refine", "--table", "t.json", "-"],
        Some(polar.as_bytes()),
        "--table applies to --scheme eg only",
        true,
    );
    fails(
        &["refine", "--scheme", "c2ps", "--table", "t.json", "-"],
        Some(cnet.as_bytes()),
        "--table applies to --scheme eg only",
        true,
    );
    fails(
        &["patches", "--depth", "1", "--table", "t.json", "-"],
        Some(polar.as_bytes()),
        "--table applies to EG inputs (cnet, dnet) only",
        true,
    );
}

#[test]
fn eg_schema_errors() {
    let p = "[0, 0, 0]";
    let five = [p; 5].join(", ");
    let six = [p; 6].join(", ");
    fails_eg_everywhere(
        &format!(r#"{{"kind": "cnet", "sectors": [[{six}], [{six}], [{six}]]}}"#),
        "missing field `center`",
    );
    fails_eg_everywhere(
        &format!(r#"{{"kind": "cnet", "center": {p}, "sectors": [[{six}], [{six}], [{five}]]}}"#),
        "wrong schema",
    );
    fails_eg_everywhere(
        &format!(r#"{{"kind": "cnet", "center": {p}, "c0": {p}, "sectors": [[{six}]]}}"#),
        "unknown field `c0`",
    );
    fails_eg_everywhere(
        &format!(r#"{{"kind": "dnet", "sectors": [[{six}], [{six}], [{six}]]}}"#),
        "wrong schema",
    );
}

#[test]
fn eg_kernel_errors() {
    let p = "[0, 0, 0]";
    let six = [p; 6].join(", ");
    let twelve = [p; 12].join(", ");
    let cnet_of = |n: usize| {
        let secs = vec![format!("[{six}]"); n].join(", ");
        format!(r#"{{"kind": "cnet", "center": {p}, "sectors": [{secs}]}}"#)
    };
    let dnet_of = |n: usize| {
        let secs = vec![format!("[{twelve}]"); n].join(", ");
        format!(r#"{{"kind": "dnet", "sectors": [{secs}]}}"#)
    };
    for (n, needle) in [
        (0, "valence 0 is below 3"),
        (2, "valence 2 is below 3"),
        (11, "valence 11 is not supported"),
    ] {
        fails_eg_everywhere(&cnet_of(n), needle);
        fails_eg_everywhere(&dnet_of(n), needle);
    }
    // Valences 6..10 have no built-in rule: refine and patches need a table,
    // pole (c0 by (3) or (4)) and refine --steps 0 do not.
    for input in [cnet_of(6), dnet_of(10)] {
        let n = if input.contains("cnet") { 6 } else { 10 };
        let needle = format!("<stdin>: valence {n} is not supported");
        for cmd in [
            &["refine", "-"][..],
            &["refine", "--steps", "1", "-"],
            &["patches", "--depth", "1", "-"],
        ] {
            fails(cmd, Some(input.as_bytes()), &needle, true);
        }
        capdiv(&["pole", "-"], Some(input.as_bytes())).assert_ok();
        capdiv(&["refine", "--steps", "0", "-"], Some(input.as_bytes())).assert_ok();
    }
    // Finite in f64, infinite in f32.
    let (center, mut sectors) = cnet(3, 5);
    sectors[1][3][2] = 1e39;
    let big = cnet_json(center, &sectors).to_string();
    for cmd in [
        &["refine", "--precision", "f32", "-"][..],
        &["pole", "--precision", "f32", "-"],
        &["patches", "--precision", "f32", "--depth", "1", "-"],
    ] {
        fails(
            cmd,
            Some(big.as_bytes()),
            "a coordinate is not finite",
            true,
        );
    }
    capdiv(&["refine", "-"], Some(big.as_bytes())).assert_ok();
    // Overflow in f64 while raising to the d-net (differences to the center
    // exceed f64::MAX): finite input, non-finite result.
    let (_, mut sectors) = cnet(5, 6);
    for p in sectors.iter_mut().flatten() {
        *p = [1.7e308, 0.0, 0.0];
    }
    let huge = cnet_json([-1.7e308, 0.0, 0.0], &sectors).to_string();
    fails(
        &["refine", "--steps", "3", "-"],
        Some(huge.as_bytes()),
        "not finite",
        true,
    );
}

/// A table file in `dir` from the spec's n = 3 arrays changed by `edit`.
fn table_file(
    dir: &Path,
    name: &str,
    edit: impl FnOnce(&mut serde_json::Value),
) -> std::path::PathBuf {
    let mut t = table_json(3, SPEC_N3);
    edit(&mut t);
    write_json(dir, name, &t)
}

#[test]
fn spectrum_and_table_errors() {
    let dir = tempdir();
    let d = dir.path();
    fails(
        &["spectrum", "--valence", "6"],
        None,
        "valence 6: valence 6 is not supported",
        true,
    );
    fails(
        &["spectrum", "--valence", "2"],
        None,
        "valence 2 is below 3",
        true,
    );
    fails(
        &["spectrum", "--valence", "11"],
        None,
        "valence 11 is not supported",
        true,
    );
    fails(&["spectrum"], None, "--valence", false);
    // The kernel's checks of a user table, each named (docs/math/eg.md §6–§8).
    let cases: Vec<(std::path::PathBuf, &str)> = vec![
        (
            table_file(d, "rows.json", |t| {
                t["A11"].as_array_mut().unwrap().pop();
            }),
            "rows.json: rule table has the wrong shape",
        ),
        (
            table_file(d, "big.json", |t| t["A11"][0][0] = 100000.into()),
            "big.json: rule table has the wrong shape",
        ),
        (
            table_file(d, "huge.json", |t| t["A11"][0][0] = 1e15.into()),
            "wrong schema",
        ),
        (
            table_file(d, "i64.json", |t| t["A11"][0][0] = 10_000_000_000i64.into()),
            "i64.json: rule table has the wrong shape",
        ),
        (
            // A31 rows 0 and 1 are tied by the spoke symmetry (§6).
            table_file(d, "sym.json", |t| t["A31"][1][1] = 17.into()),
            "sym.json: rule table violates the EG symmetries",
        ),
        (
            table_file(d, "sum.json", |t| t["A22"][0][10] = 99999.into()),
            "sum.json: rule table rows do not sum as required",
        ),
        (
            table_file(d, "lambda.json", |t| t["A21"][0][11] = 30229.into()),
            "lambda.json: rule table's subdominant eigenvalue is not Catmull-Clark's",
        ),
        (
            table_file(d, "short.json", |t| {
                t["A11"][0].as_array_mut().unwrap().pop();
            }),
            "short.json: wrong schema: A11 row 0 has 11 entries, 12 expected",
        ),
        (
            table_file(d, "float.json", |t| t["A22"][1][3] = 0.5.into()),
            "float.json: wrong schema",
        ),
        (
            table_file(d, "extra.json", |t| t["A12"] = serde_json::json!([])),
            "unknown field `A12`",
        ),
    ];
    for (file, needle) in &cases {
        fails(
            &["spectrum", "--valence", "3", "--table", s(file)],
            None,
            needle,
            true,
        );
    }
    // The same tables refused by refine and patches.
    let (center, sectors) = cnet(3, 7);
    let net = write_json(d, "c.json", &cnet_json(center, &sectors));
    for (file, needle) in &cases[..4] {
        fails(&["refine", "--table", s(file), s(&net)], None, needle, true);
        fails(
            &["patches", "--depth", "1", "--table", s(file), s(&net)],
            None,
            needle,
            true,
        );
    }
    // A table for n = 4 (regular, no EG rule): the kernel's shape error.
    let four = write_json(
        d,
        "four.json",
        &serde_json::json!({"valence": 4, "A11": [], "A22": [], "A21": [], "A31": [], "A32": []}),
    );
    fails(
        &["spectrum", "--valence", "4", "--table", s(&four)],
        None,
        "four.json: rule table has the wrong shape",
        true,
    );
    // A table of another valence than asked for.
    let good = write_json(d, "good.json", &table_json(3, SPEC_N3));
    fails(
        &["spectrum", "--valence", "5", "--table", s(&good)],
        None,
        "good.json: the rule table is for valence 3, valence 5 has valence 5",
        true,
    );
    let (center, sectors) = cnet(5, 8);
    let net5 = write_json(d, "c5.json", &cnet_json(center, &sectors));
    fails(
        &["refine", "--table", s(&good), s(&net5)],
        None,
        "the rule table is for valence 3, ",
        true,
    );
    fails(
        &[
            "spectrum",
            "--valence",
            "3",
            "--table",
            s(&d.join("none.json")),
        ],
        None,
        "none.json",
        true,
    );
    fails(
        &["spectrum", "--valence", "3", "--table", "-"],
        Some(b"{\"valence\": 3,"),
        "malformed JSON",
        true,
    );
    capdiv(&["spectrum", "--valence", "3", "--table", s(&good)], None).assert_ok();
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
    // 6·2^15 = 196608 > 131072 = the largest valence; 6·2^14 = 98304 fits.
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
        &["refine", "--scheme", "bogus", "x.json"],
        None,
        "invalid value 'bogus'",
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
    for cmd in ["refine", "pole", "patches", "spectrum", "demo"] {
        assert!(help.stdout_str().contains(cmd));
    }
    capdiv(&["--version"], None).assert_ok();
    capdiv(&["refine", "--help"], None).assert_ok();
    capdiv(&["spectrum", "--help"], None).assert_ok();
}

/// A net whose coordinates an f32 step could overflow (near 1e37, above
/// `f32::MAX/(16·6)`): RTS fails exactly as C²PS does (exit 2, "not
/// finite"), instead of printing the input unrefined; in f64 both refine.
#[test]
fn rts_overflow_fails_like_c2ps() {
    let (pole, links) = config(6, 5, 11);
    let scale = |p: [f64; 3]| p.map(|c| c * 1e37);
    let links: Vec<Vec<[f64; 3]>> = links
        .iter()
        .map(|l| l.iter().map(|&p| scale(p)).collect())
        .collect();
    let input = serde_json::to_string(&polar_json(scale(pole), &links)).unwrap();
    for scheme in ["rts", "c2ps"] {
        let args = [
            "refine",
            "--scheme",
            scheme,
            "--steps",
            "3",
            "--precision",
            "f32",
            "-",
        ];
        fails(&args, Some(input.as_bytes()), "not finite", true);
        let f64_args = ["refine", "--scheme", scheme, "--steps", "3", "-"];
        capdiv(&f64_args, Some(input.as_bytes())).assert_ok();
    }
}
