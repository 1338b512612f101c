//! Numbers and counts in human-readable text (summaries, headers, legends):
//! counts with the right plural, measured values to a few significant
//! digits. Machine output (JSON, OBJ coordinates) keeps every digit; see
//! [`capdiv_mesh::tessellate::write_number`].

/// `n` with the noun in the singular for 1 and the plural otherwise:
/// `count(1, "face", "faces")` = `1 face`, `count(0, …)` = `0 faces`.
pub fn count(n: usize, singular: &str, plural: &str) -> String {
    format!("{n} {}", if n == 1 { singular } else { plural })
}

/// `x` to `digits` significant digits in the shorter of positional and
/// exponent form, without trailing zeros: `sig(3.7632650000000004e-9, 3)` =
/// `3.76e-9`, `sig(0.25, 3)` = `0.25`, `sig(1234.5, 3)` = `1.23e3`. For
/// human text only: the value is rounded.
pub fn sig(x: f64, digits: usize) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x == 0.0 {
        return "0".into();
    }
    let digits = digits.max(1);
    // `{:.*e}` rounds to the digits asked for; the exponent it prints is the
    // rounded value's (9.996 → 1.00e1).
    let e_form = format!("{:.*e}", digits - 1, x);
    let (mantissa, exponent) = e_form.split_once('e').unwrap_or((&e_form, "0"));
    let exponent: i32 = exponent.parse().unwrap_or(0);
    let mantissa = trim_zeros(mantissa);
    let scientific = if exponent == 0 {
        mantissa.clone()
    } else {
        format!("{mantissa}e{exponent}")
    };
    // Positional form with the same significant digits, when the exponent
    // is small enough to need no padding zeros beyond the digits.
    let decimals = digits as i32 - 1 - exponent;
    if (0..=digits as i32 + 2).contains(&decimals) && exponent < digits as i32 {
        let rounded: f64 = e_form.parse().unwrap_or(x);
        let positional = trim_zeros(&format!("{:.*}", decimals as usize, rounded));
        if positional.len() <= scientific.len() {
            return positional;
        }
    }
    scientific
}

/// `1.500` → `1.5`, `2.000` → `2`, `120` unchanged (no decimal point).
fn trim_zeros(s: &str) -> String {
    if !s.contains('.') {
        return s.to_string();
    }
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[cfg(test)]
mod tests {
    use super::{count, sig};

    #[test]
    fn counts_take_the_plural_except_for_one() {
        assert_eq!(count(1, "face", "faces"), "1 face");
        assert_eq!(count(0, "face", "faces"), "0 faces");
        assert_eq!(count(2, "vertex", "vertices"), "2 vertices");
    }

    #[test]
    fn significant_digits_in_the_shorter_form() {
        assert_eq!(sig(3.7632650000000004e-9, 3), "3.76e-9");
        assert_eq!(sig(1e-9, 3), "1e-9");
        assert_eq!(sig(0.25, 3), "0.25");
        assert_eq!(sig(1.0, 3), "1");
        assert_eq!(sig(-2.25, 3), "-2.25");
        assert_eq!(sig(0.012345, 3), "0.0123");
        assert_eq!(sig(1234.5, 3), "1.23e3");
        assert_eq!(sig(120.0, 3), "120");
        assert_eq!(sig(9.996, 3), "10");
        assert_eq!(sig(0.0, 3), "0");
        assert_eq!(sig(f64::INFINITY, 3), "inf");
    }

    #[test]
    fn rounding_stays_within_half_a_unit_of_the_last_digit() {
        // Every printed value reads back within 0.5·10^(e−d+1) of x.
        for k in -40..40 {
            let x = 1.234_567_89_f64 * 10f64.powi(k) * if k % 2 == 0 { 1.0 } else { -1.0 };
            let back: f64 = sig(x, 4).parse().unwrap();
            let unit = 10f64.powi(x.abs().log10().floor() as i32 - 3);
            assert!(
                (back - x).abs() <= 0.5 * unit * (1.0 + 1e-9),
                "{x} → {back}"
            );
        }
    }
}
