//! `capdiv surface` with texture coordinates: an OBJ with `vt` and `f v/vt`
//! (a checkerboard-textured torus whose UVs wrap at two seams, and a cube
//! on a 3×2 atlas with EG caps at its corners) gives an OBJ with `vt`, a glb
//! with `TEXCOORD_0` holding the same UVs, and JSON patches with their UV
//! corners; malformed texture data exit with status 2 and one line naming
//! the offending line.

mod common;

use common::*;
use serde_json::Value;
use std::path::Path;

const NU: usize = 8;
const NV: usize = 6;

/// A torus OBJ, `NU × NV` quads; with `uv`, corner `(i, j)` has `vt i/NU
/// j/NV` with `i = NU`, `j = NV` kept apart from 0 (the seams). Also returns
/// each face's corner UVs.
fn torus(uv: bool) -> (String, Vec<[[f64; 2]; 4]>) {
    let mut t = String::from("# checker torus\n");
    for i in 0..NU {
        let a = std::f64::consts::TAU * i as f64 / NU as f64;
        for j in 0..NV {
            let b = std::f64::consts::TAU * j as f64 / NV as f64;
            let r = 1.0 + 0.35 * b.cos();
            t += &format!("v {} {} {}\n", r * a.cos(), r * a.sin(), 0.35 * b.sin());
        }
    }
    if uv {
        for i in 0..=NU {
            for j in 0..=NV {
                t += &format!("vt {} {}\n", i as f64 / NU as f64, j as f64 / NV as f64);
            }
        }
    }
    let v = |i: usize, j: usize| (i % NU) * NV + j % NV + 1;
    let vt = |i: usize, j: usize| i * (NV + 1) + j + 1;
    let mut uvs = Vec::new();
    for i in 0..NU {
        for j in 0..NV {
            let c = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
            t.push('f');
            for (a, b) in c {
                if uv {
                    t += &format!(" {}/{}", v(a, b), vt(a, b));
                } else {
                    t += &format!(" {}", v(a, b));
                }
            }
            t.push('\n');
            uvs.push(c.map(|(a, b)| [a as f64 / NU as f64, b as f64 / NV as f64]));
        }
    }
    (t, uvs)
}

/// The cube on a 3×2 atlas, corners written `v/vt/vn`.
fn atlas_cube() -> (String, Vec<[[f64; 2]; 4]>) {
    let mut t = String::from("vn 0 0 1\n");
    for p in [
        [0, 0, 0],
        [1, 0, 0],
        [1, 1, 0],
        [0, 1, 0],
        [0, 0, 1],
        [1, 0, 1],
        [1, 1, 1],
        [0, 1, 1],
    ] {
        t += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    let faces = [
        [1, 4, 3, 2],
        [5, 6, 7, 8],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 4, 8, 7],
        [4, 1, 5, 8],
    ];
    let mut uvs = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        let (x, y) = ((f % 3) as f64, (f / 3) as f64);
        let c = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
            .map(|c| [(x + c[0]) / 3.0, (y + c[1]) / 2.0]);
        for q in c {
            t += &format!("vt {} {}\n", q[0], q[1]);
        }
        t.push('f');
        for (k, v) in face.iter().enumerate() {
            t += &format!(" {v}/{}/1", 4 * f + k + 1);
        }
        t.push('\n');
        uvs.push(c);
    }
    (t, uvs)
}

fn run(dir: &Path, name: &str, text: &str, format: &str) -> (Vec<u8>, String) {
    let input = dir.join(name);
    std::fs::write(&input, text).unwrap();
    let out = dir.join(format!("{name}.out.{format}"));
    let r = capdiv(
        &[
            "surface",
            "--depth",
            "3",
            "--grid",
            "3",
            "--format",
            format,
            "-o",
            s(&out),
            s(&input),
        ],
        None,
    );
    assert_eq!(r.code, Some(0), "stderr: {}", r.stderr);
    (std::fs::read(&out).unwrap(), r.stderr)
}

/// The OBJ the CLI writes: `v`, `vt` and faces of vertex indices (checking
/// that every corner is `i/i/i` or `i//i`).
struct Obj {
    v: Vec<[f64; 3]>,
    vt: Vec<[f64; 2]>,
    f: Vec<Vec<usize>>,
}

fn parse_obj(bytes: &[u8]) -> Obj {
    let text = std::str::from_utf8(bytes).unwrap();
    let mut o = Obj {
        v: vec![],
        vt: vec![],
        f: vec![],
    };
    for line in text.lines() {
        let mut w = line.split_whitespace();
        let nums =
            |w: std::str::SplitWhitespace| -> Vec<f64> { w.map(|x| x.parse().unwrap()).collect() };
        match w.next() {
            Some("v") => {
                let x = nums(w);
                o.v.push([x[0], x[1], x[2]]);
            }
            Some("vt") => {
                let x = nums(w);
                assert_eq!(x.len(), 2, "{line}");
                o.vt.push([x[0], x[1]]);
            }
            Some("f") => o.f.push(
                w.map(|c| {
                    let parts: Vec<&str> = c.split('/').collect();
                    assert_eq!(parts.len(), 3, "{line}");
                    assert!(parts[1].is_empty() || parts[1] == parts[0], "{line}");
                    assert_eq!(parts[2], parts[0], "{line}");
                    parts[0].parse::<usize>().unwrap() - 1
                })
                .collect(),
            ),
            _ => {}
        }
    }
    o
}

