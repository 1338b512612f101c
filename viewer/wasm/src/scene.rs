//! One mesh on the page: its topology analysed once ([`SurfacePlan`]), an
//! [`Evaluator`] sized for it, and the current positions. An edit of a
//! control point re-runs only the evaluate-only path — `Evaluator::evaluate`
//! on the same plan, then the per-vertex tessellation and paint — never the
//! analysis. Options (depth, scheme, grid) make a new plan.

use crate::paint::{self, Mode, Paint};
use crate::tess::{Surface, Tessellator};
use capdiv_mesh::shade::HighlightLines;
use capdiv_mesh::{Evaluator, MeshInput, PlanOptions, SurfacePlan, Topology};
use std::fmt::Write;

/// Deepest cap depth the page offers.
pub const MAX_DEPTH: u32 = 7;
/// Largest grid (segments per side of the coarsest patches).
pub const MAX_GRID: usize = 32;

/// What the page chooses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// Rings per cap (1..=[`MAX_DEPTH`]).
    pub depth: u32,
    /// Catmull-Clark caps everywhere instead of C²PS and EG.
    pub catmull_clark: bool,
    /// Segments per side of the coarsest patches: a power of two up to
    /// [`MAX_GRID`], or 0 for [`auto_grid`].
    pub grid: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            depth: 4,
            catmull_clark: false,
            grid: 0,
        }
    }
}

/// The mesh crate's options for `o`, or why they cannot be had.
pub fn plan_options(o: &Options) -> Result<PlanOptions<'static>, String> {
    if !(1..=MAX_DEPTH).contains(&o.depth) {
        return Err(format!(
            "depth {}: the viewer offers 1..={MAX_DEPTH}",
            o.depth
        ));
    }
    if o.grid != 0 && (!o.grid.is_power_of_two() || o.grid > MAX_GRID) {
        return Err(format!(
            "grid {}: a power of two up to {MAX_GRID}, or 0 (automatic)",
            o.grid
        ));
    }
    Ok(PlanOptions {
        depth: o.depth,
        catmull_clark: o.catmull_clark,
        ..PlanOptions::default()
    })
}

/// What [`auto_grid`] keeps its estimate of the surface's vertices under.
pub const VERTEX_BUDGET: usize = 40_000;

/// The grid for `plan` when the page leaves it to the viewer: the largest of
/// 8, 4, 2 with `(regular + 2·caps)·(g + 1)² ≤` [`VERTEX_BUDGET`], else 1 —
/// `regular` the regular patches, `caps` the caps' sectors (their rings,
/// halving in size and in grid, add about two coarse patches per sector at
/// depth 4).
pub fn auto_grid(plan: &SurfacePlan<'_>) -> usize {
    let caps = plan.polar.iter().map(|p| p.valence).sum::<usize>()
        + plan.ev.iter().map(|e| e.sectors.len()).sum::<usize>();
    let coarse = plan.regular.len() + 2 * caps;
    [8, 4, 2]
        .into_iter()
        .find(|g| coarse * (g + 1) * (g + 1) <= VERTEX_BUDGET)
        .unwrap_or(1)
}

/// The plan and evaluator of one option set.
struct Analysis {
    plan: SurfacePlan<'static>,
    evaluator: Evaluator<f64>,
    grid: usize,
}

impl Analysis {
    fn new(topo: &Topology, o: &Options) -> Result<Self, String> {
        let plan = SurfacePlan::new(topo, plan_options(o)?).map_err(|e| e.to_string())?;
        let evaluator = Evaluator::new(&plan).map_err(|e| e.to_string())?;
        let grid = if o.grid == 0 {
            auto_grid(&plan)
        } else {
            o.grid
        };
        Ok(Analysis {
            plan,
            evaluator,
            grid,
        })
    }
}

/// A mesh being viewed.
pub struct Scene {
    name: String,
    mesh: MeshInput,
    topo: Topology,
    analysis: Analysis,
    options: Options,
    positions: Vec<[f64; 3]>,
    tess: Tessellator,
    /// The plan changed since the last evaluation.
    new_plan: bool,
    /// Its GPU attributes under the current shading.
    pub paint: Paint,
    mode: Mode,
    scale: f64,
    lines: Option<HighlightLines>,
    /// Edges of the control mesh (pairs of vertex indices, each once).
    pub edges: Vec<u32>,
}

