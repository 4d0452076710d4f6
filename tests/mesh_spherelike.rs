//! Spherelike subdivision (seed 003 §3): the invariants the construction proves, checked on
//! generated nets and the shared meshes.
//!
//! `cargo test --release --test mesh_spherelike -- --nocapture` prints the measured figures.
#![allow(clippy::indexing_slicing, clippy::unwrap_used, clippy::expect_used)]

mod common;

use common::*;
use nlsubdiv::mesh::MeshOut;
use nlsubdiv::scheme::{self, Options, Scheme, Scratch};
use nlsubdiv::{Point, Status};
use std::f64::consts::PI;

const S: Scheme = Scheme::Spherelike;

fn dist(a: Point, b: Point) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// `n` sorted angles in `[lo, hi)`, unevenly spaced: gaps `(1 + 0.8·r)` for `r` in
/// `[-1, 1)` (gap ratio up to 9), scaled to the interval.
fn uneven(n: usize, lo: f64, hi: f64, closed: bool, rng: &mut Lcg) -> Vec<f64> {
    let gaps: Vec<f64> = (0..n).map(|_| 1.0 + 0.8 * rng.next()).collect();
    let used = if closed { n } else { n - 1 };
    let total: f64 = gaps[..used].iter().sum();
    let mut t = lo;
    let mut v = Vec::new();
    for g in gaps.iter().take(n) {
        v.push(t);
        t += (hi - lo) * g / total;
    }
    v
}

