//! `SurfacePlan`: the analysis of a mesh's topology, done once — which faces
//! are regular, which vertices get which cap, the gather indices of every
//! patch and cap, and the refinement step when the mesh needs one. Positions
//! play no part; [`crate::evaluate`] runs the plan on positions.
//!
//! Coverage rules, for faces and configurations that no tag reaches (see
//! [`SurfacePlan::for_mesh`]):
//! 1. a regular face (a quad with four regular corners, its 4×4 neighbourhood
//!    a grid, phantom points at a boundary) is a uniform bicubic B-spline
//!    patch;
//! 2. a polar configuration (a fan of triangles ringed by three rings of
//!    regular quads, docs/math/c2ps.md §1) is a C²PS cap over its triangles and
//!    the quads between links 1 and 2 (its level-0 ring and outer region are
//!    the regular faces around it);
//! 3. an extraordinary point (interior, valence n ≠ 4, quads around, 1-ring
//!    regular: its c-net exists, docs/math/eg.md §1) is an EG cap for n = 3, 5 and
//!    for n = 6..10 with a rule table, else a Catmull-Clark cap, over its n
//!    faces;
//! 4. where a step refines no face that does not need it — a polar fan's
//!    C²PS configuration is incomplete (links 1 and 2 are there, link 3 or
//!    the rings' regularity is not), one step completes it and no tag
//!    reaches its triangles and quads (nor the faces around their
//!    vertices); or, in a mesh without tags, every face needs refinement —
//!    the whole mesh is refined once and analysed again, at most
//!    [`MAX_STEPS`] times: Catmull-Clark ([`crate::global_step`]), in a mesh
//!    with tags with OpenSubdiv's rules ([`crate::tagged_step`]), and C²PS
//!    at the poles of the fans no tag reaches (docs/adaptive.md, "Whole-mesh
//!    steps"). A fan a tag reaches is Catmull-Clark: its pole falls back
//!    for a feature, its triangles become quads in a step;
//! 5. every face left is refined adaptively with OpenSubdiv's rules
//!    ([`crate::adaptive`]): nothing is left uncovered. Where that
//!    refinement separates an extraordinary point from every other feature
//!    (its c-net appears, as after one step at a cube's corners, or two at
//!    a triangle's centre), rule 3 applies there: a cap (EG or Catmull-Clark)
//!    over the faces around it at that level.
//!
//! With [`PlanOptions::catmull_clark`] every cap is a Catmull-Clark cap (the
//! papers' baseline): rule 2 is skipped (a fan's triangles are non-quad faces,
//! refined adaptively; the pole becomes an extraordinary point of the same
//! valence) and rule 3 always picks Catmull-Clark.

use crate::adaptive::base::{plain_base, tagged_base, TaggedBase};
use crate::adaptive::subdivide::Rules;
use crate::adaptive::{self, AdaptiveOptions};
use crate::caps::{
    extraordinary_config, is_fan, polar_config, ExtraordinaryConfig, PolarConfig, Reason,
};
use crate::chart::{Affine, FaceChart};
use crate::error::MeshError;
use crate::global_step::{try_global_step, PolarSeed};
use crate::grid::{face_grid, interior_face_grid, GridPoint};
use crate::input::MeshInput;
use crate::mem::{self, OutOfMemory};
use crate::stencil::{Primvar, StencilTable};
use crate::tagged_step::tagged_step;
use crate::topology::{check_sizes_and_positions, Topology, NONE};
use alloc::borrow::Cow;
use alloc::boxed::Box;
use alloc::collections::BTreeSet;
use alloc::vec::Vec;
use capdiv::eg::RuleTable;
use capdiv::FirstStep;

/// At most this many refinement steps before the analysis gives up on a face.
pub const MAX_STEPS: u32 = 2;

/// The cap scheme at a vertex.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Scheme {
    /// C²PS (docs/math/c2ps.md).
    C2ps,
    /// Evolving Guide (docs/math/eg.md).
    Eg,
    /// Catmull-Clark.
    CatmullClark,
}

impl Scheme {
    /// Identifier used in JSON.
    pub fn id(self) -> &'static str {
        match self {
            Scheme::C2ps => "c2ps",
            Scheme::Eg => "eg",
            Scheme::CatmullClark => "catmull-clark",
        }
    }
}

/// Options of the analysis.
#[derive(Clone, Debug)]
pub struct PlanOptions<'t> {
    /// Rings every cap emits (C²PS levels 1..=depth, EG and Catmull-Clark
    /// steps 1..=depth).
    pub depth: u32,
    /// EG rule tables for valences 6..10 (checked by [`RuleTable::new`]).
    pub eg_tables: Vec<RuleTable<'t>>,
    /// Every cap a Catmull-Clark cap: polar vertices are not detected — their
    /// triangles get a Catmull-Clark step like other non-quad faces — and
    /// extraordinary points of valence 3 and 5 get CC caps instead of EG.
    /// (The baseline the papers compare C²PS and EG with; `eg_tables` are
    /// then unused.)
    pub catmull_clark: bool,
}

impl PlanOptions<'_> {
    /// The cap of an extraordinary point of valence `n`: EG with the
    /// built-in rules (n = 3, 5) or the table `eg_tables[i]` (`Some(i)`),
    /// else Catmull-Clark.
    pub fn cap_scheme(&self, n: usize) -> (Scheme, Option<usize>) {
        let table = self.eg_tables.iter().position(|t| t.valence() == n);
        match n {
            _ if self.catmull_clark => (Scheme::CatmullClark, None),
            3 | 5 => (Scheme::Eg, None),
            6..=10 if table.is_some() => (Scheme::Eg, table),
            _ => (Scheme::CatmullClark, None),
        }
    }
}

impl Default for PlanOptions<'_> {
    fn default() -> Self {
        PlanOptions {
            depth: 6,
            eg_tables: Vec::new(),
            catmull_clark: false,
        }
    }
}

