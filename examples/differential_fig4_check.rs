//! Seed 001 §3.3, Fig. 4, the cheap check run by `scripts/test-all.sh`: when does
//! `i^1.5 h_i` decrease, `h_i = d_H(M̃_i, M̃_{i−1})` the Hausdorff distance between the
//! results with `i` and `i − 1` levels (vertex-sampled, over the control mesh's bounding-box
//! diagonal)? docs/differential.md, "Convergence of the levels (§3.3, Fig. 4)", states what is
//! asserted and why:
//!
//! * `i^1.5 h_i` decreases from `i` to `i + 1` exactly when `r_i = h_{i+1}/h_i` is below
//!   `b_i = (i/(i+1))^1.5` (0.354, 0.544, 0.650, 0.716 for `i` = 1 … 4);
//! * the rates: spatial Loop `r_i → max(1/4, λ_n²)`, `λ_n = 3/8 + cos(2π/n)/4` (its
//!   rotationally symmetric eigenvalue at a vertex of valence `n`); differential Loop and
//!   Butterfly `r_i → ρ_n = max(1/4, 4^(−6/n))`, `n` the highest valence;
//! * hence `i^1.5 h_i` decreases from the first `i ≥ 3` with `b_i > ρ + 0.1` on, and from
//!   `i = 1` when every valence is at most 6; with a vertex of valence 16 it does not.
//!
//! Two meshes generated here, 5 levels each: the icosahedron (valence 5) and the bipyramid
//! over a 16-gon (two valence-16 poles). Exits 1 when a statement fails.
//!
//! `cargo run --release --example differential_fig4_check` (about a second).
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

/// Levels measured: `h_1 … h_LEVELS`.
const LEVELS: usize = 5;
/// Allowed distance of the differential rates at `i ≥ 3` above the predicted `ρ_n`, and of
/// the last one (`r_4`) on either side.
const DIFF_SLACK: f64 = 0.1;
const DIFF_LAST: f64 = 0.05;
/// The same for spatial Loop (an eigenvalue of a fixed matrix: tight).
const SPATIAL_SLACK: f64 = 0.01;

#[derive(Clone, Copy)]
enum Method {
    Spatial,
    Differential(Stencil),
}

