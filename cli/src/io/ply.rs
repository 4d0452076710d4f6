//! Stanford PLY: ASCII, binary little- and big-endian.
//!
//! **Read** by the reader below, which follows the PLY definition (Turk, "The PLY Polygon
//! File Format") and refuses, naming the line (ASCII) or the byte offset (binary), whatever
//! it cannot read exactly:
//!
//! * the header: the magic line `ply`, one `format ascii|binary_little_endian|
//!   binary_big_endian 1.0` line, `comment` and `obj_info` lines (ignored), `element NAME
//!   COUNT`, `property TYPE NAME` and `property list COUNT_TYPE ITEM_TYPE NAME`, `end_header`.
//!   Types: `char uchar short ushort int uint float double` and their sized names `int8 uint8
//!   int16 uint16 int32 uint32 float32 float64`. An element or a property named twice in an
//!   element, a property before any element, an element without properties, an unknown line
//!   and a list count of a floating type are refused (the column of every later value would
//!   be ambiguous). Keywords are case-sensitive; the header's lines end at LF, CR LF or CR
//!   (the line end of `ply` says which, and the binary data starts after `end_header`'s);
//!   a UTF-8 byte-order mark before `ply` is skipped.
//! * the data: element `vertex` with scalar properties `x y z` of any type (other properties
//!   read and ignored), element `face` with a list `vertex_indices` (or `vertex_index`) of an
//!   integer type; every other element is read (checked) and ignored. `float` values are
//!   32-bit: an ASCII value of a `float` property is rounded to the nearest `f32`, as a
//!   binary one would be. ASCII: one element per line, with exactly its properties' values
//!   (blank lines are skipped); integer values must be integers in their type's range.
//! * anything after the last element (other than white space in ASCII) is refused: the
//!   counts are wrong or the file is not what the header says.
//!
//! **Written** through the `ply-rs-bw` crate: `x y z` as `double` (exact), optional
//! `red green blue` (`uchar`) and one `float` scalar per vertex, faces as
//! `list uchar int vertex_indices` (a wider count type for faces of more than 255 corners).

use std::io::Write;
use std::path::Path;

use ply_rs_bw::ply::{
    Addable, ElementDef, Encoding, Header, PropertyAccess, PropertyDef, PropertyType, ScalarType,
};
use ply_rs_bw::writer::Writer;

use super::text::{self, Lines};
use super::{check_indices, WriteOptions};
use crate::error::{quote, CliError, CliResult};
use crate::mesh::{Mesh, Source};

/// A scalar type of the format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn from_name(name: &[u8]) -> Option<Scalar> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// The range of an integer type.
    fn range(self) -> (i64, i64) {
        match self {
            Scalar::I8 => (i8::MIN.into(), i8::MAX.into()),
            Scalar::U8 => (0, u8::MAX.into()),
            Scalar::I16 => (i16::MIN.into(), i16::MAX.into()),
            Scalar::U16 => (0, u16::MAX.into()),
            Scalar::I32 => (i32::MIN.into(), i32::MAX.into()),
            Scalar::U32 => (0, u32::MAX.into()),
            Scalar::F32 | Scalar::F64 => (i64::MIN, i64::MAX),
        }
    }

    fn name(self) -> &'static str {
        match self {
            Scalar::I8 => "char",
            Scalar::U8 => "uchar",
            Scalar::I16 => "short",
            Scalar::U16 => "ushort",
            Scalar::I32 => "int",
            Scalar::U32 => "uint",
            Scalar::F32 => "float",
            Scalar::F64 => "double",
        }
    }
}

/// A value as read: integers exactly, floating values widened to `f64` (exactly).
#[derive(Clone, Copy, Debug)]
enum Value {
    Int(i64),
    Float(f64),
}

