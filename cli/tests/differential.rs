//! `subdivide --scheme differential-*` and the thin-plate energy of `metrics`: the output is
//! the library's (`nlsubdiv::differential::subdivide`) bit for bit for 1 and 3 threads, the
//! summary reports the thread count and the reconstruction, non-triangles and non-convergence give exit 2 with a message and no
//! output, and `metrics` reports the thin-plate energy of a sphere as about 2/r².

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]

mod common;

use common::*;
use nlsubdiv::differential::{self as diff, DifferentialOptions, DifferentialReport, Stencil};
use nlsubdiv::mesh::{Mesh as CoreMesh, MeshOut};

fn library(m: &TMesh, stencil: Stencil, levels: usize, dirmag: usize) -> TMesh {
    let opts = DifferentialOptions {
        stencil,
        levels,
        dirmag_levels: dirmag,
        ..Default::default()
    };
    library_with(m, &opts)
}

fn library_with(m: &TMesh, opts: &DifferentialOptions<'_>) -> TMesh {
    let (off, idx) = m.csr();
    let mesh = CoreMesh::new(&m.positions, &off, &idx);
    let opts = *opts;
    let mut s0 = vec![0u32; diff::plan_scratch_size(&mesh).unwrap()];
    let plan = diff::plan(mesh, &opts, &mut s0).unwrap();
    let mut su = vec![0u32; plan.scratch_u32];
    let mut sp = vec![[0.0; 3]; plan.scratch_points];
    let o = plan.output();
    let (mut pos, mut offs, mut ix) = (
        vec![[0.0; 3]; o.vertices],
        vec![0u32; o.faces + 1],
        vec![0u32; o.indices],
    );
    let mut out = MeshOut::new(&mut pos, &mut offs, &mut ix);
    let mut rep = DifferentialReport::default();
    diff::subdivide(mesh, &opts, &mut su, &mut sp, &mut out, &mut rep).unwrap();
    TMesh::from_csr(pos, &offs, &ix)
}

#[test]
fn differential_schemes_give_the_library_output_bit_for_bit() {
    let dir = TempDir::new("differential");
    let input = dir.path("ico.off");
    let mut m = icosphere(1);
    // Not on a sphere, so the three schemes differ.
    for (i, p) in m.positions.iter_mut().enumerate() {
        p[2] *= 1.0 + 0.1 * (i % 3) as f64;
    }
    m.write_off(&input);
    for (name, stencil, dirmag) in [
        ("differential-loop", Stencil::Loop, 0),
        ("differential-butterfly", Stencil::ModifiedButterfly, 0),
        ("differential-dirmag", Stencil::ModifiedButterfly, 1),
    ] {
        let want = library(&m, stencil, 2, dirmag);
        for threads in ["1", "3"] {
            let out = dir.path(&format!("{name}-{threads}.off"));
            let o = run(&[
                "subdivide",
                "--scheme",
                name,
                "--levels",
                "2",
                "--threads",
                threads,
                input.to_str().unwrap(),
                out.to_str().unwrap(),
            ]);
            assert_eq!(code(&o), 0, "{}", stderr(&o));
            assert!(stderr(&o).contains("reconstruction:"), "{}", stderr(&o));
            let plural = if threads == "1" { "thread" } else { "threads" };
            assert!(
                stderr(&o).contains(&format!(" s ({threads} {plural}); ")),
                "{}",
                stderr(&o)
            );
            let got = read_off(&out);
            assert_eq!(got.faces, want.faces, "{name}");
            assert_eq!(got.bits(), want.bits(), "{name} {threads} threads");
        }
    }
}

