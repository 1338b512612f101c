//! Output types (serialised with serde_json) and the all-or-nothing writers.
//!
//! Every command builds its whole output in memory first; nothing reaches
//! stdout or the output file before the command has succeeded. A new or
//! regular output file is written to a temporary sibling and renamed into
//! place, so a failure never leaves a partial file; FIFOs, devices and the
//! targets of links are written through ([`write_path`]).

use crate::error::CliError;
use crate::Scalar;
use capdiv::{DNet, NetStorage, Point3, PolarNetInner, PoleGeometry, PoleJet, TensorPatch};
use serde::Serialize;
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};

/// `true` for output that is not text: bytes that are not UTF-8 or hold a
/// NUL byte. Every text output (JSON, OBJ, glTF JSON) is UTF-8 without NUL;
/// a PNG's signature starts with the byte 0x89 (never UTF-8), a GLB's
/// version field holds NUL bytes.
pub fn is_binary(bytes: &[u8]) -> bool {
    bytes.contains(&0) || std::str::from_utf8(bytes).is_err()
}

/// The refusal of binary output on a terminal, with the way out.
fn binary_to_terminal(what: &str) -> CliError {
    CliError::Usage(format!(
        "refusing to write binary output (PNG, GLB) to a terminal ({what}): give -o FILE \
         or redirect it (> FILE)"
    ))
}

/// A polar configuration, the input schema (`kind: "polar"`).
#[derive(Clone, Debug, Serialize)]
pub struct PolarOutput<R> {
    /// Always `"polar"`.
    pub kind: &'static str,
    /// The pole `q00`.
    pub pole: [R; 3],
    /// Links 1..K (K ≤ 5, what the net holds).
    pub links: Vec<Vec<[R; 3]>>,
}

impl<R: Scalar> PolarOutput<R> {
    /// The configuration a net holds at its current level.
    pub fn of<S: NetStorage<R>>(net: &PolarNetInner<R, S>) -> Self {
        let links = (1..=net.link_count())
            .filter_map(|i| net.link(i))
            .map(|l| l.iter().map(|p| p.0).collect())
            .collect();
        PolarOutput {
            kind: "polar",
            pole: net.pole().0,
            links,
        }
    }

    /// `true` when every coordinate is finite.
    pub fn is_finite(&self) -> bool {
        finite(&self.pole) && self.links.iter().flatten().all(finite)
    }
}

/// An EG d-net, the `dnet` input schema (docs/math/eg.md §2): `c0` and `n`
/// sectors of 12 nodes in the order `00 10 20 30 01 11 21 31 02 12 22 32`.
#[derive(Clone, Debug, Serialize)]
pub struct DnetOutput<R> {
    /// Always `"dnet"`.
    pub kind: &'static str,
    /// The limit point (fixed for all steps, §4).
    pub c0: [R; 3],
    /// The sectors, counter-clockwise.
    pub sectors: Vec<[[R; 3]; 12]>,
}

impl<R: Scalar> DnetOutput<R> {
    /// The d-net as printed.
    pub fn of(net: &DNet<R>) -> Self {
        DnetOutput {
            kind: "dnet",
            c0: net.c0().0,
            sectors: net.sectors().iter().map(|s| s.map(|p| p.0)).collect(),
        }
    }

    /// `true` when every coordinate is finite.
    pub fn is_finite(&self) -> bool {
        finite(&self.c0) && self.sectors.iter().flatten().all(finite)
    }
}

/// `capdiv pole` of an EG input: the limit point `c0` (docs/math/eg.md §4).
#[derive(Clone, Debug, Serialize)]
pub struct EgPoleOutput<R> {
    /// `c0`: formula (3) of a c-net, the given or fitted (4) `c0` of a d-net.
    pub limit: [R; 3],
}

/// `capdiv spectrum`: the spectrum of the EG subdivision matrix `A_n`
/// (docs/math/eg.md §6, §8); see [`crate::commands::spectrum`] for the definitions.
#[derive(Clone, Debug, Serialize)]
pub struct SpectrumOutput {
    /// The valence n.
    pub valence: usize,
    /// `"builtin"` (n = 3, 5), `"regular"` (n = 4) or the table file's name.
    pub table: String,
    /// The 8 largest eigenvalue moduli `|ν|`, largest first.
    pub eigenvalues: Vec<f64>,
    /// The same 8 eigenvalues as `[re, im]`.
    pub eigenvalues_re_im: Vec<[f64; 2]>,
    /// The subdominant eigenvalue λ (the 2nd and 3rd modulus, a double pair).
    pub lambda: f64,
    /// Catmull-Clark's subdominant eigenvalue λ_CC(n).
    pub lambda_cc: f64,
    /// The three eigenvalues after the λ pair, divided by λ².
    pub mu_over_lambda2: [f64; 3],
}

