//! Shared test support: mesh generators, a tiny OFF reader, owned meshes and helpers.
// Test code: indexing and unwrap are fine here (clippy's in-test allowances do not reach
// helper functions outside #[test]).
#![allow(
    dead_code,
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

use nlsubdiv::mesh::{topology_scratch_size, Mesh, MeshOut, MeshSizes, Topology};
use nlsubdiv::scheme::{self, Options, Report, Scheme, Scratch};
use nlsubdiv::{Point, Result};
use std::path::{Path, PathBuf};

// Finding the shared meshes, and skipping visibly without them: one file for every test
// crate (the command's tests include it too).
#[path = "shared_data.rs"]
mod shared_data;
#[allow(unused_imports)] // each test crate uses some of them
pub use shared_data::{shared_meshes, shared_meshes_dir, shared_meshes_partly, skip};

/// A mesh owning its buffers.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OwnedMesh {
    pub positions: Vec<Point>,
    pub offsets: Vec<u32>,
    pub indices: Vec<u32>,
}

impl OwnedMesh {
    pub fn from_faces(positions: Vec<Point>, faces: &[Vec<u32>]) -> Self {
        let mut offsets = vec![0u32];
        let mut indices = Vec::new();
        for f in faces {
            indices.extend_from_slice(f);
            offsets.push(indices.len() as u32);
        }
        OwnedMesh {
            positions,
            offsets,
            indices,
        }
    }

    pub fn view(&self) -> Mesh<'_> {
        Mesh::new(&self.positions, &self.offsets, &self.indices)
    }

    pub fn faces(&self) -> Vec<Vec<u32>> {
        self.offsets
            .windows(2)
            .map(|w| self.indices[w[0] as usize..w[1] as usize].to_vec())
            .collect()
    }

    pub fn num_faces(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    pub fn map_positions(&self, mut f: impl FnMut(Point) -> Point) -> Self {
        OwnedMesh {
            positions: self.positions.iter().map(|&p| f(p)).collect(),
            ..self.clone()
        }
    }
}

/// Builds the topology (owning its scratch) and runs `f` on it.
pub fn with_topology<R>(m: &OwnedMesh, f: impl FnOnce(&Topology<'_, '_>) -> R) -> Result<R> {
    let mut scratch = vec![0u32; topology_scratch_size(m.positions.len(), m.indices.len())?];
    let topo = Topology::build(m.view(), &mut scratch)?;
    Ok(f(&topo))
}

pub fn validate(m: &OwnedMesh) -> Result<()> {
    with_topology(m, |_| ())
}

/// The public path with owned buffers: `plan` (in a scratch of `plan_scratch_size`
/// entries), then `subdivide` with buffers of exactly the planned sizes. The output starts as
/// NaN/`u32::MAX` so that an unwritten entry cannot pass unnoticed.
pub fn run(m: &OwnedMesh, opts: &Options) -> Result<(OwnedMesh, Report)> {
    run_with(m, opts, &nlsubdiv::exec::Serial)
}

/// Runs `subdivide` (one of the public entry points) on buffers of exactly the sizes `plan`
/// asked for: the plan's scratch `su` grown to its `u32` count, a point scratch and an output
/// starting as NaN/`u32::MAX`. Checks that the report's sizes are the planned ones.
fn run_planned(
    p: &scheme::Plan,
    mut su: Vec<u32>,
    subdivide: impl FnOnce(Scratch<'_>, &mut MeshOut<'_>) -> Result<Report>,
) -> Result<(OwnedMesh, Report)> {
    let o = p.output();
    su.resize(p.scratch.u32s, 0);
    let mut sp = vec![[0.0f64; 3]; p.scratch.points];
    let mut out = OwnedMesh {
        positions: vec![[f64::NAN; 3]; o.vertices],
        offsets: vec![u32::MAX; o.faces + 1],
        indices: vec![u32::MAX; o.indices],
    };
    let report = subdivide(
        Scratch::new(&mut su, &mut sp),
        &mut MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices),
    )?;
    assert_eq!(report.sizes, o, "sizes written differ from the plan");
    Ok((out, report))
}

