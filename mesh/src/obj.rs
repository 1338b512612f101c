//! Wavefront OBJ reader: vertex positions, polygon faces and OpenSubdiv's
//! subdivision tags, nothing else.
//!
//! Read: `v x y z [w …]` (only `x y z` kept; further numbers — a `w`, or the
//! `r g b` some tools append — must be numbers and are ignored),
//! `vt u [v [w]]` (texture coordinates: `v` is 0 when missing, `w` is
//! ignored), `f a b c …` with corners written `i`, `i/t`, `i//n` or `i/t/n`,
//! 1-based or negative (relative to the vertices — for `t`, the texture
//! coordinates — read so far, `-1` being the last), any polygon size,
//! `o NAME` (the object the following faces belong to, kept by
//! [`parse_obj_objects`] only), and tag lines (below). Lines may end in
//! `\r\n`; `#` starts a comment; a line ending in `\` continues on the next
//! one. Every other statement (`vn`, `vp`, `g`, `s`, `usemtl`, `mtllib`, `l`,
//! `p`, …) is ignored, and so are normal indices `n`.
//!
//! Texture indices `t` become the mesh's face-varying UVs
//! ([`MeshInput::uv_faces`]): either every corner of every face has one or
//! none does; a face that breaks the rule is a [`MeshError::Parse`] naming
//! its line. Out-of-range texture indices are [`MeshError::UvOutOfRange`].
//!
//! Tags are OpenSubdiv's shape-file lines `t NAME nint/nfloat/nstring`
//! followed by that many integers, then numbers, then strings, as its
//! regression tools read them (`regression/common/shape_utils.cpp`,
//! `Shape::tag::parseTag`) and apply them to the refiner
//! (`regression/common/far_utils.h`). Indices in tags are 0-based (unlike
//! `f` lines: OpenSubdiv passes them to the refiner unchanged), sharpness is
//! an `f32`:
//!
//! - `crease`: vertex pairs `a0 b0 a1 b1 …`, each an edge of the mesh; one
//!   sharpness for all of them, or (far_utils.h indexes the floats by the
//!   pair's first integer) edge `k`'s sharpness at float `2k`, so `2·edges −
//!   1` or `2·edges` floats;
//! - `corner`: vertices, one sharpness for all or one per vertex;
//! - `hole`: face indices (0-based, in `f` order);
//! - `interpolateboundary`: one integer, RenderMan's numbering: 0 none,
//!   1 edge-and-corner, 2 edge-only (without the tag: edge-and-corner,
//!   [`BoundaryInterpolation`]'s default, where far_utils.h would start
//!   from edge-only);
//! - `creasemethod`: one string, `normal` or `chaikin`;
//! - `smoothtriangles`: one string, `catmark` or `smooth` (far_utils.h), or
//!   one integer, 0 or 1 (Hbr's shape files): [`TriangleSubdivision`].
//!
//! A later `interpolateboundary`, `creasemethod` or `smoothtriangles`
//! replaces an earlier one.
//! Any other tag name (`facevaryinginterpolateboundary`,
//! `facevaryingpropagatecorners`, `vertexedit`, …) is syntax-checked and
//! listed in [`SubdivTags::ignored`] with its line, not applied. Where
//! OpenSubdiv's tools would print a warning and go on (a count, value or
//! string they do not expect, a missing edge) or clamp (a negative
//! sharpness), this reader rejects the line.
//!
//! Checked here, in this order: the syntax of the whole text, tag lines
//! included ([`MeshError::Parse`], first offending line), then the face
//! vertex indices ([`MeshError::IndexOutOfRange`], first offending face and
//! corner; a positive index may refer to a vertex defined later in the file),
//! then the tags' indices (vertices, edges, faces; [`MeshError::Parse`]
//! naming the first offending tag line; see [`crate::tags`]). Not checked
//! here: finiteness (`1e999` reads as ∞ and is kept; the topology reports
//! [`MeshError::NonFinite`]), face sizes, repeated vertices, manifoldness —
//! all [`crate::Topology::new`]'s job. No input makes the reader panic.

use crate::error::{MeshError, Names};
use crate::input::{
    BoundaryInterpolation, CreaseMethod, EdgeCrease, MeshInput, SubdivTags, TriangleSubdivision,
    VertexCorner,
};
use crate::tags::TagCheck;
use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;

/// Whether `text` looks like JSON rather than OBJ: its first character other
/// than whitespace (or a byte-order mark) is `{`.
pub fn looks_like_json(text: &str) -> bool {
    strip_bom(text).trim_start().starts_with('{')
}

fn strip_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// Reads the vertices, faces and subdivision tags of a Wavefront OBJ text;
/// face indices become 0-based. See the module doc for what is read, ignored
/// and checked.
///
/// # Example
///
/// A quad with OpenSubdiv's tag lines (`t NAME nint/nfloat/nstring ints
/// floats strings`): edge 0–1 creased with sharpness 2.5, face 0 a hole.
///
/// ```
/// use capdiv_mesh::obj::parse_obj;
///
/// let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n\
///             t crease 2/1/0 0 1 2.5\nt hole 1/0/0 0\n";
/// let mesh = parse_obj(text)?;
/// assert_eq!(mesh.faces, vec![vec![0, 1, 2, 3]]);
/// assert_eq!(mesh.tags.creases[0].vertices, [0, 1]);
/// assert_eq!(mesh.tags.creases[0].sharpness, 2.5);
/// assert_eq!(mesh.tags.holes, vec![0]);
///
/// // A malformed tag is an error that names its line.
/// let err = parse_obj("v 0 0 0\nt crease 2/1/0 0\n").unwrap_err();
/// assert!(err.to_string().contains("line 2"));
/// # Ok::<(), capdiv_mesh::MeshError>(())
/// ```
pub fn parse_obj(text: &str) -> Result<MeshInput, MeshError> {
    parse_obj_objects(text).map(|(mesh, _)| mesh)
}

/// A named object of an OBJ file: the faces from one `o NAME` statement to
/// the next (or to the end).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObjObject {
    /// The name after `o` (the rest of the line, blanks trimmed; may be empty).
    pub name: String,
    /// Its faces, as indices into [`MeshInput::faces`].
    pub faces: core::ops::Range<usize>,
}

