//! Instruction-count probe for one C²PS step at valence 6·2^13 → 6·2^14
//! (run under `valgrind --tool=callgrind`; not part of the suite).
use capdiv::{FirstStep, PolarNet};
fn main() {
    std::thread::Builder::new()
        .stack_size(1 << 30)
        .spawn(|| {
            let links: Vec<Vec<[f64; 3]>> = (1..=5)
                .map(|i| {
                    (0..6)
                        .map(|j| {
                            let t = std::f64::consts::TAU * j as f64 / 6.0;
                            let r = i as f64;
                            [r * t.cos(), r * t.sin(), 0.2 * r * r]
                        })
                        .collect()
                })
                .collect();
            let mut net: Box<PolarNet<f64, { 6 << 14 }>> =
                Box::new(PolarNet::new([0.0; 3], &links).unwrap());
            for _ in 0..14 {
                net.step(FirstStep::Uniform).unwrap();
            }
            println!("{}", net.valence());
        })
        .unwrap()
        .join()
        .unwrap();
}
