//! EG and Catmull-Clark kernels: `CNet`, `DNet`, `EgSubdivision` (new,
//! reset*, step, step_fourier against step, ring patches, `DNet::refined`), `RuleTable::new` on
//! arbitrary integer arrays (and mutations of the published ones), `CcCap`
//! (new with arbitrary storage length, step, ring patches, limit, normal) on
//! arbitrary f32 / f64 bit patterns.
//!
//! Oracle: no panic; on every error the state (subdivision, cap, storage) is
//! bitwise unchanged; an `Ok` step is finite (both kernels document
//! `NonFinite` for overflow); an `Ok` normal is finite; for coordinates at
//! most MAX/2^20 ring patches and limits are finite too.
#![no_main]

use arbitrary::{Result, Unstructured};
use capdiv::eg::tables::{self, Row};
use capdiv::eg::FourierRule;
use capdiv::{CNet, CcCap, DNet, EgSubdivision, Error, Point3, RuleTable};
use capdiv_fuzz::{all_finite, arb_point, arb_pool, bounded, point_bits, FuzzReal};
use libfuzzer_sys::fuzz_target;

/// `count` points cycling through a pool, optionally on an analytic sheet.
fn arb_points<R: FuzzReal>(u: &mut Unstructured<'_>, count: usize) -> Result<Vec<[R; 3]>> {
    let pool = arb_pool::<R>(u, 8)?;
    let analytic: bool = u.arbitrary()?;
    let scale = R::arb(u)?.to_f64();
    Ok((0..count)
        .map(|i| {
            let q = pool[(i * 5 + i / 7) % pool.len()];
            if analytic {
                let t = i as f64 * 0.7;
                let r = 1.0 + (i % 6) as f64 * 0.5;
                let b = [r * t.cos(), r * t.sin(), 0.25 * r * r];
                let mut p = [R::ZERO; 3];
                for c in 0..3 {
                    p[c] = R::from_f64(b[c] * scale + q[c].to_f64() * 1e-3);
                }
                p
            } else {
                q
            }
        })
        .collect())
}

/// A flat constructor's error with `WrongLength` counted in points (the
/// flat forms count coordinates, as documented).
fn points_err(e: &Error) -> Error {
    match *e {
        Error::WrongLength { expected, found } => Error::WrongLength {
            expected: expected / 3,
            found: found / 3,
        },
        other => other,
    }
}

fn arb_count(u: &mut Unstructured<'_>, per: usize) -> Result<usize> {
    let n = u.int_in_range(0..=12usize)?;
    let off: u8 = u.arbitrary()?;
    Ok(match off {
        0 => n * per + 1,
        1 => (n * per).saturating_sub(1),
        _ => n * per,
    })
}

fn dnet_bits<R: FuzzReal>(d: &DNet<R>, v: &mut Vec<u64>) {
    v.push(d.valence() as u64);
    point_bits(d.c0(), v);
    for s in d.sectors() {
        for p in s {
            point_bits(*p, v);
        }
    }
}

fn snap_eg<R: FuzzReal>(e: &EgSubdivision<'_, R>) -> Vec<u64> {
    let mut v = vec![u64::from(e.level()), e.valence() as u64];
    v.push(e.table().map_or(0, |t| t.valence() as u64 + 1));
    dnet_bits(e.net(), &mut v);
    if let Some(p) = e.previous() {
        dnet_bits(p, &mut v);
    }
    v
}

fn dnet_finite<R: FuzzReal>(d: &DNet<R>) -> bool {
    d.c0().is_finite() && d.sectors().iter().all(|s| all_finite(s.iter().copied()))
}

fn dnet_small<R: FuzzReal>(d: &DNet<R>) -> bool {
    bounded(
        d.sectors().iter().flatten().map(|p| p.0).chain([d.c0().0]),
        20,
    )
}

fn snap_cc<R: FuzzReal>(c: &CcCap<'_, R>) -> Vec<u64> {
    let mut v = vec![u64::from(c.level()), c.valence() as u64];
    point_bits(c.center(), &mut v);
    for s in 0..c.valence() {
        for x in 0..=3 {
            for y in 0..=3 {
                if let Some(p) = c.node(s, x, y) {
                    point_bits(p, &mut v);
                }
            }
        }
    }
    v
}

fn cc_points<R: FuzzReal>(c: &CcCap<'_, R>) -> Vec<[R; 3]> {
    let mut v = vec![c.center().0];
    for s in 0..c.valence() {
        for x in 0..=3 {
            for y in 0..=3 {
                if let Some(p) = c.node(s, x, y) {
                    v.push(p.0);
                }
            }
        }
    }
    v
}

