//! Sharp-feature tags on linear Modified Butterfly (`docs/creases.md`, "Modified
//! Butterfly"): expectations from the rule, not recorded output. An infinitely sharp crease
//! is the 4-point curve of its polygon (closed, and open with the virtual end points), a
//! crease is a cut (the tagged mesh refines as the mesh cut open along it), old vertices are
//! kept, sharpness 1 is one crease level then a smooth one, a fractional sharpness blends the
//! crease's own edge point, empty and zero tags are the untagged call bit for bit, and bad
//! tags keep their statuses.

// Test helpers outside #[test] functions: clippy's in-test allowances do not reach them.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::indexing_slicing
)]

mod common;

use common::{icosahedron, jitter, tri_grid, tri_torus, OwnedMesh};
use nlsubdiv::curve::four_point;
use nlsubdiv::mesh::MeshOut;
use nlsubdiv::scheme::{self, CreaseMethod, Options, Scheme, Scratch, Tags};
use nlsubdiv::{Result, Status};
use std::collections::BTreeSet;

const MB: Scheme = Scheme::ModifiedButterfly;

/// The public tagged path with owned buffers of exactly the planned sizes.
fn run_tagged(m: &OwnedMesh, opts: &Options, tags: &Tags<'_>) -> Result<OwnedMesh> {
    let mut su = vec![0u32; scheme::plan_scratch_size_tagged(&m.view(), tags)?];
    let p = scheme::plan_tagged(m.view(), opts, tags, &mut su)?;
    let o = p.output();
    su.resize(p.scratch.u32s, 0);
    let mut sp = vec![[0.0f64; 3]; p.scratch.points];
    let mut out = OwnedMesh {
        positions: vec![[f64::NAN; 3]; o.vertices],
        offsets: vec![u32::MAX; o.faces + 1],
        indices: vec![u32::MAX; o.indices],
    };
    let r = scheme::subdivide_tagged(
        m.view(),
        opts,
        tags,
        Scratch::new(&mut su, &mut sp),
        &mut MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices),
    )?;
    assert_eq!(r.sizes, o);
    Ok(out)
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

/// A jittered triangulated torus (8 × 6 quads, every face split) and the vertex ids of its
/// ring `j = 0`.
fn torus() -> (OwnedMesh, Vec<u32>) {
    (jitter(&tri_torus(8, 6), 0.08, 11), (0..8).collect())
}

