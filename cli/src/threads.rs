//! `--threads`: how many threads evaluate a surface. One thread is
//! [`Evaluator::evaluate`]; more run [`Evaluator::evaluate_parallel`] on a
//! rayon pool of that size, with the same output bit for bit.

use capdiv_mesh::{EvalError, Evaluator, SurfaceSink};

/// Stack of each evaluation thread: the caps' nets live on the heap, so a
/// modest stack suffices.
const THREAD_STACK: usize = 16 << 20;

/// The default of `--threads`: the machine's available parallelism (1 when
/// it cannot be told).
pub fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Evaluates `evaluator`'s plan on `positions` into `sink` with `threads` threads
/// (`None`: [`default_threads`]). A pool that cannot be started falls back
/// to one thread.
pub fn evaluate<R: capdiv::Real + Send + Sync>(
    threads: Option<usize>,
    evaluator: &mut Evaluator<'_, R>,
    positions: &[[R; 3]],
    sink: &mut (dyn SurfaceSink<R> + Send),
) -> Result<(), EvalError> {
    let threads = threads.unwrap_or_else(default_threads).max(1);
    let pool = (threads > 1)
        .then(|| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .stack_size(THREAD_STACK)
                .thread_name(|i| format!("capdiv-eval-{i}"))
                .build()
                .ok()
        })
        .flatten();
    match pool {
        Some(pool) => pool.install(|| evaluator.evaluate_parallel(positions, sink)),
        None => evaluator.evaluate(positions, sink),
    }
}
