//! Every bad-input class of reliability-anchors.md §2 that the mesh layer owns, with its
//! status and the element it names; and the broken files of `data/meshes/bad/`.
// Test code: indexing and unwrap are fine here (clippy's in-test allowances do not reach
// helper functions outside #[test]).
#![allow(
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

mod common;

use common::*;
use nlsubdiv::mesh::{topology_scratch_size, Mesh, MeshOut, Topology};
use nlsubdiv::scheme::{self, Options, Scheme, Scratch};
use nlsubdiv::{Error, Status, MAX_FACE_SIZE, MAX_VALENCE, NO_ELEMENT};

fn check(m: &OwnedMesh) -> Result<(), Error> {
    validate(m)
}

fn expect(m: &OwnedMesh, status: Status, element: u32) {
    let e = check(m).expect_err("mesh should be rejected");
    assert_eq!((e.status, e.element), (status, element), "{e}");
    // Every scheme reports the same validation error, and never writes its out sizes.
    for s in Scheme::ALL {
        let e2 = subdivide(s, m).expect_err("scheme accepted a bad mesh");
        assert_eq!(e2.status, status, "{s:?}");
    }
}

fn mesh(positions: usize, faces: &[&[u32]]) -> OwnedMesh {
    let p = (0..positions)
        .map(|i| [i as f64, (i * i % 7) as f64, (i % 3) as f64])
        .collect();
    OwnedMesh::from_faces(p, &faces.iter().map(|f| f.to_vec()).collect::<Vec<_>>())
}

#[test]
fn bad_offsets() {
    let t = tetrahedron();
    let mut m = t.clone();
    m.offsets.clear();
    expect(&m, Status::BadOffsets, 0);
    let mut m = t.clone();
    m.offsets[0] = 1;
    expect(&m, Status::BadOffsets, 0);
    let mut m = t.clone();
    m.offsets[2] = 2; // face 1 ends before it starts
    expect(&m, Status::BadOffsets, 1);
    let mut m = t.clone();
    *m.offsets.last_mut().unwrap() = 11; // not the index count
    expect(&m, Status::BadOffsets, 3);
    let mut m = t.clone();
    m.indices.push(0); // index count beyond the last offset
    expect(&m, Status::BadOffsets, 3);
    // offsets = [0] with indices is bad, without is the empty mesh.
    let m = OwnedMesh {
        positions: vec![],
        offsets: vec![0],
        indices: vec![0],
    };
    expect(&m, Status::BadOffsets, 0);
}

#[test]
fn face_too_small_and_too_large() {
    expect(&mesh(4, &[&[0, 1, 2], &[0, 1]]), Status::FaceTooSmall, 1);
    expect(&mesh(4, &[&[0, 1, 2], &[]]), Status::FaceTooSmall, 1);
    expect(&mesh(4, &[&[3], &[0, 1, 2]]), Status::FaceTooSmall, 0);
    // A face of MAX_FACE_SIZE corners is fine, one more is ValenceTooHigh naming the face.
    let n = MAX_FACE_SIZE as u32;
    let big: Vec<u32> = (0..n).collect();
    let ok = mesh(n as usize, &[&big]);
    assert!(check(&ok).is_ok());
    let big: Vec<u32> = (0..n + 1).collect();
    expect(
        &mesh(n as usize + 1, &[&[0, 1, 2], &big]),
        Status::ValenceTooHigh,
        1,
    );
}

#[test]
fn index_out_of_range() {
    expect(
        &mesh(4, &[&[0, 1, 2], &[0, 3, 4]]),
        Status::IndexOutOfRange,
        1,
    );
    expect(&mesh(4, &[&[0, 1, u32::MAX]]), Status::IndexOutOfRange, 0);
    expect(&mesh(0, &[&[0, 1, 2]]), Status::IndexOutOfRange, 0);
}

#[test]
fn repeated_vertex() {
    expect(
        &mesh(4, &[&[0, 1, 2], &[0, 0, 1]]),
        Status::RepeatedVertex,
        1,
    );
    expect(&mesh(4, &[&[0, 1, 0, 2]]), Status::RepeatedVertex, 0);
}

#[test]
fn non_manifold_edge() {
    // Three triangles on the edge (0, 1).
    expect(
        &mesh(5, &[&[0, 1, 2], &[1, 0, 3], &[0, 1, 4]]),
        Status::NonManifoldEdge,
        2,
    );
    // Four faces, alternating directions (each pair consistent).
    expect(
        &mesh(6, &[&[0, 1, 2], &[1, 0, 3], &[0, 1, 4], &[1, 0, 5]]),
        Status::NonManifoldEdge,
        3,
    );
}

