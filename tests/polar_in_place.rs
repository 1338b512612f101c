//! `PolarNet::empty` + `reset`: the in-place construction for statics and
//! small stacks gives the same net as `new`, and rejects bad input unchanged.

use capdiv::{Error, FirstStep, PolarNet, PoleJet};

fn links(n: usize, count: usize, bump: f64) -> Vec<Vec<[f64; 3]>> {
    (1..=count)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / n as f64;
                    let r = i as f64;
                    [
                        r * t.cos(),
                        r * t.sin(),
                        bump * r * r + 0.1 * (2.0 * t).sin(),
                    ]
                })
                .collect()
        })
        .collect()
}

#[test]
fn reset_equals_new_and_reuses_the_net() {
    let mut net: PolarNet<f64, 384> = PolarNet::empty();
    assert_eq!(net.valence(), 0);
    assert_eq!(net.link_count(), 0);
    // An empty net refuses to step; an RTS step on it does nothing.
    assert_eq!(
        net.step(FirstStep::Uniform),
        Err(Error::NotEnoughLinks {
            needed: 2,
            present: 0
        })
    );
    assert_eq!(net.rts_step(), Ok(()));
    assert_eq!(net.valence(), 0);
    assert_eq!(PoleJet::of(&net).geometry(), Err(Error::Degenerate));

    for (n, count, bump) in [(6, 5, 0.2), (5, 2, -0.3), (12, 3, 0.1)] {
        let l = links(n, count, bump);
        net.reset([0.0, 0.0, 0.05], &l).unwrap();
        let fresh: PolarNet<f64, 384> = PolarNet::new([0.0, 0.0, 0.05], &l).unwrap();
        for _ in 0..3 {
            net.step(FirstStep::Uniform).unwrap();
        }
        let mut fresh = fresh;
        for _ in 0..3 {
            fresh.step(FirstStep::Uniform).unwrap();
        }
        assert_eq!(net.valence(), n * 8);
        assert_eq!(net.level(), 3);
        assert_eq!(net.pole(), fresh.pole());
        for i in 1..=net.link_count() {
            assert_eq!(net.link(i), fresh.link(i));
        }
    }
}

#[test]
fn reset_with_bad_input_leaves_the_net_unchanged() {
    let mut net: PolarNet<f64, 64> = PolarNet::new([0.0; 3], &links(6, 5, 0.2)).unwrap();
    net.step(FirstStep::Plain).unwrap();
    let before = (
        net.pole(),
        net.link(1).unwrap().to_vec(),
        net.valence(),
        net.level(),
    );
    let mut bad = links(6, 3, 0.1);
    bad[1][2][0] = f64::NAN;
    assert_eq!(net.reset([0.0; 3], &bad), Err(Error::NonFinite));
    assert_eq!(
        net.reset([0.0; 3], &links(65, 2, 0.1)),
        Err(Error::CapacityExceeded {
            needed: 65,
            capacity: 64
        })
    );
    assert_eq!(
        net.reset_flat([0.0; 3], 6, &[0.0; 17]),
        Err(Error::WrongLength {
            expected: 18,
            found: 17
        })
    );
    let after = (
        net.pole(),
        net.link(1).unwrap().to_vec(),
        net.valence(),
        net.level(),
    );
    assert_eq!(before, after);
}
