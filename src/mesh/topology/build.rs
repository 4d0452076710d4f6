//! Validation of a [`Mesh`] and the construction of its [`Topology`] arrays.
//!
//! Every check runs before anything is written to the caller's scratch beyond the topology
//! arrays, in the order of the table in the module docs of [`super`] ("Validation order");
//! the first failed check is returned, naming its element. The arrays are built in linear
//! time without hashing: the directed-edge table by two stable counting sorts
//! ([`crate::mesh::sort`]).

use super::queries::prev_in;
use super::{regions, Regions, Topology};
use crate::error::{Error, Result, Status};
use crate::mesh::sort::counting_sort;
use crate::mesh::{get, internal, set, Mesh, MAX_COUNT, NONE};
use crate::point;
use crate::{MAX_FACE_SIZE, MAX_VALENCE};

fn check_offsets(mesh: &Mesh<'_>) -> Result<()> {
    let offs = mesh.offsets;
    let first = offs
        .first()
        .copied()
        .ok_or(Error::at(Status::BadOffsets, 0))?;
    if first != 0 {
        return Err(Error::at(Status::BadOffsets, 0));
    }
    let mut prev = 0u32;
    for (i, &o) in offs.iter().enumerate().skip(1) {
        if o < prev {
            return Err(Error::at(Status::BadOffsets, (i - 1) as u32));
        }
        prev = o;
    }
    if prev as usize != mesh.indices.len() {
        let f = mesh.num_faces().saturating_sub(1) as u32;
        return Err(Error::at(Status::BadOffsets, f));
    }
    Ok(())
}

/// Whether face `face` passes every per-face check (classes 2–5) for `nv` vertices.
fn face_ok(face: &[u32], nv: usize) -> bool {
    (3..=MAX_FACE_SIZE).contains(&face.len())
        && face
            .iter()
            .enumerate()
            .all(|(i, &a)| (a as usize) < nv && !face.iter().skip(i + 1).any(|&b| b == a))
}

fn check_faces(mesh: &Mesh<'_>) -> Result<()> {
    let nf = mesh.num_faces();
    let nv = mesh.num_vertices();
    // One pass when every face is good (the common case); otherwise the class-by-class
    // passes below find the error the module table promises.
    let indices = mesh.indices;
    let all_ok = mesh.offsets.windows(2).all(|w| match *w {
        [a, b] => indices
            .get(a as usize..b as usize)
            .is_some_and(|face| face_ok(face, nv)),
        _ => false,
    });
    if all_ok {
        return Ok(());
    }
    let faces = || (0..nf).map(|f| (f as u32, mesh.face(f).unwrap_or(&[])));
    for (f, face) in faces() {
        if face.len() < 3 {
            return Err(Error::at(Status::FaceTooSmall, f));
        }
    }
    for (f, face) in faces() {
        if face.len() > MAX_FACE_SIZE {
            return Err(Error::at(Status::ValenceTooHigh, f));
        }
    }
    for (f, face) in faces() {
        if face.iter().any(|&v| v as usize >= nv) {
            return Err(Error::at(Status::IndexOutOfRange, f));
        }
    }
    for (f, face) in faces() {
        for (i, &a) in face.iter().enumerate() {
            if face.iter().skip(i + 1).any(|&b| b == a) {
                return Err(Error::at(Status::RepeatedVertex, f));
            }
        }
    }
    Ok(())
}

/// Whether faces `f` and `g` have the same vertex set (faces have no repeated vertices).
/// `h` is a half-edge of `f` on an edge the two faces share: `f`'s corners are tested from
/// the second corner after `h` on, which for neighbouring faces (the usual case) is off the
/// shared edge and answers at the first test. The answer does not depend on the order.
fn same_vertex_set(mesh: &Mesh<'_>, f: u32, g: u32, h: u32) -> bool {
    let (Some(a), Some(b)) = (mesh.face(f as usize), mesh.face(g as usize)) else {
        return false;
    };
    if a.len() != b.len() {
        return false;
    }
    let first = mesh.offsets.get(f as usize).copied().unwrap_or(h);
    let mut k = (h.wrapping_sub(first) as usize).saturating_add(2);
    if k >= a.len() {
        k -= a.len(); // h is a corner of f: k < 2 len
    }
    // Plain loops: `contains` takes a chunked path that costs more on 3–4 corners (measured
    // with callgrind).
    #[allow(clippy::manual_contains)]
    let has = |x: u32| b.iter().any(|&y| y == x);
    match a.get(k) {
        Some(&x) if !has(x) => false,
        _ => a.iter().all(|&v| has(v)),
    }
}

