//! glTF 2.0 (Khronos, *glTF 2.0 Specification*) of a welded tessellation:
//! one node per group (an OBJ object, or the whole surface), each with a mesh
//! of one indexed triangle primitive (§3.7.2, mode 4 `TRIANGLES`) carrying
//! `POSITION` and `NORMAL` (`FLOAT` `VEC3`, §3.7.2.1), `TEXCOORD_0`
//! (`FLOAT` `VEC2`) when the tessellation has UVs, and `UNSIGNED_INT`
//! indices; one material (§3.9, not metallic) shared by all.
//! glTF's UV origin is the image's top-left corner, OBJ's (and the input's)
//! its bottom-left: a UV `(u, v)` is written `(u, 1 − v)`.
//!
//! Each group's vertices are the tessellation's vertices its faces use,
//! renumbered in order of first use (a vertex shared by two groups appears in
//! both). Quads become two triangles `(a, b, c)`, `(a, c, d)`; orientation is
//! kept (counter-clockwise about the normals, §3.7.2.1 "front face").
//! Positions and normals are rounded to `f32`; normals are renormalised
//! after rounding (the attribute must be unit length), and a vertex with no
//! normal gets its faces' area-weighted normal (or `+z` if that is zero too).
//!
//! The document is built with the schema types of `gltf::json`; [`glb`] packs
//! it in the binary container (§4.4, `gltf::binary::Glb`), [`gltf_text`]
//! writes it as JSON with the buffer embedded as a base64 `data:` URI (§3.6.1).

use base64::Engine;
use capdiv::{Point3, Real};
use capdiv_mesh::tessellate::{Face, Tessellation};
use gltf::json;
use json::validation::{Checked::Valid, USize64};
use std::borrow::Cow;
use std::collections::BTreeMap;

/// Faces of the tessellation that make one node.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Group {
    /// The node's name (`None`: unnamed).
    pub name: Option<String>,
    /// Indices into [`Tessellation::faces`].
    pub faces: Vec<usize>,
}

/// A glTF document and its binary buffer, with what it holds.
#[derive(Clone, Debug)]
pub struct Document {
    /// The JSON part (`buffers[0]` has no URI yet).
    pub root: json::Root,
    /// The buffer's bytes.
    pub bin: Vec<u8>,
    /// Vertices over all nodes.
    pub vertices: usize,
    /// Triangles over all nodes.
    pub triangles: usize,
    /// Nodes (groups with at least one face).
    pub nodes: usize,
}

/// The document of `t` with one node per group (empty groups are left out).
pub fn document<R: Real>(t: &Tessellation<R>, groups: &[Group]) -> Document {
    let mut root = json::Root {
        asset: json::Asset {
            generator: Some("capdiv surface".into()),
            ..Default::default()
        },
        ..Default::default()
    };
    let buffer = root.push(json::Buffer {
        byte_length: USize64(0),
        name: None,
        uri: None,
        extensions: None,
        extras: Default::default(),
    });
    let material = root.push(json::Material {
        name: Some("surface".into()),
        pbr_metallic_roughness: json::material::PbrMetallicRoughness {
            base_color_factor: json::material::PbrBaseColorFactor([0.8, 0.8, 0.85, 1.0]),
            metallic_factor: json::material::StrengthFactor(0.0),
            roughness_factor: json::material::StrengthFactor(0.5),
            ..Default::default()
        },
        ..Default::default()
    });
    let mut bin = Vec::new();
    let mut nodes = Vec::new();
    let (mut vertices, mut triangles) = (0, 0);
    for g in groups {
        let part = Part::of(t, &g.faces);
        if part.indices.is_empty() {
            continue;
        }
        vertices += part.positions.len();
        triangles += part.indices.len() / 3;
        let (min, max) = bounds(&part.positions);
        use json::accessor::Type::{Vec2, Vec3};
        let position = push_attribute(&mut root, &mut bin, buffer, &part.positions, Vec3, min, max);
        let normal = push_attribute(&mut root, &mut bin, buffer, &part.normals, Vec3, None, None);
        let texcoord = (!part.uvs.is_empty())
            .then(|| push_attribute(&mut root, &mut bin, buffer, &part.uvs, Vec2, None, None));
        let indices = push_indices(&mut root, &mut bin, buffer, &part.indices);
        let mut attributes = BTreeMap::from([
            (Valid(json::mesh::Semantic::Positions), position),
            (Valid(json::mesh::Semantic::Normals), normal),
        ]);
        if let Some(t) = texcoord {
            attributes.insert(Valid(json::mesh::Semantic::TexCoords(0)), t);
        }
        let mesh = root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: g.name.clone(),
            primitives: vec![json::mesh::Primitive {
                attributes,
                extensions: None,
                extras: Default::default(),
                indices: Some(indices),
                material: Some(material),
                mode: Valid(json::mesh::Mode::Triangles),
                targets: None,
            }],
            weights: None,
        });
        nodes.push(root.push(json::Node {
            mesh: Some(mesh),
            name: g.name.clone(),
            ..Default::default()
        }));
    }
    root.buffers[buffer.value()].byte_length = USize64(bin.len() as u64);
    let count = nodes.len();
    let scene = root.push(json::Scene {
        extensions: None,
        extras: Default::default(),
        name: None,
        nodes,
    });
    root.scene = Some(scene);
    Document {
        root,
        bin,
        vertices,
        triangles,
        nodes: count,
    }
}

