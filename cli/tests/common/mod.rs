//! Shared support of the `nlsubdiv` integration tests: running the binary, temporary
//! folders, the shared test meshes, mesh generators and an independent OFF reader.
// Test code: indexing, unwrap and panics are the point here (clippy's in-test allowances do
// not reach helper functions outside #[test]).
#![allow(
    dead_code,
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The binary under test.
pub fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_nlsubdiv")
}

/// Runs `nlsubdiv ARGS…` (quiet progress: stderr is not a terminal anyway).
pub fn run<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Output {
    Command::new(bin())
        .args(args)
        .output()
        .expect("cannot run the nlsubdiv binary")
}

/// Exit status of an output (-1 when killed by a signal).
pub fn code(o: &Output) -> i32 {
    o.status.code().unwrap_or(-1)
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A fresh temporary folder, removed on drop.
pub struct TempDir(pub PathBuf);

impl TempDir {
    pub fn new(name: &str) -> TempDir {
        let p =
            std::env::temp_dir().join(format!("nlsubdiv-cli-test-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&p);
        std::fs::create_dir_all(&p).unwrap();
        TempDir(p)
    }

    pub fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }

    /// Names of the files in the folder, sorted.
    pub fn files(&self) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(&self.0)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

// Finding the shared meshes, and skipping visibly without them: the one file that every
// test crate of the workspace includes.
#[path = "../../../tests/common/shared_data.rs"]
mod shared_data;
#[allow(unused_imports)] // each test crate uses some of them
pub use shared_data::{shared_meshes, skip};

/// The `.off` files of a folder, sorted.
pub fn off_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "off"))
        .collect();
    v.sort();
    v
}

/// A mesh owned by the tests.
#[derive(Clone, Debug, PartialEq)]
pub struct TMesh {
    pub positions: Vec<[f64; 3]>,
    pub faces: Vec<Vec<u32>>,
}

impl TMesh {
    /// Bit patterns of all coordinates, for exact comparison (`-0.0 ≠ 0.0`).
    pub fn bits(&self) -> Vec<[u64; 3]> {
        self.positions.iter().map(|p| p.map(f64::to_bits)).collect()
    }

    /// OFF text with 17 significant digits in exponent form (not the writer's shortest
    /// format, so that a round trip through the command re-formats every number).
    pub fn to_off(&self) -> String {
        let mut s = format!("OFF\n{} {} 0\n", self.positions.len(), self.faces.len());
        for p in &self.positions {
            writeln!(s, "{:.16e} {:.16e} {:.16e}", p[0], p[1], p[2]).unwrap();
        }
        for f in &self.faces {
            write!(s, "{}", f.len()).unwrap();
            for i in f {
                write!(s, " {i}").unwrap();
            }
            s.push('\n');
        }
        s
    }

    pub fn write_off(&self, path: &Path) {
        std::fs::write(path, self.to_off()).unwrap();
    }
}

/// An OFF reader independent of the command's: whitespace tokens, `#` comments, no
/// colours. Enough for the shared meshes and the command's own output.
pub fn read_off(path: &Path) -> TMesh {
    let text = std::fs::read_to_string(path).unwrap();
    let mut toks = text
        .lines()
        .map(|l| l.split('#').next().unwrap())
        .flat_map(str::split_whitespace);
    let kw = toks.next().unwrap();
    assert!(kw.ends_with("OFF"), "{}: {kw}", path.display());
    let nv: usize = toks.next().unwrap().parse().unwrap();
    let nf: usize = toks.next().unwrap().parse().unwrap();
    let _ne: usize = toks.next().unwrap().parse().unwrap();
    let mut positions = Vec::with_capacity(nv);
    for _ in 0..nv {
        let mut p = [0.0; 3];
        for c in &mut p {
            *c = toks.next().unwrap().parse().unwrap();
        }
        positions.push(p);
    }
    let mut faces = Vec::with_capacity(nf);
    for _ in 0..nf {
        let n: usize = toks.next().unwrap().parse().unwrap();
        faces.push(
            (0..n)
                .map(|_| toks.next().unwrap().parse().unwrap())
                .collect(),
        );
    }
    assert!(toks.next().is_none(), "{}: trailing data", path.display());
    TMesh { positions, faces }
}

/// A deterministic pseudo-random generator (SplitMix64).
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}

/// A quad torus, `n × m` vertices, radii `r0 > r1`, counter-clockwise seen from outside.
pub fn torus(n: u32, m: u32, r0: f64, r1: f64) -> TMesh {
    let mut positions = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (u, v) = (
                std::f64::consts::TAU * i as f64 / n as f64,
                std::f64::consts::TAU * j as f64 / m as f64,
            );
            positions.push([
                (r0 + r1 * v.cos()) * u.cos(),
                (r0 + r1 * v.cos()) * u.sin(),
                r1 * v.sin(),
            ]);
        }
    }
    let id = |i: u32, j: u32| (i % n) * m + (j % m);
    let mut faces = Vec::new();
    for i in 0..n {
        for j in 0..m {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TMesh { positions, faces }
}

/// An open `n × m` grid of quads in the plane z = 0 (a disk: one boundary loop), with the
/// diagonal of every other quad split into two triangles (mixed faces).
pub fn open_grid(n: u32, m: u32) -> TMesh {
    let mut positions = Vec::new();
    for j in 0..=m {
        for i in 0..=n {
            positions.push([i as f64 * 0.25, j as f64 / 3.0, 0.0]);
        }
    }
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut faces = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                faces.push(vec![a, b, c, d]);
            } else {
                faces.push(vec![a, b, c]);
                faces.push(vec![a, c, d]);
            }
        }
    }
    TMesh { positions, faces }
}

