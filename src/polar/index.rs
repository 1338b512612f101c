//! Checked element access for the refinement sweeps.
//!
//! The sweeps index links and root rings at positions that are in range by
//! construction (`j < n`, `2j + 1 < 2n`, lengths checked before the sweep), but
//! the optimiser cannot always prove it (`2n` may wrap for all it knows), and
//! every unproven `s[i]` leaves a panic path in the binary. These helpers turn
//! that path into a plain branch: same results for every in-range index, and
//! an out-of-range one — unreachable — reads `fallback` / writes nothing
//! instead of panicking. The firmware's link-time panic check relies
//! on them.

/// `s[i]`, or `fallback` when `i` is out of range.
#[inline(always)]
pub(crate) fn at<T: Copy>(s: &[T], i: usize, fallback: T) -> T {
    match s.get(i) {
        Some(v) => *v,
        None => fallback,
    }
}

/// `s[i] = v`, or nothing when `i` is out of range.
#[inline(always)]
pub(crate) fn put<T>(s: &mut [T], i: usize, v: T) {
    if let Some(x) = s.get_mut(i) {
        *x = v;
    }
}

/// `(i + 1) mod n` for `i < n`, without a division (so no divide-by-zero path).
#[inline(always)]
pub(crate) fn next_mod(i: usize, n: usize) -> usize {
    if i + 1 >= n {
        0
    } else {
        i + 1
    }
}

/// `(i + k) mod n` for `i, k < n` (one subtraction instead of `%`).
#[inline(always)]
pub(crate) fn add_mod(i: usize, k: usize, n: usize) -> usize {
    let s = i.wrapping_add(k);
    if s >= n {
        s.wrapping_sub(n)
    } else {
        s
    }
}