impl Method {
    fn name(self) -> &'static str {
        match self {
            Method::Spatial => "spatial Loop",
            Method::Differential(Stencil::Loop) => "differential Loop",
            Method::Differential(_) => "differential Butterfly",
        }
    }
    fn run(self, m: &OwnedMesh, k: usize) -> OwnedMesh {
        match self {
            Method::Spatial => subdivide_n(Scheme::Loop, m, k).unwrap(),
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
    /// The predicted limit of `h_{i+1}/h_i` with highest valence `n`.
    fn rate(self, n: usize) -> f64 {
        let n = n as f64;
        match self {
            Method::Spatial => {
                let l = 3.0 / 8.0 + (2.0 * PI / n).cos() / 4.0;
                (l * l).max(0.25)
            }
            Method::Differential(_) => 4f64.powf(-6.0 / n).max(0.25),
        }
    }
    fn slack(self) -> (f64, f64) {
        match self {
            Method::Spatial => (SPATIAL_SLACK, SPATIAL_SLACK),
            Method::Differential(_) => (DIFF_SLACK, DIFF_LAST),
        }
    }
}

const METHODS: [Method; 3] = [
    Method::Differential(Stencil::Loop),
    Method::Differential(Stencil::ModifiedButterfly),
    Method::Spatial,
];

/// `b_i = (i/(i+1))^1.5`: `i^1.5 h_i` decreases from `i` to `i + 1` iff `r_i < b_i`.
fn bound(i: usize) -> f64 {
    (i as f64 / (i + 1) as f64).powf(1.5)
}

fn max_valence(m: &OwnedMesh) -> usize {
    let mut val = vec![0usize; m.positions.len()];
    for &v in &m.indices {
        val[v as usize] += 1;
    }
    val.into_iter().max().unwrap()
}

/// `h_1 … h_LEVELS` over the bounding-box diagonal, whole surfaces.
fn distances(m: &OwnedMesh, meth: Method) -> Vec<f64> {
    let d = diagonal(m);
    let mut prev = m.clone();
    let mut h = Vec::new();
    for i in 1..=LEVELS {
        let cur = meth.run(m, i);
        let (vc, vp): (Vec<usize>, Vec<usize>) = (
            (0..cur.positions.len()).collect(),
            (0..prev.positions.len()).collect(),
        );
        h.push(hausdorff(&cur, &vc, &prev, &vp) / d);
        prev = cur;
    }
    h
}

fn main() {
    let t0 = Instant::now();
    let meshes = [
        ("icosahedron", icosahedron(), true),
        ("bipyramid(16)", bipyramid(16), false),
    ];
    let mut failures = Vec::new();
    println!("| mesh | n | method | i^1.5 h_i / d, i = 1 … {LEVELS} | r_i = h_(i+1)/h_i | predicted ρ | decreasing from |");
    println!("|---|---|---|---|---|---|---|");
    for (name, m, from_one) in &meshes {
        let n = max_valence(m);
        for meth in METHODS {
            let h = distances(m, meth);
            let scaled: Vec<f64> = h
                .iter()
                .enumerate()
                .map(|(i, x)| ((i + 1) as f64).powf(1.5) * x)
                .collect();
            let r: Vec<f64> = h.windows(2).map(|w| w[1] / w[0]).collect();
            let rho = meth.rate(n);
            // The first i from which i^1.5 h_i decreases at every measured step.
            let first = (1..=scaled.len())
                .find(|&i| scaled[i - 1..].windows(2).all(|w| w[1] < w[0]))
                .unwrap();
            println!(
                "| {name} | {n} | {} | {} | {} | {rho:.3} | {first} |",
                meth.name(),
                scaled
                    .iter()
                    .map(|x| format!("{x:.2e}"))
                    .collect::<Vec<_>>()
                    .join(", "),
                r.iter()
                    .enumerate()
                    .map(|(i, x)| format!("{x:.3}{}", if *x < bound(i + 1) { "" } else { "*" }))
                    .collect::<Vec<_>>()
                    .join(", "),
            );
            let label = format!("{name}, {}", meth.name());
            let (slack, last_slack) = meth.slack();
            // (A) the rate: r_i for i >= 3 at most ρ + slack, the last one within last_slack.
            for (i, &ri) in r.iter().enumerate().skip(2) {
                if ri > rho + slack {
                    failures.push(format!(
                        "{label}: r_{} = {ri:.3} above ρ + {slack} = {:.3}",
                        i + 1,
                        rho + slack
                    ));
                }
            }
            let last = r[r.len() - 1];
            if (last - rho).abs() > last_slack {
                failures.push(format!(
                    "{label}: r_{} = {last:.3} not within {last_slack} of ρ = {rho:.3}",
                    r.len()
                ));
            }
            // (B) the consequence: decreasing from the first i >= 3 with b_i > ρ + slack.
            let i0 = (3..LEVELS)
                .find(|&i| bound(i) > rho + slack)
                .unwrap_or(LEVELS);
            if first > i0 {
                failures.push(format!(
                    "{label}: i^1.5 h_i decreases only from i = {first}, predicted from {i0}"
                ));
            }
            // (C) Fig. 4 from i = 1: with valences <= 6 yes; with a valence-16 vertex no
            // (ρ exceeds b_1 for spatial Loop and b_2 for the differential methods).
            if *from_one != (first == 1) {
                failures.push(format!(
                    "{label}: i^1.5 h_i {} from i = 1, stated the opposite",
                    if first == 1 {
                        "decreases"
                    } else {
                        "does not decrease"
                    }
                ));
            }
        }
    }
    println!("\n`*`: r_i not below b_i = (i/(i+1))^1.5 (0.354, 0.544, 0.650, 0.716), so i^1.5 h_i grows from i to i+1.");
    println!("{:.1} s", t0.elapsed().as_secs_f64());
    if !failures.is_empty() {
        for f in &failures {
            eprintln!("FAIL: {f}");
        }
        std::process::exit(1);
    }
    println!("Fig. 4 statement holds (docs/differential.md, \"Convergence of the levels\").");
}