/// `(origin, dest)` of half-edge `h` from the corners and a table of end vertices (the
/// build's first pass); `NONE` out of range.
#[inline]
fn ends_in(indices: &[u32], dest: &[u32], h: u32) -> (u32, u32) {
    let a = indices.get(h as usize).copied().unwrap_or(NONE);
    let b = dest.get(h as usize).copied().unwrap_or(NONE);
    (a, b)
}

/// The undirected key `(min, max)` of half-edge `h`, as one `u64`.
#[inline]
fn key_in(indices: &[u32], dest: &[u32], h: u32) -> u64 {
    let (a, b) = ends_in(indices, dest, h);
    ((a.min(b) as u64) << 32) | a.max(b) as u64
}

impl<'m, 's> Topology<'m, 's> {
    /// Validates `mesh` (see the module docs for the order of checks) and builds its topology
    /// in `scratch`, which must hold [`super::topology_scratch_size`] entries.
    ///
    /// # Errors
    /// The first failed check, naming its element; [`Status::BufferTooSmall`] with the needed
    /// length when `scratch` is short.
    pub fn build(mesh: Mesh<'m>, scratch: &'s mut [u32]) -> Result<Self> {
        let nv = mesh.num_vertices();
        let nh = mesh.num_corners();
        if nv > MAX_COUNT || nh > MAX_COUNT || mesh.offsets.len() > MAX_COUNT {
            return Err(Error::new(Status::SizeOverflow));
        }
        check_offsets(&mesh)?;
        check_faces(&mesh)?;
        let Regions {
            face_of,
            twin,
            edge_of,
            edge_he,
            vert_he,
            valence,
            bnd_rank,
        } = regions(scratch, nv, nh)?;
        let (max_face, min_face) = face_pass(&mesh, face_of, edge_of)?;
        let face_of_ro: &[u32] = face_of;
        sort_directed_edges(&mesh, edge_of, twin, edge_he, vert_he)?;
        let (n_edges, n_boundary_edges) = number_edges(&mesh, face_of_ro, twin, edge_of, edge_he)?;
        check_pillows(&mesh, face_of_ro, twin)?;
        vertex_stars(&mesh, face_of_ro, twin, vert_he, valence)?;
        let v = vertex_counts(twin, vert_he, valence, bnd_rank)?;
        for (v, p) in mesh.positions().enumerate() {
            if !point::is_finite(&p) {
                return Err(Error::at(Status::NonFiniteInput, v as u32));
            }
        }
        let edge_he: &'s [u32] = edge_he;
        Ok(Topology {
            mesh,
            face_of,
            twin,
            edge_of,
            edge_he: edge_he.get(..n_edges).ok_or(internal())?,
            vert_he,
            valence,
            bnd_rank,
            n_boundary_edges,
            n_boundary_vertices: v.boundary,
            n_isolated: v.isolated,
            interior_spokes: v.interior_spokes,
            boundary_spokes: v.boundary_spokes,
            max_face,
            min_face,
        })
    }
}

/// The face of every half-edge into `face_of`, and its end vertex into `edge_of` (read by
/// the sort and the edge scan; each entry is overwritten by its edge id after its last read).
/// Returns the largest and the smallest face size (0 for a mesh without faces).
fn face_pass(mesh: &Mesh<'_>, face_of: &mut [u32], edge_of: &mut [u32]) -> Result<(usize, usize)> {
    let nf = mesh.num_faces();
    let (offsets, indices) = (mesh.offsets, mesh.indices);
    let mut max_face = 0usize;
    let mut min_face = if nf == 0 { 0 } else { usize::MAX };
    for f in 0..nf {
        let a = get(offsets, f)? as usize;
        let b = get(offsets, f + 1)? as usize;
        max_face = max_face.max(b - a);
        min_face = min_face.min(b - a);
        for slot in face_of.get_mut(a..b).ok_or(internal())? {
            *slot = f as u32;
        }
        let corners = indices.get(a..b).ok_or(internal())?;
        let ends = edge_of.get_mut(a..b).ok_or(internal())?;
        let first = corners.first().copied().ok_or(internal())?;
        for (k, slot) in ends.iter_mut().enumerate() {
            *slot = corners.get(k + 1).copied().unwrap_or(first);
        }
    }
    Ok((max_face, min_face))
}

