//! `TensorPatch::jet` and `SurfaceJet::geometry` against closed forms.
//!
//! A polynomial graph `z = a x² + b xy + c y² + p x + q y` over `[0,1]²` is a
//! Bézier patch of any degree `d ≥ 2` exactly (its Bernstein coefficients are
//! `x_i = i/d`, `x_i² ↦ i(i−1)/(d(d−1))`), so the patch's curvature must equal
//! the graph's analytic curvature:
//! `K = (z_xx z_yy − z_xy²)/W⁴`, `H = ((1+z_y²) z_xx − 2 z_x z_y z_xy + (1+z_x²) z_yy)/(2W³)`,
//! `W = √(1 + z_x² + z_y²)` (do Carmo §3-3, Example 5 / Exercise 5).
//! Tolerance: the de Casteljau sums of a few O(1) terms in f64, a handful of
//! ulps each, amplified by at most W⁴ ≤ 100 for the coefficients used: 1e-12.

use capdiv::{Error, Point3, TensorPatch};
use proptest::prelude::*;

#[derive(Clone, Copy, Debug)]
struct Quadric {
    a: f64,
    b: f64,
    c: f64,
    p: f64,
    q: f64,
}

impl Quadric {
    fn z(&self, x: f64, y: f64) -> f64 {
        self.a * x * x + self.b * x * y + self.c * y * y + self.p * x + self.q * y
    }

    /// The graph over `[0,1]²` as a `K×K` Bézier patch.
    fn patch<const K: usize>(&self) -> TensorPatch<f64, K> {
        let d = (K - 1) as f64;
        let lin = |i: usize| i as f64 / d;
        let sq = |i: usize| (i * i.saturating_sub(1)) as f64 / (d * (d - 1.0));
        let mut points = [[Point3::new(0.0, 0.0, 0.0); K]; K];
        for (i, row) in points.iter_mut().enumerate() {
            for (j, pt) in row.iter_mut().enumerate() {
                let z = self.a * sq(i)
                    + self.b * lin(i) * lin(j)
                    + self.c * sq(j)
                    + self.p * lin(i)
                    + self.q * lin(j);
                *pt = Point3::new(lin(i), lin(j), z);
            }
        }
        TensorPatch { points }
    }

    /// Analytic `(K, H)` at `(x, y)`, normal `(−z_x, −z_y, 1)/W`.
    fn curvature(&self, x: f64, y: f64) -> (f64, f64) {
        let zx = 2.0 * self.a * x + self.b * y + self.p;
        let zy = self.b * x + 2.0 * self.c * y + self.q;
        let (zxx, zxy, zyy) = (2.0 * self.a, self.b, 2.0 * self.c);
        let w2 = 1.0 + zx * zx + zy * zy;
        let k = (zxx * zyy - zxy * zxy) / (w2 * w2);
        let h = ((1.0 + zy * zy) * zxx - 2.0 * zx * zy * zxy + (1.0 + zx * zx) * zyy)
            / (2.0 * w2 * w2.sqrt());
        (k, h)
    }
}

fn check<const K: usize>(quad: Quadric, u: f64, v: f64) {
    let patch = quad.patch::<K>();
    let jet = patch.jet(u, v).unwrap();
    assert!((jet.position.0[2] - quad.z(u, v)).abs() < 1e-13);
    let g = jet.geometry().unwrap();
    let (k, h) = quad.curvature(u, v);
    assert!((g.gaussian - k).abs() < 1e-12, "K {} vs {k}", g.gaussian);
    assert!((g.mean - h).abs() < 1e-12, "H {} vs {h}", g.mean);
    // Principal curvatures: their sum and product are 2H and K.
    let [k1, k2] = g.principal;
    assert!(k1 >= k2);
    assert!((k1 + k2 - 2.0 * h).abs() < 1e-11);
    assert!((k1 * k2 - k).abs() < 1e-10);
    // The graph's normal has a positive z component.
    assert!(g.normal.0[2] > 0.0);
}

