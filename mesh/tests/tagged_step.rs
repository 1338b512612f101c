//! The whole-mesh step in meshes with tags (`SurfacePlan`'s rule 4,
//! docs/adaptive.md "Whole-mesh steps"): a polar fan whose C²PS
//! configuration one step completes gets its C²PS cap when no tag reaches
//! it, whatever tags the mesh has elsewhere; a tag inside it makes it
//! Catmull-Clark with the tag rules.
//!
//! Oracles: the same mesh without its tags (the C²PS cap must not see a tag
//! it does not reach), OpenSubdiv (tests/osd) on the faces whose patches no
//! C²PS point reaches, and per input face the patches' domains and the
//! holes adding up to the face.

mod common;
#[path = "osd/mod.rs"]
mod osd;

use capdiv_mesh::adaptive::base::plain_base;
use capdiv_mesh::caps::{is_fan, polar_config, Reason};
use capdiv_mesh::chart::FaceChart;
use capdiv_mesh::global_step::{global_step, PolarSeed};
use capdiv_mesh::tessellate::{is_closed_and_oriented, tessellate, PatchGeometry};
use capdiv_mesh::{
    samples, BoundaryInterpolation, CreaseMethod, EdgeCrease, MeshInput, PatchKind, PatchRecord,
    SurfacePlan, VertexCorner,
};
use common::{check_coverage, control_grid, plan_and_evaluate, Collect};
use osd::{Answer, Job, Query};
use std::collections::BTreeSet;
use std::f64::consts::{PI, TAU};

/// A globe-like mesh: a north pole (vertex 0) and a fan of `sizes[0]`
/// triangles, latitude rings `r_i` of `sizes[i]` points on the unit sphere,
/// and with `south` a south pole (the last vertex) and its fan, else the
/// last ring is the boundary. Neighbouring rings of one size are joined by
/// quads; where the size grows or shrinks by one, by quads and one
/// pentagon. Face order: the north fan, then strip by strip (`r_i`–`r_{i+1}`,
/// column 0 first), then the south fan.
struct RingMesh {
    mesh: MeshInput,
    /// Vertices of each ring.
    rings: Vec<Vec<u32>>,
    /// Per face: its strip, counted from the north fan (0) to the south fan
    /// (`rings.len()`).
    strip: Vec<usize>,
}

fn ring_mesh(sizes: &[usize], south: bool) -> RingMesh {
    let mut v = vec![[0.0, 0.0, 1.0]];
    let mut rings: Vec<Vec<u32>> = Vec::new();
    for (i, &m) in sizes.iter().enumerate() {
        let th = PI * (i + 1) as f64 / (sizes.len() + 1) as f64;
        let ids = (0..m)
            .map(|j| {
                let ph = TAU * j as f64 / m as f64;
                v.push([th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()]);
                (v.len() - 1) as u32
            })
            .collect();
        rings.push(ids);
    }
    let pole = v.len() as u32;
    if south {
        v.push([0.0, 0.0, -1.0]);
    }
    let mut faces = Vec::new();
    let mut strip = Vec::new();
    let n = sizes[0];
    for j in 0..n {
        faces.push(vec![0, rings[0][j], rings[0][(j + 1) % n]]);
        strip.push(0);
    }
    for (i, w) in rings.windows(2).enumerate() {
        let (up, down) = (&w[0], &w[1]);
        let m = up.len().min(down.len());
        let quads = if up.len() == down.len() { m } else { m - 1 };
        for j in 0..quads {
            faces.push(vec![up[j], down[j], down[(j + 1) % m], up[(j + 1) % m]]);
        }
        if down.len() == m + 1 {
            faces.push(vec![up[m - 1], down[m - 1], down[m], down[0], up[0]]);
        } else if up.len() == m + 1 {
            faces.push(vec![up[m - 1], down[m - 1], down[0], up[0], up[m]]);
        }
        strip.resize(faces.len(), i + 1);
    }
    let last = &rings[rings.len() - 1];
    let m = last.len();
    for j in (0..m).filter(|_| south) {
        faces.push(vec![pole, last[(j + 1) % m], last[j]]);
    }
    strip.resize(faces.len(), rings.len());
    RingMesh {
        mesh: MeshInput::new(v, faces),
        rings,
        strip,
    }
}

