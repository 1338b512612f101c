//! JSON text: serde_json's compact form, re-indented for `--pretty`
//! ([`Indent`]), into buffers that grow fallibly ([`TryBytes`]), of lists
//! serialised as they are made ([`Lazy`]) instead of collected first. The
//! patch lists of `surface` and `patches`, the largest JSON the CLI
//! writes, take their text and nothing more this way, and a refused
//! allocation is an [`OutOfMemory`] error.

use capdiv_mesh::{mem, OutOfMemory};
use serde::{Serialize, Serializer};

/// Serialises `value` as JSON, compact or pretty, with a final newline
/// (aborting, as a `Vec` does, when the text cannot be allocated: for
/// outputs of bounded size, a pole's jet, a spectrum, a summary).
pub fn to_json<T: Serialize>(value: &T, pretty: bool) -> Vec<u8> {
    mem::or_abort(try_to_json(value, pretty))
}

/// [`to_json`], or the error when its text cannot be allocated.
pub fn try_to_json<T: Serialize>(value: &T, pretty: bool) -> Result<Vec<u8>, OutOfMemory> {
    let mut compact = TryBytes::default();
    // Cannot fail but for the buffer: the output types are plain structs of
    // numbers and strings.
    let _ = serde_json::to_writer(&mut compact, value);
    let mut out = compact.into_result()?;
    if pretty {
        let mut text = Vec::new();
        Indent::default().feed(&out, &mut text)?;
        out = text;
    }
    mem::push(&mut out, b'\n')?;
    Ok(out)
}

/// An `io::Write` into memory whose buffer grows through
/// [`capdiv_mesh::mem`] (doubling, as a `Vec` does): a write the system
/// cannot make room for fails (`ErrorKind::OutOfMemory`), and the first
/// refusal is kept.
#[derive(Debug, Default)]
pub struct TryBytes {
    bytes: Vec<u8>,
    refused: Option<OutOfMemory>,
}

impl TryBytes {
    /// An empty buffer with room for `capacity` bytes.
    pub fn with_capacity(capacity: usize) -> Result<Self, OutOfMemory> {
        Ok(TryBytes {
            bytes: mem::with_capacity(capacity)?,
            refused: None,
        })
    }

    /// Room for `additional` more bytes, or the refusal as an I/O error.
    #[inline(never)]
    fn grow(&mut self, additional: usize) -> std::io::Result<()> {
        mem::reserve(&mut self.bytes, additional).map_err(|e| {
            self.refused.get_or_insert(e);
            std::io::Error::new(std::io::ErrorKind::OutOfMemory, e.message())
        })
    }

    /// The bytes written so far.
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes
    }

    /// Empties the buffer, keeping its room (and any refusal).
    pub fn clear(&mut self) {
        self.bytes.clear();
    }

    /// The first refusal, if any.
    pub fn refused(&self) -> Option<OutOfMemory> {
        self.refused
    }

    /// The bytes written, or the first refusal.
    pub fn into_result(self) -> Result<Vec<u8>, OutOfMemory> {
        match self.refused {
            Some(e) => Err(e),
            None => Ok(self.bytes),
        }
    }
}

impl std::io::Write for TryBytes {
    #[inline]
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.bytes.capacity() - self.bytes.len() < buf.len() {
            self.grow(buf.len())?;
        }
        self.bytes.extend_from_slice(buf);
        Ok(buf.len())
    }
    #[inline]
    fn write_all(&mut self, buf: &[u8]) -> std::io::Result<()> {
        self.write(buf).map(|_| ())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// A JSON array of the items `make()` yields, serialised as they are made:
/// no list of them is built.
pub struct Lazy<F>(pub F);

impl<F, I> Serialize for Lazy<F>
where
    F: Fn() -> I,
    I: IntoIterator,
    I::Item: Serialize,
{
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq((self.0)())
    }
}

/// Re-indents compact JSON (serde_json's), two spaces a level, keeping
/// arrays that hold no array or object on one line (a point stays
/// `[x, y, z]`). Works on the text, so numbers keep serde_json's shortest
/// round-trip form (also for `f32`).
///
/// The nesting is kept between calls of [`Indent::feed`]: a document fed
/// in pieces that each end after a complete value, or after the `[`/`{`
/// opening a non-empty container whose first value follows in the same
/// piece, comes out as it does fed whole. A streamed surface is fed that
/// way (`{"patches":[` with the first patch, then `,` and a patch, …).
#[derive(Clone, Debug, Default)]
pub struct Indent {
    depth: usize,
    /// Nesting of open containers: `true` when printed on one line.
    inline: Vec<bool>,
}

/// Where [`Indent`] writes: a buffer that grows fallibly (doubling, as a
/// `Vec` does); after a refusal, kept in `refused`, nothing more is
/// written.
struct Text<'a> {
    out: &'a mut Vec<u8>,
    refused: Option<OutOfMemory>,
}

impl Text<'_> {
    /// Whether there is room for `n` more bytes (made if needed).
    #[inline]
    fn room(&mut self, n: usize) -> bool {
        if self.out.capacity() - self.out.len() >= n {
            return true;
        }
        if self.refused.is_none() {
            match mem::reserve(self.out, n) {
                Ok(()) => return true,
                Err(e) => self.refused = Some(e),
            }
        }
        false
    }
    #[inline]
    fn byte(&mut self, b: u8) {
        if self.room(1) {
            self.out.push(b);
        }
    }
    #[inline]
    fn bytes(&mut self, s: &[u8]) {
        if self.room(s.len()) {
            self.out.extend_from_slice(s);
        }
    }
    fn newline(&mut self, depth: usize) {
        if self.room(1 + 2 * depth) {
            self.out.push(b'\n');
            self.out.extend(std::iter::repeat_n(b' ', 2 * depth));
        }
    }
}