impl Scene {
    /// Validates, analyses and evaluates `mesh`. `Err`: the page's message.
    pub fn new(name: &str, mesh: MeshInput, options: Options, mode: Mode) -> Result<Self, String> {
        let topo = Topology::new(&mesh).map_err(|e| e.to_string())?;
        let analysis = Analysis::new(&topo, &options)?;
        let positions = mesh.vertices.clone();
        let mut edges: Vec<(u32, u32)> = mesh
            .faces
            .iter()
            .flat_map(|f| {
                (0..f.len()).map(move |k| {
                    let (a, b) = (f[k], f[(k + 1) % f.len()]);
                    (a.min(b), a.max(b))
                })
            })
            .collect();
        edges.sort_unstable();
        edges.dedup();
        let mut scene = Scene {
            name: name.into(),
            mesh,
            topo,
            analysis,
            options,
            positions,
            tess: Tessellator::default(),
            new_plan: true,
            paint: Paint::default(),
            mode,
            scale: 1.0,
            lines: None,
            edges: edges.into_iter().flat_map(|(a, b)| [a, b]).collect(),
        };
        scene.evaluate()?;
        scene.rescale();
        Ok(scene)
    }

    /// Evaluates the current positions through the plan and samples the
    /// patches that changed (all of them after a new plan; no paint).
    fn evaluate(&mut self) -> Result<(), String> {
        let a = &mut self.analysis;
        let base = a.plan.steps.len() as u32;
        let mut rebuild = self.new_plan;
        loop {
            self.tess.begin(rebuild, base, a.grid);
            let r = a
                .evaluator
                .evaluate(&a.plan, &self.positions, &mut self.tess);
            if let Err(e) = r {
                // Partly re-sampled: the next evaluation starts afresh.
                self.new_plan = true;
                return Err(e.to_string());
            }
            if self.tess.finish() {
                break;
            }
            rebuild = true;
        }
        self.new_plan = false;
        Ok(())
    }

    /// The sampled surface.
    pub fn surface(&self) -> &Surface {
        &self.tess.surface
    }

    /// Vertices rewritten by the last edit (`first..end`; the whole surface
    /// after a load, new options or shading).
    pub fn dirty(&self) -> (usize, usize) {
        self.tess.dirty
    }

    /// Paints the dirty vertices.
    fn repaint(&mut self) {
        paint::paint_range(
            &self.tess.surface,
            self.mode,
            self.scale,
            self.lines.as_ref(),
            self.tess.dirty,
            &mut self.paint,
        );
    }

    /// New options: a new plan. On error the scene is unchanged.
    pub fn set_options(&mut self, options: Options) -> Result<(), String> {
        let analysis = Analysis::new(&self.topo, &options)?;
        let old = std::mem::replace(&mut self.analysis, analysis);
        let old_options = std::mem::replace(&mut self.options, options);
        self.new_plan = true;
        if let Err(e) = self.evaluate() {
            self.analysis = old;
            self.options = old_options;
            self.new_plan = true;
            self.evaluate()?;
            return Err(e);
        }
        self.rescale();
        Ok(())
    }

    /// Moves control point `vertex` to `p` and re-evaluates (the edit path:
    /// evaluate, sample, paint; the colour scale and light lines stay as
    /// they are until [`Scene::rescale`]). On error the point stays where it
    /// was.
    pub fn move_vertex(&mut self, vertex: usize, p: [f64; 3]) -> Result<(), String> {
        let Some(old) = self.positions.get(vertex).copied() else {
            return Err(format!(
                "vertex {vertex}: the mesh has {}",
                self.positions.len()
            ));
        };
        self.positions[vertex] = p;
        if let Err(e) = self.evaluate() {
            self.positions[vertex] = old;
            self.evaluate()?;
            return Err(e);
        }
        self.repaint();
        Ok(())
    }