/// Five arrays of rows: a published table (mutated) or arbitrary ones.
fn arb_rows(u: &mut Unstructured<'_>) -> Result<(usize, [Vec<Row>; 5])> {
    let base: u8 = u.arbitrary()?;
    let (mut n, mut arrays): (usize, [Vec<Row>; 5]) = match base % 3 {
        0 => (
            3,
            [
                tables::A11_3.to_vec(),
                tables::A22_3.to_vec(),
                tables::A21_3.to_vec(),
                tables::A31_3.to_vec(),
                tables::A32_3.to_vec(),
            ],
        ),
        1 => (
            5,
            [
                tables::A11_5.to_vec(),
                tables::A22_5.to_vec(),
                tables::A21_5.to_vec(),
                tables::A31_5.to_vec(),
                tables::A32_5.to_vec(),
            ],
        ),
        _ => {
            let n = u.int_in_range(0..=12usize)?;
            let mut arrays: [Vec<Row>; 5] = Default::default();
            for a in &mut arrays {
                let rows = u.int_in_range(0..=12usize)?;
                for _ in 0..rows {
                    let mut row = [0i32; 12];
                    for e in &mut row {
                        *e = if u.arbitrary::<bool>()? {
                            i32::from(u.arbitrary::<i16>()?) % 100_000
                        } else {
                            u.arbitrary()?
                        };
                    }
                    a.push(row);
                }
            }
            (n, arrays)
        }
    };
    if base & 0x80 != 0 {
        n = u.int_in_range(0..=12usize)?;
    }
    let mutations = u.int_in_range(0..=4u8)?;
    for _ in 0..mutations {
        let a = u.int_in_range(0..=4usize)?;
        let len = arrays[a].len();
        if len == 0 {
            continue;
        }
        let r = u.int_in_range(0..=len - 1)?;
        let c = u.int_in_range(0..=11usize)?;
        let delta: i32 = match u.int_in_range(0..=2u8)? {
            0 => i32::from(u.arbitrary::<i8>()?),
            1 => u.arbitrary()?,
            _ => {
                arrays[a].remove(r);
                continue;
            }
        };
        arrays[a][r][c] = arrays[a][r][c].wrapping_add(delta);
    }
    Ok((n, arrays))
}

/// `step_fourier` with the Fourier rule of the subdivision's table, or of a
/// built-in table of any valence: the same outcome as the dense `step` with
/// the rule's table on a copy (the same error with the state bitwise
/// unchanged, or a finite net within a few thousand ulps of the largest old
/// coordinate of the dense step's), or `TableShape` for a rule of another
/// valence.
fn fourier_step<R: FuzzReal>(
    u: &mut Unstructured<'_>,
    eg: &mut EgSubdivision<'_, R>,
) -> Result<()> {
    let rule = match (eg.table(), u.arbitrary::<bool>()?) {
        (Some(t), true) => FourierRule::new(t),
        _ => {
            let Some(t) = RuleTable::builtin(*u.choose(&[3usize, 5])?) else {
                return Ok(());
            };
            FourierRule::new(&t)
        }
    };
    let rule = rule.expect("the Fourier rule of a checked table");
    let before = snap_eg(eg);
    let old = eg.net().clone();
    // The dense step with the rule's table (which may differ from the
    // subdivision's: `step_fourier` applies the rule's).
    let mut dense = None;
    let want = if eg.valence() == 0 {
        Err(Error::ValenceTooSmall { valence: 0 })
    } else if rule.valence() != eg.valence() || eg.table().is_none() {
        Err(Error::TableShape)
    } else {
        let mut d = EgSubdivision::new(&old, Some(*rule.table()))
            .expect("a held net is finite and of the table's valence");
        let r = d.step();
        dense = Some(d);
        r
    };
    let got = eg.step_fourier(&rule);
    assert_eq!(got, want, "step_fourier and step disagree");
    let Some(dense) = dense.filter(|_| got.is_ok()) else {
        assert_eq!(before, snap_eg(eg), "step_fourier {got:?} changed state");
        return Ok(());
    };
    assert!(dnet_finite(eg.net()), "Ok step_fourier not finite");
    let m = old
        .sectors()
        .iter()
        .flatten()
        .copied()
        .chain([old.c0()])
        .flat_map(|p| p.0)
        .fold(0.0f64, |m, c| m.max(c.to_f64().abs()));
    // Plus 256 quanta of the subnormal range (2^-149 in f32, 2^-1074 in
    // f64), where rounding is absolute: each node sums at most 12n + 1 terms.
    let quantum = if R::EPSILON.to_f64() > 1e-10 {
        1.401_298_464_324_817e-45
    } else {
        4.940_656_458_412_465e-324
    };
    let tol = R::EPSILON.to_f64() * 4096.0 * m + 256.0 * quantum;
    for (p, q) in eg
        .net()
        .sectors()
        .iter()
        .flatten()
        .zip(dense.net().sectors().iter().flatten())
    {
        assert!(
            p.max_abs_diff(*q).to_f64() <= tol,
            "step_fourier {p:?} vs step {q:?}"
        );
    }
    Ok(())
}

