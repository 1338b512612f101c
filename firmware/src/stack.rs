//! Stack high-water mark. `cortex-m-rt`'s `paint-stack` feature fills the
//! whole stack region `[_stack_end, _stack_start)` with `0xCCCC_CCCC` before
//! `main`; whatever the program ever used is no longer painted. The lowest
//! unpainted word marks the deepest the stack reached.

/// The paint `cortex-m-rt` writes (its `STACK_PAINT_VALUE`).
const PAINT: u32 = 0xcccc_cccc;

use core::sync::atomic::{AtomicUsize, Ordering};

extern "C" {
    static _stack_start: u32;
    static _stack_end: u32;
}

/// Deepest use seen before the last [`repaint`], in bytes.
static EARLIER: AtomicUsize = AtomicUsize::new(0);

/// `(high-water mark since start or the last repaint, stack region size)`
/// in bytes.
///
/// The count may under-report by the few bytes of a frame that happened to
/// store the paint value itself at its deepest word; it cannot over-report.
pub fn high_water_mark() -> (usize, usize) {
    let top = core::ptr::addr_of!(_stack_start) as usize;
    let bottom = core::ptr::addr_of!(_stack_end) as usize;
    let mut p = bottom;
    while p < top {
        // SAFETY: [bottom, top) is the stack region of the linker script: RAM,
        // word-aligned (link.x asserts both ends are), readable.
        let w = unsafe { core::ptr::read_volatile(p as *const u32) };
        if w != PAINT {
            break;
        }
        p += 4;
    }
    (top - p, top.saturating_sub(bottom))
}

/// Margin kept between the caller's stack pointer and the repainted area.
const MARGIN: usize = 256;

/// Paints the unused stack again, from `_stack_end` up to `MARGIN` bytes below
/// the current stack pointer, so that a later [`high_water_mark`] measures the
/// phase that follows. Frames deeper than the caller's are dead here; the
/// margin keeps this function's own frame out of reach (no interrupt is
/// enabled, so nothing else lives below the stack pointer).
#[inline(never)]
pub fn repaint() {
    let (used, _) = high_water_mark();
    // Load and store only (thumbv6m has no atomic read-modify-write); single core.
    if used > EARLIER.load(Ordering::Relaxed) {
        EARLIER.store(used, Ordering::Relaxed);
    }
    let bottom = core::ptr::addr_of!(_stack_end) as usize;
    let sp = cortex_m::register::msp::read() as usize;
    let mut p = bottom;
    while p + MARGIN < sp {
        // SAFETY: [bottom, sp - MARGIN) is unused stack RAM (see above),
        // word-aligned.
        unsafe { core::ptr::write_volatile(p as *mut u32, PAINT) };
        p += 4;
    }
}

/// `(high-water mark of the whole run so far, stack region size)` in bytes.
pub fn peak() -> (usize, usize) {
    let (now, size) = high_water_mark();
    (now.max(EARLIER.load(Ordering::Relaxed)), size)
}
