//! Per-vertex weights of the Möbius–linear spectrum (seed 000 §7.2;
//! [`nlsubdiv::subdivide_weighted`]): the properties the definition implies, for every scheme
//! with a Möbius form, with and without sharp-feature tags.
//!
//! * All weights 1 is the Möbius result, all 0 the linear one, all equal to `w` the global
//!   weight `w`, bit for bit (equal weights stay equal exactly under the carry rule, and
//!   uniform levels run the one step alone); no weights is the global weight bit for bit.
//! * One level: every output vertex is `w · Möbius + (1 − w) · linear` with `w` the carry
//!   rule's weight (old vertex: its own, edge point: the mean of its ends, face point: the
//!   mean of its corners).
//! * A region of weight 0 far from a region of weight 1 (farther than the stencils reach in
//!   two levels): the output there is the linear or the Möbius output, bit for bit.
//! * Continuity: a perturbation of 1e-9 of every weight moves the output by about as much.
//! * A weight NaN or outside `[0, 1]` is `InvalidArgument` naming the vertex, a wrong length
//!   `InvalidArgument` without element, and nothing is written to the output.
#![allow(
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

mod common;

use common::*;
use nlsubdiv::exec::Serial;
use nlsubdiv::mesh::MeshOut;
use nlsubdiv::scheme::{self, Options, Scheme, Scratch, Tags, VertexWeights};
use nlsubdiv::{Error, Point, Status, NO_ELEMENT};

fn mobius_schemes() -> impl Iterator<Item = Scheme> {
    Scheme::ALL.into_iter().filter(|s| s.has_mobius_form())
}

fn triangles(s: Scheme) -> bool {
    matches!(s, Scheme::Loop | Scheme::ModifiedButterfly)
}

/// A closed mesh and a mesh with a boundary of the scheme's face type, off the plane and off
/// any sphere (so that Möbius and linear differ).
fn meshes(s: Scheme) -> Vec<OwnedMesh> {
    if triangles(s) {
        vec![
            jitter(&tri_torus(8, 6), 0.08, 31),
            bent(&tri_grid(6, 5), 32),
        ]
    } else {
        vec![
            jitter(&quad_torus(8, 6, 3.0, 1.0), 0.08, 33),
            bent(&quad_grid(6, 5), 34),
        ]
    }
}

/// A grid scaled to the unit square, bent into a saddle and jittered.
fn bent(m: &OwnedMesh, seed: u64) -> OwnedMesh {
    let (mx, my) = m
        .positions
        .iter()
        .fold((0.0f64, 0.0f64), |(a, b), p| (a.max(p[0]), b.max(p[1])));
    let scaled = m.map_positions(|p| {
        let (x, y) = (p[0] / mx, p[1] / my);
        [x, y, 0.4 * (x * x - y * y) + 0.2 * x * y]
    });
    jitter(&scaled, 0.1 / mx, seed)
}

fn weighted(
    m: &OwnedMesh,
    opts: &Options,
    w: Option<&[f64]>,
) -> nlsubdiv::Result<(OwnedMesh, nlsubdiv::Report)> {
    run_weighted(m, opts, &Tags::new(), w.map(VertexWeights::Mobius), &Serial)
}

/// Pseudo-random weights in `[lo, hi]`.
fn random_weights(n: usize, lo: f64, hi: f64, seed: u64) -> Vec<f64> {
    let mut r = Lcg(seed);
    (0..n)
        .map(|_| (lo + (hi - lo) * 0.5 * (r.next() + 1.0)).clamp(lo, hi))
        .collect()
}

fn gap(a: &[Point], b: &[Point]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| {
            let d = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
            (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
        })
        .fold(0.0, f64::max)
}

