//! Sharp-feature tags (creases, corners, darts; Uniform and Chaikin) on linear Loop and
//! Catmull–Clark: equal to OpenSubdiv 3.5 (`peers/peer_osd_tags.cpp`, built here with g++ and
//! run on every case; skipped visibly when g++ or libosd-dev is missing), the tag validation
//! statuses, and untagged behaviour unchanged.

// Test helpers outside #[test] functions: clippy's in-test allowances do not reach them.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]

mod common;

use common::{cube, icosahedron, jitter, octahedron, prism, quad_grid, skip, tri_grid, OwnedMesh};
use nlsubdiv::scheme::{self, CreaseMethod, Options, Scheme, Tags};
use nlsubdiv::{Result, Status};
use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::sync::OnceLock;

/// The public tagged path ([`common::run_tagged`]), its output.
fn run_tagged(m: &OwnedMesh, opts: &Options, tags: &Tags<'_>) -> Result<OwnedMesh> {
    common::run_tagged(m, opts, tags).map(|(o, _)| o)
}

/// The OpenSubdiv runner, compiled once per test binary; `None` (reported as a skip) when
/// g++ or the OpenSubdiv headers are missing.
fn osd_runner() -> Option<&'static PathBuf> {
    static RUNNER: OnceLock<Option<PathBuf>> = OnceLock::new();
    RUNNER
        .get_or_init(|| {
            if !std::path::Path::new("/usr/include/opensubdiv/far/topologyRefinerFactory.h")
                .exists()
            {
                return None;
            }
            let src = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("peers/peer_osd_tags.cpp");
            let exe = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("peer_osd_tags");
            let st = Command::new(std::env::var("CXX").unwrap_or_else(|_| "g++".into()))
                .args(["-std=c++17", "-O1", "-ffp-contract=off"])
                .arg(&src)
                .arg("-o")
                .arg(&exe)
                .arg("-losdCPU")
                .status();
            match st {
                Ok(s) if s.success() => Some(exe),
                Ok(s) => panic!("building {} failed: {s}", src.display()),
                Err(_) => None,
            }
        })
        .as_ref()
}

struct Case {
    name: &'static str,
    scheme: Scheme,
    mesh: OwnedMesh,
    levels: usize,
    method: CreaseMethod,
    creases: Vec<[u32; 2]>,
    sharpness: Vec<f64>,
    corners: Vec<u32>,
    corner_sharpness: Vec<f64>,
}

