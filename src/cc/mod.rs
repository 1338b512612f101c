//! Catmull-Clark caps (Catmull & Clark 1978): the baseline scheme EG is
//! compared with, and the fallback for valences EG has no rule for.
//!
//! A [`CcCap`] holds the c-net of an extraordinary vertex (docs/math/eg.md §1:
//! center `e` of valence `n ≥ 3`, 6 nodes per sector) in storage the caller
//! provides ([`CcCap::storage_len`] points), refines it by Catmull-Clark steps
//! and emits each level's ring of `3n` bicubic Bézier patches, in exactly the
//! layout of the EG rings ([`crate::eg::EgSubdivision::ring_patch`]):
//!
//! - [`cap`]: the type, construction, node access, the ring patches;
//! - [`step`]: one Catmull-Clark step (face, edge and vertex points);
//! - [`limit`]: the limit point, limit tangents and unit normal at the center.
//!
//! ```
//! use capdiv::{CcCap, Point3};
//! // Valence 5: center and 6 nodes per sector, §1 order, a paraboloid.
//! let n = 5;
//! let mut nodes = Vec::new();
//! for s in 0..n {
//!     let a = s as f64 * core::f64::consts::TAU / n as f64;
//!     for (x, y) in [(1.0, 0.0), (2.0, 0.0), (1.0, 1.0), (2.0, 1.0), (1.0, 2.0), (2.0, 2.0)] {
//!         let t = a + f64::atan2(y, x) * 4.0 / n as f64;
//!         let r = f64::hypot(x, y);
//!         nodes.push([r * t.cos(), r * t.sin(), 0.1 * r * r]);
//!     }
//! }
//! let mut storage = vec![Point3::ZERO; CcCap::<f64>::storage_len(n)];
//! let mut cap = CcCap::new([0.0; 3], &nodes, &mut storage)?;
//! for _ in 0..4 {
//!     cap.step()?;
//!     for (k, patch) in cap.ring_patches().enumerate() {
//!         let domain = cap.ring_patch_domain(k)?;
//!         assert!(patch.normal(0.5, 0.5)?.0[2] > 0.0 && domain.size > 0.0);
//!     }
//! }
//! assert!(cap.normal()?.0[2] > 0.99); // the paraboloid's normal at its apex
//! # Ok::<(), capdiv::Error>(())
//! ```

pub mod cap;
pub mod limit;
pub mod step;

pub use cap::{CcCap, CcRingPatches, EXT_SECTOR, PATCHES_PER_SECTOR};
