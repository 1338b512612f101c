//! Ready-made [`SurfaceSink`]s: [`CollectSurface`] keeps every record,
//! [`SurfaceStats`] counts them, [`PatchCounts`] counts only patches per
//! kind, [`Tee`] hands each record to two sinks
//! (counting what another sink writes, say).

mod collect;
mod stats;

pub use collect::CollectSurface;
pub use stats::{CapCount, PatchCounts, SurfaceStats};

use crate::evaluate::{CapRecord, PatchRecord, SurfaceSink};

/// Two sinks as one: each record goes to the first, then to the second.
#[derive(Clone, Debug, Default)]
pub struct Tee<A, B>(pub A, pub B);

impl<R, A: SurfaceSink<R>, B: SurfaceSink<R>> SurfaceSink<R> for Tee<A, B> {
    fn patch(&mut self, p: &PatchRecord<R>) {
        self.0.patch(p);
        self.1.patch(p);
    }
    fn cap(&mut self, c: &CapRecord<R>) {
        self.0.cap(c);
        self.1.cap(c);
    }
}

/// A sink borrowed is a sink (so a [`Tee`] can borrow its two).
impl<R, S: SurfaceSink<R> + ?Sized> SurfaceSink<R> for &mut S {
    fn patch(&mut self, p: &PatchRecord<R>) {
        (**self).patch(p);
    }
    fn cap(&mut self, c: &CapRecord<R>) {
        (**self).cap(c);
    }
}
