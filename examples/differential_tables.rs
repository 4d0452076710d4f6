//! Seed 001 §4.3: normalised thin-plate energy at 3 levels, differential space vs spatial.
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    dead_code
)]

#[path = "../tests/common/mod.rs"]
mod common;

use common::*;
use nlsubdiv::differential::{DifferentialOptions, Stencil};
use std::time::Instant;

fn main() {
    let dir = std::env::args()
        .nth(1)
        .map(std::path::PathBuf::from)
        .unwrap_or_else(shared_meshes_dir);
    for name in ["fertility", "rocker_arm", "epcot"] {
        let m = read_off(&dir.join(format!("{name}.off"))).unwrap();
        let opts = DifferentialOptions {
            stencil: Stencil::Loop,
            levels: 3,
            ..Default::default()
        };
        let t = Instant::now();
        let r = differential_subdivide(&m, &opts);
        let (out, rep) = match r {
            Ok(x) => x,
            Err((e, rep)) => {
                println!("{name}: {e} {:.3}s {rep:?}", t.elapsed().as_secs_f64());
                continue;
            }
        };
        println!(
            "{name}: {} V, {:.3}s, {:?}",
            out.positions.len(),
            t.elapsed().as_secs_f64(),
            rep
        );
    }
}
