//! The mesh pipeline: OBJ text (`obj::parse_obj`) or a face list built from
//! the bytes (arbitrary sizes and indices, or a sample mesh with mutations),
//! through `Topology::new`, `SurfacePlan::new` (depth 1–2), `Evaluator`
//! (f64 or f32, by a bit of the first byte), `tessellate` and
//! `is_closed_and_oriented` (up to 96 patches).
//!
//! Oracle: no panic; every failure a typed `MeshError` / `EvalError`; every
//! successful evaluation is finite (any magnitude).
#![no_main]

use arbitrary::{Result, Unstructured};
use capdiv::Point3;
use capdiv_fuzz::FuzzReal;
use capdiv_mesh::obj::parse_obj;
use capdiv_mesh::tessellate::{is_closed_and_oriented, tessellate, PatchGeometry, TessPatch};
use capdiv_mesh::{
    samples, CapRecord, Evaluator, MeshInput, PatchRecord, PlanOptions, SurfacePlan, SurfaceSink,
    Topology,
};
use libfuzzer_sys::fuzz_target;

struct Collect<R> {
    patches: Vec<PatchRecord<R>>,
    caps: Vec<CapRecord<R>>,
}

impl<R: Clone> SurfaceSink<R> for Collect<R> {
    fn patch(&mut self, p: &PatchRecord<R>) {
        self.patches.push(p.clone());
    }
    fn cap(&mut self, c: &CapRecord<R>) {
        self.caps.push(c.clone());
    }
}

fn points<R: FuzzReal>(g: &PatchGeometry<R>) -> Vec<Point3<R>> {
    match g {
        PatchGeometry::Cubic(t) => t.points.iter().flatten().copied().collect(),
        PatchGeometry::Quartic(t) => t.points.iter().flatten().copied().collect(),
    }
}

fn evaluate<R: FuzzReal>(plan: &SurfacePlan<'_>, mesh: &MeshInput, grid: usize) {
    let Ok(mut ev) = Evaluator::<R>::new(plan) else {
        return;
    };
    let positions: Vec<[R; 3]> = mesh.vertices.iter().map(|p| p.map(R::from_f64)).collect();
    let mut sink = Collect {
        patches: Vec::new(),
        caps: Vec::new(),
    };
    let r = ev.evaluate(plan, &positions, &mut sink);
    // Every successful evaluation is finite, at any magnitude (overflow is
    // EvalError::Overflow or the kernel's NonFinite).
    if r.is_err() {
        return;
    }
    let size = positions
        .iter()
        .flatten()
        .fold(0.0f64, |m, c| m.max(c.to_f64().abs()));
    for p in &sink.patches {
        assert!(
            points(&p.geometry).iter().all(|q| q.is_finite()),
            "{} patch not finite ({:?}, face {}, level {})",
            R::NAME,
            p.kind,
            p.face,
            p.level
        );
    }
    for c in &sink.caps {
        assert!(c.limit.is_finite(), "{} cap limit not finite", R::NAME);
        if let Some(n) = c.normal {
            assert!(n.is_finite(), "{} cap normal not finite", R::NAME);
        }
        if let Some(k) = c.principal_curvatures {
            assert!(
                k.iter().all(|x| x.is_finite()),
                "{} cap curvatures not finite",
                R::NAME
            );
        }
    }
    // Tessellate (bounded: a few hundred samples; the sorts of the weld and
    // the closedness check dominated the run time with up to 400 patches).
    if sink.patches.len() <= 96 {
        let t = tessellate(
            sink.patches.iter().map(|p| TessPatch {
                geometry: p.geometry,
                finer: p.finer,
                hole: p.hole,
                hole_point: p.hole_point,
                tag: p.level,
            }),
            grid,
            // Relative to the mesh's size, as the CLI welds (an absolute
            // tolerance makes the weld quadratic on tiny meshes: every
            // sample in one cell).
            R::from_f64(1e-9 * size),
        );
        assert_eq!(t.positions.len(), t.normals.len());
        assert_eq!(t.faces.len(), t.tags.len());
        for f in &t.faces {
            assert!(f
                .corners()
                .iter()
                .all(|&c| (c as usize) < t.positions.len()));
        }
        let _ = is_closed_and_oriented(&t.faces);
    }
}

