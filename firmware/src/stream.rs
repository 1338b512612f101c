//! The streaming C²PS workload (kernel `PolarStream`, docs/math/c2ps.md
//! §2, §4, §5): the sample net (valence 6) streamed to depth [`DEPTH`] — 12,
//! i.e. 24,576 columns at the deepest ring — in one sweep whose whole state
//! is a `PolarStream<f32, DEPTH>` static (4,732 bytes of `.bss`), far below
//! what the in-place net would need (`17·6·2^12·4` bytes = 1.6 MiB).
//!
//! Per level it logs two checksums of the ring's patches: the patch count
//! (`scount`) and the mean over the patches of the mean of their 16 control
//! points weighted by the column's angle fraction `(column + ½)/N`
//! (`sweight`: every control point counts, and so does the order), a
//! Kahan-compensated `f32` sum; plus the pole jet. `embedded-tests`
//! recomputes them with the `f64` in-place kernel.

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
    weighted: Sum,
    count: usize,
}

/// Links 1..5 of the sample in `f32` (exact: the coordinates are dyadic),
/// converted at compile time: read-only data, not a 360-byte temporary on the
/// stack.
static LINKS5: [[[f32; 3]; VALENCE]; 5] = {
    let mut out = [[[0.0f32; 3]; VALENCE]; 5];
    let mut i = 0;
    while i < 5 {
        let mut j = 0;
        while j < VALENCE {
            let mut c = 0;
            while c < 3 {
                out[i][j][c] = LINKS[i][j][c] as f32;
                c += 1;
            }
            j += 1;
        }
        i += 1;
    }
    out
};

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
    let mut checks = [Check {
        weighted: Sum::ZERO,
        count: 0,
    }; LEVELS];
    let jet = state.run(pole, &LINKS5, StreamOptions::depth(DEPTH), |p| {
        let Some(c) = checks.get_mut(p.level as usize) else {
            return;
        };
        // 16 points summed plainly (a few ulps), weighted by the column's
        // angle fraction (so the order counts), the patch sums compensated.
        let mut s = Point3::ZERO;
        for q in p.patch.points.iter().flatten() {
            s += *q;
        }
        let frac = (p.column as f32 + 0.5) / p.valence as f32;
        c.weighted.add(s * (frac / 16.0));
        c.count += 1;
    })?;
    for (k, q) in jet.p.iter().enumerate() {
        point("sjet", &[k], *q);
    }
    for (m, c) in checks.iter().enumerate() {
        let n = c.count.max(1) as f32;
        defmt::println!("scount {=usize} {=usize}", m, c.count);
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
