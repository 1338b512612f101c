//! Caps are computed around their centre: the kernel gets the polar net or
//! c-net minus its pole or centre point, and the rings are moved back
//! afterwards. The schemes are affine invariant, so this changes nothing in
//! exact arithmetic; in `f32` it keeps every subdivision step's rounding
//! relative to the cap's size, not to its distance from the origin.

mod common;

use capdiv_mesh::sinks::CollectSurface;
use capdiv_mesh::tessellate::PatchGeometry;
use capdiv_mesh::{samples, Evaluator, MeshInput, Scheme, SurfacePlan, Topology};

/// An offset exactly representable in `f32` under which every coordinate
/// below stays exact (a multiple of 2⁻⁶ below 2¹¹ needs 17 bits).
const OFFSET: [f64; 3] = [1024.0, -512.0, 768.0];

/// `mesh` with every coordinate rounded to a multiple of 2⁻⁶.
fn on_grid(mut mesh: MeshInput) -> MeshInput {
    for p in &mut mesh.vertices {
        *p = p.map(|c| (c * 64.0).round() / 64.0);
    }
    mesh
}

fn evaluate_f32(plan: &SurfacePlan<'_>, mesh: &MeshInput, offset: [f64; 3]) -> CollectSurface<f32> {
    evaluate_f32_with(plan, mesh, offset, false)
}

/// [`evaluate_f32`], cap patches relative to their centre when `relative`.
fn evaluate_f32_with(
    plan: &SurfacePlan<'_>,
    mesh: &MeshInput,
    offset: [f64; 3],
    relative: bool,
) -> CollectSurface<f32> {
    let at: Vec<[f32; 3]> = mesh
        .vertices
        .iter()
        .map(|p| [0, 1, 2].map(|k| (p[k] + offset[k]) as f32))
        .collect();
    assert!(
        at.iter()
            .zip(&mesh.vertices)
            .all(|(a, p)| (0..3).all(|k| a[k] as f64 == p[k] + offset[k])),
        "the moved coordinates are exact in f32"
    );
    let mut sink = CollectSurface::new();
    let mut ev = Evaluator::<f32>::new(plan).expect("evaluator");
    ev.set_relative_caps(relative);
    ev.evaluate(&at, &mut sink).expect("evaluate");
    sink
}

fn points(g: &PatchGeometry<f32>) -> Vec<[f32; 3]> {
    match g {
        PatchGeometry::Cubic(t) => t.points.iter().flatten().map(|p| p.0).collect(),
        PatchGeometry::Quartic(t) => t.points.iter().flatten().map(|p| p.0).collect(),
    }
}

/// Largest `|(moved − OFFSET) − here|` per coordinate, in units of one
/// `f32` rounding to nearest of each side (`ε/2·|moved| + ε/2·|here|`).
fn roundings(here: [f32; 3], moved: [f32; 3]) -> f64 {
    (0..3)
        .map(|k| {
            let (a, b) = (here[k] as f64, moved[k] as f64);
            let unit = 0.5 * f32::EPSILON as f64 * (a.abs() + b.abs());
            ((b - OFFSET[k]) - a).abs() / unit
        })
        .fold(0.0, f64::max)
}

/// Moving a mesh by an exact offset moves every cap patch, hole point and
/// cap limit by that offset up to one rounding of each side: the kernel saw
/// the same net relative to the cap's centre both times. Computed on the
/// moved coordinates, the steps' rounding would be relative to 2¹⁰ and add
/// up over the rings. Caps to depth 4, every cap Catmull-Clark when
/// `catmull_clark`.
fn caps_move_with_the_mesh(name: &str, mesh: MeshInput, catmull_clark: bool, scheme: Scheme) {
    let options = common::plan_options(4, catmull_clark);
    let mesh = on_grid(mesh);
    let t = Topology::new(&mesh).expect("valid mesh");
    let plan = SurfacePlan::new(&t, options).expect("plan");
    assert!(plan.steps.is_empty(), "{name}: caps on the input level");
    let here = evaluate_f32(&plan, &mesh, [0.0; 3]);
    let moved = evaluate_f32(&plan, &mesh, OFFSET);
    assert!(
        here.caps.iter().any(|c| c.scheme == scheme),
        "{name}: a {scheme:?} cap"
    );
    assert_eq!(here.patches.len(), moved.patches.len());
    let mut worst = 0.0f64;
    let mut cap_patches = 0;
    for (a, b) in here.patches.iter().zip(&moved.patches) {
        if a.cap.is_none() {
            continue;
        }
        cap_patches += 1;
        for (p, q) in points(&a.geometry).into_iter().zip(points(&b.geometry)) {
            worst = worst.max(roundings(p, q));
        }
        if a.hole != 0 {
            worst = worst.max(roundings(a.hole_point.0, b.hole_point.0));
        }
    }
    for (a, b) in here.caps.iter().zip(&moved.caps) {
        worst = worst.max(roundings(a.limit.0, b.limit.0));
    }
    assert!(cap_patches > 0, "{name}: cap patches");
    assert!(worst <= 1.0, "{name}: cap moved by {worst} roundings");
}

#[test]
fn eg_caps_move_with_the_mesh_up_to_one_rounding() {
    caps_move_with_the_mesh(
        "valence 5",
        samples::extraordinary_disk(5, 4),
        false,
        Scheme::Eg,
    );
    caps_move_with_the_mesh(
        "valence 3",
        samples::extraordinary_disk(3, 4),
        false,
        Scheme::Eg,
    );
}

