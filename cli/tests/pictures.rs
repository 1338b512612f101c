//! The CLI's pictures as a user meets them: one set of defaults (depth 4,
//! 800×600) for `surface`, `render` and `compare`; highlight stripes that
//! are resolved (or fade) instead of aliasing on a tall object; the up
//! axis; `--focus` framing a vertex's cap; what a picture says it draws
//! (the curvature sign, the panels' schemes); the options' errors.
mod common;

use capdiv_cli::input::{Input, MeshJson};
use capdiv_cli::picture::{highlight_lines, probe, Camera, LightLines};
use capdiv_mesh::MeshInput;
use common::*;

const BACKGROUND: [u8; 3] = [246, 246, 246];

/// A closed tube of radius 1 around the z-axis from z = 0 to z = 12: 13
/// rings of `n` vertices one unit apart, each end closed by a fan to a pole
/// vertex (C²PS caps), faces counter-clockwise about the outward normal.
/// The cubic B-spline surface between the second and second-to-last ring
/// is exactly a vertical cylinder in z (equally spaced, identical rings): its
/// normals are horizontal.
fn tall_tube(n: usize) -> MeshInput {
    let rings = 13;
    let mut v = vec![[0.0, 0.0, 0.0]];
    for i in 0..rings {
        for j in 0..n {
            let t = std::f64::consts::TAU * j as f64 / n as f64;
            v.push([t.cos(), t.sin(), i as f64]);
        }
    }
    v.push([0.0, 0.0, (rings - 1) as f64]);
    let top = (v.len() - 1) as u32;
    let id = |i: usize, j: usize| (1 + i * n + j % n) as u32;
    let mut f = Vec::new();
    for j in 0..n {
        f.push(vec![0, id(0, j + 1), id(0, j)]);
        f.push(vec![top, id(rings - 1, j), id(rings - 1, j + 1)]);
    }
    for i in 0..rings - 1 {
        for j in 0..n {
            f.push(vec![id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)]);
        }
    }
    MeshInput::new(v, f)
}