#[test]
fn obj_with_vt_gives_obj_with_vt_split_only_at_the_seams() {
    let dir = tempdir();
    let (with, _) = torus(true);
    let (without, _) = torus(false);
    let (out, report) = run(dir.path(), "t.obj", &with, "obj");
    let (plain, _) = run(dir.path(), "p.obj", &without, "obj");
    let (o, p) = (parse_obj(&out), parse_obj(&plain));
    assert_eq!(o.vt.len(), o.v.len());
    assert!(p.vt.is_empty());
    assert_eq!(o.f.len(), p.f.len());
    // The same surface: its distinct positions are the plain output's
    // vertices (welding is by position; only seams split).
    let key = |q: &[f64; 3]| q.map(f64::to_bits);
    let distinct: std::collections::BTreeSet<_> = o.v.iter().map(key).collect();
    assert_eq!(distinct.len(), p.v.len());
    assert!(o.v.len() > p.v.len());
    let plain_set: std::collections::BTreeSet<_> = p.v.iter().map(key).collect();
    assert_eq!(distinct, plain_set);
    // Seams split vertices, the surface stays closed through them.
    assert!(
        report.contains("closed and consistently oriented"),
        "{report}"
    );
    // No face straddles a seam: each spans at most one checker square.
    for f in &o.f {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for &i in f {
            for d in 0..2 {
                lo[d] = lo[d].min(o.vt[i][d]);
                hi[d] = hi[d].max(o.vt[i][d]);
            }
        }
        assert!(hi[0] - lo[0] <= 1.0 / NU as f64 + 1e-12, "{lo:?} {hi:?}");
        assert!(hi[1] - lo[1] <= 1.0 / NV as f64 + 1e-12, "{lo:?} {hi:?}");
    }
}

fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

/// The first primitive's attribute `name` as `width` f32 per vertex.
fn attribute(glb: &[u8], name: &str, width: usize) -> Vec<Vec<f32>> {
    assert_eq!(&glb[0..4], b"glTF");
    let json_len = u32_at(glb, 12) as usize;
    let doc: Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
    let bin = &glb[20 + json_len + 8..];
    let a = doc["meshes"][0]["primitives"][0]["attributes"][name]
        .as_u64()
        .unwrap_or_else(|| panic!("no {name}")) as usize;
    let acc = &doc["accessors"][a];
    assert_eq!(acc["componentType"], 5126);
    let view = &doc["bufferViews"][acc["bufferView"].as_u64().unwrap() as usize];
    let off = view["byteOffset"].as_u64().unwrap_or(0) as usize;
    let count = acc["count"].as_u64().unwrap() as usize;
    (0..count)
        .map(|k| {
            (0..width)
                .map(|c| {
                    f32::from_le_bytes(bin[off + 4 * (width * k + c)..][..4].try_into().unwrap())
                })
                .collect()
        })
        .collect()
}

#[test]
fn glb_texcoord_0_holds_the_objs_uvs_with_v_flipped() {
    let dir = tempdir();
    for (name, text) in [("torus.obj", torus(true).0), ("cube.obj", atlas_cube().0)] {
        let (obj, _) = run(dir.path(), name, &text, "obj");
        let (glb, _) = run(dir.path(), name, &text, "glb");
        let o = parse_obj(&obj);
        let pos = attribute(&glb, "POSITION", 3);
        let tex = attribute(&glb, "TEXCOORD_0", 2);
        assert_eq!(tex.len(), pos.len());
        assert_eq!(pos.len(), o.v.len(), "{name}");
        // As sets of (position, UV) pairs in f32 (the glb's precision): the
        // glb renumbers vertices, nothing else. glTF's v runs down the
        // image: (u, 1 − v).
        let mut from_obj: Vec<[u32; 5]> =
            o.v.iter()
                .zip(&o.vt)
                .map(|(p, t)| {
                    let q = [p[0], p[1], p[2], t[0], 1.0 - t[1]];
                    q.map(|x| (x as f32).to_bits())
                })
                .collect();
        let mut from_glb: Vec<[u32; 5]> = pos
            .iter()
            .zip(&tex)
            .map(|(p, t)| [p[0], p[1], p[2], t[0], t[1]].map(f32::to_bits))
            .collect();
        from_obj.sort();
        from_glb.sort();
        assert_eq!(from_obj, from_glb, "{name}");
    }
    // Without UVs: no TEXCOORD_0.
    let (glb, _) = run(dir.path(), "plain.obj", &torus(false).0, "glb");
    let json_len = u32_at(&glb, 12) as usize;
    let doc: Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
    assert!(doc["meshes"][0]["primitives"][0]["attributes"]
        .get("TEXCOORD_0")
        .is_none());
}

