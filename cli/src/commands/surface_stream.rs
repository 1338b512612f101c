//! `capdiv surface` written as it is produced: `--format obj` (f64) through
//! the streaming tessellator ([`StreamTessellator`]), `--format json`
//! (compact) patch by patch. Peak memory is the input, its plan and the
//! weld front (the open edges between the input faces done and those to
//! come, in the evaluator's breadth-first order), not the output. The output is the collected one's
//! ([`super::surface`]): OBJ with the same vertices, normals and faces in
//! the same order (faces follow their vertices instead of all coming last;
//! the counts and closedness come as comments at the end), JSON byte for
//! byte, compact or `--pretty`.
//!
//! Collected instead: `--precision f32` OBJ (welded where the f64 surface
//! welds, which needs both), OBJ of a mesh that is not a consistently
//! oriented manifold (the weld front relies on each edge having two sides),
//! a mesh with UVs, and the formats that need the whole surface (PNG,
//! glTF, STEP).

use super::patches::StreamOut;
use super::surface::{
    closed_text, report, run_scheme, weld_tolerance, CapJson, PatchJson, SchemeOptions, TessInfo,
    WELD_F64,
};
use super::Outcome;
use crate::args::{SurfaceArgs, SurfaceFormat, SurfaceScheme};
use crate::error::{CliError, Naming};
use crate::json::{Indent, TryBytes};
use crate::output::Sink;
use crate::table::Table;
use crate::text::{count, sig};
use capdiv_mesh::tessellate::{MeshSink, ObjWriter, StreamTessellator};
use capdiv_mesh::{mem, CapRecord, MeshInput, OutOfMemory, PatchRecord, SurfaceSink, Topology};
use std::io::Write;
use std::time::{Duration, Instant};

/// Whether `surface` streams this output (see the module doc).
pub fn streams(args: &SurfaceArgs, mesh: &MeshInput) -> bool {
    use crate::args::Precision;
    // Face-varying UVs go through the collected path only (its tessellation
    // splits welded vertices at seams; the streaming weld does not).
    if mesh.has_uvs() {
        return false;
    }
    match args.format() {
        SurfaceFormat::Json => true,
        SurfaceFormat::Obj => args.precision == Precision::F64 && Topology::new(mesh).is_ok(),
        _ => false,
    }
}

/// `fmt::Write` over an `io::Write`, keeping the first I/O error; `header`
/// goes first, with the first write (a surface refused as empty writes
/// nothing).
pub(crate) struct IoText<'a, W> {
    pub(crate) w: &'a mut W,
    pub(crate) header: String,
    pub(crate) error: Option<std::io::Error>,
}

impl<W: Write> std::fmt::Write for IoText<'_, W> {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        let header = std::mem::take(&mut self.header);
        let all = self
            .w
            .write_all(header.as_bytes())
            .and_then(|()| self.w.write_all(s.as_bytes()));
        all.map_err(|e| {
            self.error.get_or_insert(e);
            std::fmt::Error
        })
    }
}

fn io_error(args: &SurfaceArgs) -> impl Fn(std::io::Error) -> CliError + '_ {
    move |e| CliError::Io {
        path: args
            .output
            .as_ref()
            .map_or("<stdout>".into(), |p| p.display().to_string()),
        message: e.to_string(),
    }
}

fn options<'a>(args: &SurfaceArgs, tables: &'a [Table]) -> SchemeOptions<'a> {
    SchemeOptions {
        depth: args.depth,
        tables,
        precision: "f64",
        catmull_clark: args.scheme == SurfaceScheme::CatmullClark,
        max_patches: args
            .max_patches
            .unwrap_or(crate::args::DEFAULT_MAX_STREAMED_PATCHES),
        tolerance: args.tolerance,
        threads: args.threads.map(|t| t as usize),
    }
}

/// Tessellates the evaluator's patches into an OBJ writer as they come.
struct ObjStream<'a, W: std::fmt::Write> {
    tess: StreamTessellator<f64>,
    obj: &'a mut ObjWriter<W>,
    time: Duration,
}

