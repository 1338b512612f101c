//! The firmware under QEMU: build it, run it with a time limit,
//! decode its defmt log and compare every number it reports with the same
//! computation in `f64` on the host: the kernel's `f64` path for every number,
//! and for the C²PS numbers also the independent reference crate
//! (`capdiv-reference`: the paper's literal O(n²) sums with `std` cos, Bernstein
//! evaluation). The sample's inputs are exact in both types, so the difference
//! is the firmware's `f32` rounding.
//!
//! A kernel error, a fault, a hang (time limit), a missing or extra line or a
//! number outside the tolerance fails the test.

use capdiv::eg::{CNet, EgSubdivision};
use capdiv::{FirstStep, OuterRegion, Point3, PolarNet, PoleJet};
use capdiv_embedded_tests::report::{parse, Entry};
use capdiv_embedded_tests::{build_firmware, decode_defmt, qemu, run_with_limit};
use std::collections::BTreeMap;
use std::time::Duration;

#[path = "../../firmware/src/sample.rs"]
#[allow(dead_code)]
mod sample;

use sample::{EG_CENTER, EG_NODES_3, EG_NODES_5, LINKS, POLE, VALENCE};

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

/// What one firmware build runs: the C²PS sample to `Some(depth)`, the EG samples.
#[derive(Clone, Copy, Debug)]
struct Workloads {
    c2ps: Option<u32>,
    eg: bool,
}

/// Everything the firmware reports, recomputed in f64, keyed by `Entry::id`.
fn reference(w: Workloads) -> BTreeMap<String, Entry> {
    let mut out = BTreeMap::new();
    let mut add = |key: &str, idx: &[usize], vals: Vec<f64>| {
        let e = Entry::new(key, idx, &vals);
        assert!(out.insert(e.id(), e).is_none(), "duplicate {key} {idx:?}");
    };
    if let Some(depth) = w.c2ps {
        c2ps_reference(depth, &mut add);
    }
    if w.eg {
        eg_reference(&mut add);
    }
    out
}

/// `Σ|xᵢ|` per coordinate over the centres of the ring patches the firmware
/// sums (`ringsum`) after `depth` steps, in f64: the scale of that sum's
/// rounding.
fn ring_magnitudes(depth: u32) -> [f64; 3] {
    let mut net: PolarNet<f64, CAP> = PolarNet::new(POLE, &LINKS[..5]).unwrap();
    for _ in 0..depth {
        net.step(FirstStep::Uniform).unwrap();
    }
    let mut sum = [0.0; 3];
    for patch in net.ring_patches() {
        let x = patch.position(0.5, 0.5).unwrap();
        for (s, c) in sum.iter_mut().zip(x.0) {
            *s += c.abs();
        }
    }
    sum
}

