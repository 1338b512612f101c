//! The adaptive refinement's surface as a whole, in both modes (default:
//! C²PS and EG caps where no tag reaches; and every cap Catmull-Clark):
//! - coverage: per input face (per corner sub-square of a non-quad), the
//!   patches' domains, the adaptive last holes and the caps' last holes add
//!   up to the face's square exactly (0 for a hole face);
//! - the welded tessellation of a closed input is closed and consistently
//!   oriented, across every level transition the refinement makes (so no
//!   edge of a patch meets patches more than one level finer, and the finer
//!   bits are right); an open input's tessellation has as many boundary
//!   loops as the input has boundary and hole loops, and on grids whose
//!   limit map is known (a uniform grid's `x, y` are reproduced) its boundary
//!   is exactly the image of the input's boundary and holes;
//! - in the default mode, EG and C²PS caps stay where their configuration
//!   has no tag, and the faces whose configuration a tag reaches are
//!   Catmull-Clark with OpenSubdiv's rules (checked against OpenSubdiv in
//!   `osd_surface.rs`).

mod common;

use capdiv::Point3;
use capdiv_mesh::tessellate::{is_closed_and_oriented, tessellate};
use capdiv_mesh::{samples, EdgeCrease, MeshInput, PatchKind, Scheme, SurfacePlan, VertexCorner};
use common::{plan_and_evaluate, Collect};
use std::collections::HashMap;

/// [`common::check_coverage`] on a mesh without poles (C²PS patches are
/// checked in `tagged_step.rs`).
fn check_coverage(name: &str, m: &MeshInput, plan: &SurfacePlan<'_>, c: &Collect<f64>) {
    for p in &c.patches {
        assert_ne!(
            p.kind,
            PatchKind::C2ps,
            "coverage is checked on meshes without poles"
        );
    }
    common::check_coverage(name, m, &[], plan, c);
}

fn tess(c: &Collect<f64>) -> capdiv_mesh::tessellate::Tessellation<f64> {
    let patches = c.patches.iter().map(|p| (p, p.face));
    tessellate(patches, 3, 1e-9)
}

/// Boundary loops of a tessellation: boundary edges (used once) chained.
fn boundary_loops(faces: &[capdiv_mesh::tessellate::Face]) -> usize {
    let boundary = boundary_edges(faces.iter().map(|f| f.corners()));
    // Union-find over boundary vertices.
    let mut parent: HashMap<u32, u32> = HashMap::new();
    fn find(p: &mut HashMap<u32, u32>, x: u32) -> u32 {
        let y = *p.entry(x).or_insert(x);
        if y == x {
            x
        } else {
            let r = find(p, y);
            p.insert(x, r);
            r
        }
    }
    for &(a, b) in &boundary {
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        if ra != rb {
            parent.insert(ra, rb);
        }
    }
    let keys: Vec<u32> = parent.keys().copied().collect();
    let mut roots: Vec<u32> = keys.into_iter().map(|k| find(&mut parent, k)).collect();
    roots.sort_unstable();
    roots.dedup();
    roots.len()
}

fn crease(a: u32, b: u32, s: f32) -> EdgeCrease {
    EdgeCrease {
        vertices: [a, b],
        sharpness: s,
    }
}

