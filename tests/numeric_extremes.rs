//! The numeric contract at the edges of the floating-point range:
//! for huge (near and beyond `MAX/1024`, up to `MAX`), tiny (`MIN_POSITIVE`),
//! subnormal, mixed-scale (one coordinate 1e30, the rest 1e-30) and zero-size
//! nets, in f32 and f64, every call of C²PS (step, RTS step, ring patches,
//! jet), EG (c-net → d-net, steps, ring patches) and Catmull-Clark caps
//! (steps, ring patches, limit, tangents, normal) returns either an error —
//! and then the state is unchanged — or finite output. Never a NaN or an
//! infinity silently.
//!
//! Besides that contract, the magnitudes the README states are pinned: a
//! C²PS/RTS step never fails below `MAX/(16·N)`, an EG step never below
//! `MAX/1024`.

use capdiv::eg::{CNet, EgSubdivision, FourierRule};
use capdiv::{CcCap, Error, FirstStep, Point3, PolarNet, PoleJet, Real};
use proptest::prelude::*;

/// Cases per property (a handful under Miri).
const CASES: u32 = if cfg!(miri) { 2 } else { 256 };

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: CASES,
        failure_persistence: if cfg!(miri) {
            None
        } else {
            ProptestConfig::default().failure_persistence
        },
        ..ProptestConfig::default()
    }
}

/// The range constants of a scalar type, in f64.
trait Range: Real {
    const MAX: f64;
    const MIN_POSITIVE: f64;
    /// The smallest positive subnormal.
    const TINIEST: f64;
}
impl Range for f32 {
    const MAX: f64 = f32::MAX as f64;
    const MIN_POSITIVE: f64 = f32::MIN_POSITIVE as f64;
    const TINIEST: f64 = f32::from_bits(1) as f64;
}
impl Range for f64 {
    const MAX: f64 = f64::MAX;
    const MIN_POSITIVE: f64 = f64::MIN_POSITIVE;
    const TINIEST: f64 = f64::from_bits(1);
}

/// How the coordinates of a net are drawn.
#[derive(Clone, Copy, Debug)]
enum Scale {
    /// `MAX · 2^-k`: `k = 10` is `MAX/1024`.
    Huge(i32),
    /// `MIN_POSITIVE · 2^k`.
    Tiny(i32),
    /// `MIN_POSITIVE · 2^-k`, subnormal (down to the tiniest).
    Subnormal(i32),
    /// One coordinate `big`, the rest `small` (1e30 / 1e-30; f32: 1e30 / 1e-30
    /// as well, 1e-30 being normal there too).
    Mixed,
    /// Every point equal (a net of size zero) at `MAX · 2^-k`.
    Point(i32),
    /// Every point equal, at `MIN_POSITIVE · 2^-k` (subnormal for k ≥ 1).
    PointTiny(i32),
}

fn scale() -> impl Strategy<Value = Scale> {
    prop_oneof![
        3 => (0i32..=24).prop_map(Scale::Huge),
        1 => (0i32..=20).prop_map(Scale::Tiny),
        2 => (1i32..=160).prop_map(Scale::Subnormal),
        1 => Just(Scale::Mixed),
        1 => (0i32..=16).prop_map(Scale::Point),
        1 => (0i32..=30).prop_map(Scale::PointTiny),
    ]
}

/// A deterministic stream of numbers in `[-1, 1]`.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// `count` points at the given scale (the first one is the `Mixed` big one).
fn points<R: Range>(count: usize, scale: Scale, seed: u64) -> Vec<[R; 3]> {
    let mut rng = Rng(seed | 1);
    let max = R::MAX;
    let at = |c: f64| R::from_f64(c);
    let fixed = [rng.next(), rng.next(), rng.next()];
    (0..count)
        .map(|i| {
            let mut p = [0.0f64; 3];
            for (k, c) in p.iter_mut().enumerate() {
                let r = rng.next();
                *c = match scale {
                    Scale::Huge(e) => r * max * libm::exp2(-f64::from(e)),
                    Scale::Tiny(e) => r * R::MIN_POSITIVE * libm::exp2(f64::from(e)),
                    Scale::Subnormal(e) => {
                        let v = r * R::MIN_POSITIVE * libm::exp2(-f64::from(e));
                        if v.abs() < R::TINIEST {
                            R::TINIEST.copysign(r)
                        } else {
                            v
                        }
                    }
                    Scale::Mixed => {
                        if i == 0 && k == 2 {
                            1e30
                        } else {
                            r * 1e-30
                        }
                    }
                    Scale::Point(e) => fixed[k] * max * libm::exp2(-f64::from(e)),
                    Scale::PointTiny(e) => fixed[k] * R::MIN_POSITIVE * libm::exp2(-f64::from(e)),
                };
            }
            p.map(at)
        })
        .collect()
}

