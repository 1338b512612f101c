//! Wavefront OBJ reader: vertex positions and polygon faces, nothing else.
//!
//! Read: `v x y z [w …]` (only `x y z` kept; further numbers — a `w`, or the
//! `r g b` some tools append — must be numbers and are ignored) and
//! `f a b c …` with corners written `i`, `i/t`, `i//n` or `i/t/n`, 1-based or
//! negative (relative to the vertices read so far, `-1` being the last), any
//! polygon size. Lines may end in `\r\n`; `#` starts a comment; a line ending
//! in `\` continues on the next one. Every other statement (`vt`, `vn`, `vp`,
//! `o`, `g`, `s`, `usemtl`, `mtllib`, `l`, `p`, …) is ignored.
//!
//! Checked here, in this order: the syntax of the whole text
//! ([`MeshError::Parse`], first offending line), then the vertex indices
//! ([`MeshError::IndexOutOfRange`], first offending face and corner; a
//! positive index may refer to a vertex defined later in the file). Not
//! checked here: finiteness (`1e999` reads as ∞ and is kept; the topology
//! reports [`MeshError::NonFinite`]), face sizes, repeated vertices,
//! manifoldness — all [`crate::Topology::new`]'s job. No input makes the
//! reader panic.

use crate::error::MeshError;
use crate::input::MeshInput;
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

/// Reads the vertices and faces of a Wavefront OBJ text; indices become
/// 0-based. See the module doc for what is read, ignored and checked.
pub fn parse_obj(text: &str) -> Result<MeshInput, MeshError> {
    let mut vertices: Vec<[f64; 3]> = Vec::new();
    // Resolved 0-based indices, possibly out of range; checked at the end.
    let mut corners: Vec<i64> = Vec::new();
    let mut face_ends: Vec<usize> = Vec::new();
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
        statement(
            line,
            statement_line,
            &mut vertices,
            &mut corners,
            &mut face_ends,
        )?;
    }
    if continuing {
        // The text ended on a continuation: the statement is what was read.
        let line = core::mem::take(&mut joined);
        statement(
            &line,
            statement_line,
            &mut vertices,
            &mut corners,
            &mut face_ends,
        )?;
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
    Ok(MeshInput::new(vertices, faces))
}

/// One logical line, comments removed.
fn statement(
    line: &str,
    line_no: usize,
    vertices: &mut Vec<[f64; 3]>,
    corners: &mut Vec<i64>,
    face_ends: &mut Vec<usize>,
) -> Result<(), MeshError> {
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
            vertices.push(p);
        }
        "f" => {
            let nv = vertices.len() as i64;
            for token in tokens {
                let mut parts = token.split('/');
                let first = parts.next().unwrap_or("");
                let index = parse_index(first).ok_or_else(|| {
                    error(format!("face: `{}` is not a vertex index", clip(token)))
                })?;
                // Texture and normal indices are ignored but must be indices.
                let mut extra = 0;
                for part in parts {
                    extra += 1;
                    if extra > 2 || (!part.is_empty() && parse_index(part).is_none()) {
                        return Err(error(format!(
                            "face: `{}` is not a corner (i, i/t, i//n or i/t/n)",
                            clip(token)
                        )));
                    }
                }
                let resolved = match index {
                    0 => {
                        return Err(error(String::from(
                            "face: index 0 (OBJ indices start at 1)",
                        )))
                    }
                    i if i > 0 => i - 1,
                    i => nv.saturating_add(i),
                };
                corners.push(resolved);
            }
            face_ends.push(corners.len());
        }
        _ => {}
    }
    Ok(())
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

    fn parse_err(text: &str) -> MeshError {
        parse_obj(text).unwrap_err()
    }

    #[test]
    fn reads_vertices_and_faces_of_every_corner_form() {
        let text = "# a quad and a triangle\n\
                    mtllib x.mtl\no thing\n\
                    v 0 0 0\nv 1 0 0 1.0\nv 1 1 0\nv 0 1 0\n\
                    vt 0 0\nvn 0 0 1\ng group\ns off\nusemtl m\n\
                    f 1 2 3 4\n\
                    f 1/1 3/1 4/1\n\
                    f 1//1 2//1 3//1\n\
                    f 2/1/1 3/1/1 4/1/1\n\
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
    fn negative_indices_are_relative_to_the_vertices_so_far() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 1 1 0\nf -3/-1 -1 -2//-2\n";
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