/// Closed meshes with features: creases of several sharpness, corners,
/// triangles and pentagons, extraordinary points.
fn closed_cases() -> Vec<(&'static str, MeshInput)> {
    let mut creased_cube = samples::cube();
    for k in 0..4 {
        let f = creased_cube.faces[0].clone();
        creased_cube
            .tags
            .creases
            .push(crease(f[k], f[(k + 1) % 4], [0.5, 1.0, 2.5, 10.0][k]));
    }
    creased_cube.tags.corners.push(VertexCorner {
        vertex: creased_cube.faces[5][0],
        sharpness: 3.0,
    });
    let mut chaikin = creased_cube.clone();
    chaikin.tags.crease_method = capdiv_mesh::CreaseMethod::Chaikin;
    let mut torus = samples::torus(8, 6);
    for i in 0..8u32 {
        // A crease ring around the tube, sharpness rising along it.
        torus
            .tags
            .creases
            .push(crease(i * 6, ((i + 1) % 8) * 6, 0.5 + i as f32));
    }
    let mut rounded = samples::rounded_cube(3);
    rounded
        .tags
        .creases
        .push(crease(rounded.faces[0][0], rounded.faces[0][1], 10.0));
    vec![
        ("creased cube", creased_cube),
        ("creased cube, Chaikin", chaikin),
        ("creased torus", torus),
        (
            "triangle and pentagon",
            samples::triangle_and_pentagon_mesh(),
        ),
        ("rounded cube with one sharp edge", rounded),
        ("two-beam corner", samples::two_beam_corner()),
    ]
}

#[test]
fn closed_inputs_are_covered_and_tessellate_closed_in_both_modes() {
    for (name, m) in closed_cases() {
        for cc in [false, true] {
            for depth in [2, 4] {
                let (plan, c) = plan_and_evaluate(&m, depth, cc);
                let deepest = c.patches.iter().map(|p| p.level).max().unwrap();
                assert_eq!(plan.level_jumps, 0, "{name} (cc {cc}, depth {depth})");
                assert_eq!(plan.hole_conflicts, 0, "{name} (cc {cc}, depth {depth})");
                check_coverage(name, &m, &plan, &c);
                let t = tess(&c);
                assert_eq!(t.degenerate_dropped, 0, "{name}");
                is_closed_and_oriented(&t.faces).unwrap_or_else(|e| {
                    panic!("{name} (cc {cc}, depth {depth}, deepest level {deepest}): {e:?}")
                });
            }
        }
    }
}

/// A grid with one boundary and one interior hole of three faces, and a
/// semi-sharp crease.
fn holed_grid() -> MeshInput {
    let mut m = samples::grid(6, 6);
    m.tags.holes = vec![14, 15, 21];
    m.tags.creases.push(crease(9, 10, 2.0));
    m
}

/// A grid with a hole at its corner (the hole merges with the boundary).
fn corner_hole_grid() -> MeshInput {
    let mut m = samples::grid(4, 4);
    m.tags.holes = vec![0];
    m
}

#[test]
fn open_inputs_keep_their_boundary_and_hole_loops() {
    let holed = holed_grid();
    let mut fan = samples::extraordinary_disk(5, 3);
    fan.tags.creases.push(crease(0, 1, 10.0));
    let corner_hole = corner_hole_grid();
    let cases: Vec<(&str, MeshInput, usize)> = vec![
        ("grid", samples::grid(4, 3), 1),
        // One boundary and one interior hole of three faces.
        ("grid with holes", holed, 2),
        ("disk with a dart", fan, 1),
        // A hole at the corner merges with the boundary.
        ("grid, corner hole", corner_hole, 1),
    ];
    for (name, m, loops) in cases {
        for cc in [false, true] {
            let (plan, c) = plan_and_evaluate(&m, 3, cc);
            check_coverage(name, &m, &plan, &c);
            let t = tess(&c);
            assert_eq!(boundary_loops(&t.faces), loops, "{name} (cc {cc})");
        }
    }
}

/// Boundary edges (used by one face) of `faces`, as vertex pairs.
fn boundary_edges<'a>(faces: impl Iterator<Item = &'a [u32]>) -> Vec<(u32, u32)> {
    let mut count: HashMap<(u32, u32), i32> = HashMap::new();
    for c in faces {
        for k in 0..c.len() {
            let (a, b) = (c[k], c[(k + 1) % c.len()]);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    count
        .into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|(e, _)| e)
        .collect()
}

/// Distance in the `x, y` plane from `p` to the segment `a b`.
fn to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let t = ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1]);
    let t = t.clamp(0.0, 1.0);
    let q = [a[0] + t * d[0] - p[0], a[1] + t * d[1] - p[1]];
    q[0].hypot(q[1])
}

