//! `PolarNetBuf` (a C²PS net in caller storage) against `PolarNet`: the same
//! pole, links, roots, ring patches and jet bit for bit at every level, for
//! C²PS and RTS steps, f32 and f64, both first-step variants; the same errors
//! in the same order; storage too small is `CapacityExceeded` with the
//! storage and the net unchanged.

use capdiv::{
    BicubicPatch, Error, FirstStep, NetStorage, Point3, PolarNet, PolarNetBuf, PolarNetInner,
    PoleJet, Real, SliceStorage,
};
use proptest::prelude::*;

/// Capacity of the reference nets: valence 64, depth 6.
/// Capacity of the reference `PolarNet` (under Miri, whose cases are small,
/// 256: every PolarNet construction touches its whole array).
const CAP: usize = if cfg!(miri) { 256 } else { 64 << 6 };

/// Bit patterns of every coordinate (f32 → f64 is exact and injective).
fn bits<R: Real>(pts: &[Point3<R>]) -> Vec<u64> {
    pts.iter()
        .flat_map(|p| p.0.map(|c| c.to_f64().to_bits()))
        .collect()
}

fn patch_bits<R: Real>(patches: impl Iterator<Item = BicubicPatch<R>>) -> Vec<u64> {
    patches
        .flat_map(|p| bits(p.points.as_flattened()))
        .collect()
}

fn root_bits<R: Real>(roots: &[[R; 2]]) -> Vec<u64> {
    roots
        .iter()
        .flat_map(|r| r.map(|c| c.to_f64().to_bits()))
        .collect()
}

/// Everything observable about a polar net over any storage, as bits.
fn observe<R: Real, S: NetStorage<R>>(net: &PolarNetInner<R, S>) -> Vec<Vec<u64>> {
    let mut out = vec![
        vec![
            net.valence() as u64,
            net.base_valence() as u64,
            net.level() as u64,
            net.link_count() as u64,
            net.ring_len() as u64,
        ],
        bits(&[net.pole()]),
        root_bits(net.roots()),
        bits(&PoleJet::of(net).p),
    ];
    for i in 0..=6 {
        out.push(net.link(i).map_or(vec![u64::MAX], bits));
    }
    let p = net.ring_patches();
    assert_eq!(p.len(), net.ring_len());
    out.push(patch_bits(p));
    out.push(err_bits(net.ring_patch(2 * net.valence())));
    out.push(err_bits(net.ring_patch(usize::MAX)));
    out.push(err_bits(
        net.ring_patch((2 * net.valence()).saturating_sub(1)),
    ));
    out
}

fn err_bits<R: Real>(r: Result<BicubicPatch<R>, Error>) -> Vec<u64> {
    match r {
        Ok(p) => bits(p.points.as_flattened()),
        Err(e) => vec![u64::MAX, format!("{e:?}").bytes().map(u64::from).sum()],
    }
}

/// A random polar configuration: `count` links of valence `n`, a bumpy cone
/// with random noise.
fn config(n: usize, count: usize, noise: &[f64], seed: u64) -> ([f64; 3], Vec<Vec<[f64; 3]>>) {
    let mut k = seed as usize;
    let mut next = || {
        k = k.wrapping_add(1);
        noise[k % noise.len()]
    };
    let pole = [0.1 * next(), 0.1 * next(), 0.2 * next()];
    let links = (1..=count)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / n as f64;
                    let r = i as f64 * (1.0 + 0.2 * next());
                    [
                        r * t.cos() + 0.1 * next(),
                        r * t.sin() + 0.1 * next(),
                        0.3 * r * r * next() + 0.1 * (2.0 * t).sin(),
                    ]
                })
                .collect()
        })
        .collect();
    (pole, links)
}

fn cast<R: Real>(links: &[Vec<[f64; 3]>]) -> Vec<Vec<[R; 3]>> {
    links
        .iter()
        .map(|l| l.iter().map(|p| p.map(R::from_f64)).collect())
        .collect()
}

