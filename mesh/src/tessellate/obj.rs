//! Wavefront OBJ text of a [`Tessellation`].

use super::Tessellation;
use crate::mem::{reserve_str, OutOfMemory};
use alloc::string::String;
use capdiv::Real;
use core::any::Any;
use core::fmt::{Display, LowerExp, Write};

/// OBJ text: `header` lines as `#` comments, then one `v x y z` and one
/// `vn x y z` line per vertex, then one `f a//a b//b c//c[ d//d]` line per
/// face (1-based, counter-clockwise about the normals, tags not written).
/// With texture coordinates ([`Tessellation::uvs`]), a `vt u v` line follows
/// each vertex's `vn` and faces are written `f a/a/a b/b/b …`.
/// Numbers as [`write_number`]: every digit needed to read them back
/// exactly, no more.
///
/// Aborts, as a `Vec` does, when the text cannot be allocated:
/// [`try_write_obj`] returns the error instead.
pub fn write_obj<R: Real + Display + LowerExp>(t: &Tessellation<R>, header: &[String]) -> String {
    crate::mem::or_abort(try_write_obj(t, header))
}

/// The most bytes one vertex's lines take: `v`, `vn` (a keyword and three
/// numbers of at most 25 characters each: sign, 17 digits, point,
/// exponent) and `vt`.
const VERTEX_LINES: usize = 256;
/// The most bytes one face's line takes (four corners `a/a/a` of at most
/// ten digits each).
const FACE_LINE: usize = 160;

/// [`write_obj`], or the error when the text cannot be allocated: room for
/// each line is reserved before it is written.
pub fn try_write_obj<R: Real + Display + LowerExp>(
    t: &Tessellation<R>,
    header: &[String],
) -> Result<String, OutOfMemory> {
    let mut text = String::new();
    let estimate =
        (t.positions.len().saturating_mul(96)).saturating_add(t.faces.len().saturating_mul(40));
    reserve_str(&mut text, estimate)?;
    for line in header {
        reserve_str(&mut text, line.len() + 3)?;
        let _ = writeln!(text, "# {line}");
    }
    let with_uv = !t.uvs.is_empty();
    for (k, (p, n)) in t.positions.iter().zip(&t.normals).enumerate() {
        reserve_str(&mut text, VERTEX_LINES)?;
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
        reserve_str(&mut text, FACE_LINE)?;
        write_face(&mut text, f.corners(), with_uv);
    }
    Ok(text)
}

