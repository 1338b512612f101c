//! The WASM module under node: build `capi-wasm/` for
//! `wasm32-unknown-unknown`, run `capi-wasm/demo.mjs` (which instantiates it with no
//! imports, so a panic path left in the module fails here), and recompute
//! every case — C²PS refinement and pole jet, EG d-nets and rings — with the
//! native kernel: outputs, status codes and output counts must agree bit for
//! bit in f64.

use capdiv::eg::{CNet, EgSubdivision};
use capdiv::{Error, FirstStep, PolarNet, PoleJet};
use capdiv_embedded_tests::{cargo_in, repo_root, run_with_limit};
use std::process::Command;
use std::time::Duration;

#[path = "../../capi/src/codes.rs"]
#[allow(dead_code)]
mod codes;

/// The module's capacity per link (`capi-wasm/src/lib.rs`, checked against the
/// module's own `capdiv_capacity` through the demo's output sizes).
const CAP: usize = 1536;

fn bits(words: &[&str]) -> Vec<u64> {
    words
        .iter()
        .map(|w| u64::from_str_radix(w, 16).unwrap_or_else(|_| panic!("bad hex {w}")))
        .collect()
}

fn f64s(words: &[&str]) -> Vec<f64> {
    bits(words).into_iter().map(f64::from_bits).collect()
}

/// What the ABI must return for one case: (refine status, refine output,
/// jet status, jet output), computed natively.
fn native(
    pole: [f64; 3],
    coords: &[f64],
    valence: usize,
    steps: u32,
    plain: bool,
) -> (i32, Vec<f64>, i32, Vec<f64>) {
    let first = if plain {
        FirstStep::Plain
    } else {
        FirstStep::Uniform
    };
    let mut net = match PolarNet::<f64, CAP>::from_flat(pole, valence, coords) {
        Ok(net) => net,
        Err(e) => return (codes::code(&e), vec![], codes::code(&e), vec![]),
    };
    for _ in 0..steps {
        if let Err(e) = net.step(first) {
            return (codes::code(&e), vec![], codes::code(&e), vec![]);
        }
    }
    let (n, held) = (net.valence(), net.link_count());
    let mut out = vec![n as f64, held as f64];
    out.extend(net.pole().0);
    for i in 1..=held {
        out.extend(net.link(i).unwrap().iter().flat_map(|p| p.0));
    }
    let jet = PoleJet::of(&net);
    let mut j: Vec<f64> = jet.p.iter().flat_map(|p| p.0).collect();
    if let Ok(g) = jet.geometry() {
        j.extend(g.normal.0);
        j.extend([g.gaussian, g.mean, g.principal[0], g.principal[1]]);
    }
    (out.len() as i32, out, j.len() as i32, j)
}

/// What the EG calls must return: (refine status, output, ring status, output).
fn native_eg(center: [f64; 3], nodes: &[f64], steps: u32) -> (i32, Vec<f64>, i32, Vec<f64>) {
    let fail = |e: Error| (codes::code(&e), vec![], codes::code(&e), vec![]);
    let (points, rest) = nodes.as_chunks::<3>();
    if !rest.is_empty() {
        return fail(Error::WrongLength {
            expected: nodes.len() - rest.len() + 3,
            found: nodes.len(),
        });
    }
    let net = match CNet::new(center, points) {
        Ok(net) => net,
        Err(e) => return fail(e),
    };
    let mut sub = match EgSubdivision::new(&net, None) {
        Ok(sub) => sub,
        Err(e) => return fail(e),
    };
    for _ in 0..steps {
        if let Err(e) = sub.step() {
            return fail(e);
        }
    }
    let d = sub.net();
    let mut out = vec![d.valence() as f64];
    out.extend(d.c0().0);
    for s in 0..d.valence() {
        for j in 0..3 {
            for i in 0..4 {
                out.extend(d.node(s, i, j).unwrap().0);
            }
        }
    }
    let mut ring = vec![];
    for k in 0..sub.ring_len() {
        let patch = sub.ring_patch(k).unwrap();
        for row in patch.points {
            for p in row {
                ring.extend(p.0);
            }
        }
    }
    (out.len() as i32, out, ring.len() as i32, ring)
}