#[test]
fn inconsistent_orientation() {
    // Two triangles traversing (0, 1) in the same direction.
    expect(
        &mesh(4, &[&[0, 1, 2], &[0, 1, 3]]),
        Status::InconsistentOrientation,
        1,
    );
    // A cube with one face reversed.
    let mut c = cube();
    let f: Vec<u32> = c.faces()[5].iter().rev().copied().collect();
    let mut faces = c.faces();
    faces[5] = f;
    c = OwnedMesh::from_faces(c.positions, &faces);
    let e = check(&c).unwrap_err();
    assert_eq!((e.status, e.element), (Status::InconsistentOrientation, 5));
}

#[test]
fn non_manifold_vertex() {
    // Two fans sharing vertex 0 only (bow-tie): two half-disks.
    let bowtie = mesh(5, &[&[0, 1, 2], &[0, 3, 4]]);
    expect(&bowtie, Status::NonManifoldVertex, 0);
    // Two closed cones touching at their apex: two disks at vertex 0 (no boundary there).
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for (base, ring) in [(1u32, 4u32), (5, 8)] {
        let r = |i: u32| base + i % 3;
        for i in 0..3 {
            faces.push(vec![0, r(i), r(i + 1)]);
        }
        faces.push(vec![r(2), r(1), r(0)]);
        let _ = ring;
    }
    let m = OwnedMesh::from_faces(mesh(8, &[]).positions, &faces);
    expect(&m, Status::NonManifoldVertex, 0);
    // A disk and a closed cone at vertex 0: one half-disk plus one disk.
    let mut faces2 = faces[..4].to_vec();
    faces2.push(vec![0, 5, 6]);
    let m = OwnedMesh::from_faces(mesh(8, &[]).positions, &faces2);
    expect(&m, Status::NonManifoldVertex, 0);
}

#[test]
fn duplicate_faces_and_pillows() {
    // Same orientation, on a tetrahedron (three faces on each of its edges).
    let mut f = tetrahedron().faces();
    f.push(f[0].clone());
    let m = OwnedMesh::from_faces(tetrahedron().positions, &f);
    expect(&m, Status::DuplicateFace, 4);
    // Rotated copy is the same face.
    let mut f = tetrahedron().faces();
    f.push(vec![f[1][1], f[1][2], f[1][0]]);
    let m = OwnedMesh::from_faces(tetrahedron().positions, &f);
    expect(&m, Status::DuplicateFace, 4);
    // Pillow: a face and its reverse, alone (passes the edge test).
    expect(
        &mesh(4, &[&[0, 1, 2, 3], &[3, 2, 1, 0]]),
        Status::DuplicateFace,
        1,
    );
    expect(
        &mesh(3, &[&[0, 1, 2], &[0, 2, 1]]),
        Status::DuplicateFace,
        1,
    );
    // A pillow next to a valid mesh.
    let mut t = tetrahedron();
    let base = t.positions.len() as u32;
    t.positions
        .extend([[5.0, 0.0, 0.0], [6.0, 0.0, 0.0], [5.0, 1.0, 0.0]]);
    let mut f = t.faces();
    f.push(vec![base, base + 1, base + 2]);
    f.push(vec![base, base + 2, base + 1]);
    let m = OwnedMesh::from_faces(t.positions, &f);
    expect(&m, Status::DuplicateFace, 5);
}

#[test]
fn non_finite_input_anywhere() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut t = tetrahedron();
        t.positions[2][1] = bad;
        expect(&t, Status::NonFiniteInput, 2);
        // Also in an unreferenced vertex.
        let mut t = tetrahedron();
        t.positions.push([0.0, 0.0, bad]);
        expect(&t, Status::NonFiniteInput, 4);
    }
}

#[test]
fn valence_capacity() {
    // Fans of valence MAX_VALENCE − 1, MAX_VALENCE pass; MAX_VALENCE + 1 names the centre.
    // (A fan's centre is interior: valence = faces; its rim vertices have valence 3.)
    for n in [MAX_VALENCE - 1, MAX_VALENCE] {
        assert!(check(&fan(n)).is_ok(), "n = {n}");
        assert!(check(&bipyramid(n)).is_ok(), "n = {n}");
    }
    expect(&fan(MAX_VALENCE + 1), Status::ValenceTooHigh, 0);
    expect(&bipyramid(MAX_VALENCE + 1), Status::ValenceTooHigh, 0);
    // On the boundary, valence = faces + 1: an open fan of MAX_VALENCE faces is too much.
    let mut open = fan(MAX_VALENCE);
    open.offsets.pop();
    open.indices.truncate(open.indices.len() - 3);
    assert!(check(&open).is_ok());
    let mut open = fan(MAX_VALENCE + 1);
    open.offsets.pop();
    open.indices.truncate(open.indices.len() - 3);
    expect(&open, Status::ValenceTooHigh, 0);
}

