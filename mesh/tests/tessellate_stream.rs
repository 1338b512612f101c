//! Streaming tessellation (`capdiv_mesh::tessellate::stream`) against the
//! collected one (`tessellate`): the same welded mesh — vertices in the same
//! order with the same positions and normals, the same faces in the same
//! order, the same closedness verdict — on the sample meshes (caps of every
//! scheme, adaptive refinement with tags, open meshes), while the weld table
//! holds a front whose size does not grow with the depth.

mod common;

use capdiv::{Point3, TensorPatch};
use capdiv_mesh::samples;
use capdiv_mesh::sinks::CollectSurface;
use capdiv_mesh::tessellate::{
    closed_in_order, is_closed_and_oriented, tessellate, write_obj, MeshSink, ObjWriter,
    PatchGeometry, StreamSummary, StreamTessellator, TessellatingSink, Tessellation,
};
use capdiv_mesh::{CapRecord, Evaluator, MeshInput, PatchKind, PatchRecord, SurfaceSink, Unit};
use common::plan;

/// Every patch and cap, in the evaluator's order.
type Collect = CollectSurface<f64>;

fn patches(mesh: &MeshInput, depth: u32) -> Vec<PatchRecord<f64>> {
    let plan = plan(mesh, depth);
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    let mut c = Collect::default();
    ev.evaluate(&mesh.vertices, &mut c).expect("evaluate");
    c.patches
}

/// A patch to tessellate, tagged by its level.
fn tess_patch(p: &PatchRecord<f64>) -> (&PatchRecord<f64>, u32) {
    (p, p.level)
}

/// The CLI's weld tolerance: 1e-9 of the bounding box's largest side.
fn weld_tolerance(mesh: &MeshInput) -> f64 {
    let mut size: f64 = 0.0;
    for k in 0..3 {
        let lo = mesh
            .vertices
            .iter()
            .map(|p| p[k])
            .fold(f64::INFINITY, f64::min);
        let hi = mesh
            .vertices
            .iter()
            .map(|p| p[k])
            .fold(f64::NEG_INFINITY, f64::max);
        size = size.max(hi - lo);
    }
    1e-9 * size
}

/// The streamed tessellation of `patches`, collected by the sink.
fn streamed(
    patches: &[PatchRecord<f64>],
    grid: usize,
    tol: f64,
) -> (Tessellation<f64>, StreamSummary) {
    let mut tess = StreamTessellator::new(grid, tol);
    let mut out = Tessellation::default();
    for p in patches {
        tess.push(p, p.level, &mut out);
    }
    let summary = tess.finish(&mut out);
    (out, summary)
}

fn meshes() -> Vec<(&'static str, MeshInput)> {
    vec![
        ("globe", samples::globe(8, 6)),
        ("mushroom", samples::mushroom()),
        ("hand", samples::hand()),
        ("cube", samples::cube()),
        ("rounded cube", samples::rounded_cube(2)),
        ("two-beam corner", samples::two_beam_corner()),
        ("torus", samples::torus(6, 5)),
        ("grid (open)", samples::grid(4, 3)),
        (
            "extraordinary disk (open)",
            samples::extraordinary_disk(5, 2),
        ),
        (
            "triangle and pentagon",
            samples::triangle_and_pentagon_mesh(),
        ),
        ("pole disk (open)", samples::pole_disk(7, 3)),
        ("feature mix (tags)", samples::feature_mix(200)),
    ]
}

fn assert_same(
    name: &str,
    collected: &Tessellation<f64>,
    got: &Tessellation<f64>,
    s: &StreamSummary,
) {
    assert_eq!(
        got.positions.len(),
        collected.positions.len(),
        "{name}: vertices"
    );
    // Positions are first samples, normals computed by the same formulas in
    // the same order: equal bit for bit.
    assert!(got.positions == collected.positions, "{name}: positions");
    assert!(got.normals == collected.normals, "{name}: normals");
    assert_eq!(got.faces, collected.faces, "{name}: faces");
    assert_eq!(got.tags, collected.tags, "{name}: tags");
    assert_eq!(s.samples, collected.samples, "{name}: samples");
    assert_eq!(s.degenerate_dropped, collected.degenerate_dropped, "{name}");
    assert_eq!(s.vertices, collected.positions.len(), "{name}");
    assert_eq!(s.triangles + s.quads, collected.faces.len(), "{name}");
    assert_eq!(
        s.closed,
        is_closed_and_oriented(&collected.faces),
        "{name}: closedness"
    );
}