#[test]
fn bad_input_and_non_convergence_fail_with_a_message_and_no_output() {
    let dir = TempDir::new("differential-bad");
    let quads = dir.path("quads.off");
    open_grid(3, 3).write_off(&quads);
    let ico = dir.path("ico.off");
    icosphere(1).write_off(&ico);
    let out = dir.path("out.off");
    let o = run(&[
        "subdivide",
        "--scheme",
        "differential-butterfly",
        "--levels",
        "1",
        quads.to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    // open_grid's face 0 is a quad.
    assert_eq!(code(&o), 2, "{}", stderr(&o));
    assert!(stderr(&o).contains("face 0"), "{}", stderr(&o));
    assert!(stderr(&o).contains("not a triangle"), "{}", stderr(&o));
    assert!(!out.exists());
    let o = run(&[
        "subdivide",
        "--scheme",
        "differential-loop",
        "--levels",
        "3",
        "--max-iterations",
        "1",
        ico.to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    assert_eq!(code(&o), 2, "{}", stderr(&o));
    assert!(stderr(&o).contains("did not converge"), "{}", stderr(&o));
    assert!(!out.exists());
    let o = run(&[
        "subdivide",
        "--scheme",
        "differential-loop",
        "--levels",
        "1",
        "--tolerance",
        "nan",
        ico.to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    assert_eq!(code(&o), 4, "{}", stderr(&o));
    assert!(!out.exists());
}

#[test]
fn metrics_report_the_thin_plate_energy_of_a_sphere() {
    let dir = TempDir::new("differential-metrics");
    let f = dir.path("sphere.off");
    icosphere(4).write_off(&f);
    let o = run(&["metrics", "--json", f.to_str().unwrap()]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let e = v["thin_plate"].as_f64().unwrap();
    // Unit sphere: κ₁ = κ₂ = 1, so ∫(κ₁² + κ₂²)/area = 2 (up to the discretisation).
    assert!((e - 2.0).abs() < 0.05, "{e}");
    let o = run(&["metrics", f.to_str().unwrap()]);
    assert!(stdout(&o).contains("thin-plate energy"), "{}", stdout(&o));
}

#[test]
fn edits_from_a_file_are_the_library_edits_and_do_what_they_ask() {
    let dir = TempDir::new("differential-edit");
    let input = dir.path("ico.off");
    let m = icosphere(1);
    m.write_off(&input);
    let n = m.positions.len();
    // Vertex 1 is at (1, φ, 0) scaled: a normal tilted from its own by about 17°.
    let p1 = m.positions[1];
    let tilted = [p1[0] + 0.3, p1[1], p1[2] + 0.3];
    let edits = dir.path("edits.txt");
    std::fs::write(
        &edits,
        format!(
            "# doubled curvature at 0, a tilted normal at 1\ncurvature 0 2\n\nnormal 1 {} {} {}  # tilt\n",
            tilted[0], tilted[1], tilted[2]
        ),
    )
    .unwrap();
    let out = dir.path("out.off");
    let o = run(&[
        "subdivide",
        "--scheme",
        "differential-loop",
        "--levels",
        "2",
        "--edit",
        edits.to_str().unwrap(),
        input.to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert!(stderr(&o).contains("edits: 2 from"), "{}", stderr(&o));
    assert!(stderr(&o).contains("0 folded faces"), "{}", stderr(&o));
    let mut scale = vec![1.0; n];
    scale[0] = 2.0;
    let mut normals = vec![[0.0; 3]; n];
    normals[1] = tilted;
    let edited = DifferentialOptions {
        stencil: Stencil::Loop,
        levels: 2,
        curvature_scale: Some(&scale),
        normals: Some(&normals),
        ..Default::default()
    };
    let got = read_off(&out);
    let want = library_with(&m, &edited);
    assert_eq!(got.faces, want.faces);
    assert_eq!(got.bits(), want.bits());
    // What the edits do: the doubled curvature moves vertex 0 outward (away from the centre
    // of the sphere-like mesh), which the unedited result does not.
    let plain = library(&m, Stencil::Loop, 2, 0);
    let r = |p: [f64; 3]| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    assert!(
        r(got.positions[0]) > r(plain.positions[0]) + 1e-3,
        "{} vs {}",
        r(got.positions[0]),
        r(plain.positions[0])
    );
}

#[test]
fn folding_edits_are_counted_or_refused_and_bad_edit_files_name_the_line() {
    let dir = TempDir::new("differential-edit-bad");
    let input = dir.path("ico.off");
    icosphere(1).write_off(&input);
    let out = dir.path("out.off");
    let edit = |name: &str, text: &str, extra: &[&str]| {
        let f = dir.path(name);
        std::fs::write(&f, text).unwrap();
        let mut args = vec![
            "subdivide".to_string(),
            "--scheme".into(),
            "differential-loop".into(),
            "--levels".into(),
            "2".into(),
            "--edit".into(),
            f.to_str().unwrap().into(),
        ];
        args.extend(extra.iter().map(|s| s.to_string()));
        args.push(input.to_str().unwrap().into());
        args.push(out.to_str().unwrap().into());
        run(&args)
    };
    // A strongly negative curvature turns vertex 0's neighbourhood inside out.
    let o = edit("fold.txt", "curvature 0 -20\n", &[]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert!(!stderr(&o).contains(" 0 folded faces"), "{}", stderr(&o));
    assert!(stderr(&o).contains("folded face"), "{}", stderr(&o));
    std::fs::remove_file(&out).unwrap();
    let o = edit("fold.txt", "curvature 0 -20\n", &["--strict"]);
    assert_eq!(code(&o), 2, "{}", stderr(&o));
    assert!(stderr(&o).contains("fold the surface"), "{}", stderr(&o));
    assert!(!out.exists());
    for (text, at) in [
        (
            "curvature 0 2\nnormal 99 0 0 1\n",
            ":2: vertex 99 is out of range",
        ),
        ("curvature 0 nan\n", ":1: 'nan' is not finite"),
        (
            "normal 0 0 0 0\n",
            ":1: the normal of vertex 0 has length 0",
        ),
        ("twist 0 1\n", ":1: unknown edit"),
    ] {
        let o = edit("bad.txt", text, &[]);
        assert_eq!(code(&o), 2, "{text:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(at), "{text:?}: {}", stderr(&o));
        assert!(!out.exists());
    }
    // Edits belong to differential-space subdivision.
    let f = dir.path("ok.txt");
    std::fs::write(&f, "curvature 0 2\n").unwrap();
    let o = run(&[
        "subdivide",
        "--scheme",
        "loop",
        "--levels",
        "1",
        "--edit",
        f.to_str().unwrap(),
        input.to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    assert_ne!(code(&o), 0, "{}", stderr(&o));
    assert!(stderr(&o).contains("differential-*"), "{}", stderr(&o));
    assert!(!out.exists());
}
