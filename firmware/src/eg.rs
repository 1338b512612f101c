//! The EG workload (spec EG.md): the sample c-nets of valence 3 and 5
//! (§1), their limit point (§4, formula (3)), four EG steps each (§5, §6) on
//! an [`EgSubdivision`] in a static, d-net nodes, and the last ring's bi-4
//! patches evaluated (§9).
//!
//! Every number logged here is recomputed in `f64` by
//! `embedded-tests/tests/firmware_qemu.rs`.

use crate::report::{point, Failure};
use crate::sample::{EG_CENTER, EG_NODES_3, EG_NODES_5};
use capdiv::eg::{CNet, EgSubdivision};
use capdiv::{Error, Point3};
use core::cell::UnsafeCell;
use core::mem::MaybeUninit;
use core::sync::atomic::{AtomicBool, Ordering};

/// EG steps per sample.
pub const STEPS: u32 = 4;

type Sub = EgSubdivision<'static, f32>;

fn to_f32<const M: usize>(nodes: &[[f64; 3]; M]) -> [[f32; 3]; M] {
    nodes.map(|p| p.map(|c| c as f32))
}

fn cnet<const M: usize>(nodes: &[[f64; 3]; M]) -> Result<CNet<f32>, Error> {
    CNet::new(EG_CENTER.map(|c| c as f32), &to_f32(nodes))
}

/// Runs both samples, one after the other in the same static; logs as it goes.
#[inline(never)]
pub fn run() -> Result<(), Failure> {
    sample(&EG_NODES_3)?;
    sample(&EG_NODES_5)
}

/// One sample: c-net, its subdivision built into [`SLOT`], steps, report.
#[inline(never)]
fn sample<const M: usize>(nodes: &[[f64; 3]; M]) -> Result<(), Failure> {
    let net = cnet(nodes)?;
    SLOT.with(
        || EgSubdivision::from_cnet(&net),
        |sub| match sub {
            Ok(sub) => one(&net, sub),
            Err(e) => Err(Failure::Kernel(*e)),
        },
    )
}

/// The static an EG subdivision lives in (`.bss`, size known at link time),
/// reused by each sample in turn: with two, the micro:bit's 16 KiB would not
/// hold the statics and the stack.
struct Slot {
    value: UnsafeCell<MaybeUninit<Result<Sub, Error>>>,
    busy: AtomicBool,
}

// SAFETY: `busy` admits one `with` at a time (load/store suffice: single
// core, never used from an interrupt).
unsafe impl Sync for Slot {}

static SLOT: Slot = Slot {
    value: UnsafeCell::new(MaybeUninit::uninit()),
    busy: AtomicBool::new(false),
};

impl Slot {
    /// Writes `init()` into the slot and runs `f` on it; [`Failure::Reused`]
    /// if called from inside `f`.
    fn with<T>(
        &self,
        init: impl FnOnce() -> Result<Sub, Error>,
        f: impl FnOnce(&mut Result<Sub, Error>) -> Result<T, Failure>,
    ) -> Result<T, Failure> {
        if self.busy.load(Ordering::Relaxed) {
            return Err(Failure::Reused);
        }
        self.busy.store(true, Ordering::Relaxed);
        // SAFETY: `busy` guarantees no other reference into the slot exists;
        // the old value (plain data, no Drop) is simply overwritten.
        let value = unsafe { (*self.value.get()).write(init()) };
        let out = f(value);
        self.busy.store(false, Ordering::Relaxed);
        out
    }
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
    point("egc0", &[n], sub.c0());
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
