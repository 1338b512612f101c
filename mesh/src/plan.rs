//! `SurfacePlan`: the analysis of a mesh's topology, done once — which faces
//! are regular, which vertices get which cap, the gather indices of every
//! patch and cap, and the refinement step when the mesh needs one. Positions
//! play no part; [`crate::evaluate`] runs the plan on positions.
//!
//! Coverage rules (issue 7):
//! 1. a regular face (a quad with four regular corners, its 4×4 neighbourhood
//!    a grid, phantom points at a boundary) is a uniform bicubic B-spline
//!    patch;
//! 2. a polar configuration (a fan of triangles ringed by three rings of
//!    regular quads, spec C2PS.md §1) is a C²PS cap over its triangles and
//!    the quads between links 1 and 2 (its level-0 ring and outer region are
//!    the regular faces around it);
//! 3. an extraordinary point (interior, valence n ≠ 4, quads around, 1-ring
//!    regular: its c-net exists, spec EG.md §1) is an EG cap for n = 3, 5 and
//!    for n = 6..10 with a rule table, else a Catmull-Clark cap, over its n
//!    faces;
//! 4. anything else is uncovered. When a reason for that can be cured by
//!    refinement, the whole mesh is refined once (Catmull-Clark, C²PS at
//!    poles) and analysed again — at most [`MAX_STEPS`] times: one step
//!    makes every face a quad and separates extraordinary points, but a quad
//!    can then hold two of them at opposite corners (an old vertex and the
//!    centre of a non-quad face), which a second step separates.
//!
//! With [`PlanOptions::catmull_clark`] every cap is a Catmull-Clark cap (the
//! papers' baseline): rule 2 is skipped (a fan's triangles are non-quad faces,
//! refined by a Catmull-Clark step; the pole becomes an extraordinary point of
//! the same valence) and rule 3 always picks Catmull-Clark.

use crate::caps::{ev_config, is_fan, polar_config, EvConfig, PolarConfig, Reason};
use crate::chart::{Affine, FaceChart};
use crate::error::MeshError;
use crate::grid::{face_grid, Combo};
use crate::refine::{refine, PolarSeed};
use crate::stencil::StencilTable;
use crate::topology::{Topology, NONE};
use alloc::vec;
use alloc::vec::Vec;
use capdiv::eg::RuleTable;
use capdiv::FirstStep;

/// At most this many refinement steps before the analysis gives up on a face.
pub const MAX_STEPS: u32 = 2;

/// The cap scheme at a vertex.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Scheme {
    /// C²PS (spec C2PS.md).
    C2ps,
    /// Evolving Guide (spec EG.md).
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
    /// Bit `k`: the face across the face's edge `k` (corner k → k+1) is a cap
    /// face (two ring patches of half the size meet that edge).
    pub finer: u8,
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
    /// Refinement steps the pole has had (the cap's level-0 unit is `2^-pre`
    /// of the input's).
    pub pre: u32,
    /// Per cap column at the analysed level: the input triangle it lies in.
    pub triangles: Vec<u32>,
    /// With `pre = 0`, per column: the quad between links 1 and 2 and its
    /// map from polar coordinates `(r − 1, τn − j)` to its own square.
    pub quads: Vec<FaceChart>,
}

/// An EG or Catmull-Clark cap.
#[derive(Clone, Debug, PartialEq)]
pub struct EvPlan {
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
    pub ev: Vec<EvPlan>,
    /// Faces left without a patch (input faces, each once).
    pub uncovered: Vec<UncoveredFace>,
    /// Input faces whose neighbourhood made the refinement step necessary,
    /// with the first reason found.
    pub needed_refinement: Vec<UncoveredFace>,
    /// Options.
    pub options: PlanOptions<'t>,
}

/// One analysis pass on one level.
struct Pass {
    regular: Vec<(u32, [[Combo; 4]; 4], u8)>,
    polar: Vec<PolarConfig>,
    ev: Vec<(EvConfig, Scheme, Option<usize>)>,
    /// Per face of the level: the reason it is uncovered, if it is.
    uncovered: Vec<Option<Reason>>,
}

