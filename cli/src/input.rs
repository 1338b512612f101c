//! Reading and parsing the JSON input.
//!
//! The schema is tagged by `kind` (docs/math/c2ps.md §1 for `polar`):
//!
//! ```json
//! {"kind": "polar", "pole": [x, y, z], "links": [[[x, y, z], ...], ...]}
//! ```
//!
//! `links[0]` is the 1-link; every link is a closed ring, counter-clockwise seen
//! from the side the surface normal points to. The EG inputs (docs/math/eg.md §1,
//! §2):
//!
//! ```json
//! {"kind": "cnet", "center": [x, y, z], "sectors": [[6 points], ...]}
//! {"kind": "dnet", "sectors": [[12 points], ...], "c0": [x, y, z]}
//! ```
//!
//! c-net sectors in the §1 order `(1,0) (2,0) (1,1) (2,1) (1,2) (2,2)`, d-net
//! sectors in the §2 order `00 10 20 30 01 11 21 31 02 12 22 32`, sectors
//! counter-clockwise; `c0` is optional (fitted by formula (4) when absent).
//! A whole mesh (`capdiv surface` only; the other commands refuse it):
//!
//! ```json
//! {"kind": "mesh", "vertices": [[x, y, z], ...], "faces": [[i, j, k, ...], ...]}
//! ```
//!
//! 0-based vertex indices, faces counter-clockwise about the outward normal.
//! Optional OpenSubdiv subdivision tags (0-based indices):
//!
//! ```json
//! {"creases": [[a, b, sharpness], ...], "corners": [[v, sharpness], ...],
//!  "holes": [f, ...], "boundary": "none" | "edge-only" | "edge-and-corner",
//!  "crease_method": "normal" | "chaikin", "triangles": "catmark" | "smooth"}
//! ```
//!
//! Optional texture coordinates, one `[u, v]` per face corner (face by face,
//! corners in the order of `faces`; OBJ's `vt`), interpolated linearly within
//! each face (OpenSubdiv's `FVAR_LINEAR_ALL`):
//!
//! ```json
//! {"uvs": [[[u, v], [u, v], [u, v], [u, v]], ...]}
//! ```
//!
//! Unknown fields are rejected.

use crate::error::CliError;
use serde::{Deserialize, Serialize};
use std::io::Read;

/// One point `[x, y, z]`.
pub type P3 = [f64; 3];

/// A parsed input, by its `kind` tag.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Input {
    /// A polar configuration (C²PS).
    Polar(PolarInput),
    /// An EG control net around an extraordinary node: center and `n` sectors
    /// of 6 points (docs/math/eg.md §1).
    Cnet(CnetInput),
    /// An EG d-net: `n` sectors of 12 points, optional `c0` (docs/math/eg.md §2).
    Dnet(DnetInput),
    /// A whole polygon mesh (`capdiv surface`).
    Mesh(MeshJson),
}

/// `{"kind": "mesh", "vertices", "faces"}`, the optional subdivision
/// tags `creases`, `corners`, `holes`, `boundary`, `crease_method`,
/// `triangles`, and the optional per-corner texture coordinates `uvs`.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MeshJson {
    /// Vertex positions.
    pub vertices: Vec<P3>,
    /// Faces: 0-based vertex indices, counter-clockwise.
    pub faces: Vec<Vec<i64>>,
    /// Edge sharpness `[a, b, sharpness]`: 0-based vertices of an edge.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub creases: Vec<(i64, i64, f64)>,
    /// Vertex sharpness `[v, sharpness]`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub corners: Vec<(i64, f64)>,
    /// 0-based faces that are holes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub holes: Vec<i64>,
    /// The boundary rule (default `edge-and-corner`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub boundary: Option<BoundaryJson>,
    /// The creasing method (default `normal`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crease_method: Option<CreaseMethodJson>,
    /// The edge rule next to triangles (default `catmark`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub triangles: Option<TrianglesJson>,
    /// Texture coordinates: per face, one `[u, v]` per corner (empty: none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub uvs: Vec<Vec<[f64; 2]>>,
    /// Tags an OBJ file had that are not applied (name, line); not part of
    /// the JSON, carried so that a mesh read from OBJ keeps them.
    #[serde(skip)]
    pub ignored: Vec<(String, usize)>,
}

/// `"boundary"` of a JSON mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BoundaryJson {
    /// [`capdiv_mesh::BoundaryInterpolation::None`].
    None,
    /// [`capdiv_mesh::BoundaryInterpolation::EdgeOnly`].
    EdgeOnly,
    /// [`capdiv_mesh::BoundaryInterpolation::EdgeAndCorner`].
    EdgeAndCorner,
}