/// The C²PS workload of `firmware/src/c2ps.rs` in f64.
fn c2ps_reference(depth: u32, add: &mut impl FnMut(&str, &[usize], Vec<f64>)) {
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
            .ring_patch(span * n + col)
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
    for patch in net.ring_patches() {
        sum += patch.position(0.5, 0.5).unwrap();
        count += 1;
    }
    add("ringcount", &[count], vec![]);
    add("ringsum", &[], p(sum));

    let flat: Vec<f64> = LINKS[..5].iter().flatten().flatten().copied().collect();
    let mut rts = PolarNet::<f64, VALENCE>::from_flat(POLE, VALENCE, &flat).unwrap();
    for k in 1..=3 {
        rts.rts_step().unwrap();
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
}

/// The EG workload of `firmware/src/eg.rs` in f64.
fn eg_reference(add: &mut impl FnMut(&str, &[usize], Vec<f64>)) {
    for nodes in [&EG_NODES_3[..], &EG_NODES_5[..]] {
        let net = CNet::new(EG_CENTER, nodes).unwrap();
        let n = net.valence();
        add("eglimit", &[n], p(net.limit()));
        let mut sub = EgSubdivision::new(&net, None).unwrap();
        for _ in 0..EG_STEPS {
            sub.step().unwrap();
        }
        add("egc0", &[n], p(sub.limit()));
        for s in 0..n {
            for (i, j) in [(0, 0), (3, 0), (1, 1), (3, 2)] {
                add("egnode", &[n, s, i, j], p(sub.net().node(s, i, j).unwrap()));
            }
        }
        let len = sub.ring_len();
        add("egringcount", &[n, len], vec![]);
        for (k, ui, vi) in [(0, 2, 2), (1, 1, 3), (len - 1, 4, 0)] {
            let e = sub
                .ring_patch(k)
                .unwrap()
                .evaluate(quarter(ui), quarter(vi))
                .unwrap();
            add("egpos", &[n, k, ui, vi], p(e.position));
            add("egnrm", &[n, k, ui, vi], p(e.normal().unwrap()));
        }
        let mut sum = Point3::ZERO;
        for patch in sub.ring_patches() {
            sum += patch.position(0.5, 0.5).unwrap();
        }
        add("egsum", &[n], p(sum));
    }
}

/// EG steps the firmware applies to each sample (docs/math/eg.md: n = 3, 5).
const EG_STEPS: u32 = 4;

/// The C²PS numbers of `firmware/src/c2ps.rs` from the independent reference
/// crate (no kernel code): pole, jets, geometry, links, ring patches, RTS.
fn c2ps_independent(depth: u32) -> BTreeMap<String, Entry> {
    use capdiv_reference::c2ps::{refine, TwoLinkRule};
    use capdiv_reference::polar::Polar;
    use capdiv_reference::{bezier, jet, ring, rts, vec3};
    let mut out = BTreeMap::new();
    let mut add = |key: &str, idx: &[usize], vals: Vec<f64>| {
        let e = Entry::new(key, idx, &vals);
        out.insert(e.id(), e);
    };
    let cfg0 = Polar::new(POLE, LINKS[..5].iter().map(|l| l.to_vec()).collect());
    for (k, q) in jet::coefficients(&cfg0).iter().enumerate() {
        add("jet0", &[k], q.to_vec());
    }
    let levels = refine(&cfg0, depth, TwoLinkRule::Uniform);
    for (m, cfg) in levels.iter().enumerate().skip(1) {
        add("pole", &[m], cfg.pole.to_vec());
    }
    let cfg = levels.last().unwrap();
    let p = jet::coefficients(cfg);
    for (k, q) in p.iter().enumerate() {
        add("jet", &[k], q.to_vec());
    }
    add("limit", &[], p[0].to_vec());
    let g = jet::geometry(&p).unwrap();
    add("normal", &[], g.normal.to_vec());
    add(
        "curv",
        &[],
        vec![g.gaussian, g.mean, g.principal[0], g.principal[1]],
    );
    let n = cfg.valence();
    for i in 1..=5 {
        for j in [0, 1, n / 2, n - 1] {
            add("link", &[i, j], cfg.q(i, j).to_vec());
        }
    }
    for (span, col, ui, vi) in [(0, 0, 2, 2), (1, n - 1, 1, 3), (0, n / 3, 4, 0)] {
        let patch = ring::patch(cfg, span, col);
        let (u, v) = (quarter(ui), quarter(vi));
        let id = [span, col, ui, vi];
        let du = bezier::eval(&patch, u, v, 1, 0);
        let dv = bezier::eval(&patch, u, v, 0, 1);
        add("ringpos", &id, bezier::eval(&patch, u, v, 0, 0).to_vec());
        add("ringdu", &id, du.to_vec());
        add("ringdv", &id, dv.to_vec());
        let c = vec3::cross(du, dv);
        add("ringnrm", &id, vec3::scale(1.0 / vec3::norm(c), c).to_vec());
    }
    let mut sum = vec3::ZERO;
    for span in 0..2 {
        for col in 0..n {
            sum = vec3::add(
                sum,
                bezier::eval(&ring::patch(cfg, span, col), 0.5, 0.5, 0, 0),
            );
        }
    }
    add("ringsum", &[], sum.to_vec());
    let mut r = cfg0.clone();
    for k in 1..=3 {
        r = rts::step(&r);
        add("rtspole", &[k], r.pole.to_vec());
    }
    for j in 0..VALENCE {
        add("rtslink", &[j], r.q(1, j).to_vec());
    }
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
///   `ringsum`, the sum of the `2N` ring patches' centres, rounds relative to
///   the sum of their magnitudes `Σ|xᵢ|`, not to the sum itself (which
///   cancels: 0.81 against `Σ|yᵢ|` = 22.4 on the M0): allowed
///   `16·u·max(1, Σ|xᵢ|)` per coordinate ([`ring_magnitudes`]).
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
        "ringnrm" | "outernrm" | "egnrm" => 2048.0 * U,
        _ => 16.0 * U * scale,
    }
}