/// A grid net over parameters `us` (periodic) × `vs` (periodic when `v_closed`) on a surface
/// `f(u, v)`; vertex `(i, j)` has index `j·nu + i`.
fn grid_net(us: &[f64], vs: &[f64], v_closed: bool, f: &dyn Fn(f64, f64) -> Point) -> OwnedMesh {
    let (nu, nv) = (us.len(), vs.len());
    let id = |i: usize, j: usize| ((j % nv) * nu + (i % nu)) as u32;
    let mut p = Vec::new();
    for &v in vs {
        for &u in us {
            p.push(f(u, v));
        }
    }
    let rows = if v_closed { nv } else { nv - 1 };
    let mut faces = Vec::new();
    for j in 0..rows {
        for i in 0..nu {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    OwnedMesh::from_faces(p, &faces)
}

/// Parameters of the next level: the old ones with the arc middles (angle midpoints)
/// between neighbours inserted.
fn refine_params(t: &[f64], closed: bool) -> Vec<f64> {
    let n = t.len();
    let mut r = Vec::new();
    for i in 0..n {
        r.push(t[i]);
        if i + 1 < n {
            r.push(0.5 * (t[i] + t[i + 1]));
        } else if closed {
            r.push(0.5 * (t[i] + t[0] + 2.0 * PI));
        }
    }
    r
}

/// Grid coordinates of the vertices of the next level, in the output order of every primal
/// quad scheme (old vertices, edge points by `(min, max)` key, face points): old `(a, b)` go
/// to `(2a, 2b)`, edge and face points to the middle of their corners, modulo the periods
/// `pu`, `pv` of the next level (0 for an open direction).
fn refine_coords(m: &OwnedMesh, c: &[(i64, i64)], pu: i64, pv: i64) -> Vec<(i64, i64)> {
    let unwrap = |x: i64, r: i64, p: i64| {
        if p > 0 && x - r > p / 2 {
            x - p
        } else if p > 0 && r - x > p / 2 {
            x + p
        } else {
            x
        }
    };
    let wrap = |x: i64, p: i64| if p > 0 { x.rem_euclid(p) } else { x };
    let centre = |vs: &[u32]| {
        let r = (2 * c[vs[0] as usize].0, 2 * c[vs[0] as usize].1);
        let (mut su, mut sv) = (0, 0);
        for &v in vs {
            su += unwrap(2 * c[v as usize].0, r.0, pu);
            sv += unwrap(2 * c[v as usize].1, r.1, pv);
        }
        let k = vs.len() as i64;
        assert!(su % k == 0 && sv % k == 0);
        (wrap(su / k, pu), wrap(sv / k, pv))
    };
    let mut out: Vec<(i64, i64)> = c.iter().map(|&(a, b)| (2 * a, 2 * b)).collect();
    let mut edges = Vec::new();
    for f in m.faces() {
        for i in 0..f.len() {
            let (a, b) = (f[i], f[(i + 1) % f.len()]);
            edges.push((a.min(b), a.max(b)));
        }
    }
    edges.sort();
    edges.dedup();
    for (a, b) in edges {
        out.push(centre(&[a, b]));
    }
    for f in m.faces() {
        out.push(centre(&f));
    }
    out
}

/// Subdivides a grid net `levels` times and returns the largest distance of an output vertex
/// from the surface point at its grid parameters, relative to `scale`. The construction
/// proves that every row stays on its circle and every new point sits at the arc middle.
fn circle_rows_deviation(
    us: &[f64],
    vs: &[f64],
    v_closed: bool,
    f: &dyn Fn(f64, f64) -> Point,
    levels: usize,
    scale: f64,
) -> f64 {
    let mut m = grid_net(us, vs, v_closed, f);
    let (mut us, mut vs) = (us.to_vec(), vs.to_vec());
    let mut c: Vec<(i64, i64)> = (0..vs.len())
        .flat_map(|j| (0..us.len()).map(move |i| (i as i64, j as i64)))
        .collect();
    let mut worst = 0.0_f64;
    for _ in 0..levels {
        let next = subdivide(S, &m).unwrap();
        us = refine_params(&us, true);
        vs = refine_params(&vs, v_closed);
        let pu = us.len() as i64;
        let pv = if v_closed { vs.len() as i64 } else { 0 };
        c = refine_coords(&m, &c, pu, pv);
        assert_eq!(c.len(), next.positions.len());
        for (p, &(a, b)) in next.positions.iter().zip(&c) {
            let want = f(us[a as usize], vs[b as usize]);
            worst = worst.max(dist(*p, want) / scale);
        }
        m = next;
    }
    worst
}

#[test]
fn torus_rows_and_meridians_stay_on_their_circles() {
    let mut rng = Lcg(0x5eed_0006);
    let (big, small) = (3.0, 1.2);
    let torus = |u: f64, v: f64| {
        let r = big + small * v.cos();
        [r * u.cos(), r * u.sin(), small * v.sin()]
    };
    let mut worst = 0.0_f64;
    for _ in 0..3 {
        let us = uneven(7, 0.3, 0.3 + 2.0 * PI, true, &mut rng);
        let vs = uneven(6, -0.2, -0.2 + 2.0 * PI, true, &mut rng);
        worst = worst.max(circle_rows_deviation(
            &us,
            &vs,
            true,
            &torus,
            3,
            big + small,
        ));
    }
    println!("torus, uneven rows: max relative deviation from the circles {worst:.2e}");
    assert!(worst < 1e-12, "{worst:e}");
}

#[test]
fn open_sphere_band_rows_and_meridians_stay_on_their_circles() {
    let mut rng = Lcg(0x5eed_0106);
    let sphere = |u: f64, v: f64| [v.cos() * u.cos(), v.cos() * u.sin(), v.sin()];
    let mut worst = 0.0_f64;
    for _ in 0..3 {
        let us = uneven(8, 0.1, 0.1 + 2.0 * PI, true, &mut rng);
        let vs = uneven(5, -1.1, 1.2, false, &mut rng);
        worst = worst.max(circle_rows_deviation(&us, &vs, false, &sphere, 3, 1.0));
    }
    println!("sphere band, uneven rows (open ends): max relative deviation {worst:.2e}");
    assert!(worst < 1e-12, "{worst:e}");
}

/// Generated meshes of every kind the scheme accepts: quads, odd and even n-gons, odd and
/// even valences, boundaries.
fn generated() -> Vec<(String, OwnedMesh)> {
    vec![
        ("cube".to_string(), cube()),
        ("tetrahedron".to_string(), tetrahedron()),
        ("octahedron".to_string(), octahedron()),
        ("prism5".to_string(), prism(5)),
        ("prism6".to_string(), prism(6)),
        ("bipyramid5".to_string(), bipyramid(5)),
        ("fan6".to_string(), fan(6)),
        ("quad_grid".to_string(), jitter(&quad_grid(4, 3), 0.05, 7)),
        (
            "torus".to_string(),
            jitter(&quad_torus(6, 5, 3.0, 1.0), 0.05, 8),
        ),
    ]
}

/// The generated meshes and seven shared ones (`test` names the caller for the skip report
/// when those are missing).
fn assorted(test: &str) -> Vec<(String, OwnedMesh)> {
    let mut v = generated();
    if let Some(dir) = shared_meshes_partly(test, "the shared meshes (cube.off, ...)") {
        for name in [
            "cube.off",
            "house_pentagons.off",
            "hexagon_pyramid.off",
            "pyramid_mixed.off",
            "torus_quad.off",
            "dome_polygon_pattern.off",
            "vase_quad.off",
        ] {
            let path = dir.join(name);
            match read_off(&path) {
                Ok(m) => v.push((name.to_string(), m)),
                Err(e) => skip(
                    test,
                    &format!("{} not readable ({e}); not checked", path.display()),
                ),
            }
        }
    }
    v
}

#[test]
fn old_vertices_are_kept_bit_for_bit_at_every_level() {
    let mut runs = 0;
    for (name, m) in assorted("mesh_spherelike::old_vertices_are_kept_bit_for_bit_at_every_level") {
        let mut cur = m;
        for level in 1..=3 {
            if cur.indices.len() > 400_000 {
                break;
            }
            let next = match subdivide(S, &cur) {
                Ok(n) => n,
                Err(e) => panic!("{name} level {level}: {e}"),
            };
            for (v, (a, b)) in cur.positions.iter().zip(&next.positions).enumerate() {
                assert!(
                    a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits()),
                    "{name} level {level} vertex {v}"
                );
            }
            assert!(next.positions.iter().flatten().all(|x| x.is_finite()));
            runs += 1;
            cur = next;
        }
    }
    println!("old vertices bit-exact: {runs} steps");
}

#[test]
fn connectivity_and_sizes_are_catmull_clarks() {
    for (name, m) in assorted("mesh_spherelike::connectivity_and_sizes_are_catmull_clarks") {
        let a = subdivide(S, &m).unwrap();
        let b = subdivide(Scheme::CatmullClark, &m).unwrap();
        assert_eq!((&a.offsets, &a.indices), (&b.offsets, &b.indices), "{name}");
        assert_eq!(a.positions.len(), b.positions.len(), "{name}");
    }
}

#[test]
fn multi_level_call_is_the_chain_of_one_level_calls() {
    for (name, m) in generated() {
        let levels = 3;
        let (out, _) = run(&m, &Options::new(S).levels(levels)).unwrap();
        let chain = subdivide_n(S, &m, levels).unwrap();
        assert_eq!(hash(&out), hash(&chain), "{name}");
    }
}

/// A similarity `x ↦ s·R·x + t` (rotation about an oblique axis).
fn similarity(p: Point) -> Point {
    let (c, s) = (0.6_f64, 0.8_f64); // rotation by atan2(0.8, 0.6) about z, then about x
    let q = [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]];
    let r = [q[0], c * q[1] - s * q[2], s * q[1] + c * q[2]];
    let k = 2.5;
    [k * r[0] + 1.0, k * r[1] - 3.0, k * r[2] + 0.5]
}

