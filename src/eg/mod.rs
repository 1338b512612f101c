//! EG — Evolving Guide subdivision (spec `EG.md`, Karčiauskas & Peters): bi-4
//! C² caps around an extraordinary Catmull-Clark node of valence 3..=10.
//!
//! Data flows one way:
//! - a [`CNet`] (§1) is degree-raised to a [`DNet`] (§3, `c0` by (3)), or a
//!   [`DNet`] (§2) is given directly (`c0` given, or fitted by (4));
//! - an [`EgSubdivision`] refines it step by step (§5 regular rules outside,
//!   §6 EG rule inside, `c0` fixed) with a [`RuleTable`] (§7: built in for
//!   n = 3, 5; the caller's, checked, for n = 6..10; none for the regular n = 4);
//! - every step emits a ring of `3n` bi-4 Bézier patches (§9,
//!   [`EgSubdivision::ring_patches`]); for n = 4 [`CNet::regular_cap`] gives
//!   the bicubic cap directly.
//!
//! Fixed capacity: at most [`MAX_VALENCE`] sectors, no heap, no panics.

mod layout;
pub mod net;
mod refine;
pub mod regular;
pub mod ring;
pub mod rule;
mod spectrum;
pub mod subdivision;
pub mod tables;

pub use net::{CNet, CSector, DNet, DSector, C_SECTOR, D_SECTOR};
pub use ring::PATCHES_PER_SECTOR;
pub use rule::{InnerNode, RuleTable, WEIGHT_SCALE};
pub use spectrum::{lambda_catmull_clark, LAMBDA_TOLERANCE};
pub use subdivision::{EgRingPatches, EgSubdivision};

/// The largest valence EG supports (the paper's tables stop at 10).
pub const MAX_VALENCE: usize = 10;