/// The directed-edge table: half-edge ids sorted by (min, max, half-edge) into `edge_he`.
/// Two stable counting sorts (least significant key first): by the larger endpoint into
/// `twin` (used as scratch), then by the smaller one into `edge_he`; the counts live in the
/// still unused `vert_he`. Linear time, no comparisons, and the same total order as one
/// global sort. `ends` holds the end vertex of every half-edge ([`face_pass`]).
fn sort_directed_edges(
    mesh: &Mesh<'_>,
    ends: &[u32],
    twin: &mut [u32],
    edge_he: &mut [u32],
    vert_he: &mut [u32],
) -> Result<()> {
    let indices = mesh.indices;
    let by_max = indices
        .iter()
        .zip(ends.iter())
        .enumerate()
        .map(|(h, (&a, &b))| (h as u32, a.max(b)));
    counting_sort(by_max, twin, vert_he)?;
    let by_min = twin.iter().map(|&h| {
        let (a, b) = ends_in(indices, ends, h);
        (h, a.min(b))
    });
    counting_sort(by_min, edge_he, vert_he)
}

/// Walks the sorted directed-edge table one edge (run of equal keys) at a time: checks
/// classes 7 (duplicate faces among the first four on the edge, orientation, non-manifold
/// edges), sets the twins, numbers the edges in key order (`edge_of`, overwriting the end
/// vertices once read) and puts each edge's representative half-edge at `edge_he[e]`.
/// Returns the numbers of edges and of boundary edges.
fn number_edges(
    mesh: &Mesh<'_>,
    face_of: &[u32],
    twin: &mut [u32],
    edge_of: &mut [u32],
    edge_he: &mut [u32],
) -> Result<(usize, usize)> {
    let nh = mesh.num_corners();
    let indices = mesh.indices;
    let mut n_edges = 0usize;
    let mut n_boundary_edges = 0usize;
    let mut s = 0usize;
    while s < nh {
        let h0 = get(edge_he, s)?;
        let k0 = key_in(indices, edge_of, h0);
        let mut e = s + 1;
        while e < nh && key_in(indices, edge_of, get(edge_he, e)?) == k0 {
            e += 1;
        }
        let len = e - s;
        let last = get(edge_he, e - 1)?;
        let last_face = get(face_of, last as usize)?;
        if len >= 2 {
            // Duplicate faces among the first four faces on this edge.
            let m = len.min(4);
            for i in 0..m {
                for j in i + 1..m {
                    let hi = get(edge_he, s + i)?;
                    let fi = get(face_of, hi as usize)?;
                    let fj = get(face_of, get(edge_he, s + j)? as usize)?;
                    if same_vertex_set(mesh, fi, fj, hi) {
                        return Err(Error::at(Status::DuplicateFace, fi.max(fj)));
                    }
                }
            }
        }
        let rep = match len {
            1 => {
                set(twin, h0 as usize, NONE)?;
                n_boundary_edges += 1;
                h0
            }
            2 => {
                let h1 = get(edge_he, s + 1)?;
                let a0 = get(indices, h0 as usize)?;
                let a1 = get(indices, h1 as usize)?;
                if a0 == a1 {
                    return Err(Error::at(Status::InconsistentOrientation, last_face));
                }
                set(twin, h0 as usize, h1)?;
                set(twin, h1 as usize, h0)?;
                set(edge_of, h1 as usize, n_edges as u32)?;
                if a0 < a1 {
                    h0
                } else {
                    h1
                }
            }
            _ => return Err(Error::at(Status::NonManifoldEdge, last_face)),
        };
        set(edge_of, h0 as usize, n_edges as u32)?;
        // n_edges <= s: the run at s has been read, later runs start after it.
        set(edge_he, n_edges, rep)?;
        n_edges += 1;
        s = e;
    }
    Ok((n_edges, n_boundary_edges))
}