impl<'t> SurfacePlan<'t> {
    /// Analyses a validated mesh.
    pub fn new(topo: &Topology, options: PlanOptions<'t>) -> Result<Self, MeshError> {
        let mut level_topo = topo.clone();
        let mut charts: Vec<FaceChart> =
            (0..topo.num_faces() as u32).map(FaceChart::input).collect();
        let mut steps = Vec::new();
        let mut needed = Vec::new();
        // Per vertex at the current level: has it been a C²PS pole (refined by
        // the step), and how often.
        let mut pole_steps: Vec<u32> = vec![0; topo.num_vertices()];
        let mut pass = analyse(&level_topo, &options);
        while (steps.len() as u32) < MAX_STEPS
            && pass
                .uncovered
                .iter()
                .flatten()
                .any(|r| r.refinement_helps())
        {
            if steps.is_empty() {
                needed = uncovered_list(&pass.uncovered, &charts, true);
            }
            let seeds: Vec<PolarSeed> = (0..level_topo.num_vertices())
                .filter(|&v| !options.catmull_clark && is_fan(&level_topo, v))
                .filter_map(|v| polar_config(&level_topo, v, None, false).ok())
                .map(|c| PolarSeed {
                    pole: c.pole,
                    link1: c.links[0].clone(),
                    link2: c.links[1].clone(),
                    triangles: c.triangles.clone(),
                    quads: c.quads.clone(),
                })
                .collect();
            let refined = refine(&level_topo, &charts, &seeds);
            let mut new_pole_steps = vec![0; refined.num_vertices];
            for (seed, &p) in seeds.iter().zip(&refined.poles) {
                new_pole_steps[p as usize] = pole_steps[seed.pole as usize] + 1;
            }
            level_topo = Topology::from_faces(refined.num_vertices, &refined.faces)?;
            charts = refined.charts;
            steps.push(refined.stencils);
            pole_steps = new_pole_steps;
            pass = analyse(&level_topo, &options);
        }
        let mut plan = SurfacePlan {
            input_vertices: topo.num_vertices(),
            input_faces: topo.num_faces(),
            steps,
            vertices: level_topo.num_vertices(),
            phantoms: StencilTable::new(),
            regular: Vec::new(),
            polar: Vec::new(),
            ev: Vec::new(),
            uncovered: uncovered_list(&pass.uncovered, &charts, false),
            needed_refinement: needed,
            options,
        };
        let input_vertex = |v: u32| (v < topo.num_vertices() as u32).then_some(v);
        let cap_face: Vec<bool> = {
            let mut c = vec![false; level_topo.num_faces()];
            for p in &pass.polar {
                for &f in p.triangles.iter().chain(&p.quads) {
                    c[f as usize] = true;
                }
            }
            for (e, _, _) in &pass.ev {
                for &(f, _) in &e.sectors {
                    c[f as usize] = true;
                }
            }
            c
        };
        for (f, grid, _) in &pass.regular {
            let f = *f as usize;
            let mut gather = [0u32; 16];
            for i in 0..4 {
                for j in 0..4 {
                    gather[4 * i + j] = plan.point(&grid[i][j]);
                }
            }
            let mut finer = 0u8;
            for k in 0..4 {
                let tw = level_topo.twin(level_topo.face_half_edge(f, k));
                if tw != NONE && cap_face[level_topo.face_of(tw) as usize] {
                    finer |= 1 << k;
                }
            }
            plan.regular.push(RegularPlan {
                gather,
                chart: charts[f],
                finer,
            });
        }
        for c in &pass.polar {
            plan.push_polar(&level_topo, c, &charts, pole_steps[c.pole as usize]);
        }
        for (e, scheme, table) in &pass.ev {
            let sectors = e
                .sectors
                .iter()
                .map(|&(f, k)| {
                    let ch = charts[f as usize];
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
                None => (None, Some(charts[e.sectors[0].0 as usize].face)),
            };
            plan.ev.push(EvPlan {
                vertex,
                face,
                scheme: *scheme,
                center: e.center,
                nodes: e.nodes.clone(),
                sectors,
                table: *table,
            });
        }
        Ok(plan)
    }

    /// Working-point index of a grid entry: the vertex itself, or a new
    /// phantom point.
    fn point(&mut self, c: &Combo) -> u32 {
        match c.as_vertex() {
            Some(v) => v,
            None => self.vertices as u32 + self.phantoms.push_row(c.terms().iter().copied()),
        }
    }

    fn push_polar(&mut self, t: &Topology, c: &PolarConfig, charts: &[FaceChart], pre: u32) {
        let n = c.links[0].len();
        // After refinement, start the columns at a spoke of the input pole
        // (where the input triangle changes), so that column groups of 2^pre
        // fill one input triangle each.
        let c = if pre > 0 {
            let face = |j: usize| charts[c.triangles[j] as usize].face;
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
                    let ch = charts[f as usize];
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
            pre,
            triangles: c
                .triangles
                .iter()
                .map(|&f| charts[f as usize].face)
                .collect(),
            quads,
        });
    }