#[test]
fn streamed_tessellation_equals_the_collected_one() {
    for (name, mesh) in meshes() {
        let tol = weld_tolerance(&mesh);
        for depth in [1, 3] {
            let ps = patches(&mesh, depth);
            for grid in [1, 4] {
                let collected = tessellate(ps.iter().map(tess_patch), grid, tol);
                let (got, s) = streamed(&ps, grid, tol);
                let what = format!("{name}, depth {depth}, grid {grid}");
                assert_same(&what, &collected, &got, &s);
                assert!(s.peak_weld <= got.positions.len(), "{what}");
            }
        }
    }
}

#[test]
fn streamed_tessellation_welds_equal_coordinates_with_tolerance_zero() {
    for (name, mesh) in [("hand", samples::hand()), ("globe", samples::globe(6, 5))] {
        let ps = patches(&mesh, 2);
        let collected = tessellate(ps.iter().map(tess_patch), 3, 0.0);
        let (got, s) = streamed(&ps, 3, 0.0);
        assert_same(name, &collected, &got, &s);
    }
}

#[test]
fn tessellating_sink_streams_the_evaluation() {
    let mesh = samples::mushroom();
    let plan = plan(&mesh, 3);
    let tol = weld_tolerance(&mesh);
    let ps = patches(&mesh, 3);
    let collected = tessellate(ps.iter().map(tess_patch), 4, tol);

    let mut tess = StreamTessellator::new(4, tol);
    let mut out = Tessellation::default();
    let mut sink = TessellatingSink {
        tess: &mut tess,
        out: &mut out,
        tag: |p| p.level,
    };
    let mut ev = Evaluator::<f64>::new(&plan).unwrap();
    ev.evaluate(&mesh.vertices, &mut sink).unwrap();
    let s = tess.finish(&mut out);
    assert_same("mushroom through the sink", &collected, &out, &s);
    assert_eq!(s.closed, Ok(()));
}

#[test]
fn obj_writer_writes_the_lines_of_write_obj() {
    let mesh = samples::globe(6, 4);
    let tol = weld_tolerance(&mesh);
    let ps = patches(&mesh, 2);
    let collected = tessellate(ps.iter().map(tess_patch), 2, tol);
    let whole = write_obj(&collected, &[]);

    let mut tess = StreamTessellator::new(2, tol);
    let mut w = ObjWriter::new(String::new(), &["streamed"]);
    for p in &ps {
        tess.push(p, 0, &mut w);
    }
    tess.finish(&mut w);
    assert_eq!(w.error, Ok(()));
    assert!(w.out.starts_with("# streamed\n"));
    // Each face comes after its vertices; the vertex lines and the face
    // lines are each those of the collected file, in the same order.
    let mut vertices = 0usize;
    for line in w
        .out
        .lines()
        .filter(|l| l.starts_with("v ") || l.starts_with("f "))
    {
        if line.starts_with("v ") {
            vertices += 1;
        } else {
            for c in line.split_whitespace().skip(1) {
                let i: usize = c.split("//").next().unwrap().parse().unwrap();
                assert!(i <= vertices, "{line} before its vertex");
            }
        }
    }
    let pick = |text: &str, keys: &[&str]| -> Vec<String> {
        text.lines()
            .filter(|l| keys.iter().any(|k| l.starts_with(k)))
            .map(String::from)
            .collect()
    };
    assert_eq!(pick(&w.out, &["v ", "vn "]), pick(&whole, &["v ", "vn "]));
    assert_eq!(pick(&w.out, &["f "]), pick(&whole, &["f "]));
}

/// The table holds the front between patches done and to come: for caps
/// whose rings keep their patch count (EG, Catmull-Clark), deeper caps add
/// rings behind the front, not to it. (From depth 3 on the front is whole:
/// a ring's inner edge waiting for the next ring, beside the last ring's
/// hole corners.)
#[test]
fn weld_table_does_not_grow_with_the_depth() {
    for (name, mesh) in [
        ("cube", samples::cube()),
        ("rounded cube", samples::rounded_cube(3)),
        (
            "triangle and pentagon",
            samples::triangle_and_pentagon_mesh(),
        ),
    ] {
        let tol = weld_tolerance(&mesh);
        let shallow = streamed(&patches(&mesh, 3), 4, tol);
        let deep = streamed(&patches(&mesh, 8), 4, tol);
        assert!(
            deep.0.positions.len() > 2 * shallow.0.positions.len(),
            "{name}"
        );
        assert!(
            deep.1.peak_weld <= shallow.1.peak_weld,
            "{name}: {} at depth 8, {} at depth 3",
            deep.1.peak_weld,
            shallow.1.peak_weld
        );
        // Output waits only within one cap's last ring.
        assert!(deep.1.peak_waiting < deep.0.positions.len() / 4, "{name}");
    }
}

