//! Vector arithmetic on `[f64; 3]`: the reference's only point type.

/// A point or vector in 3-space.
pub type P3 = [f64; 3];

/// The origin.
pub const ZERO: P3 = [0.0; 3];

/// `a + b`.
pub fn add(a: P3, b: P3) -> P3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a − b`.
pub fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `s · a`.
pub fn scale(s: f64, a: P3) -> P3 {
    [s * a[0], s * a[1], s * a[2]]
}

/// `acc + s · a`.
pub fn axpy(acc: P3, s: f64, a: P3) -> P3 {
    [acc[0] + s * a[0], acc[1] + s * a[1], acc[2] + s * a[2]]
}

/// Dot product.
pub fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Cross product.
pub fn cross(a: P3, b: P3) -> P3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Euclidean length.
pub fn norm(a: P3) -> f64 {
    dot(a, a).sqrt()
}

/// Largest absolute coordinate difference.
pub fn max_abs_diff(a: P3, b: P3) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max)
}
