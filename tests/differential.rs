//! Differential-space subdivision (seed 001): k = 0 reproduces the control mesh, the solved
//! system's residual is below the tolerance, translation invariance, agreement with an
//! independent dense least-squares solve, editing, metrics and statuses.
#![allow(
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::needless_range_loop
)]

mod common;

use common::*;
use nlsubdiv::differential::metrics::thin_plate_energy;
use nlsubdiv::differential::solve::SolveOptions;
use nlsubdiv::differential::{DifferentialOptions, Stencil};
use nlsubdiv::scheme::Scheme;
use nlsubdiv::{Point, Status};
use std::collections::BTreeSet;

fn closed() -> OwnedMesh {
    jitter(&subdivide(Scheme::Loop, &octahedron()).unwrap(), 0.05, 7)
}

fn open() -> OwnedMesh {
    jitter(&tri_grid(4, 3), 0.05, 3).map_positions(|p| [p[0], p[1], 0.3 * p[0] * p[1]])
}

fn opts(stencil: Stencil, levels: usize) -> DifferentialOptions<'static> {
    DifferentialOptions {
        stencil,
        levels,
        ..Default::default()
    }
}

fn diameter(p: &[Point]) -> f64 {
    let mut d = 0.0f64;
    for a in p {
        for b in p {
            d = d.max(dist(*a, *b));
        }
    }
    d
}

fn dist(a: Point, b: Point) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Rings and boundary neighbours computed here from the faces with std collections.
fn rows_of(m: &OwnedMesh) -> Vec<Vec<usize>> {
    let n = m.positions.len();
    let mut nb = vec![BTreeSet::new(); n];
    let mut directed = BTreeSet::new();
    for f in m.faces() {
        for i in 0..f.len() {
            let (a, b) = (f[i] as usize, f[(i + 1) % f.len()] as usize);
            nb[a].insert(b);
            nb[b].insert(a);
            directed.insert((a, b));
        }
    }
    let mut bnd = vec![Vec::new(); n];
    for &(a, b) in &directed {
        if !directed.contains(&(b, a)) {
            bnd[a].push(b);
            bnd[b].push(a);
        }
    }
    (0..n)
        .map(|i| {
            if bnd[i].is_empty() {
                nb[i].iter().copied().collect()
            } else {
                bnd[i].clone()
            }
        })
        .collect()
}

fn apply_l(rows: &[Vec<usize>], x: &[Point]) -> Vec<Point> {
    rows.iter()
        .enumerate()
        .map(|(i, r)| {
            let w = 1.0 / r.len() as f64;
            let mut s = x[i];
            for &j in r {
                for c in 0..3 {
                    s[c] -= w * x[j][c];
                }
            }
            s
        })
        .collect()
}

/// The paper's least-squares problem solved densely: normal equations with an anchor at
/// vertex 0 by Gaussian elimination with partial pivoting, then the centroid placement.
fn dense_reference(control: &OwnedMesh, stencil: Scheme, k: usize) -> Vec<Point> {
    let d0 = apply_l(&rows_of(control), &control.positions);
    let dk = subdivide_n(
        stencil,
        &OwnedMesh {
            positions: d0,
            ..control.clone()
        },
        k,
    )
    .unwrap();
    let spatial = subdivide_n(stencil, control, k).unwrap();
    let rows = rows_of(&dk);
    let n = rows.len();
    let mut l = vec![vec![0.0; n]; n];
    for (i, r) in rows.iter().enumerate() {
        l[i][i] = 1.0;
        for &j in r {
            l[i][j] -= 1.0 / r.len() as f64;
        }
    }
    let c = 0.25f64.powi(k as i32);
    let mut a = vec![vec![0.0; n + 3]; n];
    for i in 0..n {
        for j in 0..n {
            a[i][j] = (0..n).map(|r| l[r][i] * l[r][j]).sum();
        }
        for d in 0..3 {
            a[i][n + d] = (0..n).map(|r| l[r][i] * c * dk.positions[r][d]).sum();
        }
    }
    a[0][0] += 1.0;
    for d in 0..3 {
        a[0][n + d] += spatial.positions[0][d];
    }
    for col in 0..n {
        let piv = (col..n)
            .max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))
            .unwrap();
        a.swap(col, piv);
        for r in 0..n {
            if r != col {
                let f = a[r][col] / a[col][col];
                if f != 0.0 {
                    for j in col..n + 3 {
                        a[r][j] -= f * a[col][j];
                    }
                }
            }
        }
    }
    let mut v: Vec<Point> = (0..n)
        .map(|i| {
            [
                a[i][n] / a[i][i],
                a[i][n + 1] / a[i][i],
                a[i][n + 2] / a[i][i],
            ]
        })
        .collect();
    let mean = |p: &[Point]| {
        let mut s = [0.0; 3];
        for q in p {
            for d in 0..3 {
                s[d] += q[d] / p.len() as f64;
            }
        }
        s
    };
    let (ms, mv) = (mean(&spatial.positions), mean(&v));
    for p in &mut v {
        for d in 0..3 {
            p[d] += ms[d] - mv[d];
        }
    }
    v
}