impl<W: std::fmt::Write> SurfaceSink<f64> for ObjStream<'_, W> {
    fn patch(&mut self, p: &PatchRecord<f64>) {
        let start = Instant::now();
        self.tess
            .push(p, p.level, self.obj as &mut dyn MeshSink<f64>);
        self.time += start.elapsed();
    }
    fn cap(&mut self, _: &CapRecord<f64>) {
        let start = Instant::now();
        self.tess.end_group(self.obj as &mut dyn MeshSink<f64>);
        self.time += start.elapsed();
    }
}

/// `--format obj`, f64, streamed.
pub fn obj(
    name: &str,
    naming: &Naming,
    mesh: &MeshInput,
    tables: &[Table],
    args: &SurfaceArgs,
) -> Result<Outcome, CliError> {
    let io = io_error(args);
    let grid = args.grid as usize;
    let (tolerance, size) = weld_tolerance(mesh, WELD_F64);
    let mut out = StreamOut::open(args.output.as_deref())?;
    let title = format!(
        "capdiv surface --depth {} --tolerance {} --grid {grid} --precision f64 {name}",
        args.depth, args.tolerance
    );
    let weld = format!(
        "grid {grid}x{grid} per patch; welded within {} ({} x bounding-box size {})",
        sig(tolerance, 3),
        sig(WELD_F64, 3),
        sig(size, 6)
    );
    let text = IoText {
        w: &mut out,
        header: format!("# {title}\n# {weld}\n"),
        error: None,
    };
    let mut obj = ObjWriter::new(text, &[]);
    let mut sink = ObjStream {
        tess: StreamTessellator::new(grid, tolerance),
        obj: &mut obj,
        time: Duration::ZERO,
    };
    let result = run_scheme::<f64>(name, mesh, &options(args, tables), &mut sink).map(|(s, _)| s);
    let start = Instant::now();
    let s = sink.tess.finish(sink.obj);
    let (tess_time, time) = (sink.time, sink.time + start.elapsed());
    let mut summary = result?;
    if let Some(e) = sink.tess.refused() {
        return Err(CliError::out_of_memory(name, e.bytes));
    }
    if let Some(e) = obj.out.error.take() {
        return Err(io(e));
    }
    // The evaluation's time without the tessellation it fed.
    summary.times_ms.evaluation =
        (summary.times_ms.evaluation - tess_time.as_secs_f64() * 1e3).max(0.0);
    let info = TessInfo {
        grid,
        tolerance,
        factor: WELD_F64,
        size,
        vertices: s.vertices,
        triangles: s.triangles,
        quads: s.quads,
        degenerate_dropped: s.degenerate_dropped,
        closed: s.closed,
        time_ms: time.as_secs_f64() * 1e3,
    };
    let p = &summary.patches;
    let trailer = [
        format!(
            "{} ({} regular, {} c2ps, {} eg, {} catmull-clark), {}",
            count(p.total, "patch", "patches"),
            p.regular,
            p.c2ps,
            p.eg,
            p.catmull_clark,
            count(
                summary.caps.iter().map(|c| c.count).sum::<usize>(),
                "cap",
                "caps"
            )
        ),
        format!(
            "{}, {} ({}, {}); {}",
            count(s.vertices, "vertex", "vertices"),
            count(s.triangles + s.quads, "face", "faces"),
            count(s.triangles, "triangle", "triangles"),
            count(s.quads, "quad", "quads"),
            closed_text(&s.closed)
        ),
    ];
    for line in trailer {
        writeln!(out, "# {line}").map_err(&io)?;
    }
    out.commit().map_err(&io)?;
    let mut outcome = Outcome::new(Vec::new(), Sink::Stdout);
    if !args.quiet {
        outcome.report = report(name, &summary, Some(&info), naming);
        outcome.report.push_str(&format!(
            "  streamed     weld table at most {}, {} waiting for a normal at most\n",
            count(s.peak_weld, "vertex", "vertices"),
            count(s.peak_waiting, "vertex or face", "vertices and faces")
        ));
    }
    Ok(outcome)
}

