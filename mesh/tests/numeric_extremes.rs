//! The numeric contract of the kernel (docs/accuracy.md, "Numeric contract") through
//! whole meshes: sample meshes scaled to huge (up to `MAX`), tiny, subnormal
//! and mixed magnitudes, evaluated in f64 and f32. Every evaluation either
//! returns an error or emits only finite patches and caps — never a NaN or an
//! infinity silently.

mod common;

use capdiv::Point3;
use capdiv_mesh::{samples, EvalError, Evaluator, MeshInput, SurfacePlan, Topology};
use common::*;

/// The samples: C²PS (pole disk, globe), EG (n = 3, 5), Catmull-Clark (n = 7),
/// a refined cube, a grid with boundaries.
fn meshes() -> Vec<(&'static str, MeshInput)> {
    vec![
        ("pole_disk(8, 5)", samples::pole_disk(8, 5)),
        ("globe(5, 6)", samples::globe(5, 6)),
        (
            "extraordinary_disk(3, 3)",
            samples::extraordinary_disk(3, 3),
        ),
        (
            "extraordinary_disk(5, 3)",
            samples::extraordinary_disk(5, 3),
        ),
        (
            "extraordinary_disk(7, 3)",
            samples::extraordinary_disk(7, 3),
        ),
        ("cube", samples::cube()),
        ("grid(4, 4)", samples::grid(4, 4)),
    ]
}

/// Coordinate maps: `x ↦ s·x` for the extreme scales, and one mixed map.
/// `(vertex, coordinate index, value) ↦ scaled value`.
type CoordMap = Box<dyn Fn(usize, usize, f64) -> f64>;

/// Huge scales `MAX/2^k` for the given `k`.
fn scalings(max: f64, min_pos: f64, huge: &[i32]) -> Vec<(String, CoordMap)> {
    let mut out: Vec<(String, CoordMap)> = Vec::new();
    for &k in huge {
        let s = max * libm::exp2(-f64::from(k)) / 4.0;
        out.push((format!("MAX/2^{k}"), Box::new(move |_, _, x| x * s)));
    }
    for k in [0, 8, 20, 40] {
        let s = min_pos * libm::exp2(-f64::from(k));
        out.push((
            format!("MIN_POSITIVE/2^{k}"),
            Box::new(move |_, _, x| x * s),
        ));
    }
    out.push((
        "mixed 1e30 / 1e-30".into(),
        Box::new(|v, c, x| if v == 0 && c == 2 { 1e30 } else { x * 1e-30 }),
    ));
    out.push(("zero size".into(), Box::new(|_, _, _| 1e-30)));
    out
}

fn check<R: capdiv::Real>(
    name: &str,
    plan: &SurfacePlan<'_>,
    positions: &[[R; 3]],
) -> Result<(), EvalError> {
    let mut ev = Evaluator::<R>::new(plan).expect("evaluator");
    let mut out = Collect::<R>::default();
    ev.evaluate(positions, &mut out)?;
    let fin = |p: &Point3<R>| p.is_finite();
    for p in &out.patches {
        let pts: Vec<Point3<R>> = match &p.geometry {
            capdiv_mesh::tessellate::PatchGeometry::Cubic(b) => {
                b.points.iter().flatten().copied().collect()
            }
            capdiv_mesh::tessellate::PatchGeometry::Quartic(b) => {
                b.points.iter().flatten().copied().collect()
            }
        };
        assert!(
            pts.iter().all(fin),
            "{name}: non-finite patch of face {:?} ({:?})",
            p.face,
            p.kind
        );
    }
    for c in &out.caps {
        assert!(fin(&c.limit), "{name}: cap limit {:?}", c.limit);
        assert!(c.normal.as_ref().is_none_or(fin), "{name}: cap normal");
        assert!(
            c.principal_curvatures
                .is_none_or(|k| k.iter().all(|x| x.is_finite())),
            "{name}: curvatures"
        );
    }
    Ok(())
}

/// Coordinates up to `MAX/2^10` (and all tiny, subnormal, mixed scales).
#[test]
#[cfg_attr(miri, ignore = "whole meshes: too large for Miri")]
fn scaled_samples_are_finite_or_errors() {
    scaled_samples(&[10, 12, 20]);
}

/// Coordinates up to `MAX/4` (regular patches near `MAX/4` overflowed
/// silently before `EvalError::Overflow`).
#[test]
#[cfg_attr(miri, ignore = "whole meshes: too large for Miri")]
fn scaled_samples_up_to_max_are_finite_or_errors() {
    scaled_samples(&[0, 1, 2, 4, 8]);
}

