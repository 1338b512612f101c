//! The CLI's error type. Every failure — usage, I/O, malformed JSON, wrong
//! schema, wrong kind for the command, capacity, kernel error — is reported as exactly
//! one line on stderr and exit status [`EXIT_FAILURE`].

use core::fmt;

/// Exit status of every failure.
pub const EXIT_FAILURE: i32 = 2;

/// Everything that can make a command fail.
#[derive(Debug)]
#[non_exhaustive]
pub enum CliError {
    /// The command line is wrong (message from clap or from our own checks).
    Usage(String),
    /// Reading the input or writing the output failed.
    Io {
        /// The file (or `<stdin>`, `<stdout>`).
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// The input is not JSON.
    MalformedJson {
        /// The input's name.
        source: String,
        /// serde_json's message (with line and column).
        message: String,
    },
    /// The input is JSON but not of the expected schema.
    Schema {
        /// The input's name.
        source: String,
        /// What is wrong.
        message: String,
    },
    /// A valid input of a `kind` the command or scheme does not take (e.g.
    /// `--scheme eg` on a `polar` input).
    WrongKind {
        /// The input's name.
        source: String,
        /// The `kind` tag of the input.
        kind: &'static str,
        /// What was needed, in words (`"--scheme eg needs a 'cnet' or 'dnet' input"`).
        need: String,
    },
    /// The valence the job needs exceeds [`crate::net::MAX_VALENCE`].
    Capacity {
        /// What was asked for, in words.
        what: String,
        /// The largest valence.
        max: usize,
    },
    /// The kernel refused the configuration.
    Kernel {
        /// The input's name.
        source: String,
        /// The kernel's error.
        error: capdiv::Error,
    },
    /// The mesh was rejected (syntax, indices, topology), naming the face
    /// or vertex.
    Mesh {
        /// The input's name.
        source: String,
        /// The mesh crate's error.
        error: capdiv_mesh::MeshError,
        /// How the input counts its vertices and faces.
        naming: Naming,
    },
    /// Evaluating the surface of a mesh failed (capacity, kernel).
    Eval {
        /// The input's name.
        source: String,
        /// The evaluator's error.
        error: capdiv_mesh::EvalError,
        /// How the input counts its vertices and faces.
        naming: Naming,
    },
    /// A result coordinate overflowed the chosen precision.
    NonFiniteResult {
        /// The input's name.
        source: String,
    },
    /// The surface has no patch (every face a hole).
    EmptySurface {
        /// The input's name.
        source: String,
    },
    /// An allocation could not be made (the analysis', the evaluation's or
    /// the output's).
    OutOfMemory {
        /// The input's name.
        source: String,
        /// The size asked for.
        bytes: usize,
    },
    /// The surface would have more patches than allowed (`--max-patches`):
    /// refused after the analysis, before any patch is made.
    TooLarge {
        /// The input's name.
        source: String,
        /// Patches the surface would have (with every cap at the depth).
        patches: u64,
        /// `patches` is an upper bound (caps may stop earlier).
        up_to: bool,
        /// The limit.
        max: u64,
    },
}

/// How messages name a mesh's vertices and faces: as the input file counts
/// them.
#[derive(Clone, Debug, Default)]
pub enum Naming {
    /// 0-based indices, as the JSON mesh schema writes them (`faces[0]` is
    /// face 0).
    #[default]
    Indices,
    /// 1-based, with the `v` or `f` line, as a Wavefront OBJ file counts them.
    Obj(std::sync::Arc<capdiv_mesh::obj::ObjLines>),
}

impl Naming {
    /// The naming of a mesh read from `text`: [`Naming::Obj`] unless the text
    /// is JSON.
    pub fn of_text(text: &str) -> Self {
        if capdiv_mesh::obj::looks_like_json(text) {
            Naming::Indices
        } else {
            Naming::Obj(std::sync::Arc::new(capdiv_mesh::obj::ObjLines::of(text)))
        }
    }

    /// The number the input gives the vertex or face of 0-based `index`
    /// (OBJ: `index + 1`).
    pub fn number(&self, index: usize) -> usize {
        match self {
            Naming::Indices => index,
            Naming::Obj(_) => index + 1,
        }
    }

    fn names(&self) -> &dyn capdiv_mesh::error::Names {
        match self {
            Naming::Indices => &capdiv_mesh::error::Indices,
            Naming::Obj(lines) => lines.as_ref(),
        }
    }
}

impl CliError {
    /// A mesh error of `source`, named by 0-based indices until
    /// [`CliError::named`].
    pub fn mesh(source: &str, error: capdiv_mesh::MeshError) -> Self {
        if let capdiv_mesh::MeshError::OutOfMemory { bytes } = error {
            return CliError::out_of_memory(source, bytes);
        }
        CliError::Mesh {
            source: source.to_string(),
            error,
            naming: Naming::Indices,
        }
    }

