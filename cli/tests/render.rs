//! `capdiv render` and `capdiv compare`. The numbers the pictures
//! are made of (per-pixel exact normals → highlight lines of a plane), and
//! the commands' PNGs: size, drawn pixels, the hatched hole, the legend, the
//! labels, errors.
mod common;

use capdiv_cli::args::ShapeScheme;
use capdiv_cli::input::Input;
use capdiv_cli::picture::{highlight_lines, probe, Camera, LightLines, HATCH, LEGEND_HEIGHT};
use capdiv_cli::samples::{sample_cnet, sample_surface};
use capdiv_cli::shape::build;
use common::{capdiv, read_png};

/// Highlight lines of a plane, through the render path (rasterised
/// tessellation → per-pixel (u, v) → patch jet → normal → the lines'
/// parameter): a plane has one normal, so the parameter must be an affine
/// function of the surface point — stripes straight and evenly spaced.
/// Lines from a light plane on the camera's right.
/// Checked on a tilted planar polar net (C²PS and Catmull-Clark) and a tilted
/// planar c-net (EG): (1) every pixel's normal equals the plane's to 1e-12;
/// (2) the parameter, fitted by least squares as `a + b·x + c·y` over the
/// pixels, has residual below 1e-9 (straight lines); (3) along the middle
/// pixel row the integer crossings (interpolated between samples) are
/// evenly spaced: gaps within 1 % of each other (measured 0.3 %; the row is sampled at
/// pixel centres; measured spread printed), at least 4 of them.
#[test]
#[allow(clippy::needless_range_loop)] // Gauss-Jordan on a 3x4 array
fn highlight_stripes_of_a_plane_are_straight_and_evenly_spaced() {
    let plane = |x: f64, y: f64| 0.3 * x - 0.2 * y + 0.1;
    let want = {
        let n = [-0.3f64, 0.2, 1.0];
        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        n.map(|c| c / l)
    };
    let cases = [
        (
            Input::Polar(sample_surface(7, 5, 0.3, plane)),
            ShapeScheme::C2ps,
        ),
        (
            Input::Polar(sample_surface(7, 5, 0.3, plane)),
            ShapeScheme::CatmullClark,
        ),
        (Input::Cnet(sample_cnet(5, 0.5, plane)), ShapeScheme::Eg),
    ];
    let cam = Camera {
        width: 200,
        height: 160,
        azimuth: -60.0,
        elevation: 70.0,
        grid: 4,
        ..Camera::default()
    };
    // The light plane on the camera's right: its lines run along the
    // screen's vertical, so the stripes cross the middle row; 3 spacings
    // across the height keep the stripes some 20 samples apart.
    let light = LightLines {
        direction: Some(cam.frame().right),
        lines: 3.0,
    };
    for (input, scheme) in cases {
        let shape = build("plane", &input, Some(scheme), 3).unwrap();
        let samples = probe(&[&shape], &cam).unwrap();
        let lines = highlight_lines(&[&shape], &cam, &light).unwrap().unwrap();
        let px = &samples[0];
        let w = 2 * cam.width;
        let mut pts = Vec::new();
        for (k, s) in px.iter().enumerate() {
            let Some(s) = s else { continue };
            let dn = (0..3)
                .map(|c| (s.normal[c] - want[c]).abs())
                .fold(0.0, f64::max);
            assert!(dn < 1e-12, "{scheme:?}: normal {:?}", s.normal);
            let t = lines.parameter(s.point, s.normal).unwrap();
            pts.push((k % w, k / w, s.point, t));
        }
        assert!(pts.len() > w * 40, "{scheme:?}: {} pixels", pts.len());
        // Least squares t = a + b x + c y over the surface points.
        let mut m = [[0.0f64; 4]; 3];
        for &(_, _, p, t) in &pts {
            let r = [1.0, p[0], p[1]];
            for i in 0..3 {
                for j in 0..3 {
                    m[i][j] += r[i] * r[j];
                }
                m[i][3] += r[i] * t;
            }
        }
        for i in 0..3 {
            let piv = m[i][i];
            for j in i..4 {
                m[i][j] /= piv;
            }
            for r in 0..3 {
                if r != i {
                    let f = m[r][i];
                    for j in i..4 {
                        m[r][j] -= f * m[i][j];
                    }
                }
            }
        }
        let (a, b, c) = (m[0][3], m[1][3], m[2][3]);
        let resid = pts
            .iter()
            .map(|&(_, _, p, t)| (t - a - b * p[0] - c * p[1]).abs())
            .fold(0.0, f64::max);
        assert!(resid < 1e-9, "{scheme:?}: residual {resid}");
        // Crossings along the middle row.
        let row =
            pts.iter().map(|p| p.1).max().unwrap() / 2 + pts.iter().map(|p| p.1).min().unwrap() / 2;
        let mut line: Vec<(usize, f64)> = pts
            .iter()
            .filter(|p| p.1 == row)
            .map(|p| (p.0, p.3))
            .collect();
        line.sort_by_key(|p| p.0);
        // Crossings of integer parameters, interpolated between samples
        // (also across the hole, where the row has no surface pixel).
        let mut crossings: Vec<f64> = Vec::new();
        for w in line.windows(2) {
            let ((x0, t0), (x1, t1)) = (w[0], w[1]);
            let (a, b) = (t0.min(t1), t0.max(t1));
            let mut k = a.floor() + 1.0;
            while k <= b {
                crossings.push(x0 as f64 + (k - t0) / (t1 - t0) * (x1 as f64 - x0 as f64));
                k += 1.0;
            }
        }
        assert!(crossings.len() >= 4, "{scheme:?}: {crossings:?}");
        let gaps: Vec<f64> = crossings.windows(2).map(|w| w[1] - w[0]).collect();
        let lo = gaps.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = gaps.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        assert!(hi - lo < 0.01 * hi, "{scheme:?}: uneven gaps {gaps:?}");
        println!(
            "{scheme:?}: {} pixels, residual {resid:.1e}, stripe gaps {gaps:?} (supersamples)",
            pts.len()
        );
    }
}

