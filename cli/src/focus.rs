//! `--focus V --zoom Z`: the region a zoomed picture frames, the
//! neighbourhood of input vertex `V` and its cap. `V` is numbered as the
//! input numbers it: 1-based for a Wavefront OBJ, 0-based for JSON (a polar
//! net, c-net or d-net has one cap, at vertex 0: the pole or centre).
//!
//! The centre is the limit point of `V`'s cap when `V` has one in the first
//! panel's surface, else the patch corner nearest to `V` (a regular vertex's
//! limit point is a corner of its patches). At zoom 1 the picture's shorter
//! side spans the 1-ring: twice the largest distance from `V` to a vertex it
//! shares an edge with (polar: link 1; c-net: the nodes (1,0) and (1,1) of
//! every sector; d-net: the nodes within one c-unit of the centre); zoom
//! `Z` magnifies that `Z` times.

use crate::camera::{Focus, V3};
use crate::error::{CliError, Naming};
use crate::input::Input;
use crate::shape::Shape;

/// Default magnification of `--focus`.
pub const DEFAULT_ZOOM: f64 = 4.0;

fn dist(a: V3, b: V3) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// The input's 0-based vertex for the number `number` as the file gives
/// it, or a one-line error naming the numbers there are.
pub fn vertex_index(
    name: &str,
    input: &Input,
    naming: &Naming,
    number: usize,
) -> Result<usize, CliError> {
    let bad = |range: String| {
        CliError::Usage(format!(
            "{name}: --focus {number}: no such vertex ({range})"
        ))
    };
    match input {
        Input::Mesh(m) => {
            let n = m.vertices.len();
            let (first, last) = (naming.number(0), naming.number(n.saturating_sub(1)));
            let index = number.checked_sub(first).filter(|&i| i < n);
            index.ok_or_else(|| bad(format!("the mesh has vertices {first}..={last}")))
        }
        other => {
            if number == 0 {
                Ok(0)
            } else {
                let centre = match other {
                    Input::Polar(_) => "the pole",
                    _ => "the centre",
                };
                Err(bad(format!(
                    "a '{}' input has one cap, at vertex 0, {centre}",
                    other.kind()
                )))
            }
        }
    }
}

/// The framed region of vertex `number` at magnification `zoom`.
pub fn focus(
    name: &str,
    input: &Input,
    naming: &Naming,
    shape: &Shape,
    number: usize,
    zoom: f64,
) -> Result<Focus, CliError> {
    let index = vertex_index(name, input, naming, number)?;
    let cap = shape
        .caps
        .iter()
        .find(|c| c.vertex == Some(index as u32))
        .map(|c| c.limit);
    let (position, ring): (V3, f64) = match input {
        Input::Mesh(m) => {
            let p = m.vertices[index];
            let mut r: f64 = 0.0;
            for f in &m.faces {
                let k = f.len();
                for (i, &a) in f.iter().enumerate() {
                    let b = f[(i + 1) % k];
                    let other = if a == index as i64 {
                        b
                    } else if b == index as i64 {
                        a
                    } else {
                        continue;
                    };
                    if let Some(&q) = usize::try_from(other).ok().and_then(|o| m.vertices.get(o)) {
                        r = r.max(dist(p, q));
                    }
                }
            }
            (p, r)
        }
        Input::Polar(p) => {
            let r = p.links.first().map_or(0.0, |l| {
                l.iter().map(|&q| dist(p.pole, q)).fold(0.0, f64::max)
            });
            (p.pole, r)
        }
        Input::Cnet(c) => {
            let r = c
                .sectors
                .iter()
                .flat_map(|s| [s[0], s[2]])
                .map(|q| dist(c.center, q))
                .fold(0.0, f64::max);
            (c.center, r)
        }
        Input::Dnet(d) => {
            let centre = cap.unwrap_or([0.0; 3]);
            // d_ij at c-coordinates ((3−i)/2, (3−j)/2), stored j·4 + i.
            let r = d
                .sectors
                .iter()
                .flat_map(|s| [s[5], s[6], s[7], s[9], s[10], s[11]])
                .map(|q| dist(centre, q))
                .fold(0.0, f64::max);
            (centre, r)
        }
    };
    let centre = match cap {
        Some(c) => c,
        None => nearest_corner(shape, position).unwrap_or(position),
    };
    let radius = ring / zoom;
    if !(radius > 0.0 && radius.is_finite() && centre.iter().all(|c| c.is_finite())) {
        return Err(CliError::Usage(format!(
            "{name}: --focus {number}: the vertex has no neighbour at a positive distance to frame"
        )));
    }
    Ok(Focus { centre, radius })
}

/// The patch corner of `shape` nearest to `p`.
fn nearest_corner(shape: &Shape, p: V3) -> Option<V3> {
    shape
        .patches
        .iter()
        .flat_map(|sp| {
            [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
                .into_iter()
                .filter_map(|(u, v)| sp.geometry().jet(u, v).ok().map(|j| j.position.0))
        })
        .filter(|q| q.iter().all(|c| c.is_finite()))
        .min_by(|a, b| dist(*a, p).total_cmp(&dist(*b, p)))
}

/// A panel's label under `--focus`: the cap at the vertex of 0-based
/// `index` (numbered `number` in the file), `vertex 7: EG cap`, or
/// `vertex 7: no cap; ` and the shape's own label.
pub fn focus_label(shape: &Shape, index: usize, number: usize) -> String {
    match shape.caps.iter().find(|c| c.vertex == Some(index as u32)) {
        Some(c) => format!("vertex {number}: {} cap", c.scheme),
        None => format!("vertex {number}: no cap; {}", shape.label),
    }
}
