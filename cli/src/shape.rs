//! The surface a picture or a curvature table is made of: every
//! input kind under every scheme that applies, as one list of Bézier patches
//! (f64) that know their ring level, which of their edges border the cap's
//! last hole, and the cap's limit point.
//!
//! | input | scheme | patches |
//! |---|---|---|
//! | polar | `c2ps` (default) | `PolarNet::step` rings (docs/math/c2ps.md §5), levels 0..M (those with 5 links), plus the level-0 outer region |
//! | polar | `rts` | the same rings after `PolarNet::rts_step` (§3; valence kept) |
//! | polar | `catmull-clark` | the configuration as a mesh (pole fan of triangles, quad rings between the links) through `capdiv_mesh` with `PlanOptions::catmull_clark`: two Catmull-Clark refinement steps, then a CC cap at the pole (and at the fan triangles' centres); only the faces between the pole and link 4 are kept, the region the C²PS rings cover |
//! | cnet | `eg` (default) | `EgSubdivision` rings of steps 1..M (docs/math/eg.md §9) |
//! | cnet | `catmull-clark` | the kernel's `CcCap` on the same c-net, rings of steps 1..M (same layout) |
//! | dnet | `eg` | as cnet |
//! | mesh | default, `c2ps`, `eg` | `capdiv surface`'s pipeline (C²PS at poles, EG at n = 3, 5, CC elsewhere) |
//! | mesh | `catmull-clark` | the same with `PlanOptions::catmull_clark` |
//!
//! The c-net's Catmull-Clark cap comes from
//! [`capdiv_mesh::rings::catmull_clark_rings`], as a mesh's cap would. The
//! polar rings keep their own loop (they start at level 0, with the outer
//! region and RTS steps, which a surface cap has not), and so do the EG
//! rings (a `dnet` input has no c-net to give them).
//!
//! Hole edges (the last ring's inner side): C²PS/RTS span-0 patches along
//! `u = 0`; EG/CC piece 0 (`[½,1]×[0,½]`) along `u = 0`, piece 1 along
//! `v = 0` (as `capdiv_mesh::evaluate` marks them).

use crate::args::{ShapeScheme, DEFAULT_MAX_PATCHES};
use crate::commands::eg::{cnet, subdivision};
use crate::commands::polar::Config;
use crate::error::{CliError, Naming};
use crate::input::{CnetInput, EgInput, Input, MeshJson, PolarInput};
use crate::net::{valence_after, HeapStorage};
use capdiv::{FirstStep, OuterRegion, Point3, PolarNet, PoleJet};
use capdiv_mesh::rings::{catmull_clark_rings, RingError, RingOptions};
use capdiv_mesh::sinks::CollectSurface;
use capdiv_mesh::tessellate::{ring_edge_flags, PatchGeometry, RingLayout};
use capdiv_mesh::{mem, BoundedPlan, MeshInput, PatchKind, PatchRecord, PlanOptions, Scheme};

/// One patch of a [`Shape`].
#[derive(Clone, Debug)]
pub struct ShapePatch {
    /// The Bézier patch with its finer and hole edges and the limit point
    /// the hole closes to, as the evaluator gives it and the tessellator
    /// takes it.
    pub patch: PatchRecord<f64>,
    /// Ring level (C²PS/RTS: the level of the ring, 0 for the outer region;
    /// EG/CC: the step that emitted it; meshes: the patch's level).
    pub level: u32,
    /// Whether it is a ring patch of the cap the curvature table follows.
    pub ring: bool,
}

impl ShapePatch {
    /// A ring patch (or, with `ring` false, an outer-region patch) of
    /// `level` with its `(finer, hole)` edges ([`ring_edge_flags`]), the
    /// hole closed to `hole_point`.
    fn ring(
        kind: PatchKind,
        geometry: PatchGeometry<f64>,
        level: u32,
        ring: bool,
        (finer, hole): (u8, u8),
        hole_point: [f64; 3],
    ) -> Self {
        ShapePatch {
            patch: PatchRecord {
                level,
                finer,
                hole,
                hole_point: Point3(hole_point),
                ..PatchRecord::new(kind, geometry)
            },
            level,
            ring,
        }
    }

