//! In-place EG construction (`CNet`/`DNet`/`EgSubdivision::empty` + `reset*`,
//! for statics and small stacks) gives exactly what the by-value constructors
//! give; the double-buffered `step` (new net written over the previous one)
//! gives exactly the out-of-place `DNet::refined` chain; bad input and a
//! failing step leave everything unchanged (docs/math/eg.md §1–§9; kernel rule:
//! every bad input a typed error, state untouched).

mod eg_support;

use capdiv::bezier::BiquarticPatch;
use capdiv::eg::tables::{A11_5, A21_5, A22_5, A31_5, A32_5};
use capdiv::eg::{CNet, DNet, EgSubdivision, RuleTable};
use capdiv::{Error, Real};
use eg_support::{ExtNet, Rng};

fn cnet(n: usize, seed: u64) -> CNet<f64> {
    let e = ExtNet::random(n, &mut Rng(seed), 0.3);
    CNet::new(e.center, &e.cnet_nodes()).unwrap()
}

/// Everything observable about a subdivision, for exact comparison.
#[derive(Debug, PartialEq)]
struct State<R> {
    valence: usize,
    level: u32,
    c0: [R; 3],
    net: Option<DNet<R>>,
    previous: Option<DNet<R>>,
    ring: Vec<BiquarticPatch<R>>,
    table: Option<RuleTable<'static>>,
}

fn state<R: Real>(s: &EgSubdivision<'static, R>) -> State<R> {
    State {
        valence: s.valence(),
        level: s.level(),
        c0: s.limit().0,
        net: (s.valence() > 0).then(|| s.net().clone()),
        previous: s.previous().cloned(),
        ring: s.ring_patches().collect(),
        table: s.table().copied(),
    }
}

/// Bit patterns of every coordinate (so −0.0 ≠ 0.0 and NaN = NaN).
fn bits(net: &DNet<f64>) -> Vec<u64> {
    let mut v: Vec<u64> = net.c0().0.iter().map(|c| c.to_bits()).collect();
    v.extend(
        net.sectors()
            .iter()
            .flatten()
            .flat_map(|p| p.0.map(f64::to_bits)),
    );
    v
}

#[test]
fn empty_values_are_empty_and_refuse_to_step() {
    let c: CNet<f32> = CNet::empty();
    assert_eq!(c.valence(), 0);
    let d: DNet<f32> = DNet::empty();
    assert_eq!(d.valence(), 0);
    let mut sub: EgSubdivision<'static, f32> = EgSubdivision::empty();
    assert_eq!((sub.valence(), sub.level(), sub.ring_len()), (0, 0, 0));
    assert_eq!(sub.step(), Err(Error::ValenceTooSmall { valence: 0 }));
    assert!(sub.previous().is_none());
    assert_eq!(sub.ring_patches().count(), 0);
    assert_eq!(sub.ring_patch(0).unwrap_err(), Error::OutOfDomain);
    // An empty c-net or d-net cannot start a subdivision.
    assert_eq!(
        sub.reset(&c, None),
        Err(Error::ValenceTooSmall { valence: 0 })
    );
    assert_eq!(
        sub.reset(&d, None),
        Err(Error::ValenceTooSmall { valence: 0 })
    );
    assert_eq!(sub.level(), 0);
    // `empty` is a const fn: usable to initialise a static.
    static EMPTY: EgSubdivision<'static, f32> = EgSubdivision::empty();
    assert_eq!(EMPTY.valence(), 0);
}

