//! `capdiv compare`: the same input under every scheme that applies, side
//! by side in one labelled PNG, same view (one fit for all panels, or one
//! `--focus` frame) and, for curvature maps, one colour scale: polar — C²PS,
//! RTS, Catmull-Clark; c-net — EG, Catmull-Clark; d-net — EG; mesh — the
//! default pipeline, Catmull-Clark.
//!
//! A panel is labelled by what it used: the scheme, for a mesh the caps it
//! got (the default pipeline falls back to Catmull-Clark caps where C²PS or
//! EG does not apply), and with `--focus V` the cap at `V`. Panels that
//! draw the same surface are named in a note on stderr.

use super::render::{camera, framed, hole_only, png_bytes};
use super::Outcome;
use crate::args::CompareArgs;
use crate::error::CliError;
use crate::focus::{focus_label, vertex_index};
use crate::output::Sink;
use crate::picture::draw;
use crate::shape::{build, drawable, override_boundary, read_any, schemes_for, Shape};

/// Runs the command.
pub fn run(args: &CompareArgs) -> Result<Outcome, CliError> {
    let (name, mut input, naming) = read_any(&args.picture.file)?;
    override_boundary(&name, &mut input, args.picture.boundary)?;
    let mut shapes: Vec<Shape> = schemes_for(&input)
        .into_iter()
        .map(|s| build(&name, &input, Some(s), args.picture.depth))
        .collect::<Result<_, _>>()
        .map_err(|e: CliError| e.named(&naming))?;
    for s in &shapes {
        drawable(&name, s, args.picture.depth)?;
    }
    let (mut cam, shading) = camera(&args.picture);
    // Framed on the first (the input's default) scheme's cap.
    cam.focus = match shapes.first() {
        Some(first) => framed(&name, &input, &naming, first, &args.picture)?,
        None => None,
    };
    if let Some(number) = args.picture.focus {
        let index = vertex_index(&name, &input, &naming, number)?;
        for s in &mut shapes {
            s.label = focus_label(s, index, number);
        }
    }
    let report = same_surfaces(&shapes);
    let refs: Vec<&Shape> = shapes.iter().collect();
    let pic = draw(&refs, &cam, shading, true).map_err(CliError::out_of_memory_in(&name))?;
    let mut outcome = Outcome::new(png_bytes(&pic)?, Sink::File(args.picture.output.clone()));
    outcome.report = report + &hole_only(&pic, &args.picture);
    Ok(outcome)
}

/// A note naming the panels (1-based, left to right) that draw the same
/// patches, or nothing.
fn same_surfaces(shapes: &[Shape]) -> String {
    let mut out = String::new();
    for (i, a) in shapes.iter().enumerate() {
        for (j, b) in shapes.iter().enumerate().skip(i + 1) {
            let same = a.patches.len() == b.patches.len()
                && a.patches
                    .iter()
                    .zip(&b.patches)
                    .all(|(p, q)| p.geometry() == q.geometry());
            if same {
                out += &format!(
                    "note: panels {} and {} draw the same surface ({})\n",
                    i + 1,
                    j + 1,
                    b.label
                );
            }
        }
    }
    out
}
