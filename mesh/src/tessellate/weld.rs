//! Welding coincident points: a hash grid built by sorting.
//!
//! Two points are *close* when `max(|Δx|, |Δy|, |Δz|) ≤ tol`; a vertex is a
//! class of points linked by chains of close pairs (the connected components
//! of "close", so the result does not depend on the order of the points).
//!
//! Each point is keyed by its cell `⌊x / c⌋` (per coordinate, in `f64`), cell
//! size `c = 32·tol`; the points are sorted by cell (then by coordinates, so
//! equal points are consecutive), making each cell one run. Close pairs are
//! found within a run, and — only for a point within `tol` of a cell face —
//! with the neighbouring cells that the box `x ± tol` touches (at most 7,
//! each found by binary search, each pair looked at from the lower cell);
//! equal points are joined at once and looked at as one. They are joined in
//! a union-find. Cost: one sort, `O(N log N)`, plus the pairs of distinct
//! points sharing a cell — a handful per point when samples lie further apart
//! than the cell size.
//!
//! Tolerance 0 (or negative, or NaN) welds equal coordinates only (`0.0` and
//! `−0.0` are equal); a point with a NaN coordinate is never close to any
//! other. Coordinates beyond `i64::MAX · c` share the saturated cells: still
//! correct, only slower.

use crate::mem::{self, OutOfMemory};
use alloc::vec::Vec;
use capdiv::{Point3, Real};

/// Cell size in tolerances: a point looks beyond its own cell only within
/// `tol` of a cell face, a fraction `1 − (1 − 2/CELL)³` (18 %) of the points.
const CELL: f64 = 32.0;

/// A point in sorted order.
struct Entry {
    key: [i64; 3],
    x: [f64; 3],
    index: u32,
}

/// For each point, the first point of its class (the smallest index; the
/// point itself when it is the first).
pub fn representatives<R: Real>(points: &[Point3<R>], tol: R) -> Result<Vec<u32>, OutOfMemory> {
    let count = points.len();
    assert!(
        u32::try_from(count).is_ok(),
        "weld: more than u32::MAX points"
    );
    let tol = tol.to_f64();
    let tol = if tol > 0.0 { tol } else { 0.0 };
    let cell = CELL * tol;
    let key_of = |x: f64| -> i64 {
        if tol == 0.0 {
            x.to_bits() as i64
        } else {
            // Saturating cast; NaN gives 0.
            libm::floor(x / cell) as i64
        }
    };
    let mut sorted: Vec<Entry> = mem::collect(points.iter().enumerate().map(|(k, p)| {
        // −0 made +0.
        let x = p.0.map(|c| c.to_f64() + 0.0);
        Entry {
            key: x.map(key_of),
            x,
            index: k as u32,
        }
    }))?;
    sorted.sort_unstable_by(|a, b| {
        a.key
            .cmp(&b.key)
            .then_with(|| a.x.map(f64::to_bits).cmp(&b.x.map(f64::to_bits)))
            .then(a.index.cmp(&b.index))
    });

    let close = |a: &[f64; 3], b: &[f64; 3]| (0..3).all(|d| libm::fabs(a[d] - b[d]) <= tol);
    let mut parent: Vec<u32> = mem::collect(0..count as u32)?;
    let mut run_start = 0;
    for s in 0..count {
        let e = &sorted[s];
        if s > 0 && sorted[s - 1].key != e.key {
            run_start = s;
        }
        // Equal to the previous point (NaN never is): same class, same pairs.
        if s > run_start && sorted[s - 1].x == e.x {
            union(&mut parent, s - 1, s);
            continue;
        }
        // Later points of the run (cells are small).
        for (t, f) in sorted.iter().enumerate().skip(s + 1) {
            if f.key != e.key {
                break;
            }
            if close(&e.x, &f.x) {
                union(&mut parent, s, t);
            }
        }
        if tol == 0.0 {
            continue;
        }
        let lo = e.x.map(|c| key_of(c - tol));
        let hi = e.x.map(|c| key_of(c + tol));
        if lo == hi {
            continue;
        }
        // At most 2 cells per axis (the box is narrower than a cell); the
        // cap guards against rounding. Only cells after this one.
        for i in lo[0]..=hi[0].min(lo[0].saturating_add(1)) {
            for j in lo[1]..=hi[1].min(lo[1].saturating_add(1)) {
                for l in lo[2]..=hi[2].min(lo[2].saturating_add(1)) {
                    let key = [i, j, l];
                    if key <= e.key {
                        continue;
                    }
                    let first = sorted.partition_point(|f| f.key < key);
                    for (t, f) in sorted.iter().enumerate().skip(first) {
                        if f.key != key {
                            break;
                        }
                        if close(&e.x, &f.x) {
                            union(&mut parent, s, t);
                        }
                    }
                }
            }
        }
    }

    // The smallest index of each class, at its root.
    let mut first = mem::filled(count, u32::MAX)?;
    for (s, e) in sorted.iter().enumerate() {
        let r = find(&mut parent, s);
        first[r] = first[r].min(e.index);
    }
    let mut rep = mem::filled(count, 0u32)?;
    for (s, e) in sorted.iter().enumerate() {
        let r = find(&mut parent, s);
        rep[e.index as usize] = first[r];
    }
    Ok(rep)
}

/// Two texture coordinates closer than this (per component, relative to
/// `max(1, |uv|)`) belong to one vertex. The UVs of one point sampled by two
/// patches differ by rounding only (about 1e-16: the bilinear forms of the
/// two patches), a UV seam by the texture layout's own gaps; 1e-9 lies far
/// from both.
pub const UV_TOLERANCE: f64 = 1e-9;

/// Splits the classes of `rep` (as [`representatives`] returns them: each
/// point's class's first point, `rep[k] ≤ k`) by texture coordinate: points
/// of one class whose `uvs` differ by more than `tol` (see
/// [`UV_TOLERANCE`]) from the first point of every sub-class so far start
/// a sub-class of their own. Returns each point's sub-class's first point.
/// Points of different classes are never joined.
pub fn split_by_uv(rep: &[u32], uvs: &[[f64; 2]], tol: f64) -> Result<Vec<u32>, OutOfMemory> {
    const END: u32 = u32::MAX;
    let close = |a: [f64; 2], b: [f64; 2]| {
        (0..2).all(|d| {
            let scale = libm::fmax(1.0, libm::fmax(libm::fabs(a[d]), libm::fabs(b[d])));
            libm::fabs(a[d] - b[d]) <= tol * scale
        })
    };
    // The sub-classes of a class, as a chain of their first points from the
    // class's first point.
    let mut next = mem::filled(rep.len(), END)?;
    let mut out = mem::filled(rep.len(), 0u32)?;
    for k in 0..rep.len() {
        let r = rep[k] as usize;
        if r >= k {
            out[k] = k as u32;
            continue;
        }
        let mut head = r;
        loop {
            if close(uvs[k], uvs[head]) {
                out[k] = head as u32;
                break;
            }
            if next[head] == END {
                next[head] = k as u32;
                out[k] = k as u32;
                break;
            }
            head = next[head] as usize;
        }
    }
    Ok(out)
}

/// Root of `s`, halving the path.
fn find(parent: &mut [u32], mut s: usize) -> usize {
    while parent[s] as usize != s {
        let g = parent[parent[s] as usize];
        parent[s] = g;
        s = g as usize;
    }
    s
}

/// Joins the classes of `a` and `b` (the smaller root becomes the root).
fn union(parent: &mut [u32], a: usize, b: usize) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra < rb {
        parent[rb] = ra as u32;
    } else if rb < ra {
        parent[ra] = rb as u32;
    }
}