#[test]
fn json_patches_carry_the_bilinear_uvs_of_their_face_at_their_corners() {
    let dir = tempdir();
    for (name, (text, uvs)) in [("torus.obj", torus(true)), ("cube.obj", atlas_cube())] {
        let (json, _) = run(dir.path(), name, &text, "json");
        let v: Value = serde_json::from_slice(&json).unwrap();
        let patches = v["patches"].as_array().unwrap();
        assert!(!patches.is_empty());
        for p in patches {
            let c = &uvs[p["face"].as_u64().unwrap() as usize];
            let d: Vec<f64> = p["domain"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            let uv = p["uv"].as_array().expect("uv on every patch");
            for (k, (s, t)) in [(d[0], d[2]), (d[1], d[2]), (d[1], d[3]), (d[0], d[3])]
                .into_iter()
                .enumerate()
            {
                for dim in 0..2 {
                    let want = (1.0 - s) * (1.0 - t) * c[0][dim]
                        + s * (1.0 - t) * c[1][dim]
                        + s * t * c[2][dim]
                        + (1.0 - s) * t * c[3][dim];
                    let got = uv[k][dim].as_f64().unwrap();
                    // Same products, summed in a possibly different order.
                    assert!((got - want).abs() < 1e-15, "{name}: {p}");
                }
            }
        }
    }
    let (json, _) = run(dir.path(), "plain.obj", &torus(false).0, "json");
    assert!(!String::from_utf8(json).unwrap().contains("\"uv\""));
}

#[test]
fn malformed_texture_data_exit_2_with_one_line_naming_the_line() {
    let dir = tempdir();
    let head = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
    for (body, needle) in [
        ("vt 0 zz\nf 1/1 2/1 3/1 4/1\n", "line 5"),
        ("vt\nf 1/1 2/1 3/1 4/1\n", "line 5"),
        ("vt 0 0\nf 1/1 2/1 3/1\nf 1 3 4\n", "line 7"),
        ("vt 0 0\nf 1/1 2 3/1\n", "line 6"),
        ("vt 0 0\nf 1/1 2/1 3/2\n", "line 6"),
        ("vt 0 0\nf 1/1 2/1 3/0\n", "line 6"),
    ] {
        let path = dir.path().join("bad.obj");
        std::fs::write(&path, format!("{head}{body}")).unwrap();
        let r = capdiv(&["surface", s(&path)], None);
        assert_eq!(r.code, Some(2), "{body}: {}", r.stderr);
        assert_eq!(r.stderr.lines().count(), 1, "{body}: {}", r.stderr);
        assert!(r.stderr.contains(needle), "{body}: {}", r.stderr);
        assert!(r.stdout.is_empty());
    }
    // JSON: a face's UV list must match its corners.
    let bad = serde_json::json!({
        "kind": "mesh",
        "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0]],
        "faces": [[0, 1, 2]],
        "uvs": [[[0, 0], [1, 0]]]
    });
    let path = write_json(dir.path(), "bad.json", &bad);
    let r = capdiv(&["surface", s(&path)], None);
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert_eq!(r.stderr.lines().count(), 1);
    assert!(
        r.stderr
            .contains("face 0 has 2 texture coordinates for 3 vertices"),
        "{}",
        r.stderr
    );
}

#[test]
fn json_mesh_uvs_give_the_same_surface_uvs_as_obj_vt() {
    let dir = tempdir();
    let (text, uvs) = torus(true);
    let (from_obj, _) = run(dir.path(), "t.obj", &text, "json");
    // The same mesh as JSON, UVs per face corner.
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.first() {
            Some(&"v") => vertices.push(
                w[1..]
                    .iter()
                    .map(|x| x.parse::<f64>().unwrap())
                    .collect::<Vec<_>>(),
            ),
            Some(&"f") => faces.push(
                w[1..]
                    .iter()
                    .map(|c| c.split('/').next().unwrap().parse::<i64>().unwrap() - 1)
                    .collect::<Vec<_>>(),
            ),
            _ => {}
        }
    }
    let mesh =
        serde_json::json!({"kind": "mesh", "vertices": vertices, "faces": faces, "uvs": uvs});
    let path = write_json(dir.path(), "t.json", &mesh);
    let out = dir.path().join("t.json.out");
    let r = capdiv(
        &[
            "surface",
            "--depth",
            "3",
            "--format",
            "json",
            "-o",
            s(&out),
            s(&path),
        ],
        None,
    );
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    let a: Value = serde_json::from_slice(&from_obj).unwrap();
    let b: Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(a["patches"], b["patches"]);
}
