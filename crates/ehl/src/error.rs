//! Library error type. Case errors name the file, the key and the reason; solver failures are
//! not errors (a solver returns what it did, converged or not) except where no result exists.

use std::path::PathBuf;

/// Everything the library can fail with.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A problem with the case file: which file, which key (dotted path) and what is wrong.
    #[error("{file}: {key}: {message}")]
    Case {
        file: String,
        key: String,
        message: String,
    },
    /// The case file could not be read or parsed as TOML.
    #[error("{file}: {message}")]
    CaseFile { file: String, message: String },
    /// A feature of the case format that is not built yet.
    #[error("{file}: {key}: {message}")]
    Unsupported {
        file: String,
        key: String,
        message: String,
    },
    /// Writing outputs failed.
    #[error("writing {path}: {message}")]
    Output { path: PathBuf, message: String },
    /// A numerical failure that leaves no usable result.
    #[error("solver: {0}")]
    Solver(String),
    /// The solve was stopped from outside through its [`crate::run::cancel::CancelToken`]
    /// (the Python package's Ctrl-C); no result.
    #[error("cancelled")]
    Cancelled,
}

pub type Result<T> = std::result::Result<T, Error>;
