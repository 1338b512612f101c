//! `capdiv demo`: refines the built-in samples ([`crate::samples`]) with C²PS
//! (f64, first step uniform), writes `<name>.obj` (patches through the
//! sample's depth, tessellated), `<name>.png` (a shaded preview of that mesh,
//! rings coloured by level) and `<name>.json` (the level-0 input, usable with
//! the other commands) to the output directory, and prints a summary:
//! limit point, curvature at the pole against the sampled surface's,
//! patch counts, time taken.
//!
//! Each file is written atomically; the summary is printed once all samples
//! have succeeded.

use super::patches::{collect, png_bytes};
use super::pole::pole;
use super::Outcome;
use crate::args::DemoArgs;
use crate::error::CliError;
use crate::output::{to_json, write_atomic, Sink};
use crate::samples::{demo_samples, Sample};
use capdiv::FirstStep;
use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

/// Grid segments per patch side in the demo's OBJ files.
pub const DEMO_GRID: usize = 4;

/// Runs the command.
pub fn run(args: &DemoArgs) -> Result<Outcome, CliError> {
    let start = Instant::now();
    std::fs::create_dir_all(&args.out).map_err(|e| CliError::Io {
        path: args.out.display().to_string(),
        message: e.to_string(),
    })?;
    let mut text = String::new();
    let _ = writeln!(
        text,
        "capdiv demo: C2PS polar subdivision (spec C2PS.md), f64, first step 'uniform' (§6)"
    );
    let _ = writeln!(text, "writing to {}/\n", args.out.display());
    for sample in demo_samples() {
        one(sample, &args.out, &mut text)?;
    }
    let _ = writeln!(
        text,
        "total time {:.1} ms",
        start.elapsed().as_secs_f64() * 1e3
    );
    Ok(Outcome {
        bytes: text.into_bytes(),
        sink: Sink::Stdout,
    })
}

fn one(sample: Sample, dir: &Path, text: &mut String) -> Result<(), CliError> {
    let start = Instant::now();
    let name = sample.name;
    let input = &sample.input;
    let n = input.links.first().map_or(0, Vec::len);
    let jet = pole::<f64>(name, input)?;
    let set = collect::<f64>(name, input, sample.depth, FirstStep::Uniform)?;
    let obj_path = dir.join(format!("{name}.obj"));
    let title = format!("capdiv demo: {name}, {}", sample.surface);
    let mesh = set.to_mesh(DEMO_GRID);
    let obj = set.to_obj(&mesh, DEMO_GRID, &title);
    let png = png_bytes(&mesh)?;
    let compute = start.elapsed();
    write_atomic(&obj_path, obj.as_bytes())?;
    let png_path = dir.join(format!("{name}.png"));
    write_atomic(&png_path, &png)?;
    let json_path = dir.join(format!("{name}.json"));
    let mut json_input = serde_json::to_value(input).unwrap_or_default();
    if let Some(obj) = json_input.as_object_mut() {
        obj.insert("kind".into(), "polar".into());
    }
    write_atomic(&json_path, &to_json(&json_input, false))?;
    let total = start.elapsed();

    let a = sample.analytic;
    let w = |label: &str, value: String| format!("  {label:<20}{value}\n");
    let mut s = format!("{name}: {}\n", sample.surface);
    s += &w(
        "input",
        format!(
            "valence n = {n}, {} links; refined to level {} (valence {})",
            input.links.len(),
            sample.depth,
            set.valence
        ),
    );
    s += &w(
        "limit point",
        format!("{} (pole q00 = {})", fmt3(&jet.limit), fmt3(&input.pole)),
    );
    s += &w("normal", fmt3(&jet.normal));
    s += &w(
        "Gaussian curvature",
        compare(jet.gaussian_curvature, a.gaussian),
    );
    s += &w("mean curvature", compare(jet.mean_curvature, a.mean));
    s += &w(
        "principal curv.",
        format!(
            "{:.6}, {:.6}",
            tidy(jet.principal_curvatures[0]),
            tidy(jet.principal_curvatures[1])
        ),
    );
    s += &w("note", sample.note.to_string());
    s += &w("patches", set.describe());
    s += &w(
        "files",
        format!(
            "{} ({} vertices, {} quads), {}, {}",
            obj_path.display(),
            mesh.positions.len(),
            mesh.quads.len(),
            png_path.display(),
            json_path.display()
        ),
    );
    s += &w(
        "time",
        format!(
            "{:.1} ms refine + tessellate + render, {:.1} ms with writing",
            compute.as_secs_f64() * 1e3,
            total.as_secs_f64() * 1e3
        ),
    );
    text.push_str(&s);
    text.push('\n');
    Ok(())
}

fn fmt3(p: &[f64; 3]) -> String {
    let [x, y, z] = p.map(tidy);
    format!("[{x:.6}, {y:.6}, {z:.6}]")
}

/// Round-off below the printed digits shown as 0 (not `-0.000000`).
fn tidy(v: f64) -> f64 {
    if v.abs() < 5e-7 {
        0.0
    } else {
        v
    }
}

/// `got` against the sampled surface's `want`, with the ratio when defined.
fn compare(got: f64, want: f64) -> String {
    let ratio = if want != 0.0 {
        format!(", ratio {:.4}", got / want)
    } else {
        String::new()
    };
    format!(
        "{:.6}  (sampled surface: {want:.6}, diff {:+.2e}{ratio})",
        tidy(got),
        got - want
    )
}
