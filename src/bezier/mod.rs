//! Tensor-product Bézier patches: the output form of both schemes.
//!
//! C²PS rings are bicubic (`K = 4` control points per direction, docs/math/c2ps.md
//! §5), EG rings bi-quartic (`K = 5`, docs/math/eg.md §9). One type and one
//! evaluator serve both: [`TensorPatch`], compiled once per `K`.

pub mod convert;
pub mod jet;
pub mod patch;

pub use convert::{bspline_to_bezier_cubic, BSPLINE_TO_BEZIER_CUBIC};
pub use jet::{SurfaceGeometry, SurfaceJet};
pub use patch::{BicubicPatch, BiquarticPatch, IsoCurve, PatchLines, PatchPoint, TensorPatch};