/// A regular face's patch.
#[derive(Clone, Debug, PartialEq)]
pub struct RegularPlan {
    /// Its 16 B-spline control points (indices into the working points),
    /// `[4·i + j]` with `i` along the face's own `u`.
    pub gather: [u32; 16],
    /// Where the face lies in the input.
    pub chart: FaceChart,
    /// Bit `k`: two patches of half the size meet the face's edge `k`
    /// (corner k → k+1): a cap face or a more refined face lies across.
    pub finer: u8,
    /// Refinement levels below the analysed level: the patch is a face of
    /// the adaptive refinement ([`crate::adaptive`]), `2^-level` of its
    /// analysed face across (0 for an analysed face itself).
    pub level: u32,
    /// Bit `k`: edge `k` borders the last hole around an irregular vertex,
    /// closed to `hole_point`.
    pub hole: u8,
    /// Working-point index of that vertex's limit point (unused without
    /// `hole` bits).
    pub hole_point: u32,
    /// Bit `k`: edge `k` lies on the surface's boundary. Bit `4 + k`:
    /// corner `k` is a boundary vertex of exactly two faces (a straight
    /// piece of boundary, half a turn of surface around it). Known for the
    /// analysed level's faces; 0 for the adaptive refinement's.
    pub boundary: u8,
}

/// A C²PS cap.
#[derive(Clone, Debug, PartialEq)]
pub struct PolarPlan {
    /// The input vertex (the pole).
    pub vertex: u32,
    /// Working-point indices of the pole and links 1..3 (`3n`, link by link).
    pub pole: u32,
    /// Links 1..3, `n` each.
    pub links: Vec<u32>,
    /// Valence at the analysed level.
    pub valence: usize,
    /// First-step rule of the first cap step ([`FirstStep::Plain`] when the
    /// refinement step already took the C²PS first step).
    pub first: FirstStep,
    /// Refinement steps the pole has had (the cap's level-0 unit is `2^-prior_steps`
    /// of the input's).
    pub prior_steps: u32,
    /// Per cap column at the analysed level: the input triangle it lies in.
    pub triangles: Vec<u32>,
    /// With `prior_steps = 0`, per column: the quad between links 1 and 2 and its
    /// map from polar coordinates `(r − 1, τn − j)` to its own square.
    pub quads: Vec<FaceChart>,
}

/// An EG or Catmull-Clark cap.
#[derive(Clone, Debug, PartialEq)]
pub struct ExtraordinaryCapPlan {
    /// The input vertex, or `None` for the centre of an input face that is
    /// not a quad (made a vertex by refinement).
    pub vertex: Option<u32>,
    /// The input face whose centre it is, when `vertex` is `None`.
    pub face: Option<u32>,
    /// EG or Catmull-Clark.
    pub scheme: Scheme,
    /// Working-point index of the center.
    pub center: u32,
    /// `6n` c-net nodes, §1 order.
    pub nodes: Vec<u32>,
    /// Per sector: from sector coordinates `(x, y)` (level-0 c-units, the
    /// sector's face is `[0,1]²`) to the input face.
    pub sectors: Vec<FaceChart>,
    /// Index into [`PlanOptions::eg_tables`] for n = 6..10.
    pub table: Option<usize>,
    /// Refinement level of its sectors' faces below the input (the
    /// refinement steps, and the adaptive refinement's levels for a cap it
    /// made): the sectors are `2^-level` of an input face across.
    pub level: u32,
}

/// One entry of [`SurfacePlan::order`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Unit {
    /// The patch of [`SurfacePlan::regular`]`[i]`.
    Regular(u32),
    /// Cap `i`, numbered as in [`crate::PatchRecord::cap`]: the polar caps
    /// first, then [`SurfacePlan::extraordinary`].
    Cap(u32),
}

/// A face without a patch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UncoveredFace {
    /// Input face.
    pub face: u32,
    /// Why.
    pub reason: Reason,
}

/// The analysis of a mesh: everything evaluation needs but positions.
#[derive(Clone, Debug)]
pub struct SurfacePlan<'t> {
    /// Vertices of the input.
    pub input_vertices: usize,
    /// Faces of the input.
    pub input_faces: usize,
    /// Refinement steps taken, each a stencil table over the previous level's
    /// points (the first over the input vertices).
    pub steps: Vec<StencilTable>,
    /// Vertices at the analysed level.
    pub vertices: usize,
    /// Phantom points (boundaries), appended after the analysed level's
    /// vertices: the working points are `vertices + phantoms.len()`.
    pub phantoms: StencilTable,
    /// Regular faces.
    pub regular: Vec<RegularPlan>,
    /// C²PS caps.
    pub polar: Vec<PolarPlan>,
    /// EG and Catmull-Clark caps.
    pub extraordinary: Vec<ExtraordinaryCapPlan>,
    /// The order [`crate::Evaluator::evaluate`] emits the regular patches
    /// and caps in, each once: first the regular faces and caps of the
    /// analysed level (the module doc's rules 1–3), by the input face they
    /// lie in, the input faces taken breadth first across their edges (one
    /// connected part after the other, each from its lowest-numbered face),
    /// a face's regular patches before the caps first reached at it; then
    /// the patches of the adaptive refinement and its caps, in plan order.
    /// So the surface grows as a front from a seed face, and the boundary
    /// between the patches given and those to come (what a streaming
    /// welder holds) is about that front, not the whole surface.
    pub order: Vec<Unit>,
    /// Faces left without a patch (input faces, each once).
    pub uncovered: Vec<UncoveredFace>,
    /// Input faces that needed refinement, with the first reason found:
    /// those that made the whole-mesh step necessary when one was taken,
    /// else those refined adaptively.
    pub needed_refinement: Vec<UncoveredFace>,
    /// Vertices of the analysed level where a cap's configuration (a polar
    /// fan, an extraordinary point) is but no cap was made, and why; their
    /// faces are Catmull-Clark by adaptive refinement. The pole of a fan a
    /// tag reached before a step keeps [`Reason::Feature`].
    pub fallbacks: Vec<(u32, Reason)>,
    /// Faces of the adaptive refinement left as the last hole around an
    /// irregular vertex (closed by a fan to its limit point): where each lies
    /// in the input.
    pub last_holes: Vec<FaceChart>,
    /// Crease tags on two vertices that share no edge (ignored, as
    /// OpenSubdiv ignores them).
    pub creases_not_edges: usize,
    /// Patch edges met by patches two or more levels finer (see
    /// [`crate::adaptive::Adaptive::level_jumps`]).
    pub level_jumps: usize,
    /// Patches next to the last holes of two vertices (see
    /// [`crate::adaptive::Adaptive::hole_conflicts`]).
    pub hole_conflicts: usize,
    /// Options.
    pub options: PlanOptions<'t>,
}

