//! Stanford PLY through the `ply-rs-bw` crate: ASCII, binary little- and big-endian.
//!
//! Read: element `vertex` with `x y z` of any numeric type (other properties ignored), element
//! `face` with a list `vertex_indices` (or `vertex_index`) of any integer type; every other
//! element is read and ignored. Written: `x y z` as `double` (exact), optional
//! `red green blue` (`uchar`) and one `float` scalar per vertex, faces as
//! `list uchar int vertex_indices` (a wider count type for faces of more than 255 corners).

use std::io::{BufReader, Write};
use std::path::Path;

use ply_rs_bw::parser::{ParseError, Parser, Reader};
use ply_rs_bw::ply::{
    Addable, ElementDef, Encoding, Header, PropertyAccess, PropertyDef, PropertyType, ScalarType,
};
use ply_rs_bw::writer::Writer;

use super::{check_indices, WriteOptions};
use crate::error::{CliError, CliResult};
use crate::mesh::{Mesh, Source};

/// A vertex as read: the position and which coordinates were present.
#[derive(Debug)]
struct VertexRow {
    p: [f64; 3],
}

impl VertexRow {
    fn set(&mut self, name: &str, v: f64) -> ply_rs_bw::ply::PropertyAccessResult {
        use ply_rs_bw::ply::PropertyAccessResult::{Ignored, Set};
        let k = match name {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => return Ignored,
        };
        self.p[k] = v;
        Set
    }
}

impl PropertyAccess for VertexRow {
    fn new() -> Self {
        VertexRow { p: [0.0; 3] }
    }
    fn set_double(&mut self, n: &str, v: f64) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, v)
    }
    fn set_float(&mut self, n: &str, v: f32) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, f64::from(v))
    }
    fn set_int(&mut self, n: &str, v: i32) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, f64::from(v))
    }
    fn set_uint(&mut self, n: &str, v: u32) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, f64::from(v))
    }
    fn set_short(&mut self, n: &str, v: i16) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, f64::from(v))
    }
    fn set_ushort(&mut self, n: &str, v: u16) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, f64::from(v))
    }
    fn set_char(&mut self, n: &str, v: i8) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, f64::from(v))
    }
    fn set_uchar(&mut self, n: &str, v: u8) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, f64::from(v))
    }
}

/// A face as read: its index list, widened.
#[derive(Debug)]
struct FaceRow {
    idx: Vec<i64>,
}

impl FaceRow {
    fn set<T: Into<i64>>(&mut self, name: &str, v: Vec<T>) -> ply_rs_bw::ply::PropertyAccessResult {
        use ply_rs_bw::ply::PropertyAccessResult::{Ignored, Set};
        if name == "vertex_indices" || name == "vertex_index" {
            self.idx = v.into_iter().map(Into::into).collect();
            Set
        } else {
            Ignored
        }
    }
}

impl PropertyAccess for FaceRow {
    fn new() -> Self {
        FaceRow { idx: Vec::new() }
    }
    fn set_list_int(&mut self, n: &str, v: Vec<i32>) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, v)
    }
    fn set_list_uint(&mut self, n: &str, v: Vec<u32>) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, v)
    }
    fn set_list_short(&mut self, n: &str, v: Vec<i16>) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, v)
    }
    fn set_list_ushort(&mut self, n: &str, v: Vec<u16>) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, v)
    }
    fn set_list_char(&mut self, n: &str, v: Vec<i8>) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, v)
    }
    fn set_list_uchar(&mut self, n: &str, v: Vec<u8>) -> ply_rs_bw::ply::PropertyAccessResult {
        self.set(n, v)
    }
}

/// Any other element: read and dropped.
#[derive(Debug)]
struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}

/// An element span of an ASCII payload: name, first line, count.
type Span = (String, usize, usize);

