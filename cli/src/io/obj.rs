//! Wavefront OBJ, polygonal subset.
//!
//! Read, statement by statement (a line, joined with the next ones while it ends in `\`;
//! `#` starts a comment; a UTF-8 byte-order mark at the start is skipped; lines end at LF,
//! CR LF or CR):
//!
//! * `v x y z`, `v x y z w` (`w` is the weight of rational free-form geometry, which has no
//!   meaning for polygons: the position is `x y z`) and `v x y z r g b` (the vertex-colour
//!   extension MeshLab and others write); any other number of values is refused;
//! * `f` and `fo` with corners `v`, `v/vt`, `v//vn` or `v/vt/vn`: one-based or negative
//!   (relative: `-1` is the last vertex so far) indices; the texture and normal references
//!   are checked (integers, not 0, in range) but not used;
//! * `vt`, `vn`, `vp` (counted and checked as numbers), and the grouping, display and
//!   material statements `g`, `o`, `s`, `mg`, `usemtl`, `mtllib`, `usemap`, `maplib`, `lod`,
//!   `bevel`, `c_interp`, `d_interp`, `shadow_obj`, `trace_obj` are read and ignored; so are
//!   point and line elements `p` and `l` (not polygons: a polygon mesh has none);
//! * OpenSubdiv's shape tags `t NAME ni/nf/ns INTS FLOATS STRINGS` for sharp features, with
//!   0-based vertex indices: `t crease n/m/0 v0 … v(n−1) s…` tags the edges of the chain
//!   `v0 – v1 – …` (`n ≥ 2`) with one sharpness for all (`m = 1`) or one per edge
//!   (`m = n − 1`); `t corner n/m/0 v… s…` tags vertices, one sharpness for all or one each.
//!   Other tag names (`interpolateboundary`, `hole`, …) are refused naming the line (they
//!   would change the surface); whether a pair is an edge, a tag is repeated or a sharpness
//!   valid, the kernel checks, and the command names this line;
//! * free-form geometry (`cstype`, `curv`, `surf`, … ), `call` and `csh`, and every statement
//!   the format does not define are refused, naming the line and the statement: a mangled
//!   keyword (a stray byte-order mark, a control byte, `V` for `v`) must never drop a vertex
//!   and silently renumber every later one.
//!
//! Vertices keep file order; groups and objects do not split or re-index the mesh.
//!
//! Written: `v x y z` (with `r g b` in 0…1 when colours are given, the extension MeshLab and
//! others read) and `f` with one-based indices.

use std::io::Write;
use std::path::Path;

use super::text::{self, parse_f64, parse_i64};
use super::{check_indices, fmt_f64, WriteOptions};
use crate::error::{quote, CliError, CliResult};
use crate::mesh::{FileTags, Mesh, Source};

/// Statements that are read and ignored: they carry no polygon geometry.
const IGNORED: &[&[u8]] = &[
    b"g",
    b"o",
    b"s",
    b"mg",
    b"usemtl",
    b"mtllib",
    b"usemap",
    b"maplib",
    b"lod",
    b"bevel",
    b"c_interp",
    b"d_interp",
    b"shadow_obj",
    b"trace_obj",
    b"p",
    b"l",
];

/// Free-form geometry statements: refused (curves and surfaces are not polygons, and
/// dropping them would give a different mesh).
const FREE_FORM: &[&[u8]] = &[
    b"cstype", b"deg", b"bmat", b"step", b"curv", b"curv2", b"surf", b"parm", b"trim", b"hole",
    b"scrv", b"sp", b"end", b"con", b"ctech", b"stech",
];

/// Counts of the attribute vertices, for checking the `vt` and `vn` references of corners.
#[derive(Default)]
struct Refs {
    vt: i64,
    vn: i64,
    /// The largest positive `vt`/`vn` reference and its line (checked at the end: OBJ
    /// allows references to elements defined later in the file).
    max_vt: Option<(i64, u32)>,
    max_vn: Option<(i64, u32)>,
}

