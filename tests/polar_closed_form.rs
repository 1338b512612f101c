//! docs/math/c2ps.md §4, eq. (30): after m plain C²PS steps the pole is
//! `p0 − μ^m/3 p3` and link 1 its closed form in p0..p5, to round-off.

use capdiv::{FirstStep, Point3, PolarNet, PoleJet};

#[test]
fn pole_and_link1_match_eq30_closed_forms_for_8_levels() {
    let n = 5usize;
    let mut links = vec![];
    for i in 1..=5 {
        let l: Vec<[f64; 3]> = (0..n)
            .map(|j| {
                let t = std::f64::consts::TAU * j as f64 / n as f64;
                let r = i as f64;
                [
                    r * t.cos() + 0.1 * (j as f64).sin(),
                    r * t.sin(),
                    0.3 * r * r + 0.05 * j as f64,
                ]
            })
            .collect();
        links.push(l);
    }
    let mut net: PolarNet<f64, 1280> = PolarNet::new([0.0, 0.1, 0.0], &links).unwrap();
    let jet0 = PoleJet::of(&net);
    for m in 1..=8u32 {
        net.step(FirstStep::Plain).unwrap();
        let nn = net.valence();
        let lam = 0.5f64.powi(m as i32);
        let mu = 0.25f64.powi(m as i32);
        let p = jet0.p;
        let q00 = p[0] - p[3] * (mu / 3.0);
        assert!(net.pole().max_abs_diff(q00) < 1e-12, "pole m={m}");
        for j in 0..nn {
            let t = std::f64::consts::TAU * j as f64 / nn as f64;
            let e = p[0]
                + (p[1] * t.cos() + p[2] * t.sin()) * lam
                + (p[3] + p[4] * (2.0 * t).cos() + p[5] * (2.0 * t).sin()) * (2.0 / 3.0 * mu);
            let got: Point3<f64> = net.link(1).unwrap()[j];
            assert!(got.max_abs_diff(e) < 1e-12, "m={m} j={j} {:?} {:?}", got, e);
        }
    }
}