/// North fan of valence 8 with links 1 and 2 (rings 0, 1) regular and no
/// link 3 (a pentagon between rings 1 and 2: one step completes it); ten
/// rings; the south fan (valence 9) complete.
fn incomplete_north() -> RingMesh {
    ring_mesh(&[8, 8, 9, 9, 9, 9, 9, 9, 9, 9], true)
}

fn crease(a: u32, b: u32, s: f32) -> EdgeCrease {
    EdgeCrease {
        vertices: [a, b],
        sharpness: s,
    }
}

/// Creases of sharpness `s(j)` along ring `i`'s edges.
fn ring_crease(r: &RingMesh, i: usize, s: impl Fn(usize) -> f32) -> Vec<EdgeCrease> {
    let ring = &r.rings[i];
    (0..ring.len())
        .map(|j| crease(ring[j], ring[(j + 1) % ring.len()], s(j)))
        .collect()
}

/// Tags that reach neither pole's configuration (both poles' triangles,
/// the quads out to their links 2 and the faces around those links), each
/// with its name.
fn far_tags(r: &RingMesh) -> Vec<(&'static str, MeshInput)> {
    let with = |f: &dyn Fn(&mut MeshInput)| {
        let mut m = r.mesh.clone();
        f(&mut m);
        m
    };
    vec![
        (
            "infinitely sharp crease",
            with(&|m| m.tags.creases = ring_crease(r, 5, |_| 10.0)),
        ),
        (
            "semi-sharp crease 2.5",
            with(&|m| m.tags.creases = ring_crease(r, 5, |_| 2.5)),
        ),
        (
            "hole",
            with(&|m| {
                let f = r.strip.iter().position(|&s| s == 5).unwrap();
                m.tags.holes.push(f as u32 + 2);
            }),
        ),
        (
            "Chaikin, creases 0.5 to 3.5",
            with(&|m| {
                m.tags.crease_method = CreaseMethod::Chaikin;
                m.tags.creases = ring_crease(r, 5, |j| 0.5 + (j % 4) as f32);
            }),
        ),
    ]
}

fn closed(name: &str, c: &Collect<f64>) {
    let t = tessellate(c.patches.iter().map(|p| (p, p.face)), 3, 1e-9);
    is_closed_and_oriented(&t.faces).unwrap_or_else(|e| panic!("{name}: not closed: {e:?}"));
}

/// The C²PS patches of the cap at `pole`, in emission order.
fn c2ps_patches(plan: &SurfacePlan<'_>, c: &Collect<f64>, pole: u32) -> Vec<Vec<Vec<[f64; 3]>>> {
    let index = plan
        .polar
        .iter()
        .position(|p| p.vertex == pole)
        .unwrap_or_else(|| panic!("no C²PS cap at vertex {pole}")) as u32;
    c.patches
        .iter()
        .filter(|p| p.cap == Some(index))
        .inspect(|p| assert_eq!(p.kind, PatchKind::C2ps))
        .map(|p| control_grid(&p.geometry))
        .collect()
}

fn max_diff(a: &[Vec<Vec<[f64; 3]>>], b: &[Vec<Vec<[f64; 3]>>]) -> f64 {
    assert_eq!(a.len(), b.len());
    let mut worst = 0.0f64;
    for (ga, gb) in a.iter().zip(b) {
        for (ra, rb) in ga.iter().zip(gb) {
            for (pa, pb) in ra.iter().zip(rb) {
                for k in 0..3 {
                    worst = worst.max((pa[k] - pb[k]).abs());
                }
            }
        }
    }
    worst
}