#[test]
fn net_resets_equal_constructors() {
    let mut c = CNet::empty();
    let mut d = DNet::empty();
    // Under Miri (an EG net operation takes a second there) two nets.
    let nets: &[(usize, u64)] = if cfg!(miri) {
        &[(5, 1), (10, 3)]
    } else {
        &[(5, 1), (3, 2), (10, 3), (4, 4)]
    };
    for &(n, seed) in nets {
        let e = ExtNet::random(n, &mut Rng(seed), 0.3);
        let nodes = e.cnet_nodes();
        c.reset(e.center, &nodes).unwrap();
        assert_eq!(c, CNet::new(e.center, &nodes).unwrap());
        let flat: Vec<f64> = nodes.iter().flatten().copied().collect();
        c.reset_flat(e.center, &flat).unwrap();
        assert_eq!(c, CNet::new(e.center, &nodes).unwrap());

        // d-net: in place from the c-net, from nodes (c0 given or fitted),
        // from flat coordinates, from sectors.
        let raised = c.to_dnet();
        d.reset_from_cnet(&c);
        assert_eq!(bits(&d), bits(&raised));
        let dn: Vec<[f64; 3]> = raised.sectors().iter().flatten().map(|p| p.0).collect();
        for c0 in [None, Some([0.5, -1.0, 2.0])] {
            d.reset(&dn, c0).unwrap();
            let want = DNet::new(&dn, c0).unwrap();
            assert_eq!(bits(&d), bits(&want));
            let df: Vec<f64> = dn.iter().flatten().copied().collect();
            d.reset_flat(&df, c0).unwrap();
            assert_eq!(bits(&d), bits(&want));
            let secs: Vec<[[f64; 3]; 12]> =
                raised.sectors().iter().map(|s| s.map(|p| p.0)).collect();
            d.reset_sectors(&secs, c0).unwrap();
            assert_eq!(bits(&d), bits(&want));
        }
        // Fitted c0 of a raised net is formula (4) of it, as before.
        d.reset(&dn, None).unwrap();
        assert_eq!(d.c0(), raised.fitted_limit());
    }
}

#[test]
fn reset_equals_new_and_steps_equal_the_refined_chain() {
    // One subdivision reused for every net, valence changing between uses.
    let mut sub = EgSubdivision::empty();
    // Under Miri (an EG step takes seconds there) at most one step.
    let nets: &[(usize, u64, u32)] = if cfg!(miri) {
        &[(5, 11, 1), (3, 12, 1), (4, 13, 0), (3, 15, 0)]
    } else {
        &[(5, 11, 4), (3, 12, 5), (4, 13, 3), (5, 14, 1), (3, 15, 0)]
    };
    for &(n, seed, steps) in nets {
        let c = cnet(n, seed);
        sub.reset(&c, None).unwrap();
        let mut fresh = EgSubdivision::new(&c, None).unwrap();
        assert_eq!(state(&sub), state(&fresh));
        // The same from the raised d-net, with `reset`.
        let mut again = EgSubdivision::empty();
        again.reset(&c.to_dnet(), None).unwrap();
        assert_eq!(state(&again), state(&fresh));

        // Each step's net and predecessor are the out-of-place refinements
        // (`DNet::refined` builds a fresh net) bit for bit.
        let mut chain = vec![c.to_dnet()];
        for m in 1..=steps {
            sub.step().unwrap();
            fresh.step().unwrap();
            let next = chain.last().unwrap().refined(None).unwrap();
            chain.push(next);
            assert_eq!(sub.level(), m);
            assert_eq!(bits(sub.net()), bits(&chain[m as usize]));
            assert_eq!(bits(sub.previous().unwrap()), bits(&chain[m as usize - 1]));
            assert_eq!(sub.limit(), c.limit());
            assert_eq!(state(&sub), state(&fresh));
        }
    }
}

#[test]
fn reset_with_a_table_equals_new_with_the_table() {
    // Under Miri the built-in table: RuleTable::new's spectral check runs 96
    // EG steps (minutes there).
    let table = if cfg!(miri) {
        RuleTable::builtin(5).unwrap()
    } else {
        RuleTable::new(5, &A11_5, &A22_5, &A21_5, &A31_5, &A32_5).unwrap()
    };
    let c = cnet(5, 21);
    let mut a = EgSubdivision::empty();
    a.reset(&c, Some(table)).unwrap();
    let mut b = EgSubdivision::new(&c.to_dnet(), Some(table)).unwrap();
    let mut d = EgSubdivision::empty();
    d.reset(&c.to_dnet(), Some(table)).unwrap();
    for _ in 0..if cfg!(miri) { 1 } else { 3 } {
        a.step().unwrap();
        b.step().unwrap();
        d.step().unwrap();
    }
    assert_eq!(state(&a), state(&b));
    assert_eq!(state(&d), state(&b));
}