#[test]
fn open_grids_boundary_is_the_image_of_the_input_boundary_and_holes() {
    // `samples::grid` spaces x and y uniformly (z is a bump): Catmull-Clark
    // reproduces linear data, with the boundary, corner and crease rules
    // too, so the limit map is the identity in `x, y` and the surface's
    // boundary is the input's boundary and hole edges, in `x, y`. Every
    // tessellation boundary vertex must lie on an input boundary edge
    // (round-off: 1e-12) and the boundary lengths must agree (1e-9: a few
    // hundred edges of round-off each): no piece missing, none added.
    let holed = holed_grid();
    let corner_hole = corner_hole_grid();
    for (name, m) in [
        ("grid", samples::grid(4, 3)),
        ("grid with holes and a crease", holed),
        ("grid, corner hole", corner_hole),
    ] {
        let open = boundary_edges(
            m.faces
                .iter()
                .enumerate()
                .filter(|(f, _)| !m.tags.holes.contains(&(*f as u32)))
                .map(|(_, f)| &f[..]),
        );
        let xy = |v: u32| [m.vertices[v as usize][0], m.vertices[v as usize][1]];
        let input_length: f64 = open
            .iter()
            .map(|&(a, b)| (xy(a)[0] - xy(b)[0]).hypot(xy(a)[1] - xy(b)[1]))
            .sum();
        for cc in [false, true] {
            let (_, c) = plan_and_evaluate(&m, 3, cc);
            let t = tess(&c);
            let edges = boundary_edges(t.faces.iter().map(|f| f.corners()));
            let pxy = |v: u32| [t.positions[v as usize].0[0], t.positions[v as usize].0[1]];
            let mut length = 0.0;
            for &(a, b) in &edges {
                length += (pxy(a)[0] - pxy(b)[0]).hypot(pxy(a)[1] - pxy(b)[1]);
                for v in [a, b] {
                    let d = open
                        .iter()
                        .map(|&(p, q)| to_segment(pxy(v), xy(p), xy(q)))
                        .fold(f64::INFINITY, f64::min);
                    assert!(
                        d <= 1e-12,
                        "{name} (cc {cc}): boundary vertex {:?} is {d:e} off",
                        pxy(v)
                    );
                }
            }
            assert!(
                (length - input_length).abs() <= 1e-9,
                "{name} (cc {cc}): boundary length {length}, input's {input_length}"
            );
        }
    }
}

