//! C²PS — bi-3 C² polar subdivision (`docs/math/c2ps.md`).
//!
//! Data flows one way: a net ([`PolarNetInner`] over any [`NetStorage`]: a
//! [`PolarNet`] holds its storage inline, a [`PolarNetBuf`] borrows it) is
//! built and validated once, refined in place by [`PolarNetInner::step`]
//! (C²PS, §2) or [`PolarNetInner::rts_step`] (RTS, §3), and read out as a
//! [`PoleJet`] (§4) or as bicubic ring patches (§5).

mod column;
mod fourier;
pub(crate) mod index;
pub mod jet;
pub mod net;
pub mod outer;
pub mod ring;
mod rts;
mod step;
pub mod storage;
pub mod stream;
mod stream_level;

pub use jet::{PoleGeometry, PoleJet};
pub use net::{FirstStep, PolarNet, PolarNetBuf, PolarNetInner, MAX_STORED_LINKS};
pub use outer::OuterRegion;
pub use ring::PolarRingPatches;
pub use storage::{capacity_for, ArrayStorage, NetStorage, SliceStorage};
pub use stream::{PolarStream, StreamOptions, StreamedPatch, Sweep};