#[test]
fn bad_input_leaves_everything_unchanged() {
    let c5 = cnet(5, 31);
    let mut sub = EgSubdivision::new(&c5, None).unwrap();
    // Under Miri (an EG step takes seconds there) no step before the errors.
    let pre = if cfg!(miri) { 0 } else { 2 };
    for _ in 0..pre {
        sub.step().unwrap();
    }
    let before = state(&sub);

    // A c-net whose raised d-net overflows.
    let e = ExtNet::random(3, &mut Rng(32), 0.3);
    let mut far = e.cnet_nodes();
    far.iter_mut().for_each(|p| p[0] = 1.5e308);
    let huge = CNet::new([-1.5e308, 0.0, 0.0], &far).unwrap();
    assert!(!huge.to_dnet().is_finite());
    assert_eq!(sub.reset(&huge, None), Err(Error::NonFinite));
    assert_eq!(sub.reset(&huge.to_dnet(), None), Err(Error::NonFinite));
    // Valences without a built-in rule.
    let c6 = cnet(6, 33);
    assert_eq!(
        sub.reset(&c6, None),
        Err(Error::ValenceUnsupported { valence: 6 })
    );
    assert_eq!(
        sub.reset(&c6.to_dnet(), None),
        Err(Error::ValenceUnsupported { valence: 6 })
    );
    // A table of another valence.
    let t3 = RuleTable::builtin(3).unwrap();
    assert_eq!(sub.reset(&c5.to_dnet(), Some(t3)), Err(Error::TableShape));
    assert_eq!(sub.reset(&c5, Some(t3)), Err(Error::TableShape));
    assert_eq!(state(&sub), before);
    // Still steps on as if nothing happened.
    let mut twin = EgSubdivision::new(&c5, None).unwrap();
    for _ in 0..pre + 1 {
        twin.step().unwrap();
    }
    sub.step().unwrap();
    assert_eq!(state(&sub), state(&twin));

    // CNet / DNet resets: every error leaves the net as it was.
    let mut c = cnet(3, 34);
    let keep = c.clone();
    let (center, nodes) = (e.center, e.cnet_nodes());
    assert_eq!(
        c.reset(center, &nodes[..17]),
        Err(Error::WrongLength {
            expected: 18,
            found: 17
        })
    );
    assert_eq!(
        c.reset(center, &nodes[..12]),
        Err(Error::ValenceTooSmall { valence: 2 })
    );
    let mut bad = nodes.clone();
    bad[7][2] = f64::NAN;
    assert_eq!(c.reset(center, &bad), Err(Error::NonFinite));
    assert_eq!(
        c.reset([f64::INFINITY, 0.0, 0.0], &nodes),
        Err(Error::NonFinite)
    );
    assert_eq!(
        c.reset_flat(center, &[0.0; 53]),
        Err(Error::WrongLength {
            expected: 54,
            found: 53
        })
    );
    let big = vec![[1.0, 2.0, 3.0]; 66];
    assert_eq!(
        c.reset(center, &big),
        Err(Error::ValenceUnsupported { valence: 11 })
    );
    assert_eq!(c, keep);

    let mut d = c5.to_dnet();
    let keep = bits(&d);
    let dn: Vec<[f64; 3]> = c
        .to_dnet()
        .sectors()
        .iter()
        .flatten()
        .map(|p| p.0)
        .collect();
    assert_eq!(
        d.reset(&dn[..35], None),
        Err(Error::WrongLength {
            expected: 36,
            found: 35
        })
    );
    let mut bad = dn.clone();
    bad[20][0] = f64::NEG_INFINITY;
    assert_eq!(d.reset(&bad, None), Err(Error::NonFinite));
    assert_eq!(
        d.reset(&dn, Some([0.0, f64::NAN, 0.0])),
        Err(Error::NonFinite)
    );
    // Finite nodes whose fitted c0 (4) overflows.
    let mut wild = dn.clone();
    for (k, p) in wild.iter_mut().enumerate() {
        p[0] = if k % 2 == 0 { 1.7e308 } else { -1.7e308 };
    }
    assert_eq!(d.reset(&wild, None), Err(Error::NonFinite));
    assert_eq!(
        d.reset_flat(&[0.0; 71], None),
        Err(Error::WrongLength {
            expected: 72,
            found: 71
        })
    );
    assert_eq!(bits(&d), keep);
}

