//! Wavefront OBJ, polygonal subset.
//!
//! Read: `v x y z [w | r g b]` (the first three numbers are the position), `f` and `fo` with
//! corners `i`, `i/t`, `i//n` or `i/t/n` (only the position index is used), one-based and
//! negative (relative) indices, `\` line continuation, `#` comments. Every other statement
//! (`vt`, `vn`, `g`, `o`, `s`, `usemtl`, `mtllib`, `l`, `p`, …) is ignored. Vertices keep
//! file order; groups and objects do not split or re-index the mesh.
//!
//! Written: `v x y z` (with `r g b` in 0…1 when colours are given, the extension MeshLab and
//! others read) and `f` with one-based indices.

use std::io::Write;
use std::path::Path;

use super::{check_indices, fmt_f64, WriteOptions};
use crate::error::{CliError, CliResult};
use crate::mesh::{Mesh, Source};

/// Reads an OBJ file.
///
/// # Errors
/// Exit 2 with file, line and element for anything malformed.
pub fn read(path: &Path, bytes: &[u8]) -> CliResult<(Mesh, Source)> {
    let err =
        |line: u32, msg: String| CliError::bad_input(format!("{}:{line}: {msg}", path.display()));
    let mut mesh = Mesh::default();
    let mut vertex_lines = Vec::new();
    let mut face_lines = Vec::new();
    let mut lines = bytes.split(|&b| b == b'\n').enumerate().peekable();
    let mut stmt: Vec<u8> = Vec::new();
    while let Some((i, raw)) = lines.next() {
        let line = u32::try_from(i + 1).unwrap_or(u32::MAX);
        // Join continuation lines (a trailing backslash).
        stmt.clear();
        let mut cur = raw;
        loop {
            let trimmed = strip_cr(cur);
            let no_comment = match trimmed.iter().position(|&b| b == b'#') {
                Some(p) => &trimmed[..p],
                None => trimmed,
            };
            let t = trim_end(no_comment);
            if let Some(body) = t.strip_suffix(b"\\") {
                stmt.extend_from_slice(body);
                stmt.push(b' ');
                match lines.next() {
                    Some((_, next)) => cur = next,
                    None => break,
                }
            } else {
                stmt.extend_from_slice(t);
                break;
            }
        }
        let text = String::from_utf8_lossy(&stmt);
        let mut toks = text.split_ascii_whitespace();
        let Some(kw) = toks.next() else { continue };
        match kw {
            "v" => {
                let v = mesh.positions.len();
                let mut p = [0.0; 3];
                for (k, c) in p.iter_mut().enumerate() {
                    let axis = ["x", "y", "z"][k];
                    let t = toks.next().ok_or_else(|| {
                        err(line, format!("vertex {v}: missing coordinate {axis}"))
                    })?;
                    *c = t.parse::<f64>().map_err(|_| {
                        err(
                            line,
                            format!("vertex {v}: coordinate {axis} is not a number: '{t}'"),
                        )
                    })?;
                }
                for t in toks {
                    if t.parse::<f64>().is_err() {
                        return Err(err(line, format!("vertex {v}: '{t}' is not a number")));
                    }
                }
                mesh.positions.push(p);
                vertex_lines.push(line);
            }
            "f" | "fo" => {
                let f = mesh.num_faces();
                let nv = mesh.positions.len() as i64;
                let start = mesh.indices.len();
                for t in toks {
                    let first = t.split('/').next().unwrap_or("");
                    let i: i64 = first.parse().map_err(|_| {
                        err(line, format!("face {f}: '{t}' is not a vertex reference"))
                    })?;
                    let resolved = match i {
                        0 => {
                            return Err(err(
                                line,
                                format!(
                                    "face {f}: index 0 is invalid (OBJ indices start at 1; \
                                     the file looks zero-based)"
                                ),
                            ))
                        }
                        i if i > 0 => i - 1,
                        i => {
                            let r = nv + i;
                            if r < 0 {
                                return Err(err(
                                    line,
                                    format!(
                                        "face {f}: relative index {i} points before the first \
                                         vertex (only {nv} vertices so far)"
                                    ),
                                ));
                            }
                            r
                        }
                    };
                    let u = u32::try_from(resolved)
                        .map_err(|_| err(line, format!("face {f}: index {i} is out of range")))?;
                    mesh.indices.push(u);
                }
                let n = mesh.indices.len() - start;
                if n < 3 {
                    return Err(err(
                        line,
                        format!("face {f} has {n} corners (a face needs at least 3)"),
                    ));
                }
                mesh.offsets.push(mesh.indices.len() as u32);
                face_lines.push(line);
            }
            _ => {}
        }
    }
    let source = Source::with_lines(path, vertex_lines, face_lines);
    check_indices(&mesh, &source, false)?;
    Ok((mesh, source))
}

