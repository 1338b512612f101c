//! The analysis and the tessellation under refused allocations: whichever
//! of their allocations of a mesh's size the system refuses,
//! `SurfacePlan::for_mesh` returns `MeshError::OutOfMemory` (naming the
//! size it needed), `try_tessellate` an `OutOfMemory`, and
//! `StreamTessellator` reports it and stops; none aborts the process (an
//! infallible allocation that is refused would) nor goes on around the
//! refusal.
//!
//! A global allocator refuses, on the armed test thread, the `k`-th
//! allocation of [`LARGE`] bytes or more (new blocks and growth alike), for
//! every `k` the work reaches. Smaller allocations are let through: what is
//! allocated as it is has the size of one vertex's neighbourhood (its fan,
//! a stencil row being built, a cap's c-net), and a valence that needed
//! 4 KB there would be a mesh no other buffer could hold.

use capdiv::Point3;
use capdiv_mesh::sinks::CollectSurface;
use capdiv_mesh::tessellate::{try_tessellate, Face, MeshSink, StreamTessellator};
use capdiv_mesh::{
    samples, Evaluator, MeshError, MeshInput, PatchRecord, PlanOptions, SurfacePlan,
};
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

/// `work` with the `refuse`-th large allocation of this thread refused;
/// returns its outcome and how many large allocations it asked for.
fn refusing<T>(refuse: usize, work: impl FnOnce() -> T) -> (T, usize) {
    LARGE_SEEN.with(|n| n.set(0));
    REFUSE.with(|r| r.set(refuse));
    ARMED.with(|a| a.set(true));
    let outcome = work();
    ARMED.with(|a| a.set(false));
    (outcome, LARGE_SEEN.with(Cell::get))
}

/// Plans `mesh` with the `refuse`-th large allocation refused.
fn plan_refusing(mesh: &MeshInput, refuse: usize) -> (Result<(), MeshError>, usize) {
    refusing(refuse, || {
        SurfacePlan::for_mesh(mesh, PlanOptions::default()).map(drop)
    })
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

/// Counts what a stream hands over, without allocating.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Handed {
    vertices: usize,
    faces: usize,
}

impl MeshSink<f64> for Handed {
    fn vertex(&mut self, _: Point3<f64>, _: Point3<f64>) {
        self.vertices += 1;
    }
    fn face(&mut self, _: Face, _: u32) {
        self.faces += 1;
    }
}

/// Streams `patches` through `tess` (cap groups end where the cap
/// changes); returns what was handed over when the stream first reported a
/// refusal (if it did) and in all.
fn stream(
    mut tess: StreamTessellator<f64>,
    patches: &[PatchRecord<f64>],
) -> (Option<Handed>, Handed) {
    let mut out = Handed::default();
    let mut at_refusal = None;
    for p in patches {
        tess.push(p, p.level, &mut out);
        if at_refusal.is_none() && tess.refused().is_some() {
            at_refusal = Some(out);
        }
    }
    tess.finish(&mut out);
    if at_refusal.is_none() && tess.refused().is_some() {
        at_refusal = Some(out);
    }
    (at_refusal, out)
}

/// The patches of the feature torus (6), evaluated unarmed.
fn feature_torus_patches() -> Vec<PatchRecord<f64>> {
    let mesh = samples::feature_torus(6);
    let plan = SurfacePlan::for_mesh(&mesh, PlanOptions::default()).unwrap();
    let mut collected = CollectSurface::new();
    Evaluator::<f64>::new(&plan)
        .unwrap()
        .evaluate(&mesh.vertices, &mut collected)
        .unwrap();
    collected.finish().unwrap().0
}

#[test]
fn every_large_allocation_of_the_collected_tessellation_can_be_refused() {
    let patches = feature_torus_patches();
    let tessellate = || try_tessellate(patches.iter().map(|p| (p, p.level)), 4, 8e-9);
    let (whole, large) = refusing(usize::MAX, tessellate);
    assert!(whole.unwrap().faces.len() > 10_000);
    // The samples, the weld's sorted points and classes, the vertices and
    // faces: each past 4 KB.
    assert!(large > 10, "{large} large allocations");
    for k in 0..large {
        match refusing(k, tessellate).0 {
            Err(e) => assert!(e.bytes > 0, "refusal {k}"),
            Ok(_) => panic!("refusal {k} of {large}: a tessellation"),
        }
    }
}

#[test]
fn every_large_allocation_of_the_stream_can_be_refused() {
    let patches = feature_torus_patches();
    // (The tessellator is made unarmed: its fixed tables, a layout per
    // kind of patch edge, do not depend on the mesh.)
    let new = || StreamTessellator::new(4, 1e-9 * 8.0);
    let tess = new();
    let ((refused, whole), large) = refusing(usize::MAX, || stream(tess, &patches));
    assert_eq!(refused, None);
    assert!(whole.faces > 10_000, "{whole:?}");
    // The weld table, the waiting output and the open edges grow past
    // 4 KB again and again.
    assert!(large > 10, "{large} large allocations");
    for k in 0..large {
        let tess = new();
        let ((refused, out), _) = refusing(k, || stream(tess, &patches));
        // Reported, and nothing handed over after it: a prefix of the
        // output.
        assert_eq!(refused, Some(out), "refusal {k} of {large}");
        assert!(
            out.vertices <= whole.vertices && out.faces <= whole.faces,
            "refusal {k}: {out:?} of {whole:?}"
        );
    }
}
