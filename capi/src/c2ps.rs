//! The C²PS calls (docs/math/c2ps.md), once for both scalar types: build a
//! [`PolarNetBuf`] in the caller's work buffer from a flat level-0
//! configuration (§1), refine it (§2), write the net or its pole jet (§4).

use crate::buffers::{input, output, point, split_work, WORK_PER_CAP};
use crate::codes::{code, CAPDIV_BAD_BUFFER};
use capdiv::{Error, FirstStep, PolarNetBuf, PoleJet, Real, SliceStorage};

/// Values the jet call writes.
pub(crate) const JET_LEN: usize = crate::CAPDIV_JET_LEN;

/// Values of the jet alone, written when the geometry is degenerate.
pub(crate) const JET_COEFFS_LEN: usize = crate::CAPDIV_JET_COEFFS_LEN;

/// Values written before the links by the refine call: `N, K, pole`.
pub(crate) const REFINE_HEAD_LEN: usize = 5;

fn first_step(plain: u32) -> FirstStep {
    if plain != 0 {
        FirstStep::Plain
    } else {
        FirstStep::Uniform
    }
}

/// `valence·2^steps`, `None` on overflow.
pub fn capacity_for(valence: usize, steps: u32) -> Option<usize> {
    capdiv::polar::capacity_for(valence, steps)
}

/// Scalars of work buffer for `steps` steps from `valence`: `17·valence·2^steps`.
pub fn work_len(valence: usize, steps: u32) -> Option<usize> {
    capacity_for(valence, steps)?.checked_mul(WORK_PER_CAP)
}

/// Largest output of the refine call: `5 + 15·valence·2^steps` (5 links).
pub fn out_len(valence: usize, steps: u32) -> Option<usize> {
    capacity_for(valence, steps)?
        .checked_mul(15)?
        .checked_add(REFINE_HEAD_LEN)
}

/// The polar configuration `pole`, `coords` (links 1..L, `valence` points
/// each, as `x, y, z`) built in `work` and refined `steps` times.
///
/// # Safety
/// `pole` → 3 readable `R`, `coords` → `coords_len`, neither inside `work`.
pub(crate) unsafe fn refined<R: Real>(
    pole: *const R,
    coords: *const R,
    coords_len: usize,
    valence: usize,
    steps: u32,
    plain: u32,
    work: &mut [R],
) -> Result<PolarNetBuf<'_, R>, i32> {
    // SAFETY: forwarded caller contract.
    let (pole, coords) = unsafe { (point(pole), input(coords, coords_len)) };
    let (pole, coords) = (pole?, coords?);
    let (links, roots) = split_work(work);
    let mut net = PolarNetBuf::from_flat_in(pole, valence, coords, SliceStorage::new(links, roots))
        .map_err(|e| code(&e))?;
    for _ in 0..steps {
        net.step(first_step(plain)).map_err(|e| code(&e))?;
    }
    Ok(net)
}

/// Writes `[N, K, pole x y z, links 1..K]` (`5 + 3·K·N` values) to `out`.
pub(crate) fn write_refined<R: Real>(net: &PolarNetBuf<'_, R>, out: &mut [R]) -> i32 {
    let n = net.valence();
    let held = net.link_count();
    let Some(needed) = held
        .checked_mul(n)
        .and_then(|k| k.checked_mul(3))
        .and_then(|k| k.checked_add(REFINE_HEAD_LEN))
    else {
        return CAPDIV_BAD_BUFFER;
    };
    let [p0, p1, p2] = net.pole().0;
    let head = [R::from_f64(n as f64), R::from_f64(held as f64), p0, p1, p2];
    let points = (1..=held).flat_map(|i| net.link(i).unwrap_or(&[]).iter());
    let values = head.into_iter().chain(points.flat_map(|p| p.0));
    crate::buffers::emit(out, values, needed)
}

/// Writes the pole jet `p0..p5` and, unless degenerate, the unit normal,
/// Gaussian and mean curvature and the principal curvatures: 25 values, or
/// 18 when the tangent plane is degenerate. `out` must hold 25.
pub(crate) fn write_jet<R: Real>(net: &PolarNetBuf<'_, R>, out: &mut [R]) -> i32 {
    let Some(out) = out.get_mut(..JET_LEN) else {
        return CAPDIV_BAD_BUFFER;
    };
    let jet = PoleJet::of(net);
    for (d, s) in out.iter_mut().zip(jet.p.iter().flat_map(|p| p.0)) {
        *d = s;
    }
    match jet.geometry() {
        Ok(g) => {
            let [n0, n1, n2] = g.normal.0;
            let [k1, k2] = g.principal;
            let tail = [n0, n1, n2, g.gaussian, g.mean, k1, k2];
            for (d, s) in out.iter_mut().skip(JET_COEFFS_LEN).zip(tail) {
                *d = s;
            }
            JET_LEN as i32
        }
        Err(Error::Degenerate) => JET_COEFFS_LEN as i32,
        Err(e) => code(&e),
    }
}

/// The refine call over a work buffer.
///
/// # Safety
/// As the exported `capdiv_c2ps_refine_f32`.
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn refine<R: Real>(
    pole: *const R,
    coords: *const R,
    coords_len: usize,
    valence: usize,
    steps: u32,
    plain: u32,
    work: &mut [R],
    out: *mut R,
    out_len: usize,
) -> i32 {
    let input = (pole, coords, coords_len, valence, steps, plain);
    // SAFETY: forwarded caller contract.
    unsafe { refined_into(input, work, out, out_len, write_refined) }
}

/// The jet call over a work buffer.
///
/// # Safety
/// As the exported `capdiv_c2ps_jet_f32`.
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn jet<R: Real>(
    pole: *const R,
    coords: *const R,
    coords_len: usize,
    valence: usize,
    steps: u32,
    plain: u32,
    work: &mut [R],
    out: *mut R,
    out_len: usize,
) -> i32 {
    let input = (pole, coords, coords_len, valence, steps, plain);
    // SAFETY: forwarded caller contract.
    unsafe { refined_into(input, work, out, out_len, write_jet) }
}

/// `(pole, coords, coords_len, valence, steps, plain)` of a call.
type Input<R> = (*const R, *const R, usize, usize, u32, u32);

/// The refine and jet calls' common part: the net refined in `work`
/// ([`refined`]), then `write` into the caller's `out` (its code returned).
///
/// # Safety
/// As the exported `capdiv_c2ps_refine_f32`.
unsafe fn refined_into<R: Real>(
    (pole, coords, coords_len, valence, steps, plain): Input<R>,
    work: &mut [R],
    out: *mut R,
    out_len: usize,
    write: impl FnOnce(&PolarNetBuf<'_, R>, &mut [R]) -> i32,
) -> i32 {
    // SAFETY: forwarded caller contract.
    let net = match unsafe { refined(pole, coords, coords_len, valence, steps, plain, work) } {
        Ok(net) => net,
        Err(c) => return c,
    };
    // SAFETY: forwarded caller contract.
    match unsafe { output(out, out_len) } {
        Ok(out) => write(&net, out),
        Err(c) => c,
    }
}

/// The caller's work buffer.
///
/// # Safety
/// `work` → `work_len` writable `R`, disjoint from every other buffer.
pub(crate) unsafe fn work<'a, R>(work: *mut R, work_len: usize) -> Result<&'a mut [R], i32> {
    // SAFETY: forwarded caller contract.
    unsafe { output(work, work_len) }
}