fn strip_cr(s: &[u8]) -> &[u8] {
    s.strip_suffix(b"\r").unwrap_or(s)
}

fn trim_end(s: &[u8]) -> &[u8] {
    let mut end = s.len();
    while end > 0 && s[end - 1].is_ascii_whitespace() {
        end -= 1;
    }
    &s[..end]
}

/// Writes OBJ.
///
/// # Errors
/// I/O errors of `out`.
pub fn write(out: &mut dyn Write, mesh: &Mesh, opts: &WriteOptions) -> std::io::Result<()> {
    writeln!(out, "# written by nlsubdiv {}", env!("CARGO_PKG_VERSION"))?;
    writeln!(
        out,
        "# {} vertices, {} faces",
        mesh.num_vertices(),
        mesh.num_faces()
    )?;
    let colors = opts.colors.as_deref();
    for (v, p) in mesh.positions.iter().enumerate() {
        write!(
            out,
            "v {} {} {}",
            fmt_f64(p[0]),
            fmt_f64(p[1]),
            fmt_f64(p[2])
        )?;
        if let Some(c) = colors.and_then(|c| c.get(v)) {
            let f = |x: u8| fmt_f64(f64::from(x) / 255.0);
            write!(out, " {} {} {}", f(c[0]), f(c[1]), f(c[2]))?;
        }
        writeln!(out)?;
    }
    for face in mesh.faces() {
        write!(out, "f")?;
        for &i in face {
            write!(out, " {}", u64::from(i) + 1)?;
        }
        writeln!(out)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> CliResult<Mesh> {
        read(Path::new("t.obj"), s.as_bytes()).map(|(m, _)| m)
    }

    #[test]
    fn statements() {
        let m = parse(
            "# c\nmtllib x.mtl\nv 0 0 0\nv 1 0 0 1\r\nv 0 1 0 0.5 0.5 0.5\nvt 0 0\nvn 0 0 1\n\
             o a\ng b\nusemtl m\ns 1\nf 1/1/1 2//1 3\nf -3 \\\n -2 -1\nv 0 0 1\nf 1 2 4\nl 1 2\n",
        )
        .unwrap();
        assert_eq!(m.num_vertices(), 4);
        assert_eq!(m.indices, vec![0, 1, 2, 0, 1, 2, 0, 1, 3]);
        assert_eq!(m.positions[1], [1.0, 0.0, 0.0]);
    }

    #[test]
    fn errors() {
        let e = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")
            .unwrap_err()
            .message;
        assert!(e.contains("t.obj:4") && e.contains("zero-based"), "{e}");
        let e = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")
            .unwrap_err()
            .message;
        assert!(
            e.contains("t.obj:4") && e.contains("face 0") && e.contains("out of range"),
            "{e}"
        );
        let e = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 -5 2\n")
            .unwrap_err()
            .message;
        assert!(e.contains("relative index -5"), "{e}");
        let e = parse("v 0 0 0\nv 1 0 zz\n").unwrap_err().message;
        assert!(
            e.contains("t.obj:2") && e.contains("vertex 1") && e.contains("'zz'"),
            "{e}"
        );
        let e = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n")
            .unwrap_err()
            .message;
        assert!(e.contains("2 corners"), "{e}");
    }
}