impl Value {
    fn as_f64(self) -> f64 {
        match self {
            Value::Int(i) => i as f64,
            Value::Float(x) => x,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Debug)]
struct Property {
    name: Vec<u8>,
    kind: Kind,
}

#[derive(Debug)]
struct Element {
    name: Vec<u8>,
    count: u64,
    props: Vec<Property>,
    line: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Ascii,
    Little,
    Big,
}

#[derive(Debug)]
struct PlyHeader {
    format: Format,
    elements: Vec<Element>,
    /// Byte offset of the data.
    data: usize,
    /// Line number of the first data line (ASCII).
    data_line: u32,
}

fn err(path: &Path, line: u32, msg: impl std::fmt::Display) -> CliError {
    CliError::bad_input(format!("{}:{line}: {msg}", path.display()))
}

/// Reads and checks the header.
fn header(path: &Path, bytes: &[u8]) -> CliResult<PlyHeader> {
    let magic_ok = bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r");
    if !magic_ok {
        let first = bytes
            .split(|&b| b == b'\n' || b == b'\r')
            .next()
            .unwrap_or(b"");
        let why = if first.eq_ignore_ascii_case(b"ply") {
            "the magic line is lowercase 'ply' (PLY keywords are case-sensitive)"
        } else {
            "not a PLY file: the first line must be 'ply'"
        };
        return Err(err(path, 1, format_args!("{why}; found {}", quote(first))));
    }
    // The header's line ends are those of the magic line: LF (or CR LF), or CR alone.
    let cr_only = bytes.get(3) == Some(&b'\r') && bytes.get(4) != Some(&b'\n');
    let sep = if cr_only { b'\r' } else { b'\n' };
    let mut pos = 0usize;
    let mut line = 0u32;
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        let rest = bytes.get(pos..).unwrap_or(b"");
        let Some(end) = rest.iter().position(|&b| b == sep) else {
            return Err(err(
                path,
                line.saturating_add(1),
                "the header ends without 'end_header' (the file is truncated or not PLY)",
            ));
        };
        let raw = rest.get(..end).unwrap_or(b"");
        pos += end + 1;
        line += 1;
        // A CR before the LF is part of the line end.
        let l = raw.strip_suffix(b"\r").unwrap_or(raw);
        if line == 1 {
            continue; // "ply"
        }
        let toks: Vec<&[u8]> = text::tokens(l).collect();
        let Some(&kw) = toks.first() else { continue };
        match kw {
            b"comment" | b"obj_info" => {}
            b"format" => {
                if format.is_some() {
                    return Err(err(path, line, "a second 'format' line"));
                }
                let f = match toks.get(1).copied() {
                    Some(b"ascii") => Format::Ascii,
                    Some(b"binary_little_endian") => Format::Little,
                    Some(b"binary_big_endian") => Format::Big,
                    _ => {
                        return Err(err(
                            path,
                            line,
                            format_args!(
                                "unknown format line {} (ascii, binary_little_endian or \
                                 binary_big_endian, then 1.0)",
                                quote(l)
                            ),
                        ))
                    }
                };
                if toks.get(2).copied() != Some(b"1.0") || toks.len() != 3 {
                    return Err(err(
                        path,
                        line,
                        format_args!("unsupported format line {} (version 1.0 only)", quote(l)),
                    ));
                }
                format = Some(f);
            }
            b"element" => {
                let (Some(name), Some(count), 3) = (toks.get(1), toks.get(2), toks.len()) else {
                    return Err(err(
                        path,
                        line,
                        format_args!("malformed element line {} ('element NAME COUNT')", quote(l)),
                    ));
                };
                let count = std::str::from_utf8(count)
                    .ok()
                    .and_then(|c| c.parse::<u64>().ok())
                    .ok_or_else(|| {
                        err(
                            path,
                            line,
                            format_args!(
                                "the element count {} is not a non-negative integer",
                                quote(count)
                            ),
                        )
                    })?;
                if let Some(prev) = elements.last() {
                    if prev.props.is_empty() {
                        return Err(err(
                            path,
                            prev.line,
                            format_args!("element {} has no properties", quote(&prev.name)),
                        ));
                    }
                }
                if elements.iter().any(|e| e.name == *name) {
                    return Err(err(
                        path,
                        line,
                        format_args!("element {} is declared twice", quote(name)),
                    ));
                }
                elements.push(Element {
                    name: name.to_vec(),
                    count,
                    props: Vec::new(),
                    line,
                });
            }
            b"property" => {
                let Some(el) = elements.last_mut() else {
                    return Err(err(path, line, "a property before any element"));
                };
                let bad_type = |t: &[u8]| {
                    err(
                        path,
                        line,
                        format_args!("unknown property type {}", quote(t)),
                    )
                };
                let (kind, name) = match toks.as_slice() {
                    [_, b"list", ct, it, name] => {
                        let count = Scalar::from_name(ct).ok_or_else(|| bad_type(ct))?;
                        let item = Scalar::from_name(it).ok_or_else(|| bad_type(it))?;
                        if !count.is_integer() {
                            return Err(err(
                                path,
                                line,
                                format_args!(
                                    "the count type of a list must be an integer type, not {}",
                                    count.name()
                                ),
                            ));
                        }
                        (Kind::List { count, item }, *name)
                    }
                    [_, t, name] if *t != b"list" => (
                        Kind::Scalar(Scalar::from_name(t).ok_or_else(|| bad_type(t))?),
                        *name,
                    ),
                    _ => {
                        return Err(err(
                            path,
                            line,
                            format_args!(
                                "malformed property line {} ('property TYPE NAME' or 'property \
                                 list COUNT_TYPE ITEM_TYPE NAME')",
                                quote(l)
                            ),
                        ))
                    }
                };
                if el.props.iter().any(|p| p.name == name) {
                    return Err(err(
                        path,
                        line,
                        format_args!(
                            "property {} is declared twice in element {} (which column is it?)",
                            quote(name),
                            quote(&el.name)
                        ),
                    ));
                }
                el.props.push(Property {
                    name: name.to_vec(),
                    kind,
                });
            }
            b"end_header" => {
                if toks.len() != 1 {
                    return Err(err(
                        path,
                        line,
                        format_args!("unexpected {} after end_header", quote(l)),
                    ));
                }
                break;
            }
            _ => {
                return Err(err(
                    path,
                    line,
                    format_args!("unknown PLY header line {}", quote(l)),
                ))
            }
        }
    }
    let Some(format) = format else {
        return Err(err(path, 2, "the header has no 'format' line"));
    };
    if let Some(prev) = elements.last() {
        if prev.props.is_empty() {
            return Err(err(
                path,
                prev.line,
                format_args!("element {} has no properties", quote(&prev.name)),
            ));
        }
    }
    Ok(PlyHeader {
        format,
        elements,
        data: pos,
        data_line: line.saturating_add(1),
    })
}