/// Writes `{"patches": [...], "caps": [...], "summary": {...}}` a patch at
/// a time, compact or (with `indent`) pretty: the compact text of each
/// piece re-indented as it comes ([`Indent`]), the same text as the whole
/// document's. Caps, one per cap, are held for after the patches.
struct JsonStream<'a, R, W> {
    out: &'a mut W,
    patches: usize,
    caps: Vec<CapJson<R>>,
    error: Option<std::io::Error>,
    /// The first allocation refused (the caps' list, or the indentation).
    refused: Option<OutOfMemory>,
    /// One patch's compact text, and its indented text.
    line: TryBytes,
    indent: Option<(Indent, Vec<u8>)>,
}

impl<R: crate::Scalar, W: Write> JsonStream<'_, R, W> {
    /// Writes one piece of the compact document (indented when pretty).
    fn write(&mut self, compact: &[u8]) {
        let result = match &mut self.indent {
            Some((indent, text)) => {
                text.clear();
                match indent.feed(compact, text) {
                    Ok(()) => self.out.write_all(text),
                    Err(e) => {
                        self.refused = Some(e);
                        return;
                    }
                }
            }
            None => self.out.write_all(compact),
        };
        if let Err(e) = result {
            self.error = Some(e);
        }
    }
}

impl<R: crate::Scalar, W: Write> SurfaceSink<R> for JsonStream<'_, R, W> {
    fn patch(&mut self, p: &PatchRecord<R>) {
        if self.error.is_some() || self.refused.is_some() {
            return;
        }
        let mut line = std::mem::take(&mut self.line);
        line.clear();
        // Cannot fail but for the buffer: plain numbers and strings.
        let _ = line.write_all(if self.patches == 0 {
            b"{\"patches\":["
        } else {
            b","
        });
        let _ = serde_json::to_writer(&mut line, &PatchJson::new(p));
        self.patches += 1;
        match line.refused() {
            Some(e) => self.refused = Some(e),
            None => self.write(line.as_bytes()),
        }
        self.line = line;
    }
    fn cap(&mut self, c: &CapRecord<R>) {
        if self.refused.is_none() {
            if let Err(e) = mem::push(&mut self.caps, CapJson::new(c)) {
                self.refused = Some(e);
            }
        }
    }
}

/// `--format json` (compact or `--pretty`), f64 or f32, streamed.
pub fn json<R: crate::Scalar>(
    name: &str,
    naming: &Naming,
    mesh: &MeshInput,
    tables: &[Table],
    args: &SurfaceArgs,
    precision: &str,
) -> Result<Outcome, CliError> {
    let io = io_error(args);
    let mut out = StreamOut::open(args.output.as_deref())?;
    let mut sink = JsonStream::<R, _> {
        out: &mut out,
        patches: 0,
        caps: Vec::new(),
        error: None,
        refused: None,
        line: TryBytes::default(),
        indent: args.pretty.then(|| (Indent::default(), Vec::new())),
    };
    let mut opts = options(args, tables);
    opts.precision = precision;
    let (summary, _) = run_scheme::<R>(name, mesh, &opts, &mut sink)?;
    let memory = CliError::out_of_memory_in(name);
    if let Some(e) = sink.refused.take() {
        return Err(memory(e));
    }
    if let Some(e) = sink.error.take() {
        return Err(io(e));
    }
    let caps = std::mem::take(&mut sink.caps);
    let mut tail = TryBytes::default();
    // Cannot fail but for the buffer: plain numbers and strings.
    let _ = tail.write_all(b"],\"caps\":");
    let _ = serde_json::to_writer(&mut tail, &caps);
    let _ = tail.write_all(b",\"summary\":");
    let _ = serde_json::to_writer(&mut tail, &summary);
    let _ = tail.write_all(b"}");
    sink.write(&tail.into_result().map_err(&memory)?);
    if let Some(e) = sink.refused.take() {
        return Err(memory(e));
    }
    if let Some(e) = sink.error.take() {
        return Err(io(e));
    }
    out.write_all(b"\n").map_err(&io)?;
    out.commit().map_err(&io)?;
    let mut outcome = Outcome::new(Vec::new(), Sink::Stdout);
    if !args.quiet {
        outcome.report = report(name, &summary, None, naming);
    }
    Ok(outcome)
}
