//! `shade`: highlight lines of a plane are straight and evenly spaced; the
//! colour map and the colour scale do what their docs say.

use capdiv_mesh::shade::{diverging, symmetric_scale, HighlightLines};
use proptest::prelude::*;

/// A horizontal plane under light lines along `y`, spaced `s` along `x`: its
/// normal lines are vertical, so the stripe parameter is `(x − x0)/s`
/// exactly (up to rounding of the few operations: 1e-12 for `|x| ≤ 10`).
#[test]
fn stripes_of_a_horizontal_plane_are_the_light_lines_themselves() {
    let lines =
        HighlightLines::new([0.5, 0.0, 3.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0], 0.25).unwrap();
    for i in -40..=40 {
        for j in -5..=5 {
            let (x, y) = (i as f64 * 0.1, j as f64 * 0.7);
            let s = lines.parameter([x, y, -1.0], [0.0, 0.0, 1.0]).unwrap();
            assert!((s - (x - 0.5) / 0.25).abs() < 1e-12, "{s} at {x}");
        }
    }
    // On a line: full intensity; halfway between lines: none.
    assert_eq!(lines.intensity([0.5, 2.0, 0.0], [0.0, 0.0, 1.0], 0.2), 1.0);
    assert_eq!(
        lines.intensity([0.625, 2.0, 0.0], [0.0, 0.0, 1.0], 0.2),
        0.0
    );
}

proptest! {
    /// Any plane (constant normal) under any light lines: the stripe
    /// parameter is an affine function of the point on the plane, so its
    /// level sets — the highlight lines — are straight, parallel and evenly
    /// spaced: `s(p+a) + s(p+b) = s(p) + s(p+a+b)` for in-plane `a`, `b`.
    #[test]
    fn stripes_of_any_plane_are_straight_and_evenly_spaced(
        n in prop::array::uniform3(-1.0f64..1.0),
        dir in prop::array::uniform3(-1.0f64..1.0),
        across in prop::array::uniform3(-1.0f64..1.0),
        origin in prop::array::uniform3(-2.0f64..2.0),
        p in prop::array::uniform3(-1.0f64..1.0),
        ab in prop::array::uniform4(-1.0f64..1.0),
    ) {
        let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        prop_assume!(norm(n) > 0.2);
        let Some(lines) = HighlightLines::new(origin, dir, across, 0.3) else {
            return Ok(());
        };
        // Two in-plane directions of the plane with normal n.
        let helper = if n[0].abs() < 0.5 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
        };
        let t1 = cross(n, helper);
        let t2 = cross(n, t1);
        let at = |x: f64, y: f64| [
            p[0] + x * t1[0] + y * t2[0],
            p[1] + x * t1[1] + y * t2[1],
            p[2] + x * t1[2] + y * t2[2],
        ];
        let s = |q: [f64; 3]| lines.parameter(q, n);
        let (Some(s0), Some(sa), Some(sb), Some(sab)) = (
            s(at(0.0, 0.0)),
            s(at(ab[0], ab[1])),
            s(at(ab[2], ab[3])),
            s(at(ab[0] + ab[2], ab[1] + ab[3])),
        ) else {
            return Ok(());
        };
        // Rounding relative to the largest term (|μ| grows as n turns
        // parallel to the light plane).
        let scale = 1.0 + s0.abs() + sa.abs() + sb.abs() + sab.abs();
        prop_assert!((sa + sb - s0 - sab).abs() < 1e-9 * scale);
    }
}

#[test]
fn diverging_map_runs_blue_white_red() {
    assert_eq!(diverging(-1.0), [0, 0, 255]);
    assert_eq!(diverging(0.0), [255, 255, 255]);
    assert_eq!(diverging(1.0), [255, 0, 0]);
    assert_eq!(diverging(7.0), diverging(1.0));
    assert_eq!(diverging(f64::NAN), diverging(0.0));
    // Monotone in each half: more curvature, more colour.
    for k in 0..100 {
        let (a, b) = (k as f64 / 100.0, (k + 1) as f64 / 100.0);
        assert!(diverging(b)[1] <= diverging(a)[1]);
        assert!(diverging(-b)[0] <= diverging(-a)[0]);
    }
}

#[test]
fn symmetric_scale_ignores_the_extreme_few() {
    let mut values: Vec<f64> = (0..1000).map(|k| (k as f64 / 999.0) * 2.0 - 1.0).collect();
    values.push(1e9);
    values.push(f64::NAN);
    let m = symmetric_scale(&values, 0.98);
    assert!((0.95..=1.0).contains(&m), "{m}");
    assert_eq!(symmetric_scale(&[0.0, 0.0], 0.98), f64::MIN_POSITIVE);
    assert_eq!(symmetric_scale(&[], 0.98), 1.0);
}

#[test]
fn bad_light_lines_are_refused() {
    assert!(HighlightLines::new([0.0; 3], [0.0; 3], [1.0, 0.0, 0.0], 1.0).is_none());
    assert!(HighlightLines::new([0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], 1.0).is_none());
    assert!(HighlightLines::new([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0.0).is_none());
    assert!(HighlightLines::new([f64::NAN; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 1.0).is_none());
}