/// A message for an error of the crate: `path:line: element i: cannot read 'text': why` for
/// ASCII element lines, `path: what: why` otherwise. The crate nests its messages as
/// `Line N: outer\n\tString: …\n\tError: inner`; the outer and innermost parts are kept.
fn parse_error(
    path: &Path,
    binary: bool,
    e: &ParseError,
    bytes: &[u8],
    spans: &[Span],
) -> CliError {
    let full = format!("{e}");
    let full = match e.line() {
        Some(l) => full
            .strip_prefix(&format!("Line {l}: "))
            .unwrap_or(&full)
            .to_string(),
        None => full,
    };
    let outer = full
        .split("\n\t")
        .next()
        .unwrap_or("")
        .trim()
        .trim_end_matches('.')
        .to_string();
    let inner = full
        .rsplit("Error: ")
        .next()
        .unwrap_or("")
        .trim()
        .to_string();
    let why = if inner.is_empty() || inner == outer {
        outer.clone()
    } else if binary || e.line().is_none() {
        format!("{outer}: {inner}")
    } else {
        inner.clone()
    };
    let p = path.display();
    let line_text = |line: usize| {
        bytes
            .split(|&b| b == b'\n')
            .nth(line.saturating_sub(1))
            .map(|l| String::from_utf8_lossy(l).trim().to_string())
            .unwrap_or_default()
    };
    // The grammar's "error at 1:COL: expected one of …" says which column is malformed.
    let why = match why.strip_prefix("error at 1:") {
        Some(rest) => {
            let col = rest.split(':').next().unwrap_or("?");
            format!("malformed or missing value at column {col}")
        }
        None => why,
    };
    let why = why.trim_end_matches('.').to_string();
    if e.kind() == std::io::ErrorKind::UnexpectedEof {
        return CliError::bad_input(format!(
            "{p}: the file ends early (truncated, or the header's counts are wrong): {why}"
        ));
    }
    match e.line() {
        Some(line) if !binary => {
            let span = spans
                .iter()
                .find(|(_, first, count)| (*first..first.saturating_add(*count)).contains(&line));
            match span {
                Some((name, first, _)) => CliError::bad_input(format!(
                    "{p}:{line}: {name} {}: cannot read '{}': {why}",
                    line - first,
                    line_text(line)
                )),
                None if spans.is_empty() => CliError::bad_input(format!(
                    "{p}:{line}: invalid PLY header line '{}'",
                    line_text(line)
                )),
                None => CliError::bad_input(format!("{p}:{line}: {why}")),
            }
        }
        _ => CliError::bad_input(format!("{p}: {why}")),
    }
}

fn is_coordinate_type(t: &PropertyType) -> bool {
    matches!(t, PropertyType::Scalar(_))
}

/// Reads a PLY file.
///
/// # Errors
/// Exit 2 for anything malformed, with the crate's line for ASCII files.
pub fn read(path: &Path, bytes: &[u8]) -> CliResult<(Mesh, Source)> {
    let mut reader = Reader::new(BufReader::new(bytes));
    let header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(|e| parse_error(path, false, &e, bytes, &[]))?;
    let binary = header.encoding != Encoding::Ascii;
    let Some(vdef) = header.elements.get("vertex") else {
        return Err(CliError::bad_input(format!(
            "{}: the PLY header declares no 'vertex' element",
            path.display()
        )));
    };
    for axis in ["x", "y", "z"] {
        match vdef.properties.get(axis) {
            Some(p) if is_coordinate_type(&p.data_type) => {}
            Some(_) => {
                return Err(CliError::bad_input(format!(
                    "{}: the PLY vertex property '{axis}' is a list, not a number",
                    path.display()
                )))
            }
            None => {
                return Err(CliError::bad_input(format!(
                    "{}: the PLY vertex element has no '{axis}' property",
                    path.display()
                )))
            }
        }
    }
    if let Some(fdef) = header.elements.get("face") {
        let has = ["vertex_indices", "vertex_index"]
            .iter()
            .any(|n| fdef.properties.get(*n).is_some());
        if !has {
            return Err(CliError::bad_input(format!(
                "{}: the PLY face element has no 'vertex_indices' list",
                path.display()
            )));
        }
    }
    let limit = (u32::MAX - 1) as usize;
    let first_payload_line = reader.line();
    let mut line = first_payload_line;
    let (mut vline, mut fline) = (0usize, 0usize);
    let mut spans = Vec::new();
    for (name, def) in &header.elements {
        spans.push((name.clone(), line, def.count));
        line = line.saturating_add(def.count);
    }
    line = first_payload_line;
    let mut verts: Vec<VertexRow> = Vec::new();
    let mut faces: Vec<FaceRow> = Vec::new();
    for (name, def) in &header.elements {
        if (name == "vertex" || name == "face") && def.count > limit {
            return Err(CliError::bad_input(format!(
                "{}: {} {name} elements: too many (at most {limit})",
                path.display(),
                def.count
            )));
        }
        match name.as_str() {
            "vertex" => {
                vline = line;
                verts = Parser::<VertexRow>::new()
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(|e| parse_error(path, binary, &e, bytes, &spans))?;
            }
            "face" => {
                fline = line;
                faces = Parser::<FaceRow>::new()
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(|e| parse_error(path, binary, &e, bytes, &spans))?;
            }
            _ => {
                Parser::<Skip>::new()
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(|e| parse_error(path, binary, &e, bytes, &spans))?;
            }
        }
        line = line.saturating_add(def.count);
    }
    let source = if binary {
        Source::new(path)
    } else {
        let l = |x: usize| u32::try_from(x).unwrap_or(u32::MAX);
        Source::with_consecutive_lines(path, l(vline), l(fline))
    };
    let mut mesh = Mesh {
        positions: verts.into_iter().map(|v| v.p).collect(),
        offsets: Vec::with_capacity(faces.len() + 1),
        indices: Vec::new(),
    };
    mesh.offsets.push(0);
    for (f, face) in faces.iter().enumerate() {
        if face.idx.len() < 3 {
            return Err(CliError::bad_input(format!(
                "{}: has {} corners (a face needs at least 3)",
                source.at_face(f),
                face.idx.len()
            )));
        }
        for &i in &face.idx {
            if i < 0 {
                return Err(CliError::bad_input(format!(
                    "{}: negative index {i} (PLY indices start at 0)",
                    source.at_face(f)
                )));
            }
            let u = u32::try_from(i).map_err(|_| {
                CliError::bad_input(format!("{}: index {i} is out of range", source.at_face(f)))
            })?;
            mesh.indices.push(u);
        }
        mesh.offsets.push(mesh.indices.len() as u32);
    }
    check_indices(&mesh, &source, true)?;
    Ok((mesh, source))
}

