//! The level-0 outer region (docs/math/c2ps.md §5): span count and C² contact with
//! the level-0 ring.

use capdiv::{OuterRegion, Point3, PolarNet};

fn config(links: usize, n: usize) -> Vec<Vec<[f64; 3]>> {
    (1..=links)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / n as f64;
                    let r = i as f64 + 0.1 * (j as f64 * 1.7).sin();
                    [
                        r * t.cos(),
                        r * t.sin(),
                        0.1 * r * r + 0.2 * (3.0 * t).cos(),
                    ]
                })
                .collect()
        })
        .collect()
}

/// K links (pole = link 0, so the spec's L = K + 1) give r ∈ [4, K−1]: K − 5 spans.
#[test]
fn outer_region_has_one_span_per_link_beyond_five() {
    for k in 2..=9 {
        let links = config(k, 7);
        let region = OuterRegion::new([0.0; 3], &links).unwrap();
        assert_eq!(region.spans(), k.saturating_sub(5), "K = {k}");
        assert_eq!(region.len(), region.spans() * 7);
        assert_eq!(region.patches().count(), region.len());
    }
}

/// The outermost span uses the last link: its outer boundary (u = 1) is the
/// uniform cubic B-spline of links K−2, K−1, K at the Greville point of K−1.
#[test]
fn outer_region_last_span_reaches_the_last_link() {
    let links = config(8, 6);
    let region = OuterRegion::new([0.0; 3], &links).unwrap();
    let last = region.patch(region.len() - 1).unwrap(); // span 2, column 5
    let b = |i: usize, j: usize| Point3(links[i][j % 6]);
    let expect = |j: usize| (b(5, j) + b(6, j) * 4.0 + b(7, j)) * (1.0 / 6.0);
    // Corner (u=1, v=0) of column 5: the B-spline's value at the Greville
    // point of link 7 and column 5, which combines columns 4, 5, 6.
    let corner = (expect(4) + expect(5) * 4.0 + expect(6)) * (1.0 / 6.0);
    assert!(last.points[3][0].max_abs_diff(corner) < 1e-14);
}

/// Value, first and second radial derivatives agree where the level-0 ring
/// (span 1, r ∈ [3, 4]) meets the outer region (span 0, r ∈ [4, 5]).
#[test]
fn outer_region_joins_level0_ring_c2() {
    let links = config(7, 5);
    let net: PolarNet<f64, 64> = PolarNet::new([0.0; 3], &links).unwrap();
    let region = OuterRegion::new([0.0; 3], &links).unwrap();
    for col in 0..5 {
        let inner = net.ring_patch(net.valence() + col).unwrap().points;
        let outer = region.patch(col).unwrap().points;
        for j in 0..4 {
            let (a0, a1, a2) = (inner[3][j], inner[2][j], inner[1][j]);
            let (b0, b1, b2) = (outer[0][j], outer[1][j], outer[2][j]);
            assert!(a0.max_abs_diff(b0) < 1e-14);
            assert!((a0 - a1).max_abs_diff(b1 - b0) < 1e-14);
            assert!((a0 - a1 * 2.0 + a2).max_abs_diff(b0 - b1 * 2.0 + b2) < 1e-14);
        }
    }
}