fn scaled_samples(huge: &[i32]) {
    let (mut ok, mut err) = (0, 0);
    for (mesh_name, m) in meshes() {
        let topo = Topology::new(&m).unwrap();
        let plan = SurfacePlan::new(&topo, common::plan_options(3, false)).unwrap();
        for (f32_run, (max, min_pos)) in [
            (false, (f64::MAX, f64::MIN_POSITIVE)),
            (true, (f32::MAX as f64, f32::MIN_POSITIVE as f64)),
        ] {
            for (scale_name, map) in scalings(max, min_pos, huge) {
                let pos: Vec<[f64; 3]> = m
                    .vertices
                    .iter()
                    .enumerate()
                    .map(|(v, p)| [0, 1, 2].map(|c| map(v, c, p[c])))
                    .collect();
                let name = format!("{mesh_name} at {scale_name} (f32: {f32_run})");
                let r = if f32_run {
                    let p32: Vec<[f32; 3]> = pos.iter().map(|p| p.map(|c| c as f32)).collect();
                    if !p32.iter().flatten().all(|c| c.is_finite()) {
                        continue;
                    }
                    check::<f32>(&name, &plan, &p32)
                } else {
                    check::<f64>(&name, &plan, &pos)
                };
                match r {
                    Ok(()) => ok += 1,
                    Err(e) => {
                        // Only overflow errors (the kernel's or the
                        // refined mesh's), at huge scales.
                        assert!(
                            matches!(
                                e,
                                EvalError::Kernel {
                                    error: capdiv::Error::NonFinite | capdiv::Error::Degenerate,
                                    ..
                                } | EvalError::Overflow
                            ),
                            "{name}: {e:?}"
                        );
                        err += 1;
                    }
                }
            }
        }
    }
    println!("evaluations: {ok} finite, {err} errors");
    assert!(ok > 0);
}

/// Each sample scaled so that its largest coordinate is `MAX·2^-k`.
fn scaled_to<R: capdiv::Real>(m: &MeshInput, max: f64, k: i32, cast: fn(f64) -> R) -> Vec<[R; 3]> {
    let big = m
        .vertices
        .iter()
        .flatten()
        .fold(0.0f64, |a, c| a.max(c.abs()));
    let s = max * libm::exp2(-f64::from(k)) / big;
    m.vertices.iter().map(|p| p.map(|c| cast(c * s))).collect()
}

fn evaluate_all<R: capdiv::Real>(
    plan: &SurfacePlan<'_>,
    positions: &[[R; 3]],
) -> (Result<(), EvalError>, usize) {
    let mut ev = Evaluator::<R>::new(plan).expect("evaluator");
    let mut out = Collect::<R>::default();
    let r = ev.evaluate(positions, &mut out);
    (r, out.patches.len() + out.caps.len())
}

/// The refined-mesh check (`EvalError::Overflow`) never fires for input
/// coordinates up to `MAX/32` (its documented bound: refined points are
/// convex combinations, phantom points at most 9 times the input); at
/// `MAX/2` every sample fails it, before emitting anything. f32 and f64.
#[test]
#[cfg_attr(miri, ignore = "whole meshes: too large for Miri")]
fn refined_mesh_overflow_is_reported_before_any_patch() {
    for (name, m) in meshes() {
        let topo = Topology::new(&m).unwrap();
        let plan = SurfacePlan::new(&topo, common::plan_options(3, false)).unwrap();
        for k in 5..=12 {
            let (r64, _) = evaluate_all(&plan, &scaled_to(&m, f64::MAX, k, |c| c));
            let (r32, _) = evaluate_all(&plan, &scaled_to(&m, f32::MAX.into(), k, |c| c as f32));
            for r in [r64, r32] {
                assert!(r != Err(EvalError::Overflow), "{name} at MAX/2^{k}: {r:?}");
            }
        }
        // Measured edge (printed): the smallest k with no Overflow.
        let edge = |max: f64, f32_run: bool| {
            (0..5).find(|&k| {
                let r = if f32_run {
                    evaluate_all(&plan, &scaled_to(&m, max, k, |c| c as f32)).0
                } else {
                    evaluate_all(&plan, &scaled_to(&m, max, k, |c| c)).0
                };
                r != Err(EvalError::Overflow)
            })
        };
        println!(
            "{name}: first scale without Overflow MAX/2^k, k = {:?} (f64), {:?} (f32)",
            edge(f64::MAX, false),
            edge(f32::MAX.into(), true)
        );
        let (r64, n64) = evaluate_all(&plan, &scaled_to(&m, f64::MAX, 0, |c| c));
        let (r32, n32) = evaluate_all(&plan, &scaled_to(&m, f32::MAX.into(), 0, |c| c as f32));
        for (r, n) in [(r64, n64), (r32, n32)] {
            assert_eq!(r, Err(EvalError::Overflow), "{name} at MAX");
            assert_eq!(n, 0, "{name}: emitted before the error");
        }
    }
}
