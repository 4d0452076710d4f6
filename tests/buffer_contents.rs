//! The output of a call depends on its inputs only: not on what the caller's output and
//! scratch buffers held before the call (a C host passes `malloc`ed memory, a Rust host may
//! reuse the buffers of an earlier call), and one call of several levels equals the chain of
//! one-level calls bit for bit. Every scheme, linear and Möbius (default fold guard, paper
//! literal, a spectrum weight), with and without sharp-feature tags, on small meshes with
//! boundaries, mixed face sizes and an isolated vertex: the guard's audits read the step's
//! output points, so a point read before the step writes it shows up here as a difference
//! between fills.

// Test helpers outside #[test] functions: clippy's in-test allowances do not reach them.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]

mod common;

use common::{fan, jitter, prism, quad_grid, tri_grid, OwnedMesh};
use nlsubdiv::mesh::MeshOut;
use nlsubdiv::scheme::{self, Options, Report, Scheme, Scratch, Tags};
use nlsubdiv::{Point, Result};

/// What the buffers hold before the call.
#[derive(Clone, Copy, Debug)]
enum Fill {
    /// NaN positions, `u32::MAX` indices, zero scratch (what `common::run` passes).
    Nan,
    /// All zero (a `calloc`ed host buffer).
    Zero,
    /// Finite values that look like plausible points and indices.
    Pattern,
}

const FILLS: [Fill; 3] = [Fill::Nan, Fill::Zero, Fill::Pattern];

/// `plan_tagged`, then `subdivide_tagged`, on buffers of exactly the planned sizes filled
/// as `fill` says (the `u32` scratch beyond the plan's own part too).
fn run_filled(
    m: &OwnedMesh,
    opts: &Options,
    tags: &Tags<'_>,
    fill: Fill,
) -> Result<(OwnedMesh, Report)> {
    let mut su = vec![0u32; scheme::plan_scratch_size_tagged(&m.view(), tags)?];
    let p = scheme::plan_tagged(m.view(), opts, tags, &mut su)?;
    let o = p.output();
    let (point, index, scratch_u32, scratch_point): (Point, u32, u32, Point) = match fill {
        Fill::Nan => ([f64::NAN; 3], u32::MAX, 0, [0.0; 3]),
        Fill::Zero => ([0.0; 3], 0, 0, [0.0; 3]),
        Fill::Pattern => ([0.75, -0.5, 1.25], 1, 0x0000_0003, [1.0, 0.5, -2.0]),
    };
    su.resize(p.scratch.u32s, scratch_u32);
    let mut sp = vec![scratch_point; p.scratch.points];
    let mut out = OwnedMesh {
        positions: vec![point; o.vertices],
        offsets: vec![index; o.faces + 1],
        indices: vec![index; o.indices],
    };
    let report = scheme::subdivide_tagged(
        m.view(),
        opts,
        tags,
        Scratch::new(&mut su, &mut sp),
        &mut MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices),
    )?;
    Ok((out, report))
}

/// A steep open hexagonal pyramid (its apex high above the rim): the boundary stars' forms
/// fold, so the fold guard acts at every level.
fn steep_pyramid() -> OwnedMesh {
    let mut p = vec![[0.0, 0.0, 2.0]];
    for i in 0..6 {
        let t = core::f64::consts::PI * i as f64 / 3.0;
        p.push([libm::cos(t), libm::sin(t), 0.0]);
    }
    let faces: Vec<Vec<u32>> = (0..6u32).map(|i| vec![0, 1 + i, 1 + (i + 1) % 6]).collect();
    OwnedMesh::from_faces(p, &faces)
}

/// A closed hexagonal prism (two hexagons, six quads) and one isolated vertex.
fn prism_and_isolated_vertex() -> OwnedMesh {
    let m = jitter(&prism(6), 0.05, 11);
    let mut positions = m.positions.clone();
    positions.push([3.0, 0.0, 0.0]);
    OwnedMesh::from_faces(positions, &m.faces())
}

fn meshes() -> Vec<(&'static str, OwnedMesh)> {
    vec![
        ("steep pyramid", steep_pyramid()),
        ("wavy fan", fan(7)),
        ("tri grid", jitter(&tri_grid(4, 3), 0.2, 3)),
        ("quad grid", jitter(&quad_grid(4, 3), 0.25, 5)),
        ("prism + isolated vertex", prism_and_isolated_vertex()),
    ]
}