impl Indent {
    /// Appends `compact` re-indented to `out`, or the error when `out`
    /// cannot grow: `out` is then left as it was, and the nesting is lost
    /// (the document cannot be continued).
    pub fn feed(&mut self, compact: &[u8], out: &mut Vec<u8>) -> Result<(), OutOfMemory> {
        let start = out.len();
        let mut text = Text { out, refused: None };
        self.write(compact, &mut text);
        match text.refused {
            None => Ok(()),
            Some(e) => {
                out.truncate(start);
                Err(e)
            }
        }
    }

    fn write(&mut self, compact: &[u8], out: &mut Text<'_>) {
        let mut i = 0;
        while i < compact.len() {
            let c = compact[i];
            match c {
                b'"' => {
                    // Copy a string literal verbatim, escapes included.
                    let start = i;
                    i += 1;
                    while i < compact.len() && compact[i] != b'"' {
                        i += if compact[i] == b'\\' { 2 } else { 1 };
                    }
                    out.bytes(&compact[start..(i + 1).min(compact.len())]);
                }
                b'[' | b'{' => {
                    let close = if c == b'[' { b']' } else { b'}' };
                    let flat = c == b'[' && is_flat(&compact[i + 1..]);
                    let empty = compact.get(i + 1) == Some(&close);
                    out.byte(c);
                    self.inline.push(flat || empty);
                    self.depth += 1;
                    if !(flat || empty) {
                        out.newline(self.depth);
                    }
                }
                b']' | b'}' => {
                    self.depth = self.depth.saturating_sub(1);
                    if !self.inline.pop().unwrap_or(true) {
                        out.newline(self.depth);
                    }
                    out.byte(c);
                }
                b',' => {
                    out.byte(b',');
                    if self.inline.last().copied().unwrap_or(false) {
                        out.byte(b' ');
                    } else {
                        out.newline(self.depth);
                    }
                }
                b':' => out.bytes(b": "),
                _ => out.byte(c),
            }
            i += 1;
        }
    }
}

/// [`Indent`] of a whole document.
pub fn indent(compact: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    mem::or_abort(Indent::default().feed(compact, &mut out));
    out
}

/// `true` when the array whose body starts at `rest` closes before any `[`,
/// `{` or string opens.
fn is_flat(rest: &[u8]) -> bool {
    for &c in rest {
        match c {
            b']' => return true,
            b'[' | b'{' | b'"' => return false,
            _ => {}
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::{indent, try_to_json, Indent, Lazy};
    use serde_json::{json, Value};

    #[test]
    fn indent_keeps_the_value_and_puts_points_on_one_line() {
        let v = json!({
            "kind": "po[la]r \"q\" {x}",
            "pole": [0.1, -2e-30, 3.0],
            "links": [[[1, 2, 3], [4, 5, 6]], []],
            "empty": {},
            "n": 1.5
        });
        let compact = serde_json::to_vec(&v).unwrap();
        let pretty = indent(&compact);
        let text = String::from_utf8(pretty.clone()).unwrap();
        let back: Value = serde_json::from_slice(&pretty).unwrap();
        assert_eq!(back, v);
        assert!(text.contains("\"pole\": [0.1, -2e-30, 3.0]"), "{text}");
        assert!(
            text.contains("      [1, 2, 3],\n      [4, 5, 6]\n"),
            "{text}"
        );
        assert!(text.contains("\"empty\": {}"), "{text}");
    }

    #[test]
    fn a_document_fed_in_the_streams_pieces_is_indented_as_whole() {
        // The pieces a streamed surface writes: the opening with the first
        // patch, each further patch after its comma, the tail.
        let patch = |k: u32| json!({"kind": "eg", "level": k, "points": [[k, 1], [2, 3]]});
        let pieces: Vec<Vec<u8>> = vec![
            [
                &b"{\"patches\":["[..],
                &serde_json::to_vec(&patch(0)).unwrap(),
            ]
            .concat(),
            [&b","[..], &serde_json::to_vec(&patch(1)).unwrap()].concat(),
            [&b","[..], &serde_json::to_vec(&patch(2)).unwrap()].concat(),
            br#"],"caps":[{"n":5,"rings":[]}],"summary":{"depth":[3,4],"x":{}}}"#.to_vec(),
        ];
        let whole = indent(&pieces.concat());
        let mut fed = Vec::new();
        let mut state = Indent::default();
        for piece in &pieces {
            let mut text = Vec::new();
            state.feed(piece, &mut text).unwrap();
            fed.extend_from_slice(&text);
        }
        assert_eq!(
            String::from_utf8(fed).unwrap(),
            String::from_utf8(whole).unwrap()
        );
    }

    #[test]
    fn a_lazy_list_is_the_collected_lists_json() {
        let items = [1.5, -2.0, 3.25];
        let lazy = Lazy(|| items.iter().map(|x| x * 2.0));
        let list: Vec<f64> = items.iter().map(|x| x * 2.0).collect();
        for pretty in [false, true] {
            assert_eq!(
                try_to_json(&json!({"a": lazy_value(&lazy)}), pretty).unwrap(),
                try_to_json(&json!({"a": list}), pretty).unwrap()
            );
        }
    }

    fn lazy_value<T: serde::Serialize>(v: &T) -> Value {
        serde_json::to_value(v).unwrap()
    }
}