/// A torus of `2·k²` triangles: every vertex of valence 6, so a cap at
/// every vertex and every face centre.
fn triangle_torus(k: usize) -> MeshInput {
    let mut vertices = Vec::new();
    for i in 0..k {
        let a = std::f64::consts::TAU * i as f64 / k as f64;
        for j in 0..k {
            let b = std::f64::consts::TAU * j as f64 / k as f64;
            let r = 3.0 + b.cos();
            vertices.push([r * a.cos(), r * a.sin(), b.sin()]);
        }
    }
    let at = |i: usize, j: usize| ((i % k) * k + j % k) as u32;
    let mut faces = Vec::new();
    for i in 0..k {
        for j in 0..k {
            faces.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            faces.push(vec![at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    MeshInput::new(vertices, faces)
}

/// The evaluator's order (regular patches and caps interleaved, by input
/// face) keeps the weld table to a front: a torus with four times the
/// faces (and output) holds at most about twice the vertices, the front
/// being about as long as the torus is wide. Emitting every cap after
/// every regular patch held the boundary of every cap (a fifth of the
/// vertices here, growing with the mesh).
#[test]
fn weld_table_grows_with_the_front_not_the_mesh() {
    let run = |k: usize| {
        let mesh = triangle_torus(k);
        let (t, s) = streamed(&patches(&mesh, 2), 2, weld_tolerance(&mesh));
        assert!(s.closed.is_ok(), "k = {k}: {:?}", s.closed);
        (t.positions.len(), s.peak_weld)
    };
    let (small, big) = (run(12), run(24));
    assert!(big.0 >= 4 * small.0 - 16, "{small:?} {big:?}");
    assert!(
        big.1 <= small.1 * 5 / 2,
        "weld table {} for {} vertices, {} for {}",
        big.1,
        big.0,
        small.1,
        small.0
    );
    assert!(big.1 * 10 < big.0, "{big:?}");
}

/// Samples on a boundary marked by the records ([`PatchRecord::boundary`])
/// leave the weld table once their patches are done: sixteen disjoint copies
/// of the feature mix (each with an open disk) hold about what one copy
/// holds. Without the marks each copy leaves its whole boundary behind.
#[test]
fn weld_table_lets_go_of_marked_boundaries() {
    let run = |copies: usize, marks: bool| {
        let mesh = samples::feature_mix(1077 * copies);
        let mut ps = patches(&mesh, 2);
        if !marks {
            for p in &mut ps {
                p.boundary = 0;
            }
        }
        let (t, s) = streamed(&ps, 2, weld_tolerance(&mesh));
        (t.positions.len(), s.peak_weld)
    };
    let (one, sixteen) = (run(1, true), run(16, true));
    assert!(sixteen.0 > 14 * one.0, "{one:?} {sixteen:?}");
    assert!(sixteen.1 < 2 * one.1, "{one:?} {sixteen:?}");
    let unmarked = run(16, false);
    assert!(unmarked.1 > 4 * sixteen.1, "{unmarked:?} {sixteen:?}");
}

/// [`SurfacePlan::order`] lists every regular patch and every cap once, and
/// the evaluator gives each cap's record after its patches.
#[test]
fn the_emission_order_gives_every_patch_and_cap_once() {
    for (name, mesh) in meshes() {
        let plan = plan(&mesh, 2);
        let caps = plan.polar.len() + plan.extraordinary.len();
        let mut regular = vec![0; plan.regular.len()];
        let mut cap = vec![0; caps];
        for u in &plan.order {
            match *u {
                Unit::Regular(i) => regular[i as usize] += 1,
                Unit::Cap(i) => cap[i as usize] += 1,
            }
        }
        assert!(regular.iter().all(|&c| c == 1), "{name}: {regular:?}");
        assert!(cap.iter().all(|&c| c == 1), "{name}: {cap:?}");

        /// Checks that no patch of a cap comes after that cap's record.
        #[derive(Default)]
        struct Order {
            ended: Vec<u32>,
            late: usize,
            regular: usize,
        }
        impl SurfaceSink<f64> for Order {
            fn patch(&mut self, p: &PatchRecord<f64>) {
                match p.cap {
                    Some(c) => self.late += usize::from(self.ended.contains(&c)),
                    None => self.regular += 1,
                }
            }
            fn cap(&mut self, c: &CapRecord<f64>) {
                self.ended.push(c.index);
            }
        }
        let mut sink = Order::default();
        let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
        ev.evaluate(&mesh.vertices, &mut sink).expect("evaluate");
        assert_eq!(sink.late, 0, "{name}");
        assert_eq!(sink.regular, plan.regular.len(), "{name}");
        let mut ended = sink.ended.clone();
        ended.sort_unstable();
        assert_eq!(ended, (0..caps as u32).collect::<Vec<_>>(), "{name}");
    }
}

/// A sink that counts, to check that nothing is handed over twice.
#[derive(Default)]
struct Count {
    vertices: usize,
    faces: usize,
    max_index: u32,
}

impl MeshSink<f64> for Count {
    fn vertex(&mut self, _: capdiv::Point3<f64>, _: capdiv::Point3<f64>) {
        self.vertices += 1;
    }
    fn face(&mut self, f: capdiv_mesh::tessellate::Face, _: u32) {
        self.faces += 1;
        for &c in f.corners() {
            assert!((c as usize) < self.vertices, "a face before its vertex");
            self.max_index = self.max_index.max(c);
        }
    }
}

#[test]
fn faces_follow_their_vertices() {
    let mesh = samples::hand();
    let ps = patches(&mesh, 3);
    let mut tess = StreamTessellator::new(3, weld_tolerance(&mesh));
    let mut c = Count::default();
    for p in &ps {
        tess.push(p, 0, &mut c);
    }
    let s = tess.finish(&mut c);
    assert_eq!(c.vertices, s.vertices);
    assert_eq!(c.faces, s.triangles + s.quads);
    assert_eq!(c.max_index as usize + 1, c.vertices);
}

/// A bicubic patch record of the plane `z = 0` over `x ∈ [x0, x0 + 1]`,
/// `y ∈ [0, 1]`, with the control points' `x` given per row `i` (along `u`).
fn planar(x: [f64; 4]) -> PatchRecord<f64> {
    let mut points = [[Point3::ZERO; 4]; 4];
    for (i, row) in points.iter_mut().enumerate() {
        for (j, p) in row.iter_mut().enumerate() {
            *p = Point3::new(x[i], j as f64 / 3.0, 0.0);
        }
    }
    PatchRecord::new(
        PatchKind::Regular,
        PatchGeometry::Cubic(TensorPatch { points }),
    )
}

/// `x ∈ [x0, x0 + 1]` at uniform speed.
fn square(x0: f64) -> PatchRecord<f64> {
    planar([x0, x0 + 1.0 / 3.0, x0 + 2.0 / 3.0, x0 + 1.0])
}

/// [`square`] facing the other way (`x` from `x0 + 1` down to `x0`).
fn reversed(x0: f64) -> PatchRecord<f64> {
    planar([x0 + 1.0, x0 + 2.0 / 3.0, x0 + 1.0 / 3.0, x0])
}

#[test]
fn closedness_verdict_is_that_of_checking_every_edge_in_order() {
    // The stream checks the edges at a sample inside a patch's lattice only
    // when the patch's samples did not weld together or into older
    // vertices; these sequences make both happen.
    let fine = 1e-9;
    let mut cases: Vec<(String, Vec<PatchRecord<f64>>, f64)> = [
        (
            "two squares side by side",
            vec![square(0.0), square(1.0)],
            fine,
        ),
        ("a square twice", vec![square(0.0), square(0.0)], fine),
        // x = 3u(1 − u): u and 1 − u sample the same points.
        ("a folded patch", vec![planar([0.0, 1.5, 1.5, 0.0])], fine),
        ("a patch collapsed to a line", vec![planar([0.0; 4])], fine),
        // Samples a quarter apart weld together inside the patch.
        ("a square welded across its samples", vec![square(0.0)], 0.3),
        // Interior samples of the later patches weld into older vertices.
        (
            "a reversed square over two squares' seam",
            vec![square(1.0), reversed(0.5)],
            fine,
        ),
        (
            "reversed squares over a square's sides",
            vec![square(1.0), reversed(0.25), reversed(1.25)],
            fine,
        ),
        (
            "a square, a fold, a square",
            vec![square(0.0), planar([1.0, 2.5, 2.5, 1.0]), square(1.0)],
            fine,
        ),
    ]
    .into_iter()
    .map(|(name, ps, tol)| (name.to_string(), ps, tol))
    .collect();
    for (name, mesh) in meshes() {
        let tol = weld_tolerance(&mesh);
        cases.push((name.to_string(), patches(&mesh, 2), tol));
    }
    let mut faults = 0;
    for (name, ps, tol) in &cases {
        for grid in [1, 2, 4] {
            let (got, s) = streamed(ps, grid, *tol);
            let expected = closed_in_order(&got.faces);
            assert_eq!(s.closed, expected, "{name}, grid {grid}");
            faults += usize::from(expected.is_err());
        }
    }
    // The degenerate sequences do exercise faults (open meshes add more).
    assert!(faults >= 12, "{faults} faulty cases");
}
