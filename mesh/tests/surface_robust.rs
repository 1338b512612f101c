//! Bad meshes give their `MeshError` through
//! the whole path (`parse_obj` → `Topology::new`); random and mutated face
//! lists never make the analysis or the evaluation panic, and every plan
//! that is made evaluates to finite patches; f32 evaluation tracks f64.
mod common;

use capdiv_mesh::obj::parse_obj;
use capdiv_mesh::{samples, Evaluator, MeshError, MeshInput, SurfacePlan, Topology};
use common::*;

fn topo_err(obj: &str) -> MeshError {
    match parse_obj(obj) {
        Err(e) => e,
        Ok(m) => Topology::new(&m).expect_err("the mesh must be rejected"),
    }
}

#[test]
fn bad_obj_meshes_give_their_errors() {
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    assert_eq!(topo_err(""), MeshError::Empty);
    assert_eq!(topo_err(tri), MeshError::Empty);
    assert!(matches!(
        topo_err("v 0 0 zero\nf 1 2 3\n"),
        MeshError::Parse { line: 1, .. }
    ));
    assert_eq!(
        topo_err("v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n"),
        MeshError::NonFinite { vertex: 1 }
    );
    assert!(matches!(
        topo_err(&format!("{tri}f 1 2 4\n")),
        MeshError::IndexOutOfRange { face: 0, .. }
    ));
    assert_eq!(
        topo_err(&format!("{tri}f 1 2\n")),
        MeshError::FaceTooSmall { face: 0, len: 2 }
    );
    assert_eq!(
        topo_err(&format!("{tri}f 1 2 3\nf 1 3 2 1\n")),
        MeshError::RepeatedVertex { face: 1, vertex: 0 }
    );
    let five = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n";
    assert_eq!(
        topo_err(&format!("{five}f 1 2 3\nf 1 2 4\n")),
        MeshError::InconsistentOrientation {
            face: 1,
            edge: [0, 1]
        }
    );
    assert_eq!(
        topo_err(&format!("{five}f 1 2 3\nf 2 1 4\nf 2 1 5\n")),
        MeshError::NonManifoldEdge {
            face: 2,
            edge: [0, 1]
        }
    );
    assert_eq!(
        topo_err(&format!("{five}f 1 2 3\nf 1 4 5\n")),
        MeshError::NonManifoldVertex { vertex: 0 }
    );
    // TooLarge needs more than 2^31 items: not built here (unit-tested in
    // topology.rs by its limit only).
}

/// xorshift64*: deterministic, no dependency.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Runs the whole pipeline; panics (the test fails) on a panic inside, on an
/// evaluation error for a plan that was made, or on a non-finite patch.
/// Returns whether a plan was made.
fn pipeline(m: &MeshInput, depth: u32) -> bool {
    let Ok(t) = Topology::new(m) else {
        return false;
    };
    let Ok(plan) = SurfacePlan::new(&t, common::plan_options(depth, false)) else {
        return false;
    };
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    let mut out = Collect::default();
    ev.evaluate(&m.vertices, &mut out).expect("evaluate");
    for p in &out.patches {
        assert!(
            control_grid(&p.geometry)
                .iter()
                .flatten()
                .flatten()
                .all(|c| c.is_finite()),
            "non-finite patch"
        );
        assert!(p.domain.iter().all(|d| d.is_finite()));
    }
    true
}

#[test]
fn random_face_lists_never_panic() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut planned = 0;
    for case in 0..3000 {
        let nv = 3 + rng.below(12);
        let nf = 1 + rng.below(14);
        let vertices: Vec<[f64; 3]> = (0..nv)
            .map(|_| [rng.unit(), rng.unit(), rng.unit()])
            .collect();
        let faces: Vec<Vec<u32>> = (0..nf)
            .map(|_| {
                let k = 1 + rng.below(6);
                (0..k).map(|_| rng.below(nv + 1) as u32).collect()
            })
            .collect();
        let m = MeshInput::new(vertices, faces);
        let r = std::panic::catch_unwind(|| pipeline(&m, 2));
        match r {
            Ok(p) => planned += usize::from(p),
            Err(_) => panic!("case {case} panicked: {:?}", m.faces),
        }
    }
    println!("random face lists: {planned} of 3000 planned");
}