#[test]
fn uniform_weights_are_the_global_weight_bit_for_bit() {
    for s in mobius_schemes() {
        for m in meshes(s) {
            let n = m.positions.len();
            let mob = Options::new(s).mobius(true).levels(2);
            for opts in [mob, mob.literal(true), mob.spectrum(0.3)] {
                // No weights: the global weight, whatever it is.
                assert_eq!(
                    weighted(&m, &opts, None).unwrap(),
                    run(&m, &opts).unwrap(),
                    "{s:?} none"
                );
            }
            let lin = run(&m, &Options::new(s).levels(2)).unwrap().0;
            for w in [0.0, 1.0, 0.1, 0.3, 1.0 / 3.0, 0.7, 5e-324] {
                let ws = vec![w; n];
                let (got, report) = weighted(&m, &mob, Some(&ws)).unwrap();
                let (want, want_report) = run(&m, &mob.spectrum(w)).unwrap();
                assert_eq!(got, want, "{s:?} all {w}");
                assert_eq!(report, want_report, "{s:?} all {w}");
                if w == 0.0 {
                    assert_eq!(got, lin, "{s:?} all 0 is linear");
                }
            }
            // The weights replace the global one.
            let ws = vec![1.0; n];
            assert_eq!(
                weighted(&m, &mob.spectrum(0.4), Some(&ws)).unwrap(),
                run(&m, &mob).unwrap(),
                "{s:?}"
            );
            // Checked, and without effect, for the linear scheme.
            let ws = random_weights(n, 0.0, 1.0, 5);
            assert_eq!(
                weighted(&m, &Options::new(s).levels(2), Some(&ws)).unwrap(),
                run(&m, &Options::new(s).levels(2)).unwrap(),
                "{s:?} linear"
            );
        }
    }
}

/// Weights of the linear result ([`VertexWeights::Linear`], the C ABI's convention): equal
/// values `u` are the global weight `1 − u` bit for bit (as the C ABI's `linear_weight` is
/// turned into it), mixed ones the same result as the weights `1 − u` of the Möbius result
/// up to rounding, and bad values are refused alike.
#[test]
fn weights_of_the_linear_result() {
    let lin_w = |m: &OwnedMesh, o: &Options, u: &[f64]| {
        run_weighted(m, o, &Tags::new(), Some(VertexWeights::Linear(u)), &Serial)
    };
    for s in mobius_schemes() {
        for m in meshes(s) {
            let n = m.positions.len();
            let mob = Options::new(s).mobius(true).levels(2);
            for u in [0.0, 1.0, 0.25, 0.1, 0.9] {
                assert_eq!(
                    lin_w(&m, &mob, &vec![u; n]).unwrap(),
                    run(&m, &mob.spectrum(1.0 - u)).unwrap(),
                    "{s:?} all u = {u}"
                );
            }
            let us = random_weights(n, 0.0, 1.0, 19);
            let ws: Vec<f64> = us.iter().map(|u| 1.0 - u).collect();
            let a = lin_w(&m, &mob, &us).unwrap().0;
            let b = weighted(&m, &mob, Some(&ws)).unwrap().0;
            let scale = gap(&a.positions, &vec![[0.0; 3]; a.positions.len()]);
            let g = gap(&a.positions, &b.positions) / scale;
            assert!(g < 1e-13, "{s:?}: {g:e}");
            let mut bad = vec![0.5; n];
            bad[2] = f64::NAN;
            assert_eq!(
                lin_w(&m, &mob, &bad).unwrap_err(),
                Error::at(Status::InvalidArgument, 2)
            );
        }
    }
}

/// The edges in the crate's numbering ((min, max) key order), each as its two vertices.
fn edges(m: &OwnedMesh) -> Vec<(u32, u32)> {
    let mut e: Vec<(u32, u32)> = m
        .faces()
        .iter()
        .flat_map(|f| {
            (0..f.len()).map(move |i| {
                let (a, b) = (f[i], f[(i + 1) % f.len()]);
                (a.min(b), a.max(b))
            })
        })
        .collect();
    e.sort_unstable();
    e.dedup();
    e
}

