//! The `f64` calls: the `*_f64` calls take the same arguments as the `f32`
//! ones; the unsuffixed calls are the WASM module's original ABI (C²PS with a
//! built-in capacity, [`CAPDIV_CAPACITY`] points per link, whose work buffer
//! of about 209 KiB lives on the stack).

use crate::{c2ps, eg};

/// Points per link the unsuffixed C²PS calls (`capdiv_c2ps_refine`,
/// `capdiv_c2ps_jet`) may reach: `valence·2^steps ≤ 1536`, e.g. valence 6
/// refined 8 times.
pub const CAPDIV_CAPACITY: usize = 1536;

/// Work buffer of the unsuffixed calls, on the stack.
const STACK_WORK: usize = crate::buffers::WORK_PER_CAP * CAPDIV_CAPACITY;

/// `capdiv_c2ps_refine_f32` in `f64`.
///
/// # Safety
/// As `capdiv_c2ps_refine_f32`, with `double` buffers.
#[no_mangle]
pub unsafe extern "C" fn capdiv_c2ps_refine_f64(
    pole: *const f64,
    coords: *const f64,
    coords_len: usize,
    valence: usize,
    steps: u32,
    plain: u32,
    work: *mut f64,
    work_len: usize,
    out: *mut f64,
    out_len: usize,
) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe {
        match c2ps::work(work, work_len) {
            Ok(w) => c2ps::refine(
                pole, coords, coords_len, valence, steps, plain, w, out, out_len,
            ),
            Err(c) => c,
        }
    }
}

/// `capdiv_c2ps_jet_f32` in `f64`.
///
/// # Safety
/// As `capdiv_c2ps_refine_f32`, with `double` buffers.
#[no_mangle]
pub unsafe extern "C" fn capdiv_c2ps_jet_f64(
    pole: *const f64,
    coords: *const f64,
    coords_len: usize,
    valence: usize,
    steps: u32,
    plain: u32,
    work: *mut f64,
    work_len: usize,
    out: *mut f64,
    out_len: usize,
) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe {
        match c2ps::work(work, work_len) {
            Ok(w) => c2ps::jet(
                pole, coords, coords_len, valence, steps, plain, w, out, out_len,
            ),
            Err(c) => c,
        }
    }
}

/// `capdiv_eg_refine_f32` in `f64` (the same call as `capdiv_eg_refine`).
///
/// # Safety
/// As `capdiv_eg_refine_f32`, with `double` buffers.
#[no_mangle]
pub unsafe extern "C" fn capdiv_eg_refine_f64(
    center: *const f64,
    nodes: *const f64,
    nodes_len: usize,
    steps: u32,
    out: *mut f64,
    out_len: usize,
) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { eg::refine(center, nodes, nodes_len, steps, out, out_len) }
}

/// `capdiv_eg_ring_f32` in `f64` (the same call as `capdiv_eg_ring`).
///
/// # Safety
/// As `capdiv_eg_refine_f32`, with `double` buffers.
#[no_mangle]
pub unsafe extern "C" fn capdiv_eg_ring_f64(
    center: *const f64,
    nodes: *const f64,
    nodes_len: usize,
    steps: u32,
    out: *mut f64,
    out_len: usize,
) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { eg::ring(center, nodes, nodes_len, steps, out, out_len) }
}

/// `capdiv_c2ps_refine_f64` with its work buffer on the stack: capacity
/// `CAPDIV_CAPACITY` (`valence·2^steps ≤ 1536`), about 209 KiB of stack. The
/// WASM module's call.
///
/// # Safety
/// As `capdiv_c2ps_refine_f32` without `work`, with `double` buffers.
#[no_mangle]
pub unsafe extern "C" fn capdiv_c2ps_refine(
    pole: *const f64,
    coords: *const f64,
    coords_len: usize,
    valence: usize,
    steps: u32,
    plain: u32,
    out: *mut f64,
    out_len: usize,
) -> i32 {
    let mut work = [0.0f64; STACK_WORK];
    // SAFETY: forwarded caller contract; `work` is this call's own.
    unsafe {
        c2ps::refine(
            pole, coords, coords_len, valence, steps, plain, &mut work, out, out_len,
        )
    }
}

/// `capdiv_c2ps_jet_f64` with its work buffer on the stack (as
/// `capdiv_c2ps_refine`); `out` → 25 writable `double`s.
///
/// # Safety
/// As `capdiv_c2ps_refine`, with `out` → 25 writable `double`s.
#[no_mangle]
pub unsafe extern "C" fn capdiv_c2ps_jet(
    pole: *const f64,
    coords: *const f64,
    coords_len: usize,
    valence: usize,
    steps: u32,
    plain: u32,
    out: *mut f64,
) -> i32 {
    let mut work = [0.0f64; STACK_WORK];
    // SAFETY: forwarded caller contract; `work` is this call's own.
    unsafe {
        c2ps::jet(
            pole,
            coords,
            coords_len,
            valence,
            steps,
            plain,
            &mut work,
            out,
            c2ps::JET_LEN,
        )
    }
}

/// The WASM module's name of `capdiv_eg_refine_f64`.
///
/// # Safety
/// As `capdiv_eg_refine_f64`.
#[no_mangle]
pub unsafe extern "C" fn capdiv_eg_refine(
    center: *const f64,
    nodes: *const f64,
    nodes_len: usize,
    steps: u32,
    out: *mut f64,
    out_len: usize,
) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { eg::refine(center, nodes, nodes_len, steps, out, out_len) }
}

/// The WASM module's name of `capdiv_eg_ring_f64`.
///
/// # Safety
/// As `capdiv_eg_ring_f64`.
#[no_mangle]
pub unsafe extern "C" fn capdiv_eg_ring(
    center: *const f64,
    nodes: *const f64,
    nodes_len: usize,
    steps: u32,
    out: *mut f64,
    out_len: usize,
) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { eg::ring(center, nodes, nodes_len, steps, out, out_len) }
}

/// The capacity per link of the unsuffixed C²PS calls, `CAPDIV_CAPACITY`.
#[no_mangle]
pub extern "C" fn capdiv_capacity() -> usize {
    CAPDIV_CAPACITY
}
