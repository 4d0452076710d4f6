//! OFF (Object File Format), ASCII.
//!
//! Accepted layout (a whitespace-token format, as most OFF readers treat it):
//!
//! * an optional keyword `[ST][C][N]OFF` (texture coordinates, colours, normals per vertex);
//!   a file without one starts with the counts. `4OFF`, `nOFF` and `OFF BINARY` are refused
//!   with a message saying so;
//! * the counts `V F [E]`, on the keyword's line or later; `E` is ignored;
//! * `V` vertices `x y z`, then the declared extras (`N`: 3 numbers, `ST`: 2, `C`: the rest
//!   of the line: RGB, RGBA or a colour-map index);
//! * `F` faces `n i_1 … i_n`, which may be wrapped over several lines; numbers after the last
//!   index on its line are a face colour and are skipped;
//! * `#` starts a comment anywhere; blank lines, tabs and CRLF or CR line ends are fine.
//!
//! Anything after the last face other than comments is an error (the counts are wrong).

use std::io::Write;
use std::path::Path;

use super::{check_indices, fmt_f64, WriteOptions};
use crate::error::{CliError, CliResult};
use crate::mesh::{Mesh, Source};

/// A token and the (1-based) line it is on.
#[derive(Clone, Copy, Debug)]
struct Tok<'a> {
    text: &'a [u8],
    line: u32,
}

/// Whitespace-and-comment tokenizer over the bytes of a file.
struct Tokens<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: u32,
    /// The line of the last token returned (for messages at the end of the file).
    last: u32,
    peeked: Option<Option<Tok<'a>>>,
}

impl<'a> Tokens<'a> {
    fn new(bytes: &'a [u8]) -> Self {
        Tokens {
            bytes,
            pos: 0,
            line: 1,
            last: 1,
            peeked: None,
        }
    }

    fn scan(&mut self) -> Option<Tok<'a>> {
        let b = self.bytes;
        loop {
            let c = *b.get(self.pos)?;
            match c {
                b'\n' => {
                    self.line += 1;
                    self.pos += 1;
                }
                b'\r' => {
                    // CR LF counts once; a lone CR (old Mac) ends a line too.
                    if b.get(self.pos + 1) != Some(&b'\n') {
                        self.line += 1;
                    }
                    self.pos += 1;
                }
                b'#' => {
                    while let Some(&c) = b.get(self.pos) {
                        if c == b'\n' || c == b'\r' {
                            break;
                        }
                        self.pos += 1;
                    }
                }
                c if c.is_ascii_whitespace() => self.pos += 1,
                _ => break,
            }
        }
        let start = self.pos;
        while let Some(&c) = b.get(self.pos) {
            if c.is_ascii_whitespace() || c == b'#' {
                break;
            }
            self.pos += 1;
        }
        Some(Tok {
            text: b.get(start..self.pos)?,
            line: self.line,
        })
    }

    fn next(&mut self) -> Option<Tok<'a>> {
        let t = match self.peeked.take() {
            Some(t) => t,
            None => self.scan(),
        };
        if let Some(t) = t {
            self.last = t.line;
        }
        t
    }

    fn peek(&mut self) -> Option<Tok<'a>> {
        if self.peeked.is_none() {
            self.peeked = Some(self.scan());
        }
        self.peeked.flatten()
    }

    /// The next token if it is on `line`.
    fn next_on_line(&mut self, line: u32) -> Option<Tok<'a>> {
        match self.peek() {
            Some(t) if t.line == line => self.next(),
            _ => None,
        }
    }

    /// The line of the last token read (for messages at the end of the file).
    fn last_line(&self) -> u32 {
        self.last
    }
}

fn text(t: &Tok<'_>) -> String {
    String::from_utf8_lossy(t.text).into_owned()
}

struct Ctx<'p> {
    path: &'p Path,
}

impl Ctx<'_> {
    fn err(&self, line: u32, msg: impl std::fmt::Display) -> CliError {
        CliError::bad_input(format!("{}:{line}: {msg}", self.path.display()))
    }
}

/// Vertex extras declared by the keyword.
#[derive(Clone, Copy, Debug, Default)]
struct Extras {
    texcoords: bool,
    colors: bool,
    normals: bool,
}