impl From<BoundaryJson> for capdiv_mesh::BoundaryInterpolation {
    fn from(b: BoundaryJson) -> Self {
        match b {
            BoundaryJson::None => capdiv_mesh::BoundaryInterpolation::None,
            BoundaryJson::EdgeOnly => capdiv_mesh::BoundaryInterpolation::EdgeOnly,
            BoundaryJson::EdgeAndCorner => capdiv_mesh::BoundaryInterpolation::EdgeAndCorner,
        }
    }
}

impl From<capdiv_mesh::BoundaryInterpolation> for BoundaryJson {
    fn from(b: capdiv_mesh::BoundaryInterpolation) -> Self {
        match b {
            capdiv_mesh::BoundaryInterpolation::None => BoundaryJson::None,
            capdiv_mesh::BoundaryInterpolation::EdgeOnly => BoundaryJson::EdgeOnly,
            capdiv_mesh::BoundaryInterpolation::EdgeAndCorner => BoundaryJson::EdgeAndCorner,
        }
    }
}

/// `"crease_method"` of a JSON mesh (OpenSubdiv's shape-file names).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum CreaseMethodJson {
    /// [`capdiv_mesh::CreaseMethod::Uniform`].
    Normal,
    /// [`capdiv_mesh::CreaseMethod::Chaikin`].
    Chaikin,
}

/// `"triangles"` of a JSON mesh (OpenSubdiv's shape-file names of
/// `Sdc::Options::TriangleSubdivision`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum TrianglesJson {
    /// [`capdiv_mesh::TriangleSubdivision::Catmark`].
    Catmark,
    /// [`capdiv_mesh::TriangleSubdivision::Smooth`].
    Smooth,
}

impl MeshJson {
    /// The mesh crate's input. A face index outside `0..vertices` is
    /// [`capdiv_mesh::MeshError::IndexOutOfRange`] (first offending face); a
    /// tag that names a missing vertex, edge or face, or has a negative
    /// sharpness, is [`CliError::Schema`] naming the entry (checked by
    /// [`capdiv_mesh::tags::TagCheck`], as for OBJ tags).
    pub fn to_mesh(&self, source: &str) -> Result<capdiv_mesh::MeshInput, CliError> {
        use capdiv_mesh::tags::TagCheck;
        use capdiv_mesh::{CreaseMethod, EdgeCrease, SubdivTags, VertexCorner};
        let nv = self.vertices.len();
        let mut faces = Vec::with_capacity(self.faces.len());
        for (face, list) in self.faces.iter().enumerate() {
            let mut out = Vec::with_capacity(list.len());
            for &index in list {
                if index < 0 || index as u64 >= nv as u64 || index > i64::from(u32::MAX) {
                    return Err(CliError::mesh(
                        source,
                        capdiv_mesh::MeshError::IndexOutOfRange {
                            face,
                            index,
                            vertices: nv,
                        },
                    ));
                }
                out.push(index as u32);
            }
            faces.push(out);
        }
        let schema = |field: &str, k: usize, message: String| CliError::Schema {
            source: source.to_string(),
            message: format!("{field}[{k}]: {message}"),
        };
        let check = TagCheck::new(nv, &faces);
        let mut tags = SubdivTags {
            ignored: self.ignored.clone(),
            ..Default::default()
        };
        for (k, &(a, b, s)) in self.creases.iter().enumerate() {
            let sharpness = TagCheck::sharpness(s).map_err(|m| schema("creases", k, m))?;
            let vertices = check.crease(a, b).map_err(|m| schema("creases", k, m))?;
            tags.creases.push(EdgeCrease {
                vertices,
                sharpness,
            });
        }
        for (k, &(v, s)) in self.corners.iter().enumerate() {
            let sharpness = TagCheck::sharpness(s).map_err(|m| schema("corners", k, m))?;
            let vertex = check.corner(v).map_err(|m| schema("corners", k, m))?;
            tags.corners.push(VertexCorner { vertex, sharpness });
        }
        for (k, &f) in self.holes.iter().enumerate() {
            tags.holes
                .push(check.hole(f).map_err(|m| schema("holes", k, m))?);
        }
        if let Some(b) = self.boundary {
            tags.boundary = b.into();
        }
        tags.crease_method = match self.crease_method {
            None | Some(CreaseMethodJson::Normal) => CreaseMethod::Uniform,
            Some(CreaseMethodJson::Chaikin) => CreaseMethod::Chaikin,
        };
        tags.triangles = match self.triangles {
            None | Some(TrianglesJson::Catmark) => capdiv_mesh::TriangleSubdivision::Catmark,
            Some(TrianglesJson::Smooth) => capdiv_mesh::TriangleSubdivision::Smooth,
        };
        // Per-corner UVs: the pool is the corners in order.
        let mut uvs = Vec::new();
        let mut uv_faces = Vec::new();
        if !self.uvs.is_empty() {
            uvs.reserve(self.uvs.iter().map(Vec::len).sum());
            for list in &self.uvs {
                uv_faces.push((uvs.len() as u32..(uvs.len() + list.len()) as u32).collect());
                uvs.extend_from_slice(list);
            }
        }
        let mesh = capdiv_mesh::MeshInput {
            vertices: self.vertices.clone(),
            faces,
            tags,
            uvs,
            uv_faces,
        };
        mesh.check_uvs().map_err(|e| CliError::mesh(source, e))?;
        Ok(mesh)
    }

