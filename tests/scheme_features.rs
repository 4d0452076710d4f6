//! The Cargo features of the crate (`Cargo.toml`, docs/firmware.md "Link only what you use"):
//! every scheme, form and method this build contains computes, and every one it leaves out is
//! refused with `Status::SchemeNotBuilt` by the plan and by the call, writing nothing.
//!
//! What a build contains is read here from the features the test itself is compiled with
//! (integration tests get their package's features), through a table written out below, not
//! from the crate's own `is_built`: a feature wired to the wrong scheme fails. The default
//! build checks that everything is there; `scripts/test-features.sh` runs this file in builds
//! that leave schemes out (e.g. `--no-default-features --features loop`, where Catmull–Clark
//! must be refused).
#![allow(
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

mod common;

use common::*;
use nlsubdiv::curve::{self, CurveScheme};
use nlsubdiv::differential::{DifferentialOptions, Stencil};
use nlsubdiv::scheme::{self, Options, Scheme, Scratch, Tags};
use nlsubdiv::{MeshOut, Status};

/// The feature of each scheme, as `Cargo.toml` documents it.
fn feature_on(s: Scheme) -> bool {
    match s {
        Scheme::Loop => cfg!(feature = "loop"),
        Scheme::CatmullClark => cfg!(feature = "catmull-clark"),
        Scheme::ModifiedButterfly => cfg!(feature = "butterfly"),
        Scheme::Kobbelt => cfg!(feature = "kobbelt"),
        Scheme::DooSabin => cfg!(feature = "doo-sabin"),
        Scheme::Simplest => cfg!(feature = "simplest"),
        Scheme::Dual | Scheme::VertexInsertion | Scheme::DualTruncation => {
            cfg!(feature = "akleman")
        }
        Scheme::Spherelike => cfg!(feature = "spherelike"),
        _ => panic!("a scheme without a feature in this table: {s:?}"),
    }
}

/// A mesh every scheme accepts in its own way: triangles for Loop and Modified Butterfly,
/// quads (a cube) for the others, both on the unit sphere.
fn mesh_for(s: Scheme) -> OwnedMesh {
    match s {
        Scheme::Loop | Scheme::ModifiedButterfly => octahedron(),
        _ => cube(),
    }
}

/// `plan` and `subdivide` with buffers of the given sizes (empty when the plan failed),
/// the output starting as a sentinel: returns the call's status and whether the output is
/// unchanged.
fn call(m: &OwnedMesh, opts: &Options, sizes: Option<&scheme::Plan>) -> (Status, bool) {
    let (nv, nf, ni, su, sp) = match sizes {
        Some(p) => {
            let o = p.output();
            (
                o.vertices,
                o.faces,
                o.indices,
                p.scratch.u32s,
                p.scratch.points,
            )
        }
        None => (16, 8, 32, 1024, 1024),
    };
    let mut pos = vec![[7.0f64; 3]; nv];
    let mut offs = vec![7u32; nf + 1];
    let mut idx = vec![7u32; ni];
    let mut u32s = vec![0u32; su];
    let mut pts = vec![[0.0f64; 3]; sp];
    let r = scheme::subdivide(
        m.view(),
        opts,
        Scratch::new(&mut u32s, &mut pts),
        &mut MeshOut::new(&mut pos, &mut offs, &mut idx),
    );
    let untouched = pos.iter().all(|p| *p == [7.0; 3])
        && offs.iter().all(|&o| o == 7)
        && idx.iter().all(|&i| i == 7);
    (r.map_or_else(|e| e.status, |_| Status::Ok), untouched)
}

