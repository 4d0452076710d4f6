//! Side-by-side timings of our linear and Möbius mesh schemes in one run (single thread):
//! the rows of DESIGN.md "Performance" and seed 000 Table 1 (Möbius / linear ratio).
//!
//! `cargo bench --bench mesh` (reads `../shared/data/meshes`; prints SKIP rows otherwise).
//! The peers' side (OpenMesh, CGAL, OpenSubdiv) is timed by `scripts/bench-peers.sh`.
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    dead_code
)]

#[path = "../tests/common/mod.rs"]
mod common;

use std::time::Instant;

use common::*;
use nlsubdiv::scheme::Scheme;

fn linear_levels(s: Scheme, m: &OwnedMesh, levels: usize) -> OwnedMesh {
    subdivide_n(s, m, levels).unwrap()
}

fn mobius_levels(s: Scheme, m: &OwnedMesh, levels: usize) -> OwnedMesh {
    let mut cur = m.clone();
    for _ in 0..levels {
        cur = mobius_subdivide(s, &cur, false).unwrap().0;
    }
    cur
}

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
    let dir = shared_meshes_dir();
    let rows = [
        ("epcot.off", Scheme::Loop, 4),
        ("epcot.off", Scheme::ModifiedButterfly, 4),
        ("cube.off", Scheme::CatmullClark, 8),
        ("spot_quad.off", Scheme::CatmullClark, 3),
        ("cube.off", Scheme::DooSabin, 8),
        ("spot_quad.off", Scheme::Kobbelt, 3),
    ];
    println!("| mesh | scheme | levels | output faces | linear ms | Möbius ms | Möbius / linear |");
    println!("|---|---|---|---|---|---|---|");
    for (name, s, levels) in rows {
        let Ok(m) = read_off(&dir.join(name)) else {
            println!(
                "| {name} | {} | {levels} | SKIP: {} not found | | | |",
                s.name(),
                dir.display()
            );
            continue;
        };
        let (lin, faces) = best_ms(3, || linear_levels(s, &m, levels).num_faces());
        let (mob, _) = best_ms(3, || mobius_levels(s, &m, levels).num_faces());
        println!(
            "| {name} | {} | {levels} | {faces} | {lin:.1} | {mob:.1} | {:.2} |",
            s.name(),
            mob / lin
        );
    }
}
