//! Compile-time table of `cos(2π/o)`, `sin(2π/o)` for odd `o`.
//!
//! Method: the angle `x = 2π/o` is divided by 4, `sin` and `cos` of `x/4 ≤ π/6`
//! are summed from their Taylor series to 24 terms (the truncation is below
//! 1e-30), then doubled twice with `cos 2y = 1 − 2 sin² y`, `sin 2y = 2 sin y cos y`.
//! All of it is `const fn` `f64` arithmetic, evaluated by the compiler, so the
//! table is read-only data with no start-up cost. Accuracy: within 4e-16 of the
//! host's `f64::cos`/`sin` (tested in `tests/trig.rs`).
//!
//! A valence `n = o·2^f` (odd `o`) takes its primitive root from the entry for
//! `o` and `f` half-angle steps (`cos θ/2 = √((1+cos θ)/2)`,
//! `sin θ/2 = sin θ / (2 cos θ/2)`) through `libm::sqrt`: [`primitive_root`].

/// Largest odd part of a supported valence (`n = o·2^f` with odd `o ≤ 127`:
/// every valence up to 128 and e.g. 3·2^k, 5·2^k, …, 127·2^k).
pub const MAX_ODD_PART: usize = 127;

const TABLE_LEN: usize = MAX_ODD_PART.div_ceil(2);

const fn sin_cos_small(x: f64) -> (f64, f64) {
    // Taylor series, 24 terms each; |x| <= pi/6 so x^48/48! < 1e-60.
    let x2 = x * x;
    let mut s = 0.0;
    let mut c = 0.0;
    let mut ts = x; // x^(2k+1)/(2k+1)!
    let mut tc = 1.0; // x^(2k)/(2k)!
    let mut k = 0;
    while k < 24 {
        s += ts;
        c += tc;
        let a = (2 * k + 2) as f64;
        let b = (2 * k + 3) as f64;
        ts = -ts * x2 / (a * b);
        tc = -tc * x2 / ((2 * k + 1) as f64 * a);
        k += 1;
    }
    (s, c)
}

const fn root_of(o: usize) -> (f64, f64) {
    if o == 1 {
        return (1.0, 0.0);
    }
    let (mut s, mut c) = sin_cos_small(core::f64::consts::TAU / o as f64 / 4.0);
    let mut d = 0;
    while d < 2 {
        let s2 = 2.0 * s * c;
        c = 1.0 - 2.0 * s * s;
        s = s2;
        d += 1;
    }
    (c, s)
}

const fn build() -> [(f64, f64); TABLE_LEN] {
    let mut t = [(0.0, 0.0); TABLE_LEN];
    let mut i = 0;
    while i < TABLE_LEN {
        t[i] = root_of(2 * i + 1);
        i += 1;
    }
    t
}

/// `ODD_ROOTS[i] = (cos(2π/o), sin(2π/o))` with `o = 2i + 1`.
pub static ODD_ROOTS: [(f64, f64); TABLE_LEN] = build();

/// `(cos(2π/n), sin(2π/n))` for a valence `n ≥ 3` whose odd part is at most
/// [`MAX_ODD_PART`]; `None` otherwise.
pub fn primitive_root(n: usize) -> Option<(f64, f64)> {
    if n < 3 {
        return None;
    }
    let f = n.trailing_zeros();
    let o = n >> f;
    if o > MAX_ODD_PART {
        return None;
    }
    // Start at an angle below pi so that every half-angle has a positive cosine.
    let (mut c, mut s, mut halvings) = if o == 1 {
        (0.0, 1.0, f - 2) // n = 2^f, f >= 2: start at 2pi/4
    } else {
        let (c, s) = ODD_ROOTS[o / 2];
        (c, s, f)
    };
    while halvings > 0 {
        let ch = libm::sqrt(0.5 * (1.0 + c));
        s /= 2.0 * ch;
        c = ch;
        halvings -= 1;
    }
    Some((c, s))
}
