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
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

extern crate alloc;

pub mod adaptive;
pub mod caps;
pub mod chart;
pub mod error;
pub mod evaluate;
pub mod grid;
pub mod input;
pub mod obj;
pub mod plan;
pub mod refine;
pub mod samples;
pub mod shade;
pub mod stencil;
pub mod tags;
pub mod tessellate;
pub mod topology;

pub use error::MeshError;
pub use evaluate::{CapRecord, EvalError, Evaluator, PatchKind, PatchRecord, SurfaceSink};
pub use input::{
    BoundaryInterpolation, CreaseMethod, EdgeCrease, MeshInput, SubdivTags, TriangleSubdivision,
    VertexCorner,
};
pub use plan::{PlanOptions, Scheme, SurfacePlan};
pub use stencil::StencilTable;
pub use topology::Topology;
