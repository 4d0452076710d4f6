//! Topology invariants on generated meshes and on the shared meshes of `data/meshes/`
//! (expected counts read from the README table written by `inspect_off.py`, an independent
//! implementation).
// Test code: indexing and unwrap are fine here.
#![allow(
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

mod common;

use common::*;
use nlsubdiv::mesh::{Topology, NONE};
use nlsubdiv::{Status, MAX_VALENCE};
use std::collections::BTreeSet;
use std::path::Path;

#[derive(Debug, PartialEq)]
struct Summary {
    v: usize,
    e: usize,
    f: usize,
    chi: i64,
    loops: usize,
    max_valence: usize,
    isolated: usize,
}

/// Checks every invariant of the topology and returns its counts.
fn invariants(m: &OwnedMesh) -> Summary {
    with_topology(m, |t: &Topology<'_, '_>| {
        let nh = t.num_half_edges() as u32;
        let faces = m.faces();
        let mut lowest_out = vec![NONE; t.num_vertices()];
        for h in (0..nh).rev() {
            lowest_out[t.origin(h).unwrap() as usize] = h;
        }
        // Independent edge set.
        let mut edges = BTreeSet::new();
        for f in &faces {
            for i in 0..f.len() {
                let (a, b) = (f[i], f[(i + 1) % f.len()]);
                edges.insert((a.min(b), a.max(b)));
            }
        }
        let edges: Vec<(u32, u32)> = edges.into_iter().collect();
        assert_eq!(t.num_edges(), edges.len());
        // Edge ids follow the sorted (min, max) keys.
        for (e, &k) in edges.iter().enumerate() {
            assert_eq!(t.edge_vertices(e as u32).unwrap(), k);
            let h = t.edge_half_edge(e as u32).unwrap();
            assert_eq!(t.edge(h).unwrap(), e as u32);
            if t.twin(h).unwrap() != NONE {
                assert_eq!(t.origin(h).unwrap(), k.0, "representative runs min -> max");
            }
        }
        let mut nb = 0;
        for h in 0..nh {
            let (a, b) = (t.origin(h).unwrap(), t.dest(h).unwrap());
            assert_eq!(t.prev(t.next(h).unwrap()).unwrap(), h);
            assert_eq!(t.face(t.next(h).unwrap()).unwrap(), t.face(h).unwrap());
            let tw = t.twin(h).unwrap();
            if tw == NONE {
                nb += 1;
                let n = t.next_boundary(h).unwrap();
                assert_eq!(t.origin(n).unwrap(), b);
                assert_eq!(t.twin(n).unwrap(), NONE);
                assert_eq!(t.prev_boundary(n).unwrap(), h);
            } else {
                assert_eq!(t.twin(tw).unwrap(), h);
                assert_eq!((t.origin(tw).unwrap(), t.dest(tw).unwrap()), (b, a));
                assert_ne!(t.face(tw).unwrap(), t.face(h).unwrap());
                assert_eq!(t.edge(tw).unwrap(), t.edge(h).unwrap());
            }
        }
        assert_eq!(nb, t.num_boundary_edges());
        assert_eq!(t.num_boundary_vertices(), t.num_boundary_edges());
        // Stars.
        let mut valence_sum = 0;
        let mut max_valence = 0;
        for v in 0..t.num_vertices() as u32 {
            let spokes = t.spokes(v).unwrap();
            let n = t.valence(v).unwrap();
            assert_eq!(spokes.len(), n);
            valence_sum += n;
            max_valence = max_valence.max(n);
            if n == 0 {
                assert!(t.is_isolated(v).unwrap());
                continue;
            }
            let nbrs: BTreeSet<u32> = spokes.iter().map(|s| s.neighbour).collect();
            assert_eq!(nbrs.len(), n, "neighbours of {v} are distinct");
            let boundary = t.is_boundary_vertex(v).unwrap();
            for (i, s) in spokes.iter().enumerate() {
                let ev = t.edge_vertices(s.edge).unwrap();
                assert_eq!(ev, (v.min(s.neighbour), v.max(s.neighbour)));
                if s.half_edge != NONE {
                    assert_eq!(t.origin(s.half_edge).unwrap(), v);
                    assert_eq!(t.face(s.half_edge).unwrap(), s.face);
                }
                if boundary && i + 1 == n {
                    assert_eq!((s.half_edge, s.face), (NONE, NONE));
                    continue;
                }
                // Counter-clockwise: the face after spoke i holds v -> q_i and q_{i+1} -> v.
                let next = spokes[(i + 1) % n].neighbour;
                let f = &faces[s.face as usize];
                let k = f.iter().position(|&x| x == v).unwrap();
                assert_eq!(f[(k + 1) % f.len()], s.neighbour);
                assert_eq!(f[(k + f.len() - 1) % f.len()], next);
            }
            if boundary {
                let (b0, b1) = t.boundary_neighbours(v).unwrap();
                assert_eq!(spokes[0].neighbour, b0);
                assert_eq!(spokes[n - 1].neighbour, b1);
                assert_eq!(t.twin(spokes[0].half_edge).unwrap(), NONE);
                assert_eq!(t.vertex_face_count(v).unwrap(), n - 1);
            } else {
                // Interior stars start at the lowest outgoing half-edge.
                assert_eq!(spokes[0].half_edge, lowest_out[v as usize]);
                assert_eq!(t.vertex_face_count(v).unwrap(), n);
            }
        }
        assert_eq!(valence_sum, 2 * t.num_edges());
        let mut mark = vec![0u32; nh as usize];
        let loops = t.boundary_loops(&mut mark).unwrap();
        Summary {
            v: t.num_vertices(),
            e: t.num_edges(),
            f: t.num_faces(),
            chi: t.euler_characteristic(),
            loops,
            max_valence,
            isolated: t.num_isolated_vertices(),
        }
    })
    .unwrap()
}

