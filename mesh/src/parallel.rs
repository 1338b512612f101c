//! Parallel evaluation on hosts (feature `parallel`):
//! [`Evaluator::evaluate_parallel`] runs the same code as
//! [`Evaluator::evaluate`] over rayon's threads and gives the sink the same
//! records, bit for bit, in the same order.
//!
//! The refinement steps are applied in blocks of rows, one block per task
//! (each row is computed as on one thread). The patches and caps are cut
//! into pieces (runs of [`SurfacePlan::order`]) of similar work; the
//! pieces of a window are evaluated by one task per thread, each with its
//! own cap buffers, taking the next piece as it finishes one; the calling
//! thread meanwhile hands the previous window's records to the sink in
//! order, so the sink needs neither `Send` nor locking.

extern crate std;

use crate::evaluate::{emit_regular, polar_need, EvalError, Scratch};
use crate::mem::{self, OutOfMemory};
use crate::plan::{SurfacePlan, Unit};
use crate::{CapRecord, Evaluator, PatchRecord, StencilTable, SurfaceSink};
use alloc::vec::Vec;
use capdiv::eg::FourierRule;
use capdiv::{Point3, Real};
use core::ops::Range;
use core::sync::atomic::{AtomicUsize, Ordering};
use rayon::prelude::*;
use std::sync::{Mutex, PoisonError};

/// Patches per piece (about): enough to outweigh taking a piece, few
/// enough to balance the threads.
const PIECE_PATCHES: u64 = 512;

/// Pieces per thread in a window: the records of a window are held until
/// the sink has them.
const PIECES_PER_THREAD: usize = 4;

/// Rows of a refinement step per task.
const STENCIL_BLOCK: usize = 4096;

/// A part of the surface: a run of [`SurfacePlan::order`].
type Piece = Range<usize>;

/// What a piece gave: its records, and the error that stopped it.
enum Event<R> {
    Patch(PatchRecord<R>),
    Cap(CapRecord<R>),
}

/// A piece's records and error. The slots of a window are reused by the
/// windows after it, so their buffers are allocated (and their pages
/// touched) once, not once per piece.
struct Done<R> {
    events: Vec<Event<R>>,
    error: Option<EvalError>,
}

/// A sink that keeps the records it receives (fallibly: the first
/// allocation that fails is kept as the piece's error).
struct Buffer<'a, R> {
    events: &'a mut Vec<Event<R>>,
    failed: Option<OutOfMemory>,
}

impl<R: Clone> Buffer<'_, R> {
    fn keep(&mut self, e: Event<R>) {
        if self.failed.is_none() {
            if let Err(oom) = mem::push(self.events, e) {
                self.failed = Some(oom);
            }
        }
    }
}

impl<R: Clone> SurfaceSink<R> for Buffer<'_, R> {
    fn patch(&mut self, p: &PatchRecord<R>) {
        self.keep(Event::Patch(p.clone()));
    }
    fn cap(&mut self, c: &CapRecord<R>) {
        self.keep(Event::Cap(c.clone()));
    }
}

/// The pieces of `plan`, in emission order: runs of [`SurfacePlan::order`]
/// of about [`PIECE_PATCHES`] patches.
fn pieces(plan: &SurfacePlan<'_>) -> Result<Vec<Piece>, OutOfMemory> {
    let depth = u64::from(plan.options.depth);
    let levels = 1u64
        .checked_shl(plan.options.depth)
        .map_or(u64::MAX, |p| p - 1);
    let polar = plan.polar.len();
    // Patches of each unit, as counted by `SurfacePlan::patch_count`.
    let weight = |u: Unit| match u {
        Unit::Regular(_) => 1,
        Unit::Cap(i) => match plan.polar.get(i as usize) {
            Some(p) => 4u64.saturating_mul(p.valence as u64).saturating_mul(levels),
            None => plan.extraordinary.get(i as usize - polar).map_or(1, |e| {
                3u64.saturating_mul(e.sectors.len() as u64)
                    .saturating_mul(depth)
            }),
        },
    };
    let mut out = Vec::new();
    let (mut start, mut sum) = (0, 0u64);
    for (i, &u) in plan.order.iter().enumerate() {
        sum = sum.saturating_add(weight(u).max(1));
        if sum >= PIECE_PATCHES {
            mem::push(&mut out, start..i + 1)?;
            (start, sum) = (i + 1, 0);
        }
    }
    if start < plan.order.len() {
        mem::push(&mut out, start..plan.order.len())?;
    }
    Ok(out)
}

