//! One error type for the whole crate: every failure names what was wrong.

use std::fmt;

/// Result alias used throughout twoball.
pub type Result<T> = std::result::Result<T, Error>;

/// What can go wrong in twoball. Every variant carries a message that names the offending
/// field, value or file, so the CLI can print it as one line and exit non-zero.
#[derive(Debug)]
pub enum Error {
    /// A user-supplied value is outside its allowed range (`field`, `value`, `allowed`).
    Invalid {
        /// Dotted name of the field, e.g. `ball1.material.E`.
        field: String,
        /// The value as given, printed.
        value: String,
        /// The allowed range or set, in words.
        allowed: String,
    },
    /// Input that could not be parsed (scene, mesh, CLI value); the message says where.
    Parse(String),
    /// A file could not be read or written.
    Io {
        /// The path involved.
        path: String,
        /// The operating-system error.
        source: std::io::Error,
    },
    /// A computation went numerically wrong (instability, non-finite value); the message
    /// names where, when and the likely cause.
    Numerical(String),
    /// The explicit integration created energy beyond the solver's limit: the measured
    /// values; the layer that knows the input's key names adds the advice.
    EnergyGrowth(Box<EnergyGrowth>),
    /// An external program (gmsh, ccx) is missing or failed.
    External(String),
    /// Work is not finished (a sweep with cases still missing); the message says what is left.
    Incomplete(String),
    /// The user pressed Ctrl-C; the message says where the job stopped and what was written.
    Interrupted(String),
}

impl Error {
    /// Shorthand for [`Error::Invalid`].
    pub fn invalid(
        field: impl Into<String>,
        value: impl fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        Error::Invalid {
            field: field.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }

    /// The same error with an [`Error::Invalid`] field renamed by `rename` (the layer that
    /// called a lower one knows where the lower one's field names came from). Other variants
    /// are returned unchanged.
    pub fn map_field(self, rename: impl FnOnce(String) -> String) -> Self {
        match self {
            Error::Invalid {
                field,
                value,
                allowed,
            } => Error::Invalid {
                field: rename(field),
                value,
                allowed,
            },
            other => other,
        }
    }

    /// [`Error::map_field`] naming the field from the scene's root: `prefix.field` (e.g.
    /// `size` from the mesh generator becomes `ball2.mesh.size`).
    pub fn within(self, prefix: &str) -> Self {
        self.map_field(|field| format!("{prefix}.{field}"))
    }

    /// Shorthand for [`Error::Io`].
    pub fn io(path: impl AsRef<std::path::Path>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.as_ref().display().to_string(),
            source,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Invalid {
                field,
                value,
                allowed,
            } => {
                write!(f, "invalid {field} = {value}: allowed {allowed}")
            }
            Error::Parse(m) => write!(f, "{m}"),
            Error::Io { path, source } => write!(f, "{path}: {source}"),
            Error::Numerical(m) => write!(f, "numerical failure: {m}"),
            Error::EnergyGrowth(g) => write!(f, "numerical failure: {g}"),
            Error::External(m) => write!(f, "{m}"),
            Error::Incomplete(m) => write!(f, "{m}"),
            Error::Interrupted(m) => write!(f, "interrupted {m}"),
        }
    }
}

/// Energy created by the explicit integration, as measured when the solver stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct EnergyGrowth {
    /// Energy created, as a fraction of the start energy.
    pub created: f64,
    /// The solver's limit on that fraction.
    pub limit: f64,
    /// Time, s.
    pub time: f64,
    /// Step number.
    pub step: u64,
    /// The fastest node (where an instability shows first) and its speed, m/s.
    pub fastest_node: (usize, f64),
    /// What controls the stable time step (an element or an interaction, by name).
    pub controlled_by: String,
}

impl fmt::Display for EnergyGrowth {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (node, speed) = self.fastest_node;
        write!(
            f,
            "energy grew by {:.3e} of its start value (limit {:.3e}) at t = {:.6e} s, step {} \
             (fastest node {node}, {speed:.3e} m/s; step controlled by {}): energy grows, the \
             time step is too large for an element or the penalty is too stiff",
            self.created, self.limit, self.time, self.step, self.controlled_by
        )
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}
