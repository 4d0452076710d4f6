//! Scale covariance over the whole range of `f64`: subdividing a mesh scaled by `s` must give
//! the result at scale 1 scaled by `s`, or a status — never a wrong result reported as
//! success. Differential-space and spherelike subdivision refuse meshes outside
//! `mesh::MIN_EXTENT ..= mesh::MAX_EXTENT` (1e-140 to 1e140), where their squared distances
//! underflow or overflow; the other schemes, linear and Möbius, must compute at every scale.
#![allow(
    clippy::unwrap_used,
    clippy::indexing_slicing,
    clippy::expect_used,
    clippy::panic
)]

mod common;
use common::*;
use nlsubdiv::differential::{DifferentialOptions, Stencil};
use nlsubdiv::scheme::{Options, Scheme};

/// The largest coordinate difference between `got / s` and `reference`, over the
/// reference's extent.
fn deviation(got: &OwnedMesh, reference: &OwnedMesh, s: f64) -> f64 {
    let ext = reference
        .positions
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |a, x| a.max(x.abs()))
        .max(1e-300);
    got.positions
        .iter()
        .zip(&reference.positions)
        .flat_map(|(a, b)| (0..3).map(move |k| (a[k] / s - b[k]).abs()))
        .fold(0.0f64, f64::max)
        / ext
}

fn scales() -> Vec<f64> {
    let mut v = Vec::new();
    for e in [
        -300, -250, -200, -160, -150, -120, -100, -50, 50, 100, 120, 150, 155, 200, 250, 300,
    ] {
        v.push(10f64.powi(e));
    }
    for k in [
        -1000, -800, -600, -500, -400, -300, 300, 400, 500, 600, 800, 1000,
    ] {
        v.push(2f64.powi(k));
    }
    v
}

/// Checks one method over every scale: an OK result is finite and within 1e-9 (relative to
/// the extent) of the scaled reference; a refusal is allowed only outside [1e-130, 1e130]
/// and only as `NumericalFailure` or `DegenerateGeometry`. Failures go to `failures`.
fn check(
    name: &str,
    m: &OwnedMesh,
    run: &dyn Fn(&OwnedMesh) -> Result<OwnedMesh, nlsubdiv::Error>,
    may_refuse_outside: bool,
    failures: &mut Vec<String>,
) {
    let reference = run(m).unwrap_or_else(|e| panic!("{name}: reference failed: {e:?}"));
    for s in scales() {
        let scaled = m.map_positions(|p| p.map(|x| x * s));
        match run(&scaled) {
            Ok(got) => {
                let d = deviation(&got, &reference, s);
                let finite = got.positions.iter().flatten().all(|x| x.is_finite());
                if !finite || d.is_nan() || d > 1e-9 {
                    failures.push(format!("{name} at scale {s:e}: OK with deviation {d:.2e}"));
                }
            }
            // Inside the documented range of the squared-distance methods every method must
            // compute; outside it a refusal is the specific status.
            Err(e) if !may_refuse_outside || (1e-130..=1e130).contains(&s) => {
                failures.push(format!("{name} at scale {s:e}: refused ({:?})", e.status))
            }
            Err(e)
                if e.status != nlsubdiv::Status::NumericalFailure
                    && e.status != nlsubdiv::Status::DegenerateGeometry =>
            {
                failures.push(format!("{name} at scale {s:e}: unexpected {:?}", e.status))
            }
            Err(e) => println!("{name} at scale {s:e}: {:?}", e.status),
        }
    }
}

#[test]
fn every_method_is_scale_covariant_or_refuses() {
    let mut failures = Vec::new();
    let tri = jitter(&icosahedron(), 0.05, 7);
    let quad = jitter(&cube(), 0.05, 11);
    for s in [
        Scheme::Loop,
        Scheme::ModifiedButterfly,
        Scheme::CatmullClark,
        Scheme::DooSabin,
        Scheme::Spherelike,
    ] {
        let m = if matches!(s, Scheme::Loop | Scheme::ModifiedButterfly) {
            &tri
        } else {
            &quad
        };
        for mobius in [false, true] {
            if mobius && s == Scheme::Spherelike {
                continue;
            }
            let opts = Options::new(s).mobius(mobius).levels(2);
            let name = format!("{s:?}{}", if mobius { " (Möbius)" } else { "" });
            let squares = s == Scheme::Spherelike;
            check(
                &name,
                m,
                &|m| run(m, &opts).map(|r| r.0),
                squares,
                &mut failures,
            );
        }
    }
    for stencil in [Stencil::Loop, Stencil::ModifiedButterfly] {
        let opts = DifferentialOptions {
            stencil,
            levels: 2,
            ..Default::default()
        };
        let name = format!("differential {stencil:?}");
        check(
            &name,
            &tri,
            &|m| {
                differential_subdivide(m, &opts)
                    .map(|r| r.0)
                    .map_err(|e| e.0)
            },
            true,
            &mut failures,
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
