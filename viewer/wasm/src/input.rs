//! A file the user drops on the page, to a mesh: Wavefront OBJ (read by
//! [`capdiv_mesh::obj::parse_obj`]) or JSON in the CLI's formats
//! (`docs/cli.md`): `{"kind": "mesh", "vertices", "faces"}`, or
//! `{"kind": "polar", "pole", "links"}` shown as the open disk it spans (a fan
//! of triangles from the pole to link 1, quads between consecutive links).
//! Anything else is an error with a one-line message for the page; nothing
//! here panics on any text.

use capdiv_mesh::obj::{looks_like_json, parse_obj};
use capdiv_mesh::{MeshError, MeshInput};
use serde::Deserialize;

/// Largest mesh the viewer accepts (faces), so a huge file cannot freeze the
/// page; the CLI has no such limit.
pub const MAX_FACES: usize = 100_000;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MeshJson {
    #[allow(dead_code)]
    kind: String,
    vertices: Vec<[f64; 3]>,
    faces: Vec<Vec<i64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PolarJson {
    #[allow(dead_code)]
    kind: String,
    pole: [f64; 3],
    links: Vec<Vec<[f64; 3]>>,
}

#[derive(Deserialize)]
struct Kind {
    kind: Option<String>,
}

/// Reads a dropped file's text. `Err` is the message the page shows.
pub fn parse(text: &str) -> Result<MeshInput, String> {
    let mesh = if looks_like_json(text) {
        parse_json(text.trim_start_matches('\u{feff}'))?
    } else {
        parse_obj(text).map_err(|e| format!("OBJ: {e}"))?
    };
    if mesh.faces.is_empty() {
        return Err("the file has no faces".into());
    }
    if mesh.faces.len() > MAX_FACES {
        return Err(format!(
            "{} faces: the viewer takes at most {MAX_FACES} (use `capdiv surface`)",
            mesh.faces.len()
        ));
    }
    Ok(mesh)
}

fn parse_json(text: &str) -> Result<MeshInput, String> {
    let json = |e: serde_json::Error| format!("JSON: {e}");
    let kind: Kind = serde_json::from_str(text).map_err(json)?;
    match kind.kind.as_deref() {
        Some("mesh") => {
            let m: MeshJson = serde_json::from_str(text).map_err(json)?;
            mesh_of_json(m.vertices, &m.faces).map_err(|e| format!("mesh: {e}"))
        }
        Some("polar") => {
            let p: PolarJson = serde_json::from_str(text).map_err(json)?;
            polar_disk(p.pole, &p.links)
        }
        Some(k @ ("cnet" | "dnet")) => Err(format!(
            "a {k} is a single cap, not a mesh: the viewer shows meshes and polar nets (use `capdiv eg`)"
        )),
        Some(k) => Err(format!(
            "unknown kind {k:?}: the viewer reads \"mesh\" and \"polar\" JSON, or OBJ"
        )),
        None => Err("JSON without a \"kind\": expected {\"kind\": \"mesh\", ...}".into()),
    }
}

/// Faces as 0-based indices; an index outside the vertices is
/// [`MeshError::IndexOutOfRange`] (first offending face).
fn mesh_of_json(vertices: Vec<[f64; 3]>, faces: &[Vec<i64>]) -> Result<MeshInput, MeshError> {
    let nv = vertices.len();
    let mut out = Vec::with_capacity(faces.len());
    for (face, list) in faces.iter().enumerate() {
        let mut f = Vec::with_capacity(list.len());
        for &index in list {
            if index < 0 || index as u64 >= nv as u64 || index > i64::from(u32::MAX) {
                return Err(MeshError::IndexOutOfRange {
                    face,
                    index,
                    vertices: nv,
                });
            }
            f.push(index as u32);
        }
        out.push(f);
    }
    Ok(MeshInput::new(vertices, out))
}

/// The open disk of a polar configuration ([`MeshInput::polar_disk`]),
/// after checking its shape (at least 2 links of one length `n ≥ 3`).
pub fn polar_disk(pole: [f64; 3], links: &[Vec<[f64; 3]>]) -> Result<MeshInput, String> {
    let n = links.first().map_or(0, Vec::len);
    if links.len() < 2 {
        return Err("polar: at least 2 links are needed".into());
    }
    if n < 3 {
        return Err(format!("polar: valence {n}, at least 3 is needed"));
    }
    if let Some(k) = links.iter().position(|l| l.len() != n) {
        return Err(format!(
            "polar: link {} has {} points, link 1 has {n}",
            k + 1,
            links[k].len()
        ));
    }
    Ok(MeshInput::polar_disk(pole, links))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn obj_and_json_give_the_same_mesh() {
        let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
        let json = r#"{"kind": "mesh", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "faces": [[0,1,2,3]]}"#;
        let a = parse(obj).unwrap();
        let b = parse(json).unwrap();
        assert_eq!(a, b);
        assert_eq!(a.faces, vec![vec![0, 1, 2, 3]]);
    }

    #[test]
    fn broken_files_are_messages() {
        let cases = [
            ("", "no faces"),
            ("{", "JSON"),
            (
                "{\"kind\": \"mesh\", \"vertices\": [[0,0,0]], \"faces\": [[0,1,2]]}",
                "mesh",
            ),
            ("{\"kind\": \"cnet\"}", "cnet"),
            ("{\"kind\": \"teapot\"}", "unknown kind"),
            ("{\"vertices\": []}", "kind"),
            ("v 0 0 0\nf 1 2 3\n", "OBJ"),
            ("v 0 zero 0\n", "OBJ"),
            ("\u{0}\u{1}binary\u{ff}", "no faces"),
        ];
        for (text, needle) in cases {
            let e = parse(text).expect_err(text);
            assert!(e.contains(needle), "{text:?}: {e}");
            assert!(!e.contains('\n'), "one line: {e}");
        }
    }

    #[test]
    fn polar_json_is_a_disk_of_fan_and_quads() {
        let ring = |r: f64| -> Vec<[f64; 3]> {
            (0..6)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / 6.0;
                    [r * t.cos(), r * t.sin(), 0.0]
                })
                .collect()
        };
        let links: Vec<_> = (1..=4).map(|k| ring(k as f64)).collect();
        let text = serde_json::json!({"kind": "polar", "pole": [0.0, 0.0, 0.0], "links": links})
            .to_string();
        let m = parse(&text).unwrap();
        assert_eq!(m.vertices.len(), 1 + 4 * 6);
        assert_eq!(m.faces.iter().filter(|f| f.len() == 3).count(), 6);
        assert_eq!(m.faces.iter().filter(|f| f.len() == 4).count(), 3 * 6);
        // Counter-clockwise about +z like the links: positive signed area.
        for f in &m.faces {
            let p: Vec<[f64; 3]> = f.iter().map(|&i| m.vertices[i as usize]).collect();
            let area: f64 = (0..p.len())
                .map(|i| {
                    let (a, b) = (p[i], p[(i + 1) % p.len()]);
                    a[0] * b[1] - a[1] * b[0]
                })
                .sum();
            assert!(area > 0.0, "{f:?}");
        }
        assert!(polar_disk([0.0; 3], &links[..1]).is_err());
        assert!(polar_disk([0.0; 3], &[ring(1.0), ring(2.0)[..5].to_vec()]).is_err());
    }
}
