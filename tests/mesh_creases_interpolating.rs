//! Sharp-feature tags on linear Modified Butterfly and Kobbelt (`docs/creases.md`, "The
//! interpolating schemes"): expectations from the rule, not recorded output. An infinitely
//! sharp crease is the 4-point curve of its polygon (closed, and open with the virtual end
//! points), a crease is a cut (the tagged mesh refines as the mesh cut open along it), old
//! vertices are kept, sharpness 1 is one crease level then a smooth one, a fractional
//! sharpness blends the crease's own edge point, empty and zero tags are the untagged call
//! bit for bit, and bad tags keep their statuses.

// Test helpers outside #[test] functions: clippy's in-test allowances do not reach them.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]

mod common;

use common::{cube, icosahedron, jitter, quad_grid, quad_torus, tri_grid, tri_torus, OwnedMesh};
use nlsubdiv::curve::four_point;
use nlsubdiv::scheme::{CreaseMethod, Options, Scheme, Tags};
use nlsubdiv::{Result, Status};
use std::collections::BTreeSet;

const MB: Scheme = Scheme::ModifiedButterfly;
const KOBBELT: Scheme = Scheme::Kobbelt;
const BOTH: [Scheme; 2] = [MB, KOBBELT];

/// The public tagged path ([`common::run_tagged`]), its output.
fn run_tagged(m: &OwnedMesh, opts: &Options, tags: &Tags<'_>) -> Result<OwnedMesh> {
    common::run_tagged(m, opts, tags).map(|(o, _)| o)
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The largest distance from a point of `a` to its nearest point of `b`.
fn one_way(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .map(|p| b.iter().map(|q| dist(*p, *q)).fold(f64::INFINITY, f64::min))
        .fold(0.0, f64::max)
}

fn scale_of(p: &[[f64; 3]]) -> f64 {
    p.iter()
        .flat_map(|q| q.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

/// The edges of `m` sorted by `(min, max)` vertex key: the kernel's edge numbering, so the
/// edge point of edge `k` is output vertex `V + k`.
fn sorted_edges(m: &OwnedMesh) -> Vec<[u32; 2]> {
    let mut set = BTreeSet::new();
    for f in m.faces() {
        for i in 0..f.len() {
            let (a, b) = (f[i], f[(i + 1) % f.len()]);
            set.insert([a.min(b), a.max(b)]);
        }
    }
    set.into_iter().collect()
}

/// `levels` levels of the 4-point curve scheme on `poly`.
fn four_point_levels(poly: &[[f64; 3]], closed: bool, levels: usize) -> Vec<[f64; 3]> {
    let mut cur = poly.to_vec();
    for _ in 0..levels {
        let n = if closed {
            2 * cur.len()
        } else {
            2 * cur.len() - 1
        };
        let mut out = vec![[0.0; 3]; n];
        assert_eq!(four_point::refine(&cur, closed, &mut out).unwrap(), n);
        cur = out;
    }
    cur
}

/// A jittered torus of 8 × 6 quads (for Butterfly every quad split in two triangles) and
/// the vertex ids of its ring `j = 0`.
fn torus(s: Scheme) -> (OwnedMesh, Vec<u32>) {
    let m = if s == MB {
        tri_torus(8, 6)
    } else {
        quad_torus(8, 6, 3.0, 1.0)
    };
    (jitter(&m, 0.08, 11), (0..8).collect())
}

/// A jittered `n × n` grid of the scheme's faces.
fn grid(s: Scheme, n: usize, amp: f64, seed: u64) -> OwnedMesh {
    let m = if s == MB {
        tri_grid(n, n)
    } else {
        quad_grid(n, n)
    };
    jitter(&m, amp, seed)
}

#[test]
fn empty_and_zero_tags_are_untagged_bit_for_bit() {
    for (s, m) in [
        (MB, grid(MB, 4, 0.05, 3)),
        (MB, jitter(&icosahedron(), 0.05, 4)),
        (MB, torus(MB).0),
        (KOBBELT, grid(KOBBELT, 4, 0.05, 3)),
        (KOBBELT, jitter(&cube(), 0.05, 4)),
        (KOBBELT, torus(KOBBELT).0),
    ] {
        let opts = Options::new(s).levels(2);
        let (plain, _) = common::run(&m, &opts).unwrap();
        assert_eq!(run_tagged(&m, &opts, &Tags::new()).unwrap(), plain);
        // A zero tag takes the tagged rules, which must reduce to the untagged ones.
        let f = m.faces();
        let creases = [[f[0][0], f[0][1]], [f[3][1], f[3][2]]];
        let tags = Tags::new()
            .creases(&creases, &[0.0, 0.0])
            .corners(&[2], &[0.0]);
        assert_eq!(run_tagged(&m, &opts, &tags).unwrap(), plain);
    }
}

#[test]
fn closed_infinitely_sharp_crease_is_the_four_point_curve_of_its_polygon() {
    for s in BOTH {
        closed_infinitely_sharp_crease_is_the_four_point_curve_of_its_polygon_for(s);
    }
}

fn closed_infinitely_sharp_crease_is_the_four_point_curve_of_its_polygon_for(s: Scheme) {
    // A staircase around the torus (six steps right and up, then two right): a closed crease
    // of 14 edges that no grid line of the untagged surface follows.
    let (m, _) = torus(s);
    let mut ring = Vec::new();
    for k in 0..6u32 {
        ring.push(k * 8 + k);
        ring.push(k * 8 + k + 1);
    }
    ring.extend([6, 7]);
    let n = ring.len();
    let creases: Vec<[u32; 2]> = (0..n).map(|i| [ring[i], ring[(i + 1) % n]]).collect();
    let poly: Vec<[f64; 3]> = ring.iter().map(|&v| m.positions[v as usize]).collect();
    let sharpness = vec![10.0; n];
    let tags = Tags::new().creases(&creases, &sharpness);
    let (plain, _) = common::run(&m, &Options::new(s)).unwrap();
    for levels in 1..=3 {
        let out = run_tagged(&m, &Options::new(s).levels(levels), &tags).unwrap();
        let curve = four_point_levels(&poly, true, levels);
        assert_eq!(curve.len(), n << levels);
        let err = one_way(&curve, &out.positions) / scale_of(&poly);
        assert!(err <= 1e-15, "{s:?}, {levels} levels: {err:e}");
        if levels == 1 {
            // The tags change the result: the untagged surface does not hold the curve.
            assert!(one_way(&curve, &plain.positions) / scale_of(&poly) > 1e-6);
            // Level 1 exactly: edge point of crease edge k is vertex V + id(k).
            let edges = sorted_edges(&m);
            let nv = m.positions.len();
            for i in 0..n {
                let (a, b) = (ring[i], ring[(i + 1) % n]);
                let id = edges.binary_search(&[a.min(b), a.max(b)]).unwrap();
                assert_eq!(out.positions[nv + id], curve[2 * i + 1], "edge {a}-{b}");
            }
        }
    }
}

#[test]
fn open_crease_ends_with_the_virtual_points_of_the_open_curve() {
    for s in BOTH {
        open_crease_ends_with_the_virtual_points_of_the_open_curve_for(s);
    }
}

fn open_crease_ends_with_the_virtual_points_of_the_open_curve_for(s: Scheme) {
    // A chain of four edges ending at two darts: the open 4-point curve, whose end segments
    // take the virtual points 2 p0 − p1.
    let (m, ring) = torus(s);
    let creases: Vec<[u32; 2]> = (0..4).map(|i| [ring[i], ring[i + 1]]).collect();
    let poly: Vec<[f64; 3]> = ring[..5].iter().map(|&v| m.positions[v as usize]).collect();
    let tags = Tags::new().creases(&creases, &[10.0; 4]);
    for levels in 1..=3 {
        let out = run_tagged(&m, &Options::new(s).levels(levels), &tags).unwrap();
        let curve = four_point_levels(&poly, false, levels);
        let err = one_way(&curve, &out.positions) / scale_of(&poly);
        assert!(err <= 1e-15, "{s:?}, {levels} levels: {err:e}");
    }
    // A corner tag ends the crease too: two chains, each open.
    let creases: Vec<[u32; 2]> = (0..8).map(|i| [ring[i], ring[(i + 1) % 8]]).collect();
    let corners = [ring[0], ring[4]];
    let tags = Tags::new()
        .creases(&creases, &[10.0; 8])
        .corners(&corners, &[10.0, 10.0]);
    let out = run_tagged(&m, &Options::new(s).levels(2), &tags).unwrap();
    let all: Vec<[f64; 3]> = ring.iter().map(|&v| m.positions[v as usize]).collect();
    for half in [&all[0..5], &[all[4], all[5], all[6], all[7], all[0]][..]] {
        let curve = four_point_levels(half, false, 2);
        let err = one_way(&curve, &out.positions) / scale_of(&all);
        assert!(err <= 1e-15, "{err:e}");
    }
}

/// `m` cut open along the closed loop `loop_` (consecutive vertices): every face in
/// `inside` takes copies of the loop vertices, appended after the others.
fn cut_open(m: &OwnedMesh, loop_: &[u32], inside: impl Fn(&[u32]) -> bool) -> OwnedMesh {
    let mut pos = m.positions.clone();
    let mut copy = std::collections::HashMap::new();
    for &v in loop_ {
        copy.insert(v, pos.len() as u32);
        pos.push(m.positions[v as usize]);
    }
    let faces: Vec<Vec<u32>> = m
        .faces()
        .into_iter()
        .map(|f| {
            if inside(&f) {
                f.iter().map(|v| *copy.get(v).unwrap_or(v)).collect()
            } else {
                f
            }
        })
        .collect();
    OwnedMesh::from_faces(pos, &faces)
}

#[test]
fn a_closed_crease_refines_as_the_mesh_cut_open_along_it() {
    for s in BOTH {
        a_closed_crease_refines_as_the_mesh_cut_open_along_it_for(s);
    }
}

fn a_closed_crease_refines_as_the_mesh_cut_open_along_it_for(s: Scheme) {
    // A 6 × 6 triangle grid, jittered off its plane; the loop is the square [2, 4]².
    let m = grid(s, 6, 0.1, 21);
    let id = |i: u32, j: u32| j * 7 + i;
    let loop_: Vec<u32> = [
        (2, 2),
        (3, 2),
        (4, 2),
        (4, 3),
        (4, 4),
        (3, 4),
        (2, 4),
        (2, 3),
    ]
    .iter()
    .map(|&(i, j)| id(i, j))
    .collect();
    let creases: Vec<[u32; 2]> = (0..8).map(|k| [loop_[k], loop_[(k + 1) % 8]]).collect();
    let tags = Tags::new().creases(&creases, &[10.0; 8]);
    // A face is inside when all its grid coordinates lie in [2, 4].
    let inside = |f: &[u32]| {
        f.iter()
            .all(|&v| (2..=4).contains(&(v % 7)) && (2..=4).contains(&(v / 7)))
    };
    let cut = cut_open(&m, &loop_, inside);
    let sc = scale_of(&m.positions);
    for levels in 1..=3 {
        let opts = Options::new(s).levels(levels);
        let tagged = run_tagged(&m, &opts, &tags).unwrap();
        let (open, _) = common::run(&cut, &opts).unwrap();
        let (plain, _) = common::run(&m, &opts).unwrap();
        // Every vertex of each is a vertex of the other (the cut doubles the crease's).
        let e = one_way(&tagged.positions, &open.positions)
            .max(one_way(&open.positions, &tagged.positions));
        assert!(e / sc <= 1e-15, "{s:?}, {levels} levels: {e:e}");
        assert!(one_way(&tagged.positions, &plain.positions) / sc > 1e-6);
    }
}

#[test]
fn old_vertices_are_kept_bit_for_bit() {
    for s in BOTH {
        old_vertices_are_kept_bit_for_bit_for(s);
    }
}

fn old_vertices_are_kept_bit_for_bit_for(s: Scheme) {
    let (m, ring) = torus(s);
    let creases: Vec<[u32; 2]> = (0..8).map(|i| [ring[i], ring[(i + 1) % 8]]).collect();
    let sharp = [10.0, 2.5, 0.5, 1.0, 3.0, 10.0, 0.25, 1.75];
    for method in [CreaseMethod::Uniform, CreaseMethod::Chaikin] {
        let tags = Tags::new()
            .creases(&creases, &sharp)
            .corners(&[20], &[2.0])
            .method(method);
        for levels in 1..=3 {
            let out = run_tagged(&m, &Options::new(s).levels(levels), &tags).unwrap();
            assert_eq!(&out.positions[..m.positions.len()], &m.positions[..]);
        }
    }
}

#[test]
fn sharpness_one_is_one_crease_level_then_a_smooth_level() {
    for s in BOTH {
        sharpness_one_is_one_crease_level_then_a_smooth_level_for(s);
    }
}

fn sharpness_one_is_one_crease_level_then_a_smooth_level_for(s: Scheme) {
    let (m, ring) = torus(s);
    let creases: Vec<[u32; 2]> = (0..8).map(|i| [ring[i], ring[(i + 1) % 8]]).collect();
    let one = Tags::new().creases(&creases, &[1.0; 8]);
    let inf = Tags::new().creases(&creases, &[10.0; 8]);
    let two = run_tagged(&m, &Options::new(s).levels(2), &one).unwrap();
    let first = run_tagged(&m, &Options::new(s), &inf).unwrap();
    let (then, _) = common::run(&first, &Options::new(s)).unwrap();
    assert_eq!(two, then);
    // And the crease is really there in the first level.
    let (plain, _) = common::run(&m, &Options::new(s).levels(2)).unwrap();
    assert_ne!(two.positions, plain.positions);
}

#[test]
fn fractional_sharpness_blends_the_edge_point() {
    for s in BOTH {
        fractional_sharpness_blends_the_edge_point_for(s);
    }
}

fn fractional_sharpness_blends_the_edge_point_for(s: Scheme) {
    // One tagged edge of sharpness 0.25: its edge point is 1/4 of the crease rule (an
    // isolated crease edge ends at both ends: the 4-point rule with virtual points is the
    // midpoint) and 3/4 of the untagged rule.
    let (m, _) = torus(s);
    let edges = sorted_edges(&m);
    let nv = m.positions.len();
    let k = 17;
    let [a, b] = edges[k];
    let creases = [[b, a]];
    let opts = Options::new(s);
    let (plain, _) = common::run(&m, &opts).unwrap();
    let full = run_tagged(&m, &opts, &Tags::new().creases(&creases, &[10.0])).unwrap();
    let (pa, pb) = (m.positions[a as usize], m.positions[b as usize]);
    let mid: [f64; 3] = std::array::from_fn(|c| 0.5 * (pa[c] + pb[c]));
    assert!(dist(full.positions[nv + k], mid) <= 1e-15 * scale_of(&m.positions));
    let quarter = run_tagged(&m, &opts, &Tags::new().creases(&creases, &[0.25])).unwrap();
    let want: [f64; 3] = std::array::from_fn(|c| {
        0.25 * full.positions[nv + k][c] + 0.75 * plain.positions[nv + k][c]
    });
    assert!(dist(quarter.positions[nv + k], want) <= 1e-15 * scale_of(&m.positions));
    assert!(dist(quarter.positions[nv + k], plain.positions[nv + k]) > 1e-6);
}

#[test]
fn bad_tags_keep_their_statuses_with_butterfly_and_kobbelt() {
    bad_tags_for(MB, &icosahedron());
    bad_tags_for(KOBBELT, &cube());
}

fn bad_tags_for(s: Scheme, m: &OwnedMesh) {
    let opts = Options::new(s).levels(2);
    let err = |creases: &[[u32; 2]], s: &[f64], corners: &[u32], cs: &[f64]| {
        let tags = Tags::new().creases(creases, s).corners(corners, cs);
        run_tagged(m, &opts, &tags).unwrap_err()
    };
    let f = m.faces();
    let (a, b) = (f[0][0], f[0][1]);
    // A pair that is no edge: a vertex and one not in its star.
    let nv = m.positions.len() as u32;
    let far = (0..nv)
        .find(|&v| v != a && !f.iter().any(|g| g.contains(&a) && g.contains(&v)))
        .unwrap();
    let e = err(&[[a, b], [a, far]], &[1.0, 1.0], &[], &[]);
    assert_eq!((e.status, e.element), (Status::TagNotAnEdge, 1));
    let e = err(&[[a, b], [b, a]], &[1.0, 2.0], &[], &[]);
    assert_eq!((e.status, e.element), (Status::RepeatedTag, 1));
    for bad in [f64::NAN, -0.5, f64::INFINITY] {
        let e = err(&[[a, b]], &[bad], &[], &[]);
        assert_eq!((e.status, e.element), (Status::InvalidSharpness, 0));
        let e = err(&[[a, b]], &[1.0], &[3], &[bad]);
        assert_eq!((e.status, e.element), (Status::InvalidSharpness, 1));
    }
    let e = err(&[[a, nv]], &[1.0], &[], &[]);
    assert_eq!((e.status, e.element), (Status::IndexOutOfRange, 0));
    let e = err(&[], &[], &[4, 4], &[1.0, 2.0]);
    assert_eq!((e.status, e.element), (Status::RepeatedTag, 1));
    let e = err(&[[a, b]], &[], &[], &[]);
    assert_eq!(e.status, Status::InvalidArgument);
    // The Möbius version takes tags (`tests/mesh_creases_mobius.rs`); its bad tags are the
    // same statuses.
    let e = run_tagged(
        m,
        &Options::new(s).mobius(true),
        &Tags::new().creases(&[[a, nv]], &[1.0]),
    )
    .unwrap_err();
    assert_eq!((e.status, e.element), (Status::IndexOutOfRange, 0));
}

#[test]
fn a_crease_across_a_grid_ends_at_the_boundary() {
    for s in BOTH {
        a_crease_across_a_grid_ends_at_the_boundary_for(s);
    }
}

fn a_crease_across_a_grid_ends_at_the_boundary_for(s: Scheme) {
    // The grid line j = 3 of a 6 × 6 grid, boundary to boundary: its ends have three sharp
    // edges (two boundary edges and the crease), so the crease is the open 4-point curve of
    // its polygon, and the boundary curves end there too.
    let m = grid(s, 6, 0.1, 5);
    let line: Vec<u32> = (0..7).map(|i| 3 * 7 + i).collect();
    let creases: Vec<[u32; 2]> = (0..6).map(|i| [line[i], line[i + 1]]).collect();
    let tags = Tags::new().creases(&creases, &[10.0; 6]);
    let poly: Vec<[f64; 3]> = line.iter().map(|&v| m.positions[v as usize]).collect();
    let sc = scale_of(&m.positions);
    for levels in 1..=3 {
        let out = run_tagged(&m, &Options::new(s).levels(levels), &tags).unwrap();
        let curve = four_point_levels(&poly, false, levels);
        let err = one_way(&curve, &out.positions) / sc;
        assert!(err <= 1e-15, "{s:?}, {levels} levels: {err:e}");
    }
    // Level 1: the boundary edge (14, 21) of the column i = 0 ends at the crease's end 21:
    // its point beyond vertex 21 is the virtual point 2 p21 − p14 (beyond 14 the real 7).
    let out = run_tagged(&m, &Options::new(s), &tags).unwrap();
    let (a, b) = (14u32, 21u32);
    let edges = sorted_edges(&m);
    let id = edges.binary_search(&[a, b]).unwrap();
    let p = |v: u32| m.positions[v as usize];
    let virt = four_point::virtual_end_point(p(b), p(a));
    let want = four_point::edge_point(p(7), p(a), p(b), virt);
    assert_eq!(out.positions[m.positions.len() + id], want, "{s:?}");
}