/// One row to write (a vertex or a face), reused for every element.
#[derive(Debug, Default)]
struct Row {
    p: [f64; 3],
    rgb: [u8; 3],
    scalar: f32,
    scalar_name: String,
    idx: Vec<i32>,
    idx_u: Vec<u32>,
}

impl PropertyAccess for Row {
    fn new() -> Self {
        Row::default()
    }
    fn get_double(&self, n: &str) -> Option<f64> {
        match n {
            "x" => Some(self.p[0]),
            "y" => Some(self.p[1]),
            "z" => Some(self.p[2]),
            _ => None,
        }
    }
    fn get_uchar(&self, n: &str) -> Option<u8> {
        match n {
            "red" => Some(self.rgb[0]),
            "green" => Some(self.rgb[1]),
            "blue" => Some(self.rgb[2]),
            _ => None,
        }
    }
    fn get_float(&self, n: &str) -> Option<f32> {
        (n == self.scalar_name).then_some(self.scalar)
    }
    fn get_list_int(&self, n: &str) -> Option<&[i32]> {
        (n == "vertex_indices").then_some(self.idx.as_slice())
    }
    fn get_list_uint(&self, n: &str) -> Option<&[u32]> {
        (n == "vertex_indices").then_some(self.idx_u.as_slice())
    }
}

fn scalar(name: &str, t: ScalarType) -> PropertyDef {
    PropertyDef::new(name.to_string(), PropertyType::Scalar(t))
}

