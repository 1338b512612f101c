//! The compile-time root table and the root ring against the host's `f64`
//! `cos`/`sin` (docs/math/c2ps.md §2 angles `c(j/N)`, `s(j/N)`).

use capdiv::trig::{primitive_root, RootsOfUnity, MAX_ODD_PART, ODD_ROOTS};
use std::f64::consts::TAU;

/// The const-evaluated table is within 4 ulp-of-1 of `f64::cos`/`sin`.
#[test]
fn odd_root_table_matches_std() {
    for (i, &(c, s)) in ODD_ROOTS.iter().enumerate() {
        let o = 2 * i + 1;
        let t = TAU / o as f64;
        assert!(
            (c - t.cos()).abs() <= 4e-16,
            "cos 2pi/{o}: {c} vs {}",
            t.cos()
        );
        assert!(
            (s - t.sin()).abs() <= 4e-16,
            "sin 2pi/{o}: {s} vs {}",
            t.sin()
        );
    }
    assert_eq!(ODD_ROOTS.len(), MAX_ODD_PART / 2 + 1);
}

/// Half-angle steps keep the primitive root within a few ulp for deep levels.
#[test]
fn primitive_roots_of_all_supported_valences() {
    // Under Miri every 37th valence (supported and unsupported ones).
    for n in (3..=4096usize).step_by(if cfg!(miri) { 37 } else { 1 }) {
        let odd = n >> n.trailing_zeros();
        match primitive_root(n) {
            Some((c, s)) => {
                assert!(odd <= MAX_ODD_PART);
                let t = TAU / n as f64;
                assert!((c - t.cos()).abs() <= 1e-15, "n={n}");
                assert!((s - t.sin()).abs() <= 1e-15, "n={n}");
            }
            None => assert!(odd > MAX_ODD_PART, "n={n} should be supported"),
        }
    }
    assert_eq!(primitive_root(2), None);
    assert_eq!(primitive_root(129), None);
}

/// Every entry of the ring after construction and after doublings.
/// The error grows by about one rounding per level plus the odd part's chain
/// (at most 63 products), so 64 ulp-of-1 (1.4e-14) bounds it in f64.
#[test]
fn root_ring_entries_match_std_f64() {
    // Under Miri four valences, levels 0..=3.
    let (valences, levels): (&[usize], usize) = if cfg!(miri) {
        (&[3, 5, 12, 127], 3)
    } else {
        (&[3, 4, 5, 6, 7, 12, 17, 48, 64, 127], 8)
    };
    for &n0 in valences {
        let mut ring: RootsOfUnity<f64, { 127 * 256 }> = RootsOfUnity::new(n0).unwrap();
        for _level in 0..=levels {
            let n = ring.len();
            if n > 127 * 128 {
                break;
            }
            for (j, &[c, s]) in ring.as_slice().iter().enumerate() {
                let t = TAU * j as f64 / n as f64;
                assert!((c - t.cos()).abs() <= 64.0 * f64::EPSILON, "n={n} j={j}");
                assert!((s - t.sin()).abs() <= 64.0 * f64::EPSILON, "n={n} j={j}");
            }
            ring.double().unwrap();
        }
    }
}

/// The f32 ring stays within 8 f32-ulps-of-1 (9.5e-7) of the exact roots at depth 8.
#[test]
fn root_ring_entries_f32() {
    let mut worst = 0.0f64;
    for n0 in [3usize, 5, 6, 64] {
        let mut ring: RootsOfUnity<f32, { 64 * 256 }> = RootsOfUnity::new(n0).unwrap();
        // Under Miri depth 3 (the error grows with the depth: the bound holds a
        // fortiori).
        for _ in 0..if cfg!(miri) { 3 } else { 8 } {
            ring.double().unwrap();
        }
        let n = ring.len();
        for (j, &[c, s]) in ring.as_slice().iter().enumerate() {
            let t = TAU * j as f64 / n as f64;
            worst = worst
                .max((c as f64 - t.cos()).abs())
                .max((s as f64 - t.sin()).abs());
        }
    }
    assert!(worst <= 8.0 * f32::EPSILON as f64, "worst {worst}");
}

#[test]
fn root_ring_rejects_bad_valences_and_keeps_state() {
    assert!(RootsOfUnity::<f64, 64>::new(2).is_err());
    assert!(RootsOfUnity::<f64, 64>::new(65).is_err());
    assert!(RootsOfUnity::<f64, 1024>::new(131).is_err());
    let mut ring: RootsOfUnity<f64, 12> = RootsOfUnity::new(6).unwrap();
    ring.double().unwrap();
    let before = ring.as_slice().to_vec();
    assert!(ring.double().is_err());
    assert_eq!(ring.as_slice(), &before[..]);
}
