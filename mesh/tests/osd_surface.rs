//! capdiv's surface against OpenSubdiv's (tests/osd) on meshes with every
//! topology feature OpenSubdiv handles: the three boundary rules, boundary
//! vertices with 1..6 faces (convex and concave), extraordinary points 0, 1
//! and 2 rings from the boundary, creases of sharpness 0.5, 1, 2.5, 4 and 10,
//! crease chains, darts, crease vertices with 3 and more sharp edges,
//! Chaikin, corners, holes, non-manifold edges and vertices, interior
//! valence-2 vertices, triangles and n-gons, faces listing a vertex twice.
//!
//! With every cap Catmull-Clark (`PlanOptions::catmull_clark`), every
//! capdiv patch is sampled at 3×3 interior parameters and asked of
//! OpenSubdiv at the same (face, corner, u, v); where OpenSubdiv's patch is a
//! regular one (exact), the two points agree within 1e-10 of the mesh size
//! (both are exact B-spline evaluations of the same refinement in f64, so
//! their difference is round-off, ~1e-15 of the size per level); where
//! OpenSubdiv has no patch (a hole), capdiv has none either. Also: per input
//! face, the patches' domains and the last holes add up to the face (0 for
//! a hole).

mod common;
#[path = "osd/mod.rs"]
mod osd;

use capdiv_mesh::tessellate::PatchGeometry;
use capdiv_mesh::{
    samples, BoundaryInterpolation, CreaseMethod, EdgeCrease, Evaluator, MeshInput, PatchKind,
    PatchRecord, SurfacePlan, TriangleSubdivision, VertexCorner,
};
use common::Collect;
use osd::{Answer, Job, Query};

const PARAMS: [f64; 3] = [0.2, 0.5, 0.8];

/// The point of a patch at its own `(s, t)`.
fn eval(p: &PatchRecord<f64>, s: f64, t: f64) -> [f64; 3] {
    match &p.geometry {
        PatchGeometry::Cubic(g) => g.evaluate(s, t).unwrap().position.0,
        PatchGeometry::Quartic(g) => g.evaluate(s, t).unwrap().position.0,
    }
}

fn size(m: &MeshInput) -> f64 {
    let mut lo = [f64::MAX; 3];
    let mut hi = [f64::MIN; 3];
    for p in &m.vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
}

struct Report {
    compared: usize,
    worst: f64,
    /// The input faces with a sample compared.
    faces: std::collections::BTreeSet<u32>,
}

/// Plans `m` with every cap Catmull-Clark, evaluates it and compares with
/// OpenSubdiv; returns how many samples were compared and the worst
/// difference relative to the mesh size.
fn compare(name: &str, m: &MeshInput, depth: u32) -> Report {
    compare_in(name, m, depth, true).0
}

