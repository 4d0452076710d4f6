//! Mesh files: OFF, OBJ and PLY (ASCII and binary), read into [`Mesh`] and written from it.
//!
//! * **Readers** keep the file's vertex order, face order and corner order exactly
//!   (unreferenced vertices included), so indices mean the same in the file and in the
//!   core's buffers. Every reader rejects, naming the file, the line (where the format has
//!   lines) and the element: text that is not a number, NaN or infinite coordinates,
//!   negative, out-of-range or (for OFF and PLY) one-based indices, faces with fewer than
//!   three corners, a file that ends early, data after the last element, and a mesh with
//!   no faces.
//! * **Writers** print every coordinate as the shortest decimal string that parses back to
//!   the same `f64` (Rust's float formatting), so positions survive a round trip through
//!   any text format bit for bit; binary PLY stores the doubles themselves. Files are
//!   written to a temporary file in the target's directory and renamed into place only
//!   when complete: an error never leaves a partial output behind.
//!
//! OFF ([`off`]) and OBJ ([`obj`]) are read by hand-written readers: the OBJ crates on
//! crates.io (`tobj`) re-index vertices by first use, which drops unreferenced vertices and
//! changes the order the core's output contract relies on, and none reports line numbers.
//! PLY goes through the `ply-rs-bw` crate ([`ply`]).

pub mod obj;
pub mod off;
pub mod ply;
pub mod text;

use std::fs::{self, File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

use crate::error::{CliError, CliResult};
use crate::mesh::{Mesh, Source};

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Object File Format (`.off`).
    Off,
    /// Wavefront OBJ (`.obj`).
    Obj,
    /// Stanford PLY (`.ply`), ASCII or binary.
    Ply,
}

/// `--input-format` and `--output-format`, set once by `main` from the command line.
static FORMAT_OPTIONS: OnceLock<(Option<Format>, Option<Format>)> = OnceLock::new();

/// Records `--input-format` and `--output-format` (the formats of every mesh the command
/// reads and writes, whatever the file names say). Called once, by `main`.
pub fn set_format_options(input: Option<Format>, output: Option<Format>) {
    let _ = FORMAT_OPTIONS.set((input, output));
}

fn format_options() -> (Option<Format>, Option<Format>) {
    FORMAT_OPTIONS.get().copied().unwrap_or((None, None))
}

impl Format {
    fn from_extension(path: &Path) -> Option<Format> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("off") => Some(Format::Off),
            Some("obj") => Some(Format::Obj),
            Some("ply") => Some(Format::Ply),
            _ => None,
        }
    }

    /// The format to write `path` in: `--output-format` when given, else the extension
    /// (case-insensitive); a name without a mesh extension (`/dev/stdout`, `out.txt`) is
    /// refused, never guessed.
    ///
    /// # Errors
    /// Exit 4 naming the file.
    pub fn from_path(path: &Path) -> CliResult<Format> {
        if let (_, Some(f)) = format_options() {
            return Ok(f);
        }
        Format::from_extension(path).ok_or_else(|| {
            CliError::usage(format!(
                "{}: cannot tell the mesh format to write from the file name: use a name \
                 ending in .off, .obj or .ply, or give --output-format off|obj|ply",
                path.display()
            ))
        })
    }

    /// The format of a file to read: `--input-format` when given; else the file's own
    /// signature (the PLY magic line `ply`, an OFF keyword `[ST][C][N][4][n]OFF` as the first
    /// word), which wins over a misleading extension; else the extension; else OBJ when the
    /// first statement is an OBJ one. Anything else is refused, never guessed.
    fn of_input(path: &Path, bytes: &[u8]) -> CliResult<Format> {
        if let (Some(f), _) = format_options() {
            return Ok(f);
        }
        let body = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
        if body.starts_with(b"ply\n") || body.starts_with(b"ply\r") {
            return Ok(Format::Ply);
        }
        let first = first_word(body);
        if is_off_keyword(first) {
            return Ok(Format::Off);
        }
        if let Some(f) = Format::from_extension(path) {
            return Ok(f);
        }
        const OBJ_FIRST: &[&[u8]] = &[
            b"v", b"vt", b"vn", b"vp", b"f", b"g", b"o", b"s", b"mtllib", b"usemtl",
        ];
        if OBJ_FIRST.contains(&first) {
            return Ok(Format::Obj);
        }
        Err(CliError::usage(format!(
            "{}: cannot tell the mesh format: the name does not end in .off, .obj or .ply and \
             the content starts with {}, which is none of them (give --input-format off|obj|ply)",
            path.display(),
            crate::error::quote(first)
        )))
    }
}

