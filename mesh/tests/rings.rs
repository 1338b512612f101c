//! `capdiv_mesh::rings`: one cap configuration's rings are the evaluator's
//! rings of the same cap in a mesh, bit for bit; a cap gives `depth` rings
//! of the scheme's size; every ring patch's edges follow `ring_edge_flags`;
//! bad configurations are errors, with nothing emitted.

mod common;

use capdiv::Error;
use capdiv_mesh::chart::Affine;
use capdiv_mesh::rings::{catmull_clark_rings, eg_rings, polar_rings, RingError, RingOptions};
use capdiv_mesh::sinks::CollectSurface;
use capdiv_mesh::tessellate::{ring_edge_flags, PatchGeometry, RingLayout};
use capdiv_mesh::{samples, Evaluator, MeshInput, PatchKind, PatchRecord, Scheme, SurfaceSink};

type Collect = CollectSurface<f64>;

/// `g` re-expressed through `map` (as the evaluator places a patch in its
/// face), as exact text (`{:?}` of f64 reads back to the same bits).
fn oriented(g: &PatchGeometry<f64>, map: &Affine) -> String {
    match g {
        PatchGeometry::Cubic(t) => format!("{:?}", map.orient(&t.points)),
        PatchGeometry::Quartic(t) => format!("{:?}", map.orient(&t.points)),
    }
}

fn exact(g: &PatchGeometry<f64>) -> String {
    oriented(g, &Affine::IDENTITY)
}

/// Compares one cap's rings, made from its configuration alone, with the
/// evaluator's patches of cap `index`: the same patches in the same order,
/// each placed by `chart_of(ring patch)` (its face's map, and the level the
/// evaluator adds), and the same cap record. Returns the patches compared.
fn same_as_evaluator(
    name: &str,
    single: &Collect,
    evaluated: &Collect,
    index: u32,
    chart_of: &dyn Fn(&PatchRecord<f64>) -> (Affine, u32),
) -> usize {
    let theirs: Vec<&PatchRecord<f64>> = evaluated
        .patches
        .iter()
        .filter(|p| p.cap == Some(index))
        .collect();
    assert_eq!(single.patches.len(), theirs.len(), "{name}: patches");
    for (k, (mine, theirs)) in single.patches.iter().zip(&theirs).enumerate() {
        let (map, level0) = chart_of(mine);
        assert_eq!(mine.kind, theirs.kind, "{name} patch {k}");
        assert_eq!(mine.level + level0, theirs.level, "{name} patch {k}");
        assert_eq!(
            oriented(&mine.geometry, &map),
            exact(&theirs.geometry),
            "{name} patch {k}: geometry"
        );
        assert_eq!(
            format!("{:?}", mine.hole_point),
            format!("{:?}", theirs.hole_point),
            "{name} patch {k}: hole point"
        );
        if map == Affine::IDENTITY {
            assert_eq!((mine.finer, mine.hole), (theirs.finer, theirs.hole));
        } else {
            // The same edges, renamed by the face's frame.
            assert_eq!(mine.finer.count_ones(), theirs.finer.count_ones());
            assert_eq!(mine.hole.count_ones(), theirs.hole.count_ones());
        }
    }
    let cap = single.caps.first().expect("a cap record");
    let their_cap = evaluated
        .caps
        .iter()
        .find(|c| c.index == index)
        .expect("the evaluator's cap");
    assert_eq!(single.caps.len(), 1);
    assert_eq!(
        (cap.scheme, cap.valence, cap.rings),
        (their_cap.scheme, their_cap.valence, their_cap.rings),
        "{name}"
    );
    assert_eq!(
        format!(
            "{:?} {:?} {:?}",
            cap.limit, cap.normal, cap.principal_curvatures
        ),
        format!(
            "{:?} {:?} {:?}",
            their_cap.limit, their_cap.normal, their_cap.principal_curvatures
        ),
        "{name}: cap"
    );
    theirs.len()
}