/// Writes PLY, binary little-endian unless `opts.ply_ascii`.
///
/// # Errors
/// I/O errors of `out`.
pub fn write(out: &mut dyn Write, mesh: &Mesh, opts: &WriteOptions) -> std::io::Result<()> {
    let mut header = Header::new();
    header.encoding = if opts.ply_ascii {
        Encoding::Ascii
    } else {
        Encoding::BinaryLittleEndian
    };
    header
        .comments
        .push(format!("written by nlsubdiv {}", env!("CARGO_PKG_VERSION")));
    let mut vdef = ElementDef::new("vertex".to_string());
    vdef.count = mesh.num_vertices();
    for a in ["x", "y", "z"] {
        vdef.properties.add(scalar(a, ScalarType::Double));
    }
    let colors = opts
        .colors
        .as_deref()
        .filter(|c| c.len() == mesh.num_vertices());
    if colors.is_some() {
        for c in ["red", "green", "blue"] {
            vdef.properties.add(scalar(c, ScalarType::UChar));
        }
    }
    let values = opts
        .scalar
        .as_ref()
        .filter(|(_, v)| v.len() == mesh.num_vertices());
    if let Some((name, _)) = values {
        vdef.properties.add(scalar(name, ScalarType::Float));
    }
    let mut fdef = ElementDef::new("face".to_string());
    fdef.count = mesh.num_faces();
    let max_corners = mesh.faces().map(<[u32]>::len).max().unwrap_or(0);
    let count_type = if max_corners <= usize::from(u8::MAX) {
        ScalarType::UChar
    } else if max_corners <= usize::from(u16::MAX) {
        ScalarType::UShort
    } else {
        ScalarType::UInt
    };
    let wide = mesh.num_vertices() > i32::MAX as usize;
    let index_type = if wide {
        ScalarType::UInt
    } else {
        ScalarType::Int
    };
    fdef.properties.add(PropertyDef::new(
        "vertex_indices".to_string(),
        PropertyType::List(count_type, index_type),
    ));
    header.elements.add(vdef.clone());
    header.elements.add(fdef.clone());

    let w = Writer::<Row>::new();
    let mut out = out;
    w.write_header(&mut out, &header)?;
    let mut row = Row {
        scalar_name: values.map(|(n, _)| n.clone()).unwrap_or_default(),
        ..Row::default()
    };
    let put = |out: &mut &mut dyn Write, row: &Row, def: &ElementDef| -> std::io::Result<usize> {
        if opts.ply_ascii {
            w.write_ascii_element(out, row, def)
        } else {
            w.write_little_endian_element(out, row, def)
        }
    };
    for (v, p) in mesh.positions.iter().enumerate() {
        row.p = *p;
        if let Some(c) = colors {
            row.rgb = c[v];
        }
        if let Some((_, vals)) = values {
            row.scalar = vals[v] as f32;
        }
        put(&mut out, &row, &vdef)?;
    }
    for face in mesh.faces() {
        if wide {
            row.idx_u.clear();
            row.idx_u.extend_from_slice(face);
        } else {
            row.idx.clear();
            row.idx.extend(face.iter().map(|&i| i as i32));
        }
        put(&mut out, &row, &fdef)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &[u8]) -> CliResult<Mesh> {
        read(Path::new("t.ply"), s).map(|(m, _)| m)
    }

    const HEAD: &str = "ply\nformat ascii 1.0\ncomment hi\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";

    #[test]
    fn ascii_with_lines() {
        let ok = format!(
            "{HEAD}1 1 1 0\n1 -1 -1 0\n-1 1 -1 0\n-1 -1 1 0\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n"
        );
        let m = parse(ok.as_bytes()).unwrap();
        assert_eq!(m.num_faces(), 4);
        assert_eq!(m.positions[3], [-1.0, -1.0, 1.0]);
        let bad = format!(
            "{HEAD}1 1 1 0\n1 -1 -1 0\n-1 1 -1 0\n-1 -1 1 0\n3 0 1 2\n3 0 3 1\n3 0 2 -3\n3 1 3 2\n"
        );
        let e = parse(bad.as_bytes()).unwrap_err().message;
        assert!(
            e.contains("t.ply:18") && e.contains("face 2") && e.contains("negative"),
            "{e}"
        );
        let bad = format!("{HEAD}1 1 1 0\n1 -1 -1 0\n-1 1 -1 0\n-1 -1 nan 0\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n");
        let e = parse(bad.as_bytes()).unwrap_err().message;
        assert!(
            e.starts_with("t.ply:15: vertex 3: cannot read '-1 -1 nan 0'"),
            "{e}"
        );
        let bad = format!("{HEAD}1 1 1 0\n1 -1 -1 0\n-1 1 -1 0\n-1 -1 1 0\n3 0 1 2\n3 0 3 1\n");
        let e = parse(bad.as_bytes()).unwrap_err().message;
        assert!(e.to_lowercase().contains("end of file"), "{e}");
        let one = format!(
            "{HEAD}1 1 1 0\n1 -1 -1 0\n-1 1 -1 0\n-1 -1 1 0\n3 1 2 3\n3 1 4 2\n3 1 3 4\n3 2 4 3\n"
        );
        let e = parse(one.as_bytes()).unwrap_err().message;
        assert!(e.contains("one-based"), "{e}");
    }
}
