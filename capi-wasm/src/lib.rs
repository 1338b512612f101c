//! capdiv for WebAssembly (`wasm32-unknown-unknown`, `no_std`, no allocator,
//! no wasm-bindgen): the `f64` calls of capdiv's C ABI, which lives in
//! `capi/` (crate `capdiv-capi`, shared with the C firmware's staticlib; its
//! header `capi/include/capdiv.h` documents every call).
//!
//! The caller places its `f64` inputs and output buffers in the module's
//! linear memory (for instance from the exported `__heap_base` upwards, after
//! `memory.grow` if needed: nothing in the module allocates there) and passes
//! pointers and lengths. Every call is stateless: it builds the net from the
//! inputs, works, writes the outputs, returns a status (`≥ 0` the number of
//! `f64` written, `< 0` a code of `capi/src/codes.rs`; on error nothing is
//! written).
//!
//! Exports: `capdiv_c2ps_refine`, `capdiv_c2ps_jet` (work buffer of capacity
//! 1536 on the module's stack), `capdiv_c2ps_refine_f64`,
//! `capdiv_c2ps_jet_f64` (work buffer from the caller, any capacity),
//! `capdiv_eg_refine`, `capdiv_eg_ring` (and their `_f64` names),
//! `capdiv_capacity` and the length helpers `capdiv_c2ps_work_len`,
//! `capdiv_c2ps_out_len`, `capdiv_eg_refine_len`, `capdiv_eg_ring_len`.
//!
//! Panic-free: the C ABI's panic handler calls a function no caller provides,
//! so a panic path left in the module shows as an import
//! `env.capdiv_panic_path_linked` and instantiation without imports fails (the
//! node demo instantiates with none).
#![no_std]

// Links the C ABI: its `#[no_mangle]` calls become the module's exports.
pub use capdiv_capi::*;