/// Evaluates `piece` into `done` (emptied first), with `scratch` for its
/// caps.
fn run_piece<R: Real>(
    piece: &Piece,
    done: &mut Done<R>,
    scratch: &mut Scratch<R>,
    work: &[Point3<R>],
    rules: &[FourierRule<'static, R>],
    plan: &SurfacePlan<'_>,
) {
    done.events.clear();
    let mut buf = Buffer {
        events: &mut done.events,
        failed: None,
    };
    let mut error = None;
    for &unit in &plan.order[piece.clone()] {
        match unit {
            Unit::Regular(i) => emit_regular(plan, work, i as usize, &mut buf),
            Unit::Cap(index) => {
                if let Err(e) = scratch.cap(work, rules, plan, index, &mut buf) {
                    error = Some(e);
                    break;
                }
            }
        }
        if buf.failed.is_some() {
            break;
        }
    }
    done.error = buf.failed.map(EvalError::from).or(error);
}

/// Evaluates the pieces `window` over the scratches (one task each, every
/// task taking the next piece not yet taken), piece `i` into `slots[i]`.
fn run_window<R: Real + Send + Sync>(
    window: &[Piece],
    slots: &[Mutex<Done<R>>],
    scratches: &mut [&mut Scratch<R>],
    work: &[Point3<R>],
    rules: &[FourierRule<'static, R>],
    plan: &SurfacePlan<'_>,
) {
    let next = AtomicUsize::new(0);
    scratches.par_iter_mut().for_each(|scratch| loop {
        let i = next.fetch_add(1, Ordering::Relaxed);
        let (Some(piece), Some(slot)) = (window.get(i), slots.get(i)) else {
            break;
        };
        // Each slot is taken by one task only: the lock never waits.
        let mut done = slot.lock().unwrap_or_else(PoisonError::into_inner);
        run_piece(piece, &mut done, scratch, work, rules, plan);
    });
}

/// Hands the records of the first `len` slots to `sink` in order; the
/// first piece's error ends it, as it ends the one-thread evaluation.
fn emit<R>(
    slots: &mut [Mutex<Done<R>>],
    len: usize,
    sink: &mut dyn SurfaceSink<R>,
) -> Result<(), EvalError> {
    for slot in &mut slots[..len] {
        let d = slot.get_mut().unwrap_or_else(PoisonError::into_inner);
        for e in &d.events {
            match e {
                Event::Patch(p) => sink.patch(p),
                Event::Cap(c) => sink.cap(c),
            }
        }
        if let Some(e) = d.error.take() {
            return Err(e);
        }
    }
    Ok(())
}

/// [`StencilTable::apply`] in blocks of rows over rayon's threads.
fn apply_parallel<R: Real + Send + Sync>(
    table: &StencilTable,
    src: &[Point3<R>],
    out: &mut [Point3<R>],
) {
    out.par_chunks_mut(STENCIL_BLOCK)
        .enumerate()
        .for_each(|(b, block)| table.apply_from(src, block, b * STENCIL_BLOCK));
}

impl<R: Real + Send + Sync> Evaluator<'_, R> {
    /// [`Self::evaluate`] over the threads of the current rayon pool (the
    /// global one, or the one a caller entered with `ThreadPool::install`):
    /// the sink receives the same records, bit for bit, in the same order,
    /// on the calling thread. With one thread it is [`Self::evaluate`].
    ///
    /// The first call sizes one set of cap buffers per extra thread
    /// ([`EvalError::OutOfMemory`] if they cannot be allocated); the records
    /// of a few pieces per thread are held until the sink has them.
    pub fn evaluate_parallel(
        &mut self,
        positions: &[[R; 3]],
        sink: &mut dyn SurfaceSink<R>,
    ) -> Result<(), EvalError> {
        let threads = rayon::current_num_threads().max(1);
        if threads == 1 {
            return self.evaluate(positions, sink);
        }
        self.prepare(positions, apply_parallel)?;
        let plan = self.plan();
        let b = &mut self.buffers;
        if b.extra.len() + 1 < threads {
            let need = polar_need(plan)?;
            let more = threads - 1 - b.extra.len();
            mem::reserve_exact(&mut b.extra, more)?;
            while b.extra.len() + 1 < threads {
                let mut extra = Scratch::new(plan, need)?;
                extra.hole_tolerance = b.scratch.hole_tolerance;
                extra.relative_caps = b.scratch.relative_caps;
                b.extra.push(extra);
            }
        }
        let pieces = pieces(plan)?;
        let (work, rules) = (&b.work, &b.eg_rules);
        let mut scratches: Vec<&mut Scratch<R>> = mem::with_capacity(threads)?;
        scratches.push(&mut b.scratch);
        scratches.extend(b.extra.iter_mut().take(threads - 1));
        let per_window = PIECES_PER_THREAD * threads;
        let slots = || -> Result<Vec<Mutex<Done<R>>>, OutOfMemory> {
            let mut v = mem::with_capacity(per_window)?;
            v.resize_with(per_window, || {
                Mutex::new(Done {
                    events: Vec::new(),
                    error: None,
                })
            });
            Ok(v)
        };
        let (mut ready, mut next) = (slots()?, slots()?);
        let mut windows = pieces.chunks(per_window);
        let Some(first) = windows.next() else {
            return Ok(());
        };
        run_window(first, &ready, &mut scratches, work, rules, plan);
        let mut ready_len = first.len();
        for window in windows {
            // The next window is evaluated while this thread emits the last.
            let emitted = rayon::in_place_scope(|scope| {
                let (scratches, next) = (&mut scratches, &next);
                scope.spawn(move |_| run_window(window, next, scratches, work, rules, plan));
                emit(&mut ready, ready_len, sink)
            });
            emitted?;
            core::mem::swap(&mut ready, &mut next);
            ready_len = window.len();
        }
        emit(&mut ready, ready_len, sink)
    }
}