/// Binary glTF (§4.4): header, JSON chunk, BIN chunk.
pub fn glb(doc: &Document) -> Vec<u8> {
    let json = doc
        .root
        .to_vec()
        .expect("glTF JSON of plain numbers and strings");
    let glb = gltf::binary::Glb {
        header: gltf::binary::Header {
            magic: *b"glTF",
            version: 2,
            length: 0, // computed by the writer
        },
        json: Cow::Owned(json),
        bin: Some(Cow::Borrowed(&doc.bin)),
    };
    glb.to_vec().expect("writing to memory")
}

/// glTF JSON with the buffer embedded as `data:application/octet-stream;base64,…`.
pub fn gltf_text(doc: &Document) -> Vec<u8> {
    let mut root = doc.root.clone();
    root.buffers[0].uri = Some(format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&doc.bin)
    ));
    root.to_vec()
        .expect("glTF JSON of plain numbers and strings")
}

/// One group's vertices and triangles, renumbered.
struct Part {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    /// `(u, 1 − v)` per vertex; empty without UVs.
    uvs: Vec<[f32; 2]>,
    indices: Vec<u32>,
}

impl Part {
    fn of<R: Real>(t: &Tessellation<R>, faces: &[usize]) -> Part {
        let mut local = vec![u32::MAX; t.positions.len()];
        let mut used: Vec<u32> = Vec::new();
        let mut indices = Vec::new();
        for &f in faces {
            let tris: &[[usize; 3]] = match t.faces[f] {
                Face::Tri(_) => &[[0, 1, 2]],
                Face::Quad(_) => &[[0, 1, 2], [0, 2, 3]],
            };
            let c = t.faces[f].corners();
            for tri in tris {
                for &k in tri {
                    let v = c[k] as usize;
                    if local[v] == u32::MAX {
                        local[v] = used.len() as u32;
                        used.push(v as u32);
                    }
                    indices.push(local[v]);
                }
            }
        }
        let positions: Vec<[f32; 3]> = used
            .iter()
            .map(|&v| t.positions[v as usize].0.map(|x| x.to_f64() as f32))
            .collect();
        // Area-weighted normals of the group's triangles, for vertices without one.
        let mut fallback = vec![[0.0f64; 3]; used.len()];
        for tri in indices.chunks_exact(3) {
            let p: [[f64; 3]; 3] =
                core::array::from_fn(|k| positions[tri[k] as usize].map(f64::from));
            let [a, b, c] = p.map(Point3);
            let n = (b - a).cross(c - a).0;
            for &i in tri {
                for k in 0..3 {
                    fallback[i as usize][k] += n[k];
                }
            }
        }
        let normals = used
            .iter()
            .zip(&fallback)
            .map(|(&v, fb)| {
                let n: Point3<R> = t.normals[v as usize];
                unit(n.0.map(|x| x.to_f64()))
                    .or_else(|| unit(*fb))
                    .unwrap_or([0.0, 0.0, 1.0])
            })
            .collect();
        let uvs = if t.uvs.is_empty() {
            Vec::new()
        } else {
            used.iter()
                .map(|&v| {
                    let [u, w] = t.uvs.get(v as usize).copied().unwrap_or([0.0; 2]);
                    [u as f32, (1.0 - w) as f32]
                })
                .collect()
        };
        Part {
            positions,
            normals,
            uvs,
            indices,
        }
    }
}

