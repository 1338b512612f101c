//! `capdiv refine` on EG inputs (docs/math/eg.md §1–§6): the output is the `dnet`
//! schema and a valid input again (round trip), steps compose through the
//! printed output, and the numbers are the kernel's, bit for bit.

mod common;

use capdiv::{CNet, DNet, EgSubdivision};
use common::*;

/// The kernel's level-`m` d-net of a c-net, in `R`.
fn kernel_cnet<R: capdiv::Real>(
    center: [f64; 3],
    sectors: &[[[f64; 3]; 6]],
    m: u32,
) -> ([R; 3], Vec<[[R; 3]; 12]>) {
    let cast = |p: [f64; 3]| p.map(R::from_f64);
    let sectors: Vec<[[R; 3]; 6]> = sectors.iter().map(|s| s.map(cast)).collect();
    let net = CNet::from_sectors(cast(center), &sectors).unwrap();
    let mut eg = EgSubdivision::new(&net, None).unwrap();
    for _ in 0..m {
        eg.step().unwrap();
    }
    dump(eg.net())
}

fn dump<R: capdiv::Real>(net: &DNet<R>) -> ([R; 3], Vec<[[R; 3]; 12]>) {
    (
        net.c0().0,
        net.sectors().iter().map(|s| s.map(|p| p.0)).collect(),
    )
}

#[test]
fn output_is_the_dnet_schema_of_the_same_valence_and_reads_back_exactly() {
    let dir = tempdir();
    for n in [3, 4, 5] {
        let (center, sectors) = cnet(n, n as u64);
        let file = write_json(dir.path(), "in.json", &cnet_json(center, &sectors));
        for m in 0..=3u32 {
            let steps = m.to_string();
            let run = capdiv(&["refine", "--steps", &steps, s(&file)], None);
            let (_, got) = parse_dnet(&run.ok_json());
            assert_eq!(got.len(), n, "EG keeps the valence, n={n} m={m}");
            // The printed d-net is an input; 0 steps of it print it again,
            // byte for byte (c0 given, numbers shortest-round-trip).
            let back = capdiv(&["refine", "--steps", "0", "-"], Some(&run.stdout));
            back.assert_ok();
            assert_eq!(back.stdout, run.stdout, "round trip n={n} m={m}");
            // --scheme eg explicitly is the same as the default for a cnet.
            let explicit = capdiv(
                &["refine", "--scheme", "eg", "--steps", &steps, s(&file)],
                None,
            );
            assert_eq!(explicit.stdout, run.stdout);
        }
    }
}

#[test]
fn steps_compose_through_the_printed_output() {
    let dir = tempdir();
    for n in [3, 5] {
        let (center, sectors) = cnet(n, 10 + n as u64);
        let file = write_json(dir.path(), "in.json", &cnet_json(center, &sectors));
        let two = capdiv(&["refine", "--steps", "2", s(&file)], None);
        let one = capdiv(&["refine", "--steps", "1", s(&file)], None);
        let one_one = capdiv(&["refine", "--steps", "1", "-"], Some(&one.stdout));
        one_one.assert_ok();
        assert_eq!(one_one.stdout, two.stdout, "n={n}");
    }
}

#[test]
fn f64_output_equals_the_kernel_bit_for_bit() {
    let dir = tempdir();
    for (n, seed) in [(3, 1), (4, 2), (5, 3)] {
        let (center, sectors) = cnet(n, seed);
        let file = write_json(dir.path(), "in.json", &cnet_json(center, &sectors));
        for m in [0u32, 1, 4] {
            let steps = m.to_string();
            let out = capdiv(&["refine", "--steps", &steps, s(&file)], None).ok_json();
            let got = parse_dnet(&out);
            assert_eq!(got, kernel_cnet::<f64>(center, &sectors, m), "n={n} m={m}");
        }
    }
}

#[test]
fn dnet_inputs_equal_the_kernel_with_and_without_c0() {
    let dir = tempdir();
    for (n, seed) in [(3, 4), (5, 5)] {
        // A d-net not raised from any c-net: random nodes.
        let mut rng = Lcg::new(seed);
        let sectors: Vec<[[f64; 3]; 12]> = (0..n)
            .map(|_| std::array::from_fn(|_| [rng.next(), rng.next(), rng.next()]))
            .collect();
        let c0 = [0.25, -0.5, 0.125];
        for given in [Some(c0), None] {
            let file = write_json(dir.path(), "d.json", &dnet_json(&sectors, given));
            let out = capdiv(&["refine", "--steps", "3", s(&file)], None).ok_json();
            let mut eg =
                EgSubdivision::new(&DNet::from_sectors(&sectors, given).unwrap(), None).unwrap();
            for _ in 0..3 {
                eg.step().unwrap();
            }
            assert_eq!(parse_dnet(&out), dump(eg.net()), "n={n} c0 {given:?}");
            if let Some(c0) = given {
                assert_eq!(parse_dnet(&out).0, c0, "c0 is kept (§4)");
            }
        }
    }
}

#[test]
fn f32_output_equals_the_kernel_in_f32() {
    let dir = tempdir();
    let (center, sectors) = cnet(5, 7);
    let file = write_json(dir.path(), "in.json", &cnet_json(center, &sectors));
    let out = capdiv(
        &["refine", "--precision", "f32", "--steps", "3", s(&file)],
        None,
    )
    .ok_json();
    let (c0, got) = parse_dnet(&out);
    // f32 printed shortest-round-trip, read back as f64 and rounded to f32.
    let as32 = |p: [f64; 3]| p.map(|c| c as f32);
    let got = (
        as32(c0),
        got.iter().map(|s| s.map(as32)).collect::<Vec<_>>(),
    );
    assert_eq!(got, kernel_cnet::<f32>(center, &sectors, 3));
}

#[test]
fn valence_4_refines_with_the_regular_rules() {
    // n = 4 is regular (§7): the kernel refines every node with §5's rules.
    // A c-net sampled from a plane z = ax + by + c is refined to nodes on
    // that plane (bi-4 refinement reproduces linear functions).
    let dir = tempdir();
    let (center, mut sectors) = cnet(4, 9);
    let plane = |p: [f64; 3]| 0.3 * p[0] - 0.2 * p[1] + 1.0;
    for p in sectors.iter_mut().flatten() {
        p[2] = plane(*p);
    }
    let center = [center[0], center[1], plane(center)];
    let file = write_json(dir.path(), "in.json", &cnet_json(center, &sectors));
    let out = capdiv(&["refine", "--steps", "3", s(&file)], None).ok_json();
    let (c0, got) = parse_dnet(&out);
    assert_eq!(got.len(), 4);
    for p in got.iter().flatten().chain(std::iter::once(&c0)) {
        assert!((p[2] - plane(*p)).abs() < 1e-14, "{p:?} off the plane");
    }
    assert_eq!(
        (c0, got),
        kernel_cnet::<f64>(center, &sectors, 3),
        "bit for bit"
    );
}
