//! 1 thread against 2 (or `NLS_BENCH_THREADS`) on the Möbius benchmark rows (`MOBIUS_BENCH_ROWS`),
//! linear and Möbius (the guarded default), interleaved A B A B, best of 7 each: each row is
//! one multi-level call as a host makes it (`plan`, the buffers, `subdivide_with` on
//! [`nlsubdiv_threads::Threads`]). Every pair's outputs are also compared bit for bit.
//!
//! `cargo bench -p nlsubdiv-threads --bench threads` (reads `../shared/data/meshes`).
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
use nlsubdiv::scheme::Options;
use nlsubdiv_threads::Threads;

fn main() {
    let n: usize = std::env::var("NLS_BENCH_THREADS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2);
    let reps = 7;
    let dir = shared_meshes_dir();
    println!("| row | output faces | 1 thread ms | {n} threads ms | speed-up |");
    println!("|---|---|---|---|---|");
    for (name, s, levels) in MOBIUS_BENCH_ROWS {
        let Ok(m) = read_off(&dir.join(name)) else {
            println!("| {name} | SKIP: {} not found | | | |", dir.display());
            continue;
        };
        for mobius in [false, true] {
            let opts = Options::new(s).mobius(mobius).levels(levels);
            let (one, many) = (Threads::new(1), Threads::new(n));
            let (mut a, mut b) = (f64::MAX, f64::MAX);
            let mut faces = 0;
            for _ in 0..reps {
                let t = Instant::now();
                let (oa, _) = run_with(&m, &opts, &one).expect("1 thread");
                a = a.min(t.elapsed().as_secs_f64() * 1e3);
                let t = Instant::now();
                let (ob, _) = run_with(&m, &opts, &many).expect("n threads");
                b = b.min(t.elapsed().as_secs_f64() * 1e3);
                assert_eq!(hash(&oa), hash(&ob), "{name}: outputs differ");
                faces = ob.num_faces();
            }
            println!(
                "| {} {}{} {levels} | {faces} | {a:.1} | {b:.1} | {:.2} |",
                s.name(),
                name.trim_end_matches(".off"),
                if mobius { " Möbius" } else { "" },
                a / b
            );
        }
    }
}
