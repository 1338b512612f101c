//! Polar nets on heap storage sized at run time: a job that reaches valence
//! `N` owns one [`HeapNet`], a kernel `PolarNetInner` over [`HeapStorage`]
//! (two `Vec`s of exactly `N`'s size, `17·N·size_of::<R>()` bytes; the
//! kernel's [`capdiv::NetStorage`] implemented here, as the kernel does for
//! its inline and borrowed storages), so nothing large lives on the stack
//! and one code path serves every valence.

use crate::error::CliError;
use crate::Scalar;
use capdiv::{Error, NetStorage, Point3, PolarNetInner, SliceStorage};

/// The largest valence a job may reach (17.8 MB of storage in `f64`): a
/// bound on what a command line can ask for, not on the kernel.
pub const MAX_VALENCE: usize = 1 << 17;

/// Valence after `steps` C²PS steps from valence `n`: `n·2^steps`, or `None`
/// on overflow.
pub fn valence_after(n: usize, steps: u32) -> Option<usize> {
    n.checked_mul(1usize.checked_shl(steps)?)
}

/// Link and root storage of one net on the heap, in the kernel's layout
/// (lengths [`SliceStorage::links_len`] and [`SliceStorage::roots_len`] of
/// the capacity).
pub struct HeapStorage<R> {
    links: Vec<Point3<R>>,
    roots: Vec<[R; 2]>,
}

/// A polar net that owns its heap storage.
pub type HeapNet<R> = PolarNetInner<R, HeapStorage<R>>;

impl<R: Scalar> HeapStorage<R> {
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
        Ok(HeapStorage {
            links: vec![Point3::ZERO; SliceStorage::<R>::links_len(cap)],
            roots: vec![[R::ZERO; 2]; SliceStorage::<R>::roots_len(cap)],
        })
    }

    /// A net owning this storage, loaded with a level-0 configuration
    /// ([`PolarNetInner::new_in`]'s checks and errors).
    pub fn net<L: AsRef<[[R; 3]]>>(self, pole: [R; 3], links: &[L]) -> Result<HeapNet<R>, Error> {
        PolarNetInner::new_in(pole, links, self)
    }
}

impl<R> NetStorage<R> for HeapStorage<R> {
    fn parts(&self) -> (&[Point3<R>], &[[R; 2]]) {
        (&self.links, &self.roots)
    }
    fn parts_mut(&mut self) -> (&mut [Point3<R>], &mut [[R; 2]]) {
        (&mut self.links, &mut self.roots)
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
        let s = HeapStorage::<f64>::for_valence(Some(12), String::new).unwrap();
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
    fn a_heap_net_gives_the_inline_net_bit_for_bit() {
        let ring = |r: f64| -> Vec<[f64; 3]> {
            (0..5)
                .map(|j| {
                    let t = core::f64::consts::TAU * j as f64 / 5.0;
                    [r * t.cos(), r * t.sin(), 0.3 * r * r + 0.1 * j as f64]
                })
                .collect()
        };
        let links: Vec<_> = (1..=5).map(|i| ring(i as f64)).collect();
        let mut heap = HeapStorage::<f64>::for_valence(Some(20), String::new)
            .unwrap()
            .net([0.0, 0.0, 0.2], &links)
            .unwrap();
        let mut inline: capdiv::PolarNet<f64, 20> =
            capdiv::PolarNet::new([0.0, 0.0, 0.2], &links).unwrap();
        for _ in 0..2 {
            heap.step(capdiv::FirstStep::Uniform).unwrap();
            inline.step(capdiv::FirstStep::Uniform).unwrap();
        }
        assert_eq!(heap.valence(), 20);
        assert_eq!(heap.ring_len(), 40);
        assert!(heap.ring_patches().eq(inline.ring_patches()));
        assert_eq!(capdiv::PoleJet::of(&heap).p, capdiv::PoleJet::of(&inline).p);
        // The net owns its storage: it can be returned and kept.
        let storage = heap.into_storage();
        assert_eq!(storage.parts().0.len(), SliceStorage::<f64>::links_len(20));
    }

    #[test]
    fn storage_above_the_bound_or_overflowed_is_a_capacity_error() {
        for needed in [Some(MAX_VALENCE + 1), None] {
            let e = HeapStorage::<f32>::for_valence(needed, || "valence x".into());
            assert!(matches!(
                e,
                Err(CliError::Capacity {
                    max: MAX_VALENCE,
                    ..
                })
            ));
        }
        assert!(HeapStorage::<f32>::for_valence(Some(MAX_VALENCE), String::new).is_ok());
    }
}