    /// The Bézier patch.
    pub fn geometry(&self) -> &PatchGeometry<f64> {
        &self.patch.geometry
    }
}

/// Limit curvature at the cap's centre, or why there is none.
#[derive(Clone, Debug, PartialEq)]
pub enum Limit {
    /// Gaussian and mean curvature at the centre.
    Known {
        /// `K`.
        gaussian: f64,
        /// `H`.
        mean: f64,
    },
    /// Not defined by the scheme (the reason, for the stderr note).
    Undefined(&'static str),
}

/// One cap of a [`Shape`]: where it sits and what made it.
#[derive(Clone, Debug, PartialEq)]
pub struct ShapeCap {
    /// The input vertex at its centre (0-based; polar: 0 is the pole,
    /// c-net and d-net: 0 is the centre), if it is at one.
    pub vertex: Option<u32>,
    /// The scheme as pictures name it (`C2PS`, `RTS`, `EG`,
    /// `Catmull-Clark`).
    pub scheme: &'static str,
    /// Its limit point.
    pub limit: [f64; 3],
}

/// A surface to draw or measure.
#[derive(Clone, Debug)]
pub struct Shape {
    /// The scheme's name (`c2ps`, `rts`, `eg`, `catmull-clark`, `mesh`).
    pub scheme: &'static str,
    /// A label for pictures, naming what made the surface (`C²PS` is drawn
    /// as `C2PS`): the scheme, or for a mesh its caps ([`caps_label`]).
    pub label: String,
    /// The patches.
    pub patches: Vec<ShapePatch>,
    /// The limit curvature at the centre.
    pub limit: Limit,
    /// Its caps.
    pub caps: Vec<ShapeCap>,
}

/// Why EG has no limit value here.
pub const EG_NO_LIMIT: &str = "EG: the spec gives the limit point c0 (docs/math/eg.md §4) but no \
     limit curvature, and mu/lambda^2 = 1.00016 (n = 3, 5; docs/math/eg.md §8) is not exactly 1, \
     so curvature at the centre is only nearly settled";
/// Why RTS has none.
pub const RTS_NO_LIMIT: &str = "RTS: its rings' curvature does not settle to one value \
     at the pole (min and max stay apart level after level, measured in the README), \
     so the pole jet's K, H are not its limit";
/// Why Catmull-Clark has none.
pub const CC_NO_LIMIT: &str = "Catmull-Clark: mu/lambda^2 != 1 at extraordinary points, \
     curvature at the centre is 0 or unbounded";
/// Why a mesh has none.
pub const MESH_NO_LIMIT: &str = "mesh: one limit value only for a mesh with a single C2PS cap";

/// The schemes that apply to an input kind, default first.
pub fn schemes_for(input: &Input) -> Vec<ShapeScheme> {
    match input {
        Input::Polar(_) => vec![
            ShapeScheme::C2ps,
            ShapeScheme::Rts,
            ShapeScheme::CatmullClark,
        ],
        Input::Cnet(_) => vec![ShapeScheme::Eg, ShapeScheme::CatmullClark],
        Input::Dnet(_) => vec![ShapeScheme::Eg],
        Input::Mesh(_) => vec![ShapeScheme::C2ps, ShapeScheme::CatmullClark],
    }
}

/// Builds the shape of `input` under `scheme` (default: the kind's own) with
/// `depth` rings.
pub fn build(
    name: &str,
    input: &Input,
    scheme: Option<ShapeScheme>,
    depth: u32,
) -> Result<Shape, CliError> {
    let scheme = scheme.unwrap_or(schemes_for(input)[0]);
    let refuse = |need: &str| CliError::WrongKind {
        source: name.to_string(),
        kind: input.kind(),
        need: format!("--scheme {} needs {need}", scheme.name()),
    };
    let shape = match (input, scheme) {
        (Input::Polar(p), ShapeScheme::C2ps) => polar(name, p, depth, false)?,
        (Input::Polar(p), ShapeScheme::Rts) => polar(name, p, depth, true)?,
        (Input::Polar(p), ShapeScheme::CatmullClark) => polar_cc(name, p, depth)?,
        (Input::Polar(_), ShapeScheme::Eg) => return Err(refuse("a 'cnet' or 'dnet' input")),
        (Input::Cnet(c), ShapeScheme::Eg) => eg(name, &EgInput::Cnet(c.clone()), depth)?,
        (Input::Dnet(d), ShapeScheme::Eg) => eg(name, &EgInput::Dnet(d.clone()), depth)?,
        (Input::Cnet(c), ShapeScheme::CatmullClark) => cnet_cc(name, c, depth)?,
        (Input::Dnet(_), ShapeScheme::CatmullClark) => {
            return Err(refuse(
                "a 'cnet', 'polar' or 'mesh' input (a d-net is not a Catmull-Clark net)",
            ))
        }
        (Input::Cnet(_) | Input::Dnet(_), _) => return Err(refuse("a 'polar' input")),
        (Input::Mesh(m), ShapeScheme::Rts) => {
            let _ = m;
            return Err(refuse("a 'polar' input"));
        }
        (Input::Mesh(m), s) => {
            let mesh = m.to_mesh(name)?;
            let cc = s == ShapeScheme::CatmullClark;
            mesh_shape(name, &mesh, depth, cc, None)?
        }
    };
    let finite = shape.patches.iter().all(|p| match p.geometry() {
        PatchGeometry::Cubic(q) => q.points.iter().flatten().all(Point3::is_finite),
        PatchGeometry::Quartic(q) => q.points.iter().flatten().all(Point3::is_finite),
    });
    if !finite {
        return Err(CliError::NonFiniteResult {
            source: name.to_string(),
        });
    }
    Ok(shape)
}

/// C²PS or RTS rings of a polar configuration.
fn polar(name: &str, input: &PolarInput, depth: u32, rts: bool) -> Result<Shape, CliError> {
    let config = Config::<f64>::of(input);
    let n = config.valence();
    let needed = if rts {
        Some(n)
    } else {
        valence_after(n, depth)
    };
    PolarJob {
        name,
        config: &config,
        depth,
        rts,
    }
    .run(HeapStorage::for_valence(needed, || {
        format!("valence n·2^M = {n}·2^{depth}")
    })?)
}

struct PolarJob<'a> {
    name: &'a str,
    config: &'a Config<f64>,
    depth: u32,
    rts: bool,
}

