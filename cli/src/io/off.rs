//! OFF (Object File Format, Geomview's definition), ASCII.
//!
//! The grammar, as Geomview's manual defines it:
//!
//! ```text
//! [ST][C][N][4][n]OFF          keyword, optional; the prefixes in this order
//! [Ndim]                       only with n: the space dimension
//! NVertices NFaces NEdges      NEdges is not used
//! x y z [w] [nx ny nz] [colour] [s t]     one vertex; in this order
//! Nv v[0] … v[Nv-1] [colour]   one face; the colour is the rest of the line
//! ```
//!
//! * `N`: a normal (3 numbers) per vertex; `C`: a colour per vertex (Geomview writes 4
//!   numbers, RGBA; 3, RGB, and 1, a colour-map index, are read too); `ST`: texture
//!   coordinates (2 numbers); `4`: homogeneous coordinates, the position is `x/w y/w z/w`
//!   (`w = 0`, a point at infinity, is refused); `n`: the dimension follows the keyword
//!   (2 or 3 here: a 2-dimensional mesh lies in the plane `z = 0`; `4n` adds the
//!   homogeneous coordinate). Normals, colours and texture coordinates are checked as
//!   numbers and not used.
//! * The counts are one line of three integers (the edge count may be 0 and is not used;
//!   it may be left out, since it is the last thing on the line); the counts may share the
//!   keyword's line.
//! * Every vertex is one line holding exactly the numbers the keyword declares: a line with
//!   more or fewer is refused, naming it (an `OFF` file with colours on its vertex lines, or
//!   `COFF` with numbers the keyword does not account for, would otherwise shift every
//!   later coordinate). Geomview itself reads vertices as a stream of numbers; every file
//!   it writes has one vertex per line.
//! * A face's indices may wrap over several lines; the numbers after the last index on its
//!   line are the face colour: none, 1 (colour-map index), 3 or 4 (RGB or RGBA).
//! * `#` starts a comment anywhere; blank lines, tabs, LF, CR LF and CR line ends are
//!   fine; a UTF-8 byte-order mark at the start is skipped. Keywords are case-sensitive
//!   (`N` and `n` mean different things): `off` is refused with a message saying so.
//!   `OFF BINARY` is refused (use ASCII OFF or PLY).
//!
//! Anything after the last face other than comments is an error (the counts are wrong).

use std::io::Write;
use std::path::Path;

use super::text::{self, parse_f64, parse_i64};
use super::{check_indices, fmt_f64, WriteOptions};
use crate::error::{quote, CliError, CliResult};
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

struct Ctx<'p> {
    path: &'p Path,
}

impl Ctx<'_> {
    fn err(&self, line: u32, msg: impl std::fmt::Display) -> CliError {
        CliError::bad_input(format!("{}:{line}: {msg}", self.path.display()))
    }
}

/// What the keyword declares about every vertex line.
#[derive(Clone, Copy, Debug)]
struct Layout {
    texcoords: bool,
    colors: bool,
    normals: bool,
    homogeneous: bool,
    /// `n`: the dimension is given after the keyword.
    ndim: bool,
    /// The space dimension (3 unless `n`).
    dim: usize,
}

impl Default for Layout {
    fn default() -> Self {
        Layout {
            texcoords: false,
            colors: false,
            normals: false,
            homogeneous: false,
            ndim: false,
            dim: 3,
        }
    }
}

impl Layout {
    /// Coordinates per vertex (the homogeneous one included).
    fn coords(&self) -> usize {
        self.dim + usize::from(self.homogeneous)
    }

    /// A description of the vertex line, for messages.
    fn describe(&self) -> String {
        let mut parts = vec![match (self.dim, self.homogeneous) {
            (2, false) => "x y",
            (2, true) => "x y w",
            (_, false) => "x y z",
            (_, true) => "x y z w",
        }
        .to_string()];
        if self.normals {
            parts.push("nx ny nz".into());
        }
        if self.colors {
            parts.push("r g b a (or r g b, or a colour-map index)".into());
        }
        if self.texcoords {
            parts.push("s t".into());
        }
        parts.join(" ")
    }
}

