//! The ready-made sinks (`capdiv_mesh::sinks`) on small meshes whose counts
//! follow from their shape: `SurfaceStats` counts, `PatchCounts` counts only
//! patches per kind, `CollectSurface` keeps,
//! `Tee` hands each record to both.

mod common;

use capdiv_mesh::sinks::{CapCount, CollectSurface, PatchCounts, SurfaceStats, Tee};
use capdiv_mesh::{samples, Evaluator, MeshInput, PatchKind, Scheme};
use common::plan;

/// Counts and keeps one evaluation of `mesh` at `depth`.
fn stats_and_records(mesh: &MeshInput, depth: u32) -> (SurfaceStats, CollectSurface<f64>) {
    let plan = plan(mesh, depth);
    let mut stats = SurfaceStats::new();
    let mut kept = CollectSurface::new();
    Evaluator::<f64>::new(&plan)
        .unwrap()
        .evaluate(&mesh.vertices, &mut Tee(&mut stats, &mut kept))
        .unwrap();
    (stats, kept)
}

#[test]
fn a_cube_is_eight_eg_caps_of_valence_3() {
    // Every face of a cube touches a corner of valence 3: none is a regular
    // patch. The adaptive refinement splits each face in four, one quarter
    // per corner, so each corner's three quarters make a valence-3 EG cap
    // one level in. An EG ring has 3 patches per sector: 9 per cap, 72 for
    // the 8 caps, at levels 2..=depth+1.
    let depth = 3;
    let (stats, kept) = stats_and_records(&samples::cube(), depth);
    assert_eq!(
        stats.patches,
        PatchCounts {
            regular: 0,
            c2ps: 0,
            eg: 72 * depth as usize,
            catmull_clark: 0,
            total: 72 * depth as usize,
        }
    );
    assert_eq!(stats.levels, [0, 0, 72, 72, 72]);
    assert_eq!(
        stats.caps,
        [CapCount {
            scheme: Scheme::Eg,
            valence: 3,
            count: 8
        }]
    );
    assert_eq!(stats.cap_total(), 8);
    assert_eq!(stats.rings, Some([depth; 2]));
    assert!(stats.finite);
    assert_eq!(stats.refused(), None);
    let (patches, caps) = kept.finish().unwrap();
    assert_eq!(patches.len(), stats.patches.total);
    assert_eq!(caps.len(), 8);
}

#[test]
fn a_globe_is_two_c2ps_caps_and_regular_quads() {
    // globe(6, 7): two poles of valence 6 (a fan of 6 triangles each) and 7
    // rings of 6 points joined by 6 rings of 6 quads. A C²PS cap covers its
    // fan and the quads out to link 2 (its rings reach radius 2 in link
    // units), so 36 − 2·6 = 24 quads are regular patches at level 0. Ring
    // `m` of a C²PS cap of valence n is 2 spans of n·2^m patches at level m:
    // 24 and 48 per cap at depth 2.
    let (stats, kept) = stats_and_records(&samples::globe(6, 7), 2);
    assert_eq!(
        stats.patches,
        PatchCounts {
            regular: 24,
            c2ps: 2 * (24 + 48),
            eg: 0,
            catmull_clark: 0,
            total: 24 + 2 * (24 + 48),
        }
    );
    assert_eq!(stats.levels, [24, 48, 96]);
    assert_eq!(
        stats.caps,
        [CapCount {
            scheme: Scheme::C2ps,
            valence: 6,
            count: 2
        }]
    );
    assert_eq!(stats.rings, Some([2, 2]));
    assert!(stats.finite);
    let (patches, caps) = kept.finish().unwrap();
    assert_eq!(patches.len(), stats.patches.total);
    assert!(caps
        .iter()
        .all(|c| c.scheme == Scheme::C2ps && c.valence == 6));
}

#[test]
fn a_tolerance_shows_in_the_ring_range() {
    // A hole tolerance of the cube's size stops every cap after its first
    // ring; none stops later than the depth.
    let mesh = samples::cube();
    let plan = plan(&mesh, 4);
    let mut stats = SurfaceStats::new();
    let mut ev = Evaluator::<f64>::new(&plan).unwrap();
    ev.set_hole_tolerance(Some(100.0));
    ev.evaluate(&mesh.vertices, &mut stats).unwrap();
    assert_eq!(stats.rings, Some([1, 1]));
    assert_eq!(stats.patches.eg, 72);
}

#[test]
fn a_collection_keeps_the_records_in_order() {
    let mesh = samples::cube();
    let (_, kept) = stats_and_records(&mesh, 2);
    let (patches, caps) = kept.finish().unwrap();
    // Each cap's record follows its patches: cap indices are met in the
    // order the caps are.
    let mut seen = Vec::new();
    for p in &patches {
        let c = p.cap.expect("every cube patch is a cap's");
        if seen.last() != Some(&c) {
            assert!(!seen.contains(&c), "cap {c}'s patches are not together");
            seen.push(c);
        }
    }
    let order: Vec<u32> = caps.iter().map(|c| c.index).collect();
    assert_eq!(seen, order);
}

#[test]
fn non_finite_points_are_seen() {
    // A patch with a NaN control point makes the counts not finite (the
    // CLI refuses such a surface).
    let mut stats = SurfaceStats::new();
    let p = capdiv_mesh::PatchRecord::new(
        capdiv_mesh::PatchKind::Regular,
        capdiv_mesh::tessellate::PatchGeometry::Cubic(capdiv::TensorPatch {
            points: [[capdiv::Point3([f64::NAN, 0.0, 0.0]); 4]; 4],
        }),
    );
    capdiv_mesh::SurfaceSink::patch(&mut stats, &p);
    assert!(!stats.finite);
    assert_eq!(stats.patches.regular, 1);
    assert_eq!(stats.levels, [1]);
}

#[test]
fn patch_counts_alone_count_each_kept_patch_by_its_kind() {
    // PatchCounts as a sink sees the same patches as SurfaceStats and
    // CollectSurface beside it, and ignores caps: each per-kind count is the
    // number of kept patches of that kind, and the total their sum.
    for (mesh, depth) in [
        (samples::feature_mix(40), 2),
        (samples::mushroom(), 3),
        (samples::cube(), 1),
    ] {
        let plan = plan(&mesh, depth);
        let mut alone = PatchCounts::default();
        let mut stats = SurfaceStats::new();
        let mut kept = CollectSurface::new();
        Evaluator::<f64>::new(&plan)
            .unwrap()
            .evaluate(
                &mesh.vertices,
                &mut Tee(&mut alone, Tee(&mut stats, &mut kept)),
            )
            .unwrap();
        assert_eq!(alone, stats.patches);
        let (patches, caps) = kept.finish().unwrap();
        assert!(!caps.is_empty());
        for kind in PatchKind::ALL {
            let n = patches.iter().filter(|p| p.kind == kind).count();
            assert_eq!(alone.of(kind), n, "{kind:?}");
        }
        assert_eq!(alone.total, patches.len());
        assert_eq!(
            alone.total,
            alone.regular + alone.c2ps + alone.eg + alone.catmull_clark
        );
        assert_eq!(alone.total as u64, plan.patch_count());
    }
}