/// Every cap of `mesh` at `depth` whose configuration is made of input
/// vertices (no refinement before it), made alone and compared with the
/// evaluator's. Returns the caps compared per scheme.
fn compare_caps(
    name: &str,
    mesh: &MeshInput,
    depth: u32,
    catmull_clark: bool,
    tolerance: Option<f64>,
) -> Vec<Scheme> {
    let plan = common::plan_with(mesh, depth, catmull_clark);
    let mut evaluated = Collect::new();
    let mut ev = Evaluator::<f64>::new(&plan).expect("evaluator");
    ev.set_hole_tolerance(tolerance);
    ev.evaluate(&mesh.vertices, &mut evaluated)
        .expect("evaluate");
    let input = |i: u32| mesh.vertices.get(i as usize).copied();
    let options = |first| RingOptions {
        depth,
        hole_tolerance: tolerance,
        first,
    };
    let mut compared = Vec::new();
    if !plan.steps.is_empty() {
        return compared;
    }
    for (k, p) in plan.polar.iter().enumerate() {
        let (Some(pole), Some(links)) = (
            input(p.pole),
            p.links
                .iter()
                .map(|&i| input(i))
                .collect::<Option<Vec<_>>>(),
        ) else {
            continue;
        };
        let mut single = Collect::new();
        polar_rings(pole, &links, &options(p.first), &mut single).expect("polar rings");
        // Ring patches beyond link 1 lie in the quads between links 1 and
        // 2, placed by their quad's chart; the rest in the pole's triangles.
        let chart = |r: &PatchRecord<f64>| {
            let map = if r.domain[1] <= 1.0 || p.quads.is_empty() {
                Affine::IDENTITY
            } else {
                p.quads[r.face as usize].map
            };
            (map, p.prior_steps)
        };
        let n = same_as_evaluator(
            &format!("{name} pole {k}"),
            &single,
            &evaluated,
            k as u32,
            &chart,
        );
        assert!(n > 0);
        compared.push(Scheme::C2ps);
    }
    for (k, e) in plan.extraordinary.iter().enumerate() {
        let (Some(centre), Some(nodes)) = (
            input(e.center),
            e.nodes
                .iter()
                .map(|&i| input(i))
                .collect::<Option<Vec<_>>>(),
        ) else {
            continue;
        };
        if e.table.is_some() {
            continue;
        }
        let mut single = Collect::new();
        let o = options(Default::default());
        match e.scheme {
            Scheme::Eg => eg_rings(centre, &nodes, &o, &mut single),
            _ => catmull_clark_rings(centre, &nodes, &o, &mut single),
        }
        .expect("rings");
        let chart = |r: &PatchRecord<f64>| (e.sectors[r.face as usize].map, e.level);
        let index = (plan.polar.len() + k) as u32;
        same_as_evaluator(
            &format!("{name} cap {k}"),
            &single,
            &evaluated,
            index,
            &chart,
        );
        compared.push(e.scheme);
    }
    compared
}

#[test]
fn a_caps_rings_are_the_evaluators_bit_for_bit() {
    let cases: [(&str, MeshInput, bool); 6] = [
        ("pole disk", samples::pole_disk(6, 4), false),
        ("globe", samples::globe(5, 8), false),
        ("eg n=3", samples::extraordinary_disk(3, 3), false),
        ("eg n=5", samples::extraordinary_disk(5, 3), false),
        ("cc n=7", samples::extraordinary_disk(7, 3), false),
        ("cc n=5", samples::extraordinary_disk(5, 3), true),
    ];
    let mut seen = Vec::new();
    for (name, mesh, cc) in &cases {
        for tolerance in [None, Some(0.01)] {
            let compared = compare_caps(name, mesh, 3, *cc, tolerance);
            assert!(!compared.is_empty(), "{name}: no cap compared");
            seen.extend(compared);
        }
    }
    // Every scheme was compared, not only the easy ones.
    for scheme in [Scheme::C2ps, Scheme::Eg, Scheme::CatmullClark] {
        assert!(seen.contains(&scheme), "{scheme:?} never compared");
    }
}

/// A valence-`n` c-net around the origin on a paraboloid, sector by sector
/// in the order (1,0) (2,0) (1,1) (2,1) (1,2) (2,2).
fn cnet(n: usize) -> Vec<[f64; 3]> {
    let mut nodes = Vec::new();
    for s in 0..n {
        let a = std::f64::consts::TAU * s as f64 / n as f64;
        let b = a + std::f64::consts::TAU / n as f64;
        for (x, y) in [(1., 0.), (2., 0.), (1., 1.), (2., 1.), (1., 2.), (2., 2.)] {
            let p = [x * a.cos() + y * b.cos(), x * a.sin() + y * b.sin()];
            nodes.push([p[0], p[1], 0.1 * (p[0] * p[0] + p[1] * p[1]) + 0.02 * p[0]]);
        }
    }
    nodes
}

/// Links 1, 2, 3 of a valence-`n` pole at the origin on a paraboloid.
fn polar_links(n: usize) -> Vec<[f64; 3]> {
    (1..=3)
        .flat_map(|i| {
            (0..n).map(move |j| {
                let t = std::f64::consts::TAU * j as f64 / n as f64;
                let r = i as f64;
                [r * t.cos(), r * t.sin(), 0.1 * r * r + 0.01 * r * t.sin()]
            })
        })
        .collect()
}

