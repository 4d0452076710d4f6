//! The linear schemes: output sizes equal the size queries, outputs are valid oriented
//! manifolds with the input's Euler characteristic, positions equal independent reference
//! implementations of peer-rules.md written here with std collections, interpolating schemes
//! keep old vertices bit for bit, Kobbelt reproduces the 4-point rule and bicubics, every
//! scheme is affine-covariant and deterministic, and multi-level plans are exact.
// Test code: indexing and unwrap are fine here.
#![allow(
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

mod common;

use common::*;
use nlsubdiv::mesh::MeshOut;
use nlsubdiv::scheme::{self, Options, Scheme, Scratch, MAX_LEVELS};
use nlsubdiv::{Point, Status};
use std::collections::{BTreeMap, BTreeSet};
use std::f64::consts::PI;

// ------------------------------------------------------------ reference implementations

struct Ref {
    pos: Vec<Point>,
    faces: Vec<Vec<u32>>,
    /// Edges in (min, max) order with their faces.
    edges: BTreeMap<(u32, u32), Vec<usize>>,
    nbrs: Vec<BTreeSet<u32>>,
    vfaces: Vec<Vec<usize>>,
}

fn add(a: Point, b: Point) -> Point {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn mul(a: Point, s: f64) -> Point {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn avg(ps: &[Point]) -> Point {
    mul(
        ps.iter().fold([0.0; 3], |a, &b| add(a, b)),
        1.0 / ps.len() as f64,
    )
}

impl Ref {
    fn new(m: &OwnedMesh) -> Ref {
        let faces = m.faces();
        let mut edges: BTreeMap<(u32, u32), Vec<usize>> = BTreeMap::new();
        let mut nbrs = vec![BTreeSet::new(); m.positions.len()];
        let mut vfaces = vec![Vec::new(); m.positions.len()];
        for (fi, f) in faces.iter().enumerate() {
            for i in 0..f.len() {
                let (a, b) = (f[i], f[(i + 1) % f.len()]);
                edges.entry((a.min(b), a.max(b))).or_default().push(fi);
                nbrs[a as usize].insert(b);
                nbrs[b as usize].insert(a);
                vfaces[a as usize].push(fi);
            }
        }
        Ref {
            pos: m.positions.clone(),
            faces,
            edges,
            nbrs,
            vfaces,
        }
    }
    fn p(&self, v: u32) -> Point {
        self.pos[v as usize]
    }
    fn is_boundary_edge(&self, a: u32, b: u32) -> bool {
        self.edges[&(a.min(b), a.max(b))].len() == 1
    }
    fn boundary_nbrs(&self, v: u32) -> Vec<u32> {
        self.nbrs[v as usize]
            .iter()
            .copied()
            .filter(|&u| self.is_boundary_edge(v, u))
            .collect()
    }
    fn is_boundary(&self, v: u32) -> bool {
        !self.boundary_nbrs(v).is_empty()
    }
    /// The vertex of triangle `f` that is neither `a` nor `b`.
    fn third(&self, f: usize, a: u32, b: u32) -> u32 {
        *self.faces[f].iter().find(|&&x| x != a && x != b).unwrap()
    }
    fn face_centroid(&self, f: usize) -> Point {
        avg(&self.faces[f].iter().map(|&v| self.p(v)).collect::<Vec<_>>())
    }
    /// Ring of interior vertex v in rotational order starting at q0.
    fn ring_from(&self, v: u32, q0: u32) -> Vec<u32> {
        let mut next = BTreeMap::new();
        for &f in &self.vfaces[v as usize] {
            let face = &self.faces[f];
            let k = face.iter().position(|&x| x == v).unwrap();
            let after = face[(k + 1) % face.len()];
            let before = face[(k + face.len() - 1) % face.len()];
            next.insert(after, before);
        }
        let mut r = vec![q0];
        while r.len() < self.nbrs[v as usize].len() {
            r.push(next[r.last().unwrap()]);
        }
        r
    }
}

fn ref_loop(m: &OwnedMesh) -> Vec<Point> {
    let r = Ref::new(m);
    let mut out = Vec::new();
    for v in 0..m.positions.len() as u32 {
        let n = r.nbrs[v as usize].len();
        out.push(if n == 0 {
            r.p(v)
        } else if r.is_boundary(v) {
            let b = r.boundary_nbrs(v);
            add(mul(r.p(v), 0.75), mul(add(r.p(b[0]), r.p(b[1])), 0.125))
        } else {
            let c = 3.0 / 8.0 + 0.25 * (2.0 * PI / n as f64).cos();
            let alpha = 5.0 / 8.0 - c * c;
            let s = r.nbrs[v as usize]
                .iter()
                .fold([0.0; 3], |a, &q| add(a, r.p(q)));
            add(mul(r.p(v), 1.0 - alpha), mul(s, alpha / n as f64))
        });
    }
    for (&(a, b), fs) in &r.edges {
        let ab = add(r.p(a), r.p(b));
        out.push(if fs.len() == 1 {
            mul(ab, 0.5)
        } else {
            let cd = add(r.p(r.third(fs[0], a, b)), r.p(r.third(fs[1], a, b)));
            add(mul(ab, 3.0 / 8.0), mul(cd, 1.0 / 8.0))
        });
    }
    out
}

fn ref_catmull_clark(m: &OwnedMesh) -> Vec<Point> {
    let r = Ref::new(m);
    let fp: Vec<Point> = (0..r.faces.len()).map(|f| r.face_centroid(f)).collect();
    let mut out = Vec::new();
    for v in 0..m.positions.len() as u32 {
        let n = r.nbrs[v as usize].len();
        out.push(if n == 0 {
            r.p(v)
        } else if r.is_boundary(v) {
            let b = r.boundary_nbrs(v);
            add(mul(r.p(v), 0.75), mul(add(r.p(b[0]), r.p(b[1])), 0.125))
        } else {
            // (F + 2R + (n − 3) v) / n, the CGAL form.
            let nf = n as f64;
            let f = avg(&r.vfaces[v as usize]
                .iter()
                .map(|&f| fp[f])
                .collect::<Vec<_>>());
            let rr = avg(&r.nbrs[v as usize]
                .iter()
                .map(|&q| mul(add(r.p(q), r.p(v)), 0.5))
                .collect::<Vec<_>>());
            mul(add(add(f, mul(rr, 2.0)), mul(r.p(v), nf - 3.0)), 1.0 / nf)
        });
    }
    for (&(a, b), fs) in &r.edges {
        let ab = add(r.p(a), r.p(b));
        out.push(if fs.len() == 1 {
            mul(ab, 0.5)
        } else {
            mul(add(ab, add(fp[fs[0]], fp[fs[1]])), 0.25)
        });
    }
    out.extend(fp);
    out
}

fn zorin(n: usize, j: usize) -> f64 {
    match n {
        3 => [5.0 / 12.0, -1.0 / 12.0, -1.0 / 12.0][j],
        4 => [3.0 / 8.0, 0.0, -1.0 / 8.0, 0.0][j],
        _ => {
            let t = 2.0 * PI * j as f64 / n as f64;
            (0.25 + t.cos() + 0.5 * (2.0 * t).cos()) / n as f64
        }
    }
}

fn ref_butterfly(m: &OwnedMesh) -> Vec<Point> {
    let r = Ref::new(m);
    let mut out = m.positions.clone();
    let stencil = |v: u32, other: u32| {
        let ring = r.ring_from(v, other);
        let n = ring.len();
        ring.iter()
            .enumerate()
            .fold(mul(r.p(v), 0.75), |a, (j, &q)| {
                add(a, mul(r.p(q), zorin(n, j)))
            })
    };
    for (&(a, b), fs) in &r.edges {
        if fs.len() == 1 {
            let beyond = |v: u32, o: u32| *r.boundary_nbrs(v).iter().find(|&&x| x != o).unwrap();
            let (p0, p1) = (beyond(a, b), beyond(b, a));
            out.push(add(
                mul(add(r.p(a), r.p(b)), 9.0 / 16.0),
                mul(add(r.p(p0), r.p(p1)), -1.0 / 16.0),
            ));
            continue;
        }
        let irr = |v: u32| !r.is_boundary(v) && r.nbrs[v as usize].len() != 6;
        out.push(match (irr(a), irr(b)) {
            (false, false) => {
                let mut acc = mul(add(r.p(a), r.p(b)), 0.5);
                for &f in fs {
                    let z = r.third(f, a, b);
                    acc = add(acc, mul(r.p(z), 0.125));
                    for (u, w, opp) in [(a, z, b), (b, z, a)] {
                        let ef = &r.edges[&(u.min(w), u.max(w))];
                        let c = if ef.len() == 1 {
                            add(add(r.p(u), r.p(w)), mul(r.p(opp), -1.0))
                        } else {
                            let g = *ef.iter().find(|&&g| g != f).unwrap();
                            r.p(r.third(g, u, w))
                        };
                        acc = add(acc, mul(c, -1.0 / 16.0));
                    }
                }
                acc
            }
            (true, false) => stencil(a, b),
            (false, true) => stencil(b, a),
            (true, true) => mul(add(stencil(a, b), stencil(b, a)), 0.5),
        });
    }
    out
}

fn ref_doo_sabin(m: &OwnedMesh) -> Vec<Point> {
    let r = Ref::new(m);
    let mut out = Vec::new();
    for f in &r.faces {
        let n = f.len();
        for i in 0..n {
            let mut acc = [0.0; 3];
            for k in 0..n {
                let w = if k == 0 {
                    0.25 + 5.0 / (4.0 * n as f64)
                } else {
                    (3.0 + 2.0 * (2.0 * PI * k as f64 / n as f64).cos()) / (4.0 * n as f64)
                };
                acc = add(acc, mul(r.p(f[(i + k) % n]), w));
            }
            out.push(acc);
        }
    }
    for v in 0..m.positions.len() as u32 {
        if r.nbrs[v as usize].is_empty() {
            out.push(r.p(v));
        }
    }
    out
}

fn assert_close(got: &[Point], want: &[Point], tol: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: vertex count");
    let scale = want
        .iter()
        .flat_map(|p| p.iter())
        .fold(1.0f64, |a, &c| a.max(c.abs()));
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        for k in 0..3 {
            assert!(
                (g[k] - w[k]).abs() <= tol * scale,
                "{what}: vertex {i}: got {g:?}, want {w:?}"
            );
        }
    }
}

// ------------------------------------------------------------ test meshes

fn closed_meshes() -> Vec<(&'static str, OwnedMesh)> {
    vec![
        ("tetrahedron", jitter(&tetrahedron(), 0.1, 1)),
        ("bipyramid 5", jitter(&bipyramid(5), 0.1, 2)),
        ("bipyramid 9", jitter(&bipyramid(9), 0.1, 3)),
        ("tri torus", jitter(&tri_torus(6, 5), 0.1, 4)),
        ("cube", jitter(&cube(), 0.1, 5)),
        ("quad torus", jitter(&quad_torus(6, 5, 3.0, 1.0), 0.1, 6)),
        ("prism 7", jitter(&prism(7), 0.1, 7)),
    ]
}

fn open_meshes() -> Vec<(&'static str, OwnedMesh)> {
    let mut tri_hole = tri_grid(4, 4);
    tri_hole.positions.push([9.0, 9.0, 9.0]); // an isolated vertex
    vec![
        ("fan 3", jitter(&fan(3), 0.1, 8)),
        ("fan 7", jitter(&fan(7), 0.1, 9)),
        ("tri grid + isolated", jitter(&tri_hole, 0.1, 10)),
        ("quad grid", jitter(&quad_grid(5, 4), 0.1, 11)),
        ("quad 1x1", quad_grid(1, 1)),
        ("quad strip", jitter(&quad_grid(4, 1), 0.1, 12)),
    ]
}

fn all_meshes() -> Vec<(&'static str, OwnedMesh)> {
    let mut v = closed_meshes();
    v.extend(open_meshes());
    v
}

fn accepts(s: Scheme, m: &OwnedMesh) -> bool {
    let faces = m.faces();
    match s {
        Scheme::Loop | Scheme::ModifiedButterfly => faces.iter().all(|f| f.len() == 3),
        Scheme::Kobbelt => faces.iter().all(|f| f.len() == 4),
        _ => true,
    }
}

fn euler(m: &OwnedMesh) -> i64 {
    with_topology(m, |t| t.euler_characteristic()).unwrap()
}

// ------------------------------------------------------------ tests

#[test]
fn loop_equals_reference() {
    for (name, m) in all_meshes() {
        if !accepts(Scheme::Loop, &m) {
            continue;
        }
        let out = subdivide(Scheme::Loop, &m).unwrap();
        assert_close(&out.positions, &ref_loop(&m), 1e-14, name);
    }
}

#[test]
fn catmull_clark_equals_reference() {
    for (name, m) in all_meshes() {
        let out = subdivide(Scheme::CatmullClark, &m).unwrap();
        assert_close(&out.positions, &ref_catmull_clark(&m), 1e-14, name);
    }
}

#[test]
fn butterfly_equals_reference() {
    for (name, m) in all_meshes() {
        if !accepts(Scheme::ModifiedButterfly, &m) {
            continue;
        }
        let out = subdivide(Scheme::ModifiedButterfly, &m).unwrap();
        assert_close(&out.positions, &ref_butterfly(&m), 1e-14, name);
    }
}

#[test]
fn doo_sabin_equals_reference() {
    for (name, m) in all_meshes() {
        let out = subdivide(Scheme::DooSabin, &m).unwrap();
        assert_close(&out.positions, &ref_doo_sabin(&m), 1e-14, name);
    }
}

#[test]
fn loop_and_catmull_clark_connectivity_as_documented() {
    let m = jitter(&tri_torus(4, 3), 0.1, 20);
    let r = Ref::new(&m);
    let eid: BTreeMap<(u32, u32), u32> = r
        .edges
        .keys()
        .enumerate()
        .map(|(i, &k)| (k, i as u32))
        .collect();
    let nv = m.positions.len() as u32;
    let e = |a: u32, b: u32| nv + eid[&(a.min(b), a.max(b))];
    let out = subdivide(Scheme::Loop, &m).unwrap();
    let mut want = Vec::new();
    for f in &r.faces {
        let (v0, v1, v2) = (f[0], f[1], f[2]);
        let (e0, e1, e2) = (e(v0, v1), e(v1, v2), e(v2, v0));
        want.extend([
            vec![v0, e0, e2],
            vec![v1, e1, e0],
            vec![v2, e2, e1],
            vec![e0, e1, e2],
        ]);
    }
    assert_eq!(out.faces(), want);
    let m = jitter(&prism(5), 0.1, 21);
    let r = Ref::new(&m);
    let eid: BTreeMap<(u32, u32), u32> = r
        .edges
        .keys()
        .enumerate()
        .map(|(i, &k)| (k, i as u32))
        .collect();
    let nv = m.positions.len() as u32;
    let ne = eid.len() as u32;
    let e = |a: u32, b: u32| nv + eid[&(a.min(b), a.max(b))];
    let out = subdivide(Scheme::CatmullClark, &m).unwrap();
    let mut want = Vec::new();
    for (fi, f) in r.faces.iter().enumerate() {
        let n = f.len();
        for i in 0..n {
            let (p, v, q) = (f[(i + n - 1) % n], f[i], f[(i + 1) % n]);
            want.push(vec![v, e(v, q), nv + ne + fi as u32, e(p, v)]);
        }
    }
    assert_eq!(out.faces(), want);
}

#[test]
fn outputs_are_valid_and_keep_euler_characteristic() {
    for (name, m) in all_meshes() {
        for s in Scheme::ALL {
            if !accepts(s, &m) {
                continue;
            }
            let mut cur = m.clone();
            for level in 0..2 {
                let next = subdivide(s, &cur).unwrap_or_else(|e| panic!("{name} {s:?}: {e}"));
                assert_eq!(euler(&next), euler(&cur), "{name} {s:?} level {level}");
                cur = next;
            }
        }
    }
}

#[test]
fn interpolating_schemes_keep_old_vertices_bit_exact() {
    for (name, m) in all_meshes() {
        for s in [
            Scheme::ModifiedButterfly,
            Scheme::Kobbelt,
            Scheme::VertexInsertion,
        ] {
            if !accepts(s, &m) {
                continue;
            }
            let out = subdivide(s, &m).unwrap();
            for (i, p) in m.positions.iter().enumerate() {
                assert_eq!(
                    out.positions[i].map(f64::to_bits),
                    p.map(f64::to_bits),
                    "{name} {s:?}"
                );
            }
        }
        // Dual truncation keeps boundary and isolated vertices.
        let out = subdivide(Scheme::DualTruncation, &m).unwrap();
        with_topology(&m, |t| {
            for v in 0..m.positions.len() as u32 {
                if t.is_boundary_vertex(v).unwrap() || t.is_isolated(v).unwrap() {
                    assert_eq!(out.positions[v as usize], m.positions[v as usize]);
                }
            }
        })
        .unwrap();
    }
}

#[test]
fn kobbelt_is_the_four_point_rule_on_a_torus() {
    // All vertices of valence 4, closed: every edge point is the 4-point rule along its line,
    // every face point the tensor product.
    let (m_, n_) = (7usize, 5usize);
    let m = jitter(&quad_torus(m_, n_, 3.0, 1.0), 0.2, 30);
    let out = subdivide(Scheme::Kobbelt, &m).unwrap();
    let id = |i: usize, j: usize| ((j % n_) * m_ + (i % m_)) as u32;
    let p = |i: usize, j: usize| m.positions[id(i, j) as usize];
    let fp = |a: Point, b: Point, c: Point, d: Point| {
        add(mul(add(b, c), 9.0 / 16.0), mul(add(a, d), -1.0 / 16.0))
    };
    let r = Ref::new(&m);
    let eid: BTreeMap<(u32, u32), usize> =
        r.edges.keys().enumerate().map(|(i, &k)| (k, i)).collect();
    let nv = m.positions.len();
    let epos = |a: u32, b: u32| out.positions[nv + eid[&(a.min(b), a.max(b))]];
    let mut want_face = vec![[0.0; 3]; m.num_faces()];
    for j in 0..n_ {
        for i in 0..m_ {
            let (ii, jj) = (i + m_, j + n_);
            // Horizontal edge (i, j)-(i+1, j).
            let h = fp(p(ii - 1, jj), p(ii, jj), p(ii + 1, jj), p(ii + 2, jj));
            assert_close(&[epos(id(i, j), id(i + 1, j))], &[h], 1e-15, "horizontal");
            let v = fp(p(ii, jj - 1), p(ii, jj), p(ii, jj + 1), p(ii, jj + 2));
            assert_close(&[epos(id(i, j), id(i, j + 1))], &[v], 1e-15, "vertical");
            // Face (i, j): the 4-point rule across four rows of row edge points.
            let row = |jr: usize| fp(p(ii - 1, jr), p(ii, jr), p(ii + 1, jr), p(ii + 2, jr));
            want_face[j * m_ + i] = fp(row(jj - 1), row(jj), row(jj + 1), row(jj + 2));
        }
    }
    let ne = r.edges.len();
    assert_close(&out.positions[nv + ne..], &want_face, 1e-14, "faces");
}

#[test]
fn kobbelt_reproduces_bicubic_height_fields() {
    let k = 10usize;
    let g = quad_grid(k, k);
    let poly = |x: f64, y: f64| {
        0.3 * x * x * x - 0.2 * x * x * y + 0.1 * x * y * y * y - 0.05 * x * x * x * y * y * y
            + y * y
            - x
            + 2.0
    };
    // Normalise coordinates so the cubic terms stay moderate.
    let sc = 0.1;
    let m = g.map_positions(|p| [p[0], p[1], poly(p[0] * sc, p[1] * sc)]);
    let out = subdivide(Scheme::Kobbelt, &m).unwrap();
    let r = Ref::new(&m);
    let nv = m.positions.len();
    let ne = r.edges.len();
    let interior = |i: usize| (1..k).contains(&i);
    let mut checked = 0;
    for (e, &(a, b)) in r.edges.keys().enumerate() {
        let (pa, pb) = (m.positions[a as usize], m.positions[b as usize]);
        let (ia, ja) = (pa[0] as usize, pa[1] as usize);
        let (ib, jb) = (pb[0] as usize, pb[1] as usize);
        // Both endpoints interior and the line continues inside on both sides.
        let ok = if ja == jb {
            interior(ja) && interior(ia.min(ib)) && interior(ia.max(ib))
        } else {
            interior(ia) && interior(ja.min(jb)) && interior(ja.max(jb))
        };
        if !ok {
            continue;
        }
        let (x, y) = ((pa[0] + pb[0]) / 2.0, (pa[1] + pb[1]) / 2.0);
        let want = [x, y, poly(x * sc, y * sc)];
        assert_close(&[out.positions[nv + e]], &[want], 1e-13, "edge point");
        checked += 1;
    }
    for (f, face) in r.faces.iter().enumerate() {
        let p0 = m.positions[face[0] as usize];
        let (i, j) = (p0[0] as usize, p0[1] as usize);
        if !(i >= 2 && i + 3 <= k && j >= 2 && j + 3 <= k) {
            continue;
        }
        let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
        let want = [x, y, poly(x * sc, y * sc)];
        assert_close(&[out.positions[nv + ne + f]], &[want], 1e-13, "face point");
        checked += 1;
    }
    assert!(checked > 150, "{checked}");
}

#[test]
fn simplest_and_akleman_positions() {
    for (name, m) in all_meshes() {
        let r = Ref::new(&m);
        let iso: Vec<Point> = (0..m.positions.len())
            .filter(|&v| r.nbrs[v].is_empty())
            .map(|v| m.positions[v])
            .collect();
        let bnd: Vec<u32> = (0..m.positions.len() as u32)
            .filter(|&v| r.is_boundary(v))
            .collect();
        // Simplest: midpoints in edge order, boundary vertices, isolated vertices.
        let out = subdivide(Scheme::Simplest, &m).unwrap();
        let mut want: Vec<Point> = r
            .edges
            .keys()
            .map(|&(a, b)| mul(add(r.p(a), r.p(b)), 0.5))
            .collect();
        want.extend(bnd.iter().map(|&v| r.p(v)));
        want.extend(iso.iter().copied());
        assert_close(&out.positions, &want, 1e-15, name);
        // Dual: centroids in face order, midpoints of the boundary vertices' outgoing
        // boundary edges, boundary vertices, isolated vertices.
        let out = subdivide(Scheme::Dual, &m).unwrap();
        let mut want: Vec<Point> = (0..r.faces.len()).map(|f| r.face_centroid(f)).collect();
        for &v in &bnd {
            // The outgoing boundary edge v -> b0 is the one whose face has v -> b0 in order.
            let b0 = *r
                .boundary_nbrs(v)
                .iter()
                .find(|&&b| {
                    let f = &r.faces[r.edges[&(v.min(b), v.max(b))][0]];
                    let k = f.iter().position(|&x| x == v).unwrap();
                    f[(k + 1) % f.len()] == b
                })
                .unwrap();
            want.push(mul(add(r.p(v), r.p(b0)), 0.5));
        }
        want.extend(bnd.iter().map(|&v| r.p(v)));
        want.extend(iso.iter().copied());
        assert_close(&out.positions, &want, 1e-15, name);
        // Vertex insertion: old, then centroids.
        let out = subdivide(Scheme::VertexInsertion, &m).unwrap();
        let mut want = m.positions.clone();
        want.extend((0..r.faces.len()).map(|f| r.face_centroid(f)));
        assert_close(&out.positions, &want, 1e-15, name);
        // Dual truncation: interior vertices 2/3 v + 1/3 mean(ring), then centroids.
        let out = subdivide(Scheme::DualTruncation, &m).unwrap();
        let mut want = Vec::new();
        for v in 0..m.positions.len() as u32 {
            want.push(if r.nbrs[v as usize].is_empty() || r.is_boundary(v) {
                r.p(v)
            } else {
                let mean = avg(&r.nbrs[v as usize]
                    .iter()
                    .map(|&q| r.p(q))
                    .collect::<Vec<_>>());
                add(mul(r.p(v), 2.0 / 3.0), mul(mean, 1.0 / 3.0))
            });
        }
        want.extend((0..r.faces.len()).map(|f| r.face_centroid(f)));
        assert_close(&out.positions, &want, 1e-15, name);
    }
}

#[test]
fn isolated_vertices_are_carried_through() {
    let mut m = cube();
    m.positions.insert(0, [7.0, 8.0, 9.0]);
    m.indices.iter_mut().for_each(|i| *i += 1);
    m.positions.push([-7.0, -8.0, -9.0]);
    for s in Scheme::ALL {
        if !accepts(s, &m) {
            continue;
        }
        let out = subdivide(s, &m).unwrap();
        if s.pattern().keeps_old_vertices() {
            assert_eq!(out.positions[0], [7.0, 8.0, 9.0], "{s:?}");
            assert_eq!(out.positions[9], [-7.0, -8.0, -9.0], "{s:?}");
        } else {
            let n = out.positions.len();
            assert_eq!(
                out.positions[n - 2..],
                [[7.0, 8.0, 9.0], [-7.0, -8.0, -9.0]],
                "{s:?}"
            );
        }
        with_topology(&out, |t| assert_eq!(t.num_isolated_vertices(), 2)).unwrap();
    }
}

#[test]
fn affine_covariance() {
    let a = [[0.8, -0.3, 0.2], [0.1, 1.2, -0.4], [-0.2, 0.5, 0.9]];
    let b = [3.0, -2.0, 0.5];
    let f = |p: Point| {
        let mut q = b;
        for i in 0..3 {
            for (k, pk) in p.iter().enumerate() {
                q[i] += a[i][k] * pk;
            }
        }
        q
    };
    for (name, m) in all_meshes() {
        for s in Scheme::ALL {
            // The spherelike scheme is not affine: circles are only similarity-invariant
            // (tests/mesh_spherelike.rs checks similarities).
            if !accepts(s, &m) || s == Scheme::Spherelike {
                continue;
            }
            let lhs = subdivide(s, &m.map_positions(f)).unwrap();
            let rhs = subdivide(s, &m).unwrap().map_positions(f);
            assert_eq!(lhs.indices, rhs.indices);
            assert_close(
                &lhs.positions,
                &rhs.positions,
                1e-13,
                &format!("{name} {s:?}"),
            );
        }
    }
}

#[test]
fn determinism_same_bits_twice() {
    for (name, m) in all_meshes() {
        for s in Scheme::ALL {
            if !accepts(s, &m) {
                continue;
            }
            let a = subdivide_n(s, &m, 2).unwrap();
            let b = subdivide_n(s, &m, 2).unwrap();
            assert_eq!(hash(&a), hash(&b), "{name} {s:?}");
        }
    }
}

#[test]
fn plans_are_exact_and_multi_level_equals_single_steps() {
    for (name, m) in all_meshes() {
        for s in Scheme::ALL {
            if !accepts(s, &m) {
                continue;
            }
            let levels = if matches!(s, Scheme::VertexInsertion) {
                2
            } else {
                3
            };
            let opts = Options::new(s).levels(levels);
            let mut scratch = vec![0u32; scheme::plan_scratch_size(&m.view()).unwrap()];
            let plan = scheme::plan(m.view(), &opts, &mut scratch);
            let plan = plan.unwrap_or_else(|e| panic!("{name} {s:?}: {e}"));
            let mut cur = m.clone();
            assert_eq!(plan.sizes[0], sizes_of(&cur));
            for k in 1..=levels {
                cur = subdivide(s, &cur).unwrap();
                assert_eq!(plan.sizes[k], sizes_of(&cur), "{name} {s:?} level {k}");
            }
            // One multi-level call gives the same bits as the single steps.
            let mut su = vec![0u32; plan.scratch.u32s];
            let mut sp = vec![[0.0; 3]; plan.scratch.points];
            let o = plan.output();
            let mut out = OwnedMesh {
                positions: vec![[0.0; 3]; o.vertices],
                offsets: vec![0; o.faces + 1],
                indices: vec![0; o.indices],
            };
            let got = scheme::subdivide(
                m.view(),
                &opts,
                Scratch::new(&mut su, &mut sp),
                &mut MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices),
            )
            .unwrap();
            assert_eq!(got.sizes, o);
            assert_eq!((got.fallbacks, got.first_fallback_level), (0, 0));
            assert_eq!(hash(&out), hash(&cur), "{name} {s:?}");
            // Short scratch is reported with the needed size.
            let mut su_short = vec![0u32; plan.scratch.u32s - 1];
            let e = scheme::subdivide(
                m.view(),
                &opts,
                Scratch::new(&mut su_short, &mut sp),
                &mut MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices),
            )
            .unwrap_err();
            assert_eq!(
                e,
                nlsubdiv::Error::too_small(plan.scratch.u32s),
                "{name} {s:?}"
            );
            if plan.scratch.points > 0 {
                let mut sp = vec![[0.0; 3]; plan.scratch.points - 1];
                let e = scheme::subdivide(
                    m.view(),
                    &opts,
                    Scratch::new(&mut su, &mut sp),
                    &mut MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices),
                )
                .unwrap_err();
                assert_eq!(e, nlsubdiv::Error::too_small(plan.scratch.points));
            }
        }
    }
    // Level 0 copies; too many levels is an argument error.
    let m = cube();
    let mut scratch = vec![0u32; 1000];
    let cc = Options::new(Scheme::CatmullClark);
    assert_eq!(
        scheme::plan(m.view(), &cc.levels(MAX_LEVELS + 1), &mut scratch)
            .unwrap_err()
            .status,
        Status::InvalidArgument
    );
    let plan = scheme::plan(m.view(), &cc.levels(0), &mut scratch).unwrap();
    assert_eq!(plan.output(), sizes_of(&m));
}