/// Largest absolute coordinate of a net (nodes and `c0`).
fn max_abs(net: &DNet<f64>) -> f64 {
    net.sectors()
        .iter()
        .flatten()
        .chain([net.c0()].iter())
        .flat_map(|p| p.0)
        .fold(0.0, |m, c| m.max(c.abs()))
}

/// Each step keeps its result only if finite; otherwise state, previous net
/// and ring stay as they were. Nets with a coordinate above `MAX/1024` go
/// through the kernel's check-first path: those that do not overflow must
/// give exactly the out-of-place result.
#[test]
fn huge_nets_step_exactly_or_fail_unchanged() {
    let (mut checked_first, mut failures) = (0, 0);
    // Under Miri (an EG step takes seconds there) valence 4 at two scales
    // that take both paths (measured natively: 1e306 steps on through the
    // check-first path, 1e307 overflows in the first step), one step.
    let (nets, scales, steps): (&[(usize, u64)], &[f64], usize) = if cfg!(miri) {
        (&[(4, 42)], &[1e306, 1e307], 1)
    } else {
        (
            &[(3, 41), (4, 42), (5, 43)],
            &[1e300, 1e305, 1e306, 3e306, 1e307, 2e307, 3e307, 5e307],
            4,
        )
    };
    for &(n, seed) in nets {
        let e = ExtNet::random(n, &mut Rng(seed), 0.5);
        let base = CNet::new(e.center, &e.cnet_nodes()).unwrap().to_dnet();
        let nodes: Vec<[f64; 3]> = base.sectors().iter().flatten().map(|p| p.0).collect();
        // Scale the net up towards the largest finite f64, c0 far the other
        // way, so that the differences d − c0 come near (or past) overflow.
        for &f in scales {
            let scaled: Vec<[f64; 3]> = nodes.iter().map(|p| p.map(|c| c * f)).collect();
            let Ok(d) = DNet::new(&scaled, Some([-f * 10.0, 0.0, 0.0])) else {
                continue;
            };
            let mut sub = EgSubdivision::new(&d, None).unwrap();
            let mut chain = d;
            for _ in 0..steps {
                let before = state(&sub);
                let slow = !(max_abs(&chain) * 1024.0).is_finite();
                match (sub.step(), chain.refined(None)) {
                    (Ok(()), Ok(next)) => {
                        assert_eq!(bits(sub.net()), bits(&next));
                        assert_eq!(bits(sub.previous().unwrap()), bits(&chain));
                        chain = next;
                        checked_first += usize::from(slow);
                    }
                    (Err(Error::NonFinite), Err(Error::NonFinite)) => {
                        assert!(slow, "a net below MAX/1024 overflowed");
                        assert_eq!(state(&sub), before);
                        failures += 1;
                        break;
                    }
                    (a, b) => panic!("in place {a:?}, out of place {:?}", b.map(|_| ())),
                }
            }
        }
    }
    // Both outcomes of the check-first path were exercised.
    assert!(
        checked_first > 0 && failures > 0,
        "{checked_first} {failures}"
    );
}