#[test]
fn matches_an_independent_dense_least_squares_solve() {
    for (name, m) in [("closed", closed()), ("open", open())] {
        for (st, sc) in [
            (Stencil::Loop, Scheme::Loop),
            (Stencil::ModifiedButterfly, Scheme::ModifiedButterfly),
        ] {
            for k in 1..=2 {
                let (out, rep) = differential_subdivide(&m, &opts(st, k)).unwrap();
                let want = dense_reference(&m, sc, k);
                let diam = diameter(&out.positions);
                let err = out
                    .positions
                    .iter()
                    .zip(&want)
                    .map(|(a, b)| dist(*a, *b))
                    .fold(0.0, f64::max);
                println!("{name} {st:?} k={k}: {} V, max |ours − dense| / diam = {:.2e}, {} it, residual {:.1e}",
                    want.len(), err / diam, rep.solve.iterations, rep.solve.relative_residual);
                assert!(err <= 1e-7 * diam, "{name} {st:?} k={k}: {err}");
            }
        }
    }
}

#[test]
fn residual_is_below_the_tolerance() {
    for tol in [1e-6, 1e-10] {
        let mut o = opts(Stencil::Loop, 3);
        o.solve.tolerance = tol;
        let (out, rep) = differential_subdivide(&closed(), &o).unwrap();
        assert!(rep.solve.converged && rep.solve.relative_residual <= tol);
        assert_eq!(out.positions.len(), 1026);
    }
}

#[test]
fn zero_levels_reproduce_the_control_mesh() {
    for m in [closed(), open()] {
        for st in [Stencil::Loop, Stencil::ModifiedButterfly] {
            let (out, _) = differential_subdivide(&m, &opts(st, 0)).unwrap();
            let diam = diameter(&m.positions);
            for (a, b) in out.positions.iter().zip(&m.positions) {
                assert!(dist(*a, *b) <= 1e-12 * diam);
            }
            assert_eq!(
                (out.offsets, out.indices),
                (m.offsets.clone(), m.indices.clone())
            );
        }
    }
}

#[test]
fn closed_results_are_translation_invariant() {
    let m = closed();
    let t = [10.0, -3.0, 5.0];
    let moved = m.map_positions(|p| [p[0] + t[0], p[1] + t[1], p[2] + t[2]]);
    for st in [Stencil::Loop, Stencil::ModifiedButterfly] {
        let mut o = opts(st, 2);
        o.dirmag_levels = usize::from(st == Stencil::ModifiedButterfly);
        let (a, _) = differential_subdivide(&m, &o).unwrap();
        let (b, _) = differential_subdivide(&moved, &o).unwrap();
        let diam = diameter(&a.positions);
        for (p, q) in a.positions.iter().zip(&b.positions) {
            let back = [q[0] - t[0], q[1] - t[1], q[2] - t[2]];
            assert!(dist(*p, back) <= 1e-8 * diam, "{st:?}");
        }
    }
}

#[test]
fn zero_curvature_collapses_to_the_centroid_and_unit_scale_changes_nothing() {
    let m = closed();
    let zeros = vec![0.0; m.positions.len()];
    let ones = vec![1.0; m.positions.len()];
    let mut o = opts(Stencil::Loop, 2);
    let (plain, _) = differential_subdivide(&m, &o).unwrap();
    o.curvature_scale = Some(&ones);
    let (same, _) = differential_subdivide(&m, &o).unwrap();
    assert_eq!(plain, same);
    o.curvature_scale = Some(&zeros);
    let (flat, _) = differential_subdivide(&m, &o).unwrap();
    let spatial = subdivide_n(Scheme::Loop, &m, 2).unwrap();
    let n = spatial.positions.len() as f64;
    let c: Vec<f64> = (0..3)
        .map(|d| spatial.positions.iter().map(|p| p[d]).sum::<f64>() / n)
        .collect();
    for p in &flat.positions {
        assert!(dist(*p, [c[0], c[1], c[2]]) < 1e-9);
    }
}