/// [`compare`] in either mode; in the default mode only Catmull-Clark
/// patches (kind `Regular`: B-spline patches of the mesh or of its
/// adaptive refinement) are held to 1e-10, and the worst distance of the EG
/// cap patches from OpenSubdiv's surface is returned beside (C²PS patches
/// are not asked, see below).
fn compare_in(name: &str, m: &MeshInput, depth: u32, cc: bool) -> (Report, f64) {
    let plan = SurfacePlan::for_mesh(m, common::plan_options(depth, cc))
        .unwrap_or_else(|e| panic!("{name}: plan: {e}"));
    assert!(
        plan.uncovered.is_empty(),
        "{name}: uncovered {:?}",
        plan.uncovered
    );
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    let mut c = Collect::default();
    ev.evaluate(&m.vertices, &mut c).expect("evaluate");
    assert!(!c.patches.is_empty(), "{name}: no patches");
    let mut job = Job::new(m);
    job.isolation = 10;
    let mut ours = Vec::new();
    // C²PS patches in fan triangles are given in polar coordinates, which
    // have no ptex counterpart: not asked.
    for p in c.patches.iter().filter(|p| p.kind != PatchKind::C2ps) {
        let [u0, u1, v0, v1] = p.domain;
        for &s in &PARAMS {
            for &t in &PARAMS {
                let (u, v) = (u0 + s * (u1 - u0), v0 + t * (v1 - v0));
                job.queries.push(Query {
                    face: p.face,
                    corner: p.corner,
                    u,
                    v,
                });
                ours.push((eval(p, s, t), p.level, p.kind));
            }
        }
    }
    let (answers, _) = osd::run(&job);
    let scale = size(m);
    let mut worst = 0.0f64;
    let mut caps = 0.0f64;
    let mut compared = 0;
    let mut faces = std::collections::BTreeSet::new();
    for (k, (a, (mine, level, kind))) in answers.iter().zip(&ours).enumerate() {
        match a {
            Answer::Exact(p, _) => {
                let d = (0..3).map(|i| (p[i] - mine[i]).abs()).fold(0.0, f64::max) / scale;
                if matches!(kind, PatchKind::Eg | PatchKind::C2ps) {
                    caps = caps.max(d);
                    continue;
                }
                assert!(
                    d <= 1e-10,
                    "{name}: query {:?} ({kind:?}, level {level}): capdiv {mine:?}, OpenSubdiv {p:?}, diff {d:e}",
                    job.queries[k]
                );
                worst = worst.max(d);
                compared += 1;
                faces.insert(job.queries[k].face);
            }
            Answer::Irregular(_) => {}
            Answer::NoPatch => panic!(
                "{name}: capdiv has a patch where OpenSubdiv has none: {:?}",
                job.queries[k]
            ),
        }
    }
    assert!(compared > 0, "{name}: nothing compared");
    (
        Report {
            compared,
            worst,
            faces,
        },
        caps,
    )
}

fn crease(a: u32, b: u32, s: f32) -> EdgeCrease {
    EdgeCrease {
        vertices: [a, b],
        sharpness: s,
    }
}

/// Vertex index of grid point `(i, j)` of `samples::grid(nu, _)`.
fn gv(nu: usize, i: usize, j: usize) -> u32 {
    (j * (nu + 1) + i) as u32
}

#[test]
fn open_grid_under_every_boundary_rule() {
    for b in [
        BoundaryInterpolation::EdgeAndCorner,
        BoundaryInterpolation::EdgeOnly,
        BoundaryInterpolation::None,
    ] {
        let mut m = samples::grid(5, 4);
        m.tags.boundary = b;
        let r = compare(b.id(), &m, 5);
        eprintln!(
            "grid {}: {} samples, worst {:e}",
            b.id(),
            r.compared,
            r.worst
        );
    }
}

#[test]
fn creases_of_every_sharpness_uniform_and_chaikin() {
    for method in [CreaseMethod::Uniform, CreaseMethod::Chaikin] {
        for s in [0.5f32, 1.0, 2.5, 4.0, 10.0] {
            let mut m = samples::grid(6, 6);
            // A chain along j = 3 from i = 1 to 5, its last edge half as sharp.
            for i in 1..5 {
                let si = if i == 4 { s * 0.5 } else { s };
                m.tags
                    .creases
                    .push(crease(gv(6, i, 3), gv(6, i + 1, 3), si));
            }
            m.tags.crease_method = method;
            let r = compare(&format!("crease {s} {}", method.id()), &m, 4);
            eprintln!(
                "crease {s} {}: {} samples, worst {:e}",
                method.id(),
                r.compared,
                r.worst
            );
        }
    }
}

#[test]
fn darts_corners_and_crease_junctions() {
    let mut m = samples::grid(6, 6);
    // A dart: one sharp edge ending inside.
    m.tags.creases.push(crease(gv(6, 1, 1), gv(6, 2, 1), 10.0));
    // Three and four sharp edges at a vertex.
    for (a, b) in [((3, 3), (4, 3)), ((3, 3), (3, 4)), ((3, 3), (2, 3))] {
        m.tags
            .creases
            .push(crease(gv(6, a.0, a.1), gv(6, b.0, b.1), 10.0));
    }
    for (a, b) in [
        ((5, 1), (5, 2)),
        ((5, 1), (4, 1)),
        ((5, 1), (5, 0)),
        ((5, 1), (6, 1)),
    ] {
        m.tags
            .creases
            .push(crease(gv(6, a.0, a.1), gv(6, b.0, b.1), 3.0));
    }
    // Corners: semi-sharp and infinitely sharp.
    m.tags.corners.push(VertexCorner {
        vertex: gv(6, 1, 4),
        sharpness: 0.5,
    });
    m.tags.corners.push(VertexCorner {
        vertex: gv(6, 4, 5),
        sharpness: 10.0,
    });
    let r = compare("darts and corners", &m, 4);
    eprintln!(
        "darts and corners: {} samples, worst {:e}",
        r.compared, r.worst
    );
}

