//! `StencilTable`: points as fixed linear combinations of other points (the
//! "stencil table" of OpenSubdiv's Far). Built once by the analysis (a
//! refinement step, phantom points at boundaries), applied to new positions on
//! every evaluation without allocating.
//!
//! The rows apply to any per-vertex data, not only positions: colours,
//! weights, any vector type implementing [`Primvar`] (OpenSubdiv's
//! `Far::PrimvarRefiner` takes any class with `Clear` and `AddWithWeight`
//! the same way). Each row's weights sum to 1 (refinement and phantom rules
//! are affine combinations), so constant data stay constant.

use alloc::vec::Vec;
use capdiv::{Point3, Real};

/// Per-vertex data the stencils can combine: a zero and a weighted sum.
pub trait Primvar: Clone {
    /// The zero value (the start of every row's sum).
    fn zero() -> Self;
    /// `self += w · src`.
    fn add_scaled(&mut self, src: &Self, w: f64);
}

impl<R: Real> Primvar for Point3<R> {
    fn zero() -> Self {
        Point3::ZERO
    }
    fn add_scaled(&mut self, src: &Self, w: f64) {
        *self += *src * R::from_f64(w);
    }
}

impl Primvar for f64 {
    fn zero() -> Self {
        0.0
    }
    fn add_scaled(&mut self, src: &Self, w: f64) {
        *self += *src * w;
    }
}

impl Primvar for f32 {
    fn zero() -> Self {
        0.0
    }
    fn add_scaled(&mut self, src: &Self, w: f64) {
        *self += *src * w as f32;
    }
}

impl<P: Primvar + Copy, const N: usize> Primvar for [P; N] {
    fn zero() -> Self {
        [P::zero(); N]
    }
    fn add_scaled(&mut self, src: &Self, w: f64) {
        for (a, b) in self.iter_mut().zip(src) {
            a.add_scaled(b, w);
        }
    }
}

/// Sparse rows `out[i] = Σ_k weights[k] · src[indices[k]]`, `k` over row `i`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StencilTable {
    /// `offsets[i]..offsets[i+1]` index row `i`'s entries.
    offsets: Vec<u32>,
    indices: Vec<u32>,
    weights: Vec<f64>,
}

impl StencilTable {
    /// An empty table (no rows).
    pub fn new() -> Self {
        StencilTable {
            offsets: alloc::vec![0],
            indices: Vec::new(),
            weights: Vec::new(),
        }
    }

    /// The leading offset 0 a table made by `Default` lacks until its first
    /// row.
    #[inline]
    fn open(&mut self) {
        if self.offsets.is_empty() {
            self.offsets.push(0);
        }
    }

    /// Ends the row whose entries were just pushed; returns its index.
    #[inline]
    fn close_row(&mut self) -> u32 {
        self.offsets.push(self.indices.len() as u32);
        (self.offsets.len() - 2) as u32
    }

    /// Appends a row; entries with the same index are kept separately (their
    /// weights add up when applied). Returns the row's index.
    pub fn push_row(&mut self, entries: impl IntoIterator<Item = (u32, f64)>) -> u32 {
        self.open();
        for (i, w) in entries {
            self.indices.push(i);
            self.weights.push(w);
        }
        self.close_row()
    }

    /// [`StencilTable::push_row`] of a row given as a slice (one copy per
    /// array, no per-entry growth check).
    pub fn push_slice(&mut self, entries: &[(u32, f64)]) -> u32 {
        self.open();
        self.indices.extend(entries.iter().map(|e| e.0));
        self.weights.extend(entries.iter().map(|e| e.1));
        self.close_row()
    }

    /// Appends every row of `other` (indices as they are).
    pub fn append(&mut self, other: &StencilTable) {
        self.open();
        let shift = self.indices.len() as u32;
        self.offsets
            .extend(other.offsets.iter().skip(1).map(|&o| o + shift));
        self.indices.extend_from_slice(&other.indices);
        self.weights.extend_from_slice(&other.weights);
    }

    /// Room for `rows` more rows of `entries` entries in all (amortised
    /// growth, as [`Vec::reserve`]).
    pub fn reserve(&mut self, rows: usize, entries: usize) {
        let first = usize::from(self.offsets.is_empty());
        self.offsets.reserve(rows + first);
        self.indices.reserve(entries);
        self.weights.reserve(entries);
    }

    /// Whether `rows` more rows of `entries` entries in all fit without
    /// growing the table.
    #[inline]
    pub fn has_room(&self, rows: usize, entries: usize) -> bool {
        let first = usize::from(self.offsets.is_empty());
        self.offsets.capacity() - self.offsets.len() >= rows + first
            && self.indices.capacity() - self.indices.len() >= entries
            && self.weights.capacity() - self.weights.len() >= entries
    }

