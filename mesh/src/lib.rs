//! # capdiv-mesh
//!
//! Whole meshes to smooth surfaces over the `capdiv` kernel: C²PS caps at polar
//! vertices, EG caps at extraordinary points, Catmull-Clark caps where EG has no
//! rule, uniform bicubic B-spline patches on regular faces.
//!
//! `no_std` with `alloc`, so the same code runs in WASM and in host tools.
//! As in OpenSubdiv's Far, topology is analysed once ([`Topology`], then a
//! surface plan) and positions flow through a separate, allocation-free
//! evaluation that a caller repeats when vertices move.
//!
//! # Example
//!
//! The smooth surface of a cube: its eight corners are extraordinary points
//! of valence 3, so it becomes eight EG caps (docs/math/eg.md) whose ring
//! patches a [`SurfaceSink`] receives.
//!
//! ```
//! use capdiv_mesh::{
//!     CapRecord, Evaluator, MeshInput, PatchKind, PatchRecord, PlanOptions, Scheme,
//!     SurfacePlan, SurfaceSink,
//! };
//!
//! let vertices = vec![
//!     [-1.0, -1.0, -1.0], [1.0, -1.0, -1.0], [1.0, 1.0, -1.0], [-1.0, 1.0, -1.0],
//!     [-1.0, -1.0, 1.0], [1.0, -1.0, 1.0], [1.0, 1.0, 1.0], [-1.0, 1.0, 1.0],
//! ];
//! let faces = vec![
//!     vec![0, 3, 2, 1], vec![4, 5, 6, 7], vec![0, 1, 5, 4],
//!     vec![1, 2, 6, 5], vec![2, 3, 7, 6], vec![3, 0, 4, 7],
//! ];
//! let mesh = MeshInput::new(vertices.clone(), faces);
//!
//! // Topology once: which faces are regular patches, which vertices caps.
//! let plan = SurfacePlan::for_mesh(&mesh, PlanOptions { depth: 3, ..Default::default() })?;
//!
//! #[derive(Default)]
//! struct Count { eg_patches: usize, caps: Vec<(Scheme, usize)> }
//! impl SurfaceSink<f64> for Count {
//!     fn patch(&mut self, p: &PatchRecord<f64>) {
//!         self.eg_patches += usize::from(p.kind == PatchKind::Eg);
//!     }
//!     fn cap(&mut self, c: &CapRecord<f64>) {
//!         self.caps.push((c.scheme, c.valence));
//!     }
//! }
//!
//! // Positions through the plan, as often as the vertices move.
//! let mut evaluator = Evaluator::<f64>::new(&plan).unwrap();
//! let mut sink = Count::default();
//! evaluator.evaluate(&vertices, &mut sink).unwrap();
//! assert_eq!(sink.caps, vec![(Scheme::Eg, 3); 8]);
//! assert!(sink.eg_patches > 0);
//! # Ok::<(), capdiv_mesh::MeshError>(())
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

extern crate alloc;

/// The README's Rust examples (the kernel's and this crate's), compiled and
/// run as doctests so that they stay true.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
pub struct ReadmeExamples;

pub mod adaptive;
pub mod bounded;
pub mod caps;
pub mod chart;
pub mod error;
pub mod evaluate;
pub mod facevarying;
pub mod global_step;
pub mod grid;
mod hole;
pub mod input;
pub mod mem;
pub mod obj;
#[cfg(feature = "parallel")]
pub mod parallel;
pub mod plan;
pub mod rings;
pub mod samples;
pub mod shade;
pub mod sinks;
pub mod stencil;
pub mod tagged_step;
pub mod tags;
pub mod tessellate;
pub mod topology;

pub use bounded::{BoundedPlan, SurfaceError};
pub use error::MeshError;
pub use evaluate::{
    CapRecord, EvalBuffers, EvalError, Evaluator, PatchKind, PatchRecord, SurfaceSink,
};
pub use facevarying::{FaceVarying, PatchUv};
pub use input::{
    BoundaryInterpolation, CreaseMethod, EdgeCrease, MeshInput, SubdivTags, TriangleSubdivision,
    VertexCorner,
};
pub use mem::OutOfMemory;
pub use plan::{PlanOptions, Scheme, SurfacePlan, Unit};
pub use stencil::{Primvar, StencilTable};
pub use topology::Topology;
