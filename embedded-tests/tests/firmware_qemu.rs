//! The firmware under QEMU (issue 4): build it, run it with a time limit,
//! decode its defmt log and compare every number it reports with the same
//! computation in `f64` on the host (the kernel's `f64` path; the sample's
//! inputs are exact in both types, so the difference is the firmware's `f32`
//! rounding alone).
//!
//! A kernel error, a fault, a hang (time limit), a missing or extra line or a
//! number outside the tolerance fails the test.

use capdiv::{FirstStep, OuterRegion, Point3, PolarNet, PoleJet};
use capdiv_embedded_tests::report::{parse, Entry};
use capdiv_embedded_tests::{build_firmware, decode_defmt, qemu, run_with_limit};
use std::collections::BTreeMap;
use std::time::Duration;

#[path = "../../firmware/src/sample.rs"]
#[allow(dead_code)]
mod sample;

use sample::{LINKS, POLE, VALENCE};

/// Generous for a run that takes well under a second; a hang ends here.
const LIMIT: Duration = Duration::from_secs(60);

/// Capacity of the f64 reference net: enough for depth 6.
const CAP: usize = VALENCE << 6;

fn p(v: Point3<f64>) -> Vec<f64> {
    v.0.to_vec()
}

fn quarter(i: usize) -> f64 {
    i as f64 * 0.25
}

/// Everything the firmware reports, recomputed in f64, keyed by `Entry::id`.
fn reference(depth: u32) -> BTreeMap<String, Entry> {
    let mut out = BTreeMap::new();
    let mut add = |key: &str, idx: &[usize], vals: Vec<f64>| {
        let e = Entry::new(key, idx, &vals);
        assert!(out.insert(e.id(), e).is_none(), "duplicate {key} {idx:?}");
    };
    let mut net: PolarNet<f64, CAP> = PolarNet::new(POLE, &LINKS[..5]).unwrap();
    for (k, q) in PoleJet::of(&net).p.iter().enumerate() {
        add("jet0", &[k], p(*q));
    }
    for _ in 0..depth {
        net.step(FirstStep::Uniform).unwrap();
        add("pole", &[net.level() as usize], p(net.pole()));
    }
    let jet = PoleJet::of(&net);
    for (k, q) in jet.p.iter().enumerate() {
        add("jet", &[k], p(*q));
    }
    add("limit", &[], p(jet.limit()));
    let g = jet.geometry().unwrap();
    add("normal", &[], p(g.normal));
    add(
        "curv",
        &[],
        vec![g.gaussian, g.mean, g.principal[0], g.principal[1]],
    );
    let n = net.valence();
    for i in 1..=5 {
        let link = net.link(i).unwrap();
        for j in [0, 1, n / 2, n - 1] {
            add("link", &[i, j], p(link[j]));
        }
    }
    for (span, col, ui, vi) in [(0, 0, 2, 2), (1, n - 1, 1, 3), (0, n / 3, 4, 0)] {
        let e = net
            .ring_patch(span, col)
            .unwrap()
            .evaluate(quarter(ui), quarter(vi))
            .unwrap();
        let id = [span, col, ui, vi];
        add("ringpos", &id, p(e.position));
        add("ringdu", &id, p(e.du));
        add("ringdv", &id, p(e.dv));
        add("ringnrm", &id, p(e.normal().unwrap()));
    }
    let mut sum = Point3::ZERO;
    let mut count = 0;
    for patch in net.ring_patches().unwrap() {
        sum += patch.position(0.5, 0.5).unwrap();
        count += 1;
    }
    add("ringcount", &[count], vec![]);
    add("ringsum", &[], p(sum));

    let flat: Vec<f64> = LINKS[..5].iter().flatten().flatten().copied().collect();
    let mut rts = PolarNet::<f64, VALENCE>::from_flat(POLE, VALENCE, &flat).unwrap();
    for k in 1..=3 {
        rts.rts_step();
        add("rtspole", &[k], p(rts.pole()));
    }
    for (j, q) in rts.link(1).unwrap().iter().enumerate() {
        add("rtslink", &[j], p(*q));
    }

    let region = OuterRegion::new(POLE, &LINKS[..]).unwrap();
    add("outercount", &[region.len()], vec![]);
    for (i, ui, vi) in [(0, 2, 2), (VALENCE - 1, 4, 1)] {
        let e = region
            .patch(i)
            .unwrap()
            .evaluate(quarter(ui), quarter(vi))
            .unwrap();
        add("outerpos", &[i, ui, vi], p(e.position));
        add("outernrm", &[i, ui, vi], p(e.normal().unwrap()));
    }
    let mut sum = Point3::ZERO;
    for patch in region.patches() {
        sum += patch.position(0.5, 0.5).unwrap();
    }
    add("outersum", &[], p(sum));
    out
}

