//! Seed 001 §3.3, Fig. 4: convergence of the reconstructed surfaces. With
//! `h_i = d_H(M̃_i, M̃_{i−1})` the Hausdorff distance between the results at `i` and `i − 1`
//! levels (each its own reconstruction: the method solves once, at the last level), the paper
//! plots `i^1.5 h_i` around vertices of valence 3 to 12 and finds it decreasing monotonically
//! to zero.
//!
//! Measured here, for differential Loop (the stencil of the paper's Table 1), differential
//! Modified Butterfly and, for reference, spatial Loop:
//!
//! * **local cages**, one per valence `d = 3 … 12`: a disk of four rings around a centre of
//!   valence `d` (a planar fan of `d` triangles refined twice by Loop: every other interior
//!   vertex has valence 6), lifted onto the quadric `z = 0.4x² + 0.2y² + 0.1xy`; `h_i` over
//!   the centre's control 1-ring (output vertices at most `2^i` edges from the centre), levels
//!   1–5;
//! * **shared meshes** (whole surface): epcot to level 4, pawn_tri to level 3; with the
//!   argument `full` also fertility and rocker_arm to level 3.
//!
//! `h_i` is the vertex-sampled symmetric Hausdorff distance (every vertex of each mesh to the
//! other surface, exact point–triangle distances), over the bounding-box diagonal of the
//! control mesh. `i^1.5 h_i` decreases from `i` to `i + 1` exactly when the contraction ratio
//! `h_{i+1}/h_i` is below `(i/(i+1))^1.5` (0.354, 0.544, 0.650, 0.716 for `i` = 1 … 4); the
//! tables give the ratios and that bound.
//!
//! `cargo run --release --example differential_fig4 [MESH_DIR] [full]` (default: about a
//! minute on a loaded 2-core machine). The cheap check of the statement these tables support
//! is `examples/differential_fig4_check.rs` (docs/differential.md, "Convergence of the levels").
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    dead_code
)]

#[path = "../tests/common/mod.rs"]
mod common;
#[path = "support/distance.rs"]
mod distance;

use common::*;
use distance::{diagonal, hausdorff};
use nlsubdiv::differential::{DifferentialOptions, Stencil};
use nlsubdiv::scheme::Scheme;
use std::f64::consts::PI;
use std::time::Instant;

/// The vertices of `m` at most `hops` edges from `v`.
fn within_hops(m: &OwnedMesh, v: usize, hops: usize) -> Vec<usize> {
    let mut nb = vec![Vec::new(); m.positions.len()];
    for f in m.faces() {
        for i in 0..f.len() {
            let (a, b) = (f[i] as usize, f[(i + 1) % f.len()] as usize);
            nb[a].push(b);
            nb[b].push(a);
        }
    }
    let mut seen = vec![false; nb.len()];
    seen[v] = true;
    let (mut all, mut frontier) = (vec![v], vec![v]);
    for _ in 0..hops {
        let mut next = Vec::new();
        for &a in &frontier {
            for &b in &nb[a] {
                if !seen[b] {
                    seen[b] = true;
                    next.push(b);
                }
            }
        }
        all.extend_from_slice(&next);
        frontier = next;
    }
    all
}

/// The local cage of valence `d` (module docs).
fn cage(d: usize) -> OwnedMesh {
    let mut p = vec![[0.0, 0.0, 0.0]];
    for i in 0..d {
        let t = 2.0 * PI * i as f64 / d as f64;
        p.push([t.cos(), t.sin(), 0.0]);
    }
    let faces: Vec<Vec<u32>> = (0..d)
        .map(|i| vec![0, 1 + i as u32, 1 + ((i + 1) % d) as u32])
        .collect();
    let flat = subdivide_n(Scheme::Loop, &OwnedMesh::from_faces(p, &faces), 2).unwrap();
    flat.map_positions(|q| {
        [
            q[0],
            q[1],
            0.4 * q[0] * q[0] + 0.2 * q[1] * q[1] + 0.1 * q[0] * q[1],
        ]
    })
}

#[derive(Clone, Copy)]
enum Method {
    Spatial(Scheme),
    Differential(Stencil),
}