    /// Room for `rows` more rows of `entries` entries in all, reserved
    /// fallibly so that the pushes that follow do not allocate.
    pub fn try_reserve(
        &mut self,
        rows: usize,
        entries: usize,
    ) -> Result<(), crate::mem::OutOfMemory> {
        let first = usize::from(self.offsets.is_empty());
        crate::mem::reserve(&mut self.offsets, rows + first)?;
        crate::mem::reserve(&mut self.indices, entries)?;
        crate::mem::reserve(&mut self.weights, entries)
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// `true` without rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Row `i` as `(index, weight)` pairs.
    pub fn row(&self, i: usize) -> impl Iterator<Item = (u32, f64)> + '_ {
        let (a, b) = (self.offsets[i] as usize, self.offsets[i + 1] as usize);
        self.indices[a..b]
            .iter()
            .copied()
            .zip(self.weights[a..b].iter().copied())
    }

    /// Total number of entries (the cost of one application).
    pub fn entries(&self) -> usize {
        self.indices.len()
    }

    /// Largest source index used plus one (0 for an empty table).
    pub fn source_len(&self) -> usize {
        self.indices
            .iter()
            .map(|&i| i as usize + 1)
            .max()
            .unwrap_or(0)
    }

    /// Applies every row to `src`, writing `out[i]`. `out` must have
    /// [`Self::len`] entries and `src` at least [`Self::source_len`]; the
    /// analysis guarantees both (rows past `out`'s end are skipped, indices
    /// past `src`'s end add nothing).
    pub fn apply<P: Primvar>(&self, src: &[P], out: &mut [P]) {
        self.apply_from(src, out, 0);
    }

    /// [`Self::apply`] for rows `first..first + out.len()`, writing row
    /// `first + k` to `out[k]`: a part of the output, for one thread.
    pub fn apply_from<P: Primvar>(&self, src: &[P], out: &mut [P], first: usize) {
        let rows = self.len().saturating_sub(first);
        for (k, o) in out.iter_mut().enumerate().take(rows) {
            let i = first + k;
            let mut acc = P::zero();
            for (idx, w) in self.row(i) {
                if let Some(p) = src.get(idx as usize) {
                    acc.add_scaled(p, w);
                }
            }
            *o = acc;
        }
    }

    /// Applies every row in order, row `i` writing `out[i]` from `src` and
    /// the rows before it: index `j < src.len()` is `src[j]`, index
    /// `src.len() + k` is `out[k]` (`k < i`). Rows of later points (the
    /// adaptive refinement's, [`crate::adaptive`]) are built over earlier
    /// ones; indices not yet written read as zero.
    pub fn apply_chained<P: Primvar>(&self, src: &[P], out: &mut [P]) {
        let base = src.len();
        for i in 0..out.len().min(self.len()) {
            let mut acc = P::zero();
            for (idx, w) in self.row(i) {
                let idx = idx as usize;
                let p = if idx < base {
                    &src[idx]
                } else if idx - base < i {
                    &out[idx - base]
                } else {
                    continue;
                };
                acc.add_scaled(p, w);
            }
            out[i] = acc;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::StencilTable;
    use alloc::vec::Vec;

    fn rows(t: &StencilTable) -> Vec<Vec<(u32, f64)>> {
        (0..t.len()).map(|i| t.row(i).collect()).collect()
    }

    /// Appending a table gives the rows that pushing them one by one gives
    /// (from iterators and from slices),
    /// behind the rows already there, including an empty row and a table
    /// made by `Default` (no offsets yet) on either side.
    #[test]
    fn append_equals_pushing_the_rows_one_by_one() {
        let mut other = StencilTable::new();
        other.push_row([(4, 0.25), (5, 0.75)]);
        other.push_row([]);
        other.push_slice(&[(1, 1.0), (1, -0.5), (9, 0.5)]);
        for first in [StencilTable::default(), StencilTable::new(), {
            let mut t = StencilTable::new();
            t.push_row([(0, 1.0)]);
            t
        }] {
            let mut appended = first.clone();
            appended.append(&other);
            appended.append(&StencilTable::default());
            let mut pushed = first.clone();
            for i in 0..other.len() {
                pushed.push_row(other.row(i));
            }
            assert_eq!(rows(&appended), rows(&pushed));
            assert_eq!(appended.len(), first.len() + 3);
            assert_eq!(appended.entries(), first.entries() + 5);
        }
    }
}