    /// Working points evaluation needs: vertices of the analysed level plus
    /// phantoms.
    pub fn working_points(&self) -> usize {
        self.vertices + self.phantoms.len()
    }
}

/// Uncovered faces as input faces (each once, first reason), `fixable_only`
/// keeping those refinement can cure.
fn uncovered_list(
    reasons: &[Option<Reason>],
    charts: &[FaceChart],
    fixable_only: bool,
) -> Vec<UncoveredFace> {
    let mut out: Vec<UncoveredFace> = reasons
        .iter()
        .enumerate()
        .filter_map(|(f, r)| r.map(|r| (charts[f].face, r)))
        .filter(|(_, r)| !fixable_only || r.refinement_helps())
        .map(|(face, reason)| UncoveredFace { face, reason })
        .collect();
    out.sort_by_key(|u| u.face);
    out.dedup_by_key(|u| u.face);
    out
}

/// Classifies every face of one level.
fn analyse(t: &Topology, options: &PlanOptions<'_>) -> Pass {
    let nf = t.num_faces();
    let mut owner: Vec<Option<Reason>> = vec![None; nf];
    let mut covered = vec![false; nf];
    let mut pass = Pass {
        regular: Vec::new(),
        polar: Vec::new(),
        ev: Vec::new(),
        uncovered: Vec::new(),
    };
    // Per vertex: the reason its cap failed (for the faces around it).
    let mut vertex_reason: Vec<Option<Reason>> = vec![None; t.num_vertices()];
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
                    if claim(&faces, &mut covered) {
                        pass.polar.push(c);
                    } else {
                        vertex_reason[v] = Some(Reason::Overlap);
                    }
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
        match ev_config(t, v) {
            Ok(e) => {
                let faces: Vec<u32> = e.sectors.iter().map(|&(f, _)| f).collect();
                if !claim(&faces, &mut covered) {
                    vertex_reason[v] = Some(Reason::Overlap);
                    continue;
                }
                let (scheme, table) = match n {
                    _ if options.catmull_clark => (Scheme::CatmullClark, None),
                    3 | 5 => (Scheme::Eg, None),
                    6..=10 => match options.eg_tables.iter().position(|t| t.valence() == n) {
                        Some(i) => (Scheme::Eg, Some(i)),
                        None => (Scheme::CatmullClark, None),
                    },
                    _ => (Scheme::CatmullClark, None),
                };
                pass.ev.push((e, scheme, table));
            }
            Err(r) => vertex_reason[v] = Some(r),
        }
    }
    for f in 0..nf {
        if covered[f] {
            continue;
        }
        if let Some(grid) = face_grid(t, f) {
            pass.regular.push((f as u32, grid, 0));
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
    pass
}
