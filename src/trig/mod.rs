//! Angles for the refinement: a read-only table of primitive roots of unity,
//! built by const evaluation, and a ring of the current valence's roots.
//!
//! C²PS (docs/math/c2ps.md §2, §4) needs `c(j/N) = cos(2πj/N)` and `s(j/N)` for the
//! valence `N = n·2^m` of every level. No trig function is called at run time:
//!
//! - [`table`] holds `cos, sin (2π/o)` for every odd `o ≤ MAX_ODD_PART`,
//!   computed at compile time (`f64`, 64 entries, 1 KiB of `.rodata`);
//! - [`RootsOfUnity`] holds `(c(j/N), s(j/N))` for `j < N` in a ring of fixed
//!   capacity; it is built from the table and doubled in place by every C²PS
//!   step (`2·CAP·size_of::<R>()` bytes per net).

pub mod angles;
mod double_single;
pub mod roots;
pub mod table;

pub use angles::UnitRoots;
pub use roots::RootsOfUnity;
pub use table::{primitive_root, MAX_ODD_PART, ODD_ROOTS};