/// [`run`] through [`scheme::subdivide_with`] with the executor `exec`.
pub fn run_with(
    m: &OwnedMesh,
    opts: &Options,
    exec: &dyn nlsubdiv::exec::Executor,
) -> Result<(OwnedMesh, Report)> {
    let mut su = vec![0u32; scheme::plan_scratch_size(&m.view())?];
    let p = scheme::plan(m.view(), opts, &mut su)?;
    assert!(
        p.scratch.u32s >= su.len(),
        "the plan's scratch is below its own"
    );
    run_planned(&p, su, |scratch, out| {
        scheme::subdivide_with(m.view(), opts, scratch, out, exec)
    })
}

/// The tagged public path (`plan_tagged`, then `subdivide_tagged`) with owned buffers of
/// exactly the planned sizes, the output starting as NaN/`u32::MAX` as in [`run`].
pub fn run_tagged(
    m: &OwnedMesh,
    opts: &Options,
    tags: &scheme::Tags<'_>,
) -> Result<(OwnedMesh, Report)> {
    let mut su = vec![0u32; scheme::plan_scratch_size_tagged(&m.view(), tags)?];
    let p = scheme::plan_tagged(m.view(), opts, tags, &mut su)?;
    run_planned(&p, su, |scratch, out| {
        scheme::subdivide_tagged(m.view(), opts, tags, scratch, out)
    })
}

/// The whole public path (`plan_weighted`, then `subdivide_weighted`) with tags, per-vertex
/// spectrum weights and an executor, owned buffers of exactly the planned sizes, the output
/// starting as NaN/`u32::MAX` as in [`run`].
pub fn run_weighted(
    m: &OwnedMesh,
    opts: &Options,
    tags: &scheme::Tags<'_>,
    weights: Option<scheme::VertexWeights<'_>>,
    exec: &dyn nlsubdiv::exec::Executor,
) -> Result<(OwnedMesh, Report)> {
    let mut su = vec![0u32; scheme::plan_scratch_size_tagged(&m.view(), tags)?];
    let p = scheme::plan_weighted(m.view(), opts, tags, weights, &mut su)?;
    run_planned(&p, su, |scratch, out| {
        scheme::subdivide_weighted(m.view(), opts, tags, weights, scratch, out, exec)
    })
}

/// One linear step of `s` ([`run`]).
pub fn subdivide(s: Scheme, m: &OwnedMesh) -> Result<OwnedMesh> {
    run(m, &Options::new(s)).map(|(o, _)| o)
}

pub fn subdivide_n(s: Scheme, m: &OwnedMesh, levels: usize) -> Result<OwnedMesh> {
    let mut cur = m.clone();
    for _ in 0..levels {
        cur = subdivide(s, &cur)?;
    }
    Ok(cur)
}

pub fn sizes_of(m: &OwnedMesh) -> MeshSizes {
    MeshSizes {
        vertices: m.positions.len(),
        faces: m.num_faces(),
        indices: m.indices.len(),
    }
}

/// FNV-1a over the bits of every output array.
pub fn hash(m: &OwnedMesh) -> u64 {
    let mut h = 0xcbf29ce484222325u64;
    let mut eat = |x: u64| {
        for b in x.to_le_bytes() {
            h ^= b as u64;
            h = h.wrapping_mul(0x100000001b3);
        }
    };
    for p in &m.positions {
        for c in p {
            eat(c.to_bits());
        }
    }
    for &o in &m.offsets {
        eat(o as u64);
    }
    for &i in &m.indices {
        eat(i as u64);
    }
    h
}

// ---------------------------------------------------------------- generators