/// The first word of a text, after white space, blank lines and `#` comment lines.
fn first_word(bytes: &[u8]) -> &[u8] {
    for (_, line) in text::Lines::new(bytes, 1) {
        let line = match line.iter().position(|&b| b == b'#') {
            Some(p) => line.get(..p).unwrap_or(line),
            None => line,
        };
        if let Some(w) = text::tokens(line).next() {
            return w;
        }
    }
    b""
}

/// Whether `w` is an OFF keyword `[ST][C][N][4][n]OFF`.
fn is_off_keyword(w: &[u8]) -> bool {
    let Some(mut rest) = w.strip_suffix(b"OFF") else {
        return false;
    };
    for p in [&b"ST"[..], b"C", b"N", b"4", b"n"] {
        rest = rest.strip_prefix(p).unwrap_or(rest);
    }
    rest.is_empty()
}

/// How to write a mesh.
#[derive(Clone, Debug, Default)]
pub struct WriteOptions {
    /// PLY only: ASCII instead of binary little-endian.
    pub ply_ascii: bool,
    /// Per-vertex colours (OFF writes COFF, OBJ writes `v x y z r g b`, PLY `red green blue`).
    pub colors: Option<Vec<[u8; 3]>>,
    /// PLY only: a per-vertex scalar written as a `float` property of this name (MeshLab
    /// reads `quality`).
    pub scalar: Option<(String, Vec<f64>)>,
    /// OBJ only: sharp-feature tags written as `t crease 2/1/0 a b s` and
    /// `t corner 1/1/0 v s` lines (0-based vertices, OpenSubdiv's shape tags).
    pub tags: Option<crate::mesh::FileTags>,
}

/// Reads a mesh file in the format of its content or extension (see [`Format`]).
///
/// # Errors
/// Exit 3 when the file cannot be read, exit 2 for anything wrong in it (see the module
/// docs), exit 4 for an unknown format.
pub fn read_mesh(path: &Path) -> CliResult<(Mesh, Source)> {
    let bytes = fs::read(path).map_err(|e| CliError::io(path, "read", &e))?;
    parse_mesh(path, &bytes)
}

/// Parses the bytes of a mesh file named `path` (the name is used for the format, when the
/// content does not tell, and in messages). The whole of [`read_mesh`] but the reading:
/// also the entry point of the `parsers` fuzz target.
///
/// # Errors
/// Exit 2 for anything wrong in the bytes, exit 4 for an unknown format.
pub fn parse_mesh(path: &Path, bytes: &[u8]) -> CliResult<(Mesh, Source)> {
    let format = Format::of_input(path, bytes)?;
    let (mesh, source) = match format {
        Format::Off => off::read(path, bytes)?,
        Format::Obj => obj::read(path, bytes)?,
        Format::Ply => ply::read(path, bytes)?,
    };
    check_loaded(&mesh, &source)?;
    Ok((mesh, source))
}

/// Writes `mesh` in `format` to `out` (no file, no checks of the options: [`write_mesh`]
/// does those).
///
/// # Errors
/// I/O errors of `out`.
pub fn write_to(
    format: Format,
    out: &mut dyn Write,
    mesh: &Mesh,
    opts: &WriteOptions,
) -> std::io::Result<()> {
    match format {
        Format::Off => off::write(out, mesh, opts),
        Format::Obj => obj::write(out, mesh, opts),
        Format::Ply => ply::write(out, mesh, opts),
    }
}