#[test]
fn statuses() {
    let m = closed();
    // Quads.
    let e = differential_subdivide(&cube(), &opts(Stencil::Loop, 1))
        .unwrap_err()
        .0;
    assert_eq!((e.status, e.element), (Status::UnsupportedFaceType, 0));
    // Too many levels, bad tolerance, edit of the wrong length, non-finite edit.
    let e = differential_subdivide(&m, &opts(Stencil::Loop, 17))
        .unwrap_err()
        .0;
    assert_eq!(e.status, Status::InvalidArgument);
    let mut o = opts(Stencil::Loop, 1);
    o.solve.tolerance = f64::NAN;
    assert_eq!(
        differential_subdivide(&m, &o).unwrap_err().0.status,
        Status::InvalidArgument
    );
    let short = vec![1.0; 3];
    let mut o = opts(Stencil::Loop, 1);
    o.curvature_scale = Some(&short);
    assert_eq!(
        differential_subdivide(&m, &o).unwrap_err().0.status,
        Status::InvalidArgument
    );
    let mut bad = vec![1.0; m.positions.len()];
    bad[4] = f64::INFINITY;
    o.curvature_scale = Some(&bad);
    let e = differential_subdivide(&m, &o).unwrap_err().0;
    assert_eq!((e.status, e.element), (Status::NonFiniteInput, 4));
    // Non-convergence: one iteration at 1e-14, the report says how far it got.
    let mut o = opts(Stencil::Loop, 3);
    o.solve = SolveOptions {
        tolerance: 1e-14,
        max_iterations: 1,
        ..SolveOptions::default()
    };
    let (e, rep) = differential_subdivide(&m, &o).unwrap_err();
    assert_eq!(e.status, Status::NotConverged);
    assert_eq!(rep.solve.iterations, 1);
    assert!(rep.solve.relative_residual > 1e-14 && rep.solve.relative_residual.is_finite());
    // Too-small scratch: the needed size is reported.
    use nlsubdiv::differential as d;
    let o = opts(Stencil::Loop, 1);
    let mut ps = vec![0u32; d::plan_scratch_size(&m.view()).unwrap()];
    let plan = d::plan(m.view(), &o, &mut ps).unwrap();
    let out = plan.output();
    let mut su = vec![0u32; plan.scratch_u32];
    let mut sp = vec![[0.0; 3]; plan.scratch_points - 1];
    let (mut p, mut of, mut ix) = (
        vec![[0.0; 3]; out.vertices],
        vec![0u32; out.faces + 1],
        vec![0u32; out.indices],
    );
    let mut mo = nlsubdiv::mesh::MeshOut::new(&mut p, &mut of, &mut ix);
    let mut rep = d::DifferentialReport::default();
    let e = d::subdivide(m.view(), &o, &mut su, &mut sp, &mut mo, &mut rep).unwrap_err();
    assert_eq!(
        (e.status, e.needed),
        (Status::BufferTooSmall, plan.scratch_points)
    );
}

fn thin_plate(m: &OwnedMesh) -> f64 {
    with_topology(m, |t| {
        let mut s = vec![[0.0; 3]; m.positions.len()];
        thin_plate_energy(t, &mut s).unwrap()
    })
    .unwrap()
}

#[test]
fn thin_plate_energy_of_a_sphere_is_two_over_r_squared() {
    let mut m = icosahedron();
    for _ in 0..4 {
        m = subdivide(Scheme::Loop, &m).unwrap().map_positions(|p| {
            let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            [p[0] / l, p[1] / l, p[2] / l]
        });
    }
    let e = thin_plate(&m);
    println!("unit sphere: E = {e}");
    assert!((e - 2.0).abs() < 0.05 * 2.0, "{e}");
    let big = m.map_positions(|p| [3.0 * p[0], 3.0 * p[1], 3.0 * p[2]]);
    let eb = thin_plate(&big);
    assert!((eb * 9.0 - e).abs() <= 1e-12 * e);
}

/// Seed 001 §4.3 measures `∫(κ₁² + κ₂²) / ∫1`. On the torus of radii `R > r`
/// (`κ₁ = 1/r`, `κ₂ = cos θ / (R + r cos θ)`, `dA = r (R + r cos θ) dθ dφ`) this is
/// `R / (r² √(R² − r²))`. Unlike the sphere, the torus is not umbilic (κ₁ ≠ κ₂, `K < 0` on
/// its inner half): an estimator returning `2H²`, exact on the sphere, gives half this value
/// here (`∫4H² = ∫(κ₁² + κ₂²) + 2∫K` and `∫K = 0`).
#[test]
fn thin_plate_energy_of_a_torus_matches_the_analytic_value() {
    let (big, small) = (3.0f64, 1.0f64);
    let exact = big / (small * small * (big * big - small * small).sqrt());
    let m = tri_torus(96, 32); // radii 3 and 1 (tests/common)
    let e = thin_plate(&m);
    println!("torus R = 3, r = 1 (96 × 32): E = {e}, analytic {exact}");
    assert!((e - exact).abs() < 1e-3 * exact, "{e} vs {exact}");
    // Finer sampling gets closer (the estimate converges).
    let ef = thin_plate(&tri_torus(192, 64));
    assert!((ef - exact).abs() < (e - exact).abs(), "{ef} vs {e}");
}

// ---------------------------------------------------------------- §4.4 editing