pub fn tetrahedron() -> OwnedMesh {
    OwnedMesh::from_faces(
        vec![
            [1.0, 1.0, 1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
        ],
        &[vec![0, 1, 2], vec![0, 3, 1], vec![0, 2, 3], vec![1, 3, 2]],
    )
}

pub fn cube() -> OwnedMesh {
    let mut p = Vec::new();
    for i in 0..8 {
        p.push([
            (i & 1) as f64 * 2.0 - 1.0,
            ((i >> 1) & 1) as f64 * 2.0 - 1.0,
            ((i >> 2) & 1) as f64 * 2.0 - 1.0,
        ]);
    }
    OwnedMesh::from_faces(
        p,
        &[
            vec![0, 2, 3, 1],
            vec![4, 5, 7, 6],
            vec![0, 1, 5, 4],
            vec![2, 6, 7, 3],
            vec![0, 4, 6, 2],
            vec![1, 3, 7, 5],
        ],
    )
}

/// An `m × n` quad grid on the plane z = 0 with unit spacing (boundary).
pub fn quad_grid(m: usize, n: usize) -> OwnedMesh {
    let id = |i: usize, j: usize| (j * (m + 1) + i) as u32;
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=m {
            p.push([i as f64, j as f64, 0.0]);
        }
    }
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..m {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    OwnedMesh::from_faces(p, &faces)
}

/// An `m × n` quad grid split into triangles (interior valence 6).
pub fn tri_grid(m: usize, n: usize) -> OwnedMesh {
    let q = quad_grid(m, n);
    let mut faces = Vec::new();
    for f in q.faces() {
        faces.push(vec![f[0], f[1], f[2]]);
        faces.push(vec![f[0], f[2], f[3]]);
    }
    OwnedMesh::from_faces(q.positions, &faces)
}

/// A quad torus with `m × n` faces (all valence 4, closed).
pub fn quad_torus(m: usize, n: usize, big: f64, small: f64) -> OwnedMesh {
    let id = |i: usize, j: usize| ((j % n) * m + (i % m)) as u32;
    let mut p = Vec::new();
    for j in 0..n {
        for i in 0..m {
            let u = 2.0 * std::f64::consts::PI * i as f64 / m as f64;
            let v = 2.0 * std::f64::consts::PI * j as f64 / n as f64;
            let r = big + small * v.cos();
            p.push([r * u.cos(), r * u.sin(), small * v.sin()]);
        }
    }
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..m {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    OwnedMesh::from_faces(p, &faces)
}

pub fn tri_torus(m: usize, n: usize) -> OwnedMesh {
    let q = quad_torus(m, n, 3.0, 1.0);
    let mut faces = Vec::new();
    for f in q.faces() {
        faces.push(vec![f[0], f[1], f[2]]);
        faces.push(vec![f[0], f[2], f[3]]);
    }
    OwnedMesh::from_faces(q.positions, &faces)
}

/// A disk: centre 0 with `n` triangles around it (centre interior of valence n).
pub fn fan(n: usize) -> OwnedMesh {
    let mut p = vec![[0.0, 0.0, 0.0]];
    for i in 0..n {
        let t = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
        p.push([t.cos(), t.sin(), 0.1 * (3.0 * t).sin()]);
    }
    let faces: Vec<Vec<u32>> = (0..n)
        .map(|i| vec![0, 1 + i as u32, 1 + ((i + 1) % n) as u32])
        .collect();
    OwnedMesh::from_faces(p, &faces)
}

/// A closed bipyramid: poles 0 and 1 of valence n.
pub fn bipyramid(n: usize) -> OwnedMesh {
    let mut p = vec![[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
    for i in 0..n {
        let t = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
        p.push([t.cos(), t.sin(), 0.0]);
    }
    let r = |i: usize| 2 + (i % n) as u32;
    let mut faces = Vec::new();
    for i in 0..n {
        faces.push(vec![0, r(i), r(i + 1)]);
        faces.push(vec![1, r(i + 1), r(i)]);
    }
    OwnedMesh::from_faces(p, &faces)
}

/// A closed prism with n-gon caps (quads on the side).
pub fn prism(n: usize) -> OwnedMesh {
    let mut p = Vec::new();
    for k in 0..2 {
        for i in 0..n {
            let t = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
            p.push([t.cos(), t.sin(), k as f64]);
        }
    }
    let b = |i: usize| (i % n) as u32;
    let t = |i: usize| (n + i % n) as u32;
    let mut faces = vec![
        (0..n).rev().map(b).collect::<Vec<_>>(),
        (0..n).map(t).collect(),
    ];
    for i in 0..n {
        faces.push(vec![b(i), b(i + 1), t(i + 1), t(i)]);
    }
    OwnedMesh::from_faces(p, &faces)
}

/// Deterministic pseudo-random numbers in [-1, 1).
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

/// `m` with its vertices renumbered by a random permutation (Fisher–Yates on `Lcg(seed)`),
/// faces and positions moved with them: the same surface under other vertex ids.
pub fn renumbered(m: &OwnedMesh, seed: u64) -> OwnedMesh {
    let n = m.positions.len();
    let mut perm: Vec<usize> = (0..n).collect();
    let mut rng = Lcg(seed);
    for i in (1..n).rev() {
        let j = (((rng.next() + 1.0) / 2.0) * (i + 1) as f64) as usize;
        perm.swap(i, j.min(i));
    }
    let mut pos = vec![[0.0; 3]; n];
    for (old, &new) in perm.iter().enumerate() {
        pos[new] = m.positions[old];
    }
    let faces: Vec<Vec<u32>> = m
        .faces()
        .iter()
        .map(|f| f.iter().map(|&v| perm[v as usize] as u32).collect())
        .collect();
    OwnedMesh::from_faces(pos, &faces)
}

pub fn jitter(m: &OwnedMesh, amp: f64, seed: u64) -> OwnedMesh {
    let mut r = Lcg(seed);
    m.map_positions(|p| {
        [
            p[0] + amp * r.next(),
            p[1] + amp * r.next(),
            p[2] + amp * r.next(),
        ]
    })
}

// ---------------------------------------------------------------- OFF files

/// The `.off` files of a folder, sorted. The folder must exist: a test finds the shared
/// meshes with `shared_meshes` first, which reports a missing folder as a skip.
pub fn off_files(dir: &Path) -> Vec<PathBuf> {
    let rd = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    let mut v: Vec<PathBuf> = rd
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "off"))
        .collect();
    v.sort();
    v
}

/// A tiny OFF reader: `OFF`/`COFF` header (counts may follow on the same line), `#`
/// comments, extra tokens after a vertex's 3 coordinates or a face's indices (colours),
/// faces wrapped over several lines. Negative indices wrap to large `u32` (so that the kernel
/// sees them as out of range, as a C host casting them would).
pub fn read_off(path: &Path) -> std::result::Result<OwnedMesh, String> {
    let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
    // Tokens with their line numbers.
    let mut toks: Vec<(usize, &str)> = Vec::new();
    for (ln, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("");
        for t in line.split_whitespace() {
            toks.push((ln, t));
        }
    }
    let mut it = toks.into_iter().peekable();
    let head = it.next().ok_or("empty file")?.1;
    if !head.ends_with("OFF") {
        return Err(format!("bad header {head}"));
    }
    let mut num = || -> std::result::Result<(usize, &str), String> {
        it.next()
            .ok_or_else(|| "unexpected end of file".to_string())
    };
    let nv: usize = num()?.1.parse().map_err(|e| format!("{e}"))?;
    let nf: usize = num()?.1.parse().map_err(|e| format!("{e}"))?;
    let _ne = num()?;
    let mut positions = Vec::with_capacity(nv);
    // Re-collect the remaining tokens so that we can skip the rest of a line.
    let rest: Vec<(usize, &str)> = std::iter::from_fn(|| num().ok()).collect();
    let mut k = 0usize;
    let tok = |k: &mut usize| -> std::result::Result<(usize, &str), String> {
        let t = rest.get(*k).copied().ok_or("unexpected end of file")?;
        *k += 1;
        Ok(t)
    };
    for _ in 0..nv {
        let (l0, x) = tok(&mut k)?;
        let (_, y) = tok(&mut k)?;
        let (_, z) = tok(&mut k)?;
        let p = |s: &str| s.parse::<f64>().map_err(|e| format!("{s}: {e}"));
        positions.push([p(x)?, p(y)?, p(z)?]);
        while rest.get(k).is_some_and(|t| t.0 == l0) {
            k += 1;
        }
    }
    let mut offsets = vec![0u32];
    let mut indices = Vec::new();
    for _ in 0..nf {
        let (_, n) = tok(&mut k)?;
        let n: usize = n.parse().map_err(|e| format!("{e}"))?;
        let mut line = 0;
        for _ in 0..n {
            let (l, s) = tok(&mut k)?;
            let i: i64 = s.parse().map_err(|e| format!("{s}: {e}"))?;
            indices.push(i as u32);
            line = l;
        }
        while rest.get(k).is_some_and(|t| t.0 == line) {
            k += 1;
        }
        offsets.push(indices.len() as u32);
    }
    Ok(OwnedMesh {
        positions,
        offsets,
        indices,
    })
}

/// Writes an ASCII OFF file (positions with Rust's shortest round-trip formatting).
pub fn write_off(path: &Path, m: &OwnedMesh) -> std::io::Result<()> {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = writeln!(s, "OFF\n{} {} 0", m.positions.len(), m.num_faces());
    for p in &m.positions {
        let _ = writeln!(s, "{:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    for f in m.faces() {
        let _ = write!(s, "{}", f.len());
        for i in f {
            let _ = write!(s, " {i}");
        }
        s.push('\n');
    }
    std::fs::write(path, s)
}

/// An octahedron (all vertices valence 4), symmetric under every coordinate reflection.
pub fn octahedron() -> OwnedMesh {
    OwnedMesh::from_faces(
        vec![
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ],
        &[
            vec![0, 2, 4],
            vec![2, 1, 4],
            vec![1, 3, 4],
            vec![3, 0, 4],
            vec![2, 0, 5],
            vec![1, 2, 5],
            vec![3, 1, 5],
            vec![0, 3, 5],
        ],
    )
}

/// The regular icosahedron on the unit sphere (all vertices valence 5), faces oriented
/// outwards: the vertices are the cyclic permutations of (0, ±1, ±φ), scaled.
pub fn icosahedron() -> OwnedMesh {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let s = 1.0 / (1.0 + phi * phi).sqrt();
    let (a, b) = (s, phi * s);
    OwnedMesh::from_faces(
        vec![
            [-a, b, 0.0],
            [a, b, 0.0],
            [-a, -b, 0.0],
            [a, -b, 0.0],
            [0.0, -a, b],
            [0.0, a, b],
            [0.0, -a, -b],
            [0.0, a, -b],
            [b, 0.0, -a],
            [b, 0.0, a],
            [-b, 0.0, -a],
            [-b, 0.0, a],
        ],
        &[
            vec![0, 11, 5],
            vec![0, 5, 1],
            vec![0, 1, 7],
            vec![0, 7, 10],
            vec![0, 10, 11],
            vec![1, 5, 9],
            vec![5, 11, 4],
            vec![11, 10, 2],
            vec![10, 7, 6],
            vec![7, 1, 8],
            vec![3, 9, 4],
            vec![3, 4, 2],
            vec![3, 2, 6],
            vec![3, 6, 8],
            vec![3, 8, 9],
            vec![4, 9, 5],
            vec![2, 4, 11],
            vec![6, 2, 10],
            vec![8, 6, 7],
            vec![9, 8, 1],
        ],
    )
}

// ---------------------------------------------------------------- Möbius steps and measures

/// One canonical Möbius step (seed 000 §4) of `s` ([`run`]).
pub fn mobius_subdivide(s: Scheme, m: &OwnedMesh, strict: bool) -> Result<(OwnedMesh, Report)> {
    run(m, &Options::new(s).mobius(true).strict(strict))
}

/// The longest edge of any face.
pub fn max_edge(m: &OwnedMesh) -> f64 {
    let mut best: f64 = 0.0;
    for f in m.faces() {
        for i in 0..f.len() {
            let (a, b) = (
                m.positions[f[i] as usize],
                m.positions[f[(i + 1) % f.len()] as usize],
            );
            let d = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
            best = best.max(d);
        }
    }
    best
}

/// The mean discrete Willmore energy (seed 000 §3.3) over interior vertices with at least
/// four neighbours.
pub fn mean_willmore(m: &OwnedMesh) -> f64 {
    with_topology(m, |t| {
        let (mut sum, mut n) = (0.0, 0usize);
        for v in 0..t.num_vertices() as u32 {
            if t.is_isolated(v).unwrap() || t.is_boundary_vertex(v).unwrap() {
                continue;
            }
            let ring: Vec<Point> = t
                .ring(v)
                .unwrap()
                .iter()
                .map(|&u| t.position(u).unwrap())
                .collect();
            if ring.len() >= 4 {
                sum += nlsubdiv::metrics::willmore_energy(t.position(v).unwrap(), &ring, true)
                    .unwrap();
                n += 1;
            }
        }
        sum / n.max(1) as f64
    })
    .unwrap()
}

// ---------------------------------------------------------------- differential space

/// Differential-space subdivision with owned buffers (plan, then run).
pub fn differential_subdivide(
    m: &OwnedMesh,
    opts: &nlsubdiv::differential::DifferentialOptions<'_>,
) -> std::result::Result<
    (OwnedMesh, nlsubdiv::differential::DifferentialReport),
    (nlsubdiv::Error, nlsubdiv::differential::DifferentialReport),
> {
    differential_subdivide_with(m, opts, None)
}

/// [`differential_subdivide`] through `subdivide_with(exec)` when `exec` is given.
pub fn differential_subdivide_with(
    m: &OwnedMesh,
    opts: &nlsubdiv::differential::DifferentialOptions<'_>,
    exec: Option<&dyn nlsubdiv::exec::Executor>,
) -> std::result::Result<
    (OwnedMesh, nlsubdiv::differential::DifferentialReport),
    (nlsubdiv::Error, nlsubdiv::differential::DifferentialReport),
> {
    use nlsubdiv::differential as d;
    let mut rep = d::DifferentialReport::default();
    let mut ps = vec![0u32; d::plan_scratch_size(&m.view()).map_err(|e| (e, rep))?];
    let plan = d::plan(m.view(), opts, &mut ps).map_err(|e| (e, rep))?;
    let o = plan.output();
    let mut su = vec![0u32; plan.scratch_u32];
    let mut sp = vec![[0.0; 3]; plan.scratch_points];
    let mut pos = vec![[0.0; 3]; o.vertices];
    let mut offs = vec![0u32; o.faces + 1];
    let mut idx = vec![0u32; o.indices];
    let mut out = nlsubdiv::mesh::MeshOut::new(&mut pos, &mut offs, &mut idx);
    let r = match exec {
        Some(e) => d::subdivide_with(m.view(), opts, &mut su, &mut sp, &mut out, &mut rep, e),
        None => d::subdivide(m.view(), opts, &mut su, &mut sp, &mut out, &mut rep),
    };
    match r {
        Ok(_) => Ok((
            OwnedMesh {
                positions: pos,
                offsets: offs,
                indices: idx,
            },
            rep,
        )),
        Err(e) => Err((e, rep)),
    }
}

/// `levels` steps in one call, linear or Möbius, as a host makes it ([`run`]: `plan`, then
/// `subdivide` with buffers of the planned sizes): the benchmarks time this.
pub fn levels_call(s: Scheme, m: &OwnedMesh, levels: usize, mobius: bool) -> OwnedMesh {
    run(m, &Options::new(s).mobius(mobius).levels(levels))
        .unwrap()
        .0
}

/// The benchmark rows of the Möbius speed target (issue 5, DESIGN.md "Performance"): mesh
/// file in `../shared/data/meshes`, scheme, levels. `benches/mesh.rs` times them all;
/// `benches/blend_floor.rs` the Loop, Butterfly and Catmull–Clark ones, whose blends it counts.
pub const MOBIUS_BENCH_ROWS: [(&str, Scheme, usize); 6] = [
    ("epcot.off", Scheme::Loop, 4),
    ("epcot.off", Scheme::ModifiedButterfly, 4),
    ("cube.off", Scheme::CatmullClark, 8),
    ("spot_quad.off", Scheme::CatmullClark, 3),
    ("cube.off", Scheme::DooSabin, 8),
    ("spot_quad.off", Scheme::Kobbelt, 3),
];