fn obj_of(m: &MeshInput) -> String {
    let mut obj = String::new();
    for v in &m.vertices {
        obj += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    for f in &m.faces {
        let ids: Vec<String> = f.iter().map(|i| (i + 1).to_string()).collect();
        obj += &format!("f {}\n", ids.join(" "));
    }
    obj
}

/// The rows of the middle 60 % of the drawn span of column `x`.
fn middle_rows(png: &Png, x: usize) -> std::ops::Range<usize> {
    let drawn: Vec<usize> = (0..png.h).filter(|&y| png.at(x, y) != BACKGROUND).collect();
    let (a, b) = (drawn[0], *drawn.last().unwrap());
    let cut = (b - a) / 5;
    a + cut..b - cut
}

/// Highlight stripes on a tall cylinder, seen from the side (`--view 90,0`:
/// camera on `+y`, level) with the default light (the plane faces the
/// camera, lines along the screen's horizontal). A side point `p` has a
/// horizontal normal `n`, so the normal line `p + μn` meets the light plane
/// `y = const` at height `p_z`: the stripes are the heights `p_z` a whole
/// spacing apart, and with `N` spacings across the picture's 600 rows they
/// are exactly `600/N` pixels apart on screen, whatever the fit.
///
/// Along the middle column of the cylinder (constant normal, so constant
/// Lambert shading and red channel `g·(1 − i)`, `i` the stripe intensity):
/// - `N` = 37 and 90 (periods 16.2 and 6.7 pixels): the stripes are counted
///   as runs of rows darker than half the darkest; their count is the
///   analytic `rows / period` within 1, every gap between stripe centres is
///   the period within 1 pixel, and every stripe's darkness is at least 40 %
///   of the darkest (a stripe narrower than a pixel neither vanishes nor
///   flickers: a 6.7-pixel period has stripes 1.6 pixels wide, whose share of
///   a pixel varies with their phase between 0.40 and 0.69).
/// - `N` = 433 (period 1.39 pixels, beyond what 600 rows can show): the
///   column is flat (red within 2 levels) — no false stripes. Sampling the
///   stripe pulse at the same supersamples without the footprint filter
///   (the library's `HighlightLines::intensity`, averaged 2×2) gives a moiré
///   of more than 0.2 in intensity there: without the anti-aliasing this
///   check fails.
#[test]
fn highlight_stripes_on_a_tall_cylinder_are_resolved_not_aliased() {
    let dir = tempdir();
    let mesh = tall_tube(12);
    let obj = dir.path().join("tube.obj");
    std::fs::write(&obj, obj_of(&mesh)).unwrap();
    let picture = |lines: f64| {
        let out = dir.path().join(format!("tube-{lines}.png"));
        let n = lines.to_string();
        let args = [
            "render",
            "--shade",
            "highlight",
            "--view",
            "90,0",
            "--lines",
            &n,
            s(&obj),
            "-o",
            s(&out),
        ];
        capdiv(&args, None).assert_ok();
        read_png(&out)
    };
    for lines in [37.0, 90.0] {
        let png = picture(lines);
        assert_eq!((png.w, png.h), (800, 600));
        let period = 600.0 / lines;
        let mid_row = png.h / 2;
        let xs: Vec<usize> = (0..png.w)
            .filter(|&x| png.at(x, mid_row) != BACKGROUND)
            .collect();
        let x = (xs[0] + xs[xs.len() - 1]) / 2;
        let rows = middle_rows(&png, x);
        let red: Vec<f64> = rows.clone().map(|y| png.at(x, y)[0] as f64).collect();
        let g = red.iter().cloned().fold(0.0, f64::max);
        let dark: Vec<f64> = red.iter().map(|r| 1.0 - r / g).collect();
        let top = dark.iter().cloned().fold(0.0, f64::max);
        assert!(top > 0.3, "N = {lines}: no stripe ({top})");
        // Runs above half the darkest: centre (darkness-weighted) and peak.
        let mut stripes: Vec<(f64, f64)> = Vec::new();
        let mut run: Vec<(usize, f64)> = Vec::new();
        for (k, &d) in dark.iter().chain([0.0].iter()).enumerate() {
            if d > 0.5 * top {
                run.push((k, d));
            } else if !run.is_empty() {
                let mass: f64 = run.iter().map(|r| r.1).sum();
                let centre = run.iter().map(|r| r.0 as f64 * r.1).sum::<f64>() / mass;
                let peak = run.iter().map(|r| r.1).fold(0.0, f64::max);
                stripes.push((centre, peak));
                run.clear();
            }
        }
        let want = dark.len() as f64 / period;
        assert!(
            (stripes.len() as f64 - want).abs() <= 1.0,
            "N = {lines}: {} stripes in {} rows, want {want:.1}",
            stripes.len(),
            dark.len()
        );
        for w in stripes.windows(2) {
            let gap = w[1].0 - w[0].0;
            assert!(
                (gap - period).abs() <= 1.0,
                "N = {lines}: gap {gap:.2}, period {period}: {stripes:?}"
            );
        }
        let weakest = stripes.iter().map(|s| s.1).fold(f64::INFINITY, f64::min);
        assert!(
            weakest >= 0.4 * top,
            "N = {lines}: a stripe of {weakest:.2} against {top:.2}"
        );
        println!(
            "N = {lines}: {} stripes (analytic {want:.1}), darkness {weakest:.2}..{top:.2}",
            stripes.len()
        );
    }

    // Too dense for the pixels: flat, where point samples alias.
    let lines = 433.0;
    let png = picture(lines);
    let mid_row = png.h / 2;
    let xs: Vec<usize> = (0..png.w)
        .filter(|&x| png.at(x, mid_row) != BACKGROUND)
        .collect();
    let x = (xs[0] + xs[xs.len() - 1]) / 2;
    let rows = middle_rows(&png, x);
    let red: Vec<u8> = rows.clone().map(|y| png.at(x, y)[0]).collect();
    let (lo, hi) = (red.iter().min().unwrap(), red.iter().max().unwrap());
    assert!(hi - lo <= 2, "N = {lines}: red {lo}..{hi} along the column");

    let shape =
        capdiv_cli::shape::build("tube", &Input::Mesh(MeshJson::of(&mesh)), None, 4).unwrap();
    let cam = Camera {
        azimuth: 90.0,
        elevation: 0.0,
        ..Camera::default()
    };
    let light = LightLines {
        lines,
        ..LightLines::default()
    };
    let family = highlight_lines(&[&shape], &cam, &light).unwrap().unwrap();
    let samples = &probe(&[&shape], &cam).unwrap()[0];
    let w = 2 * cam.width;
    let naive: Vec<f64> = rows
        .map(|y| {
            let mut sum = 0.0;
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let smp = samples[(2 * y + dy) * w + 2 * x + dx].unwrap();
                sum += family.intensity(smp.point, smp.normal, 0.12);
            }
            sum / 4.0
        })
        .collect();
    let spread = naive.iter().cloned().fold(0.0, f64::max)
        - naive.iter().cloned().fold(f64::INFINITY, f64::min);
    assert!(
        spread > 0.2,
        "point samples would not alias here ({spread})"
    );
    println!("N = {lines}: red {lo}..{hi}; point-sampled intensity spread {spread:.2}");
}