#[test]
fn eg_and_c2ps_caps_stay_where_no_tag_reaches() {
    // Two-beam corner: EG caps at valence 3 and 5. An infinitely sharp
    // crease on an edge of one extraordinary point's 1-ring takes that cap
    // away, no other; a semi-sharp one (2) holds it off until its sharpness
    // has decayed (level 2), the levels above it Catmull-Clark with the
    // crease rules.
    let m = samples::two_beam_corner();
    let (plain, _) = plan_and_evaluate(&m, 3, false);
    let eg = |p: &SurfacePlan<'_>| {
        p.extraordinary
            .iter()
            .filter(|e| e.scheme == Scheme::Eg)
            .count()
    };
    assert!(eg(&plain) >= 2);
    let v = plain.extraordinary[0].vertex.expect("an input vertex");
    let w = m
        .faces
        .iter()
        .find_map(|f| {
            let k = f.iter().position(|&x| x == v)?;
            Some(f[(k + 1) % f.len()])
        })
        .unwrap();
    let mut tagged = m.clone();
    tagged.tags.creases.push(crease(v, w, 10.0));
    let (plan, c) = plan_and_evaluate(&tagged, 3, false);
    assert!(
        plan.extraordinary.iter().all(|e| e.vertex != Some(v)),
        "cap at the crease kept"
    );
    assert!(
        eg(&plan) >= 1 && eg(&plan) < eg(&plain),
        "{} of {}",
        eg(&plan),
        eg(&plain)
    );
    // The caps whose faces the crease only neighbours come back a level
    // further in, where it is out of their c-nets' reach.
    let vertices = |p: &SurfacePlan<'_>| {
        let mut v: Vec<Option<u32>> = p.extraordinary.iter().map(|e| e.vertex).collect();
        v.sort();
        v
    };
    let mut expected = vertices(&plain);
    expected.retain(|&x| x != Some(v));
    assert_eq!(vertices(&plan), expected);
    check_coverage("two-beam corner with a crease", &tagged, &plan, &c);
    let mut semi = m.clone();
    semi.tags.creases.push(crease(v, w, 2.0));
    let (plan, c) = plan_and_evaluate(&semi, 3, false);
    let at_v: Vec<u32> = plan
        .extraordinary
        .iter()
        .filter(|e| e.vertex == Some(v))
        .map(|e| e.level)
        .collect();
    assert_eq!(at_v, [2], "one cap at v, below the crease's two levels");
    assert_eq!(eg(&plan), eg(&plain));
    check_coverage("two-beam corner with a semi-sharp crease", &semi, &plan, &c);
    // A globe: both poles keep C²PS when a crease runs along the equator.
    let mut globe = samples::globe(8, 6);
    let eq: Vec<u32> = (0..globe.vertices.len() as u32)
        .filter(|&i| globe.vertices[i as usize][2].abs() < 1e-9)
        .collect();
    assert!(eq.len() >= 8, "equator found");
    for f in globe.faces.clone() {
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            if eq.contains(&a) && eq.contains(&b) && a < b {
                globe.tags.creases.push(crease(a, b, 10.0));
            }
        }
    }
    let (plan, c) = plan_and_evaluate(&globe, 3, false);
    assert_eq!(plan.polar.len(), 2, "C2PS at both poles");
    let t = tess(&c);
    is_closed_and_oriented(&t.faces).expect("globe with a sharp equator closed");
    let _ = Point3::<f64>::ZERO;
}

/// Joins across level transitions: on closed meshes whose tags all decay
/// (semi-sharp creases and corners), the limit surface is C² away from the
/// irregular vertices, so at every shared patch edge sample (level 0 against
/// level 1 against level 2, …) the unit normals agree to 1e-9 and H, K to
/// 1e-6 of the local curvature scale (the tolerances of
/// `surface_smooth.rs`). Across an infinitely sharp crease the join is C⁰
/// by design: the same check on a mesh with one sees normals jump there.
#[test]
fn joins_across_level_transitions_are_c2_and_infinitely_sharp_creases_c0() {
    let mut torus = samples::torus(10, 8);
    for i in 0..10u32 {
        torus
            .tags
            .creases
            .push(crease(i * 8, ((i + 1) % 10) * 8, 0.5 + 0.3 * i as f32));
    }
    torus.tags.corners.push(VertexCorner {
        vertex: 43,
        sharpness: 2.0,
    });
    for cc in [false, true] {
        let (_, c) = plan_and_evaluate(&torus, 3, cc);
        let levels: std::collections::BTreeSet<u32> = c.patches.iter().map(|p| p.level).collect();
        assert!(levels.len() >= 3, "several levels meet: {levels:?}");
        let (pairs, wn, wh, wk) = common::closed_and_smooth("semi-sharp torus", &c.patches);
        assert!(pairs > 0);
        assert!(
            wn <= 1e-9 && wh <= 1e-6 && wk <= 1e-6,
            "normal {wn:e}, H {wh:e}, K {wk:e}"
        );
    }
    let mut sharp = samples::torus(10, 8);
    for i in 0..10u32 {
        sharp
            .tags
            .creases
            .push(crease(i * 8, ((i + 1) % 10) * 8, 10.0));
    }
    let (_, c) = plan_and_evaluate(&sharp, 3, true);
    let (_, wn, _, _) = common::closed_and_smooth("sharp torus", &c.patches);
    assert!(
        wn > 1e-2,
        "an infinitely sharp crease is a visible C0 join: normal jump {wn:e}"
    );
}

