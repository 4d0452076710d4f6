//! `subdivide` with sharp-feature tags: OBJ `t crease` / `t corner` statements and
//! `--crease-angle` give the library's tagged result bit for bit (one
//! `scheme::subdivide_tagged` call); bad tags exit 2 naming the OBJ line.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]

mod common;

use common::*;
use nlsubdiv::mesh::{Mesh as CoreMesh, MeshOut};
use nlsubdiv::scheme::{self, CreaseMethod, Options, Scheme, Scratch, Tags};

const CUBE: &str = "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\n\
v 1 1 1\nf 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";

fn cube() -> TMesh {
    let mut positions = Vec::new();
    for i in 0..8 {
        positions.push([
            (i & 1) as f64 * 2.0 - 1.0,
            ((i >> 1) & 1) as f64 * 2.0 - 1.0,
            ((i >> 2) & 1) as f64 * 2.0 - 1.0,
        ]);
    }
    let faces = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    TMesh {
        positions,
        faces: faces.iter().map(|f| f.to_vec()).collect(),
    }
}

/// The library's tagged result.
fn library(m: &TMesh, s: Scheme, levels: usize, tags: &Tags<'_>) -> TMesh {
    library_with(m, Options::new(s).levels(levels), tags)
}

/// The library's tagged result with `opts`.
fn library_with(m: &TMesh, opts: Options, tags: &Tags<'_>) -> TMesh {
    let (offsets, indices) = m.csr();
    let mesh = CoreMesh::new(&m.positions, &offsets, &indices);
    let mut s0 = vec![0u32; scheme::plan_scratch_size_tagged(&mesh, tags).unwrap()];
    let plan = scheme::plan_tagged(mesh, &opts, tags, &mut s0).unwrap();
    let mut su = vec![0u32; plan.scratch.u32s];
    let mut sp = vec![[0.0; 3]; plan.scratch.points];
    let o = plan.output();
    let (mut pos, mut offs, mut idx) = (
        vec![[0.0; 3]; o.vertices],
        vec![0u32; o.faces + 1],
        vec![0u32; o.indices],
    );
    let mut out = MeshOut::new(&mut pos, &mut offs, &mut idx);
    scheme::subdivide_tagged(mesh, &opts, tags, Scratch::new(&mut su, &mut sp), &mut out).unwrap();
    TMesh::from_csr(pos, &offs, &idx)
}

#[test]
fn obj_tags_give_the_library_result() {
    let dir = TempDir::new("creases");
    let input = dir.path("cube.obj");
    let text = format!("{CUBE}t crease 5/4/0 4 5 7 6 4 10 1.5 2.25 0.5\nt corner 1/1/0 0 2.5\n");
    std::fs::write(&input, text).unwrap();
    let creases = [[4, 5], [5, 7], [7, 6], [6, 4]];
    let s = [10.0, 1.5, 2.25, 0.5];
    for (method, name) in [
        (CreaseMethod::Uniform, "uniform"),
        (CreaseMethod::Chaikin, "chaikin"),
    ] {
        let out = dir.path(&format!("out-{name}.off"));
        let o = run(&[
            "subdivide",
            "--scheme",
            "catmull-clark",
            "--levels",
            "3",
            "--crease-method",
            name,
            input.to_str().unwrap(),
            out.to_str().unwrap(),
        ]);
        assert_eq!(code(&o), 0, "{}", stderr(&o));
        let tags = Tags::new()
            .creases(&creases, &s)
            .corners(&[0], &[2.5])
            .method(method);
        let want = library(&cube(), Scheme::CatmullClark, 3, &tags);
        let got = read_off(&out);
        assert_eq!(got.bits(), want.bits(), "{name}");
        assert_eq!(got.faces, want.faces, "{name}");
    }
}