/// Reads an OBJ file.
///
/// # Errors
/// Exit 2 with file, line and element for anything malformed or not supported.
pub fn read(path: &Path, bytes: &[u8]) -> CliResult<(Mesh, Source)> {
    let err =
        |line: u32, msg: String| CliError::bad_input(format!("{}:{line}: {msg}", path.display()));
    let bytes = text::strip_bom(path, bytes)?;
    let mut mesh = Mesh::default();
    let mut vertex_lines = Vec::new();
    let mut face_lines = Vec::new();
    let mut refs = Refs::default();
    let mut tags = FileTags::default();
    let mut lines = text::Lines::new(bytes, 1);
    let mut stmt: Vec<u8> = Vec::new();
    while let Some((line, raw)) = lines.next() {
        // Join continuation lines (a trailing backslash).
        stmt.clear();
        let mut cur = raw;
        loop {
            let no_comment = match cur.iter().position(|&b| b == b'#') {
                Some(p) => cur.get(..p).unwrap_or(cur),
                None => cur,
            };
            let t = no_comment.trim_ascii_end();
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
        let mut toks = text::tokens(&stmt);
        let Some(kw) = toks.next() else { continue };
        match kw {
            b"v" => {
                let v = mesh.positions.len();
                let vals: Vec<&[u8]> = toks.collect();
                let mut nums = Vec::with_capacity(vals.len());
                for (k, t) in vals.iter().enumerate() {
                    let what = match k {
                        0 => "coordinate x".to_string(),
                        1 => "coordinate y".to_string(),
                        2 => "coordinate z".to_string(),
                        k => format!("value {}", k + 1),
                    };
                    let x = parse_f64(t).ok_or_else(|| {
                        err(
                            line,
                            format!("vertex {v}: {what} is not a number: {}", quote(t)),
                        )
                    })?;
                    nums.push(x);
                }
                let [x, y, z] = match nums.as_slice() {
                    [x, y, z] | [x, y, z, _] | [x, y, z, _, _, _] => [*x, *y, *z],
                    _ => {
                        return Err(err(
                            line,
                            format!(
                                "vertex {v} has {} values; a vertex is 'v x y z', 'v x y z w' \
                                 or 'v x y z r g b'",
                                nums.len()
                            ),
                        ))
                    }
                };
                mesh.positions.push([x, y, z]);
                vertex_lines.push(line);
            }
            b"vt" | b"vn" | b"vp" => {
                let name = String::from_utf8_lossy(kw).into_owned();
                let mut n = 0usize;
                for t in toks {
                    if parse_f64(t).is_none() {
                        return Err(err(
                            line,
                            format!("'{name}' value {} is not a number", quote(t)),
                        ));
                    }
                    n += 1;
                }
                let (lo, hi) = if kw == b"vn" { (3, 3) } else { (1, 3) };
                if !(lo..=hi).contains(&n) {
                    return Err(err(
                        line,
                        format!("'{name}' has {n} values (it takes {lo} to {hi})"),
                    ));
                }
                match kw {
                    b"vt" => refs.vt += 1,
                    b"vn" => refs.vn += 1,
                    _ => {}
                }
            }
            b"f" | b"fo" => {
                let f = mesh.num_faces();
                let nv = mesh.positions.len() as i64;
                let start = mesh.indices.len();
                for t in toks {
                    let i = corner(t, nv, &mut refs, line).map_err(|why| {
                        err(line, format!("face {f}: corner {}: {why}", quote(t)))
                    })?;
                    mesh.indices.push(i);
                }
                let n = mesh.indices.len() - start;
                if n < 3 {
                    return Err(err(
                        line,
                        format!("face {f} has {n} corners (a face needs at least 3)"),
                    ));
                }
                let end = u32::try_from(mesh.indices.len()).map_err(|_| {
                    err(
                        line,
                        "more corners than 32-bit indices can hold".to_string(),
                    )
                })?;
                mesh.offsets.push(end);
                face_lines.push(line);
            }
            b"t" => tag(&mut toks, line, &mut tags).map_err(|why| err(line, why))?,
            kw if IGNORED.contains(&kw) => {}
            kw if FREE_FORM.contains(&kw) => {
                return Err(err(
                    line,
                    format!(
                        "{}: free-form curves and surfaces are not supported (only polygons)",
                        quote(kw)
                    ),
                ))
            }
            kw => {
                return Err(err(
                    line,
                    format!(
                        "unknown OBJ statement {} (a keyword such as v, vt, vn, f, g, o, s, \
                         usemtl must start the line)",
                        quote(kw)
                    ),
                ))
            }
        }
    }
    for (max, count, what) in [
        (refs.max_vt, refs.vt, "texture vertex"),
        (refs.max_vn, refs.vn, "normal"),
    ] {
        if let Some((i, line)) = max {
            if i > count {
                return Err(err(
                    line,
                    format!("{what} {i} does not exist (the file has {count})"),
                ));
            }
        }
    }
    let mut source = Source::with_lines(path, vertex_lines, face_lines);
    source.tags = tags;
    check_indices(&mesh, &source, false)?;
    Ok((mesh, source))
}

/// One `t` statement (module docs) into `tags`.
fn tag<'a>(
    toks: &mut impl Iterator<Item = &'a [u8]>,
    line: u32,
    tags: &mut FileTags,
) -> Result<(), String> {
    let name = toks.next().ok_or("'t' without a tag name")?;
    let counts = toks
        .next()
        .ok_or("'t': no counts ni/nf/ns after the name")?;
    let n: Vec<usize> = std::str::from_utf8(counts)
        .ok()
        .map(|s| {
            s.split('/')
                .map(str::parse)
                .collect::<Result<Vec<usize>, _>>()
        })
        .and_then(Result::ok)
        .filter(|n| n.len() == 3)
        .ok_or_else(|| format!("'t': counts {} are not ni/nf/ns", quote(counts)))?;
    let (ni, nf, ns) = (n[0], n[1], n[2]);
    let rest: Vec<&[u8]> = toks.collect();
    // Checked: the counts come from the file and may be as large as `usize` allows.
    let announced = ni.checked_add(nf).and_then(|x| x.checked_add(ns));
    if announced != Some(rest.len()) {
        return Err(format!(
            "tag {}: {} values after the counts, {ni}/{nf}/{ns} announce {}",
            quote(name),
            rest.len(),
            announced.map_or_else(|| "more than can be counted".to_string(), |a| a.to_string())
        ));
    }
    let mut ints = Vec::with_capacity(ni);
    for t in &rest[..ni] {
        let v = parse_i64(t)
            .and_then(|v| u32::try_from(v).ok())
            .ok_or_else(|| format!("tag vertex {} is not a 0-based index", quote(t)))?;
        ints.push(v);
    }
    let mut floats = Vec::with_capacity(nf);
    for t in &rest[ni..ni + nf] {
        floats.push(parse_f64(t).ok_or_else(|| format!("sharpness {} is not a number", quote(t)))?);
    }
    let shared = nf == 1;
    match name {
        b"crease" => {
            if ni < 2 || ns != 0 || !(shared || nf == ni - 1) {
                return Err(format!(
                    "'t crease {ni}/{nf}/{ns}': a crease is n/1/0 or n/(n-1)/0 with n ≥ 2 vertices"
                ));
            }
            for (k, w) in ints.windows(2).enumerate() {
                tags.creases.push([w[0], w[1]]);
                tags.crease_sharpness
                    .push(floats[if shared { 0 } else { k }]);
                tags.crease_lines.push(line);
            }
        }
        b"corner" => {
            if ni < 1 || ns != 0 || !(shared || nf == ni) {
                return Err(format!(
                    "'t corner {ni}/{nf}/{ns}': a corner tag is n/1/0 or n/n/0 with n ≥ 1 vertices"
                ));
            }
            for (k, &v) in ints.iter().enumerate() {
                tags.corners.push(v);
                tags.corner_sharpness
                    .push(floats[if shared { 0 } else { k }]);
                tags.corner_lines.push(line);
            }
        }
        other => {
            return Err(format!(
                "tag {} is not supported (only crease and corner)",
                quote(other)
            ))
        }
    }
    Ok(())
}

