//! C²PS kernel: `PolarNet` and `PolarNetBuf` (new, reset, reset_flat, step,
//! rts_step, ring patches, jet) on arbitrary f32 / f64 bit patterns, valences
//! 0..=64, up to 6 steps, arbitrary storage sizes for the buffer net.
//!
//! Oracle: no panic; on every error the net is bitwise unchanged; both nets
//! agree bit for bit while they have taken the same successful operations
//! (the kernel's promise: one code path); an `Ok` step or RTS step is finite
//! (the kernel documents `NonFinite` when a step could overflow); an `Ok`
//! jet (`PoleJet::finite`) and `PoleGeometry` are finite; for inputs whose
//! coordinates are at most MAX/2^40, every ring patch and jet is finite.
#![no_main]

use arbitrary::{Result, Unstructured};
use capdiv::{FirstStep, Point3, PolarNet, PolarNetBuf, PoleJet, SliceStorage};
use capdiv_fuzz::{all_finite, arb_point, arb_pool, bounded, point_bits, FuzzReal};
use libfuzzer_sys::fuzz_target;

const CAP: usize = 1024;

struct Cfg<R> {
    pole: [R; 3],
    links: Vec<Vec<[R; 3]>>,
}

fn arb_cfg<R: FuzzReal>(u: &mut Unstructured<'_>) -> Result<Cfg<R>> {
    let n = u.int_in_range(0..=64usize)?;
    let nl = u.int_in_range(0..=7usize)?;
    let analytic: bool = u.arbitrary()?;
    let mismatch: u8 = u.arbitrary()?;
    let pool = arb_pool::<R>(u, 8)?;
    let scale = R::arb(u)?.to_f64();
    let shape = [
        f64::from(u.arbitrary::<i8>()?) / 16.0,
        f64::from(u.arbitrary::<i8>()?) / 16.0,
    ];
    let pick = |i: usize| pool[i % pool.len()];
    let mut links = Vec::with_capacity(nl);
    for k in 0..nl {
        let len = if mismatch < 8 && usize::from(mismatch) % nl.max(1) == k {
            n + 1 - 2 * usize::from(n > 0 && mismatch & 1 == 0)
        } else {
            n
        };
        let mut link = Vec::with_capacity(len);
        for j in 0..len {
            let q = pick(k * 7 + j);
            if analytic {
                let t = 2.0 * std::f64::consts::PI * j as f64 / len.max(1) as f64;
                let r = (k + 1) as f64;
                let (x, y) = (r * t.cos(), r * t.sin());
                let z = shape[0] * x * x + shape[1] * y * y;
                let base = [x, y, z];
                let mut p = [R::ZERO; 3];
                for c in 0..3 {
                    p[c] = R::from_f64(base[c] * scale + q[c].to_f64() * 1e-3);
                }
                link.push(p);
            } else {
                link.push(q);
            }
        }
        links.push(link);
    }
    let pole = if analytic {
        let q = pick(99);
        [q[0], q[1], q[2]].map(|c| R::from_f64(c.to_f64() * 1e-3))
    } else {
        arb_point(u)?
    };
    Ok(Cfg { pole, links })
}

fn snap_net<R: FuzzReal, const C: usize>(net: &PolarNet<R, C>) -> Vec<u64> {
    let mut v = vec![
        net.valence() as u64,
        net.base_valence() as u64,
        u64::from(net.level()),
        net.link_count() as u64,
    ];
    point_bits(net.pole(), &mut v);
    for i in 1..=net.link_count() {
        for p in net.link(i).unwrap_or(&[]) {
            point_bits(*p, &mut v);
        }
    }
    for r in net.roots() {
        v.push(r[0].bits());
        v.push(r[1].bits());
    }
    v
}

fn snap_buf<R: FuzzReal>(net: &PolarNetBuf<'_, R>) -> Vec<u64> {
    let mut v = vec![
        net.valence() as u64,
        net.base_valence() as u64,
        u64::from(net.level()),
        net.link_count() as u64,
    ];
    point_bits(net.pole(), &mut v);
    for i in 1..=net.link_count() {
        for p in net.link(i).unwrap_or(&[]) {
            point_bits(*p, &mut v);
        }
    }
    for r in net.roots() {
        v.push(r[0].bits());
        v.push(r[1].bits());
    }
    v
}

fn links_finite_net<R: FuzzReal, const C: usize>(net: &PolarNet<R, C>) -> bool {
    net.pole().is_finite()
        && (1..=net.link_count()).all(|i| all_finite(net.link(i).unwrap_or(&[]).iter().copied()))
}

