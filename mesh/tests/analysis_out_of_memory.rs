//! The analysis of a tagged mesh under refused allocations: whichever of
//! its allocations of a mesh's size the system refuses, `SurfacePlan::for_mesh`
//! returns `MeshError::OutOfMemory` (naming the size it needed), and never
//! aborts the process (an infallible allocation that is refused would) nor
//! plans around the refusal.
//!
//! A global allocator refuses, on this test's thread, the `k`-th allocation
//! of [`LARGE`] bytes or more (new blocks and growth alike), for every `k`
//! the analysis reaches. Smaller allocations are let through: what the
//! analysis allocates as it is has the size of one vertex's neighbourhood
//! (its fan, a stencil row being built, a cap's c-net), and a valence
//! that needed 4 KB there would be a mesh no other buffer could hold.

use capdiv_mesh::{samples, MeshError, MeshInput, PlanOptions, SurfacePlan};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// Allocations from this size on count, and may be refused.
const LARGE: usize = 4096;

/// Refuses the [`REFUSE`]-th large allocation of a thread that has armed it.
struct Refusing;

thread_local! {
    /// Large allocations so far while armed.
    static LARGE_SEEN: Cell<usize> = const { Cell::new(0) };
    /// The index (in `LARGE_SEEN` order) of the one to refuse.
    static REFUSE: Cell<usize> = const { Cell::new(usize::MAX) };
    static ARMED: Cell<bool> = const { Cell::new(false) };
}

/// Whether an allocation of `size` bytes is refused (and counts it).
fn refuse(size: usize) -> bool {
    if size < LARGE || !ARMED.try_with(Cell::get).unwrap_or(false) {
        return false;
    }
    let k = LARGE_SEEN.with(|n| {
        let k = n.get();
        n.set(k + 1);
        k
    });
    REFUSE.with(Cell::get) == k
}

unsafe impl GlobalAlloc for Refusing {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if refuse(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded as given.
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if refuse(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded as given.
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > layout.size() && refuse(new_size) {
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded as given.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded as given.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static REFUSING: Refusing = Refusing;

/// Plans `mesh` with the `refuse`-th large allocation refused; returns the
/// outcome and how many large allocations were asked for.
fn plan_refusing(mesh: &MeshInput, refuse: usize) -> (Result<(), MeshError>, usize) {
    LARGE_SEEN.with(|n| n.set(0));
    REFUSE.with(|r| r.set(refuse));
    ARMED.with(|a| a.set(true));
    let outcome = SurfacePlan::for_mesh(mesh, PlanOptions::default()).map(drop);
    ARMED.with(|a| a.set(false));
    (outcome, LARGE_SEEN.with(Cell::get))
}

#[test]
fn every_large_allocation_of_the_analysis_can_be_refused() {
    // Creases, corners, holes and extraordinary points (adaptive
    // refinement and its caps); a boundary (`--boundary none` makes its
    // boundary faces holes); polar fans (C²PS caps) on a mesh with a crease.
    let mut open = samples::grid(24, 20);
    open.tags.boundary = capdiv_mesh::BoundaryInterpolation::None;
    let mut globe = samples::globe(12, 24);
    let f = globe.faces[40].clone();
    globe.tags.creases.push(capdiv_mesh::EdgeCrease {
        vertices: [f[0], f[1]],
        sharpness: 2.0,
    });
    let meshes = [
        ("feature torus", samples::feature_torus(6)),
        ("open grid", open),
        ("creased globe", globe),
    ];
    for (name, mesh) in meshes {
        let (whole, large) = plan_refusing(&mesh, usize::MAX);
        assert_eq!(whole, Ok(()), "{name}");
        // A mesh this size has level arrays of more than 4 KB.
        assert!(large > 10, "{name}: {large} large allocations");
        for k in 0..large {
            match plan_refusing(&mesh, k).0 {
                Err(MeshError::OutOfMemory { bytes }) => {
                    assert!(bytes > 0, "{name}, refusal {k}")
                }
                other => panic!("{name}, refusal {k} of {large}: {other:?}"),
            }
        }
    }
}
