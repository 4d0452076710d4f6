//! `subdivide` and `demo`: every scheme, linear and Möbius, gives the library's output bit
//! for bit through every file format; bad input gives its exit status, a message naming the
//! file and element, and no output; the demo runs on nothing and draws a picture.

// Test helpers outside #[test] functions: clippy's in-test allowances do not reach them.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]

mod common;

use common::*;
use nlsubdiv::mesh::{Mesh as CoreMesh, MeshOut};
use nlsubdiv::scheme::{self, Options, Scheme, Scratch};

/// The library's result: one `scheme::subdivide` call of all the levels, linear or Möbius
/// (the command makes one call per level), buffers from `scheme::plan`. `Err` with the
/// status when the library refuses the mesh.
fn library(m: &TMesh, s: Scheme, is_mobius: bool, levels: usize) -> Result<TMesh, String> {
    library_with(m, &Options::new(s).mobius(is_mobius).levels(levels)).map(|(m, _)| m)
}

/// [`library`] with any options, and the report.
fn library_with(m: &TMesh, opts: &Options) -> Result<(TMesh, scheme::Report), String> {
    let (offsets, indices) = m.csr();
    let mesh = CoreMesh::new(&m.positions, &offsets, &indices);
    let opts = *opts;
    let mut s0 = vec![0u32; scheme::plan_scratch_size(&mesh).unwrap()];
    let plan = scheme::plan(mesh, &opts, &mut s0).map_err(|e| e.to_string())?;
    let mut su = vec![0u32; plan.scratch.u32s];
    let mut sp = vec![[0.0; 3]; plan.scratch.points];
    let o = plan.output();
    let (mut pos, mut offs, mut idx) = (
        vec![[0.0; 3]; o.vertices],
        vec![0u32; o.faces + 1],
        vec![0u32; o.indices],
    );
    let mut out = MeshOut::new(&mut pos, &mut offs, &mut idx);
    let report = scheme::subdivide(mesh, &opts, Scratch::new(&mut su, &mut sp), &mut out)
        .map_err(|e| e.to_string())?;
    Ok((TMesh::from_csr(pos, &offs, &idx), report))
}

fn name(s: Scheme, is_mobius: bool) -> String {
    if is_mobius {
        format!("mobius-{}", s.name())
    } else {
        s.name().to_string()
    }
}

fn assert_same(a: &TMesh, b: &TMesh, what: &str) {
    assert_eq!(a.faces, b.faces, "{what}: faces differ");
    assert_eq!(a.positions.len(), b.positions.len(), "{what}: vertex count");
    for (i, (p, q)) in a.positions.iter().zip(&b.positions).enumerate() {
        assert_eq!(
            p.map(f64::to_bits),
            q.map(f64::to_bits),
            "{what}: vertex {i}: {p:?} vs {q:?}"
        );
    }
}