    /// Shading `mode`, its colour scale recomputed.
    pub fn set_mode(&mut self, mode: Mode) {
        self.mode = mode;
        self.rescale();
    }

    /// Recomputes the colour scale and the light lines for the current
    /// surface, and repaints.
    pub fn rescale(&mut self) {
        let s = &self.tess.surface;
        self.scale = paint::scale(s, self.mode);
        self.lines = paint::lines(s.lo, s.hi);
        self.tess.dirty = (0, s.len());
        self.repaint();
    }

    /// Current control-point positions.
    pub fn positions(&self) -> &[[f64; 3]] {
        &self.positions
    }

    /// Current colour scale `m` (the map spans `[−m, m]`).
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Current options.
    pub fn options(&self) -> Options {
        self.options
    }

    /// The grid in use (the automatic one when the options say 0).
    pub fn grid(&self) -> usize {
        self.analysis.grid
    }

    /// Puts the control points back where the file had them.
    pub fn reset_positions(&mut self) -> Result<(), String> {
        self.positions.clone_from(&self.mesh.vertices);
        self.evaluate()?;
        self.rescale();
        Ok(())
    }

    /// One line of JSON about the scene for the page's status line.
    pub fn summary(&self) -> String {
        let plan = &self.analysis.plan;
        let kinds = self.tess.kinds;
        let mut caps: Vec<(&str, usize, usize)> = Vec::new();
        for c in &self.tess.caps {
            match caps
                .iter_mut()
                .find(|k| k.0 == c.scheme.id() && k.1 == c.valence)
            {
                Some(k) => k.2 += 1,
                None => caps.push((c.scheme.id(), c.valence, 1)),
            }
        }
        caps.sort();
        let mut s = String::new();
        let _ = write!(
            s,
            "{{\"name\":{},\"vertices\":{},\"faces\":{},\"refinement_steps\":{},\"uncovered_faces\":{},\
             \"patches\":{{\"regular\":{},\"polar\":{},\"eg\":{},\"catmull-clark\":{}}},\"caps\":[",
            json_string(&self.name),
            self.mesh.vertices.len(),
            self.mesh.faces.len(),
            plan.steps.len(),
            plan.uncovered.len(),
            kinds[0],
            kinds[1],
            kinds[2],
            kinds[3]
        );
        for (i, (scheme, valence, count)) in caps.iter().enumerate() {
            let sep = if i > 0 { "," } else { "" };
            let _ = write!(
                s,
                "{sep}{{\"scheme\":\"{scheme}\",\"valence\":{valence},\"count\":{count}}}"
            );
        }
        let _ = write!(
            s,
            "],\"grid\":{},\"surface_vertices\":{},\"triangles\":{},\"scale\":{}}}",
            self.analysis.grid,
            self.tess.surface.len(),
            self.tess.surface.indices.len() / 3,
            if self.scale.is_finite() {
                self.scale
            } else {
                0.0
            }
        );
        s
    }
}

