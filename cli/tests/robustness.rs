//! Hostile input and hostile environments: every file is read exactly as its format says or
//! refused with exit 2 naming the line (never a different mesh with exit 0); resources are
//! checked; closed pipes, signals and file-size limits end the command cleanly; messages
//! never echo raw control bytes; comparisons do not depend on the scale.
//! (docs/bad-input-catalogue.md, rows 28–33.)

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use common::*;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const TET_V: [[f64; 3]; 4] = [
    [1.0, 1.0, 1.0],
    [1.0, -1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
];
const TET_F: &str = "3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n";

/// Converts `input` to OFF with the command and reads the result independently.
fn read_back(dir: &TempDir, input: &Path) -> Result<TMesh, String> {
    let out = dir.path("back.off");
    let _ = std::fs::remove_file(&out);
    let o = run(&[
        "convert",
        "-q",
        input.to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    if code(&o) != 0 {
        return Err(format!("exit {}: {}", code(&o), stderr(&o)));
    }
    Ok(read_off(&out))
}

fn tet() -> TMesh {
    TMesh {
        positions: TET_V.to_vec(),
        faces: vec![vec![0, 1, 2], vec![0, 3, 1], vec![0, 2, 3], vec![1, 3, 2]],
    }
}

/// Writes `text` to `name` and checks that the command refuses it with exit 2 and a message
/// holding `needle`.
fn refused(dir: &TempDir, name: &str, text: &[u8], needle: &str) {
    let p = dir.path(name);
    std::fs::write(&p, text).unwrap();
    let r = read_back(dir, &p);
    match r {
        Ok(m) => panic!("{name}: accepted as {m:?}, expected a refusal naming '{needle}'"),
        Err(e) => {
            assert!(e.starts_with("exit 2"), "{name}: {e}");
            assert!(e.contains(needle), "{name}: message lacks '{needle}': {e}");
        }
    }
}

/// Row 28. A UTF-8 byte-order mark before the first OBJ statement is skipped (the statement is
/// read), and any statement the format does not define is refused: a mangled keyword never
/// drops a vertex and renumbers the rest.
#[test]
fn obj_byte_order_mark_and_unknown_statements_never_drop_a_vertex() {
    let dir = TempDir::new("obj-bom");
    let body = "v 1 1 1\nv 1 -1 -1\nv -1 1 -1\nv -1 -1 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n";
    let p = dir.path("bom.obj");
    std::fs::write(&p, format!("\u{feff}{body}")).unwrap();
    assert_eq!(
        read_back(&dir, &p).unwrap(),
        tet(),
        "BOM before the first vertex"
    );
    // A byte-order mark (or any junk) glued to a later keyword: refused by line.
    refused(
        &dir,
        "mid.obj",
        "v 1 1 1\n\u{feff}v 1 -1 -1\nv -1 1 -1\nv -1 -1 1\nf 1 2 3\n".as_bytes(),
        "mid.obj:2: unknown OBJ statement '\\u{feff}v'",
    );
    refused(
        &dir,
        "upper.obj",
        b"V 1 1 1\nv 0 0 0\nv 1 0 0\nf 1 2 3\n",
        "upper.obj:1:",
    );
    // CR-only line ends, continuation lines, w and colours, negative indices, v/vt/vn.
    let p = dir.path("variants.obj");
    std::fs::write(
        &p,
        "# c\rv 1 1 1 1\rv 1 -1 -1 0.5 0.5 0.5\rv -1 1 \\\r-1\rv -1 -1 1\rvt 0 0\rvn 0 0 1\r\
         g a\ro b\rusemtl m\rs off\rf 1/1/1 2//1 3/1\rf -4 -1 -3\rf 1 3 4\rf 2 4 3\r",
    )
    .unwrap();
    assert_eq!(read_back(&dir, &p).unwrap(), tet(), "OBJ variants");
    refused(
        &dir,
        "vt.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2 2/1 3/1\n",
        "texture vertex",
    );
    refused(
        &dir,
        "five.obj",
        b"v 0 0 0 1 2\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        "5 values",
    );
    refused(&dir, "surf.obj", b"v 0 0 0\ncstype bspline\n", "free-form");
}

/// Row 28. Geomview OFF with every prefix combination: the vertex line is
/// `x y z [w] [nx ny nz] [colour] [s t]`, `4` divides by w, `n` puts the dimension after
/// the keyword; face colours follow the indices. Each variant must give the tetrahedron.
#[test]
fn off_prefixes_are_read_as_geomview_defines_them() {
    let dir = TempDir::new("off-variants");
    let want = tet();
    for kw in [
        "OFF",
        "COFF",
        "NOFF",
        "STOFF",
        "4OFF",
        "nOFF",
        "CNOFF",
        "STCOFF",
        "STCNOFF",
        "STCN4OFF",
        "4nOFF",
        "STCN4nOFF",
        "CN4OFF",
        "NnOFF",
    ] {
        let (st, c, n) = (kw.starts_with("ST"), kw.contains('C'), kw.contains('N'));
        let (four, dim) = (kw.contains('4'), kw.contains("nOFF"));
        let mut s = format!("{kw}\n");
        if dim {
            s.push_str("3\n");
        }
        s.push_str("4 4 6\n");
        for (i, p) in TET_V.iter().enumerate() {
            let w = if four { 2.0 + i as f64 } else { 1.0 };
            s.push_str(&format!("{} {} {}", p[0] * w, p[1] * w, p[2] * w));
            if four {
                s.push_str(&format!(" {w}"));
            }
            if n {
                s.push_str(" 0 0 1");
            }
            if c {
                s.push_str(" 0.25 0.5 0.75 1");
            }
            if st {
                s.push_str(" 0.5 0.125");
            }
            s.push('\n');
        }
        s.push_str("3 0 1 2 255 0 0\n3 0 3 1 0.5 0.5 0.5 1\n3 0 2 3 7\n3 1 3 2\n");
        let p = dir.path(&format!("{kw}.off"));
        std::fs::write(&p, &s).unwrap();
        let got = read_back(&dir, &p).unwrap_or_else(|e| panic!("{kw}: {e}\n{s}"));
        assert_eq!(got.faces, want.faces, "{kw}");
        for (a, b) in got.positions.iter().zip(&want.positions) {
            for k in 0..3 {
                assert!((a[k] - b[k]).abs() <= 1e-15, "{kw}: {a:?} vs {b:?}");
            }
        }
    }
    // Numbers the keyword does not declare: refused, never shifted into the next vertex.
    let mut s = String::from("OFF\n4 4 0\n");
    for p in TET_V {
        s.push_str(&format!("{} {} {} 255 0 0\n", p[0], p[1], p[2]));
    }
    s.push_str(TET_F);
    refused(
        &dir,
        "undeclared.off",
        s.as_bytes(),
        "undeclared.off:3: vertex 0 has 6 numbers",
    );
    refused(
        &dir,
        "w0.off",
        b"4OFF\n3 1 0\n0 0 0 0\n1 0 0 1\n0 1 0 1\n3 0 1 2\n",
        "w0.off:3: vertex 0: homogeneous",
    );
    refused(
        &dir,
        "wrongcorners.off",
        b"OFF\n4 4 0\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n3 0 1 2 3 1\n3 0 3 1\n3 0 2 3\n3 1 3 2\n",
        "wrongcorners.off:7: face 0: 2 numbers after",
    );
}

/// Row 28. PLY: a property named twice would shift the columns; data after the last element
/// means the counts are wrong. Both are refused. Binary big- and little-endian files and
/// every list count type read to the same mesh as ASCII.
#[test]
fn ply_repeated_property_and_trailing_data_are_refused_and_binaries_read_exactly() {
    let dir = TempDir::new("ply");
    let head = |extra_prop: &str, fmt: &str, ct: &str, it: &str| {
        format!(
            "ply\nformat {fmt} 1.0\ncomment c\nobj_info o\nelement vertex 4\nproperty double x\n{extra_prop}property double y\nproperty double z\nelement face 4\nproperty list {ct} {it} vertex_indices\nend_header\n"
        )
    };
    let mut dup = head("property double x\n", "ascii", "uchar", "int");
    for p in TET_V {
        dup.push_str(&format!("9 {} {} {}\n", p[0], p[1], p[2]));
    }
    dup.push_str(TET_F);
    refused(
        &dir,
        "dup.ply",
        dup.as_bytes(),
        "dup.ply:7: property 'x' is declared twice",
    );
    let mut ok = head("", "ascii", "uchar", "int");
    for p in TET_V {
        ok.push_str(&format!("{} {} {}\n", p[0], p[1], p[2]));
    }
    ok.push_str(TET_F);
    let p = dir.path("ok.ply");
    std::fs::write(&p, &ok).unwrap();
    assert_eq!(read_back(&dir, &p).unwrap(), tet());
    refused(
        &dir,
        "trail.ply",
        format!("{ok}3 0 1 2\n").as_bytes(),
        "trail.ply:20: unexpected '3 0 1 2' after the last element",
    );
    for (fmt, big) in [("binary_little_endian", false), ("binary_big_endian", true)] {
        for (ct, it, cs, is) in [
            ("uchar", "int", 1, 4),
            ("ushort", "uint", 2, 4),
            ("uint8", "int16", 1, 2),
            ("int", "uint8", 4, 1),
        ] {
            let mut b = head("", fmt, ct, it).into_bytes();
            let num = |x: u64, size: usize| -> Vec<u8> {
                let le = x.to_le_bytes();
                let mut v = le[..size].to_vec();
                if big {
                    v.reverse();
                }
                v
            };
            for p in TET_V {
                for x in p {
                    b.extend(num(x.to_bits(), 8));
                }
            }
            for f in tet().faces {
                b.extend(num(3, cs));
                for i in f {
                    b.extend(num(u64::from(i), is));
                }
            }
            let p = dir.path("bin.ply");
            std::fs::write(&p, &b).unwrap();
            assert_eq!(read_back(&dir, &p).unwrap(), tet(), "{fmt} {ct} {it}");
            b.push(0);
            refused(&dir, "bin_trail.ply", &b, "1 bytes after the last element");
        }
    }
}

/// Row 28. Header oddities: a byte-order mark before `OFF` or `ply` is skipped; a lowercase
/// keyword is refused saying why; CR-only line ends are lines.
#[test]
fn header_oddities_are_read_or_refused_by_name() {
    let dir = TempDir::new("headers");
    let off = format!("OFF\n4 4 0\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n{TET_F}");
    let p = dir.path("bom.off");
    std::fs::write(&p, format!("\u{feff}{off}")).unwrap();
    assert_eq!(read_back(&dir, &p).unwrap(), tet(), "BOM before OFF");
    let p = dir.path("cr.off");
    std::fs::write(&p, off.replace('\n', "\r")).unwrap();
    assert_eq!(read_back(&dir, &p).unwrap(), tet(), "CR-only OFF");
    refused(
        &dir,
        "lower.off",
        off.replace("OFF", "off").as_bytes(),
        "lower.off:1: 'off': OFF keywords are case-sensitive",
    );
    let ply = format!("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n{TET_F}");
    for (name, text) in [
        ("bom.ply", format!("\u{feff}{ply}")),
        ("cr.ply", ply.replace('\n', "\r")),
        ("crlf.ply", ply.replace('\n', "\r\n")),
    ] {
        let p = dir.path(name);
        std::fs::write(&p, text).unwrap();
        assert_eq!(read_back(&dir, &p).unwrap(), tet(), "{name}");
    }
    refused(
        &dir,
        "upper.ply",
        ply.replace("ply\n", "PLY\n").as_bytes(),
        "upper.ply:1: the magic line is lowercase 'ply'",
    );
}

/// Row 28. Formats by content: a PLY or OFF file with a misleading or missing extension is read
/// by its signature; an output name without a mesh extension needs --output-format.
#[test]
fn formats_by_content_and_explicit_output_format() {
    let dir = TempDir::new("formats");
    let off = format!("OFF\n4 4 0\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n{TET_F}");
    let p = dir.path("mesh.txt");
    std::fs::write(&p, &off).unwrap();
    assert_eq!(read_back(&dir, &p).unwrap(), tet(), ".txt holding OFF");
    let p2 = dir.path("looks.obj");
    std::fs::write(&p2, &off).unwrap();
    assert_eq!(read_back(&dir, &p2).unwrap(), tet(), "OFF named .obj");
    let o = run(&["convert", "-q", p.to_str().unwrap(), "/dev/stdout"]);
    assert_eq!(code(&o), 4, "{}", stderr(&o));
    assert!(stderr(&o).contains("--output-format"), "{}", stderr(&o));
    let o = run(&[
        "convert",
        "-q",
        "--output-format",
        "off",
        p.to_str().unwrap(),
        "/dev/stdout",
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert!(stdout(&o).starts_with("OFF\n4 4 0\n"), "{}", stdout(&o));
    let q = dir.path("junk.dat");
    std::fs::write(&q, "hello 1 2 3\n").unwrap();
    let o = run(&["check", q.to_str().unwrap()]);
    assert_eq!(code(&o), 4);
    assert!(stderr(&o).contains("--input-format"), "{}", stderr(&o));
}

/// CPU seconds allowed to the linear-time commands of the row 29 tests (they need about 2 in
/// a debug build; the quadratic versions needed hundreds).
const CPU_SECONDS: u32 = 30;

/// Runs `nlsubdiv ARGS…` under a CPU-time limit (`ulimit -t`: SIGXCPU kills it past the limit).
fn within_cpu_seconds(seconds: u32, args: &[&str]) -> std::process::Output {
    let mut line = format!("ulimit -t {seconds}; exec '{}'", bin());
    for a in args {
        line.push_str(&format!(" '{a}'"));
    }
    Command::new("sh").arg("-c").arg(&line).output().unwrap()
}

/// A triangle fan of `n` triangles around vertex 0 (valence n + 1).
fn fan(n: usize) -> String {
    let mut s = format!("OFF\n{} {n} 0\n0 0 0\n", n + 2);
    for i in 0..=n {
        let a = std::f64::consts::PI * i as f64 / n as f64;
        s.push_str(&format!("{} {} 0\n", a.cos(), a.sin()));
    }
    for i in 0..n {
        s.push_str(&format!("3 0 {} {}\n", i + 1, i + 2));
    }
    s
}

/// Row 29. `render` is linear in the valence: a 60,000-triangle fan (whose corner normals were
/// compared pairwise: 3.6e9 pairs) renders in seconds.
#[test]
fn render_of_a_high_valence_fan_is_not_quadratic() {
    let dir = TempDir::new("fan");
    let p = dir.path("fan.off");
    std::fs::write(&p, fan(60_000)).unwrap();
    let png = dir.path("fan.png");
    // A CPU-time limit, not a wall clock: a loaded machine must not fail the test, and the
    // quadratic version needs minutes of CPU (3.6e9 pairs of faces).
    let o = within_cpu_seconds(
        CPU_SECONDS,
        &[
            "render",
            "-q",
            "--size",
            "16x16",
            p.to_str().unwrap(),
            png.to_str().unwrap(),
        ],
    );
    assert_eq!(
        code(&o),
        0,
        "render of a 60,000-triangle fan: {:?} (killed by the {CPU_SECONDS} s CPU limit?) {}",
        o.status,
        stderr(&o)
    );
}

/// Row 29. `compare` is not quadratic in coincident vertices: 60,000 vertices at one position.
#[test]
fn compare_of_coincident_vertices_is_not_quadratic() {
    let dir = TempDir::new("coincident");
    let n = 60_000;
    let mut s = format!("OFF\n{} 1 0\n0 0 0\n1 0 0\n0 1 0\n", n + 3);
    for _ in 0..n {
        s.push_str("0.5 0.5 0\n");
    }
    s.push_str("3 0 1 2\n");
    let p = dir.path("a.off");
    std::fs::write(&p, &s).unwrap();
    let o = within_cpu_seconds(
        CPU_SECONDS,
        &["compare", "-q", p.to_str().unwrap(), p.to_str().unwrap()],
    );
    assert_eq!(
        code(&o),
        0,
        "compare of 60,000 coincident vertices: {:?} (killed by the {CPU_SECONDS} s CPU limit?) {}{}",
        o.status,
        stdout(&o),
        stderr(&o)
    );
}

/// Row 30. A reader that closed standard output: exit 3, no message, no abort (was: a panic in
/// `println!`, SIGABRT, exit 134).
#[test]
fn closed_stdout_ends_quietly_with_exit_3() {
    let dir = TempDir::new("pipe");
    let p = dir.path("t.off");
    tet().write_off(&p);
    for args in [
        vec!["metrics", "--json"],
        vec!["metrics"],
        vec!["compare", "--json"],
        vec!["check"],
    ] {
        let mut cmd = Command::new(bin());
        cmd.args(&args).arg(&p);
        if args[0] == "compare" {
            cmd.arg(&p);
        }
        // A pipe whose reader is gone before the command starts: every write fails (EPIPE).
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let o = cmd
            .stdout(Stdio::from(writer))
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        assert_eq!(
            o.status.code(),
            Some(3),
            "{args:?}: {:?} {}",
            o.status,
            stderr(&o)
        );
        assert!(o.stderr.is_empty(), "{args:?}: {}", stderr(&o));
    }
}

/// Row 29. Allocations the process cannot make (here under `ulimit -v`) are refused with exit 4
/// and a message (were: an allocation failure, abort, exit 134): a huge picture, and the
/// differential path's buffers.
#[test]
fn allocations_beyond_the_limit_are_refused_with_exit_4() {
    let dir = TempDir::new("alloc");
    let p = dir.path("t.off");
    tet().write_off(&p);
    let png = dir.path("big.png");
    let out = dir.path("out.off");
    let b = bin();
    for (what, cmdline) in [
        (
            "render 8192x8192",
            format!("ulimit -v 1500000; exec '{b}' render -q --size 8192x8192 '{}' '{}'", p.display(), png.display()),
        ),
        (
            "differential-loop 11 levels",
            format!("ulimit -v 1500000; exec '{b}' subdivide -q --scheme differential-loop --levels 11 '{}' '{}'", p.display(), out.display()),
        ),
    ] {
        let o = Command::new("sh").arg("-c").arg(&cmdline).output().unwrap();
        assert_eq!(code(&o), 4, "{what}: {:?} {}", o.status, stderr(&o));
        assert!(stderr(&o).contains("nlsubdiv: error:"), "{what}: {}", stderr(&o));
    }
    assert_files(&dir, &["t.off"], "refused allocations");
}

/// Row 31. Text echoed from a file is quoted, escaped and bounded: no terminal escape reaches
/// stderr, and a 2 MB token gives a short message.
#[test]
fn messages_escape_control_bytes_and_bound_long_tokens() {
    let dir = TempDir::new("quote");
    let p = dir.path("esc.off");
    std::fs::write(
        &p,
        b"OFF\n3 1 0\n0 0 \x1b]0;pwned\x07\x1b[31m\n1 0 0\n0 1 0\n3 0 1 2\n",
    )
    .unwrap();
    let o = run(&["check", p.to_str().unwrap()]);
    assert_eq!(code(&o), 2);
    assert!(
        !o.stderr.contains(&0x1b) && !o.stderr.contains(&0x07),
        "{:?}",
        stderr(&o)
    );
    assert!(stderr(&o).contains("\\x1b"), "{}", stderr(&o));
    let mut big = b"OFF\n3 1 0\n0 0 ".to_vec();
    big.extend(std::iter::repeat_n(b'7', 2_000_000));
    big.extend(b"x\n1 0 0\n0 1 0\n3 0 1 2\n");
    let q = dir.path("big.off");
    std::fs::write(&q, &big).unwrap();
    let o = run(&["check", q.to_str().unwrap()]);
    assert_eq!(code(&o), 2);
    assert!(o.stderr.len() < 1000, "a {} byte message", o.stderr.len());
    for (name, text) in [
        (
            "esc.obj",
            &b"v 0 0 0\nv 1 0 0\nv 0 1 0\n\x1b[2Jf 1 2 3\n"[..],
        ),
        (
            "esc.ply",
            b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\x1b[2J\nend_header\n",
        ),
    ] {
        let r = dir.path(name);
        std::fs::write(&r, text).unwrap();
        let o = run(&["check", r.to_str().unwrap()]);
        assert_eq!(code(&o), 2, "{name}: {}", stderr(&o));
        assert!(!o.stderr.contains(&0x1b), "{name}: {:?}", stderr(&o));
    }
}

/// An OFF file of about `mb` megabytes (a long strip of triangles).
fn big_off(path: &Path, n: usize) {
    let mut s = String::with_capacity(n * 60);
    s.push_str(&format!("OFF\n{} {} 0\n", 2 * n, 2 * (n - 1)));
    for i in 0..n {
        s.push_str(&format!(
            "{}.123456789012345 0.123456789012345 0.5\n{}.123456789012345 1.123456789012345 0.25\n",
            i, i
        ));
    }
    for i in 0..n - 1 {
        let (a, b, c, d) = (2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1);
        s.push_str(&format!("3 {a} {b} {c}\n3 {a} {c} {d}\n"));
    }
    std::fs::write(path, s).unwrap();
}

/// Row 32. SIGTERM, SIGINT and SIGHUP during a write remove the temporary output file; a
/// file-size limit (SIGXFSZ) ends the command with exit 3 and no file left.
#[test]
fn signals_and_file_size_limits_leave_no_temporary_file() {
    let src = TempDir::new("sig-src");
    let input = src.path("big.off");
    big_off(&input, 400_000);
    // File-size limit: 2 MB of output allowed, far less than the output.
    let out = TempDir::new("sig-fsize");
    let cmdline = format!(
        "ulimit -f 4000; exec '{}' convert -q '{}' '{}'",
        bin(),
        input.display(),
        out.path("o.ply").display()
    );
    let mut cmd = Command::new("sh");
    let o = cmd.arg("-c").arg(&cmdline).output().unwrap();
    assert_eq!(
        code(&o),
        3,
        "file-size limit: {:?} {}",
        o.status,
        stderr(&o)
    );
    assert_files(&out, &[], "file-size limit");
    for sig in ["TERM", "INT", "HUP"] {
        let out = TempDir::new(&format!("sig-{sig}"));
        let target = out.path("o.obj");
        let mut child = Command::new(bin())
            .args([
                "convert",
                "-q",
                input.to_str().unwrap(),
                target.to_str().unwrap(),
            ])
            .stdin(Stdio::null())
            .spawn()
            .unwrap();
        // Wait for the temporary file to appear, then signal.
        let t = Instant::now();
        while out.files().is_empty() && t.elapsed() < Duration::from_secs(60) {
            std::thread::sleep(Duration::from_millis(2));
        }
        let st = Command::new("kill")
            .args([&format!("-{sig}"), &child.id().to_string()])
            .status()
            .unwrap();
        assert!(st.success());
        let status = child.wait().unwrap();
        let files = out.files();
        assert!(
            files.is_empty() || files == ["o.obj"],
            "SIG{sig} ({status:?}) left {files:?}"
        );
    }
}

/// Row 33. `compare` at any scale: two different meshes stay different with coordinates of
/// 1e200 (the bounding-box diagonal overflows `f64`) and of 1e-200 (squared distances
/// underflow), and a mesh still equals itself.
#[test]
fn compare_is_scale_safe() {
    let dir = TempDir::new("scale");
    for s in [1e200, 1e155, 1e-160, 1e-200, 1.7e308] {
        let a = TMesh {
            positions: TET_V.iter().map(|p| p.map(|x| x * s / 2.0)).collect(),
            faces: tet().faces,
        };
        let mut b = a.clone();
        b.positions[2][0] *= 0.5; // moved by a quarter of the diagonal
        let (pa, pb) = (dir.path("a.off"), dir.path("b.off"));
        a.write_off(&pa);
        b.write_off(&pb);
        let o = run(&[
            "compare",
            "--json",
            pa.to_str().unwrap(),
            pb.to_str().unwrap(),
        ]);
        assert_eq!(
            code(&o),
            1,
            "scale {s}: different meshes called equal\n{}",
            stdout(&o)
        );
        let o = run(&[
            "compare",
            "--json",
            pa.to_str().unwrap(),
            pa.to_str().unwrap(),
        ]);
        assert_eq!(
            code(&o),
            0,
            "scale {s}: a mesh differs from itself\n{}",
            stdout(&o)
        );
    }
}