/// Checks every reader makes on its result: finite coordinates, at least one face, counts
/// that fit the core's `u32` indices. Index ranges and face sizes are the readers' own.
fn check_loaded(mesh: &Mesh, src: &Source) -> CliResult<()> {
    for (v, p) in mesh.positions.iter().enumerate() {
        for (k, c) in p.iter().enumerate() {
            if !c.is_finite() {
                let axis = ["x", "y", "z"][k];
                let what = if c.is_nan() { "NaN" } else { "infinite" };
                return Err(CliError::bad_input(format!(
                    "{}: coordinate {axis} is {what}",
                    src.at_vertex(v)
                )));
            }
        }
    }
    if mesh.num_faces() == 0 {
        return Err(CliError::bad_input(format!(
            "{}: the mesh has no faces ({} vertices)",
            src.path.display(),
            mesh.num_vertices()
        )));
    }
    Ok(())
}

/// Writes `mesh` to `path` in the format of its extension, atomically (a temporary file in
/// the same directory, renamed on success).
///
/// # Errors
/// Exit 4 for an unknown extension or options the format cannot carry, exit 3 on I/O errors.
pub fn write_mesh(path: &Path, mesh: &Mesh, opts: &WriteOptions) -> CliResult<()> {
    let format = Format::from_path(path)?;
    if opts.scalar.is_some() && format != Format::Ply {
        return Err(CliError::usage(format!(
            "{}: a per-vertex scalar needs a .ply output",
            path.display()
        )));
    }
    let mut file = AtomicFile::create(path)?;
    let result = write_to(format, file.writer(), mesh, opts);
    result.map_err(|e| write_error(path, &e))?;
    file.commit()
}

/// Shortest decimal string that parses back to the same `f64` (exponent form for very
/// large and small magnitudes): Rust's `Debug` formatting of floats.
pub fn fmt_f64(x: f64) -> String {
    format!("{x:?}")
}

/// The temporary files being written, so that a signal (SIGINT, SIGTERM, SIGHUP) or a
/// panic can remove them before the process ends: [`AtomicFile`] registers its temporary
/// name before it creates the file and removes the name (under this lock) when it renames or
/// removes the file.
static TEMPORARY_FILES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn temporary_files() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    // A panic while the lock was held must not stop the cleanup.
    TEMPORARY_FILES
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Removes every temporary output file and keeps the list locked for the rest of the
/// process: no new temporary file can be created or renamed after it. Called on the way
/// out by the signal handler thread and the panic hook (`main.rs`).
pub fn remove_temporary_files_for_exit() {
    // try_lock, not lock: a panic on a thread that holds the list (it never should) must not
    // hang the process in its panic hook. Another thread holds it only for a rename or a
    // removal: a second is plenty.
    let mut guard = None;
    for _ in 0..1000 {
        match TEMPORARY_FILES.try_lock() {
            Ok(g) => {
                guard = Some(g);
                break;
            }
            Err(std::sync::TryLockError::Poisoned(p)) => {
                guard = Some(p.into_inner());
                break;
            }
            Err(std::sync::TryLockError::WouldBlock) => {
                std::thread::sleep(std::time::Duration::from_millis(1));
            }
        }
    }
    let Some(guard) = guard else { return };
    for p in guard.iter() {
        let _ = fs::remove_file(p);
    }
    // Never unlocked: the process is ending, and another thread must not start a file now.
    std::mem::forget(guard);
}

/// A file written under a temporary name in the target's directory and renamed to the
/// target by [`AtomicFile::commit`]. Dropped without commit, it removes the temporary file,
/// so an error leaves nothing behind; a signal or a panic removes it too (see
/// [`remove_temporary_files_for_exit`]).
///
/// A target that exists and is not a regular file (`/dev/stdout`, a named pipe, a
/// terminal) cannot be replaced by a rename: it is written directly.
#[derive(Debug)]
pub struct AtomicFile {
    target: PathBuf,
    /// The temporary file; empty when writing directly or once renamed or removed.
    temp: PathBuf,
    out: Option<BufWriter<File>>,
    sink: std::io::Sink,
}