#[test]
fn check_order_is_topology_first() {
    // A NaN and a repeated vertex: the topology error wins.
    let mut m = mesh(4, &[&[0, 1, 2], &[0, 0, 3]]);
    m.positions[0][0] = f64::NAN;
    assert_eq!(check(&m).unwrap_err().status, Status::RepeatedVertex);
    // Face too small beats an out-of-range index in an earlier face.
    let m = mesh(3, &[&[0, 1, 9], &[0, 1]]);
    assert_eq!(check(&m).unwrap_err().status, Status::FaceTooSmall);
    // Scratch is checked after the scratch-free classes.
    let m = mesh(3, &[&[0, 1]]);
    let mut small = [0u32; 1];
    let e = Topology::build(m.view(), &mut small).unwrap_err();
    assert_eq!(e.status, Status::FaceTooSmall);
    let t = tetrahedron();
    let need = topology_scratch_size(4, 12).unwrap();
    let mut small = vec![0u32; need - 1];
    let e = Topology::build(t.view(), &mut small).unwrap_err();
    assert_eq!(e, Error::too_small(need));
}

#[test]
fn empty_mesh_and_isolated_vertices_are_valid() {
    let empty = OwnedMesh {
        positions: vec![],
        offsets: vec![0],
        indices: vec![],
    };
    assert!(check(&empty).is_ok());
    let only_points = OwnedMesh {
        positions: vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]],
        offsets: vec![0],
        indices: vec![],
    };
    with_topology(&only_points, |t| {
        assert_eq!(t.num_isolated_vertices(), 2);
        assert_eq!(t.num_edges(), 0);
        assert_eq!(t.euler_characteristic(), 2);
        assert_eq!(t.star(0).count(), 0);
    })
    .unwrap();
    for s in Scheme::ALL {
        let out = subdivide(s, &empty).unwrap();
        assert_eq!(sizes_of(&out).faces, 0, "{s:?}");
        assert_eq!(out.offsets, vec![0]);
        let out = subdivide(s, &only_points).unwrap();
        assert_eq!(out.positions, only_points.positions, "{s:?}");
        assert_eq!(out.offsets, vec![0]);
    }
}

#[test]
fn size_overflow_is_reported_not_wrapped() {
    assert_eq!(
        topology_scratch_size(usize::MAX / 2, 1).unwrap_err().status,
        Status::SizeOverflow
    );
    assert_eq!(
        topology_scratch_size(0, usize::MAX / 3).unwrap_err().status,
        Status::SizeOverflow
    );
}

#[test]
fn short_output_buffers_are_rejected_before_writing() {
    for s in [Scheme::Loop, Scheme::CatmullClark, Scheme::DooSabin] {
        let m = if s == Scheme::Loop {
            tetrahedron()
        } else {
            cube()
        };
        let opts = Options::new(s);
        let mut scratch = vec![0u32; scheme::plan_scratch_size(&m.view()).unwrap()];
        let plan = scheme::plan(m.view(), &opts, &mut scratch).unwrap();
        let sz = plan.output();
        assert_eq!(plan.scratch.u32s, scratch.len());
        for which in 0..3 {
            let mut p = vec![[7.0; 3]; sz.vertices - usize::from(which == 0)];
            let mut o = vec![7u32; sz.faces + 1 - usize::from(which == 1)];
            let mut i = vec![7u32; sz.indices - usize::from(which == 2)];
            let e = scheme::subdivide(
                m.view(),
                &opts,
                Scratch::new(&mut scratch, &mut []),
                &mut MeshOut::new(&mut p, &mut o, &mut i),
            )
            .unwrap_err();
            let need = [sz.vertices, sz.faces + 1, sz.indices][which];
            assert_eq!(e, Error::too_small(need));
            assert!(p.iter().all(|x| *x == [7.0; 3]) && o.iter().all(|&x| x == 7));
            assert!(i.iter().all(|&x| x == 7));
        }
    }
}