/// Per input face, its place in a breadth-first walk across the edges of
/// `topo` (each connected part from its lowest-numbered face); the identity
/// without a topology of `faces` faces.
fn face_ranks(topo: Option<&Topology>, faces: usize) -> Result<Vec<u32>, MeshError> {
    let Some(t) = topo.filter(|t| t.num_faces() == faces) else {
        return Ok(mem::collect(0..faces as u32)?);
    };
    let mut rank = mem::filled(faces, NONE)?;
    // The faces in walk order (the queue of the walk).
    let mut walk: Vec<u32> = mem::with_capacity(faces)?;
    for seed in 0..faces {
        if rank[seed] != NONE {
            continue;
        }
        rank[seed] = walk.len() as u32;
        walk.push(seed as u32);
        let mut head = walk.len() - 1;
        while let Some(&f) = walk.get(head) {
            head += 1;
            for k in 0..t.face_len(f as usize) {
                let tw = t.twin(t.face_half_edge(f as usize, k));
                if tw == NONE {
                    continue;
                }
                let g = t.face_of(tw) as usize;
                if rank[g] == NONE {
                    rank[g] = walk.len() as u32;
                    walk.push(g as u32);
                }
            }
        }
    }
    Ok(rank)
}

/// One analysis pass on one level.
struct Pass {
    /// The regular faces' patches, in face order: each with its face (of
    /// this level) in `chart.face` and, where its grid is made of the
    /// level's vertices, its `gather`; the plan fills in the rest
    /// ([`SurfacePlan::push_caps_and_regular`]) and keeps the list, so
    /// that the patches are not written twice.
    regular: Vec<RegularPlan>,
    /// The grids with phantom points (at a boundary), by the index of their
    /// patch in `regular`.
    phantom_grids: Vec<(u32, Box<[[GridPoint; 4]; 4]>)>,
    polar: Vec<PolarConfig>,
    extraordinary: Vec<(ExtraordinaryConfig, Scheme, Option<usize>)>,
    /// Per face of the level: the reason it is uncovered, if it is.
    uncovered: Vec<Option<Reason>>,
    /// Vertices with a cap configuration type (a fan, an extraordinary
    /// point) but no cap, and why.
    fallbacks: Vec<(u32, Reason)>,
}

