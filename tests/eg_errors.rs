//! Every bad input to the EG kernel maps to its typed error, and nothing the
//! caller owns (or the subdivision state) changes.

mod eg_support;

use capdiv::eg::tables::{A11_3, A11_5, A21_3, A21_5, A22_3, A22_5, A31_3, A31_5, A32_3, A32_5};
use capdiv::eg::{CNet, DNet, EgSubdivision, RuleTable};
use capdiv::Error;
use eg_support::{ExtNet, Rng};

fn cnet_nodes(n: usize) -> ([f64; 3], Vec<[f64; 3]>) {
    let mut rng = Rng(4242 + n as u64);
    let e = ExtNet::random(n, &mut rng, 0.3);
    (e.center, e.cnet_nodes())
}

#[test]
fn cnet_errors() {
    let (e, nodes) = cnet_nodes(5);
    let keep = nodes.clone();
    // Not a multiple of 6.
    assert_eq!(
        CNet::new(e, &nodes[..29]).unwrap_err(),
        Error::WrongLength {
            expected: 30,
            found: 29
        }
    );
    // Valence 2 and 11.
    assert_eq!(
        CNet::new(e, &nodes[..12]).unwrap_err(),
        Error::ValenceTooSmall { valence: 2 }
    );
    assert_eq!(
        CNet::<f64>::new(e, &[]).unwrap_err(),
        Error::ValenceTooSmall { valence: 0 }
    );
    let big: Vec<[f64; 3]> = (0..66).map(|k| [k as f64, 0.0, 1.0]).collect();
    assert_eq!(
        CNet::new(e, &big).unwrap_err(),
        Error::ValenceUnsupported { valence: 11 }
    );
    // Non-finite anywhere.
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut v = nodes.clone();
        v[17][1] = bad;
        assert_eq!(CNet::new(e, &v).unwrap_err(), Error::NonFinite);
        assert_eq!(
            CNet::new([0.0, bad, 0.0], &nodes).unwrap_err(),
            Error::NonFinite
        );
    }
    assert_eq!(nodes, keep);
    // Flat coordinates: same net, or WrongLength when not whole triples.
    let coords: Vec<f64> = nodes.iter().flatten().copied().collect();
    assert_eq!(
        CNet::from_flat(e, &coords).unwrap(),
        CNet::new(e, &nodes).unwrap()
    );
    // Counted in coordinates, like PolarNet::from_flat: 18 per sector.
    assert_eq!(
        CNet::from_flat(e, &coords[..89]).unwrap_err(),
        Error::WrongLength {
            expected: 90,
            found: 89
        }
    );
    assert_eq!(
        CNet::from_flat(e, &coords[..87]).unwrap_err(),
        Error::WrongLength {
            expected: 90,
            found: 87
        }
    );
    assert_eq!(
        CNet::from_flat(e, &coords[..36]).unwrap_err(),
        Error::ValenceTooSmall { valence: 2 }
    );
    // Finite c-net whose raised d-net overflows: rejected when the cap starts.
    let mut far = nodes.clone();
    far.iter_mut().for_each(|p| p[0] = 1.5e308);
    let c = CNet::new([-1.5e308, 0.0, 0.0], &far).unwrap();
    assert!(!c.to_dnet().is_finite());
    assert_eq!(EgSubdivision::new(&c, None).unwrap_err(), Error::NonFinite);
    // n = 4 cap only for n = 4.
    let c5 = CNet::new(e, &nodes).unwrap();
    assert_eq!(
        c5.regular_cap().unwrap_err(),
        Error::ValenceUnsupported { valence: 5 }
    );
}

#[test]
fn dnet_errors() {
    let (e, nodes) = cnet_nodes(3);
    let d = CNet::new(e, &nodes).unwrap().to_dnet();
    let flat: Vec<[f64; 3]> = d.sectors().iter().flatten().map(|p| p.0).collect();
    let keep = flat.clone();
    assert_eq!(
        DNet::new(&flat[..35], None).unwrap_err(),
        Error::WrongLength {
            expected: 36,
            found: 35
        }
    );
    assert_eq!(
        DNet::new(&flat[..24], None).unwrap_err(),
        Error::ValenceTooSmall { valence: 2 }
    );
    let big = vec![[0.5f64; 3]; 132];
    assert_eq!(
        DNet::new(&big, None).unwrap_err(),
        Error::ValenceUnsupported { valence: 11 }
    );
    let mut v = flat.clone();
    v[35][2] = f64::NAN;
    assert_eq!(DNet::new(&v, None).unwrap_err(), Error::NonFinite);
    assert_eq!(
        DNet::new(&flat, Some([f64::INFINITY, 0.0, 0.0])).unwrap_err(),
        Error::NonFinite
    );
    let coords: Vec<f64> = flat.iter().flatten().copied().collect();
    assert_eq!(
        DNet::from_flat(&coords, None).unwrap(),
        DNet::new(&flat, None).unwrap()
    );
    assert_eq!(
        DNet::from_flat(&coords[..100], None).unwrap_err(),
        Error::WrongLength {
            expected: 108,
            found: 100
        }
    );
    // Finite nodes whose (4) sum overflows.
    let huge = vec![[1e308f64, -1e308, 1e308]; 36];
    let mut h2 = huge.clone();
    h2[0] = [-1e308, 1e308, -1e308];
    assert_eq!(DNet::new(&h2, None).unwrap_err(), Error::NonFinite);
    assert_eq!(flat, keep);
}

