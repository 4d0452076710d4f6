//! Bad input: every broken file gives a non-zero exit, a message naming the problem (and
//! the line and element where the file has them), and no output file left behind.

// Test helpers outside #[test] functions: clippy's in-test allowances do not reach them.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;

use common::*;
use std::path::Path;

/// What the message for each broken shared file must contain, and whether the kernel
/// would refuse it (an error: exit 2 even without `--strict`) or accept it (a warning).
const SHARED_BAD: &[(&str, &str, bool)] = &[
    ("bowtie_vertex.off", "non-manifold vertex", true),
    ("degenerate_face.off", "zero area", false),
    ("duplicate_face.off", "same vertices as face 0", true),
    ("duplicate_vertex.off", "duplicated vertices", false),
    ("empty_mesh.off", "no faces", true),
    ("inconsistent_orientation.off", "same direction", true),
    (
        "inf_coordinate.off",
        ":5: vertex 2: coordinate x is infinite",
        true,
    ),
    ("mobius_strip.off", "non-orientable", true),
    (
        "nan_coordinate.off",
        ":6: vertex 3: coordinate z is NaN",
        true,
    ),
    ("negative_index.off", ":10: face 3: negative index -1", true),
    ("nonmanifold_edge.off", "shared by 3 faces", true),
    ("one_based_indices.off", "one-based", true),
    (
        "out_of_range_index.off",
        ":10: face 3: index 4 is out of range",
        true,
    ),
    ("repeated_index_face.off", "appears twice", true),
    ("truncated_file.off", "ends in face 3 of 4", true),
    ("two_vertex_face.off", ":11: face 4 has 2 corners", true),
    (
        "unreferenced_vertex.off",
        ":7: vertex 4: no face uses the vertex",
        false,
    ),
];

/// Runs a writing command that must fail; checks status, message and that the output
/// folder stays empty.
fn must_fail(args: &[&str], out_dir: &TempDir, want_code: i32, needle: &str, what: &str) {
    let o = run(args);
    let err = stderr(&o);
    assert_eq!(code(&o), want_code, "{what}: {args:?}\n{err}");
    assert!(
        err.contains(needle),
        "{what}: message lacks '{needle}':\n{err}"
    );
    assert!(
        out_dir.files().is_empty(),
        "{what}: left behind {:?}",
        out_dir.files()
    );
}

