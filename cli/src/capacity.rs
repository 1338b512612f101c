//! Compile-time capacity tiers for [`capdiv::PolarNet`].
//!
//! A net's capacity `CAP` is a const generic: it bounds the valence, and a
//! level-`m` configuration has valence `n·2^m` (docs/math/c2ps.md §1). The CLI
//! compiles a few tiers and runs each job in the smallest that fits.
//! Memory of one net is about `17·CAP·size_of::<R>()` bytes (kernel
//! `polar::net`), 17.8 MB for the largest tier in `f64`: nets live on the
//! stack, so the binary runs its work on a thread with [`WORK_STACK`] bytes.

use crate::error::CliError;
use crate::Scalar;

/// The capacities compiled in, smallest first.
pub const TIERS: [usize; 3] = [1 << 10, 1 << 14, 1 << 17];

/// The largest capacity (the largest valence any job may reach).
pub const MAX_CAPACITY: usize = TIERS[TIERS.len() - 1];

/// Stack size of the worker thread that runs every command.
pub const WORK_STACK: usize = 512 << 20;

/// A job that needs one net of some capacity, written once for every `CAP`.
pub trait NetJob<R: Scalar> {
    /// What the job produces.
    type Output;
    /// Runs the job with nets of capacity `CAP`.
    fn run<const CAP: usize>(self) -> Result<Self::Output, CliError>;
}

/// Valence after `steps` C²PS steps from valence `n`: `n·2^steps`, or `None`
/// on overflow.
pub fn valence_after(n: usize, steps: u32) -> Option<usize> {
    n.checked_mul(1usize.checked_shl(steps)?)
}

/// The capacity a job needing valence `needed` runs with, if any.
pub fn tier_for(needed: usize) -> Option<usize> {
    TIERS.iter().copied().find(|&cap| needed <= cap)
}

/// Runs `job` in the smallest tier holding valence `needed` (`None` =
/// overflowed); `what` describes the need for the error message.
pub fn dispatch<R: Scalar, J: NetJob<R>>(
    needed: Option<usize>,
    what: impl FnOnce() -> String,
    job: J,
) -> Result<J::Output, CliError> {
    let too_big = |what: String| CliError::Capacity {
        what,
        max: MAX_CAPACITY,
    };
    let Some(needed) = needed else {
        return Err(too_big(what()));
    };
    match tier_for(needed) {
        Some(c) if c == TIERS[0] => job.run::<{ TIERS[0] }>(),
        Some(c) if c == TIERS[1] => job.run::<{ TIERS[1] }>(),
        Some(c) if c == TIERS[2] => job.run::<{ TIERS[2] }>(),
        _ => Err(too_big(what())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn valence_and_tiers() {
        assert_eq!(valence_after(6, 0), Some(6));
        assert_eq!(valence_after(6, 4), Some(96));
        assert_eq!(valence_after(3, 63), None);
        assert_eq!(valence_after(3, 64), None);
        assert_eq!(valence_after(3, u32::MAX), None);
        assert_eq!(tier_for(0), Some(1 << 10));
        assert_eq!(tier_for(1 << 10), Some(1 << 10));
        assert_eq!(tier_for((1 << 10) + 1), Some(1 << 14));
        assert_eq!(tier_for(1 << 17), Some(1 << 17));
        assert_eq!(tier_for((1 << 17) + 1), None);
    }
}
