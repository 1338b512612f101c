//! The C²PS workload (docs/math/c2ps.md): the sample net refined `DEPTH` times in
//! place in a static, its pole jet and geometry (§4), links, ring patches
//! evaluated (§5), three RTS steps (§3) and the level-0 outer region (§5).
//!
//! Every number logged here is recomputed in `f64` by
//! `embedded-tests/tests/firmware_qemu.rs`; evaluation parameters are logged as
//! quarters (`u = ui/4`) so the host evaluates at exactly the same points.

use crate::report::{point, Failure};
use crate::sample::{LINKS_F32, LINKS_GIVEN, POLE_F32, VALENCE};
use capdiv::{FirstStep, OuterRegion, PolarNet, PoleJet};

/// Steps applied: 6 on the Cortex-M4 board, 3 on the 16 KiB micro:bit.
#[cfg(not(armv6m))]
pub const DEPTH: u32 = 6;
/// Steps applied: 6 on the Cortex-M4 board, 3 on the 16 KiB micro:bit.
#[cfg(armv6m)]
pub const DEPTH: u32 = 3;

/// Capacity per link: the valence after `DEPTH` steps.
pub const CAP: usize = VALENCE << DEPTH;

type Net = PolarNet<f32, CAP>;

/// Links the net stores (1..5).
const STORED: usize = 5;

fn pole() -> [f32; 3] {
    POLE_F32
}

fn links() -> [[[f32; 3]; VALENCE]; LINKS_GIVEN] {
    LINKS_F32
}

/// Runs the workload; logs as it goes.
#[inline(never)]
pub fn run() -> Result<(), Failure> {
    let net = build()?;
    // The construction's stack peak (its frame is gone now), then a fresh
    // paint for the refinement and evaluation.
    let (built, _) = crate::stack::high_water_mark();
    crate::stack::repaint();
    refine_and_report(net)?;
    let (rest, _) = crate::stack::high_water_mark();
    defmt::println!("stackc2ps {=usize} {=usize}", built, rest);
    Ok(())
}

/// Builds the sample net into its static (`.bss`, size known at link time):
/// the const-constructed empty net is loaded in place by `PolarNet::reset`,
/// so no net-sized temporary lives on the stack.
#[inline(never)]
fn build() -> Result<&'static mut Net, Failure> {
    let links = links();
    let stored = links.get(..STORED).unwrap_or(&[]);
    let net = cortex_m::singleton!(C2PS_NET: Net = Net::empty()).ok_or(Failure::Reused)?;
    net.reset(pole(), stored)?;
    Ok(net)
}

/// Refines in place, reads the results out, logs them.
#[inline(never)]
fn refine_and_report(net: &mut Net) -> Result<(), Failure> {
    defmt::println!(
        "cfg {=usize} {=u32} {=usize} {=usize}",
        VALENCE,
        DEPTH,
        CAP,
        core::mem::size_of::<Net>()
    );
    log_jet("jet0", &PoleJet::of(net));
    for _ in 0..DEPTH {
        net.step(FirstStep::Uniform)?;
        point("pole", &[net.level() as usize], net.pole());
    }
    let jet = PoleJet::of(net);
    log_jet("jet", &jet);
    point("limit", &[], jet.limit());
    let g = jet.geometry()?;
    point("normal", &[], g.normal);
    defmt::println!(
        "curv {=f32} {=f32} {=f32} {=f32}",
        g.gaussian,
        g.mean,
        g.principal[0],
        g.principal[1]
    );
    defmt::println!("geometry {}", g);
    let n = net.valence();
    for i in 1..=STORED {
        let link = net.link(i).unwrap_or(&[]);
        for j in [0, 1, n / 2, n - 1] {
            if let Some(p) = link.get(j) {
                point("link", &[i, j], *p);
            }
        }
    }
    ring(net)?;
    rts()?;
    outer(&links())
}

fn log_jet(key: &str, jet: &PoleJet<f32>) {
    for (k, p) in jet.p.iter().enumerate() {
        point(key, &[k], *p);
    }
}

/// Quarter-grid parameter `i/4`.
fn quarter(i: usize) -> f32 {
    i as f32 * 0.25
}

/// Ring patches of the final level: a few evaluations, then all `2N`.
fn ring(net: &Net) -> Result<(), Failure> {
    let n = net.valence();
    for (span, col, ui, vi) in [(0, 0, 2, 2), (1, n - 1, 1, 3), (0, n / 3, 4, 0)] {
        let patch = net.ring_patch(span * n + col)?;
        let e = patch.evaluate(quarter(ui), quarter(vi))?;
        point("ringpos", &[span, col, ui, vi], e.position);
        point("ringdu", &[span, col, ui, vi], e.du);
        point("ringdv", &[span, col, ui, vi], e.dv);
        point("ringnrm", &[span, col, ui, vi], e.normal()?);
    }
    let mut sum = capdiv::Point3::ZERO;
    let mut count = 0usize;
    for patch in net.ring_patches() {
        sum += patch.position(0.5, 0.5)?;
        count += 1;
    }
    defmt::println!("ringcount {=usize}", count);
    point("ringsum", &[], sum);
    Ok(())
}

/// Three RTS steps on a level-0 net built from flat coordinates.
fn rts() -> Result<(), Failure> {
    let mut flat = [0.0f32; STORED * VALENCE * 3];
    for (dst, src) in flat
        .iter_mut()
        .zip(LINKS_F32.iter().take(STORED).flatten().flatten())
    {
        *dst = *src;
    }
    let mut net = PolarNet::<f32, VALENCE>::from_flat(pole(), VALENCE, &flat)?;
    for k in 1..=3 {
        net.rts_step()?;
        point("rtspole", &[k], net.pole());
    }
    for (j, p) in net.link(1).unwrap_or(&[]).iter().enumerate() {
        point("rtslink", &[j], *p);
    }
    // The whole net through the kernel's `defmt::Format` (for a human reader).
    defmt::println!("rtsnet {}", net);
    Ok(())
}

/// The level-0 outer region of all 7 links: one span of `VALENCE` patches.
fn outer(links: &[[[f32; 3]; VALENCE]; LINKS_GIVEN]) -> Result<(), Failure> {
    let region = OuterRegion::new(pole(), links)?;
    defmt::println!("outercount {=usize}", region.len());
    for (i, ui, vi) in [(0, 2, 2), (VALENCE - 1, 4, 1)] {
        let e = region.patch(i)?.evaluate(quarter(ui), quarter(vi))?;
        point("outerpos", &[i, ui, vi], e.position);
        point("outernrm", &[i, ui, vi], e.normal()?);
    }
    let mut sum = capdiv::Point3::ZERO;
    for patch in region.patches() {
        sum += patch.position(0.5, 0.5)?;
    }
    point("outersum", &[], sum);
    Ok(())
}
