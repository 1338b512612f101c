//! The `f32` calls: for microcontrollers (a Cortex-M4F computes `f32` in
//! hardware, `f64` in software). Same layouts and status codes as the `f64`
//! calls.

use crate::{c2ps, eg};

/// C²PS (docs/math/c2ps.md §2): builds the level-0 configuration `pole`, `coords`
/// in `work`, refines it `steps` times and writes
/// `[N, K, pole x y z, links 1..K]` (`5 + 3·K·N` values, `N` the new valence,
/// `K ≤ 5` the links held, each link `N` points `x, y, z`) to `out`.
///
/// - `coords`: links 1..L (L ≥ 2), each `valence` points of `x, y, z`,
///   counter-clockwise; `coords_len = 3·L·valence`.
/// - `work`: `work_len ≥ capdiv_c2ps_work_len(valence, steps)` floats (17 per
///   point of capacity); the capacity is `work_len / 17`.
/// - `out`: `out_len ≥ capdiv_c2ps_out_len(valence, steps)` floats.
/// - `plain != 0`: rules (1)–(3) in the first step too, else the paper's
///   uniform first step.
///
/// Returns the number of floats written, or a negative `CAPDIV_ERR_*` /
/// `CAPDIV_BAD_BUFFER` code (then `out` is untouched).
///
/// # Safety
/// `pole` → 3 readable floats; `coords` → `coords_len`; `work` → `work_len`
/// and `out` → `out_len` writable floats; the buffers pairwise disjoint.
#[no_mangle]
pub unsafe extern "C" fn capdiv_c2ps_refine_f32(
    pole: *const f32,
    coords: *const f32,
    coords_len: usize,
    valence: usize,
    steps: u32,
    plain: u32,
    work: *mut f32,
    work_len: usize,
    out: *mut f32,
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

/// C²PS: as `capdiv_c2ps_refine_f32`, then writes the pole jet (docs/math/c2ps.md
/// §4): `p0..p5` (18 floats), then the unit normal (3), Gaussian and mean
/// curvature, the two principal curvatures — 25 floats, or only the 18 of the
/// jet when the tangent plane is degenerate. `out_len ≥ 25`.
///
/// # Safety
/// As `capdiv_c2ps_refine_f32`.
#[no_mangle]
pub unsafe extern "C" fn capdiv_c2ps_jet_f32(
    pole: *const f32,
    coords: *const f32,
    coords_len: usize,
    valence: usize,
    steps: u32,
    plain: u32,
    work: *mut f32,
    work_len: usize,
    out: *mut f32,
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

/// EG (docs/math/eg.md): builds the c-net `center`, `nodes` (`6n` points, §1
/// order, as `x, y, z`; `nodes_len = 18n`), refines it `steps` times (§5, §6;
/// built-in rules for n = 3, 4, 5) and writes
/// `[n, c0 x y z, d-net: n sectors × 12 nodes (§2 order)]`, `4 + 36n` floats
/// (`capdiv_eg_refine_len(n)`). Needs no work buffer: the subdivision lives on
/// the stack.
///
/// # Safety
/// `center` → 3 readable floats; `nodes` → `nodes_len`; `out` → `out_len`
/// writable floats, disjoint from the inputs.
#[no_mangle]
pub unsafe extern "C" fn capdiv_eg_refine_f32(
    center: *const f32,
    nodes: *const f32,
    nodes_len: usize,
    steps: u32,
    out: *mut f32,
    out_len: usize,
) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { eg::refine(center, nodes, nodes_len, steps, out, out_len) }
}

/// EG: as `capdiv_eg_refine_f32`, then writes the last step's ring (spec
/// docs/math/eg.md §9): `3n` bi-4 Bézier patches of 5×5 control points (`points[i][j]`,
/// `j` fastest, each `x, y, z`), `225n` floats (`capdiv_eg_ring_len(n)`);
/// 0 before the first step (no ring yet).
///
/// # Safety
/// As `capdiv_eg_refine_f32`.
#[no_mangle]
pub unsafe extern "C" fn capdiv_eg_ring_f32(
    center: *const f32,
    nodes: *const f32,
    nodes_len: usize,
    steps: u32,
    out: *mut f32,
    out_len: usize,
) -> i32 {
    // SAFETY: forwarded caller contract.
    unsafe { eg::ring(center, nodes, nodes_len, steps, out, out_len) }
}
