//! `capdiv curvature`: per ring level the extremes of the Gaussian and mean
//! curvature over samples of that ring, exact from the patches' derivatives
//! (`TensorPatch::jet`, `SurfaceJet::geometry`), and the limit values at the
//! centre where the scheme defines them (C²PS, RTS: the pole jet, spec
//! docs/math/c2ps.md §4; EG and Catmull-Clark: `null`, the reason on stderr).
//!
//! ```json
//! {"scheme": "c2ps", "levels": [{"level": 0, "gaussian": [min, max], "mean": [min, max]}, ...],
//!  "limit": {"gaussian": K, "mean": H}}
//! ```
//!
//! Samples: every ring patch at `(a/S, b/S)`, `a, b = 0..S` (`--samples S`,
//! default 8), edges included; points where the tangent plane degenerates are
//! skipped. The sign of `H` follows the patch normal `∂u × ∂v`.

use super::Outcome;
use crate::args::CurvatureArgs;
use crate::error::CliError;
use crate::json::to_json;
use crate::output::Sink;
use crate::shape::{build, geometry_at, read_any, Limit, Shape};
use serde::Serialize;

/// One ring level's extremes.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LevelRange {
    /// The ring level.
    pub level: u32,
    /// `[min, max]` of `K`.
    pub gaussian: [f64; 2],
    /// `[min, max]` of `H`.
    pub mean: [f64; 2],
}

/// Limit values at the centre.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LimitValues {
    /// `K`.
    pub gaussian: f64,
    /// `H`.
    pub mean: f64,
}

/// The command's output.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CurvatureTable {
    /// The scheme.
    pub scheme: &'static str,
    /// Per ring level, increasing.
    pub levels: Vec<LevelRange>,
    /// At the centre, where defined.
    pub limit: Option<LimitValues>,
}

/// The table of a shape, `samples` segments per patch side.
pub fn table(shape: &Shape, samples: u32) -> CurvatureTable {
    let s = samples.max(1);
    let mut levels: Vec<LevelRange> = Vec::new();
    for p in shape.patches.iter().filter(|p| p.ring) {
        for a in 0..=s {
            for b in 0..=s {
                let (u, v) = (f64::from(a) / f64::from(s), f64::from(b) / f64::from(s));
                let Some((_, _, k, h)) = geometry_at(p.geometry(), u, v) else {
                    continue;
                };
                let entry = match levels.iter_mut().find(|l| l.level == p.level) {
                    Some(e) => e,
                    None => {
                        levels.push(LevelRange {
                            level: p.level,
                            gaussian: [k, k],
                            mean: [h, h],
                        });
                        levels.last_mut().unwrap_or_else(|| unreachable!())
                    }
                };
                entry.gaussian = [entry.gaussian[0].min(k), entry.gaussian[1].max(k)];
                entry.mean = [entry.mean[0].min(h), entry.mean[1].max(h)];
            }
        }
    }
    levels.sort_by_key(|l| l.level);
    let limit = match shape.limit {
        Limit::Known { gaussian, mean } => Some(LimitValues { gaussian, mean }),
        Limit::Undefined(_) => None,
    };
    CurvatureTable {
        scheme: shape.scheme,
        levels,
        limit,
    }
}

/// Runs the command.
pub fn run(args: &CurvatureArgs) -> Result<Outcome, CliError> {
    let (name, input, naming) = read_any(&args.io.file)?;
    let shape = build(&name, &input, args.scheme, args.depth).map_err(|e| e.named(&naming))?;
    let t = table(&shape, args.samples);
    let mut out = Outcome::new(
        to_json(&t, args.pretty),
        Sink::from_option(args.io.output.clone()),
    );
    if let Limit::Undefined(why) = shape.limit {
        out.report = format!("note: limit is null: {why}\n");
    }
    Ok(out)
}
