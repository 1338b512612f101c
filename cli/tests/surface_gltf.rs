//! `capdiv surface --format glb|gltf`: the container (glTF 2.0 §4.4: header,
//! JSON chunk, BIN chunk), the document's buffers, views and accessors, and
//! the mesh against the OBJ output of the same surface (same vertices, same
//! faces, quads as two triangles). The validator and three.js run in
//! `scripts/ci-exchange.sh`.

mod common;

use base64::Engine;
use common::*;
use serde_json::Value;
use std::path::Path;

/// The cube as an OBJ, in one object or two (the second moved along x).
fn cubes(objects: usize) -> String {
    let mut t = String::new();
    for k in 0..objects {
        t += &format!("o cube_{k}\n");
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
            t += &format!("v {} {} {}\n", p[0] + 2 * k as i32, p[1], p[2]);
        }
        let o = 8 * k;
        for f in [
            [1, 4, 3, 2],
            [5, 6, 7, 8],
            [1, 2, 6, 5],
            [2, 3, 7, 6],
            [3, 4, 8, 7],
            [4, 1, 5, 8],
        ] {
            t += &format!("f {} {} {} {}\n", f[0] + o, f[1] + o, f[2] + o, f[3] + o);
        }
    }
    t
}

fn run(dir: &Path, input: &Path, format: &str) -> (Vec<u8>, String) {
    let out = dir.join(format!("out.{format}"));
    let r = capdiv(
        &[
            "surface",
            "--depth",
            "3",
            "--grid",
            "2",
            "--format",
            format,
            "-o",
            s(&out),
            s(input),
        ],
        None,
    );
    assert_eq!(r.code, Some(0), "stderr: {}", r.stderr);
    (std::fs::read(&out).unwrap(), r.stderr)
}

fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

/// JSON and BIN of a GLB, checking the container's lengths and padding.
fn split_glb(b: &[u8]) -> (Value, Vec<u8>) {
    assert_eq!(&b[0..4], b"glTF");
    assert_eq!(u32_at(b, 4), 2);
    assert_eq!(u32_at(b, 8) as usize, b.len());
    let json_len = u32_at(b, 12) as usize;
    assert_eq!(&b[16..20], b"JSON");
    assert_eq!(json_len % 4, 0);
    let json: Value = serde_json::from_slice(&b[20..20 + json_len]).unwrap();
    let at = 20 + json_len;
    let bin_len = u32_at(b, at) as usize;
    assert_eq!(&b[at + 4..at + 8], b"BIN\0");
    assert_eq!(bin_len % 4, 0);
    assert_eq!(at + 8 + bin_len, b.len());
    (json, b[at + 8..].to_vec())
}