#[test]
fn unsupported_face_types() {
    for s in [Scheme::Loop, Scheme::ModifiedButterfly] {
        let e = subdivide(s, &cube()).unwrap_err();
        assert_eq!((e.status, e.element), (Status::UnsupportedFaceType, 0));
        let mut f = tetrahedron().faces();
        f.push(vec![4, 5, 6, 7]);
        let mut p = tetrahedron().positions;
        p.extend([
            [5.0, 0.0, 0.0],
            [6.0, 0.0, 0.0],
            [6.0, 1.0, 0.0],
            [5.0, 1.0, 0.0],
        ]);
        let e = subdivide(s, &OwnedMesh::from_faces(p, &f)).unwrap_err();
        assert_eq!((e.status, e.element), (Status::UnsupportedFaceType, 4));
    }
    let e = subdivide(Scheme::Kobbelt, &prism(5)).unwrap_err();
    assert_eq!((e.status, e.element), (Status::UnsupportedFaceType, 0));
    let e = subdivide(Scheme::Kobbelt, &tetrahedron()).unwrap_err();
    assert_eq!((e.status, e.element), (Status::UnsupportedFaceType, 0));
}

#[test]
fn output_valence_is_checked() {
    // Vertex insertion doubles interior valences: MAX/2 fits (64 → 128 at the default
    // cap), MAX/2 + 1 does not.
    let half = MAX_VALENCE / 2;
    assert!(subdivide(Scheme::VertexInsertion, &bipyramid(half)).is_ok());
    let e = subdivide(Scheme::VertexInsertion, &bipyramid(half + 1)).unwrap_err();
    assert_eq!((e.status, e.element), (Status::ValenceTooHigh, 0));
    // Dual truncation: a face point gets n + (interior edges) neighbours.
    let big = prism(MAX_VALENCE / 2 + 1);
    let e = subdivide(Scheme::DualTruncation, &big).unwrap_err();
    assert_eq!((e.status, e.element), (Status::ValenceTooHigh, 0));
    assert!(subdivide(Scheme::DualTruncation, &prism(MAX_VALENCE / 2)).is_ok());
}

#[test]
fn numerical_failure_never_returns_non_finite_output() {
    let big = cube().map_positions(|p| [p[0] * 1.7e308, p[1] * 1.7e308, p[2]]);
    let e = subdivide(Scheme::CatmullClark, &big).unwrap_err();
    assert_eq!(e.status, Status::NumericalFailure);
    assert_ne!(e.element, NO_ELEMENT);
}

#[test]
fn mesh_view_accessors_are_total() {
    let t = tetrahedron();
    let m: Mesh<'_> = t.view();
    assert_eq!(m.face(3), Some(&[1u32, 3, 2][..]));
    assert_eq!(m.face(4), None);
    assert_eq!(m.face(usize::MAX), None);
    assert_eq!(m.position(9), None);
}

/// The broken files of the shared test data, each with the status it must produce.
#[test]
fn shared_bad_files() {
    let Some(shared) = shared_meshes("mesh_validation::shared_bad_files") else {
        return;
    };
    let files = off_files(&shared.join("bad"));
    let expected: &[(&str, Option<Status>)] = &[
        ("bowtie_vertex.off", Some(Status::NonManifoldVertex)),
        ("degenerate_face.off", None),
        ("duplicate_face.off", Some(Status::DuplicateFace)),
        ("duplicate_vertex.off", None),
        ("empty_mesh.off", None),
        ("format_coff_colors.off", None),
        ("format_comments_crlf.off", None),
        ("format_counts_on_header_line.off", None),
        ("format_wrapped_faces.off", None),
        (
            "inconsistent_orientation.off",
            Some(Status::InconsistentOrientation),
        ),
        ("inf_coordinate.off", Some(Status::NonFiniteInput)),
        ("mobius_strip.off", Some(Status::InconsistentOrientation)),
        ("nan_coordinate.off", Some(Status::NonFiniteInput)),
        ("negative_index.off", Some(Status::IndexOutOfRange)),
        ("nonmanifold_edge.off", Some(Status::NonManifoldEdge)),
        ("one_based_indices.off", Some(Status::IndexOutOfRange)),
        ("out_of_range_index.off", Some(Status::IndexOutOfRange)),
        ("repeated_index_face.off", Some(Status::RepeatedVertex)),
        ("two_vertex_face.off", Some(Status::FaceTooSmall)),
        ("unreferenced_vertex.off", None),
    ];
    let mut seen = 0;
    for path in files {
        let name = path.file_name().unwrap().to_str().unwrap();
        let m = match read_off(&path) {
            Ok(m) => m,
            Err(e) => {
                println!("{name}: rejected by the OFF reader ({e})");
                assert_eq!(name, "truncated_file.off", "{name}: {e}");
                continue;
            }
        };
        let Some((_, want)) = expected.iter().find(|(n, _)| *n == name) else {
            println!("{name}: no expectation recorded; only checking that nothing panics");
            for s in Scheme::ALL {
                let _ = subdivide(s, &m);
            }
            continue;
        };
        seen += 1;
        let got = check(&m).err().map(|e| e.status);
        assert_eq!(got, *want, "{name}");
        if name.starts_with("format_") {
            assert_eq!(m, tetrahedron_of_format_files(), "{name}");
        }
        for s in Scheme::ALL {
            match subdivide(s, &m) {
                Ok(_) => assert!(want.is_none() || got.is_none(), "{name} {s:?}"),
                Err(e) => {
                    if let Some(w) = want {
                        assert_eq!(e.status, *w, "{name} {s:?}")
                    }
                }
            }
        }
        println!("{name}: {:?}", got.unwrap_or(Status::Ok));
    }
    assert_eq!(seen, expected.len());
}

