//! `capdiv refine`: schema round trip, valence n·2^M, exact agreement with the
//! kernel called directly, composition of steps, stdin and `-o`.

mod common;

use capdiv::{FirstStep, PolarNet};
use common::*;

/// Links the kernel holds after `m` steps from `k` input links: old links up
/// to K give new links up to 2K−1, at most 5 are stored (docs/math/c2ps.md §2).
fn links_after(k: usize, m: u32) -> usize {
    let mut held = k.min(5);
    for _ in 0..m {
        held = (2 * held - 1).min(5);
    }
    held
}

#[test]
fn output_is_the_input_schema_with_valence_n_times_2_pow_m() {
    let dir = tempdir();
    for (n, k) in [(3, 5), (5, 2), (8, 3), (6, 7)] {
        let (pole, links) = config(n, k, n as u64);
        let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
        for m in 0..=4u32 {
            let steps = m.to_string();
            let out = capdiv(&["refine", "--steps", &steps, s(&file)], None).ok_json();
            let (_, got) = parse_polar(&out);
            assert_eq!(got.len(), links_after(k, m), "links held n={n} k={k} m={m}");
            for l in &got {
                assert_eq!(l.len(), n << m, "valence n·2^M, n={n} m={m}");
            }
        }
    }
}

#[test]
fn rts_keeps_the_valence() {
    let dir = tempdir();
    let (pole, links) = config(7, 5, 3);
    let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
    let out = capdiv(
        &["refine", "--scheme", "rts", "--steps", "4", s(&file)],
        None,
    )
    .ok_json();
    let (_, got) = parse_polar(&out);
    assert_eq!(got.len(), 5);
    assert!(got.iter().all(|l| l.len() == 7));
}

/// The kernel's level-`m` net, computed directly.
fn kernel_f64(
    pole: [f64; 3],
    links: &[Vec<[f64; 3]>],
    m: u32,
    rts: bool,
    first: FirstStep,
) -> ([f64; 3], Vec<Vec<[f64; 3]>>) {
    let mut net: PolarNet<f64, 2048> = PolarNet::new(pole, links).unwrap();
    for _ in 0..m {
        if rts {
            net.rts_step().unwrap();
        } else {
            net.step(first).unwrap();
        }
    }
    let links = (1..=net.link_count())
        .map(|i| net.link(i).unwrap().iter().map(|p| p.0).collect())
        .collect();
    (net.pole().0, links)
}

#[test]
fn f64_output_equals_the_kernel_bit_for_bit() {
    let dir = tempdir();
    for (n, k, seed) in [(3, 5, 1), (5, 2, 2), (6, 4, 3), (12, 6, 4)] {
        let (pole, links) = config(n, k, seed);
        let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
        for m in [0u32, 1, 3, 5] {
            let steps = m.to_string();
            let cases: [(&[&str], bool, FirstStep); 3] = [
                (&[], false, FirstStep::Uniform),
                (&["--first-step", "plain"], false, FirstStep::Plain),
                (&["--scheme", "rts"], true, FirstStep::Uniform),
            ];
            for (extra, rts, first) in cases {
                let mut args = vec!["refine", "--steps", &steps];
                args.extend_from_slice(extra);
                args.push(s(&file));
                let (gp, gl) = parse_polar(&capdiv(&args, None).ok_json());
                let (kp, kl) = kernel_f64(pole, &links, m, rts, first);
                // Exact: serde_json prints f64 in shortest round-trip form.
                assert_eq!(gp, kp, "pole {args:?}");
                assert_eq!(gl, kl, "links {args:?}");
            }
        }
    }
}