#[test]
fn generated_meshes() {
    let cases: Vec<(&str, OwnedMesh, i64, usize)> = vec![
        ("tetrahedron", tetrahedron(), 2, 0),
        ("cube", cube(), 2, 0),
        ("quad grid 4x3", quad_grid(4, 3), 1, 1),
        ("quad grid 1x1", quad_grid(1, 1), 1, 1),
        ("tri grid 5x4", tri_grid(5, 4), 1, 1),
        ("quad torus 6x4", quad_torus(6, 4, 3.0, 1.0), 0, 0),
        ("tri torus 5x3", tri_torus(5, 3), 0, 0),
        ("prism 7", prism(7), 2, 0),
        ("fan 3", fan(3), 1, 1),
        ("fan MAX-1", fan(MAX_VALENCE - 1), 1, 1),
        ("fan MAX", fan(MAX_VALENCE), 1, 1),
        ("bipyramid MAX", bipyramid(MAX_VALENCE), 2, 0),
    ];
    for (name, m, chi, loops) in cases {
        let s = invariants(&m);
        assert_eq!((s.chi, s.loops), (chi, loops), "{name}");
    }
    let s = invariants(&fan(MAX_VALENCE));
    assert_eq!(s.max_valence, MAX_VALENCE);
    let e = validate(&fan(MAX_VALENCE + 1)).unwrap_err();
    assert_eq!((e.status, e.element), (Status::ValenceTooHigh, 0));
}