/// One level of Loop and Catmull–Clark (primal: old vertices, edge points, face points) with
/// random weights: each output vertex is the blend at the weight the carry rule gives it.
#[test]
fn one_level_blends_each_vertex_at_its_carried_weight() {
    for s in [Scheme::Loop, Scheme::CatmullClark, Scheme::Kobbelt] {
        for m in meshes(s) {
            let n = m.positions.len();
            let ws = random_weights(n, 0.0, 1.0, 7);
            let mob = Options::new(s).mobius(true);
            let (got, _) = weighted(&m, &mob, Some(&ws)).unwrap();
            let (lin, _) = run(&m, &Options::new(s)).unwrap();
            let (full, _) = run(&m, &mob).unwrap();
            let mut want_w: Vec<f64> = ws.clone();
            for (a, b) in edges(&m) {
                want_w.push(0.5 * (ws[a as usize] + ws[b as usize]));
            }
            if !triangles(s) {
                for f in m.faces() {
                    want_w.push(f.iter().map(|&v| ws[v as usize]).sum::<f64>() / f.len() as f64);
                }
            }
            assert_eq!(want_w.len(), got.positions.len(), "{s:?}");
            let scale = 1.0 + gap(&lin.positions, &vec![[0.0; 3]; lin.positions.len()]);
            let mut differ = 0;
            for (i, w) in want_w.iter().enumerate() {
                let (p, l, q) = (got.positions[i], lin.positions[i], full.positions[i]);
                for k in 0..3 {
                    let want = w * q[k] + (1.0 - w) * l[k];
                    assert!(
                        (p[k] - want).abs() <= 1e-14 * scale,
                        "{s:?} vertex {i}: {} vs {want}",
                        p[k]
                    );
                }
                differ += usize::from(gap(&[q], &[l]) > 1e-9 * scale);
            }
            assert!(differ > n / 2, "{s:?}: Möbius and linear agree");
        }
    }
}

/// The weights the carry rule gives one level of `s` on a closed mesh (no boundary or
/// isolated vertices), by the pattern's documented output order (`mesh::refine`): old
/// vertices, edge points (mean of the ends) in `(min, max)` order, face points (mean of the
/// corners); Doo–Sabin corner `h` its vertex's weight.
fn carried_closed(s: Scheme, m: &OwnedMesh, ws: &[f64]) -> Vec<f64> {
    use nlsubdiv::mesh::refine::Pattern;
    let mean = |vs: &[u32]| vs.iter().map(|&v| ws[v as usize]).sum::<f64>() / vs.len() as f64;
    let edge_w: Vec<f64> = edges(m).iter().map(|&(a, b)| mean(&[a, b])).collect();
    let face_w: Vec<f64> = m.faces().iter().map(|f| mean(f)).collect();
    match s.pattern() {
        Pattern::Split1To4 => [ws, &edge_w[..]].concat(),
        Pattern::Quads => [ws, &edge_w[..], &face_w[..]].concat(),
        Pattern::VertexInsertion | Pattern::DualTruncation => [ws, &face_w[..]].concat(),
        Pattern::CornerCut => m.indices.iter().map(|&v| ws[v as usize]).collect(),
        Pattern::MidEdge => edge_w,
        Pattern::Dual => face_w,
        _ => panic!("a new pattern: {s:?}"),
    }
}

/// Every scheme, one level on a closed mesh with random weights: each output vertex is the
/// blend at the weight the documented carry rule gives it.
#[test]
fn every_pattern_carries_the_weights_as_documented() {
    for s in mobius_schemes() {
        let m = meshes(s).remove(0);
        let ws = random_weights(m.positions.len(), 0.0, 1.0, 23);
        let mob = Options::new(s).mobius(true);
        let (got, _) = weighted(&m, &mob, Some(&ws)).unwrap();
        let (lin, _) = run(&m, &Options::new(s)).unwrap();
        let (full, _) = run(&m, &mob).unwrap();
        let want_w = carried_closed(s, &m, &ws);
        assert_eq!(want_w.len(), got.positions.len(), "{s:?}");
        let scale = 1.0 + gap(&lin.positions, &vec![[0.0; 3]; lin.positions.len()]);
        for (i, w) in want_w.iter().enumerate() {
            let (p, l, q) = (got.positions[i], lin.positions[i], full.positions[i]);
            for k in 0..3 {
                let want = w * q[k] + (1.0 - w) * l[k];
                assert!((p[k] - want).abs() <= 1e-14 * scale, "{s:?} vertex {i}");
            }
        }
        assert!(gap(&full.positions, &lin.positions) > 1e-6, "{s:?}");
    }
}

/// The weight of an input vertex: 0 left of `x = 0.35`, 1 right of `x = 0.65`, a ramp between.
fn ramp(p: Point) -> f64 {
    ((p[0] - 0.35) / 0.3).clamp(0.0, 1.0)
}