impl PolarJob<'_> {
    fn run(self, storage: HeapStorage<f64>) -> Result<Shape, CliError> {
        let kernel = |e| CliError::kernel(self.name, e);
        let (pole, links) = (self.config.pole, &self.config.links);
        let mut net = storage.net(pole, links).map_err(kernel)?;
        let jet = PoleJet::of(&net).finite().map_err(kernel)?;
        let limit = match jet.geometry() {
            Ok(g) => Limit::Known {
                gaussian: g.gaussian,
                mean: g.mean,
            },
            Err(_) => Limit::Undefined("the pole's tangent plane is degenerate (p1 x p2 = 0)"),
        };
        let hole_point = jet.limit().0;
        let outer = OuterRegion::new(pole, links).map_err(kernel)?;
        let memory = CliError::out_of_memory_in(self.name);
        let mut patches: Vec<ShapePatch> = mem::collect(outer.patches().map(|p| {
            ShapePatch::ring(
                PatchKind::C2ps,
                PatchGeometry::Cubic(p),
                0,
                false,
                (0, 0),
                hole_point,
            )
        }))
        .map_err(&memory)?;
        for level in 0..=self.depth {
            if net.link_count() >= 5 {
                let cols = net.valence();
                for (k, p) in net.ring_patches().enumerate() {
                    let last = level == self.depth;
                    let patch = ShapePatch::ring(
                        PatchKind::C2ps,
                        PatchGeometry::Cubic(p),
                        level,
                        true,
                        ring_edge_flags(RingLayout::Polar, k, 2 * cols, last),
                        hole_point,
                    );
                    mem::push(&mut patches, patch).map_err(&memory)?;
                }
            }
            if level < self.depth {
                if self.rts {
                    net.rts_step().map_err(kernel)?;
                } else {
                    net.step(FirstStep::Uniform).map_err(kernel)?;
                }
            }
        }
        let limit = if self.rts {
            Limit::Undefined(RTS_NO_LIMIT)
        } else {
            limit
        };
        Ok(Shape {
            scheme: if self.rts { "rts" } else { "c2ps" },
            label: if self.rts { "RTS" } else { "C2PS" }.into(),
            patches,
            limit,
            caps: vec![ShapeCap {
                vertex: Some(0),
                scheme: if self.rts { "RTS" } else { "C2PS" },
                limit: hole_point,
            }],
        })
    }
}

