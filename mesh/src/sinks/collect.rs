//! [`CollectSurface`]: a sink that keeps every patch and cap, fallibly.

use crate::evaluate::{CapRecord, PatchRecord, SurfaceSink};
use crate::mem::{self, OutOfMemory};
use alloc::vec::Vec;

/// Keeps every patch and cap in the order given. Growth is fallible: the
/// first allocation refused is kept, the records from then on are dropped,
/// and [`CollectSurface::finish`] reports it.
#[derive(Clone, Debug)]
pub struct CollectSurface<R> {
    /// The patches received.
    pub patches: Vec<PatchRecord<R>>,
    /// The caps received.
    pub caps: Vec<CapRecord<R>>,
    /// The first growth the allocator refused.
    refused: Option<OutOfMemory>,
}

impl<R> Default for CollectSurface<R> {
    fn default() -> Self {
        Self::new()
    }
}

impl<R> CollectSurface<R> {
    /// An empty collection.
    pub fn new() -> Self {
        CollectSurface {
            patches: Vec::new(),
            caps: Vec::new(),
            refused: None,
        }
    }

    /// The first allocation refused, if any (the collection is then
    /// incomplete).
    pub fn refused(&self) -> Option<OutOfMemory> {
        self.refused
    }

    /// The patches and caps, or the allocation that was refused.
    #[allow(clippy::type_complexity)]
    pub fn finish(self) -> Result<(Vec<PatchRecord<R>>, Vec<CapRecord<R>>), OutOfMemory> {
        match self.refused {
            Some(oom) => Err(oom),
            None => Ok((self.patches, self.caps)),
        }
    }
}

impl<R: Clone> SurfaceSink<R> for CollectSurface<R> {
    fn patch(&mut self, p: &PatchRecord<R>) {
        if self.refused.is_none() {
            self.refused = mem::push(&mut self.patches, p.clone()).err();
        }
    }
    fn cap(&mut self, c: &CapRecord<R>) {
        if self.refused.is_none() {
            self.refused = mem::push(&mut self.caps, c.clone()).err();
        }
    }
}