    /// The JSON form of a mesh (tags at their defaults are left out).
    pub fn of(mesh: &capdiv_mesh::MeshInput) -> Self {
        let t = &mesh.tags;
        MeshJson {
            vertices: mesh.vertices.clone(),
            faces: mesh
                .faces
                .iter()
                .map(|f| f.iter().map(|&i| i64::from(i)).collect())
                .collect(),
            creases: t
                .creases
                .iter()
                .map(|c| {
                    let [a, b] = c.vertices;
                    (i64::from(a), i64::from(b), f64::from(c.sharpness))
                })
                .collect(),
            corners: t
                .corners
                .iter()
                .map(|c| (i64::from(c.vertex), f64::from(c.sharpness)))
                .collect(),
            holes: t.holes.iter().map(|&f| i64::from(f)).collect(),
            boundary: (t.boundary != capdiv_mesh::BoundaryInterpolation::default())
                .then(|| t.boundary.into()),
            crease_method: match t.crease_method {
                capdiv_mesh::CreaseMethod::Uniform => None,
                capdiv_mesh::CreaseMethod::Chaikin => Some(CreaseMethodJson::Chaikin),
            },
            triangles: match t.triangles {
                capdiv_mesh::TriangleSubdivision::Catmark => None,
                capdiv_mesh::TriangleSubdivision::Smooth => Some(TrianglesJson::Smooth),
            },
            uvs: mesh
                .uv_faces
                .iter()
                .map(|f| {
                    f.iter()
                        .map(|&t| mesh.uvs.get(t as usize).copied().unwrap_or([0.0; 2]))
                        .collect()
                })
                .collect(),
            ignored: t.ignored.clone(),
        }
    }
}

/// `{"kind": "polar", "pole", "links"}`.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PolarInput {
    /// The pole `q00`.
    pub pole: P3,
    /// Links 1, 2, …, each a closed ring of `n` points.
    pub links: Vec<Vec<P3>>,
}

/// `{"kind": "cnet", "center", "sectors"}`.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CnetInput {
    /// The extraordinary node.
    pub center: P3,
    /// One entry of 6 points per sector.
    pub sectors: Vec<[P3; 6]>,
}

/// `{"kind": "dnet", "sectors", "c0"?}`.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DnetInput {
    /// One entry of 12 points per sector.
    pub sectors: Vec<[P3; 12]>,
    /// The central point, when given.
    #[serde(default)]
    pub c0: Option<P3>,
}

impl Input {
    /// The `kind` tag as written in the input.
    pub fn kind(&self) -> &'static str {
        match self {
            Input::Polar(_) => "polar",
            Input::Cnet(_) => "cnet",
            Input::Dnet(_) => "dnet",
            Input::Mesh(_) => "mesh",
        }
    }

    /// The polar configuration, or [`CliError::WrongKind`] (saying that
    /// `who` needs a polar input) for other kinds.
    pub fn into_polar(self, source: &str, who: &str) -> Result<PolarInput, CliError> {
        match self {
            Input::Polar(p) => Ok(p),
            other => Err(CliError::WrongKind {
                source: source.to_string(),
                kind: other.kind(),
                need: format!("{who} needs a 'polar' input"),
            }),
        }
    }

    /// The EG input (c-net or d-net), or [`CliError::WrongKind`] (saying that
    /// `who` needs one) for a polar input.
    pub fn into_eg(self, source: &str, who: &str) -> Result<EgInput, CliError> {
        match self {
            Input::Cnet(c) => Ok(EgInput::Cnet(c)),
            Input::Dnet(d) => Ok(EgInput::Dnet(d)),
            other => Err(CliError::WrongKind {
                source: source.to_string(),
                kind: other.kind(),
                need: format!("{who} needs a 'cnet' or 'dnet' input"),
            }),
        }
    }
}

