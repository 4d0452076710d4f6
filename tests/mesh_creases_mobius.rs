//! Sharp-feature tags on the Möbius schemes (`docs/creases.md`, "Möbius creases"): the
//! expectations come from the mathematics, not from recorded output. A crease is subdivided
//! by the Möbius curve rules of its polygon (closed, or open between corners), so a tagged
//! circle stays a circle and a tagged circle of a spherical cage keeps the cage's output on
//! its sphere; the result commutes with random Möbius maps; semi-sharp values are whole
//! sharp levels; empty and zero tags are the untagged Möbius call bit for bit; the spectrum
//! weight blends with the tagged linear rules; bad tags keep their statuses.

// Test helpers outside #[test] functions: clippy's in-test allowances do not reach them.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]

mod common;

use common::OwnedMesh;
use common::{cube, icosahedron, jitter, octahedron, quad_grid, quad_torus, tri_grid, tri_torus};
use nlsubdiv::curve::mobius as curve;
use nlsubdiv::mobius::MobiusMap;
use nlsubdiv::scheme::{Options, Scheme, Tags};
use nlsubdiv::{Point, Status};
use std::collections::{BTreeMap, BTreeSet};

const LOOP: Scheme = Scheme::Loop;
const CC: Scheme = Scheme::CatmullClark;
const MB: Scheme = Scheme::ModifiedButterfly;
const KOBBELT: Scheme = Scheme::Kobbelt;
const ALL: [Scheme; 4] = [LOOP, CC, MB, KOBBELT];
const INF: f64 = 10.0;

fn triangles(s: Scheme) -> bool {
    matches!(s, LOOP | MB)
}

fn approximating(s: Scheme) -> bool {
    matches!(s, LOOP | CC)
}

use common::run_tagged;

fn mobius(s: Scheme, levels: usize) -> Options {
    Options::new(s).mobius(true).levels(levels)
}

fn dist(a: Point, b: Point) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

fn norm(p: Point) -> f64 {
    dist(p, [0.0; 3])
}

