//! `capdiv demo`: runs, writes its OBJ and JSON files into the directory it is
//! given (creating it), and the files are usable.

mod common;

use common::*;

const SAMPLES: [&str; 5] = ["paraboloid", "saddle", "sphere-n48", "eg-n3", "eg-n5"];

/// Whole-mesh samples and the caps their summaries must list.
const MESHES: [(&str, &[&str]); 6] = [
    ("globe", &["c2ps x2 n=8"]),
    ("mushroom", &["c2ps x2 n=12"]),
    ("hand", &["c2ps x5 n=8", "c2ps x1 n=26", "eg x16 n=5"]),
    ("rounded-cube", &["eg x8 n=3"]),
    ("cube", &["eg x8 n=3"]),
    ("two-beam-corner", &["eg x10 n=3", "eg x2 n=5"]),
];

const MESH_FILES: usize = 4 * MESHES.len();

#[test]
fn demo_writes_its_files_and_summary() {
    let dir = tempdir();
    let out = dir.path().join("nested/out");
    let run = capdiv(&["demo", "--out", s(&out)], None);
    run.assert_ok();
    let text = run.stdout_str();
    for name in SAMPLES {
        assert!(text.contains(&format!("{name}: ")), "summary lacks {name}");
    }
    for label in [
        "limit point",
        "Gaussian curvature",
        "mean curvature",
        "patches",
        "total time",
    ] {
        assert!(text.contains(label), "summary lacks {label}");
    }

    // Exactly the 15 + 24 files, no temporary file left behind.
    let mut files: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    files.sort();
    let mut want: Vec<String> = SAMPLES
        .iter()
        .flat_map(|n| [format!("{n}.json"), format!("{n}.obj"), format!("{n}.png")])
        .chain(MESHES.iter().flat_map(|(n, _)| {
            [
                format!("{n}.json"),
                format!("{n}.obj"),
                format!("{n}.png"),
                format!("{n}.summary.json"),
            ]
        }))
        .collect();
    want.sort();
    assert_eq!(files, want);

    for name in SAMPLES {
        // OBJ: v/vn/f lines, every face index refers to an existing vertex.
        let obj = std::fs::read_to_string(out.join(format!("{name}.obj"))).unwrap();
        let v = obj.lines().filter(|l| l.starts_with("v ")).count();
        let vn = obj.lines().filter(|l| l.starts_with("vn ")).count();
        assert!(v > 0 && v == vn, "{name}: {v} v, {vn} vn");
        let mut faces = 0;
        for l in obj.lines().filter(|l| l.starts_with("f ")) {
            faces += 1;
            for c in l.split_whitespace().skip(1) {
                let i: usize = c.split("//").next().unwrap().parse().unwrap();
                assert!(i >= 1 && i <= v, "{name}: face index {i} of {v}");
            }
        }
        assert!(faces > 0);
        // Welded: the rings around the open hole (and the outer region)
        // make one annulus, with no crack or T-junction between rings.
        assert_welded_annulus(&parse_obj(&obj), name);
        // PNG: decodes, 800×600 RGB, and the surface covers a good part of it.
        let png = std::fs::read(out.join(format!("{name}.png"))).unwrap();
        let (w, h, rgb) = decode_png(&png);
        assert_eq!((w, h), (800, 600));
        let drawn = rgb.chunks(3).filter(|p| p != &[246, 246, 246]).count();
        assert!(drawn > w * h / 5, "{name}: only {drawn} pixels drawn");
        // The ring colours' legend in the bottom margin: both swatches
        // (12×8 pixels of the unshaded even and odd colours) and its text.
        let bottom = &rgb[3 * w * (h - 16)..];
        for swatch in [[235, 150, 90], [95, 155, 215]] {
            let n = bottom.chunks(3).filter(|p| p == &swatch).count();
            assert!(n >= 96, "{name}: swatch {swatch:?}: {n} pixels");
        }
        let ink = bottom
            .chunks(3)
            .filter(|p| p.iter().all(|&c| c < 70))
            .count();
        assert!(ink > 300, "{name}: legend text: {ink} dark pixels");
        // JSON: a valid input of the other commands.
        let json = out.join(format!("{name}.json"));
        capdiv(&["pole", s(&json)], None).ok_json();
    }

    // EG samples: c-nets of valence 3 and 5, 8 steps, 3n patches a ring;
    // the printed limit is c0 of the written c-net.
    for (name, n) in [("eg-n3", 3usize), ("eg-n5", 5)] {
        let json = out.join(format!("{name}.json"));
        let input: serde_json::Value =
            serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
        assert_eq!(input["kind"], "cnet");
        assert_eq!(input["sectors"].as_array().unwrap().len(), n);
        let patches = format!("{} bi-4 Bézier patches in rings of levels 1..=8", 24 * n);
        assert!(text.contains(&patches), "summary lacks {patches:?}");
        let limit = p3(&capdiv(&["pole", s(&json)], None).ok_json()["limit"]);
        let shown = format!(
            "[{:.6}, {:.6}, {:.6}]",
            limit[0].abs(),
            limit[1].abs(),
            limit[2]
        );
        let section = &text[text.find(&format!("{name}: ")).unwrap()..];
        assert!(
            section.contains(&shown),
            "{name}: limit {shown} not in summary"
        );
        // 8 rings of 3n patches, 4×4 cells each; in rings 1..=7, pieces 0
        // and 1 (2n patches) meet the next ring along one edge, whose 4
        // cells become 3 triangles each (fans from the midpoints).
        let obj = parse_obj(&std::fs::read_to_string(out.join(format!("{name}.obj"))).unwrap());
        let loops = assert_welded_annulus(&obj, name);
        assert_eq!(loops[0], n * 2 * 4, "{name}: the hole's edges");
        let tris = obj.f.iter().filter(|f| f.len() == 3).count();
        assert_eq!(tris, 7 * 2 * n * 4 * 3);
        assert_eq!(obj.f.len() - tris, 24 * n * 16 - 7 * 2 * n * 4);
    }
    // The saddle's curvature line compares two surfaces and says so; its
    // note says the difference is expected.
    let saddle = &text[text.find("saddle: ").unwrap()..];
    let saddle = &saddle[..saddle.find("\n\n").unwrap()];
    assert!(
        saddle.contains(
            "Gaussian curvature  -2.250000 at the limit; the sampled surface has -1.000000, \
             ratio 2.2500"
        ),
        "{saddle}"
    );
    assert!(
        saddle.contains("note                expected: "),
        "{saddle}"
    );
    assert!(text.contains("curvatures: the limit surface at the pole against the surface"));

    // The monkey saddle's c0 by (3): 1/6·3·(1/32) − 5/96·3·(1/32) = 11/1024.
    assert!(text.contains("[0.000000, 0.000000, 0.010742]"), "{text}");

    // The paraboloid z = (x² + y²)/2 is reproduced: K = 1, H = 1 (see
    // tests/pole.rs for the derivation).
    let pole = capdiv(&["pole", s(&out.join("paraboloid.json"))], None).ok_json();
    let k = pole["gaussian_curvature"].as_f64().unwrap();
    let h = pole["mean_curvature"].as_f64().unwrap();
    assert!(
        (k - 1.0).abs() < 1e-12 && (h - 1.0).abs() < 1e-12,
        "K={k} H={h}"
    );

    // A second run replaces the files in place.
    let again = capdiv(&["demo", "--out", s(&out)], None);
    again.assert_ok();
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 15 + MESH_FILES);
}