impl AtomicFile {
    /// Creates the temporary file beside `target` (or opens `target` itself when it is not a
    /// regular file).
    ///
    /// # Errors
    /// Exit 3 when it cannot be created.
    pub fn create(target: &Path) -> CliResult<AtomicFile> {
        if let Ok(meta) = fs::metadata(target) {
            if !meta.is_file() && !meta.is_dir() {
                let f = OpenOptions::new()
                    .write(true)
                    .truncate(true)
                    .open(target)
                    .map_err(|e| CliError::io(target, "open", &e))?;
                return Ok(AtomicFile {
                    target: target.to_path_buf(),
                    temp: PathBuf::new(),
                    out: Some(BufWriter::with_capacity(1 << 16, f)),
                    sink: std::io::sink(),
                });
            }
        }
        let dir = match target.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "out".to_string());
        let mut last_err = None;
        for attempt in 0..100u32 {
            let temp = dir.join(format!(
                ".{name}.nlsubdiv-{}-{attempt}.tmp",
                std::process::id()
            ));
            let mut list = temporary_files();
            match OpenOptions::new().write(true).create_new(true).open(&temp) {
                Ok(f) => {
                    list.push(temp.clone());
                    return Ok(AtomicFile {
                        target: target.to_path_buf(),
                        temp,
                        out: Some(BufWriter::with_capacity(1 << 16, f)),
                        sink: std::io::sink(),
                    });
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => last_err = Some(e),
                Err(e) => return Err(CliError::io(target, "create", &e)),
            }
        }
        let e = last_err.unwrap_or_else(|| std::io::Error::other("no free temporary name"));
        Err(CliError::io(target, "create a temporary file for", &e))
    }

    /// The buffered writer of the temporary file.
    pub fn writer(&mut self) -> &mut dyn Write {
        match self.out.as_mut() {
            Some(w) => w,
            None => &mut self.sink,
        }
    }

    /// Flushes the temporary file and renames it to the target.
    ///
    /// # Errors
    /// Exit 3 when flushing or renaming fails (the temporary file is removed).
    pub fn commit(mut self) -> CliResult<()> {
        let Some(w) = self.out.take() else {
            return Err(CliError::internal("AtomicFile committed twice"));
        };
        let file = w
            .into_inner()
            .map_err(|e| write_error(&self.target, e.error()))?;
        if self.temp.as_os_str().is_empty() {
            // Written directly (not a regular file): nothing to sync or rename.
            return Ok(());
        }
        file.sync_all().map_err(|e| write_error(&self.target, &e))?;
        drop(file);
        let mut list = temporary_files();
        fs::rename(&self.temp, &self.target)
            .map_err(|e| CliError::io(&self.target, "rename the temporary file to", &e))?;
        // Renamed: nothing left to clean up.
        list.retain(|p| *p != self.temp);
        self.temp = PathBuf::new();
        Ok(())
    }
}

/// An error writing `path`: exit 3; a closed pipe (the reader stopped reading) ends the
/// program quietly, without a message.
pub fn write_error(path: &Path, e: &std::io::Error) -> CliError {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        CliError::quiet(crate::error::Exit::Io)
    } else {
        CliError::io(path, "write", e)
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        self.out = None;
        if !self.temp.as_os_str().is_empty() {
            let mut list = temporary_files();
            let _ = fs::remove_file(&self.temp);
            list.retain(|p| *p != self.temp);
        }
    }
}