#[test]
fn without_a_tolerance_a_cap_has_depth_rings_of_the_schemes_size() {
    for depth in [1u32, 2, 4] {
        let o = RingOptions::new(depth);
        for n in [3usize, 5, 6] {
            // C²PS ring m: 2 spans of n·2^m columns.
            let mut c = Collect::new();
            let rings = polar_rings([0.0; 3], &polar_links(n), &o, &mut c).unwrap();
            assert_eq!(rings, depth);
            assert_eq!(c.caps[0].rings, depth);
            for m in 1..=depth {
                let count = c.patches.iter().filter(|p| p.level == m).count();
                assert_eq!(count, (2 * n) << m, "c2ps n={n} ring {m}");
            }
            // EG (n = 3, 5: built-in rules) and Catmull-Clark: 3n per ring.
            let mut runs = vec![(PatchKind::CatmullClark, Collect::new())];
            if n != 6 {
                runs.push((PatchKind::Eg, Collect::new()));
            }
            for (kind, c) in &mut runs {
                let rings = match kind {
                    PatchKind::Eg => eg_rings([0.0; 3], &cnet(n), &o, c),
                    _ => catmull_clark_rings([0.0; 3], &cnet(n), &o, c),
                }
                .unwrap();
                assert_eq!(rings, depth);
                assert_eq!(c.caps[0].rings, depth);
                assert!(c.patches.iter().all(|p| p.kind == *kind));
                for m in 1..=depth {
                    let count = c.patches.iter().filter(|p| p.level == m).count();
                    assert_eq!(count, 3 * n, "{kind:?} n={n} ring {m}");
                }
            }
        }
    }
}

#[test]
fn a_tolerance_stops_a_cap_no_later_than_its_depth() {
    // A hole tolerance larger than the configuration itself is met after
    // the first ring; a tiny one never before the depth.
    let depth = 5;
    for (tolerance, want) in [(Some(1e3), 1), (Some(1e-12), depth), (None, depth)] {
        let o = RingOptions {
            hole_tolerance: tolerance,
            ..RingOptions::new(depth)
        };
        let mut c = Collect::new();
        assert_eq!(polar_rings([0.0; 3], &polar_links(5), &o, &mut c), Ok(want));
        let mut c = Collect::new();
        assert_eq!(eg_rings([0.0; 3], &cnet(5), &o, &mut c), Ok(want));
        let mut c = Collect::new();
        assert_eq!(
            catmull_clark_rings([0.0; 3], &cnet(7), &o, &mut c),
            Ok(want)
        );
        assert_eq!(c.patches.iter().map(|p| p.level).max(), Some(want));
    }
}

/// The ring patches of `c`, ring by ring (by level, in emission order).
fn by_ring(c: &Collect) -> Vec<Vec<&PatchRecord<f64>>> {
    let last = c.patches.iter().map(|p| p.level).max().unwrap_or(0);
    (1..=last)
        .map(|m| c.patches.iter().filter(|p| p.level == m).collect())
        .collect()
}

#[test]
fn edge_flags_follow_ring_edge_flags() {
    let o = RingOptions::new(3);
    let mut polar = Collect::new();
    polar_rings([0.0; 3], &polar_links(5), &o, &mut polar).unwrap();
    let mut eg = Collect::new();
    eg_rings([0.0; 3], &cnet(5), &o, &mut eg).unwrap();
    let mut cc = Collect::new();
    catmull_clark_rings([0.0; 3], &cnet(6), &o, &mut cc).unwrap();
    for (layout, c) in [
        (RingLayout::Polar, &polar),
        (RingLayout::Sectors, &eg),
        (RingLayout::Sectors, &cc),
    ] {
        let rings = by_ring(c);
        let last = rings.len();
        for (m, ring) in rings.iter().enumerate() {
            let is_last = m + 1 == last;
            for (j, p) in ring.iter().enumerate() {
                assert_eq!(
                    (p.finer, p.hole),
                    ring_edge_flags(layout, j, ring.len(), is_last),
                    "{layout:?} ring {} patch {j}",
                    m + 1
                );
            }
            // What the rule means: only the last ring borders the hole, and
            // it meets no finer ring; the others meet the next ring along
            // the same inner edges (C²PS: span 0; EG/CC: pieces 0 and 1).
            let inner = ring.iter().filter(|p| p.finer | p.hole != 0).count();
            let want = match layout {
                RingLayout::Polar => ring.len() / 2,
                RingLayout::Sectors => 2 * ring.len() / 3,
            };
            assert_eq!(inner, want);
            if is_last {
                assert!(ring.iter().all(|p| p.finer == 0));
            } else {
                assert!(ring.iter().all(|p| p.hole == 0));
            }
        }
    }
}