/// The unit vector of `a`.
fn unit(a: Point) -> Point {
    let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

fn cross3(a: Point, b: Point) -> Point {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot3(a: Point, b: Point) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub3(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The angle between two vectors (radians, `atan2` form, accurate near 0 and π).
fn angle_between(a: Point, b: Point) -> f64 {
    let c = cross3(a, b);
    dot3(c, c).sqrt().atan2(dot3(a, b))
}

/// `v` rotated about the unit `axis` by `t` radians (Rodrigues), written here.
fn rotate(v: Point, axis: Point, t: f64) -> Point {
    let (s, c) = t.sin_cos();
    let kxv = cross3(axis, v);
    let kd = dot3(axis, v);
    [0, 1, 2].map(|i| v[i] * c + kxv[i] * s + axis[i] * kd * (1.0 - c))
}

/// The surface normal at vertex `v` as docs/differential.md defines it: the angle-weighted
/// normal of its star (Σ corner angle × unit face normal, normalised), computed here from the
/// face list.
fn vertex_normal(m: &OwnedMesh, v: usize) -> Point {
    let mut s = [0.0; 3];
    for f in m.faces() {
        let Some(k) = f.iter().position(|&x| x as usize == v) else {
            continue;
        };
        let p = |i: usize| m.positions[f[i % f.len()] as usize];
        let (a, b, c) = (p(k), p(k + 1), p(k + f.len() - 1));
        let n = unit(cross3(sub3(b, a), sub3(c, a)));
        let w = angle_between(sub3(b, a), sub3(c, a));
        for d in 0..3 {
            s[d] += w * n[d];
        }
    }
    unit(s)
}

/// The neighbour sets of `m`'s vertices, from the faces.
fn neighbours(m: &OwnedMesh) -> Vec<BTreeSet<usize>> {
    let mut nb = vec![BTreeSet::new(); m.positions.len()];
    for f in m.faces() {
        for i in 0..f.len() {
            let (a, b) = (f[i] as usize, f[(i + 1) % f.len()] as usize);
            nb[a].insert(b);
            nb[b].insert(a);
        }
    }
    nb
}

/// The number of edges from each vertex to the nearest of `sources` (breadth-first;
/// `usize::MAX` where unreachable).
fn hops_from(m: &OwnedMesh, sources: &[usize]) -> Vec<usize> {
    let nb = neighbours(m);
    let mut d = vec![usize::MAX; nb.len()];
    let mut frontier: Vec<usize> = sources.to_vec();
    for &s in sources {
        d[s] = 0;
    }
    let mut h = 0;
    while !frontier.is_empty() {
        h += 1;
        let mut next = Vec::new();
        for &a in &frontier {
            for &b in &nb[a] {
                if d[b] == usize::MAX {
                    d[b] = h;
                    next.push(b);
                }
            }
        }
        frontier = next;
    }
    d
}

/// Control vertices pairwise at least `gap` edges apart (greedy in index order), at most `n`.
fn separated(m: &OwnedMesh, gap: usize, n: usize) -> Vec<usize> {
    let nb = neighbours(m);
    let mut chosen: Vec<usize> = Vec::new();
    for v in 0..nb.len() {
        if chosen.len() == n || nb[v].is_empty() {
            continue;
        }
        let mut with = chosen.clone();
        with.push(v);
        if chosen.is_empty() || hops_from(m, &chosen)[v] >= gap {
            chosen = with;
        }
    }
    chosen
}

/// A closed test surface: a twice Loop-subdivided icosahedron on the unit sphere, jittered
/// (162 vertices, valences 5 and 6).
fn ball() -> OwnedMesh {
    jitter(
        &subdivide_n(Scheme::Loop, &icosahedron(), 2).unwrap(),
        0.02,
        11,
    )
}

/// The options of the three stencils used by the editing tests.
fn stencils(k: usize) -> [(&'static str, DifferentialOptions<'static>); 3] {
    let mut dirmag = opts(Stencil::ModifiedButterfly, k);
    dirmag.dirmag_levels = 1;
    [
        ("Loop", opts(Stencil::Loop, k)),
        ("Butterfly", opts(Stencil::ModifiedButterfly, k)),
        ("DirMag", dirmag),
    ]
}

/// Requested normals: each vertex of `vs` tilted by `deg` degrees from its normal in the
/// unedited output `base`, about an axis that varies with the vertex; zero elsewhere.
fn tilted(base: &OwnedMesh, n0: usize, vs: &[usize], deg: f64) -> Vec<Point> {
    let mut normals = vec![[0.0; 3]; n0];
    for (j, &v) in vs.iter().enumerate() {
        let m = vertex_normal(base, v);
        let e = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]][j % 3];
        let axis = unit(cross3(m, e));
        normals[v] = rotate(m, axis, deg.to_radians());
    }
    normals
}

/// Tolerance of the measured normal at an edited vertex, radians. The edited result is the
/// unedited one plus a displacement that turns the vertex's star rigidly (docs/differential.md
/// "Editing"), confirmed by a solve to the relative residual 1e-10; positions then carry
/// errors around 1e-10 of the diameter, and over star edges of about a tenth of the
/// diameter (k = 2) the normal carries about 1e-9 rad. 1e-7 rad leaves two orders of margin
/// and is 5e6 times smaller than the 30° asked.
const NORMAL_TOL: f64 = 1e-7;

#[test]
fn a_normal_edit_turns_the_surface_normal_at_the_vertex() {
    let m = ball();
    let vs = separated(&m, 3, 6);
    assert!(vs.len() >= 4, "{vs:?}");
    for (name, o) in stencils(2) {
        let (base, _) = differential_subdivide(&m, &o).unwrap();
        let normals = tilted(&base, m.positions.len(), &vs, 30.0);
        let mut e = o;
        e.normals = Some(&normals);
        let (out, rep) = differential_subdivide(&m, &e).unwrap();
        let diam = diameter(&base.positions);
        let mut worst = 0.0f64;
        for &v in &vs {
            let got = vertex_normal(&out, v);
            worst = worst.max(angle_between(got, normals[v]));
            // The unedited normal was 30° away.
            let before = angle_between(vertex_normal(&base, v), normals[v]);
            assert!((before - 30f64.to_radians()).abs() < 1e-12, "{before}");
        }
        // What the edit does not reach stays, up to the one translation of the placement
        // (centroid kept): the rotation field of an old vertex comes from its control 1-ring
        // (Loop), so control vertices three or more edges from every edited vertex are
        // displaced by that translation alone.
        let hops = hops_from(&m, &vs);
        let far: Vec<usize> = (0..hops.len()).filter(|&v| hops[v] >= 3).collect();
        let t = sub3(out.positions[far[0]], base.positions[far[0]]);
        let far_moved = far
            .iter()
            .map(|&v| dist(sub3(out.positions[v], base.positions[v]), t))
            .fold(0.0, f64::max);
        let far = far.len();
        println!(
            "{name}: {} edited vertices tilted 30°, worst normal error {worst:.2e} rad; \
             {far} control vertices ≥ 3 edges away moved by one translation ({:.1e}) to \
             ≤ {:.2e} of the diameter; folds {} faces, {} edges; \
             solves {} + {} iterations",
            vs.len(),
            dot3(t, t).sqrt() / diam,
            far_moved / diam,
            rep.folded_faces,
            rep.folded_edges,
            rep.reference_solve.iterations,
            rep.solve.iterations
        );
        assert!(worst <= NORMAL_TOL, "{name}: {worst}");
        assert!(
            far > 0 && far_moved <= 1e-12 * diam,
            "{name}: {far} {far_moved}"
        );
        assert_eq!((rep.folded_faces, rep.folded_edges), (0, 0), "{name}");
    }
}

#[test]
fn a_normal_edit_works_on_a_flat_region_where_a_curvature_edit_cannot() {
    // A 12 × 12 grid in the plane z = 0, regular and jittered in the plane. On the regular
    // grid every interior differential coordinate is zero (zero mean curvature, §4.4's
    // `δ = H n` with `H = 0`); on the jittered one it lies in the plane.
    let regular = tri_grid(12, 12);
    let jittered = jitter(&regular, 0.1, 5).map_positions(|p| [p[0], p[1], 0.0]);
    let centre = 6 * 13 + 6;
    let n0 = regular.positions.len();
    let mut normals = vec![[0.0; 3]; n0];
    let want = rotate([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], 30f64.to_radians());
    normals[centre] = want;
    let mut scale = vec![1.0; n0];
    scale[centre] = 5.0;
    for (grid, g) in [("regular", &regular), ("jittered", &jittered)] {
        for (name, o) in stencils(2) {
            let (base, _) = differential_subdivide(g, &o).unwrap();
            let flat = base
                .positions
                .iter()
                .map(|p| p[2].abs())
                .fold(0.0, f64::max);
            // Curvature ×5 of a vertex of zero curvature: nothing to scale.
            let mut e = o;
            e.curvature_scale = Some(&scale);
            let (same, _) = differential_subdivide(g, &e).unwrap();
            let moved = base
                .positions
                .iter()
                .zip(&same.positions)
                .map(|(a, b)| dist(*a, *b))
                .fold(0.0, f64::max);
            // The normal edit turns the surface there.
            let mut e = o;
            e.normals = Some(&normals);
            let (out, rep) = differential_subdivide(g, &e).unwrap();
            let got = vertex_normal(&out, centre);
            let err = angle_between(got, want);
            let lift = out.positions.iter().map(|p| p[2].abs()).fold(0.0, f64::max);
            println!(
                "{grid} {name}: unedited |z| ≤ {flat:.1e}; curvature ×5 moved ≤ {moved:.1e}; \
                 normal 30°: error {err:.2e} rad, largest |z| {lift:.3}, folds {} faces {} edges",
                rep.folded_faces, rep.folded_edges
            );
            // DirMag lifts a flat open grid out of its plane: the boundary's Eq. (8)
            // coordinates lie in the plane, the interior's directions are the plane's normal,
            // and their normalised averages on the sphere mix the two (docs/differential.md
            // "Limits"). Loop and Butterfly on Δ keep the plane.
            assert!(flat < 1e-12 || name == "DirMag", "{grid} {name}");
            if grid == "regular" {
                assert!(moved < 1e-12, "{grid} {name}: {moved}");
            }
            assert!(err <= NORMAL_TOL, "{grid} {name}: {err}");
            assert!(
                lift > 0.1,
                "{grid} {name}: the surface did not leave the plane ({lift})"
            );
            assert_eq!(
                (rep.folded_faces, rep.folded_edges),
                (0, 0),
                "{grid} {name}"
            );
        }
    }
}

/// The differential coordinate of output vertex `v` in the units of the control mesh:
/// `4ᵏ (x_v − mean of its ring)` (Eq. (2); the reconstruction solves `4ᵏ L_k V = Δᵏ`).
fn output_delta(m: &OwnedMesh, nb: &[BTreeSet<usize>], v: usize, k: usize) -> Point {
    let r = &nb[v];
    let mut c = [0.0; 3];
    for &j in r {
        for d in 0..3 {
            c[d] += m.positions[j][d] / r.len() as f64;
        }
    }
    let s = 4f64.powi(k as i32);
    [0, 1, 2].map(|d| s * (m.positions[v][d] - c[d]))
}

#[test]
fn a_curvature_edit_scales_the_vertex_and_moves_it_out_linearly() {
    let m = ball();
    let k = 2;
    let nb0 = neighbours(&m);
    let n0 = m.positions.len();
    let vs = separated(&m, 3, 4);
    let delta0: Vec<Point> = (0..n0).map(|v| output_delta(&m, &nb0, v, 0)).collect();
    for (name, o) in [
        ("Loop", opts(Stencil::Loop, k)),
        ("Butterfly", opts(Stencil::ModifiedButterfly, k)),
    ] {
        let (base, _) = differential_subdivide(&m, &o).unwrap();
        let nbk = neighbours(&base);
        let run = |s: f64, which: &[usize]| {
            let mut sc = vec![1.0; n0];
            for &v in which {
                sc[v] = s;
            }
            let mut e = o;
            e.curvature_scale = Some(&sc);
            differential_subdivide(&m, &e).unwrap()
        };
        // One vertex: the edit adds (s − 1) δ⁰_v to Δ⁰, so the displacement of every output
        // vertex is (s − 1) δ⁰_v times one scalar field (the reconstruction solves the three
        // coordinates with one matrix, and the anchors and translation are the unedited
        // result's): parallel to δ⁰_v, linear in s − 1, outwards at the edited vertex.
        let v = vs[0];
        let (two, rep2) = run(2.0, &[v]);
        let (three, _) = run(3.0, &[v]);
        let diam = diameter(&base.positions);
        let (mut lin, mut par) = (0.0f64, 0.0f64);
        for i in 0..base.positions.len() {
            let d2 = sub3(two.positions[i], base.positions[i]);
            let d3 = sub3(three.positions[i], base.positions[i]);
            lin = lin.max(dist(d3, [2.0 * d2[0], 2.0 * d2[1], 2.0 * d2[2]]));
            let off = cross3(d2, unit(delta0[v]));
            par = par.max(dot3(off, off).sqrt());
        }
        let dv = sub3(two.positions[v], base.positions[v]);
        let outward = dot3(dv, vertex_normal(&base, v));
        println!(
            "{name}: ×2 at vertex {v}: displacement {:.4e} (along the outward normal \
             {outward:.4e}); |d(×3) − 2 d(×2)| ≤ {:.1e}, part across δ⁰ ≤ {:.1e} of the \
             diameter; folds {}",
            dot3(dv, dv).sqrt(),
            lin / diam,
            par / diam,
            rep2.folded_faces
        );
        assert!(lin <= 1e-8 * diam, "{name}: {lin}");
        assert!(par <= 1e-8 * diam, "{name}: {par}");
        assert!(outward > 0.0, "{name}");
        // Four vertices ×2 (Fig. 11(c)): with the interpolating stencil the differential
        // coordinate of the output at each edited vertex is twice the control one. The
        // residue is the closed-surface compatibility term of the least-squares solve,
        // `c d_i` with `c = −Σ d_j δ_j / Σ d_j²` over the output (docs/differential.md "The
        // reconstruction"): the subdivided Δ is not exactly the Laplacian of a closed
        // surface. It is a fraction of a percent with and without the edit (0.2–0.6 %
        // measured), so the bound is 2 %.
        if name == "Butterfly" {
            let (four, _) = run(2.0, &vs);
            for &v in &vs {
                let got = output_delta(&four, &nbk, v, k);
                let unedited = output_delta(&base, &nbk, v, k);
                let want = [0, 1, 2].map(|c| 2.0 * delta0[v][c]);
                let rel = dist(got, want) / dot3(want, want).sqrt();
                let rel0 = dist(unedited, delta0[v]) / dot3(delta0[v], delta0[v]).sqrt();
                println!(
                    "  vertex {v}: |δ_out − 2 δ⁰| / |2 δ⁰| = {rel:.2e} (unedited |δ_out − δ⁰| / \
                     |δ⁰| = {rel0:.2e})"
                );
                assert!(rel < 0.02 && rel0 < 0.02, "{v}: {rel} {rel0}");
            }
        }
    }
}

/// Faces of `m` as triangles and their normals.
fn face_normals(m: &OwnedMesh) -> Vec<Point> {
    m.faces()
        .iter()
        .map(|f| {
            let p = |i: usize| m.positions[f[i] as usize];
            cross3(sub3(p(1), p(0)), sub3(p(2), p(0)))
        })
        .collect()
}

/// The folds of `out` against `base`, counted here: faces turned by more than 90°, and
/// interior edges whose faces are more than 90° apart in `out` but not in `base`, with the
/// lowest face and the lowest edge `(a, b)`, `a < b`.
fn count_folds(base: &OwnedMesh, out: &OwnedMesh) -> (u32, u32, u32, [u32; 2]) {
    let (nb, no) = (face_normals(base), face_normals(out));
    let flipped: Vec<usize> = (0..nb.len())
        .filter(|&f| dot3(nb[f], no[f]) < 0.0)
        .collect();
    let mut edge_faces: std::collections::BTreeMap<(u32, u32), Vec<usize>> = Default::default();
    for (fi, f) in out.faces().iter().enumerate() {
        for i in 0..3 {
            let (a, b) = (f[i], f[(i + 1) % 3]);
            edge_faces.entry((a.min(b), a.max(b))).or_default().push(fi);
        }
    }
    let folded: Vec<(u32, u32)> = edge_faces
        .iter()
        .filter(|(_, fs)| {
            fs.len() == 2 && dot3(no[fs[0]], no[fs[1]]) < 0.0 && dot3(nb[fs[0]], nb[fs[1]]) >= 0.0
        })
        .map(|(e, _)| *e)
        .collect();
    (
        flipped.len() as u32,
        flipped.first().map_or(u32::MAX, |&f| f as u32),
        folded.len() as u32,
        folded.first().map_or([u32::MAX; 2], |e| [e.0, e.1]),
    )
}

/// Requested normals for a pair of adjacent vertices `v`, `w`, each tilted by `deg` degrees
/// towards the other (about the axis normal to `v`'s normal and the edge).
fn towards_each_other(base: &OwnedMesh, n0: usize, v: usize, w: usize, deg: f64) -> Vec<Point> {
    let mut normals = vec![[0.0; 3]; n0];
    let axis = unit(cross3(
        vertex_normal(base, v),
        sub3(base.positions[w], base.positions[v]),
    ));
    normals[v] = rotate(vertex_normal(base, v), axis, deg.to_radians());
    normals[w] = rotate(vertex_normal(base, w), axis, -deg.to_radians());
    normals
}

#[test]
fn adjacent_edited_vertices_are_met_exactly_from_two_levels() {
    let m = ball();
    let n0 = m.positions.len();
    let v = 20;
    let w = *neighbours(&m)[v].iter().next().unwrap();
    let u = hops_from(&m, &[v]).iter().position(|&h| h == 2).unwrap();
    for (name, o) in stencils(2) {
        let (base, _) = differential_subdivide(&m, &o).unwrap();
        let mut normals = towards_each_other(&base, n0, v, w, 40.0);
        normals[u] = tilted(&base, n0, &[u], 40.0)[u];
        let mut e = o;
        e.normals = Some(&normals);
        let (out, rep) = differential_subdivide(&m, &e).unwrap();
        let worst = [v, w, u]
            .iter()
            .map(|&x| angle_between(vertex_normal(&out, x), normals[x]))
            .fold(0.0, f64::max);
        println!(
            "{name}: vertices {v}, {w} adjacent and {u} two edges from {v}, 40° each: worst \
             normal error {worst:.2e} rad, folds {} faces {} edges",
            rep.folded_faces, rep.folded_edges
        );
        assert!(worst <= NORMAL_TOL, "{name}: {worst}");
    }
}

#[test]
fn folds_of_an_edit_are_reported_and_strict_mode_refuses_them() {
    let m = ball();
    let n0 = m.positions.len();
    let vs = separated(&m, 3, 3);
    let v = 20;
    let w = *neighbours(&m)[v].iter().next().unwrap();
    for (name, o) in stencils(2) {
        let (base, _) = differential_subdivide(&m, &o).unwrap();
        let cases = [
            (
                "10° on three separated vertices",
                tilted(&base, n0, &vs, 10.0),
            ),
            ("90° on one vertex", tilted(&base, n0, &vs[..1], 90.0)),
            ("180° on one vertex", tilted(&base, n0, &vs[..1], 180.0)),
            (
                "90° on two adjacent vertices, towards each other",
                towards_each_other(&base, n0, v, w, 90.0),
            ),
        ];
        for (case, normals) in &cases {
            let mut e = o;
            e.normals = Some(normals);
            let (out, rep) = differential_subdivide(&m, &e).unwrap();
            let (faces, first_face, edges, first_edge) = count_folds(&base, &out);
            println!(
                "{name}, {case}: {faces} folded faces (first {first_face}), {edges} folded \
                 edges (first {first_edge:?})"
            );
            assert_eq!(
                (
                    rep.folded_faces,
                    rep.first_folded_face,
                    rep.folded_edges,
                    rep.first_folded_edge
                ),
                (faces, first_face, edges, first_edge),
                "{name}, {case}"
            );
            e.strict = true;
            match differential_subdivide(&m, &e) {
                Ok((same, _)) => {
                    assert_eq!(faces + edges, 0, "{name}, {case}");
                    assert_eq!(same, out);
                }
                Err((err, srep)) => {
                    assert!(faces + edges > 0, "{name}, {case}");
                    assert_eq!(err.status, Status::FoldedSurface);
                    assert_eq!((srep.folded_faces, srep.folded_edges), (faces, edges));
                    // The element is a face of the output: the first folded face, or a face
                    // of the first folded edge.
                    if faces > 0 {
                        assert_eq!(err.element, first_face);
                    } else {
                        let f = &out.faces()[err.element as usize];
                        assert!(f.contains(&first_edge[0]) && f.contains(&first_edge[1]));
                    }
                }
            }
            // Small turns do not fold; turning a star upside down turns its faces over, and
            // two neighbours turned into each other crease the edge between them.
            match *case {
                "10° on three separated vertices" => assert_eq!(faces + edges, 0),
                "180° on one vertex" => assert!(faces >= 5, "{faces}"),
                "90° on two adjacent vertices, towards each other" => {
                    assert!(edges > 0, "{edges}")
                }
                _ => {}
            }
        }
    }
}

#[test]
fn edit_inputs_are_checked_and_name_the_vertex() {
    let m = ball();
    let n0 = m.positions.len();
    let o = opts(Stencil::Loop, 1);
    let code = |o: &DifferentialOptions<'_>| {
        let e = differential_subdivide(&m, o).unwrap_err().0;
        (e.status, e.element)
    };
    // Lengths: the element is the first index without a partner.
    for len in [0, 5, n0 - 1, n0 + 1, n0 + 7] {
        let s = vec![1.0; len];
        let mut e = o;
        e.curvature_scale = Some(&s);
        assert_eq!(code(&e), (Status::InvalidArgument, len.min(n0) as u32));
        let nrm = vec![[0.0; 3]; len];
        let mut e = o;
        e.normals = Some(&nrm);
        assert_eq!(code(&e), (Status::InvalidArgument, len.min(n0) as u32));
    }
    // Non-finite values.
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut s = vec![1.0; n0];
        s[17] = bad;
        let mut e = o;
        e.curvature_scale = Some(&s);
        assert_eq!(code(&e), (Status::NonFiniteInput, 17));
        let mut nrm = vec![[0.0; 3]; n0];
        nrm[23] = [0.0, bad, 1.0];
        let mut e = o;
        e.normals = Some(&nrm);
        assert_eq!(code(&e), (Status::NonFiniteInput, 23));
    }
    // A zero normal means "no edit": the same bits as no normals at all.
    let (plain, _) = differential_subdivide(&m, &o).unwrap();
    let zeros = vec![[0.0; 3]; n0];
    let mut e = o;
    e.normals = Some(&zeros);
    assert_eq!(differential_subdivide(&m, &e).unwrap().0, plain);
    // Tiny and huge directions are directions.
    for len in [1e-300, 1e300] {
        let mut nrm = vec![[0.0; 3]; n0];
        nrm[3] = [0.0, 0.0, len];
        let mut e = o;
        e.normals = Some(&nrm);
        let (out, _) = differential_subdivide(&m, &e).unwrap();
        assert!(angle_between(vertex_normal(&out, 3), [0.0, 0.0, 1.0]) <= NORMAL_TOL);
    }
    // A normal edit of an isolated vertex: it has no surface normal to turn.
    let mut iso = m.clone();
    iso.positions.push([5.0, 0.0, 0.0]);
    let mut nrm = vec![[0.0; 3]; n0 + 1];
    nrm[n0] = [0.0, 0.0, 1.0];
    let mut e = o;
    e.normals = Some(&nrm);
    let err = differential_subdivide(&iso, &e).unwrap_err().0;
    assert_eq!(
        (err.status, err.element),
        (Status::DegenerateGeometry, n0 as u32)
    );
    // `strict` without edits changes nothing.
    let mut e = o;
    e.strict = true;
    assert_eq!(differential_subdivide(&m, &e).unwrap().0, plain);
}