/// Steps both nets through `ops` (true: C²PS, false: RTS) and compares them
/// after every operation. The buffer net's storage is exactly `n·2^depth`.
fn compare<R: Real>(
    pole: [f64; 3],
    links: &[Vec<[f64; 3]>],
    ops: &[bool],
    first: FirstStep,
) -> Result<(), TestCaseError> {
    let pole = pole.map(R::from_f64);
    let links = cast::<R>(links);
    let n = links[0].len();
    let depth = ops.iter().filter(|&&c| c).count() as u32;
    let cap = capdiv::polar::capacity_for(n, depth).unwrap();
    prop_assert!(cap <= CAP);
    let mut reference: Box<PolarNet<R, CAP>> = Box::new(PolarNet::empty());
    reference.reset(pole, &links).unwrap();
    let mut link_storage = vec![Point3([R::ZERO; 3]); SliceStorage::<R>::links_len(cap)];
    let mut root_storage = vec![[R::ZERO; 2]; SliceStorage::<R>::roots_len(cap)];
    let mut net = PolarNetBuf::new_in(
        pole,
        &links,
        SliceStorage::new(&mut link_storage, &mut root_storage),
    )
    .unwrap();
    prop_assert_eq!(net.capacity(), cap);
    prop_assert_eq!(observe(&net), observe(&*reference));
    for &c2ps in ops {
        if c2ps {
            prop_assert_eq!(net.step(first), reference.step(first));
        } else {
            prop_assert_eq!(net.rts_step(), reference.rts_step());
        }
        prop_assert_eq!(observe(&net), observe(&*reference));
    }
    // The storage is full: one more step fails and changes nothing.
    let before = observe(&net);
    prop_assert_eq!(
        net.step(first),
        Err(Error::CapacityExceeded {
            needed: 2 * cap,
            capacity: cap
        })
    );
    prop_assert_eq!(observe(&net), before);
    // `reset` reuses the storage: the level-0 net again.
    net.reset(pole, &links).unwrap();
    reference.reset(pole, &links).unwrap();
    prop_assert_eq!(observe(&net), observe(&*reference));
    Ok(())
}

fn first_step() -> impl Strategy<Value = FirstStep> {
    prop_oneof![Just(FirstStep::Uniform), Just(FirstStep::Plain)]
}

/// Random configurations: valence 3..=64, 2..=7 links, 0..=6 C²PS steps with
/// RTS steps mixed in (at most one between two C²PS steps). Under Miri
/// (~10⁴× slower than native here) valence 3..=8 and at most 2 steps.
fn case() -> impl Strategy<Value = (usize, usize, Vec<f64>, u64, Vec<bool>, FirstStep)> {
    let (max_n, max_steps) = if cfg!(miri) { (8, 2) } else { (64, 6) };
    (
        3usize..=max_n,
        2usize..=7,
        prop::collection::vec(-1.0f64..1.0, 1..64),
        any::<u64>(),
        prop::collection::vec((any::<bool>(), prop::bool::weighted(0.15)), 0..=max_steps),
        first_step(),
    )
        .prop_map(|(n, count, noise, seed, steps, first)| {
            let ops = steps
                .into_iter()
                .flat_map(|(rts_before, rts)| {
                    let mut v = Vec::new();
                    if rts_before && rts {
                        v.push(false);
                    }
                    v.push(true);
                    v
                })
                .collect();
            (n, count, noise, seed, ops, first)
        })
}