/// The icosahedron subdivided `levels` times (1→4), every vertex projected to the unit
/// sphere.
pub fn icosphere(levels: u32) -> TMesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut positions: Vec<[f64; 3]> = vec![
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let mut faces: Vec<Vec<u32>> = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ]
    .iter()
    .map(|f| f.to_vec())
    .collect();
    for _ in 0..levels {
        let mut mid = std::collections::BTreeMap::new();
        let mut next = Vec::new();
        for f in &faces {
            let mut m = [0u32; 3];
            for k in 0..3 {
                let (a, b) = (f[k], f[(k + 1) % 3]);
                let key = (a.min(b), a.max(b));
                m[k] = *mid.entry(key).or_insert_with(|| {
                    let (p, q) = (positions[a as usize], positions[b as usize]);
                    positions.push([
                        0.5 * (p[0] + q[0]),
                        0.5 * (p[1] + q[1]),
                        0.5 * (p[2] + q[2]),
                    ]);
                    positions.len() as u32 - 1
                });
            }
            next.push(vec![f[0], m[0], m[2]]);
            next.push(vec![f[1], m[1], m[0]]);
            next.push(vec![f[2], m[2], m[1]]);
            next.push(vec![m[0], m[1], m[2]]);
        }
        faces = next;
    }
    for p in &mut positions {
        let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        *p = p.map(|x| x / l);
    }
    TMesh { positions, faces }
}

/// Coordinates that are hard to print and parse: signed zeros, subnormals, extremes,
/// values without a short decimal form.
pub fn nasty(mut m: TMesh, rng: &mut Rng) -> TMesh {
    let specials = [
        -0.0,
        5e-324,
        -2.2250738585072014e-308,
        1e300,
        -1.7976931348623157e308,
        0.1,
        1.0 / 3.0,
        -1.40201e-05,
        123_456_789.123_456_78,
        f64::EPSILON,
    ];
    for (i, p) in m.positions.iter_mut().enumerate() {
        if i < specials.len() {
            p[i % 3] = specials[i];
        } else {
            for c in p.iter_mut() {
                // Random low bits: every digit matters.
                *c = f64::from_bits(c.to_bits() ^ (rng.next_u64() & 0xfff));
            }
        }
    }
    m
}

/// Decodes an RGB PNG: width, height and the pixels, rows top to bottom.
pub fn decode_png(path: &std::path::Path) -> (u32, u32, Vec<u8>) {
    let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut r = dec.read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size().unwrap()];
    let info = r.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Variance of the luminance over the picture, and the share of pixels that differ from
/// the background's colour in their row.
pub fn picture_stats(w: u32, h: u32, rgb: &[u8]) -> (f64, f64) {
    let lum: Vec<f64> = rgb
        .chunks(3)
        .map(|c| 0.299 * c[0] as f64 + 0.587 * c[1] as f64 + 0.114 * c[2] as f64)
        .collect();
    let mean = lum.iter().sum::<f64>() / lum.len() as f64;
    let var = lum.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / lum.len() as f64;
    let mut covered = 0;
    for y in 0..h as usize {
        let row = &rgb[y * w as usize * 3..(y + 1) * w as usize * 3];
        let bg = &row[..3]; // the left edge is background
        covered += row
            .chunks(3)
            .filter(|c| c.iter().zip(bg).any(|(a, b)| a.abs_diff(*b) > 12))
            .count();
    }
    (var, covered as f64 / (w * h) as f64)
}

impl TMesh {
    /// The faces as CSR offsets and indices (the core's layout).
    pub fn csr(&self) -> (Vec<u32>, Vec<u32>) {
        let mut offsets = vec![0u32];
        let mut indices = Vec::new();
        for f in &self.faces {
            indices.extend_from_slice(f);
            offsets.push(indices.len() as u32);
        }
        (offsets, indices)
    }

    /// A mesh from positions and CSR faces.
    pub fn from_csr(positions: Vec<[f64; 3]>, offsets: &[u32], indices: &[u32]) -> TMesh {
        let faces = offsets
            .windows(2)
            .map(|w| indices[w[0] as usize..w[1] as usize].to_vec())
            .collect();
        TMesh { positions, faces }
    }
}

/// Points of a curve text file: `x y z` lines, `#` comments and blank lines skipped.
pub fn read_points(path: &Path) -> Vec<[f64; 3]> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| l.split('#').next().unwrap().trim())
        .filter(|l| !l.is_empty())
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            assert_eq!(v.len(), 3, "{l}");
            [v[0], v[1], v[2]]
        })
        .collect()
}

/// Asserts that `dir` holds exactly the files `expected` (no output, no temporary file).
pub fn assert_files(dir: &TempDir, expected: &[&str], what: &str) {
    let mut want: Vec<String> = expected.iter().map(|s| s.to_string()).collect();
    want.sort();
    assert_eq!(dir.files(), want, "{what}: files left in the folder");
}
