//! docs/math/c2ps.md §6 item 1: the kernel's O(n) C²PS step (f64) equals the literal
//! O(n²) sums of the paper's rules (1)–(5), (29) with the weights of eq. (4)
//! (`capdiv_reference::c2ps`), at every level, to ≤ 1e-12 relative to the
//! configuration's size (its largest absolute coordinate).
//!
//! Tolerance: both sides round differently (sums of `n ≤ 8192` products, the
//! kernel's root table vs `std::cos`), so agreement is to round-off, which
//! grows at worst like `n·ε` per step; measured ≤ 7.2e-15 relative (12
//! random configurations, valences 3..64, depth 8). 1e-12 is the spec's bound.
//!
//! Sizes: the literal sums cost `2n²` per link, so proptest cases (valences
//! 3..64, depths 0..8) clamp the depth to keep the final valence
//! `n·2^depth ≤ 2048` (1024 for the first-step variant);
//! `valence_64_depth_8_kernel_equals_literal_rules` covers the corner once.

mod common;

use capdiv::FirstStep;
use capdiv_reference::c2ps::{refine, TwoLinkRule};
use capdiv_reference::polar::Polar;
use common::*;
use proptest::prelude::*;

/// Relative tolerance of docs/math/c2ps.md §6 item 1.
const REL_TOL: f64 = 1e-12;

/// Refines `cfg` `depth` times with the kernel and with the reference and
/// returns the worst difference over all levels, relative to the size.
fn worst_relative_difference(cfg: &Polar, depth: u32, first: FirstStep) -> f64 {
    let rule = match first {
        FirstStep::Plain => TwoLinkRule::Plain,
        FirstStep::Uniform => TwoLinkRule::Uniform,
    };
    let reference = refine(cfg, depth, rule);
    let mut net: Box<Net> = Box::new(to_net(cfg));
    let size = cfg.max_abs();
    let mut worst = max_diff(&from_net(&net), &reference[0]) / size;
    for level in reference.iter().skip(1) {
        net.step(first).expect("capacity suffices");
        assert_eq!(net.valence(), level.valence());
        worst = worst.max(max_diff(&from_net(&net), level) / size);
    }
    worst
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Rules (1)–(5), (29) in every step (`FirstStep::Plain`).
    #[test]
    fn kernel_step_equals_literal_rules_at_every_level(
        cfg in config(3..=64, 2..=5),
        depth in 0u32..=8,
    ) {
        let depth = clamp_depth(cfg.valence(), depth, 2048);
        let worst = worst_relative_difference(&cfg, depth, FirstStep::Plain);
        prop_assert!(worst <= REL_TOL, "relative difference {worst:e}");
    }

    /// The first-step variant (docs/math/c2ps.md §2): the uniform 2-link rule in step 1,
    /// rules (1)–(5), (29) after it.
    #[test]
    fn kernel_first_step_variant_equals_literal_reference(
        cfg in config(3..=64, 2..=5),
        depth in 1u32..=8,
    ) {
        let depth = clamp_depth(cfg.valence(), depth, 1024);
        let worst = worst_relative_difference(&cfg, depth, FirstStep::Uniform);
        prop_assert!(worst <= REL_TOL, "relative difference {worst:e}");
    }
}

/// The largest case of the spec's range, valence 64 refined 8 times
/// (valence 16384), both variants of the first step.
#[test]
fn valence_64_depth_8_kernel_equals_literal_rules() {
    let links: Vec<Vec<[f64; 3]>> = (1..=5)
        .map(|i| {
            (0..64)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / 64.0;
                    let wobble = ((j * 37 + i * 11) % 17) as f64 / 17.0 - 0.5;
                    [
                        i as f64 * t.cos(),
                        i as f64 * t.sin(),
                        0.3 * wobble + 0.1 * (i * i) as f64,
                    ]
                })
                .collect()
        })
        .collect();
    let cfg = Polar::new([0.05, -0.02, 0.0], links);
    for first in [FirstStep::Plain, FirstStep::Uniform] {
        let worst = worst_relative_difference(&cfg, 8, first);
        assert!(worst <= REL_TOL, "{first:?}: relative difference {worst:e}");
    }
}