    /// An evaluation error of `source`, named by 0-based indices until
    /// [`CliError::named`].
    pub fn eval(source: &str, error: capdiv_mesh::EvalError) -> Self {
        if let capdiv_mesh::EvalError::OutOfMemory { bytes } = error {
            return CliError::out_of_memory(source, bytes);
        }
        CliError::Eval {
            source: source.to_string(),
            error,
            naming: Naming::Indices,
        }
    }

    /// A planning, bounding or evaluation error of `source`
    /// ([`capdiv_mesh::SurfaceError`]): as [`CliError::mesh`],
    /// [`CliError::TooLarge`] (the limit is `--max-patches`) or
    /// [`CliError::eval`].
    pub fn surface(source: &str, error: capdiv_mesh::SurfaceError) -> Self {
        use capdiv_mesh::SurfaceError;
        match error {
            SurfaceError::Mesh(e) => CliError::mesh(source, e),
            SurfaceError::Eval(e) => CliError::eval(source, e),
            SurfaceError::TooLarge {
                patches,
                max,
                upper_bound,
            } => CliError::TooLarge {
                source: source.to_string(),
                patches,
                up_to: upper_bound,
                max,
            },
            // A cause the library may add later: its own one-line message.
            other => CliError::Usage(format!("{source}: {other}")),
        }
    }

    /// The error with its vertices and faces named by `naming` (mesh and
    /// evaluation errors; others unchanged).
    pub fn named(self, naming: &Naming) -> Self {
        match self {
            CliError::Mesh { source, error, .. } => CliError::Mesh {
                source,
                error,
                naming: naming.clone(),
            },
            CliError::Eval { source, error, .. } => CliError::Eval {
                source,
                error,
                naming: naming.clone(),
            },
            other => other,
        }
    }

    /// An allocation of `bytes` bytes for `source` failed.
    pub fn out_of_memory(source: &str, bytes: usize) -> Self {
        CliError::OutOfMemory {
            source: source.to_string(),
            bytes,
        }
    }

    /// [`CliError::out_of_memory`] for `source`, as a function of the
    /// allocation's error (for `map_err`).
    pub fn out_of_memory_in(source: &str) -> impl Fn(capdiv_mesh::OutOfMemory) -> Self + '_ {
        move |e| CliError::out_of_memory(source, e.bytes)
    }

    /// Attaches the input's name to a kernel error.
    pub fn kernel(source: &str, error: capdiv::Error) -> Self {
        CliError::Kernel {
            source: source.to_string(),
            error,
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Usage(m) => write!(f, "{m}"),
            CliError::Io { path, message } => write!(f, "{path}: {message}"),
            CliError::MalformedJson { source, message } => {
                write!(f, "{source}: malformed JSON: {message}")
            }
            CliError::Schema { source, message } => {
                write!(f, "{source}: wrong schema: {message}")
            }
            CliError::WrongKind { source, kind, need } => {
                write!(f, "{source}: {need}, got kind '{kind}'")
            }
            CliError::Capacity { what, max } => write!(
                f,
                "{what} exceeds the largest supported capacity {max} (use fewer steps)"
            ),
            CliError::Kernel { source, error } => write!(f, "{source}: {error}"),
            CliError::Mesh {
                source,
                error,
                naming,
            } => write!(f, "{source}: {}", error.describe(naming.names())),
            CliError::Eval {
                source,
                error,
                naming,
            } => write!(f, "{source}: {}", error.describe(naming.names())),
            CliError::NonFiniteResult { source } => write!(
                f,
                "{source}: a result coordinate is not finite (input too large for the precision)"
            ),
            CliError::EmptySurface { source } => write!(
                f,
                "{source}: the surface is empty (every face is a hole, or the boundary rule 'none' removed them all)"
            ),
            CliError::OutOfMemory { source, bytes } => write!(
                f,
                "{source}: {}",
                capdiv_mesh::OutOfMemory { bytes: *bytes }
            ),
            CliError::TooLarge {
                source,
                patches,
                up_to,
                max,
            } => write!(
                f,
                "{source}: the surface would have {}{patches} patches, more than --max-patches {max} (lower --depth, or raise --max-patches)",
                if *up_to { "up to " } else { "" }
            ),
        }
    }
}

/// The message includes the kernel's, the mesh's or the evaluator's error
/// it wraps, so none is reported again as a source.
impl core::error::Error for CliError {}

impl CliError {
    /// The message as printed: `error: …`, newlines folded so that it is
    /// always exactly one line.
    pub fn line(&self) -> String {
        let text = format!("error: {self}");
        text.split_whitespace().collect::<Vec<_>>().join(" ")
    }
}