/// Records what it is given.
#[derive(Default)]
struct Seen(usize);

impl SurfaceSink<f64> for Seen {
    fn patch(&mut self, _: &PatchRecord<f64>) {
        self.0 += 1;
    }
    fn cap(&mut self, _: &capdiv_mesh::CapRecord<f64>) {
        self.0 += 1;
    }
}

#[test]
fn bad_configurations_are_errors_and_emit_nothing() {
    let o = RingOptions::new(2);
    let mut links = polar_links(5);
    let mut nodes = cnet(5);
    type Rings = fn(
        [f64; 3],
        &[[f64; 3]],
        &RingOptions,
        &mut dyn SurfaceSink<f64>,
    ) -> Result<u32, RingError>;
    let check = |f: Rings, around: &[[f64; 3]], o: &RingOptions, want: RingError| {
        let mut seen = Seen::default();
        assert_eq!(f([0.0; 3], around, o, &mut seen), Err(want));
        assert_eq!(seen.0, 0, "{want:?}: something was emitted");
        // The message is one line.
        assert!(!want.to_string().contains('\n'));
    };
    // Not whole links or sectors.
    check(
        polar_rings,
        &links[..14],
        &o,
        RingError::Length {
            found: 14,
            multiple: 3,
        },
    );
    check(
        polar_rings,
        &[],
        &o,
        RingError::Length {
            found: 0,
            multiple: 3,
        },
    );
    for f in [eg_rings as Rings, catmull_clark_rings] {
        check(
            f,
            &nodes[..29],
            &o,
            RingError::Length {
                found: 29,
                multiple: 6,
            },
        );
        check(
            f,
            &[],
            &o,
            RingError::Length {
                found: 0,
                multiple: 6,
            },
        );
        // Valence 2.
        check(
            f,
            &nodes[..12],
            &o,
            RingError::Kernel(Error::ValenceTooSmall { valence: 2 }),
        );
    }
    check(
        polar_rings,
        &polar_links(2),
        &o,
        RingError::Kernel(Error::ValenceTooSmall { valence: 2 }),
    );
    // A point that is not finite.
    links[7][1] = f64::NAN;
    nodes[7][1] = f64::INFINITY;
    for (f, around) in [
        (polar_rings as Rings, &links),
        (eg_rings as Rings, &nodes),
        (catmull_clark_rings as Rings, &nodes),
    ] {
        let mut seen = Seen::default();
        let e = f([0.0; 3], around, &o, &mut seen).unwrap_err();
        assert!(matches!(e, RingError::Kernel(_)), "{e:?}");
        assert_eq!(seen.0, 0);
    }
    // A C²PS cap too deep for the largest net: valence 5·2^40.
    let deep = RingOptions::new(40);
    check(
        polar_rings,
        &polar_links(5),
        &deep,
        RingError::Capacity {
            needed: Some(5 << 40),
            max: capdiv_mesh::evaluate::MAX_POLAR_VALENCE,
        },
    );
}

#[test]
fn a_cap_far_from_the_origin_is_the_cap_at_the_origin_moved() {
    // The rings are computed around the centre: a configuration moved by a
    // power of two (exact in f64 for these coordinates) gives the same
    // rings moved, to within one rounding of the moved coordinates.
    let shift = [1024.0, -2048.0, 512.0];
    let moved = |p: [f64; 3]| [p[0] + shift[0], p[1] + shift[1], p[2] + shift[2]];
    let o = RingOptions::new(3);
    let (mut at0, mut far) = (Collect::new(), Collect::new());
    let nodes = cnet(5);
    eg_rings([0.0; 3], &nodes, &o, &mut at0).unwrap();
    let far_nodes: Vec<_> = nodes.iter().copied().map(moved).collect();
    eg_rings(moved([0.0; 3]), &far_nodes, &o, &mut far).unwrap();
    // One ulp of 2048.
    let ulp = 2048.0 * f64::EPSILON;
    for (a, b) in at0.patches.iter().zip(&far.patches) {
        let (PatchGeometry::Quartic(a), PatchGeometry::Quartic(b)) = (&a.geometry, &b.geometry)
        else {
            panic!("EG patches are quartic");
        };
        for (pa, pb) in a.points.iter().flatten().zip(b.points.iter().flatten()) {
            for ((a, b), s) in pa.0.iter().zip(pb.0).zip(shift) {
                assert!((a + s - b).abs() <= ulp);
            }
        }
    }
}
