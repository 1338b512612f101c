//! The EG calls (docs/math/eg.md), once for both scalar types: a c-net (§1) from
//! flat coordinates, refined on the stack (§5, §6), written as its d-net (§2)
//! or its last ring of bi-4 patches (§9).

use crate::buffers::{emit, input, output, point};
use crate::codes::code;
use capdiv::eg::{CNet, EgSubdivision};
use capdiv::{Error, Real};

/// Values of the refine call for valence `n`: `n, c0, 12n nodes`.
pub fn refine_len(n: usize) -> Option<usize> {
    n.checked_mul(36)?.checked_add(4)
}

/// Values of the ring call for valence `n`: `3n` patches of 5×5 points.
pub fn ring_len(n: usize) -> Option<usize> {
    n.checked_mul(225)
}

/// Builds the c-net from `center` and `nodes` (`6n` points, §1 order, as
/// `x, y, z`) into `sub` and refines it `steps` times with EG's built-in rule
/// (n = 3, 5; the regular rules for n = 4).
///
/// # Safety
/// `center` → 3 readable `R`, `nodes` → `nodes_len`.
unsafe fn eg_refined<R: Real>(
    center: *const R,
    nodes: *const R,
    nodes_len: usize,
    steps: u32,
    sub: &mut EgSubdivision<'static, R>,
) -> Result<(), i32> {
    // SAFETY: forwarded caller contract.
    let (center, nodes) = unsafe { (point(center), input(nodes, nodes_len)) };
    let (center, nodes) = (center?, nodes?);
    let (points, rest) = nodes.as_chunks::<3>();
    if !rest.is_empty() {
        return Err(code(&Error::WrongLength {
            expected: nodes.len() - rest.len() + 3,
            found: nodes.len(),
        }));
    }
    let net = CNet::new(center, points).map_err(|e| code(&e))?;
    sub.reset(&net, None).map_err(|e| code(&e))?;
    for _ in 0..steps {
        sub.step().map_err(|e| code(&e))?;
    }
    Ok(())
}

/// `[n, c0 x y z, d-net: n sectors × 12 nodes (§2 order)]`, `4 + 36n` values.
///
/// # Safety
/// As the exported `capdiv_eg_refine_f32`.
pub(crate) unsafe fn refine<R: Real>(
    center: *const R,
    nodes: *const R,
    nodes_len: usize,
    steps: u32,
    out: *mut R,
    out_len: usize,
) -> i32 {
    let input = (center, nodes, nodes_len, steps);
    // SAFETY: forwarded caller contract.
    unsafe {
        refined_into(input, out, out_len, |sub, out| {
            let d = sub.net();
            let n = d.valence();
            let head = [R::from_f64(n as f64)].into_iter().chain(d.c0().0);
            let body = d.sectors().iter().flatten().flat_map(|p| p.0);
            emit(out, head.chain(body), refine_len(n).unwrap_or(usize::MAX))
        })
    }
}

/// The last step's ring: `3n` bi-4 patches of 5×5 control points
/// (`points[i][j]`, `j` fastest), `225n` values; 0 before the first step.
///
/// # Safety
/// As the exported `capdiv_eg_ring_f32`.
pub(crate) unsafe fn ring<R: Real>(
    center: *const R,
    nodes: *const R,
    nodes_len: usize,
    steps: u32,
    out: *mut R,
    out_len: usize,
) -> i32 {
    let input = (center, nodes, nodes_len, steps);
    // SAFETY: forwarded caller contract.
    unsafe {
        refined_into(input, out, out_len, |sub, out| {
            let count = sub.ring_len().saturating_mul(75);
            let values = sub
                .ring_patches()
                .flat_map(|patch| patch.points.into_iter().flatten().flat_map(|p| p.0));
            emit(out, values, count)
        })
    }
}

/// The refine and ring calls' common part: the c-net refined on the stack
/// ([`eg_refined`]), then `write` into the caller's `out` (its code returned).
///
/// # Safety
/// As the exported `capdiv_eg_refine_f32`.
unsafe fn refined_into<R: Real>(
    (center, nodes, nodes_len, steps): (*const R, *const R, usize, u32),
    out: *mut R,
    out_len: usize,
    write: impl FnOnce(&EgSubdivision<'static, R>, &mut [R]) -> i32,
) -> i32 {
    let mut sub = EgSubdivision::empty();
    // SAFETY: forwarded caller contract.
    if let Err(c) = unsafe { eg_refined(center, nodes, nodes_len, steps, &mut sub) } {
        return c;
    }
    // SAFETY: forwarded caller contract.
    match unsafe { output(out, out_len) } {
        Ok(out) => write(&sub, out),
        Err(c) => c,
    }
}