/// `f a//a b//b c//c[ d//d]` (or `f a/a/a …` `with_uv`) and a newline: the
/// 0-based `corners` written 1-based.
pub fn write_face(text: &mut String, corners: &[u32], with_uv: bool) {
    let mut digits = itoa::Buffer::new();
    text.push('f');
    for &i in corners {
        let i = digits.format(u64::from(i) + 1);
        text.push(' ');
        text.push_str(i);
        text.push_str(if with_uv { "/" } else { "//" });
        if with_uv {
            text.push_str(i);
            text.push('/');
        }
        text.push_str(i);
    }
    text.push('\n');
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
/// The digits of `f32` and `f64` come from Ryū (the `ryu` crate: the
/// shortest round-trip digits, the closest to `x` among them, as
/// `core::fmt` gives them), laid out here in either notation; other
/// [`Real`] types go through `core::fmt`. The text is the one `core::fmt`
/// gives except where `x` lies exactly halfway between the two closest
/// shortest digit strings: Ryū then rounds the last digit to even where
/// `core::fmt` rounds up (`312985.12` for the `f32` `312985.125`, not
/// `…13`); both read back as `x`.
pub fn write_number<R: Real + Display + LowerExp>(text: &mut String, x: R) {
    let mut buffer = ryu::Buffer::new();
    let any: &dyn Any = &x;
    let ryu_text = if let Some(&v) = any.downcast_ref::<f64>() {
        buffer.format(v)
    } else if let Some(&v) = any.downcast_ref::<f32>() {
        buffer.format(v)
    } else {
        return write_number_fmt(text, x);
    };
    // Ryū writes integers as `100.0` and, between `1e-5` and `1e16`
    // (`1e-6`, `1e13` for `f32`), the rest positionally as `core::fmt`
    // does: then only the exponent form may remain to be considered. Most
    // coordinates and normal components lie where the positional form is
    // kept whatever its length, which needs no look at the text.
    if (1e-3..1e7).contains(&x.to_f64().abs()) {
        text.push_str(ryu_text.strip_suffix(".0").unwrap_or(ryu_text));
        return;
    }
    if !ryu_text.contains('e') {
        let positional = ryu_text.strip_suffix(".0").unwrap_or(ryu_text);
        if positional.len() <= 8 || (1e-3..1e7).contains(&x.to_f64().abs()) {
            text.push_str(positional);
            return;
        }
    }
    match Decimal::parse(ryu_text) {
        Some(d) => d.write(text),
        // NaN and infinities: ryu writes them as `core::fmt` does.
        None => text.push_str(ryu_text),
    }
}

/// [`write_number`] through `core::fmt`: both notations formatted, the
/// shorter kept.
fn write_number_fmt<R: Real + Display + LowerExp>(text: &mut String, x: R) {
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

/// A finite number as `±0.D × 10^point`: `D`, the significant digits as
/// ASCII without leading or trailing zeros (none for zero), in
/// `digits[..len]`.
struct Decimal {
    negative: bool,
    digits: [u8; 24],
    len: usize,
    point: i32,
}

impl Decimal {
    /// Reads Ryū's text (`-12.5`, `0.001`, `1e-7`, `1.25e30`, `100.0`) in
    /// one pass; `None` for `NaN`, `inf` and anything else that is not a
    /// decimal number of at most 24 significant digits.
    fn parse(text: &str) -> Option<Self> {
        let bytes = text.as_bytes();
        let negative = bytes.first() == Some(&b'-');
        let mut d = Decimal {
            negative,
            digits: [0; 24],
            len: 0,
            point: 0,
        };
        let mut after_point = false;
        let mut at = usize::from(negative);
        while let Some(&b) = bytes.get(at) {
            match b {
                b'0' if d.len == 0 => d.point -= i32::from(after_point),
                b'0'..=b'9' => {
                    *d.digits.get_mut(d.len)? = b;
                    d.len += 1;
                    d.point += i32::from(!after_point);
                }
                b'.' if !after_point => after_point = true,
                b'e' => break,
                _ => return None,
            }
            at += 1;
        }
        if let Some(exponent) = bytes.get(at + 1..) {
            let (sign, digits) = match exponent.split_first() {
                Some((b'-', rest)) => (-1, rest),
                _ => (1, exponent),
            };
            if digits.is_empty() || digits.len() > 4 {
                return None;
            }
            let mut e = 0i32;
            for &b in digits {
                if !b.is_ascii_digit() {
                    return None;
                }
                e = e * 10 + i32::from(b - b'0');
            }
            d.point += sign * e;
        }
        while d.len > 0 && d.digits[d.len - 1] == b'0' {
            d.len -= 1;
        }
        Some(d)
    }

    /// Appends the significant digits `from..to` (ASCII digits, so the
    /// bytes are UTF-8).
    fn push_digits(&self, text: &mut String, from: usize, to: usize) {
        if let Some(Ok(s)) = self.digits.get(from..to).map(core::str::from_utf8) {
            text.push_str(s);
        }
    }

    /// The notation rule of [`write_number`], without formatting either
    /// form to measure it.
    fn write(&self, text: &mut String) {
        if self.negative {
            text.push('-');
        }
        let n = self.len as i32;
        if n == 0 {
            text.push('0');
            return;
        }
        let p = self.point;
        let positional = if p <= 0 {
            2 - p + n
        } else if p < n {
            n + 1
        } else {
            p
        } + i32::from(self.negative);
        let e = p - 1;
        let exponent = n
            + i32::from(n > 1)
            + 1
            + i32::from(e < 0)
            + decimal_len(e.unsigned_abs())
            + i32::from(self.negative);
        // `1e-3 ≤ |x| < 1e7` is `-2 ≤ p ≤ 7`.
        let n = n as usize;
        if positional > 8 && !(-2..=7).contains(&p) && exponent < positional {
            self.push_digits(text, 0, 1);
            if n > 1 {
                text.push('.');
                self.push_digits(text, 1, n);
            }
            text.push('e');
            text.push_str(itoa::Buffer::new().format(e));
        } else if p <= 0 {
            text.push_str("0.");
            (0..-p).for_each(|_| text.push('0'));
            self.push_digits(text, 0, n);
        } else if (p as usize) < n {
            self.push_digits(text, 0, p as usize);
            text.push('.');
            self.push_digits(text, p as usize, n);
        } else {
            self.push_digits(text, 0, n);
            (n..p as usize).for_each(|_| text.push('0'));
        }
    }
}

/// Decimal digits of `v`.
fn decimal_len(v: u32) -> i32 {
    let mut len = 1;
    let mut v = v / 10;
    while v > 0 {
        len += 1;
        v /= 10;
    }
    len
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

    #[test]
    fn ryu_digits_laid_out_equal_core_fmt_byte_for_byte() {
        // Bit patterns spread over every exponent (xorshift64), the edges of
        // the notation rule, zeros, subnormals, extremes and non-finite
        // values; the oracle is `core::fmt`'s `{}` / `{:e}` with the rule.
        fn fmt_number<R: Real + core::fmt::Display + core::fmt::LowerExp>(x: R) -> String {
            let mut s = String::new();
            super::write_number_fmt(&mut s, x);
            s
        }
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut values64 = alloc::vec![
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e-3,
            1e7,
            9_999_999.0,
            99_999_999.0,
            123_456_789.0,
            0.000_123_456_789,
        ];
        for _ in 0..200_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            values64.push(f64::from_bits(state));
            // Short digit strings: integers and few-digit fractions.
            values64.push((state >> 40) as f64 / 1000.0);
        }
        // Where `x` lies exactly halfway between the two closest shortest
        // digit strings, Ryū rounds the last digit to even and `core::fmt`
        // up: the same length, the same value read back.
        fn same<F: core::str::FromStr + PartialEq + core::fmt::Debug>(
            ryu: &str,
            fmt: &str,
        ) -> bool {
            ryu == fmt
                || (ryu.len() == fmt.len()
                    && ryu.parse::<F>().ok() == fmt.parse::<F>().ok()
                    && ryu.bytes().zip(fmt.bytes()).filter(|(a, b)| a != b).count() == 1)
        }
        let mut ties = 0;
        for &v in &values64 {
            let (a, b) = (number(v), fmt_number(v));
            assert!(same::<f64>(&a, &b), "{a} {b}");
            ties += usize::from(a != b);
            for f in [f32::from_bits(v.to_bits() as u32), v as f32] {
                let (a, b) = (number(f), fmt_number(f));
                assert!(same::<f32>(&a, &b), "{a} {b}");
                ties += usize::from(a != b);
            }
        }
        // Ties need a value with few more bits than its shortest digits.
        assert!(ties * 1000 < 3 * values64.len(), "{ties}");
    }
}