/// [`parse_obj`], and the file's objects in order: empty if the file has no
/// `o` statement. Faces before the first `o` form an object named `""`;
/// objects without faces are left out.
pub fn parse_obj_objects(text: &str) -> Result<(MeshInput, Vec<ObjObject>), MeshError> {
    let mut reader = Reader::default();
    for_each_statement(text, |line, line_no| reader.statement(line, line_no))?;

    let Reader {
        vertices,
        corners,
        face_ends,
        mut tags,
        pending,
        objects: starts,
        uvs,
        uv_corners,
        ..
    } = reader;
    let mut objects = Vec::new();
    if !starts.is_empty() {
        let mut bounds: Vec<(String, usize)> = Vec::with_capacity(starts.len() + 1);
        if starts[0].1 > 0 {
            bounds.push((String::new(), 0));
        }
        bounds.extend(starts);
        for k in 0..bounds.len() {
            let end = bounds.get(k + 1).map_or(face_ends.len(), |b| b.1);
            let (name, start) = &bounds[k];
            if end > *start {
                objects.push(ObjObject {
                    name: name.clone(),
                    faces: *start..end,
                });
            }
        }
    }
    let nv = vertices.len();
    let mut faces: Vec<Vec<u32>> = Vec::with_capacity(face_ends.len());
    let mut start = 0usize;
    for (face, &end) in face_ends.iter().enumerate() {
        let mut list = Vec::with_capacity(end - start);
        for &index in &corners[start..end] {
            if index < 0 || index as u64 >= nv as u64 || index > u32::MAX as i64 {
                return Err(MeshError::IndexOutOfRange {
                    face,
                    index,
                    vertices: nv,
                });
            }
            list.push(index as u32);
        }
        faces.push(list);
        start = end;
    }
    let mut uv_faces: Vec<Vec<u32>> = Vec::new();
    if !uv_corners.is_empty() {
        let nt = uvs.len();
        uv_faces.reserve(face_ends.len());
        let mut start = 0usize;
        for (face, &end) in face_ends.iter().enumerate() {
            let mut list = Vec::with_capacity(end - start);
            for &index in &uv_corners[start..end] {
                if index < 0 || index as u64 >= nt as u64 || index > u32::MAX as i64 {
                    return Err(MeshError::UvOutOfRange {
                        face,
                        index,
                        uvs: nt,
                    });
                }
                list.push(index as u32);
            }
            uv_faces.push(list);
            start = end;
        }
    }

    // Tag indices, in line order, now that every vertex and face is known.
    let check = TagCheck::new(nv, &faces);
    for p in pending {
        let error = |message: String| MeshError::Parse {
            line: p.line,
            message: format!("tag {}: {message}", p.name),
        };
        match p.values {
            Pending::Creases(list) => {
                for (a, b, sharpness) in list {
                    let vertices = check.crease(a, b).map_err(error)?;
                    tags.creases.push(EdgeCrease {
                        vertices,
                        sharpness,
                    });
                }
            }
            Pending::Corners(list) => {
                for (v, sharpness) in list {
                    let vertex = check.corner(v).map_err(error)?;
                    tags.corners.push(VertexCorner { vertex, sharpness });
                }
            }
            Pending::Holes(list) => {
                for f in list {
                    tags.holes.push(check.hole(f).map_err(error)?);
                }
            }
        }
    }
    Ok((
        MeshInput {
            vertices,
            faces,
            tags,
            uvs,
            uv_faces,
        },
        objects,
    ))
}

/// Calls `f` with every logical line of `text` (comments removed, `\`
/// continuations joined) and the 1-based line where it starts.
fn for_each_statement(
    text: &str,
    mut f: impl FnMut(&str, usize) -> Result<(), MeshError>,
) -> Result<(), MeshError> {
    let mut joined = String::new();
    let mut statement_line = 0usize;
    let mut continuing = false;
    for (k, raw) in strip_bom(text).split('\n').enumerate() {
        let raw = raw.strip_suffix('\r').unwrap_or(raw);
        // A comment ends the physical line (a `\` inside it continues nothing).
        let raw = match raw.find('#') {
            Some(at) => &raw[..at],
            None => raw,
        };
        if !continuing {
            statement_line = k + 1;
            joined.clear();
        }
        // A trailing backslash (after trailing blanks) continues the line.
        let trimmed = raw.trim_end();
        if let Some(head) = trimmed.strip_suffix('\\') {
            joined.push_str(head);
            joined.push(' ');
            continuing = true;
            continue;
        }
        continuing = false;
        let line: &str = if joined.is_empty() {
            raw
        } else {
            joined.push_str(raw);
            &joined
        };
        f(line, statement_line)?;
    }
    if continuing {
        // The text ended on a continuation: the statement is what was read.
        f(&joined, statement_line)?;
    }
    Ok(())
}

/// Where each vertex and face of an OBJ text is written: the 1-based line of
/// its `v` or `f` statement. As [`Names`] it names them as the file counts
/// them: `vertex 3 (line 5)`, `face 1 (line 9)` (1-based).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ObjLines {
    /// Line of vertex `i` (0-based `i`).
    pub vertices: Vec<usize>,
    /// Line of face `i` (0-based `i`, faces in `f` order).
    pub faces: Vec<usize>,
    /// Line of texture coordinate `i` (0-based `i`, `vt` order).
    pub uvs: Vec<usize>,
}

impl ObjLines {
    /// The lines of every `v` and `f` statement of `text` (read as
    /// [`parse_obj`] reads it; the text need not be valid).
    pub fn of(text: &str) -> Self {
        let mut lines = ObjLines::default();
        let _ = for_each_statement(text, |line, line_no| {
            match line.split_whitespace().next() {
                Some("v") => lines.vertices.push(line_no),
                Some("f") => lines.faces.push(line_no),
                Some("vt") => lines.uvs.push(line_no),
                _ => {}
            }
            Ok(())
        });
        lines
    }
}

