//! Spherelike against linear Kobbelt on the same mesh and level, side by side in one run
//! (single thread, best of 5 wall-clock runs): the cost of the circle-blend rules over
//! Kobbelt's four-point rule with the same connectivity.
//!
//! `cargo bench --bench spherelike` (reads `../shared/data/meshes`; SKIP rows otherwise).
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
    let mut rows: Vec<(String, Option<OwnedMesh>, usize)> = vec![
        ("cube (generated)".into(), Some(cube()), 8),
        (
            "torus 24×16 (generated)".into(),
            Some(quad_torus(24, 16, 3.0, 1.0)),
            5,
        ),
    ];
    for (name, levels) in [("spot_quad.off", 3), ("torus_quad.off", 3)] {
        rows.push((name.into(), read_off(&dir.join(name)).ok(), levels));
    }
    println!(
        "| mesh | levels | output faces | Kobbelt ms | spherelike ms | spherelike / Kobbelt |"
    );
    println!("|---|---|---|---|---|---|");
    for (name, m, levels) in rows {
        let Some(m) = m else {
            println!(
                "| {name} | {levels} | SKIP: not in {} | | | |",
                dir.display()
            );
            continue;
        };
        let (k, faces) = best_ms(5, || {
            subdivide_n(Scheme::Kobbelt, &m, levels)
                .unwrap()
                .num_faces()
        });
        let (s, _) = best_ms(5, || {
            subdivide_n(Scheme::Spherelike, &m, levels)
                .unwrap()
                .num_faces()
        });
        println!(
            "| {name} | {levels} | {faces} | {k:.1} | {s:.1} | {:.2} |",
            s / k
        );
    }
}