#[test]
fn holes_leave_the_neighbours_unchanged() {
    let mut m = samples::grid(5, 5);
    m.tags.holes = vec![6, 7, 18];
    let r = compare("holes", &m, 4);
    eprintln!("holes: {} samples, worst {:e}", r.compared, r.worst);
}

#[test]
fn extraordinary_points_near_the_boundary() {
    for n in [3, 5, 6] {
        for rings in [1, 2, 3] {
            let m = samples::extraordinary_disk(n, rings.max(2));
            let m = if rings == 1 {
                // Drop the outer ring: the point is one ring from the boundary.
                shrink_disk(&m)
            } else {
                m
            };
            let r = compare(&format!("n={n} rings={rings}"), &m, 4);
            eprintln!(
                "ev n={n} rings={rings}: {} samples, worst {:e}",
                r.compared, r.worst
            );
        }
    }
}

/// The faces of an extraordinary disk within one ring of its centre.
fn shrink_disk(m: &MeshInput) -> MeshInput {
    let faces: Vec<Vec<u32>> = m.faces.iter().filter(|f| f.contains(&0)).cloned().collect();
    MeshInput::new(m.vertices.clone(), faces)
}

/// Bumpy height over the plane.
fn height(x: f64, y: f64) -> f64 {
    0.15 * (1.3 * x).sin() * (0.9 * y + 0.2).cos() + 0.05 * x * y
}

/// Builds faces from keyed points: `key(a, b)` names a vertex.
struct Builder {
    keys: std::collections::HashMap<(i64, i64, i64), u32>,
    vertices: Vec<[f64; 3]>,
    faces: Vec<Vec<u32>>,
}

impl Builder {
    fn new() -> Self {
        Builder {
            keys: Default::default(),
            vertices: Vec::new(),
            faces: Vec::new(),
        }
    }
    fn vertex(&mut self, key: (i64, i64, i64), p: [f64; 3]) -> u32 {
        let n = self.vertices.len() as u32;
        *self.keys.entry(key).or_insert_with(|| {
            self.vertices.push(p);
            n
        })
    }
    fn finish(self) -> MeshInput {
        MeshInput::new(self.vertices, self.faces)
    }
}

/// A boundary vertex with `k` quad sectors spanning `angle` degrees, each
/// sector a 2×2 grid: convex below 180°, concave above.
fn boundary_fan(k: usize, angle: f64) -> MeshInput {
    let mut b = Builder::new();
    let dir = |i: usize| {
        let a = (angle * i as f64 / k as f64).to_radians();
        [a.cos(), a.sin()]
    };
    let key = |s: usize, a: i64, c: i64| -> (i64, i64, i64) {
        match (a, c) {
            (0, 0) => (-1, 0, 0),
            (_, 0) => (s as i64, a, 0),
            (0, _) => (s as i64 + 1, c, 0),
            _ => (s as i64, a, c + 100),
        }
    };
    for s in 0..k {
        let (u, w) = (dir(s), dir(s + 1));
        let mut id = [[0u32; 3]; 3];
        for (a, row) in id.iter_mut().enumerate() {
            for (c, x) in row.iter_mut().enumerate() {
                let (af, cf) = (a as f64, c as f64);
                let (px, py) = (af * u[0] + cf * w[0], af * u[1] + cf * w[1]);
                *x = b.vertex(key(s, a as i64, c as i64), [px, py, height(px, py)]);
            }
        }
        for a in 0..2 {
            for c in 0..2 {
                b.faces
                    .push(vec![id[a][c], id[a + 1][c], id[a + 1][c + 1], id[a][c + 1]]);
            }
        }
    }
    b.finish()
}

