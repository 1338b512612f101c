//! # capdiv-viewer
//!
//! The browser viewer's WebAssembly module (`viewer/`): a mesh — one of
//! [`capdiv_mesh::samples`] or a dropped OBJ/JSON file — analysed once into a
//! [`capdiv_mesh::SurfacePlan`], evaluated by [`capdiv_mesh::Evaluator`]
//! whenever a control point moves, and sampled per vertex at exact patch
//! parameters with normal, Gaussian and mean curvature
//! ([`capdiv::SurfaceJet::geometry`]) and the highlight-line parameter
//! ([`capdiv_mesh::shade`]) — the same formulas as the CLI's pictures.
//!
//! Built for `wasm32-unknown-unknown` with `std` (its allocator); the exports
//! ([`abi`]) are plain `extern "C"` functions over numbers and pointers into
//! the module's memory, so the page needs no wasm-bindgen, only
//! `WebAssembly.instantiate`. The logic modules are tested on the host with
//! `cargo test`.
#![forbid(unsafe_op_in_unsafe_fn)]
#![warn(missing_docs)]

pub mod abi;
pub mod input;
pub mod paint;
pub mod samples;
pub mod scene;
pub mod tess;