/// Zero levels copy the input, but the call still validates it into the `u32` scratch: the
/// plan reports exactly that scratch (the input's topology), an exact-size buffer is enough
/// and one entry less is refused with the same size.
#[test]
fn zero_level_plan_reports_the_validation_scratch() {
    for (name, m) in all_meshes() {
        for s in Scheme::ALL {
            if !accepts(s, &m) {
                continue;
            }
            let need = scheme::plan_scratch_size(&m.view()).unwrap();
            for mobius in [false, true] {
                if mobius && !s.has_mobius_form() {
                    continue;
                }
                let opts = Options::new(s).mobius(mobius).levels(0);
                let mut scratch = vec![0u32; need];
                let plan = scheme::plan(m.view(), &opts, &mut scratch).unwrap();
                assert_eq!(plan.scratch.u32s, need, "{name} {s:?}");
                assert_eq!(plan.scratch.points, 0, "{name} {s:?}");
                let o = plan.output();
                assert_eq!(o, sizes_of(&m));
                let mut out = OwnedMesh {
                    positions: vec![[0.0; 3]; o.vertices],
                    offsets: vec![0; o.faces + 1],
                    indices: vec![0; o.indices],
                };
                let mut su = vec![0u32; plan.scratch.u32s];
                let got = scheme::subdivide(
                    m.view(),
                    &opts,
                    Scratch::new(&mut su, &mut []),
                    &mut MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices),
                )
                .unwrap();
                assert_eq!(got.sizes, o);
                assert_eq!(hash(&out), hash(&m), "{name} {s:?}: level 0 is the input");
                let mut su = vec![0u32; plan.scratch.u32s - 1];
                let e = scheme::subdivide(
                    m.view(),
                    &opts,
                    Scratch::new(&mut su, &mut []),
                    &mut MeshOut::new(&mut out.positions, &mut out.offsets, &mut out.indices),
                )
                .unwrap_err();
                assert_eq!(e, nlsubdiv::Error::too_small(need), "{name} {s:?}");
            }
        }
    }
}