/// Parses the keyword `[ST][C][N][4][n]OFF`, if there is one.
fn keyword(ctx: &Ctx<'_>, toks: &mut Tokens<'_>) -> CliResult<Layout> {
    let Some(t) = toks.peek() else {
        return Err(CliError::bad_input(format!(
            "{}: the file is empty",
            ctx.path.display()
        )));
    };
    if parse_i64(t.text).is_some() {
        return Ok(Layout::default()); // no keyword: counts first
    }
    let Some(prefix) = t.text.strip_suffix(b"OFF") else {
        let upper = t.text.to_ascii_uppercase();
        if upper.ends_with(b"OFF") && upper.len() <= 9 {
            return Err(ctx.err(
                t.line,
                format_args!(
                    "{}: OFF keywords are case-sensitive (the prefixes N and n mean different \
                     things): write OFF, COFF, NOFF, …",
                    quote(t.text)
                ),
            ));
        }
        let hint = if t.text.starts_with(b"ply") {
            " (the file looks like PLY)"
        } else if matches!(t.text, b"v" | b"#" | b"o" | b"g" | b"mtllib") {
            " (the file looks like OBJ)"
        } else {
            ""
        };
        return Err(ctx.err(
            t.line,
            format_args!(
                "not an OFF file: expected the keyword OFF or the vertex count, found {}{hint}",
                quote(t.text)
            ),
        ));
    };
    toks.next();
    let mut e = Layout::default();
    let mut rest = prefix;
    for (p, flag) in [
        (&b"ST"[..], &mut e.texcoords),
        (b"C", &mut e.colors),
        (b"N", &mut e.normals),
        (b"4", &mut e.homogeneous),
        (b"n", &mut e.ndim),
    ] {
        if let Some(r) = rest.strip_prefix(p) {
            *flag = true;
            rest = r;
        }
    }
    if !rest.is_empty() {
        return Err(ctx.err(
            t.line,
            format_args!(
                "unknown OFF keyword {} (the keyword is [ST][C][N][4][n]OFF, prefixes in \
                 this order)",
                quote(t.text)
            ),
        ));
    }
    if let Some(n) = toks.next_on_line(t.line) {
        if n.text == b"BINARY" {
            return Err(ctx.err(n.line, "binary OFF is not supported (use ASCII OFF or PLY)"));
        }
        // Counts (or the dimension) on the keyword's line: hand the token back.
        toks.peeked = Some(Some(n));
    }
    if e.ndim {
        let d = toks.next().ok_or_else(|| {
            ctx.err(
                toks.last_line(),
                "the file ends before the dimension (nOFF)",
            )
        })?;
        e.dim = match parse_i64(d.text) {
            Some(2) => 2,
            Some(3) => 3,
            Some(k) => {
                return Err(ctx.err(
                    d.line,
                    format_args!(
                        "dimension {k}: only 2- and 3-dimensional OFF meshes are supported"
                    ),
                ))
            }
            None => {
                return Err(ctx.err(
                    d.line,
                    format_args!(
                        "the dimension of nOFF must be an integer, found {}",
                        quote(d.text)
                    ),
                ))
            }
        };
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
                    "the {what} must be a non-negative integer, found {}",
                    quote(t.text)
                ),
            )
        })
}

/// Reads one vertex line: the position, after checking that the line holds exactly the
/// numbers `layout` declares.
fn vertex(
    ctx: &Ctx<'_>,
    toks: &mut Tokens<'_>,
    layout: &Layout,
    v: u64,
    nv: u64,
) -> CliResult<(u32, [f64; 3])> {
    let first = toks.next().ok_or_else(|| {
        ctx.err(
            toks.last_line(),
            format_args!(
                "the file ends in vertex {v} of {nv} (truncated, or the header's vertex count \
                 is wrong)"
            ),
        )
    })?;
    let line = first.line;
    let mut vals: Vec<f64> = Vec::with_capacity(16);
    let mut tok = Some(first);
    while let Some(t) = tok {
        let x = parse_f64(t.text).ok_or_else(|| {
            let what = match vals.len() {
                0 => "coordinate x".to_string(),
                1 => "coordinate y".to_string(),
                2 if layout.dim == 3 => "coordinate z".to_string(),
                k => format!("value {}", k + 1),
            };
            ctx.err(
                line,
                format_args!("vertex {v}: {what} is not a number: {}", quote(t.text)),
            )
        })?;
        vals.push(x);
        if vals.len() > 64 {
            break;
        }
        tok = toks.next_on_line(line);
    }
    let fixed =
        layout.coords() + if layout.normals { 3 } else { 0 } + if layout.texcoords { 2 } else { 0 };
    let color = vals.len().checked_sub(fixed);
    let fits = match color {
        Some(0) => !layout.colors,
        Some(1 | 3 | 4) => layout.colors,
        _ => false,
    };
    if !fits {
        let hint = if !layout.colors && !layout.normals && !layout.texcoords && vals.len() > fixed {
            "; a keyword COFF, NOFF or STOFF declares colours, normals or texture coordinates"
        } else {
            ""
        };
        return Err(ctx.err(
            line,
            format_args!(
                "vertex {v} has {}{} numbers on its line, but this OFF keyword declares {} \
                 (one vertex per line){hint}",
                vals.len().min(64),
                if vals.len() > 64 { " or more" } else { "" },
                layout.describe()
            ),
        ));
    }
    let mut p = [0.0; 3];
    for (k, c) in p.iter_mut().enumerate().take(layout.dim) {
        *c = vals.get(k).copied().unwrap_or(0.0);
    }
    if layout.homogeneous {
        let w = vals.get(layout.dim).copied().unwrap_or(1.0);
        if w == 0.0 || !w.is_finite() {
            return Err(ctx.err(
                line,
                format_args!(
                    "vertex {v}: homogeneous coordinate w = {w} (a point at infinity, or not a \
                     number): 4OFF positions are x/w y/w z/w"
                ),
            ));
        }
        for (k, c) in p.iter_mut().enumerate().take(layout.dim) {
            let q = *c / w;
            if c.is_finite() && !q.is_finite() {
                return Err(ctx.err(
                    line,
                    format_args!(
                        "vertex {v}: {} / w overflows ({c:e} / {w:e})",
                        ["x", "y", "z"][k]
                    ),
                ));
            }
            *c = q;
        }
    }
    Ok((line, p))
}

