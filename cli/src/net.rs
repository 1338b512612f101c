//! Polar nets on heap storage sized at run time: a job that reaches valence
//! `N` gets one [`PolarNetBuf`] over two `Vec`s of exactly `N`'s size
//! (`17·N·size_of::<R>()` bytes, kernel `polar::buf`), so nothing large
//! lives on the stack and one code path serves every valence.

use crate::error::CliError;
use crate::Scalar;
use capdiv::{Error, Point3, PolarNetBuf, SliceStorage};

/// The largest valence a job may reach (17.8 MB of storage in `f64`): a
/// bound on what a command line can ask for, not on the kernel.
pub const MAX_VALENCE: usize = 1 << 17;

/// Valence after `steps` C²PS steps from valence `n`: `n·2^steps`, or `None`
/// on overflow.
pub fn valence_after(n: usize, steps: u32) -> Option<usize> {
    n.checked_mul(1usize.checked_shl(steps)?)
}

/// Link and root storage for one net.
pub struct NetStorage<R> {
    links: Vec<Point3<R>>,
    roots: Vec<[R; 2]>,
}

impl<R: Scalar> NetStorage<R> {
    /// Storage for a net that reaches valence `needed` (`None`: the valence
    /// overflowed); [`CliError::Capacity`] above [`MAX_VALENCE`], with
    /// `what` describing the need.
    pub fn for_valence(
        needed: Option<usize>,
        what: impl FnOnce() -> String,
    ) -> Result<Self, CliError> {
        let cap = needed
            .filter(|&n| n <= MAX_VALENCE)
            .ok_or_else(|| CliError::Capacity {
                what: what(),
                max: MAX_VALENCE,
            })?;
        Ok(NetStorage {
            links: vec![Point3::ZERO; SliceStorage::<R>::links_len(cap)],
            roots: vec![[R::ZERO; 2]; SliceStorage::<R>::roots_len(cap)],
        })
    }

    /// A net over this storage loaded with a level-0 configuration
    /// ([`PolarNetBuf::new`]'s checks and errors).
    pub fn net<L: AsRef<[[R; 3]]>>(
        &mut self,
        pole: [R; 3],
        links: &[L],
    ) -> Result<PolarNetBuf<'_, R>, Error> {
        PolarNetBuf::new_in(
            pole,
            links,
            SliceStorage::new(&mut self.links, &mut self.roots),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn valence_after_doubles_per_step_and_reports_overflow() {
        assert_eq!(valence_after(6, 0), Some(6));
        assert_eq!(valence_after(6, 4), Some(96));
        assert_eq!(valence_after(3, 63), None);
        assert_eq!(valence_after(3, 64), None);
        assert_eq!(valence_after(3, u32::MAX), None);
    }

    #[test]
    fn storage_holds_exactly_the_valence_asked_for() {
        let ring: Vec<[f64; 3]> = (0..6).map(|j| [j as f64, 1.0, 0.0]).collect();
        let links = [ring.clone(), ring.clone(), ring];
        let mut s = NetStorage::<f64>::for_valence(Some(12), String::new).unwrap();
        let mut net = s.net([0.0; 3], &links).unwrap();
        assert_eq!(net.capacity(), 12);
        assert!(net.step(capdiv::FirstStep::Uniform).is_ok());
        assert_eq!(
            net.step(capdiv::FirstStep::Uniform),
            Err(Error::CapacityExceeded {
                needed: 24,
                capacity: 12
            })
        );
    }

    #[test]
    fn storage_above_the_bound_or_overflowed_is_a_capacity_error() {
        for needed in [Some(MAX_VALENCE + 1), None] {
            let e = NetStorage::<f32>::for_valence(needed, || "valence x".into());
            assert!(matches!(
                e,
                Err(CliError::Capacity {
                    max: MAX_VALENCE,
                    ..
                })
            ));
        }
        assert!(NetStorage::<f32>::for_valence(Some(MAX_VALENCE), String::new).is_ok());
    }
}