/// The incomplete north fan gets its C²PS cap after one step whatever tag
/// lies beyond its configuration, and that cap's patches are those of the
/// mesh without the tag: the cap is made of the step's points at and around
/// the pole, which are the untagged step's stencils — the same C²PS rows
/// for the pole and links 1 and 2, the smooth Catmull-Clark rule for link 3
/// (there `adaptive::subdivide`'s, which sums the same weights). Round-off
/// is all they may differ by: 1e-14 of the mesh size (2) allowed; measured
/// 0 (bit for bit). The complete south fan, stepped by C²PS in both, too.
#[test]
fn incomplete_fan_gets_c2ps_with_a_tag_far_away() {
    let r = incomplete_north();
    let south = (r.mesh.vertices.len() - 1) as u32;
    let depth = 4;
    let (plain, pc) = plan_and_evaluate(&r.mesh, depth, false);
    assert_eq!(plain.steps.len(), 1);
    for (name, m) in far_tags(&r) {
        let (tagged, tc) = plan_and_evaluate(&m, depth, false);
        assert_eq!(tagged.steps.len(), 1, "{name}: one step");
        assert_eq!(tagged.polar.len(), 2, "{name}: both poles C²PS");
        let mut worst = 0.0f64;
        for pole in [0, south] {
            let p = tagged.polar.iter().find(|p| p.vertex == pole).unwrap();
            let q = plain.polar.iter().find(|p| p.vertex == pole).unwrap();
            assert_eq!(p, q, "{name}: the cap at {pole} is the untagged one's");
            assert_eq!(p.prior_steps, 1);
            let d = max_diff(
                &c2ps_patches(&tagged, &tc, pole),
                &c2ps_patches(&plain, &pc, pole),
            );
            worst = worst.max(d);
        }
        println!("{name}: C²PS patches from the untagged mesh's: {worst:.1e}");
        assert!(worst <= 2e-14, "{name}: {worst:e}");
        assert!(
            tagged.input_fallbacks().next().is_none(),
            "{name}: {:?}",
            tagged.fallbacks
        );
        check_coverage(name, &m, &[], &tagged, &tc);
        if m.tags.holes.is_empty() {
            closed(name, &tc);
        }
    }
}

/// Samples of `p` at its own `(s, t)`.
fn eval(p: &PatchRecord<f64>, s: f64, t: f64) -> [f64; 3] {
    match &p.geometry {
        PatchGeometry::Cubic(g) => g.evaluate(s, t).unwrap().position.0,
        PatchGeometry::Quartic(g) => g.evaluate(s, t).unwrap().position.0,
    }
}

/// Asks OpenSubdiv for 3×3 samples of every B-spline patch of `c` in the
/// faces `far` picks; where its patch is exact, the two agree within 1e-10
/// of the mesh size (2). Returns the faces compared and the worst
/// difference.
fn compare_with_opensubdiv(
    name: &str,
    m: &MeshInput,
    c: &Collect<f64>,
    far: impl Fn(u32) -> bool,
) -> (BTreeSet<u32>, f64) {
    let mut job = Job::new(m);
    job.isolation = 10;
    let mut ours = Vec::new();
    for p in c
        .patches
        .iter()
        .filter(|p| p.kind == PatchKind::Regular && far(p.face))
    {
        let [u0, u1, v0, v1] = p.domain;
        for s in [0.2, 0.5, 0.8] {
            for t in [0.2, 0.5, 0.8] {
                job.queries.push(Query {
                    face: p.face,
                    corner: p.corner,
                    u: u0 + s * (u1 - u0),
                    v: v0 + t * (v1 - v0),
                });
                ours.push(eval(p, s, t));
            }
        }
    }
    let (answers, _) = osd::run(&job);
    let scale = 2.0;
    let (mut worst, mut compared) = (0.0f64, 0);
    let mut faces = BTreeSet::new();
    for (k, (a, mine)) in answers.iter().zip(&ours).enumerate() {
        match a {
            Answer::Exact(p, _) => {
                let d = (0..3).map(|i| (p[i] - mine[i]).abs()).fold(0.0, f64::max) / scale;
                assert!(
                    d <= 1e-10,
                    "{name}: {:?}: capdiv {mine:?}, OpenSubdiv {p:?}",
                    job.queries[k]
                );
                worst = worst.max(d);
                compared += 1;
                faces.insert(job.queries[k].face);
            }
            Answer::Irregular(_) => {}
            Answer::NoPatch => {
                panic!("{name}: OpenSubdiv has no patch at {:?}", job.queries[k])
            }
        }
    }
    println!(
        "{name}: {compared} samples on {} faces, worst {worst:.1e} of the size",
        faces.len()
    );
    (faces, worst)
}

