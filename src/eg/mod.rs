//! EG — Evolving Guide subdivision (`docs/math/eg.md`, Karčiauskas & Peters): bi-4
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
//!
//! ```
//! use capdiv::eg::{CNet, EgSubdivision};
//! // A valence-3 c-net: center and 6 nodes per sector in the §1 order
//! // (1,0) (2,0) (1,1) (2,1) (1,2) (2,2), here a flat grid bent upwards.
//! let mut nodes = Vec::new();
//! for s in 0..3 {
//!     let a = s as f64 * core::f64::consts::TAU / 3.0;
//!     for (x, y) in [(1.0, 0.0), (2.0, 0.0), (1.0, 1.0), (2.0, 1.0), (1.0, 2.0), (2.0, 2.0)] {
//!         let t = a + (y as f64).atan2(x) * 4.0 / 3.0;
//!         let r = f64::hypot(x, y);
//!         nodes.push([r * t.cos(), r * t.sin(), 0.1 * r * r]);
//!     }
//! }
//! let net = CNet::new([0.0, 0.0, 0.0], &nodes)?;
//! let mut eg = EgSubdivision::new(&net, None)?;
//! for _ in 0..4 {
//!     eg.step()?;
//!     for (k, patch) in eg.ring_patches().enumerate() {
//!         let domain = eg.ring_patch_domain(k)?; // where it lies in sector `domain.sector`
//!         let normal = patch.normal(0.5, 0.5)?;   // bi-4 Bézier patch (§9)
//!         assert!(normal.0[2] > 0.0 && domain.size > 0.0);
//!     }
//! }
//! assert_eq!(eg.limit(), net.limit()); // c0 by (3), fixed for all steps
//! # Ok::<(), capdiv::Error>(())
//! ```

pub mod fourier;
mod layout;
pub mod net;
pub mod regular;
pub mod ring;
pub mod rule;
mod spectrum;
mod step;
pub mod subdivision;
pub mod tables;

pub use fourier::FourierRule;
pub use net::{CNet, CSector, DNet, DSector, C_SECTOR, D_SECTOR};
pub use ring::PATCHES_PER_SECTOR;
pub use rule::{InnerNode, RuleTable, WEIGHT_SCALE};
pub use spectrum::{lambda_catmull_clark, LAMBDA_TOLERANCE};
pub use subdivision::{EgRingPatches, EgStart, EgSubdivision, PatchDomain};

/// The largest valence EG supports (the paper's tables stop at 10).
pub const MAX_VALENCE: usize = 10;

// With the `defmt` feature every public EG type is `defmt::Format`,
// checked here at compile time for both scalar types.
#[cfg(feature = "defmt")]
const _: () = {
    const fn format<T: defmt::Format + ?Sized>() {}
    const fn all<R: defmt::Format + 'static>() {
        format::<CNet<R>>();
        format::<DNet<R>>();
        format::<CSector<R>>();
        format::<DSector<R>>();
        format::<EgSubdivision<'static, R>>();
        format::<EgRingPatches<'static, 'static, R>>();
        format::<FourierRule<'static, R>>();
    }
    all::<f32>();
    all::<f64>();
    format::<RuleTable<'static>>();
    format::<InnerNode>();
    format::<PatchDomain>();
    format::<tables::Row>();
};