#[test]
fn boundary_vertices_with_one_to_six_faces_convex_and_concave() {
    for (k, angles) in [
        (1, vec![90.0]),
        (2, vec![120.0, 180.0, 270.0]),
        (3, vec![180.0, 270.0]),
        (4, vec![180.0, 300.0]),
        (5, vec![180.0, 300.0]),
        (6, vec![180.0, 300.0]),
    ] {
        for angle in angles {
            for b in [
                BoundaryInterpolation::EdgeAndCorner,
                BoundaryInterpolation::EdgeOnly,
            ] {
                let mut m = boundary_fan(k, angle);
                m.tags.boundary = b;
                let name = format!("boundary fan k={k} {angle}° {}", b.id());
                let r = compare(&name, &m, 4);
                eprintln!("{name}: {} samples, worst {:e}", r.compared, r.worst);
            }
        }
    }
}

/// `pages` quad grids of 3×2 faces sharing their first column of vertices
/// (a non-manifold "book" spine of 3 edges).
fn book(pages: usize) -> MeshInput {
    let mut b = Builder::new();
    for p in 0..pages {
        let a = std::f64::consts::TAU * p as f64 / pages as f64;
        let mut id = [[0u32; 4]; 4];
        for (i, row) in id.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                let r = i as f64;
                let key = if i == 0 {
                    (-1, j as i64, 0)
                } else {
                    (p as i64, i as i64, j as i64)
                };
                let pos = [
                    r * a.cos(),
                    r * a.sin() + 0.1 * r * r,
                    j as f64 + 0.05 * r * j as f64,
                ];
                *x = b.vertex(key, pos);
            }
        }
        for i in 0..3 {
            for j in 0..3 {
                b.faces
                    .push(vec![id[i][j], id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]]);
            }
        }
    }
    b.finish()
}

/// Two 3×3 grids touching at one vertex (a bowtie vertex).
fn bowtie() -> MeshInput {
    let mut b = Builder::new();
    for g in 0..2i64 {
        let sign = if g == 0 { 1.0 } else { -1.0 };
        let mut id = [[0u32; 4]; 4];
        for (i, row) in id.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                let key = if i == 0 && j == 0 {
                    (-1, 0, 0)
                } else {
                    (g, i as i64, j as i64)
                };
                let (px, py) = (sign * i as f64, sign * j as f64);
                *x = b.vertex(key, [px, py, height(px, py) + 0.1 * g as f64 * px * px]);
            }
        }
        for i in 0..3 {
            for j in 0..3 {
                b.faces
                    .push(vec![id[i][j], id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]]);
            }
        }
    }
    b.finish()
}

#[test]
fn non_manifold_edges_and_vertices() {
    for pages in [3, 4] {
        let r = compare(&format!("book of {pages}"), &book(pages), 4);
        eprintln!(
            "book of {pages}: {} samples, worst {:e}",
            r.compared, r.worst
        );
    }
    let r = compare("bowtie", &bowtie(), 4);
    eprintln!("bowtie: {} samples, worst {:e}", r.compared, r.worst);
}

#[test]
fn interior_valence_two_vertex() {
    // A 4×4 grid whose middle quad (a, b, c, d) is split at a new vertex x
    // into (a, b, x, d) and (b, c, d, x): x has two edges and two faces.
    let mut m = samples::grid(4, 4);
    let (a, bb, c, d) = (gv(4, 1, 1), gv(4, 2, 1), gv(4, 2, 2), gv(4, 1, 2));
    let mid = m
        .faces
        .iter()
        .position(|f| f.contains(&a) && f.contains(&c))
        .unwrap();
    let x = m.vertices.len() as u32;
    let (pa, pc) = (m.vertices[a as usize], m.vertices[c as usize]);
    m.vertices.push([
        (pa[0] + pc[0]) / 2.0,
        (pa[1] + pc[1]) / 2.0,
        (pa[2] + pc[2]) / 2.0 + 0.05,
    ]);
    m.faces[mid] = vec![a, bb, x, d];
    m.faces.push(vec![bb, c, d, x]);
    let r = compare("valence 2", &m, 4);
    eprintln!("valence 2: {} samples, worst {:e}", r.compared, r.worst);
}