impl Case {
    fn tags(&self) -> Tags<'_> {
        Tags::new()
            .creases(&self.creases, &self.sharpness)
            .corners(&self.corners, &self.corner_sharpness)
            .method(self.method)
    }

    /// OpenSubdiv's last level: its vertex count, face count and positions.
    fn osd(&self, exe: &PathBuf) -> (usize, usize, Vec<[f64; 3]>) {
        let mut input = String::new();
        let scheme = if self.scheme == Scheme::Loop {
            "loop"
        } else {
            "catmark"
        };
        let method = match self.method {
            CreaseMethod::Uniform => "uniform",
            _ => "chaikin",
        };
        input += &format!("scheme {scheme}\nlevels {}\nmethod {method}\n", self.levels);
        for p in &self.mesh.positions {
            input += &format!("v {:e} {:e} {:e}\n", p[0], p[1], p[2]);
        }
        for f in self.mesh.faces() {
            let idx: Vec<String> = f.iter().map(|i| i.to_string()).collect();
            input += &format!("f {} {}\n", f.len(), idx.join(" "));
        }
        for (c, s) in self.creases.iter().zip(&self.sharpness) {
            input += &format!("crease {} {} {s:e}\n", c[0], c[1]);
        }
        for (c, s) in self.corners.iter().zip(&self.corner_sharpness) {
            input += &format!("corner {c} {s:e}\n");
        }
        let mut child = Command::new(exe)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("run peer_osd_tags");
        child
            .stdin
            .take()
            .unwrap()
            .write_all(input.as_bytes())
            .unwrap();
        let out = child.wait_with_output().unwrap();
        assert!(
            out.status.success(),
            "{}: {}",
            self.name,
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8(out.stdout).unwrap();
        let mut lines = text.lines();
        let head: Vec<usize> = lines
            .next()
            .unwrap()
            .split_whitespace()
            .map(|t| t.parse().unwrap())
            .collect();
        let pts = lines
            .map(|l| {
                let v: Vec<f64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
                [v[0], v[1], v[2]]
            })
            .collect();
        (head[0], head[1], pts)
    }
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The largest distance from a point of `a` to its nearest point of `b`.
fn one_way(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .map(|&p| b.iter().map(|&q| dist(p, q)).fold(f64::INFINITY, f64::min))
        .fold(0.0, f64::max)
}

fn diag(p: &[[f64; 3]]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for q in p {
        for c in 0..3 {
            lo[c] = lo[c].min(q[c]);
            hi[c] = hi[c].max(q[c]);
        }
    }
    dist(lo, hi)
}

/// Vertex `(i, j)` of `quad_grid(m, _)`.
fn g(m: usize, i: usize, j: usize) -> u32 {
    (j * (m + 1) + i) as u32
}

fn cases() -> Vec<Case> {
    let base = |name, scheme, mesh, levels, method| Case {
        name,
        scheme,
        mesh,
        levels,
        method,
        creases: vec![],
        sharpness: vec![],
        corners: vec![],
        corner_sharpness: vec![],
    };
    let cube = jitter(&cube(), 0.05, 7);
    // The cube's vertices: bit 0 → x, bit 1 → y, bit 2 → z (tests/common).
    let top = vec![[4, 5], [5, 7], [7, 6], [6, 4]];
    let mut out = Vec::new();

    let mut c = base(
        "cube: infinitely sharp top loop",
        Scheme::CatmullClark,
        cube.clone(),
        2,
        CreaseMethod::Uniform,
    );
    c.creases = top.clone();
    c.sharpness = vec![10.0; 4];
    out.push(c);

    let mut c = base(
        "cube: semi-sharp loop 1.5, 2.25, 0.75, 3 (uniform)",
        Scheme::CatmullClark,
        cube.clone(),
        3,
        CreaseMethod::Uniform,
    );
    c.creases = top.clone();
    c.sharpness = vec![1.5, 2.25, 0.75, 3.0];
    out.push(c);

    let mut c = base(
        "cube: the same loop, Chaikin",
        Scheme::CatmullClark,
        cube.clone(),
        3,
        CreaseMethod::Chaikin,
    );
    c.creases = top.clone();
    c.sharpness = vec![1.5, 2.25, 0.75, 3.0];
    out.push(c);

    let mut c = base(
        "cube: corners 10 and 1.25, a dart edge 0.5",
        Scheme::CatmullClark,
        cube.clone(),
        2,
        CreaseMethod::Uniform,
    );
    c.corners = vec![0, 3];
    c.corner_sharpness = vec![10.0, 1.25];
    c.creases = vec![[1, 5]];
    c.sharpness = vec![0.5];
    out.push(c);

    let mut c = base(
        "cube: infinitely sharp dart and a three-edge corner",
        Scheme::CatmullClark,
        cube.clone(),
        2,
        CreaseMethod::Uniform,
    );
    c.creases = vec![[0, 1], [2, 6], [6, 7], [6, 4]];
    c.sharpness = vec![10.0, 2.5, 10.0, 1.75];
    out.push(c);

    // A grid with a crease across it, meeting the boundary at both ends (corners there).
    let m = 4;
    let grid = jitter(&quad_grid(m, m), 0.03, 3);
    let line: Vec<[u32; 2]> = (0..m).map(|i| [g(m, i, 2), g(m, i + 1, 2)]).collect();
    let mut c = base(
        "grid: crease to the boundary, varying sharpness, Chaikin",
        Scheme::CatmullClark,
        grid.clone(),
        3,
        CreaseMethod::Chaikin,
    );
    c.creases = line.clone();
    c.sharpness = vec![1.25, 2.5, 0.5, 3.0];
    out.push(c);

    let mut c = base(
        "grid: the same crease, uniform, interior corner",
        Scheme::CatmullClark,
        grid,
        2,
        CreaseMethod::Uniform,
    );
    c.creases = line.clone();
    c.sharpness = vec![1.25, 2.5, 0.5, 10.0];
    c.corners = vec![g(m, 2, 1)];
    c.corner_sharpness = vec![0.75];
    out.push(c);

    let mut c = base(
        "grid: sharpness 1.3, 0.7, 2.1, 0.1 (rounded to single precision, as OpenSubdiv)",
        Scheme::CatmullClark,
        jitter(&quad_grid(m, m), 0.03, 4),
        3,
        CreaseMethod::Chaikin,
    );
    c.creases = line.clone();
    c.sharpness = vec![1.3, 0.7, 2.1, 0.1];
    out.push(c);

    let tg = jitter(&tri_grid(m, m), 0.03, 5);
    let mut c = base(
        "Loop triangle grid: infinitely sharp crease to the boundary, corner",
        Scheme::Loop,
        tg.clone(),
        2,
        CreaseMethod::Uniform,
    );
    c.creases = line.clone();
    c.sharpness = vec![10.0; 4];
    c.corners = vec![g(m, 1, 3)];
    c.corner_sharpness = vec![10.0];
    out.push(c);

    let mut c = base(
        "Loop triangle grid: semi-sharp crease, Chaikin",
        Scheme::Loop,
        tg,
        3,
        CreaseMethod::Chaikin,
    );
    c.creases = line;
    c.sharpness = vec![0.25, 1.5, 2.75, 1.0];
    out.push(c);

    let ico = jitter(&icosahedron(), 0.02, 11);
    let mut c = base(
        "Loop icosahedron: fractional crease path and a dart",
        Scheme::Loop,
        ico.clone(),
        3,
        CreaseMethod::Uniform,
    );
    let f = ico.faces();
    // Two edges of face 0 (a path) and the first edge of a later face touching neither.
    let path = [[f[0][0], f[0][1]], [f[0][1], f[0][2]]];
    let far = f
        .iter()
        .find(|g| !g.iter().any(|v| f[0].contains(v)))
        .expect("a face away from face 0");
    c.creases = vec![path[0], path[1], [far[0], far[1]]];
    c.sharpness = vec![1.5, 0.5, 10.0];
    out.push(c);

    let oct = jitter(&octahedron(), 0.02, 13);
    let mut c = base(
        "Loop octahedron: equator crease 2.5, corner 3.5, Chaikin",
        Scheme::Loop,
        oct.clone(),
        2,
        CreaseMethod::Chaikin,
    );
    let eq = equator(&oct);
    c.sharpness = vec![2.5; eq.len()];
    c.creases = eq;
    c.corners = vec![oct.faces()[0][0]];
    c.corner_sharpness = vec![3.5];
    out.push(c);

    let pr = jitter(&prism(5), 0.02, 17);
    let mut c = base(
        "Catmull–Clark pentagonal prism: cap rim crease 1.5 (n-gon faces)",
        Scheme::CatmullClark,
        pr.clone(),
        2,
        CreaseMethod::Uniform,
    );
    c.creases = (0..5u32).map(|i| [i, (i + 1) % 5]).collect();
    c.sharpness = vec![1.5; 5];
    out.push(c);
    out
}

/// The edges of `m` whose endpoints are both at |z| below 0.5 (an octahedron's equator).
fn equator(m: &OwnedMesh) -> Vec<[u32; 2]> {
    let mut e = Vec::new();
    for f in m.faces() {
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            if a < b
                && m.positions[a as usize][2].abs() < 0.5
                && m.positions[b as usize][2].abs() < 0.5
            {
                e.push([a, b]);
            }
        }
    }
    e
}

