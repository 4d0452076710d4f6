//! Seed 000 Table 2 and Fig. 9 for our Möbius schemes: the maximal edge length per level
//! with its convergence rate `10^(−s)` (`s` the least-squares slope of log10 of the data),
//! and the mean discrete Willmore energy (tangent-polygon planarity, §3.3) per level.
//!
//! `cargo run --release --example mobius_tables [MESH_DIR]` (default `../shared/data/meshes`).
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

fn mobius_step(s: Scheme, m: &OwnedMesh) -> (OwnedMesh, u32) {
    let (out, rep) = mobius_subdivide(s, m, false).unwrap();
    (out, rep.fallbacks)
}

fn main() {
    let dir = std::env::args()
        .nth(1)
        .map(std::path::PathBuf::from)
        .unwrap_or_else(shared_meshes_dir);
    let rows = [
        ("epcot.off", Scheme::ModifiedButterfly),
        ("epcot.off", Scheme::Loop),
        ("cube.off", Scheme::CatmullClark),
        ("torus_quad.off", Scheme::CatmullClark),
        ("cross_quad.off", Scheme::CatmullClark),
        ("spot_control.off", Scheme::CatmullClark),
        ("cross_quad.off", Scheme::Kobbelt),
        ("cube.off", Scheme::DooSabin),
        ("spot_control.off", Scheme::DooSabin),
        ("epcot.off", Scheme::DualTruncation),
    ];
    println!("| mesh | Möbius scheme | max edge, levels 0–4 | rate 10^-s | mean Willmore, levels 0–4 | fallbacks |");
    println!("|---|---|---|---|---|---|");
    for (name, s) in rows {
        let Ok(mut m) = read_off(&dir.join(name)) else {
            println!("| {name} | {} | SKIP: not found | | | |", s.name());
            continue;
        };
        let (mut lengths, mut willmore, mut fb) = (vec![max_edge(&m)], vec![mean_willmore(&m)], 0);
        for _ in 0..4 {
            let (next, f) = mobius_step(s, &m);
            fb += f;
            m = next;
            lengths.push(max_edge(&m));
            willmore.push(mean_willmore(&m));
        }
        // Least-squares slope of log10(length) against the level.
        let n = lengths.len() as f64;
        let xs: Vec<f64> = (0..lengths.len()).map(|i| i as f64).collect();
        let ys: Vec<f64> = lengths.iter().map(|l| l.log10()).collect();
        let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
        let slope = xs
            .iter()
            .zip(&ys)
            .map(|(x, y)| (x - mx) * (y - my))
            .sum::<f64>()
            / xs.iter().map(|x| (x - mx).powi(2)).sum::<f64>();
        let fmt = |v: &[f64]| {
            v.iter()
                .map(|x| format!("{x:.3}"))
                .collect::<Vec<_>>()
                .join(" ")
        };
        let fmtw = |v: &[f64]| {
            v.iter()
                .map(|x| format!("{x:.2e}"))
                .collect::<Vec<_>>()
                .join(" ")
        };
        println!(
            "| {name} | mobius-{} | {} | {:.3} | {} | {fb} |",
            s.name(),
            fmt(&lengths),
            10f64.powf(-slope),
            fmtw(&willmore)
        );
    }
}
