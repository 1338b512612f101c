//! `SurfacePlan::input_fallbacks`: the extraordinary points of the input
//! whose cap a tag or a nearby feature holds off, numbered as in the input.

use capdiv_mesh::caps::Reason;
use capdiv_mesh::{samples, EdgeCrease, PlanOptions, SurfacePlan};

/// Valence (faces around) of every vertex.
fn valences(faces: &[Vec<u32>], n: usize) -> Vec<usize> {
    let mut v = vec![0; n];
    for &i in faces.iter().flatten() {
        v[i as usize] += 1;
    }
    v
}

#[test]
fn an_infinitely_sharp_crease_at_an_extraordinary_point_is_its_fallback() {
    let mut mesh = samples::two_beam_corner();
    let valence = valences(&mesh.faces, mesh.vertices.len());
    // An input extraordinary point that gets a cap without tags, and an
    // edge from it.
    let plain = SurfacePlan::for_mesh(&mesh, PlanOptions::default()).unwrap();
    let capped: Vec<u32> = plain
        .extraordinary
        .iter()
        .filter_map(|c| c.vertex)
        .filter(|&v| (v as usize) < mesh.vertices.len() && valence[v as usize] != 4)
        .collect();
    let v = *capped
        .first()
        .expect("the sample has a capped extraordinary point");
    assert!(plain.input_fallbacks().all(|(w, _)| w != v));
    let w = mesh
        .faces
        .iter()
        .find_map(|f| {
            let k = f.iter().position(|&x| x == v)?;
            Some(f[(k + 1) % f.len()])
        })
        .unwrap();
    mesh.tags.creases.push(EdgeCrease {
        vertices: [v, w],
        sharpness: 10.0,
    });
    let plan = SurfacePlan::for_mesh(&mesh, PlanOptions::default()).unwrap();
    let fallbacks: Vec<(u32, Reason)> = plan.input_fallbacks().collect();
    assert!(
        fallbacks.contains(&(v, Reason::Feature)),
        "vertex {v} creased: {fallbacks:?}"
    );
    assert!(plan.extraordinary.iter().all(|c| c.vertex != Some(v)));
    // Every listed vertex is one of the input's.
    assert!(fallbacks
        .iter()
        .all(|&(u, _)| (u as usize) < mesh.vertices.len()));
}
