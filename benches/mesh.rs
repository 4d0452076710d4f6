//! Side-by-side timings of our linear and Möbius mesh schemes in one run (single thread):
//! the rows of docs/RESULTS.md and seed 000 Table 1 (Möbius / linear ratio).
//!
//! `cargo bench --bench mesh` (reads `../shared/data/meshes`; prints SKIP rows otherwise):
//! linear and Möbius interleaved, best of 5 each.
//! The peers' side (OpenMesh, CGAL, OpenSubdiv) is timed by `scripts/bench_peers.py`.
//!
//! Each row is one multi-level call (`common::levels_call`: `plan` + `subdivide`, linear or
//! Möbius), as a host would make it: validation, topology of every
//! level, every level, with the caller's buffers allocated inside the timed region.
//!
//! `cargo bench --bench mesh -- SCHEME LEVELS MESH.off [--mobius]` runs one such call once
//! (for `valgrind --tool=callgrind`: the instruction count is then the kernel's plus reading
//! the small input file).
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    dead_code
)]

#[path = "../tests/common/mod.rs"]
mod common;

use std::path::Path;
use std::time::Instant;

use common::*;
use nlsubdiv::scheme::Scheme;

/// Best of `reps` wall-clock runs, in milliseconds.
fn best_ms(reps: usize, mut f: impl FnMut() -> usize) -> (f64, usize) {
    let mut best = f64::MAX;
    let mut faces = 0;
    for _ in 0..reps {
        let t = Instant::now();
        faces = f();
        best = best.min(t.elapsed().as_secs_f64() * 1e3);
    }
    (best, faces)
}

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| a != "--bench")
        .collect();
    if args.len() >= 3 {
        let s = Scheme::from_name(&args[0]).expect("scheme name");
        let levels: usize = args[1].parse().expect("levels");
        let m = read_off(Path::new(&args[2])).expect("mesh");
        let mobius = args.get(3).is_some_and(|a| a == "--mobius");
        let t = Instant::now();
        let out = levels_call(s, &m, levels, mobius);
        println!(
            "{} {levels} {}{}: {} faces, {:.1} ms",
            s.name(),
            args[2],
            if mobius { " (Möbius)" } else { "" },
            out.num_faces(),
            t.elapsed().as_secs_f64() * 1e3
        );
        return;
    }
    let dir = shared_meshes_dir();
    println!("| mesh | scheme | levels | output faces | linear ms | Möbius ms | Möbius / linear |");
    println!("|---|---|---|---|---|---|---|");
    for (name, s, levels) in MOBIUS_BENCH_ROWS {
        let Ok(m) = read_off(&dir.join(name)) else {
            println!(
                "| {name} | {} | {levels} | SKIP: {} not found | | | |",
                s.name(),
                dir.display()
            );
            continue;
        };
        // Interleaved, best of 5 each: linear and Möbius are timed in the same minutes, so
        // a slow spell of the shared machine does not favour one of them.
        let (mut lin, mut mob, mut faces) = (f64::MAX, f64::MAX, 0);
        for _ in 0..5 {
            let (l, f) = best_ms(1, || levels_call(s, &m, levels, false).num_faces());
            let (b, _) = best_ms(1, || levels_call(s, &m, levels, true).num_faces());
            (lin, mob, faces) = (lin.min(l), mob.min(b), f);
        }
        println!(
            "| {name} | {} | {levels} | {faces} | {lin:.1} | {mob:.1} | {:.2} |",
            s.name(),
            mob / lin
        );
    }
}