/// EG rings of a c-net or d-net (built-in rules: n = 3, 4, 5).
fn eg(name: &str, input: &EgInput, depth: u32) -> Result<Shape, CliError> {
    let mut sub = subdivision::<f64>(name, input, None)?;
    let kernel = |e| CliError::kernel(name, e);
    let hole_point = sub.limit().0;
    let mut patches = Vec::new();
    for level in 1..=depth {
        sub.step().map_err(kernel)?;
        for (k, p) in sub.ring_patches().enumerate() {
            let patch = ShapePatch::ring(
                PatchKind::Eg,
                PatchGeometry::Quartic(p),
                level,
                true,
                ring_edge_flags(RingLayout::Sectors, k, 0, level == depth),
                hole_point,
            );
            mem::push(&mut patches, patch).map_err(CliError::out_of_memory_in(name))?;
        }
    }
    Ok(Shape {
        scheme: "eg",
        label: "EG".into(),
        patches,
        limit: Limit::Undefined(EG_NO_LIMIT),
        caps: vec![ShapeCap {
            vertex: Some(0),
            scheme: "EG",
            limit: hole_point,
        }],
    })
}

/// The kernel's Catmull-Clark cap on a c-net, through
/// [`capdiv_mesh::rings::catmull_clark_rings`] (rings of steps 1..M, the
/// cap computed around its centre as in a mesh).
fn cnet_cc(name: &str, input: &CnetInput, depth: u32) -> Result<Shape, CliError> {
    // The kernel's own message for a malformed c-net.
    cnet::<f64>(name, input)?;
    let nodes: Vec<[f64; 3]> = mem::collect(input.sectors.iter().flatten().copied())
        .map_err(CliError::out_of_memory_in(name))?;
    let mut out = CollectSurface::new();
    catmull_clark_rings(input.center, &nodes, &RingOptions::new(depth), &mut out)
        .map_err(|e| ring_err(name, e))?;
    if let Some(e) = out.refused() {
        return Err(CliError::out_of_memory(name, e.bytes));
    }
    let hole_point = match out.caps.first() {
        Some(c) if c.limit.is_finite() => c.limit.0,
        _ => return Err(CliError::kernel(name, capdiv::Error::NonFinite)),
    };
    let patches = mem::collect(out.patches.into_iter().map(|patch| ShapePatch {
        level: patch.level,
        patch,
        ring: true,
    }))
    .map_err(CliError::out_of_memory_in(name))?;
    Ok(Shape {
        scheme: "catmull-clark",
        label: "Catmull-Clark".into(),
        patches,
        limit: Limit::Undefined(CC_NO_LIMIT),
        caps: vec![ShapeCap {
            vertex: Some(0),
            scheme: "Catmull-Clark",
            limit: hole_point,
        }],
    })
}

/// A ring error of a single configuration: the kernel's, or the
/// allocation's.
fn ring_err(name: &str, e: RingError) -> CliError {
    match e {
        RingError::Kernel(e) => CliError::kernel(name, e),
        RingError::OutOfMemory { bytes } => CliError::out_of_memory(name, bytes),
        other => CliError::Usage(format!("{name}: {other}")),
    }
}

/// A polar configuration as a mesh ([`MeshInput::polar_disk`]).
pub fn polar_mesh(input: &PolarInput) -> MeshInput {
    MeshInput::polar_disk(input.pole, &input.links)
}