#[test]
fn f32_output_equals_the_kernel_in_f32() {
    let dir = tempdir();
    let (pole, links) = config(5, 5, 9);
    let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
    let out = capdiv(
        &["refine", "--precision", "f32", "--steps", "3", s(&file)],
        None,
    )
    .ok_json();
    let (gp, gl) = parse_polar(&out);
    let p32 = pole.map(|c| c as f32);
    let l32: Vec<Vec<[f32; 3]>> = links
        .iter()
        .map(|l| l.iter().map(|p| p.map(|c| c as f32)).collect())
        .collect();
    let mut net: PolarNet<f32, 1024> = PolarNet::new(p32, &l32).unwrap();
    for _ in 0..3 {
        net.step(FirstStep::Uniform).unwrap();
    }
    // f32 printed shortest-round-trip, read back as f64 and rounded to f32.
    let as32 = |p: [f64; 3]| p.map(|c| c as f32);
    assert_eq!(as32(gp), net.pole().0);
    for (i, l) in gl.iter().enumerate() {
        let k = net.link(i + 1).unwrap();
        assert_eq!(l.len(), k.len());
        for (a, b) in l.iter().zip(k) {
            assert_eq!(as32(*a), b.0);
        }
    }
    // f32 numbers are printed as f32 (short), not widened to f64 digits.
    let text = capdiv(&["refine", "--precision", "f32", s(&file)], None).stdout_str();
    let longest = text
        .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == 'e'))
        .map(str::len)
        .max()
        .unwrap();
    assert!(longest <= 16, "f32 numbers printed long: {longest} chars");
}

#[test]
fn output_is_valid_input_and_steps_compose() {
    let dir = tempdir();
    let (pole, links) = config(5, 5, 11);
    let file = write_json(dir.path(), "in.json", &polar_json(pole, &links));
    let tol = 1e-12 * scale(&pole, &links);

    // RTS: three steps = two steps, printed, read back, one more step. The
    // state (pole, links 1..5, valence) is all there is, so this is exact.
    let two = capdiv(
        &["refine", "--scheme", "rts", "--steps", "2", s(&file)],
        None,
    );
    let mid = write_json(dir.path(), "mid.json", &two.ok_json());
    let a = capdiv(
        &["refine", "--scheme", "rts", "--steps", "1", s(&mid)],
        None,
    )
    .ok_json();
    let b = capdiv(
        &["refine", "--scheme", "rts", "--steps", "3", s(&file)],
        None,
    )
    .ok_json();
    assert_eq!(a, b);

    // C²PS: steps after the first use rules (1)–(3) (`plain`); the roots of
    // unity are rebuilt for the read-back valence instead of doubled, so
    // agreement is to round-off.
    let two = capdiv(&["refine", "--steps", "2", s(&file)], None);
    let mid = write_json(dir.path(), "mid.json", &two.ok_json());
    let (ap, al) = parse_polar(
        &capdiv(
            &["refine", "--first-step", "plain", "--steps", "2", s(&mid)],
            None,
        )
        .ok_json(),
    );
    let (bp, bl) = parse_polar(&capdiv(&["refine", "--steps", "4", s(&file)], None).ok_json());
    assert!(diff(&ap, &bp) <= tol);
    assert_eq!(al.len(), bl.len());
    for (x, y) in al.iter().zip(&bl) {
        assert_eq!(x.len(), y.len());
        for (p, q) in x.iter().zip(y) {
            assert!(diff(p, q) <= tol, "{p:?} vs {q:?}");
        }
    }
}

#[test]
fn dash_reads_stdin_and_output_file_matches_stdout() {
    let dir = tempdir();
    let (pole, links) = config(4, 3, 5);
    let value = polar_json(pole, &links);
    let file = write_json(dir.path(), "in.json", &value);
    let text = serde_json::to_vec_pretty(&value).unwrap();
    let from_file = capdiv(&["refine", "--steps", "2", s(&file)], None);
    let from_stdin = capdiv(&["refine", "--steps", "2", "-"], Some(&text));
    from_file.assert_ok();
    from_stdin.assert_ok();
    assert_eq!(from_file.stdout, from_stdin.stdout);

    let out = dir.path().join("out.json");
    let written = capdiv(&["refine", "--steps", "2", "-o", s(&out), s(&file)], None);
    written.assert_ok();
    assert!(written.stdout.is_empty());
    assert_eq!(std::fs::read(&out).unwrap(), from_file.stdout);

    // --pretty changes the layout only.
    let pretty = capdiv(&["refine", "--steps", "2", "--pretty", s(&file)], None);
    assert!(pretty.stdout.len() > from_file.stdout.len());
    assert_eq!(pretty.json(), from_file.json());
}

#[test]
fn example_file_refines() {
    let example = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/saddle.json");
    let (_, links) = parse_polar(&capdiv(&["refine", "--steps", "2", example], None).ok_json());
    assert_eq!(links.len(), 5);
    assert!(links.iter().all(|l| l.len() == 24));
}
