//! Findings of the coverage-guided fuzz targets (`fuzz/`), each with
//! its minimized input inline.

use capdiv::{CcCap, Point3, PoleJet};

/// `fuzz/kernel_polar` (on 4f57ec0): `PoleJet::geometry` returned `Ok` with a
/// NaN Gaussian curvature and curvatures near `f64::MAX` for the jet of a net
/// with coordinates near 1e305 (its 1-link lifted far above its tangents).
/// Fixed by e5b66d1 (curvature overflow is `NonFinite`); kept so it stays so.
#[test]
fn pole_geometry_of_huge_jet_is_finite_or_error() {
    let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    let jet = PoleJet {
        p: [
            p(
                2.6702067057291665,
                1.1703731346759867e305,
                -57.804341634114586,
            ),
            p(-0.1409195878777399, 0.0, -0.24349148682731814),
            p(0.0522473058275148, 0.0, -0.005265542538584356),
            p(2.002655029296875, -4.38889925503495e304, 27.404556274414055),
            p(
                -0.100904821396015,
                -7.308985508549999e288,
                -0.18498023641256467,
            ),
            p(
                0.0787520060221877,
                -5.938550725696874e288,
                -0.00793671618357919,
            ),
        ],
    };
    if let Ok(g) = jet.geometry() {
        assert!(g.normal.is_finite(), "{g:?}");
        assert!(g.gaussian.is_finite() && g.mean.is_finite(), "{g:?}");
        assert!(g.principal.iter().all(|c| c.is_finite()), "{g:?}");
    }
}

/// `fuzz/kernel_eg_cc`: `CcCap::<f32>::normal` is `Ok` but 1.4 % short of unit
/// length (`(0, 0, -0.98611695)`) for a flat, tiny net: valence 11, center 0,
/// every node `(0.0009648437, -2^-18, 0)`, after 3 steps. The tangents are
/// about 1e-10, so the components of `t1 × t2` square into the f32 subnormal
/// range and `|t1 × t2|` loses precision (e5b66d1 made a *subnormal* `|t1 × t2|`
/// `Degenerate`; here the length itself is normal, its square is not).
/// Fixed: `normal` scales `t1 × t2` by its largest component before
/// normalizing. A second input (level 3, 88 % of unit length) is below.
#[test]
fn cc_normal_of_tiny_flat_net_is_unit() {
    let n = 11;
    let nodes = vec![[0.0009648437f32, -3.90625e-6, 0.0]; 6 * n];
    let mut storage = vec![Point3::<f32>::ZERO; CcCap::<f32>::storage_len(n)];
    let mut cap = CcCap::new([0.0; 3], &nodes, &mut storage).unwrap();
    for _ in 0..3 {
        cap.step().unwrap();
    }
    if let Ok(nrm) = cap.normal() {
        let len = nrm.norm();
        assert!((len - 1.0).abs() < 1e-3, "normal {nrm:?} has length {len}");
    }
}

/// `fuzz/kernel_eg_cc`, second input of the same finding: valence 11 (as
/// the campaign's 12-node prefix, repeated), center `-7.1402575e-17` in every
/// coordinate; normal was `(0, 0, 0.8838835)` after 3 steps.
#[test]
fn cc_normal_of_mixed_scale_net_is_unit() {
    let c = -7.1402575e-17f32;
    let a = [0.0, -91.59375, c];
    let b = [c; 3];
    let prefix = [a, b, b, a, b, b, a, a, b, b, a, b];
    // Under Miri valences 3, 7 and 11 (the finding's).
    for n in (3..=11).step_by(if cfg!(miri) { 4 } else { 1 }) {
        let nodes: Vec<[f32; 3]> = (0..6 * n).map(|i| prefix[i % 12]).collect();
        let mut storage = vec![Point3::<f32>::ZERO; CcCap::<f32>::storage_len(n)];
        let mut cap = CcCap::new([c; 3], &nodes, &mut storage).unwrap();
        for _ in 0..3 {
            if cap.step().is_err() {
                break;
            }
            if let Ok(nrm) = cap.normal() {
                let len = nrm.norm();
                assert!(
                    (len - 1.0).abs() < 1e-3,
                    "n = {n}: normal {nrm:?} has length {len}"
                );
            }
        }
    }
}