/// Resolves one OBJ reference (`i` one-based or negative relative to `count` so far) to a
/// zero-based index; positive references beyond `count` are checked by the caller.
fn resolve(t: &[u8], count: i64, what: &str) -> Result<i64, String> {
    let i = parse_i64(t).ok_or_else(|| format!("the {what} reference is not an integer"))?;
    match i {
        0 => Err(format!(
            "{what} index 0 is invalid (OBJ indices start at 1; the file looks zero-based)"
        )),
        i if i > 0 => Ok(i - 1),
        i => {
            let r = count + i;
            if r < 0 {
                Err(format!(
                    "relative index {i} points before the first {what} (only {count} so far)"
                ))
            } else {
                Ok(r)
            }
        }
    }
}

/// One face corner `v`, `v/vt`, `v//vn` or `v/vt/vn`: the zero-based vertex index.
fn corner(t: &[u8], nv: i64, refs: &mut Refs, line: u32) -> Result<u32, String> {
    let parts: Vec<&[u8]> = t.split(|&b| b == b'/').collect();
    let (v, vt, vn) = match parts.as_slice() {
        [v] => (*v, None, None),
        [v, vt] => (*v, Some(*vt), None),
        [v, vt, vn] => (*v, (!vt.is_empty()).then_some(*vt), Some(*vn)),
        _ => return Err("a corner is v, v/vt, v//vn or v/vt/vn".to_string()),
    };
    let i = resolve(v, nv, "vertex")?;
    for (part, count, max, what) in [
        (vt, refs.vt, &mut refs.max_vt, "texture vertex"),
        (vn, refs.vn, &mut refs.max_vn, "normal"),
    ] {
        if let Some(p) = part {
            let r = resolve(p, count, what)?;
            let one_based = r + 1;
            if max.is_none_or(|(m, _)| one_based > m) {
                *max = Some((one_based, line));
            }
        }
    }
    u32::try_from(i).map_err(|_| format!("vertex index {} is out of range", i + 1))
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
    if let Some(t) = &opts.tags {
        for ([a, b], &s) in t.creases.iter().zip(&t.crease_sharpness) {
            writeln!(out, "t crease 2/1/0 {a} {b} {}", fmt_f64(s))?;
        }
        for (v, &s) in t.corners.iter().zip(&t.corner_sharpness) {
            writeln!(out, "t corner 1/1/0 {v} {}", fmt_f64(s))?;
        }
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
        // Tag counts whose sum overflows (a fuzz finding): an error naming the line.
        let e = parse(&format!(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nt crease {}/1/0 0 1 10\n",
            usize::MAX
        ))
        .unwrap_err()
        .message;
        assert!(
            e.contains("t.obj:5") && e.contains("more than can be counted"),
            "{e}"
        );
    }
}
