//! [`BoundedPlan`]: a surface plan that is refused, before any evaluation
//! state is allocated, when it would give more patches than a limit, and
//! [`SurfaceError`]: why planning, bounding or evaluating a surface failed.
//!
//! The count is [`SurfacePlan::patch_count`], known from the topology alone.
//! With a hole tolerance ([`crate::Evaluator::set_hole_tolerance`]) caps may
//! stop before the plan's depth, so the count is then an upper bound and the
//! refusal says so ([`SurfaceError::TooLarge::upper_bound`]).
//!
//! ```
//! use capdiv_mesh::bounded::{BoundedPlan, SurfaceError};
//! use capdiv_mesh::sinks::SurfaceStats;
//! use capdiv_mesh::{MeshInput, PlanOptions};
//!
//! // One quad: one regular patch.
//! let quad = MeshInput::new(
//!     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
//!     vec![vec![0, 1, 2, 3]],
//! );
//! let options = || PlanOptions { depth: 2, ..Default::default() };
//! let too_small = BoundedPlan::new(&quad, options(), 0, None);
//! assert!(matches!(
//!     too_small,
//!     Err(SurfaceError::TooLarge { patches: 1, max: 0, upper_bound: false })
//! ));
//!
//! let plan = BoundedPlan::new(&quad, options(), 1, None)?;
//! let mut stats = SurfaceStats::new();
//! plan.evaluate::<f64>(&quad.vertices, &mut stats)?;
//! assert_eq!(stats.patches.total, 1);
//! # Ok::<(), SurfaceError>(())
//! ```

use crate::error::MeshError;
use crate::evaluate::{EvalError, Evaluator, SurfaceSink};
use crate::input::MeshInput;
use crate::mem;
use crate::plan::{PlanOptions, SurfacePlan};
use capdiv::Real;
use core::fmt;

/// Why a surface could not be planned, bounded or evaluated.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum SurfaceError {
    /// The mesh was rejected by the analysis.
    Mesh(MeshError),
    /// The surface would have more patches than the limit; nothing was
    /// allocated for its evaluation and nothing was emitted.
    TooLarge {
        /// The patches the plan would give ([`SurfacePlan::patch_count`]).
        patches: u64,
        /// The limit.
        max: u64,
        /// `patches` is an upper bound: caps may stop before the plan's
        /// depth (a hole tolerance is set).
        upper_bound: bool,
    },
    /// The evaluation failed.
    Eval(EvalError),
}

impl From<MeshError> for SurfaceError {
    fn from(e: MeshError) -> Self {
        SurfaceError::Mesh(e)
    }
}

impl From<mem::OutOfMemory> for SurfaceError {
    fn from(e: mem::OutOfMemory) -> Self {
        SurfaceError::Eval(e.into())
    }
}

impl From<EvalError> for SurfaceError {
    fn from(e: EvalError) -> Self {
        SurfaceError::Eval(e)
    }
}

impl fmt::Display for SurfaceError {
    /// The mesh's or the evaluation's message, or for
    /// [`SurfaceError::TooLarge`]: `the surface would have [up to ]P
    /// patches, more than M`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SurfaceError::Mesh(e) => fmt::Display::fmt(e, f),
            SurfaceError::Eval(e) => fmt::Display::fmt(e, f),
            SurfaceError::TooLarge {
                patches,
                max,
                upper_bound,
            } => write!(
                f,
                "the surface would have {}{patches} patches, more than {max}",
                if *upper_bound { "up to " } else { "" }
            ),
        }
    }
}

/// The mesh's or the evaluation's error is the message itself, so no error
/// is reported again as a source.
impl core::error::Error for SurfaceError {}

/// A [`SurfacePlan`] whose patch count is known to be within a limit, with
/// the hole tolerance its evaluators get.
#[derive(Clone, Debug)]
pub struct BoundedPlan<'t> {
    plan: SurfacePlan<'t>,
    hole_tolerance: Option<f64>,
}

impl<'t> BoundedPlan<'t> {
    /// Plans `mesh` ([`SurfacePlan::for_mesh`]) and refuses it when it would
    /// give more than `max_patches` patches ([`SurfaceError::TooLarge`],
    /// an upper bound when `hole_tolerance` is set).
    pub fn new(
        mesh: &MeshInput,
        options: PlanOptions<'t>,
        max_patches: u64,
        hole_tolerance: Option<f64>,
    ) -> Result<Self, SurfaceError> {
        let plan = SurfacePlan::for_mesh(mesh, options)?;
        Self::from_plan(plan, max_patches, hole_tolerance)
    }

    /// Plans `mesh`, refuses it above `max_patches` as [`Self::new`] does,
    /// and evaluates it at its own positions (cast to `R`) into `sink`: a
    /// refused mesh gives the sink nothing. Returns the plan, to evaluate
    /// again when the vertices move.
    pub fn evaluate_mesh<R: Real>(
        mesh: &MeshInput,
        options: PlanOptions<'t>,
        max_patches: u64,
        hole_tolerance: Option<f64>,
        sink: &mut dyn SurfaceSink<R>,
    ) -> Result<Self, SurfaceError> {
        let plan = Self::new(mesh, options, max_patches, hole_tolerance)?;
        let mut positions = mem::with_capacity(mesh.vertices.len())?;
        positions.extend(mesh.vertices.iter().map(|p| p.map(R::from_f64)));
        plan.evaluate(&positions, sink)?;
        Ok(plan)
    }

    /// Bounds a plan already made, as [`Self::new`] does.
    pub fn from_plan(
        plan: SurfacePlan<'t>,
        max_patches: u64,
        hole_tolerance: Option<f64>,
    ) -> Result<Self, SurfaceError> {
        let patches = plan.patch_count();
        if patches > max_patches {
            return Err(SurfaceError::TooLarge {
                patches,
                max: max_patches,
                upper_bound: hole_tolerance.is_some(),
            });
        }
        Ok(BoundedPlan {
            plan,
            hole_tolerance,
        })
    }

    /// The plan.
    pub fn plan(&self) -> &SurfacePlan<'t> {
        &self.plan
    }

    /// The plan, given back.
    pub fn into_plan(self) -> SurfacePlan<'t> {
        self.plan
    }

    /// The hole tolerance its evaluators get.
    pub fn hole_tolerance(&self) -> Option<f64> {
        self.hole_tolerance
    }

    /// An evaluator of the plan in `R` with the hole tolerance set (to
    /// evaluate repeatedly, or on several threads).
    pub fn evaluator<R: Real>(&self) -> Result<Evaluator<'_, R>, SurfaceError> {
        let mut evaluator = Evaluator::new(&self.plan)?;
        evaluator.set_hole_tolerance(self.hole_tolerance);
        Ok(evaluator)
    }

    /// Evaluates the surface for `positions` (one per input vertex) into
    /// `sink`, as [`Evaluator::evaluate`] on [`Self::evaluator`].
    pub fn evaluate<R: Real>(
        &self,
        positions: &[[R; 3]],
        sink: &mut dyn SurfaceSink<R>,
    ) -> Result<(), SurfaceError> {
        self.evaluator()?.evaluate(positions, sink)?;
        Ok(())
    }
}