/// Refinement stays local: a plain cube (every face next to four valence-3
/// points) beside a 16×16 torus. Only the cube's faces are refined, no
/// whole-mesh step is taken, each torus face keeps its one level-0
/// B-spline patch, and the cube's corners get their caps one level in (EG
/// by default, Catmull-Clark with every cap Catmull-Clark), whose rings
/// meet the refined faces around them closed and oriented.
#[test]
fn refinement_stays_local_and_caps_come_one_level_in() {
    let cube = samples::cube();
    let torus = samples::torus(16, 16);
    let mut m = cube.clone();
    let base = m.vertices.len() as u32;
    m.vertices
        .extend(torus.vertices.iter().map(|p| [p[0] + 10.0, p[1], p[2]]));
    m.faces.extend(
        torus
            .faces
            .iter()
            .map(|f| f.iter().map(|&v| v + base).collect::<Vec<u32>>()),
    );
    for (cc, scheme) in [(false, Scheme::Eg), (true, Scheme::CatmullClark)] {
        let (plan, c) = plan_and_evaluate(&m, 3, cc);
        assert!(plan.steps.is_empty(), "cc {cc}: a whole-mesh step");
        let refined: Vec<u32> = plan.needed_refinement.iter().map(|u| u.face).collect();
        assert_eq!(refined, [0, 1, 2, 3, 4, 5], "cc {cc}");
        for f in 6..m.faces.len() as u32 {
            let on_f: Vec<&capdiv_mesh::PatchRecord<f64>> =
                c.patches.iter().filter(|p| p.face == f).collect();
            assert_eq!(on_f.len(), 1, "cc {cc}: torus face {f}");
            assert_eq!((on_f[0].kind, on_f[0].level), (PatchKind::Regular, 0));
        }
        let mut corners: Vec<(Option<u32>, u32, usize)> = plan
            .extraordinary
            .iter()
            .map(|e| {
                assert_eq!(e.scheme, scheme, "cc {cc}");
                (e.vertex, e.level, e.sectors.len())
            })
            .collect();
        corners.sort();
        let want: Vec<(Option<u32>, u32, usize)> = (0..8).map(|v| (Some(v), 1, 3)).collect();
        assert_eq!(corners, want, "cc {cc}");
        assert!(plan.fallbacks.is_empty(), "cc {cc}: {:?}", plan.fallbacks);
        check_coverage("cube beside a torus", &m, &plan, &c);
        is_closed_and_oriented(&tess(&c).faces).expect("closed and oriented");
    }
}

/// When every face of a mesh needs refinement, the whole-mesh step is the
/// adaptive refinement's first level made at once: the plan with the step
/// and the same mesh through the adaptive path alone (a boundary rule on a
/// closed mesh changes no rule, but is a tag, and tagged meshes take no
/// step) give the same patches — kind, level, face, domain, and control
/// points within 1e-12 of the mesh size (the two paths sum the same
/// stencils in another order).
#[test]
fn a_whole_mesh_step_is_the_adaptive_first_level_made_at_once() {
    for (name, m) in [
        ("cube", samples::cube()),
        (
            "triangle_and_pentagon",
            samples::triangle_and_pentagon_mesh(),
        ),
    ] {
        let mut tagged = m.clone();
        tagged.tags.boundary = capdiv_mesh::BoundaryInterpolation::EdgeOnly;
        let (plan_step, step) = plan_and_evaluate(&m, 3, false);
        let (plan_adaptive, adaptive) = plan_and_evaluate(&tagged, 3, false);
        assert!(!plan_step.steps.is_empty(), "{name}: no step");
        assert!(plan_adaptive.steps.is_empty(), "{name}: a step");
        let key = |p: &capdiv_mesh::PatchRecord<f64>| {
            (
                p.face,
                p.corner,
                p.level,
                p.domain.map(|x| (x * 65536.0).round() as i64),
            )
        };
        fn sorted<K: Ord>(
            c: &Collect<f64>,
            key: impl Fn(&capdiv_mesh::PatchRecord<f64>) -> K,
        ) -> Vec<&capdiv_mesh::PatchRecord<f64>> {
            let mut v: Vec<&capdiv_mesh::PatchRecord<f64>> = c.patches.iter().collect();
            v.sort_by_key(|p| key(p));
            v
        }
        let (a, b) = (sorted(&step, key), sorted(&adaptive, key));
        assert_eq!(a.len(), b.len(), "{name}: patch counts");
        let size = (0..3)
            .map(|k| {
                let (lo, hi) = m.vertices.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
                    (lo.min(p[k]), hi.max(p[k]))
                });
                hi - lo
            })
            .fold(0.0, f64::max);
        let mut worst = 0.0f64;
        for (p, q) in a.iter().zip(&b) {
            assert_eq!((key(p), p.kind), (key(q), q.kind), "{name}");
            let (gp, gq) = (
                common::control_grid(&p.geometry),
                common::control_grid(&q.geometry),
            );
            worst = worst.max(common::grid_distance(&gp, &gq) / size);
        }
        println!("{name}: {} patches, worst {worst:.1e}", a.len());
        assert!(worst <= 1e-12, "{name}: {worst:e}");
    }
}

