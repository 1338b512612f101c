//! capdiv for WebAssembly (`wasm32-unknown-unknown`, `no_std`, no allocator,
//! no wasm-bindgen): a C ABI over buffers the caller owns.
//!
//! The caller places its `f64` inputs and output buffers in the module's
//! linear memory (for instance from the exported `__heap_base` upwards, after
//! `memory.grow` if needed: nothing in the module allocates there) and passes
//! pointers and lengths. Every call is stateless: it builds the net from the
//! inputs on its own stack, works, writes the outputs, returns a status.
//!
//! Layout of a polar configuration (spec C2PS.md §1; the same as
//! [`capdiv::PolarNet::from_flat`]): `pole` = 3 `f64`; `coords` = links 1..L,
//! each `valence` points of `x, y, z`.
//!
//! An EG c-net (spec EG.md §1): `center` = 3 `f64`; `nodes` = `6n` points of
//! `x, y, z`, sector by sector in the §1 order.
//!
//! Status: `≥ 0` success (the number of `f64` written), `< 0` an error
//! ([`codes`]); on error nothing is written.
//!
//! Panic-free: the panic handler calls an import that no caller provides, so a
//! panic path left in the module shows as an import `env.capdiv_panic_path_linked`
//! and instantiation without imports fails (the node demo instantiates with none).
#![no_std]

pub mod codes;

use capdiv::eg::{CNet, EgSubdivision};
use capdiv::{Error, FirstStep, PolarNet, PoleJet};
use codes::{code, BAD_BUFFER};

/// Capacity per link: the deepest valence reachable, e.g. valence 6 refined
/// 8 times or valence 3 refined 9 times.
pub const CAP: usize = 1536;

type Net = PolarNet<f64, CAP>;

/// Jet output: `p0..p5` (18) then normal (3), Gaussian, mean, principal (2).
const JET_LEN: usize = 25;

/// A caller's input slice; `None` for a null pointer with a non-zero length.
///
/// # Safety
/// `ptr` must point to `len` readable `f64` (or be null).
unsafe fn input<'a>(ptr: *const f64, len: usize) -> Option<&'a [f64]> {
    if len == 0 {
        Some(&[])
    } else if ptr.is_null() {
        None
    } else {
        // SAFETY: the caller's contract.
        Some(unsafe { core::slice::from_raw_parts(ptr, len) })
    }
}

/// A caller's output slice.
///
/// # Safety
/// `ptr` must point to `len` writable `f64` not aliasing the inputs (or be null).
unsafe fn output<'a>(ptr: *mut f64, len: usize) -> Option<&'a mut [f64]> {
    if ptr.is_null() {
        None
    } else {
        // SAFETY: the caller's contract.
        Some(unsafe { core::slice::from_raw_parts_mut(ptr, len) })
    }
}

fn first_step(plain: u32) -> FirstStep {
    if plain != 0 {
        FirstStep::Plain
    } else {
        FirstStep::Uniform
    }
}

/// Builds and refines a net; `Err(code)` on failure.
fn refined(
    pole: Option<&[f64]>,
    coords: Option<&[f64]>,
    valence: usize,
    steps: u32,
    plain: u32,
) -> Result<Net, i32> {
    let (Some(pole), Some(coords)) = (pole, coords) else {
        return Err(BAD_BUFFER);
    };
    let Ok(pole) = <[f64; 3]>::try_from(pole) else {
        return Err(BAD_BUFFER);
    };
    let mut net = Net::from_flat(pole, valence, coords).map_err(|e| code(&e))?;
    for _ in 0..steps {
        net.step(first_step(plain)).map_err(|e| code(&e))?;
    }
    Ok(net)
}

/// Refines the configuration `steps` times (C²PS, §2) and writes
/// `[N, K, pole x y z, links 1..K (K·N points)]`, `N` the new valence and `K`
/// the links held, as `3 + 2 + 3·K·N` `f64` to `out` (`out_len` available).
/// `plain != 0` selects [`FirstStep::Plain`], else the paper's uniform first step.
///
/// # Safety
/// `pole` → 3 readable `f64`; `coords` → `coords_len`; `out` → `out_len`
/// writable `f64`, disjoint from the inputs.
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
    // SAFETY: forwarded caller contract.
    let (pole, coords) = unsafe { (input(pole, 3), input(coords, coords_len)) };
    let net = match refined(pole, coords, valence, steps, plain) {
        Ok(net) => net,
        Err(c) => return c,
    };
    let n = net.valence();
    let held = net.links_held();
    let needed = 5 + 3 * held * n;
    // SAFETY: forwarded caller contract.
    let Some(out) = (unsafe { output(out, out_len) }) else {
        return BAD_BUFFER;
    };
    let Some(out) = out.get_mut(..needed) else {
        return BAD_BUFFER;
    };
    let Some((head, rest)) = out.split_at_mut_checked(5) else {
        return BAD_BUFFER;
    };
    let [p0, p1, p2] = net.pole().0;
    for (d, s) in head.iter_mut().zip([n as f64, held as f64, p0, p1, p2]) {
        *d = s;
    }
    let points = (1..=held).flat_map(|i| net.link(i).unwrap_or(&[]).iter());
    for (d, s) in rest.iter_mut().zip(points.flat_map(|p| p.0)) {
        *d = s;
    }
    needed as i32
}