proptest! {
    #![proptest_config(ProptestConfig {
        // Under Miri: a couple of cases, no regression files (isolation).
        cases: if cfg!(miri) { 2 } else { 96 },
        failure_persistence: if cfg!(miri) { None } else { ProptestConfig::default().failure_persistence },
        ..ProptestConfig::default()
    })]

    #[test]
    fn same_bits_as_polar_net_f64((n, count, noise, seed, ops, first) in case()) {
        let (pole, links) = config(n, count, &noise, seed);
        compare::<f64>(pole, &links, &ops, first)?;
    }

    #[test]
    fn same_bits_as_polar_net_f32((n, count, noise, seed, ops, first) in case()) {
        let (pole, links) = config(n, count, &noise, seed);
        compare::<f32>(pole, &links, &ops, first)?;
    }

    /// Storage below the valence: `CapacityExceeded { needed: n, capacity }`,
    /// nothing written, and a net already held stays as it was.
    #[test]
    fn storage_too_small_is_capacity_exceeded(
        n in 10usize..=64,
        short in 1usize..=3,
        links_short in any::<bool>(),
        noise in prop::collection::vec(-1.0f64..1.0, 1..16),
        seed in any::<u64>(),
    ) {
        let (pole, links) = config(n, 5, &noise, seed);
        let cap = n - short;
        let sentinel = Point3([-7.5f64; 3]);
        let (l_len, r_len) = if links_short {
            // Links short, roots ample.
            (SliceStorage::<f64>::links_len(cap) + 4, n + 10)
        } else {
            (SliceStorage::<f64>::links_len(n) + 4, cap)
        };
        let mut ls = vec![sentinel; l_len];
        let mut rs = vec![[0.25f64; 2]; r_len];
        let r = PolarNetBuf::new_in(pole, &links, SliceStorage::new(&mut ls, &mut rs));
        prop_assert_eq!(r.err(), Some(Error::CapacityExceeded { needed: n, capacity: cap }));
        prop_assert!(ls.iter().all(|p| *p == sentinel));
        prop_assert!(rs.iter().all(|r| *r == [0.25; 2]));

        // A net holding a smaller configuration refuses the larger one unchanged.
        let (small_pole, small_links) = config(3, 4, &noise, seed ^ 1);
        let mut net = PolarNetBuf::new_in(small_pole, &small_links, SliceStorage::new(&mut ls, &mut rs)).unwrap();
        net.step(FirstStep::Plain).unwrap();
        let before = observe(&net);
        prop_assert_eq!(
            net.reset(pole, &links),
            Err(Error::CapacityExceeded { needed: n, capacity: cap })
        );
        prop_assert_eq!(observe(&net), before);
        let (ls2, rs2) = net.into_storage().into_parts();
        let (ls2, rs2) = (ls2.to_vec(), rs2.to_vec());
        let mut net = PolarNetBuf::new_in(small_pole, &small_links, SliceStorage::new(&mut ls, &mut rs)).unwrap();
        net.step(FirstStep::Plain).unwrap();
        let _ = net.reset(pole, &links);
        let (ls3, rs3) = net.into_storage().into_parts();
        prop_assert_eq!(bits(&ls2), bits(ls3));
        prop_assert_eq!(root_bits(&rs2), root_bits(rs3));
    }

    /// Every bad input: the error `PolarNet::new` gives (same capacity), the
    /// storage untouched; the same for the flat constructors.
    #[test]
    fn bad_input_gives_polar_nets_error(
        n in 1usize..=80,
        count in 0usize..=6,
        defect in 0usize..6,
        at in any::<prop::sample::Index>(),
        noise in prop::collection::vec(-1.0f64..1.0, 1..16),
        seed in any::<u64>(),
    ) {
        let (mut pole, mut links) = config(n, count, &noise, seed);
        match defect {
            0 => {}
            1 if !links.is_empty() => {
                // A link of another length.
                let i = at.index(links.len());
                links[i].push([0.5; 3]);
            }
            2 if !links.is_empty() && n > 0 => {
                let i = at.index(links.len());
                links[i][at.index(n)][at.index(3)] = f64::NAN;
            }
            3 => pole[at.index(3)] = f64::INFINITY,
            4 if !links.is_empty() && n > 1 => {
                let i = at.index(links.len());
                links[i].pop();
            }
            _ => {}
        }
        const SMALL: usize = 64;
        let expected = PolarNet::<f64, SMALL>::new(pole, &links).err();
        let sentinel = Point3([3.25f64; 3]);
        let mut ls = vec![sentinel; SliceStorage::<f64>::links_len(SMALL)];
        let mut rs = vec![[0.5f64; 2]; SliceStorage::<f64>::roots_len(SMALL)];
        let got = PolarNetBuf::new_in(pole, &links, SliceStorage::new(&mut ls, &mut rs)).err();
        prop_assert_eq!(got, expected);
        if expected.is_some() {
            prop_assert!(ls.iter().all(|p| *p == sentinel));
            prop_assert!(rs.iter().all(|r| *r == [0.5; 2]));
        }

        // Flat coordinates, with a few truncations.
        let mut flat: Vec<f64> = links.iter().flatten().flatten().copied().collect();
        flat.truncate(flat.len().saturating_sub(at.index(4)));
        let expected = PolarNet::<f64, SMALL>::from_flat(pole, n, &flat).err();
        let got = PolarNetBuf::from_flat_in(pole, n, &flat, SliceStorage::new(&mut ls, &mut rs)).err();
        prop_assert_eq!(got, expected);
    }
}