/// Bounded work per input (about 10⁴ executions per second): at most 200
/// vertices, 200 faces and 800 corners.
fn pipeline(mesh: &MeshInput, depth: u32, grid: usize, f32_run: bool) {
    if mesh.vertices.len() > 200
        || mesh.faces.len() > 200
        || mesh.faces.iter().map(Vec::len).sum::<usize>() > 800
    {
        return;
    }
    let Ok(topo) = Topology::new(mesh) else {
        return;
    };
    let same = Topology::from_faces(mesh.vertices.len(), &mesh.faces);
    assert!(same.is_ok());
    let Ok(plan) = SurfacePlan::new(
        &topo,
        PlanOptions {
            depth,
            ..Default::default()
        },
    ) else {
        return;
    };
    if f32_run {
        evaluate::<f32>(&plan, mesh, grid);
    } else {
        evaluate::<f64>(&plan, mesh, grid);
    }
}

fn arb_mesh(u: &mut Unstructured<'_>) -> Result<MeshInput> {
    let mut mesh = match u.int_in_range(0..=6u8)? {
        0 => samples::cube(),
        1 => samples::globe(u.int_in_range(3..=12)?, u.int_in_range(1..=3)?),
        2 => samples::extraordinary_disk(u.int_in_range(3..=11)?, u.int_in_range(1..=2)?),
        3 => samples::grid(u.int_in_range(1..=5)?, u.int_in_range(1..=5)?),
        4 => samples::triangle_and_pentagon_mesh(),
        5 => samples::pole_disk(u.int_in_range(3..=12)?, u.int_in_range(2..=3)?),
        _ => {
            // Arbitrary sizes and indices.
            let nv = u.int_in_range(0..=40usize)?;
            let nf = u.int_in_range(0..=40usize)?;
            let mut faces = Vec::with_capacity(nf);
            for _ in 0..nf {
                let k = match u.int_in_range(0..=7u8)? {
                    0..=2 => 4,
                    3 | 4 => 3,
                    _ => u.int_in_range(0..=12usize)?,
                };
                let mut f = Vec::with_capacity(k);
                for _ in 0..k {
                    f.push(if u.ratio(1, 20)? {
                        u.arbitrary()?
                    } else {
                        u.int_in_range(0..=nv.max(1) as u32 - 1)?
                    });
                }
                faces.push(f);
            }
            let vertices = (0..nv)
                .map(|i| {
                    let t = i as f64;
                    [t.cos() * (1.0 + t * 0.1), t.sin(), (t * 0.37).sin()]
                })
                .collect();
            MeshInput::new(vertices, faces)
        }
    };
    // Mutations: move a vertex (any bits), change an index, drop or flip a face.
    let k = u.int_in_range(0..=4u8)?;
    for _ in 0..k {
        match u.int_in_range(0..=3u8)? {
            0 if !mesh.vertices.is_empty() => {
                let v = u.int_in_range(0..=mesh.vertices.len() - 1)?;
                let c = u.int_in_range(0..=2usize)?;
                mesh.vertices[v][c] = f64::arb(u)?;
            }
            1 if !mesh.faces.is_empty() => {
                let f = u.int_in_range(0..=mesh.faces.len() - 1)?;
                if !mesh.faces[f].is_empty() {
                    let i = u.int_in_range(0..=mesh.faces[f].len() - 1)?;
                    mesh.faces[f][i] = u.int_in_range(0..=mesh.vertices.len() as u32)?;
                }
            }
            2 if !mesh.faces.is_empty() => {
                let f = u.int_in_range(0..=mesh.faces.len() - 1)?;
                mesh.faces.remove(f);
            }
            3 if !mesh.faces.is_empty() => {
                let f = u.int_in_range(0..=mesh.faces.len() - 1)?;
                mesh.faces[f].reverse();
            }
            _ => {}
        }
    }
    // A global scale (any bits).
    if u.ratio(1, 4)? {
        let s = f64::arb(u)?;
        for p in &mut mesh.vertices {
            for c in p {
                *c *= s;
            }
        }
    }
    Ok(mesh)
}

fuzz_target!(|data: &[u8]| {
    let Some((&mode, rest)) = data.split_first() else {
        return;
    };
    let depth = 1 + u32::from(mode >> 7);
    let grid = 1 + usize::from((mode >> 5) & 1);
    let f32_run = mode & 0x40 != 0;
    if mode & 1 == 0 {
        let Ok(text) = std::str::from_utf8(rest) else {
            return;
        };
        if let Ok(mesh) = parse_obj(text) {
            pipeline(&mesh, depth, grid, f32_run);
        }
    } else {
        let mut u = Unstructured::new(rest);
        if let Ok(mesh) = arb_mesh(&mut u) {
            pipeline(&mesh, depth, grid, f32_run);
        }
    }
});
