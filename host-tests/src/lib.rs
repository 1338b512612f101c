//! `capdiv-reference`: an independent, `std`, `f64` reference implementation of
//! the C²PS scheme (`docs/math/c2ps.md`), written straight from the paper's formulas
//! and sharing no code with the `capdiv` kernel, plus the property tests (in
//! `tests/`) that hold the kernel to it.
//!
//! - [`vec3`]: the few vector operations on `[f64; 3]` everything uses.
//! - [`polar`]: a polar configuration as `Vec<Vec<[f64; 3]>>` (docs/math/c2ps.md §1).
//! - [`c2ps`]: one C²PS step as the literal O(n²) sums of rules (1)–(5), (29)
//!   with the weights of eq. (4), and the first-step variant (docs/math/c2ps.md §2).
//! - [`rts`]: RTS (docs/math/c2ps.md §3) literally and as a dense matrix, and
//!   its spectrum.
//! - [`bezier`]: B-spline → Bézier conversion and Bernstein-sum evaluation
//!   (docs/math/c2ps.md §5).
//! - [`ring`]: the surface ring of a configuration (docs/math/c2ps.md §5).
//! - [`jet`]: eigencoefficients, closed forms, Taylor quadratic, curvatures
//!   (docs/math/c2ps.md §4).
//! - [`eg`]: the EG subdivision matrix straight from `docs/math/eg.md` §5–§7.
//! - [`catmull_clark`]: a literal Catmull-Clark step on a polygon mesh, the
//!   dense matrix of a c-net, its limit weights, bicubic B-spline evaluation.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod bezier;
pub mod c2ps;
pub mod catmull_clark;
pub mod eg;
pub mod eigen;
pub mod jet;
pub mod polar;
pub mod ring;
pub mod rts;
pub mod vec3;