#[test]
fn tagged_loop_and_catmull_clark_equal_opensubdiv() {
    let Some(exe) = osd_runner() else {
        skip(
            "mesh_creases::tagged_loop_and_catmull_clark_equal_opensubdiv",
            "g++ or libosd-dev (OpenSubdiv headers) not installed: tagged meshes not compared",
        );
        return;
    };
    let all = cases();
    assert!(all.len() >= 8);
    for c in &all {
        let ours = run_tagged(&c.mesh, &Options::new(c.scheme).levels(c.levels), &c.tags())
            .unwrap_or_else(|e| panic!("{}: {e}", c.name));
        let (nv, nf, theirs) = c.osd(exe);
        assert_eq!(ours.positions.len(), nv, "{}: vertex count", c.name);
        assert_eq!(ours.num_faces(), nf, "{}: face count", c.name);
        let scale = diag(&theirs);
        let d = one_way(&ours.positions, &theirs).max(one_way(&theirs, &ours.positions));
        assert!(
            d <= 1e-10 * scale,
            "{}: differs from OpenSubdiv by {d:e}",
            c.name
        );
        // The tags change the result: the comparison would catch tags that are ignored.
        let plain = run_tagged(
            &c.mesh,
            &Options::new(c.scheme).levels(c.levels),
            &Tags::new(),
        )
        .unwrap();
        assert!(
            one_way(&ours.positions, &plain.positions) > 1e-6 * scale,
            "{}: tags had no effect",
            c.name
        );
    }
}