#[test]
fn plan_reports_overflow_at_high_levels() {
    let m = cube();
    let mut scratch = vec![0u32; 1000];
    let opts = Options::new(Scheme::CatmullClark).levels(MAX_LEVELS);
    let e = scheme::plan(m.view(), &opts, &mut scratch).unwrap_err();
    assert_eq!(e.status, Status::SizeOverflow);
    // Vertex insertion doubles valences: the plan sees the cap before any level is built.
    let opts = Options::new(Scheme::VertexInsertion).levels(8);
    let e = scheme::plan(m.view(), &opts, &mut scratch).unwrap_err();
    assert_eq!(e.status, Status::ValenceTooHigh);
}

/// Every applicable scheme on every shared mesh: one level, sizes as queried, a valid mesh
/// with the same Euler characteristic.
#[test]
fn shared_meshes_one_level() {
    let Some(dir) = shared_meshes("mesh_schemes::shared_meshes_one_level") else {
        return;
    };
    let files = off_files(&dir);
    for path in files {
        let name = path.file_name().unwrap().to_str().unwrap().to_string();
        let m = read_off(&path).unwrap();
        if validate(&m).is_err() {
            continue; // teapot: non-manifold (see mesh_topology)
        }
        if m.num_faces() > 6000 && cfg!(debug_assertions) {
            println!(
                "SKIP {name}: {} faces (run with --release for all)",
                m.num_faces()
            );
            continue;
        }
        let chi = euler(&m);
        for s in Scheme::ALL {
            if !accepts(s, &m) {
                assert_eq!(
                    subdivide(s, &m).unwrap_err().status,
                    Status::UnsupportedFaceType,
                    "{name} {s:?}"
                );
                continue;
            }
            match subdivide(s, &m) {
                Ok(out) => {
                    let e = with_topology(&out, |t| t.euler_characteristic())
                        .unwrap_or_else(|e| panic!("{name} {s:?}: output invalid: {e}"));
                    assert_eq!(e, chi, "{name} {s:?}")
                }
                Err(e) => {
                    // Only the capacity, or a 2-gon of a dual pattern at an interior vertex of
                    // valence 2 (house_pentagons), may stop a scheme on valid input.
                    let dual2 = e.status == Status::FaceTooSmall
                        && matches!(
                            s,
                            Scheme::DooSabin
                                | Scheme::Simplest
                                | Scheme::Dual
                                | Scheme::DualTruncation
                        );
                    // The spherelike circles need distinct points: meshes with coincident
                    // vertices (cow.off has two at one position) are DegenerateGeometry.
                    let circles = e.status == Status::DegenerateGeometry && s == Scheme::Spherelike;
                    assert!(
                        e.status == Status::ValenceTooHigh || dual2 || circles,
                        "{name} {s:?}: {e}"
                    );
                    println!("{name} {s:?}: {e}");
                }
            }
        }
    }
}

