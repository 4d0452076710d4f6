//! The chess-pawn experiment of seed 003 Fig. 8: one coarse cage of revolution (an 8-sided
//! profile sweep closed by quad fans at both poles, so that Kobbelt's quad-only scheme takes
//! it too) subdivided 4 levels by the spherelike scheme, Kobbelt's scheme and Catmull–Clark.
//!
//! Printed: how far each result is from a surface of revolution (every horizontal ring of
//! vertices: `(ρ_max − ρ_min)/ρ_mean` of its distances to the axis; worst ring), how far the
//! head's vertices are from the sphere the head cage was sampled on, and whether the cage is
//! interpolated. Written to `DIR` (default `target/pawn`): the cage and the three results as
//! OFF, and `pawn_fig8.off`, the four side by side (cage, spherelike, Kobbelt, Catmull–Clark)
//! for `nlsubdiv render --up z` (docs/img/pawn_fig8.png).
//!
//! `cargo run --release --example pawn [DIR]`
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    dead_code
)]

#[path = "../tests/common/mod.rs"]
mod common;

use common::*;
use nlsubdiv::scheme::Scheme;
use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::path::PathBuf;

/// Sides of the sweep.
const N: usize = 8;
/// Head sphere: centre height and radius (the head rings are sampled on it).
const HEAD_Z: f64 = 1.95;
const HEAD_R: f64 = 0.5;

/// The profile `(ρ, z)` from the base to the head, poles excluded.
fn profile() -> Vec<(f64, f64)> {
    let head = |deg: f64| {
        let t = deg * PI / 180.0;
        (HEAD_R * t.cos(), HEAD_Z + HEAD_R * t.sin())
    };
    vec![
        (1.0, 0.0),
        (1.0, 0.2),
        (0.72, 0.36),
        (0.42, 0.9),
        (0.34, 1.3),
        (0.66, 1.4),
        (0.3, 1.5),
        head(-45.0),
        head(0.0),
        head(45.0),
    ]
}

/// The cage: rings of `N` vertices, a pole below and above, each pole closed by `N/2` quads
/// (pole, r_2k, r_2k+1, r_2k+2) — a quad fan: pole valence `N/2`, the odd ring vertices at
/// the caps valence 3.
fn pawn_cage() -> OwnedMesh {
    let prof = profile();
    let rings = prof.len();
    let mut p = Vec::new();
    for &(r, z) in &prof {
        for i in 0..N {
            let t = 2.0 * PI * i as f64 / N as f64;
            p.push([r * t.cos(), r * t.sin(), z]);
        }
    }
    let bottom = p.len() as u32;
    p.push([0.0, 0.0, 0.0]);
    let top = p.len() as u32;
    p.push([0.0, 0.0, HEAD_Z + HEAD_R]);
    let id = |j: usize, i: usize| (j * N + i % N) as u32;
    let mut faces = Vec::new();
    for j in 0..rings - 1 {
        for i in 0..N {
            faces.push(vec![id(j, i), id(j, i + 1), id(j + 1, i + 1), id(j + 1, i)]);
        }
    }
    for k in 0..N / 2 {
        let i = 2 * k;
        faces.push(vec![bottom, id(0, i + 2), id(0, i + 1), id(0, i)]);
        let t = rings - 1;
        faces.push(vec![top, id(t, i), id(t, i + 1), id(t, i + 2)]);
    }
    OwnedMesh::from_faces(p, &faces)
}

/// Worst ring out-of-roundness: vertices grouped by height (to 1e-9).
fn out_of_roundness(m: &OwnedMesh) -> f64 {
    let mut rings: BTreeMap<i64, Vec<f64>> = BTreeMap::new();
    for p in &m.positions {
        let rho = (p[0] * p[0] + p[1] * p[1]).sqrt();
        if rho > 1e-6 {
            rings
                .entry((p[2] * 1e9).round() as i64)
                .or_default()
                .push(rho);
        }
    }
    let mut worst = 0.0_f64;
    for r in rings.values().filter(|r| r.len() >= N) {
        let (lo, hi) = r
            .iter()
            .fold((f64::MAX, 0.0_f64), |(a, b), &x| (a.min(x), b.max(x)));
        let mean = r.iter().sum::<f64>() / r.len() as f64;
        worst = worst.max((hi - lo) / mean);
    }
    worst
}

/// Largest relative distance from the head sphere of the vertices above the head's lowest
/// cage ring.
fn head_deviation(m: &OwnedMesh) -> f64 {
    let z0 = HEAD_Z - HEAD_R * (PI / 4.0).sin() + 1e-9;
    m.positions
        .iter()
        .filter(|p| p[2] >= z0)
        .map(|p| {
            let d = (p[0] * p[0] + p[1] * p[1] + (p[2] - HEAD_Z).powi(2)).sqrt();
            (d - HEAD_R).abs() / HEAD_R
        })
        .fold(0.0, f64::max)
}

fn shifted(m: &OwnedMesh, dx: f64) -> OwnedMesh {
    m.map_positions(|p| [p[0] + dx, p[1], p[2]])
}

/// Several meshes as one (faces renumbered).
fn concat(parts: &[OwnedMesh]) -> OwnedMesh {
    let (mut p, mut faces) = (Vec::new(), Vec::new());
    for m in parts {
        let base = p.len() as u32;
        p.extend_from_slice(&m.positions);
        faces.extend(
            m.faces()
                .into_iter()
                .map(|f| f.iter().map(|v| v + base).collect::<Vec<_>>()),
        );
    }
    OwnedMesh::from_faces(p, &faces)
}

fn main() {
    let dir = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target/pawn"));
    std::fs::create_dir_all(&dir).unwrap();
    let cage = pawn_cage();
    write_off(&dir.join("pawn_cage.off"), &cage).unwrap();
    let levels = 4;
    println!(
        "pawn cage: {} vertices, {} quads; {levels} levels",
        cage.positions.len(),
        cage.num_faces()
    );
    println!("| scheme | vertices | worst ring (ρmax−ρmin)/ρmean | head: max rel. distance from its sphere | cage interpolated |");
    println!("|---|---|---|---|---|");
    let mut parts = vec![cage.clone()];
    for (k, s) in [Scheme::Spherelike, Scheme::Kobbelt, Scheme::CatmullClark]
        .into_iter()
        .enumerate()
    {
        let out = subdivide_n(s, &cage, levels).unwrap();
        let kept = cage
            .positions
            .iter()
            .zip(&out.positions)
            .all(|(a, b)| a.map(f64::to_bits) == b.map(f64::to_bits));
        println!(
            "| {} | {} | {:.2e} | {:.2e} | {} |",
            s.name(),
            out.positions.len(),
            out_of_roundness(&out),
            head_deviation(&out),
            if kept { "yes, bit for bit" } else { "no" }
        );
        write_off(&dir.join(format!("pawn_{}.off", s.name())), &out).unwrap();
        parts.push(shifted(&out, 2.4 * (k + 1) as f64));
    }
    let fig = concat(&parts);
    write_off(&dir.join("pawn_fig8.off"), &fig).unwrap();
    println!("wrote {}", dir.display());
}