impl<'t> SurfacePlan<'t> {
    /// The [`Self::fallbacks`] at vertices of the input mesh: a whole-mesh
    /// step numbers the vertex point of old vertex `v` as `v`
    /// ([`crate::global_step`]), so the analysed level's vertices below
    /// [`Self::input_vertices`] are the input's own; the others are points
    /// the steps made.
    pub fn input_fallbacks(&self) -> impl Iterator<Item = (u32, Reason)> + '_ {
        let input = self.input_vertices;
        self.fallbacks
            .iter()
            .copied()
            .filter(move |&(v, _)| (v as usize) < input)
    }

    /// The number of patches [`crate::Evaluator::evaluate`] hands on,
    /// known before any is made: one per regular face, `3n` per ring of an
    /// EG or Catmull-Clark cap of valence `n`, and `2·n·2^m` at level
    /// `m = 1..=depth` of a C²PS cap of valence `n` (its two spans of
    /// `n·2^m` columns). Saturates at `u64::MAX`.
    pub fn patch_count(&self) -> u64 {
        let depth = u64::from(self.options.depth);
        let ev = self.extraordinary.iter().map(|e| {
            3u64.saturating_mul(e.sectors.len() as u64)
                .saturating_mul(depth)
        });
        // Σ_{m=1..depth} 2·n·2^m = 4n·(2^depth − 1).
        let levels = 1u64
            .checked_shl(self.options.depth)
            .map_or(u64::MAX, |p| p - 1);
        let polar = self
            .polar
            .iter()
            .map(|p| 4u64.saturating_mul(p.valence as u64).saturating_mul(levels));
        ev.chain(polar)
            .fold(self.regular.len() as u64, u64::saturating_add)
    }

    /// Analyses a validated mesh without tags (OpenSubdiv's defaults:
    /// edge-and-corner boundaries, no creases).
    pub fn new(topo: &Topology, options: PlanOptions<'t>) -> Result<Self, MeshError> {
        Self::build(Some(topo), None, topo.num_vertices(), options)
    }

    /// Validates and analyses a mesh with its tags ([`crate::SubdivTags`]):
    /// every face that OpenSubdiv accepts is covered. A mesh without tags is
    /// analysed as by [`Self::new`]; with tags, or when it is not a
    /// consistently oriented manifold, caps and level-0 patches go only
    /// where no tag reaches them and every other face is refined adaptively
    /// with OpenSubdiv's rules ([`crate::adaptive`]), after a whole-mesh
    /// step with those rules where a polar fan no tag reaches needs one
    /// (rule 4 of the module doc).
    ///
    /// # Example
    ///
    /// The cube's corners are valence-3 points that touch each other, so
    /// the whole mesh is refined once (rule 4 of the module doc); then each
    /// corner's c-net is there and its three faces become an EG cap — or a
    /// Catmull-Clark cap with [`PlanOptions::catmull_clark`].
    ///
    /// ```
    /// use capdiv_mesh::{samples, PlanOptions, Scheme, SurfacePlan};
    ///
    /// let cube = samples::cube();
    /// let plan = SurfacePlan::for_mesh(&cube, PlanOptions::default())?;
    /// assert_eq!(plan.steps.len(), 1);
    /// assert!(plan.regular.is_empty() && plan.uncovered.is_empty());
    /// assert_eq!(plan.extraordinary.len(), 8);
    /// assert!(plan.extraordinary.iter().all(|c| c.scheme == Scheme::Eg));
    ///
    /// let baseline = PlanOptions { catmull_clark: true, ..Default::default() };
    /// let plan = SurfacePlan::for_mesh(&cube, baseline)?;
    /// assert!(plan.extraordinary.iter().all(|c| c.scheme == Scheme::CatmullClark));
    /// # Ok::<(), capdiv_mesh::MeshError>(())
    /// ```
    pub fn for_mesh(mesh: &MeshInput, options: PlanOptions<'t>) -> Result<Self, MeshError> {
        validate(mesh)?;
        // A mesh Topology refuses (not a manifold) is planned from its
        // tagged base alone; an allocation refused is an error.
        let topo = match Topology::new(mesh) {
            Ok(t) => Some(t),
            Err(e @ MeshError::OutOfMemory { .. }) => return Err(e),
            Err(_) => None,
        };
        if mesh.tags.is_plain() {
            if let Some(t) = &topo {
                return Self::new(t, options);
            }
        }
        let tagged = tagged_base(mesh)?;
        Self::build(topo.as_ref(), Some(tagged), mesh.vertices.len(), options)
    }

    fn build(
        topo: Option<&Topology>,
        mut tagged: Option<TaggedBase>,
        num_vertices: usize,
        options: PlanOptions<'t>,
    ) -> Result<Self, MeshError> {
        let input_faces = topo
            .map(Topology::num_faces)
            .or(tagged.as_ref().map(|b| b.level.num_faces()))
            .unwrap_or(0);
        // The input's faces are their own charts until a step refines them.
        let mut charts = Charts::Input(input_faces);
        let mut steps = Vec::new();
        let mut needed = Vec::new();
        // The analysed level: the input's topology (borrowed) until a step.
        let mut level_topo = topo.map(Cow::Borrowed);
        // Per vertex at the current level: has it been a C²PS pole (refined by
        // the step), and how often.
        let mut pole_steps: Vec<u32> = mem::filled(num_vertices, 0)?;
        let clean = tagged.as_ref().map(|b| b.clean.as_slice());
        let mut pass = match &level_topo {
            Some(t) => analyse(t, &options, clean)?,
            None => Pass {
                regular: Vec::new(),
                phantom_grids: Vec::new(),
                polar: Vec::new(),
                extraordinary: Vec::new(),
                uncovered: mem::filled(input_faces, Some(Reason::Feature))?,
                fallbacks: Vec::new(),
            },
        };
        // Poles of fans a tag reached at a coarser level (a vertex keeps
        // its index through a step).
        let mut tagged_fans: BTreeSet<u32> = BTreeSet::new();
        // Whole-mesh steps only where they refine no face that does not
        // need it: for a polar fan whose C²PS configuration a step
        // completes and no tag reaches (the step refines poles by C²PS), or,
        // in a mesh without tags, when every face needs refinement (a
        // triangle mesh; the step is the adaptive refinement's first level,
        // made at once). A mesh with tags is stepped with OpenSubdiv's rules
        // ([`crate::tagged_step`]). Everything else is refined adaptively,
        // caps included.
        while let Some(t) = level_topo.as_ref() {
            let clean = tagged.as_ref().map(|b| b.clean.as_slice());
            let polar_pending = !options.catmull_clark
                && pass.fallbacks.iter().any(|&(v, r)| {
                    r == Reason::PolarIncomplete && step_seed(t, v as usize, clean).is_some()
                });
            let every_face = tagged.is_none()
                && pass
                    .uncovered
                    .iter()
                    .all(|r| r.is_some_and(Reason::refinement_helps));
            if (steps.len() as u32) >= MAX_STEPS
                || !(polar_pending || every_face)
                || !pass
                    .uncovered
                    .iter()
                    .flatten()
                    .any(|r| r.refinement_helps())
            {
                break;
            }
            let seeds: Vec<PolarSeed> = mem::collect(
                (0..t.num_vertices())
                    .filter(|&v| !options.catmull_clark && is_fan(t, v))
                    .filter_map(|v| step_seed(t, v, clean)),
            )?;
            let parents = charts.to_vec()?;
            let (refined, next_base) = match &tagged {
                None => (try_global_step(t, &parents, &seeds)?, None),
                Some(b) => match tagged_step(t, b, &parents, &seeds)? {
                    Some((r, next)) => (r, Some(next)),
                    None => break,
                },
            };
            if steps.is_empty() {
                needed = uncovered_list(&pass.uncovered, &charts, true)?;
            }
            // A fan a tag reached is Catmull-Clark: its triangles are quads
            // after the step, and the pole's fallback stays the tag's.
            tagged_fans.extend(
                pass.fallbacks
                    .iter()
                    .filter(|&&(v, r)| r == Reason::Feature && is_fan(t, v as usize))
                    .map(|&(v, _)| v),
            );
            let mut new_pole_steps = mem::filled(refined.num_vertices, 0)?;
            for (seed, &p) in seeds.iter().zip(&refined.poles) {
                new_pole_steps[p as usize] = pole_steps[seed.pole as usize] + 1;
            }
            let next = Topology::from_faces(refined.num_vertices, &refined.faces)?;
            charts = Charts::Refined(refined.charts);
            steps.push(refined.stencils);
            pole_steps = new_pole_steps;
            pass = analyse(
                &next,
                &options,
                next_base.as_ref().map(|b| b.clean.as_slice()),
            )?;
            for (v, r) in &mut pass.fallbacks {
                if tagged_fans.contains(v) {
                    *r = Reason::Feature;
                }
            }
            tagged = next_base;
            level_topo = Some(Cow::Owned(next));
        }
        if steps.is_empty() {
            needed = uncovered_list(&pass.uncovered, &charts, false)?;
        }
        let vertices = level_topo
            .as_ref()
            .map_or(num_vertices, |t| t.num_vertices());
        let mut plan = SurfacePlan {
            input_vertices: num_vertices,
            input_faces,
            steps,
            vertices,
            phantoms: StencilTable::new(),
            regular: Vec::new(),
            polar: Vec::new(),
            extraordinary: Vec::new(),
            order: Vec::new(),
            uncovered: Vec::new(),
            needed_refinement: needed,
            last_holes: Vec::new(),
            fallbacks: mem::to_vec(&pass.fallbacks)?,
            creases_not_edges: 0,
            level_jumps: 0,
            hole_conflicts: 0,
            options,
        };
        let level_faces = charts.len();
        let cap_face: Vec<bool> = {
            let mut c = mem::filled(level_faces, false)?;
            for p in &pass.polar {
                for &f in p.triangles.iter().chain(&p.quads) {
                    c[f as usize] = true;
                }
            }
            for (e, _, _) in &pass.extraordinary {
                for &(f, _) in &e.sectors {
                    c[f as usize] = true;
                }
            }
            c
        };
        if let Some(level_topo) = &level_topo {
            mem::reserve(&mut plan.polar, pass.polar.len())?;
            mem::reserve(&mut plan.extraordinary, pass.extraordinary.len())?;
            plan.push_caps_and_regular(level_topo, &mut pass, &charts, &pole_steps, &cap_face);
        }
        // Patches and caps of the analysed level (the adaptive refinement's
        // come after them).
        let analysed = (plan.regular.len(), plan.extraordinary.len());
        // Every other face: adaptive refinement over the analysed level
        // (its base level built only when some face needs it).
        if pass.uncovered.iter().any(Option::is_some) {
            let base = match tagged {
                Some(b) => b,
                None => {
                    let t = level_topo.as_ref().ok_or(MeshError::Empty)?;
                    plain_base(t)?
                }
            };
            let roots: Vec<(u32, FaceChart)> = mem::collect(
                pass.uncovered
                    .iter()
                    .enumerate()
                    .filter(|(f, r)| r.is_some() && !base.level.hole[*f])
                    .map(|(f, _)| (f as u32, charts.get(f))),
            )?;
            plan.push_adaptive(&base, &roots, &cap_face)?;
        }
        plan.order = plan.emission_order(topo, analysed)?;
        Ok(plan)
    }

    /// [`Self::order`]: `analysed` counts the regular patches and EG /
    /// Catmull-Clark caps of the analysed level (the first of
    /// [`Self::regular`] and [`Self::extraordinary`]); `topo` is the input's topology,
    /// if it has one (without it, faces are taken in input order).
    fn emission_order(
        &self,
        topo: Option<&Topology>,
        analysed: (usize, usize),
    ) -> Result<Vec<Unit>, MeshError> {
        let rank = face_ranks(topo, self.input_faces)?;
        let rank_of = |f: u32| rank.get(f as usize).copied().unwrap_or(NONE);
        let polar = self.polar.len();
        let mut keyed: Vec<(u32, Unit)> = mem::with_capacity(analysed.0 + polar + analysed.1)?;
        for (i, r) in self.regular[..analysed.0].iter().enumerate() {
            keyed.push((rank_of(r.chart.face), Unit::Regular(i as u32)));
        }
        for (i, p) in self.polar.iter().enumerate() {
            let faces = p.triangles.iter().copied();
            let key = faces
                .chain(p.quads.iter().map(|q| q.face))
                .map(rank_of)
                .min();
            keyed.push((key.unwrap_or(NONE), Unit::Cap(i as u32)));
        }
        for (i, e) in self.extraordinary[..analysed.1].iter().enumerate() {
            let key = e.sectors.iter().map(|s| rank_of(s.face)).min();
            keyed.push((key.unwrap_or(NONE), Unit::Cap((polar + i) as u32)));
        }
        keyed.sort_unstable();
        let total = self.regular.len() + polar + self.extraordinary.len();
        let mut order = mem::with_capacity(total)?;
        order.extend(keyed.into_iter().map(|(_, u)| u));
        drop(rank);
        order.extend((analysed.0..self.regular.len()).map(|i| Unit::Regular(i as u32)));
        order.extend(
            (polar + analysed.1..polar + self.extraordinary.len()).map(|i| Unit::Cap(i as u32)),
        );
        Ok(order)
    }

    /// The fast path's patches and caps: regular faces of the analysed level,
    /// C²PS and EG / Catmull-Clark caps.
    fn push_caps_and_regular(
        &mut self,
        level_topo: &Topology,
        pass: &mut Pass,
        charts: &Charts,
        pole_steps: &[u32],
        cap_face: &[bool],
    ) {
        let input_vertices = self.input_vertices as u32;
        let input_vertex = |v: u32| (v < input_vertices).then_some(v);
        // The pass's patches become the plan's: the analysed level's come
        // first (this runs on a new plan, before the adaptive refinement's).
        self.regular = core::mem::take(&mut pass.regular);
        for (i, grid) in &pass.phantom_grids {
            for (k, p) in grid.iter().flatten().enumerate() {
                let point = self.point(p);
                self.regular[*i as usize].gather[k] = point;
            }
        }
        for r in &mut self.regular {
            let f = r.chart.face as usize;
            let (mut finer, mut boundary) = (0u8, 0u8);
            for k in 0..4 {
                let h = level_topo.face_half_edge(f, k);
                let tw = level_topo.twin(h);
                if tw == NONE {
                    boundary |= 1 << k;
                } else if cap_face[level_topo.face_of(tw) as usize] {
                    finer |= 1 << k;
                }
                let v = level_topo.origin(h) as usize;
                if level_topo.is_boundary(v) && level_topo.vertex_face_count(v) == 2 {
                    boundary |= 1 << (4 + k);
                }
            }
            r.chart = charts.get(f);
            r.finer = finer;
            r.boundary = boundary;
        }
        for c in &pass.polar {
            self.push_polar(level_topo, c, charts, pole_steps[c.pole as usize]);
        }
        for (e, scheme, table) in &pass.extraordinary {
            let sectors = e
                .sectors
                .iter()
                .map(|&(f, k)| {
                    let ch = charts.get(f as usize);
                    FaceChart {
                        face: ch.face,
                        corner: ch.corner,
                        map: ch.map.compose(&Affine::rotation(k as usize)),
                    }
                })
                .collect();
            let (vertex, face) = match input_vertex(e.center) {
                Some(v) => (Some(v), None),
                // A face point: all its sectors lie in one input face.
                None => (None, Some(charts.get(e.sectors[0].0 as usize).face)),
            };
            self.extraordinary.push(ExtraordinaryCapPlan {
                vertex,
                face,
                scheme: *scheme,
                center: e.center,
                nodes: e.nodes.clone(),
                sectors,
                table: *table,
                level: self.steps.len() as u32,
            });
        }
    }

    /// Covers `roots` (faces of the analysed level) by adaptive refinement
    /// and marks the edges of level-0 patches that finer patches meet.
    fn push_adaptive(
        &mut self,
        base: &TaggedBase,
        roots: &[(u32, FaceChart)],
        cap_face: &[bool],
    ) -> Result<(), MeshError> {
        if roots.is_empty() {
            return Ok(());
        }
        let first = (self.vertices + self.phantoms.len()) as u32;
        let a = adaptive::cover(
            &base.level,
            roots,
            AdaptiveOptions {
                depth: self.options.depth,
                rules: Rules {
                    chaikin: base.chaikin,
                    smooth_triangles: base.smooth_triangles,
                },
                caps: true,
            },
            first,
        )?;
        self.phantoms
            .try_reserve(a.points.rows.len(), a.points.rows.entries())?;
        mem::reserve(&mut self.regular, a.patches.len())?;
        self.phantoms.append(&a.points.rows);
        let edges = &a.edges;
        // Across an edge of the analysed level the refinement is finer
        // only where the face beyond it was refined: both ends are then
        // corners of a refined face (a cheap test that spares most edges
        // the refinement's look-ups).
        let mut refined_corner = mem::filled(self.vertices, false)?;
        for &(f, _) in roots {
            for &v in base.level.face(f as usize) {
                if let Some(t) = refined_corner.get_mut(base.level.point[v as usize] as usize) {
                    *t = true;
                }
            }
        }
        let refined = |p: u32| refined_corner.get(p as usize).copied().unwrap_or(true);
        // Level-0 patches: the analysed face's corners are its grid's inner
        // points.
        for r in self.regular.iter_mut().filter(|r| r.level == 0) {
            let c = [r.gather[5], r.gather[9], r.gather[10], r.gather[6]];
            for k in 0..4 {
                let (x, y) = (c[k], c[(k + 1) % 4]);
                if refined(x) && refined(y) && adaptive::finer_across(&a.points, edges, x, y) {
                    r.finer |= 1 << k;
                }
            }
        }
        for p in a.patches {
            let mut finer = p.finer;
            if p.level == 0 {
                // Across from a cap face: the cap's first ring is finer.
                for k in 0..4 {
                    let (x, y) = (p.corners[k], p.corners[(k + 1) % 4]);
                    if base.edge_faces(x, y).any(|g| cap_face[g]) {
                        finer |= 1 << k;
                    }
                }
            }
            self.regular.push(RegularPlan {
                gather: p.gather,
                chart: p.chart,
                finer,
                level: p.level,
                hole: p.hole,
                hole_point: p.hole_point,
                boundary: 0,
            });
        }
        // A vertex of the analysed level whose cap came a level or more
        // further in has not fallen back.
        let mut capped: Vec<u32> = mem::collect(
            a.caps
                .iter()
                .filter_map(|cap| a.points.vertex_origin(cap.center)),
        )?;
        capped.sort_unstable();
        self.fallbacks
            .retain(|(v, _)| capped.binary_search(v).is_err());
        mem::reserve(&mut self.extraordinary, a.caps.len())?;
        for cap in &a.caps {
            let sectors: Vec<FaceChart> = cap.sectors.iter().flatten().copied().collect();
            let n = sectors.len();
            let origin = a.points.vertex_origin(cap.center);
            // Named by the input vertex it is the child of, else by the
            // input face whose centre (or whose centre's child) it is.
            let vertex = origin.filter(|&v| (v as usize) < self.input_vertices);
            let (scheme, table) = self.options.cap_scheme(n);
            self.extraordinary.push(ExtraordinaryCapPlan {
                vertex,
                face: vertex.is_none().then_some(sectors[0].face),
                scheme,
                center: cap.center,
                nodes: cap.nodes.clone(),
                sectors,
                table,
                level: self.steps.len() as u32 + cap.level,
            });
        }
        mem::reserve(&mut self.last_holes, a.holes.len())?;
        self.last_holes.extend(a.holes.iter().map(|h| h.chart));
        self.hole_conflicts = a.hole_conflicts;
        self.creases_not_edges = base.creases_not_edges;
        self.level_jumps = a.level_jumps;
        mem::reserve(&mut self.uncovered, a.unresolved_faces.len())?;
        for &face in &a.unresolved_faces {
            self.uncovered.push(UncoveredFace {
                face,
                reason: Reason::CrowdedIrregular,
            });
        }
        self.uncovered.sort_by_key(|u| u.face);
        self.uncovered.dedup_by_key(|u| u.face);
        Ok(())
    }

    /// Working-point index of a grid entry: the vertex itself, or a new
    /// phantom point.
    fn point(&mut self, c: &GridPoint) -> u32 {
        match c.as_vertex() {
            Some(v) => v,
            None => self.vertices as u32 + self.phantoms.push_row(c.terms().iter().copied()),
        }
    }

    fn push_polar(&mut self, t: &Topology, c: &PolarConfig, charts: &Charts, pre: u32) {
        let n = c.links[0].len();
        // After refinement, start the columns at a spoke of the input pole
        // (where the input triangle changes), so that column groups of 2^pre
        // fill one input triangle each.
        let c = if pre > 0 {
            let face = |j: usize| charts.get(c.triangles[j] as usize).face;
            let shift = (0..n)
                .find(|&j| face(j) != face((j + n - 1) % n))
                .unwrap_or(0);
            let start = t.outgoing(c.pole as usize).nth(shift);
            polar_config(t, c.pole as usize, start, true).unwrap_or_else(|_| c.clone())
        } else {
            c.clone()
        };
        let mut links = Vec::with_capacity(3 * n);
        links.extend_from_slice(&c.links[0]);
        links.extend_from_slice(&c.links[1]);
        for combo in &c.link3 {
            let p = self.point(combo);
            links.push(p);
        }
        let quads = if pre == 0 {
            c.quads
                .iter()
                .zip(&c.quad_corner)
                .map(|(&f, &k)| {
                    let ch = charts.get(f as usize);
                    FaceChart {
                        face: ch.face,
                        corner: ch.corner,
                        map: ch.map.compose(&Affine::rotation(k as usize)),
                    }
                })
                .collect()
        } else {
            Vec::new()
        };
        self.polar.push(PolarPlan {
            vertex: c.pole,
            pole: c.pole,
            links,
            valence: n,
            first: if pre > 0 {
                FirstStep::Plain
            } else {
                FirstStep::Uniform
            },
            prior_steps: pre,
            triangles: c
                .triangles
                .iter()
                .map(|&f| charts.get(f as usize).face)
                .collect(),
            quads,
        });
    }

    /// Working points evaluation needs: vertices of the analysed level plus
    /// phantoms.
    pub fn working_points(&self) -> usize {
        self.vertices + self.phantoms.len()
    }

    /// Per-vertex data (`primvar[v]` for input vertex `v`: colours, weights,
    /// …) carried to the working points as positions are: through every
    /// refinement step, then the phantom points. `None` unless `primvar` has
    /// one entry per input vertex. The working points' data are what the
    /// patches' control points are made of, as OpenSubdiv's
    /// `Far::PrimvarRefiner` refines primvars with the vertex stencils.
    pub fn refine_primvar<P: Primvar>(&self, primvar: &[P]) -> Option<Vec<P>> {
        if primvar.len() != self.input_vertices {
            return None;
        }
        let mut level: Vec<P> = primvar.to_vec();
        for s in &self.steps {
            let mut next = alloc::vec![P::zero(); s.len()];
            s.apply(&level, &mut next);
            level = next;
        }
        level.truncate(self.vertices);
        level.resize(self.vertices, P::zero());
        let mut phantoms = alloc::vec![P::zero(); self.phantoms.len()];
        self.phantoms.apply_chained(&level, &mut phantoms);
        level.extend(phantoms);
        Some(level)
    }
}

