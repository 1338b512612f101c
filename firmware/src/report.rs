//! The log lines the host test reads. Every line is a key followed by
//! integers and `f32` numbers, space separated (`defmt` prints `f32` in the
//! shortest form that reads back to the same bits).

use capdiv::{Error, Point3};

/// Logs `key i... x y z`: up to 4 integer indices, then the point.
pub fn point(key: &str, idx: &[usize], p: Point3<f32>) {
    let [x, y, z] = p.0;
    match *idx {
        [] => defmt::println!("{=str} {=f32} {=f32} {=f32}", key, x, y, z),
        [a] => defmt::println!("{=str} {=usize} {=f32} {=f32} {=f32}", key, a, x, y, z),
        [a, b] => defmt::println!(
            "{=str} {=usize} {=usize} {=f32} {=f32} {=f32}",
            key,
            a,
            b,
            x,
            y,
            z
        ),
        [a, b, c] => defmt::println!(
            "{=str} {=usize} {=usize} {=usize} {=f32} {=f32} {=f32}",
            key,
            a,
            b,
            c,
            x,
            y,
            z
        ),
        [a, b, c, d, ..] => defmt::println!(
            "{=str} {=usize} {=usize} {=usize} {=usize} {=f32} {=f32} {=f32}",
            key,
            a,
            b,
            c,
            d,
            x,
            y,
            z
        ),
    }
}

/// Logs the outcome of one workload; `true` on success.
pub fn outcome(name: &str, r: Result<(), Failure>) -> bool {
    match r {
        Ok(()) => true,
        Err(Failure::Kernel(e)) => {
            defmt::println!("error {=str} {}", name, e);
            false
        }
        Err(Failure::Reused) => {
            defmt::println!("error {=str} static already taken", name);
            false
        }
    }
}

/// Why a workload stopped.
pub enum Failure {
    /// The kernel returned an error.
    Kernel(Error),
    /// A static was claimed twice.
    Reused,
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        Failure::Kernel(e)
    }
}