#[test]
fn valences_without_rules_are_unsupported() {
    for n in 6..=10 {
        let d = DNet::new(&vec![[0.25f64, 0.5, 1.0]; 12 * n], None).unwrap();
        assert_eq!(
            EgSubdivision::new(&d, None).unwrap_err(),
            Error::ValenceUnsupported { valence: n }
        );
        assert_eq!(
            d.refined(None).unwrap_err(),
            Error::ValenceUnsupported { valence: n }
        );
        assert!(RuleTable::builtin(n).is_none());
    }
    assert!(RuleTable::builtin(4).is_none());
    assert!(EgSubdivision::new(&DNet::new(&vec![[0.0f64; 3]; 48], None).unwrap(), None).is_ok());
}

#[test]
fn step_overflow_leaves_state_untouched() {
    // Finite nodes 1.5e308 with c0 = −1.5e308: d − c0 overflows to ∞.
    let nodes = vec![[1.5e308f64, 0.0, 1.0]; 36];
    let d = DNet::new(&nodes, Some([-1.5e308, 0.0, 1.0])).unwrap();
    let mut sub = EgSubdivision::new(&d, None).unwrap();
    let before = sub.net().clone();
    assert_eq!(sub.step().unwrap_err(), Error::NonFinite);
    assert_eq!(sub.net(), &before);
    assert_eq!(sub.level(), 0);
    assert_eq!(sub.ring_len(), 0);
    assert_eq!(d.refined(None).unwrap_err(), Error::NonFinite);
}

#[test]
fn ring_index_errors() {
    let (e, nodes) = cnet_nodes(5);
    let mut sub = EgSubdivision::new(&CNet::new(e, &nodes).unwrap(), None).unwrap();
    assert_eq!(sub.ring_patch(0).unwrap_err(), Error::OutOfDomain);
    assert_eq!(sub.ring_patch_domain(0).unwrap_err(), Error::OutOfDomain);
    assert_eq!(sub.ring_patches().count(), 0);
    sub.step().unwrap();
    assert_eq!(sub.ring_len(), 15);
    assert!(sub.ring_patch(14).is_ok());
    assert_eq!(sub.ring_patch(15).unwrap_err(), Error::OutOfDomain);
    assert_eq!(sub.ring_patch_domain(15).unwrap_err(), Error::OutOfDomain);
    assert_eq!(sub.ring_patches().len(), 15);
}

type Rows = Vec<[i32; 12]>;

fn table5() -> [Rows; 5] {
    [
        A11_5.to_vec(),
        A22_5.to_vec(),
        A21_5.to_vec(),
        A31_5.to_vec(),
        A32_5.to_vec(),
    ]
}

fn check(n: usize, t: &[Rows; 5]) -> Result<(), Error> {
    RuleTable::new(n, &t[0], &t[1], &t[2], &t[3], &t[4]).map(|_| ())
}

#[test]
#[cfg_attr(
    miri,
    ignore = "RuleTable::new's spectral check runs 96 EG steps (minutes under Miri per table)"
)]
fn user_table_shape() {
    let good = table5();
    assert_eq!(check(5, &good), Ok(()));
    let t3 = [
        A11_3.to_vec(),
        A22_3.to_vec(),
        A21_3.to_vec(),
        A31_3.to_vec(),
        A32_3.to_vec(),
    ];
    assert_eq!(check(3, &t3), Ok(()));
    // Wrong valence for the rows, or valence 4 (no EG rule), or out of range.
    assert_eq!(check(7, &good), Err(Error::TableShape));
    assert_eq!(check(4, &good), Err(Error::TableShape));
    assert_eq!(check(2, &good), Err(Error::ValenceTooSmall { valence: 2 }));
    assert_eq!(
        check(11, &good),
        Err(Error::ValenceUnsupported { valence: 11 })
    );
    // One row missing / one too many in each array.
    for k in 0..5 {
        let mut t = good.clone();
        t[k].pop();
        assert_eq!(check(5, &t), Err(Error::TableShape), "array {k} short");
        let mut t = good.clone();
        let last = *t[k].last().unwrap();
        t[k].push(last);
        assert_eq!(check(5, &t), Err(Error::TableShape), "array {k} long");
    }
    // An entry of absolute value ≥ 10⁵ (weights are fractions below 1).
    let mut t = good.clone();
    t[2][4][0] = 100_000;
    assert_eq!(check(5, &t), Err(Error::TableShape));
    // The paper's appendix keeps one row per array for n = 6 (docs/math/eg.md §7).
    let one: Rows = vec![[
        195, -490, 623, -140, -490, 4810, 4137, 3117, 623, 4137, 63933, 7100,
    ]];
    assert_eq!(
        check(
            6,
            &[one.clone(), one.clone(), one.clone(), one.clone(), one]
        ),
        Err(Error::TableShape)
    );
}