/// Away from the poles the surface of the stepped tagged mesh is
/// OpenSubdiv's: every B-spline patch in a face at least 3 strips from both
/// poles (no C²PS point is among the control points there: the step's C²PS
/// rows are points inside the fans' triangles and the quads out to link 2)
/// agrees with OpenSubdiv at 3×3 parameters within 1e-10 of the mesh size,
/// where OpenSubdiv's patch is exact — the crease's and the hole's
/// neighbours' faces included.
#[test]
fn away_from_the_poles_the_tagged_surface_is_opensubdivs() {
    let r = incomplete_north();
    let rings = r.rings.len();
    for (name, m) in far_tags(&r) {
        let (plan, c) = plan_and_evaluate(&m, 4, false);
        assert_eq!(plan.steps.len(), 1);
        let (faces, _) = compare_with_opensubdiv(name, &m, &c, |f| {
            let s = r.strip[f as usize];
            s >= 3 && rings - s >= 3
        });
        // Every face of the strips on either side of ring 5 (the creases'
        // and the hole's) had a sample compared, but the hole.
        for f in (0..m.faces.len() as u32).filter(|&f| matches!(r.strip[f as usize], 5 | 6)) {
            assert!(
                faces.contains(&f) || m.tags.holes.contains(&f),
                "{name}: face {f} not compared"
            );
        }
    }
}

/// An open mesh (the north fan and seven rings, the last the boundary)
/// under each boundary rule, with a semi-sharp crease beyond the fan: the
/// step is taken with the rule, the fan's C²PS cap is the one of the mesh
/// without tags (the default rule), and the faces at least 3 strips from
/// the pole are OpenSubdiv's surface — the boundary's included (under
/// `none` its faces are holes: no patch, as in OpenSubdiv).
#[test]
fn open_mesh_under_every_boundary_rule() {
    let r = ring_mesh(&[8, 8, 9, 9, 9, 9, 9], false);
    let depth = 4;
    let (plain, pc) = plan_and_evaluate(&r.mesh, depth, false);
    assert_eq!(plain.steps.len(), 1);
    let last = r.rings.len() - 1;
    for boundary in [
        BoundaryInterpolation::EdgeAndCorner,
        BoundaryInterpolation::EdgeOnly,
        BoundaryInterpolation::None,
    ] {
        let name = format!("boundary {}", boundary.id());
        let mut m = r.mesh.clone();
        m.tags.boundary = boundary;
        m.tags.creases = ring_crease(&r, 4, |_| 2.5);
        let (tagged, tc) = plan_and_evaluate(&m, depth, false);
        assert_eq!(tagged.steps.len(), 1, "{name}");
        let d = max_diff(
            &c2ps_patches(&tagged, &tc, 0),
            &c2ps_patches(&plain, &pc, 0),
        );
        assert!(d <= 2e-14, "{name}: C²PS {d:e}");
        let holes: Vec<u32> = (0..m.faces.len() as u32)
            .filter(|&f| boundary == BoundaryInterpolation::None && r.strip[f as usize] == last)
            .collect();
        check_coverage(&name, &m, &holes, &tagged, &tc);
        let (faces, _) = compare_with_opensubdiv(&name, &m, &tc, |f| r.strip[f as usize] >= 3);
        for f in (0..m.faces.len() as u32).filter(|&f| r.strip[f as usize] >= 4) {
            assert!(
                faces.contains(&f) || holes.contains(&f),
                "{name}: face {f} not compared"
            );
        }
    }
}

/// The pole of a fan a tag reaches is Catmull-Clark: it falls back for a
/// feature and is the centre of the adaptive refinement's rings, or, where
/// that refinement separates it from the tag (its c-net clear of it, two or
/// more levels in), of an EG or Catmull-Clark cap there (rule 5), and then
/// has not fallen back.
fn tagged_pole_is_catmull_clark(
    name: &str,
    plan: &SurfacePlan<'_>,
    pole: u32,
    fallbacks: &[(u32, Reason)],
) {
    assert!(
        plan.polar.iter().all(|p| p.vertex != pole),
        "{name}: C²PS at {pole}"
    );
    let caps: Vec<u32> = plan
        .extraordinary
        .iter()
        .filter(|e| e.vertex == Some(pole))
        .map(|e| e.level)
        .collect();
    let others: Vec<_> = fallbacks.iter().filter(|f| f.0 != pole).collect();
    assert!(others.is_empty(), "{name}: other fallbacks {others:?}");
    match caps[..] {
        [] => assert_eq!(fallbacks, [(pole, Reason::Feature)], "{name}"),
        [level] => {
            assert!(level >= 2, "{name}: cap at level {level}");
            assert!(fallbacks.is_empty(), "{name}: {fallbacks:?}");
        }
        _ => panic!("{name}: caps at levels {caps:?}"),
    }
    println!("{name}: pole {pole}: fallbacks {fallbacks:?}, caps at levels {caps:?}");
}