#[test]
fn triangles_and_ngons() {
    let r = compare(
        "triangle and pentagon",
        &samples::triangle_and_pentagon_mesh(),
        4,
    );
    eprintln!(
        "triangle and pentagon: {} samples, worst {:e}",
        r.compared, r.worst
    );
    // An open grid with a triangulated quad and a quad pair merged into a hexagon.
    let mut m = samples::grid(5, 5);
    let f = m.faces.remove(12);
    m.faces.push(vec![f[0], f[1], f[2]]);
    m.faces.push(vec![f[0], f[2], f[3]]);
    let (g, h) = (m.faces[0].clone(), m.faces[1].clone());
    m.faces[0] = vec![g[0], h[0], h[1], h[2], g[2], g[3]];
    m.faces.remove(1);
    let r = compare("triangulated grid", &m, 4);
    eprintln!(
        "triangulated grid: {} samples, worst {:e}",
        r.compared, r.worst
    );
}

/// An octahedron: every vertex a fan of four triangles.
fn octahedron() -> MeshInput {
    let vertices = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let faces = vec![
        vec![0, 2, 4],
        vec![2, 1, 4],
        vec![1, 3, 4],
        vec![3, 0, 4],
        vec![2, 0, 5],
        vec![1, 2, 5],
        vec![3, 1, 5],
        vec![0, 3, 5],
    ];
    MeshInput::new(vertices, faces)
}

#[test]
fn smooth_triangle_rule_next_to_triangles() {
    // `TRI_SUB_SMOOTH` changes the edge points of edges with a triangle on
    // one or both sides: open and closed meshes, triangles beside quads and
    // pentagons, a closed all-triangle mesh, and a crease on a triangle.
    let mut pentagon = samples::triangle_and_pentagon_mesh();
    pentagon.tags.triangles = TriangleSubdivision::Smooth;
    let mut grid = samples::grid(5, 5);
    let f = grid.faces.remove(12);
    grid.faces.push(vec![f[0], f[1], f[2]]);
    grid.faces.push(vec![f[0], f[2], f[3]]);
    grid.tags.triangles = TriangleSubdivision::Smooth;
    let mut octa = octahedron();
    octa.tags.triangles = TriangleSubdivision::Smooth;
    let mut creased = octa.clone();
    creased.tags.creases.push(crease(0, 2, 1.5));
    for (name, m) in [
        ("triangle and pentagon", &pentagon),
        ("triangulated grid", &grid),
        ("octahedron", &octa),
        ("creased octahedron", &creased),
    ] {
        let r = compare(name, m, 4);
        eprintln!(
            "smooth triangles, {name}: {} samples, worst {:e}",
            r.compared, r.worst
        );
    }
    // The rule changes the surface: the octahedron's smooth and Catmark
    // limit points differ (by much more than round-off).
    let limit = |m: &MeshInput| {
        let mut job = Job::new(m);
        job.limits = vec![4];
        osd::run(&job).1[0]
    };
    let mut catmark = octa.clone();
    catmark.tags.triangles = TriangleSubdivision::Catmark;
    let (a, b) = (limit(&octa), limit(&catmark));
    assert!((a[2] - b[2]).abs() > 1e-3, "smooth {a:?} vs catmark {b:?}");
}

#[test]
fn cube_with_creased_edges_and_a_hole() {
    let mut m = samples::cube();
    for f in m.faces.clone().iter().take(1) {
        for k in 0..4 {
            m.tags.creases.push(crease(f[k], f[(k + 1) % 4], 2.5));
        }
    }
    m.tags.holes.push(5);
    let r = compare("creased cube", &m, 5);
    eprintln!("creased cube: {} samples, worst {:e}", r.compared, r.worst);
}

