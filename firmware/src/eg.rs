//! The EG workload (docs/math/eg.md): the sample c-nets of valence 3 and 5
//! (§1), their limit point (§4, formula (3)), four EG steps each (§5, §6) on
//! an [`EgSubdivision`] in a static, d-net nodes, and the last ring's bi-4
//! patches evaluated (§9).
//!
//! Every number logged here is recomputed in `f64` by
//! `embedded-tests/tests/firmware_qemu.rs`.

use crate::report::{point, Failure};
use crate::sample::{EG_CENTER_F32, EG_NODES_3_F32, EG_NODES_5_F32};
use capdiv::eg::{CNet, EgSubdivision};
use capdiv::Point3;

/// EG steps per sample.
pub const STEPS: u32 = 4;

type Sub = EgSubdivision<'static, f32>;

/// Runs both samples, one after the other in the same statics; logs as it goes.
#[inline(never)]
pub fn run() -> Result<(), Failure> {
    let (net, sub) = statics()?;
    sample(&EG_NODES_3_F32, net, sub)?;
    sample(&EG_NODES_5_F32, net, sub)
}

/// The c-net and the subdivision live in statics (`.bss`, size known at link
/// time), const-constructed empty and loaded in place by `CNet::reset` and
/// `EgSubdivision::reset`, so no net-sized value is ever on the
/// stack. Each sample reuses them: with two, the micro:bit's 16 KiB would not
/// hold the statics and the stack.
#[inline(never)]
fn statics() -> Result<(&'static mut CNet<f32>, &'static mut Sub), Failure> {
    let net = cortex_m::singleton!(EG_CNET: CNet<f32> = CNet::empty()).ok_or(Failure::Reused)?;
    let sub = cortex_m::singleton!(EG_SUB: Sub = Sub::empty()).ok_or(Failure::Reused)?;
    Ok((net, sub))
}

/// One sample: the c-net and its subdivision loaded in place, steps, report.
#[inline(never)]
fn sample<const M: usize>(
    nodes: &[[f32; 3]; M],
    net: &mut CNet<f32>,
    sub: &mut Sub,
) -> Result<(), Failure> {
    net.reset(EG_CENTER_F32, nodes)?;
    sub.reset(net, None)?;
    one(net, sub)
}

/// Quarter-grid parameter `i/4`.
fn quarter(i: usize) -> f32 {
    i as f32 * 0.25
}

#[inline(never)]
fn one(net: &CNet<f32>, sub: &mut Sub) -> Result<(), Failure> {
    let n = net.valence();
    defmt::println!(
        "egcfg {=usize} {=u32} {=usize}",
        n,
        STEPS,
        core::mem::size_of::<Sub>()
    );
    point("eglimit", &[n], net.limit());
    for _ in 0..STEPS {
        sub.step()?;
    }
    point("egc0", &[n], sub.limit());
    let d = sub.net();
    for s in 0..n {
        for (i, j) in [(0, 0), (3, 0), (1, 1), (3, 2)] {
            if let Some(p) = d.node(s, i, j) {
                point("egnode", &[n, s, i, j], p);
            }
        }
    }
    let len = sub.ring_len();
    defmt::println!("egringcount {=usize} {=usize}", n, len);
    for (k, ui, vi) in [(0, 2, 2), (1, 1, 3), (len - 1, 4, 0)] {
        let e = sub.ring_patch(k)?.evaluate(quarter(ui), quarter(vi))?;
        point("egpos", &[n, k, ui, vi], e.position);
        point("egnrm", &[n, k, ui, vi], e.normal()?);
    }
    let mut sum = Point3::ZERO;
    for patch in sub.ring_patches() {
        sum += patch.position(0.5, 0.5)?;
    }
    point("egsum", &[n], sum);
    Ok(())
}