/// Where each face of the analysed level lies in the input: the input's
/// faces themselves until a step refines them (so that a mesh no step
/// refines, the common case, holds no chart per face), then the steps'
/// charts.
enum Charts {
    /// The input's faces (this many), each in its own square.
    Input(usize),
    /// Per face of the refined level.
    Refined(Vec<FaceChart>),
}

impl Charts {
    /// Face `f`'s chart.
    fn get(&self, f: usize) -> FaceChart {
        match self {
            Charts::Input(_) => FaceChart::input(f as u32),
            Charts::Refined(c) => c[f],
        }
    }

    /// Faces of the level.
    fn len(&self) -> usize {
        match self {
            Charts::Input(n) => *n,
            Charts::Refined(c) => c.len(),
        }
    }

    /// The charts as a list (a step's parents), reserved fallibly.
    fn to_vec(&self) -> Result<Vec<FaceChart>, OutOfMemory> {
        mem::collect((0..self.len()).map(|f| self.get(f)))
    }
}

/// Uncovered faces as input faces (each once, first reason), `fixable_only`
/// keeping those refinement can cure.
fn uncovered_list(
    reasons: &[Option<Reason>],
    charts: &Charts,
    fixable_only: bool,
) -> Result<Vec<UncoveredFace>, OutOfMemory> {
    let mut out: Vec<UncoveredFace> = mem::collect(
        reasons
            .iter()
            .enumerate()
            .filter_map(|(f, r)| r.map(|r| (charts.get(f).face, r)))
            .filter(|(_, r)| !fixable_only || r.refinement_helps())
            .map(|(face, reason)| UncoveredFace { face, reason }),
    )?;
    out.sort_by_key(|u| u.face);
    out.dedup_by_key(|u| u.face);
    Ok(out)
}