fn tetrahedron_of_format_files() -> OwnedMesh {
    OwnedMesh::from_faces(
        vec![
            [1.0, 1.0, 1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
        ],
        &[vec![0, 1, 2], vec![0, 3, 1], vec![0, 2, 3], vec![1, 3, 2]],
    )
}

#[test]
fn dual_patterns_reject_interior_valence_two() {
    // A cube with a vertex inserted on edge (0, 1): an interior vertex of valence 2 whose
    // dual face would be a 2-gon.
    let mut c = cube();
    c.positions.push([0.0, -1.0, -1.0]);
    let mut faces = c.faces();
    faces[0] = vec![0, 2, 3, 1, 8];
    faces[2] = vec![0, 8, 1, 5, 4];
    let m = OwnedMesh::from_faces(c.positions, &faces);
    assert!(check(&m).is_ok());
    for s in [
        Scheme::DooSabin,
        Scheme::Simplest,
        Scheme::Dual,
        Scheme::DualTruncation,
    ] {
        let e = subdivide(s, &m).unwrap_err();
        assert_eq!((e.status, e.element), (Status::FaceTooSmall, 8), "{s:?}");
    }
    for s in [Scheme::CatmullClark, Scheme::VertexInsertion] {
        assert!(subdivide(s, &m).is_ok(), "{s:?}");
    }
}

/// Small hostile meshes from a fixed-seed generator: random face sizes (0–5), indices up to
/// one past the vertex count, occasional NaN, shuffled duplicates of valid faces. Nothing may
/// panic; an accepted mesh gives, for every scheme, an error or a valid output with the same
/// Euler characteristic.
#[test]
fn random_small_meshes_never_panic() {
    let mut r = Lcg(0x5eed);
    let mut accepted = 0;
    let mut outputs = 0;
    for case in 0..4000 {
        let mut u = |n: usize| ((r.next() + 1.0) * 0.5 * n as f64) as usize % n.max(1);
        let nv = u(9);
        let nf = u(7);
        let mut faces = Vec::new();
        for _ in 0..nf {
            let k = u(6);
            faces.push((0..k).map(|_| u(nv + 1) as u32).collect::<Vec<u32>>());
        }
        // Sometimes start from a valid mesh and break it a little.
        let mut m = if case % 3 == 0 {
            let base = [tetrahedron(), cube(), quad_grid(2, 1), fan(4), prism(3)][u(5)].clone();
            let mut f = base.faces();
            match u(4) {
                0 => {
                    let i = u(f.len());
                    f[i].reverse();
                }
                1 => {
                    let i = u(f.len());
                    f.remove(i);
                }
                2 => {
                    let i = u(f.len());
                    let g = f[i].clone();
                    f.push(g);
                }
                _ => {}
            }
            OwnedMesh::from_faces(base.positions, &f)
        } else {
            let p = (0..nv)
                .map(|i| [i as f64, (i * i) as f64 * 0.1, 1.0 / (1.0 + i as f64)])
                .collect();
            OwnedMesh::from_faces(p, &faces)
        };
        if case % 17 == 0 && !m.positions.is_empty() {
            let i = u(m.positions.len());
            m.positions[i][u(3)] = f64::NAN;
        }
        if validate(&m).is_err() {
            continue;
        }
        accepted += 1;
        let chi = with_topology(&m, |t| t.euler_characteristic()).unwrap();
        for s in Scheme::ALL {
            if let Ok(out) = subdivide(s, &m) {
                outputs += 1;
                let chi2 = with_topology(&out, |t| t.euler_characteristic())
                    .unwrap_or_else(|e| panic!("case {case} {s:?}: invalid output {e}"));
                assert_eq!(chi2, chi, "case {case} {s:?}");
            }
        }
    }
    assert!(accepted > 300 && outputs > 1500, "{accepted} {outputs}");
}
