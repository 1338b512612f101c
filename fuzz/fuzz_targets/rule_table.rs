//! Rule-table files (`--table FILE`, `--eg-table N=FILE`) through the CLI's
//! parser (`table::Table::parse`) and the kernel's `RuleTable::new`
//! (`Table::rule`); an accepted table then drives an EG subdivision of a
//! c-net of its valence (2 steps, rings).
//!
//! Oracle: no panic; failures are `CliError`s; an accepted table gives finite
//! steps and ring patches on a unit-size net.
#![no_main]

use capdiv::{CNet, EgSubdivision};
use capdiv_cli::table::Table;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(table) = Table::parse("fuzz-table.json", text) else {
        return;
    };
    let Ok(rule) = table.rule() else { return };
    let n = rule.valence();
    assert_eq!(n, table.valence);
    // A c-net of valence n on a paraboloid.
    let mut nodes = Vec::new();
    for s in 0..n {
        let (a, b) = (
            2.0 * std::f64::consts::PI * s as f64 / n as f64,
            2.0 * std::f64::consts::PI * (s + 1) as f64 / n as f64,
        );
        for (x, y) in [
            (1.0, 0.0),
            (2.0, 0.0),
            (1.0, 1.0),
            (2.0, 1.0),
            (1.0, 2.0),
            (2.0, 2.0),
        ] {
            let px = 0.5 * (x * a.cos() + y * b.cos());
            let py = 0.5 * (x * a.sin() + y * b.sin());
            nodes.push([px, py, 0.5 * (px * px + py * py)]);
        }
    }
    let cnet = CNet::<f64>::new([0.0; 3], &nodes).expect("valid c-net");
    let mut eg =
        EgSubdivision::new(&cnet.to_dnet(), Some(rule)).expect("table of the net's valence");
    for _ in 0..2 {
        eg.step().expect("a checked table refines a unit net");
        assert_eq!(eg.ring_patches().count(), 3 * n);
        for p in eg.ring_patches() {
            assert!(p.points.iter().flatten().all(|q| q.is_finite()));
        }
    }
});
