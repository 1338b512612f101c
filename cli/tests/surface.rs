//! `capdiv surface`: whole meshes (OBJ or JSON) to patches and caps, welded
//! OBJ and PNG. Patches are compared with `capdiv_mesh`'s evaluator called
//! here directly; closedness of the OBJ is checked on the parsed output.

mod common;

use capdiv_mesh::samples;
use capdiv_mesh::sinks::CollectSurface;
use capdiv_mesh::{Evaluator, MeshInput, PatchRecord, PlanOptions, Scheme, SurfacePlan, Topology};
use common::*;
use serde_json::{json, Value};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Corner forms an OBJ face can be written in.
#[derive(Clone, Copy)]
enum Corners {
    Plain,
    TexNormal,
    Normal,
    Negative,
}

/// OBJ text of a mesh, faces written in `form` (texture and normal indices
/// refer to one dummy `vt`/`vn` each).
fn obj_text(m: &MeshInput, form: Corners) -> String {
    let mut t = String::from("# written by the test\nvt 0 0\nvn 0 0 1\n");
    let mut written = 0usize;
    let mut vlines = String::new();
    for p in &m.vertices {
        vlines += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    if !matches!(form, Corners::Negative) {
        t += &vlines;
        written = m.vertices.len();
    }
    for f in &m.faces {
        if let Corners::Negative = form {
            // Emit every vertex the face needs before it; refer backwards.
            let need = f.iter().map(|&i| i as usize + 1).max().unwrap();
            while written < need {
                let p = m.vertices[written];
                t += &format!("v {} {} {}\n", p[0], p[1], p[2]);
                written += 1;
            }
        }
        t.push('f');
        for &i in f {
            let one = i as i64 + 1;
            match form {
                Corners::Plain => t += &format!(" {one}"),
                Corners::TexNormal => t += &format!(" {one}/1/1"),
                Corners::Normal => t += &format!(" {one}//1"),
                Corners::Negative => t += &format!(" {}", one - written as i64 - 1),
            }
        }
        t.push('\n');
    }
    t
}

fn mesh_json(m: &MeshInput) -> Value {
    json!({"kind": "mesh", "vertices": m.vertices, "faces": m.faces})
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Runs `capdiv surface --quiet args… FILE` and returns the JSON.
fn surface(args: &[&str], file: &str, stdin: Option<&[u8]>) -> Value {
    let mut all = vec!["surface", "--quiet"];
    all.extend_from_slice(args);
    all.push(file);
    capdiv(&all, stdin).ok_json()
}

/// The output without its wall-clock times.
fn untimed(mut v: Value) -> Value {
    v["summary"]
        .as_object_mut()
        .expect("summary")
        .remove("times_ms")
        .expect("times_ms");
    v
}

/// The library's own evaluation of `m`, and its plan's patch counts per
/// kind computed from the plan's structure.
fn library(m: &MeshInput, depth: u32) -> (CollectSurface<f64>, HashMap<&'static str, usize>) {
    let topo = Topology::new(m).unwrap();
    let plan = SurfacePlan::new(
        &topo,
        PlanOptions {
            depth,
            ..Default::default()
        },
    )
    .unwrap();
    let mut counts = HashMap::new();
    counts.insert("regular", plan.regular.len());
    // A C²PS cap emits levels 1..=depth, each 2 spans of n·2^m columns.
    counts.insert(
        "c2ps",
        plan.polar
            .iter()
            .map(|p| (1..=depth).map(|m| 2 * (p.valence << m)).sum::<usize>())
            .sum(),
    );
    // EG and Catmull-Clark: 3n patches a step.
    for (scheme, id) in [(Scheme::Eg, "eg"), (Scheme::CatmullClark, "catmull-clark")] {
        counts.insert(
            id,
            plan.extraordinary
                .iter()
                .filter(|e| e.scheme == scheme)
                .map(|e| 3 * e.sectors.len() * depth as usize)
                .sum(),
        );
    }
    let mut ev = Evaluator::<f64>::new(&plan).unwrap();
    let mut sink = CollectSurface::new();
    ev.evaluate(&m.vertices, &mut sink).unwrap();
    (sink, counts)
}

fn geometry_points(p: &PatchRecord<f64>) -> (usize, Vec<Vec<[f64; 3]>>) {
    use capdiv_mesh::tessellate::PatchGeometry;
    match &p.geometry {
        PatchGeometry::Cubic(t) => (
            3,
            t.points
                .iter()
                .map(|r| r.iter().map(|q| q.0).collect())
                .collect(),
        ),
        PatchGeometry::Quartic(t) => (
            4,
            t.points
                .iter()
                .map(|r| r.iter().map(|q| q.0).collect())
                .collect(),
        ),
    }
}

fn small_meshes() -> Vec<(&'static str, MeshInput)> {
    vec![
        ("rounded-cube", samples::rounded_cube(2)),
        ("globe", samples::globe(6, 7)),
        ("ev-disk7", samples::extraordinary_disk(7, 3)),
        ("tri-pent", samples::triangle_and_pentagon_mesh()),
        ("two-beam", samples::two_beam_corner()),
    ]
}

#[test]
fn json_patches_equal_the_library() {
    let dir = tempdir();
    let depth = 2;
    for (name, m) in small_meshes() {
        let path = write(
            dir.path(),
            &format!("{name}.obj"),
            &obj_text(&m, Corners::Plain),
        );
        let out = surface(&["--depth", "2"], s(&path), None);
        let (lib, counts) = library(&m, depth);
        let patches = out["patches"].as_array().unwrap();
        assert_eq!(patches.len(), lib.patches.len(), "{name}");
        for (k, (got, want)) in patches.iter().zip(&lib.patches).enumerate() {
            let (d, pts) = geometry_points(want);
            assert_eq!(got["kind"], want.kind.id(), "{name} patch {k}");
            assert_eq!(got["degree"], d, "{name} patch {k}");
            assert_eq!(got["level"], want.level, "{name} patch {k}");
            assert_eq!(got["face"], want.face, "{name} patch {k}");
            match want.corner {
                Some(c) => assert_eq!(got["corner"], c, "{name} patch {k}"),
                None => assert!(got.get("corner").is_none(), "{name} patch {k}"),
            }
            let dom: Vec<f64> = got["domain"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            assert_eq!(dom, want.domain.to_vec(), "{name} patch {k}");
            assert!(
                dom.iter().all(|&x| (0.0..=1.0).contains(&x)) && dom[0] < dom[1] && dom[2] < dom[3],
                "{name} patch {k}: domain {dom:?}"
            );
            let got_pts = got["points"].as_array().unwrap();
            assert_eq!(got_pts.len(), (d + 1) * (d + 1), "{name} patch {k}");
            // points[(d+1)·j + i] = b_ij, i along u.
            for (i, row) in pts.iter().enumerate() {
                for (j, b) in row.iter().enumerate() {
                    assert_eq!(
                        p3(&got_pts[(d + 1) * j + i]),
                        *b,
                        "{name} patch {k} b{i}{j}"
                    );
                }
            }
        }
        // Counts per kind: the JSON, the summary and the plan agree.
        for (kind, &n) in &counts {
            let in_json = patches.iter().filter(|p| p["kind"] == *kind).count();
            assert_eq!(in_json, n, "{name}: {kind}");
            assert_eq!(out["summary"]["patches"][*kind], n, "{name}: {kind}");
        }
        assert_eq!(out["summary"]["patches"]["total"], lib.patches.len());
        // Caps: same order, vertex/face, scheme, valence, limit.
        let caps = out["caps"].as_array().unwrap();
        assert_eq!(caps.len(), lib.caps.len(), "{name}");
        for (got, want) in caps.iter().zip(&lib.caps) {
            match want.vertex {
                Some(v) => {
                    assert_eq!(got["vertex"], v);
                    assert!(got.get("face").is_none());
                }
                None => {
                    assert!(got["vertex"].is_null());
                    assert_eq!(got["face"], want.face.unwrap());
                }
            }
            assert_eq!(got["scheme"], want.scheme.id());
            assert_eq!(got["valence"], want.valence);
            assert_eq!(p3(&got["limit"]), want.limit.0);
            match want.normal {
                Some(n) => assert_eq!(p3(&got["normal"]), n.0),
                None => assert!(got["normal"].is_null()),
            }
            assert_eq!(
                got["principal_curvatures"].is_null(),
                want.principal_curvatures.is_none()
            );
        }
        let sum = &out["summary"];
        assert_eq!(sum["input"]["vertices"], m.vertices.len());
        assert_eq!(sum["input"]["faces"], m.faces.len());
        assert_eq!(sum["depth"], depth);
        assert!(sum["times_ms"]["analysis"].as_f64().unwrap() >= 0.0);
        assert!(sum["times_ms"]["evaluation"].as_f64().unwrap() >= 0.0);
    }
}

#[test]
fn summary_reports_refinement_caps_and_reasons() {
    let dir = tempdir();
    // The plain cube: every face next to four valence-3 points, so one
    // whole-mesh step (it refines no face that does not need it); the caps
    // one level in.
    let path = write(
        dir.path(),
        "cube.obj",
        &obj_text(&samples::cube(), Corners::Plain),
    );
    let out = surface(&["--depth", "1"], s(&path), None);
    let sum = &out["summary"];
    assert_eq!(sum["refinement_steps"], 1);
    assert_eq!(sum["fallbacks"], json!([]));
    let needed = sum["needed_refinement"].as_array().unwrap();
    assert_eq!(needed.len(), 6);
    for (k, f) in needed.iter().enumerate() {
        assert_eq!(f["face"], k);
        assert_eq!(f["reason"], "crowded-irregular");
        assert!(f["description"].as_str().unwrap().len() > 5);
    }
    assert_eq!(sum["uncovered"], json!([]));
    assert_eq!(
        sum["caps"],
        json!([{"scheme": "eg", "valence": 3, "count": 8}])
    );
    // The triangle-and-pentagon prism (no face a quad: one whole-mesh step,
    // then adaptive): caps at face centres (two levels in) name their face.
    let path = write(
        dir.path(),
        "tp.obj",
        &obj_text(&samples::triangle_and_pentagon_mesh(), Corners::Plain),
    );
    let out = surface(&["--depth", "1"], s(&path), None);
    assert_eq!(out["summary"]["refinement_steps"], 1);
    assert!(out["caps"]
        .as_array()
        .unwrap()
        .iter()
        .any(|c| c["vertex"].is_null() && c["face"].is_u64()));
    // An open mesh with an irregular boundary vertex: uncovered with a reason.
    let open = MeshInput::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        vec![vec![0, 1, 2, 3]],
    );
    let path = write(dir.path(), "quad.obj", &obj_text(&open, Corners::Plain));
    let out = surface(&[], s(&path), None);
    assert_eq!(out["summary"]["input"]["closed"], false);
    let unc = out["summary"]["uncovered"].as_array().unwrap();
    assert_eq!(unc.len() + out["patches"].as_array().unwrap().len(), 1);
    for u in unc {
        assert_eq!(u["face"], 0);
        assert!(u["reason"].is_string() && u["description"].is_string());
    }
}

#[test]
fn obj_corner_forms_parse_the_same() {
    let dir = tempdir();
    let m = samples::two_beam_corner();
    let mut outs = vec![];
    for (k, form) in [
        Corners::Plain,
        Corners::TexNormal,
        Corners::Normal,
        Corners::Negative,
    ]
    .into_iter()
    .enumerate()
    {
        let text = obj_text(&m, form);
        let path = write(dir.path(), &format!("m{k}.obj"), &text);
        let mut out = untimed(surface(&["--depth", "2"], s(&path), None));
        // The `v/t/n` form gives every corner the one `vt 0 0`: a constant
        // UV, which every patch carries at its four corners; the rest of the
        // output is that of the other forms.
        for p in out["patches"].as_array_mut().expect("patches") {
            let uv = p.as_object_mut().expect("patch").remove("uv");
            match form {
                Corners::TexNormal => assert_eq!(
                    uv,
                    Some(serde_json::json!([
                        [0.0, 0.0],
                        [0.0, 0.0],
                        [0.0, 0.0],
                        [0.0, 0.0]
                    ]))
                ),
                _ => assert_eq!(uv, None),
            }
        }
        outs.push(out);
    }
    // The negative-index file orders its vertices differently only if the
    // faces did; samples list vertices in use order, so all must match.
    for o in &outs[1..] {
        assert_eq!(o, &outs[0]);
    }
}

#[test]
fn stdin_and_json_mesh_give_the_same_output_as_obj() {
    let dir = tempdir();
    let m = samples::globe(5, 7);
    let obj = obj_text(&m, Corners::Plain);
    let obj_path = write(dir.path(), "g.obj", &obj);
    let json_path = write_json(dir.path(), "g.json", &mesh_json(&m));
    let args = ["--depth", "2"];
    let from_obj = untimed(surface(&args, s(&obj_path), None));
    let from_json = untimed(surface(&args, s(&json_path), None));
    let obj_stdin = untimed(surface(&args, "-", Some(obj.as_bytes())));
    let json_text = serde_json::to_vec(&mesh_json(&m)).unwrap();
    let json_stdin = untimed(surface(&args, "-", Some(&json_text)));
    assert_eq!(from_json, from_obj);
    assert_eq!(obj_stdin, from_obj);
    assert_eq!(json_stdin, from_obj);
    // OBJ output through stdin and -o is the same file.
    let out = dir.path().join("g-out.obj");
    let run = capdiv(
        &["surface", "--quiet", "--format", "obj", "-o", s(&out), "-"],
        Some(&json_text),
    );
    run.assert_ok();
    assert!(run.stdout.is_empty());
    let direct = capdiv(
        &["surface", "--quiet", "--format", "obj", s(&obj_path)],
        None,
    );
    direct.assert_ok();
    // Only the title line names the input.
    let strip = |t: &str| -> String {
        t.lines()
            .filter(|l| !l.starts_with("# capdiv surface"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(
        strip(&std::fs::read_to_string(&out).unwrap()),
        strip(&direct.stdout_str())
    );
}

/// Every undirected edge of the OBJ's faces used exactly twice, in opposite
/// directions; returns (vertices, edges, faces).
fn assert_closed_oriented(text: &str, what: &str) -> (usize, usize, usize) {
    let obj = parse_obj(text);
    assert_eq!(obj.v.len(), obj.vn.len(), "{what}");
    let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
    for f in &obj.f {
        assert!(f.len() == 3 || f.len() == 4, "{what}: face of {}", f.len());
        for k in 0..f.len() {
            let (a, b) = (f[k].0, f[(k + 1) % f.len()].0);
            assert_eq!(f[k].0, f[k].1, "{what}: v//vn indices differ");
            assert!(a >= 1 && a <= obj.v.len(), "{what}");
            assert_ne!(a, b, "{what}: degenerate edge");
            *directed.entry((a, b)).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &directed {
        assert_eq!(
            n, 1,
            "{what}: edge {a}->{b} used {n} times in one direction"
        );
        assert_eq!(
            directed.get(&(b, a)),
            Some(&1),
            "{what}: edge {a}->{b} has no opposite"
        );
    }
    // Normals are unit vectors.
    for n in &obj.vn {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-4, "{what}: normal {n:?}");
    }
    (obj.v.len(), directed.len() / 2, obj.f.len())
}

#[test]
fn closed_inputs_give_closed_oriented_objs() {
    let dir = tempdir();
    let meshes = [
        ("rounded-cube", samples::rounded_cube(2)),
        ("globe", samples::globe(6, 7)),
        ("cube", samples::cube()),
        ("tri-pent", samples::triangle_and_pentagon_mesh()),
        ("two-beam", samples::two_beam_corner()),
    ];
    for (name, m) in meshes {
        let path = write(
            dir.path(),
            &format!("{name}.obj"),
            &obj_text(&m, Corners::Plain),
        );
        for (precision, grid, depth) in [("f64", "3", "3"), ("f32", "2", "4")] {
            let what = format!("{name} {precision}");
            let run = capdiv(
                &[
                    "surface",
                    "--format",
                    "obj",
                    "--depth",
                    depth,
                    "--grid",
                    grid,
                    "--precision",
                    precision,
                    s(&path),
                ],
                None,
            );
            assert_eq!(run.code, Some(0), "{what}: {}", run.stderr);
            // The summary on stderr reports closedness, and is no error.
            assert!(run.stderr.starts_with("capdiv surface: "), "{}", run.stderr);
            assert!(!run.stderr.lines().any(|l| l.starts_with("error")));
            assert!(
                run.stderr.contains("closed and consistently oriented"),
                "{what}: {}",
                run.stderr
            );
            let (v, e, f) = assert_closed_oriented(&run.stdout_str(), &what);
            // A closed surface of genus 0.
            assert_eq!(v as i64 - e as i64 + f as i64, 2, "{what}: Euler");
        }
    }
    // A torus: genus 1.
    let path = write(
        dir.path(),
        "torus.obj",
        &obj_text(&samples::torus(6, 5), Corners::Plain),
    );
    let run = capdiv(&["surface", "--quiet", "--format", "obj", s(&path)], None);
    run.assert_ok();
    let (v, e, f) = assert_closed_oriented(&run.stdout_str(), "torus");
    assert_eq!(v as i64 - e as i64 + f as i64, 0);
}

/// f32 output near deep poles: the hand (finger-tip poles of valence 8, a
/// wrist pole of valence 26) at depth 5 has ring columns closer together than
/// f32 rounding separates; welded by the f64 surface's connectivity it is
/// closed and has exactly the f64 output's vertices, faces and edges.
#[test]
fn deep_f32_objs_weld_like_f64() {
    let dir = tempdir();
    let path = write(
        dir.path(),
        "hand.obj",
        &obj_text(&samples::hand(), Corners::Plain),
    );
    let counts = |precision: &str| {
        let run = capdiv(
            &[
                "surface",
                "--quiet",
                "--format",
                "obj",
                "--depth",
                "5",
                "--grid",
                "2",
                "--precision",
                precision,
                s(&path),
            ],
            None,
        );
        run.assert_ok();
        assert_closed_oriented(&run.stdout_str(), precision)
    };
    let f64_counts = counts("f64");
    assert_eq!(counts("f32"), f64_counts);
    let (v, e, f) = f64_counts;
    assert_eq!(v as i64 - e as i64 + f as i64, 2);
}

#[test]
fn obj_vertices_lie_on_the_patches() {
    // Every patch corner b_00 evaluated by the library is an OBJ vertex (to
    // the weld tolerance).
    let dir = tempdir();
    let m = samples::rounded_cube(2);
    let path = write(dir.path(), "rc.obj", &obj_text(&m, Corners::Plain));
    let run = capdiv(
        &[
            "surface",
            "--quiet",
            "--format",
            "obj",
            "--depth",
            "2",
            s(&path),
        ],
        None,
    );
    run.assert_ok();
    let obj = parse_obj(&run.stdout_str());
    let (lib, _) = library(&m, 2);
    for p in &lib.patches {
        let (_, pts) = geometry_points(p);
        let c = pts[0][0];
        let near = obj
            .v
            .iter()
            .map(|v| diff(v, &c))
            .fold(f64::INFINITY, f64::min);
        assert!(near < 1e-12, "corner {c:?} is {near} from the OBJ");
    }
}

#[test]
fn png_output_decodes() {
    let dir = tempdir();
    let path = write(
        dir.path(),
        "g.obj",
        &obj_text(&samples::globe(6, 7), Corners::Plain),
    );
    let out = dir.path().join("g.png");
    let run = capdiv(
        &[
            "surface",
            "--quiet",
            "--format",
            "png",
            "--depth",
            "3",
            "-o",
            s(&out),
            s(&path),
        ],
        None,
    );
    run.assert_ok();
    let (w, h, rgb) = decode_png(&std::fs::read(&out).unwrap());
    assert_eq!((w, h), (800, 600));
    let drawn = rgb.chunks(3).filter(|p| p != &[246, 246, 246]).count();
    assert!(drawn > w * h / 10, "only {drawn} pixels drawn");
}

#[test]
fn f32_patches_equal_the_library_in_f32() {
    let dir = tempdir();
    let m = samples::globe(6, 7);
    let path = write(dir.path(), "g.obj", &obj_text(&m, Corners::Plain));
    let out = surface(&["--depth", "2", "--precision", "f32"], s(&path), None);
    let topo = Topology::new(&m).unwrap();
    let plan = SurfacePlan::new(
        &topo,
        PlanOptions {
            depth: 2,
            ..Default::default()
        },
    )
    .unwrap();
    let pos: Vec<[f32; 3]> = m.vertices.iter().map(|p| p.map(|c| c as f32)).collect();
    let mut ev = Evaluator::<f32>::new(&plan).unwrap();
    let mut sink = CollectSurface::new();
    ev.evaluate(&pos, &mut sink).unwrap();
    let patches = out["patches"].as_array().unwrap();
    assert_eq!(patches.len(), sink.patches.len());
    assert_eq!(out["summary"]["precision"], "f32");
    for (got, want) in patches.iter().zip(&sink.patches) {
        let capdiv_mesh::tessellate::PatchGeometry::Cubic(t) = &want.geometry else {
            panic!("globe patches are bicubic")
        };
        for i in 0..4 {
            for j in 0..4 {
                let g = &got["points"][4 * j + i];
                for k in 0..3 {
                    // Printed as the shortest f32 form: parses back exactly.
                    assert_eq!(g[k].as_f64().unwrap() as f32, t.points[i][j].0[k]);
                }
            }
        }
    }
}

/// Runs `surface` on `content` (written to a file), expects a clean failure
/// whose line contains `needle`.
fn expect_failure(dir: &Path, label: &str, content: &[u8], extra: &[&str], needle: &str) {
    let input = dir.join(format!("{label}.in"));
    std::fs::write(&input, content).unwrap();
    let out = dir.join(format!("{label}.out"));
    let mut args = vec!["surface", "-o", s(&out)];
    args.extend_from_slice(extra);
    args.push(s(&input));
    let run = capdiv(&args, None);
    assert_eq!(run.code, Some(2), "{label}: {}", run.stderr);
    assert!(run.stdout.is_empty(), "{label}");
    assert_eq!(run.stderr.lines().count(), 1, "{label}: {}", run.stderr);
    assert!(run.stderr.starts_with("error: "), "{label}: {}", run.stderr);
    assert!(
        run.stderr.contains(needle),
        "{label}: {:?} lacks {needle:?}",
        run.stderr
    );
    assert!(!out.exists(), "{label}: output file written");
}

/// Meshes OpenSubdiv takes and capdiv once refused: a non-manifold edge
/// (infinitely sharp), two faces running an edge the same way, and faces
/// listing a vertex twice (a degenerate edge; an edge run twice).
#[test]
fn non_manifold_and_inconsistent_meshes_give_a_surface() {
    let dir = tempdir();
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
    for (label, content) in [
        (
            "non-manifold-edge",
            format!("{tri}v 0 0 1\nv 0 0 -1\nf 1 2 3\nf 2 1 5\nf 2 1 4\n"),
        ),
        ("inconsistent", format!("{tri}f 1 2 3\nf 1 2 4\n")),
        ("repeated", format!("{tri}f 1 2 3\nf 2 4 4 3\n")),
        ("repeated-twice", format!("{tri}f 1 2 3\nf 3 2 4 2\n")),
    ] {
        let input = dir.path().join(format!("{label}.obj"));
        std::fs::write(&input, content).unwrap();
        let out = dir.path().join(format!("{label}.json"));
        let run = capdiv(&["surface", "-o", s(&out), s(&input)], None);
        assert_eq!(run.code, Some(0), "{label}: {}", run.stderr);
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
        assert!(!json["patches"].as_array().unwrap().is_empty(), "{label}");
        assert!(
            json["summary"]["uncovered"].as_array().unwrap().is_empty(),
            "{label}"
        );
    }
}

#[test]
fn bad_meshes_fail_cleanly() {
    let dir = tempdir();
    let d = dir.path();
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "out-of-range",
            format!("{tri}f 1 2 9\n"),
            "face 1 (line 5) refers to vertex 9, the mesh has 4 vertices",
        ),
        (
            "negative-out-of-range",
            format!("{tri}f 1 2 3\nf 1 -9 2\n"),
            "face 2 (line 6) refers to a vertex before the first one",
        ),
        (
            "two-vertices",
            format!("{tri}f 1 2 3\nf 2 3\n"),
            "face 2 (line 6) has 2 vertices",
        ),
        (
            "nan",
            "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n".into(),
            "vertex 2 (line 2) has a coordinate",
        ),
        (
            "inf",
            "v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n".into(),
            "vertex 3 (line 3) has a coordinate",
        ),
        ("empty", String::new(), "no faces"),
        ("only-vertices", tri.into(), "no faces"),
        ("syntax", format!("{tri}v 1 2 x\n"), "line 5"),
        ("syntax-face", format!("{tri}f 1 a 3\n"), "line 5"),
        ("zero-index", format!("{tri}f 0 1 2\n"), "line 5"),
        (
            "json-out-of-range",
            r#"{"kind": "mesh", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "faces": [[0,1,3]]}"#.into(),
            "face 0 refers to vertex 3",
        ),
        (
            "json-negative",
            r#"{"kind": "mesh", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "faces": [[0,-1,2]]}"#
                .into(),
            "face 0 refers to vertex -1",
        ),
        (
            "json-unknown-field",
            r#"{"kind": "mesh", "vertices": [], "faces": [], "colors": []}"#.into(),
            "unknown field `colors`",
        ),
        (
            "json-empty",
            r#"{"kind": "mesh", "vertices": [], "faces": []}"#.into(),
            "no faces",
        ),
        (
            "json-malformed",
            r#"{"kind": "mesh", "vertices": [[0,0"#.into(),
            "malformed JSON",
        ),
        (
            "json-polar",
            r#"{"kind": "polar", "pole": [0,0,0], "links": []}"#.into(),
            "surface needs a 'mesh' input",
        ),
    ];
    for (label, content, needle) in &cases {
        expect_failure(d, label, content.as_bytes(), &[], needle);
    }
    expect_failure(d, "not-utf8", b"v 0 0 0\n\xff\xfe\n", &[], "not UTF-8");
    // A pole too deep for the largest net: by default refused for its size
    // (2·4·32·(2^16 − 1) ≈ 1.7e7 C²PS patches) when the output is built
    // whole in memory (PNG); allowed that many, the evaluator's capacity
    // error (valence 32·2^16 = 2^21 beyond the library's limit).
    let globe = obj_text(&samples::globe(32, 7), Corners::Plain);
    expect_failure(
        d,
        "too-large",
        globe.as_bytes(),
        &["--depth", "16", "--format", "png"],
        "would have up to 167",
    );
    // Written as made (JSON), the default allows 5e7 patches: a valence-128
    // globe's 2·4·128·(2^16 − 1) ≈ 6.7e7 are refused.
    let big = obj_text(&samples::globe(128, 7), Corners::Plain);
    expect_failure(
        d,
        "too-large-streamed",
        big.as_bytes(),
        &["--depth", "16"],
        "patches, more than --max-patches 50000000",
    );
    let max = capdiv_mesh::evaluate::MAX_POLAR_VALENCE;
    assert!(32 << 16 > max);
    expect_failure(
        d,
        "capacity",
        globe.as_bytes(),
        &["--depth", "16", "--max-patches", "100000000"],
        &format!("at most {max} is supported"),
    );
    // Options.
    expect_failure(d, "depth", globe.as_bytes(), &["--depth", "17"], "--depth");
    expect_failure(d, "grid", globe.as_bytes(), &["--grid", "0"], "--grid");
    // f32 overflow of the input.
    expect_failure(
        d,
        "f32-range",
        "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n".as_bytes(),
        &["--precision", "f32"],
        "vertex 2 (line 2) has a coordinate that is not finite",
    );
}

#[test]
fn other_commands_refuse_a_mesh() {
    let dir = tempdir();
    let path = write_json(dir.path(), "m.json", &mesh_json(&samples::cube()));
    for cmd in [
        vec!["pole"],
        vec!["refine"],
        vec!["patches", "--depth", "1"],
    ] {
        let mut args = cmd.clone();
        args.push(s(&path));
        let run = capdiv(&args, None);
        assert_eq!(run.code, Some(2), "{cmd:?}");
        assert!(run.stdout.is_empty());
        assert_eq!(run.stderr.lines().count(), 1);
        assert!(
            run.stderr.contains("got kind 'mesh'") && run.stderr.contains("capdiv surface"),
            "{cmd:?}: {}",
            run.stderr
        );
    }
}

#[test]
fn random_bytes_never_panic() {
    let dir = tempdir();
    let mut rng = Lcg::new(7);
    let mut byte = || (rng.next() * 256.0) as u8;
    let alphabet = b"vf0123456789 -./\n#\\\r{}[]\",:eE+nai";
    for case in 0..300 {
        let len = 1 + (byte() as usize % 200);
        let bytes: Vec<u8> = if case % 2 == 0 {
            (0..len).map(|_| byte()).collect()
        } else {
            // OBJ- and JSON-like text: more likely to get far.
            (0..len)
                .map(|_| alphabet[byte() as usize % alphabet.len()])
                .collect()
        };
        let path = dir.path().join("r.in");
        std::fs::write(&path, &bytes).unwrap();
        let run = capdiv(&["surface", "--quiet", "--depth", "1", s(&path)], None);
        match run.code {
            Some(0) => assert!(run.stderr.is_empty()),
            Some(2) => {
                assert_eq!(run.stderr.lines().count(), 1, "{bytes:?}: {}", run.stderr);
                assert!(run.stdout.is_empty());
                assert!(
                    !run.stderr.contains("internal error"),
                    "{bytes:?}: {}",
                    run.stderr
                );
            }
            other => panic!("{bytes:?}: exit {other:?}, {}", run.stderr),
        }
    }
}

#[test]
fn valence_6_without_table_is_catmull_clark_and_eg_table_is_checked() {
    let dir = tempdir();
    let d = dir.path();
    let m = samples::extraordinary_disk(6, 3);
    let path = write(d, "ev6.obj", &obj_text(&m, Corners::Plain));
    let out = surface(&["--depth", "2"], s(&path), None);
    let caps = out["caps"].as_array().unwrap();
    assert_eq!(caps.len(), 1);
    assert_eq!(caps[0]["scheme"], "catmull-clark");
    assert_eq!(caps[0]["valence"], 6);
    assert_eq!(out["summary"]["patches"]["catmull-clark"], 3 * 6 * 2);

    // The spec's n = 5 table: valid, but for valence 5.
    let t5 = write_json(d, "t5.json", &table_json(5, SPEC_N5));
    let spec = format!("6={}", s(&t5));
    expect_failure(
        d,
        "table-wrong-valence",
        obj_text(&m, Corners::Plain).as_bytes(),
        &["--eg-table", &spec],
        "is for valence 5, --eg-table names valence 6",
    );
    let spec = format!("5={}", s(&t5));
    expect_failure(
        d,
        "table-n5",
        obj_text(&m, Corners::Plain).as_bytes(),
        &["--eg-table", &spec],
        "N in 6..10",
    );
    expect_failure(
        d,
        "table-syntax",
        obj_text(&m, Corners::Plain).as_bytes(),
        &["--eg-table", "six"],
        "N=FILE",
    );
    // The n = 5 rows relabelled as valence 6: refused by the kernel's checks,
    // named with the file.
    let t6 = write_json(d, "t6.json", &table_json(6, SPEC_N5));
    let spec = format!("6={}", s(&t6));
    expect_failure(
        d,
        "table-bad-n6",
        obj_text(&m, Corners::Plain).as_bytes(),
        &["--eg-table", &spec],
        "t6.json: rule table",
    );
    let missing = format!("7={}", s(&d.join("nope.json")));
    expect_failure(
        d,
        "table-missing",
        obj_text(&m, Corners::Plain).as_bytes(),
        &["--eg-table", &missing],
        "nope.json",
    );
}

#[test]
fn summary_goes_to_stderr_unless_quiet() {
    let dir = tempdir();
    let path = write(
        dir.path(),
        "c.obj",
        &obj_text(&samples::rounded_cube(2), Corners::Plain),
    );
    let run = capdiv(&["surface", "--depth", "2", s(&path)], None);
    assert_eq!(run.code, Some(0));
    let json = run.json();
    assert!(json["patches"].is_array());
    let err = &run.stderr;
    assert!(err.starts_with("capdiv surface: "), "{err}");
    for label in [
        "patches",
        "caps",
        "eg x8 n=3",
        "refinement",
        "uncovered",
        "time",
    ] {
        assert!(err.contains(label), "summary lacks {label}: {err}");
    }
    assert!(!err.contains("error"), "{err}");
    let quiet = capdiv(&["surface", "--quiet", "--depth", "2", s(&path)], None);
    quiet.assert_ok();
    // Pretty JSON is the same value.
    let pretty = surface(&["--depth", "2", "--pretty"], s(&path), None);
    assert_eq!(untimed(pretty), untimed(json));
}

/// Index of the input vertex nearest to `p`.
fn nearest(m: &MeshInput, p: [f64; 3]) -> usize {
    (0..m.vertices.len())
        .min_by(|&a, &b| diff(&m.vertices[a], &p).total_cmp(&diff(&m.vertices[b], &p)))
        .unwrap()
}

#[test]
fn domains_follow_the_parameter_conventions() {
    let dir = tempdir();
    // Quads: the corner b_00 of a whole-face patch sits near the face's first
    // vertex, b_d0 (u = 1) near the second, b_0d (v = 1) near the last.
    let m = samples::torus(12, 8);
    let path = write(dir.path(), "t.obj", &obj_text(&m, Corners::Plain));
    let out = surface(&["--depth", "1"], s(&path), None);
    for p in out["patches"].as_array().unwrap() {
        assert_eq!(p["domain"], json!([0.0, 1.0, 0.0, 1.0]));
        let f = &m.faces[p["face"].as_u64().unwrap() as usize];
        let pts = &p["points"];
        let at = |i: usize, j: usize| p3(&pts[4 * j + i]);
        assert_eq!(nearest(&m, at(0, 0)), f[0] as usize);
        assert_eq!(nearest(&m, at(3, 0)), f[1] as usize);
        assert_eq!(nearest(&m, at(3, 3)), f[2] as usize);
        assert_eq!(nearest(&m, at(0, 3)), f[3] as usize);
    }
    // Polar fan triangles: u from the pole (u = 0) to the 1-link (u = 1),
    // v from the first spoke (towards the vertex after the pole in the face)
    // to the second, counter-clockwise.
    let m = samples::globe(8, 9);
    let path = write(dir.path(), "g.obj", &obj_text(&m, Corners::Plain));
    let out = surface(&["--depth", "3"], s(&path), None);
    let caps = out["caps"].as_array().unwrap();
    let mut checked = 0;
    for p in out["patches"].as_array().unwrap() {
        let f = &m.faces[p["face"].as_u64().unwrap() as usize];
        if p["kind"] != "c2ps" || f.len() != 3 {
            continue;
        }
        let dom: Vec<f64> = p["domain"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let pole = caps
            .iter()
            .find(|c| f.contains(&(c["vertex"].as_u64().unwrap() as u32)))
            .unwrap();
        let k = f
            .iter()
            .position(|&v| u64::from(v) == pole["vertex"].as_u64().unwrap())
            .unwrap();
        let (first, second) = (f[(k + 1) % 3], f[(k + 2) % 3]);
        let limit = p3(&pole["limit"]);
        let pts = &p["points"];
        let at = |i: usize, j: usize| p3(&pts[4 * j + i]);
        // Farther along u is farther from the pole.
        assert!(diff(&at(3, 0), &limit) > diff(&at(0, 0), &limit));
        // The outermost patches at the spokes: v = 0 towards the first spoke's
        // link vertex, v = 1 towards the second's.
        if dom[1] == 1.0 && dom[2] == 0.0 {
            assert_eq!(nearest(&m, at(3, 0)), first as usize);
            checked += 1;
        }
        if dom[1] == 1.0 && dom[3] == 1.0 {
            assert_eq!(nearest(&m, at(3, 3)), second as usize);
            checked += 1;
        }
    }
    assert_eq!(checked, 2 * 2 * 8, "two spokes of 8 triangles at 2 poles");
}

/// An empty surface is an error, never a blank picture: every face a hole,
/// or the boundary rule `none` on a mesh whose faces all touch the boundary.
#[test]
fn an_empty_surface_is_an_error() {
    let dir = tempdir();
    let quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    expect_failure(
        dir.path(),
        "all-holes",
        format!("{quad}t hole 1/0/0 0\n").as_bytes(),
        &[],
        "empty",
    );
    expect_failure(
        dir.path(),
        "boundary-none",
        quad.as_bytes(),
        &["--boundary", "none"],
        "empty",
    );
    expect_failure(
        dir.path(),
        "boundary-none-png",
        quad.as_bytes(),
        &["--boundary", "none", "--format", "png"],
        "empty",
    );
    // The picture commands refuse it too: no blank PNG.
    let input = dir.path().join("all-holes.obj");
    std::fs::write(&input, format!("{quad}t hole 1/0/0 0\n")).unwrap();
    for command in ["render", "compare"] {
        let out = dir.path().join(format!("{command}.png"));
        let run = capdiv(&[command, "-o", s(&out), s(&input)], None);
        assert_eq!(run.code, Some(2), "{command}: {}", run.stderr);
        assert_eq!(run.stderr.lines().count(), 1, "{command}: {}", run.stderr);
        assert!(
            run.stderr
                .contains("no patch to draw: the surface is empty"),
            "{command}: {}",
            run.stderr
        );
        assert!(!out.exists(), "{command}: a picture was written");
    }
}

/// The summary says per level how many patches there are, and why a cap
/// fell back: an EG configuration with an infinitely sharp crease in it.
#[test]
fn summary_reports_levels_and_fallbacks() {
    let dir = tempdir();
    let m = capdiv_mesh::samples::two_beam_corner();
    let mut obj = String::new();
    for p in &m.vertices {
        obj.push_str(&format!("v {} {} {}\n", p[0], p[1], p[2]));
    }
    for f in &m.faces {
        let idx: Vec<String> = f.iter().map(|v| (v + 1).to_string()).collect();
        obj.push_str(&format!("f {}\n", idx.join(" ")));
    }
    // An infinitely sharp crease on an edge at an extraordinary point (0-based
    // vertex numbers; a semi-sharp one only holds the cap off until it has
    // decayed, one further away only until the cap's c-net is clear of it).
    let mut valence = vec![0; m.vertices.len()];
    for &v in m.faces.iter().flatten() {
        valence[v as usize] += 1;
    }
    let (v, w) = m
        .faces
        .iter()
        .find_map(|f| {
            let k = f.iter().position(|&v| valence[v as usize] != 4)?;
            Some((f[k], f[(k + 1) % f.len()]))
        })
        .unwrap();
    obj.push_str(&format!("t crease 2/1/0 {v} {w} 10.0\n"));
    let input = dir.path().join("beams.obj");
    std::fs::write(&input, obj).unwrap();
    let out = dir.path().join("beams.json");
    let run = capdiv(&["surface", "-o", s(&out), s(&input)], None);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(
        run.stderr.contains("patches per level 0: "),
        "{}",
        run.stderr
    );
    let json: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let levels = json["summary"]["patches_per_level"].as_array().unwrap();
    let total: u64 = levels.iter().map(|n| n.as_u64().unwrap()).sum();
    assert_eq!(total as usize, json["patches"].as_array().unwrap().len());
    assert!(levels.len() > 1, "adaptive levels below the input");
    let fallbacks = json["summary"]["fallbacks"].as_array().unwrap();
    assert!(
        fallbacks.iter().any(|f| f["reason"] == "feature"),
        "a cap fell back for the crease: {fallbacks:?}"
    );
    assert!(
        run.stderr.contains("fallback     Catmull-Clark at"),
        "{}",
        run.stderr
    );
}

/// `--max-patches` refuses, after the analysis and before making any
/// patch, a surface of more patches than allowed, saying how many it would
/// have: exactly the number the surface has without the limit.
#[test]
fn max_patches_refuses_a_larger_surface_and_says_its_size() {
    let dir = tempdir();
    let path = write(
        dir.path(),
        "cube.obj",
        &obj_text(&samples::cube(), Corners::Plain),
    );
    // Exact at a fixed depth (a tolerance may stop caps earlier: then the
    // count is an upper bound, tested in surface_tolerance.rs).
    let full = surface(&["--depth", "3", "--tolerance", "none"], s(&path), None);
    let n = full["patches"].as_array().unwrap().len();
    let at = capdiv(
        &[
            "surface",
            "--depth",
            "3",
            "--tolerance",
            "none",
            "--max-patches",
            &n.to_string(),
            s(&path),
        ],
        None,
    );
    assert_eq!(at.code, Some(0), "{}", at.stderr);
    let run = capdiv(
        &[
            "surface",
            "--depth",
            "3",
            "--tolerance",
            "none",
            "--max-patches",
            &(n - 1).to_string(),
            s(&path),
        ],
        None,
    );
    assert_eq!(run.code, Some(2));
    assert!(run.stdout.is_empty());
    assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    assert!(
        run.stderr.contains(&format!("would have {n} patches")),
        "{}",
        run.stderr
    );
}
