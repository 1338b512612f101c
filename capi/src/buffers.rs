//! The caller's buffers: raw pointers and lengths turned into slices, with
//! null and alignment checks (a bad pointer is [`CAPDIV_BAD_BUFFER`], never
//! undefined behaviour this side can detect), and the work buffer split into
//! the storage of a [`PolarNetBuf`](capdiv::PolarNetBuf).

use crate::codes::CAPDIV_BAD_BUFFER;
use capdiv::Point3;

/// A caller's input slice: `Err` for a null or misaligned pointer with a
/// non-zero length.
///
/// # Safety
/// `ptr` must point to `len` readable `R`, not written during the call (or be
/// null).
pub(crate) unsafe fn input<'a, R>(ptr: *const R, len: usize) -> Result<&'a [R], i32> {
    if len == 0 {
        Ok(&[])
    } else if ptr.is_null() || !ptr.is_aligned() {
        Err(CAPDIV_BAD_BUFFER)
    } else {
        // SAFETY: non-null, aligned; the rest is the caller's contract.
        Ok(unsafe { core::slice::from_raw_parts(ptr, len) })
    }
}

/// A point or centre: 3 readable `R`.
///
/// # Safety
/// As [`input`] with `len = 3`.
pub(crate) unsafe fn point<R: Copy>(ptr: *const R) -> Result<[R; 3], i32> {
    // SAFETY: forwarded caller contract.
    let s = unsafe { input(ptr, 3) }?;
    <[R; 3]>::try_from(s).map_err(|_| CAPDIV_BAD_BUFFER)
}

/// A caller's output slice: `Err` for a null or misaligned pointer (even with
/// length 0: an output is always expected).
///
/// # Safety
/// `ptr` must point to `len` writable `R`, disjoint from every other buffer of
/// the call (or be null).
pub(crate) unsafe fn output<'a, R>(ptr: *mut R, len: usize) -> Result<&'a mut [R], i32> {
    if ptr.is_null() || !ptr.is_aligned() {
        Err(CAPDIV_BAD_BUFFER)
    } else {
        // SAFETY: non-null, aligned; the rest is the caller's contract.
        Ok(unsafe { core::slice::from_raw_parts_mut(ptr, len) })
    }
}

/// Writes the first `count` of `values` to the front of `out`; the count, or
/// [`CAPDIV_BAD_BUFFER`] (nothing written) when `out` is shorter.
pub(crate) fn emit<R>(out: &mut [R], values: impl Iterator<Item = R>, count: usize) -> i32 {
    let (Some(out), Ok(n)) = (out.get_mut(..count), i32::try_from(count)) else {
        return CAPDIV_BAD_BUFFER;
    };
    for (d, s) in out.iter_mut().zip(values) {
        *d = s;
    }
    n
}

/// Scalars of work buffer per unit of C²PS capacity.
pub(crate) const WORK_PER_CAP: usize = crate::CAPDIV_WORK_PER_POINT;

/// Splits a work buffer of `17·cap` scalars (any longer tail unused) into the
/// link storage (`5·cap` points) and root storage (`cap` pairs) of a
/// `PolarNetBuf`.
pub(crate) fn split_work<R>(work: &mut [R]) -> (&mut [Point3<R>], &mut [[R; 2]]) {
    let cap = work.len() / WORK_PER_CAP;
    // Both splits are in range (15·cap + 2·cap ≤ len); the checked forms keep
    // a panic path out of the binary all the same.
    let (links, rest) = work.split_at_mut_checked(15 * cap).unwrap_or_default();
    let roots = rest.get_mut(..2 * cap).unwrap_or_default();
    let (links, _) = links.as_chunks_mut::<3>();
    let (roots, _) = roots.as_chunks_mut::<2>();
    (points_mut(links), roots)
}

/// `[R; 3]` triples as [`Point3`]s.
fn points_mut<R>(xs: &mut [[R; 3]]) -> &mut [Point3<R>] {
    // `Point3<R>` is a one-field struct around `[R; 3]`; checked at compile
    // time: same size and alignment, the field at offset 0, so the layouts
    // agree and every `[R; 3]` is a valid `Point3<R>`.
    const {
        assert!(core::mem::size_of::<Point3<R>>() == core::mem::size_of::<[R; 3]>());
        assert!(core::mem::align_of::<Point3<R>>() == core::mem::align_of::<[R; 3]>());
        assert!(core::mem::offset_of!(Point3<R>, 0) == 0);
    }
    let len = xs.len();
    // SAFETY: same layout (above); the borrow of `xs` moves into the result.
    unsafe { core::slice::from_raw_parts_mut(xs.as_mut_ptr().cast::<Point3<R>>(), len) }
}
