//! Streaming C²PS (`PolarStream`, docs/math/c2ps.md §2, §4, §5): every patch of
//! every ring equals the in-place `PolarNetBuf` path's, the pole jet equals
//! `PoleJet::of`, errors come before any patch, and the state grows linearly
//! with the maximum depth.
//!
//! Tolerances, relative to the level-0 configuration's bounding-box size `s`:
//! f64 `1e-12·s` (the bound; the two paths differ only in rounding:
//! closed-form vs summed 1-link sums, rotated vs doubled roots); f32 `1e-6·s`,
//! the f32 bound stated in docs/accuracy.md (*Accuracy*: f32 vs f64 at depth 8, of the
//! level-0 box).
//!
//! Not run under Miri (`scripts/ci-miri.sh`): streaming to depth 20 and the
//! equality sweeps take over 10 minutes there; the streaming code is safe
//! Rust over arrays, and the equality tests run natively.
#![cfg(not(miri))]

use capdiv::{
    BicubicPatch, Error, FirstStep, Point3, PolarNetBuf, PolarStream, PoleJet, Real, SliceStorage,
    StreamOptions, StreamedPatch,
};
use proptest::prelude::*;
use std::collections::BTreeMap;

/// A random-ish configuration: link `i` a ring of radius `i` with bumps.
fn config(n: usize, count: usize, seed: u64) -> ([f64; 3], Vec<Vec<[f64; 3]>>) {
    let mut x = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
    let mut rnd = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let links = (1..=count)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / n as f64;
                    let r = i as f64 * (1.0 + 0.3 * rnd());
                    [r * t.cos(), r * t.sin(), 0.25 * r * r + 0.5 * rnd()]
                })
                .collect()
        })
        .collect();
    ([0.1 * rnd(), 0.1 * rnd(), 0.1 * rnd()], links)
}

fn cast<R: Real>(pole: [f64; 3], links: &[Vec<[f64; 3]>]) -> ([R; 3], Vec<Vec<[R; 3]>>) {
    let c = |p: [f64; 3]| p.map(R::from_f64);
    (
        c(pole),
        links
            .iter()
            .map(|l| l.iter().map(|&p| c(p)).collect())
            .collect(),
    )
}