#[test]
fn unsupported_valence_and_order_of_errors() {
    // Odd part 131 > 127: unsupported, checked after the capacity.
    let (pole, links) = config(131, 2, &[0.3, -0.2, 0.7], 1);
    let mut ls = vec![Point3::ZERO; SliceStorage::<f64>::links_len(256)];
    let mut rs = vec![[0.0f64; 2]; 256];
    assert_eq!(
        PolarNetBuf::new_in(pole, &links, SliceStorage::new(&mut ls, &mut rs)).err(),
        PolarNet::<f64, 256>::new(pole, &links).err()
    );
    assert_eq!(
        PolarNetBuf::new_in(pole, &links, SliceStorage::new(&mut ls, &mut rs)).err(),
        Some(Error::ValenceUnsupported { valence: 131 })
    );
    let (small_ls, small_rs) = (&mut ls[..5 * 100], &mut rs[..100]);
    assert_eq!(
        PolarNetBuf::new_in(pole, &links, SliceStorage::new(small_ls, small_rs)).err(),
        Some(Error::CapacityExceeded {
            needed: 131,
            capacity: 100
        })
    );
}

#[test]
fn empty_net_behaves_like_polar_net_empty() {
    let mut ls = [Point3::<f32>::ZERO; 40];
    let mut rs = [[0.0f32; 2]; 8];
    let mut net = PolarNetBuf::empty_in(SliceStorage::new(&mut ls, &mut rs));
    let mut reference: PolarNet<f32, 8> = PolarNet::empty();
    assert_eq!(net.capacity(), 8);
    assert_eq!(observe(&net), observe(&reference));
    assert_eq!(
        net.step(FirstStep::Uniform),
        reference.step(FirstStep::Uniform)
    );
    assert_eq!(net.rts_step(), reference.rts_step());
    assert_eq!(observe(&net), observe(&reference));
    assert_eq!(
        PoleJet::of(&net).geometry(),
        PoleJet::of(&reference).geometry()
    );
    // Zero-sized storage: capacity 0, every valence exceeds it.
    let mut none: [Point3<f32>; 0] = [];
    let mut no_roots: [[f32; 2]; 0] = [];
    let (pole, links) = config(3, 2, &[0.1], 0);
    let links = cast::<f32>(&links);
    assert_eq!(
        PolarNetBuf::new_in(
            pole.map(|c| c as f32),
            &links,
            SliceStorage::new(&mut none, &mut no_roots)
        )
        .err(),
        Some(Error::CapacityExceeded {
            needed: 3,
            capacity: 0
        })
    );
}

/// The case that motivated the type: f64, capacity 2^17 (17.8 MB), which a
/// `Box::new(PolarNet::empty())` overflows the stack building in a debug
/// build. Here the storage is two `Vec`s; valence 4 refined to 2^17.
#[test]
fn large_capacity_in_heap_storage() {
    // Under Miri (millions of points are out of reach there) depth 5.
    let depth = if cfg!(miri) { 5 } else { 15 };
    let cap = capdiv::polar::capacity_for(4, depth).unwrap();
    assert_eq!(cap, 1 << (depth + 2));
    let mut ls = vec![Point3::<f64>::ZERO; SliceStorage::<f64>::links_len(cap)];
    let mut rs = vec![[0.0f64; 2]; SliceStorage::<f64>::roots_len(cap)];
    let (pole, links) = config(4, 3, &[0.3, -0.1, 0.2, 0.5], 9);
    let mut net = PolarNetBuf::new_in(pole, &links, SliceStorage::new(&mut ls, &mut rs)).unwrap();
    for _ in 0..depth {
        net.step(FirstStep::Uniform).unwrap();
    }
    assert_eq!(net.valence(), 1 << (depth + 2));
    assert_eq!(net.ring_patches().len(), 1 << (depth + 3));
    let jet = PoleJet::of(&net);
    assert!(jet.p.iter().all(|p| p.0.iter().all(|c| c.is_finite())));
    assert!(matches!(
        net.step(FirstStep::Uniform),
        Err(Error::CapacityExceeded { .. })
    ));
    assert_eq!(capdiv::polar::capacity_for(3, 64), None);
    assert_eq!(capdiv::polar::capacity_for(usize::MAX, 1), None);
}