/// An accessor's data: `count` items of `width` little-endian 4-byte words.
fn words(doc: &Value, bin: &[u8], accessor: usize, width: usize) -> Vec<[u8; 4]> {
    let a = &doc["accessors"][accessor];
    let v = &doc["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
    let off = v["byteOffset"].as_u64().unwrap_or(0) as usize;
    let len = v["byteLength"].as_u64().unwrap() as usize;
    let count = a["count"].as_u64().unwrap() as usize;
    assert_eq!(len, count * width * 4, "view length of accessor {accessor}");
    assert!(off + len <= bin.len());
    bin[off..off + len]
        .chunks_exact(4)
        .map(|c| c.try_into().unwrap())
        .collect()
}

/// Per node: (name, positions, triangles).
type Node = (Option<String>, Vec<[f32; 3]>, Vec<[u32; 3]>);

fn nodes(doc: &Value, bin: &[u8]) -> Vec<Node> {
    assert_eq!(doc["asset"]["version"], "2.0");
    assert_eq!(
        doc["buffers"][0]["byteLength"].as_u64().unwrap() as usize,
        bin.len()
    );
    let scene = &doc["scenes"][doc["scene"].as_u64().unwrap() as usize];
    let mut out = Vec::new();
    for n in scene["nodes"].as_array().unwrap() {
        let node = &doc["nodes"][n.as_u64().unwrap() as usize];
        let mesh = &doc["meshes"][node["mesh"].as_u64().unwrap() as usize];
        let prims = mesh["primitives"].as_array().unwrap();
        assert_eq!(prims.len(), 1);
        let p = &prims[0];
        assert_eq!(p.get("mode").and_then(Value::as_u64).unwrap_or(4), 4);
        let attr = |k: &str| p["attributes"][k].as_u64().unwrap() as usize;
        let f = |w: &[u8; 4]| f32::from_le_bytes(*w);
        let pos: Vec<[f32; 3]> = words(doc, bin, attr("POSITION"), 3)
            .chunks_exact(3)
            .map(|c| [f(&c[0]), f(&c[1]), f(&c[2])])
            .collect();
        let nrm: Vec<[f32; 3]> = words(doc, bin, attr("NORMAL"), 3)
            .chunks_exact(3)
            .map(|c| [f(&c[0]), f(&c[1]), f(&c[2])])
            .collect();
        assert_eq!(nrm.len(), pos.len());
        for n in &nrm {
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            // f32 rounding of a unit vector: well within the validator's 4e-4.
            assert!((len - 1.0).abs() < 1e-6, "normal length {len}");
        }
        // POSITION's min and max are the data's.
        let acc = &doc["accessors"][attr("POSITION")];
        for k in 0..3 {
            let lo = pos.iter().map(|q| q[k]).fold(f32::INFINITY, f32::min);
            let hi = pos.iter().map(|q| q[k]).fold(f32::NEG_INFINITY, f32::max);
            assert_eq!(acc["min"][k].as_f64().unwrap() as f32, lo);
            assert_eq!(acc["max"][k].as_f64().unwrap() as f32, hi);
        }
        let idx: Vec<u32> = words(doc, bin, p["indices"].as_u64().unwrap() as usize, 1)
            .iter()
            .map(|w| u32::from_le_bytes(*w))
            .collect();
        assert_eq!(
            doc["accessors"][p["indices"].as_u64().unwrap() as usize]["componentType"],
            5125
        );
        assert_eq!(idx.len() % 3, 0);
        assert!(idx.iter().all(|&i| (i as usize) < pos.len()));
        // Every vertex is used.
        let mut used = vec![false; pos.len()];
        for &i in &idx {
            used[i as usize] = true;
        }
        assert!(used.iter().all(|&u| u));
        let tris = idx.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        out.push((node["name"].as_str().map(String::from), pos, tris));
    }
    out
}

#[test]
fn glb_and_gltf_hold_the_obj_surface_with_quads_as_two_triangles() {
    let dir = tempdir();
    let input = dir.path().join("cube.obj");
    std::fs::write(&input, cubes(1)).unwrap();
    let (glb, report) = run(dir.path(), &input, "glb");
    let (doc, bin) = split_glb(&glb);
    let got = nodes(&doc, &bin);
    assert_eq!(got.len(), 1);
    let (name, pos, tris) = &got[0];
    assert_eq!(name.as_deref(), Some("cube_0"));

    // The OBJ of the same surface: same vertices (f32-rounded) and faces.
    let (obj, _) = run(dir.path(), &input, "obj");
    let obj = parse_obj(std::str::from_utf8(&obj).unwrap());
    let quads = obj.f.iter().filter(|f| f.len() == 4).count();
    let triangles = obj.f.len() - quads;
    assert_eq!(tris.len(), triangles + 2 * quads);
    assert_eq!(pos.len(), obj.v.len());
    assert!(quads > 0 && triangles > 0);
    // Vertices renumber in order of first use along the faces, quads split
    // (a, b, c), (a, c, d): the OBJ's faces so renumbered are the triangles.
    let mut local = vec![u32::MAX; obj.v.len()];
    let mut order = Vec::new();
    let mut expect = Vec::new();
    for f in &obj.f {
        let c: Vec<usize> = f.iter().map(|&(v, _)| v - 1).collect(); // 1-based
        let split: &[[usize; 3]] = if c.len() == 4 {
            &[[0, 1, 2], [0, 2, 3]]
        } else {
            &[[0, 1, 2]]
        };
        for t in split {
            expect.push(t.map(|k| {
                if local[c[k]] == u32::MAX {
                    local[c[k]] = order.len() as u32;
                    order.push(c[k]);
                }
                local[c[k]]
            }));
        }
    }
    assert_eq!(tris, &expect);
    for (q, &v) in pos.iter().zip(&order) {
        // The OBJ prints f64 in shortest round-trip form.
        assert_eq!(*q, obj.v[v].map(|x| x as f32));
    }
    assert!(report.contains(&format!(
        "gltf         1 node, {} vertices, {} triangles",
        pos.len(),
        tris.len()
    )));

    // The embedded form: the same document, the buffer as a data URI.
    let (gltf, _) = run(dir.path(), &input, "gltf");
    let text: Value = serde_json::from_slice(&gltf).unwrap();
    let uri = text["buffers"][0]["uri"].as_str().unwrap();
    let data = uri
        .strip_prefix("data:application/octet-stream;base64,")
        .unwrap();
    let decoded = base64::engine::general_purpose::STANDARD
        .decode(data)
        .unwrap();
    assert_eq!(decoded, bin);
    let mut without_uri = text.clone();
    without_uri["buffers"][0]
        .as_object_mut()
        .unwrap()
        .remove("uri");
    assert_eq!(without_uri, doc);
}

#[test]
fn each_obj_object_is_a_node() {
    let dir = tempdir();
    let input = dir.path().join("cubes.obj");
    std::fs::write(&input, cubes(2)).unwrap();
    let (glb, _) = run(dir.path(), &input, "glb");
    let (doc, bin) = split_glb(&glb);
    let got = nodes(&doc, &bin);
    let names: Vec<_> = got.iter().map(|n| n.0.clone().unwrap()).collect();
    assert_eq!(names, ["cube_0", "cube_1"]);
    // The two cubes are the same surface, the second moved by 2 along x.
    assert_eq!(got[0].2, got[1].2);
    for (a, b) in got[0].1.iter().zip(&got[1].1) {
        // f32 rounding of coordinates below 3: 2.4e-7.
        assert!((b[0] - (a[0] + 2.0)).abs() < 5e-7);
        assert!((a[1] - b[1]).abs() < 5e-7 && (a[2] - b[2]).abs() < 5e-7);
    }
    assert!(got[0].1.iter().all(|p| p[0] <= 1.0));
}
