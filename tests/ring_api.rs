//! The three schemes' rings share one API (docs/architecture.md,
//! "Conventions"): `ring_len()`, `ring_patch(k)` in ring order with
//! `Error::OutOfDomain` from `k = ring_len()` on, and `ring_patches()`, a
//! fused `ExactSizeIterator` yielding exactly those patches. Limits that can
//! overflow are checked by `finite()`.

mod eg_support;

use capdiv::eg::{CNet, EgSubdivision};
use capdiv::{CcCap, Error, FirstStep, Point3, PolarNet, PoleJet};
use eg_support::{ExtNet, Rng};

/// What every ring must satisfy: the iterator's length, its patches equal to
/// `ring_patch(k)` in order, the error past the end, fusing, and a clone taken
/// part-way yielding the rest.
fn check_ring<P, I>(len: usize, patches: I, patch: impl Fn(usize) -> Result<P, Error>)
where
    P: PartialEq + core::fmt::Debug,
    I: ExactSizeIterator<Item = P> + core::iter::FusedIterator + Clone,
{
    let mut it = patches;
    assert_eq!(it.len(), len);
    let mut rest = None;
    for k in 0..len {
        if k == len / 2 {
            rest = Some(it.clone());
        }
        assert_eq!(it.next().as_ref(), Some(&patch(k).unwrap()), "patch {k}");
        assert_eq!(it.len(), len - k - 1);
    }
    assert!(it.next().is_none() && it.next().is_none());
    if let Some(rest) = rest {
        let tail: Vec<P> = rest.collect();
        assert_eq!(tail.len(), len - len / 2);
        for (i, p) in tail.iter().enumerate() {
            assert_eq!(p, &patch(len / 2 + i).unwrap());
        }
    }
    for k in [len, len + 1, usize::MAX] {
        assert!(patch(k).is_err(), "patch {k} of {len}");
    }
}

fn polar_links(n: usize, count: usize) -> Vec<Vec<[f64; 3]>> {
    (1..=count)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let t = core::f64::consts::TAU * j as f64 / n as f64;
                    let r = i as f64;
                    [
                        r * t.cos(),
                        r * t.sin(),
                        0.2 * r * r + 0.05 * (j % 3) as f64,
                    ]
                })
                .collect()
        })
        .collect()
}

#[test]
fn polar_ring_has_the_common_shape() {
    // From 2 links: no ring until 5 links are held (after 2 steps).
    let mut net: PolarNet<f64, 20> = PolarNet::new([0.0; 3], &polar_links(5, 2)).unwrap();
    for _ in 0..2 {
        assert_eq!(net.ring_len(), 0);
        assert_eq!(net.ring_patches().len(), 0);
        for k in [0, 1, 2 * net.valence()] {
            assert!(matches!(
                net.ring_patch(k),
                Err(Error::NotEnoughLinks { needed: 5, .. })
            ));
        }
        net.step(FirstStep::Uniform).unwrap();
    }
    assert_eq!((net.valence(), net.link_count()), (20, 5));
    assert_eq!(net.ring_len(), 2 * 20);
    check_ring(net.ring_len(), net.ring_patches(), |k| net.ring_patch(k));
    assert_eq!(net.ring_patch(net.ring_len()), Err(Error::OutOfDomain));
    // Ring order: k = span·N + column; span 1 starts where span 0's
    // column ends (r = 3), column by column.
    let n = net.valence();
    for c in 0..n {
        let inner = net.ring_patch(c).unwrap().points;
        let outer = net.ring_patch(n + c).unwrap().points;
        for j in 0..4 {
            assert!(inner[3][j].max_abs_diff(outer[0][j]) < 1e-13, "column {c}");
        }
    }
}

#[test]
fn eg_and_cc_rings_have_the_common_shape() {
    let mut rng = Rng(31337);
    for n in [3, 5] {
        let ext = ExtNet::random(n, &mut rng, 0.2);
        let nodes = ext.cnet_nodes();
        let net = CNet::new(ext.center, &nodes).unwrap();
        let mut eg = EgSubdivision::new(&net, None).unwrap();
        let mut storage = vec![Point3::ZERO; CcCap::<f64>::storage_len(n)];
        let mut cc = CcCap::new(ext.center, &nodes, &mut storage).unwrap();
        // No ring before the first step.
        assert_eq!((eg.ring_len(), eg.ring_patches().len()), (0, 0));
        assert_eq!((cc.ring_len(), cc.ring_patches().len()), (0, 0));
        assert_eq!(eg.ring_patch(0), Err(Error::OutOfDomain));
        assert_eq!(cc.ring_patch(0), Err(Error::OutOfDomain));
        for _ in 0..2 {
            eg.step().unwrap();
            cc.step().unwrap();
            assert_eq!((eg.ring_len(), cc.ring_len()), (3 * n, 3 * n));
            check_ring(eg.ring_len(), eg.ring_patches(), |k| eg.ring_patch(k));
            check_ring(cc.ring_len(), cc.ring_patches(), |k| cc.ring_patch(k));
            assert_eq!(eg.ring_patch(3 * n), Err(Error::OutOfDomain));
            assert_eq!(cc.ring_patch(3 * n), Err(Error::OutOfDomain));
            // Same order: patch k of both lies on the same square.
            for k in 0..3 * n {
                assert_eq!(eg.ring_patch_domain(k), cc.ring_patch_domain(k));
            }
        }
    }
}

#[test]
fn limits_are_checked_by_finite() {
    assert_eq!(
        Point3([1.0, -2.0, 0.5]).finite(),
        Ok(Point3([1.0, -2.0, 0.5]))
    );
    for bad in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
        assert_eq!(Point3([0.0, bad, 0.0]).finite(), Err(Error::NonFinite));
    }
    // A Catmull-Clark net with coordinates of both signs near MAX: its limit
    // overflows, and finite() says so; a moderate one passes unchanged.
    let n = 3;
    let big = f64::MAX * 0.9;
    let nodes: Vec<[f64; 3]> = (0..6 * n)
        .map(|i| {
            if i % 2 == 0 {
                [big, 0.0, 0.0]
            } else {
                [-big, 0.0, 0.0]
            }
        })
        .collect();
    let mut storage = vec![Point3::ZERO; CcCap::<f64>::storage_len(n)];
    let cc = CcCap::new([-big, 0.0, 0.0], &nodes, &mut storage).unwrap();
    assert!(!cc.limit().is_finite());
    assert_eq!(cc.limit().finite(), Err(Error::NonFinite));
    let small: Vec<[f64; 3]> = nodes.iter().map(|p| p.map(|c| c * 1e-300)).collect();
    let mut storage = vec![Point3::ZERO; CcCap::<f64>::storage_len(n)];
    let cc = CcCap::new([0.0; 3], &small, &mut storage).unwrap();
    assert_eq!(cc.limit().finite(), Ok(cc.limit()));
    // The C²PS jet: the same check.
    let net: PolarNet<f64, 6> = PolarNet::new([0.0; 3], &polar_links(6, 5)).unwrap();
    let jet = PoleJet::of(&net);
    assert_eq!(jet.finite(), Ok(jet));
    let mut bad = jet;
    bad.p[4] = Point3([0.0, f64::INFINITY, 0.0]);
    assert_eq!(bad.finite(), Err(Error::NonFinite));
}
