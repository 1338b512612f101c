//! # capdiv
//!
//! A `no_std`, allocation-free kernel for smooth subdivision-surface caps:
//!
//! - [`polar`]: C²PS, bi-3 C² polar subdivision (`docs/math/c2ps.md`) — caps around
//!   polar vertices; the valence doubles every step.
//! - [`eg`]: Evolving Guide subdivision (`docs/math/eg.md`) — bi-4 caps around
//!   extraordinary Catmull-Clark nodes.
//! - [`cc`]: Catmull-Clark caps in caller-provided storage — the baseline EG
//!   is compared with, for any valence ≥ 3.
//!
//! Everything is generic over [`Real`] (`f32`, `f64`), stored in fixed capacity
//! (const generics, `heapless`), and reports bad input as an [`Error`] without
//! panicking or touching the caller's data.
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod bezier;
pub mod cc;
pub mod eg;
pub mod error;
pub mod point;
pub mod polar;
pub mod real;
pub mod trig;

pub use bezier::{
    BicubicPatch, BiquarticPatch, PatchPoint, SurfaceGeometry, SurfaceJet, TensorPatch,
};
pub use cc::CcCap;
pub use eg::{CNet, DNet, EgSubdivision, RuleTable};
pub use error::Error;
pub use point::Point3;
pub use polar::{
    FirstStep, OuterRegion, PolarNet, PolarNetBuf, PolarStream, PoleGeometry, PoleJet,
    StreamOptions, StreamedPatch,
};
pub use real::Real;
