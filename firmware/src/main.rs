//! capdiv on a Cortex-M: refines the fixed sample nets of [`sample`] in `f32`
//! with the kernel, logs every result with `defmt` over semihosting, reports
//! the stack high-water mark and exits with a semihosting status (0 on
//! success, 1 on a kernel error, a fault or — debug builds only — a panic).
//!
//! Runs on QEMU's `mps2-an386` (Cortex-M4F, `thumbv7em-none-eabihf`) and
//! `microbit` (Cortex-M0, `thumbv6m-none-eabi`); `host-tests`-independent
//! checks live in `embedded-tests/`.
//!
//! Panic-free: in release builds the panic handler calls a symbol that exists
//! nowhere, so the image links only if the optimiser removed every panic path
//! from the kernel calls made here and from this firmware.
#![no_std]
#![no_main]

mod logger;
mod report;
#[allow(dead_code)] // each workload uses its own part
mod sample;
mod stack;
#[cfg(feature = "api-check")]
mod surface;

#[cfg(feature = "c2ps")]
mod c2ps;
#[cfg(feature = "eg")]
mod eg;
#[cfg(feature = "c2ps-stream")]
mod stream;

use cortex_m_rt::{entry, exception, ExceptionFrame};
use cortex_m_semihosting::debug::{self, EXIT_FAILURE, EXIT_SUCCESS};

#[entry]
fn main() -> ! {
    defmt::println!("start");
    #[cfg(feature = "api-check")]
    surface::link();
    #[allow(unused_mut)]
    let mut ok = true;
    #[cfg(feature = "c2ps")]
    {
        ok &= report::outcome("c2ps", c2ps::run());
    }
    #[cfg(feature = "eg")]
    {
        // The EG workload's own peak, apart from C²PS's.
        stack::repaint();
        ok &= report::outcome("eg", eg::run());
        let (used, _) = stack::high_water_mark();
        defmt::println!("stackeg {=usize}", used);
    }
    #[cfg(feature = "c2ps-stream")]
    {
        stack::repaint();
        ok &= report::outcome("c2ps-stream", stream::run());
    }
    let (hwm, size) = stack::peak();
    defmt::println!("stack {=usize} {=usize}", hwm, size);
    defmt::println!("done {=bool}", ok);
    debug::exit(if ok { EXIT_SUCCESS } else { EXIT_FAILURE });
    #[allow(clippy::empty_loop)]
    loop {}
}

#[exception]
unsafe fn HardFault(ef: &ExceptionFrame) -> ! {
    defmt::println!("hardfault pc={=u32:#x}", ef.pc());
    debug::exit(EXIT_FAILURE);
    #[allow(clippy::empty_loop)]
    loop {}
}

/// Release: any panic path left makes the link fail with an undefined
/// reference to this symbol, naming the caller (`debug = true` keeps lines).
#[cfg(all(not(debug_assertions), not(feature = "linkable-panic")))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    extern "Rust" {
        fn capdiv_firmware_panic_path_is_linked() -> !;
    }
    // SAFETY: never runs: the symbol is undefined, so a build that keeps this
    // call does not link.
    unsafe { capdiv_firmware_panic_path_is_linked() }
}

/// Debug (unoptimised) builds keep bounds checks; a panic is reported and
/// fails the run. So does the diagnosis feature `linkable-panic`.
#[cfg(any(debug_assertions, feature = "linkable-panic"))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    defmt::println!("panic");
    debug::exit(EXIT_FAILURE);
    #[allow(clippy::empty_loop)]
    loop {}
}
