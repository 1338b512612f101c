//! Reading and parsing the JSON input.
//!
//! The schema is tagged by `kind` (spec C2PS.md §1 for `polar`):
//!
//! ```json
//! {"kind": "polar", "pole": [x, y, z], "links": [[[x, y, z], ...], ...]}
//! ```
//!
//! `links[0]` is the 1-link; every link is a closed ring, counter-clockwise seen
//! from the side the surface normal points to. The EG inputs (spec EG.md §1,
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
    /// of 6 points (spec EG.md §1).
    Cnet(CnetInput),
    /// An EG d-net: `n` sectors of 12 points, optional `c0` (spec EG.md §2).
    Dnet(DnetInput),
    /// A whole polygon mesh (`capdiv surface`).
    Mesh(MeshJson),
}

/// `{"kind": "mesh", "vertices", "faces"}`.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MeshJson {
    /// Vertex positions.
    pub vertices: Vec<P3>,
    /// Faces: 0-based vertex indices, counter-clockwise.
    pub faces: Vec<Vec<i64>>,
}

impl MeshJson {
    /// The mesh crate's input; an index outside `0..vertices` is
    /// [`capdiv_mesh::MeshError::IndexOutOfRange`] (first offending face).
    pub fn to_mesh(&self) -> Result<capdiv_mesh::MeshInput, capdiv_mesh::MeshError> {
        let nv = self.vertices.len();
        let mut faces = Vec::with_capacity(self.faces.len());
        for (face, list) in self.faces.iter().enumerate() {
            let mut out = Vec::with_capacity(list.len());
            for &index in list {
                if index < 0 || index as u64 >= nv as u64 || index > i64::from(u32::MAX) {
                    return Err(capdiv_mesh::MeshError::IndexOutOfRange {
                        face,
                        index,
                        vertices: nv,
                    });
                }
                out.push(index as u32);
            }
            faces.push(out);
        }
        Ok(capdiv_mesh::MeshInput::new(self.vertices.clone(), faces))
    }

    /// The JSON form of a mesh.
    pub fn of(mesh: &capdiv_mesh::MeshInput) -> Self {
        MeshJson {
            vertices: mesh.vertices.clone(),
            faces: mesh
                .faces
                .iter()
                .map(|f| f.iter().map(|&i| i64::from(i)).collect())
                .collect(),
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