/// Parses the keyword, if there is one.
fn keyword(ctx: &Ctx<'_>, toks: &mut Tokens<'_>) -> CliResult<Extras> {
    let Some(t) = toks.peek() else {
        return Err(CliError::bad_input(format!(
            "{}: the file is empty",
            ctx.path.display()
        )));
    };
    let Some(prefix) = t.text.strip_suffix(b"OFF") else {
        if t.text.first().is_some_and(|c| c.is_ascii_digit()) {
            return Ok(Extras::default()); // no keyword: counts first
        }
        return Err(ctx.err(
            t.line,
            format_args!(
                "not an OFF file: expected the keyword OFF, found '{}'",
                text(&t)
            ),
        ));
    };
    toks.next();
    let mut e = Extras::default();
    let mut rest = prefix;
    if let Some(r) = rest.strip_prefix(b"ST") {
        e.texcoords = true;
        rest = r;
    }
    if let Some(r) = rest.strip_prefix(b"C") {
        e.colors = true;
        rest = r;
    }
    if let Some(r) = rest.strip_prefix(b"N") {
        e.normals = true;
        rest = r;
    }
    if rest == b"4" || rest == b"n" || rest == b"4n" {
        return Err(ctx.err(
            t.line,
            format_args!(
                "'{}': only 3-dimensional OFF is supported, not 4D or n-dimensional",
                text(&t)
            ),
        ));
    }
    if !rest.is_empty() {
        return Err(ctx.err(t.line, format_args!("unknown OFF keyword '{}'", text(&t))));
    }
    if let Some(n) = toks.next_on_line(t.line) {
        if n.text.eq_ignore_ascii_case(b"BINARY") {
            return Err(ctx.err(n.line, "binary OFF is not supported (use ASCII OFF or PLY)"));
        }
        // Counts on the keyword's line: put the token back by re-peeking is not possible,
        // so hand it over.
        toks.peeked = Some(Some(n));
    }
    Ok(e)
}

fn parse_count(ctx: &Ctx<'_>, t: Option<Tok<'_>>, what: &str, eof_line: u32) -> CliResult<u64> {
    let t = t.ok_or_else(|| ctx.err(eof_line, format_args!("the file ends before the {what}")))?;
    std::str::from_utf8(t.text)
        .ok()
        .and_then(|s| s.parse::<u64>().ok())
        .ok_or_else(|| {
            ctx.err(
                t.line,
                format_args!(
                    "the {what} must be a non-negative integer, found '{}'",
                    text(&t)
                ),
            )
        })
}

fn parse_f64(t: &Tok<'_>) -> Option<f64> {
    std::str::from_utf8(t.text).ok()?.parse::<f64>().ok()
}

/// Skips `n` numbers of vertex `v`'s extras.
fn skip(ctx: &Ctx<'_>, toks: &mut Tokens<'_>, v: u64, n: usize, what: &str) -> CliResult<()> {
    for _ in 0..n {
        let t = toks.next().ok_or_else(|| {
            ctx.err(
                toks.last_line(),
                format_args!("the file ends in the {what} of vertex {v}"),
            )
        })?;
        if parse_f64(&t).is_none() {
            return Err(ctx.err(
                t.line,
                format_args!("vertex {v}: {what} '{}' is not a number", text(&t)),
            ));
        }
    }
    Ok(())
}

