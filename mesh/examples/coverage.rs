//! Prints the coverage of every sample mesh: patches per kind, caps per
//! scheme, refinement steps, uncovered faces.
use capdiv_mesh::sinks::SurfaceStats;
use capdiv_mesh::*;
use std::collections::BTreeMap;

/// Patches per kind id and `cap SCHEME n=VALENCE` counts, those met only.
fn counts(stats: &SurfaceStats) -> BTreeMap<String, usize> {
    let kinds = PatchKind::ALL
        .into_iter()
        .map(|k| (k.id().to_string(), stats.patches.of(k)));
    let caps = stats
        .caps
        .iter()
        .map(|c| (format!("cap {} n={}", c.scheme.id(), c.valence), c.count));
    kinds.chain(caps).filter(|&(_, n)| n > 0).collect()
}

fn main() {
    let meshes: Vec<(&str, MeshInput)> = vec![
        ("globe", samples::globe(8, 9)),
        ("pole_disk", samples::pole_disk(6, 4)),
        ("mushroom", samples::mushroom()),
        ("hand", samples::hand()),
        ("cube", samples::cube()),
        ("rounded_cube", samples::rounded_cube(3)),
        ("two_beam", samples::two_beam_corner()),
        ("torus", samples::torus(6, 5)),
        ("grid", samples::grid(5, 4)),
        ("ev_disk5", samples::extraordinary_disk(5, 3)),
        ("ev_disk7", samples::extraordinary_disk(7, 3)),
        ("tri_pent", samples::triangle_and_pentagon_mesh()),
    ];
    for (name, m) in meshes {
        let t = Topology::new(&m).unwrap();
        let plan = SurfacePlan::new(
            &t,
            PlanOptions {
                depth: 3,
                ..Default::default()
            },
        )
        .unwrap();
        let mut ev = Evaluator::<f64>::new(&plan).unwrap();
        let mut stats = SurfaceStats::new();
        ev.evaluate(&m.vertices, &mut stats).unwrap();
        println!(
            "{name}: steps {} needed {} uncovered {:?} {:?}",
            plan.steps.len(),
            plan.needed_refinement.len(),
            plan.uncovered
                .iter()
                .map(|u| (u.face, u.reason.id()))
                .take(6)
                .collect::<Vec<_>>(),
            counts(&stats)
        );
    }
}