/// The option sets tried for `s`: linear, and where it has a Möbius form the default
/// (guarded), the paper-literal and a spectrum weight.
fn option_sets(s: Scheme, levels: usize) -> Vec<Options> {
    let linear = Options::new(s).levels(levels);
    if !s.has_mobius_form() {
        return vec![linear];
    }
    let mobius = linear.mobius(true);
    vec![linear, mobius, mobius.literal(true), mobius.spectrum(0.4)]
}

/// Two interior edges of `m` (each shared by two faces), as crease tags.
fn two_interior_edges(m: &OwnedMesh) -> Vec<[u32; 2]> {
    let mut seen = std::collections::BTreeMap::new();
    for f in m.faces() {
        for i in 0..f.len() {
            let (a, b) = (f[i], f[(i + 1) % f.len()]);
            *seen.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    seen.into_iter()
        .filter(|&(_, n)| n == 2)
        .map(|((a, b), _)| [a, b])
        .take(2)
        .collect()
}

#[test]
fn output_does_not_depend_on_what_the_buffers_held() {
    let mut runs = 0;
    for s in Scheme::ALL {
        for (name, m) in meshes() {
            let creases = two_interior_edges(&m);
            let sharpness = vec![f64::INFINITY; creases.len()];
            let tagged = Tags::new().creases(&creases, &sharpness);
            for levels in 1..=3 {
                for opts in option_sets(s, levels) {
                    for tags in [Tags::new(), tagged] {
                        let first = run_filled(&m, &opts, &tags, Fill::Nan);
                        if first.is_err() && levels == 1 {
                            // The scheme refuses this mesh (face sizes): nothing to compare.
                            continue;
                        }
                        for fill in &FILLS[1..] {
                            let other = run_filled(&m, &opts, &tags, *fill);
                            match (&first, &other) {
                                (Ok((a, ra)), Ok((b, rb))) => {
                                    assert!(
                                        a.positions
                                            .iter()
                                            .zip(&b.positions)
                                            .all(|(p, q)| (0..3).all(|k| p[k].to_bits() == q[k].to_bits())),
                                        "{s:?} {name} {opts:?}: positions differ with {fill:?} buffers"
                                    );
                                    assert_eq!((&a.offsets, &a.indices), (&b.offsets, &b.indices));
                                    assert_eq!(ra, rb, "{s:?} {name} {opts:?}: report, {fill:?}");
                                }
                                (Err(e), Err(f)) => assert_eq!(e, f, "{s:?} {name} {opts:?}"),
                                _ => panic!(
                                    "{s:?} {name} {opts:?}: {fill:?} buffers change the status"
                                ),
                            }
                        }
                        runs += 1;
                    }
                }
            }
        }
    }
    // 10 schemes, most of them on most meshes: a bound that fails if the loop skips them.
    assert!(runs > 400, "only {runs} comparisons ran");
}

#[test]
fn levels_in_one_call_are_the_chain_of_one_level_calls() {
    let mut runs = 0;
    for s in Scheme::ALL {
        for (name, m) in meshes() {
            for opts in option_sets(s, 3) {
                let Ok((all, report)) = run_filled(&m, &opts, &Tags::new(), Fill::Nan) else {
                    continue;
                };
                let mut cur = m.clone();
                let (mut guarded, mut fallbacks) = (0, 0);
                for _ in 0..3 {
                    let (next, r) =
                        run_filled(&cur, &opts.levels(1), &Tags::new(), Fill::Nan).unwrap();
                    guarded += r.guarded;
                    fallbacks += r.fallbacks;
                    cur = next;
                }
                let bits = |m: &OwnedMesh| -> Vec<u64> {
                    m.positions
                        .iter()
                        .flat_map(|p| p.map(f64::to_bits))
                        .collect()
                };
                assert_eq!(bits(&all), bits(&cur), "{s:?} {name} {opts:?}: positions");
                assert_eq!((&all.offsets, &all.indices), (&cur.offsets, &cur.indices));
                assert_eq!(
                    (report.guarded, report.fallbacks),
                    (guarded, fallbacks),
                    "{s:?} {name} {opts:?}: counts"
                );
                runs += 1;
            }
        }
    }
    assert!(runs > 60, "only {runs} comparisons ran");
}
