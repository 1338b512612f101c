//! Shared by the property tests: conversion between the kernel's `PolarNet`
//! and the reference's `Polar`, comparison, and proptest strategies.
#![allow(dead_code)]

use capdiv::{PolarNet, Real};
use capdiv_reference::polar::Polar;
use capdiv_reference::vec3::{max_abs_diff, P3};
use proptest::prelude::*;

/// Capacity of every test net: valence 64 refined 8 times.
pub const CAP: usize = 64 << 8;
/// The f64 kernel net of the tests.
pub type Net = PolarNet<f64, CAP>;
/// The f32 kernel net of the tests.
pub type Net32 = PolarNet<f32, CAP>;

/// A kernel net (scalar `R`) from a reference configuration.
pub fn to_net<R: Real, const C: usize>(cfg: &Polar) -> PolarNet<R, C> {
    let conv = |p: &P3| p.map(R::from_f64);
    let links: Vec<Vec<[R; 3]>> = cfg
        .links
        .iter()
        .map(|l| l.iter().map(conv).collect())
        .collect();
    PolarNet::new(conv(&cfg.pole), &links).expect("test data is a valid configuration")
}

/// The reference view (`f64`) of a kernel net: pole and the links it holds.
pub fn from_net<R: Real, const C: usize>(net: &PolarNet<R, C>) -> Polar {
    let conv = |p: &capdiv::Point3<R>| p.0.map(|c| c.to_f64());
    Polar {
        pole: conv(&net.pole()),
        links: (1..=net.link_count())
            .map(|i| net.link(i).expect("held").iter().map(conv).collect())
            .collect(),
    }
}

/// Largest coordinate difference of two configurations of the same shape.
pub fn max_diff(a: &Polar, b: &Polar) -> f64 {
    assert_eq!(a.links.len(), b.links.len(), "link counts differ");
    let mut m = max_abs_diff(a.pole, b.pole);
    for (la, lb) in a.links.iter().zip(&b.links) {
        assert_eq!(la.len(), lb.len(), "link lengths differ");
        for (p, q) in la.iter().zip(lb) {
            m = m.max(max_abs_diff(*p, *q));
        }
    }
    m
}

/// A point with coordinates in `[-1, 1]`.
pub fn point() -> impl Strategy<Value = P3> {
    [-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0]
}

/// A configuration of valence in `valences` with a link count in `links`,
/// points uniform in `[-1, 1]³` (generic data: no structure to hide errors).
pub fn config(
    valences: std::ops::RangeInclusive<usize>,
    links: std::ops::RangeInclusive<usize>,
) -> impl Strategy<Value = Polar> {
    (valences, links).prop_flat_map(|(n, k)| {
        (
            point(),
            proptest::collection::vec(proptest::collection::vec(point(), n), k),
        )
            .prop_map(|(pole, links)| Polar::new(pole, links))
    })
}

/// The deepest level `≤ depth` whose valence `n·2^m` stays within `max_valence`.
pub fn clamp_depth(n: usize, depth: u32, max_valence: usize) -> u32 {
    let mut d = depth;
    while d > 0 && n << d > max_valence {
        d -= 1;
    }
    d
}
