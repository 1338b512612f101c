//! `capdiv demo`: refines the built-in samples ([`crate::samples`]) with C²PS
//! (f64, first step uniform) and with EG (c-nets of valence 3 and 5, spec
//! docs/math/eg.md), writes `<name>.obj` (patches through the sample's depth,
//! tessellated), `<name>.png` (a shaded preview of that mesh, rings coloured
//! by level) and `<name>.json` (the level-0 input, usable with the other
//! commands) to the output directory, and prints a summary: limit point
//! (C²PS: curvature at the pole against the sampled surface's; EG: `c0` by
//! (3) and how close the last ring has come to it), patch counts, time taken.
//!
//! Then whole meshes from [`capdiv_mesh::samples`] through `capdiv surface`'s
//! pipeline ([`super::surface`], depth [`MESH_DEPTH`], grid [`MESH_GRID`]):
//! `<name>.obj` (welded, closed), `<name>.png`, `<name>.json` (the mesh as a
//! `kind: "mesh"` input) and `<name>.summary.json` (the summary `surface`
//! prints), and a line per mesh: caps, patches, refinement, closedness.
//!
//! Each file is written atomically; the summary is printed once all samples
//! have succeeded.

use super::patches::{collect, collect_eg, png_bytes, PatchSet};
use super::pole::pole;
use super::surface::WELD_F64;
use super::Outcome;
use crate::args::DemoArgs;
use crate::camera::Up;
use crate::error::CliError;
use crate::input::EgInput;
use crate::json::to_json;
use crate::output::{write_path, Sink};
use crate::samples::{demo_samples, eg_samples, EgSample, Sample};
use capdiv::{FirstStep, TensorPatch};
use capdiv_mesh::tessellate::PatchGeometry;
use capdiv_mesh::{samples, MeshInput};
use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

/// Grid segments per patch side in the demo's OBJ files.
pub const DEMO_GRID: usize = 4;

/// Rings every cap of the whole-mesh samples emits.
pub const MESH_DEPTH: u32 = 4;

/// Grid segments per patch side of the whole-mesh samples.
pub const MESH_GRID: usize = 3;

/// The whole-mesh samples: name, description, mesh.
pub fn mesh_samples() -> Vec<(&'static str, &'static str, MeshInput)> {
    vec![
        (
            "globe",
            "unit sphere as a latitude-longitude grid, two poles of valence 8",
            samples::globe(8, 9),
        ),
        (
            "mushroom",
            "surface of revolution, poles of valence 12 at the cap and the foot",
            samples::mushroom(),
        ),
        (
            "hand",
            "palm, four fingers and a thumb with polar finger tips (n = 8), wrist pole n = 26",
            samples::hand(),
        ),
        (
            "rounded-cube",
            "cube of 3x3 grids bulged towards a sphere: eight valence-3 points",
            samples::rounded_cube(3),
        ),
        (
            "cube",
            "the plain cube: valence-3 neighbours, EG caps one refinement level in",
            samples::cube(),
        ),
        (
            "two-beam-corner",
            "L-shaped corner of two square beams: valence 5 inside, valence 3 outside",
            samples::two_beam_corner(),
        ),
    ]
}

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
        "capdiv demo: C2PS polar subdivision (docs/math/c2ps.md), f64, first step 'uniform' (paper §6)"
    );
    let _ = writeln!(
        text,
        "curvatures: the limit surface at the pole against the surface the control points\n\
         were sampled from; they differ unless the scheme reproduces that surface (see each note)"
    );
    let _ = writeln!(text, "writing to {}/\n", args.out.display());
    for sample in demo_samples() {
        one(sample, &args.out, &mut text)?;
    }
    let _ = writeln!(
        text,
        "EG: Evolving Guide subdivision (docs/math/eg.md) of c-nets, f64, built-in rules (§7)\n"
    );
    for sample in eg_samples() {
        one_eg(sample, &args.out, &mut text)?;
    }
    let _ = writeln!(
        text,
        "Whole meshes (capdiv surface): regular faces B-spline, polar fans C2PS, \
         extraordinary points EG (n = 3, 5) or Catmull-Clark; depth {MESH_DEPTH}, grid {MESH_GRID}, f64\n"
    );
    for (name, what, mesh) in mesh_samples() {
        one_mesh(name, what, &mesh, &args.out, &mut text)?;
    }
    let _ = writeln!(
        text,
        "total time {:.1} ms",
        start.elapsed().as_secs_f64() * 1e3
    );
    Ok(Outcome::new(text.into_bytes(), Sink::Stdout))
}

/// A sample's patches as the demo writes them.
struct Drawn {
    /// The welded OBJ.
    obj: String,
    /// The PNG preview, patch boundaries drawn.
    png: Vec<u8>,
    /// The OBJ's vertices and faces.
    counts: (usize, usize),
}

