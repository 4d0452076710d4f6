//! What the three text formats share below their grammars: the byte-order mark and line
//! ends.
//!
//! * A UTF-8 byte-order mark (`EF BB BF`) at the very start is what Unicode says it is, a
//!   signature of the encoding and not content: it is skipped, so that the first statement
//!   of a file saved by a Windows editor is read like any other. A UTF-16 or UTF-32 mark is
//!   refused by name (mesh files are ASCII); a byte-order mark anywhere else is content and
//!   is refused by the grammar that meets it (quoted, as `\u{feff}`).
//! * A line ends at LF, CR LF or a lone CR (classic Mac OS), in every text format, so line
//!   numbers in messages are those an editor shows.

use std::path::Path;

use crate::error::{CliError, CliResult};

/// The bytes after a UTF-8 byte-order mark, or all of them; refuses UTF-16 and UTF-32 text.
///
/// # Errors
/// Exit 2 for a UTF-16 or UTF-32 byte-order mark.
pub fn strip_bom<'a>(path: &Path, bytes: &'a [u8]) -> CliResult<&'a [u8]> {
    if let Some(rest) = bytes.strip_prefix(b"\xEF\xBB\xBF") {
        return Ok(rest);
    }
    let utf32 = bytes.starts_with(b"\xFF\xFE\x00\x00") || bytes.starts_with(b"\x00\x00\xFE\xFF");
    let utf16 = bytes.starts_with(b"\xFF\xFE") || bytes.starts_with(b"\xFE\xFF");
    if utf32 || utf16 {
        return Err(CliError::bad_input(format!(
            "{}:1: the file is {} text (it starts with that byte-order mark); mesh files are \
             ASCII: save it as UTF-8 or ASCII",
            path.display(),
            if utf32 { "UTF-32" } else { "UTF-16" }
        )));
    }
    Ok(bytes)
}

/// The lines of `bytes` with their 1-based numbers, without their line ends (LF, CR LF or
/// CR). A file that ends with a line end has no empty last line.
#[derive(Debug, Clone)]
pub struct Lines<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: u32,
}

impl<'a> Lines<'a> {
    /// The lines of `bytes`, the first numbered `first_line`.
    pub fn new(bytes: &'a [u8], first_line: u32) -> Self {
        Lines {
            bytes,
            pos: 0,
            line: first_line,
        }
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = (u32, &'a [u8]);

    fn next(&mut self) -> Option<(u32, &'a [u8])> {
        let rest = self.bytes.get(self.pos..)?;
        if rest.is_empty() {
            return None;
        }
        let end = rest
            .iter()
            .position(|&b| b == b'\n' || b == b'\r')
            .unwrap_or(rest.len());
        let line = rest.get(..end)?;
        let skip = match (rest.get(end), rest.get(end + 1)) {
            (Some(b'\r'), Some(b'\n')) => 2,
            (Some(_), _) => 1,
            (None, _) => 0,
        };
        self.pos += end + skip;
        let n = self.line;
        self.line = self.line.saturating_add(1);
        Some((n, line))
    }
}

/// The whitespace-separated tokens of a line (space, tab, form feed; line ends were cut).
pub fn tokens(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(|b| b.is_ascii_whitespace())
        .filter(|t| !t.is_empty())
}

/// Parses a token as a decimal `f64` (Rust's grammar, correctly rounded: `1`, `-2.5e-3`,
/// `inf` and `nan` are numbers; the readers refuse non-finite coordinates by name).
pub fn parse_f64(t: &[u8]) -> Option<f64> {
    std::str::from_utf8(t).ok()?.parse::<f64>().ok()
}

/// Parses a token as a decimal integer (an optional sign and digits only).
pub fn parse_i64(t: &[u8]) -> Option<i64> {
    std::str::from_utf8(t).ok()?.parse::<i64>().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_ends() {
        let l: Vec<(u32, &[u8])> = Lines::new(b"a\nb\r\nc\rd\n\ne", 1).collect();
        let want: Vec<(u32, &[u8])> = vec![
            (1, b"a"),
            (2, b"b"),
            (3, b"c"),
            (4, b"d"),
            (5, b""),
            (6, b"e"),
        ];
        assert_eq!(l, want);
        assert_eq!(Lines::new(b"x\n", 1).count(), 1);
    }

    #[test]
    fn byte_order_marks() {
        let p = Path::new("t");
        assert_eq!(strip_bom(p, b"\xEF\xBB\xBFOFF").unwrap(), b"OFF");
        assert_eq!(strip_bom(p, b"OFF").unwrap(), b"OFF");
        assert!(strip_bom(p, b"\xFF\xFEO\x00")
            .unwrap_err()
            .message
            .contains("UTF-16"));
    }
}
