//! Differential-space subdivision (seed 001), 1 thread against 2 (or `NLS_BENCH_THREADS`):
//! interleaved A B A B, best of `NLS_BENCH_REPS` (default 7) each, one call as a host makes
//! it (plan, the buffers, `differential::subdivide_with` on [`nlsubdiv_threads::Threads`] with
//! [`nlsubdiv_threads::DIFFERENTIAL_MIN_CHUNK`], as `nlsubdiv_threads::differential_subdivide`).
//! Every pair's outputs and reports are also compared bit for bit.
//!
//! `cargo bench -p nlsubdiv-threads --bench differential` (reads `../shared/data/meshes`).
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    dead_code
)]

#[path = "../../tests/common/mod.rs"]
mod common;

use std::time::Instant;

use common::*;
use nlsubdiv::differential::{DifferentialOptions, Stencil};
use nlsubdiv_threads::{Threads, DIFFERENTIAL_MIN_CHUNK};

fn main() {
    let n: usize = std::env::var("NLS_BENCH_THREADS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2);
    let reps: usize = std::env::var("NLS_BENCH_REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(7);
    let dir = shared_meshes_dir();
    println!("| row | output vertices | iterations | 1 thread ms | {n} threads ms | speed-up |");
    println!("|---|---|---|---|---|---|");
    for (name, levels) in [("pawn_tri.off", 3), ("rocker_arm.off", 2)] {
        let Ok(m) = read_off(&dir.join(name)) else {
            println!("| {name} | SKIP: {} not found | | | | |", dir.display());
            continue;
        };
        for stencil in [Stencil::Loop, Stencil::ModifiedButterfly] {
            let opts = DifferentialOptions {
                stencil,
                levels,
                ..Default::default()
            };
            let (one, many) = (
                Threads::new(1),
                Threads::new(n).min_chunk(DIFFERENTIAL_MIN_CHUNK),
            );
            let (mut a, mut b) = (f64::MAX, f64::MAX);
            let (mut verts, mut its) = (0, 0);
            for _ in 0..reps {
                let t = Instant::now();
                let (oa, ra) = differential_subdivide_with(&m, &opts, Some(&one)).expect("1");
                a = a.min(t.elapsed().as_secs_f64() * 1e3);
                let t = Instant::now();
                let (ob, rb) = differential_subdivide_with(&m, &opts, Some(&many)).expect("n");
                b = b.min(t.elapsed().as_secs_f64() * 1e3);
                assert_eq!(hash(&oa), hash(&ob), "{name}: outputs differ");
                assert_eq!(ra, rb, "{name}: reports differ");
                verts = ob.positions.len();
                its = rb.solve.iterations;
            }
            println!(
                "| {stencil:?} {} {levels} | {verts} | {its} | {a:.1} | {b:.1} | {:.2} |",
                name.trim_end_matches(".off"),
                a / b
            );
        }
    }
}