fn png_size(path: &std::path::Path) -> (usize, usize) {
    let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let info = dec.read_info().unwrap();
    let i = info.info();
    (i.width as usize, i.height as usize)
}

/// Without `--depth` and `--size`: `surface` reports depth 4; `render`
/// draws 800×600 and the same bytes as with `--depth 4 --size 800x600`
/// (and other bytes than `--depth 3`, so the depth is not ignored);
/// `compare` draws 800-pixel panels; each command's `--help` states the
/// defaults.
#[test]
fn one_set_of_defaults() {
    let dir = tempdir();
    let mesh = write_json(
        dir.path(),
        "cube.json",
        &serde_json::json!({
            "kind": "mesh",
            "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0],[0,0,1],[1,0,1],[1,1,1],[0,1,1]],
            "faces": [[0,3,2,1],[4,5,6,7],[0,1,5,4],[1,2,6,5],[2,3,7,6],[3,0,4,7]]
        }),
    );
    let sum = capdiv(&["surface", "--quiet", s(&mesh)], None).ok_json();
    assert_eq!(sum["summary"]["depth"], 4);

    let out = |n: &str| dir.path().join(n);
    let render = |extra: &[&str], name: &str| {
        let mut args = vec!["render", "--shade", "mean", "sample:eg-saddle-n5"];
        args.extend_from_slice(extra);
        let path = out(name);
        args.extend_from_slice(&["-o", s(&path)]);
        capdiv(&args, None).assert_ok();
        std::fs::read(out(name)).unwrap()
    };
    let plain = render(&[], "default.png");
    assert_eq!(png_size(&out("default.png")).0, 800);
    // The legend strip is under the 600 rows of the picture.
    assert!(png_size(&out("default.png")).1 > 600);
    let explicit = render(&["--depth", "4", "--size", "800x600"], "explicit.png");
    assert_eq!(plain, explicit, "the defaults are not depth 4, 800x600");
    let shallower = render(&["--depth", "3"], "depth3.png");
    assert_ne!(plain, shallower, "--depth changes nothing");

    let run = capdiv(
        &["compare", "sample:eg-saddle-n5", "-o", s(&out("c.png"))],
        None,
    );
    run.assert_ok();
    // Two panels (EG, Catmull-Clark) and an 8-pixel gap.
    assert_eq!(png_size(&out("c.png")).0, 2 * 800 + 8);

    for cmd in ["surface", "render", "compare"] {
        let help = capdiv(&[cmd, "--help"], None).stdout_str();
        let depth = help
            .split("--depth")
            .nth(1)
            .unwrap_or_else(|| panic!("{cmd}: no --depth"));
        let depth = &depth[..depth.find("\n  -").unwrap_or(depth.len())];
        assert!(depth.contains("[default: 4]"), "{cmd}: {depth}");
        if cmd != "surface" {
            assert!(help.contains("[default: 800x600]"), "{cmd}: {help}");
        }
    }
}