/// The output point set of a mesh symmetric under x ↦ −x is symmetric too (catches stencils
/// indexed asymmetrically around a vertex, e.g. Kobbelt's virtual points at valence 3).
#[test]
fn symmetric_meshes_give_symmetric_outputs() {
    // A cube stretched along y keeps only the x and z mirror symmetries.
    let stretched = cube().map_positions(|p| [p[0], 2.0 * p[1] + 0.3, p[2]]);
    for m in [cube(), octahedron(), prism(6), stretched] {
        for s in Scheme::ALL {
            if !accepts(s, &m) {
                continue;
            }
            let out = subdivide_n(s, &m, 2).unwrap();
            for p in &out.positions {
                let q = [-p[0], p[1], p[2]];
                let d = out
                    .positions
                    .iter()
                    .map(|r| (0..3).map(|k| (r[k] - q[k]).abs()).fold(0.0, f64::max))
                    .fold(f64::INFINITY, f64::min);
                assert!(d < 1e-12, "{s:?}: mirror image of {p:?} missing ({d})");
            }
        }
    }
}

/// Every scheme, linear and Möbius (guarded), on stars at the valence capacity, which the
/// build may set (`NLSUBDIV_MAX_VALENCE`; `scripts/test-features.sh` runs this at 12): the
/// star arrays of every rule must hold them.
#[test]
fn schemes_at_the_valence_capacity() {
    for n in [nlsubdiv::MAX_VALENCE - 1, nlsubdiv::MAX_VALENCE] {
        for m in [fan(n), bipyramid(n), quad_fan(n)] {
            for (s, mobius) in Scheme::ALL
                .into_iter()
                .flat_map(|s| [(s, false), (s, true)])
            {
                if !accepts(s, &m) || (mobius && !s.has_mobius_form()) {
                    continue;
                }
                match run(&m, &Options::new(s).mobius(mobius)).map(|(o, _)| o) {
                    Ok(out) => {
                        assert_eq!(euler(&out), euler(&m), "{s:?} n = {n}");
                        assert!(
                            out.positions.iter().flatten().all(|x| x.is_finite()),
                            "{s:?} mobius {mobius} n = {n}"
                        );
                    }
                    Err(e) => {
                        // Only the output capacity may stop a scheme: vertex insertion doubles
                        // valences; dual faces of boundary vertices grow by one or two corners.
                        assert_eq!(e.status, Status::ValenceTooHigh, "{s:?} n = {n}: {e}");
                        assert!(
                            matches!(
                                s,
                                Scheme::VertexInsertion
                                    | Scheme::DualTruncation
                                    | Scheme::Dual
                                    | Scheme::Simplest
                            ),
                            "{s:?} n = {n}: {e}"
                        );
                    }
                }
            }
        }
    }
}