/// Class 8: a pillow, a face all of whose edges are shared with one and the same other face.
fn check_pillows(mesh: &Mesh<'_>, face_of: &[u32], twin: &[u32]) -> Result<()> {
    let offsets = mesh.offsets;
    for f in 0..mesh.num_faces() {
        let a = get(offsets, f)? as usize;
        let b = get(offsets, f + 1)? as usize;
        let mut other = NONE;
        let mut pillow = true;
        for h in a..b {
            let t = get(twin, h)?;
            if t == NONE {
                pillow = false;
                break;
            }
            let g = get(face_of, t as usize)?;
            if other == NONE {
                other = g;
            } else if other != g {
                pillow = false;
                break;
            }
        }
        if pillow && other != NONE {
            return Err(Error::at(Status::DuplicateFace, (f as u32).max(other)));
        }
    }
    Ok(())
}

/// The star of every vertex: its first spoke (`vert_he`, a boundary vertex's outgoing
/// boundary half-edge), its out-degree (`valence`), and class 9: the faces at a vertex must
/// be one disk or one half-disk (the walk `h → twin(prev(h))` from the first spoke meets
/// every outgoing half-edge).
fn vertex_stars(
    mesh: &Mesh<'_>,
    face_of: &[u32],
    twin: &[u32],
    vert_he: &mut [u32],
    valence: &mut [u32],
) -> Result<()> {
    let (nv, nh) = (mesh.num_vertices(), mesh.num_corners());
    let (offsets, indices) = (mesh.offsets, mesh.indices);
    for slot in vert_he.iter_mut() {
        *slot = NONE;
    }
    for slot in valence.iter_mut() {
        *slot = 0;
    }
    let mut bad_vertex = NONE;
    for h in 0..nh {
        let v = get(indices, h)? as usize;
        set(valence, v, get(valence, v)? + 1)?;
        let cur = get(vert_he, v)?;
        if get(twin, h)? == NONE {
            if cur != NONE && get(twin, cur as usize)? == NONE {
                // Two outgoing boundary half-edges: two half-disks meet at v.
                bad_vertex = bad_vertex.min(v as u32);
            }
            set(vert_he, v, h as u32)?;
        } else if cur == NONE {
            set(vert_he, v, h as u32)?;
        }
    }
    for v in 0..nv.min(bad_vertex as usize) {
        let start = get(vert_he, v)?;
        if start == NONE {
            continue;
        }
        let out = get(valence, v)?;
        let start_is_boundary = get(twin, start as usize)? == NONE;
        let mut count = 1u32;
        let mut h = start;
        let mut ok = true;
        loop {
            let p = prev_in(offsets, face_of, h)?;
            let t = get(twin, p as usize)?;
            if t == NONE {
                ok = start_is_boundary;
                break;
            }
            if t == start {
                break;
            }
            h = t;
            count += 1;
            if count > out {
                ok = false;
                break;
            }
        }
        if !ok || count != out {
            bad_vertex = v as u32;
            break;
        }
    }
    if bad_vertex != NONE {
        return Err(Error::at(Status::NonManifoldVertex, bad_vertex));
    }
    Ok(())
}

/// The counts of [`vertex_counts`].
struct VertexCounts {
    boundary: usize,
    isolated: usize,
    interior_spokes: usize,
    boundary_spokes: usize,
}

/// Valences (a boundary vertex has one neighbour more than outgoing half-edges), boundary
/// ranks and the vertex counts; class 10, [`Status::ValenceTooHigh`] above
/// [`MAX_VALENCE`].
fn vertex_counts(
    twin: &[u32],
    vert_he: &[u32],
    valence: &mut [u32],
    bnd_rank: &mut [u32],
) -> Result<VertexCounts> {
    let mut c = VertexCounts {
        boundary: 0,
        isolated: 0,
        interior_spokes: 0,
        boundary_spokes: 0,
    };
    for v in 0..vert_he.len() {
        let start = get(vert_he, v)?;
        let out = get(valence, v)?;
        set(bnd_rank, v, NONE)?;
        if start == NONE {
            c.isolated += 1;
            continue;
        }
        let val = if get(twin, start as usize)? == NONE {
            set(bnd_rank, v, c.boundary as u32)?;
            c.boundary += 1;
            c.boundary_spokes += out as usize + 1;
            out + 1
        } else {
            c.interior_spokes += out as usize;
            out
        };
        if val as usize > MAX_VALENCE {
            return Err(Error::at(Status::ValenceTooHigh, v as u32));
        }
        set(valence, v, val)?;
    }
    Ok(c)
}
