//! Every bad input gives its own `capdiv::Error`, and a failing call leaves
//! the caller's data and the net unchanged (kernel contract, `src/error.rs`).
//! Inputs are borrowed immutably by `PolarNet::new`; we still compare them
//! before and after. For a failing `step`, the whole net (pole, links,
//! valence, level, links held, roots of unity) is compared before and after.

mod common;

use capdiv::{Error, FirstStep, PolarNet};
use capdiv_reference::polar::Polar;
use common::*;
use proptest::prelude::*;

type Small = PolarNet<f64, 256>;

fn raw(cfg: &Polar) -> ([f64; 3], Vec<Vec<[f64; 3]>>) {
    (cfg.pole, cfg.links.clone())
}

/// Everything observable about a net, for before/after comparison.
fn snapshot<const C: usize>(net: &PolarNet<f64, C>) -> (Polar, usize, u32, usize, Vec<[f64; 2]>) {
    (
        from_net(net),
        net.valence(),
        net.level(),
        net.link_count(),
        net.roots().to_vec(),
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// 0 or 1 links: `TooFewLinks { links }`.
    #[test]
    fn fewer_than_two_links_is_too_few_links(cfg in config(3..=64, 1..=1), keep in 0usize..=1) {
        let (pole, mut links) = raw(&cfg);
        links.truncate(keep);
        let before = links.clone();
        let r = Small::new(pole, &links);
        prop_assert_eq!(r.err(), Some(Error::TooFewLinks { links: keep }));
        prop_assert_eq!(links, before);
    }

    /// Valence 0, 1 or 2: `ValenceTooSmall { valence }`.
    #[test]
    fn valence_below_3_is_valence_too_small(cfg in config(0..=2, 2..=5)) {
        let (pole, links) = raw(&cfg);
        let before = links.clone();
        let r = Small::new(pole, &links);
        prop_assert_eq!(r.err(), Some(Error::ValenceTooSmall { valence: cfg.links[0].len() }));
        prop_assert_eq!(links, before);
    }

    /// One link (2..K) one point longer or shorter than the 1-link:
    /// `LinkLengthMismatch { link, len, expected }` naming that link.
    #[test]
    fn unequal_link_lengths_is_link_length_mismatch(
        cfg in config(3..=64, 2..=5),
        which in any::<prop::sample::Index>(),
        longer in any::<bool>(),
    ) {
        let (pole, mut links) = raw(&cfg);
        let n = links[0].len();
        let i = 1 + which.index(links.len() - 1); // 0-based slot of links 2..K
        if longer {
            links[i].push([0.0; 3]);
        } else {
            links[i].pop();
        }
        let len = links[i].len();
        let before = links.clone();
        let r = Small::new(pole, &links);
        prop_assert_eq!(r.err(), Some(Error::LinkLengthMismatch { link: i + 1, len, expected: n }));
        prop_assert_eq!(links, before);
    }

    /// A NaN or ±∞ anywhere (pole or any link point, any coordinate): `NonFinite`.
    #[test]
    fn non_finite_coordinate_is_non_finite(
        cfg in config(3..=64, 2..=5),
        spot in any::<prop::sample::Index>(),
        coord in 0usize..3,
        bad in prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(f64::NEG_INFINITY)],
    ) {
        let (mut pole, mut links) = raw(&cfg);
        let n = links[0].len();
        let k = spot.index(1 + n * links.len());
        if k == 0 {
            pole[coord] = bad;
        } else {
            links[(k - 1) / n][(k - 1) % n][coord] = bad;
        }
        let before = format!("{links:?}");
        let r = Small::new(pole, &links);
        prop_assert_eq!(r.err(), Some(Error::NonFinite));
        prop_assert_eq!(format!("{links:?}"), before);
    }

    /// Valence above the capacity: `CapacityExceeded { needed: n, capacity }`.
    #[test]
    fn valence_above_capacity_is_capacity_exceeded(cfg in config(3..=64, 2..=5)) {
        let (pole, links) = raw(&cfg);
        let r = PolarNet::<f64, 2>::new(pole, &links);
        prop_assert_eq!(r.err(), Some(Error::CapacityExceeded { needed: cfg.valence(), capacity: 2 }));
    }

    /// Refining until `2N > CAP`: the failing step returns
    /// `CapacityExceeded { needed: 2N, capacity: CAP }` and the net is exactly
    /// as before it; its jet is as before.
    #[test]
    fn step_beyond_capacity_is_capacity_exceeded_and_leaves_net_unchanged(
        cfg in config(3..=64, 2..=5),
        first in prop_oneof![Just(FirstStep::Plain), Just(FirstStep::Uniform)],
    ) {
        let mut net = Small::new(cfg.pole, &cfg.links).unwrap();
        while 2 * net.valence() <= 256 {
            net.step(first).unwrap();
        }
        let before = snapshot(&net);
        let jet_before = capdiv::PoleJet::of(&net);
        let n = net.valence();
        prop_assert_eq!(net.step(first), Err(Error::CapacityExceeded { needed: 2 * n, capacity: 256 }));
        prop_assert_eq!(snapshot(&net), before);
        prop_assert_eq!(capdiv::PoleJet::of(&net), jet_before);
    }
}
