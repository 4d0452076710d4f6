//! Errors of the command and the exit statuses they map to.

use std::fmt;
use std::path::Path;

/// The documented exit statuses of `nlsubdiv` (see `nlsubdiv --help` and cli/README.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    /// 0: success.
    Ok = 0,
    /// 1: the command ran, and the answer is "no": a comparison found a difference, or
    /// `check` found warnings (or errors under `--strict`… see `check`).
    Failed = 1,
    /// 2: bad input: a file that is not a valid mesh, or a mesh with defects the command
    /// does not accept.
    BadInput = 2,
    /// 3: an I/O error: a file that cannot be opened, read or written.
    Io = 3,
    /// 4: a bad command line (unknown option, missing argument, unsupported extension).
    Usage = 4,
    /// 5: an internal error (a bug: please report it with the input).
    Internal = 5,
}

/// An error with the exit status it maps to and a message for a person. The message names
/// the file, the line and the element at fault wherever they are known.
#[derive(Debug)]
pub struct CliError {
    /// Exit status.
    pub exit: Exit,
    /// One-line (or a few lines) message, without a trailing newline.
    pub message: String,
}

impl CliError {
    /// Bad input (exit 2).
    pub fn bad_input(message: impl Into<String>) -> Self {
        CliError {
            exit: Exit::BadInput,
            message: message.into(),
        }
    }

    /// An I/O error on `path` (exit 3).
    pub fn io(path: &Path, what: &str, err: &std::io::Error) -> Self {
        CliError {
            exit: Exit::Io,
            message: format!("{}: cannot {what}: {err}", path.display()),
        }
    }

    /// A usage error (exit 4).
    pub fn usage(message: impl Into<String>) -> Self {
        CliError {
            exit: Exit::Usage,
            message: message.into(),
        }
    }

    /// An internal error (exit 5).
    pub fn internal(message: impl Into<String>) -> Self {
        CliError {
            exit: Exit::Internal,
            message: message.into(),
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for CliError {}

/// Result of the command's functions.
pub type CliResult<T> = Result<T, CliError>;
