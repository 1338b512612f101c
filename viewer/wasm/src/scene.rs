//! One mesh on the page: its topology and subdivision tags analysed once
//! ([`SurfacePlan::for_mesh`]), an [`Evaluator`] sized for it, and the
//! current positions. An edit of a control point re-runs only the evaluate-only path — `Evaluator::evaluate`
//! on the same plan, then the per-vertex tessellation and paint — never the
//! analysis. Options (depth, scheme, grid) make a new plan.

use crate::paint::{self, Mode, Paint, View};
use crate::tess::{Surface, Tessellator};
use capdiv::Point3;
use capdiv_mesh::shade::HighlightLines;
use capdiv_mesh::sinks::SurfaceStats;
use capdiv_mesh::tessellate::weld::representatives;
use capdiv_mesh::tessellate::{write_obj, write_point};
use capdiv_mesh::tessellate::{Face, Tessellation};
use capdiv_mesh::{
    BoundaryInterpolation, CreaseMethod, EvalBuffers, Evaluator, MeshInput, PlanOptions,
    SurfacePlan, SurfaceSink, Topology, TriangleSubdivision,
};
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

/// The message for a mesh whose surface has no patch.
pub const EMPTY_SURFACE: &str =
    "no patch to draw: the surface is empty (every face a hole, or dropped by the boundary rule)";

/// The axis the page shows upward: `z` (the CLI's, CAD's) or `y` (glTF's,
/// Blender's export default).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Up {
    /// `+z` up.
    #[default]
    Z,
    /// `+y` up.
    Y,
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
        + plan
            .extraordinary
            .iter()
            .map(|e| e.sectors.len())
            .sum::<usize>();
    let coarse = plan.regular.len() + 2 * caps;
    [8, 4, 2]
        .into_iter()
        .find(|g| coarse * (g + 1) * (g + 1) <= VERTEX_BUDGET)
        .unwrap_or(1)
}

/// The plan of one option set and the buffers of its evaluator (taken back
/// by each evaluation: [`Evaluator::with_buffers`]).
struct Analysis {
    plan: SurfacePlan<'static>,
    buffers: Option<EvalBuffers<f64>>,
    grid: usize,
}

impl Analysis {
    /// The plan of `mesh` with its subdivision tags (creases, corners,
    /// holes, boundary rule: [`SurfacePlan::for_mesh`]).
    fn new(mesh: &MeshInput, o: &Options) -> Result<Self, String> {
        let plan = SurfacePlan::for_mesh(mesh, plan_options(o)?).map_err(|e| e.to_string())?;
        let buffers = Evaluator::new(&plan)
            .map_err(|e| e.to_string())?
            .into_buffers();
        let grid = if o.grid == 0 {
            auto_grid(&plan)
        } else {
            o.grid
        };
        Ok(Analysis {
            plan,
            buffers: Some(buffers),
            grid,
        })
    }
}

/// A mesh being viewed.
pub struct Scene {
    name: String,
    mesh: MeshInput,
    analysis: Analysis,
    options: Options,
    positions: Vec<[f64; 3]>,
    tess: Tessellator,
    /// The plan changed since the last evaluation.
    new_plan: bool,
    /// Its GPU attributes under the current shading.
    pub paint: Paint,
    mode: Mode,
    up: Up,
    scale: f64,
    view: View,
    lines: Option<HighlightLines>,
    /// Edges of the control mesh (pairs of vertex indices, each once).
    pub edges: Vec<u32>,
}

