//! The mesh pipeline with OpenSubdiv's subdivision tags: OBJ text
//! (`obj::parse_obj`, tag lines `t crease|corner|hole|interpolateboundary|
//! creasemethod …` included) or a face list built from the bytes (arbitrary
//! sizes and indices — non-manifold edges, bowties, repeated vertices in a
//! face, valence-2 vertices — or a sample mesh with mutations) with arbitrary
//! tags (creases, corners, holes, boundary rule, crease method; sharpness any
//! `f32`, indices sometimes out of range), through `SurfacePlan::for_mesh`
//! (depth 1–3, `catmull_clark` on or off), `Evaluator` (f64 or f32, by a bit
//! of the first byte), `tessellate` and `is_closed_and_oriented`, and the
//! same patches through the streaming weld (`StreamTessellator`). A bit of the
//! first byte also runs the tagless path `Topology::new` + `SurfacePlan::new`.
//!
//! First byte: bit 0 OBJ text (0) or face list (1); bit 1 `catmull_clark`;
//! bits 2–3 depth (1, 2, 3, 2); bit 4 tessellation grid 1 or 2; bit 5 f32;
//! bit 6 also `SurfacePlan::new`.
//!
//! Oracle: no panic; every failure a typed `MeshError` / `EvalError`;
//! `for_mesh` succeeds on every mesh it documents as accepted (faces of ≥ 3
//! in-range vertices, a vertex listed twice included, finite positions, tag
//! indices in range) and leaves no face uncovered; every successful evaluation is finite (any magnitude);
//! the tessellation (up to 2000 patches) indexes its own vertices, and so
//! does the streamed one, whose closedness verdict is that of checking each
//! of its faces' edges in order (it skips the edges its module doc says need
//! no check); and when
//! the input is a closed, consistently oriented manifold (`Topology::new`
//! succeeds, `is_closed`) without hole tags, the f64 surface at generic
//! vertex positions tessellates to a closed, consistently oriented mesh.
//! Work is bounded: at most 200 vertices, 200 faces, 800 corners, 40 tags,
//! and evaluation only of plans with at most 4000 patches and caps.
#![no_main]

use arbitrary::{Result, Unstructured};
use capdiv::Point3;
use capdiv_fuzz::FuzzReal;
use capdiv_mesh::obj::parse_obj;
use capdiv_mesh::sinks::CollectSurface;
use capdiv_mesh::tessellate::{
    closed_in_order, is_closed_and_oriented, tessellate, PatchGeometry, StreamTessellator,
    Tessellation,
};
use capdiv_mesh::{
    samples, BoundaryInterpolation, CreaseMethod, EdgeCrease, EvalError, Evaluator, MeshInput,
    PlanOptions, SurfacePlan, Topology, TriangleSubdivision, VertexCorner,
};
use libfuzzer_sys::fuzz_target;

fn points<R: FuzzReal>(g: &PatchGeometry<R>) -> Vec<Point3<R>> {
    match g {
        PatchGeometry::Cubic(t) => t.points.iter().flatten().copied().collect(),
        PatchGeometry::Quartic(t) => t.points.iter().flatten().copied().collect(),
    }
}

/// Tessellates at most this many patches (the weld's and the closedness
/// check's sorts dominate the run time).
const MAX_TESSELLATED: usize = 2000;