impl Method {
    fn name(self) -> &'static str {
        match self {
            Method::Spatial(_) => "spatial Loop",
            Method::Differential(Stencil::Loop) => "differential Loop",
            Method::Differential(_) => "differential Butterfly",
        }
    }
    fn run(self, m: &OwnedMesh, k: usize) -> OwnedMesh {
        match self {
            Method::Spatial(s) => subdivide_n(s, m, k).unwrap(),
            Method::Differential(stencil) => {
                let o = DifferentialOptions {
                    stencil,
                    levels: k,
                    ..Default::default()
                };
                differential_subdivide(m, &o).unwrap().0
            }
        }
    }
}

const METHODS: [Method; 3] = [
    Method::Differential(Stencil::Loop),
    Method::Differential(Stencil::ModifiedButterfly),
    Method::Spatial(Scheme::Loop),
];

/// `h_1 … h_k` of `m` (over the diagonal `d`) for `meth`; `region(level, mesh)` selects the
/// vertices measured.
fn distances(
    m: &OwnedMesh,
    meth: Method,
    k: usize,
    d: f64,
    region: &dyn Fn(usize, &OwnedMesh) -> Vec<usize>,
) -> Vec<f64> {
    let mut prev = m.clone();
    let mut h = Vec::new();
    for i in 1..=k {
        let t = Instant::now();
        let cur = meth.run(m, i);
        let ts = t.elapsed().as_secs_f64();
        let (vc, vp) = (region(i, &cur), region(i - 1, &prev));
        h.push(hausdorff(&cur, &vc, &prev, &vp) / d);
        eprintln!(
            "  level {i}: {} V run {ts:.3} s, hausdorff {:.3} s",
            cur.positions.len(),
            t.elapsed().as_secs_f64() - ts
        );
        prev = cur;
    }
    h
}

/// One table row: `i^1.5 h_i`, the ratios and whether the sequence decreases.
fn row(label: &str, meth: Method, h: &[f64]) {
    let scaled: Vec<f64> = h
        .iter()
        .enumerate()
        .map(|(i, x)| ((i + 1) as f64).powf(1.5) * x)
        .collect();
    let ratios: Vec<String> = h
        .windows(2)
        .enumerate()
        .map(|(i, w)| {
            let bound = ((i + 1) as f64 / (i + 2) as f64).powf(1.5);
            let r = w[1] / w[0];
            format!("{r:.2}{}", if r < bound { "" } else { "*" })
        })
        .collect();
    let monotone = scaled.windows(2).all(|w| w[1] < w[0]);
    println!(
        "| {label} | {} | {} | {} | {} |",
        meth.name(),
        scaled
            .iter()
            .map(|x| format!("{x:.2e}"))
            .collect::<Vec<_>>()
            .join(", "),
        ratios.join(", "),
        if monotone { "yes" } else { "no" }
    );
}

fn main() {
    let t0 = Instant::now();
    let args: Vec<String> = std::env::args().skip(1).collect();
    let full = args.iter().any(|a| a == "full");
    let dir = args
        .iter()
        .find(|a| *a != "full")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(shared_meshes_dir);
    println!("`*`: the ratio h_(i+1)/h_i is not below (i/(i+1))^1.5, so i^1.5 h_i does not decrease there.\n");
    println!("| cage / mesh | method | i^1.5 h_i / d, i = 1, 2, … | h_(i+1)/h_i | decreasing |");
    println!("|---|---|---|---|---|");
    for d in 3..=12 {
        let m = cage(d);
        let diag = diagonal(&m);
        let region = |i: usize, mesh: &OwnedMesh| within_hops(mesh, 0, 1 << i);
        for meth in METHODS {
            let h = distances(&m, meth, 5, diag, &region);
            row(&format!("valence {d}"), meth, &h);
        }
    }
    eprintln!("cages {:.1} s", t0.elapsed().as_secs_f64());
    let mut meshes = vec![("epcot", 4), ("pawn_tri", 3)];
    if full {
        meshes.extend([("fertility", 3), ("rocker_arm", 3)]);
    }
    for (name, k) in meshes {
        let p = dir.join(format!("{name}.off"));
        let Ok(m) = read_off(&p) else {
            println!("| {name} | skipped: {} not found | | | |", p.display());
            continue;
        };
        let diag = diagonal(&m);
        let region = |_: usize, mesh: &OwnedMesh| (0..mesh.positions.len()).collect();
        for meth in METHODS {
            let h = distances(&m, meth, k, diag, &region);
            row(name, meth, &h);
        }
    }
    println!("\n{:.1} s", t0.elapsed().as_secs_f64());
}