impl Names for ObjLines {
    fn vertex(&self, v: usize) -> String {
        match self.vertices.get(v) {
            Some(line) => format!("vertex {} (line {line})", v + 1),
            None => format!("vertex {}", v + 1),
        }
    }
    fn missing_vertex(&self, index: i64) -> String {
        match usize::try_from(index) {
            Ok(v) => format!("vertex {}", v as u64 + 1),
            // A relative index reaching before the first vertex.
            Err(_) => String::from("a vertex before the first one"),
        }
    }
    fn face(&self, f: usize) -> String {
        match self.faces.get(f) {
            Some(line) => format!("face {} (line {line})", f + 1),
            None => format!("face {}", f + 1),
        }
    }
    fn uv(&self, t: usize) -> String {
        match self.uvs.get(t) {
            Some(line) => format!("texture coordinate {} (line {line})", t + 1),
            None => format!("texture coordinate {}", t + 1),
        }
    }
    fn missing_uv(&self, index: i64) -> String {
        match usize::try_from(index) {
            Ok(t) => format!("texture coordinate {}", t as u64 + 1),
            Err(_) => String::from("a texture coordinate before the first one"),
        }
    }
}

/// What has been read so far.
#[derive(Default)]
struct Reader {
    vertices: Vec<[f64; 3]>,
    /// Resolved 0-based indices, possibly out of range; checked at the end.
    corners: Vec<i64>,
    face_ends: Vec<usize>,
    /// Boundary rule, creasing method and ignored tags (applied as read);
    /// creases, corners and holes are filled in at the end from `pending`.
    tags: SubdivTags,
    pending: Vec<PendingTag>,
    /// `o` statements: name and the number of faces read before it.
    objects: Vec<(String, usize)>,
    /// `vt` statements: `(u, v)`.
    uvs: Vec<[f64; 2]>,
    /// Resolved 0-based texture indices, one per corner once the first face
    /// had them (possibly out of range; checked at the end).
    uv_corners: Vec<i64>,
    /// Whether the faces carry texture indices (decided by the first face).
    faces_have_uvs: Option<bool>,
}

/// A `crease`, `corner` or `hole` tag whose indices are checked at the end.
struct PendingTag {
    line: usize,
    name: &'static str,
    values: Pending,
}

enum Pending {
    /// Vertex pairs and their sharpness.
    Creases(Vec<(i64, i64, f32)>),
    /// Vertices and their sharpness.
    Corners(Vec<(i64, f32)>),
    /// Faces.
    Holes(Vec<i64>),
}

impl Reader {
    /// One logical line, comments removed.
    fn statement(&mut self, line: &str, line_no: usize) -> Result<(), MeshError> {
        let mut tokens = line.split_whitespace();
        let Some(keyword) = tokens.next() else {
            return Ok(());
        };
        let error = |message: String| MeshError::Parse {
            line: line_no,
            message,
        };
        match keyword {
            "v" => {
                let mut p = [0.0f64; 3];
                let mut count = 0usize;
                for token in tokens {
                    let value: f64 = token
                        .parse()
                        .map_err(|_| error(format!("vertex: `{}` is not a number", clip(token))))?;
                    if count < 3 {
                        p[count] = value;
                    }
                    count += 1;
                }
                if count < 3 {
                    return Err(error(format!("vertex: needs 3 coordinates, found {count}")));
                }
                self.vertices.push(p);
            }
            "vt" => {
                let mut t = [0.0f64; 2];
                let mut count = 0usize;
                for token in tokens {
                    let value: f64 = token.parse().map_err(|_| {
                        error(format!(
                            "texture coordinate: `{}` is not a number",
                            clip(token)
                        ))
                    })?;
                    if count < 2 {
                        t[count] = value;
                    }
                    count += 1;
                }
                if count == 0 || count > 3 {
                    return Err(error(format!(
                        "texture coordinate: needs 1 to 3 numbers (u [v [w]]), found {count}"
                    )));
                }
                if !t.iter().all(|c| c.is_finite()) {
                    return Err(error(String::from(
                        "texture coordinate: not a finite number",
                    )));
                }
                self.uvs.push(t);
            }
            "f" => {
                let nv = self.vertices.len() as i64;
                let nt = self.uvs.len() as i64;
                let start = self.corners.len();
                let mut with_uv = 0usize;
                let resolve = |index: i64, count: i64, what: &str| match index {
                    0 => Err(error(format!(
                        "face: {what} index 0 (OBJ indices start at 1)"
                    ))),
                    i if i > 0 => Ok(i - 1),
                    i => Ok(count.saturating_add(i)),
                };
                for token in tokens {
                    let mut parts = token.split('/');
                    let first = parts.next().unwrap_or("");
                    let index = parse_index(first).ok_or_else(|| {
                        error(format!("face: `{}` is not a vertex index", clip(token)))
                    })?;
                    // Normal indices are ignored but must be indices.
                    let mut extra = 0;
                    let mut texture = None;
                    for part in parts {
                        extra += 1;
                        if extra > 2 || (!part.is_empty() && parse_index(part).is_none()) {
                            return Err(error(format!(
                                "face: `{}` is not a corner (i, i/t, i//n or i/t/n)",
                                clip(token)
                            )));
                        }
                        if extra == 1 && !part.is_empty() {
                            texture = parse_index(part);
                        }
                    }
                    let index = if index == 0 {
                        // Kept as the vertex message it always was.
                        return Err(error(String::from(
                            "face: index 0 (OBJ indices start at 1)",
                        )));
                    } else {
                        resolve(index, nv, "vertex")?
                    };
                    self.corners.push(index);
                    if let Some(t) = texture {
                        with_uv += 1;
                        self.uv_corners.push(resolve(t, nt, "texture")?);
                    }
                }
                let corners = self.corners.len() - start;
                if with_uv != 0 && with_uv != corners {
                    return Err(error(String::from(
                        "face: some corners have a texture index (v/vt) and some do not",
                    )));
                }
                let has = with_uv != 0;
                match self.faces_have_uvs {
                    None => self.faces_have_uvs = Some(has),
                    Some(earlier) if earlier != has => {
                        return Err(error(String::from(if has {
                            "face: has texture indices (v/vt) but earlier faces have none"
                        } else {
                            "face: has no texture indices (v/vt) but earlier faces have them"
                        })));
                    }
                    Some(_) => {}
                }
                self.face_ends.push(self.corners.len());
            }
            "t" => self.tag(tokens, line_no).map_err(error)?,
            "o" => {
                let name = line.trim_start()[1..].trim();
                self.objects
                    .push((String::from(name), self.face_ends.len()));
            }
            _ => {}
        }
        Ok(())
    }