fn links_finite_buf<R: FuzzReal>(net: &PolarNetBuf<'_, R>) -> bool {
    net.pole().is_finite()
        && (1..=net.link_count()).all(|i| all_finite(net.link(i).unwrap_or(&[]).iter().copied()))
}

/// The net's pole and links are at most MAX/2^40 (finite results expected).
fn net_small<R: FuzzReal, const C: usize>(net: &PolarNet<R, C>) -> bool {
    bounded(
        (1..=net.link_count())
            .flat_map(|i| net.link(i).unwrap_or(&[]).iter().map(|p| p.0))
            .chain([net.pole().0]),
        40,
    )
}

fn buf_small<R: FuzzReal>(net: &PolarNetBuf<'_, R>) -> bool {
    bounded(
        (1..=net.link_count())
            .flat_map(|i| net.link(i).unwrap_or(&[]).iter().map(|p| p.0))
            .chain([net.pole().0]),
        40,
    )
}

fn jet_bits<R: FuzzReal>(j: &PoleJet<R>) -> Vec<u64> {
    let mut v = Vec::new();
    for p in j.p {
        point_bits(p, &mut v);
    }
    v
}

fn check_jet<R: FuzzReal>(jet: &PoleJet<R>, finite_expected: bool) {
    if finite_expected {
        assert!(
            all_finite(jet.p),
            "jet not finite for bounded input: {jet:?}"
        );
    }
    if let Ok(g) = jet.geometry() {
        assert!(
            g.normal.is_finite()
                && g.gaussian.is_finite()
                && g.mean.is_finite()
                && g.principal.iter().all(|c| c.is_finite()),
            "Ok geometry not finite: {g:?} of {jet:?}"
        );
    }
}