/// Reads an OFF file.
///
/// # Errors
/// Exit 2 with the file, line and element for anything malformed (see the module docs).
pub fn read(path: &Path, bytes: &[u8]) -> CliResult<(Mesh, Source)> {
    let ctx = Ctx { path };
    let bytes = text::strip_bom(path, bytes)?;
    let mut toks = Tokens::new(bytes);
    let layout = keyword(&ctx, &mut toks)?;
    let t_nv = toks.next();
    let nv = parse_count(&ctx, t_nv, "vertex count", toks.last_line())?;
    let counts_line = t_nv.map_or(1, |t| t.line);
    let t_nf = toks.next_on_line(counts_line);
    if t_nf.is_none() {
        return Err(ctx.err(
            counts_line,
            "the counts line must hold the vertex, face and edge counts ('V F E')",
        ));
    }
    let nf = parse_count(&ctx, t_nf, "face count", toks.last_line())?;
    // The edge count, when it is there (the last number of the line: it is not used).
    if let Some(e) = toks.next_on_line(counts_line) {
        if parse_count(&ctx, Some(e), "edge count", counts_line).is_err() {
            return Err(ctx.err(
                e.line,
                format_args!(
                    "the edge count must be a non-negative integer, found {}",
                    quote(e.text)
                ),
            ));
        }
    }
    if let Some(x) = toks.next_on_line(counts_line) {
        return Err(ctx.err(
            x.line,
            format_args!(
                "unexpected {} after the counts 'V F E' on their line",
                quote(x.text)
            ),
        ));
    }
    let limit = u64::from(u32::MAX - 1);
    if nv > limit || nf > limit {
        return Err(ctx.err(
            counts_line,
            format_args!("{nv} vertices, {nf} faces: too many (at most {limit} each)"),
        ));
    }
    // Every vertex takes at least 6 bytes and every face at least 8: cap the reservation by
    // the file size so that a lying header cannot exhaust memory.
    let cap = |n: u64, min_bytes: usize| (n as usize).min(bytes.len() / min_bytes + 1);
    let mut positions = Vec::with_capacity(cap(nv, 6));
    let mut vertex_lines = Vec::with_capacity(cap(nv, 6));
    for v in 0..nv {
        let (line, p) = vertex(&ctx, &mut toks, &layout, v, nv)?;
        vertex_lines.push(line);
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
        let n = parse_i64(t.text).ok_or_else(|| {
            ctx.err(
                t.line,
                format_args!(
                    "face {f}: the corner count must be an integer, found {}",
                    quote(t.text)
                ),
            )
        })?;
        if n < 3 {
            return Err(ctx.err(
                t.line,
                format_args!("face {f} has {n} corners (a face needs at least 3)"),
            ));
        }
        // A face may name a vertex twice (more corners than vertices): that is a defect of
        // the mesh, which the topology check names, not of the file; the same face read from
        // OBJ or PLY must give the same answer. A lying count runs into the end of the file.
        let mut last_line = t.line;
        for _ in 0..n {
            let t = toks.next().ok_or_else(|| eof(&toks))?;
            last_line = t.line;
            let i = parse_i64(t.text).ok_or_else(|| {
                ctx.err(
                    t.line,
                    format_args!("face {f}: index {} is not an integer", quote(t.text)),
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
        let mut ncol = 0usize;
        while let Some(c) = toks.next_on_line(last_line) {
            if parse_f64(c.text).is_none() {
                return Err(ctx.err(
                    c.line,
                    format_args!("face {f}: unexpected {} after its indices", quote(c.text)),
                ));
            }
            ncol += 1;
        }
        if !matches!(ncol, 0 | 1 | 3 | 4) {
            return Err(ctx.err(
                last_line,
                format_args!(
                    "face {f}: {ncol} numbers after its {n} indices; a face colour is 1 \
                     (colour-map index), 3 or 4 numbers (is the corner count right?)"
                ),
            ));
        }
        let end = u32::try_from(mesh.indices.len())
            .map_err(|_| ctx.err(last_line, "more corners than 32-bit indices can hold"))?;
        mesh.offsets.push(end);
    }
    if let Some(t) = toks.next() {
        return Err(ctx.err(
            t.line,
            format_args!(
                "unexpected {} after the last face (the header says {nv} vertices and {nf} \
                 faces)",
                quote(t.text)
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
        assert!(e.contains("ends before the vertex count"), "{e}");
        let e = err("4nOFF 4\n");
        assert!(e.contains("dimension 4"), "{e}");
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