/// Refines `steps` times and writes the pole jet (spec C2PS.md §4):
/// `p0..p5` (18 `f64`), then — unless the tangent plane is degenerate — the
/// unit normal, Gaussian and mean curvature and the two principal curvatures
/// (7 more). Returns 25, or 18 when the geometry is degenerate.
///
/// # Safety
/// As [`capdiv_c2ps_refine`], with `out` → 25 writable `f64`.
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
    // SAFETY: forwarded caller contract.
    let (pole, coords) = unsafe { (input(pole, 3), input(coords, coords_len)) };
    let net = match refined(pole, coords, valence, steps, plain) {
        Ok(net) => net,
        Err(c) => return c,
    };
    // SAFETY: forwarded caller contract.
    let Some(out) = (unsafe { output(out, JET_LEN) }) else {
        return BAD_BUFFER;
    };
    let jet = PoleJet::of(&net);
    for (d, s) in out.iter_mut().zip(jet.p.iter().flat_map(|p| p.0)) {
        *d = s;
    }
    match jet.geometry() {
        Ok(g) => {
            let [n0, n1, n2] = g.normal.0;
            let [k1, k2] = g.principal;
            let tail = [n0, n1, n2, g.gaussian, g.mean, k1, k2];
            for (d, s) in out.iter_mut().skip(18).zip(tail) {
                *d = s;
            }
            JET_LEN as i32
        }
        Err(Error::Degenerate) => 18,
        Err(e) => code(&e),
    }
}

/// Builds the c-net (§1) from `center` and `nodes` (`6n` points, §1 order, as
/// `x, y, z`) and refines it `steps` times with EG (its built-in rule: n = 3,
/// 5, or the regular rules for n = 4).
fn eg_refined(
    center: Option<&[f64]>,
    nodes: Option<&[f64]>,
    steps: u32,
) -> Result<EgSubdivision<'static, f64>, i32> {
    let (Some(center), Some(nodes)) = (center, nodes) else {
        return Err(BAD_BUFFER);
    };
    let Ok(center) = <[f64; 3]>::try_from(center) else {
        return Err(BAD_BUFFER);
    };
    let (points, rest) = nodes.as_chunks::<3>();
    if !rest.is_empty() {
        return Err(code(&Error::WrongLength {
            expected: nodes.len() - rest.len() + 3,
            found: nodes.len(),
        }));
    }
    let net = CNet::new(center, points).map_err(|e| code(&e))?;
    let mut sub = EgSubdivision::from_cnet(&net).map_err(|e| code(&e))?;
    for _ in 0..steps {
        sub.step().map_err(|e| code(&e))?;
    }
    Ok(sub)
}

/// Writes `values` to the caller's `out` (`out_len` available); the count, or
/// [`BAD_BUFFER`].
///
/// # Safety
/// `out` → `out_len` writable `f64`, disjoint from any input.
unsafe fn emit(
    out: *mut f64,
    out_len: usize,
    values: impl Iterator<Item = f64>,
    count: usize,
) -> i32 {
    // SAFETY: forwarded caller contract.
    let Some(out) = (unsafe { output(out, out_len) }) else {
        return BAD_BUFFER;
    };
    let Some(out) = out.get_mut(..count) else {
        return BAD_BUFFER;
    };
    for (d, s) in out.iter_mut().zip(values) {
        *d = s;
    }
    count as i32
}

/// EG (spec EG.md): builds the c-net `center`, `nodes` (`6n` points, §1
/// order), refines it `steps` times (§5, §6) and writes
/// `[n, c0 x y z, d-net: n sectors × 12 nodes (§2 order)]`, `4 + 36n` `f64`.
///
/// # Safety
/// `center` → 3 readable `f64`; `nodes` → `nodes_len`; `out` → `out_len`
/// writable `f64`, disjoint from the inputs.
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
    let (center, nodes) = unsafe { (input(center, 3), input(nodes, nodes_len)) };
    let sub = match eg_refined(center, nodes, steps) {
        Ok(sub) => sub,
        Err(c) => return c,
    };
    let d = sub.net();
    let n = d.valence();
    let head = [n as f64].into_iter().chain(d.c0().0);
    let body = d.sectors().iter().flatten().flat_map(|p| p.0);
    // SAFETY: forwarded caller contract.
    unsafe { emit(out, out_len, head.chain(body), 4 + 36 * n) }
}

/// EG: as [`capdiv_eg_refine`], then writes the last step's ring (§9): `3n`
/// bi-4 Bézier patches of 5×5 control points (`points[i][j]`, `j` fastest),
/// `225n` `f64`; 0 before the first step (no ring yet).
///
/// # Safety
/// As [`capdiv_eg_refine`].
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
    let (center, nodes) = unsafe { (input(center, 3), input(nodes, nodes_len)) };
    let sub = match eg_refined(center, nodes, steps) {
        Ok(sub) => sub,
        Err(c) => return c,
    };
    let count = 75 * sub.ring_len();
    let values = sub
        .ring_patches()
        .flat_map(|patch| patch.points.into_iter().flatten().flat_map(|p| p.0));
    // SAFETY: forwarded caller contract.
    unsafe { emit(out, out_len, values, count) }
}

/// The capacity per link, [`CAP`]: `valence·2^steps` may not exceed it.
#[no_mangle]
pub extern "C" fn capdiv_capacity() -> usize {
    CAP
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    extern "C" {
        fn capdiv_panic_path_linked() -> !;
    }
    // SAFETY: never provided; see the crate docs.
    unsafe { capdiv_panic_path_linked() }
}
