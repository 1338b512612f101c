//! Compile-time table of `cos(2π/o)`, `sin(2π/o)` for odd `o`.
//!
//! Method: for `x = 2π/o ≤ π/4` the Taylor series of `sin` and `cos` at `x`,
//! otherwise at the complement `y = π/2 − x ∈ [−π/6, π/4)` with `sin` and `cos`
//! swapped; 24 terms each (truncation below 1e-30 for `|x| ≤ π/4`).
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
    // Taylor series, 24 terms each; |x| <= pi/4 so the tail is below 1e-30.
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
    let x = core::f64::consts::TAU / o as f64;
    if x <= core::f64::consts::FRAC_PI_4 {
        let (s, c) = sin_cos_small(x);
        (c, s)
    } else {
        // x in (pi/4, 2pi/3]: the complement y = pi/2 - x lies in [-pi/6, pi/4).
        let (s, c) = sin_cos_small(core::f64::consts::FRAC_PI_2 - x);
        (s, c)
    }
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
