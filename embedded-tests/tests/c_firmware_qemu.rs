//! The C firmware under QEMU: `cfirmware/` is C code that links
//! capdiv's C ABI (`capi/`, a Rust staticlib) through the generated header
//! `capi/include/capdiv.h`. This test builds it with Debian's
//! `arm-none-eabi-gcc` for the Cortex-M4F (QEMU `mps2-an386`) and the
//! Cortex-M0 (QEMU `microbit`), each with every call and with the `float`
//! calls only, runs the four images with a time limit, parses the lines it
//! prints over semihosting (inputs and outputs as hex bits, see
//! `cfirmware/main.c`) and recomputes every call with the `f64` kernel here:
//!
//! - the `double` calls must agree bit for bit (IEEE-754 operations are
//!   correctly rounded in software on the Cortex-M as in hardware here, and
//!   the kernel contracts no multiply-add);
//! - the `float` calls within the `f32` bounds of `firmware_qemu.rs` (the same
//!   kernel code on the same sample nets; see [`tolerance`]);
//! - status codes (errors included) must be the kernel's error, mapped by
//!   `capi/src/codes.rs`;
//! - the printed inputs must be the Rust firmware's sample nets
//!   (`firmware/src/sample.rs`), converted exactly.
//!
//! The same `main.c` is also built as a program for this machine (`make
//! host`: `cfirmware/host.c` instead of the startup and semihosting code,
//! the host's `cc` and the host build of the staticlib with the link line of
//! `docs/c-abi.md`) and checked the same way, as a board of the M4's
//! depths without a stack measurement.
//!
//! Needs `arm-none-eabi-gcc` and `qemu-system-arm` (`scripts/ci-cfirmware.sh`
//! installs them), hence the feature: `cargo test --release --features
//! cfirmware --test c_firmware_qemu`.

use capdiv::eg::{CNet, EgSubdivision};
use capdiv::{Error, FirstStep, Point3, PolarNetBuf, PoleJet, SliceStorage};
use capdiv_embedded_tests::{repo_root, run_with_limit};
use std::collections::BTreeMap;
use std::process::Command;
use std::time::Duration;

#[path = "../../capi/src/codes.rs"]
#[allow(dead_code)]
mod codes;

#[path = "../../firmware/src/sample.rs"]
#[allow(dead_code)]
mod sample;

/// Generous for runs of well under a second; a hang ends here.
const LIMIT: Duration = Duration::from_secs(60);

/// Unit roundoff of `f32`, `2⁻²⁴`.
const U: f64 = 1.0 / (1u64 << 24) as f64;

/// Scalars of work buffer per point of C²PS capacity (`CAPDIV_WORK_PER_POINT`).
const WORK_PER_POINT: usize = 17;