impl Scene {
    /// Validates, analyses and evaluates `mesh`. `Err`: the page's message.
    pub fn new(name: &str, mesh: MeshInput, options: Options, mode: Mode) -> Result<Self, String> {
        // The viewer takes manifold, consistently oriented meshes only.
        Topology::new(&mesh).map_err(|e| e.to_string())?;
        let analysis = Analysis::new(&mesh, &options)?;
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
            analysis,
            options,
            positions,
            tess: Tessellator::default(),
            new_plan: true,
            paint: Paint::default(),
            mode,
            up: Up::Z,
            scale: 1.0,
            view: View::of_box([0.0; 3], [0.0; 3]),
            lines: None,
            edges: edges.into_iter().flat_map(|(a, b)| [a, b]).collect(),
        };
        scene.evaluate()?;
        scene.require_surface()?;
        let (lo, hi) = (scene.surface().lo, scene.surface().hi);
        scene.view = View::of_box(lo, hi);
        scene.rescale();
        Ok(scene)
    }

    /// `Err` when the evaluation gave no triangle to show.
    fn require_surface(&self) -> Result<(), String> {
        if self.tess.surface.indices.is_empty() {
            return Err(EMPTY_SURFACE.into());
        }
        Ok(())
    }

    /// Evaluates the current positions through the plan and samples the
    /// patches that changed (all of them after a new plan; no paint).
    fn evaluate(&mut self) -> Result<(), String> {
        let a = &mut self.analysis;
        let base = a.plan.steps.len() as u32;
        let mut evaluator = match a.buffers.take() {
            Some(buffers) => Evaluator::with_buffers(&a.plan, buffers),
            None => Evaluator::new(&a.plan),
        }
        .map_err(|e| e.to_string())?;
        let mut rebuild = self.new_plan;
        let result = loop {
            self.tess.begin(rebuild, base, a.grid);
            if let Err(e) = evaluator.evaluate(&self.positions, &mut self.tess) {
                // Partly re-sampled: the next evaluation starts afresh.
                self.new_plan = true;
                break Err(e.to_string());
            }
            if self.tess.finish() {
                self.new_plan = false;
                break Ok(());
            }
            rebuild = true;
        };
        a.buffers = Some(evaluator.into_buffers());
        result
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
        let analysis = Analysis::new(&self.mesh, &options)?;
        let old = std::mem::replace(&mut self.analysis, analysis);
        let old_options = std::mem::replace(&mut self.options, options);
        self.new_plan = true;
        if let Err(e) = self.evaluate().and_then(|()| self.require_surface()) {
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
        self.lines = paint::lines(s.lo, s.hi, self.up, &self.view);
        self.tess.dirty = (0, s.len());
        self.repaint();
    }

    /// The view the light lines are spaced in (the page's camera); under
    /// the highlight shading the per-vertex parameters are rewritten, and
    /// nothing else ([`paint::restripe`]). On error the view stays.
    pub fn set_view(&mut self, view: View) -> Result<(), String> {
        view.check()?;
        if view == self.view {
            return Ok(());
        }
        self.view = view;
        let s = &self.tess.surface;
        self.lines = paint::lines(s.lo, s.hi, self.up, &self.view);
        if self.mode == Mode::Highlight {
            paint::restripe(s, self.mode, self.lines.as_ref(), &mut self.paint);
        }
        Ok(())
    }

    /// The view the light lines are spaced in.
    pub fn view(&self) -> View {
        self.view
    }

    /// The axis shown upward: the light plane of the highlight lines lies
    /// above the surface along it. Repaints.
    pub fn set_up(&mut self, up: Up) {
        self.up = up;
        self.rescale();
    }

    /// The control mesh with its current (edited) positions as Wavefront
    /// OBJ: `v x y z` per control point, `f` per face (1-based), numbers
    /// that read back exactly, and the subdivision tags the mesh has as
    /// OpenSubdiv's `t` lines (`capdiv_mesh::obj` reads them; other
    /// readers skip them): creases, corners, holes, and the boundary,
    /// crease and triangle rules where they are not the defaults.
    pub fn control_obj(&self) -> String {
        let mut text = format!("# capdiv viewer: control mesh of {}\n", self.name);
        for &p in &self.positions {
            write_point(&mut text, "v", p);
        }
        for f in &self.mesh.faces {
            text.push('f');
            for &i in f {
                let _ = write!(text, " {}", i as u64 + 1);
            }
            text.push('\n');
        }
        let tags = &self.mesh.tags;
        for c in &tags.creases {
            let [a, b] = c.vertices;
            let _ = writeln!(text, "t crease 2/1/0 {a} {b} {}", c.sharpness);
        }
        for c in &tags.corners {
            let _ = writeln!(text, "t corner 1/1/0 {} {}", c.vertex, c.sharpness);
        }
        if !tags.holes.is_empty() {
            let _ = write!(text, "t hole {}/0/0", tags.holes.len());
            for h in &tags.holes {
                let _ = write!(text, " {h}");
            }
            text.push('\n');
        }
        if tags.boundary != BoundaryInterpolation::default() {
            let n = match tags.boundary {
                BoundaryInterpolation::None => 0,
                BoundaryInterpolation::EdgeAndCorner => 1,
                BoundaryInterpolation::EdgeOnly => 2,
            };
            let _ = writeln!(text, "t interpolateboundary 1/0/0 {n}");
        }
        if tags.crease_method != CreaseMethod::default() {
            let _ = writeln!(text, "t creasemethod 0/0/1 {}", tags.crease_method.id());
        }
        if tags.triangles != TriangleSubdivision::default() {
            let _ = writeln!(text, "t smoothtriangles 0/0/1 {}", tags.triangles.id());
        }
        text
    }

    /// The shown surface as Wavefront OBJ (`capdiv_mesh::tessellate::write_obj`):
    /// its samples welded by position (tolerance 1e-9 of the box size; the
    /// patches' shared edges are sampled at the same parameters), one
    /// normal per vertex (the first welded sample's that exists), the
    /// triangles with their corners not welded together. An allocation of
    /// the weld that is refused is the error's message.
    pub fn surface_obj(&self) -> Result<String, String> {
        let s = &self.tess.surface;
        let size = (0..3).map(|c| s.hi[c] - s.lo[c]).fold(0.0, f64::max);
        let points: Vec<Point3<f64>> = s.position.iter().map(|&p| Point3(p)).collect();
        let rep = representatives(&points, 1e-9 * size).map_err(|e| e.message())?;
        let mut index = vec![u32::MAX; s.len()];
        let mut t = Tessellation {
            positions: Vec::new(),
            normals: Vec::new(),
            faces: Vec::new(),
            tags: Vec::new(),
            uvs: Vec::new(),
            seam_origin: Vec::new(),
            samples: s.len(),
            degenerate_dropped: 0,
        };
        for (i, &r) in rep.iter().enumerate() {
            let r = r as usize;
            if index[r] == u32::MAX {
                index[r] = t.positions.len() as u32;
                t.positions.push(points[r]);
                t.normals.push(Point3([0.0; 3]));
            }
            let n = &mut t.normals[index[r] as usize];
            if n.0 == [0.0; 3] && s.flags[i] & crate::tess::DEGENERATE == 0 {
                *n = Point3(s.normal[i]);
            }
        }
        for tri in s.indices.chunks(3) {
            let c = [0, 1, 2].map(|k| index[rep[tri[k] as usize] as usize]);
            if c[0] == c[1] || c[1] == c[2] || c[2] == c[0] {
                t.degenerate_dropped += 1;
            } else {
                t.faces.push(Face::Tri(c));
                t.tags.push(0);
            }
        }
        Ok(write_obj(
            &t,
            &[format!(
                "capdiv viewer: surface of {}, depth {}, {}",
                self.name,
                self.options.depth,
                if self.options.catmull_clark {
                    "Catmull-Clark caps"
                } else {
                    "C2PS and EG caps"
                }
            )],
        ))
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
        let mut stats = SurfaceStats::new();
        for c in &self.tess.caps {
            stats.cap(c);
        }
        let mut caps: Vec<(&str, usize, usize)> = stats
            .caps
            .iter()
            .map(|k| (k.scheme.id(), k.valence, k.count))
            .collect();
        caps.sort();
        let mut s = String::new();
        let _ = write!(
            s,
            "{{\"name\":{},\"vertices\":{},\"faces\":{},\"refinement_steps\":{},\"uncovered_faces\":{},\
             \"patches\":{{\"regular\":{},\"c2ps\":{},\"eg\":{},\"catmull-clark\":{}}},\"caps\":[",
            json_string(&self.name),
            self.mesh.vertices.len(),
            self.mesh.faces.len(),
            plan.steps.len(),
            plan.uncovered.len(),
            kinds.regular,
            kinds.c2ps,
            kinds.eg,
            kinds.catmull_clark
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
            "],\"depth\":{},\"grid\":{},\"surface_vertices\":{},\"triangles\":{},\"scale\":{}}}",
            self.options.depth,
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
        let rep = representatives(&points, 1e-9 * size).expect("weld");
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
            assert_eq!(v["patches"]["c2ps"], 0, "{name}");
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
    fn the_default_depth_is_4() {
        assert_eq!(Options::default().depth, 4);
        let s = crate::samples::by_name("torus").unwrap();
        let sc = Scene::new("torus", (s.build)(), Options::default(), Mode::Plain).unwrap();
        let v: serde_json::Value = serde_json::from_str(&sc.summary()).unwrap();
        assert_eq!(v["depth"], 4);
    }

    #[test]
    fn a_mesh_far_from_the_origin_has_the_box_of_its_samples() {
        // The mushroom (C²PS caps at depth 4: hole fans) moved by 1000.
        let s = crate::samples::by_name("mushroom").unwrap();
        let mut mesh = (s.build)();
        for v in &mut mesh.vertices {
            for c in v.iter_mut() {
                *c += 1000.0;
            }
        }
        let lo_net = (0..3).map(|c| {
            mesh.vertices
                .iter()
                .map(|v| v[c])
                .fold(f64::INFINITY, f64::min)
        });
        assert!(lo_net.clone().all(|x| x > 990.0));
        let sc = Scene::new("far", mesh, Options::default(), Mode::Plain).unwrap();
        let surface = sc.surface();
        assert!(surface.flags.iter().any(|&f| f & HOLE != 0));
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in &surface.position {
            for c in 0..3 {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
        }
        assert_eq!((surface.lo, surface.hi), (lo, hi));
        assert!(lo.iter().all(|&x| x > 990.0), "{lo:?}");
    }

    #[test]
    fn an_empty_surface_is_an_error() {
        // A quad whose face is a hole.
        let quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nt hole 1/0/0 0\n";
        let quad = crate::input::parse(quad).unwrap();
        let e = Scene::new("quad", quad, Options::default(), Mode::Plain)
            .err()
            .expect("an empty surface is an error");
        assert_eq!(e, EMPTY_SURFACE);
        // Every face of a torus a hole.
        let mut torus = capdiv_mesh::samples::torus(6, 5);
        torus.tags.holes = (0..torus.faces.len() as u32).collect();
        let e = Scene::new("holes", torus, Options::default(), Mode::Plain)
            .err()
            .expect("an empty surface is an error");
        assert_eq!(e, EMPTY_SURFACE);
    }

    #[test]
    fn the_control_obj_reads_back_as_the_edited_mesh() {
        use capdiv_mesh::{EdgeCrease, VertexCorner};
        let mut mesh = capdiv_mesh::samples::torus(6, 5);
        let f0 = mesh.faces[0].clone();
        mesh.tags.creases.push(EdgeCrease {
            vertices: [f0[0], f0[1]],
            sharpness: 2.5,
        });
        mesh.tags.corners.push(VertexCorner {
            vertex: f0[2],
            sharpness: 0.3,
        });
        mesh.tags.holes = vec![7, 12];
        mesh.tags.boundary = BoundaryInterpolation::EdgeOnly;
        mesh.tags.crease_method = CreaseMethod::Chaikin;
        let mut sc = Scene::new("torus", mesh.clone(), Options::default(), Mode::Plain).unwrap();
        let p = sc.positions()[3];
        let moved = [p[0] + 0.1, p[1] - 1.0 / 3.0, p[2] + 1e-7];
        sc.move_vertex(3, moved).unwrap();
        let back = crate::input::parse(&sc.control_obj()).unwrap();
        mesh.vertices[3] = moved;
        assert_eq!(back.vertices, mesh.vertices);
        assert_eq!(back.faces, mesh.faces);
        assert_eq!(back.tags, mesh.tags);
    }

    /// `v`, `vn` and `f a//a b//b c//c` lines of an OBJ text (0-based faces).
    type ObjParts = (Vec<[f64; 3]>, Vec<[f64; 3]>, Vec<[u32; 3]>);

    fn obj_parts(text: &str) -> ObjParts {
        let (mut v, mut vn, mut f) = (Vec::new(), Vec::new(), Vec::new());
        for line in text.lines() {
            let w: Vec<&str> = line.split_whitespace().collect();
            let xyz = || [1, 2, 3].map(|k| w[k].parse::<f64>().unwrap());
            match w.first() {
                Some(&"v") => v.push(xyz()),
                Some(&"vn") => vn.push(xyz()),
                Some(&"f") => {
                    assert_eq!(w.len(), 4, "{line}");
                    f.push([1, 2, 3].map(|k| {
                        let (a, b) = w[k].split_once("//").unwrap();
                        assert_eq!(a, b);
                        a.parse::<u32>().unwrap() - 1
                    }));
                }
                _ => {}
            }
        }
        (v, vn, f)
    }

    #[test]
    fn the_surface_obj_is_the_shown_surface_welded() {
        use capdiv_mesh::tessellate::{is_closed_and_oriented, Face};
        let mut sc = scene("globe", 3);
        let p = sc.positions()[0];
        sc.move_vertex(0, [p[0] * 1.2, p[1], p[2]]).unwrap();
        let (v, vn, f) = obj_parts(&sc.surface_obj().unwrap());
        let s = sc.surface();
        assert_eq!(v.len(), vn.len());
        // Welding: fewer vertices than samples, each one a sample's position
        // exactly, every triangle kept (the globe's have three distinct
        // corners), and the triangles close the globe consistently oriented.
        assert!(v.len() < s.len(), "{} of {}", v.len(), s.len());
        assert!(v.iter().all(|q| s.position.contains(q)));
        assert_eq!(f.len(), s.indices.len() / 3);
        // Each corner within the weld tolerance (1e-9 of the box) of its
        // sample.
        let size = (0..3).map(|c| s.hi[c] - s.lo[c]).fold(0.0, f64::max);
        for (t, tri) in f.iter().zip(s.indices.chunks(3)) {
            for k in 0..3 {
                let (a, b) = (v[t[k] as usize], s.position[tri[k] as usize]);
                assert!(
                    (0..3).all(|c| (a[c] - b[c]).abs() <= 1e-9 * size),
                    "{a:?} {b:?}"
                );
            }
        }
        let faces: Vec<Face> = f.iter().map(|&t| Face::Tri(t)).collect();
        assert_eq!(is_closed_and_oriented(&faces), Ok(()));
        // Unit normals (the globe has no degenerate sample).
        for n in &vn {
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            assert!((len - 1.0).abs() < 1e-12, "{n:?}");
        }
    }

    #[test]
    fn y_up_turns_the_light_lines_with_the_model() {
        // The globe z-up, and turned to y-up (x, y, z) -> (x, z, -y), an
        // exact map: the same highlight parameters at the same samples (to
        // rounding of the parameter's arithmetic in another coordinate
        // order), and y-up on the unturned globe gives other ones.
        let s = crate::samples::by_name("globe").unwrap();
        let mesh = (s.build)();
        let mut turned = mesh.clone();
        for v in &mut turned.vertices {
            *v = [v[0], v[2], -v[1]];
        }
        let o = Options {
            depth: 3,
            ..Options::default()
        };
        let a = Scene::new("z", mesh.clone(), o, Mode::Highlight).unwrap();
        let mut b = Scene::new("y", turned, o, Mode::Highlight).unwrap();
        b.set_up(Up::Y);
        let (sa, sb) = (&a.paint.stripes, &b.paint.stripes);
        assert_eq!(sa.len(), sb.len());
        for (x, y) in sa.iter().zip(sb) {
            assert!((x - y).abs() <= 1e-5 * x.abs().max(1.0), "{x} {y}");
        }
        let mut c = Scene::new("z as y", mesh, o, Mode::Highlight).unwrap();
        c.set_up(Up::Y);
        let differ = sa
            .iter()
            .zip(&c.paint.stripes)
            .filter(|(x, y)| (*x - *y).abs() > 0.1)
            .count();
        assert!(differ > sa.len() / 4, "{differ} of {}", sa.len());
    }

    #[test]
    fn a_new_view_rewrites_only_the_highlight_parameters() {
        let s = crate::samples::by_name("mushroom").unwrap();
        let o = Options {
            depth: 3,
            ..Options::default()
        };
        let mut sc = Scene::new("mushroom", (s.build)(), o, Mode::Highlight).unwrap();
        let before = sc.paint.clone();
        let v = sc.view();
        assert_eq!(v.lines, capdiv_mesh::shade::DEFAULT_LINES);
        // Half the visible height, the same target: twice the parameter
        // (line 0 stays through the target), nothing else changes.
        sc.set_view(View {
            height: 0.5 * v.height,
            ..v
        })
        .unwrap();
        assert_eq!(sc.paint.positions, before.positions);
        assert_eq!(sc.paint.normals, before.normals);
        assert_eq!(sc.paint.colors, before.colors);
        let mut lines = 0;
        for (a, b) in before.stripes.iter().zip(&sc.paint.stripes) {
            if *a != paint::NO_LINE {
                assert!((b - 2.0 * a).abs() <= 1e-6 * b.abs().max(1.0), "{a} {b}");
                lines += 1;
            }
        }
        assert!(lines > before.stripes.len() / 2, "{lines}");
        // A bad view is refused and changes nothing.
        let stripes = sc.paint.stripes.clone();
        assert!(sc
            .set_view(View {
                height: f64::NAN,
                ..v
            })
            .is_err());
        assert_eq!(sc.paint.stripes, stripes);
        // The view set under another shading is the highlight shading's
        // once chosen.
        let mut plain = Scene::new("mushroom", (s.build)(), o, Mode::Plain).unwrap();
        plain.set_view(sc.view()).unwrap();
        assert!(plain.paint.stripes.iter().all(|&t| t == paint::NO_LINE));
        plain.set_mode(Mode::Highlight);
        assert_eq!(plain.paint.stripes, sc.paint.stripes);
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