fn diameter(p: &[Point]) -> f64 {
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for q in p {
        for k in 0..3 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    dist(lo, hi)
}

/// The edges of `m` sorted by `(min, max)` vertex key: the kernel's edge numbering, so the
/// edge point of edge `k` is output vertex `V + k` (old vertices first, then edge points).
fn edge_ids(m: &OwnedMesh) -> BTreeMap<[u32; 2], u32> {
    let mut set = BTreeSet::new();
    for f in m.faces() {
        for i in 0..f.len() {
            let (a, b) = (f[i], f[(i + 1) % f.len()]);
            set.insert([a.min(b), a.max(b)]);
        }
    }
    set.into_iter().zip(0..).collect()
}

/// The vertex chains of a crease polygon after each of `levels` levels: `meshes[k]` is level
/// `k` (`meshes[0]` the input), `chain` a polygon of level 0 (closed: its last vertex joins
/// its first). Each edge `a b` of level `k` becomes `a e b` with `e` its edge point.
fn descendants(meshes: &[OwnedMesh], chain: &[u32], closed: bool) -> Vec<u32> {
    let mut cur = chain.to_vec();
    for m in &meshes[..meshes.len() - 1] {
        let ids = edge_ids(m);
        let nv = m.positions.len() as u32;
        let n = cur.len();
        let segs = if closed { n } else { n - 1 };
        let mut next = Vec::new();
        for i in 0..segs {
            let (a, b) = (cur[i], cur[(i + 1) % n]);
            next.push(a);
            next.push(nv + ids[&[a.min(b), a.max(b)]]);
        }
        if !closed {
            next.push(cur[n - 1]);
        }
        cur = next;
    }
    cur
}

/// `levels` levels of the Möbius curve rule of `s` on `poly`.
fn curve_levels(s: Scheme, poly: &[Point], closed: bool, levels: usize) -> Vec<Point> {
    let mut cur = poly.to_vec();
    for _ in 0..levels {
        let n = if closed {
            2 * cur.len()
        } else {
            2 * cur.len() - 1
        };
        let mut out = vec![[0.0; 3]; n];
        let written = if approximating(s) {
            curve::refine_approximating(&cur, closed, &mut out)
        } else {
            curve::refine_interpolating(&cur, closed, &mut out)
        };
        assert_eq!(written.unwrap(), n);
        cur = out;
    }
    cur
}

/// Level 0 to `levels` of `m` with `opts` and `tags` (level `k` from a `k`-level call).
fn level_meshes(m: &OwnedMesh, opts: Options, tags: &Tags<'_>, levels: usize) -> Vec<OwnedMesh> {
    let mut v = vec![m.clone()];
    for k in 1..=levels {
        v.push(run_tagged(m, &opts.levels(k), tags).unwrap().0);
    }
    v
}

/// The default mode (the fold guard) gives the paper's output `literal` (one mesh per level
/// from 0) bit for bit at every level where its report counts no guarded element, and
/// differs only where it counts some: it never changes a result silently.
fn guarded_where_it_differs(s: Scheme, m: &OwnedMesh, tags: &Tags<'_>, literal: &[OwnedMesh]) {
    for (k, want) in literal.iter().enumerate().skip(1) {
        let (got, r) = run_tagged(m, &mobius(s, k), tags).unwrap();
        if r.guarded == 0 {
            assert_eq!(&got, want, "{s:?} level {k}: nothing guarded");
        } else {
            assert!(got != *want, "{s:?} level {k}: guarded, same output");
        }
    }
}

fn edges_of(chain: &[u32], closed: bool) -> Vec<[u32; 2]> {
    let n = chain.len();
    let segs = if closed { n } else { n - 1 };
    (0..segs).map(|i| [chain[i], chain[(i + 1) % n]]).collect()
}

/// A jittered torus of the scheme's faces and a closed staircase crease of 14 edges around
/// it that no grid line follows.
fn torus_with_staircase(s: Scheme) -> (OwnedMesh, Vec<u32>) {
    let m = if triangles(s) {
        tri_torus(8, 6)
    } else {
        quad_torus(8, 6, 3.0, 1.0)
    };
    let mut ring = Vec::new();
    for k in 0..6u32 {
        ring.push(k * 8 + k);
        ring.push(k * 8 + k + 1);
    }
    ring.extend([6, 7]);
    (jitter(&m, 0.08, 11), ring)
}

/// A jittered `n × n` grid of the scheme's faces and its middle row, a crease from one side
/// to the other (its ends on the boundary are corners).
fn grid_with_row(s: Scheme, n: usize) -> (OwnedMesh, Vec<u32>) {
    let m = if triangles(s) {
        tri_grid(n, n)
    } else {
        quad_grid(n, n)
    };
    let m = jitter(&m, 0.05, 5);
    // Vertex (i, j) of the grid generators is j (n + 1) + i.
    let j = (n / 2) as u32;
    let row = (0..=n as u32).map(|i| j * (n as u32 + 1) + i).collect();
    (m, row)
}

#[test]
fn the_grids_row_is_a_row() {
    // The layout `grid_with_row` assumes: the row's vertices share their y coordinate.
    for s in [LOOP, CC] {
        let m = if triangles(s) {
            tri_grid(6, 6)
        } else {
            quad_grid(6, 6)
        };
        let y = m.positions[3 * 7][1];
        for i in 0..=6 {
            assert_eq!(m.positions[3 * 7 + i][1], y, "{s:?}");
        }
        assert!(m.positions[3 * 7 + 1][0] != m.positions[3 * 7][0]);
    }
}

#[test]
fn empty_and_zero_tags_are_the_untagged_mobius_call_bit_for_bit() {
    for s in ALL {
        let (m, ring) = torus_with_staircase(s);
        for levels in 1..=2 {
            for opts in [mobius(s, levels), mobius(s, levels).literal(true)] {
                let (plain, pr) = common::run(&m, &opts).unwrap();
                let (empty, er) = run_tagged(&m, &opts, &Tags::new()).unwrap();
                assert_eq!(empty, plain, "{s:?} empty tags");
                assert_eq!(er, pr);
                let creases = edges_of(&ring[..3], false);
                let corner = [ring[5]];
                let tags = Tags::new()
                    .creases(&creases, &[0.0, 0.0])
                    .corners(&corner, &[0.0]);
                let (zero, zr) = run_tagged(&m, &opts, &tags).unwrap();
                assert_eq!(zero, plain, "{s:?} zero tags");
                assert_eq!(zr, pr);
            }
        }
    }
}

#[test]
fn a_closed_crease_is_the_closed_mobius_curve_of_its_polygon() {
    for s in ALL {
        let (m, ring) = torus_with_staircase(s);
        let creases = edges_of(&ring, true);
        let infs = vec![INF; creases.len()];
        let tags = Tags::new().creases(&creases, &infs);
        let poly: Vec<Point> = ring.iter().map(|&v| m.positions[v as usize]).collect();
        // The paper's rules (`literal`): the fold guard may move crease points of this
        // jittered coarse torus toward the linear curve rule, counted (below).
        let levels = level_meshes(&m, mobius(s, 1).literal(true), &tags, 3);
        guarded_where_it_differs(s, &m, &tags, &levels);
        let scale = diameter(&poly);
        let (plain, _) = common::run(&m, &mobius(s, 1).literal(true)).unwrap();
        for k in 1..=3 {
            let chain = descendants(&levels[..=k], &ring, true);
            let want = curve_levels(s, &poly, true, k);
            assert_eq!(chain.len(), want.len());
            let err = chain
                .iter()
                .zip(&want)
                .map(|(&v, &q)| dist(levels[k].positions[v as usize], q) / scale)
                .fold(0.0, f64::max);
            assert!(err <= 1e-12, "{s:?}, level {k}: {err:e}");
            if k == 1 {
                // The tags change the result: the untagged surface does not hold the curve.
                let off = chain
                    .iter()
                    .zip(&want)
                    .map(|(&v, &q)| dist(plain.positions[v as usize], q) / scale)
                    .fold(0.0, f64::max);
                assert!(off > 1e-6, "{s:?}: the untagged step holds the curve");
            }
        }
    }
}

#[test]
fn an_open_crease_between_corners_is_the_open_mobius_curve() {
    for s in ALL {
        let (m, row) = grid_with_row(s, 6);
        let creases = edges_of(&row, false);
        let infs = vec![INF; creases.len()];
        let tags = Tags::new().creases(&creases, &infs);
        let poly: Vec<Point> = row.iter().map(|&v| m.positions[v as usize]).collect();
        // The paper's rules (`literal`): the fold guard may move crease points of this
        // jittered grid toward the linear curve rule with the interior points around them,
        // counted (below).
        let levels = level_meshes(&m, mobius(s, 1).literal(true), &tags, 3);
        guarded_where_it_differs(s, &m, &tags, &levels);
        let scale = diameter(&poly);
        for k in 1..=3 {
            let chain = descendants(&levels[..=k], &row, false);
            let want = curve_levels(s, &poly, false, k);
            let err = chain
                .iter()
                .zip(&want)
                .map(|(&v, &q)| dist(levels[k].positions[v as usize], q) / scale)
                .fold(0.0, f64::max);
            assert!(err <= 1e-12, "{s:?}, level {k}: {err:e}");
            // The corners where the crease meets the boundary stay.
            for &v in [row[0], row[row.len() - 1]].iter() {
                assert_eq!(levels[k].positions[v as usize], m.positions[v as usize]);
            }
        }
    }
}

/// A closed cylinder cage: rims of `n` vertices on the unit circles `z = 0` and `z = 1`, a
/// middle ring of radius 1.3 at `z = ½`, caps around centres off the rims' planes (quads
/// around a valence-`n/2` centre, or triangle fans). Returns the mesh and the two rims.
fn cylinder(quads: bool, n: usize) -> (OwnedMesh, [Vec<u32>; 2]) {
    let mut p = Vec::new();
    for (z, r) in [(0.0, 1.0), (0.5, 1.3), (1.0, 1.0)] {
        for i in 0..n {
            // Uneven angles: the rims are circles, not regular polygons.
            let t = 2.0 * std::f64::consts::PI * (i as f64 + 0.2 * ((i * 7) % 3) as f64) / n as f64;
            p.push([r * t.cos(), r * t.sin(), z]);
        }
    }
    p.push([0.1, 0.0, -0.4]);
    p.push([0.0, -0.1, 1.3]);
    let ring = |k: usize, i: usize| (k * n + i % n) as u32;
    let (cb, ct) = ((3 * n) as u32, (3 * n + 1) as u32);
    let mut faces = Vec::new();
    for k in 0..2 {
        for i in 0..n {
            let q = [
                ring(k, i),
                ring(k, i + 1),
                ring(k + 1, i + 1),
                ring(k + 1, i),
            ];
            if quads {
                faces.push(q.to_vec());
            } else {
                faces.push(vec![q[0], q[1], q[2]]);
                faces.push(vec![q[0], q[2], q[3]]);
            }
        }
    }
    if quads {
        for i in (0..n).step_by(2) {
            faces.push(vec![cb, ring(0, i + 2), ring(0, i + 1), ring(0, i)]);
            faces.push(vec![ct, ring(2, i), ring(2, i + 1), ring(2, i + 2)]);
        }
    } else {
        for i in 0..n {
            faces.push(vec![cb, ring(0, i + 1), ring(0, i)]);
            faces.push(vec![ct, ring(2, i), ring(2, i + 1)]);
        }
    }
    let rims = [
        (0..n).map(|i| ring(0, i)).collect(),
        (0..n).map(|i| ring(2, i)).collect(),
    ];
    (OwnedMesh::from_faces(p, &faces), rims)
}

#[test]
fn tagged_rims_of_a_cylinder_stay_on_their_circles() {
    for s in ALL {
        let (m, rims) = cylinder(!triangles(s), 8);
        let mut creases = edges_of(&rims[0], true);
        creases.extend(edges_of(&rims[1], true));
        let infs = vec![INF; creases.len()];
        let tags = Tags::new().creases(&creases, &infs);
        for literal in [false, true] {
            let opts = mobius(s, 1).literal(literal);
            let levels = level_meshes(&m, opts, &tags, 3);
            let (untagged, _) = common::run(&m, &opts.levels(1)).unwrap();
            let mut worst = 0.0f64;
            let mut untagged_worst = 0.0f64;
            for (rim, z) in rims.iter().zip([0.0, 1.0]) {
                let chain = descendants(&levels, rim, true);
                assert_eq!(chain.len(), 8 << 3);
                for &v in &chain {
                    let p = levels[3].positions[v as usize];
                    let off = (p[2] - z).abs().max((norm([p[0], p[1], 0.0]) - 1.0).abs());
                    worst = worst.max(off);
                }
                for &v in &descendants(&levels[..=1], rim, true) {
                    let p = untagged.positions[v as usize];
                    let off = (p[2] - z).abs().max((norm([p[0], p[1], 0.0]) - 1.0).abs());
                    untagged_worst = untagged_worst.max(off);
                }
            }
            assert!(worst < 1e-12, "{s:?} literal {literal}: {worst:e}");
            // Without the tags the rims do not keep their circles.
            assert!(untagged_worst > 1e-3, "{s:?}: {untagged_worst:e}");
        }
    }
}

/// A spherical cage and a circle of its edges: the octahedron's equator (a great circle)
/// and the icosahedron's pentagon around vertex 0 (a small circle) for triangles; for quads
/// the once-subdivided cube on the unit sphere and its equator of eight vertices (a great
/// circle). (A circle around a single face would not do: that face alone is a surface whose
/// boundary is the circle, and no sphere through a circle is singled out by it.)
fn spherical_cages(s: Scheme) -> Vec<(OwnedMesh, Vec<u32>)> {
    if triangles(s) {
        return vec![
            (octahedron(), vec![0, 2, 1, 3]),
            (icosahedron(), vec![11, 5, 1, 7, 10]),
        ];
    }
    let c = common::subdivide(CC, &cube()).unwrap().map_positions(|p| {
        let n = norm(p);
        [p[0] / n, p[1] / n, p[2] / n]
    });
    let mut equator: Vec<u32> = (0..c.positions.len() as u32)
        .filter(|&v| c.positions[v as usize][2].abs() < 1e-12)
        .collect();
    let angle = |v: u32| {
        let p = c.positions[v as usize];
        p[1].atan2(p[0])
    };
    equator.sort_by(|&a, &b| angle(a).total_cmp(&angle(b)));
    assert_eq!(equator.len(), 8);
    vec![(c, equator)]
}

#[test]
fn a_spherical_cage_with_a_tagged_circle_stays_on_its_sphere() {
    for s in ALL {
        for (m, circle) in spherical_cages(s) {
            for p in &m.positions {
                assert!((norm(*p) - 1.0).abs() < 1e-15);
            }
            let creases = edges_of(&circle, true);
            let infs = vec![INF; creases.len()];
            let tags = Tags::new().creases(&creases, &infs);
            let (out, _) = run_tagged(&m, &mobius(s, 3), &tags).unwrap();
            let off = out
                .positions
                .iter()
                .map(|&p| (norm(p) - 1.0).abs())
                .fold(0.0, f64::max);
            assert!(
                off < 1e-12,
                "{s:?}, {} vertices: {off:e}",
                m.positions.len()
            );
            // The circle is a crease: the linear tagged scheme leaves the sphere.
            let (lin, _) = run_tagged(&m, &Options::new(s).levels(3), &tags).unwrap();
            let lin_off = lin
                .positions
                .iter()
                .map(|&p| (norm(p) - 1.0).abs())
                .fold(0.0, f64::max);
            assert!(lin_off > 1e-3);
        }
    }
}

/// A random Möbius map with an inversion centre outside the mesh's bounding sphere,
/// composed with a rotation and a scaling (as in `tests/mesh_mobius.rs`).
fn random_mobius(m: &OwnedMesh, seed: u64) -> MobiusMap {
    let mut rng = common::Lcg(seed);
    let n = m.positions.len() as f64;
    let mut c = [0.0; 3];
    for p in &m.positions {
        for k in 0..3 {
            c[k] += p[k] / n;
        }
    }
    let r = m.positions.iter().map(|&p| dist(p, c)).fold(0.0, f64::max);
    let unit = |rng: &mut common::Lcg| loop {
        let p = [rng.next(), rng.next(), rng.next()];
        let l = norm(p);
        if l > 0.1 && l < 1.0 {
            return [p[0] / l, p[1] / l, p[2] / l];
        }
    };
    let dir = unit(&mut rng);
    let t = r * (1.65 + 0.35 * rng.next());
    let centre = [c[0] + t * dir[0], c[1] + t * dir[1], c[2] + t * dir[2]];
    MobiusMap::inversion(centre, r * (1.0 + 0.5 * rng.next().abs()))
        .compose(&MobiusMap::rotation(unit(&mut rng), 3.0 * rng.next()))
        .compose(&MobiusMap::scaling(0.5 + rng.next().abs()))
}

#[test]
fn tagged_mobius_subdivision_commutes_with_mobius_maps() {
    let mut worst = 0.0f64;
    for s in ALL {
        let (torus, ring) = torus_with_staircase(s);
        let (grid, row) = grid_with_row(s, 6);
        let (cyl, rims) = cylinder(!triangles(s), 8);
        let cases = [
            (torus, edges_of(&ring, true), vec![]),
            (grid, edges_of(&row, false), vec![row[2]]),
            (cyl, edges_of(&rims[0], true), vec![rims[1][3]]),
        ];
        for (seed, (m, creases, corners)) in cases.into_iter().enumerate() {
            // Semi-sharp values too: 1.4 is sharp at the first level only.
            let sharpness: Vec<f64> = (0..creases.len())
                .map(|i| if i % 3 == 0 { 1.4 } else { INF })
                .collect();
            let cs = vec![INF; corners.len()];
            let tags = Tags::new()
                .creases(&creases, &sharpness)
                .corners(&corners, &cs);
            let f = random_mobius(&m, 17 + seed as u64);
            let image = m.map_positions(|p| f.apply(p).unwrap());
            for literal in [true, false] {
                // Which elements the fold guard changes is Möbius-invariant: on one level, whose
                // input is the Möbius image; on two levels when the first changed nothing (a
                // point moved toward the linear rule follows similarities only, so the second
                // level's input is then no longer the Möbius image of the other's).
                let (_, r1a) = run_tagged(&image, &mobius(s, 1).literal(literal), &tags).unwrap();
                let (_, r1b) = run_tagged(&m, &mobius(s, 1).literal(literal), &tags).unwrap();
                assert_eq!(
                    (r1a.guarded, r1a.first_guarded),
                    (r1b.guarded, r1b.first_guarded),
                    "{s:?} case {seed} literal {literal}, one level"
                );
                let opts = mobius(s, 2).literal(literal);
                let (a, ra) = run_tagged(&image, &opts, &tags).unwrap();
                let (b, rb) = run_tagged(&m, &opts, &tags).unwrap();
                if r1b.guarded == 0 {
                    assert_eq!(
                        (ra.guarded, ra.first_guarded),
                        (rb.guarded, rb.first_guarded),
                        "{s:?} case {seed} literal {literal}"
                    );
                }
                assert_eq!(ra.fallbacks, rb.fallbacks);
                if !literal && rb.guarded > 0 {
                    continue;
                }
                let scale = diameter(&a.positions);
                let err = a
                    .positions
                    .iter()
                    .zip(&b.positions)
                    .map(|(&p, &q)| dist(p, f.apply(q).unwrap()) / scale)
                    .fold(0.0, f64::max);
                assert!(err < 1e-9, "{s:?} case {seed} literal {literal}: {err:e}");
                worst = worst.max(err);
            }
        }
    }
    println!("tagged Möbius equivariance: worst relative error {worst:.2e}");
}

#[test]
fn sharpness_one_is_one_sharp_level_then_smooth_levels() {
    for s in ALL {
        let (m, ring) = torus_with_staircase(s);
        let creases = edges_of(&ring, true);
        let ones = vec![1.0; creases.len()];
        let one = Tags::new().creases(&creases, &ones);
        let infs = vec![INF; creases.len()];
        let inf = Tags::new().creases(&creases, &infs);
        let (two, _) = run_tagged(&m, &mobius(s, 2), &one).unwrap();
        let (first, _) = run_tagged(&m, &mobius(s, 1), &inf).unwrap();
        let (second, _) = common::run(&first, &mobius(s, 1)).unwrap();
        assert_eq!(two, second, "{s:?}");
    }
}

#[test]
fn a_corner_tag_keeps_its_vertex() {
    for s in [LOOP, CC] {
        // A smooth vertex tagged as a corner, and a corner on a closed crease.
        let (m, ring) = torus_with_staircase(s);
        let creases = edges_of(&ring, true);
        let infs = vec![INF; creases.len()];
        let corner_ids = [ring[4], 30];
        let tags = Tags::new()
            .creases(&creases, &infs)
            .corners(&corner_ids, &[INF, INF]);
        let (out, _) = run_tagged(&m, &mobius(s, 2), &tags).unwrap();
        for v in [ring[4], 30] {
            assert_eq!(
                out.positions[v as usize], m.positions[v as usize],
                "{s:?} {v}"
            );
        }
        // The corner splits the loop into an open curve from the corner back to itself.
        let mut open: Vec<u32> = ring[4..].to_vec();
        open.extend(&ring[..=4]);
        let poly: Vec<Point> = open.iter().map(|&v| m.positions[v as usize]).collect();
        let levels = level_meshes(&m, mobius(s, 1).literal(true), &tags, 2);
        guarded_where_it_differs(s, &m, &tags, &levels);
        let chain = descendants(&levels, &open, false);
        let want = curve_levels(s, &poly, false, 2);
        let err = chain
            .iter()
            .zip(&want)
            .map(|(&v, &q)| dist(levels[2].positions[v as usize], q))
            .fold(0.0, f64::max);
        assert!(err <= 1e-12 * diameter(&poly), "{s:?}: {err:e}");
    }
}

#[test]
fn a_chain_ending_at_darts_is_smooth() {
    // A crease that does not close and meets no corner or boundary cannot be cut (module
    // docs of the kernel's crease step): the chain is subdivided smooth.
    for s in ALL {
        let (m, ring) = torus_with_staircase(s);
        let creases = edges_of(&ring[..5], false);
        let infs = vec![INF; creases.len()];
        let tags = Tags::new().creases(&creases, &infs);
        let (tagged, _) = run_tagged(&m, &mobius(s, 2), &tags).unwrap();
        let (plain, _) = common::run(&m, &mobius(s, 2)).unwrap();
        assert_eq!(tagged, plain, "{s:?}");
    }
}

#[test]
fn the_spectrum_blends_with_the_tagged_linear_scheme() {
    for s in ALL {
        let (m, ring) = torus_with_staircase(s);
        let creases = edges_of(&ring, true);
        let infs = vec![INF; creases.len()];
        let tags = Tags::new().creases(&creases, &infs);
        let (lin, _) = run_tagged(&m, &Options::new(s).levels(1), &tags).unwrap();
        let (mob, _) = run_tagged(&m, &mobius(s, 1), &tags).unwrap();
        let (zero, _) = run_tagged(&m, &mobius(s, 1).spectrum(0.0), &tags).unwrap();
        assert_eq!(zero, lin, "{s:?}: weight 0");
        let (one, _) = run_tagged(&m, &mobius(s, 1).spectrum(1.0), &tags).unwrap();
        assert_eq!(one, mob, "{s:?}: weight 1");
        for w in [0.25, 0.5, 0.75] {
            let (mid, _) = run_tagged(&m, &mobius(s, 1).spectrum(w), &tags).unwrap();
            for ((p, l), q) in mid.positions.iter().zip(&lin.positions).zip(&mob.positions) {
                for k in 0..3 {
                    let want = w * q[k] + (1.0 - w) * l[k];
                    assert!(
                        (p[k] - want).abs() <= 1e-14 * (1.0 + want.abs()),
                        "{s:?} {w}"
                    );
                }
            }
        }
    }
}

#[test]
fn bad_tags_keep_their_statuses_with_mobius() {
    for s in ALL {
        let (m, _) = torus_with_staircase(s);
        let opts = mobius(s, 1);
        let status = |t: &Tags<'_>| run_tagged(&m, &opts, t).unwrap_err();
        let e = status(&Tags::new().creases(&[[0, 30]], &[INF]));
        assert_eq!((e.status, e.element), (Status::TagNotAnEdge, 0));
        let e = status(&Tags::new().creases(&[[0, 1], [1, 0]], &[INF, INF]));
        assert_eq!((e.status, e.element), (Status::RepeatedTag, 1));
        let e = status(&Tags::new().creases(&[[0, 1]], &[f64::NAN]));
        assert_eq!((e.status, e.element), (Status::InvalidSharpness, 0));
        let e = status(&Tags::new().corners(&[9999], &[INF]));
        assert_eq!(e.status, Status::IndexOutOfRange);
    }
    // Schemes that take no tags still refuse them with Möbius.
    let (m, _) = torus_with_staircase(CC);
    let e = run_tagged(
        &m,
        &Options::new(Scheme::DooSabin).mobius(true),
        &Tags::new().creases(&[[0, 1]], &[INF]),
    )
    .unwrap_err();
    assert_eq!(e.status, Status::TagsNotSupported);
}

/// The circumcentre and circumradius of the triangle `a b c`.
fn circumcircle(a: Point, b: Point, c: Point) -> (Point, f64) {
    let sub = |p: Point, q: Point| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
    let cross = |p: Point, q: Point| {
        [
            p[1] * q[2] - p[2] * q[1],
            p[2] * q[0] - p[0] * q[2],
            p[0] * q[1] - p[1] * q[0],
        ]
    };
    let dot = |p: Point, q: Point| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
    let (u, v) = (sub(b, a), sub(c, a));
    let w = cross(u, v);
    let t1 = cross(w, u);
    let t2 = cross(v, w);
    let s = 2.0 * dot(w, w);
    let (k1, k2) = (dot(v, v) / s, dot(u, u) / s);
    let o = [
        a[0] + k1 * t1[0] + k2 * t2[0],
        a[1] + k1 * t1[1] + k2 * t2[1],
        a[2] + k1 * t1[2] + k2 * t2[2],
    ];
    (o, dist(o, a))
}

#[test]
fn a_crease_curve_of_three_points_takes_the_linear_rule_in_the_default_mode() {
    // A thin triangle of a grid with its three edges sharp: a closed crease of three points,
    // alone and with a corner on it (the curve then closes at the corner). The paper's rules
    // put its curve on the triangle's circumcircle (any three points are Möbius images of
    // any other three); the default mode takes the linear curve rule there and counts it as
    // guarded.
    for s in [LOOP, MB] {
        let mut m = jitter(&tri_grid(4, 4), 0.02, 9);
        let f = m.faces()[10].clone();
        // Thin: the third corner near the middle of the first two.
        let (a, b) = (m.positions[f[0] as usize], m.positions[f[1] as usize]);
        m.positions[f[2] as usize] = [
            0.5 * (a[0] + b[0]) + 0.05,
            0.5 * (a[1] + b[1]) + 0.08,
            0.5 * (a[2] + b[2]),
        ];
        let creases = edges_of(&f, true);
        let ids = edge_ids(&m);
        let nv = m.positions.len();
        let p = |v: u32| m.positions[v as usize];
        let (o, r) = circumcircle(p(f[0]), p(f[1]), p(f[2]));
        let corner = [f[0]];
        for with_corner in [false, true] {
            let tags = Tags::new().creases(&creases, &[INF; 3]);
            let tags = if with_corner {
                tags.corners(&corner, &[INF])
            } else {
                tags
            };
            let (lit, lr) = run_tagged(&m, &mobius(s, 1).literal(true), &tags).unwrap();
            let (def, dr) = run_tagged(&m, &mobius(s, 1), &tags).unwrap();
            assert_eq!(lr.guarded, 0);
            assert!(dr.guarded >= 3, "{s:?}: {}", dr.guarded);
            for &[x, y] in &creases {
                let k = nv + ids[&[x.min(y), x.max(y)]] as usize;
                // The paper's rules: on the circumcircle (the Möbius curve of three points).
                assert!((dist(lit.positions[k], o) - r).abs() < 1e-12 * r, "{s:?}");
                // The default: the linear curve rule — the midpoint for Loop; for Butterfly
                // the 4-point rule of the closed curve, or next to the corner of the open
                // curve with the virtual point 2 c − u before the corner c — off the circle.
                let z = f.iter().copied().find(|&v| v != x && v != y).unwrap();
                let want = if s == LOOP {
                    let (a, b) = (p(x), p(y));
                    [
                        0.5 * (a[0] + b[0]),
                        0.5 * (a[1] + b[1]),
                        0.5 * (a[2] + b[2]),
                    ]
                } else if with_corner && (x == f[0] || y == f[0]) {
                    let (c, u) = if x == f[0] { (x, y) } else { (y, x) };
                    let (pc, pu, pz) = (p(c), p(u), p(z));
                    let w = |i: usize| {
                        -1.0 / 16.0 * (2.0 * pc[i] - pu[i]) + 9.0 / 16.0 * (pc[i] + pu[i])
                            - 1.0 / 16.0 * pz[i]
                    };
                    [w(0), w(1), w(2)]
                } else {
                    let (a, b, c) = (p(x), p(y), p(z));
                    let w = |i: usize| 9.0 / 16.0 * (a[i] + b[i]) - 1.0 / 8.0 * c[i];
                    [w(0), w(1), w(2)]
                };
                let err = dist(def.positions[k], want);
                assert!(err < 1e-14, "{s:?} corner {with_corner}: {err:e}");
                assert!((dist(def.positions[k], o) - r).abs() > 1e-3 * r);
            }
        }
    }
}

#[test]
fn tagged_regular_grids_under_mobius_maps_stay_mobius_regular() {
    // A regular grid (unit quads, or the equilateral lattice for the triangle schemes) with
    // a straight crease along its middle row, boundary to boundary: the linear rules with
    // the crease reproduce the regular grid at half the spacing (each side is a half-grid
    // with a straight boundary curve), the Möbius rules equal the linear ones on it, and
    // they commute with Möbius maps. So on a Möbius image of the grid the tagged Möbius
    // result is the image of the regular grid: Möbius-regular at every interior vertex,
    // the crease's included, and equal to the image of the linear result.
    let n = 8;
    let s3 = 3f64.sqrt() / 2.0;
    let mut worst_map = 0.0f64;
    let mut worst_mr = 0.0f64;
    for (k, s) in ALL.into_iter().enumerate() {
        let param = if triangles(s) {
            tri_grid(n, n)
        } else {
            quad_grid(n, n)
        };
        let grid = if triangles(s) {
            param.map_positions(|p| [p[0] - 0.5 * p[1], s3 * p[1], 0.0])
        } else {
            param.clone()
        };
        let row: Vec<u32> = (0..=n as u32).map(|i| 4 * (n as u32 + 1) + i).collect();
        let creases = edges_of(&row, false);
        let infs = vec![INF; creases.len()];
        let tags = Tags::new().creases(&creases, &infs);
        let lin = run_tagged(&grid, &Options::new(s).levels(1), &tags)
            .unwrap()
            .0;
        let f = random_mobius(&grid, 31 + k as u64);
        let image = grid.map_positions(|p| f.apply(p).unwrap());
        let (mob, r) = run_tagged(&image, &mobius(s, 1), &tags).unwrap();
        assert_eq!((r.fallbacks, r.guarded), (0, 0), "{s:?}");
        // Interior: two original cells away from the outer boundary (whose corners the
        // curve rules round), in the parameter plane.
        let lin_param = run_tagged(&param, &Options::new(s).levels(1), &tags)
            .unwrap()
            .0;
        let interior: Vec<bool> = lin_param
            .positions
            .iter()
            .map(|p| p[0] > 2.01 && p[0] < n as f64 - 2.01 && p[1] > 2.01 && p[1] < n as f64 - 2.01)
            .collect();
        let expect = lin.map_positions(|p| f.apply(p).unwrap());
        let scale = diameter(&expect.positions);
        for (i, (&p, &q)) in mob.positions.iter().zip(&expect.positions).enumerate() {
            if interior[i] {
                let e = dist(p, q) / scale;
                assert!(e < 1e-10, "{s:?}: {e:e} at {i}");
                worst_map = worst_map.max(e);
            }
        }
        if s.pattern().keeps_old_vertices() {
            common::with_topology(&mob, |t| {
                for v in 0..t.num_vertices() as u32 {
                    if !interior[v as usize] {
                        continue;
                    }
                    let ring: Vec<Point> = t
                        .ring(v)
                        .unwrap()
                        .iter()
                        .map(|&u| t.position(u).unwrap())
                        .collect();
                    let mr =
                        nlsubdiv::metrics::mobius_regularity(t.position(v).unwrap(), &ring, true)
                            .unwrap();
                    assert!(mr < 1e-10, "{s:?}: Möbius regularity defect {mr:e} at {v}");
                    worst_mr = worst_mr.max(mr);
                }
            })
            .unwrap();
        }
    }
    println!("tagged regular grids: image error {worst_map:.2e}, regularity defect {worst_mr:.2e}");
}