#[test]
fn empty_and_zero_tags_are_untagged_bit_for_bit() {
    for m in [
        jitter(&tri_grid(4, 3), 0.05, 3),
        jitter(&icosahedron(), 0.05, 4),
        torus().0,
    ] {
        let opts = Options::new(MB).levels(2);
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
    let (m, ring) = torus();
    let creases: Vec<[u32; 2]> = (0..8).map(|i| [ring[i], ring[(i + 1) % 8]]).collect();
    let poly: Vec<[f64; 3]> = ring.iter().map(|&v| m.positions[v as usize]).collect();
    let tags = Tags::new().creases(&creases, &[10.0; 8]);
    let (plain, _) = common::run(&m, &Options::new(MB)).unwrap();
    for levels in 1..=3 {
        let out = run_tagged(&m, &Options::new(MB).levels(levels), &tags).unwrap();
        let curve = four_point_levels(&poly, true, levels);
        assert_eq!(curve.len(), 8 << levels);
        let err = one_way(&curve, &out.positions) / scale_of(&poly);
        assert!(err <= 1e-15, "{levels} levels: {err:e}");
        if levels == 1 {
            // The tags change the result: the untagged surface does not hold the curve.
            assert!(one_way(&curve, &plain.positions) / scale_of(&poly) > 1e-6);
            // Level 1 exactly: edge point of crease edge k is vertex V + id(k).
            let edges = sorted_edges(&m);
            let nv = m.positions.len();
            for i in 0..8 {
                let (a, b) = (ring[i], ring[(i + 1) % 8]);
                let id = edges.binary_search(&[a.min(b), a.max(b)]).unwrap();
                assert_eq!(out.positions[nv + id], curve[2 * i + 1], "edge {a}-{b}");
            }
        }
    }
}

#[test]
fn open_crease_ends_with_the_virtual_points_of_the_open_curve() {
    // A chain of four edges ending at two darts: the open 4-point curve, whose end segments
    // take the virtual points 2 p0 − p1.
    let (m, ring) = torus();
    let creases: Vec<[u32; 2]> = (0..4).map(|i| [ring[i], ring[i + 1]]).collect();
    let poly: Vec<[f64; 3]> = ring[..5].iter().map(|&v| m.positions[v as usize]).collect();
    let tags = Tags::new().creases(&creases, &[10.0; 4]);
    for levels in 1..=3 {
        let out = run_tagged(&m, &Options::new(MB).levels(levels), &tags).unwrap();
        let curve = four_point_levels(&poly, false, levels);
        let err = one_way(&curve, &out.positions) / scale_of(&poly);
        assert!(err <= 1e-15, "{levels} levels: {err:e}");
    }
    // A corner tag ends the crease too: two chains, each open.
    let creases: Vec<[u32; 2]> = (0..8).map(|i| [ring[i], ring[(i + 1) % 8]]).collect();
    let corners = [ring[0], ring[4]];
    let tags = Tags::new()
        .creases(&creases, &[10.0; 8])
        .corners(&corners, &[10.0, 10.0]);
    let out = run_tagged(&m, &Options::new(MB).levels(2), &tags).unwrap();
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
    // A 6 × 6 triangle grid, jittered off its plane; the loop is the square [2, 4]².
    let m = jitter(&tri_grid(6, 6), 0.1, 21);
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
    let s = scale_of(&m.positions);
    for levels in 1..=3 {
        let opts = Options::new(MB).levels(levels);
        let tagged = run_tagged(&m, &opts, &tags).unwrap();
        let (open, _) = common::run(&cut, &opts).unwrap();
        let (plain, _) = common::run(&m, &opts).unwrap();
        // Every vertex of each is a vertex of the other (the cut doubles the crease's).
        let e = one_way(&tagged.positions, &open.positions)
            .max(one_way(&open.positions, &tagged.positions));
        assert!(e / s <= 1e-15, "{levels} levels: {e:e}");
        assert!(one_way(&tagged.positions, &plain.positions) / s > 1e-6);
    }
}

#[test]
fn old_vertices_are_kept_bit_for_bit() {
    let (m, ring) = torus();
    let creases: Vec<[u32; 2]> = (0..8).map(|i| [ring[i], ring[(i + 1) % 8]]).collect();
    let sharp = [10.0, 2.5, 0.5, 1.0, 3.0, 10.0, 0.25, 1.75];
    for method in [CreaseMethod::Uniform, CreaseMethod::Chaikin] {
        let tags = Tags::new()
            .creases(&creases, &sharp)
            .corners(&[20], &[2.0])
            .method(method);
        for levels in 1..=3 {
            let out = run_tagged(&m, &Options::new(MB).levels(levels), &tags).unwrap();
            assert_eq!(&out.positions[..m.positions.len()], &m.positions[..]);
        }
    }
}

#[test]
fn sharpness_one_is_one_crease_level_then_a_smooth_level() {
    let (m, ring) = torus();
    let creases: Vec<[u32; 2]> = (0..8).map(|i| [ring[i], ring[(i + 1) % 8]]).collect();
    let one = Tags::new().creases(&creases, &[1.0; 8]);
    let inf = Tags::new().creases(&creases, &[10.0; 8]);
    let two = run_tagged(&m, &Options::new(MB).levels(2), &one).unwrap();
    let first = run_tagged(&m, &Options::new(MB), &inf).unwrap();
    let (then, _) = common::run(&first, &Options::new(MB)).unwrap();
    assert_eq!(two, then);
    // And the crease is really there in the first level.
    let (plain, _) = common::run(&m, &Options::new(MB).levels(2)).unwrap();
    assert_ne!(two.positions, plain.positions);
}

#[test]
fn fractional_sharpness_blends_the_edge_point() {
    // One tagged edge of sharpness 0.25: its edge point is 1/4 of the crease rule (an
    // isolated crease edge ends at both ends: the 4-point rule with virtual points is the
    // midpoint) and 3/4 of the untagged rule.
    let (m, _) = torus();
    let edges = sorted_edges(&m);
    let nv = m.positions.len();
    let k = 17;
    let [a, b] = edges[k];
    let creases = [[b, a]];
    let opts = Options::new(MB);
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
fn bad_tags_keep_their_statuses_with_butterfly() {
    let m = icosahedron();
    let opts = Options::new(MB).levels(2);
    let err = |creases: &[[u32; 2]], s: &[f64], corners: &[u32], cs: &[f64]| {
        let tags = Tags::new().creases(creases, s).corners(corners, cs);
        run_tagged(&m, &opts, &tags).unwrap_err()
    };
    let f = m.faces();
    let (a, b) = (f[0][0], f[0][1]);
    // A pair that is no edge: a vertex and one not in its star.
    let far = (0..12u32)
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
    let e = err(&[[a, 12]], &[1.0], &[], &[]);
    assert_eq!((e.status, e.element), (Status::IndexOutOfRange, 0));
    let e = err(&[], &[], &[4, 4], &[1.0, 2.0]);
    assert_eq!((e.status, e.element), (Status::RepeatedTag, 1));
    let e = err(&[[a, b]], &[], &[], &[]);
    assert_eq!(e.status, Status::InvalidArgument);
    // The Möbius version takes no tags.
    let one = [[a, b]];
    let tags = Tags::new().creases(&one, &[1.0]);
    let e = run_tagged(&m, &Options::new(MB).mobius(true), &tags).unwrap_err();
    assert_eq!(e.status, Status::TagsNotSupported);
}