#[test]
fn regions_of_weight_0_and_1_are_the_linear_and_the_mobius_output() {
    for s in mobius_schemes() {
        let m = if triangles(s) {
            bent(&tri_grid(30, 30), 41)
        } else {
            bent(&quad_grid(30, 30), 42)
        };
        let ws: Vec<f64> = m.positions.iter().map(|&p| ramp(p)).collect();
        let mob = Options::new(s).mobius(true).levels(2);
        let (got, _) = weighted(&m, &mob, Some(&ws)).unwrap();
        let (lin, _) = run(&m, &Options::new(s).levels(2)).unwrap();
        let (full, _) = run(&m, &mob).unwrap();
        let (mut left, mut right, mut between) = (0, 0, 0);
        for (i, l) in lin.positions.iter().enumerate() {
            let (p, q) = (got.positions[i], full.positions[i]);
            // Two levels of every rule reach less than 0.2 (six input edges) away.
            if l[0] < 0.15 {
                assert_eq!(p, *l, "{s:?} vertex {i} left");
                left += usize::from(gap(&[q], &[*l]) > 1e-9);
            } else if l[0] > 0.85 {
                assert_eq!(p, q, "{s:?} vertex {i} right");
                right += usize::from(gap(&[q], &[*l]) > 1e-9);
            } else if gap(&[p], &[*l]) > 1e-12 && gap(&[p], &[q]) > 1e-12 {
                between += 1;
            }
        }
        // The test could fail: the two outputs differ on both sides, and between them the
        // output is neither.
        assert!(left > 20 && right > 20, "{s:?}: {left} {right}");
        assert!(between > 20, "{s:?}: {between}");
    }
}

#[test]
fn the_output_is_continuous_in_the_weights() {
    for s in mobius_schemes() {
        for m in meshes(s) {
            let n = m.positions.len();
            let mob = Options::new(s).mobius(true).levels(2);
            let lin = run(&m, &Options::new(s).levels(2)).unwrap().0;
            let scale = gap(&lin.positions, &vec![[0.0; 3]; lin.positions.len()]);
            let ws = random_weights(n, 0.0, 1.0, 9);
            let near: Vec<f64> = ws
                .iter()
                .zip(random_weights(n, -1e-9, 1e-9, 10))
                .map(|(w, d)| (w + d).clamp(0.0, 1.0))
                .collect();
            let a = weighted(&m, &mob, Some(&ws)).unwrap().0;
            let b = weighted(&m, &mob, Some(&near)).unwrap().0;
            let g = gap(&a.positions, &b.positions) / scale;
            assert!(g < 1e-7, "{s:?}: {g:e}");
            // Toward the ends: weights within 1e-9 of 0 (of 1) give the linear (Möbius) output
            // within about as much.
            let tiny = random_weights(n, 0.0, 1e-9, 11);
            let almost: Vec<f64> = tiny.iter().map(|t| 1.0 - t).collect();
            let full = run(&m, &mob).unwrap().0;
            let g0 = gap(
                &weighted(&m, &mob, Some(&tiny)).unwrap().0.positions,
                &lin.positions,
            );
            let g1 = gap(
                &weighted(&m, &mob, Some(&almost)).unwrap().0.positions,
                &full.positions,
            );
            assert!(
                g0 / scale < 1e-7 && g1 / scale < 1e-7,
                "{s:?}: {g0:e} {g1:e}"
            );
            assert!(
                gap(&full.positions, &lin.positions) / scale > 1e-6,
                "{s:?}: Möbius and linear agree"
            );
        }
    }
}

