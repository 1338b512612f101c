//! `capdiv compare`: the same input under every scheme that applies, side
//! by side in one labelled PNG, same view (one fit for all panels) and, for
//! curvature maps, one colour scale: polar — C²PS, RTS, Catmull-Clark;
//! c-net — EG, Catmull-Clark; d-net — EG; mesh — the default pipeline
//! (C²PS/EG), Catmull-Clark.

use super::render::{camera, framed, png_bytes};
use super::Outcome;
use crate::args::CompareArgs;
use crate::error::CliError;
use crate::output::Sink;
use crate::picture::draw;
use crate::shape::{build, drawable, override_boundary, read_any, schemes_for, Shape};

/// Runs the command.
pub fn run(args: &CompareArgs) -> Result<Outcome, CliError> {
    let (name, mut input, naming) = read_any(&args.picture.file)?;
    override_boundary(&name, &mut input, args.picture.boundary)?;
    let shapes: Vec<Shape> = schemes_for(&input)
        .into_iter()
        .map(|s| build(&name, &input, Some(s), args.picture.depth))
        .collect::<Result<_, _>>()
        .map_err(|e: CliError| e.named(&naming))?;
    for s in &shapes {
        drawable(&name, s, args.picture.depth)?;
    }
    let refs: Vec<&Shape> = shapes.iter().collect();
    let (mut cam, shading) = camera(&args.picture);
    // Framed on the first (the input's default) scheme's cap.
    cam.focus = match shapes.first() {
        Some(first) => framed(&name, &input, &naming, first, &args.picture)?,
        None => None,
    };
    let pic = draw(&refs, &cam, shading, true);
    Ok(Outcome::new(
        png_bytes(&pic)?,
        Sink::File(args.picture.output.clone()),
    ))
}