/// Bounding-box size (largest extent over the axes) of the level-0 data.
fn size(pole: [f64; 3], links: &[Vec<[f64; 3]>]) -> f64 {
    let mut lo = pole;
    let mut hi = pole;
    for p in links.iter().flatten() {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
}

/// The in-place path: ring patches of levels `0..=depth` (empty where the net
/// holds fewer than 5 links) and the level-0 jet.
fn in_place<R: Real>(
    pole: [R; 3],
    links: &[Vec<[R; 3]>],
    depth: u32,
    first: FirstStep,
) -> (Vec<Vec<BicubicPatch<R>>>, PoleJet<R>) {
    let n = links[0].len();
    let cap = n << depth;
    let mut ls = vec![Point3::<R>::ZERO; SliceStorage::<R>::links_len(cap)];
    let mut rs = vec![[R::ZERO; 2]; SliceStorage::<R>::roots_len(cap)];
    let mut net = PolarNetBuf::new_in(pole, links, SliceStorage::new(&mut ls, &mut rs)).unwrap();
    let jet = PoleJet::of(&net);
    let mut rings = Vec::new();
    for level in 0..=depth {
        rings.push(net.ring_patches().collect());
        if level < depth {
            net.step(first).unwrap();
        }
    }
    (rings, jet)
}

fn patch_diff<R: Real>(a: &BicubicPatch<R>, b: &BicubicPatch<R>) -> f64 {
    let mut m = 0.0f64;
    for (p, q) in a.points.iter().flatten().zip(b.points.iter().flatten()) {
        m = m.max(p.max_abs_diff(*q).to_f64());
    }
    m
}

/// Streams to `depth` and compares every patch with the in-place path;
/// returns the worst difference relative to the configuration's size.
fn compare<R: Real, const D: usize>(
    pole: [f64; 3],
    links: &[Vec<[f64; 3]>],
    depth: u32,
    first: FirstStep,
    tol: f64,
) -> f64 {
    let s = size(pole, links).max(1e-300);
    let (p, l) = cast::<R>(pole, links);
    let (rings, jet) = in_place(p, &l, depth, first);
    let mut state = Box::new(PolarStream::<R, D>::empty());
    let opts = StreamOptions::depth(depth).first(first);
    let sweep = state.sweep(p, &l, opts).unwrap();
    let len = sweep.len();
    let sjet = sweep.jet();
    let mut seen = BTreeMap::new();
    let mut last_col: BTreeMap<u32, (usize, u8)> = BTreeMap::new();
    let mut worst = 0.0f64;
    for sp in sweep {
        let StreamedPatch {
            level,
            span,
            column,
            valence,
            patch,
        } = sp;
        assert_eq!(valence, links[0].len() << level);
        // Within a level: increasing column, span 0 before span 1.
        if let Some(&prev) = last_col.get(&level) {
            assert!((column, span) > prev, "order at level {level}");
        }
        last_col.insert(level, (column, span));
        assert!(seen.insert((level, span, column), ()).is_none(), "repeated");
        let want = &rings[level as usize][sp.ring_index()];
        let d = patch_diff(&patch, want) / s;
        assert!(
            d <= tol,
            "level {level} span {span} column {column}: |stream − in place| = {d:e}·size > {tol:e}"
        );
        worst = worst.max(d);
    }
    let total: usize = rings.iter().map(Vec::len).sum();
    assert_eq!(seen.len(), total, "every in-place patch streamed once");
    assert_eq!(len, total, "ExactSizeIterator length");
    for (a, b) in sjet.p.iter().zip(&jet.p) {
        let d = a.max_abs_diff(*b).to_f64() / s;
        assert!(d <= tol, "jet differs by {d:e}·size");
    }
    worst
}

const F64_TOL: f64 = 1e-12;
const F32_TOL: f64 = 1e-6;

#[test]
fn f64_equals_in_place_on_every_patch() {
    let mut worst = 0.0f64;
    for (n, count) in [
        (3, 5),
        (4, 7),
        (5, 2),
        (6, 5),
        (6, 3),
        (7, 4),
        (12, 5),
        (16, 6),
    ] {
        for first in [FirstStep::Uniform, FirstStep::Plain] {
            let depth = if n <= 6 { 8 } else { 6 };
            let (pole, links) = config(n, count, (n * 31 + count) as u64);
            worst = worst.max(compare::<f64, 8>(pole, &links, depth, first, F64_TOL));
        }
    }
    eprintln!("f64 worst |stream − in place| / size = {worst:e}");
}

#[test]
fn f32_equals_in_place_within_the_f32_bound() {
    let mut worst = 0.0f64;
    for (n, count) in [(3, 5), (6, 5), (5, 2), (12, 4)] {
        for first in [FirstStep::Uniform, FirstStep::Plain] {
            let (pole, links) = config(n, count, (n * 7 + count) as u64);
            worst = worst.max(compare::<f32, 8>(pole, &links, 8, first, F32_TOL));
        }
    }
    eprintln!("f32 worst |stream − in place| / size = {worst:e}");
}

/// f32 streamed against the f64 in-place path: the same bound as the in-place
/// f32 kernel (docs/accuracy.md, *Accuracy*, 1e-6 of the level-0 box at depth 8).
#[test]
fn f32_stream_is_within_the_bound_of_f64() {
    for (n, count) in [(6, 5), (3, 7)] {
        let (pole, links) = config(n, count, 99 + n as u64);
        let s = size(pole, &links);
        let (rings, _) = in_place::<f64>(pole, &links, 8, FirstStep::Uniform);
        let (p, l) = cast::<f32>(pole, &links);
        let mut state = PolarStream::<f32, 8>::empty();
        state
            .run(p, &l, StreamOptions::depth(8), |sp| {
                let want = &rings[sp.level as usize][sp.ring_index()];
                for (a, b) in sp
                    .patch
                    .points
                    .iter()
                    .flatten()
                    .zip(want.points.iter().flatten())
                {
                    let d = a.cast::<f64>().max_abs_diff(*b) / s;
                    assert!(d <= F32_TOL, "{d:e}");
                }
            })
            .unwrap();
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn random_configurations_match_in_place(
        n in prop::sample::select(vec![3usize, 4, 5, 6, 7, 8, 9, 10, 11, 12, 20, 24]),
        count in 2usize..=7,
        depth in 0u32..=6,
        plain in any::<bool>(),
        scale in -8i32..=8,
        seed in any::<u64>(),
    ) {
        let (pole, links) = config(n, count, seed);
        let k = 2f64.powi(scale);
        let pole = pole.map(|c| c * k);
        let links: Vec<Vec<[f64; 3]>> = links.iter().map(|l| l.iter().map(|p| p.map(|c| c * k)).collect()).collect();
        let first = if plain { FirstStep::Plain } else { FirstStep::Uniform };
        compare::<f64, 6>(pole, &links, depth, first, F64_TOL);
        compare::<f32, 6>(pole, &links, depth, first, F32_TOL);
    }
}

#[test]
fn only_one_level_and_span_gives_ring_patches_order() {
    let (pole, links) = config(5, 5, 3);
    let (rings, _) = in_place::<f64>(pole, &links, 4, FirstStep::Uniform);
    let mut state = PolarStream::<f64, 6>::empty();
    for level in 0..=4u32 {
        let mut got = Vec::new();
        for span in [0u8, 1] {
            let opts = StreamOptions::depth(level).only(level, Some(span));
            let sweep = state.sweep(pole, &links, opts).unwrap();
            assert_eq!(sweep.len(), 5 << level);
            got.extend(sweep.map(|p| {
                assert_eq!((p.level, p.span), (level, span));
                p.patch
            }));
        }
        let want = &rings[level as usize];
        assert_eq!(got.len(), want.len());
        for (a, b) in got.iter().zip(want) {
            assert!(patch_diff(a, b) <= 1e-12 * size(pole, &links));
        }
    }
}

/// Depth 20 (valence 3·2^20 = 3,145,728 columns at the deepest ring) in the
/// same fixed state: the first 400,000 patches of the sweep are finite, and
/// those of levels ≤ 9 equal the in-place path's.
#[test]
fn depth_20_streams_in_fixed_state() {
    let (pole, links) = config(3, 5, 20);
    let (rings, _) = in_place::<f64>(pole, &links, 9, FirstStep::Uniform);
    let s = size(pole, &links);
    let mut state = Box::new(PolarStream::<f64, 20>::empty());
    let sweep = state.sweep(pole, &links, StreamOptions::depth(20)).unwrap();
    let total: usize = (0..=20).map(|m| 2 * (3usize << m)).sum();
    assert_eq!(sweep.len(), total);
    let mut per_level = [0usize; 21];
    for sp in sweep.take(400_000) {
        assert!(sp.patch.points.iter().flatten().all(Point3::is_finite));
        per_level[sp.level as usize] += 1;
        if sp.level <= 9 {
            let d = patch_diff(&sp.patch, &rings[sp.level as usize][sp.ring_index()]);
            assert!(d <= F64_TOL * s, "level {}: {d:e}", sp.level);
        }
    }
    // The sweep is angular: every level has started.
    assert!(per_level.iter().all(|&c| c > 0), "{per_level:?}");
}

#[test]
fn state_size_grows_linearly_with_max_depth() {
    use std::mem::size_of;
    fn sz<R: Real, const D: usize>() -> usize {
        size_of::<PolarStream<R, D>>()
    }
    let per_level = sz::<f64, 11>() - sz::<f64, 10>();
    assert_eq!(
        sz::<f64, 20>() - sz::<f64, 10>(),
        2 * (sz::<f64, 15>() - sz::<f64, 10>())
    );
    assert_eq!(sz::<f64, 20>() - sz::<f64, 10>(), 10 * per_level);
    assert_eq!(
        sz::<f32, 20>() - sz::<f32, 12>(),
        8 * (sz::<f32, 13>() - sz::<f32, 12>())
    );
    // The module docs' formula: (D+1)·(88 scalars + 3 words).
    let formula = |d: usize, r: usize| (d + 1) * (88 * r + 3 * size_of::<usize>());
    assert_eq!(sz::<f64, 20>(), formula(20, 8));
    assert_eq!(sz::<f32, 12>(), formula(12, 4));
    for d in [8usize, 12, 16, 20] {
        eprintln!(
            "PolarStream depth {d}: f32 {} bytes, f64 {} bytes",
            formula(d, 4),
            formula(d, 8)
        );
    }
}

#[test]
fn errors_come_before_any_patch() {
    let (pole, links) = config(6, 5, 1);
    let mut state = PolarStream::<f64, 4>::empty();
    let calls = std::cell::Cell::new(0usize);
    let run = |state: &mut PolarStream<f64, 4>, pole: [f64; 3], links: &[Vec<[f64; 3]>], depth| {
        state.run(pole, links, StreamOptions::depth(depth), |_| {
            calls.set(calls.get() + 1)
        })
    };
    assert_eq!(
        run(&mut state, pole, &links[..1], 2),
        Err(Error::TooFewLinks { links: 1 })
    );
    let short: Vec<Vec<[f64; 3]>> = links.iter().map(|l| l[..2].to_vec()).collect();
    assert_eq!(
        run(&mut state, pole, &short, 2),
        Err(Error::ValenceTooSmall { valence: 2 })
    );
    let mut uneven = links.clone();
    uneven[2].pop();
    assert_eq!(
        run(&mut state, pole, &uneven, 2),
        Err(Error::LinkLengthMismatch {
            link: 3,
            len: 5,
            expected: 6
        })
    );
    let mut nan = links.clone();
    nan[4][3][1] = f64::NAN;
    assert_eq!(run(&mut state, pole, &nan, 2), Err(Error::NonFinite));
    assert_eq!(
        run(&mut state, pole, &links, 5),
        Err(Error::CapacityExceeded {
            needed: 5,
            capacity: 4
        })
    );
    let odd: Vec<Vec<[f64; 3]>> = (0..3).map(|_| vec![[0.0; 3]; 131]).collect();
    assert_eq!(
        run(&mut state, pole, &odd, 1),
        Err(Error::ValenceUnsupported { valence: 131 })
    );
    assert_eq!(
        state
            .sweep(pole, &links, StreamOptions::depth(2).only(1, Some(2)))
            .err(),
        Some(Error::OutOfDomain)
    );
    let mut huge = links.clone();
    huge[4][0][0] = f64::MAX / 64.0;
    assert_eq!(run(&mut state, pole, &huge, 2), Err(Error::NonFinite));
    assert_eq!(calls.get(), 0, "no patch delivered on error");
    // The state still works after the errors.
    let jet = run(&mut state, pole, &links, 2).unwrap();
    assert!(jet.p.iter().all(Point3::is_finite));
    assert_eq!(calls.get(), 2 * (6 + 12 + 24));

    let mut deep = PolarStream::<f64, 63>::empty();
    let r = deep.run(pole, &links, StreamOptions::depth(63), |_| {});
    assert!(matches!(
        r,
        Err(Error::CapacityExceeded {
            needed: usize::MAX,
            ..
        })
    ));
}

/// The largest magnitudes the pre-check lets through stay finite everywhere.
#[test]
fn magnitudes_at_the_bound_stay_finite() {
    for n in [3usize, 6, 17] {
        let m = f64::MAX / (16.0 * n.max(4) as f64);
        let (pole, links) = config(n, 5, 5);
        let k = m / 16.0; // config's coordinates reach ~16 in magnitude
        let links: Vec<Vec<[f64; 3]>> = links
            .iter()
            .map(|l| l.iter().map(|p| p.map(|c| c * k)).collect())
            .collect();
        let pole = pole.map(|c| c * k);
        let mut state = PolarStream::<f64, 6>::empty();
        let mut count = 0;
        state
            .run(pole, &links, StreamOptions::depth(6), |sp| {
                assert!(sp.patch.points.iter().flatten().all(Point3::is_finite));
                count += 1;
            })
            .unwrap();
        assert_eq!(count, (0..=6).map(|l| 2 * (n << l)).sum::<usize>());
    }
}
