//! `Evaluator::into_buffers` / `Evaluator::with_buffers`: an evaluator
//! rebuilt on its own plan's buffers gives the records a new evaluator
//! gives without allocating, and buffers of another plan are replaced, not
//! misused.

use capdiv_mesh::{
    samples, CapRecord, Evaluator, MeshInput, PatchRecord, SurfacePlan, SurfaceSink,
};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

mod common;
use common::Collect;

fn plan(mesh: &MeshInput) -> SurfacePlan<'static> {
    common::plan(mesh, 3)
}

/// Every record of an evaluation, in order, as text (`{:?}` of f64 is exact).
fn records(ev: &mut Evaluator<'_, f64>, positions: &[[f64; 3]]) -> Vec<String> {
    let mut c = Collect::default();
    ev.evaluate(positions, &mut c).expect("evaluate");
    let patches = c.patches.iter().map(|p| format!("{p:?}"));
    patches
        .chain(c.caps.iter().map(|k| format!("{k:?}")))
        .collect()
}

#[test]
fn buffers_back_on_their_plan_give_the_same_records() {
    // The hand: C²PS, EG and Catmull-Clark caps.
    let mesh = samples::hand();
    let plan = plan(&mesh);
    let mut ev = Evaluator::<f64>::new(&plan).unwrap();
    ev.set_hole_tolerance(Some(0.5));
    let first = records(&mut ev, &mesh.vertices);
    // The tolerance changes the surface (stops caps before the depth), so
    // losing it below would be seen.
    assert_ne!(
        records(&mut Evaluator::new(&plan).unwrap(), &mesh.vertices),
        first
    );
    let moved: Vec<[f64; 3]> = mesh
        .vertices
        .iter()
        .map(|p| [p[0] * 1.5, p[1], p[2] - 0.25])
        .collect();
    let mut fresh = Evaluator::<f64>::new(&plan).unwrap();
    fresh.set_hole_tolerance(Some(0.5));
    let want_moved = records(&mut fresh, &moved);

    let buffers = ev.into_buffers();
    let mut again = Evaluator::with_buffers(&plan, buffers).unwrap();
    // The tolerance came along: the same (shortened) rings.
    assert_eq!(records(&mut again, &mesh.vertices), first);
    assert_eq!(records(&mut again, &moved), want_moved);
}

#[test]
fn buffers_of_another_plan_are_replaced() {
    let (small, large) = (samples::cube(), samples::hand());
    let (small_plan, large_plan) = (plan(&small), plan(&large));
    let want_small = records(&mut Evaluator::new(&small_plan).unwrap(), &small.vertices);
    let want_large = records(&mut Evaluator::new(&large_plan).unwrap(), &large.vertices);

    // Buffers too small for the hand, then too large (and of other caps)
    // for the cube.
    let buffers = Evaluator::<f64>::new(&small_plan).unwrap().into_buffers();
    let mut ev = Evaluator::with_buffers(&large_plan, buffers).unwrap();
    assert_eq!(records(&mut ev, &large.vertices), want_large);
    let mut ev = Evaluator::with_buffers(&small_plan, ev.into_buffers()).unwrap();
    assert_eq!(records(&mut ev, &small.vertices), want_small);
}

/// Counts this thread's allocations.
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
        // SAFETY: forwarded as given.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded as given.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

/// Counts patches and caps without allocating.
#[derive(Default)]
struct Count(usize);

impl SurfaceSink<f64> for Count {
    fn patch(&mut self, _: &PatchRecord<f64>) {
        self.0 += 1;
    }
    fn cap(&mut self, _: &CapRecord<f64>) {
        self.0 += 1;
    }
}

#[test]
fn buffers_back_on_their_plan_allocate_nothing() {
    let mesh = samples::hand();
    let plan = plan(&mesh);
    let buffers = Evaluator::<f64>::new(&plan).unwrap().into_buffers();
    let mut sink = Count::default();
    let before = ALLOCATIONS.with(Cell::get);
    let mut ev = Evaluator::with_buffers(&plan, buffers).unwrap();
    ev.evaluate(&mesh.vertices, &mut sink).unwrap();
    let buffers = ev.into_buffers();
    assert_eq!(ALLOCATIONS.with(Cell::get), before);
    assert!(sink.0 > 0);
    // Buffers of another plan are new ones.
    let cube = samples::cube();
    let other = self::plan(&cube);
    let before = ALLOCATIONS.with(Cell::get);
    drop(Evaluator::with_buffers(&other, buffers).unwrap());
    assert!(ALLOCATIONS.with(Cell::get) > before);
}