/// [`Drawn`] of a sample's patches.
fn obj_and_png<const K: usize>(
    set: &PatchSet<f64, K>,
    name: &str,
    title: &str,
) -> Result<Drawn, CliError>
where
    TensorPatch<f64, K>: Into<PatchGeometry<f64>>,
{
    let mesh = set.tessellate(name, DEMO_GRID, WELD_F64)?;
    let obj = set.to_obj(name, &mesh, DEMO_GRID, WELD_F64, title)?;
    let drawn = set.tessellate_with_parameters(name, DEMO_GRID, WELD_F64)?;
    let png = png_bytes(name, &drawn, Some(&drawn.uvs), Up::Z)?;
    Ok(Drawn {
        obj,
        png,
        counts: (mesh.positions.len(), mesh.faces.len()),
    })
}

fn one(sample: Sample, dir: &Path, text: &mut String) -> Result<(), CliError> {
    let start = Instant::now();
    let name = sample.name;
    let input = &sample.input;
    let n = input.links.first().map_or(0, Vec::len);
    let jet = pole::<f64>(name, input)?;
    let set = collect::<f64>(name, input, sample.depth, FirstStep::Uniform)?;
    let title = format!("capdiv demo: {name}, {}", sample.surface);
    let Drawn { obj, png, counts } = obj_and_png(&set, name, &title)?;
    let compute = start.elapsed();
    let files = write_files(dir, name, &obj, &png, input, "polar", counts)?;
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
        format!(
            "{} (pole q00 = {})",
            point_6_digits(&jet.limit),
            point_6_digits(&input.pole)
        ),
    );
    s += &w("normal", point_6_digits(&jet.normal));
    s += &w(
        "Gaussian curvature",
        compare(jet.gaussian_curvature, a.gaussian),
    );
    s += &w("mean curvature", compare(jet.mean_curvature, a.mean));
    s += &w(
        "principal curv.",
        format!(
            "{:.6}, {:.6}",
            zero_below_6_digits(jet.principal_curvatures[0]),
            zero_below_6_digits(jet.principal_curvatures[1])
        ),
    );
    s += &w("note", sample.note.to_string());
    s += &w("patches", set.describe());
    s += &w("files", files);
    s += &w("time", times(compute, total));
    text.push_str(&s);
    text.push('\n');
    Ok(())
}

/// One EG sample: c-net → d-net (§3, `c0` by (3)), `depth` steps, the rings
/// of levels 1..=depth as OBJ and PNG, the c-net as JSON.
fn one_eg(sample: EgSample, dir: &Path, text: &mut String) -> Result<(), CliError> {
    let start = Instant::now();
    let name = sample.name;
    let input = EgInput::Cnet(sample.input.clone());
    let n = sample.input.sectors.len();
    let set = collect_eg::<f64>(name, &input, sample.depth, None)?;
    let c0 = super::eg::dnet::<f64>(name, &input)?.c0().0;
    let title = format!("capdiv demo: {name}, {}", sample.surface);
    let Drawn { obj, png, counts } = obj_and_png(&set, name, &title)?;
    let compute = start.elapsed();
    let files = write_files(dir, name, &obj, &png, &sample.input, "cnet", counts)?;
    let total = start.elapsed();

    // Ring M's innermost surface points: the corner (u, v) = (0, 0) of each
    // sector's [½,1]² patch, at (1, 1)·2^−M in level-0 c-units. A Bézier
    // corner lies on the surface.
    let approach = set
        .patches
        .iter()
        .skip(set.patches.len().saturating_sub(3 * n))
        .skip(2)
        .step_by(3)
        .map(|p| {
            let b = p.patch.points[0][0].0;
            (0..3).map(|k| (b[k] - c0[k]).powi(2)).sum::<f64>().sqrt()
        })
        .fold(0.0f64, f64::max);

    let w = |label: &str, value: String| format!("  {label:<20}{value}\n");
    let mut s = format!("{name}: {}\n", sample.surface);
    s += &w(
        "input",
        format!(
            "c-net of valence n = {n} (6n + 1 = {} nodes); {} EG steps",
            6 * n + 1,
            sample.depth
        ),
    );
    s += &w(
        "limit point",
        format!(
            "{} (c0 by (3); center node e = {})",
            point_6_digits(&c0),
            point_6_digits(&sample.input.center)
        ),
    );
    s += &w(
        "ring approach",
        format!(
            "ring {} reaches {:.3e} from c0 ((1,1)·2^-{} c-units from the center)",
            sample.depth, approach, sample.depth
        ),
    );
    s += &w("note", sample.note.to_string());
    s += &w(
        "patches",
        format!("{} (3n = {} per ring)", set.describe(), 3 * n),
    );
    s += &w("files", files);
    s += &w("time", times(compute, total));
    text.push_str(&s);
    text.push('\n');
    Ok(())
}