/// Where the next value comes from.
enum Data<'a> {
    /// ASCII: the lines after the header; the current line's tokens.
    Ascii {
        lines: Lines<'a>,
        line: u32,
        toks: std::vec::IntoIter<&'a [u8]>,
    },
    /// Binary: the bytes after the header and the position in them.
    Binary {
        bytes: &'a [u8],
        pos: usize,
        big: bool,
        base: usize,
    },
}

impl<'a> Data<'a> {
    /// Starts the next element's record (ASCII: the next non-blank line); its line number.
    fn start(&mut self) -> Option<u32> {
        match self {
            Data::Ascii { lines, line, toks } => loop {
                let (n, l) = lines.next()?;
                let t: Vec<&'a [u8]> = text::tokens(l).collect();
                if !t.is_empty() {
                    *line = n;
                    *toks = t.into_iter();
                    return Some(n);
                }
            },
            Data::Binary { bytes, pos, .. } => (*pos < bytes.len()).then_some(0),
        }
    }

    /// The next value of type `t`; `Err(None)` at the end of the line or file, `Err(Some(text))`
    /// for a token that is not a value of the type.
    fn value(&mut self, t: Scalar) -> Result<Value, Option<&'a [u8]>> {
        match self {
            Data::Ascii { toks, .. } => {
                let tok = toks.next().ok_or(None)?;
                if t.is_integer() {
                    let i = text::parse_i64(tok).ok_or(Some(tok))?;
                    let (lo, hi) = t.range();
                    if i < lo || i > hi {
                        return Err(Some(tok));
                    }
                    Ok(Value::Int(i))
                } else if t == Scalar::F32 {
                    let x: f32 = std::str::from_utf8(tok)
                        .ok()
                        .and_then(|s| s.parse().ok())
                        .ok_or(Some(tok))?;
                    Ok(Value::Float(f64::from(x)))
                } else {
                    Ok(Value::Float(text::parse_f64(tok).ok_or(Some(tok))?))
                }
            }
            Data::Binary {
                bytes, pos, big, ..
            } => {
                let n = t.size();
                let b = bytes.get(*pos..*pos + n).ok_or(None)?;
                *pos += n;
                let mut a = [0u8; 8];
                if *big {
                    for (k, &x) in b.iter().rev().enumerate() {
                        a[k] = x;
                    }
                } else {
                    a[..n].copy_from_slice(b);
                }
                Ok(match t {
                    Scalar::I8 => Value::Int(i8::from_le_bytes([a[0]]).into()),
                    Scalar::U8 => Value::Int(a[0].into()),
                    Scalar::I16 => Value::Int(i16::from_le_bytes([a[0], a[1]]).into()),
                    Scalar::U16 => Value::Int(u16::from_le_bytes([a[0], a[1]]).into()),
                    Scalar::I32 => Value::Int(i32::from_le_bytes([a[0], a[1], a[2], a[3]]).into()),
                    Scalar::U32 => Value::Int(u32::from_le_bytes([a[0], a[1], a[2], a[3]]).into()),
                    Scalar::F32 => {
                        Value::Float(f32::from_le_bytes([a[0], a[1], a[2], a[3]]).into())
                    }
                    Scalar::F64 => Value::Float(f64::from_le_bytes(a)),
                })
            }
        }
    }

    /// Where the reader is, for messages: `:LINE` (ASCII) or ` (byte offset N)` (binary).
    fn at(&self, path: &Path) -> String {
        match self {
            Data::Ascii { line, .. } => format!("{}:{line}:", path.display()),
            Data::Binary { pos, base, .. } => {
                format!("{}: (byte offset {})", path.display(), base + pos)
            }
        }
    }

    /// Values left on the current ASCII line.
    fn left_on_line(&mut self) -> Option<&'a [u8]> {
        match self {
            Data::Ascii { toks, .. } => toks.next(),
            Data::Binary { .. } => None,
        }
    }
}