#[test]
fn crease_angle_tags_the_cube_edges() {
    // Every cube edge has a 90° dihedral angle: --crease-angle 60 tags all twelve, so every
    // old vertex is a corner (three sharp edges) and stays put.
    let dir = TempDir::new("crease-angle");
    let input = dir.path("cube.obj");
    std::fs::write(&input, CUBE).unwrap();
    let out = dir.path("out.off");
    let o = run(&[
        "subdivide",
        "--scheme",
        "catmull-clark",
        "--levels",
        "2",
        "--crease-angle",
        "60",
        input.to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let got = read_off(&out);
    let c = cube();
    for v in 0..8 {
        assert_eq!(got.positions[v], c.positions[v]);
    }
    // Above 90° nothing is tagged: the untagged result.
    let o = run(&[
        "subdivide",
        "--scheme",
        "catmull-clark",
        "--levels",
        "2",
        "--crease-angle",
        "120",
        input.to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let plain = library(&c, Scheme::CatmullClark, 2, &Tags::new());
    assert_eq!(read_off(&out).bits(), plain.bits());
}

#[test]
fn bad_tags_exit_2_naming_the_line() {
    let dir = TempDir::new("creases-bad");
    let out = dir.path("out.off");
    for (tag, args, needle) in [
        (
            "t crease 2/1/0 0 7 1",
            "catmull-clark",
            "cube.obj:15: crease tag 0 7",
        ),
        (
            "t crease 2/1/0 0 1 nan",
            "catmull-clark",
            "cube.obj:15: crease tag 0 1: the sharpness",
        ),
        (
            "t corner 1/1/0 9 1",
            "catmull-clark",
            "cube.obj:15: corner tag 9",
        ),
        (
            "t crease 2/1/0 0 1 1\nt crease 2/1/0 1 0 2",
            "catmull-clark",
            "cube.obj:16: crease tag 1 0: this edge",
        ),
        ("t crease 3/1/0 0 1 1", "catmull-clark", "cube.obj:15:"),
        ("t hole 1/0/0 1", "catmull-clark", "cube.obj:15: tag 'hole'"),
        (
            "t crease 2/1/0 0 1 1",
            "mobius-doo-sabin",
            "does not take them",
        ),
        (
            "t crease 2/1/0 0 7 1",
            "mobius-catmull-clark",
            "cube.obj:15: crease tag 0 7",
        ),
        ("t crease 2/1/0 0 1 1", "doo-sabin", "does not take them"),
    ] {
        let input = dir.path("cube.obj");
        std::fs::write(&input, format!("{CUBE}{tag}\n")).unwrap();
        let o = run(&[
            "subdivide",
            "--scheme",
            args,
            "--levels",
            "1",
            input.to_str().unwrap(),
            out.to_str().unwrap(),
        ]);
        assert_eq!(code(&o), 2, "{tag}: {}", stderr(&o));
        assert!(stderr(&o).contains(needle), "{tag}: {}", stderr(&o));
        assert!(!out.exists(), "{tag}: output written");
    }
}

/// An octahedron, slightly irregular so that no symmetry makes a tagged point coincide with
/// the untagged one.
const OCTA: &str = "v 1 0 0.1\nv -1 0.05 0\nv 0 1 0\nv 0.1 -1 0\nv 0 0.05 1\nv 0 0 -1\n\
f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";

fn octahedron() -> TMesh {
    TMesh {
        positions: vec![
            [1.0, 0.0, 0.1],
            [-1.0, 0.05, 0.0],
            [0.0, 1.0, 0.0],
            [0.1, -1.0, 0.0],
            [0.0, 0.05, 1.0],
            [0.0, 0.0, -1.0],
        ],
        faces: [
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ]
        .iter()
        .map(|f| f.to_vec())
        .collect(),
    }
}

#[test]
fn butterfly_takes_obj_creases_and_the_crease_angle() {
    let dir = TempDir::new("creases-butterfly");
    let input = dir.path("octa.obj");
    std::fs::write(
        &input,
        format!("{OCTA}t crease 5/4/0 0 2 1 3 0 10 1.5 10 0.5\n"),
    )
    .unwrap();
    let out = dir.path("out.off");
    let o = run(&[
        "subdivide",
        "--scheme",
        "butterfly",
        "--levels",
        "2",
        input.to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let creases = [[0, 2], [2, 1], [1, 3], [3, 0]];
    let s = [10.0, 1.5, 10.0, 0.5];
    let tags = Tags::new().creases(&creases, &s);
    let m = octahedron();
    let want = library(&m, Scheme::ModifiedButterfly, 2, &tags);
    let got = read_off(&out);
    assert_eq!(got.bits(), want.bits());
    assert_eq!(got.faces, want.faces);
    assert_ne!(
        got.bits(),
        library(&m, Scheme::ModifiedButterfly, 2, &Tags::new()).bits()
    );
    // The dihedral angles are near 109°: --crease-angle 60 tags all twelve edges, every
    // vertex is a corner, and each edge point is the 4-point rule with virtual end points:
    // the library's result with every edge tagged.
    std::fs::write(&input, OCTA).unwrap();
    let o = run(&[
        "subdivide",
        "--scheme",
        "butterfly",
        "--levels",
        "2",
        "--crease-angle",
        "60",
        input.to_str().unwrap(),
        out.to_str().unwrap(),
    ]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let mut all: Vec<[u32; 2]> = Vec::new();
    for f in &m.faces {
        for i in 0..3 {
            let (a, b) = (f[i], f[(i + 1) % 3]);
            if a < b {
                all.push([a, b]);
            }
        }
    }
    assert_eq!(all.len(), 12);
    let inf = vec![10.0; 12];
    let want = library(
        &m,
        Scheme::ModifiedButterfly,
        2,
        &Tags::new().creases(&all, &inf),
    );
    assert_eq!(read_off(&out).bits(), want.bits());
}

#[test]
fn mobius_schemes_take_obj_creases() {
    // A closed crease around the octahedron's equator, one edge semi-sharp: the Möbius
    // versions give the library's tagged Möbius result.
    let dir = TempDir::new("creases-mobius");
    let input = dir.path("octa.obj");
    std::fs::write(
        &input,
        format!("{OCTA}t crease 5/4/0 0 2 1 3 0 10 1.5 10 10\n"),
    )
    .unwrap();
    let out = dir.path("out.off");
    let creases = [[0, 2], [2, 1], [1, 3], [3, 0]];
    let sharpness = [10.0, 1.5, 10.0, 10.0];
    let tags = Tags::new().creases(&creases, &sharpness);
    let m = octahedron();
    for (name, s) in [
        ("mobius-loop", Scheme::Loop),
        ("mobius-butterfly", Scheme::ModifiedButterfly),
    ] {
        let o = run(&[
            "subdivide",
            "--scheme",
            name,
            "--levels",
            "2",
            input.to_str().unwrap(),
            out.to_str().unwrap(),
        ]);
        assert_eq!(code(&o), 0, "{name}: {}", stderr(&o));
        let opts = Options::new(s).mobius(true).levels(2);
        let want = library_with(&m, opts, &tags);
        let got = read_off(&out);
        assert_eq!(got.bits(), want.bits(), "{name}");
        assert_ne!(
            got.bits(),
            library_with(&m, opts, &Tags::new()).bits(),
            "{name}: the tags change nothing"
        );
    }
}

#[test]
fn obj_output_carries_the_last_levels_tags() {
    // The tags written with level 1 are the ones the kernel carries to level 2: one more
    // level from the written OBJ gives two levels from the input, bit for bit (linear and
    // Möbius, uniform and Chaikin decay, infinitely sharp and semi-sharp creases, a corner).
    let dir = TempDir::new("creases-out-tags");
    let input = dir.path("cube.obj");
    std::fs::write(
        &input,
        format!(
            "{CUBE}t crease 2/1/0 0 1 10\nt crease 2/1/0 1 3 1.5\nt crease 2/1/0 3 2 2.25\n\
             t crease 2/1/0 2 0 10\nt crease 2/1/0 4 5 0.75\nt corner 1/1/0 6 2.5\n"
        ),
    )
    .unwrap();
    for scheme in [
        "catmull-clark",
        "mobius-catmull-clark",
        "kobbelt",
        "mobius-kobbelt",
    ] {
        for method in ["uniform", "chaikin"] {
            let (one, two, again) = (
                dir.path("one.obj"),
                dir.path("two.off"),
                dir.path("again.off"),
            );
            let sub = |levels: &str, i: &std::path::Path, o: &std::path::Path| {
                let o = run(&[
                    "subdivide",
                    "--scheme",
                    scheme,
                    "--crease-method",
                    method,
                    "--levels",
                    levels,
                    i.to_str().unwrap(),
                    o.to_str().unwrap(),
                ]);
                assert_eq!(code(&o), 0, "{scheme} {method}: {}", stderr(&o));
            };
            sub("1", &input, &one);
            sub("2", &input, &two);
            sub("1", &one, &again);
            let text = std::fs::read_to_string(&one).unwrap();
            // The four loop edges have two children each; the 0.75 edge decays to nothing.
            let creases = text.lines().filter(|l| l.starts_with("t crease")).count();
            assert_eq!(creases, 8, "{scheme} {method}:\n{text}");
            assert!(text.contains("t corner 1/1/0 6 1.5"), "{scheme} {method}");
            assert_eq!(
                std::fs::read(&two).unwrap(),
                std::fs::read(&again).unwrap(),
                "{scheme} {method}"
            );
        }
    }
}