/// The pole's jet and geometry (docs/math/c2ps.md §4).
#[derive(Clone, Debug, Serialize)]
pub struct PoleOutput<R> {
    /// Limit point `p0`.
    pub limit: [R; 3],
    /// Eigencoefficients `p0..p5`.
    pub p: [[R; 3]; 6],
    /// Unit normal.
    pub normal: [R; 3],
    /// Gaussian curvature `K`.
    pub gaussian_curvature: R,
    /// Mean curvature `H`.
    pub mean_curvature: R,
    /// `H ± √(H² − K)`.
    pub principal_curvatures: [R; 2],
}

impl<R: Scalar> PoleOutput<R> {
    /// From the kernel's jet and geometry.
    pub fn new(jet: &PoleJet<R>, g: &PoleGeometry<R>) -> Self {
        PoleOutput {
            limit: jet.limit().0,
            p: jet.p.map(|p| p.0),
            normal: g.normal.0,
            gaussian_curvature: g.gaussian,
            mean_curvature: g.mean,
            principal_curvatures: g.principal,
        }
    }

    /// `true` when every number is finite.
    pub fn is_finite(&self) -> bool {
        finite(&self.limit)
            && self.p.iter().all(finite)
            && finite(&self.normal)
            && [self.gaussian_curvature, self.mean_curvature]
                .iter()
                .chain(self.principal_curvatures.iter())
                .all(|v| v.is_finite())
    }
}

/// One Bézier patch: `{"level", "degree", "points"}`.
#[derive(Clone, Debug, Serialize)]
pub struct PatchOutput<R> {
    /// Subdivision level of the ring (C²PS: 0 also for the outer region; EG:
    /// the step 1..M that emitted it).
    pub level: u32,
    /// Degree in each direction (3 for C²PS, 4 for EG).
    pub degree: usize,
    /// `(degree+1)²` control points, row `i` (along `u`, outward) after row,
    /// `j` (along `v`, counter-clockwise) within a row.
    pub points: Vec<[R; 3]>,
}

impl<R: Scalar> PatchOutput<R> {
    /// From a tensor patch of `K×K` points.
    pub fn new<const K: usize>(level: u32, patch: &TensorPatch<R, K>) -> Self {
        PatchOutput {
            level,
            degree: K - 1,
            points: patch.points.iter().flatten().map(|p| p.0).collect(),
        }
    }
}

/// A patch with the level it belongs to (what `patches` collects): bicubic
/// (`K = 4`) for C²PS, bi-quartic (`K = 5`) for EG.
#[derive(Clone, Copy, Debug)]
pub struct LeveledPatch<R, const K: usize> {
    /// Subdivision level (C²PS: the ring's level, 0 also for the outer
    /// region; EG: the step that emitted the ring, 1..M).
    pub level: u32,
    /// The Bézier patch, `K×K` control points.
    pub patch: TensorPatch<R, K>,
}

fn finite<R: Scalar>(p: &[R; 3]) -> bool {
    Point3(*p).is_finite()
}

/// Where a command's output goes.
#[derive(Clone, Debug)]
pub enum Sink {
    /// Standard output.
    Stdout,
    /// A file path, written by [`write_path`].
    File(PathBuf),
}

impl Sink {
    /// `Some(path)` → file, `None` → stdout.
    pub fn from_option(path: Option<PathBuf>) -> Self {
        path.map_or(Sink::Stdout, Sink::File)
    }

    /// Writes all of `bytes` at once. Binary output ([`is_binary`]) is
    /// refused on a terminal, before anything is written.
    pub fn write(&self, bytes: &[u8]) -> Result<(), CliError> {
        match self {
            Sink::Stdout => {
                let mut out = std::io::stdout().lock();
                if is_binary(bytes) && out.is_terminal() {
                    return Err(binary_to_terminal("standard output"));
                }
                out.write_all(bytes)
                    .and_then(|_| out.flush())
                    .map_err(|e| CliError::Io {
                        path: "<stdout>".into(),
                        message: e.to_string(),
                    })
            }
            Sink::File(path) => write_path(path, bytes),
        }
    }
}

