//! The streaming C²PS workload (issue 9; kernel `PolarStream`, spec C2PS.md
//! §2, §4, §5): the sample net (valence 6) streamed to depth [`DEPTH`] — 12,
//! i.e. 24,576 columns at the deepest ring — in one sweep whose whole state
//! is a `PolarStream<f32, DEPTH>` static (4,732 bytes of `.bss`), far below
//! what the in-place net would need (`17·6·2^12·4` bytes = 1.6 MiB).
//!
//! Per level it logs three checksums of the ring's patches, each a
//! Kahan-compensated `f32` sum: the mean of all 16 control points of every
//! patch (`smean`), the mean corner point weighted by the column's angle
//! fraction `(column + ½)/N` (`sweight`, sensitive to the patch order), and
//! the patch count (`scount`); plus the pole jet. `embedded-tests` recomputes
//! them with the `f64` in-place kernel.

use crate::report::{point, Failure};
use crate::sample::{LINKS, POLE, VALENCE};
use capdiv::{Point3, PolarStream, StreamOptions};

/// Deepest level streamed.
pub const DEPTH: u32 = 12;

/// Levels with a ring (the sample has 7 links, so every level from 0).
const LEVELS: usize = DEPTH as usize + 1;

type State = PolarStream<f32, { DEPTH as usize }>;

/// A Kahan-compensated running sum of points.
#[derive(Clone, Copy)]
struct Sum {
    sum: Point3<f32>,
    carry: Point3<f32>,
}

impl Sum {
    const ZERO: Sum = Sum {
        sum: Point3([0.0; 3]),
        carry: Point3([0.0; 3]),
    };

    fn add(&mut self, x: Point3<f32>) {
        let y = x - self.carry;
        let t = self.sum + y;
        self.carry = (t - self.sum) - y;
        self.sum = t;
    }
}

/// Per-level accumulators.
#[derive(Clone, Copy)]
struct Check {
    points: Sum,
    weighted: Sum,
    count: usize,
}

/// Runs the workload; logs as it goes.
#[inline(never)]
pub fn run() -> Result<(), Failure> {
    let state = cortex_m::singleton!(C2PS_STREAM: State = State::empty()).ok_or(Failure::Reused)?;
    defmt::println!(
        "scfg {=usize} {=u32} {=usize}",
        VALENCE,
        DEPTH,
        core::mem::size_of::<State>()
    );
    let pole = POLE.map(|c| c as f32);
    let links = LINKS.map(|l| l.map(|p| p.map(|c| c as f32)));
    let mut checks = [Check {
        points: Sum::ZERO,
        weighted: Sum::ZERO,
        count: 0,
    }; LEVELS];
    let jet = state.run(pole, &links, StreamOptions::depth(DEPTH), |p| {
        let Some(c) = checks.get_mut(p.level as usize) else {
            return;
        };
        // 16 points summed plainly (a few ulps), the patch sums compensated.
        let mut s = Point3::ZERO;
        for q in p.patch.points.iter().flatten() {
            s += *q;
        }
        c.points.add(s);
        let frac = (p.column as f32 + 0.5) / p.valence as f32;
        c.weighted.add(p.patch.points[0][0] * frac);
        c.count += 1;
    })?;
    for (k, q) in jet.p.iter().enumerate() {
        point("sjet", &[k], *q);
    }
    for (m, c) in checks.iter().enumerate() {
        let n = c.count.max(1) as f32;
        defmt::println!("scount {=usize} {=usize}", m, c.count);
        point(
            "smean",
            &[m],
            (c.points.sum - c.points.carry) * (1.0 / (16.0 * n)),
        );
        point(
            "sweight",
            &[m],
            (c.weighted.sum - c.weighted.carry) * (1.0 / n),
        );
    }
    let (used, _) = crate::stack::high_water_mark();
    defmt::println!("stackstream {=usize}", used);
    Ok(())
}