/// Checks that every index of `mesh` is below the vertex count, naming the first face that
/// is not; recognises a one-based file (index `V` used, index 0 never) where `one_based`
/// detection applies (OFF, PLY: zero-based formats).
pub(crate) fn check_indices(mesh: &Mesh, src: &Source, detect_one_based: bool) -> CliResult<()> {
    let nv = mesh.num_vertices();
    let mut first_bad: Option<(usize, u32)> = None;
    let mut min = u32::MAX;
    let mut max = 0u32;
    for (f, face) in mesh.faces().enumerate() {
        for &i in face {
            min = min.min(i);
            max = max.max(i);
            if i as usize >= nv && first_bad.is_none() {
                first_bad = Some((f, i));
            }
        }
    }
    let Some((f, i)) = first_bad else {
        return Ok(());
    };
    if detect_one_based && min >= 1 && max as usize == nv {
        return Err(CliError::bad_input(format!(
            "{}: index {i} is out of range (the file has {nv} vertices); the indices look \
             one-based (index {nv} is used, index 0 never): OFF and PLY indices start at 0",
            src.at_face(f)
        )));
    }
    Err(CliError::bad_input(format!(
        "{}: index {i} is out of range (the file has {nv} vertices, indices 0 to {})",
        src.at_face(f),
        nv.saturating_sub(1)
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nasty_values() -> Vec<f64> {
        vec![
            0.0,
            -0.0,
            1.0,
            -1.5,
            0.1,
            1.0 / 3.0,
            2.0f64.sqrt(),
            1e-7,
            -1.40201e-05,
            123_456_789.123_456_78,
            1e300,
            -1e-300,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            std::f64::consts::PI * 1e10,
        ]
    }

    fn nasty_mesh() -> Mesh {
        let v = nasty_values();
        let n = v.len();
        let positions: Vec<[f64; 3]> = (0..n)
            .map(|i| [v[i], v[(i + 5) % n], v[(i + 11) % n]])
            .collect();
        let mut faces: Vec<Vec<u32>> = Vec::new();
        for i in 0..n as u32 - 3 {
            if i % 3 == 0 {
                faces.push(vec![i, i + 1, i + 2, i + 3]);
            } else {
                faces.push(vec![i, i + 2, i + 1]);
            }
        }
        faces.push((0..n as u32).rev().collect());
        Mesh::from_faces(positions, &faces)
    }

    #[test]
    fn float_formatting_round_trips() {
        for x in nasty_values() {
            let s = fmt_f64(x);
            let y: f64 = s.parse().unwrap();
            assert_eq!(x.to_bits(), y.to_bits(), "{x} -> {s}");
        }
        assert_eq!(fmt_f64(1.0), "1.0");
        assert_eq!(fmt_f64(1e-7), "1e-7");
    }

    #[test]
    fn every_format_round_trips_bit_exactly() {
        let m = nasty_mesh();
        let dir = std::env::temp_dir().join(format!("nlsubdiv-io-test-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        for (name, ascii) in [
            ("a.off", false),
            ("a.obj", false),
            ("a.ply", false),
            ("b.ply", true),
        ] {
            let p = dir.join(name);
            let opts = WriteOptions {
                ply_ascii: ascii,
                ..WriteOptions::default()
            };
            write_mesh(&p, &m, &opts).unwrap();
            let (back, _) = read_mesh(&p).unwrap();
            assert_eq!(back.offsets, m.offsets, "{name}");
            assert_eq!(back.indices, m.indices, "{name}");
            for (a, b) in m.positions.iter().zip(&back.positions) {
                for k in 0..3 {
                    assert_eq!(
                        a[k].to_bits(),
                        b[k].to_bits(),
                        "{name}: {} vs {}",
                        a[k],
                        b[k]
                    );
                }
            }
            // Colours and a scalar do not disturb the geometry.
            let opts = WriteOptions {
                ply_ascii: ascii,
                colors: Some(vec![[1, 2, 3]; m.num_vertices()]),
                scalar: name
                    .ends_with(".ply")
                    .then(|| ("quality".to_string(), vec![0.5; m.num_vertices()])),
                tags: None,
            };
            write_mesh(&p, &m, &opts).unwrap();
            let (back2, _) = read_mesh(&p).unwrap();
            assert_eq!(back2, back, "{name} with colours");
        }
        let leftovers: Vec<_> = fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect();
        assert!(leftovers.is_empty());
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn atomic_file_leaves_nothing_when_dropped() {
        let dir = std::env::temp_dir().join(format!("nlsubdiv-atomic-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let target = dir.join("x.off");
        {
            let mut f = AtomicFile::create(&target).unwrap();
            f.writer().write_all(b"partial").unwrap();
        }
        assert_eq!(fs::read_dir(&dir).unwrap().count(), 0);
        fs::remove_dir_all(&dir).unwrap();
    }
}