/// The smallest number of bytes one record of `el` takes (binary: its scalars and list
/// counts; ASCII: one digit and a separator per scalar or count).
fn min_record_bytes(el: &Element, ascii: bool) -> usize {
    el.props
        .iter()
        .map(|p| match (p.kind, ascii) {
            (_, true) => 2,
            (Kind::Scalar(s), false) => s.size(),
            (Kind::List { count, .. }, false) => count.size(),
        })
        .sum::<usize>()
        .max(1)
}

/// Reads a PLY file.
///
/// # Errors
/// Exit 2 for anything malformed or not supported, with the line (ASCII) or the byte
/// offset (binary).
pub fn read(path: &Path, bytes: &[u8]) -> CliResult<(Mesh, Source)> {
    let bytes = text::strip_bom(path, bytes)?;
    let h = header(path, bytes)?;
    let name_is = |e: &Element, n: &[u8]| e.name == n;
    let Some(vdef) = h.elements.iter().find(|e| name_is(e, b"vertex")) else {
        return Err(CliError::bad_input(format!(
            "{}: the PLY header declares no 'vertex' element",
            path.display()
        )));
    };
    let mut axes = [0usize; 3];
    for (k, axis) in [&b"x"[..], b"y", b"z"].iter().enumerate() {
        match vdef.props.iter().position(|p| p.name == *axis) {
            Some(i) if matches!(vdef.props[i].kind, Kind::Scalar(_)) => axes[k] = i,
            Some(_) => {
                return Err(err(
                    path,
                    vdef.line,
                    format_args!(
                        "the PLY vertex property {} is a list, not a number",
                        quote(axis)
                    ),
                ))
            }
            None => {
                return Err(err(
                    path,
                    vdef.line,
                    format_args!("the PLY vertex element has no {} property", quote(axis)),
                ))
            }
        }
    }
    let mut face_list = None;
    if let Some(fdef) = h.elements.iter().find(|e| name_is(e, b"face")) {
        let found: Vec<usize> = (0..fdef.props.len())
            .filter(|&i| {
                matches!(
                    fdef.props[i].name.as_slice(),
                    b"vertex_indices" | b"vertex_index"
                )
            })
            .collect();
        match found.as_slice() {
            [i] => {
                match fdef.props[*i].kind {
                    Kind::List { item, .. } if item.is_integer() => face_list = Some(*i),
                    _ => return Err(err(
                        path,
                        fdef.line,
                        "the PLY face property 'vertex_indices' must be a list of an integer type",
                    )),
                }
            }
            [] => {
                return Err(err(
                    path,
                    fdef.line,
                    "the PLY face element has no 'vertex_indices' list",
                ))
            }
            _ => {
                return Err(err(
                    path,
                    fdef.line,
                    "the PLY face element has both 'vertex_indices' and 'vertex_index'",
                ))
            }
        }
    }
    if let Some(e) = h.elements.iter().find(|e| name_is(e, b"tristrips")) {
        return Err(err(
            path,
            e.line,
            "triangle strips ('tristrips') are not supported: convert them to faces",
        ));
    }
    let ascii = h.format == Format::Ascii;
    let data = bytes.get(h.data..).unwrap_or(b"");
    let mut src = if ascii {
        Data::Ascii {
            lines: Lines::new(data, h.data_line),
            line: h.data_line,
            toks: Vec::new().into_iter(),
        }
    } else {
        Data::Binary {
            bytes: data,
            pos: 0,
            big: h.format == Format::Big,
            base: h.data,
        }
    };
    let limit = u64::from(u32::MAX - 1);
    let mut mesh = Mesh::default();
    let (mut vertex_lines, mut face_lines) = (Vec::new(), Vec::new());
    for el in &h.elements {
        let is_vertex = name_is(el, b"vertex");
        let is_face = face_list.is_some() && name_is(el, b"face");
        let ename = String::from_utf8_lossy(&el.name).into_owned();
        let ename = crate::error::sanitize_line(&ename, 40);
        if (is_vertex || is_face) && el.count > limit {
            return Err(err(
                path,
                el.line,
                format_args!("{} {ename} elements: too many (at most {limit})", el.count),
            ));
        }
        // A lying count must not reserve memory the file cannot fill.
        let room = (data.len() / min_record_bytes(el, ascii)) as u64 + 1;
        if el.count > room {
            return Err(err(
                path,
                el.line,
                format_args!(
                    "the header declares {} {ename} elements, but the file has room for at \
                     most {} (truncated, or the count is wrong)",
                    el.count,
                    room - 1
                ),
            ));
        }
        let n = el.count as usize;
        if is_vertex {
            mesh.positions.reserve_exact(n);
            if ascii {
                vertex_lines.reserve_exact(n);
            }
        }
        if is_face {
            mesh.offsets.reserve_exact(n);
            if ascii {
                face_lines.reserve_exact(n);
            }
        }
        for i in 0..n {
            let eof = |src: &Data<'_>| {
                CliError::bad_input(format!(
                    "{} the file ends in {ename} {i} of {} (truncated, or the header's counts \
                     are wrong)",
                    src.at(path),
                    el.count
                ))
            };
            let Some(line) = src.start() else {
                return Err(eof(&src));
            };
            let mut p = [0.0f64; 3];
            for (k, prop) in el.props.iter().enumerate() {
                let pname = crate::error::sanitize_line(&String::from_utf8_lossy(&prop.name), 40);
                let bad = |src: &Data<'_>, got: Option<&[u8]>, t: Scalar| match got {
                    Some(tok) => CliError::bad_input(format!(
                        "{} {ename} {i}: property '{pname}': {} is not a {} value",
                        src.at(path),
                        quote(tok),
                        t.name()
                    )),
                    None if ascii => CliError::bad_input(format!(
                        "{} {ename} {i}: the line ends before property '{pname}' ({} values \
                         expected per line)",
                        src.at(path),
                        el.props.len()
                    )),
                    None => eof(src),
                };
                match prop.kind {
                    Kind::Scalar(t) => {
                        let v = src.value(t).map_err(|g| bad(&src, g, t))?;
                        if is_vertex {
                            if let Some(axis) = axes.iter().position(|&a| a == k) {
                                p[axis] = v.as_f64();
                            }
                        }
                    }
                    Kind::List { count, item } => {
                        let c = match src.value(count).map_err(|g| bad(&src, g, count))? {
                            Value::Int(c) if c >= 0 => c as u64,
                            _ => {
                                return Err(CliError::bad_input(format!(
                                    "{} {ename} {i}: property '{pname}': negative list length",
                                    src.at(path)
                                )))
                            }
                        };
                        let this = is_face && face_list == Some(k);
                        if this && c < 3 {
                            return Err(CliError::bad_input(format!(
                                "{} face {i} has {c} corners (a face needs at least 3)",
                                src.at(path)
                            )));
                        }
                        for _ in 0..c {
                            let v = src.value(item).map_err(|g| bad(&src, g, item))?;
                            if this {
                                let Value::Int(idx) = v else { continue };
                                if idx < 0 {
                                    return Err(CliError::bad_input(format!(
                                        "{} face {i}: negative index {idx} (PLY indices start at 0)",
                                        src.at(path)
                                    )));
                                }
                                let u = u32::try_from(idx).map_err(|_| {
                                    CliError::bad_input(format!(
                                        "{} face {i}: index {idx} is out of range",
                                        src.at(path)
                                    ))
                                })?;
                                mesh.indices.push(u);
                            }
                        }
                        if this {
                            let end = u32::try_from(mesh.indices.len()).map_err(|_| {
                                CliError::bad_input(format!(
                                    "{} more corners than 32-bit indices can hold",
                                    src.at(path)
                                ))
                            })?;
                            mesh.offsets.push(end);
                            if ascii {
                                face_lines.push(line);
                            }
                        }
                    }
                }
            }
            if let Some(extra) = src.left_on_line() {
                return Err(CliError::bad_input(format!(
                    "{} {ename} {i}: unexpected {} after its {} properties (is the header \
                     right?)",
                    src.at(path),
                    quote(extra),
                    el.props.len()
                )));
            }
            if is_vertex {
                mesh.positions.push(p);
                if ascii {
                    vertex_lines.push(line);
                }
            }
        }
    }
    match &mut src {
        Data::Ascii { lines, .. } => {
            if let Some((n, l)) = lines.find(|(_, l)| text::tokens(l).next().is_some()) {
                return Err(err(
                    path,
                    n,
                    format_args!(
                        "unexpected {} after the last element (the header's counts are wrong)",
                        quote(l)
                    ),
                ));
            }
        }
        Data::Binary {
            bytes, pos, base, ..
        } => {
            if *pos < bytes.len() {
                return Err(CliError::bad_input(format!(
                    "{}: {} bytes after the last element, from byte offset {} (the header's \
                     counts or types are wrong)",
                    path.display(),
                    bytes.len() - *pos,
                    *base + *pos
                )));
            }
        }
    }
    let source = if ascii {
        Source::with_lines(path, vertex_lines, face_lines)
    } else {
        Source::new(path)
    };
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
        let bad = format!(
            "{HEAD}1 1 1 0\n1 -1 -1 0\n-1 1 -1 0\n-1 -1 x 0\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n"
        );
        let e = parse(bad.as_bytes()).unwrap_err().message;
        assert!(
            e.starts_with("t.ply:15: vertex 3: property 'z': 'x' is not a float value"),
            "{e}"
        );
        let bad = format!("{HEAD}1 1 1 0\n1 -1 -1 0\n-1 1 -1 0\n-1 -1 1 0\n3 0 1 2\n3 0 3 1\n");
        let e = parse(bad.as_bytes()).unwrap_err().message;
        assert!(e.contains("t.ply:17: the file ends in face 2 of 4"), "{e}");
        let one = format!(
            "{HEAD}1 1 1 0\n1 -1 -1 0\n-1 1 -1 0\n-1 -1 1 0\n3 1 2 3\n3 1 4 2\n3 1 3 4\n3 2 4 3\n"
        );
        let e = parse(one.as_bytes()).unwrap_err().message;
        assert!(e.contains("one-based"), "{e}");
    }
}
