//! `capdiv render`: one input under one scheme as a PNG, shaded per pixel
//! from the exact patches ([`crate::picture`]): plain, highlight lines, or
//! Gaussian / mean curvature with a legend. Inputs and schemes as
//! [`crate::shape`]; the last hole is hatched. The whole surface is in
//! view, or with `--focus V` the neighbourhood of vertex `V`'s cap
//! ([`crate::focus`]); the camera is [`crate::camera`]'s, the highlight
//! lines [`crate::stripes`]'.

use super::Outcome;
use crate::args::{PictureArgs, RenderArgs, Shade};
use crate::error::{CliError, Naming};
use crate::focus::focus;
use crate::input::Input;
use crate::output::Sink;
use crate::picture::{draw, png, Camera, Focus, LightLines, Picture, Shading};
use crate::shape::{build, drawable, override_boundary, read_any, Shape};

/// The picture options as the drawing's.
pub fn camera(p: &PictureArgs) -> (Camera, Shading) {
    let cam = Camera {
        width: p.size.0,
        height: p.size.1,
        azimuth: p.view.0,
        elevation: p.view.1,
        grid: p.grid as usize,
        up: p.up.into(),
        focus: None,
    };
    let shading = match p.shade {
        Shade::Plain => Shading::Plain,
        Shade::Highlight => Shading::Highlight(LightLines {
            direction: p.light,
            lines: p.lines,
        }),
        Shade::Gauss => Shading::Gauss,
        Shade::Mean => Shading::Mean,
    };
    (cam, shading)
}

/// The region `--focus` frames (its vertex looked up in `shape`), if asked.
pub fn framed(
    name: &str,
    input: &Input,
    naming: &Naming,
    shape: &Shape,
    p: &PictureArgs,
) -> Result<Option<Focus>, CliError> {
    p.focus
        .map(|v| focus(name, input, naming, shape, v, p.zoom))
        .transpose()
}

/// A note for each panel (1-based) a `--focus` frame fills with the cap's
/// hole alone, or nothing.
pub fn hole_only(pic: &Picture, p: &PictureArgs) -> String {
    if p.focus.is_none() {
        return String::new();
    }
    let mut out = String::new();
    for (k, &n) in pic.patch_samples.iter().enumerate() {
        if n == 0 {
            out += &format!(
                "note: panel {}: at zoom {} only the cap's hole is in view (depth {}): \
                 raise --depth or lower --zoom\n",
                k + 1,
                p.zoom,
                p.depth
            );
        }
    }
    out
}

/// PNG bytes, or the encoder's error.
pub fn png_bytes(pic: &crate::picture::Picture) -> Result<Vec<u8>, CliError> {
    png(pic).map_err(|e| CliError::Io {
        path: "<png encoder>".into(),
        message: e.to_string(),
    })
}

/// Runs the command.
pub fn run(args: &RenderArgs) -> Result<Outcome, CliError> {
    let (name, mut input, naming) = read_any(&args.picture.file)?;
    override_boundary(&name, &mut input, args.picture.boundary)?;
    let shape =
        build(&name, &input, args.scheme, args.picture.depth).map_err(|e| e.named(&naming))?;
    drawable(&name, &shape, args.picture.depth)?;
    let (mut cam, shading) = camera(&args.picture);
    cam.focus = framed(&name, &input, &naming, &shape, &args.picture)?;
    let pic = draw(&[&shape], &cam, shading, false).map_err(CliError::out_of_memory_in(&name))?;
    let mut outcome = Outcome::new(png_bytes(&pic)?, Sink::File(args.picture.output.clone()));
    outcome.report = hole_only(&pic, &args.picture);
    Ok(outcome)
}