/// Sample meshes with faces removed, reversed or split, and positions
/// jittered: many of these are valid with odd boundaries and crowded
/// irregular vertices, which the plan must survive.
#[test]
fn mutated_samples_never_panic() {
    let bases = [
        samples::grid(3, 3),
        samples::pole_disk(5, 3),
        samples::extraordinary_disk(5, 2),
        samples::extraordinary_disk(3, 3),
        samples::torus(4, 4),
        samples::cube(),
        samples::rounded_cube(2),
        samples::triangle_and_pentagon_mesh(),
        samples::globe(4, 7),
        samples::two_beam_corner(),
    ];
    let mut rng = Rng(0x1234_5678_9abc_def1);
    let (mut planned, mut total) = (0, 0);
    for case in 0..1500 {
        let base = &bases[case % bases.len()];
        let mut m = base.clone();
        let keep = 0.6 + 0.4 * rng.unit();
        m.faces.retain(|_| rng.unit() < keep);
        if m.faces.is_empty() {
            continue;
        }
        for _ in 0..rng.below(3) {
            let f = rng.below(m.faces.len());
            match rng.below(3) {
                0 => m.faces[f].reverse(),
                1 if m.faces[f].len() == 4 => {
                    let q = m.faces[f].clone();
                    m.faces[f] = vec![q[0], q[1], q[2]];
                    m.faces.push(vec![q[0], q[2], q[3]]);
                }
                _ => {
                    let k = m.faces[f].len();
                    m.faces[f].rotate_left(rng.below(k));
                }
            }
        }
        for p in &mut m.vertices {
            for c in p.iter_mut() {
                *c += 0.05 * (rng.unit() - 0.5);
            }
        }
        total += 1;
        let r = std::panic::catch_unwind(|| pipeline(&m, 2));
        match r {
            Ok(p) => planned += usize::from(p),
            Err(_) => panic!("case {case} panicked: {:?}", m.faces),
        }
    }
    println!("mutated samples: {planned} of {total} planned and evaluated");
    assert!(planned > total / 4);
}

/// f32 evaluation of the same plan, patch by patch (the same order), against
/// f64: the worst control-point difference relative to the mesh's size.
#[test]
fn f32_tracks_f64() {
    let cases: [(&str, MeshInput, u32); 6] = [
        ("globe(8, 9)", samples::globe(8, 9), 5),
        ("globe(64, 9)", samples::globe(64, 9), 4),
        (
            "extraordinary_disk(5, 3) EG",
            samples::extraordinary_disk(5, 3),
            5,
        ),
        (
            "extraordinary_disk(7, 3) CC",
            samples::extraordinary_disk(7, 3),
            5,
        ),
        ("rounded_cube(3)", samples::rounded_cube(3), 4),
        (
            "triangle_and_pentagon_mesh",
            samples::triangle_and_pentagon_mesh(),
            3,
        ),
    ];
    for (name, m, depth) in cases {
        let t = Topology::new(&m).unwrap();
        let plan = SurfacePlan::new(&t, common::plan_options(depth, false)).unwrap();
        let mut out64 = Collect::default();
        Evaluator::<f64>::new(&plan)
            .unwrap()
            .evaluate(&m.vertices, &mut out64)
            .unwrap();
        let pos32: Vec<[f32; 3]> = m.vertices.iter().map(|p| p.map(|c| c as f32)).collect();
        let mut out32 = Collect::default();
        Evaluator::<f32>::new(&plan)
            .unwrap()
            .evaluate(&pos32, &mut out32)
            .unwrap();
        assert_eq!(out32.patches.len(), out64.patches.len());
        let mut size = 0.0f64;
        for p in &m.vertices {
            size = size.max(norm(*p));
        }
        let mut worst = 0.0f64;
        for (a, b) in out32.patches.iter().zip(&out64.patches) {
            assert_eq!((a.kind, a.face, a.level), (b.kind, b.face, b.level));
            worst = worst.max(grid_distance(
                &control_grid32(&a.geometry),
                &control_grid(&b.geometry),
            ));
        }
        let mut limit = 0.0f64;
        for (a, b) in out32.caps.iter().zip(&out64.caps) {
            limit = limit.max(dist(a.limit.0.map(f64::from), b.limit.0));
        }
        println!("{name}: worst |f32 − f64| control point {:.1e} (relative to size {:.1e}), limit {:.1e}", worst, worst / size, limit / size);
        // f32 epsilon is 6e-8; subdivision adds a few units per level.
        assert!(worst / size < 2e-6, "{name}: {worst}");
        assert!(limit / size < 2e-6, "{name}: {limit}");
    }
}