/// The largest absolute coordinate, in f64.
fn max_abs<R: Real>(pts: impl IntoIterator<Item = Point3<R>>) -> f64 {
    pts.into_iter()
        .flat_map(|p| p.0)
        .map(|c| c.to_f64().abs())
        .fold(0.0, f64::max)
}

fn finite<R: Real>(pts: impl IntoIterator<Item = Point3<R>>) -> bool {
    pts.into_iter().all(|p| p.is_finite())
}

fn bits<R: Real>(pts: impl IntoIterator<Item = Point3<R>>) -> Vec<u64> {
    pts.into_iter()
        .flat_map(|p| p.0.map(|c| c.to_f64().to_bits()))
        .collect()
}

// ---------------------------------------------------------------- C²PS / RTS

const POLAR_CAP: usize = 12 << 4;

/// Everything observable about a polar net, as bits.
fn polar_state<R: Real>(net: &PolarNet<R, POLAR_CAP>) -> Vec<u64> {
    let mut out = vec![
        net.valence() as u64,
        net.level() as u64,
        net.link_count() as u64,
    ];
    out.extend(bits([net.pole()]));
    for i in 1..=net.link_count() {
        out.extend(bits(net.link(i).unwrap_or(&[]).iter().copied()));
    }
    out
}

/// Ring patches, jet and geometry of a polar net: each an error or finite.
fn polar_outputs_finite<R: Real>(net: &PolarNet<R, POLAR_CAP>) -> Result<(), TestCaseError> {
    prop_assert!(finite([net.pole()]), "pole not finite");
    for i in 1..=net.link_count() {
        prop_assert!(finite(net.link(i).unwrap().iter().copied()), "link {i}");
    }
    for p in net.ring_patches() {
        prop_assert!(finite(p.points.into_iter().flatten()), "ring patch");
    }
    match net.ring_patch(net.valence()) {
        Ok(p) => prop_assert!(finite(p.points.into_iter().flatten())),
        Err(e) => prop_assert!(matches!(e, Error::NotEnoughLinks { .. }), "{e:?}"),
    }
    if let Ok(jet) = PoleJet::of(net).finite() {
        prop_assert!(finite(jet.p), "jet {:?}", jet.p);
        prop_assert!(jet.limit().is_finite());
        if let Ok(g) = jet.geometry() {
            prop_assert!(g.normal.is_finite(), "normal {:?}", g.normal);
            let n = g.normal.norm().to_f64();
            prop_assert!((n - 1.0).abs() < 1e-3, "|normal| = {n}");
            for c in [g.gaussian, g.mean, g.principal[0], g.principal[1]] {
                prop_assert!(c.is_finite(), "curvature {:?}", g);
            }
        }
    }
    Ok(())
}

/// Steps (C²PS and RTS mixed) on a net at `scale`: each step errs with the net
/// unchanged, or leaves it finite; outputs are errors or finite throughout.
fn polar_contract<R: Range>(
    n: usize,
    scale: Scale,
    seed: u64,
    ops: &[bool],
) -> Result<(), TestCaseError> {
    let pts = points::<R>(5 * n + 1, scale, seed);
    let links: Vec<&[[R; 3]]> = pts[1..].chunks(n).collect();
    let mut net = PolarNet::<R, POLAR_CAP>::new(pts[0], &links).unwrap();
    polar_outputs_finite(&net)?;
    for &c2ps in ops {
        let before = polar_state(&net);
        let m = max_abs(
            [net.pole()]
                .into_iter()
                .chain((1..=3).flat_map(|i| net.link(i).unwrap_or(&[]).to_vec())),
        );
        let r = if c2ps {
            net.step(FirstStep::Uniform)
        } else {
            net.rts_step()
        };
        match r {
            Ok(()) => {}
            Err(Error::CapacityExceeded { .. }) => return Ok(()),
            Err(e) => {
                prop_assert_eq!(e, Error::NonFinite);
                prop_assert_eq!(
                    polar_state(&net),
                    before.clone(),
                    "state changed by a failed step"
                );
                // The documented bound: below MAX/(16·N) a step never fails.
                prop_assert!(
                    m > R::MAX / (16.0 * net.valence() as f64),
                    "step failed at {m:e} (N = {})",
                    net.valence()
                );
                // A retry fails the same way and still changes nothing.
                if !c2ps {
                    prop_assert_eq!(net.rts_step(), Err(Error::NonFinite));
                    prop_assert_eq!(polar_state(&net), before);
                }
                return Ok(());
            }
        }
        polar_outputs_finite(&net)?;
    }
    Ok(())
}