fn check(text: &str) -> (usize, usize) {
    let mut lines = text.lines();
    let mut cases = 0;
    let mut eg_cases = 0;
    let mut errors = 0;
    loop {
        let head = lines.next().expect("demo output ends with `done N M`");
        let w: Vec<&str> = head.split(' ').collect();
        if w[0] == "done" {
            assert_eq!(w[1].parse::<usize>().unwrap(), cases);
            assert_eq!(w[2].parse::<usize>().unwrap(), eg_cases);
            break;
        }
        if w[0] == "egcase" {
            let steps: u32 = w[2].parse().unwrap();
            let mut field = |tag: &str| -> Vec<&str> {
                let l = lines
                    .next()
                    .unwrap_or_else(|| panic!("egcase {}: no {tag}", w[1]));
                let v: Vec<&str> = l.split(' ').collect();
                assert_eq!(v[0], tag, "egcase {}: {l:.80}", w[1]);
                v
            };
            let center: [f64; 3] = f64s(&field("center")[1..]).try_into().unwrap();
            let nodes = f64s(&field("nodes")[1..]);
            assert_eq!(nodes.len(), w[3].parse::<usize>().unwrap());
            let refine = field("egrefine");
            let ring = field("egring");
            let (r, out, g, ring_out) = native_eg(center, &nodes, steps);
            assert_eq!(
                refine[1].parse::<i32>().unwrap(),
                r,
                "egcase {}: status",
                w[1]
            );
            assert_eq!(
                ring[1].parse::<i32>().unwrap(),
                g,
                "egcase {}: ring status",
                w[1]
            );
            let native_bits: Vec<u64> = out.iter().map(|x| x.to_bits()).collect();
            assert_eq!(
                bits(&refine[2..]),
                native_bits,
                "egcase {}: d-net differs from the native kernel",
                w[1]
            );
            let native_bits: Vec<u64> = ring_out.iter().map(|x| x.to_bits()).collect();
            assert_eq!(
                bits(&ring[2..]),
                native_bits,
                "egcase {}: ring differs from the native kernel",
                w[1]
            );
            if r < 0 {
                errors += 1;
            }
            eg_cases += 1;
            continue;
        }
        assert_eq!(w[0], "case", "{head}");
        let valence: usize = w[2].parse().unwrap();
        let steps: u32 = w[3].parse().unwrap();
        let plain = w[4] == "1";
        let mut field = |tag: &str| -> Vec<&str> {
            let l = lines
                .next()
                .unwrap_or_else(|| panic!("case {}: no {tag}", w[1]));
            let v: Vec<&str> = l.split(' ').collect();
            assert_eq!(v[0], tag, "case {}: {l:.80}", w[1]);
            v
        };
        let pole = field("pole");
        let coords = field("coords");
        let refine = field("refine");
        let jet = field("jet");
        let pole: [f64; 3] = f64s(&pole[1..]).try_into().unwrap();
        let coords = f64s(&coords[1..]);
        assert_eq!(coords.len(), w[5].parse::<usize>().unwrap());
        let (r, out, j, jet_out) = native(pole, &coords, valence, steps, plain);
        let wasm_r: i32 = refine[1].parse().unwrap();
        let wasm_j: i32 = jet[1].parse().unwrap();
        assert_eq!(wasm_r, r, "case {}: refine status", w[1]);
        assert_eq!(wasm_j, j, "case {}: jet status", w[1]);
        let native_bits: Vec<u64> = out.iter().map(|x| x.to_bits()).collect();
        assert_eq!(
            bits(&refine[2..]),
            native_bits,
            "case {}: refined net differs from the native kernel",
            w[1]
        );
        let native_bits: Vec<u64> = jet_out.iter().map(|x| x.to_bits()).collect();
        assert_eq!(
            bits(&jet[2..]),
            native_bits,
            "case {}: jet differs from the native kernel",
            w[1]
        );
        if r < 0 {
            errors += 1;
        }
        cases += 1;
    }
    // The demo's error cases (5 C²PS, 3 EG) came back as errors (and matched).
    assert!(errors >= 8, "only {errors} error cases");
    (cases, eg_cases)
}

#[test]
fn wasm_under_node_matches_native_bit_for_bit() {
    let dir = repo_root().join("capi-wasm");
    cargo_in(&dir, &["build", "--release"]);
    let wasm = dir.join("target/wasm32-unknown-unknown/release/capdiv_capi_wasm.wasm");
    let mut cmd = Command::new("node");
    cmd.arg(dir.join("demo.mjs")).arg(&wasm);
    let run = run_with_limit(cmd, Duration::from_secs(120)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(run.code, Some(0), "node failed: {}", run.stderr);
    let text = String::from_utf8(run.stdout).expect("text output");
    // Nets of capacity 1536 in f64 are 210 KiB: compare on a roomy stack.
    let (cases, eg_cases) = std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(move || check(&text))
        .unwrap()
        .join()
        .unwrap();
    let size = std::fs::metadata(&wasm).unwrap().len();
    eprintln!(
        "wasm: {cases} C²PS and {eg_cases} EG cases bit-identical to native in {:.2?}; \
         module {size} bytes",
        run.elapsed
    );
}