fn eg_ops<'t, R: FuzzReal>(
    u: &mut Unstructured<'_>,
    eg: &mut EgSubdivision<'t, R>,
    table: Option<RuleTable<'t>>,
) -> Result<()> {
    let ops = u.int_in_range(1..=10u8)?;
    let mut steps = 0;
    for _ in 0..ops {
        match u.int_in_range(0..=6u8)? {
            0 => {
                // a new c-net, through every constructor that takes one
                let count = arb_count(u, 6)?;
                let nodes = arb_points::<R>(u, count)?;
                let center = arb_point::<R>(u)?;
                let r = CNet::new(center, &nodes);
                let flat: Vec<R> = nodes.iter().flatten().copied().collect();
                assert_eq!(
                    r.as_ref().err().copied(),
                    CNet::from_flat(center, &flat)
                        .as_ref()
                        .err()
                        .map(points_err)
                );
                let Ok(cnet) = r else { continue };
                if bounded(nodes.iter().copied().chain([center]), 20) {
                    assert!(cnet.limit().is_finite(), "c-net limit not finite");
                    assert!(dnet_finite(&cnet.to_dnet()), "raised d-net not finite");
                }
                if cnet.valence() == 4 {
                    if let Ok(cap) = cnet.regular_cap() {
                        if bounded(nodes.iter().copied().chain([center]), 20) {
                            assert!(cap
                                .iter()
                                .all(|p| all_finite(p.points.iter().flatten().copied())));
                        }
                    }
                }
                let before = snap_eg(eg);
                let r = match (&table, u.arbitrary::<bool>()?) {
                    (Some(t), true) => eg.reset(&cnet, Some(*t)),
                    _ => eg.reset(&cnet, None),
                };
                match r {
                    Err(e) => {
                        assert_eq!(
                            before,
                            snap_eg(eg),
                            "reset from a c-net {e:?} changed state"
                        )
                    }
                    Ok(()) => {
                        assert!(dnet_finite(eg.net()), "Ok reset from a c-net not finite");
                        steps = 0;
                    }
                }
                if let Ok(fresh) = EgSubdivision::new(&cnet, None) {
                    assert!(dnet_finite(fresh.net()));
                }
            }
            1 => {
                let count = arb_count(u, 12)?;
                let nodes = arb_points::<R>(u, count)?;
                let c0 = if u.arbitrary::<bool>()? {
                    Some(arb_point::<R>(u)?)
                } else {
                    None
                };
                let r = DNet::new(&nodes, c0);
                let flat: Vec<R> = nodes.iter().flatten().copied().collect();
                assert_eq!(
                    r.as_ref().err().copied(),
                    DNet::from_flat(&flat, c0).as_ref().err().map(points_err)
                );
                let Ok(d) = r else { continue };
                let before = snap_eg(eg);
                let r = match (&table, u.arbitrary::<bool>()?) {
                    (Some(t), true) => eg.reset(&d, Some(*t)),
                    _ => eg.reset(&d, None),
                };
                match r {
                    Err(e) => assert_eq!(before, snap_eg(eg), "reset {e:?} changed state"),
                    Ok(()) => steps = 0,
                }
                let refined = d.refined(table.as_ref());
                if let Ok(x) = &refined {
                    assert!(dnet_finite(x), "Ok refined not finite");
                }
            }
            2 | 3 => {
                if steps >= 6 {
                    continue;
                }
                steps += 1;
                let before = snap_eg(eg);
                if u.arbitrary::<bool>()? {
                    fourier_step(u, eg)?;
                    continue;
                }
                match eg.step() {
                    Err(e) => assert_eq!(before, snap_eg(eg), "step {e:?} changed state"),
                    Ok(()) => assert!(dnet_finite(eg.net()), "Ok EG step not finite"),
                }
            }
            4 => {
                let small = dnet_small(eg.net()) && eg.previous().is_none_or(dnet_small);
                let patches: Vec<_> = eg.ring_patches().collect();
                assert_eq!(patches.len(), eg.ring_len());
                if small {
                    for p in &patches {
                        assert!(
                            all_finite(p.points.iter().flatten().copied()),
                            "EG ring patch not finite (net within MAX/2^20)"
                        );
                    }
                }
            }
            5 => {
                let k = u.int_in_range(0..=eg.ring_len() + 1)?;
                let a = eg.ring_patch(k);
                let d = eg.ring_patch_domain(k);
                assert_eq!(a.is_ok(), d.is_ok());
                if k >= eg.ring_len() {
                    assert_eq!(a.err(), Some(Error::OutOfDomain));
                }
            }
            _ => {
                let before = snap_eg(eg);
                let d = eg.net().clone();
                if let Ok(x) = d.refined(eg.table()) {
                    assert!(dnet_finite(&x));
                }
                assert_eq!(before, snap_eg(eg));
            }
        }
    }
    Ok(())
}