/// Whether face `f` is clean (no tag reaches it; every face without tags).
fn is_clean(clean: Option<&[bool]>, f: u32) -> bool {
    clean.is_none_or(|c| c.get(f as usize).copied().unwrap_or(false))
}

/// Whether no tag reaches `faces` of `t`: they and every face around their
/// vertices are clean.
fn around_clean(t: &Topology, clean: Option<&[bool]>, faces: &[u32]) -> bool {
    clean.is_none()
        || faces.iter().all(|&f| {
            t.face(f as usize).iter().all(|&v| {
                t.outgoing(v as usize)
                    .all(|h| is_clean(clean, t.face_of(h)))
            })
        })
}

/// The seed a whole-mesh step refines fan `v` with by C²PS (the module
/// doc's rule 4): its links 1 and 2 are there, and no tag reaches its
/// triangles and quads (nor the faces around their vertices, which hold
/// the step's C²PS rows and the next level's configuration).
fn step_seed(t: &Topology, v: usize, clean: Option<&[bool]>) -> Option<PolarSeed> {
    let c = polar_config(t, v, None, false).ok()?;
    if clean.is_some() {
        let faces: Vec<u32> = c.triangles.iter().chain(&c.quads).copied().collect();
        if !around_clean(t, clean, &faces) {
            return None;
        }
    }
    Some(PolarSeed {
        pole: c.pole,
        link1: c.links[0].clone(),
        link2: c.links[1].clone(),
        triangles: c.triangles,
        quads: c.quads,
    })
}