#[test]
fn catmull_clark_caps_move_with_the_mesh_up_to_one_rounding() {
    let mesh = samples::extraordinary_disk(6, 4);
    caps_move_with_the_mesh("valence 6", mesh, true, Scheme::CatmullClark);
}

#[test]
fn c2ps_caps_move_with_the_mesh_up_to_one_rounding() {
    caps_move_with_the_mesh(
        "valence 8 fan",
        samples::pole_disk(8, 5),
        false,
        Scheme::C2ps,
    );
}

/// Relative cap records ([`Evaluator::set_relative_caps`]) are what the
/// kernel computed about the cap's centre: the absolute records are them
/// plus the origin, bit for bit (the same one addition per coordinate), and
/// under an exact offset they do not move at all (the kernel saw the same
/// net), so their partials keep the precision of the cap's size however
/// far the mesh lies from the coordinate origin. Patches outside caps have
/// a zero origin either way.
fn relative_caps_are_the_absolute_ones_before_moving_back(
    name: &str,
    mesh: MeshInput,
    catmull_clark: bool,
) {
    let options = common::plan_options(4, catmull_clark);
    let mesh = on_grid(mesh);
    let t = Topology::new(&mesh).expect("valid mesh");
    let plan = SurfacePlan::new(&t, options).expect("plan");
    let absolute = evaluate_f32_with(&plan, &mesh, OFFSET, false);
    let relative = evaluate_f32_with(&plan, &mesh, OFFSET, true);
    let near = evaluate_f32_with(&plan, &mesh, [0.0; 3], true);
    assert_eq!(absolute.patches.len(), relative.patches.len());
    assert_eq!(near.patches.len(), relative.patches.len());
    let mut cap_patches = 0;
    for ((a, r), n) in absolute
        .patches
        .iter()
        .zip(&relative.patches)
        .zip(&near.patches)
    {
        assert_eq!(
            a.origin.0, [0.0; 3],
            "{name}: absolute records have no origin"
        );
        assert_eq!(
            a.hole_point, r.hole_point,
            "{name}: hole points stay absolute"
        );
        if r.cap.is_none() {
            assert_eq!(
                r.origin.0, [0.0; 3],
                "{name}: patches outside caps are absolute"
            );
            assert_eq!(points(&a.geometry), points(&r.geometry));
            continue;
        }
        cap_patches += 1;
        assert_ne!(
            r.origin.0, [0.0; 3],
            "{name}: a cap patch's origin is its centre"
        );
        for (p, q) in points(&a.geometry).into_iter().zip(points(&r.geometry)) {
            let moved_back = [0, 1, 2].map(|k| q[k] + r.origin.0[k]);
            assert_eq!(p, moved_back, "{name}: absolute = relative + origin");
        }
        assert_eq!(
            points(&n.geometry),
            points(&r.geometry),
            "{name}: the offset does not reach them"
        );
        let shift = [0, 1, 2].map(|k| r.origin.0[k] as f64 - n.origin.0[k] as f64);
        assert_eq!(shift, OFFSET, "{name}: the origin carries the offset");
    }
    assert!(cap_patches > 0, "{name}: cap patches");
}

#[test]
fn relative_eg_caps_are_the_absolute_ones_before_moving_back() {
    relative_caps_are_the_absolute_ones_before_moving_back(
        "valence 5",
        samples::extraordinary_disk(5, 4),
        false,
    );
}

#[test]
fn relative_catmull_clark_caps_are_the_absolute_ones_before_moving_back() {
    relative_caps_are_the_absolute_ones_before_moving_back(
        "valence 6",
        samples::extraordinary_disk(6, 4),
        true,
    );
}

#[test]
fn relative_c2ps_caps_are_the_absolute_ones_before_moving_back() {
    relative_caps_are_the_absolute_ones_before_moving_back(
        "valence 8 fan",
        samples::pole_disk(8, 5),
        false,
    );
}

/// The tessellation adds a record's origin back: relative cap records
/// tessellate to the mesh absolute ones give, the same vertices and faces,
/// positions within a few roundings (the evaluation runs on other numbers,
/// relative to the cap's centre instead of to the patch's first point).
#[test]
fn relative_cap_records_tessellate_like_absolute_ones() {
    let mesh = samples::extraordinary_disk(5, 4);
    let t = Topology::new(&mesh).expect("valid mesh");
    let plan = SurfacePlan::new(&t, common::plan_options(3, false)).expect("plan");
    let tessellation = |relative: bool| {
        let mut sink = CollectSurface::new();
        let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
        ev.set_relative_caps(relative);
        ev.evaluate(&mesh.vertices, &mut sink).expect("evaluate");
        assert_eq!(
            sink.patches.iter().any(|p| p.origin.0 != [0.0; 3]),
            relative,
            "cap patches carry their centre only when relative"
        );
        capdiv_mesh::tessellate::tessellate(sink.patches.iter().map(|p| (p, 0)), 3, 1e-9)
    };
    let (absolute, relative) = (tessellation(false), tessellation(true));
    assert_eq!(absolute.faces, relative.faces);
    assert_eq!(absolute.positions.len(), relative.positions.len());
    // Coordinates of size up to about 4: a few roundings of 2⁻⁵² · 4.
    for (a, r) in absolute.positions.iter().zip(&relative.positions) {
        assert!(a.max_abs_diff(*r) < 1e-14, "{a:?} vs {r:?}");
    }
    for (a, r) in absolute.normals.iter().zip(&relative.normals) {
        assert!(a.max_abs_diff(*r) < 1e-12, "{a:?} vs {r:?}");
    }
}
