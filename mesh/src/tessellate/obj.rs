//! Wavefront OBJ text of a [`Tessellation`].

use super::Tessellation;
use alloc::string::String;
use capdiv::Real;
use core::fmt::{Display, LowerExp, Write};

/// OBJ text: `header` lines as `#` comments, then one `v x y z` and one
/// `vn x y z` line per vertex, then one `f a//a b//b c//c[ d//d]` line per
/// face (1-based, counter-clockwise about the normals, tags not written).
/// With texture coordinates ([`Tessellation::uvs`]), a `vt u v` line follows
/// each vertex's `vn` and faces are written `f a/a/a b/b/b …`.
/// Numbers as [`write_number`]: every digit needed to read them back
/// exactly, no more.
pub fn write_obj<R: Real + Display + LowerExp>(t: &Tessellation<R>, header: &[String]) -> String {
    let mut text = String::with_capacity(t.positions.len() * 96 + t.faces.len() * 40);
    for line in header {
        let _ = writeln!(text, "# {line}");
    }
    let with_uv = !t.uvs.is_empty();
    for (k, (p, n)) in t.positions.iter().zip(&t.normals).enumerate() {
        write_point(&mut text, "v", p.0);
        write_point(&mut text, "vn", n.0);
        if with_uv {
            let uv = t.uvs.get(k).copied().unwrap_or([0.0; 2]);
            text.push_str("vt");
            for x in uv {
                text.push(' ');
                write_number(&mut text, x);
            }
            text.push('\n');
        }
    }
    for f in &t.faces {
        text.push('f');
        for &i in f.corners() {
            let i = i as u64 + 1;
            if with_uv {
                let _ = write!(text, " {i}/{i}/{i}");
            } else {
                let _ = write!(text, " {i}//{i}");
            }
        }
        text.push('\n');
    }
    text
}

/// `keyword x y z` and a newline, each number by [`write_number`].
pub fn write_point<R: Real + Display + LowerExp>(text: &mut String, keyword: &str, p: [R; 3]) {
    text.push_str(keyword);
    for x in p {
        text.push(' ');
        write_number(text, x);
    }
    text.push('\n');
}

/// Appends `x` in Rust's positional form (`{}`), or in its exponent form
/// (`{:e}`) when the positional one is longer than 8 characters and the
/// exponent one is shorter (so `100000` and `0.0001` stay positional). Both
/// print the shortest digit string that reads back as
/// the same `f32`/`f64`, so the choice changes only the notation, never the
/// value: `-4.6053215007904947e-14` instead of
/// `-0.000000000000046053215007904947`, `0.25` instead of `2.5e-1`. Every
/// OBJ reader that parses numbers with `strtod` (or Rust's `parse`) reads
/// both.
///
/// For `1e-3 ≤ |x| < 1e7` the exponent form is not formatted at all: it is
/// never chosen there. A positional form longer than 8 characters then has
/// a fractional part (an integer below 1e7 takes at most sign and 7
/// digits), so it is the `n` significant digits, one point and at most
/// `0.00` before them; the exponent form has the same digits, a point
/// unless `n = 1`, and at least `e-` or `e` and one exponent digit, never
/// fewer characters.
pub fn write_number<R: Real + Display + LowerExp>(text: &mut String, x: R) {
    let start = text.len();
    let _ = write!(text, "{x}");
    let positional = text.len() - start;
    let a = x.to_f64().abs();
    if positional > 8 && !(1e-3..1e7).contains(&a) {
        // Written right after the positional form (no temporary string),
        // then the longer of the two removed.
        let mid = text.len();
        let _ = write!(text, "{x:e}");
        if text.len() - mid < positional {
            text.replace_range(start..mid, "");
        } else {
            text.truncate(mid);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::write_number;
    use alloc::string::String;
    use capdiv::Real;
    use core::fmt::Write;

    fn number<R: Real + core::fmt::Display + core::fmt::LowerExp>(x: R) -> String {
        let mut s = String::new();
        write_number(&mut s, x);
        s
    }

    #[test]
    fn numbers_read_back_exactly_and_stay_short() {
        assert_eq!(
            number(-4.6053215007904947e-14f64),
            "-4.6053215007904947e-14"
        );
        assert_eq!(number(0.25f64), "0.25");
        assert_eq!(number(100000.0f64), "100000");
        assert_eq!(number(0.0001f64), "0.0001");
        assert_eq!(number(-0.0f64), "-0");
        assert_eq!(number(1e-7f32), "1e-7");
        // A sweep over the exponent range: bit-identical round trip, and
        // never longer than sign + 17 digits + point + `e-308` (24).
        let mut x = 1.234_567_890_123_456_7e-300f64;
        while x < 1e300 {
            for v in [x, -x, x * 0.999_999_999_999_9] {
                let s = number(v);
                assert_eq!(s.parse::<f64>().unwrap().to_bits(), v.to_bits(), "{s}");
                assert!(s.len() <= 24, "{s}");
            }
            let f = x as f32;
            if f.is_finite() && f != 0.0 {
                let s = number(f);
                assert_eq!(s.parse::<f32>().unwrap().to_bits(), f.to_bits(), "{s}");
                assert!(s.len() <= 15, "{s}");
            }
            x *= 7.77;
        }
    }

    /// The notation rule itself, both forms formatted: positional unless it
    /// is longer than 8 characters and the exponent form is shorter.
    fn by_the_rule<R: core::fmt::Display + core::fmt::LowerExp + Copy>(x: R) -> String {
        let (mut p, mut e) = (String::new(), String::new());
        let _ = write!(p, "{x}");
        let _ = write!(e, "{x:e}");
        if p.len() > 8 && e.len() < p.len() {
            e
        } else {
            p
        }
    }

    #[test]
    fn skipping_the_exponent_form_between_1e_minus_3_and_1e7_changes_nothing() {
        // Around both ends of the skipped range and across it, with many
        // and few digits, both signs, in f64 and f32.
        let mut values = alloc::vec::Vec::new();
        for base in [1e-3, 1e7, 1e8, 1.0, 0.01, 0.1, 1e6, 123456.0] {
            for k in -3i32..=3 {
                let b: f64 = base;
                values.push(b * (1.0 + f64::from(k) * f64::EPSILON));
                values.push(b * (1.0 + f64::from(k) * 1e-9));
            }
        }
        let mut x = 1.234_567_890_123_456_7e-6f64;
        while x < 1e11 {
            values.extend([
                x,
                x * 0.999_999_999_999_9,
                x.round(),
                (x * 1e3).round() / 1e3,
            ]);
            x *= 1.37;
        }
        for v in values {
            for v in [v, -v] {
                assert_eq!(number(v), by_the_rule(v), "{v:e}");
                let f = v as f32;
                assert_eq!(number(f), by_the_rule(f), "{f:e}");
            }
        }
    }
}