proptest! {
    #![proptest_config(ProptestConfig {
        // Under Miri: a few cases, no regression files (isolation).
        cases: if cfg!(miri) { 4 } else { 256 },
        failure_persistence: if cfg!(miri) { None } else { ProptestConfig::default().failure_persistence },
        ..ProptestConfig::default()
    })]
    #[test]
    fn curvature_of_a_sampled_quadric_is_the_analytic_one(
        a in -2.0f64..2.0, b in -2.0f64..2.0, c in -2.0f64..2.0,
        p in -1.0f64..1.0, q in -1.0f64..1.0,
        u in 0.0f64..=1.0, v in 0.0f64..=1.0,
    ) {
        let quad = Quadric { a, b, c, p, q };
        check::<3>(quad, u, v);
        check::<4>(quad, u, v);
        check::<5>(quad, u, v);
    }

    /// The jet's first partials are `evaluate`'s, and its second partials the
    /// central differences of the first. Truncation `h²/6·|x''''|` with
    /// `|x_uuuv| ≤ 4·3·2·4·2⁴ = 1536` for control points in `[-1, 1]`:
    /// 2.6e-7 at `h = 1e-5`; rounding `ε·|x'|/h ≤ 1e-16·64/1e-5`: 6e-10.
    #[test]
    fn second_partials_are_derivatives_of_the_first(
        seed in proptest::collection::vec(-1.0f64..1.0, 75),
        u in 0.01f64..0.99, v in 0.01f64..0.99,
    ) {
        let mut points = [[Point3::new(0.0, 0.0, 0.0); 5]; 5];
        for (k, pt) in points.iter_mut().flatten().enumerate() {
            *pt = Point3::new(seed[3 * k], seed[3 * k + 1], seed[3 * k + 2]);
        }
        let patch = TensorPatch { points };
        let jet = patch.jet(u, v).unwrap();
        let first = patch.evaluate(u, v).unwrap();
        prop_assert!((jet.du - first.du).norm() < 1e-13);
        prop_assert!((jet.dv - first.dv).norm() < 1e-13);
        prop_assert!((jet.position - first.position).norm() < 1e-14);
        let h = 1e-5;
        let at = |u: f64, v: f64| patch.evaluate(u, v).unwrap();
        let duu = (at(u + h, v).du - at(u - h, v).du) * (0.5 / h);
        let duv = (at(u + h, v).dv - at(u - h, v).dv) * (0.5 / h);
        let dvv = (at(u, v + h).dv - at(u, v - h).dv) * (0.5 / h);
        prop_assert!((jet.duu - duu).norm() < 1e-6);
        prop_assert!((jet.duv - duv).norm() < 1e-6, "{:?} vs {:?}", jet.duv, duv);
        prop_assert!((jet.dvv - dvv).norm() < 1e-6);
    }
}

/// A sphere's curvature from a rational-free approximation is not exact, but a
/// paraboloid `z = (x² + y²)/2` has `K = 1`, `H = 1` at its apex exactly.
#[test]
fn paraboloid_apex_has_unit_curvatures() {
    let quad = Quadric {
        a: 0.5,
        b: 0.0,
        c: 0.5,
        p: 0.0,
        q: 0.0,
    };
    let g = quad.patch::<4>().jet(0.0, 0.0).unwrap().geometry().unwrap();
    assert!((g.gaussian - 1.0).abs() < 1e-14);
    assert!((g.mean - 1.0).abs() < 1e-14);
    assert_eq!(g.principal, [1.0, 1.0]);
}

#[test]
fn jet_rejects_parameters_outside_the_square() {
    let patch = Quadric {
        a: 1.0,
        b: 0.0,
        c: 1.0,
        p: 0.0,
        q: 0.0,
    }
    .patch::<4>();
    for (u, v) in [
        (-0.1, 0.5),
        (0.5, 1.5),
        (f64::NAN, 0.5),
        (0.5, f64::INFINITY),
    ] {
        assert_eq!(patch.jet(u, v), Err(Error::OutOfDomain));
    }
}

#[test]
fn a_collapsed_patch_is_degenerate() {
    let points = [[Point3::new(1.0f32, 2.0, 3.0); 4]; 4];
    let jet = TensorPatch { points }.jet(0.5, 0.5).unwrap();
    assert_eq!(jet.geometry(), Err(Error::Degenerate));
}