/// Catmull-Clark on a polar configuration: through the mesh pipeline.
fn polar_cc(name: &str, input: &PolarInput, depth: u32) -> Result<Shape, CliError> {
    let n = input.links.first().map_or(0, Vec::len);
    if n < 3 || input.links.iter().any(|l| l.len() != n) || input.links.len() < 2 {
        // The kernel's own message for a malformed configuration.
        let config = Config::<f64>::of(input);
        PolarNet::<f64, 4>::new(config.pole, &config.links)
            .map_err(|e| CliError::kernel(name, e))?;
    }
    let mesh = polar_mesh(input);
    // Faces between the pole and link 4 (the C²PS rings' region).
    let keep = n * 4;
    let mut shape = mesh_shape(name, &mesh, depth, true, Some(keep))?;
    shape.scheme = "catmull-clark";
    shape.label = "Catmull-Clark".into();
    Ok(shape)
}

/// A mesh through `capdiv_mesh`; the curvature table follows the cap at
/// input vertex 0 when it has one (a polar configuration's pole), else every
/// cap. `keep`: only input faces below this index.
fn mesh_shape(
    name: &str,
    mesh: &MeshInput,
    depth: u32,
    catmull_clark: bool,
    keep: Option<usize>,
) -> Result<Shape, CliError> {
    let surface_err = |error| CliError::surface(name, error);
    let mut out = CollectSurface::new();
    BoundedPlan::evaluate_mesh(
        mesh,
        PlanOptions {
            depth,
            catmull_clark,
            ..Default::default()
        },
        DEFAULT_MAX_PATCHES,
        None,
        &mut out,
    )
    .map_err(surface_err)?;
    if let Some(e) = out.refused() {
        return Err(CliError::out_of_memory(name, e.bytes));
    }
    let memory = CliError::out_of_memory_in(name);
    let followed: Vec<u32> = match out.caps.iter().find(|c| c.vertex == Some(0)) {
        Some(c) if keep.is_some() => vec![c.index],
        _ => mem::collect(out.caps.iter().map(|c| c.index)).map_err(&memory)?,
    };
    // A single C²PS cap: its pole curvature.
    let limit = match out.caps.as_slice() {
        [c] if c.scheme == Scheme::C2ps => match c.principal_curvatures {
            Some([a, b]) => Limit::Known {
                gaussian: a * b,
                mean: 0.5 * (a + b),
            },
            None => Limit::Undefined(MESH_NO_LIMIT),
        },
        _ if catmull_clark => Limit::Undefined(CC_NO_LIMIT),
        _ => Limit::Undefined(MESH_NO_LIMIT),
    };
    // Ring levels of cap patches counted from the cap's first ring.
    let first_level = out
        .patches
        .iter()
        .filter(|p| p.cap.is_some_and(|c| followed.contains(&c)))
        .map(|p| p.level)
        .min()
        .unwrap_or(0);
    let kept = |p: &&PatchRecord<f64>| keep.is_none_or(|k| (p.face as usize) < k);
    // The caps with a patch kept.
    let caps: Vec<ShapeCap> = mem::collect(
        (out.caps.iter())
            .filter(|c| {
                out.patches
                    .iter()
                    .filter(kept)
                    .any(|p| p.cap == Some(c.index))
            })
            .map(|c| ShapeCap {
                vertex: c.vertex,
                scheme: match c.scheme {
                    Scheme::C2ps => "C2PS",
                    Scheme::Eg => "EG",
                    Scheme::CatmullClark => "Catmull-Clark",
                },
                limit: c.limit.0,
            }),
    )
    .map_err(&memory)?;
    // The kept patches, moved out of the evaluator's list.
    let patches = mem::collect(out.patches.into_iter().filter(|p| kept(&p)).map(|p| {
        let ring = p.cap.is_some_and(|c| followed.contains(&c));
        let level = if ring {
            p.level - first_level + 1
        } else {
            p.level
        };
        ShapePatch {
            patch: p,
            level,
            ring,
        }
    }))
    .map_err(&memory)?;
    Ok(Shape {
        scheme: if catmull_clark {
            "catmull-clark"
        } else {
            "mesh"
        },
        label: caps_label(&caps),
        patches,
        limit,
        caps,
    })
}