/// Reads an OFF file.
///
/// # Errors
/// Exit 2 with the file, line and element for anything malformed (see the module docs).
pub fn read(path: &Path, bytes: &[u8]) -> CliResult<(Mesh, Source)> {
    let ctx = Ctx { path };
    let mut toks = Tokens::new(bytes);
    let extras = keyword(&ctx, &mut toks)?;
    let nv = parse_count(&ctx, toks.next(), "vertex count", toks.last_line())?;
    let t_nf = toks.next();
    let nf = parse_count(&ctx, t_nf, "face count", toks.last_line())?;
    if let Some(t) = t_nf {
        // The edge count, when it is on the line of the face count.
        if let Some(e) = toks.next_on_line(t.line) {
            if std::str::from_utf8(e.text)
                .ok()
                .and_then(|s| s.parse::<u64>().ok())
                .is_none()
            {
                return Err(ctx.err(
                    e.line,
                    format_args!("the edge count must be an integer, found '{}'", text(&e)),
                ));
            }
        }
    }
    let limit = u64::from(u32::MAX - 1);
    if nv > limit || nf > limit {
        return Err(ctx.err(
            t_nf.map_or(1, |t| t.line),
            format_args!("{nv} vertices, {nf} faces: too many (at most {limit} each)"),
        ));
    }
    // Every vertex takes at least 6 bytes and every face at least 8: cap the reservation by
    // the file size so that a lying header cannot exhaust memory.
    let cap = |n: u64, min_bytes: usize| (n as usize).min(bytes.len() / min_bytes + 1);
    let mut positions = Vec::with_capacity(cap(nv, 6));
    let mut vertex_lines = Vec::with_capacity(cap(nv, 6));
    for v in 0..nv {
        let mut p = [0.0; 3];
        let mut last_line = 0;
        for (k, c) in p.iter_mut().enumerate() {
            let t = toks.next().ok_or_else(|| {
                ctx.err(
                    toks.last_line(),
                    format_args!(
                        "the file ends in vertex {v} of {nv} (truncated, or the header's \
                         vertex count is wrong)"
                    ),
                )
            })?;
            if k == 0 {
                vertex_lines.push(t.line);
            }
            last_line = t.line;
            *c = parse_f64(&t).ok_or_else(|| {
                ctx.err(
                    t.line,
                    format_args!(
                        "vertex {v}: coordinate {} is not a number: '{}'",
                        ["x", "y", "z"][k],
                        text(&t)
                    ),
                )
            })?;
        }
        if extras.normals {
            skip(&ctx, &mut toks, v, 3, "normal")?;
        }
        if extras.colors {
            // RGB, RGBA or a colour-map index: the rest of the line.
            while toks.next_on_line(last_line).is_some() {}
        }
        if extras.texcoords {
            skip(&ctx, &mut toks, v, 2, "texture coordinates")?;
        }
        positions.push(p);
    }
    let mut mesh = Mesh {
        positions,
        offsets: Vec::with_capacity(cap(nf, 8) + 1),
        indices: Vec::new(),
    };
    mesh.offsets.push(0);
    let mut face_lines = Vec::with_capacity(cap(nf, 8));
    for f in 0..nf {
        let eof = |toks: &Tokens<'_>| {
            ctx.err(
                toks.last_line(),
                format_args!(
                    "the file ends in face {f} of {nf} (truncated, or the header's face count \
                     is wrong)"
                ),
            )
        };
        let t = toks.next().ok_or_else(|| eof(&toks))?;
        face_lines.push(t.line);
        let n = std::str::from_utf8(t.text)
            .ok()
            .and_then(|s| s.parse::<i64>().ok())
            .ok_or_else(|| {
                ctx.err(
                    t.line,
                    format_args!(
                        "face {f}: the corner count must be an integer, found '{}'",
                        text(&t)
                    ),
                )
            })?;
        if n < 3 {
            return Err(ctx.err(
                t.line,
                format_args!("face {f} has {n} corners (a face needs at least 3)"),
            ));
        }
        if n as u64 > nv.max(3) {
            return Err(ctx.err(
                t.line,
                format_args!("face {f} has {n} corners but the file has only {nv} vertices"),
            ));
        }
        let mut last_line = t.line;
        for _ in 0..n {
            let t = toks.next().ok_or_else(|| eof(&toks))?;
            last_line = t.line;
            let i = std::str::from_utf8(t.text)
                .ok()
                .and_then(|s| s.parse::<i64>().ok())
                .ok_or_else(|| {
                    ctx.err(
                        t.line,
                        format_args!("face {f}: index '{}' is not an integer", text(&t)),
                    )
                })?;
            if i < 0 {
                return Err(ctx.err(
                    t.line,
                    format_args!("face {f}: negative index {i} (OFF indices start at 0)"),
                ));
            }
            let i = u32::try_from(i).map_err(|_| {
                ctx.err(
                    t.line,
                    format_args!("face {f}: index {i} is out of range ({nv} vertices)"),
                )
            })?;
            mesh.indices.push(i);
        }
        // A face colour: the numbers after the last index on its line.
        while let Some(c) = toks.next_on_line(last_line) {
            if parse_f64(&c).is_none() {
                return Err(ctx.err(
                    c.line,
                    format_args!("face {f}: unexpected '{}' after its indices", text(&c)),
                ));
            }
        }
        mesh.offsets.push(mesh.indices.len() as u32);
    }
    if let Some(t) = toks.next() {
        return Err(ctx.err(
            t.line,
            format_args!(
                "unexpected '{}' after the last face (the header says {nv} vertices and {nf} \
                 faces)",
                text(&t)
            ),
        ));
    }
    let source = Source::with_lines(path, vertex_lines, face_lines);
    check_indices(&mesh, &source, true)?;
    Ok((mesh, source))
}