/// An EG input: a c-net or a d-net.
#[derive(Clone, Debug, PartialEq)]
pub enum EgInput {
    /// `{"kind": "cnet", ...}`.
    Cnet(CnetInput),
    /// `{"kind": "dnet", ...}`.
    Dnet(DnetInput),
}

impl EgInput {
    /// The valence (number of sectors).
    pub fn valence(&self) -> usize {
        match self {
            EgInput::Cnet(c) => c.sectors.len(),
            EgInput::Dnet(d) => d.sectors.len(),
        }
    }
}

/// An input read into memory, with the name used in messages.
#[derive(Clone, Debug)]
pub struct Source {
    /// The path as given, or `<stdin>` for `-`.
    pub name: String,
    /// The whole text.
    pub text: String,
}

impl Source {
    /// Reads `path`, or standard input for `-`.
    pub fn read(path: &str) -> Result<Self, CliError> {
        if path == "-" {
            let mut text = String::new();
            std::io::stdin()
                .read_to_string(&mut text)
                .map_err(|e| CliError::Io {
                    path: "<stdin>".into(),
                    message: e.to_string(),
                })?;
            return Ok(Source {
                name: "<stdin>".into(),
                text,
            });
        }
        let text = std::fs::read_to_string(path).map_err(|e| CliError::Io {
            path: path.to_string(),
            message: e.to_string(),
        })?;
        Ok(Source {
            name: path.to_string(),
            text,
        })
    }

    /// Parses the text; syntax errors are [`CliError::MalformedJson`], the rest
    /// (missing or unknown fields, wrong lengths, unknown kind) [`CliError::Schema`].
    /// A `mesh` is [`CliError::WrongKind`]: the commands that read through
    /// here take single configurations (`capdiv surface` reads meshes).
    pub fn parse(&self) -> Result<Input, CliError> {
        match parse(&self.name, &self.text)? {
            Input::Mesh(_) => Err(CliError::WrongKind {
                source: self.name.clone(),
                kind: "mesh",
                need: "this command needs a 'polar', 'cnet' or 'dnet' input \
                       (a whole mesh is for 'capdiv surface')"
                    .into(),
            }),
            input => Ok(input),
        }
    }

    /// Reads `path` (`-` = stdin) as bytes; text that is not UTF-8 is an
    /// error naming the first bad byte's offset.
    pub fn read_text(path: &str) -> Result<Self, CliError> {
        let (name, bytes) = if path == "-" {
            let mut bytes = Vec::new();
            std::io::stdin()
                .read_to_end(&mut bytes)
                .map_err(|e| CliError::Io {
                    path: "<stdin>".into(),
                    message: e.to_string(),
                })?;
            ("<stdin>".to_string(), bytes)
        } else {
            let bytes = std::fs::read(path).map_err(|e| CliError::Io {
                path: path.to_string(),
                message: e.to_string(),
            })?;
            (path.to_string(), bytes)
        };
        match String::from_utf8(bytes) {
            Ok(text) => Ok(Source { name, text }),
            Err(e) => Err(CliError::Io {
                path: name,
                message: format!(
                    "not UTF-8 text (invalid byte at offset {})",
                    e.utf8_error().valid_up_to()
                ),
            }),
        }
    }
}

/// Parses an input text named `name`: first as JSON of any shape (syntax
/// errors are [`CliError::MalformedJson`], also when a wrong shape would be
/// seen first), then into [`Input`] ([`CliError::Schema`]). Both messages carry
/// serde_json's line and column.
pub fn parse(name: &str, text: &str) -> Result<Input, CliError> {
    parse_as(name, text)
}

/// [`parse`] into any deserialisable type (also used for rule tables).
pub fn parse_as<T: serde::de::DeserializeOwned>(name: &str, text: &str) -> Result<T, CliError> {
    if let Err(e) = serde_json::from_str::<serde::de::IgnoredAny>(text) {
        return Err(CliError::MalformedJson {
            source: name.to_string(),
            message: e.to_string(),
        });
    }
    serde_json::from_str::<T>(text).map_err(|e| {
        let message = e.to_string();
        match e.classify() {
            serde_json::error::Category::Data => CliError::Schema {
                source: name.to_string(),
                message,
            },
            _ => CliError::MalformedJson {
                source: name.to_string(),
                message,
            },
        }
    })
}
