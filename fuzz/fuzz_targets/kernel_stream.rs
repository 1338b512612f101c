//! Streaming C²PS (`PolarStream`) on arbitrary f32 / f64 bit
//! patterns: valences 0..=48, 0..=7 links, depths 0..=7 (the state holds 6),
//! both first-step variants, arbitrary level and span filters.
//!
//! Oracle: no panic; an error is typed and comes before any patch (`run`
//! never calls its sink), and input errors are the ones `PolarNetBuf::new`
//! gives; on success every patch and the jet are finite, every
//! `(level, span, column)` is delivered once and their number is the
//! iterator's length; and every patch equals the in-place `PolarNetBuf`
//! path's at the levels that path reaches (its steps may refuse earlier, by
//! their own overflow check) within `1e-12` (f64) / `1e-6` (f32) of the
//! input's largest magnitude plus a subnormal floor — the bounds of
//! `tests/polar_stream.rs`, taken relative to the magnitude because fuzzed
//! nets may be far from the origin.
#![no_main]

use arbitrary::{Result, Unstructured};
use capdiv::{
    BicubicPatch, Error, FirstStep, Point3, PolarNetBuf, PolarStream, SliceStorage, StreamOptions,
};
use capdiv_fuzz::{all_finite, arb_point, arb_pool, max_abs, FuzzReal};
use libfuzzer_sys::fuzz_target;
use std::collections::BTreeSet;

const D: usize = 6;

fn run<R: FuzzReal>(u: &mut Unstructured<'_>) -> Result<()> {
    let n = u.int_in_range(0..=48usize)?;
    let nl = u.int_in_range(0..=7usize)?;
    let short: u8 = u.arbitrary()?;
    let pool = arb_pool::<R>(u, 8)?;
    let ring: bool = u.arbitrary()?;
    let mut links = Vec::with_capacity(nl);
    for k in 0..nl {
        let len = if short < 4 && usize::from(short) == k {
            n.saturating_sub(1)
        } else {
            n
        };
        let link: Vec<[R; 3]> = (0..len)
            .map(|j| {
                let q = pool[(k * 5 + j) % pool.len()];
                if ring {
                    // A plausible net: rings of radius k+1 plus the pool's bumps.
                    let t = std::f64::consts::TAU * j as f64 / len.max(1) as f64;
                    let r = (k + 1) as f64;
                    let base = [r * t.cos(), r * t.sin(), 0.3 * r * r];
                    [0, 1, 2].map(|c| R::from_f64(base[c] + q[c].to_f64() * 1e-2))
                } else {
                    q
                }
            })
            .collect();
        links.push(link);
    }
    let pole = if ring { [R::ZERO; 3] } else { arb_point(u)? };
    let depth = u.int_in_range(0..=7u32)?;
    let first = if u.arbitrary()? {
        FirstStep::Plain
    } else {
        FirstStep::Uniform
    };
    let from_level = u.int_in_range(0..=depth + 1)?;
    let span = match u.int_in_range(0..=3u8)? {
        0 => None,
        s => Some(s - 1),
    };
    let mut opts = StreamOptions::depth(depth).first(first);
    opts.from_level = from_level;
    opts.span = span;

    let mut state = Box::new(PolarStream::<R, D>::empty());
    let mut calls = 0usize;
    let res = state.run(pole, &links, opts, |_| calls += 1);
    let Ok(jet) = res else {
        assert_eq!(calls, 0, "patches delivered before an error");
        let e = res.unwrap_err();
        let cap = n.max(3);
        let mut ls = vec![Point3::<R>::ZERO; SliceStorage::<R>::links_len(cap)];
        let mut rs = vec![[R::ZERO; 2]; SliceStorage::<R>::roots_len(cap)];
        let in_place = PolarNetBuf::new_in(pole, &links, SliceStorage::new(&mut ls, &mut rs)).err();
        match e {
            Error::TooFewLinks { .. }
            | Error::ValenceTooSmall { .. }
            | Error::LinkLengthMismatch { .. }
            | Error::ValenceUnsupported { .. } => assert_eq!(in_place, Some(e)),
            Error::NonFinite => {} // non-finite input, or the magnitude pre-check
            Error::OutOfDomain => assert!(span.is_some_and(|s| s > 1)),
            Error::CapacityExceeded { needed, capacity } => {
                assert!(needed == depth as usize && capacity == D && depth as usize > D)
            }
            other => panic!("unexpected error {other:?}"),
        }
        return Ok(());
    };
    assert!(all_finite(jet.p), "jet not finite: {jet:?}");

    // The in-place path, level by level, as far as its steps go.
    let cap = n << depth;
    let mut ls = vec![Point3::<R>::ZERO; SliceStorage::<R>::links_len(cap)];
    let mut rs = vec![[R::ZERO; 2]; SliceStorage::<R>::roots_len(cap)];
    let mut net = PolarNetBuf::new_in(pole, &links, SliceStorage::new(&mut ls, &mut rs))
        .expect("stream accepted it");
    let mut rings: Vec<Vec<BicubicPatch<R>>> = Vec::new();
    for level in 0..=depth {
        rings.push(net.ring_patches().collect());
        if level < depth && net.step(first).is_err() {
            break;
        }
    }
    let m = max_abs(links.iter().take(5).flatten().copied().chain([pole]));
    let (rel, floor) = if R::NAME == "f64" {
        (1e-12, 1e-300)
    } else {
        (1e-6, 1e-36)
    };
    let tol = rel * m + floor;

    let sweep = state.sweep(pole, &links, opts).expect("accepted before");
    let len = sweep.len();
    let mut seen = BTreeSet::new();
    for p in sweep {
        assert!(
            all_finite(p.patch.points.iter().flatten().copied()),
            "patch not finite"
        );
        assert!(p.level >= from_level && p.level <= depth && p.span <= 1);
        assert!(span.is_none_or(|s| s == p.span));
        assert!(
            seen.insert((p.level, p.span, p.column)),
            "patch delivered twice"
        );
        if let Some(ring) = rings.get(p.level as usize).filter(|r| !r.is_empty()) {
            let want = &ring[p.ring_index()];
            for (a, b) in p
                .patch
                .points
                .iter()
                .flatten()
                .zip(want.points.iter().flatten())
            {
                let d = a.max_abs_diff(*b).to_f64();
                assert!(
                    d <= tol,
                    "level {} span {} column {}: {d:e} > {tol:e}",
                    p.level,
                    p.span,
                    p.column
                );
            }
        }
    }
    assert_eq!(seen.len(), len, "length");
    Ok(())
}

fuzz_target!(|data: &[u8]| {
    let mut u = Unstructured::new(data);
    let _ = match u.arbitrary::<u8>().unwrap_or(0) & 1 {
        0 => run::<f64>(&mut u),
        _ => run::<f32>(&mut u),
    };
});