#[test]
fn every_scheme_and_form_built_computes_and_every_one_left_out_is_refused() {
    let mut refused = 0;
    for s in Scheme::ALL {
        let m = mesh_for(s);
        for mobius in [false, true] {
            if mobius && !s.has_mobius_form() {
                continue;
            }
            let built = feature_on(s) && (!mobius || cfg!(feature = "mobius"));
            let want = if mobius {
                s.is_mobius_built()
            } else {
                s.is_built()
            };
            assert_eq!(want, built, "{s:?} mobius={mobius}: is_built disagrees");
            let opts = Options::new(s).mobius(mobius).levels(2);
            let mut topo = vec![0u32; scheme::plan_scratch_size(&m.view()).unwrap()];
            let plan = scheme::plan(m.view(), &opts, &mut topo);
            if built {
                let p = plan.unwrap_or_else(|e| panic!("{s:?} mobius={mobius}: {e}"));
                let (status, _) = call(&m, &opts, Some(&p));
                assert_eq!(status, Status::Ok, "{s:?} mobius={mobius}");
                let (out, _) = run(&m, &opts).unwrap();
                assert!(out.positions.iter().flatten().all(|x| x.is_finite()));
            } else {
                refused += 1;
                let e = plan.expect_err("a scheme left out was planned");
                assert_eq!(e.status, Status::SchemeNotBuilt, "{s:?} mobius={mobius}");
                // Also with buffers that would be large enough, and with zero levels: the
                // call refuses before reading the mesh and writes nothing.
                for levels in [0, 1] {
                    let o = opts.levels(levels);
                    let (status, untouched) = call(&m, &o, None);
                    assert_eq!(status, Status::SchemeNotBuilt, "{s:?} mobius={mobius}");
                    assert!(untouched, "{s:?} mobius={mobius}: output written");
                }
                assert!(!Status::SchemeNotBuilt.message().is_empty());
            }
        }
    }
    // The default build contains everything.
    if cfg!(all(
        feature = "loop",
        feature = "catmull-clark",
        feature = "butterfly",
        feature = "kobbelt",
        feature = "doo-sabin",
        feature = "simplest",
        feature = "akleman",
        feature = "spherelike",
        feature = "mobius"
    )) {
        assert_eq!(refused, 0);
    }
    println!("scheme/form pairs refused in this build: {refused}");
}

#[test]
fn tagged_meshes_follow_the_same_features() {
    // A crease on one edge of the cube: Catmull–Clark and Kobbelt take it, linear or Möbius.
    let creases = [[0u32, 1]];
    let sharpness = [2.0];
    let tags = Tags::new().creases(&creases, &sharpness);
    for s in [Scheme::CatmullClark, Scheme::Kobbelt] {
        for mobius in [false, true] {
            let built = feature_on(s) && (!mobius || cfg!(feature = "mobius"));
            let r = run_tagged(&cube(), &Options::new(s).mobius(mobius), &tags);
            match r {
                Ok(_) => assert!(built, "{s:?} mobius={mobius} computed without its feature"),
                Err(e) => {
                    assert!(!built, "{s:?} mobius={mobius}: {e}");
                    assert_eq!(e.status, Status::SchemeNotBuilt);
                }
            }
        }
    }
}

#[test]
fn curve_schemes_follow_the_curves_and_mobius_features() {
    let pts: Vec<[f64; 3]> = (0..6)
        .map(|i| {
            let t = i as f64;
            [libm::cos(t), libm::sin(t), 0.0]
        })
        .collect();
    for s in CurveScheme::ALL {
        let is_mobius = matches!(
            s,
            CurveScheme::MobiusInterpolating | CurveScheme::MobiusApproximating
        );
        let built = cfg!(feature = "curves") && (!is_mobius || cfg!(feature = "mobius"));
        assert_eq!(s.is_built(), built, "{s:?}");
        let n = curve::refined_size(pts.len(), true, 2).unwrap();
        let mut out = vec![[7.0; 3]; n];
        let mut scratch = vec![[0.0; 3]; curve::scratch_size(s, pts.len(), true, 2).unwrap()];
        let r = curve::subdivide(s, &pts, true, 2, &mut out, &mut scratch);
        if built {
            assert_eq!(r.unwrap(), n, "{s:?}");
        } else {
            assert_eq!(r.unwrap_err().status, Status::SchemeNotBuilt, "{s:?}");
            assert!(out.iter().all(|p| *p == [7.0; 3]), "{s:?}: output written");
        }
    }
}

#[test]
fn differential_subdivision_follows_its_feature_and_its_stencils() {
    let m = octahedron();
    for (stencil, scheme) in [
        (Stencil::Loop, Scheme::Loop),
        (Stencil::ModifiedButterfly, Scheme::ModifiedButterfly),
    ] {
        let built = cfg!(feature = "differential") && feature_on(scheme);
        assert_eq!(stencil.is_built(), built, "{stencil:?}");
        let opts = DifferentialOptions {
            stencil,
            levels: 1,
            ..DifferentialOptions::default()
        };
        match differential_subdivide(&m, &opts) {
            Ok(_) => assert!(built, "{stencil:?} computed without its features"),
            Err((e, _)) => {
                assert!(!built, "{stencil:?}: {e}");
                assert_eq!(e.status, Status::SchemeNotBuilt, "{stencil:?}");
            }
        }
    }
}