/// Unit roundoff of `f32`, `2⁻²⁴`.
const U: f64 = 1.0 / (1u64 << 24) as f64;

/// Tolerance for one reported number of line `key` against its f64 value.
///
/// The inputs are exact in f32, so the difference is the firmware's rounding.
///
/// - Positions, first derivatives, jet coefficients, sums: every output is a
///   short chain of affine combinations (weights of absolute sum ≤ 3) and of
///   Fourier means over the 1-link; each rounds with relative error `u`, the
///   means over `N ≤ 384` terms at worst `√N·u` typically. We allow
///   `16·u·max(1, |x|)` (≈ 1e-6 relative); the errors measured are ≤ 1 ulp.
/// - The pole normal depends on `p1, p2`, which the 1-link at level `m` carries
///   scaled by `λᵐ = 2⁻ᵐ`: rounding of coordinates of size ~1 becomes a
///   relative error `≈ u·2ᵐ` in them, `2⁶·u ≈ 4e-6` at `m = 6`: allowed `2¹⁰·u`.
/// - Ring normals at level 6 come from `∂u × ∂v` of patches `2⁻⁶` across, the
///   same loss plus the cancellation in the Bézier differences: `2¹¹·u ≈ 1.2e-4`.
/// - Curvatures need `p3, p4, p5`, carried scaled by `μᵐ = 4⁻ᵐ`: relative error
///   `≈ u·4ᵐ/|p3| ≈ 8e-4` at `m = 6` (`|p3| ≈ 0.3`): allowed `2¹⁶·u ≈ 3.9e-3`
///   relative.
fn tolerance(key: &str, reference: f64) -> f64 {
    let scale = reference.abs().max(1.0);
    match key {
        "curv" => 65536.0 * U * scale,
        "normal" => 1024.0 * U,
        "ringnrm" | "outernrm" => 2048.0 * U,
        _ => 16.0 * U * scale,
    }
}

struct Checked {
    worst: BTreeMap<String, f64>,
    stack: (usize, usize),
    /// (construction, refinement and evaluation) high-water marks.
    phases: (usize, usize),
    net_bytes: usize,
}

