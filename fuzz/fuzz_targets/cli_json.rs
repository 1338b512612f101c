//! The CLI's JSON inputs (`polar`, `cnet`, `dnet`, `mesh`) through the
//! functions the commands use (`input::parse`, `surface::read_mesh`), then the
//! commands' jobs on what parses: polar `refine` (C²PS and RTS, 2 steps),
//! `patches` (depth 2), `pole`; EG `refine` and `patches` (2 steps) and the
//! limit; a mesh through `surface::build` (depth 1–2) and its tessellation.
//! f64 and f32. Sizes are capped so each input runs in milliseconds.
//!
//! Oracle: no panic; every failure is a `CliError`; for inputs whose
//! coordinates are at most 1e30 the numeric jobs (refine, patches, mesh
//! surface) do not end in `NonFiniteResult`.
#![no_main]

use capdiv::FirstStep;
use capdiv_cli::args::Scheme;
use capdiv_cli::commands::{eg, patches, pole, refine, surface};
use capdiv_cli::input::{parse, EgInput, Input, Source};
use capdiv_cli::CliError;
use libfuzzer_sys::fuzz_target;

const NAME: &str = "fuzz.json";
/// Coordinates up to this size must give finite results (f32 range 3.4e38).
const SMALL: f64 = 1e30;

fn small(points: impl IntoIterator<Item = [f64; 3]>) -> bool {
    points
        .into_iter()
        .all(|p| p.iter().all(|c| c.is_finite() && c.abs() <= SMALL))
}

fn not_nonfinite<T>(r: &Result<T, CliError>, expect_finite: bool, what: &str) {
    if expect_finite {
        if let Err(e @ CliError::NonFiniteResult { .. }) = r {
            panic!("{what}: {e} for coordinates within {SMALL}");
        }
    }
}

fn polar(p: &capdiv_cli::input::PolarInput) {
    let n = p.links.first().map_or(0, Vec::len);
    if n > 256 || p.links.len() > 16 {
        return;
    }
    let fin = small(p.links.iter().flatten().copied().chain([p.pole]));
    for first in [FirstStep::Uniform, FirstStep::Plain] {
        not_nonfinite(
            &refine::refine::<f64>(NAME, p, Scheme::C2ps, 2, first),
            fin,
            "refine c2ps f64",
        );
        not_nonfinite(
            &refine::refine::<f32>(NAME, p, Scheme::C2ps, 2, first),
            fin,
            "refine c2ps f32",
        );
    }
    not_nonfinite(
        &refine::refine::<f64>(NAME, p, Scheme::Rts, 2, FirstStep::Uniform),
        fin,
        "rts",
    );
    assert!(refine::refine::<f64>(NAME, p, Scheme::Eg, 1, FirstStep::Uniform).is_err());
    not_nonfinite(
        &patches::collect::<f64>(NAME, p, 2, FirstStep::Uniform),
        fin,
        "patches f64",
    );
    not_nonfinite(
        &patches::collect::<f32>(NAME, p, 2, FirstStep::Uniform),
        fin,
        "patches f32",
    );
    let _ = pole::pole::<f64>(NAME, p);
    let _ = pole::pole::<f32>(NAME, p);
}

fn eg_input(input: &Input, e: &EgInput, points: Vec<[f64; 3]>) {
    if e.valence() > 16 {
        return;
    }
    let fin = small(points);
    for steps in [0, 2] {
        not_nonfinite(
            &refine::refine_eg::<f64>(NAME, e, steps, None),
            fin,
            "refine eg f64",
        );
        not_nonfinite(
            &refine::refine_eg::<f32>(NAME, e, steps, None),
            fin,
            "refine eg f32",
        );
    }
    not_nonfinite(
        &patches::collect_eg::<f64>(NAME, e, 2, None),
        fin,
        "patches eg f64",
    );
    not_nonfinite(
        &patches::collect_eg::<f32>(NAME, e, 2, None),
        fin,
        "patches eg f32",
    );
    let _ = pole::eg_limit::<f64>(NAME, input);
    let _ = pole::eg_limit::<f32>(NAME, input);
    let _ = eg::dnet::<f64>(NAME, e);
}

fn mesh(text: &str, depth: u32) {
    let source = Source {
        name: NAME.into(),
        text: text.into(),
    };
    let Ok(m) = surface::read_mesh(&source) else {
        return;
    };
    if m.vertices.len() > 300
        || m.faces.len() > 300
        || m.faces.iter().map(Vec::len).sum::<usize>() > 1500
    {
        return;
    }
    let fin = small(m.vertices.iter().copied());
    let r = surface::build::<f64>(NAME, &m, depth, &[], "f64");
    not_nonfinite(&r, fin, "surface f64");
    if let Ok(s) = &r {
        // (A few hundred patches: running out of memory here is a bug.)
        let t = surface::tessellate_surface(s, &m, 2, surface::WELD_F64, None)
            .expect("tessellation of a small surface");
        let _ = surface::closed_text(&t.info.closed);
    }
    let r32 = surface::build::<f32>(NAME, &m, depth, &[], "f32");
    not_nonfinite(&r32, fin, "surface f32");
}

fuzz_target!(|data: &[u8]| one(data));

fn one(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let depth = 1 + (data.len() % 2) as u32;
    let parsed = parse(NAME, text);
    // `Source::parse` (the single-configuration commands) refuses meshes.
    let via_source = Source {
        name: NAME.into(),
        text: text.into(),
    }
    .parse();
    match (&parsed, &via_source) {
        (Ok(Input::Mesh(_)), Err(CliError::WrongKind { .. })) => {}
        (Ok(_), Ok(_)) | (Err(_), Err(_)) => {}
        (a, b) => panic!("parse {:?} vs Source::parse {:?}", a.is_ok(), b.is_ok()),
    }
    match parsed {
        Ok(Input::Polar(p)) => polar(&p),
        Ok(input @ Input::Cnet(_)) | Ok(input @ Input::Dnet(_)) => {
            let points: Vec<[f64; 3]> = match &input {
                Input::Cnet(c) => c
                    .sectors
                    .iter()
                    .flatten()
                    .copied()
                    .chain([c.center])
                    .collect(),
                Input::Dnet(d) => d.sectors.iter().flatten().copied().chain(d.c0).collect(),
                _ => Vec::new(),
            };
            let e = input.clone().into_eg(NAME, "fuzz").expect("EG kind");
            eg_input(&input, &e, points);
        }
        Ok(Input::Mesh(_)) => mesh(text, depth),
        Err(_) => {
            // OBJ text goes the same way as `capdiv surface` takes it.
            mesh(text, depth);
        }
    }
}