#[test]
#[cfg_attr(
    miri,
    ignore = "RuleTable::new's spectral check runs 96 EG steps (minutes under Miri per table)"
)]
fn user_table_symmetry() {
    let good = table5();
    // A11 row 0: a_10 must equal a_01 (column 1 vs 4).
    let mut t = good.clone();
    t[0][0][1] += 1;
    assert_eq!(check(5, &t), Err(Error::TableSymmetry));
    // A22 row 0: a_21 = a_12 (column 6 vs 9).
    let mut t = good.clone();
    t[1][0][9] += 1;
    assert_eq!(check(5, &t), Err(Error::TableSymmetry));
    // n = 3, A11 row 1: the spoke columns map to row −2 = 1 itself, the
    // others to row 2 (not listed): a change there is no symmetry error.
    let t3 = [
        A11_3.to_vec(),
        A22_3.to_vec(),
        A21_3.to_vec(),
        A31_3.to_vec(),
        A32_3.to_vec(),
    ];
    let mut t = t3.clone();
    t[0][1][7] += 1;
    assert_ne!(check(3, &t), Err(Error::TableSymmetry));
    // n = 3, A32 rows 1 and 2 share the spoke columns: a_3j^1 = a_3j^{−1} = a_3j^2.
    let mut t = t3.clone();
    t[4][2][7] += 1;
    assert_eq!(check(3, &t), Err(Error::TableSymmetry));
    // A31 rows 0 and 1 mirror each other: a_ij^0 = a_ji^1.
    let mut t = good.clone();
    t[3][1][4] -= 1;
    assert_eq!(check(5, &t), Err(Error::TableSymmetry));
    // A32 rows 2 and 3 share the spoke columns: a_3j^2 = a_3j^{−2} = a_3j^3.
    let mut t = good.clone();
    t[4][3][11] += 7;
    assert_eq!(check(5, &t), Err(Error::TableSymmetry));
    // A21 has no self-symmetry: a consistent small change is no symmetry error.
    let mut t = good.clone();
    t[2][0][0] += 1;
    assert_ne!(check(5, &t), Err(Error::TableSymmetry));
}

fn scaled(rows: &[[i32; 12]], f: f64) -> Rows {
    rows.iter()
        .map(|r| r.map(|a| (a as f64 * f).round() as i32))
        .collect()
}

#[test]
#[cfg_attr(
    miri,
    ignore = "RuleTable::new's spectral check runs 96 EG steps (minutes under Miri per table)"
)]
fn user_table_row_sum_and_spectrum() {
    let good = table5();
    // A22 scaled by 1.9: shape and symmetry intact, but the c0 weights a0 of
    // d̃₂₂ drop from 0.535 to 0.117 and the net no longer contracts to c0.
    let mut t = good.clone();
    t[1] = scaled(&A22_5, 1.9);
    assert_eq!(check(5, &t), Err(Error::TableRowSum));
    // A21 scaled by 1.01: still contracting, but λ moves more than 1e-3 away
    // from Catmull-Clark's (§8).
    let mut t = good.clone();
    t[2] = scaled(&A21_5, 1.01);
    assert_eq!(check(5, &t), Err(Error::TableSpectrum));
    // All zero: every inner node becomes c0 — ρ is then far below λ_CC.
    let zero = |k: usize| vec![[0i32; 12]; good[k].len()];
    let t = [zero(0), zero(1), zero(2), zero(3), zero(4)];
    assert_eq!(check(5, &t), Err(Error::TableSpectrum));
}

#[test]
fn table_valence_must_match_net() {
    let d = DNet::new(&vec![[0.0f64; 3]; 60], None).unwrap();
    let t3 = RuleTable::builtin(3).unwrap();
    assert_eq!(
        EgSubdivision::new(&d, Some(t3)).unwrap_err(),
        Error::TableShape
    );
    assert_eq!(d.refined(Some(&t3)).unwrap_err(), Error::TableShape);
}

#[test]
fn errors_display() {
    for e in [
        Error::TableShape,
        Error::TableSymmetry,
        Error::TableRowSum,
        Error::TableSpectrum,
    ] {
        assert!(!e.to_string().is_empty());
    }
}
