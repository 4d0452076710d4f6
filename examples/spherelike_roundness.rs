//! Seed 003 §5's claim on the simplest cage: a cube subdivided 5 levels by the spherelike
//! scheme is rounder than by Catmull–Clark or Kobbelt, while interpolating the cube's corners.
//! Roundness: the deviation of the vertices from their best-fit sphere (algebraic least
//! squares: `|p|² = 2 c·p + k`, `r² = k + |c|²`), max and RMS of `|‖p − c‖ − r| / r`.
//!
//! `cargo run --release --example spherelike_roundness`
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
use nlsubdiv::Point;

/// Solves the 4×4 system `a x = b` by Gaussian elimination with partial pivoting.
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> [f64; 4] {
    for c in 0..4 {
        let p = (c..4)
            .max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))
            .unwrap();
        a.swap(c, p);
        b.swap(c, p);
        let pivot = a[c];
        for r in c + 1..4 {
            let f = a[r][c] / pivot[c];
            for (x, y) in a[r].iter_mut().zip(pivot).skip(c) {
                *x -= f * y;
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = [0.0; 4];
    for c in (0..4).rev() {
        let s: f64 = (c + 1..4).map(|k| a[c][k] * x[k]).sum();
        x[c] = (b[c] - s) / a[c][c];
    }
    x
}

/// The best-fit sphere (centre, radius) and the max and RMS relative radial deviation.
pub fn sphere_fit(pts: &[Point]) -> (Point, f64, f64, f64) {
    let (mut a, mut b) = ([[0.0; 4]; 4], [0.0; 4]);
    for p in pts {
        let row = [2.0 * p[0], 2.0 * p[1], 2.0 * p[2], 1.0];
        let rhs = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
        for i in 0..4 {
            for j in 0..4 {
                a[i][j] += row[i] * row[j];
            }
            b[i] += row[i] * rhs;
        }
    }
    let x = solve4(a, b);
    let c = [x[0], x[1], x[2]];
    let r = (x[3] + c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    let (mut max, mut sq) = (0.0_f64, 0.0);
    for p in pts {
        let d = ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)).sqrt();
        let e = (d - r).abs() / r;
        max = max.max(e);
        sq += e * e;
    }
    (c, r, max, (sq / pts.len() as f64).sqrt())
}

fn main() {
    let cage = cube();
    println!("cube cage (8 vertices, 6 quads), deviation from the best-fit sphere");
    println!("| scheme | level | vertices | radius | max rel. dev. | RMS rel. dev. |");
    println!("|---|---|---|---|---|---|");
    for s in [Scheme::Spherelike, Scheme::CatmullClark, Scheme::Kobbelt] {
        let mut m = cage.clone();
        for level in 1..=5 {
            m = subdivide(s, &m).unwrap();
            let (_, r, max, rms) = sphere_fit(&m.positions);
            println!(
                "| {} | {level} | {} | {r:.4} | {max:.2e} | {rms:.2e} |",
                s.name(),
                m.positions.len()
            );
        }
        let corner = m.positions[0];
        println!(
            "| {} | corner 0 after 5 levels | ({:.3}, {:.3}, {:.3}) | | | |",
            s.name(),
            corner[0],
            corner[1],
            corner[2]
        );
    }
}