struct Checked {
    worst: BTreeMap<String, f64>,
    /// Whole run: (high-water mark, stack size).
    stack: (usize, usize),
    /// Phase high-water marks: C²PS construction, C²PS refinement and
    /// evaluation, EG (each 0 when not run).
    phases: [usize; 3],
    /// Size of the C²PS net static, 0 when not run.
    net_bytes: usize,
}

fn check_log(lines: &[String], w: Workloads) -> Checked {
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
    let mut expected = reference(w);
    let independent = w.c2ps.map(c2ps_independent).unwrap_or_default();
    let mut independent_checked = 0;
    let magnitudes = w.c2ps.map(ring_magnitudes).unwrap_or_default();
    // `ringsum` scales with its terms' magnitudes, the rest with the value.
    let tolerance_of = |key: &str, coordinate: usize, reference: f64| match key {
        "ringsum" => tolerance(key, magnitudes[coordinate].max(reference.abs())),
        _ => tolerance(key, reference),
    };
    let mut worst: BTreeMap<String, f64> = BTreeMap::new();
    let mut abs_worst: BTreeMap<String, f64> = BTreeMap::new();
    let mut stack = None;
    let mut phases = [0; 3];
    let mut cfg = None;
    let mut egcfg = Vec::new();
    let mut geometry = false;
    for line in &lines[1..lines.len() - 1] {
        // PoleGeometry is SurfaceGeometry since b327eee; defmt names the struct.
        if line.starts_with("geometry PoleGeometry {")
            || line.starts_with("geometry SurfaceGeometry {")
        {
            geometry = true;
            continue;
        }
        // The RTS net via the kernel's defmt::Format: present, not compared
        // (its numbers are the rtspole / rtslink lines).
        if line.starts_with("rtsnet PolarNet {") {
            continue;
        }
        let got = parse(line).unwrap_or_else(|| panic!("unparsable line {line:?}"));
        match got.key.as_str() {
            "stack" => {
                stack = Some((got.idx[0], got.idx[1]));
                continue;
            }
            "stackc2ps" => {
                phases[0] = got.idx[0];
                phases[1] = got.idx[1];
                continue;
            }
            "stackeg" => {
                phases[2] = got.idx[0];
                continue;
            }
            "egcfg" => {
                egcfg.push(got.idx.clone());
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
        if let Some(indep) = independent.get(&got.id()) {
            assert_eq!(got.vals.len(), indep.vals.len(), "{line:?} vs {indep:?}");
            for (c, (g, r)) in got.vals.iter().zip(&indep.vals).enumerate() {
                let (err, tol) = ((g - r).abs(), tolerance_of(&got.key, c, *r));
                assert!(
                    err <= tol,
                    "{line:?}: firmware {g} vs capdiv-reference {r}: |diff| {err:e} > tolerance {tol:e}"
                );
            }
            independent_checked += 1;
        }
        assert_eq!(got.vals.len(), want.vals.len(), "{line:?} vs {want:?}");
        for (c, (g, w)) in got.vals.iter().zip(&want.vals).enumerate() {
            let err = (g - w).abs();
            let e = abs_worst.entry(got.key.clone()).or_insert(0.0);
            *e = e.max(err);
            let tol = tolerance_of(&got.key, c, *w);
            assert!(
                err <= tol,
                "{line:?}: firmware {g} vs f64 {w}: |diff| {err:e} > tolerance {tol:e}"
            );
            let e = worst.entry(got.key.clone()).or_insert(0.0);
            *e = e.max(err / tol);
        }
    }
    assert!(
        expected.is_empty(),
        "lines missing from the firmware's log: {:?}",
        expected.keys().collect::<Vec<_>>()
    );
    for (k, v) in &abs_worst {
        eprintln!("  {k:<11} worst |f32 - f64| = {v:.3e}");
    }
    let stack = stack.expect("stack line");
    assert!(
        stack.0 > 0 && stack.0 < stack.1,
        "stack high-water mark {stack:?} outside (0, size): painting failed or overflowed"
    );
    let mut net_bytes = 0;
    if let Some(depth) = w.c2ps {
        // Every C²PS line but the outer region's has an independent value.
        assert_eq!(
            independent_checked,
            independent.len(),
            "C²PS lines without a capdiv-reference comparison"
        );
        eprintln!("  {independent_checked} C²PS lines also match capdiv-reference");
        assert!(geometry, "no defmt::Format line for PoleGeometry");
        let cfg = cfg.expect("cfg line");
        assert_eq!(
            cfg[..3],
            [VALENCE, depth as usize, VALENCE << depth],
            "cfg line"
        );
        net_bytes = cfg[3];
        assert!(phases[0] > 0 && phases[1] > 0, "no C²PS stack phases");
    }
    if w.eg {
        assert_eq!(
            egcfg.iter().map(|c| (c[0], c[1])).collect::<Vec<_>>(),
            [(3, EG_STEPS as usize), (5, EG_STEPS as usize)],
            "egcfg lines"
        );
        assert!(phases[2] > 0, "no EG stack phase");
    }
    assert!(
        phases.iter().all(|&p| p <= stack.0),
        "phase high-water marks {phases:?} exceed the whole run's {stack:?}"
    );
    Checked {
        worst,
        stack,
        phases,
        net_bytes,
    }
}

fn run_and_check(target: &str, machine: &str, cpu: Option<&str>, features: &str, w: Workloads) {
    let elf = build_firmware(target, features);
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
    let c = check_log(&lines, w);
    eprintln!(
        "{target} on {machine} ({w:?}): {} lines, {:.2?}, stack high-water mark {} of {} bytes \
         (C²PS construction {}, C²PS refinement + evaluation {}, EG {}), C²PS net static {} bytes",
        lines.len(),
        run.elapsed,
        c.stack.0,
        c.stack.1,
        c.phases[0],
        c.phases[1],
        c.phases[2],
        c.net_bytes
    );
    for (key, r) in &c.worst {
        eprintln!("  {key:<11} worst |diff| / tolerance = {r:.3}");
    }
}

/// Cortex-M4F (FPU, `thumbv7em-none-eabihf`) on QEMU's MPS2-AN386: C²PS to
/// depth 6 and EG (n = 3, 5; 4 steps) in one image.
#[test]
fn cortex_m4_matches_f64() {
    let w = Workloads {
        c2ps: Some(6),
        eg: true,
    };
    run_and_check(
        "thumbv7em-none-eabihf",
        "mps2-an386",
        Some("cortex-m4"),
        "",
        w,
    );
}

/// Cortex-M0 (no FPU: soft-float f32, `thumbv6m-none-eabi`) on QEMU's BBC
/// micro:bit, 16 KiB RAM: C²PS (depth 3) and EG in separate images, as both
/// do not fit the RAM together (see the size report).
#[test]
fn cortex_m0_matches_f64() {
    let target = "thumbv6m-none-eabi";
    let c2ps = Workloads {
        c2ps: Some(3),
        eg: false,
    };
    run_and_check(
        target,
        "microbit",
        None,
        "--no-default-features --features c2ps,api-check",
        c2ps,
    );
    let eg = Workloads {
        c2ps: None,
        eg: true,
    };
    run_and_check(
        target,
        "microbit",
        None,
        "--no-default-features --features eg,api-check",
        eg,
    );
}
