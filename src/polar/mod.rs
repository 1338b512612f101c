//! C²PS — bi-3 C² polar subdivision (`docs/math/c2ps.md`).
//!
//! Data flows one way: a [`PolarNet`] (or a [`PolarNetBuf`], the same net in
//! caller-provided storage) is built and validated once, refined in
//! place by [`PolarNet::step`] (C²PS, §2) or [`PolarNet::rts_step`] (RTS, §3),
//! and read out as a [`PoleJet`] (§4) or as bicubic ring patches (§5).

pub mod buf;
mod column;
mod fourier;
pub(crate) mod index;
pub mod jet;
pub mod net;
pub mod outer;
pub mod ring;
mod rts;
mod step;
pub mod stream;
mod stream_level;

pub use buf::PolarNetBuf;
pub use jet::{PoleGeometry, PoleJet};
pub use net::{FirstStep, PolarNet, MAX_STORED_LINKS};
pub use outer::OuterRegion;
pub use ring::{RingPatches, RingPatchesView};
pub use stream::{PolarStream, StreamOptions, StreamedPatch, Sweep};