/// A disk of `n` quads around vertex 0 (interior valence n).
fn quad_fan(n: usize) -> OwnedMesh {
    let mut p = vec![[0.0, 0.0, 0.0]];
    for i in 0..n {
        let t = 2.0 * PI * i as f64 / n as f64;
        let u = t + PI / n as f64;
        p.push([t.cos(), t.sin(), 0.0]);
        p.push([1.5 * u.cos(), 1.5 * u.sin(), 0.2]);
    }
    let r = |i: usize| 1 + 2 * (i % n) as u32;
    let faces: Vec<Vec<u32>> = (0..n).map(|i| vec![0, r(i), r(i) + 1, r(i + 1)]).collect();
    OwnedMesh::from_faces(p, &faces)
}

/// The path a peer comparison takes: read OFF, one level through the slice entry point,
/// write OFF, read it back.
#[test]
fn off_read_subdivide_write_round_trip() {
    let dir = std::env::temp_dir().join(format!("nlsubdiv-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("in.off");
    write_off(&input, &jitter(&cube(), 0.1, 40)).unwrap();
    let m = read_off(&input).unwrap();
    for s in [Scheme::CatmullClark, Scheme::DooSabin, Scheme::Kobbelt] {
        let out = subdivide(s, &m).unwrap();
        let path = dir.join(format!("{}.off", s.name()));
        write_off(&path, &out).unwrap();
        assert_eq!(read_off(&path).unwrap(), out, "{s:?}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Strided input positions (other attributes interleaved, even NaN ones) give the same bits
/// as packed ones.
#[test]
fn strided_positions_read_in_place() {
    use nlsubdiv::mesh::Mesh;
    let m = jitter(&quad_torus(5, 4, 3.0, 1.0), 0.1, 50);
    let stride = 5;
    let mut coords = Vec::new();
    for p in &m.positions {
        coords.extend_from_slice(p);
        coords.extend_from_slice(&[f64::NAN, -1.0]);
    }
    coords.truncate(coords.len() - 2); // the last vertex needs only its 3 coordinates
    let view =
        Mesh::with_stride(&coords, stride, m.positions.len(), &m.offsets, &m.indices).unwrap();
    for s in [Scheme::CatmullClark, Scheme::Kobbelt, Scheme::Dual] {
        let want = subdivide(s, &m).unwrap();
        let mut scratch = vec![0u32; scheme::plan_scratch_size(&view).unwrap()];
        let mut got = want.clone();
        scheme::subdivide(
            view,
            &Options::new(s),
            Scratch::new(&mut scratch, &mut []),
            &mut MeshOut::new(&mut got.positions, &mut got.offsets, &mut got.indices),
        )
        .unwrap();
        assert_eq!(hash(&got), hash(&want), "{s:?}");
    }
    let short = &coords[..coords.len() - 1];
    let e =
        Mesh::with_stride(short, stride, m.positions.len(), &m.offsets, &m.indices).unwrap_err();
    assert_eq!(e, nlsubdiv::Error::too_small(coords.len()));
    let e = Mesh::with_stride(&coords, 2, 3, &m.offsets, &m.indices).unwrap_err();
    assert_eq!(e.status, Status::InvalidArgument);
    let e = Mesh::with_stride(&coords, usize::MAX, 3, &m.offsets, &m.indices).unwrap_err();
    assert_eq!(e.status, Status::SizeOverflow);
    assert!(Mesh::with_stride(&[], 7, 0, &[0], &[]).is_ok());
}