#[test]
fn annulus_components_and_isolated_vertices() {
    // A 4x4 grid without its 2x2 centre: two boundary loops, χ = 0.
    let g = quad_grid(4, 4);
    let faces: Vec<Vec<u32>> = g
        .faces()
        .into_iter()
        .enumerate()
        .filter(|(i, _)| ![5, 6, 9, 10].contains(i))
        .map(|(_, f)| f)
        .collect();
    let ann = OwnedMesh::from_faces(g.positions.clone(), &faces);
    let s = invariants(&ann);
    // The 1 unreferenced centre vertex (2,2) adds 1 to χ.
    assert_eq!((s.chi - s.isolated as i64, s.loops, s.isolated), (0, 2, 1));
    // Two components plus an isolated vertex.
    let t = tetrahedron();
    let c = cube();
    let mut p = t.positions.clone();
    p.extend(c.positions.iter().map(|q| [q[0] + 5.0, q[1], q[2]]));
    p.push([9.0, 9.0, 9.0]);
    let mut f = t.faces();
    f.extend(
        c.faces()
            .into_iter()
            .map(|x| x.iter().map(|i| i + 4).collect()),
    );
    let s = invariants(&OwnedMesh::from_faces(p, &f));
    assert_eq!((s.chi, s.loops, s.isolated), (5, 0, 1));
}

#[test]
fn numbering_is_deterministic_and_independent_of_face_order() {
    let m = jitter(&tri_torus(6, 4), 0.1, 3);
    let keys = |m: &OwnedMesh| {
        with_topology(m, |t| {
            (0..t.num_edges() as u32)
                .map(|e| t.edge_vertices(e).unwrap())
                .collect::<Vec<_>>()
        })
        .unwrap()
    };
    let a = keys(&m);
    assert_eq!(a, keys(&m));
    // Reverse the face order and rotate every face: the edge numbering is the same.
    let faces: Vec<Vec<u32>> = m
        .faces()
        .into_iter()
        .rev()
        .map(|mut f| {
            f.rotate_left(1);
            f
        })
        .collect();
    let m2 = OwnedMesh::from_faces(m.positions.clone(), &faces);
    assert_eq!(a, keys(&m2));
}

/// One row of the README table: (V, F, E, χ, boundary loops, max valence).
fn readme_rows(dir: &Path) -> Option<Vec<(String, [i64; 6])>> {
    let text = std::fs::read_to_string(dir.join("README.md")).ok()?;
    let mut rows = Vec::new();
    for line in text.lines() {
        let cols: Vec<&str> = line.split('|').map(|c| c.trim()).collect();
        // | file | V | F | E | faces | closed/boundary | manifold | orient | chi | genus | comps | max val | ...
        if cols.len() < 13 || !cols[1].ends_with(".off") || cols[1].contains('`') {
            continue;
        }
        let num = |s: &str| s.parse::<i64>().ok();
        let (Some(v), Some(f), Some(e), Some(chi), Some(mv)) = (
            num(cols[2]),
            num(cols[3]),
            num(cols[4]),
            num(cols[9]),
            num(cols[12]),
        ) else {
            continue;
        };
        let loops = if cols[6] == "closed" {
            0
        } else {
            cols[6]
                .trim_start_matches("boundary (")
                .trim_end_matches(')')
                .parse()
                .ok()?
        };
        rows.push((cols[1].to_string(), [v, f, e, chi, loops, mv]));
    }
    Some(rows)
}

#[test]
fn shared_meshes() {
    let Some(dir) = common::shared_meshes("mesh_topology::shared_meshes") else {
        return;
    };
    let files = off_files(&dir);
    let rows = readme_rows(&dir).unwrap_or_default();
    let mut compared = 0;
    for path in files {
        let name = path.file_name().unwrap().to_str().unwrap().to_string();
        let m = read_off(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        if name == "teapot.off" {
            // 38 non-manifold vertices (README).
            assert_eq!(validate(&m).unwrap_err().status, Status::NonManifoldVertex);
            continue;
        }
        let s = invariants(&m);
        if let Some((_, r)) = rows.iter().find(|(n, _)| *n == name) {
            // The README counts χ without unreferenced vertices.
            let got = [
                s.v as i64,
                s.f as i64,
                s.e as i64,
                s.chi - s.isolated as i64,
                s.loops as i64,
                s.max_valence as i64,
            ];
            assert_eq!(&got, r, "{name}: [V, F, E, χ, loops, max valence]");
            compared += 1;
        }
        println!("{name}: {s:?}");
    }
    assert!(
        compared >= 30,
        "only {compared} meshes compared with the README table"
    );
}