#[test]
fn commutes_with_similarities() {
    // Circles, tangents and arc middles are similarity-invariant, so is every choice of the
    // rule (farthest vertex, straight continuation).
    let mut worst = 0.0_f64;
    for (name, m) in generated() {
        let a = subdivide_n(S, &m.map_positions(similarity), 2).unwrap();
        let b = subdivide_n(S, &m, 2).unwrap().map_positions(similarity);
        let size = b
            .positions
            .iter()
            .map(|p| dist(*p, b.positions[0]))
            .fold(0.0, f64::max);
        for (p, q) in a.positions.iter().zip(&b.positions) {
            let d = dist(*p, *q) / size;
            assert!(d < 1e-12, "{name}: {d:e}");
            worst = worst.max(d);
        }
    }
    println!("similarity commutation: max relative difference {worst:.2e}");
}

#[test]
fn planar_nets_stay_planar_and_straight_lines_stay_straight() {
    // Circle blends of coplanar points stay in the plane; collinear points give midpoints.
    let flat = jitter(&quad_grid(5, 4), 0.1, 3).map_positions(|p| [p[0], p[1], 0.0]);
    let out = subdivide_n(S, &flat, 2).unwrap();
    assert!(out.positions.iter().all(|p| p[2] == 0.0));
    let grid = quad_grid(4, 4).map_positions(|p| [p[0], p[1], 0.0]);
    let out = subdivide(S, &grid).unwrap();
    let nv = grid.positions.len();
    let mut edges = Vec::new();
    for f in grid.faces() {
        for i in 0..4 {
            let (a, b) = (f[i], f[(i + 1) % 4]);
            edges.push((a.min(b), a.max(b)));
        }
    }
    edges.sort();
    edges.dedup();
    let corners = [0, 4, 20, 24]; // their boundary curve turns a corner: not a line
    for (e, (a, b)) in edges.iter().enumerate() {
        if corners.contains(a) || corners.contains(b) {
            continue;
        }
        let (pa, pb) = (grid.positions[*a as usize], grid.positions[*b as usize]);
        let mid = [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1]), 0.0];
        assert!(dist(out.positions[nv + e], mid) < 1e-14, "edge {e}");
    }
}

#[test]
fn regular_polygon_faces_get_their_centre() {
    // A flat regular n-gon with an even or odd number of sides: the n/2 or n curve
    // applications are symmetric images of each other, so their average is the centre.
    for n in [3, 4, 5, 6, 7, 8] {
        let mut p = Vec::new();
        for i in 0..n {
            let t = 2.0 * PI * i as f64 / n as f64;
            p.push([t.cos() + 2.0, t.sin() - 1.0, 0.0]);
        }
        let m = OwnedMesh::from_faces(p, &[(0..n as u32).collect()]);
        let out = subdivide(S, &m).unwrap();
        let c = *out.positions.last().unwrap();
        assert!(dist(c, [2.0, -1.0, 0.0]) < 1e-14, "{n}: {c:?}");
    }
}