fn ops() -> impl Strategy<Value = Vec<bool>> {
    prop::collection::vec(prop::bool::weighted(0.7), 1..=4)
}

// ------------------------------------------------------------------------ EG

fn eg_contract<R: Range>(n: usize, scale: Scale, seed: u64) -> Result<(), TestCaseError> {
    let pts = points::<R>(6 * n + 1, scale, seed);
    let net = match CNet::new(pts[0], &pts[1..]) {
        Ok(net) => net,
        Err(e) => {
            prop_assert_eq!(e, Error::NonFinite);
            return Ok(());
        }
    };
    // `CNet::limit` / `to_dnet` are the unchecked forms (documented: finite
    // unless coordinate differences overflow); `EgSubdivision::new` is their check.
    prop_assert_eq!(
        EgSubdivision::new(&net, None).is_ok(),
        net.to_dnet().is_finite()
    );
    let mut eg = match EgSubdivision::new(&net, None) {
        Ok(eg) => eg,
        Err(e) => {
            // Degree raising overflowed: only possible beyond MAX/1024.
            prop_assert_eq!(e, Error::NonFinite);
            prop_assert!(max_abs(pts.iter().map(|p| Point3(*p))) > R::MAX / 1024.0);
            return Ok(());
        }
    };
    prop_assert!(eg.net().is_finite());
    // The Fourier step alongside: the same outcome at every scale,
    // its state unchanged on error.
    let mut fast = eg.clone();
    let rule = eg.table().map(|t| FourierRule::new(t).unwrap());
    // Under Miri (an EG step and ring take seconds there) one step.
    for _ in 0..if cfg!(miri) { 1 } else { 4 } {
        if let Some(rule) = &rule {
            let before = fast.net().clone();
            let dense = fast.clone().step();
            let got = fast.step_fourier(rule);
            prop_assert_eq!(got, dense);
            if got.is_err() {
                prop_assert_eq!(fast.net(), &before);
            } else {
                prop_assert!(fast.net().is_finite());
            }
        }
        let before = (
            bits(eg.net().sectors().iter().flatten().copied()),
            eg.level(),
        );
        let m = max_abs(
            eg.net()
                .sectors()
                .iter()
                .flatten()
                .copied()
                .chain([eg.limit()]),
        );
        match eg.step() {
            Ok(()) => {
                prop_assert!(eg.net().is_finite());
                for p in eg.ring_patches() {
                    prop_assert!(finite(p.points.into_iter().flatten()), "EG ring patch");
                }
                prop_assert_eq!(eg.ring_patches().len(), eg.ring_len());
            }
            Err(e) => {
                prop_assert_eq!(e, Error::NonFinite);
                prop_assert!(m > R::MAX / 1024.0, "EG step failed at {m:e}");
                let after = (
                    bits(eg.net().sectors().iter().flatten().copied()),
                    eg.level(),
                );
                prop_assert_eq!(after, before);
                return Ok(());
            }
        }
    }
    Ok(())
}

// ----------------------------------------------------------- Catmull-Clark

fn cc_outputs<R: Real>(cc: &CcCap<'_, R>) -> Result<(), TestCaseError> {
    if let Ok(p) = cc.limit().finite() {
        prop_assert!(p.is_finite());
    }
    if let Ok((t1, t2)) = cc.limit_tangents() {
        prop_assert!(t1.is_finite() && t2.is_finite(), "tangents {t1:?} {t2:?}");
    }
    match cc.normal() {
        Ok(nrm) => {
            prop_assert!(nrm.is_finite(), "normal {nrm:?}");
            let l = nrm.norm().to_f64();
            prop_assert!((l - 1.0).abs() < 1e-3, "|normal| = {l}");
        }
        Err(e) => prop_assert!(matches!(e, Error::Degenerate | Error::NonFinite), "{e:?}"),
    }
    for p in cc.ring_patches() {
        prop_assert!(finite(p.points.into_iter().flatten()), "CC ring patch");
    }
    Ok(())
}

fn cc_state<R: Real>(cc: &CcCap<'_, R>) -> Vec<u64> {
    let n = cc.valence();
    let mut pts = vec![cc.center()];
    for s in 0..n {
        for x in 0..=3 {
            for y in 0..=3 {
                pts.extend(cc.node(s, x, y));
            }
        }
    }
    let mut out = bits(pts);
    out.push(u64::from(cc.level()));
    out.extend(bits(
        cc.ring_patches()
            .flat_map(|p| p.points.into_iter().flatten()),
    ));
    out
}