fn run_eg<R: FuzzReal>(u: &mut Unstructured<'_>) -> Result<()> {
    let (n, rows) = arb_rows(u)?;
    let [a11, a22, a21, a31, a32] = &rows;
    let table = RuleTable::new(n, a11, a22, a21, a31, a32).ok();
    let mut eg = Box::new(EgSubdivision::<R>::empty());
    assert!(eg.step().is_err());
    eg_ops(u, &mut eg, table)
}

fn run_cc<R: FuzzReal>(u: &mut Unstructured<'_>) -> Result<()> {
    let count = arb_count(u, 6)?;
    let nodes = arb_points::<R>(u, count)?;
    let center = arb_point::<R>(u)?;
    let n = count / 6;
    let len = match u.int_in_range(0..=3u8)? {
        0 => u.int_in_range(0..=24 * 13)?,
        1 => CcCap::<R>::storage_len(n).saturating_sub(1),
        _ => CcCap::<R>::storage_len(n) + usize::from(u.arbitrary::<u8>()? % 4),
    };
    let sentinel = Point3([R::from_f64(7.25); 3]);
    let mut storage = vec![sentinel; len];
    let small = bounded(nodes.iter().copied().chain([center]), 20);
    let cap = match CcCap::new(center, &nodes, &mut storage) {
        Ok(c) => c,
        Err(_) => {
            assert!(storage
                .iter()
                .all(|p| p.0.map(|c| c.bits()) == sentinel.0.map(|c| c.bits())));
            return Ok(());
        }
    };
    let mut cap = cap;
    let nodes = nodes.clone();
    let steps = u.int_in_range(0..=6u8)?;
    for _ in 0..steps {
        let before = snap_cc(&cap);
        match cap.step() {
            Err(e) => {
                assert_eq!(before, snap_cc(&cap), "CC step {e:?} changed state");
                break;
            }
            Ok(()) => assert!(
                all_finite(cc_points(&cap).into_iter().map(Point3)),
                "Ok CC step not finite"
            ),
        }
        let small_now = small && bounded(cc_points(&cap), 20);
        let patches: Vec<_> = cap.ring_patches().collect();
        assert_eq!(patches.len(), cap.ring_len());
        for (k, p) in patches.iter().enumerate() {
            assert!(cap.ring_patch_domain(k).is_ok());
            if small_now {
                assert!(
                    all_finite(p.points.iter().flatten().copied()),
                    "CC patch not finite"
                );
            }
        }
        assert!(cap.ring_patch(cap.ring_len()).is_err());
    }
    let small_now = small && bounded(cc_points(&cap), 20);
    if small_now {
        assert!(cap.limit().is_finite(), "CC limit not finite");
    }
    if let Ok(nrm) = cap.normal() {
        assert!(nrm.is_finite(), "Ok CC normal not finite: {nrm:?}");
        let len = nrm.norm().to_f64();
        // Regression: tests/fuzz_regressions.rs, cc_normal_of_*_is_unit.
        assert!(
            (len - 1.0).abs() < 1e-3,
            "{} CC normal not unit: {len} ({nrm:?}) at level {}, center {center:?}, nodes {:?}",
            R::NAME,
            cap.level(),
            &nodes[..nodes.len().min(12)]
        );
    }
    if let Ok((t1, t2)) = cap.limit_tangents() {
        assert!(
            t1.is_finite() && t2.is_finite(),
            "Ok CC tangents not finite"
        );
    }
    match cap.limit().finite() {
        Ok(p) => assert!(p.is_finite(), "Ok CC limit().finite() not finite"),
        Err(_) => assert!(!cap.limit().is_finite()),
    }
    Ok(())
}

fuzz_target!(|data: &[u8]| {
    let mut u = Unstructured::new(data);
    let _ = match u.arbitrary::<u8>().unwrap_or(0) & 3 {
        0 => run_eg::<f64>(&mut u),
        1 => run_eg::<f32>(&mut u),
        2 => run_cc::<f64>(&mut u),
        _ => run_cc::<f32>(&mut u),
    };
});