/// Classifies every face of one level.
fn analyse(
    t: &Topology,
    options: &PlanOptions<'_>,
    clean: Option<&[bool]>,
) -> Result<Pass, MeshError> {
    let nf = t.num_faces();
    // A cap needs its faces and the faces around their vertices clean; a
    // regular face itself.
    let is_clean = |f: u32| is_clean(clean, f);
    let around_clean = |faces: &[u32]| around_clean(t, clean, faces);
    let mut owner: Vec<Option<Reason>> = mem::filled(nf, None)?;
    let mut covered = mem::filled(nf, false)?;
    let mut pass = Pass {
        // At most one regular patch per face.
        regular: mem::with_capacity(nf)?,
        phantom_grids: Vec::new(),
        polar: Vec::new(),
        extraordinary: Vec::new(),
        uncovered: Vec::new(),
        fallbacks: Vec::new(),
    };
    // Per vertex: the reason its cap failed (for the faces around it).
    let mut vertex_reason: Vec<Option<Reason>> = mem::filled(t.num_vertices(), None)?;
    let claim = |faces: &[u32], covered: &mut Vec<bool>| -> bool {
        if faces.iter().any(|&f| covered[f as usize]) {
            return false;
        }
        for &f in faces {
            covered[f as usize] = true;
        }
        true
    };
    #[allow(clippy::needless_range_loop)] // v is a vertex id, not only an index
    for v in 0..t.num_vertices() {
        if t.vertex_first(v) == NONE {
            continue;
        }
        if !options.catmull_clark && is_fan(t, v) {
            match polar_config(t, v, None, true) {
                Ok(c) => {
                    let faces: Vec<u32> = c.triangles.iter().chain(&c.quads).copied().collect();
                    if !around_clean(&faces) {
                        vertex_reason[v] = Some(Reason::Feature);
                    } else if claim(&faces, &mut covered) {
                        pass.polar.push(c);
                    } else {
                        vertex_reason[v] = Some(Reason::Overlap);
                    }
                }
                // A tag reaching links 1 and 2 stops the cap, whatever
                // further out is missing.
                Err(Reason::PolarIncomplete)
                    if clean.is_some() && polar_config(t, v, None, false).is_ok() =>
                {
                    vertex_reason[v] = Some(match step_seed(t, v, clean) {
                        Some(_) => Reason::PolarIncomplete,
                        None => Reason::Feature,
                    });
                }
                Err(r) => vertex_reason[v] = Some(r),
            }
            continue;
        }
        let all_quads = t
            .outgoing(v)
            .all(|h| t.face_len(t.face_of(h) as usize) == 4);
        let n = t.vertex_face_count(v);
        if !all_quads || n == 4 && !t.is_boundary(v) {
            continue;
        }
        if t.is_boundary(v) {
            if n > 2 {
                vertex_reason[v] = Some(Reason::Boundary);
            }
            continue;
        }
        if n < 3 {
            vertex_reason[v] = Some(Reason::ValenceTwo);
            continue;
        }
        match extraordinary_config(t, v) {
            Ok(e) => {
                let faces: Vec<u32> = e.sectors.iter().map(|&(f, _)| f).collect();
                if !around_clean(&faces) {
                    vertex_reason[v] = Some(Reason::Feature);
                    continue;
                }
                if !claim(&faces, &mut covered) {
                    vertex_reason[v] = Some(Reason::Overlap);
                    continue;
                }
                let (scheme, table) = options.cap_scheme(n);
                pass.extraordinary.push((e, scheme, table));
            }
            Err(r) => vertex_reason[v] = Some(r),
        }
    }
    for f in 0..nf {
        if covered[f] {
            continue;
        }
        if !is_clean(f as u32) {
            owner[f] = Some(Reason::Feature);
            continue;
        }
        // A grid of phantom points gets its gather in the plan (which
        // makes the points).
        let gather = match interior_face_grid(t, f) {
            Some(g) => Some(core::array::from_fn(|k| g[k / 4][k % 4])),
            None => match face_grid(t, f) {
                Some(g) => {
                    let at = pass.regular.len() as u32;
                    mem::push(&mut pass.phantom_grids, (at, Box::new(g)))?;
                    Some([NONE; 16])
                }
                None => None,
            },
        };
        if let Some(gather) = gather {
            pass.regular.push(RegularPlan {
                gather,
                chart: FaceChart::input(f as u32),
                finer: 0,
                level: 0,
                hole: 0,
                hole_point: 0,
                boundary: 0,
            });
            covered[f] = true;
            continue;
        }
        // Why not: the worst reason among its corners, else by its shape.
        let corner_reason = t
            .face(f)
            .iter()
            .filter_map(|&v| vertex_reason[v as usize])
            .max();
        let boundary = t.face(f).iter().any(|&v| {
            let v = v as usize;
            t.is_boundary(v) && (t.vertex_face_count(v) > 2 || vertex_reason[v].is_some())
        });
        owner[f] = Some(if t.face_len(f) != 4 {
            corner_reason.unwrap_or(Reason::NotQuad)
        } else if boundary {
            Reason::Boundary
        } else {
            corner_reason.unwrap_or(Reason::CrowdedIrregular)
        });
    }
    pass.uncovered = owner;
    pass.fallbacks = vertex_reason
        .iter()
        .enumerate()
        .filter_map(|(v, r)| r.map(|r| (v as u32, r)))
        .collect();
    Ok(pass)
}