/// What a mesh surface's caps are, counted by scheme in the order met:
/// `caps: C2PS x2, EG x8`, or `no caps (B-spline only)`.
pub fn caps_label(caps: &[ShapeCap]) -> String {
    let mut counts: Vec<(&str, usize)> = Vec::new();
    for c in caps {
        match counts.iter_mut().find(|e| e.0 == c.scheme) {
            Some(e) => e.1 += 1,
            None => counts.push((c.scheme, 1)),
        }
    }
    if counts.is_empty() {
        return "no caps (B-spline only)".into();
    }
    let list: Vec<String> = counts.iter().map(|(s, n)| format!("{s} x{n}")).collect();
    format!("caps: {}", list.join(", "))
}

/// [`CliError::Usage`] when a shape has no patch to draw (e.g. a polar net
/// of 2 links at depth 0 or 1: its first ring needs 5 links, level 2).
pub fn drawable(name: &str, shape: &Shape, depth: u32) -> Result<(), CliError> {
    if shape.patches.is_empty() && shape.scheme == "mesh" {
        return Err(CliError::Usage(format!(
            "{name}: no patch to draw: the surface is empty (every face a hole, or \
             dropped by the boundary rule)"
        )));
    }
    if shape.patches.is_empty() {
        return Err(CliError::Usage(format!(
            "{name}: no patch to draw under {} at depth {depth} (a C2PS ring needs 5 links: \
             with 2 input links rings start at level 2, with 3 or 4 at level 1)",
            shape.scheme
        )));
    }
    Ok(())
}

/// Sets a mesh input's boundary rule (`--boundary`); any other kind of input
/// is [`CliError::WrongKind`].
pub fn override_boundary(
    name: &str,
    input: &mut Input,
    boundary: Option<crate::args::BoundaryArg>,
) -> Result<(), CliError> {
    let Some(b) = boundary else {
        return Ok(());
    };
    match input {
        Input::Mesh(m) => {
            m.boundary = Some(capdiv_mesh::BoundaryInterpolation::from(b).into());
            Ok(())
        }
        other => Err(CliError::WrongKind {
            source: name.to_string(),
            kind: other.kind(),
            need: "--boundary needs a 'mesh' input (or a Wavefront OBJ)".into(),
        }),
    }
}

/// Reads any input: JSON of any kind (chosen by content), a Wavefront OBJ
/// mesh, or `sample:NAME`, a built-in test net
/// ([`crate::samples::shape_samples`]). Returns the display name and how
/// the input counts its vertices and faces with it.
pub fn read_any(file: &str) -> Result<(String, Input, Naming), CliError> {
    if let Some(name) = file.strip_prefix("sample:") {
        let all = crate::samples::shape_samples();
        let names: Vec<&str> = all.iter().map(|s| s.0).collect();
        return match all.into_iter().find(|s| s.0 == name) {
            Some((n, input)) => Ok((format!("sample:{n}"), input, Naming::Indices)),
            None => Err(CliError::Usage(format!(
                "no built-in sample '{name}' (samples: {})",
                names.join(", ")
            ))),
        };
    }
    let source = crate::input::Source::read_text(file)?;
    let naming = Naming::of_text(&source.text);
    let input = if capdiv_mesh::obj::looks_like_json(&source.text) {
        crate::input::parse(&source.name, &source.text)?
    } else {
        let mesh = capdiv_mesh::obj::parse_obj(&source.text)
            .map_err(|error| CliError::mesh(&source.name, error).named(&naming))?;
        Input::Mesh(MeshJson::of(&mesh))
    };
    Ok((source.name, input, naming))
}

/// Geometry at `(u, v)` of a patch: position, unit normal, `K`, `H`
/// (`None` where the tangent plane degenerates).
pub fn geometry_at(
    p: &PatchGeometry<f64>,
    u: f64,
    v: f64,
) -> Option<([f64; 3], [f64; 3], f64, f64)> {
    let jet = p.jet(u.clamp(0.0, 1.0), v.clamp(0.0, 1.0)).ok()?;
    let g = jet.geometry().ok()?;
    Some((jet.position.0, g.normal.0, g.gaussian, g.mean))
}