#[test]
fn bad_weights_are_refused_naming_the_vertex_and_nothing_is_written() {
    let s = Scheme::CatmullClark;
    let m = meshes(s).remove(1);
    let n = m.positions.len();
    let mob = Options::new(s).mobius(true).levels(2);
    let good = vec![0.5; n];
    let mut su = vec![0u32; scheme::plan_scratch_size(&m.view()).unwrap()];
    let p = scheme::plan_weighted(
        m.view(),
        &mob,
        &Tags::new(),
        Some(VertexWeights::Mobius(&good)),
        &mut su,
    )
    .unwrap();
    su.resize(p.scratch.u32s, 0);
    let mut sp = vec![[0.0; 3]; p.scratch.points];
    let o = p.output();
    let mut pos = vec![[f64::NAN; 3]; o.vertices];
    let mut off = vec![u32::MAX; o.faces + 1];
    let mut idx = vec![u32::MAX; o.indices];
    let mut call = |w: &[f64]| {
        let plan = scheme::plan_weighted(
            m.view(),
            &mob,
            &Tags::new(),
            Some(VertexWeights::Mobius(w)),
            &mut su.clone(),
        );
        let e = scheme::subdivide_weighted(
            m.view(),
            &mob,
            &Tags::new(),
            Some(VertexWeights::Mobius(w)),
            Scratch::new(&mut su, &mut sp),
            &mut MeshOut::new(&mut pos, &mut off, &mut idx),
            &Serial,
        )
        .unwrap_err();
        assert_eq!(plan.unwrap_err(), e);
        e
    };
    for bad in [
        f64::NAN,
        -0.1,
        1.5,
        f64::INFINITY,
        f64::NEG_INFINITY,
        -1e-300,
    ] {
        let mut w = good.clone();
        w[7] = bad;
        w[9] = bad;
        assert_eq!(call(&w), Error::at(Status::InvalidArgument, 7), "{bad}");
    }
    for len in [0, n - 1, n + 1] {
        let e = call(&vec![0.5; len]);
        assert_eq!(e, Error::new(Status::InvalidArgument), "{len}");
        assert_eq!(e.element, NO_ELEMENT);
    }
    assert!(
        pos.iter().flatten().all(|x| x.is_nan()),
        "positions written"
    );
    assert!(
        off.iter().chain(&idx).all(|&x| x == u32::MAX),
        "faces written"
    );
    // The same buffers take the good weights.
    assert!(weighted(&m, &mob, Some(&good)).is_ok());
}

/// A closed crease around a torus (a grid line) and its tags.
fn creased(s: Scheme) -> (OwnedMesh, Vec<[u32; 2]>) {
    let m = if triangles(s) {
        jitter(&tri_torus(8, 6), 0.08, 51)
    } else {
        jitter(&quad_torus(8, 6, 3.0, 1.0), 0.08, 52)
    };
    let creases = (0..8u32).map(|i| [8 + i, 8 + (i + 1) % 8]).collect();
    (m, creases)
}

#[test]
fn weights_work_with_tags() {
    for s in [
        Scheme::Loop,
        Scheme::CatmullClark,
        Scheme::ModifiedButterfly,
        Scheme::Kobbelt,
    ] {
        let (m, creases) = creased(s);
        let sharp = vec![10.0; creases.len()];
        let tags = Tags::new().creases(&creases, &sharp);
        let n = m.positions.len();
        let mob = Options::new(s).mobius(true).levels(2);
        let tagged = |o: &Options, w: Option<&[f64]>| {
            run_weighted(&m, o, &tags, w.map(VertexWeights::Mobius), &Serial)
        };
        for w in [0.0, 1.0, 0.25, 0.6] {
            let ws = vec![w; n];
            assert_eq!(
                tagged(&mob, Some(&ws)).unwrap(),
                run_tagged(&m, &mob.spectrum(w), &tags).unwrap(),
                "{s:?} all {w}"
            );
        }
        assert_eq!(
            tagged(&mob.spectrum(0.3), None).unwrap(),
            run_tagged(&m, &mob.spectrum(0.3), &tags).unwrap(),
            "{s:?} none"
        );
        // One level, random weights: the old vertices blend at their own weights.
        let one = Options::new(s).mobius(true);
        let ws = random_weights(n, 0.0, 1.0, 13);
        let got = tagged(&one, Some(&ws)).unwrap().0;
        let lin = run_tagged(&m, &Options::new(s), &tags).unwrap().0;
        let full = run_tagged(&m, &one, &tags).unwrap().0;
        for (i, w) in ws.iter().enumerate() {
            let (p, l, q) = (got.positions[i], lin.positions[i], full.positions[i]);
            for k in 0..3 {
                let want = w * q[k] + (1.0 - w) * l[k];
                assert!(
                    (p[k] - want).abs() <= 1e-14 * (1.0 + want.abs()),
                    "{s:?} {i}"
                );
            }
        }
        assert!(gap(&got.positions, &full.positions) > 1e-6, "{s:?}");
        assert!(gap(&got.positions, &lin.positions) > 1e-6, "{s:?}");
    }
}