/// Evaluates `plan` at `positions`; `Some(closedness)` when it succeeded and
/// was tessellated. Asserts finiteness and the tessellation's indices.
fn evaluate<R: FuzzReal>(
    plan: &SurfacePlan<'_>,
    positions: &[[f64; 3]],
    grid: usize,
) -> Option<bool> {
    let mut ev = Evaluator::<R>::new(plan).ok()?;
    let positions: Vec<[R; 3]> = positions.iter().map(|p| p.map(R::from_f64)).collect();
    let mut sink = CollectSurface::new();
    // Every successful evaluation is finite, at any magnitude (overflow is
    // EvalError::Overflow or the kernel's NonFinite).
    // The only evaluation errors a plan for_mesh made may meet are numeric
    // (positions the fuzzer scaled to overflow): a cap the kernel refuses
    // for its shape is a planning bug.
    match ev.evaluate(&positions, &mut sink) {
        Ok(()) if sink.refused().is_some() => return None,
        Ok(()) => {}
        Err(EvalError::Overflow | EvalError::NonFinite { .. }) => return None,
        Err(EvalError::Kernel {
            error: capdiv::Error::NonFinite,
            ..
        }) => return None,
        Err(e) => panic!("{} evaluation failed: {e:?}", R::NAME),
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
    if sink.patches.len() > MAX_TESSELLATED {
        return None;
    }
    let t = tessellate(
        sink.patches.iter().map(|p| (p, p.level)),
        grid,
        // Relative to the mesh's size, as the CLI welds (an absolute
        // tolerance makes the weld quadratic on tiny meshes: every sample in
        // one cell).
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
    let mut stream = StreamTessellator::new(grid, R::from_f64(1e-9 * size));
    let mut streamed = Tessellation::default();
    for p in &sink.patches {
        stream.push(p, p.level, &mut streamed);
    }
    let summary = stream.finish(&mut streamed);
    for f in &streamed.faces {
        assert!(f
            .corners()
            .iter()
            .all(|&c| (c as usize) < streamed.positions.len()));
    }
    assert_eq!(
        summary.closed,
        closed_in_order(&streamed.faces),
        "streamed closedness verdict"
    );
    Some(is_closed_and_oriented(&t.faces).is_ok())
}

/// Generic positions (a hash of the index in [-1, 1]³): no two patches of a
/// closed mesh touch by accident, whatever positions the input had.
fn generic(n: usize) -> Vec<[f64; 3]> {
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        s = s.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = s;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    (0..n).map(|_| [next(), next(), next()]).collect()
}

/// What `SurfacePlan::for_mesh` documents as accepted.
fn acceptable(mesh: &MeshInput) -> bool {
    let nv = mesh.vertices.len();
    let nf = mesh.faces.len();
    nv > 0
        && nf > 0
        && mesh.vertices.iter().flatten().all(|c| c.is_finite())
        && mesh
            .faces
            .iter()
            .all(|f| f.len() >= 3 && f.iter().all(|&v| (v as usize) < nv))
        && mesh
            .tags
            .creases
            .iter()
            .flat_map(|c| c.vertices)
            .chain(mesh.tags.corners.iter().map(|c| c.vertex))
            .all(|v| (v as usize) < nv)
        && mesh.tags.holes.iter().all(|&f| (f as usize) < nf)
}

#[derive(Clone, Copy)]
struct Mode {
    depth: u32,
    catmull_clark: bool,
    grid: usize,
    f32_run: bool,
    plain_too: bool,
}

fn pipeline(mesh: &MeshInput, mode: Mode) {
    if mesh.vertices.len() > 200
        || mesh.faces.len() > 200
        || mesh.faces.iter().map(Vec::len).sum::<usize>() > 800
        || mesh.tags.creases.len() + mesh.tags.corners.len() + mesh.tags.holes.len() > 40
    {
        return;
    }
    let options = PlanOptions {
        depth: mode.depth,
        catmull_clark: mode.catmull_clark,
        ..Default::default()
    };
    let topo = Topology::new(mesh).ok();
    if topo.is_some() {
        assert!(Topology::from_faces(mesh.vertices.len(), &mesh.faces).is_ok());
    }
    let plan = SurfacePlan::for_mesh(mesh, options.clone());
    let plan = match plan {
        Ok(plan) => plan,
        Err(e) => {
            assert!(!acceptable(mesh), "for_mesh rejected an accepted mesh: {e}");
            return;
        }
    };
    assert!(
        plan.uncovered.is_empty(),
        "for_mesh left faces uncovered: {:?}",
        &plan.uncovered[..plan.uncovered.len().min(4)]
    );
    let items = plan.regular.len() + plan.polar.len() + plan.extraordinary.len();
    if items <= 4000 {
        if mode.f32_run {
            evaluate::<f32>(&plan, &mesh.vertices, mode.grid);
        } else {
            evaluate::<f64>(&plan, &mesh.vertices, mode.grid);
        }
        // Two faces on the same vertex set have the same face point at any
        // positions: the surface touches itself there, and its welded
        // tessellation is rightly no manifold.
        let closed_input = topo.as_ref().is_some_and(Topology::is_closed)
            && mesh.tags.holes.is_empty()
            && !shares_a_vertex_set(&mesh.faces);
        if closed_input {
            let closed = evaluate::<f64>(&plan, &generic(mesh.vertices.len()), mode.grid);
            assert_ne!(
                closed,
                Some(false),
                "closed oriented input, tessellation not closed and oriented"
            );
        }
    }
    if mode.plain_too {
        if let Some(topo) = &topo {
            if let Ok(plan) = SurfacePlan::new(topo, options) {
                if plan.regular.len() + plan.polar.len() + plan.extraordinary.len() <= 4000 {
                    evaluate::<f64>(&plan, &mesh.vertices, mode.grid);
                }
            }
        }
    }
}

/// Whether two faces have the same set of vertices.
fn shares_a_vertex_set(faces: &[Vec<u32>]) -> bool {
    let mut sets: Vec<Vec<u32>> = faces
        .iter()
        .map(|f| {
            let mut s = f.clone();
            s.sort_unstable();
            s
        })
        .collect();
    sets.sort_unstable();
    sets.windows(2).any(|w| w[0] == w[1])
}

fn sharpness(u: &mut Unstructured<'_>) -> Result<f32> {
    Ok(match u.int_in_range(0..=9u8)? {
        0 => 0.0,
        1 => 0.5,
        2 => 1.0,
        3 => 1.5,
        4 => 2.0,
        5 => 3.25,
        6 => 10.0,
        7 => f32::from(u.int_in_range(0..=120u8)?) / 8.0,
        // Any bits: NaN, ∞, negative, subnormal.
        _ => f32::from_bits(u.arbitrary()?),
    })
}

fn arb_vertex(u: &mut Unstructured<'_>, nv: usize) -> Result<u32> {
    if u.ratio(1, 16)? {
        u.arbitrary()
    } else {
        u.int_in_range(0..=nv.max(1) as u32) // one past the end now and then
    }
}

/// Tags over `mesh`: mostly edges and vertices of it, sometimes not.
fn arb_tags(u: &mut Unstructured<'_>, mesh: &mut MeshInput) -> Result<()> {
    let nv = mesh.vertices.len();
    let nf = mesh.faces.len();
    let tags = &mut mesh.tags;
    for _ in 0..u.int_in_range(0..=8u8)? {
        let vertices = if nf > 0 && !u.ratio(1, 8)? {
            let f = &mesh.faces[u.int_in_range(0..=nf - 1)?];
            if f.is_empty() {
                continue;
            }
            let k = u.int_in_range(0..=f.len() - 1)?;
            let pair = [f[k], f[(k + 1) % f.len()]];
            if u.arbitrary()? {
                [pair[1], pair[0]]
            } else {
                pair
            }
        } else {
            [arb_vertex(u, nv)?, arb_vertex(u, nv)?]
        };
        tags.creases.push(EdgeCrease {
            vertices,
            sharpness: sharpness(u)?,
        });
    }
    for _ in 0..u.int_in_range(0..=4u8)? {
        let vertex = if nv > 0 && !u.ratio(1, 8)? {
            u.int_in_range(0..=nv as u32 - 1)?
        } else {
            arb_vertex(u, nv)?
        };
        tags.corners.push(VertexCorner {
            vertex,
            sharpness: sharpness(u)?,
        });
    }
    for _ in 0..u.int_in_range(0..=2u8)? {
        tags.holes.push(if nf > 0 && !u.ratio(1, 8)? {
            u.int_in_range(0..=nf as u32 - 1)?
        } else {
            u.arbitrary()?
        });
    }
    tags.boundary = match u.int_in_range(0..=3u8)? {
        0 => BoundaryInterpolation::None,
        1 => BoundaryInterpolation::EdgeOnly,
        _ => BoundaryInterpolation::EdgeAndCorner,
    };
    if u.arbitrary()? {
        tags.crease_method = CreaseMethod::Chaikin;
    }
    if u.arbitrary()? {
        tags.triangles = TriangleSubdivision::Smooth;
    }
    Ok(())
}

fn arb_mesh(u: &mut Unstructured<'_>) -> Result<MeshInput> {
    let mut mesh = match u.int_in_range(0..=8u8)? {
        0 => samples::cube(),
        1 => samples::globe(u.int_in_range(3..=12)?, u.int_in_range(1..=3)?),
        2 => samples::extraordinary_disk(u.int_in_range(3..=11)?, u.int_in_range(1..=2)?),
        3 => samples::grid(u.int_in_range(1..=5)?, u.int_in_range(1..=5)?),
        4 => samples::triangle_and_pentagon_mesh(),
        5 => samples::pole_disk(u.int_in_range(3..=12)?, u.int_in_range(2..=3)?),
        6 => samples::torus(u.int_in_range(3..=6)?, u.int_in_range(3..=6)?),
        7 => samples::two_beam_corner(),
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
    // Mutations: move a vertex (any bits), change an index, drop or flip a
    // face, glue a face onto an existing edge (a non-manifold edge).
    let k = u.int_in_range(0..=4u8)?;
    for _ in 0..k {
        match u.int_in_range(0..=4u8)? {
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
            4 if !mesh.faces.is_empty() && !mesh.vertices.is_empty() => {
                let f = &mesh.faces[u.int_in_range(0..=mesh.faces.len() - 1)?];
                if f.len() >= 2 {
                    let (a, b) = (f[0], f[1]);
                    let c = u.int_in_range(0..=mesh.vertices.len() as u32 - 1)?;
                    let mut g = vec![b, a, c];
                    if u.arbitrary()? {
                        g.push(u.int_in_range(0..=mesh.vertices.len() as u32 - 1)?);
                    }
                    mesh.faces.push(g);
                }
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
    arb_tags(u, &mut mesh)?;
    Ok(mesh)
}

fuzz_target!(|data: &[u8]| {
    let Some((&first, rest)) = data.split_first() else {
        return;
    };
    let mode = Mode {
        depth: [1, 2, 3, 2][usize::from((first >> 2) & 3)],
        catmull_clark: first & 2 != 0,
        grid: 1 + usize::from((first >> 4) & 1),
        f32_run: first & 0x20 != 0,
        plain_too: first & 0x40 != 0,
    };
    if first & 1 == 0 {
        let Ok(text) = std::str::from_utf8(rest) else {
            return;
        };
        if let Ok(mesh) = parse_obj(text) {
            pipeline(&mesh, mode);
        }
    } else {
        let mut u = Unstructured::new(rest);
        if let Ok(mesh) = arb_mesh(&mut u) {
            pipeline(&mesh, mode);
        }
    }
});