/// A tag inside the incomplete fan's configuration (a crease on a spoke, on
/// a link-1 edge, on a link-2 edge, a corner at the pole, a hole among its
/// triangles) makes it Catmull-Clark with the tag rules: no C²PS cap at the
/// north pole, which falls back for a feature; no step (the south fan is
/// complete, so no other fan needs one), the south pole keeps its cap.
#[test]
fn a_tag_inside_the_fan_makes_it_catmull_clark() {
    let r = incomplete_north();
    let (l1, l2) = (&r.rings[0], &r.rings[1]);
    let south = (r.mesh.vertices.len() - 1) as u32;
    let mut cases: Vec<(&str, MeshInput)> = Vec::new();
    for (name, c) in [
        ("spoke", crease(0, l1[0], 10.0)),
        ("link-1 edge", crease(l1[2], l1[3], 2.5)),
        ("link-2 edge", crease(l2[4], l2[5], 10.0)),
    ] {
        let mut m = r.mesh.clone();
        m.tags.creases.push(c);
        cases.push((name, m));
    }
    for (name, sharpness) in [
        ("infinitely sharp corner at the pole", 10.0),
        ("corner 3 at the pole", 3.0),
    ] {
        let mut m = r.mesh.clone();
        m.tags.corners.push(VertexCorner {
            vertex: 0,
            sharpness,
        });
        cases.push((name, m));
    }
    let mut m = r.mesh.clone();
    m.tags.holes.push(3);
    cases.push(("hole among the triangles", m));
    for (name, m) in cases {
        let (plan, c) = plan_and_evaluate(&m, 3, false);
        assert!(plan.steps.is_empty(), "{name}: no step");
        assert!(
            plan.polar.iter().all(|p| p.vertex != 0),
            "{name}: no C²PS at the north pole"
        );
        assert!(
            plan.polar.iter().any(|p| p.vertex == south),
            "{name}: C²PS at the south pole"
        );
        let fallbacks: Vec<(u32, Reason)> = plan.input_fallbacks().collect();
        tagged_pole_is_catmull_clark(name, &plan, 0, &fallbacks);
        check_coverage(name, &m, &[], &plan, &c);
        if m.tags.holes.is_empty() {
            closed(name, &c);
        }
    }
}

/// Two incomplete fans, a tag inside one (a crease on a spoke, on a link-1
/// edge): the step refines the other by C²PS and the tagged one by
/// OpenSubdiv's rules (its triangles become quads); the other gets its cap
/// as in the mesh without the tag, the tagged pole is Catmull-Clark.
#[test]
fn of_two_incomplete_fans_the_one_a_tag_reaches_is_catmull_clark() {
    let r = ring_mesh(&[8, 8, 9, 9, 9, 9, 9, 9, 8, 8], true);
    let south = (r.mesh.vertices.len() - 1) as u32;
    let last = &r.rings[r.rings.len() - 1];
    let (plain, pc) = plan_and_evaluate(&r.mesh, 4, false);
    assert_eq!(plain.steps.len(), 1);
    assert_eq!(plain.polar.len(), 2);
    for (name, c) in [
        ("spoke", crease(south, last[3], 10.0)),
        ("link-1 edge", crease(last[0], last[1], 10.0)),
    ] {
        let mut m = r.mesh.clone();
        m.tags.creases.push(c);
        let (tagged, tc) = plan_and_evaluate(&m, 4, false);
        assert_eq!(tagged.steps.len(), 1, "{name}");
        let poles: Vec<u32> = tagged.polar.iter().map(|p| p.vertex).collect();
        assert_eq!(poles, [0], "{name}");
        let d = max_diff(
            &c2ps_patches(&tagged, &tc, 0),
            &c2ps_patches(&plain, &pc, 0),
        );
        println!("{name}: north cap from the untagged mesh's: {d:.1e}");
        assert!(d <= 2e-14, "{name}: {d:e}");
        let fallbacks: Vec<(u32, Reason)> = tagged.input_fallbacks().collect();
        tagged_pole_is_catmull_clark(name, &tagged, south, &fallbacks);
        check_coverage(name, &m, &[], &tagged, &tc);
        closed(name, &tc);
    }
}