/// Largest CC valence drawn (under Miri, ~10⁴× slower than native here, 6).
const CC_MAX_N: usize = if cfg!(miri) { 6 } else { 12 };

fn cc_contract<R: Range>(n: usize, scale: Scale, seed: u64) -> Result<(), TestCaseError> {
    let pts = points::<R>(6 * n + 1, scale, seed);
    let mut storage = vec![Point3::<R>::ZERO; CcCap::<R>::storage_len(n)];
    let mut cc = CcCap::new(pts[0], &pts[1..], &mut storage).unwrap();
    cc_outputs(&cc)?;
    for _ in 0..if cfg!(miri) { 1 } else { 4 } {
        let before = cc_state(&cc);
        match cc.step() {
            Ok(()) => cc_outputs(&cc)?,
            Err(e) => {
                prop_assert_eq!(e, Error::NonFinite);
                prop_assert_eq!(cc_state(&cc), before);
                return Ok(());
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn polar_f64(n in 3usize..=12, scale in scale(), seed in any::<u64>(), ops in ops()) {
        polar_contract::<f64>(n, scale, seed, &ops)?;
    }

    #[test]
    fn polar_f32(n in 3usize..=12, scale in scale(), seed in any::<u64>(), ops in ops()) {
        polar_contract::<f32>(n, scale, seed, &ops)?;
    }

    #[test]
    fn eg_f64(n in 3usize..=5, scale in scale(), seed in any::<u64>()) {
        eg_contract::<f64>(n, scale, seed)?;
    }

    #[test]
    fn eg_f32(n in 3usize..=5, scale in scale(), seed in any::<u64>()) {
        eg_contract::<f32>(n, scale, seed)?;
    }

    #[test]
    fn cc_f64(n in 3usize..=CC_MAX_N, scale in scale(), seed in any::<u64>()) {
        cc_contract::<f64>(n, scale, seed)?;
    }

    #[test]
    fn cc_f32(n in 3usize..=CC_MAX_N, scale in scale(), seed in any::<u64>()) {
        cc_contract::<f32>(n, scale, seed)?;
    }
}

/// The magnitudes the README states, measured on random nets (a smooth,
/// random-noise cap scaled by `2^e`): the smallest power of two at which a
/// step (4 steps) or an output fails, per scheme and type.
#[test]
#[cfg_attr(miri, ignore = "a scan over the whole exponent range")]
fn measured_edges() {
    fn report<R: Range>(name: &str) {
        // Scan exponents e: coordinates uniform in ±2^e.
        let (lo, hi) = (
            libm::log2(R::TINIEST) as i32 - 1,
            libm::log2(R::MAX) as i32 + 1,
        );
        let mut first_fail = [None::<i32>; 6];
        let mut last_fail_low = [None::<i32>; 6];
        for e in lo..=hi {
            let s = libm::exp2(f64::from(e));
            let mut fails = [false; 6];
            for seed in 1..=8u64 {
                let mut rng = Rng(seed * 0x9e37_79b9);
                let mut pt =
                    || [0; 3].map(|_| R::from_f64((rng.next() * s).clamp(-R::MAX, R::MAX)));
                // C²PS, n = 6.
                let n = 6;
                let pts: Vec<[R; 3]> = (0..5 * n + 1).map(|_| pt()).collect();
                let links: Vec<&[[R; 3]]> = pts[1..].chunks(n).collect();
                let mut net = PolarNet::<R, POLAR_CAP>::new(pts[0], &links).unwrap();
                for _ in 0..4 {
                    if net.step(FirstStep::Uniform).is_err() {
                        fails[0] = true;
                        break;
                    }
                }
                match PoleJet::of(&net).finite().map(|j| j.geometry()) {
                    Ok(Ok(_)) => {}
                    _ => fails[1] = true,
                }
                // EG, n = 5.
                let pts: Vec<[R; 3]> = (0..31).map(|_| pt()).collect();
                let c = CNet::new(pts[0], &pts[1..]).unwrap();
                match EgSubdivision::new(&c, None) {
                    Ok(mut eg) => {
                        for _ in 0..4 {
                            if eg.step().is_err() {
                                fails[2] = true;
                                break;
                            }
                        }
                    }
                    Err(_) => fails[2] = true,
                }
                // Catmull-Clark, n = 6.
                let pts: Vec<[R; 3]> = (0..37).map(|_| pt()).collect();
                let mut st = vec![Point3::<R>::ZERO; CcCap::<R>::storage_len(6)];
                let mut cc = CcCap::new(pts[0], &pts[1..], &mut st).unwrap();
                for _ in 0..4 {
                    if cc.step().is_err() {
                        fails[3] = true;
                        break;
                    }
                }
                if cc.limit().finite().is_err() {
                    fails[4] = true;
                }
                if cc.normal().is_err() {
                    fails[5] = true;
                }
            }
            for k in 0..6 {
                if fails[k] {
                    if e > 0 {
                        first_fail[k].get_or_insert(e);
                    } else {
                        last_fail_low[k] = Some(e);
                    }
                }
            }
        }
        let names = [
            "C2PS step",
            "C2PS jet+geometry",
            "EG step",
            "CC step",
            "CC limit",
            "CC normal",
        ];
        for k in 0..6 {
            println!(
                "{name} {:18}: fails from 2^{:?} up; below 1 fails up to 2^{:?}",
                names[k], first_fail[k], last_fail_low[k]
            );
        }
        // Steps (0, 2, 3) and the CC limit (4): never below MAX/1024
        // (2^(e_max − 10)), never for tiny or subnormal nets.
        let e_max = libm::log2(R::MAX) as i32;
        for k in [0, 2, 3, 4] {
            assert!(first_fail[k].is_none_or(|e| e > e_max - 10), "{name} {k}");
            assert_eq!(last_fail_low[k], None, "{name} {k}");
        }
        // Normals and curvatures take 4th powers: fine within 2^±(e_max/4 − 2).
        for k in [1, 5] {
            assert!(
                first_fail[k].is_none_or(|e| e > e_max / 4 - 2),
                "{name} {k}"
            );
            assert!(
                last_fail_low[k].is_none_or(|e| e < -(e_max / 4 - 2)),
                "{name} {k}"
            );
        }
    }
    report::<f32>("f32");
    report::<f64>("f64");
}

/// A net whose coordinates the step could overflow (f32, valence 6,
/// coordinates near 1e37 > `MAX/(16·6)` ≈ 3.5e36): `rts_step` reports
/// [`Error::NonFinite`] exactly as `step` does, for both storages, and leaves
/// the net as it was; scaled down below the bound, the same net refines.
#[test]
fn rts_step_reports_an_overflowing_net_like_step() {
    use capdiv::{PolarNetBuf, SliceStorage};
    const N: usize = 6;
    let net_at = |scale: f32| -> ([f32; 3], Vec<Vec<[f32; 3]>>) {
        let links = (1..=5)
            .map(|i| {
                (0..N)
                    .map(|j| {
                        let t = std::f32::consts::TAU * j as f32 / N as f32;
                        let r = scale * i as f32;
                        [r * t.cos(), r * t.sin(), 0.5 * r]
                    })
                    .collect()
            })
            .collect();
        ([0.0, 0.0, -0.25 * scale], links)
    };
    let state = |net: &PolarNet<f32, 64>| {
        let links: Vec<Vec<Point3<f32>>> = (1..=5).map(|i| net.link(i).unwrap().to_vec()).collect();
        (net.pole(), net.valence(), net.link_count(), links)
    };

    let (pole, links) = net_at(1e37);
    let mut net = PolarNet::<f32, 64>::new(pole, &links).unwrap();
    let before = state(&net);
    assert_eq!(net.step(FirstStep::Uniform), Err(Error::NonFinite));
    assert_eq!(net.rts_step(), Err(Error::NonFinite));
    assert_eq!(state(&net), before, "a failed RTS step changed the net");

    let cap = capdiv::polar::capacity_for(N, 0).unwrap();
    let mut link_storage = vec![Point3([0.0f32; 3]); SliceStorage::<f32>::links_len(cap)];
    let mut root_storage = vec![[0.0f32; 2]; SliceStorage::<f32>::roots_len(cap)];
    let mut buf = PolarNetBuf::new_in(
        pole,
        &links,
        SliceStorage::new(&mut link_storage, &mut root_storage),
    )
    .unwrap();
    let pole_before = buf.pole();
    let link1_before = buf.link(1).unwrap().to_vec();
    assert_eq!(buf.rts_step(), Err(Error::NonFinite));
    assert_eq!(buf.pole(), pole_before);
    assert_eq!(buf.link(1).unwrap(), &link1_before[..]);

    // 1e34 < MAX/(16·6): three RTS steps succeed, finite, valence kept.
    let (pole, links) = net_at(1e34);
    let mut net = PolarNet::<f32, 64>::new(pole, &links).unwrap();
    for _ in 0..3 {
        assert_eq!(net.rts_step(), Ok(()));
    }
    assert_eq!(net.valence(), N);
    assert!(net.pole().0.iter().all(|c| c.is_finite()));
    assert_ne!(state(&net).0, Point3(pole));
}