#[test]
fn zero_sharpness_is_untagged_bit_for_bit() {
    for (s, m) in [
        (Scheme::CatmullClark, jitter(&cube(), 0.05, 1)),
        (Scheme::CatmullClark, jitter(&quad_grid(3, 2), 0.05, 2)),
        (Scheme::Loop, jitter(&tri_grid(3, 3), 0.05, 3)),
        (Scheme::Loop, jitter(&icosahedron(), 0.05, 4)),
    ] {
        let f = m.faces();
        let creases = [[f[0][0], f[0][1]]];
        let tags = Tags::new().creases(&creases, &[0.0]);
        let opts = Options::new(s).levels(2);
        let tagged = run_tagged(&m, &opts, &tags).unwrap();
        let (plain, _) = common::run(&m, &opts).unwrap();
        assert_eq!(tagged, plain, "{s:?}");
    }
}

#[test]
fn infinitely_sharp_crease_is_the_cubic_bspline_of_its_polygon() {
    // An infinitely sharp closed crease is subdivided as a closed cubic B-spline curve:
    // old vertices 3/4 v + 1/8 (neighbours), edge points midpoints (both exact).
    let m = jitter(&cube(), 0.05, 9);
    let top = [[4u32, 5], [5, 7], [7, 6], [6, 4]];
    let tags = Tags::new().creases(&top, &[10.0; 4]);
    let out = run_tagged(&m, &Options::new(Scheme::CatmullClark), &tags).unwrap();
    let ring = [4usize, 5, 7, 6];
    for k in 0..4 {
        let (a, v, b) = (ring[(k + 3) % 4], ring[k], ring[(k + 1) % 4]);
        let p = &m.positions;
        let want: [f64; 3] = std::array::from_fn(|c| 0.75 * p[v][c] + 0.125 * (p[a][c] + p[b][c]));
        assert!(dist(out.positions[v], want) < 1e-15, "vertex {v}");
        // The edge point of (v, b) is its midpoint.
        let mid: [f64; 3] = std::array::from_fn(|c| 0.5 * (p[v][c] + p[b][c]));
        assert!(one_way(&[mid], &out.positions) < 1e-15, "edge {v}-{b}");
    }
}

