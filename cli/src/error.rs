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

    /// An error that ends the command with `exit` and prints nothing: standard output was
    /// closed by its reader (`nlsubdiv metrics --json x.off | head -1`).
    pub fn quiet(exit: Exit) -> Self {
        CliError {
            exit,
            message: String::new(),
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

/// At most this many characters of a file's text are echoed in a message: a 2 MB token must
/// not become a 2 MB message.
pub const QUOTE_MAX_CHARS: usize = 48;

/// Text from an input file, made safe to echo on a terminal: in single quotes, every control
/// character (C0, DEL, C1), every invisible formatting character that can reorder or hide
/// text (bidirectional overrides and isolates, the byte-order mark, zero-width characters)
/// and every byte that is not UTF-8 written as an escape (`\x1b`, `\u{202e}`), backslashes
/// and quotes escaped, and at most [`QUOTE_MAX_CHARS`] characters followed by `…` and the
/// full length. The one helper every message uses to show what it read.
pub fn quote(bytes: &[u8]) -> String {
    let mut out = String::with_capacity(bytes.len().min(QUOTE_MAX_CHARS * 4) + 16);
    out.push('\'');
    let shown = escape_into(&mut out, bytes, QUOTE_MAX_CHARS, true);
    out.push('\'');
    if shown < bytes.len() {
        out.push_str(&format!("… ({} bytes)", bytes.len()));
    }
    out
}

/// A message line made safe for a terminal: control and invisible formatting characters
/// escaped as by [`quote`] (no quotes added), at most `max_chars` characters. The last
/// defence before anything is printed on stderr, for text that did not pass through
/// [`quote`] (file names from the command line, messages of libraries).
pub fn sanitize_line(line: &str, max_chars: usize) -> String {
    let mut out = String::with_capacity(line.len().min(max_chars * 4) + 16);
    let shown = escape_into(&mut out, line.as_bytes(), max_chars, false);
    if shown < line.len() {
        out.push_str(&format!("… ({} bytes)", line.len()));
    }
    out
}

/// Whether `c` is printed as an escape: control characters and the invisible formatting
/// characters that change how the surrounding text looks (Unicode bidi controls, the
/// byte-order mark / zero-width no-break space, zero-width joiners, line and paragraph
/// separators).
fn must_escape(c: char) -> bool {
    c.is_control()
        || matches!(c,
            '\u{200b}'..='\u{200f}'
            | '\u{2028}'..='\u{202e}'
            | '\u{2060}'..='\u{2069}'
            | '\u{061c}'
            | '\u{feff}')
}

/// Appends the escaped form of `bytes` to `out`, at most `max_chars` source characters;
/// returns how many bytes of `bytes` were shown. `quoted`: also escape `\` and `'` (inside
/// quotes, so that the quoted text cannot end early or fake an escape).
fn escape_into(out: &mut String, bytes: &[u8], max_chars: usize, quoted: bool) -> usize {
    use std::fmt::Write as _;
    let mut chars = 0usize;
    let mut consumed = 0usize;
    for chunk in bytes.utf8_chunks() {
        for c in chunk.valid().chars() {
            if chars >= max_chars {
                return consumed;
            }
            match c {
                '\\' if quoted => out.push_str("\\\\"),
                '\'' if quoted => out.push_str("\\'"),
                c if must_escape(c) && (c as u32) < 0x80 => {
                    let _ = write!(out, "\\x{:02x}", c as u32);
                }
                c if must_escape(c) => {
                    let _ = write!(out, "\\u{{{:x}}}", c as u32);
                }
                c => out.push(c),
            }
            chars += 1;
            consumed += c.len_utf8();
        }
        for &b in chunk.invalid() {
            if chars >= max_chars {
                return consumed;
            }
            let _ = write!(out, "\\x{b:02x}");
            chars += 1;
            consumed += 1;
        }
    }
    consumed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quote_escapes_and_bounds() {
        assert_eq!(quote(b"abc"), "'abc'");
        assert_eq!(quote(b"\x1b[31mred"), "'\\x1b[31mred'");
        assert_eq!(quote("a\u{202e}b".as_bytes()), "'a\\u{202e}b'");
        assert_eq!(quote(b"\xff\xfe"), "'\\xff\\xfe'");
        assert_eq!(quote("\u{feff}v".as_bytes()), "'\\u{feff}v'");
        let long = vec![b'7'; 2_000_000];
        let q = quote(&long);
        assert!(q.len() < 100, "{q}");
        assert!(q.ends_with("… (2000000 bytes)"), "{q}");
        assert_eq!(sanitize_line("x\ry", 10), "x\\x0dy");
        assert_eq!(sanitize_line("a '\\x1b'", 10), "a '\\x1b'");
    }
}
