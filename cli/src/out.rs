//! Standard output: every result the commands print goes through [`print`], which reports
//! a failed write instead of panicking, as `println!` does. A closed pipe (the reader
//! stopped reading, as `head` does) ends the command quietly with exit 3.

use std::io::Write;
use std::path::Path;

use crate::error::CliResult;
use crate::io::write_error;

/// Writes `text` to standard output and flushes it.
///
/// # Errors
/// Exit 3: quietly for a closed pipe, with a message for other write errors.
pub fn print(text: &str) -> CliResult<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| write_error(Path::new("standard output"), &e))
}
