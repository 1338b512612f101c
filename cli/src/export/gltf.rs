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
//!
//! The groups' face lists, each group's vertices and indices, the buffer
//! and the file's bytes are reserved through [`capdiv_mesh::mem`]: a
//! refused allocation is an [`OutOfMemory`] error. The document's JSON
//! entries (a view and an accessor per attribute, a mesh and a node per
//! group) are the `gltf` crate's own lists, a few per object of the input.

use crate::json::TryBytes;
use base64::Engine;
use capdiv::{Point3, Real};
use capdiv_mesh::tessellate::{Face, Tessellation};
use capdiv_mesh::{mem, OutOfMemory};
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
pub fn document<R: Real>(t: &Tessellation<R>, groups: &[Group]) -> Result<Document, OutOfMemory> {
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
        let part = Part::of(t, &g.faces)?;
        if part.indices.is_empty() {
            continue;
        }
        // The part's attributes and indices: the pushes below stay within.
        let floats = 3 * part.positions.len() + 3 * part.normals.len() + 2 * part.uvs.len();
        mem::reserve(&mut bin, 4 * (floats + part.indices.len()))?;
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
    Ok(Document {
        root,
        bin,
        vertices,
        triangles,
        nodes: count,
    })
}

/// The JSON text of `root`, or the error when it cannot be allocated.
fn json_text(root: &json::Root, capacity: usize) -> Result<Vec<u8>, OutOfMemory> {
    let mut text = TryBytes::with_capacity(capacity)?;
    // Cannot fail but for the buffer: plain numbers and strings.
    let _ = root.to_writer(&mut text);
    text.into_result()
}

/// Binary glTF (§4.4): header, JSON chunk, BIN chunk; the error when its
/// bytes cannot be allocated.
pub fn glb(doc: &Document) -> Result<Vec<u8>, OutOfMemory> {
    let json = json_text(&doc.root, 0)?;
    // Header, two chunk headers, each chunk padded to four bytes.
    let length = 12 + 8 + json.len().next_multiple_of(4) + 8 + doc.bin.len().next_multiple_of(4);
    let glb = gltf::binary::Glb {
        header: gltf::binary::Header {
            magic: *b"glTF",
            version: 2,
            length: 0, // computed by the writer
        },
        json: Cow::Owned(json),
        bin: Some(Cow::Borrowed(&doc.bin)),
    };
    let mut out = TryBytes::with_capacity(length)?;
    // Cannot fail but for the buffer: a writer into memory.
    let _ = glb.to_writer(&mut out);
    out.into_result()
}

/// glTF JSON with the buffer embedded as `data:application/octet-stream;base64,…`;
/// the error when its text cannot be allocated.
pub fn gltf_text(doc: &Document) -> Result<Vec<u8>, OutOfMemory> {
    const PREFIX: &str = "data:application/octet-stream;base64,";
    let base64 = base64::engine::general_purpose::STANDARD;
    let encoded = base64::encoded_len(doc.bin.len(), true).unwrap_or(usize::MAX);
    let mut uri = String::new();
    let length = PREFIX.len().saturating_add(encoded);
    uri.try_reserve_exact(length)
        .map_err(|_| OutOfMemory { bytes: length })?;
    uri.push_str(PREFIX);
    base64.encode_string(&doc.bin, &mut uri);
    let mut root = doc.root.clone();
    root.buffers[0].uri = Some(uri);
    json_text(&root, length.saturating_add(4096))
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
    /// The part of `faces`, or the error when its lists cannot be allocated.
    fn of<R: Real>(t: &Tessellation<R>, faces: &[usize]) -> Result<Part, OutOfMemory> {
        let mut local = mem::filled(t.positions.len(), u32::MAX)?;
        let triangles: usize = faces
            .iter()
            .map(|&f| match t.faces[f] {
                Face::Tri(_) => 1,
                Face::Quad(_) => 2,
            })
            .sum();
        // Exactly `3·triangles` indices; at most as many vertices (fewer
        // than the tessellation's): the pushes stay within.
        let mut indices = mem::with_capacity(3 * triangles)?;
        let mut used: Vec<u32> = mem::with_capacity((3 * triangles).min(t.positions.len()))?;
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
        let positions: Vec<[f32; 3]> = mem::collect(
            used.iter()
                .map(|&v| t.positions[v as usize].0.map(|x| x.to_f64() as f32)),
        )?;
        // Area-weighted normals of the group's triangles, for vertices without one.
        let mut fallback = mem::filled(used.len(), [0.0f64; 3])?;
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
        let normals = mem::collect(used.iter().zip(&fallback).map(|(&v, fb)| {
            let n: Point3<R> = t.normals[v as usize];
            unit(n.0.map(|x| x.to_f64()))
                .or_else(|| unit(*fb))
                .unwrap_or([0.0, 0.0, 1.0])
        }))?;
        let uvs = if t.uvs.is_empty() {
            Vec::new()
        } else {
            mem::collect(used.iter().map(|&v| {
                let [u, w] = t.uvs.get(v as usize).copied().unwrap_or([0.0; 2]);
                [u as f32, (1.0 - w) as f32]
            }))?
        };
        Ok(Part {
            positions,
            normals,
            uvs,
            indices,
        })
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
/// group of every face when `objects` is empty. The error when the lists
/// cannot be allocated.
pub fn groups(
    input_face: &[u32],
    objects: &[capdiv_mesh::obj::ObjObject],
) -> Result<Vec<Group>, OutOfMemory> {
    if objects.is_empty() {
        return Ok(vec![Group {
            name: None,
            faces: mem::collect(0..input_face.len())?,
        }]);
    }
    // The object of each input face (a later object's wins).
    const NONE: usize = usize::MAX;
    let faces = objects.iter().map(|o| o.faces.end).max().unwrap_or(0);
    let mut of_face = mem::filled(faces, NONE)?;
    for (k, o) in objects.iter().enumerate() {
        of_face[o.faces.clone()].fill(k);
    }
    let mut out: Vec<Group> = mem::collect(objects.iter().map(|o| Group {
        name: (!o.name.is_empty()).then(|| o.name.clone()),
        faces: Vec::new(),
    }))?;
    for (k, &f) in input_face.iter().enumerate() {
        match of_face.get(f as usize) {
            Some(&g) if g != NONE => mem::push(&mut out[g].faces, k)?,
            _ => {}
        }
    }
    Ok(out)
}