/// How an output path is written, decided by what is at the path now.
#[derive(Debug)]
pub enum Target {
    /// Write a temporary sibling of `path`, then rename it over `path`: the
    /// path is absent (`permissions: None`) or a regular file (its
    /// permissions, given to the new file).
    Replace {
        /// The file to replace (a link already resolved).
        path: PathBuf,
        /// The replaced file's permissions.
        permissions: Option<std::fs::Permissions>,
    },
    /// Open `path` and write into it: a FIFO, a character device such as
    /// `/dev/null`, a socket, or a dangling link (`create`: its target is
    /// created).
    Through {
        /// The path as given.
        path: PathBuf,
        /// Create the file if missing (dangling links only).
        create: bool,
    },
}

impl Target {
    /// Looks at `path` (not following a link at first):
    ///
    /// - absent path or regular file: [`Target::Replace`];
    /// - symbolic link: the same rules applied to the file it points to
    ///   (the link stays); a dangling link is [`Target::Through`], creating
    ///   its target;
    /// - a FIFO, device or socket: [`Target::Through`], never replaced;
    /// - a directory: an error.
    pub fn of(path: &Path) -> Result<Self, CliError> {
        let io_err = |e: std::io::Error| CliError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        };
        let meta = match std::fs::symlink_metadata(path) {
            Ok(m) => m,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                return Ok(Target::Replace {
                    path: path.to_path_buf(),
                    permissions: None,
                })
            }
            Err(e) => return Err(io_err(e)),
        };
        let kind = meta.file_type();
        if kind.is_symlink() {
            return match std::fs::canonicalize(path) {
                // Fully resolved: the target is not a link.
                Ok(target) => Target::of(&target),
                Err(_) => Ok(Target::Through {
                    path: path.to_path_buf(),
                    create: true,
                }),
            };
        }
        if kind.is_file() {
            return Ok(Target::Replace {
                path: path.to_path_buf(),
                permissions: Some(meta.permissions()),
            });
        }
        if kind.is_dir() {
            return Err(io_err(std::io::Error::other("is a directory")));
        }
        Ok(Target::Through {
            path: path.to_path_buf(),
            create: false,
        })
    }

    /// Opens a [`Target::Through`] path for writing.
    pub fn open_through(path: &Path, create: bool) -> std::io::Result<std::fs::File> {
        std::fs::OpenOptions::new()
            .write(true)
            .truncate(true)
            .create(create)
            .open(path)
    }
}

/// Writes `bytes` to `path` as a shell redirection would, but never leaving
/// a partial regular file (the rules are [`Target::of`]'s).
pub fn write_path(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    match Target::of(path)? {
        Target::Replace { path, permissions } => write_atomic(&path, bytes, permissions),
        Target::Through { path, create } => {
            let io_err = |e: std::io::Error| CliError::Io {
                path: path.display().to_string(),
                message: e.to_string(),
            };
            let mut f = Target::open_through(&path, create).map_err(io_err)?;
            if is_binary(bytes) && f.is_terminal() {
                return Err(binary_to_terminal(&path.display().to_string()));
            }
            f.write_all(bytes).and_then(|_| f.flush()).map_err(io_err)
        }
    }
}

/// The temporary sibling of `path` that [`write_atomic`] and streaming
/// outputs write before the rename (`tag` tells them apart).
pub fn temporary_sibling(path: &Path, tag: &str) -> PathBuf {
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(path.file_name().unwrap_or_default());
    tmp_name.push(format!(".{}.{tag}tmp", std::process::id()));
    path.with_file_name(tmp_name)
}

/// Writes `bytes` to a temporary file beside `path`, gives it `permissions`
/// (those of the file it replaces), then renames it to `path`: readers see
/// either the old file or the whole new one.
pub fn write_atomic(
    path: &Path,
    bytes: &[u8],
    permissions: Option<std::fs::Permissions>,
) -> Result<(), CliError> {
    let io_err = |e: std::io::Error| CliError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    };
    if path.file_name().is_none() {
        return Err(io_err(std::io::Error::other("not a file name")));
    }
    let tmp = temporary_sibling(path, "");
    let result = std::fs::File::create(&tmp)
        .and_then(|mut f| f.write_all(bytes).and_then(|_| f.sync_all()))
        .and_then(|_| match permissions {
            Some(p) => std::fs::set_permissions(&tmp, p),
            None => Ok(()),
        })
        .and_then(|_| std::fs::rename(&tmp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map_err(io_err)
}