/// `n / |n|` rounded to `f32` and normalised again in `f32`'s terms, or
/// `None` for a zero or non-finite `n`.
fn unit(n: [f64; 3]) -> Option<[f32; 3]> {
    Point3(n).unit().map(|u| u.0.map(|x| x as f32))
}

/// Per-component minimum and maximum (required on `POSITION`, §3.7.2.1).
fn bounds(p: &[[f32; 3]]) -> (Option<json::Value>, Option<json::Value>) {
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for q in p {
        for k in 0..3 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    (
        Some(json::Value::from(lo.to_vec())),
        Some(json::Value::from(hi.to_vec())),
    )
}

/// Appends `data` to the buffer as a view (target `ARRAY_BUFFER`) and a
/// `FLOAT` accessor of type `kind` (`VEC2` for `N = 2`, `VEC3` for 3).
fn push_attribute<const N: usize>(
    root: &mut json::Root,
    bin: &mut Vec<u8>,
    buffer: json::Index<json::Buffer>,
    data: &[[f32; N]],
    kind: json::accessor::Type,
    min: Option<json::Value>,
    max: Option<json::Value>,
) -> json::Index<json::Accessor> {
    let offset = bin.len();
    for v in data {
        for x in v {
            bin.extend_from_slice(&x.to_le_bytes());
        }
    }
    let view = push_view(
        root,
        buffer,
        offset,
        bin.len() - offset,
        json::buffer::Target::ArrayBuffer,
    );
    push_accessor(
        root,
        view,
        data.len(),
        json::accessor::ComponentType::F32,
        kind,
        min,
        max,
    )
}

/// Appends triangle indices as a view (`ELEMENT_ARRAY_BUFFER`) and an
/// `UNSIGNED_INT` `SCALAR` accessor.
fn push_indices(
    root: &mut json::Root,
    bin: &mut Vec<u8>,
    buffer: json::Index<json::Buffer>,
    indices: &[u32],
) -> json::Index<json::Accessor> {
    let offset = bin.len();
    for i in indices {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let view = push_view(
        root,
        buffer,
        offset,
        bin.len() - offset,
        json::buffer::Target::ElementArrayBuffer,
    );
    push_accessor(
        root,
        view,
        indices.len(),
        json::accessor::ComponentType::U32,
        json::accessor::Type::Scalar,
        None,
        None,
    )
}

/// Appends an accessor of `count` elements over the whole of `view`.
fn push_accessor(
    root: &mut json::Root,
    view: json::Index<json::buffer::View>,
    count: usize,
    component: json::accessor::ComponentType,
    type_: json::accessor::Type,
    min: Option<json::Value>,
    max: Option<json::Value>,
) -> json::Index<json::Accessor> {
    root.push(json::Accessor {
        buffer_view: Some(view),
        byte_offset: None,
        count: USize64(count as u64),
        component_type: Valid(json::accessor::GenericComponentType(component)),
        extensions: None,
        extras: Default::default(),
        type_: Valid(type_),
        min,
        max,
        name: None,
        normalized: false,
        sparse: None,
    })
}

fn push_view(
    root: &mut json::Root,
    buffer: json::Index<json::Buffer>,
    offset: usize,
    length: usize,
    target: json::buffer::Target,
) -> json::Index<json::buffer::View> {
    root.push(json::buffer::View {
        buffer,
        byte_length: USize64(length as u64),
        byte_offset: Some(USize64(offset as u64)),
        byte_stride: None,
        name: None,
        target: Some(Valid(target)),
        extensions: None,
        extras: Default::default(),
    })
}

/// The groups of a tessellation whose face `k` lies in input face
/// `input_face[k]`: one per object (in order, named), or a single unnamed
/// group of every face when `objects` is empty.
pub fn groups(input_face: &[u32], objects: &[capdiv_mesh::obj::ObjObject]) -> Vec<Group> {
    if objects.is_empty() {
        return vec![Group {
            name: None,
            faces: (0..input_face.len()).collect(),
        }];
    }
    let mut of_face = BTreeMap::new();
    for (k, o) in objects.iter().enumerate() {
        for f in o.faces.clone() {
            of_face.insert(f as u32, k);
        }
    }
    let mut out: Vec<Group> = objects
        .iter()
        .map(|o| Group {
            name: (!o.name.is_empty()).then(|| o.name.clone()),
            faces: Vec::new(),
        })
        .collect();
    for (k, f) in input_face.iter().enumerate() {
        if let Some(&g) = of_face.get(f) {
            out[g].faces.push(k);
        }
    }
    out
}