/// Runs `subdivide` into `out_name` (any format) and reads the result back as OFF (through
/// `convert` for OBJ and PLY, which keeps every bit and the order).
fn run_subdivide(
    dir: &TempDir,
    input: &str,
    scheme: &str,
    levels: usize,
    out_name: &str,
) -> (std::process::Output, Option<TMesh>) {
    let out = dir.path(out_name);
    let o = run(&[
        "subdivide",
        "--scheme",
        scheme,
        "--levels",
        &levels.to_string(),
        dir.path(input).to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    if code(&o) != 0 {
        return (o, None);
    }
    let off = if out_name.ends_with(".off") {
        out.clone()
    } else {
        let off = dir.path("back.off");
        let c = run(&["convert", out.to_str().unwrap(), off.to_str().unwrap()]);
        assert_eq!(code(&c), 0, "convert {out_name}: {}", stderr(&c));
        off
    };
    let m = read_off(&off);
    std::fs::remove_file(&out).unwrap();
    let _ = std::fs::remove_file(dir.path("back.off"));
    (o, Some(m))
}

/// A closed prism over a regular `n`-gon: two `n`-gons and `n` quads (mixed faces).
fn prism(n: u32) -> TMesh {
    let mut positions = Vec::new();
    for z in [-0.6, 0.7] {
        for i in 0..n {
            let t = std::f64::consts::TAU * f64::from(i) / f64::from(n);
            positions.push([t.cos(), t.sin() * 0.9, z + 0.05 * (3.0 * t).sin()]);
        }
    }
    let mut faces = vec![(0..n).rev().collect::<Vec<u32>>(), (n..2 * n).collect()];
    for i in 0..n {
        let j = (i + 1) % n;
        faces.push(vec![i, j, n + j, n + i]);
    }
    TMesh { positions, faces }
}

/// An open quad grid on a saddle.
fn quad_grid(n: u32, m: u32) -> TMesh {
    let mut positions = Vec::new();
    for j in 0..=m {
        for i in 0..=n {
            let (x, y) = (
                f64::from(i) / f64::from(n) - 0.5,
                f64::from(j) / f64::from(m) - 0.5,
            );
            positions.push([x, y, 0.4 * (x * x - y * y) + 0.1 * x * y]);
        }
    }
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut faces = Vec::new();
    for j in 0..m {
        for i in 0..n {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TMesh { positions, faces }
}

/// The quad grid with every quad split into two triangles.
fn tri_grid(n: u32, m: u32) -> TMesh {
    let q = quad_grid(n, m);
    let faces = q
        .faces
        .iter()
        .flat_map(|f| [vec![f[0], f[1], f[2]], vec![f[0], f[2], f[3]]])
        .collect();
    TMesh {
        positions: q.positions,
        faces,
    }
}

/// Generated meshes each scheme accepts: closed and open.
fn meshes_for(s: Scheme) -> Vec<(&'static str, TMesh)> {
    match s {
        Scheme::Loop | Scheme::ModifiedButterfly => {
            vec![("icosphere", icosphere(1)), ("tri-grid", tri_grid(4, 3))]
        }
        Scheme::Kobbelt => vec![
            ("torus", torus(8, 6, 2.0, 0.7)),
            ("quad-grid", quad_grid(5, 4)),
        ],
        _ => vec![("prism", prism(5)), ("mixed-grid", open_grid(4, 3))],
    }
}

#[test]
fn every_scheme_gives_the_library_output_bit_for_bit() {
    let dir = TempDir::new("subdivide-all");
    let formats = ["off", "obj", "ply"];
    let mut k = 0;
    for is_mobius in [false, true] {
        for &s in Scheme::ALL
            .iter()
            .filter(|s| !is_mobius || s.has_mobius_form())
        {
            for (mname, m) in meshes_for(s) {
                let input = format!("{mname}.off");
                m.write_off(&dir.path(&input));
                let levels = 2;
                let sname = name(s, is_mobius);
                let fmt = formats[k % formats.len()];
                k += 1;
                let (o, got) = run_subdivide(&dir, &input, &sname, levels, &format!("out.{fmt}"));
                let what = format!("{sname} on {mname} (.{fmt})");
                assert_eq!(code(&o), 0, "{what}: {}", stderr(&o));
                let want = library(&read_off(&dir.path(&input)), s, is_mobius, levels)
                    .unwrap_or_else(|e| panic!("{what}: the library refuses: {e}"));
                assert_same(&got.unwrap(), &want, &what);
                // The one-line summary.
                let err = stderr(&o);
                assert_eq!(err.lines().count(), 1, "{what}: {err}");
                assert!(
                    err.starts_with("wrote ")
                        && err.contains(&format!("{sname}, 2 levels"))
                        && err.contains(&format!("→ {} vertices", want.positions.len()))
                        && err.contains(&format!("→ {} faces", want.faces.len()))
                        && err.contains(" s"),
                    "{what}: {err}"
                );
                assert_eq!(err.contains("fallback"), is_mobius, "{what}: {err}");
            }
        }
    }
    // Level 0 copies, whatever the scheme accepts.
    let m = quad_grid(3, 2);
    m.write_off(&dir.path("q.off"));
    for s in ["loop", "mobius-kobbelt", "dual"] {
        let (o, got) = run_subdivide(&dir, "q.off", s, 0, "copy.ply");
        assert_eq!(code(&o), 0, "{s}: {}", stderr(&o));
        assert_same(&got.unwrap(), &read_off(&dir.path("q.off")), "level 0");
    }
}

#[test]
fn shared_meshes_give_the_library_output_or_are_refused() {
    const TEST: &str = "cli::subdivide::shared_meshes_give_the_library_output_or_are_refused";
    let Some(shared) = shared_meshes(TEST) else {
        return;
    };
    let dir = TempDir::new("subdivide-shared");
    let names = [
        "cube",
        "icosahedron",
        "pyramid_mixed",
        "house_pentagons",
        "helmet_quad",
        "pole8_mixed",
    ];
    let (mut ok, mut refused) = (0, 0);
    for n in names {
        let src = shared.join(format!("{n}.off"));
        if !src.exists() {
            skip(
                TEST,
                &format!("{} not found; {n} not checked", src.display()),
            );
            continue;
        }
        std::fs::copy(&src, dir.path("in.off")).unwrap();
        let m = read_off(&dir.path("in.off"));
        for is_mobius in [false, true] {
            for &s in Scheme::ALL
                .iter()
                .filter(|s| !is_mobius || s.has_mobius_form())
            {
                let sname = name(s, is_mobius);
                let what = format!("{sname} on {n}");
                let (o, got) = run_subdivide(&dir, "in.off", &sname, 2, "out.off");
                match library(&m, s, is_mobius, 2) {
                    Ok(want) => {
                        assert_eq!(code(&o), 0, "{what}: {}", stderr(&o));
                        assert_same(&got.unwrap(), &want, &what);
                        ok += 1;
                    }
                    Err(e) => {
                        assert_eq!(code(&o), 2, "{what} (library: {e}): {}", stderr(&o));
                        assert!(stderr(&o).contains("in.off"), "{what}: {}", stderr(&o));
                        refused += 1;
                    }
                }
                assert_files(&dir, &["in.off"], &what);
            }
        }
    }
    println!("shared meshes: {ok} subdivided as the library does, {refused} refused as it does");
    assert!(ok > 0);
}

fn refs(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

/// Runs a command that must fail: its status, a message containing every needle, and no
/// file but `keep` left in the folder.
fn must_fail(dir: &TempDir, args: &[&str], status: i32, needles: &[&str], keep: &[&str]) {
    let o = run(args);
    let err = stderr(&o);
    assert_eq!(code(&o), status, "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: '{n}' not in: {err}");
    }
    assert_files(dir, keep, &format!("{args:?}"));
}

#[test]
fn bad_input_gives_its_status_names_the_element_and_leaves_nothing() {
    let dir = TempDir::new("subdivide-bad");
    let p = |n: &str| dir.path(n).to_str().unwrap().to_string();
    // Loop on quads: the file, the line and the face.
    let q = quad_grid(3, 2);
    q.write_off(&dir.path("quads.off"));
    let face0_line = 3 + q.positions.len();
    // A single quad: its face point has no Möbius rule (all corners are ears).
    std::fs::write(
        dir.path("quad.off"),
        "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
    )
    .unwrap();
    // Three faces on one edge.
    std::fs::write(
        dir.path("fin.off"),
        "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n",
    )
    .unwrap();
    // An unreferenced vertex (a warning: refused with --strict only).
    std::fs::write(
        dir.path("extra.off"),
        "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n5 5 5\n3 0 1 2\n",
    )
    .unwrap();
    std::fs::write(
        dir.path("nan.off"),
        "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n",
    )
    .unwrap();
    std::fs::write(dir.path("junk.off"), "this is not a mesh\n").unwrap();
    let inputs = [
        "extra.off",
        "fin.off",
        "junk.off",
        "nan.off",
        "quad.off",
        "quads.off",
    ];
    let out = p("out.off");
    let sub = |scheme: &str, levels: &str, input: &str, out: &str| -> Vec<String> {
        [
            "subdivide",
            "--scheme",
            scheme,
            "--levels",
            levels,
            &p(input),
            out,
        ]
        .iter()
        .map(|s| s.to_string())
        .collect()
    };

    let a = sub("loop", "1", "quads.off", &out);
    must_fail(
        &dir,
        &refs(&a),
        2,
        &[&format!("quads.off:{face0_line}: face 0"), "triangles"],
        &inputs,
    );
    let a = sub("mobius-butterfly", "2", "quads.off", &out);
    must_fail(&dir, &refs(&a), 2, &["face 0", "triangles"], &inputs);
    let a = sub("kobbelt", "1", "fin.off", &out);
    must_fail(
        &dir,
        &refs(&a),
        2,
        &["fin.off", "non-manifold", "repair"],
        &inputs,
    );
    // `subdivide` has no --lenient: its refusal must not offer one.
    let o = run(&refs(&a));
    assert!(!stderr(&o).contains("--lenient"), "{}", stderr(&o));
    let a = sub("catmull-clark", "1", "junk.off", &out);
    must_fail(&dir, &refs(&a), 2, &["junk.off"], &inputs);
    let a = sub("catmull-clark", "1", "nan.off", &out);
    must_fail(&dir, &refs(&a), 2, &["nan.off:4: vertex 1", "NaN"], &inputs);
    let a = sub("catmull-clark", "1", "missing.off", &out);
    must_fail(&dir, &refs(&a), 3, &["missing.off"], &inputs);
    let a = sub("catmull-clark", "1", "quad.off", &p("no/such/dir/out.off"));
    must_fail(&dir, &refs(&a), 3, &["out.off"], &inputs);
    let a = sub("catmull-clark", "1", "quad.off", &p("out.txt"));
    must_fail(
        &dir,
        &refs(&a),
        4,
        &["out.txt", ".off, .obj or .ply"],
        &inputs,
    );

    // Möbius fallbacks: counted by default, an error naming the element with --strict.
    let mut a = sub("mobius-catmull-clark", "1", "quad.off", &out);
    a.insert(5, "--strict".into());
    must_fail(
        &dir,
        &refs(&a),
        2,
        &[
            "quad.off",
            "output vertex 8",
            "face point of face 0 (line 7)",
            "--strict",
        ],
        &inputs,
    );
    let o = run(&refs(&sub("mobius-catmull-clark", "1", "quad.off", &out)));
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert!(
        stderr(&o).contains("1 fallback to the linear rule"),
        "{}",
        stderr(&o)
    );
    std::fs::remove_file(&out).unwrap();
    // Warnings: printed by default, refused with --strict.
    let o = run(&refs(&sub("loop", "1", "extra.off", &out)));
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert!(stderr(&o).contains("unreferenced"), "{}", stderr(&o));
    std::fs::remove_file(&out).unwrap();
    let mut a = sub("loop", "1", "extra.off", &out);
    a.insert(5, "--strict".into());
    must_fail(&dir, &refs(&a), 2, &["extra.off", "vertex 3"], &inputs);

    // The command line: names this version does not have, unknown names, too many levels.
    for (scheme, needle) in [
        ("differential-spline", "unknown mesh scheme"),
        ("mobius-spherelike", "no Möbius form"),
        ("four-point", "curve scheme"),
        ("catmul-clark", "unknown mesh scheme"),
    ] {
        let a = sub(scheme, "1", "quads.off", &out);
        must_fail(
            &dir,
            &refs(&a),
            4,
            &[
                needle,
                "available: loop, catmull-clark",
                "mobius-dual-truncation",
            ],
            &inputs,
        );
    }
    // The list names every scheme once (the differential names used to appear twice).
    let o = run(&refs(&sub("catmul-clark", "1", "quads.off", &out)));
    for name in ["differential-loop", "differential-dirmag", "mobius-loop,"] {
        assert_eq!(
            stderr(&o).matches(name).count(),
            1,
            "{name}: {}",
            stderr(&o)
        );
    }
    let a = sub("vertex-insertion", "9", "quads.off", &out);
    must_fail(
        &dir,
        &refs(&a),
        4,
        &["level 6 of vertex-insertion", "use at most 5 levels"],
        &inputs,
    );
    let a = sub("loop", "17", "quads.off", &out);
    must_fail(&dir, &refs(&a), 4, &["17"], &inputs);
}

#[test]
fn demo_runs_on_nothing_and_draws_the_dome() {
    // No arguments, in an empty folder: it writes there.
    let dir = TempDir::new("demo");
    let o = std::process::Command::new(bin())
        .arg("demo")
        .current_dir(&dir.0)
        .output()
        .unwrap();
    let out = stdout(&o);
    assert_eq!(code(&o), 0, "{out}{}", stderr(&o));
    println!("{out}");
    assert_files(&dir, &["demo.png", "demo_cage.off", "demo_out.off"], "demo");
    for needle in [
        "78 vertices, 55 faces",
        "4 levels of mobius-catmull-clark",
        "15360 faces",
        "0 fallbacks",
        "best-fit sphere",
        "Willmore",
    ] {
        assert!(out.contains(needle), "'{needle}' not in:\n{out}");
    }
    // A cage on the sphere stays on it: the printed deviation is a rounding error.
    let line = out.lines().find(|l| l.contains("unit sphere")).unwrap();
    let dev: f64 = line
        .split("max |r − 1| = ")
        .nth(1)
        .unwrap()
        .split(')')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(dev < 1e-13, "{line}");
    // The picture: not blank, mostly covered by the dome, with colour.
    let (w, h, rgb) = decode_png(&dir.path("demo.png"));
    let (var, covered) = picture_stats(w, h, &rgb);
    assert!(
        var > 100.0 && covered > 0.2,
        "variance {var}, covered {covered}"
    );
    let colourful = rgb
        .chunks(3)
        .filter(|c| c.iter().max().unwrap() - c.iter().min().unwrap() > 60)
        .count();
    assert!(
        colourful as f64 > 0.05 * f64::from(w * h),
        "{colourful} coloured pixels"
    );
    // The point of the picture: in the bottom row (the cage on the unit sphere, coloured by
    // the distance from it on one scale), the linear result reaches the yellow end of the
    // scale and the Möbius one has no pixel near it (it stays on the sphere).
    assert_eq!(
        (w, h),
        (1440, 948),
        "panel layout changed: update the regions below"
    );
    let yellow_in = |x0: u32, x1: u32| {
        (492..872)
            .flat_map(|y| (x0..x1).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                let i = ((y * w + x) * 3) as usize;
                let (r, g, b) = (rgb[i], rgb[i + 1], rgb[i + 2]);
                r > 170 && g > 170 && b < 110
            })
            .count()
    };
    let (lin, mob) = (yellow_in(480, 960), yellow_in(960, 1440));
    assert!(
        lin > 1000 && mob == 0,
        "yellow pixels: linear {lin}, Möbius {mob}"
    );
    // The result is `subdivide` of the cage it wrote, bit for bit.
    let (o, got) = run_subdivide(
        &dir,
        "demo_cage.off",
        "mobius-catmull-clark",
        4,
        "again.off",
    );
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert_same(&got.unwrap(), &read_off(&dir.path("demo_out.off")), "demo");

    // --out: a new folder.
    let sub = dir.path("a/b");
    let o = run(&["demo", "--levels", "1", "--out", sub.to_str().unwrap()]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert!(sub.join("demo.png").is_file() && sub.join("demo_out.off").is_file());
}

#[test]
fn spherelike_interpolates_and_names_a_degenerate_circle() {
    let dir = TempDir::new("subdivide-spherelike");
    // A grid: old vertices are output vertices at the same indices, bit for bit.
    let g = quad_grid(3, 2);
    g.write_off(&dir.path("g.off"));
    let (o, got) = run_subdivide(&dir, "g.off", "spherelike", 3, "out.off");
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let got = got.unwrap();
    assert_eq!(got.bits()[..g.positions.len()], g.bits()[..]);
    // Two coincident neighbours (vertices 0 and 1): the circle of edge (0, 1), edge 0, output
    // vertex 12 (V = 12), is undefined. Exit 2, the output vertex named, nothing written.
    let mut d = g.clone();
    d.positions[1] = d.positions[0];
    d.write_off(&dir.path("d.off"));
    let out = dir.path("never.off").to_str().unwrap().to_string();
    let input = dir.path("d.off").to_str().unwrap().to_string();
    let args = [
        "subdivide",
        "--scheme",
        "spherelike",
        "--levels",
        "1",
        &input,
        &out,
    ];
    must_fail(
        &dir,
        &args,
        2,
        &["d.off", "output vertex 12", "no circle"],
        &["g.off", "d.off"],
    );
}

/// The fold guard is the default of `mobius-*`; `--literal` gives the paper's rules; both are
/// the library's bits, and the summary counts the guarded elements and the folded edges. The
/// mesh: a triangulated saddle with one interior vertex pulled most of the way to a
/// neighbour, so that its star's canonical form is ill-conditioned.
#[test]
fn literal_and_the_fold_guard_match_the_library_and_are_summarised() {
    let dir = TempDir::new("subdivide-literal");
    let mut m = tri_grid(6, 6);
    let (v, u) = (3 * 7 + 3, 3 * 7 + 4);
    let (p, q) = (m.positions[v], m.positions[u]);
    m.positions[v] = [
        p[0] + 0.9 * (q[0] - p[0]),
        p[1] + 0.9 * (q[1] - p[1]),
        p[2] + 0.9 * (q[2] - p[2]),
    ];
    m.write_off(&dir.path("in.off"));
    let opts = Options::new(Scheme::Loop).mobius(true).levels(2);
    let (guarded, report) = library_with(&m, &opts).unwrap();
    let (literal, lit_report) = library_with(&m, &opts.literal(true)).unwrap();
    assert!(report.guarded > 0, "the guard changes nothing on this mesh");
    assert_eq!(lit_report.guarded, 0);
    assert_ne!(guarded.positions, literal.positions);
    let (o, got) = run_subdivide(&dir, "in.off", "mobius-loop", 2, "out.off");
    assert_same(&got.unwrap(), &guarded, "default");
    let summary = stderr(&o);
    assert!(
        summary.contains(&format!(
            "{} elements changed by the fold guard",
            report.guarded
        )),
        "{summary}"
    );
    assert!(summary.contains("folded edge"), "{summary}");
    let out = dir.path("lit.off");
    let o = run(&[
        "subdivide",
        "--scheme",
        "mobius-loop",
        "--levels",
        "2",
        "--literal",
        dir.path("in.off").to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert_same(&read_off(&out), &literal, "--literal");
    assert!(stderr(&o).contains("literal rules"), "{}", stderr(&o));
    let o = run(&["metrics", out.to_str().unwrap()]);
    assert!(
        stdout(&o).contains("folds (interior edges"),
        "{}",
        stdout(&o)
    );
}

#[test]
fn spectrum_runs_from_the_linear_to_the_mobius_result() {
    let dir = TempDir::new("spectrum");
    let mut m = tri_grid(4, 3);
    for p in &mut m.positions {
        p[2] = 0.3 * (1.7 * p[0]).sin() * (1.1 * p[1]).cos();
    }
    m.write_off(&dir.path("grid.off"));
    let input = dir.path("grid.off").to_str().unwrap().to_string();
    let sub = |scheme: &str, extra: &[&str], out: &str| {
        let out = dir.path(out);
        let mut a = vec!["subdivide", "--scheme", scheme, "--levels", "2"];
        a.extend_from_slice(extra);
        a.push(&input);
        let o_str = out.to_str().unwrap().to_string();
        let o = run(&[a, vec![o_str.as_str()]].concat());
        (o, out)
    };
    let (o, lin) = sub("loop", &[], "lin.off");
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let (o, mob) = sub("mobius-loop", &[], "mob.off");
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let (o, w0) = sub("mobius-loop", &["--spectrum", "0"], "w0.off");
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let (o, w1) = sub("mobius-loop", &["--spectrum", "1"], "w1.off");
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let (o, half) = sub("mobius-loop", &["--spectrum", "0.5"], "half.off");
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let (lin, mob, w0, w1, half) = (
        read_off(&lin),
        read_off(&mob),
        read_off(&w0),
        read_off(&w1),
        read_off(&half),
    );
    assert_same(&w0, &lin, "--spectrum 0 is the linear result");
    assert_same(&w1, &mob, "--spectrum 1 is the Möbius result");
    assert!(half.positions != lin.positions && half.positions != mob.positions);
    // Out of range, or with a linear scheme: refused, nothing written.
    let (o, _) = sub("mobius-loop", &["--spectrum", "1.5"], "bad.off");
    assert_ne!(code(&o), 0);
    let (o, _) = sub("loop", &["--spectrum", "0.5"], "bad.off");
    assert_eq!(code(&o), 4, "{}", stderr(&o));
    assert!(stderr(&o).contains("--spectrum"), "{}", stderr(&o));
    assert!(!dir.path("bad.off").exists());
}

/// `--spectrum-weights FILE`: equal weights are `--spectrum` bit for bit (all 1 the Möbius
/// result, all 0 the linear one), mixed weights are the library's `subdivide_weighted` with
/// the same weights for every thread count, and a bad file is refused naming its line and
/// vertex (exit 2), with a linear scheme or with `--spectrum` as a usage error (exit 4),
/// nothing written.
#[test]
fn spectrum_weights_file() {
    let dir = TempDir::new("spectrum-weights");
    let mut m = quad_grid(4, 3);
    for p in &mut m.positions {
        p[2] = 0.3 * (1.7 * p[0]).sin() * (1.1 * p[1]).cos();
    }
    m.write_off(&dir.path("grid.off"));
    let n = m.positions.len();
    let input = dir.path("grid.off").to_str().unwrap().to_string();
    let weights_file = |name: &str, ws: &[String]| {
        let path = dir.path(name);
        std::fs::write(
            &path,
            format!("# one weight per vertex\n{}\n", ws.join("\n")),
        )
        .unwrap();
        path.to_str().unwrap().to_string()
    };
    let sub = |scheme: &str, extra: &[&str], out: &str| {
        let out = dir.path(out);
        let mut a = vec!["subdivide", "--scheme", scheme, "--levels", "2"];
        a.extend_from_slice(extra);
        a.push(&input);
        let o_str = out.to_str().unwrap().to_string();
        let o = run(&[a, vec![o_str.as_str()]].concat());
        (o, out)
    };
    let ok = |(o, path): (std::process::Output, std::path::PathBuf)| {
        assert_eq!(code(&o), 0, "{}", stderr(&o));
        read_off(&path)
    };
    for (w, global) in [("0", "0"), ("1", "1"), ("0.3", "0.3")] {
        let f = weights_file(&format!("all{w}.txt"), &vec![w.to_string(); n]);
        let a = ok(sub(
            "mobius-catmull-clark",
            &["--spectrum-weights", &f],
            "a.off",
        ));
        let b = ok(sub(
            "mobius-catmull-clark",
            &["--spectrum", global],
            "b.off",
        ));
        assert_same(&a, &b, &format!("all {w}"));
    }
    // Mixed: the library's call with the same weights, on 1 and 3 threads.
    let ws: Vec<f64> = (0..n).map(|i| (i % 4) as f64 / 3.0).collect();
    let f = weights_file(
        "mixed.txt",
        &ws.iter().map(|w| format!("{w:?}")).collect::<Vec<_>>(),
    );
    let (offsets, indices) = m.csr();
    let mesh = CoreMesh::new(&m.positions, &offsets, &indices);
    let opts = Options::new(Scheme::CatmullClark).mobius(true).levels(2);
    let (tags, weights) = (
        scheme::Tags::new(),
        Some(scheme::VertexWeights::Mobius(&ws)),
    );
    let mut su = vec![0u32; scheme::plan_scratch_size(&mesh).unwrap()];
    let plan = scheme::plan_weighted(mesh, &opts, &tags, weights, &mut su).unwrap();
    su.resize(plan.scratch.u32s, 0);
    let mut sp = vec![[0.0; 3]; plan.scratch.points];
    let o = plan.output();
    let (mut pos, mut offs, mut idx) = (
        vec![[0.0; 3]; o.vertices],
        vec![0u32; o.faces + 1],
        vec![0u32; o.indices],
    );
    scheme::subdivide_weighted(
        mesh,
        &opts,
        &tags,
        weights,
        Scratch::new(&mut su, &mut sp),
        &mut MeshOut::new(&mut pos, &mut offs, &mut idx),
        &nlsubdiv::exec::Serial,
    )
    .unwrap();
    let want = TMesh::from_csr(pos, &offs, &idx);
    for threads in ["1", "3"] {
        let got = ok(sub(
            "mobius-catmull-clark",
            &["--spectrum-weights", &f, "--threads", threads],
            "mixed.off",
        ));
        assert_same(&got, &want, &format!("mixed weights, {threads} threads"));
    }
    let lin = ok(sub("catmull-clark", &[], "lin.off"));
    assert!(want.positions != lin.positions);
    // Bad files: named by line (and vertex), nothing written.
    let mut bad = vec!["0.5".to_string(); n];
    bad[2] = "1.5".to_string();
    let f = weights_file("bad.txt", &bad);
    let (o, out) = sub(
        "mobius-catmull-clark",
        &["--spectrum-weights", &f],
        "bad.off",
    );
    assert_eq!(code(&o), 2, "{}", stderr(&o));
    assert!(
        stderr(&o).contains("bad.txt:4") && stderr(&o).contains("vertex 2"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
    let f = weights_file("short.txt", &vec!["0.5".to_string(); n - 1]);
    let (o, out) = sub(
        "mobius-catmull-clark",
        &["--spectrum-weights", &f],
        "bad.off",
    );
    assert_eq!(code(&o), 2, "{}", stderr(&o));
    assert!(stderr(&o).contains("one per vertex"), "{}", stderr(&o));
    assert!(!out.exists());
    let f = weights_file("good.txt", &vec!["0.5".to_string(); n]);
    let (o, out) = sub("catmull-clark", &["--spectrum-weights", &f], "bad.off");
    assert_eq!(code(&o), 4, "{}", stderr(&o));
    assert!(!out.exists());
    let (o, out) = sub(
        "mobius-catmull-clark",
        &["--spectrum-weights", &f, "--spectrum", "0.5"],
        "bad.off",
    );
    assert_eq!(code(&o), 4, "{}", stderr(&o));
    assert!(!out.exists());
}

/// `--threads N`: the same output file, byte for byte, for 1, 2, 3 and 7 threads, linear and
/// Möbius; the summary names the thread count and the kernel's time in milliseconds.
#[test]
fn threads_give_the_same_bytes() {
    let dir = TempDir::new("subdivide-threads");
    torus(24, 16, 2.0, 0.6).write_off(&dir.path("t.off"));
    for scheme in [
        "catmull-clark",
        "mobius-catmull-clark",
        "doo-sabin",
        "spherelike",
    ] {
        let mut first: Option<Vec<u8>> = None;
        for t in [1, 2, 3, 7] {
            let out = format!("out{t}.off");
            let o = run(&[
                "subdivide",
                "--scheme",
                scheme,
                "--levels",
                "3",
                "--threads",
                &t.to_string(),
                dir.path("t.off").to_str().unwrap(),
                dir.path(&out).to_str().unwrap(),
            ]);
            assert_eq!(code(&o), 0, "{scheme} {t}: {}", stderr(&o));
            let plural = if t == 1 { "thread" } else { "threads" };
            assert!(
                stderr(&o).contains(&format!(" ms, {t} {plural})")),
                "{scheme} {t}: {}",
                stderr(&o)
            );
            let bytes = std::fs::read(dir.path(&out)).unwrap();
            match &first {
                None => first = Some(bytes),
                Some(b) => assert!(*b == bytes, "{scheme}: {t} threads differ from 1"),
            }
        }
    }
}