#[test]
fn a_face_with_the_other_orientation() {
    // One face of a grid listed clockwise: its four edges are run twice the
    // same way, which OpenSubdiv takes as non-manifold (infinitely sharp).
    let mut m = samples::grid(5, 5);
    m.faces[12].reverse();
    let r = compare("reversed face", &m, 4);
    eprintln!("reversed face: {} samples, worst {:e}", r.compared, r.worst);
}

#[test]
fn cube_with_a_crease_of_every_sharpness_and_a_corner() {
    for depth in [2, 3, 4] {
        let mut m = samples::cube();
        for k in 0..4 {
            let f = m.faces[0].clone();
            m.tags
                .creases
                .push(crease(f[k], f[(k + 1) % 4], [0.5, 1.0, 2.5, 10.0][k]));
        }
        m.tags.corners.push(VertexCorner {
            vertex: m.faces[5][0],
            sharpness: 3.0,
        });
        let r = compare("cube, every sharpness", &m, depth);
        eprintln!(
            "cube, every sharpness, depth {depth}: {} samples, worst {:e}",
            r.compared, r.worst
        );
    }
}

/// The default mode: C²PS and EG caps where no tag reaches, Catmull-Clark
/// with OpenSubdiv's rules elsewhere. The Catmull-Clark patches equal
/// OpenSubdiv's surface as in the other tests; the caps differ by design,
/// and how much is printed per case for EG (the papers' schemes are not
/// Catmull-Clark; their distance from it is a property of the shape). On
/// the globe and the mushroom, C²PS caps take the poles; the Catmull-Clark
/// faces around them are compared.
#[test]
fn default_mode_catmull_clark_regions_equal_opensubdiv() {
    let mut beams = samples::two_beam_corner();
    let f = beams.faces[0].clone();
    beams.tags.creases.push(crease(f[0], f[1], 2.0));
    let mut globe = samples::globe(8, 6);
    globe
        .tags
        .creases
        .push(crease(globe.faces[20][0], globe.faces[20][1], 10.0));
    let mut rounded = samples::rounded_cube(3);
    rounded.tags.holes.push(0);
    for (name, m) in [
        ("two-beam corner with a crease", beams),
        ("globe with a sharp edge", globe),
        ("rounded cube with a hole", rounded),
        ("mushroom", samples::mushroom()),
    ] {
        let (r, caps) = compare_in(name, &m, 4, false);
        eprintln!(
            "{name} (default mode): {} Catmull-Clark samples, worst {:e}; EG caps from OpenSubdiv's surface: worst {caps:.3e} of the size",
            r.compared, r.worst
        );
    }
}

/// A 7×7 grid whose middle quad `[q0, q1, q2, q3]` (face 24) becomes
/// `face(q)`.
fn grid_with_middle(face: fn(&[u32]) -> Vec<u32>) -> MeshInput {
    let mut m = samples::grid(7, 7);
    let q = m.faces[24].clone();
    m.faces[24] = face(&q);
    m
}

/// A 7×7 grid whose quads (2,2) and (3,3), diagonal neighbours at one
/// vertex, are one octagon visiting that vertex twice (no edge repeated).
fn grid_with_pinched_octagon() -> MeshInput {
    let mut m = samples::grid(7, 7);
    let c = gv(7, 3, 3);
    let from_c = |f: &[u32]| -> Vec<u32> {
        let k = f.iter().position(|&x| x == c).unwrap();
        (0..4).map(|i| f[(k + i) % 4]).collect()
    };
    let mut octagon = from_c(&m.faces[16]);
    octagon.extend(from_c(&m.faces[24]));
    m.faces[16] = octagon;
    m.faces.remove(24);
    m
}