#[test]
fn shared_bad_files_are_refused_with_a_message_and_no_output() {
    let Some(dir) =
        shared_meshes("cli::bad_input::shared_bad_files_are_refused_with_a_message_and_no_output")
    else {
        return;
    };
    let bad = dir.join("bad");
    let files = off_files(&bad);
    let out = TempDir::new("shared-bad-out");
    let tetrahedron = TMesh {
        positions: vec![
            [1.0, 1.0, 1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
        ],
        faces: vec![vec![0, 1, 2], vec![0, 3, 1], vec![0, 2, 3], vec![1, 3, 2]],
    };
    let mut seen = 0;
    for f in &files {
        let name = f.file_name().unwrap().to_str().unwrap();
        let path = f.to_str().unwrap();
        if name.starts_with("format_") {
            // Valid files with an unusual layout: read as the tetrahedron.
            let o = run(&["check", path]);
            assert_eq!(code(&o), 0, "{name}: {}{}", stdout(&o), stderr(&o));
            let t = out.path("t.off");
            let o = run(&["convert", "--strict", path, t.to_str().unwrap()]);
            assert_eq!(code(&o), 0, "{name}: {}", stderr(&o));
            assert_eq!(read_off(&t), tetrahedron, "{name}");
            std::fs::remove_file(&t).unwrap();
            continue;
        }
        let Some(&(_, needle, is_error)) = SHARED_BAD.iter().find(|(n, _, _)| *n == name) else {
            panic!("{name}: a broken file without an expectation; add it to SHARED_BAD");
        };
        seen += 1;
        // check: 2 for errors, 1 for warnings; the message on stdout (report) or stderr.
        let o = run(&["check", path]);
        let text = format!("{}{}", stdout(&o), stderr(&o));
        assert_eq!(code(&o), if is_error { 2 } else { 1 }, "{name}: {text}");
        assert!(
            text.contains(needle),
            "{name}: check lacks '{needle}':\n{text}"
        );
        // Writing commands refuse it under --strict, leaving nothing behind.
        for target in ["out.ply", "out.obj", "out.off"] {
            let t = out.path(target);
            must_fail(
                &["convert", "--strict", path, t.to_str().unwrap()],
                &out,
                2,
                needle,
                name,
            );
        }
        let png = out.path("out.png");
        must_fail(
            &["render", "--strict", path, png.to_str().unwrap()],
            &out,
            2,
            needle,
            name,
        );
        let o = run(&["metrics", "--strict", path]);
        assert_eq!(code(&o), 2, "{name}: metrics --strict\n{}", stderr(&o));
        // Without --strict, errors are still refused; warnings are printed and the
        // command goes on (the kernel accepts such meshes).
        let t = out.path("plain.ply");
        let o = run(&["convert", path, t.to_str().unwrap()]);
        if is_error {
            assert_eq!(code(&o), 2, "{name}: {}", stderr(&o));
            assert!(out.files().is_empty(), "{name}: {:?}", out.files());
        } else {
            assert_eq!(code(&o), 0, "{name}: {}", stderr(&o));
            assert!(stderr(&o).contains("warning:"), "{name}: {}", stderr(&o));
            std::fs::remove_file(&t).unwrap();
        }
    }
    assert_eq!(
        seen,
        SHARED_BAD.len(),
        "some expected broken files are missing"
    );
    println!("{seen} broken shared files refused");
}

/// Broken files made here, so that a fresh clone without the shared data tests the same.
#[test]
fn generated_bad_files_name_file_line_and_element() {
    let dir = TempDir::new("gen-bad-in");
    let out = TempDir::new("gen-bad-out");
    let tet_v = "1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n";
    let ply_head = "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
    let cases: Vec<(&str, String, &str)> = vec![
        ("nan.off", "OFF\n4 4 0\n1 1 1\n1 -1 -1\n-1 1 nan\n-1 -1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n".to_string(), "nan.off:5: vertex 2: coordinate z is NaN"),
        ("word.off", "OFF\n4 4 0\n1 1 1\n1 -1 -1\n-1 1 one\n-1 -1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n".to_string(), "word.off:5: vertex 2: coordinate z is not a number: 'one'"),
        ("neg.off", format!("OFF\n4 4 0\n{tet_v}3 0 1 2\n3 0 -3 1\n3 0 2 3\n3 1 3 2\n"), "neg.off:8: face 1: negative index -3"),
        ("range.off", format!("OFF\n4 4 0\n{tet_v}3 0 1 2\n3 0 3 1\n3 0 2 7\n3 1 3 2\n"), "range.off:9: face 2: index 7 is out of range"),
        ("onebased.off", format!("OFF\n4 4 0\n{tet_v}3 1 2 3\n3 1 4 2\n3 1 3 4\n3 2 4 3\n"), "one-based"),
        ("short.off", format!("OFF\n4 4 0\n{tet_v}3 0 1 2\n3 0 3 1\n"), "short.off:8: the file ends in face 2 of 4"),
        ("extra.off", format!("OFF\n4 4 0\n{tet_v}3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n3 0 1 3\n"), "extra.off:11: unexpected '3' after the last face"),
        ("binary.off", "OFF BINARY\n".to_string(), "binary OFF is not supported"),
        ("nm.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n".to_string(), "nm.off:10: face 2: edge (0, 1) is shared by 3 faces"),
        ("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n".to_string(), "zero.obj:4: face 0: corner '0': vertex index 0 is invalid"),
        ("rel.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf -1 -2 -9\n".to_string(), "rel.obj:5: face 1: corner '-9': relative index -9"),
        ("inf.obj", "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n".to_string(), "inf.obj:2: vertex 1: coordinate y is infinite"),
        ("neg.ply", format!("{ply_head}{tet_v}3 0 1 2\n3 0 3 1\n3 0 -2 3\n3 1 3 2\n"), "neg.ply:16: face 2: negative index -2"),
        ("trunc.ply", format!("{ply_head}{tet_v}3 0 1 2\n3 0 3 1\n"), "trunc.ply:15: the file ends in face 2 of 4"),
        ("text.ply", format!("{ply_head}1 1 1\n1 -1 -1\n-1 1 x\n-1 -1 1\n3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n"), "text.ply:12: vertex 2: property 'z': 'x' is not a double value"),
        ("nofaces.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n".to_string(), "no faces"),
        ("noxyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n".to_string(), "no 'z' property"),
    ];
    for (name, text, needle) in &cases {
        let p = dir.path(name);
        std::fs::write(&p, text).unwrap();
        let path = p.to_str().unwrap();
        let (ply, png) = (out.path("o.ply"), out.path("o.png"));
        must_fail(
            &["convert", path, ply.to_str().unwrap()],
            &out,
            2,
            needle,
            name,
        );
        // render draws meshes with topological defects; --strict refuses them.
        let png = png.to_str().unwrap();
        must_fail(&["render", "--strict", path, png], &out, 2, needle, name);
    }
    // A binary PLY with NaN: no lines, but the element.
    let ok = dir.path("ok.off");
    std::fs::write(
        &ok,
        format!("OFF\n4 4 0\n{tet_v}3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n"),
    )
    .unwrap();
    let bin = dir.path("ok.ply");
    assert_eq!(
        code(&run(&[
            "convert",
            "-q",
            ok.to_str().unwrap(),
            bin.to_str().unwrap()
        ])),
        0
    );
    let mut bytes = std::fs::read(&bin).unwrap();
    let body = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .unwrap()
        + 11;
    bytes[body + 8..body + 16].copy_from_slice(&f64::NAN.to_le_bytes()); // vertex 0, y
    std::fs::write(&bin, &bytes).unwrap();
    let t = out.path("x.off");
    must_fail(
        &["convert", bin.to_str().unwrap(), t.to_str().unwrap()],
        &out,
        2,
        "ok.ply: vertex 0: coordinate y is NaN",
        "binary NaN",
    );
    bytes.truncate(bytes.len() - 5);
    std::fs::write(&bin, &bytes).unwrap();
    must_fail(
        &["convert", bin.to_str().unwrap(), t.to_str().unwrap()],
        &out,
        2,
        "the file ends in face",
        "binary truncated",
    );
}

#[test]
fn io_and_usage_errors_have_their_own_statuses() {
    let dir = TempDir::new("io-usage");
    let m = dir.path("m.off");
    torus(6, 5, 2.0, 0.5).write_off(&m);
    let m = m.to_str().unwrap();
    // A missing input: I/O error 3.
    let o = run(&[
        "convert",
        "/nonexistent/in.off",
        dir.path("o.off").to_str().unwrap(),
    ]);
    assert_eq!(code(&o), 3, "{}", stderr(&o));
    assert!(stderr(&o).contains("/nonexistent/in.off: cannot read"));
    // An output folder that does not exist: 3, nothing created.
    let o = run(&["convert", m, "/nonexistent/dir/o.off"]);
    assert_eq!(code(&o), 3, "{}", stderr(&o));
    // Unknown output format, unknown option, missing argument: 4.
    for args in [
        vec!["convert", m, "o.stl"],
        vec!["convert", m],
        vec!["metrics", "--bogus", m],
        vec!["render", m, "o.jpg"],
        vec!["render", "--size", "12x3", m, "o.png"],
        vec!["frobnicate"],
    ] {
        let o = run(&args);
        assert_eq!(code(&o), 4, "{args:?}: {}", stderr(&o));
    }
    assert_eq!(dir.files(), vec!["m.off".to_string()]);
    // --help and --version succeed and document the statuses.
    let o = run(&["--help"]);
    assert_eq!(code(&o), 0);
    assert!(stdout(&o).contains("Exit status:"), "{}", stdout(&o));
    let o = run(&["--version"]);
    assert_eq!(code(&o), 0);
    assert!(stdout(&o).contains(env!("CARGO_PKG_VERSION")));
}

#[test]
fn lenient_goes_on_and_strict_refuses_warnings() {
    let dir = TempDir::new("policy");
    // Two tetrahedra sharing one vertex: a non-manifold vertex (an error).
    let p = dir.path("bowtie.off");
    std::fs::write(
        &p,
        "OFF\n7 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n-1 0 0\n0 -1 0\n0 0 -1\n\
         3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 0 5 4\n3 0 4 6\n3 0 6 5\n3 4 5 6\n",
    )
    .unwrap();
    let out = dir.path("o.off");
    let (p, o_s) = (p.to_str().unwrap(), out.to_str().unwrap());
    let o = run(&["convert", p, o_s]);
    assert_eq!(code(&o), 2);
    assert!(stderr(&o).contains("vertex 0") && stderr(&o).contains("--lenient"));
    assert!(!Path::new(&out).exists());
    let o = run(&["convert", "--lenient", p, o_s]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert!(stderr(&o).contains("warning:") && stderr(&o).contains("non-manifold vertex"));
    // render draws it by default.
    let png = dir.path("b.png");
    let o = run(&["render", "-q", p, png.to_str().unwrap(), "--size", "64x48"]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert!(png.exists());
}