fn run<R: FuzzReal>(u: &mut Unstructured<'_>) -> Result<()> {
    let link_len = u.int_in_range(0..=5 * CAP + 7)?;
    let root_len = u.int_in_range(0..=CAP + 3)?;
    let mut ls = vec![Point3::<R>::ZERO; link_len];
    let mut rs = vec![[R::ZERO; 2]; root_len];
    let mut buf = PolarNetBuf::empty_in(SliceStorage::new(&mut ls, &mut rs));
    let mut net: Box<PolarNet<R, CAP>> = Box::new(PolarNet::empty());
    // Both nets hold the same configuration while `synced`.
    let mut synced = true;
    let mut steps = 0u32;

    let ops = u.int_in_range(1..=12u8)?;
    for _ in 0..ops {
        match u.int_in_range(0..=8u8)? {
            0 | 1 => {
                // reset (op 1 via the flat layout)
                let cfg = arb_cfg::<R>(u)?;
                let flat: Vec<R> = cfg.links.iter().flatten().flatten().copied().collect();
                let valence = cfg.links.first().map_or(0, Vec::len);
                let (before_n, before_b) = (snap_net(&net), snap_buf(&buf));
                let (rn, rb, small_net) = if u.arbitrary::<bool>()? {
                    (
                        net.reset(cfg.pole, &cfg.links),
                        buf.reset(cfg.pole, &cfg.links),
                        PolarNet::<R, 64>::new(cfg.pole, &cfg.links),
                    )
                } else {
                    (
                        net.reset_flat(cfg.pole, valence, &flat),
                        buf.reset_flat(cfg.pole, valence, &flat),
                        PolarNet::<R, 64>::from_flat(cfg.pole, valence, &flat),
                    )
                };
                // new() / from_flat() agree with the resets on a small-capacity net.
                match (&small_net, &rn) {
                    (Ok(s), Ok(())) => assert_eq!(snap_net(s), snap_net(&net)),
                    (Err(capdiv::Error::CapacityExceeded { .. }), _) => {}
                    (Err(e), Err(f)) => assert_eq!(e, f),
                    (Ok(_), Err(e)) => assert!(false, "new Ok where reset failed: {e:?}"),
                    (Err(e), Ok(())) => assert!(false, "new failed where reset Ok: {e:?}"),
                }
                if rn.is_err() {
                    assert_eq!(
                        before_n,
                        snap_net(&net),
                        "reset error {rn:?} changed the net"
                    );
                }
                if rb.is_err() {
                    assert_eq!(
                        before_b,
                        snap_buf(&buf),
                        "reset error {rb:?} changed the buf net"
                    );
                }
                match (&rn, &rb) {
                    (Ok(()), Ok(())) => {
                        synced = true;
                        steps = 0;
                    }
                    (Err(e), Err(f)) => assert_eq!(e, f, "net and buf disagree"),
                    (Err(capdiv::Error::CapacityExceeded { .. }), Ok(()))
                    | (Ok(()), Err(capdiv::Error::CapacityExceeded { .. })) => synced = false,
                    (a, b) => panic!("net {a:?} and buf {b:?} disagree"),
                }
                if rn.is_ok() != rb.is_ok() {
                    synced = false;
                }
            }
            2 | 3 => {
                if steps >= 6 {
                    continue;
                }
                steps += 1;
                let first = if u.arbitrary::<bool>()? {
                    FirstStep::Uniform
                } else {
                    FirstStep::Plain
                };
                let (before_n, before_b) = (snap_net(&net), snap_buf(&buf));
                let rn = net.step(first);
                let rb = buf.step(first);
                match &rn {
                    Err(e) => {
                        assert_eq!(before_n, snap_net(&net), "step error {e:?} changed the net")
                    }
                    Ok(()) => assert!(links_finite_net(&net), "Ok step not finite"),
                }
                match &rb {
                    Err(e) => {
                        assert_eq!(before_b, snap_buf(&buf), "step error {e:?} changed the buf")
                    }
                    Ok(()) => assert!(links_finite_buf(&buf), "Ok buf step not finite"),
                }
                if rn.is_ok() != rb.is_ok() {
                    synced = false;
                }
            }
            4 => {
                if steps >= 6 {
                    continue;
                }
                steps += 1;
                let (before_n, before_b) = (snap_net(&net), snap_buf(&buf));
                let rn = net.rts_step();
                let rb = buf.rts_step();
                match &rn {
                    Err(e) => {
                        assert_eq!(before_n, snap_net(&net), "rts error {e:?} changed the net")
                    }
                    Ok(()) => assert!(links_finite_net(&net), "Ok rts step not finite"),
                }
                match &rb {
                    Err(e) => {
                        assert_eq!(before_b, snap_buf(&buf), "rts error {e:?} changed the buf")
                    }
                    Ok(()) => assert!(links_finite_buf(&buf), "Ok buf rts step not finite"),
                }
                if rn.is_ok() != rb.is_ok() {
                    synced = false;
                }
            }
            5 => {
                let pn = net.ring_patches().collect::<Vec<_>>();
                let pb = buf.ring_patches().collect::<Vec<_>>();
                for (ps, small) in [(&pn, net_small(&net)), (&pb, buf_small(&buf))] {
                    if small {
                        assert!(ps
                            .iter()
                            .all(|p| all_finite(p.points.iter().flatten().copied())));
                    }
                }
                if synced {
                    assert_eq!(pn, pb, "ring patches of net and buf differ");
                }
                assert_eq!(pn.len(), net.ring_len());
                assert_eq!(pb.len(), buf.ring_len());
            }
            6 => {
                let k = u.int_in_range(0..=2 * net.valence() + 1)?;
                let a = net.ring_patch(k);
                let b = buf.ring_patch(k);
                if synced {
                    assert_eq!(a, b);
                }
                assert_eq!(a.is_ok(), k < net.ring_len());
            }
            _ => {
                let jn = PoleJet::of(&net);
                let jb = PoleJet::of(&buf);
                if synced {
                    assert_eq!(jet_bits(&jn), jet_bits(&jb));
                }
                check_jet(&jn, net_small(&net));
                check_jet(&jb, buf_small(&buf));
                // PoleJet::finite: Ok only when finite, and then the same jet.
                match PoleJet::of(&net).finite() {
                    Ok(j) => assert_eq!(jet_bits(&j), jet_bits(&jn)),
                    Err(_) => assert!(!all_finite(jn.p)),
                }
                match PoleJet::of(&buf).finite() {
                    Ok(j) => assert_eq!(jet_bits(&j), jet_bits(&jb)),
                    Err(_) => assert!(!all_finite(jb.p)),
                }
            }
        }
        if synced {
            assert_eq!(snap_net(&net), snap_buf(&buf), "net and buf diverged");
        }
    }
    Ok(())
}

fuzz_target!(|data: &[u8]| {
    let mut u = Unstructured::new(data);
    let _ = match u.arbitrary::<u8>().unwrap_or(0) & 1 {
        0 => run::<f64>(&mut u),
        _ => run::<f32>(&mut u),
    };
});
