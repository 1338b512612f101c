//! Accuracy of the f32 kernel's square-root-dependent outputs — pole normal,
//! curvatures, patch normals — against f64, with whichever `f32::sqrt`
//! backend is compiled in (libm by default, micromath with `--features micromath`).
//! The refinement itself never takes a square root in `R`, so link points do
//! not depend on the backend; the README quotes the bounds asserted here.

use capdiv::{FirstStep, PolarNet, PoleJet, Real};

fn sample<R: Real>(n: usize, seed: u64) -> ([R; 3], Vec<Vec<[R; 3]>>) {
    let mut s = seed;
    let mut rnd = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    };
    let (a, b) = (0.5 + rnd(), 0.3 * rnd());
    let links = (1..=5)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / n as f64;
                    let r = i as f64;
                    let (x, y) = (r * t.cos(), r * t.sin());
                    [
                        x + 0.05 * rnd(),
                        y + 0.05 * rnd(),
                        a * x * x + b * y * y + 0.05 * rnd(),
                    ]
                    .map(R::from_f64)
                })
                .collect()
        })
        .collect();
    ([R::ZERO; 3], links)
}

/// Worst relative deviations (normal, principal curvatures, patch normal).
fn deviations() -> (f64, f64, f64) {
    let (mut dn, mut dk, mut dp) = (0.0f64, 0.0f64, 0.0f64);
    // Under Miri (~10⁴× slower than native here) two configurations.
    let (seeds, valences): (u64, &[usize]) = if cfg!(miri) {
        (1, &[3, 5])
    } else {
        (32, &[3, 5, 6, 12])
    };
    for seed in 0..seeds {
        for &n in valences {
            let (p64, l64) = sample::<f64>(n, seed);
            let (p32, l32) = sample::<f32>(n, seed);
            let mut a: PolarNet<f64, 3072> = PolarNet::new(p64, &l64).unwrap();
            let mut b: PolarNet<f32, 3072> = PolarNet::new(p32, &l32).unwrap();
            for _ in 0..4 {
                a.step(FirstStep::Uniform).unwrap();
                b.step(FirstStep::Uniform).unwrap();
            }
            let ga = PoleJet::of(&a).geometry().unwrap();
            let gb = PoleJet::of(&b).geometry().unwrap();
            dn = dn.max(ga.normal.max_abs_diff(gb.normal.cast()));
            let scale = ga.principal[0].abs().max(ga.principal[1].abs()).max(1e-3);
            for k in 0..2 {
                dk = dk.max((ga.principal[k] - gb.principal[k] as f64).abs() / scale);
            }
            let pa = a.ring_patch(1).unwrap().normal(0.5, 0.5).unwrap();
            let pb = b.ring_patch(1).unwrap().normal(0.5, 0.5).unwrap();
            dp = dp.max(pa.max_abs_diff(pb.cast()));
        }
    }
    (dn, dk, dp)
}

#[test]
fn f32_sqrt_backend_accuracy() {
    let (dn, dk, dp) = deviations();
    println!("normal {dn:.3e}  principal curvature (rel) {dk:.3e}  patch normal {dp:.3e}");
    if cfg!(feature = "micromath") {
        // micromath's sqrt is a bit-level estimate with up to ~6 % error: unit
        // vectors come out with that length error (direction unaffected), and
        // √(H²−K) in the principal curvatures inherits it.
        assert!(dn < 0.07 && dp < 0.07 && dk < 0.07, "{dn} {dk} {dp}");
    } else {
        // libm's sqrtf is correctly rounded: what remains is f32 rounding of
        // the refinement (a few 1e-7 relative) amplified by the curvature
        // formulas' cancellation.
        assert!(dn < 1e-5 && dp < 1e-5 && dk < 1e-4, "{dn} {dk} {dp}");
    }
}