/// The step of a mesh with tags on a mesh without any (its level as
/// `plain_base` makes it: OpenSubdiv's defaults) is the step of a mesh
/// without tags: OpenSubdiv's rules there are the Catmull-Clark rules with
/// the edge-and-corner boundary, so the same faces, charts, parents and
/// poles, every stencil row the same weights on the same vertices to
/// round-off (1e-15 allowed; measured ≤ 4e-18), and the level's boundary
/// edges infinitely sharp, every other edge and every vertex but the
/// one-face corners smooth, every face clean.
#[test]
fn the_tagged_step_of_an_untagged_mesh_is_the_plain_step() {
    let cases = [
        ("pole disk (open, a fan)", samples::pole_disk(7, 3)),
        ("globe", samples::globe(6, 7)),
        ("cube", samples::cube()),
        ("grid (corners)", samples::grid(4, 3)),
        (
            "triangles and pentagons",
            samples::triangle_and_pentagon_mesh(),
        ),
        ("incomplete fan", incomplete_north().mesh),
    ];
    for (name, m) in cases {
        let t = capdiv_mesh::Topology::new(&m).expect("manifold");
        let charts: Vec<FaceChart> = (0..t.num_faces() as u32).map(FaceChart::input).collect();
        let seeds: Vec<PolarSeed> = (0..t.num_vertices())
            .filter(|&v| is_fan(&t, v))
            .filter_map(|v| polar_config(&t, v, None, false).ok())
            .map(|c| PolarSeed {
                pole: c.pole,
                link1: c.links[0].clone(),
                link2: c.links[1].clone(),
                triangles: c.triangles,
                quads: c.quads,
            })
            .collect();
        let plain = global_step(&t, &charts, &seeds);
        let (tagged, level) =
            capdiv_mesh::tagged_step::tagged_step(&t, &plain_base(&t).unwrap(), &charts, &seeds)
                .expect("step")
                .expect("the base is the topology's");
        assert_eq!(tagged.faces, plain.faces, "{name}");
        assert_eq!(tagged.charts, plain.charts, "{name}");
        assert_eq!(tagged.parent, plain.parent, "{name}");
        assert_eq!(tagged.poles, plain.poles, "{name}");
        assert_eq!(tagged.num_vertices, plain.num_vertices, "{name}");
        let mut worst = 0.0f64;
        for i in 0..plain.stencils.len() {
            let mut a: Vec<(u32, f64)> = tagged.stencils.row(i).collect();
            let mut b: Vec<(u32, f64)> = plain.stencils.row(i).collect();
            a.retain(|e| e.1 != 0.0);
            b.retain(|e| e.1 != 0.0);
            a.sort_by_key(|e| e.0);
            b.sort_by_key(|e| e.0);
            let ids = |r: &[(u32, f64)]| r.iter().map(|e| e.0).collect::<Vec<_>>();
            assert_eq!(ids(&a), ids(&b), "{name}: row {i}");
            for (x, y) in a.iter().zip(&b) {
                worst = worst.max((x.1 - y.1).abs());
            }
        }
        println!("{name}: rows from the plain step's: {worst:.1e}");
        assert!(worst <= 1e-15, "{name}: {worst:e}");
        let l = &level.level;
        assert_eq!(l.num_faces(), plain.faces.len());
        for e in 0..l.edge_vertices.len() {
            let boundary = l.edge_corners(e).len() == 1;
            let want = if boundary { 10.0 } else { 0.0 };
            assert_eq!(l.edge_sharpness[e], want, "{name}: edge {e}");
        }
        for v in 0..l.num_vertices() {
            let corner = l.vertex_corners(v).len() == 1 && l.vertex_edges(v).len() == 2;
            let want = if corner { 10.0 } else { 0.0 };
            assert_eq!(l.vertex_sharpness[v], want, "{name}: vertex {v}");
        }
        assert!(level.clean.iter().all(|&c| c), "{name}: clean");
    }
}
