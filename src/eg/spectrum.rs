//! The §8 acceptance check of a caller's rule table: the spectral radius of
//! `A_n` off the `c0` eigenvector, by power iteration with the table's own
//! step.
//!
//! A d-net with `c0 = 0` has no component along the eigenvector
//! `(c0, all nodes equal)` of eigenvalue 1 (every other eigenvector has a zero
//! `c0` entry, as `c0`'s row of `A_n` is the identity), so repeated steps grow
//! or shrink it by the largest remaining `|eigenvalue|`, ρ. 64 warm-up steps,
//! then ρ is the geometric mean of 32 per-step growth factors (max-norm, the
//! net renormalised every step). For a table close to the paper's the
//! dominant pair is real and double (Fourier modes 1 and n−1), the warm-up
//! leaves a relative error ~ (μ/λ)⁶⁴ — far below the 10⁻³ tolerance.

use super::net::DNet;
use super::rule::RuleTable;
use super::step::{step_into, Rule};
use crate::error::Error;
use crate::point::Point3;
use heapless::Vec;

const WARM_UP: usize = 64;
const MEASURE: usize = 32;
/// §8: EG's subdominant eigenvalue is within 10⁻³ of Catmull-Clark's.
pub const LAMBDA_TOLERANCE: f64 = 1e-3;

/// Catmull-Clark's subdominant eigenvalue
/// `λ_CC(n) = (5 + cos(2π/n) + cos(π/n)·√(2(9 + cos(2π/n)))) / 16` (§8).
pub fn lambda_catmull_clark(n: usize) -> f64 {
    let t = core::f64::consts::PI / n as f64;
    let c2 = libm::cos(2.0 * t);
    (5.0 + c2 + libm::cos(t) * libm::sqrt(2.0 * (9.0 + c2))) / 16.0
}

fn max_abs(net: &DNet<f32>) -> f32 {
    net.sectors
        .iter()
        .flatten()
        .flat_map(|p| p.0)
        .fold(0.0f32, |m, c| if c.abs() > m { c.abs() } else { m })
}

fn scale(net: &mut DNet<f32>, f: f32) {
    for p in net.sectors.iter_mut().flatten() {
        *p = *p * f;
    }
}

/// Power-iteration estimate of ρ for `table` (errors only on internal failure).
pub(crate) fn spectral_radius(table: &RuleTable<'_>) -> Result<f64, Error> {
    let n = table.valence();
    // Deterministic pseudo-random start (LCG), c0 = 0.
    let mut seed: u32 = 0x2545_f491;
    let mut next = || {
        seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (seed >> 8) as f32 / (1u32 << 24) as f32 - 0.5
    };
    let mut sectors: Vec<[Point3<f32>; 12], { super::MAX_VALENCE }> = Vec::new();
    for _ in 0..n {
        let sec = core::array::from_fn(|_| Point3([next(), next(), next()]));
        sectors
            .push(sec)
            .map_err(|_| Error::ValenceUnsupported { valence: n })?;
    }
    let mut a = DNet {
        c0: Point3::ZERO,
        sectors,
    };
    let mut b = a.clone();
    let mut log_sum = 0.0f64;
    for k in 0..WARM_UP + MEASURE {
        step_into(&a, Rule::Eg(table), &mut b)?;
        let m = max_abs(&b);
        if !m.is_finite() {
            return Ok(f64::INFINITY);
        }
        if m <= 0.0 {
            return Ok(0.0);
        }
        if k >= WARM_UP {
            log_sum += libm::log(f64::from(m));
        }
        scale(&mut b, 1.0 / m);
        core::mem::swap(&mut a, &mut b);
    }
    Ok(libm::exp(log_sum / MEASURE as f64))
}

/// [`Error::TableRowSum`] when ρ ≥ 1, [`Error::TableSpectrum`] when ρ is more
/// than [`LAMBDA_TOLERANCE`] from λ_CC(n).
pub(crate) fn check(table: &RuleTable<'_>) -> Result<(), Error> {
    let rho = spectral_radius(table)?;
    if rho.is_nan() || rho >= 1.0 {
        return Err(Error::TableRowSum);
    }
    if libm::fabs(rho - lambda_catmull_clark(table.valence())) > LAMBDA_TOLERANCE {
        return Err(Error::TableSpectrum);
    }
    Ok(())
}