/// Builds both images with `make` (which builds the staticlib with cargo).
fn build() {
    let dir = repo_root().join("cfirmware");
    let out = Command::new("make")
        .args(["-s", "all"])
        .current_dir(&dir)
        .env_remove("CARGO_TARGET_DIR")
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_BUILD_TARGET")
        .output()
        .expect("make runs (needs make and arm-none-eabi-gcc: scripts/ci-cfirmware.sh)");
    assert!(
        out.status.success(),
        "make in cfirmware/ failed:\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Builds the host program with `make host` and runs it.
fn run_host() -> String {
    let dir = repo_root().join("cfirmware");
    let out = Command::new("make")
        .args(["-s", "host"])
        .current_dir(&dir)
        .env_remove("CARGO_TARGET_DIR")
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_BUILD_TARGET")
        .output()
        .expect("make runs (needs make and a host C compiler, cc)");
    assert!(
        out.status.success(),
        "make host in cfirmware/ failed:\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    let run = run_with_limit(Command::new(dir.join("build/host/cfirmware")), LIMIT)
        .unwrap_or_else(|e| panic!("{e}"));
    let text = String::from_utf8(run.stdout).expect("text output");
    assert_eq!(
        run.code,
        Some(0),
        "host program exit status; stderr {}",
        run.stderr
    );
    text
}

/// Runs one image; its semihosting output goes to stdout through a chardev.
fn run(board: &str) -> String {
    let elf = repo_root().join(format!("cfirmware/build/{board}/cfirmware.elf"));
    let mut cmd = Command::new("qemu-system-arm");
    if board.starts_with("m4") {
        cmd.args(["-machine", "mps2-an386", "-cpu", "cortex-m4"]);
    } else {
        cmd.args(["-machine", "microbit"]);
    }
    cmd.args([
        "-nographic",
        "-monitor",
        "none",
        "-serial",
        "none",
        "-chardev",
        "stdio,id=sh",
        "-semihosting-config",
        "enable=on,target=native,chardev=sh",
        "-kernel",
    ])
    .arg(&elf);
    let run = run_with_limit(cmd, LIMIT).unwrap_or_else(|e| panic!("{e}"));
    let text = String::from_utf8(run.stdout).expect("text output");
    assert_eq!(
        run.code,
        Some(0),
        "QEMU exit status (semihosting) {:?}; stderr {}; output tail:\n{}",
        run.code,
        run.stderr,
        &text[text.len().saturating_sub(2000)..]
    );
    eprintln!(
        "{board}: {} bytes of output in {:.2?}",
        text.len(),
        run.elapsed
    );
    text
}

/// A number as printed: 8 hex digits for `f32`, 16 for `f64`, widened exactly.
fn number(prec: &str, word: &str) -> f64 {
    match prec {
        "f32" => f32::from_bits(u32::from_str_radix(word, 16).expect("f32 hex")) as f64,
        "f64" => f64::from_bits(u64::from_str_radix(word, 16).expect("f64 hex")),
        _ => panic!("precision {prec:?}"),
    }
}

fn numbers(prec: &str, words: &[&str]) -> Vec<f64> {
    words.iter().map(|w| number(prec, w)).collect()
}

fn int<T: std::str::FromStr>(word: &str) -> T
where
    T::Err: std::fmt::Debug,
{
    word.parse().expect("integer")
}

/// What the kernel gives for a call: its status and, on success, the values.
type Native = (i32, Vec<f64>);

fn fail(e: Error) -> Native {
    (codes::code(&e), vec![])
}

fn first_step(plain: u32) -> FirstStep {
    if plain != 0 {
        FirstStep::Plain
    } else {
        FirstStep::Uniform
    }
}

/// The C²PS refine and jet calls in f64: the net built in storage of
/// capacity `work_len / 17`, as the C ABI's work buffer gives.
fn native_c2ps(
    pole: [f64; 3],
    valence: usize,
    coords: &[f64],
    steps: u32,
    plain: u32,
    work_len: usize,
) -> (Native, Native) {
    let cap = work_len / WORK_PER_POINT;
    let mut links = vec![Point3::ZERO; SliceStorage::<f64>::links_len(cap)];
    let mut roots = vec![[0.0; 2]; SliceStorage::<f64>::roots_len(cap)];
    let mut net = match PolarNetBuf::from_flat_in(
        pole,
        valence,
        coords,
        SliceStorage::new(&mut links, &mut roots),
    ) {
        Ok(net) => net,
        Err(e) => return (fail(e), fail(e)),
    };
    for _ in 0..steps {
        if let Err(e) = net.step(first_step(plain)) {
            return (fail(e), fail(e));
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
    match jet.geometry() {
        Ok(g) => {
            j.extend(g.normal.0);
            j.extend([g.gaussian, g.mean, g.principal[0], g.principal[1]]);
        }
        Err(Error::Degenerate) => {}
        Err(e) => return ((out.len() as i32, out), fail(e)),
    }
    ((out.len() as i32, out), (j.len() as i32, j))
}

/// The EG refine and ring calls in f64.
fn native_eg(center: [f64; 3], nodes: &[f64], steps: u32) -> (Native, Native) {
    let (points, rest) = nodes.as_chunks::<3>();
    if !rest.is_empty() {
        let e = Error::WrongLength {
            expected: nodes.len() - rest.len() + 3,
            found: nodes.len(),
        };
        return (fail(e), fail(e));
    }
    let net = match CNet::new(center, points) {
        Ok(net) => net,
        Err(e) => return (fail(e), fail(e)),
    };
    let mut sub = match EgSubdivision::new(&net, None) {
        Ok(sub) => sub,
        Err(e) => return (fail(e), fail(e)),
    };
    for _ in 0..steps {
        if let Err(e) = sub.step() {
            return (fail(e), fail(e));
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
        for row in sub.ring_patch(k).unwrap().points {
            for p in row {
                ring.extend(p.0);
            }
        }
    }
    ((out.len() as i32, out), (ring.len() as i32, ring))
}

/// Tolerance of one `f32` output against its `f64` value; `kind` names the
/// call and `k` the value's index in the output.
///
/// The inputs are exact in `f32`, so the difference is the firmware's `f32`
/// rounding in the same kernel code that `firmware_qemu.rs` checks on the
/// same sample nets, with the same bounds and reasons (see its `tolerance`):
/// positions (pole, links, jet coefficients, d-net nodes, ring control
/// points: short chains of affine combinations and compensated Fourier means)
/// `16·u·max(1, |x|)`; the pole normal `2¹⁰·u` (it divides by `|p1 × p2|`,
/// carried scaled by `2⁻ᵐ` at level `m ≤ 6`); curvatures `2¹⁶·u·max(1, |x|)`
/// (they need `p3..p5`, carried scaled by `4⁻ᵐ`).
fn tolerance(kind: &str, k: usize, reference: f64) -> f64 {
    let scale = reference.abs().max(1.0);
    match (kind, k) {
        ("c2ps_jet", 18..=20) => 1024.0 * U,
        ("c2ps_jet", 21..) => 65536.0 * U * scale,
        _ => 16.0 * U * scale,
    }
}

/// The outcome of checking one board's output.
#[derive(Default)]
struct Summary {
    /// Calls compared, per (call, precision).
    calls: BTreeMap<(String, String), usize>,
    /// Worst |f32 − f64| / tolerance per call.
    worst: BTreeMap<String, f64>,
    /// Error statuses seen (all matched the kernel's).
    errors: usize,
    /// (high-water mark, stack size).
    stack: (usize, usize),
    /// Phase high-water marks.
    phases: Vec<(String, usize)>,
    /// The length helpers' line was seen (and right).
    lens: bool,
}

fn compare(line: &str, kind: &str, prec: &str, got: (i32, &[f64]), want: &Native, s: &mut Summary) {
    assert_eq!(got.0, want.0, "{line:.120}: status (kernel: {})", want.0);
    if got.0 < 0 {
        s.errors += 1;
    }
    assert_eq!(got.1.len(), want.1.len(), "{line:.120}: value count");
    for (k, (g, w)) in got.1.iter().zip(&want.1).enumerate() {
        if prec == "f64" {
            assert_eq!(
                g.to_bits(),
                w.to_bits(),
                "{line:.120}: value {k}: firmware {g:e} vs kernel {w:e} (f64 must be bit-exact)"
            );
        } else {
            let (err, tol) = ((g - w).abs(), tolerance(kind, k, *w));
            assert!(
                err <= tol,
                "{line:.120}: value {k}: firmware {g:e} vs f64 kernel {w:e}: |diff| {err:e} > {tol:e}"
            );
            let e = s.worst.entry(kind.to_string()).or_insert(0.0);
            *e = e.max(err / tol);
        }
    }
    *s.calls
        .entry((kind.to_string(), prec.to_string()))
        .or_insert(0) += 1;
}

/// The sample of `firmware/src/sample.rs`, flat.
fn sample_polar() -> ([f64; 3], Vec<f64>) {
    let coords = sample::LINKS.iter().flatten().flatten().copied().collect();
    (sample::POLE, coords)
}

fn sample_cnet(n: usize) -> Vec<f64> {
    let nodes: &[[f64; 3]] = match n {
        3 => &sample::EG_NODES_3,
        _ => &sample::EG_NODES_5,
    };
    nodes.iter().flatten().copied().collect()
}

/// Inputs by (precision, id): a polar configuration (valence, pole, coords).
type PolarInputs = BTreeMap<(String, usize), (usize, [f64; 3], Vec<f64>)>;

/// Inputs by (precision, id): a c-net (centre, nodes).
type CnetInputs = BTreeMap<(String, usize), ([f64; 3], Vec<f64>)>;

/// Checks a board's output: `m4`, `m0`, `m4-f32`, `m0-f32` or `host` (the
/// M4's depths, no stack measurement).
fn check(text: &str, board: &str) -> Summary {
    let f32_only = board.ends_with("-f32");
    let m0 = board.starts_with("m0");
    let mut s = Summary::default();
    let mut polar = PolarInputs::new();
    let mut cnets = CnetInputs::new();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("start"), "{text:.500}");
    let mut done = false;
    for line in lines {
        let w: Vec<&str> = line.split(' ').collect();
        assert!(!done, "output after `done`: {line:.120}");
        match w[0] {
            "abi" => {
                // Every call of the header referenced (the float ones and the
                // length helpers in the f32-only images).
                let all = if f32_only { "8" } else { "17" };
                assert_eq!(w[1], all, "calls referenced");
            }
            "polar" => {
                let (prec, id) = (w[1].to_string(), int::<usize>(w[2]));
                let (valence, len) = (int::<usize>(w[3]), int::<usize>(w[4]));
                let v = numbers(&prec, &w[5..]);
                assert_eq!(v.len(), 3 + len, "{line:.120}");
                let pole: [f64; 3] = v[..3].try_into().unwrap();
                let coords = v[3..].to_vec();
                let (sp, sc) = sample_polar();
                assert_eq!((valence, pole), (sample::VALENCE, sp), "{line:.120}");
                for (k, (a, b)) in coords.iter().zip(&sc).enumerate() {
                    // Input 1 has a NaN at coordinate 7 (an error case).
                    assert!(
                        a == b || (id == 1 && k == 7 && a.is_nan()),
                        "{line:.120}: {k}"
                    );
                }
                polar.insert((prec, id), (valence, pole, coords));
            }
            "cnet" => {
                let (prec, id) = (w[1].to_string(), int::<usize>(w[2]));
                let len = int::<usize>(w[3]);
                let v = numbers(&prec, &w[4..]);
                assert_eq!(v.len(), 3 + len, "{line:.120}");
                let center: [f64; 3] = v[..3].try_into().unwrap();
                assert_eq!(center, sample::EG_CENTER, "{line:.120}");
                let nodes = v[3..].to_vec();
                // Input 2 is the first two sectors of the valence-5 sample.
                let sample = sample_cnet(if id == 3 { 3 } else { 5 });
                assert_eq!(nodes[..], sample[..len], "{line:.120}");
                cnets.insert((prec, id), (center, nodes));
            }
            "c2ps_refine" | "c2ps_jet" => {
                let (prec, id) = (w[1].to_string(), int::<usize>(w[2]));
                let len = int::<usize>(w[3]);
                let (steps, plain) = (int::<u32>(w[4]), int::<u32>(w[5]));
                let work_len = int::<usize>(w[6]);
                let refine = w[0] == "c2ps_refine";
                let (out_len, status, values) = if refine {
                    (int::<usize>(w[7]), int::<i32>(w[8]), &w[9..])
                } else {
                    (25, int::<i32>(w[7]), &w[8..])
                };
                let (valence, pole, coords) = polar
                    .get(&(prec.clone(), id))
                    .unwrap_or_else(|| panic!("{line:.80}: no input {id}"));
                let (r, j) = native_c2ps(*pole, *valence, &coords[..len], steps, plain, work_len);
                let got = numbers(&prec, values);
                let want = if refine { r } else { j };
                // An output longer than the buffer given is CAPDIV_BAD_BUFFER.
                let want = if want.1.len() > out_len {
                    (codes::CAPDIV_BAD_BUFFER, vec![])
                } else {
                    want
                };
                compare(line, w[0], &prec, (status, &got), &want, &mut s);
            }
            "eg_refine" | "eg_ring" => {
                let (prec, id) = (w[1].to_string(), int::<usize>(w[2]));
                let (len, steps) = (int::<usize>(w[3]), int::<u32>(w[4]));
                let (out_len, status) = (int::<usize>(w[5]), int::<i32>(w[6]));
                let (center, nodes) = cnets
                    .get(&(prec.clone(), id))
                    .unwrap_or_else(|| panic!("{line:.80}: no input {id}"));
                let (r, g) = native_eg(*center, &nodes[..len], steps);
                let got = numbers(&prec, &w[7..]);
                let want = if w[0] == "eg_refine" { r } else { g };
                let want = if want.1.len() > out_len {
                    (codes::CAPDIV_BAD_BUFFER, vec![])
                } else {
                    want
                };
                compare(line, w[0], &prec, (status, &got), &want, &mut s);
            }
            "badbuf" => {
                assert_eq!(int::<i32>(w[2]), codes::CAPDIV_BAD_BUFFER, "{line}");
                s.errors += 1;
            }
            "lens" => {
                // work 17·6·2^d, out 5 + 15·6·2^d, EG 4 + 36·5 and 225·5,
                // then three lengths that overflow a 32-bit size_t: 0.
                let d = if m0 { 3 } else { 6 };
                let c = 6usize << d;
                let want = [17 * c, 5 + 15 * c, 4 + 36 * 5, 225 * 5, 0, 0, 0];
                let got: Vec<usize> = w[1..].iter().map(|x| int(x)).collect();
                assert_eq!(got, want, "{line}");
                s.lens = true;
            }
            "stackphase" => s.phases.push((w[1].to_string(), int(w[2]))),
            "stack" => s.stack = (int(w[1]), int(w[2])),
            "done" => {
                assert_eq!(w[1], "0", "the firmware's own checks failed");
                done = true;
            }
            _ => panic!("unexpected line {line:.120}"),
        }
    }
    assert!(done, "no `done` line: the firmware did not finish");
    assert!(
        board == "host" || (s.stack.0 > 0 && s.stack.0 < s.stack.1),
        "stack high-water mark {:?} outside (0, size): overflow or no painting",
        s.stack
    );
    // What each board must have run (cfirmware/main.c).
    let f32_depth = if m0 { 3 } else { 6 };
    assert!(
        text.lines()
            .any(|l| l.starts_with(&format!("c2ps_refine f32 0 126 {f32_depth} 0 "))),
        "no f32 C²PS refinement to depth {f32_depth}"
    );
    let count = |call: &str, prec: &str| {
        s.calls
            .get(&(call.to_string(), prec.to_string()))
            .copied()
            .unwrap_or(0)
    };
    for call in ["c2ps_refine", "c2ps_jet", "eg_refine", "eg_ring"] {
        assert!(count(call, "f32") >= 2, "{call} f32: too few calls");
    }
    if !f32_only {
        assert!(count("c2ps_refine", "f64") >= 2 && count("c2ps_jet", "f64") >= 2);
    }
    // The M0's 16 KiB do not hold the double EG subdivision's stack.
    if !f32_only && !m0 {
        assert!(count("eg_refine", "f64") >= 2 && count("eg_ring", "f64") >= 2);
    }
    // 5 C²PS + 4 EG error statuses, 3 null buffers, 1 short output.
    assert!(s.errors >= 13, "only {} error statuses", s.errors);
    assert!(s.lens, "no `lens` line");
    s
}

#[test]
fn c_firmware_matches_f64_kernel() {
    build();
    for board in ["m4", "m0", "m4-f32", "m0-f32"] {
        let text = run(board);
        let s = check(&text, board);
        let calls: usize = s.calls.values().sum();
        eprintln!(
            "{board}: {calls} calls match the f64 kernel (f64 bit for bit), {} errors as the \
             kernel's; stack high-water mark {} of {} bytes, by phase {:?}",
            s.errors, s.stack.0, s.stack.1, s.phases
        );
        for (kind, r) in &s.worst {
            eprintln!("  {kind:<12} f32 worst |diff| / tolerance = {r:.3}");
        }
    }
}

#[test]
fn host_c_program_matches_f64_kernel() {
    let text = run_host();
    let s = check(&text, "host");
    let calls: usize = s.calls.values().sum();
    eprintln!(
        "host: {calls} calls match the f64 kernel (f64 bit for bit), {} errors as the kernel's",
        s.errors
    );
    for (kind, r) in &s.worst {
        eprintln!("  {kind:<12} f32 worst |diff| / tolerance = {r:.3}");
    }
}
