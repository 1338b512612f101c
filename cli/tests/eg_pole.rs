//! `capdiv pole` on EG inputs: `{"limit"}` = `c0` (docs/math/eg.md §4), against
//! formulas (3) and (4) with the reference crate's weights (`capdiv_reference::eg`),
//! independent of the kernel; the limit is the same at every level.

mod common;

use capdiv_reference::eg;
use common::*;
use serde_json::Value;

fn limit_of(args: &[&str], stdin: Option<&[u8]>) -> [f64; 3] {
    let out = capdiv(args, stdin).ok_json();
    let keys: Vec<&String> = out.as_object().unwrap().keys().collect();
    assert_eq!(keys, ["limit"], "EG pole prints only the limit");
    p3(&out["limit"])
}

/// Formula (3) of docs/math/eg.md §4, by the reference crate's weights.
fn formula_3(center: [f64; 3], sectors: &[[[f64; 3]; 6]]) -> [f64; 3] {
    let n = sectors.len();
    let w = eg::c0_from_cnet_weights(n);
    // The §1 order of a sector's nodes.
    const ORDER: [(i64, i64); 6] = [(1, 0), (2, 0), (1, 1), (2, 1), (1, 2), (2, 2)];
    let mut c = center.map(|x| w[eg::c_index(n, 0, 0, 0)] * x);
    for (s, sector) in sectors.iter().enumerate() {
        for (p, &(x, y)) in sector.iter().zip(&ORDER) {
            let wk = w[eg::c_index(n, s as isize, x, y)];
            for k in 0..3 {
                c[k] += wk * p[k];
            }
        }
    }
    c
}

/// Formula (4) of docs/math/eg.md §4 (with the corrected e32), by the
/// reference crate's weights.
fn formula_4(sectors: &[[[f64; 3]; 12]]) -> [f64; 3] {
    let w = eg::c0_from_dnet_weights(sectors.len());
    let mut c = [0.0; 3];
    for (s, sector) in sectors.iter().enumerate() {
        // The §2 order 00 10 20 30 01 11 21 31 02 12 22 32: node i + 4j.
        for (ij, p) in sector.iter().enumerate() {
            let wk = w[eg::d_index(s, ij % 4, ij / 4)];
            for k in 0..3 {
                c[k] += wk * p[k];
            }
        }
    }
    c
}

fn cnet_scale(center: [f64; 3], sectors: &[[[f64; 3]; 6]]) -> f64 {
    sectors
        .iter()
        .flatten()
        .chain(std::iter::once(&center))
        .flatten()
        .fold(0.0f64, |m, c| m.max(c.abs()))
}

#[test]
fn cnet_limit_is_formula_3() {
    let dir = tempdir();
    for n in 3..=10 {
        let (center, sectors) = cnet(n, 100 + n as u64);
        let file = write_json(dir.path(), "c.json", &cnet_json(center, &sectors));
        let got = limit_of(&["pole", s(&file)], None);
        let want = formula_3(center, &sectors);
        // Weights sum to 1; the kernel sums e + Σ w (c − e): a few ulps of
        // the net's size apart.
        let tol = 1e-14 * cnet_scale(center, &sectors);
        assert!(diff(&got, &want) <= tol, "n={n}: {got:?} vs {want:?}");
    }
}

#[test]
fn dnet_limit_is_its_c0_or_formula_4() {
    let dir = tempdir();
    for n in 3..=10 {
        let mut rng = Lcg::new(200 + n as u64);
        let sectors: Vec<[[f64; 3]; 12]> = (0..n)
            .map(|_| std::array::from_fn(|_| [rng.next(), rng.next(), rng.next()]))
            .collect();
        let given = [0.5, -0.25, 3.0];
        let file = write_json(dir.path(), "d.json", &dnet_json(&sectors, Some(given)));
        assert_eq!(limit_of(&["pole", s(&file)], None), given, "n={n}");
        let file = write_json(dir.path(), "d.json", &dnet_json(&sectors, None));
        let got = limit_of(&["pole", s(&file)], None);
        let want = formula_4(&sectors);
        // |e_ij|/γ ≤ 0.2 (n ≥ 3), 12n terms of size ≤ 1: well under 1e-13.
        assert!(diff(&got, &want) <= 1e-13, "n={n}: {got:?} vs {want:?}");
    }
}

#[test]
fn formula_4_of_the_raised_cnet_is_formula_3() {
    // §4: (4)(R c) = (3)(c). `refine --steps 0` prints the raised d-net R c;
    // without its c0, pole fits c0 by (4).
    let dir = tempdir();
    for n in 3..=10 {
        let (center, sectors) = cnet(n, 300 + n as u64);
        let file = write_json(dir.path(), "c.json", &cnet_json(center, &sectors));
        let raised = capdiv(&["refine", "--steps", "0", s(&file)], None).ok_json();
        let mut d: Value = raised.clone();
        d.as_object_mut().unwrap().remove("c0");
        let text = serde_json::to_vec(&d).unwrap();
        let got = limit_of(&["pole", "-"], Some(&text));
        let want = formula_3(center, &sectors);
        let tol = 1e-12 * cnet_scale(center, &sectors);
        assert!(diff(&got, &want) <= tol, "n={n}: {got:?} vs {want:?}");
    }
}

#[test]
fn the_limit_is_the_same_at_every_level() {
    let dir = tempdir();
    for n in [3, 4, 5] {
        let (center, sectors) = cnet(n, 400 + n as u64);
        let file = write_json(dir.path(), "c.json", &cnet_json(center, &sectors));
        let level0 = limit_of(&["pole", s(&file)], None);
        for m in ["1", "5"] {
            let refined = capdiv(&["refine", "--steps", m, s(&file)], None);
            refined.assert_ok();
            let got = limit_of(&["pole", "-"], Some(&refined.stdout));
            assert_eq!(got, level0, "n={n} after {m} steps: c0 is fixed (§4)");
        }
    }
}

#[test]
fn f32_limit_is_formula_3_in_f32_precision() {
    let dir = tempdir();
    let (center, sectors) = cnet(5, 7);
    let file = write_json(dir.path(), "c.json", &cnet_json(center, &sectors));
    let got = limit_of(&["pole", "--precision", "f32", s(&file)], None);
    let want = formula_3(center, &sectors);
    // Rounding the input to f32 and 31 f32 operations: ~2^-24 relative each.
    let tol = 32.0 * f32::EPSILON as f64 * cnet_scale(center, &sectors);
    assert!(diff(&got, &want) <= tol, "{got:?} vs {want:?}");
}
