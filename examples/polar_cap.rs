//! Build a polar configuration, refine it, read out the pole and the rings.
//!
//! `cargo run --example polar_cap`

use capdiv::{Error, FirstStep, PolarNet, PoleJet};

fn main() -> Result<(), Error> {
    // Valence 8, 5 links sampled from the paraboloid z = (x² + y²)/4.
    let n = 8;
    let links: Vec<Vec<[f64; 3]>> = (1..=5)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / n as f64;
                    let (x, y) = (i as f64 * t.cos(), i as f64 * t.sin());
                    [x, y, 0.25 * (x * x + y * y)]
                })
                .collect()
        })
        .collect();

    // Capacity 8·2^6: room for 6 steps. Everything lives in this value.
    let mut net: PolarNet<f64, 512> = PolarNet::new([0.0, 0.0, 0.0], &links)?;
    let mut patches = 0;
    for _ in 0..6 {
        patches += net.ring_patches().count();
        net.step(FirstStep::Uniform)?;
    }
    let jet = PoleJet::of(&net);
    let g = jet.geometry()?;
    println!("valence after 6 steps: {}", net.valence());
    println!("ring patches emitted:   {patches}");
    println!("limit point:            {:?}", jet.limit().0);
    println!("normal:                 {:?}", g.normal.0);
    println!("principal curvatures:   {:?}", g.principal);
    // One more step would need valence 1024 > 512: a typed error, net unchanged.
    println!("7th step:               {:?}", net.step(FirstStep::Uniform));
    Ok(())
}
