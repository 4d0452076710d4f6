//! Regressions found by the `differential` fuzz target (fuzz/regressions/differential/),
//! replayed through the Rust API: a non-finite intermediate of the differential computation
//! is `NumericalFailure` (docs/bad-input-catalogue.md row 15), never `NonFiniteInput` for an
//! input the plan accepted, and never `Ok` with a non-finite position.
#![allow(
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

mod common;

use common::*;
use nlsubdiv::differential::{DifferentialOptions, Stencil};
use nlsubdiv::Status;

#[test]
fn an_overflowing_differential_field_is_a_numerical_failure_not_bad_input() {
    // The fuzz input (fuzz/regressions/differential/laplacian-overflow): a perturbed
    // octahedron with coordinates up to 3.1e231 and curvature scales up to 1.1e270, all
    // finite, so the plan accepts them; the scaled differential coordinates `s Δ` overflow.
    // Modified Butterfly (the fuzz input) and Loop must both refuse with NumericalFailure.
    let p = [
        [
            0.9517249054661783,
            -0.027629221322528534,
            -0.30570628132981614,
        ],
        [
            -0.08365021996988349,
            0.9057597633317285,
            -0.41545383838429184,
        ],
        [
            -0.11327705454675056,
            -0.007637394673585977,
            0.9935340855329586,
        ],
        [
            0.035090099042186434,
            -0.9943019502090429,
            -0.10065940969280383,
        ],
        [
            -0.010528191131751184,
            4.6943705996980564e119,
            -3.0600719933064258e231,
        ],
        [
            -3.104604286690891e231,
            8.063089174693565e-73,
            1.0145656833479137e80,
        ],
    ];
    let faces: Vec<Vec<u32>> = [
        [0, 1, 2],
        [3, 0, 2],
        [1, 0, 4],
        [0, 3, 4],
        [1, 5, 2],
        [5, 1, 4],
        [5, 3, 2],
        [3, 5, 4],
    ]
    .iter()
    .map(|f| f.to_vec())
    .collect();
    let m = OwnedMesh::from_faces(p.to_vec(), &faces);
    let scale = [
        -3.105036184601461e231,
        -1.0565890622713453e270,
        3.1e-322,
        -3.105036184601462e231,
        -1.0565890622713453e270,
        3.1e-322,
    ];
    for stencil in [Stencil::ModifiedButterfly, Stencil::Loop] {
        let o = DifferentialOptions {
            stencil,
            levels: 1,
            curvature_scale: Some(&scale[..]),
            ..Default::default()
        };
        // Coordinates of 3e231 are beyond what the normal equations can represent: the plan
        // refuses them as a numerical failure (mesh::check_extent), never as bad input.
        let mut ps = vec![0u32; nlsubdiv::differential::plan_scratch_size(&m.view()).unwrap()];
        match nlsubdiv::differential::plan(m.view(), &o, &mut ps) {
            Ok(_) => {}
            Err(e) => assert_eq!(e.status, Status::NumericalFailure, "{stencil:?}: {e:?}"),
        }
        match differential_subdivide(&m, &o) {
            Ok((out, _)) => assert!(
                out.positions.iter().flatten().all(|x| x.is_finite()),
                "Ok with a non-finite position ({stencil:?})"
            ),
            Err((e, _)) => assert_eq!(e.status, Status::NumericalFailure, "{stencil:?}: {e:?}"),
        }
    }
}