    /// A tag line `t NAME nint/nfloat/nstring ints… floats… strings…`
    /// (OpenSubdiv's `Shape::tag::parseTag`), applied as its
    /// `regression/common/far_utils.h` applies it; see the module doc.
    fn tag<'a>(
        &mut self,
        mut tokens: impl Iterator<Item = &'a str>,
        line: usize,
    ) -> Result<(), String> {
        let Some(name) = tokens.next() else {
            return Err(String::from("tag: needs a name and nint/nfloat/nstring"));
        };
        let shown = clip(name);
        let counts = tokens
            .next()
            .ok_or_else(|| format!("tag {shown}: needs nint/nfloat/nstring after the name"))?;
        let bad_counts = || format!("tag {shown}: `{}` is not nint/nfloat/nstring", clip(counts));
        let mut parts = counts.split('/');
        let mut count = || -> Result<usize, String> {
            let part = parts.next().ok_or_else(bad_counts)?;
            if part.is_empty() || !part.bytes().all(|b| b.is_ascii_digit()) {
                return Err(bad_counts());
            }
            part.parse::<usize>().map_err(|_| bad_counts())
        };
        let (ni, nf, ns) = (count()?, count()?, count()?);
        if parts.next().is_some() {
            return Err(bad_counts());
        }
        let values: Vec<&str> = tokens.collect();
        let announced = ni.checked_add(nf).and_then(|n| n.checked_add(ns));
        if announced != Some(values.len()) {
            return Err(format!(
                "tag {shown}: {ni}/{nf}/{ns} announces {} values, the line has {}",
                announced.map_or_else(|| String::from("too many"), |n| format!("{n}")),
                values.len()
            ));
        }
        let mut ints = Vec::with_capacity(ni);
        for token in &values[..ni] {
            ints.push(
                parse_index(token)
                    .ok_or_else(|| format!("tag {shown}: `{}` is not an integer", clip(token)))?,
            );
        }
        let mut floats = Vec::with_capacity(nf);
        for token in &values[ni..ni + nf] {
            let value: f64 = token
                .parse()
                .map_err(|_| format!("tag {shown}: `{}` is not a number", clip(token)))?;
            floats.push(value);
        }
        let strings = &values[ni + nf..];
        let only = |want: (bool, bool, bool), what: &str| -> Result<(), String> {
            let wrong = (ni > 0 && !want.0) || (nf > 0 && !want.1) || (ns > 0 && !want.2);
            if wrong {
                Err(format!("tag {name}: takes {what}, got {ni}/{nf}/{ns}"))
            } else {
                Ok(())
            }
        };
        let sharpness = |s: f64| TagCheck::sharpness(s).map_err(|m| format!("tag {name}: {m}"));
        match name {
            "crease" => {
                only(
                    (true, true, false),
                    "vertex pairs and sharpness (no strings)",
                )?;
                if ni % 2 != 0 {
                    return Err(format!("tag crease: {ni} vertex indices do not make pairs"));
                }
                let edges = ni / 2;
                // far_utils.h: one float for every edge, else edge k (ints
                // 2k, 2k+1) takes float 2k — the float at its first vertex's
                // position. Anything else would make it read past the floats.
                let per_int = edges > 0 && (nf == 2 * edges - 1 || nf == 2 * edges);
                if !(nf == 1 || per_int || (edges == 0 && nf == 0)) {
                    return Err(format!(
                        "tag crease: {nf} sharpness values for {edges} edge(s); OpenSubdiv \
                         reads one for all edges, or edge k's at float 2k (so {} or {})",
                        2 * edges.max(1) - 1,
                        2 * edges.max(1)
                    ));
                }
                let mut list = Vec::with_capacity(edges);
                for k in 0..edges {
                    let s = if nf == 1 { floats[0] } else { floats[2 * k] };
                    list.push((ints[2 * k], ints[2 * k + 1], sharpness(s)?));
                }
                for &s in &floats {
                    sharpness(s)?;
                }
                self.pending.push(PendingTag {
                    line,
                    name: "crease",
                    values: Pending::Creases(list),
                });
            }
            "corner" => {
                only((true, true, false), "vertices and sharpness (no strings)")?;
                // far_utils.h: one float for every vertex, else vertex j takes float j.
                if !(nf == 1 || nf == ni) {
                    return Err(format!(
                        "tag corner: {nf} sharpness values for {ni} vertices; OpenSubdiv \
                         reads one for all vertices or one per vertex"
                    ));
                }
                let mut list = Vec::with_capacity(ni);
                for (j, &v) in ints.iter().enumerate() {
                    let s = if nf == 1 { floats[0] } else { floats[j] };
                    list.push((v, sharpness(s)?));
                }
                for &s in &floats {
                    sharpness(s)?;
                }
                self.pending.push(PendingTag {
                    line,
                    name: "corner",
                    values: Pending::Corners(list),
                });
            }
            "hole" => {
                only((true, false, false), "face indices only")?;
                self.pending.push(PendingTag {
                    line,
                    name: "hole",
                    values: Pending::Holes(ints),
                });
            }
            "interpolateboundary" => {
                only((true, false, false), "one integer")?;
                if ni != 1 {
                    return Err(format!(
                        "tag interpolateboundary: takes one integer, got {ni}"
                    ));
                }
                // The RenderMan numbering, as far_utils.h's GetSdcOptions reads it.
                self.tags.boundary = match ints[0] {
                    0 => BoundaryInterpolation::None,
                    1 => BoundaryInterpolation::EdgeAndCorner,
                    2 => BoundaryInterpolation::EdgeOnly,
                    other => {
                        return Err(format!(
                            "tag interpolateboundary: {other} is not 0 (none), \
                             1 (edge-and-corner) or 2 (edge-only)"
                        ))
                    }
                };
            }
            "creasemethod" => {
                only((false, false, true), "one string")?;
                if ns != 1 {
                    return Err(format!("tag creasemethod: takes one string, got {ns}"));
                }
                self.tags.crease_method = match strings[0] {
                    "normal" => CreaseMethod::Uniform,
                    "chaikin" => CreaseMethod::Chaikin,
                    other => {
                        return Err(format!(
                            "tag creasemethod: `{}` is not `normal` or `chaikin`",
                            clip(other)
                        ))
                    }
                };
            }
            "smoothtriangles" => {
                // far_utils.h reads the string `catmark` or `smooth`; Hbr's
                // older shape files give the integer 0 or 1.
                let rule = match (ni, ns) {
                    (0, 1) => TriangleSubdivision::from_id(strings[0]),
                    (1, 0) => match ints[0] {
                        0 => Some(TriangleSubdivision::Catmark),
                        1 => Some(TriangleSubdivision::Smooth),
                        _ => None,
                    },
                    _ => {
                        return Err(String::from(
                            "tag smoothtriangles: takes one string (catmark or smooth) \
                             or one integer (0 or 1)",
                        ))
                    }
                };
                if !floats.is_empty() {
                    return Err(String::from("tag smoothtriangles: takes no floats"));
                }
                self.tags.triangles = rule.ok_or_else(|| {
                    String::from("tag smoothtriangles: is not `catmark` or `smooth` (0 or 1)")
                })?;
            }
            _ => self.tags.ignored.push((String::from(name), line)),
        }
        Ok(())
    }
}