#[test]
fn demo_meshes_are_closed_surfaces() {
    let dir = tempdir();
    let out = dir.path().join("out");
    let run = capdiv(&["demo", "--out", s(&out)], None);
    run.assert_ok();
    let text = run.stdout_str();
    for (name, caps) in MESHES {
        let section = &text[text
            .find(&format!("\n{name}: "))
            .unwrap_or_else(|| panic!("summary lacks {name}"))..];
        let section = &section[..section[1..].find("\n\n").unwrap_or(section.len() - 1) + 1];
        for cap in caps {
            assert!(section.contains(cap), "{name}: lacks {cap}: {section}");
        }
        assert!(
            section.contains("closed and consistently oriented"),
            "{name}: {section}"
        );
        // The OBJ: every edge used once in each direction; Euler 2.
        let obj = parse_obj(&std::fs::read_to_string(out.join(format!("{name}.obj"))).unwrap());
        let mut directed = std::collections::HashMap::new();
        for f in &obj.f {
            for k in 0..f.len() {
                *directed
                    .entry((f[k].0, f[(k + 1) % f.len()].0))
                    .or_insert(0) += 1;
            }
        }
        for (&(a, b), &n) in &directed {
            assert_eq!(n, 1, "{name}: edge {a}->{b}");
            assert_eq!(directed.get(&(b, a)), Some(&1), "{name}: edge {a}->{b}");
        }
        let euler = obj.v.len() as i64 - (directed.len() / 2) as i64 + obj.f.len() as i64;
        assert_eq!(euler, 2, "{name}");
        // PNG decodes; the JSON is a mesh input of `capdiv surface`; the
        // summary JSON agrees with a fresh run's.
        let (w, h, _) = decode_png(&std::fs::read(out.join(format!("{name}.png"))).unwrap());
        assert_eq!((w, h), (800, 600));
        let json = out.join(format!("{name}.json"));
        // The demo's surfaces have every cap at the full depth.
        let mut fresh = capdiv(
            &[
                "surface",
                "--quiet",
                "--depth",
                "4",
                "--tolerance",
                "none",
                s(&json),
            ],
            None,
        )
        .ok_json();
        let mut saved: serde_json::Value = serde_json::from_slice(
            &std::fs::read(out.join(format!("{name}.summary.json"))).unwrap(),
        )
        .unwrap();
        fresh["summary"].as_object_mut().unwrap().remove("times_ms");
        saved.as_object_mut().unwrap().remove("times_ms");
        assert_eq!(fresh["summary"], saved, "{name}");
    }
    // The plain cube's six faces all need refinement (each next to four
    // valence-3 points): one whole-mesh step refines them at once, and its
    // EG caps are one level in, their rings from level 2; the rounded
    // cube's caps are on its own faces.
    let summary = |n: &str| -> serde_json::Value {
        serde_json::from_slice(&std::fs::read(out.join(format!("{n}.summary.json"))).unwrap())
            .unwrap()
    };
    let levels = |n: &str| -> Vec<u64> {
        summary(n)["patches_per_level"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_u64().unwrap())
            .collect()
    };
    assert_eq!(summary("cube")["refinement_steps"], 1);
    assert_eq!(
        summary("cube")["needed_refinement"]
            .as_array()
            .unwrap()
            .len(),
        6
    );
    assert_eq!(levels("cube")[..2], [0, 0]);
    assert_eq!(summary("rounded-cube")["refinement_steps"], 0);
    assert_eq!(
        summary("rounded-cube")["needed_refinement"],
        serde_json::json!([])
    );
    assert!(levels("rounded-cube")[1] > 0);
}

#[test]
fn demo_into_an_unwritable_place_fails_cleanly() {
    let dir = tempdir();
    let file = dir.path().join("a-file");
    std::fs::write(&file, b"x").unwrap();
    // --out names a regular file: the directory cannot be created.
    let run = capdiv(&["demo", "--out", s(&file)], None);
    assert_eq!(run.code, Some(2));
    assert!(run.stdout.is_empty());
    assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    assert_eq!(std::fs::read(&file).unwrap(), b"x");
}