/// Caps that the adaptive refinement makes join their surroundings as the
/// fast path's do: the hand's sixteen valence-5 junctions get EG caps,
/// most of them one level in, next to refined faces that meet the hand's level-0 patches
/// and C²PS caps; at every shared patch edge sample the unit normals agree
/// to 1e-9 and H, K to 1e-6 of the local curvature scale (the tolerances
/// of `surface_smooth.rs`: EG rings are C² with each other and with the
/// bicubic surround, docs/math/eg.md §9, and the surround is one C²
/// Catmull-Clark limit surface across its level transitions).
#[test]
fn adaptive_caps_join_their_surroundings_c2() {
    let hand = samples::hand();
    let (plan, c) = plan_and_evaluate(&hand, 3, false);
    assert!(plan.steps.is_empty());
    let eg_levels: Vec<u32> = plan
        .extraordinary
        .iter()
        .filter(|e| e.scheme == Scheme::Eg)
        .map(|e| e.level)
        .collect();
    println!("hand: EG caps at levels {eg_levels:?}");
    assert_eq!(eg_levels.len(), 16);
    assert!(eg_levels.iter().filter(|&&l| l >= 1).count() >= 8);
    let levels: std::collections::BTreeSet<u32> = c.patches.iter().map(|p| p.level).collect();
    assert!(levels.contains(&0) && levels.contains(&1), "{levels:?}");
    let (pairs, wn, wh, wk) = common::closed_and_smooth("hand", &c.patches);
    assert!(pairs > 0);
    assert!(
        wn <= 1e-9 && wh <= 1e-6 && wk <= 1e-6,
        "normal {wn:e}, H {wh:e}, K {wk:e}"
    );
}

/// `SurfacePlan::patch_count` is the number of patches the evaluation hands
/// on, known before evaluating (the CLI refuses too large a surface with
/// it): on every sample mesh with C²PS, EG, Catmull-Clark caps, adaptive
/// refinement and whole-mesh steps, at depths 1..4, in both modes.
#[test]
fn patch_count_is_known_before_evaluation() {
    let meshes = [
        ("globe", samples::globe(8, 6)),
        ("mushroom", samples::mushroom()),
        ("hand", samples::hand()),
        ("cube", samples::cube()),
        ("two_beam_corner", samples::two_beam_corner()),
        (
            "triangle_and_pentagon",
            samples::triangle_and_pentagon_mesh(),
        ),
        ("extraordinary_disk(7)", samples::extraordinary_disk(7, 3)),
    ];
    for (name, m) in &meshes {
        for depth in 1..=4 {
            for cc in [false, true] {
                let (plan, c) = plan_and_evaluate(m, depth, cc);
                assert_eq!(
                    plan.patch_count(),
                    c.patches.len() as u64,
                    "{name} depth {depth} cc {cc}"
                );
            }
        }
    }
}