/// An integer index (optionally signed); `None` if empty or not an integer
/// that fits an `i64`.
fn parse_index(s: &str) -> Option<i64> {
    s.parse::<i64>().ok()
}

/// The token for an error message, shortened to 32 characters.
fn clip(token: &str) -> &str {
    match token.char_indices().nth(32) {
        Some((at, _)) => &token[..at],
        None => token,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;
    use alloc::vec;

    #[test]
    fn objects_are_the_face_ranges_between_o_statements() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no  first one \nf 1 2 3\nf 3 2 1\n\
                    o empty\no last\ng ignored\nf 1 3 2\n";
        let (mesh, objects) = parse_obj_objects(text).unwrap();
        assert_eq!(mesh.faces.len(), 4);
        let got: Vec<(&str, core::ops::Range<usize>)> = objects
            .iter()
            .map(|o| (o.name.as_str(), o.faces.clone()))
            .collect();
        assert_eq!(got, vec![("", 0..1), ("first one", 1..3), ("last", 3..4)]);
        // No `o` statement: no objects.
        let (_, none) = parse_obj_objects("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert!(none.is_empty());
    }

    fn parse_err(text: &str) -> MeshError {
        parse_obj(text).unwrap_err()
    }

    #[test]
    fn obj_lines_name_vertices_and_faces_as_the_file_counts_them() {
        // Comments, a `vn`, a continued face and a blank line in between.
        let text = "# a\nv 0 0 0\nvn 0 0 1\nv 1 0 0\n\nv 0 1 0\nf 1 2 \\\n 3\nf 1 2 4\n";
        let lines = ObjLines::of(text);
        assert_eq!(lines.vertices, vec![2, 4, 6]);
        assert_eq!(lines.faces, vec![7, 9]);
        let e = parse_err(text);
        assert_eq!(
            e.describe(&lines),
            "face 2 (line 9) refers to vertex 4, the mesh has 3 vertices"
        );
        // Without the lines (a JSON mesh): 0-based indices.
        assert_eq!(
            e.to_string(),
            "face 1 refers to vertex 3, the mesh has 3 vertices"
        );
    }

    #[test]
    fn reads_vertices_and_faces_of_every_corner_form() {
        let text = "# a quad and a triangle\n\
                    mtllib x.mtl\no thing\n\
                    v 0 0 0\nv 1 0 0 1.0\nv 1 1 0\nv 0 1 0\n\
                    vt 0 0\nvn 0 0 1\ng group\ns off\nusemtl m\n\
                    f 1 2 3 4\n\
                    f 1 3 4\n\
                    f 1//1 2//1 3//1\n\
                    f 2 3 4\n\
                    l 1 2\np 3\n";
        let m = parse_obj(text).unwrap();
        assert_eq!(m.vertices.len(), 4);
        assert_eq!(m.vertices[1], [1.0, 0.0, 0.0]);
        assert_eq!(
            m.faces,
            vec![
                vec![0, 1, 2, 3],
                vec![0, 2, 3],
                vec![0, 1, 2],
                vec![1, 2, 3]
            ]
        );
    }

    #[test]
    fn texture_indices_become_face_varying_uvs() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
                    vt 0 0\nvt 1 0 0\nvt 1 1\nvt 0.5\nvn 0 0 1\n\
                    f 1/1 2/2 3/3 4/4\n\
                    f 1/1/1 3/3/1 4/-1/1\n";
        let m = parse_obj(text).unwrap();
        assert!(m.has_uvs());
        assert_eq!(m.uvs, vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.5, 0.0]]);
        assert_eq!(m.uv_faces, vec![vec![0, 1, 2, 3], vec![0, 2, 3]]);
        // Without texture indices, no UVs even if `vt` lines are present.
        let plain = parse_obj("vt 0 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert!(!plain.has_uvs() && plain.uv_faces.is_empty());
    }

    #[test]
    fn mixing_faces_with_and_without_texture_indices_names_the_line() {
        let head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n";
        for (faces, line, what) in [
            ("f 1/1 2/1 3/1\nf 1 2 3\n", 6, "has no texture indices"),
            ("f 1 2 3\nf 1/1 2/1 3/1\n", 6, "has texture indices"),
            ("f 1/1 2 3/1\n", 5, "some corners"),
            ("f 1/0 2/1 3/1\n", 5, "texture index 0"),
            ("f 1/x 2/1 3/1\n", 5, "is not a corner"),
        ] {
            let e = parse_err(&format!("{head}{faces}"));
            let MeshError::Parse { line: l, message } = &e else {
                panic!("{e:?}");
            };
            assert_eq!(*l, line, "{faces}");
            assert!(message.contains(what), "{message}");
        }
        for bad in [
            "vt\n",
            "vt 1 2 3 4\n",
            "vt a\n",
            "vt 1e999 0\n",
            "vt nan 0\n",
        ] {
            let e = parse_err(&format!("{head}{bad}"));
            assert!(
                matches!(e, MeshError::Parse { line: 5, .. }),
                "{bad}: {e:?}"
            );
        }
    }

    #[test]
    fn out_of_range_texture_indices_name_the_face() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 1/1 2/2 3/1\n";
        let e = parse_err(text);
        assert_eq!(
            e,
            MeshError::UvOutOfRange {
                face: 1,
                index: 1,
                uvs: 1
            }
        );
        assert_eq!(
            e.describe(&ObjLines::of(text)),
            "face 2 (line 6) refers to texture coordinate 2, the mesh has 1 texture coordinates"
        );
        let e = parse_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/-2 2/1 3/1\n");
        assert!(
            matches!(
                e,
                MeshError::UvOutOfRange {
                    face: 0,
                    index: -1,
                    ..
                }
            ),
            "{e:?}"
        );
    }

    #[test]
    fn negative_indices_are_relative_to_the_vertices_so_far() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 1 1 0\nf -3 -1 -2//-2\n";
        let m = parse_obj(text).unwrap();
        assert_eq!(m.faces, vec![vec![0, 1, 2], vec![1, 3, 2]]);
    }

    #[test]
    fn crlf_tabs_comments_and_continuations() {
        let text = "\u{feff}v\t0 0 0 # origin\r\n\r\n  v 1 \\\r\n 0 0\r\nv 0 1 0\r\n\
                    f 1 2 \\\n3\r\n# end";
        let m = parse_obj(text).unwrap();
        assert_eq!(m.vertices, vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        assert_eq!(m.faces, vec![vec![0, 1, 2]]);
        // A continuation at the very end of the text still counts.
        let m = parse_obj("v 1 2 3 \\").unwrap();
        assert_eq!(m.vertices, vec![[1.0, 2.0, 3.0]]);
        // A backslash in a comment does not swallow the next line.
        let m = parse_obj("# note \\\nv 1 2 3\n").unwrap();
        assert_eq!(m.vertices, vec![[1.0, 2.0, 3.0]]);
    }

    #[test]
    fn any_polygon_size_and_forward_references() {
        let text = "f 1 2 3 4 5 6\nv 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 2 0\nv -1 1 0\n";
        let m = parse_obj(text).unwrap();
        assert_eq!(m.faces, vec![vec![0, 1, 2, 3, 4, 5]]);
    }

    #[test]
    fn non_finite_and_huge_numbers_are_kept() {
        let m = parse_obj("v 1e999 -1e999 1e308\nv nan 0 0\n").unwrap();
        assert_eq!(m.vertices[0][0], f64::INFINITY);
        assert_eq!(m.vertices[0][1], f64::NEG_INFINITY);
        assert_eq!(m.vertices[0][2], 1e308);
        assert!(m.vertices[1][0].is_nan());
    }

    #[test]
    fn syntax_errors_name_the_line() {
        assert!(matches!(
            parse_err("v 0 0 0\nv 1 x 0\n"),
            MeshError::Parse { line: 2, .. }
        ));
        assert!(matches!(
            parse_err("\n\nv 0 0\n"),
            MeshError::Parse { line: 3, .. }
        ));
        assert!(matches!(
            parse_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"),
            MeshError::Parse { line: 4, .. }
        ));
        assert!(matches!(
            parse_err("v 0 0 0\nf 1 a 2\n"),
            MeshError::Parse { line: 2, .. }
        ));
        assert!(matches!(
            parse_err("v 0 0 0\nf 1 /2 1\n"),
            MeshError::Parse { line: 2, .. }
        ));
        assert!(matches!(
            parse_err("v 0 0 0\nf 1/x 1 1\n"),
            MeshError::Parse { line: 2, .. }
        ));
        assert!(matches!(
            parse_err("v 0 0 0\nf 1/1/1/1 1 1\n"),
            MeshError::Parse { line: 2, .. }
        ));
        assert!(matches!(
            parse_err("v 0 0 0\nf 99999999999999999999999 1 1\n"),
            MeshError::Parse { line: 2, .. }
        ));
        // A continued statement reports its first line.
        assert!(matches!(
            parse_err("v 0 0 0\nv 1 \\\n0 q\n"),
            MeshError::Parse { line: 2, .. }
        ));
        // Syntax is checked before indices, whatever comes first.
        assert!(matches!(
            parse_err("v 0 0 0\nf 1 2 3\nv x 0 0\n"),
            MeshError::Parse { line: 3, .. }
        ));
        let e = parse_err("v 0 0 0\nv 1 0 0 bad\n");
        assert_eq!(e.to_string(), "line 2: vertex: `bad` is not a number");
    }

    #[test]
    fn out_of_range_indices_name_face_and_resolved_index() {
        assert_eq!(
            parse_err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n"),
            MeshError::IndexOutOfRange {
                face: 1,
                index: 3,
                vertices: 3
            }
        );
        assert_eq!(
            parse_err("v 0 0 0\nv 1 0 0\nf -3 1 2\nv 0 1 0\n"),
            MeshError::IndexOutOfRange {
                face: 0,
                index: -1,
                vertices: 3
            }
        );
        assert_eq!(
            parse_err("v 0 0 0\nf 1 -9223372036854775808 1\n"),
            MeshError::IndexOutOfRange {
                face: 0,
                index: i64::MIN + 1,
                vertices: 1
            }
        );
        assert_eq!(
            parse_err("v 0 0 0\nf 1 9223372036854775807 1\n"),
            MeshError::IndexOutOfRange {
                face: 0,
                index: i64::MAX - 1,
                vertices: 1
            }
        );
    }

    #[test]
    fn empty_and_degenerate_inputs_are_not_errors_here() {
        assert_eq!(parse_obj("").unwrap(), MeshInput::default());
        assert_eq!(parse_obj("\\").unwrap(), MeshInput::default());
        let m = parse_obj("v 0 0 0\nf\nf 1\n").unwrap();
        assert_eq!(m.faces, vec![vec![], vec![0]]);
    }

    #[test]
    fn json_is_recognised_by_its_first_character() {
        assert!(looks_like_json("  \n\t{\"vertices\": []}"));
        assert!(looks_like_json("\u{feff}{}"));
        assert!(!looks_like_json("v 0 0 0\n"));
        assert!(!looks_like_json("# {\n"));
        assert!(!looks_like_json(""));
    }

    /// A 2×1 grid of quads: vertices 0 1 2 / 3 4 5, faces 0 and 1.
    const STRIP: &str = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n\
                         f 1 2 5 4\nf 2 3 6 5\n";

    fn with_tags(tags: &str) -> Result<MeshInput, MeshError> {
        parse_obj(&format!("{STRIP}{tags}"))
    }

    /// The 1-based line of a tag appended to [`STRIP`] as its `k`-th line.
    fn tag_line(k: usize) -> usize {
        STRIP.lines().count() + k
    }

    fn crease(a: u32, b: u32, sharpness: f32) -> EdgeCrease {
        EdgeCrease {
            vertices: [a, b],
            sharpness,
        }
    }

    #[test]
    fn no_tags_means_default_tags() {
        let m = with_tags("").unwrap();
        assert_eq!(m.tags, SubdivTags::default());
        assert!(m.tags.is_plain());
    }

    #[test]
    fn crease_tags_pair_vertices_with_one_or_every_other_float() {
        // One float for every pair.
        let m = with_tags("t crease 4/1/0 0 1 1 4 2.5\n").unwrap();
        assert_eq!(m.tags.creases, vec![crease(0, 1, 2.5), crease(1, 4, 2.5)]);
        // Indices are 0-based: `1 4` is the edge between the 2nd and 5th `v`.
        assert_eq!(m.vertices[4], [1.0, 1.0, 0.0]);
        // Per edge: edge k's sharpness is float 2k (far_utils.h's indexing).
        let m = with_tags("t crease 4/3/0 0 1 4 5 1.0 9.0 3.0\n").unwrap();
        assert_eq!(m.tags.creases, vec![crease(0, 1, 1.0), crease(4, 5, 3.0)]);
        let m = with_tags("t crease 4/4/0 0 1 4 5 1.0 9.0 3.0 9.0\n").unwrap();
        assert_eq!(m.tags.creases, vec![crease(0, 1, 1.0), crease(4, 5, 3.0)]);
        // One edge, two floats: the first.
        let m = with_tags("t crease 2/2/0 2 1 0.5 7\n").unwrap();
        assert_eq!(m.tags.creases, vec![crease(2, 1, 0.5)]);
        // Several lines accumulate; the order is kept; 10 and ∞ are accepted.
        let m = with_tags("t crease 2/1/0 0 3 10\nt crease 2/1/0 3 0 1e999\n").unwrap();
        assert_eq!(
            m.tags.creases,
            vec![crease(0, 3, 10.0), crease(3, 0, f32::INFINITY)]
        );
        // Zero pairs: nothing.
        assert!(with_tags("t crease 0/1/0 1\n")
            .unwrap()
            .tags
            .creases
            .is_empty());
        // Tags may come before the vertices and faces they name.
        let m = parse_obj(&format!("t crease 2/1/0 0 1 4\n{STRIP}")).unwrap();
        assert_eq!(m.tags.creases, vec![crease(0, 1, 4.0)]);
    }

    #[test]
    fn corner_hole_boundary_and_creasemethod_tags() {
        let m = with_tags(
            "t corner 2/1/0 0 5 3\n\
             t corner 2/2/0 2 3 1.5 0\n\
             t hole 1/0/0 1\n\
             t interpolateboundary 1/0/0 2\n\
             t creasemethod 0/0/1 chaikin\n",
        )
        .unwrap();
        let corner = |vertex, sharpness| VertexCorner { vertex, sharpness };
        assert_eq!(
            m.tags.corners,
            vec![
                corner(0, 3.0),
                corner(5, 3.0),
                corner(2, 1.5),
                corner(3, 0.0)
            ]
        );
        assert_eq!(m.tags.holes, vec![1]);
        assert_eq!(m.tags.boundary, BoundaryInterpolation::EdgeOnly);
        assert_eq!(m.tags.crease_method, CreaseMethod::Chaikin);
        assert!(m.tags.ignored.is_empty());
        let boundary = |n: u32| {
            with_tags(&format!("t interpolateboundary 1/0/0 {n}\n"))
                .unwrap()
                .tags
                .boundary
        };
        assert_eq!(boundary(0), BoundaryInterpolation::None);
        assert_eq!(boundary(1), BoundaryInterpolation::EdgeAndCorner);
        assert_eq!(boundary(2), BoundaryInterpolation::EdgeOnly);
        // The last one wins.
        let m = with_tags(
            "t interpolateboundary 1/0/0 0\nt interpolateboundary 1/0/0 1\n\
             t creasemethod 0/0/1 chaikin\nt creasemethod 0/0/1 normal\n",
        )
        .unwrap();
        assert_eq!(m.tags.boundary, BoundaryInterpolation::EdgeAndCorner);
        assert_eq!(m.tags.crease_method, CreaseMethod::Uniform);
    }

    #[test]
    fn smoothtriangles_tag_in_far_and_hbr_forms() {
        let m = with_tags("t smoothtriangles 0/0/1 smooth\n").unwrap();
        assert_eq!(m.tags.triangles, TriangleSubdivision::Smooth);
        assert!(!m.tags.is_plain());
        let m = with_tags("t smoothtriangles 1/0/0 1\nt smoothtriangles 0/0/1 catmark\n").unwrap();
        assert_eq!(m.tags.triangles, TriangleSubdivision::Catmark);
        assert!(m.tags.is_plain());
        let m = with_tags("t smoothtriangles 1/0/0 1\n").unwrap();
        assert_eq!(m.tags.triangles, TriangleSubdivision::Smooth);
        assert!(m.tags.ignored.is_empty());
        for bad in [
            "t smoothtriangles 0/0/1 loop\n",
            "t smoothtriangles 1/0/0 2\n",
            "t smoothtriangles 0/0/0\n",
            "t smoothtriangles 0/1/0 1\n",
        ] {
            let e = with_tags(bad).unwrap_err().to_string();
            assert!(e.contains("smoothtriangles"), "{bad}: {e}");
        }
    }

    #[test]
    fn tags_not_applied_are_listed_with_their_line() {
        let m = with_tags(
            "t facevaryinginterpolateboundary 1/0/0 1\n\
             # a comment line\n\
             t facevaryingpropagatecorners 1/0/0 1\n\
             t vertexedit 3/2/2 1 2 3 0.5 1 value set\n\
             t\tsomethingnew 0/0/0\n",
        )
        .unwrap();
        assert_eq!(
            m.tags.ignored,
            vec![
                ("facevaryinginterpolateboundary".to_string(), tag_line(1)),
                ("facevaryingpropagatecorners".to_string(), tag_line(3)),
                ("vertexedit".to_string(), tag_line(4)),
                ("somethingnew".to_string(), tag_line(5)),
            ]
        );
        assert!(m.tags.is_plain());
    }

    #[test]
    fn malformed_tags_name_their_line() {
        let cases: &[(&str, &str)] = &[
            ("t", "needs a name"),
            ("t crease", "needs nint/nfloat/nstring"),
            ("t crease 2/1 0 1 2", "is not nint/nfloat/nstring"),
            ("t crease 2/1/0/0 0 1 2", "is not nint/nfloat/nstring"),
            ("t crease 2/-1/0 0 1 2", "is not nint/nfloat/nstring"),
            ("t crease a/1/0 0 1 2", "is not nint/nfloat/nstring"),
            ("t crease 2/1/0 0 1", "announces 3 values, the line has 2"),
            (
                "t crease 2/1/0 0 1 2 3",
                "announces 3 values, the line has 4",
            ),
            (
                "t crease 99999999999999999999/0/0 1",
                "is not nint/nfloat/nstring",
            ),
            (
                "t crease 18446744073709551615/1/0 1",
                "announces too many values",
            ),
            ("t crease 2/1/0 0 x 2", "`x` is not an integer"),
            ("t crease 2/1/0 0 1.5 2", "`1.5` is not an integer"),
            ("t crease 2/1/0 0 1 sharp", "`sharp` is not a number"),
            ("t crease 2/1/0 0 1 -1", "sharpness -1 is negative"),
            ("t crease 2/1/0 0 1 nan", "sharpness is NaN"),
            ("t crease 3/1/0 0 1 2 2", "do not make pairs"),
            ("t crease 2/0/0 0 1", "0 sharpness values for 1 edge(s)"),
            (
                "t crease 4/2/0 0 1 1 2 1 2",
                "2 sharpness values for 2 edge(s)",
            ),
            ("t crease 2/1/1 0 1 2 x", "takes vertex pairs and sharpness"),
            ("t corner 2/0/0 0 1", "0 sharpness values for 2 vertices"),
            (
                "t corner 3/2/0 0 1 2 1 1",
                "2 sharpness values for 3 vertices",
            ),
            ("t corner 1/1/0 0 -2", "sharpness -2 is negative"),
            ("t hole 1/1/0 0 1", "takes face indices only"),
            ("t interpolateboundary 1/0/0 3", "3 is not 0 (none)"),
            (
                "t interpolateboundary 2/0/0 1 1",
                "takes one integer, got 2",
            ),
            ("t interpolateboundary 0/0/0", "takes one integer, got 0"),
            ("t interpolateboundary 0/0/1 edge", "takes one integer"),
            (
                "t creasemethod 0/0/1 smooth",
                "`smooth` is not `normal` or `chaikin`",
            ),
            ("t creasemethod 0/0/0", "takes one string, got 0"),
            (
                "t creasemethod 0/0/2 normal chaikin",
                "takes one string, got 2",
            ),
            ("t creasemethod 1/0/1 1 normal", "takes one string"),
            // Unknown names are still syntax-checked.
            (
                "t smoothtriangles 0/0/1",
                "announces 1 values, the line has 0",
            ),
            // Indices, checked once the whole mesh is read.
            (
                "t crease 2/1/0 0 6 1",
                "tag crease: vertex 6 out of range (6 vertices)",
            ),
            ("t crease 2/1/0 -1 0 1", "vertex -1 out of range"),
            (
                "t crease 2/1/0 0 4 1",
                "vertices 0 and 4 are not joined by an edge",
            ),
            ("t crease 2/1/0 1 1 1", "vertices 1 and 1 are not joined"),
            ("t corner 1/1/0 6 1", "tag corner: vertex 6 out of range"),
            ("t corner 1/1/0 -1 1", "vertex -1 out of range"),
            ("t hole 1/0/0 2", "tag hole: face 2 out of range (2 faces)"),
            ("t hole 1/0/0 -1", "face -1 out of range"),
        ];
        for (tag, needle) in cases {
            // The bad tag is the second tag line, after a good one.
            let text = format!("{STRIP}t corner 1/1/0 0 1\n{tag}\n");
            let line = tag_line(2);
            match parse_obj(&text) {
                Err(MeshError::Parse { line: l, message }) => {
                    assert_eq!(l, line, "{tag}: {message}");
                    assert!(
                        message.contains(needle),
                        "{tag}: `{message}` lacks `{needle}`"
                    );
                }
                other => panic!("{tag}: {other:?}"),
            }
        }
        // The first bad tag line is named, in line order, also for index errors.
        let e = with_tags("t hole 1/0/0 0\nt hole 1/0/0 5\nt corner 1/1/0 9 1\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            format!(
                "line {}: tag hole: face 5 out of range (2 faces)",
                tag_line(2)
            )
        );
        // Syntax errors anywhere come before tag index errors.
        let e = with_tags("t hole 1/0/0 5\nv 1 x 0\n").unwrap_err();
        assert!(matches!(e, MeshError::Parse { line, .. } if line == tag_line(2)));
        // A continued tag line reports its first line.
        let e = with_tags("t crease 2/1/0 \\\n 0 1 -3\n").unwrap_err();
        assert!(matches!(e, MeshError::Parse { line, .. } if line == tag_line(1)));
        // Face index errors come before tag index errors.
        let e = with_tags("t hole 1/0/0 5\nf 1 2 99\n").unwrap_err();
        assert!(matches!(e, MeshError::IndexOutOfRange { face: 2, .. }));
    }

    #[test]
    fn arbitrary_bytes_never_panic() {
        // A small deterministic fuzz: random mixes of OBJ-ish fragments.
        let pieces = [
            "v",
            "f",
            " ",
            "\t",
            "\n",
            "\r\n",
            "\\",
            "#",
            "/",
            "//",
            "-",
            "1",
            "0",
            "2",
            "-1",
            "1e999",
            "nan",
            "x",
            "é",
            "\u{feff}",
            "3.5",
            "+",
            "vt",
            "99999999999999999999",
            "t",
            "crease",
            "corner",
            "hole",
            "2/1/0",
            "1/0/0",
            "0/0/1",
            "chaikin",
        ];
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..3000 {
            let mut text = String::new();
            for _ in 0..(state % 40) {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                text.push_str(pieces[(state % pieces.len() as u64) as usize]);
            }
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let _ = parse_obj(&text);
            let _ = looks_like_json(&text);
        }
    }
}
