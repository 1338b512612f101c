//! docs/math/c2ps.md §6 item 5: the f32 kernel stays within a stated bound of the
//! f64 kernel after 8 steps.
//!
//! Data: points uniform in [−1, 1]³ (so the largest coordinate and the level-0
//! bounding box are comparable; f32 errors scale with the coordinates'
//! magnitude, not with the box). Measured worst over 620 random
//! configurations (every valence 3..64, 2..5 links, both first-step variants):
//!
//! - 2.1e-7 of the level-0 bounding-box size; we assert `F32_BOUND_LEVEL0 = 1e-6`;
//! - 1.4e-4 of the depth-8 net's own bounding-box size (that net is ~2^-8 as
//!   large, while its coordinates are still ~1); we assert `F32_BOUND_DEPTH8 = 1e-3`.
//!
//! The error no longer grows with the valence: the kernel's Fourier sums (up
//! to 8192 terms here) are compensated across blocks (src/polar/fourier.rs).
//! With plain running sums it was 8.6e-6 and 3.1e-3, worst at n = 64.

mod common;

use capdiv::FirstStep;
use common::*;
use proptest::prelude::*;

/// Bound on `max |f32 − f64|` over all points at depth 8, relative to the
/// level-0 configuration's bounding-box size.
const F32_BOUND_LEVEL0: f64 = 1e-6;
/// The same difference relative to the depth-8 net's bounding-box size.
const F32_BOUND_DEPTH8: f64 = 1e-3;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn f32_kernel_stays_within_bound_of_f64_at_depth_8(
        cfg in config(3..=64, 2..=5),
        first in prop_oneof![Just(FirstStep::Plain), Just(FirstStep::Uniform)],
    ) {
        let mut n64: Box<Net> = Box::new(to_net(&cfg));
        let mut n32: Box<Net32> = Box::new(to_net(&cfg));
        for _ in 0..8 {
            n64.step(first).unwrap();
            n32.step(first).unwrap();
        }
        let (q64, q32) = (from_net(&n64), from_net(&n32));
        let diff = max_diff(&q64, &q32);
        let rel0 = diff / cfg.bbox_size();
        let rel8 = diff / q64.bbox_size();
        prop_assert!(rel0 <= F32_BOUND_LEVEL0, "relative to level-0 box: {rel0:e}");
        prop_assert!(rel8 <= F32_BOUND_DEPTH8, "relative to depth-8 box: {rel8:e}");
    }
}