/// OpenSubdiv's refusals, in this order: no faces or vertices, more than
/// 2³¹ items, a non-finite coordinate, then per face fewer than 3 vertices or
/// an index out of range, then tags naming a vertex or face that does not
/// exist. A face may list a vertex more than once, as OpenSubdiv's may (the
/// base level makes its edges as OpenSubdiv does,
/// [`crate::adaptive::level::Level::new`]).
fn validate(mesh: &MeshInput) -> Result<(), MeshError> {
    check_sizes_and_positions(mesh)?;
    mesh.check_uvs()?;
    let nv = mesh.vertices.len();
    let nf = mesh.faces.len();
    for (face, f) in mesh.faces.iter().enumerate() {
        if f.len() < 3 {
            return Err(MeshError::FaceTooSmall { face, len: f.len() });
        }
        if let Some(&index) = f.iter().find(|&&v| v as usize >= nv) {
            return Err(MeshError::IndexOutOfRange {
                face,
                index: i64::from(index),
                vertices: nv,
            });
        }
    }
    let tags = &mesh.tags;
    let bad_vertex = tags
        .creases
        .iter()
        .flat_map(|c| c.vertices)
        .chain(tags.corners.iter().map(|c| c.vertex))
        .find(|&v| v as usize >= nv);
    if let Some(v) = bad_vertex {
        return Err(MeshError::TagOutOfRange {
            what: "vertex",
            index: v as usize,
            count: nv,
        });
    }
    if let Some(&f) = tags.holes.iter().find(|&&f| f as usize >= nf) {
        return Err(MeshError::TagOutOfRange {
            what: "face",
            index: f as usize,
            count: nf,
        });
    }
    Ok(())
}