/// The drawn pixels' bounding box in the first `rows` rows: width and
/// height.
fn drawn_box(png: &Png, rows: usize) -> (usize, usize) {
    let (mut x0, mut x1, mut y0, mut y1) = (usize::MAX, 0, usize::MAX, 0);
    for y in 0..rows.min(png.h) {
        for x in 0..png.w {
            if png.at(x, y) != BACKGROUND {
                (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
            }
        }
    }
    (x1 + 1 - x0, y1 + 1 - y0)
}

/// `--up`: the tube turned to lie along `y` (13 units long, 2 across),
/// seen level from `+x` (`--view 0,0`), stands upright with `--up y` (drawn
/// box more than 3 times as tall as wide) and lies on its side with the
/// default `--up z` (more than 3 times as wide as tall) in `render`'s
/// pictures. `surface --format png` has the default view (`-60,50`): with
/// `--up y` the tube stands (more than 3 times as tall as wide, above the
/// legend's bottom 16 rows), with `--up z` its axis is along the screen's
/// horizontal turned by 60° (less than 1.5 times as tall as wide).
#[test]
fn up_axis_turns_the_picture() {
    let dir = tempdir();
    let mut mesh = tall_tube(12);
    for v in &mut mesh.vertices {
        *v = [v[0], v[2], -v[1]];
    }
    let obj = dir.path().join("tube-y.obj");
    std::fs::write(&obj, obj_of(&mesh)).unwrap();
    for (up, tall) in [(Some("y"), true), (None, false)] {
        let out = dir.path().join("up.png");
        let mut args = vec!["render", "--view", "0,0", "--size", "300x300"];
        if let Some(u) = up {
            args.extend_from_slice(&["--up", u]);
        }
        args.extend_from_slice(&[s(&obj), "-o", s(&out)]);
        capdiv(&args, None).assert_ok();
        let (w, h) = drawn_box(&read_png(&out), 300);
        if tall {
            assert!(h > 3 * w, "--up y: drawn {w}x{h}");
        } else {
            assert!(w > 3 * h, "--up z: drawn {w}x{h}");
        }
        let mut args = vec!["surface", "--quiet", "--format", "png"];
        if let Some(u) = up {
            args.extend_from_slice(&["--up", u]);
        }
        args.extend_from_slice(&[s(&obj), "-o", s(&out)]);
        capdiv(&args, None).assert_ok();
        let png = read_png(&out);
        let (w, h) = drawn_box(&png, png.h - 16);
        if tall {
            assert!(h > 3 * w, "surface --up y: drawn {w}x{h}");
        } else {
            assert!(2 * h < 3 * w, "surface --up z: drawn {w}x{h}");
        }
    }
}

/// Bad picture options are one line `error: …`, exit 2, no file.
#[test]
fn bad_picture_options_are_one_line_errors() {
    let dir = tempdir();
    let out = dir.path().join("x.png");
    let o = s(&out);
    for (args, want) in [
        (vec!["--light", "0,0,0"], "X,Y,Z"),
        (vec!["--light", "1,2"], "X,Y,Z"),
        (vec!["--light", "1,nan,2"], "X,Y,Z"),
        (vec!["--light", "1,inf,2"], "X,Y,Z"),
        (vec!["--lines", "0"], "light lines"),
        (vec!["--lines", "many"], "light lines"),
        (vec!["--up", "x"], "--up"),
    ] {
        let mut all = vec!["render", "--shade", "highlight"];
        all.extend_from_slice(&args);
        all.extend_from_slice(&["sample:eg-convex-n3", "-o", o]);
        let run = capdiv(&all, None);
        assert_eq!(run.code, Some(2), "{args:?}");
        assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
        assert!(run.stderr.starts_with("error: "), "{}", run.stderr);
        assert!(run.stderr.contains(want), "{args:?}: {}", run.stderr);
        assert!(!out.exists());
    }
}

const HATCH: [[u8; 3]; 2] = [[200, 0, 160], [255, 255, 255]];

fn hatched(png: &Png) -> usize {
    (0..png.h)
        .flat_map(|y| (0..png.w).map(move |x| (x, y)))
        .filter(|&(x, y)| png.at(x, y) == HATCH[0])
        .count()
}

/// The 12-sided tall tube written as `tube.obj` and `tube.json` in `dir`
/// (the same mesh in each file's own numbering).
fn tube_files(dir: &std::path::Path) -> (std::path::PathBuf, std::path::PathBuf) {
    let mesh = tall_tube(12);
    let obj = dir.join("tube.obj");
    std::fs::write(&obj, obj_of(&mesh)).unwrap();
    let json = write_json(
        dir,
        "tube.json",
        &serde_json::json!({"kind": "mesh", "vertices": mesh.vertices, "faces": mesh.faces}),
    );
    (obj, json)
}

/// `--focus V --zoom Z` on the tall tube, whose top pole (OBJ vertex 158,
/// JSON vertex 157) has a C²PS cap:
/// - the cap's limit point is at the picture's centre: the centre pixel is
///   the hatched hole (the hole closes to the limit point), in `render` and
///   in both `compare` panels;
/// - the OBJ's vertex 158 and the same mesh as JSON's vertex 157 give the
///   same picture, byte for byte (each file's own numbering);
/// - the view is orthographic, so the hole's hatched area grows with the
///   square of the zoom: zoom 4 against zoom 2 is 4 within 10 % (the hole's
///   rim is a few hundred of some 10⁴ pixels);
/// - a regular vertex halfway up the side facing the camera (OBJ 84, at
///   azimuth −60°), framed at zoom 4 (a quarter of its 1-ring each side of
///   the centre), fills the picture: no background pixel.
#[test]
fn focus_frames_a_vertex_cap() {
    let dir = tempdir();
    let (obj, json) = tube_files(dir.path());
    let render = |file: &std::path::Path, args: &[&str], name: &str| {
        let out = dir.path().join(name);
        let mut all = vec!["render"];
        all.extend_from_slice(args);
        all.extend_from_slice(&[s(file), "-o", s(&out)]);
        capdiv(&all, None).assert_ok();
        out
    };
    let top = render(&obj, &["--focus", "158"], "top.png");
    let png = read_png(&top);
    assert!(
        HATCH.contains(&png.at(400, 300)),
        "centre {:?}",
        png.at(400, 300)
    );
    let top_json = render(&json, &["--focus", "157"], "top-json.png");
    assert_eq!(
        std::fs::read(&top).unwrap(),
        std::fs::read(&top_json).unwrap(),
        "OBJ vertex 158 and JSON vertex 157 frame differently"
    );
    let zoom2 = read_png(&render(&obj, &["--focus", "158", "--zoom", "2"], "z2.png"));
    let (a4, a2) = (hatched(&png), hatched(&zoom2));
    let ratio = a4 as f64 / a2 as f64;
    assert!(
        (ratio - 4.0).abs() < 0.4,
        "hatched {a4} at zoom 4, {a2} at 2"
    );
    println!("hole: {a4} hatched pixels at zoom 4, {a2} at zoom 2 (ratio {ratio:.3})");

    let side = read_png(&render(&obj, &["--focus", "84"], "side.png"));
    let empty = (0..side.h)
        .flat_map(|y| (0..side.w).map(move |x| (x, y)))
        .filter(|&(x, y)| side.at(x, y) == BACKGROUND)
        .count();
    assert_eq!(
        empty, 0,
        "a regular vertex's neighbourhood leaves background"
    );

    let out = dir.path().join("compare.png");
    let run = capdiv(
        &[
            "compare",
            "--focus",
            "158",
            "--size",
            "300x200",
            s(&obj),
            "-o",
            s(&out),
        ],
        None,
    );
    run.assert_ok();
    let png = read_png(&out);
    assert_eq!(png.w, 2 * 300 + 8);
    for panel in 0..2 {
        let c = png.at(panel * 308 + 150, 20 + 100);
        assert!(HATCH.contains(&c), "panel {panel}: centre {c:?}");
    }
}

/// `--focus` errors: one line, exit 2, naming the vertex numbers the file
/// has (OBJ from 1, JSON from 0; a polar net's only cap is vertex 0);
/// `--zoom` without `--focus` and a zoom out of range are refused.
#[test]
fn focus_out_of_range_is_a_one_line_error() {
    let dir = tempdir();
    let (obj, json) = tube_files(dir.path());
    let out = dir.path().join("x.png");
    let o = s(&out);
    for (args, want) in [
        (
            vec!["render", "--focus", "159", s(&obj)],
            "vertices 1..=158",
        ),
        (vec!["render", "--focus", "0", s(&obj)], "vertices 1..=158"),
        (
            vec!["compare", "--focus", "158", s(&json)],
            "vertices 0..=157",
        ),
        (
            vec!["render", "--focus", "1", "sample:c2ps-saddle-n8"],
            "one cap, at vertex 0",
        ),
        (vec!["render", "--zoom", "2", s(&obj)], "--focus"),
        (
            vec!["render", "--focus", "1", "--zoom", "0", s(&obj)],
            "magnification",
        ),
        (vec!["render", "--focus", "-1", s(&obj)], "'-1'"),
    ] {
        let mut all = args.clone();
        all.extend_from_slice(&["-o", o]);
        let run = capdiv(&all, None);
        assert_eq!(run.code, Some(2), "{args:?}");
        assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
        assert!(run.stderr.contains(want), "{args:?}: {}", run.stderr);
        assert!(!out.exists(), "{args:?}");
    }
}

fn mesh_file(dir: &std::path::Path, name: &str, m: &MeshInput) -> std::path::PathBuf {
    write_json(
        dir,
        name,
        &serde_json::json!({"kind": "mesh", "vertices": m.vertices, "faces": m.faces}),
    )
}

/// The mean-curvature legend states its sign convention, and the colours
/// follow it: `H > 0` where the surface bends towards its normal, so the
/// globe (a unit sphere of faces counter-clockwise seen from outside:
/// outward normals) is drawn in the negative, blue half of the bar — as the
/// legend's "Outward unit sphere: H = -1" says — and the paraboloid
/// `z = (x² + y²)/2` with its normal up (`sample:c2ps-convex-n20`) in the
/// positive, red half. Counted over the surface pixels: more than 95 %
/// bluish (blue above red by 30 levels) for the sphere, more than 95 %
/// reddish for the paraboloid. The legend's second text row (rows 32..40
/// of the strip) carries the convention's text: dark pixels there.
#[test]
fn mean_curvature_legend_states_and_follows_its_sign() {
    use capdiv_cli::picture::{sign_convention, Shading, LEGEND_HEIGHT};
    let rule = sign_convention(Shading::Mean).unwrap();
    assert!(rule.contains("towards the normal"), "{rule}");
    assert!(rule.contains("Outward unit sphere: H = -1"), "{rule}");
    assert!(sign_convention(Shading::Gauss).unwrap().contains("saddle"));
    assert!(sign_convention(Shading::Plain).is_none());

    let dir = tempdir();
    let globe = mesh_file(dir.path(), "globe.json", &capdiv_mesh::samples::globe(8, 9));
    for (file, negative) in [(s(&globe), true), ("sample:c2ps-convex-n20", false)] {
        let out = dir.path().join("mean.png");
        capdiv(&["render", "--shade", "mean", file, "-o", s(&out)], None).assert_ok();
        let png = read_png(&out);
        assert_eq!(png.h, 600 + LEGEND_HEIGHT);
        let (mut blue, mut red, mut surface) = (0, 0, 0);
        for y in 0..600 {
            for x in 0..png.w {
                let [r, _, b] = png.at(x, y).map(i32::from);
                if png.at(x, y) == BACKGROUND || HATCH.contains(&png.at(x, y)) {
                    continue;
                }
                surface += 1;
                blue += usize::from(b > r + 30);
                red += usize::from(r > b + 30);
            }
        }
        let (want, other) = if negative { (blue, red) } else { (red, blue) };
        assert!(
            want * 100 > 95 * surface,
            "{file}: {blue} blue, {red} red of {surface} ({other} of the other sign)"
        );
        let ink = (600 + 32..600 + 40)
            .flat_map(|y| (0..png.w).map(move |x| (x, y)))
            .filter(|&(x, y)| png.at(x, y).iter().all(|&c| c < 60))
            .count();
        assert!(ink > 100, "{file}: no sign convention under the bar");
    }
}

/// A panel is labelled by what it used. A mesh's label counts its caps by
/// scheme: the valence-7 disk (no EG rule for 7) gets a Catmull-Clark cap
/// from the default pipeline too, so both `compare` panels read `caps:
/// Catmull-Clark x1` and the command notes on stderr that they draw the
/// same surface; the valence-5 disk's default panel reads `caps: EG x1`
/// (no note); the tube `caps: C2PS x2`; a torus (every vertex regular) `no
/// caps (B-spline only)`. With `--focus`, a label names the cap at the
/// vertex.
#[test]
fn compare_labels_panels_by_what_they_used() {
    use capdiv_cli::args::ShapeScheme;
    use capdiv_cli::shape::build;
    use capdiv_mesh::samples::{extraordinary_disk, torus};
    let label = |m: &MeshInput, scheme: Option<ShapeScheme>| {
        build("m", &Input::Mesh(MeshJson::of(m)), scheme, 3)
            .unwrap()
            .label
    };
    let cc = Some(ShapeScheme::CatmullClark);
    let disk7 = extraordinary_disk(7, 3);
    let disk5 = extraordinary_disk(5, 3);
    assert_eq!(label(&disk7, None), "caps: Catmull-Clark x1");
    assert_eq!(label(&disk7, cc), "caps: Catmull-Clark x1");
    assert_eq!(label(&disk5, None), "caps: EG x1");
    assert_eq!(label(&disk5, cc), "caps: Catmull-Clark x1");
    assert_eq!(label(&tall_tube(12), None), "caps: C2PS x2");
    assert_eq!(label(&torus(8, 6), None), "no caps (B-spline only)");

    let shape = build("m", &Input::Mesh(MeshJson::of(&disk5)), None, 3).unwrap();
    let centre = shape.caps[0].vertex.unwrap() as usize;
    assert_eq!(
        capdiv_cli::focus::focus_label(&shape, centre, centre),
        format!("vertex {centre}: EG cap")
    );
    assert_eq!(
        capdiv_cli::focus::focus_label(&shape, centre + 1, centre + 1),
        format!("vertex {}: no cap; caps: EG x1", centre + 1)
    );

    let dir = tempdir();
    let out = dir.path().join("c.png");
    for (m, note) in [(&disk7, true), (&disk5, false)] {
        let file = mesh_file(dir.path(), "disk.json", m);
        let args = ["compare", "--size", "200x150", s(&file), "-o", s(&out)];
        let run = capdiv(&args, None);
        assert_eq!(run.code, Some(0), "{}", run.stderr);
        if note {
            assert_eq!(
                run.stderr.trim(),
                "note: panels 1 and 2 draw the same surface (caps: Catmull-Clark x1)"
            );
        } else {
            assert!(run.stderr.is_empty(), "{}", run.stderr);
        }
    }
}

/// A `--focus` frame deeper than the rings reach shows only the hatched
/// hole, and the command says so on stderr (and still writes the
/// picture): the EG cap of `sample:eg-convex-n5` at depth 4 has a hole of
/// about 0.55⁴ ≈ 0.09 of its 1-ring, wider than the 1/50 a zoom of 50
/// frames; at depth 10 (0.55¹⁰ ≈ 0.003) rings are in view and there is
/// no note.
#[test]
fn focus_beyond_the_rings_says_so() {
    let dir = tempdir();
    let out = dir.path().join("deep.png");
    let run = capdiv(
        &[
            "render",
            "--focus",
            "0",
            "--zoom",
            "50",
            "sample:eg-convex-n5",
            "-o",
            s(&out),
        ],
        None,
    );
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert_eq!(
        run.stderr.trim(),
        "note: panel 1: at zoom 50 only the cap's hole is in view (depth 4): \
         raise --depth or lower --zoom"
    );
    assert!(out.exists());
    let args = [
        "render",
        "--focus",
        "0",
        "--zoom",
        "50",
        "--depth",
        "10",
        "sample:eg-convex-n5",
        "-o",
        s(&out),
    ];
    capdiv(&args, None).assert_ok();
}