fn check_log(lines: &[String], depth: u32, cap: usize) -> Checked {
    assert_eq!(
        lines.first().map(String::as_str),
        Some("start"),
        "{lines:#?}"
    );
    assert_eq!(
        lines.last().map(String::as_str),
        Some("done true"),
        "the firmware did not finish cleanly:\n{lines:#?}"
    );
    let mut expected = reference(depth);
    let mut worst: BTreeMap<String, f64> = BTreeMap::new();
    let mut abs_worst: BTreeMap<String, f64> = BTreeMap::new();
    let mut stack = None;
    let mut phases = None;
    let mut cfg = None;
    let mut geometry = false;
    for line in &lines[1..lines.len() - 1] {
        if line.starts_with("geometry PoleGeometry {") {
            geometry = true;
            continue;
        }
        let got = parse(line).unwrap_or_else(|| panic!("unparsable line {line:?}"));
        match got.key.as_str() {
            "stack" => {
                stack = Some((got.idx[0], got.idx[1]));
                continue;
            }
            "stackphase" => {
                phases = Some((got.idx[0], got.idx[1]));
                continue;
            }
            "cfg" => {
                cfg = Some(got.idx.clone());
                continue;
            }
            _ => {}
        }
        let want = expected
            .remove(&got.id())
            .unwrap_or_else(|| panic!("unexpected or repeated line {line:?}"));
        assert_eq!(got.vals.len(), want.vals.len(), "{line:?} vs {want:?}");
        for (g, w) in got.vals.iter().zip(&want.vals) {
            let err = (g - w).abs();
            let e = abs_worst.entry(got.key.clone()).or_insert(0.0);
            *e = e.max(err);
            let tol = tolerance(&got.key, *w);
            assert!(
                err <= tol,
                "{line:?}: firmware {g} vs f64 {w}: |diff| {err:e} > tolerance {tol:e}"
            );
            let rel = err / tol;
            let e = worst.entry(got.key.clone()).or_insert(0.0);
            *e = e.max(rel);
        }
    }
    assert!(
        expected.is_empty(),
        "lines missing from the firmware's log: {:?}",
        expected.keys().collect::<Vec<_>>()
    );
    assert!(geometry, "no defmt::Format line for PoleGeometry");
    let cfg = cfg.expect("cfg line");
    assert_eq!(cfg[..3], [VALENCE, depth as usize, cap], "cfg line");
    let stack = stack.expect("stack line");
    assert!(
        stack.0 > 0 && stack.0 < stack.1,
        "stack high-water mark {stack:?} outside (0, size): painting failed or overflowed"
    );
    let phases = phases.expect("stackphase line");
    assert!(
        phases.0 <= stack.0 && phases.1 <= stack.0 && phases.1 > 0,
        "phase high-water marks {phases:?} exceed the whole run's {stack:?}"
    );
    for (k, v) in &abs_worst {
        eprintln!("  {k:<10} worst |f32 - f64| = {v:.3e}");
    }
    Checked {
        worst,
        stack,
        phases,
        net_bytes: cfg[3],
    }
}

fn run_and_check(target: &str, machine: &str, cpu: Option<&str>, depth: u32) {
    let elf = build_firmware(target, "");
    let run = run_with_limit(qemu(machine, cpu, &elf), LIMIT).unwrap_or_else(|e| panic!("{e}"));
    let bytes = std::fs::read(&elf).unwrap();
    let lines = decode_defmt(&bytes, &run.stdout).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        run.code,
        Some(0),
        "QEMU exit status (semihosting) {:?}; stderr {}; log:\n{lines:#?}",
        run.code,
        run.stderr
    );
    let checked = check_log(&lines, depth, VALENCE << depth);
    eprintln!(
        "{target} on {machine}: {} lines, {:.2?}, stack high-water mark {} of {} bytes \
         (construction {}, refinement + evaluation {}), net static {} bytes",
        lines.len(),
        run.elapsed,
        checked.stack.0,
        checked.stack.1,
        checked.phases.0,
        checked.phases.1,
        checked.net_bytes
    );
    for (key, r) in &checked.worst {
        eprintln!("  {key:<10} worst |diff| / tolerance = {r:.3}");
    }
    if let Ok(path) = std::env::var("CAPDIV_FIRMWARE_REPORT") {
        let text = format!(
            "{target} {machine} stack_hwm={} stack_size={} stack_construct={} stack_refine={} net_bytes={} qemu_ms={}\n",
            checked.stack.0,
            checked.stack.1,
            checked.phases.0,
            checked.phases.1,
            checked.net_bytes,
            run.elapsed.as_millis()
        );
        let mut old = std::fs::read_to_string(&path).unwrap_or_default();
        old.push_str(&text);
        std::fs::write(&path, old).unwrap();
    }
}

/// Cortex-M4F (FPU, `thumbv7em-none-eabihf`) on QEMU's MPS2-AN386: depth 6.
#[test]
fn cortex_m4_c2ps_matches_f64() {
    run_and_check("thumbv7em-none-eabihf", "mps2-an386", Some("cortex-m4"), 6);
}

/// Cortex-M0 (no FPU: soft-float f32, `thumbv6m-none-eabi`) on QEMU's BBC
/// micro:bit (16 KiB RAM): depth 3, same checks.
#[test]
fn cortex_m0_c2ps_matches_f64() {
    run_and_check("thumbv6m-none-eabi", "microbit", None, 3);
}
