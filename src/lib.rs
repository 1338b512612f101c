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
//!
//! # Example
//!
//! A C²PS cap: a polar configuration of valence 8 with 5 links sampled from
//! the paraboloid `z = (x² + y²)/4`, refined twice in place; the rings are
//! bicubic Bézier patches, and the pole's limit geometry is known in closed
//! form (docs/math/c2ps.md §4) — here the paraboloid's own: Gaussian curvature
//! ¼, mean curvature ½.
//!
//! ```
//! use capdiv::{FirstStep, PolarNet, PoleJet};
//!
//! let n = 8;
//! let links: Vec<Vec<[f64; 3]>> = (1..=5)
//!     .map(|i| {
//!         (0..n)
//!             .map(|j| {
//!                 let t = core::f64::consts::TAU * j as f64 / n as f64;
//!                 let (x, y) = (i as f64 * t.cos(), i as f64 * t.sin());
//!                 [x, y, 0.25 * (x * x + y * y)]
//!             })
//!             .collect()
//!     })
//!     .collect();
//! // Capacity 8·2^2: room for two steps, stored inline.
//! let mut net: PolarNet<f64, 32> = PolarNet::new([0.0; 3], &links)?;
//! net.step(FirstStep::Uniform)?;
//! net.step(FirstStep::Uniform)?;
//! assert_eq!(net.valence(), 32);
//! assert_eq!(net.ring_patches().count(), 2 * 32);
//! // A third step would need valence 64: a typed error, the net unchanged.
//! assert!(net.step(FirstStep::Uniform).is_err());
//!
//! let g = PoleJet::of(&net).geometry()?;
//! assert!((g.normal.0[2] - 1.0).abs() < 1e-12);
//! assert!((g.gaussian - 0.25).abs() < 1e-12 && (g.mean - 0.5).abs() < 1e-12);
//! # Ok::<(), capdiv::Error>(())
//! ```
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
    BicubicPatch, BiquarticPatch, IsoCurve, PatchLines, PatchPoint, SurfaceGeometry, SurfaceJet,
    TensorPatch,
};
pub use cc::CcCap;
pub use eg::{CNet, DNet, EgSubdivision, RuleTable};
pub use error::Error;
pub use point::Point3;
pub use polar::{
    ArrayStorage, FirstStep, NetStorage, OuterRegion, PolarNet, PolarNetBuf, PolarNetInner,
    PolarStream, PoleGeometry, PoleJet, SliceStorage, StreamOptions, StreamedPatch,
};
pub use real::Real;