/// One whole mesh through `capdiv surface`'s pipeline: OBJ, PNG, the mesh as
/// JSON input and the summary as JSON.
fn one_mesh(
    name: &str,
    what: &str,
    mesh: &MeshInput,
    dir: &Path,
    text: &mut String,
) -> Result<(), CliError> {
    use super::surface::{build, closed_text, obj_text, tessellate_surface, WELD_F64};
    let start = Instant::now();
    let surface = build::<f64>(name, mesh, MESH_DEPTH, &[], "f64")?;
    let tess = tessellate_surface(&surface, mesh, MESH_GRID, WELD_F64, None)
        .map_err(CliError::out_of_memory_in(name))?;
    let title = format!("capdiv demo: {name}, {what}");
    let obj =
        obj_text(&tess, &surface.summary, &title).map_err(CliError::out_of_memory_in(name))?;
    let png = png_bytes(name, &tess.mesh, None, Up::Z)?;
    let compute = start.elapsed();
    let obj_path = dir.join(format!("{name}.obj"));
    write_path(&obj_path, obj.as_bytes())?;
    let png_path = dir.join(format!("{name}.png"));
    write_path(&png_path, &png)?;
    let json_path = dir.join(format!("{name}.json"));
    let mut input = serde_json::to_value(crate::input::MeshJson::of(mesh)).unwrap_or_default();
    if let Some(o) = input.as_object_mut() {
        o.insert("kind".into(), "mesh".into());
    }
    write_path(&json_path, &to_json(&input, false))?;
    let summary_path = dir.join(format!("{name}.summary.json"));
    write_path(&summary_path, &to_json(&surface.summary, true))?;
    let total = start.elapsed();

    let s = &surface.summary;
    let caps: Vec<String> = s
        .caps
        .iter()
        .map(|c| format!("{} x{} n={}", c.scheme, c.count, c.valence))
        .collect();
    let p = &s.patches;
    let i = &tess.info;
    let w = |label: &str, value: String| format!("  {label:<20}{value}\n");
    let mut out = format!("{name}: {what}\n");
    out += &w(
        "input",
        format!("{} vertices, {} faces", s.input.vertices, s.input.faces),
    );
    out += &w("caps", caps.join(", "));
    out += &w(
        "patches",
        format!(
            "{} ({} regular, {} c2ps, {} eg, {} catmull-clark)",
            p.total, p.regular, p.c2ps, p.eg, p.catmull_clark
        ),
    );
    out += &w(
        "refinement",
        format!(
            "{} whole-mesh step(s); {} input faces refined; {} uncovered",
            s.refinement_steps,
            s.needed_refinement.len(),
            s.uncovered.len()
        ),
    );
    out += &w(
        "surface",
        format!(
            "{} vertices, {} triangles, {} quads; {}",
            i.vertices,
            i.triangles,
            i.quads,
            closed_text(&i.closed)
        ),
    );
    out += &w(
        "files",
        format!(
            "{}, {}, {}, {}",
            obj_path.display(),
            png_path.display(),
            json_path.display(),
            summary_path.display()
        ),
    );
    out += &w("time", times(compute, total));
    text.push_str(&out);
    text.push('\n');
    Ok(())
}

/// Writes `<name>.obj`, `<name>.png` and `<name>.json` (the input with its
/// `kind`); returns the summary line.
fn write_files<T: serde::Serialize>(
    dir: &Path,
    name: &str,
    obj: &str,
    png: &[u8],
    input: &T,
    kind: &str,
    (vertices, faces): (usize, usize),
) -> Result<String, CliError> {
    let obj_path = dir.join(format!("{name}.obj"));
    write_path(&obj_path, obj.as_bytes())?;
    let png_path = dir.join(format!("{name}.png"));
    write_path(&png_path, png)?;
    let json_path = dir.join(format!("{name}.json"));
    let mut json_input = serde_json::to_value(input).unwrap_or_default();
    if let Some(obj) = json_input.as_object_mut() {
        obj.insert("kind".into(), kind.into());
    }
    write_path(&json_path, &to_json(&json_input, false))?;
    Ok(format!(
        "{} ({vertices} vertices, {faces} faces, welded), {}, {}",
        obj_path.display(),
        png_path.display(),
        json_path.display()
    ))
}

fn times(compute: std::time::Duration, total: std::time::Duration) -> String {
    format!(
        "{:.1} ms refine + tessellate + render, {:.1} ms with writing",
        compute.as_secs_f64() * 1e3,
        total.as_secs_f64() * 1e3
    )
}

/// A point with 6 decimals per coordinate.
fn point_6_digits(p: &[f64; 3]) -> String {
    let [x, y, z] = p.map(zero_below_6_digits);
    format!("[{x:.6}, {y:.6}, {z:.6}]")
}

/// Round-off below the printed digits shown as 0 (not `-0.000000`).
fn zero_below_6_digits(v: f64) -> f64 {
    if v.abs() < 5e-7 {
        0.0
    } else {
        v
    }
}

/// The limit's `got` against the sampled surface's `want`, with their
/// ratio when defined: two surfaces compared, not a result and its error.
fn compare(got: f64, want: f64) -> String {
    let ratio = if want != 0.0 {
        format!(", ratio {:.4}", got / want)
    } else {
        String::new()
    };
    format!(
        "{:.6} at the limit; the sampled surface has {:.6}{ratio}",
        zero_below_6_digits(got),
        zero_below_6_digits(want)
    )
}
