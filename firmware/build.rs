//! Puts the memory layout of the target board where `link.x` finds it:
//! MPS2-AN386 (Cortex-M4, thumbv7em) or the BBC micro:bit's nRF51 (Cortex-M0,
//! thumbv6m), the two boards QEMU emulates that the firmware runs on.
use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    let target = env::var("TARGET").unwrap_or_default();
    let layout = if target.starts_with("thumbv6m") {
        "memory-microbit.x"
    } else {
        "memory-mps2.x"
    };
    fs::copy(layout, out.join("memory.x")).expect("copy memory layout");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed={layout}");
    println!("cargo:rerun-if-changed=build.rs");
    // Cortex-M0 (16 KiB RAM on the micro:bit) runs a shallower sample.
    println!("cargo::rustc-check-cfg=cfg(armv6m)");
    if target.starts_with("thumbv6m") {
        println!("cargo:rustc-cfg=armv6m");
    }
}