#[test]
fn faces_listing_a_vertex_twice() {
    // OpenSubdiv makes a face's edges one by one: an edge a face runs twice
    // is two edges, both non-manifold; a degenerate edge (a, a) is
    // non-manifold; so are their vertices. Non-consecutive repeats (both
    // edges to the repeated vertex doubled, one doubled and run the same way
    // as the neighbour's, or none doubled), consecutive ones (a degenerate
    // edge in a quad, a pentagon, a lone triangle), under every boundary
    // rule, one with semi-sharp Chaikin creases beside; lone faces and a
    // third face on an edge a face runs twice; depth 4, and 2 and 5 in
    // either mode.
    // (name, mesh, the face that lists a vertex twice)
    let cases: Vec<(&str, MeshInput, u32)> = vec![
        (
            "[a b a c]",
            grid_with_middle(|q| vec![q[0], q[1], q[0], q[2]]),
            24,
        ),
        (
            "[a b c a d]",
            grid_with_middle(|q| vec![q[0], q[1], q[2], q[0], q[3]]),
            24,
        ),
        (
            "[a a b c]",
            grid_with_middle(|q| vec![q[0], q[0], q[1], q[2]]),
            24,
        ),
        (
            "[a a b c d]",
            grid_with_middle(|q| vec![q[0], q[0], q[1], q[2], q[3]]),
            24,
        ),
        (
            "[a b a b]",
            grid_with_middle(|q| vec![q[0], q[1], q[0], q[1]]),
            24,
        ),
        ("pinched octagon", grid_with_pinched_octagon(), 16),
        (
            "lone [a b a c]",
            MeshInput::new(
                vec![[0.0, 0.0, 0.0], [1.0, 0.2, 0.1], [0.1, 1.0, -0.2]],
                vec![vec![0, 1, 0, 2]],
            ),
            0,
        ),
        (
            "lone [a b b]",
            MeshInput::new(vec![[0.0, 0.0, 0.0], [1.0, 0.2, 0.1]], vec![vec![0, 1, 1]]),
            0,
        ),
        (
            "lone [a b a b a b]",
            MeshInput::new(
                vec![[0.0, 0.0, 0.0], [1.0, 0.3, 0.2]],
                vec![vec![0, 1, 0, 1, 0, 1]],
            ),
            0,
        ),
        (
            "lone [a b a c] [b a d] [a b d]",
            MeshInput::new(
                vec![
                    [0.0, 0.0, 0.0],
                    [1.0, 0.3, 0.2],
                    [2.0, 1.2, 0.0],
                    [3.0, 2.7, 0.2],
                ],
                vec![vec![0, 1, 0, 2], vec![1, 0, 3], vec![0, 1, 3]],
            ),
            0,
        ),
    ];
    for (name, m, face) in &cases {
        for b in [
            BoundaryInterpolation::EdgeAndCorner,
            BoundaryInterpolation::EdgeOnly,
            BoundaryInterpolation::None,
        ] {
            let mut m = m.clone();
            m.tags.boundary = b;
            let name = format!("{name} {}", b.id());
            if b == BoundaryInterpolation::None && name.starts_with("lone") {
                // Every face is a hole: nothing to compare.
                continue;
            }
            let r = compare(&name, &m, 4);
            // Under VTX_BOUNDARY_NONE the face is a hole (its edges run
            // once are boundary edges).
            if b != BoundaryInterpolation::None {
                assert!(r.faces.contains(face), "{name}: face {face} not compared");
            }
            eprintln!("{name}: {} samples, worst {:e}", r.compared, r.worst);
        }
        // Other depths, and the default mode (its Catmull-Clark patches;
        // EG caps, as at a pentagon's face point, differ by design).
        for depth in [2, 5] {
            for cc in [true, false] {
                let (r, _) = compare_in(name, m, depth, cc);
                eprintln!(
                    "{name} depth {depth} cc {cc}: {} samples, worst {:e}",
                    r.compared, r.worst
                );
            }
        }
    }
    let mut m = grid_with_middle(|q| vec![q[0], q[1], q[0], q[2]]);
    let q = samples::grid(7, 7).faces[24].clone();
    m.tags.creases.push(crease(q[1], q[2], 2.5));
    m.tags.creases.push(crease(q[2], gv(7, 5, 4), 1.5));
    m.tags.crease_method = CreaseMethod::Chaikin;
    let r = compare("[a b a c] with creases", &m, 4);
    assert!(r.faces.contains(&24));
    eprintln!(
        "[a b a c] with creases: {} samples, worst {:e}",
        r.compared, r.worst
    );
}