/// A JSON string literal.
fn json_string(s: &str) -> String {
    serde_json::Value::String(s.into()).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::samples::SAMPLES;
    use crate::tess::HOLE;

    fn scene(name: &str, depth: u32) -> Scene {
        let s = crate::samples::by_name(name).unwrap();
        let o = Options {
            depth,
            ..Options::default()
        };
        Scene::new(name, (s.build)(), o, Mode::Plain).unwrap()
    }

    #[test]
    fn every_sample_gives_a_finite_surface() {
        for s in SAMPLES {
            let sc = Scene::new(s.name, (s.build)(), Options::default(), Mode::Gaussian)
                .unwrap_or_else(|e| panic!("{}: {e}", s.name));
            assert!(sc.surface().len() > 100, "{}", s.name);
            assert!(sc.paint.positions.iter().all(|c| c.is_finite()));
            assert!(sc.scale().is_finite() && sc.scale() > 0.0);
            let n = sc.surface().len() as u32;
            assert!(sc.surface().indices.iter().all(|&i| i < n));
            let v: serde_json::Value = serde_json::from_str(&sc.summary()).unwrap();
            assert_eq!(v["name"], s.name);
        }
    }

    #[test]
    fn an_edit_moves_the_surface_near_the_point_and_keeps_the_layout() {
        let mut sc = scene("globe", 3);
        let before = sc.surface().clone();
        // The north pole (valence 8) is the last vertex of the globe? Take
        // the vertex of largest z.
        let v = (0..sc.positions().len())
            .max_by(|&a, &b| sc.positions()[a][2].total_cmp(&sc.positions()[b][2]))
            .unwrap();
        let p = sc.positions()[v];
        sc.move_vertex(v, [p[0], p[1], p[2] + 0.5]).unwrap();
        let after = sc.surface();
        assert_eq!(after.len(), before.len());
        assert_eq!(after.indices, before.indices);
        // The top rose, the bottom (beyond the pole's support) did not.
        assert!(after.hi[2] > before.hi[2] + 0.1);
        assert_eq!(after.lo[2], before.lo[2]);
        let moved = (0..after.len())
            .filter(|&i| after.position[i] != before.position[i])
            .count();
        assert!(moved > 0 && moved < after.len() / 2, "{moved}");
        // Moving it back gives the same surface bit for bit.
        sc.move_vertex(v, p).unwrap();
        assert_eq!(sc.surface().position, before.position);
    }

    #[test]
    fn an_edit_resamples_only_moved_patches_and_equals_a_fresh_build() {
        for name in [
            "hand",
            "rounded-cube",
            "triangle-and-pentagon",
            "extraordinary-disk-7",
        ] {
            let mut sc = scene(name, 3);
            let n = sc.surface().len();
            let mut mesh = sc.mesh.clone();
            let v = mesh.vertices.len() / 2;
            mesh.vertices[v][2] += 0.25;
            sc.move_vertex(v, mesh.vertices[v]).unwrap();
            let (a, b) = sc.dirty();
            assert!(a < b && b <= n, "{name}: {a}..{b} of {n}");
            if name == "hand" {
                // 549 control points: one moves a small part.
                assert!(b - a < n / 2, "{name}: {a}..{b} of {n}");
            }
            let o = sc.options();
            let fresh = Scene::new(name, mesh, o, Mode::Plain).unwrap();
            let (x, y) = (sc.surface(), fresh.surface());
            assert_eq!(x.position, y.position, "{name}");
            assert_eq!(x.normal, y.normal, "{name}");
            assert_eq!(x.flags, y.flags, "{name}");
            assert_eq!(x.indices, y.indices, "{name}");
            assert_eq!((x.lo, x.hi), (y.lo, y.hi), "{name}");
            let same =
                |p: &[f64], q: &[f64]| p.iter().zip(q).all(|(s, t)| s.to_bits() == t.to_bits());
            assert!(
                same(&x.gaussian, &y.gaussian) && same(&x.mean, &y.mean),
                "{name}"
            );
            assert_eq!(sc.paint.positions, fresh.paint.positions, "{name}");
        }
    }

    /// The samples welded by position (tolerance 1e-9 of the box) and the
    /// triangles on the welded vertices, degenerate ones dropped.
    fn welded(sc: &Scene) -> Vec<capdiv_mesh::tessellate::Face> {
        use capdiv::Point3;
        use capdiv_mesh::tessellate::{weld::representatives, Face};
        let s = sc.surface();
        let size = (0..3).map(|c| s.hi[c] - s.lo[c]).fold(0.0, f64::max);
        let points: Vec<Point3<f64>> = s.position.iter().map(|&p| Point3(p)).collect();
        let rep = representatives(&points, 1e-9 * size);
        s.indices
            .chunks(3)
            .map(|t| [rep[t[0] as usize], rep[t[1] as usize], rep[t[2] as usize]])
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[2] != t[0])
            .map(Face::Tri)
            .collect()
    }

    #[test]
    fn closed_samples_give_closed_oriented_triangles_at_every_grid() {
        use capdiv_mesh::tessellate::is_closed_and_oriented;
        let mut cases: Vec<(&str, usize, bool)> = Vec::new();
        for name in ["mushroom", "globe", "rounded-cube", "cube", "torus"] {
            cases.extend([(name, 1, false), (name, 8, false), (name, 1, true)]);
        }
        cases.extend([("hand", 2, false), ("hand", 1, true)]);
        for (name, grid, catmull_clark) in cases {
            let s = crate::samples::by_name(name).unwrap();
            let o = Options {
                depth: 3,
                grid,
                catmull_clark,
            };
            let sc = Scene::new(name, (s.build)(), o, Mode::Plain).unwrap();
            let faces = welded(&sc);
            assert!(
                is_closed_and_oriented(&faces).is_ok(),
                "{name} grid {grid} cc {catmull_clark}: {:?}",
                is_closed_and_oriented(&faces)
            );
        }
    }

    #[test]
    fn bad_edits_and_options_leave_the_scene_as_it_was() {
        let mut sc = scene("rounded-cube", 2);
        let before = sc.surface().position.clone();
        assert!(sc.move_vertex(1 << 30, [0.0; 3]).is_err());
        assert!(sc.move_vertex(0, [f64::NAN, 0.0, 0.0]).is_err());
        assert_eq!(sc.surface().position, before);
        assert_eq!(sc.positions()[0], sc.mesh.vertices[0]);
        for bad in [
            Options {
                depth: 0,
                ..sc.options()
            },
            Options {
                depth: MAX_DEPTH + 1,
                ..sc.options()
            },
            Options {
                grid: 3,
                ..sc.options()
            },
            Options {
                grid: 64,
                ..sc.options()
            },
        ] {
            assert!(sc.set_options(bad).is_err(), "{bad:?}");
            assert_eq!(sc.surface().position, before);
            assert_eq!(sc.options().depth, 2);
        }
    }

    #[test]
    fn deeper_caps_add_rings_and_a_smaller_hole() {
        let mut sc = scene("mushroom", 1);
        let hole_extent = |s: &Surface| s.flags.iter().filter(|&&f| f & HOLE != 0).count();
        let (n1, h1) = (sc.surface().len(), hole_extent(sc.surface()));
        sc.set_options(Options {
            depth: 4,
            ..sc.options()
        })
        .unwrap();
        assert!(sc.surface().len() > n1);
        // Deeper rings have more columns (C²PS doubles the valence) but one
        // segment each once the grid is used up: the hole fans are made of
        // more, smaller triangles.
        assert!(hole_extent(sc.surface()) > h1);
        let v: serde_json::Value = serde_json::from_str(&sc.summary()).unwrap();
        assert_eq!(v["caps"][0]["scheme"], "c2ps");
        assert_eq!(v["caps"][0]["valence"], 12);
        assert_eq!(v["caps"][0]["count"], 2);
    }

    #[test]
    fn the_catmull_clark_scheme_replaces_every_cap() {
        for name in ["mushroom", "rounded-cube", "hand"] {
            let mut sc = scene(name, 3);
            sc.set_options(Options {
                catmull_clark: true,
                ..sc.options()
            })
            .unwrap();
            let v: serde_json::Value = serde_json::from_str(&sc.summary()).unwrap();
            assert_eq!(v["patches"]["polar"], 0, "{name}");
            assert_eq!(v["patches"]["eg"], 0, "{name}");
            assert!(
                v["patches"]["catmull-clark"].as_u64().unwrap() > 0,
                "{name}"
            );
            let caps = v["caps"].as_array().unwrap();
            assert!(
                caps.iter().all(|c| c["scheme"] == "catmull-clark"),
                "{name}"
            );
            assert!(sc
                .surface()
                .position
                .iter()
                .flatten()
                .all(|c| c.is_finite()));
        }
    }

    #[test]
    fn reset_puts_the_points_back() {
        let mut sc = scene("torus", 2);
        let before = sc.surface().position.clone();
        sc.move_vertex(3, [5.0, 5.0, 5.0]).unwrap();
        assert_ne!(sc.surface().position, before);
        sc.reset_positions().unwrap();
        assert_eq!(sc.surface().position, before);
    }
}