#[test]
fn bad_tags_have_specific_statuses() {
    let m = cube();
    let opts = Options::new(Scheme::CatmullClark).levels(2);
    let err = |creases: &[[u32; 2]], s: &[f64], corners: &[u32], cs: &[f64]| {
        let tags = Tags::new().creases(creases, s).corners(corners, cs);
        run_tagged(&m, &opts, &tags).unwrap_err()
    };
    let e = err(&[[0, 1], [0, 7]], &[1.0, 1.0], &[], &[]);
    assert_eq!((e.status, e.element), (Status::TagNotAnEdge, 1));
    let e = err(&[[2, 2]], &[1.0], &[], &[]);
    assert_eq!((e.status, e.element), (Status::TagNotAnEdge, 0));
    let e = err(&[[0, 1], [1, 0]], &[1.0, 2.0], &[], &[]);
    assert_eq!((e.status, e.element), (Status::RepeatedTag, 1));
    for bad in [f64::NAN, -0.5, f64::INFINITY] {
        let e = err(&[[0, 1]], &[bad], &[], &[]);
        assert_eq!(
            (e.status, e.element),
            (Status::InvalidSharpness, 0),
            "{bad}"
        );
        let e = err(&[[0, 1]], &[1.0], &[3], &[bad]);
        assert_eq!(
            (e.status, e.element),
            (Status::InvalidSharpness, 1),
            "{bad}"
        );
    }
    let e = err(&[[0, 8]], &[1.0], &[], &[]);
    assert_eq!((e.status, e.element), (Status::IndexOutOfRange, 0));
    let e = err(&[[0, 1]], &[1.0], &[2, 99], &[1.0, 1.0]);
    assert_eq!((e.status, e.element), (Status::IndexOutOfRange, 2));
    let e = err(&[], &[], &[4, 4], &[1.0, 2.0]);
    assert_eq!((e.status, e.element), (Status::RepeatedTag, 1));
    let e = err(&[[0, 1]], &[], &[], &[]);
    assert_eq!(e.status, Status::InvalidArgument);
    // Schemes without tag rules say so (linear or Möbius).
    let creases = [[0u32, 1]];
    let tags = Tags::new().creases(&creases, &[1.0]);
    for opts in [
        Options::new(Scheme::DooSabin).mobius(true),
        Options::new(Scheme::Spherelike),
        Options::new(Scheme::DooSabin),
    ] {
        assert_eq!(
            run_tagged(&m, &opts, &tags).unwrap_err().status,
            Status::TagsNotSupported
        );
    }
    // A scratch below the tagged plan's need is reported with the size.
    let need = scheme::plan_scratch_size_tagged(&m.view(), &tags).unwrap();
    let mut su = vec![0u32; need - 1];
    let e = scheme::plan_tagged(m.view(), &opts, &tags, &mut su).unwrap_err();
    assert_eq!((e.status, e.needed), (Status::BufferTooSmall, need));
}

#[test]
fn zero_levels_validate_tags_and_copy() {
    let m = cube();
    let creases = [[0u32, 1]];
    let tags = Tags::new().creases(&creases, &[2.0]);
    let out = run_tagged(&m, &Options::new(Scheme::CatmullClark).levels(0), &tags).unwrap();
    assert_eq!(out, m);
    // No sharpness buffers for zero levels: the scratch is the plan's own.
    let mut su = vec![0u32; scheme::plan_scratch_size_tagged(&m.view(), &tags).unwrap()];
    let opts = Options::new(Scheme::CatmullClark).levels(0);
    let p = scheme::plan_tagged(m.view(), &opts, &tags, &mut su).unwrap();
    assert_eq!(p.scratch.u32s, su.len());
    let bad = Tags::new().creases(&[[0, 7]], &[2.0]);
    assert!(run_tagged(&m, &Options::new(Scheme::CatmullClark).levels(0), &bad).is_err());
}