fn background(c: [u8; 3]) -> bool {
    c == [246, 246, 246]
}
fn dark(c: [u8; 3]) -> bool {
    c.iter().all(|&v| v < 60)
}

fn write(dir: &std::path::Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

/// Every input kind renders: PNG of the requested size, most of the panel
/// drawn, the hole hatched where there is a cap; curvature maps add the
/// legend strip (the colour bar's blue and red ends and printed numbers).
#[test]
fn render_draws_every_input_kind() {
    let dir = tempfile::tempdir().unwrap();
    let polar = serde_json::to_string(&serde_json::json!({
        "kind": "polar",
        "pole": [0.0, 0.0, 0.0],
        "links": (1..=5).map(|i| (0..6).map(|j| {
            let t = std::f64::consts::TAU * j as f64 / 6.0;
            let r = 0.3 * i as f64;
            [r * t.cos(), r * t.sin(), 0.5 * r * r]
        }).collect::<Vec<_>>()).collect::<Vec<_>>(),
    }))
    .unwrap();
    let mut cnet = serde_json::to_value(sample_cnet(5, 0.5, |x, y| 0.5 * (x * x - y * y))).unwrap();
    cnet["kind"] = "cnet".into();
    let cnet = cnet.to_string();
    // The c-net's d-net (degree raised by `capdiv refine --steps 0`).
    let run = capdiv(&["refine", "--steps", "0", "-"], Some(cnet.as_bytes()));
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let dnet = run.stdout_str();
    assert!(dnet.contains("\"dnet\""));
    let mushroom = capdiv_mesh::samples::mushroom();
    let mut obj = String::new();
    for v in &mushroom.vertices {
        obj += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    for f in &mushroom.faces {
        let ids: Vec<String> = f.iter().map(|i| (i + 1).to_string()).collect();
        obj += &format!("f {}\n", ids.join(" "));
    }
    let files = [
        ("polar.json", polar, true),
        ("cnet.json", cnet, true),
        ("dnet.json", dnet, true),
        ("mushroom.obj", obj, true),
    ];
    for (name, text, hole) in files {
        let input = write(dir.path(), name, &text);
        for shade in ["plain", "highlight", "gauss", "mean"] {
            let out = dir.path().join(format!("{name}-{shade}.png"));
            let run = capdiv(
                &[
                    "render",
                    "--shade",
                    shade,
                    "--size",
                    "160x120",
                    "--depth",
                    "3",
                    &input,
                    "-o",
                    out.to_str().unwrap(),
                ],
                None,
            );
            assert_eq!(run.code, Some(0), "{name} {shade}: {}", run.stderr);
            assert!(run.stdout.is_empty());
            let png = read_png(&out);
            let legend = matches!(shade, "gauss" | "mean");
            assert_eq!(
                (png.w, png.h),
                (160, 120 + if legend { LEGEND_HEIGHT } else { 0 }),
                "{name} {shade}"
            );
            let drawn = png.count(0..120, |c| !background(c));
            assert!(
                drawn > 160 * 120 / 5,
                "{name} {shade}: {drawn} pixels drawn"
            );
            if hole {
                let hatch = png.count(0..120, |c| c == HATCH[0]);
                assert!(hatch > 0, "{name} {shade}: no hatched hole pixel");
            }
            if legend {
                let rows = 120..png.h;
                assert!(
                    png.count(rows.clone(), |c| c == [0, 0, 255]) > 0,
                    "{name} {shade}: no blue end"
                );
                assert!(
                    png.count(rows.clone(), |c| c == [255, 0, 0]) > 0,
                    "{name} {shade}: no red end"
                );
                assert!(
                    png.count(rows, dark) > 100,
                    "{name} {shade}: no printed numbers"
                );
            }
        }
    }
}

/// `compare`: one panel per applicable scheme (3 for a polar net, 2 for a
/// c-net) of the requested size, 8-pixel gaps, a label strip with text
/// over each panel, one legend for all.
#[test]
fn compare_draws_one_labelled_panel_per_scheme() {
    let dir = tempfile::tempdir().unwrap();
    for (sample, panels) in [("sample:c2ps-saddle-n8", 3), ("sample:eg-saddle-n5", 2)] {
        for shade in ["highlight", "mean"] {
            let out = dir.path().join(format!("{}-{shade}.png", &sample[7..]));
            let run = capdiv(
                &[
                    "compare",
                    "--shade",
                    shade,
                    "--size",
                    "120x100",
                    "--depth",
                    "3",
                    sample,
                    "-o",
                    out.to_str().unwrap(),
                ],
                None,
            );
            assert_eq!(run.code, Some(0), "{sample}: {}", run.stderr);
            let png = read_png(&out);
            let legend = if shade == "mean" { LEGEND_HEIGHT } else { 0 };
            assert_eq!(
                (png.w, png.h),
                (panels * 120 + (panels - 1) * 8, 20 + 100 + legend)
            );
            for p in 0..panels {
                let x0 = p * 128;
                let label = (0..20)
                    .flat_map(|y| (x0..x0 + 120).map(move |x| (x, y)))
                    .filter(|&(x, y)| dark(png.at(x, y)))
                    .count();
                assert!(label > 20, "{sample}: panel {p} has no label");
                let drawn = (20..120)
                    .flat_map(|y| (x0..x0 + 120).map(move |x| (x, y)))
                    .filter(|&(x, y)| !background(png.at(x, y)))
                    .count();
                assert!(drawn > 120 * 100 / 5, "{sample}: panel {p}: {drawn}");
            }
        }
    }
}

#[test]
fn render_and_compare_refuse_bad_options_and_input() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let o = out.to_str().unwrap();
    let dnet_cc = {
        let run = capdiv(&["refine", "--steps", "0", "-"], Some(serde_json::json!({
            "kind": "cnet", "center": [0, 0, 0],
            "sectors": serde_json::to_value(sample_cnet(3, 0.5, |_, _| 0.0)).unwrap()["sectors"]
        }).to_string().as_bytes()));
        let p = dir.path().join("d.json");
        std::fs::write(&p, run.stdout).unwrap();
        p.to_str().unwrap().to_string()
    };
    let two_links = {
        let p = dir.path().join("two.json");
        let links: Vec<Vec<[f64; 3]>> = (1..=2)
            .map(|i| {
                (0..5)
                    .map(|j| {
                        let t = std::f64::consts::TAU * j as f64 / 5.0;
                        [i as f64 * t.cos(), i as f64 * t.sin(), 0.0]
                    })
                    .collect()
            })
            .collect();
        let v = serde_json::json!({"kind": "polar", "pole": [0.0, 0.0, 0.0], "links": links});
        std::fs::write(&p, v.to_string()).unwrap();
        p.to_str().unwrap().to_string()
    };
    for (args, want) in [
        (
            vec!["render", "--shade", "shiny", "sample:eg-convex-n3", "-o", o],
            "shiny",
        ),
        (
            vec!["render", "--view", "10", "sample:eg-convex-n3", "-o", o],
            "AZIMUTH,ELEVATION",
        ),
        (
            vec!["render", "--view", "0,100", "sample:eg-convex-n3", "-o", o],
            "AZIMUTH,ELEVATION",
        ),
        (
            vec!["render", "--size", "10x10", "sample:eg-convex-n3", "-o", o],
            "WIDTHxHEIGHT",
        ),
        (vec!["render", "sample:eg-convex-n3"], "--output"),
        (
            vec!["render", "--scheme", "rts", "sample:eg-convex-n3", "-o", o],
            "--scheme rts needs",
        ),
        (
            vec!["render", "--scheme", "catmull-clark", &dnet_cc, "-o", o],
            "not a Catmull-Clark net",
        ),
        (
            vec!["compare", "sample:none", "-o", o],
            "no built-in sample",
        ),
        (
            vec!["render", "--depth", "1", &two_links, "-o", o],
            "no patch to draw",
        ),
    ] {
        let run = capdiv(&args, None);
        assert_eq!(run.code, Some(2), "{args:?}");
        assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
        assert!(run.stderr.contains(want), "{args:?}: {}", run.stderr);
        assert!(!out.exists(), "{args:?}: a partial output file");
    }
}