/// Writes ASCII OFF (COFF with `r g b 255` when colours are given).
///
/// # Errors
/// I/O errors of `out`.
pub fn write(out: &mut dyn Write, mesh: &Mesh, opts: &WriteOptions) -> std::io::Result<()> {
    let colors = opts.colors.as_deref();
    writeln!(out, "{}", if colors.is_some() { "COFF" } else { "OFF" })?;
    writeln!(out, "{} {} 0", mesh.num_vertices(), mesh.num_faces())?;
    for (v, p) in mesh.positions.iter().enumerate() {
        write!(out, "{} {} {}", fmt_f64(p[0]), fmt_f64(p[1]), fmt_f64(p[2]))?;
        if let Some(c) = colors.and_then(|c| c.get(v)) {
            write!(out, " {} {} {} 255", c[0], c[1], c[2])?;
        }
        writeln!(out)?;
    }
    for face in mesh.faces() {
        write!(out, "{}", face.len())?;
        for i in face {
            write!(out, " {i}")?;
        }
        writeln!(out)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> CliResult<Mesh> {
        read(Path::new("t.off"), s.as_bytes()).map(|(m, _)| m)
    }

    fn err(s: &str) -> String {
        parse(s).unwrap_err().message
    }

    const TET: &str =
        "OFF\n4 4 6\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n";

    #[test]
    fn layouts() {
        let want = parse(TET).unwrap();
        assert_eq!(want.num_faces(), 4);
        for s in [
            "OFF 4 4 6\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n",
            "OFF\r\n# c\r\n\r\n4 4 0\r\n1 1 1 # v0\r\n1 -1 -1\r\n-1 1 -1\r\n-1 -1 1\r\n3 0 1 2\r\n3 0 3 1\r\n3 0 2 3\r\n3 1 3 2\r\n",
            "COFF\n4 4 6\n1 1 1 0.5 0.5 0.5 1\n1 -1 -1 1 1 1 1\n-1 1 -1 0 0 0 1\n-1 -1 1 1 0 0 1\n3 0 1 2 255 0 0\n3 0 3 1\n3 0 2 3 1 0 0\n3 1 3 2\n",
            "OFF\n4 4 0\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0\n1\n2\n3 0\n3\n1\n3 0\n2 3\n3 1 3\n2\n",
            "4 4\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n",
            "NOFF\n4 4 6\n1 1 1 0 0 1\n1 -1 -1 0 0 1\n-1 1 -1 0 0 1\n-1 -1 1 0 0 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n",
            "OFF\r4 4 6\r1 1 1\r1 -1 -1\r-1 1 -1\r-1 -1 1\r3 0 1 2\r3 0 3 1\r3 0 2 3\r3 1 3 2\r",
        ] {
            assert_eq!(parse(s).unwrap(), want, "{s}");
        }
    }

    #[test]
    fn errors_name_line_and_element() {
        let e = err("OFF\n4 4 6\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n");
        assert!(e.contains("t.off:9") && e.contains("face 3 of 4"), "{e}");
        let e = err(
            "OFF\n4 4 6\n1 1 1\n1 -1 x\n-1 1 -1\n-1 -1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n",
        );
        assert!(
            e.contains("t.off:4") && e.contains("vertex 1") && e.contains("'x'"),
            "{e}"
        );
        let e = err(
            "OFF\n4 4 6\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0 1 2\n3 0 -1 1\n3 0 2 3\n3 1 3 2\n",
        );
        assert!(
            e.contains("t.off:8") && e.contains("face 1") && e.contains("negative"),
            "{e}"
        );
        let e = err(
            "OFF\n4 4 6\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0 1 2\n3 0 4 1\n3 0 2 3\n3 1 3 2\n",
        );
        assert!(
            e.contains("t.off:8") && e.contains("face 1") && e.contains("out of range"),
            "{e}"
        );
        let e = err(
            "OFF\n4 4 6\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 1 2 3\n3 1 4 2\n3 1 3 4\n3 2 4 3\n",
        );
        assert!(e.contains("one-based"), "{e}");
        let e =
            err("OFF\n4 4 6\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0 1 2\n2 0 3\n3 0 2 3\n3 1 3 2\n");
        assert!(
            e.contains("t.off:8") && e.contains("face 1 has 2 corners"),
            "{e}"
        );
        let e = err(&format!("{TET}3 0 1 2\n"));
        assert!(
            e.contains("t.off:11") && e.contains("after the last face"),
            "{e}"
        );
        let e = err("OFF BINARY\n");
        assert!(e.contains("binary OFF"), "{e}");
        let e = err("4OFF\n");
        assert!(e.contains("4D"), "{e}");
        let e = err("");
        assert!(e.contains("empty"), "{e}");
        let e = err("PLY\n");
        assert!(e.contains("not an OFF file"), "{e}");
        let e = err("OFF\n99999999999 1 0\n");
        assert!(e.contains("too many"), "{e}");
        let e = err("OFF\n1000000 1000000 0\n1 2 3\n");
        assert!(e.contains("vertex 1 of 1000000"), "{e}");
    }
}