#[test]
fn degenerate_inputs_give_statuses() {
    // Two coincident vertices: the circle through them is undefined; the error names the
    // output vertex of the first edge whose rule needs that circle (edge (0, 1), id 0).
    let mut m = cube();
    m.positions[1] = m.positions[0];
    let e = subdivide(S, &m).unwrap_err();
    assert_eq!(
        (e.status, e.element),
        (Status::DegenerateGeometry, 8),
        "{e}"
    );
    // The multi-level call reports it too and the size query still succeeds (sizes do not
    // depend on geometry).
    assert!(subdivide_n(S, &m, 2).is_err());
    let mut sc = vec![0u32; scheme::plan_scratch_size(&m.view()).unwrap()];
    assert!(scheme::plan(m.view(), &Options::new(S), &mut sc).is_ok());
    // The same on an open grid (vertices 4 and 5 are neighbours in the first inner row).
    let mut grid = quad_grid(3, 3);
    grid.positions[5] = grid.positions[4];
    let e = subdivide(S, &grid).unwrap_err();
    assert_eq!(e.status, Status::DegenerateGeometry);
    // Non-finite coordinates are refused by validation.
    let mut bad = cube();
    bad.positions[3][1] = f64::NAN;
    assert_eq!(
        subdivide(S, &bad).unwrap_err().status,
        Status::NonFiniteInput
    );
    // Overflowing coordinates: NumericalFailure or DegenerateGeometry, never infinities.
    let huge = cube().map_positions(|p| [p[0] * 1e300, p[1] * 1e300, p[2] * 1e300]);
    match subdivide(S, &huge) {
        Ok(out) => assert!(out.positions.iter().flatten().all(|x| x.is_finite())),
        Err(e) => assert!(
            matches!(
                e.status,
                Status::NumericalFailure | Status::DegenerateGeometry
            ),
            "{e}"
        ),
    }
    // No Möbius form.
    let e = mobius_subdivide(S, &cube(), false).unwrap_err();
    assert_eq!(e.status, Status::InvalidArgument);
    assert!(!S.has_mobius_form() && S.is_interpolating());
}

#[test]
fn short_output_buffers_are_refused_before_any_write() {
    let m = prism(5);
    let opts = Options::new(S);
    let mut sc = vec![0u32; scheme::plan_scratch_size(&m.view()).unwrap()];
    let sizes = scheme::plan(m.view(), &opts, &mut sc).unwrap().output();
    let mut pos = vec![[7.0; 3]; sizes.vertices - 1];
    let mut off = vec![9u32; sizes.faces + 1];
    let mut idx = vec![9u32; sizes.indices];
    let e = scheme::subdivide(
        m.view(),
        &opts,
        Scratch::new(&mut sc, &mut []),
        &mut MeshOut::new(&mut pos, &mut off, &mut idx),
    )
    .unwrap_err();
    assert_eq!(
        (e.status, e.needed),
        (Status::BufferTooSmall, sizes.vertices)
    );
    assert!(pos.iter().flatten().all(|&x| x == 7.0));
    assert!(off.iter().chain(&idx).all(|&x| x == 9));
}

#[test]
fn names_and_codes() {
    assert_eq!(S.code(), 9);
    assert_eq!(Scheme::from_code(9), Some(S));
    assert_eq!(Scheme::from_name("spherelike"), Some(S));
    assert_eq!(S.name(), "spherelike");
    assert!(Scheme::ALL.contains(&S));
}

#[test]
fn result_does_not_depend_on_vertex_numbering() {
    // Every choice of the rule (the spoke n/2 steps round, the central face, the tie among
    // equally far corners: the first counter-clockwise after V1) is defined by the geometry
    // and the orientation, not by vertex ids. Ties happen at the valence-5 poles of the
    // bipyramid (isosceles central triangles). Up to rounding (summation order of edge ends).
    let mut worst = 0.0_f64;
    for (name, m) in generated() {
        let renumbered = renumbered(&m, m.positions.len() as u64);
        let a = subdivide_n(S, &m, 2).unwrap().positions;
        let b = subdivide_n(S, &renumbered, 2).unwrap().positions;
        assert_eq!(a.len(), b.len());
        // Same point sets: every point of one has a partner in the other (and back).
        for (x, y) in [(&a, &b), (&b, &a)] {
            for p in x.iter() {
                let d = y.iter().map(|q| dist(*p, *q)).fold(f64::MAX, f64::min);
                assert!(d < 1e-12, "{name}: {d:e}");
                worst = worst.max(d);
            }
        }
    }
    println!("renumbering: max difference {worst:.2e}");
}
