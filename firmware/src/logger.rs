//! The `defmt` global logger: frames go to the host's stdout through
//! semihosting `SYS_WRITE`, where QEMU (`-semihosting-config target=native`)
//! prints them as raw bytes for `defmt-print` / the decoder to read.
//!
//! Why not the `defmt-semihosting` crate: its `acquire` panics on re-entry, and
//! the release build must link no panic path at all (see `main.rs`). Here
//! re-entry (impossible in this single-threaded firmware, which logs from no
//! interrupt) is tolerated: nested frames are dropped, never a panic.

use core::cell::UnsafeCell;
use cortex_m_semihosting::hio::{self, HostStream};

#[defmt::global_logger]
struct Logger;

/// Logger state, touched only inside the critical section `acquire` enters.
struct State {
    /// 0 outside a frame, 1 in a frame, more when re-entered.
    depth: usize,
    restore: critical_section::RestoreState,
    encoder: defmt::Encoder,
    /// The host's stdout, opened on first use; `None` if the host refused it.
    out: Option<HostStream>,
    opened: bool,
}

struct Shared(UnsafeCell<State>);

// SAFETY: every access happens with interrupts disabled (inside the critical
// section taken in `acquire`) on a single core.
unsafe impl Sync for Shared {}

static STATE: Shared = Shared(UnsafeCell::new(State {
    depth: 0,
    restore: critical_section::RestoreState::invalid(),
    encoder: defmt::Encoder::new(),
    out: None,
    opened: false,
}));

fn emit(out: &mut Option<HostStream>, bytes: &[u8]) {
    if let Some(stream) = out {
        // A failed host write loses log bytes; the host test then fails to
        // decode or misses lines, which is the right outcome.
        let _ = stream.write_all(bytes);
    }
}

unsafe impl defmt::Logger for Logger {
    fn acquire() {
        // SAFETY: paired with the `release` in `Logger::release` (defmt's contract).
        let restore = unsafe { critical_section::acquire() };
        // SAFETY: interrupts are now off; no other reference to STATE is live.
        let s = unsafe { &mut *STATE.0.get() };
        if s.depth == 0 {
            s.restore = restore;
            if !s.opened {
                s.opened = true;
                s.out = hio::hstdout().ok();
            }
            let State { encoder, out, .. } = s;
            encoder.start_frame(|b| emit(out, b));
        }
        // A nested acquire's restore state says "interrupts were off": dropping
        // it and releasing only the outermost one is what the single-core
        // implementation would do anyway.
        s.depth += 1;
    }

    unsafe fn flush() {}

    unsafe fn release() {
        // SAFETY: called after `acquire`, inside its critical section.
        let s = unsafe { &mut *STATE.0.get() };
        match s.depth {
            0 => {}
            1 => {
                s.depth = 0;
                let State { encoder, out, .. } = s;
                encoder.end_frame(|b| emit(out, b));
                // SAFETY: the state saved by the outermost `acquire`.
                unsafe { critical_section::release(s.restore) };
            }
            _ => s.depth -= 1,
        }
    }

    unsafe fn write(bytes: &[u8]) {
        // SAFETY: called between `acquire` and `release`.
        let s = unsafe { &mut *STATE.0.get() };
        if s.depth == 1 {
            let State { encoder, out, .. } = s;
            encoder.write(bytes, |b| emit(out, b));
        }
    }
}
