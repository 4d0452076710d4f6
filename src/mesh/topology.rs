//! Validation and half-edge topology of a [`Mesh`], built in caller scratch.
//!
//! # Half-edges, edges, stars
//!
//! * Half-edge `h` **is corner `h`**: it starts at `indices[h]` and ends at the next corner of
//!   its face. `next`, `prev` and `face` follow from the CSR offsets; `twin` is stored.
//! * **Edges** are numbered in ascending `(min, max)` vertex-key order: the directed-edge table
//!   is sorted by `(min, max, half-edge)` — two stable counting sorts, by `max` then by
//!   `min` (reliability-anchors.md §3.1: no hashing, no `sort_unstable`) — so numbering
//!   never depends on input order beyond the vertex indices. Each edge's representative
//!   half-edge runs from `min` to `max` when that direction exists (always, for interior
//!   edges), else it is the only half-edge.
//! * **Stars** ([`Topology::star`]) are walked counter-clockwise (faces are CCW seen from
//!   outside): `h → twin(prev(h))`. An interior vertex's star starts at its lowest-numbered
//!   outgoing half-edge; a boundary vertex's star runs from one boundary neighbour `b0`
//!   (the end of its outgoing boundary half-edge) to the other, `b1` (the start of its incoming
//!   boundary half-edge), so it has `faces + 1` spokes.
//! * **Boundary loops** follow the boundary half-edges (face on their left):
//!   [`Topology::next_boundary`].
//!
//! # Validation order and the element named by each error
//!
//! Topology first, all before any write to caller output (DESIGN.md, reliability-anchors.md §2).
//! Each class is checked over the whole mesh before the next class:
//!
//! | order | status | element |
//! |---|---|---|
//! | 0 | `SizeOverflow`: a count above [`MAX_COUNT`] | none |
//! | 1 | `BadOffsets`: `offsets` empty, `offsets[0] ≠ 0`, decreasing, or last ≠ `indices.len()` | face |
//! | 2 | `FaceTooSmall`: fewer than 3 corners | face |
//! | 3 | `ValenceTooHigh`: more than [`MAX_FACE_SIZE`] corners | face |
//! | 4 | `IndexOutOfRange` | face |
//! | 5 | `RepeatedVertex` | face |
//! | 6 | `BufferTooSmall`: scratch below [`topology_scratch_len`] | none |
//! | 7 | `DuplicateFace`: two faces on one edge with the same vertex set | the later face |
//! | 7 | `InconsistentOrientation`: two half-edges of one edge in the same direction | the later face |
//! | 7 | `NonManifoldEdge`: three or more faces on one edge | the last face on it |
//! | 8 | `DuplicateFace`: pillow (every edge of a face shared with one other face) | the later face |
//! | 9 | `NonManifoldVertex`: the faces at a vertex are not one disk or half-disk | vertex (lowest) |
//! | 10 | `ValenceTooHigh`: more than [`MAX_VALENCE`] neighbours | vertex |
//! | 11 | `NonFiniteInput`: NaN or ±∞ in any vertex, referenced or not | vertex |
//!
//! Class 7 is reported for the first offending edge in `(min, max)` key order. A duplicate is
//! recognised among the first four faces of an edge; beyond that `NonManifoldEdge` is
//! reported (bounded work on hostile input).

use arrayvec::ArrayVec;

use super::sort::counting_sort;
use super::{get, internal, set, Mesh, MAX_COUNT, NONE};
use crate::error::{Error, Result, Status};
use crate::point::{self, Point};
use crate::{MAX_FACE_SIZE, MAX_VALENCE};

/// Scratch (`u32` entries) that [`Topology::build`] needs for a mesh with `num_vertices`
/// vertices and `num_corners` corners: `4·corners + 3·vertices`.
///
/// # Errors
/// [`Status::SizeOverflow`] when the size does not fit `usize`.
pub fn topology_scratch_len(num_vertices: usize, num_corners: usize) -> Result<usize> {
    let a = num_corners
        .checked_mul(4)
        .ok_or(Error::new(Status::SizeOverflow))?;
    let b = num_vertices
        .checked_mul(3)
        .ok_or(Error::new(Status::SizeOverflow))?;
    a.checked_add(b).ok_or(Error::new(Status::SizeOverflow))
}

/// A validated mesh with its half-edge topology, held in caller scratch.
///
/// Built by [`Topology::build`] (validating) or derived from a parent level's by
/// `refine::child_topology` (multi-level calls); every query is `O(1)` except star walks (`O(valence)`).
/// Queries return `Result` only to stay panic-free: on a built topology they cannot fail for
/// indices in range.
#[derive(Clone, Copy, Debug)]
pub struct Topology<'m, 's> {
    mesh: Mesh<'m>,
    face_of: &'s [u32],
    twin: &'s [u32],
    edge_of: &'s [u32],
    edge_he: &'s [u32],
    vert_he: &'s [u32],
    valence: &'s [u32],
    bnd_rank: &'s [u32],
    n_boundary_edges: usize,
    n_boundary_vertices: usize,
    n_isolated: usize,
    interior_spokes: usize,
    boundary_spokes: usize,
    max_face: usize,
    min_face: usize,
}

/// The seven regions of a topology scratch ([`Topology::build`]'s layout).
pub(crate) struct Regions<'s> {
    pub(crate) face_of: &'s mut [u32],
    pub(crate) twin: &'s mut [u32],
    pub(crate) edge_of: &'s mut [u32],
    pub(crate) edge_he: &'s mut [u32],
    pub(crate) vert_he: &'s mut [u32],
    pub(crate) valence: &'s mut [u32],
    pub(crate) bnd_rank: &'s mut [u32],
}

/// The regions of a scratch for `nv` vertices and `nh` half-edges;
/// [`Status::BufferTooSmall`] with the needed length when it is short.
pub(crate) fn regions(scratch: &mut [u32], nv: usize, nh: usize) -> Result<Regions<'_>> {
    let need = topology_scratch_len(nv, nh)?;
    if scratch.len() < need {
        return Err(Error::too_small(need));
    }
    let (face_of, rest) = scratch.split_at_mut_checked(nh).ok_or(internal())?;
    let (twin, rest) = rest.split_at_mut_checked(nh).ok_or(internal())?;
    let (edge_of, rest) = rest.split_at_mut_checked(nh).ok_or(internal())?;
    let (edge_he, rest) = rest.split_at_mut_checked(nh).ok_or(internal())?;
    let (vert_he, rest) = rest.split_at_mut_checked(nv).ok_or(internal())?;
    let (valence, rest) = rest.split_at_mut_checked(nv).ok_or(internal())?;
    let (bnd_rank, _) = rest.split_at_mut_checked(nv).ok_or(internal())?;
    Ok(Regions {
        face_of,
        twin,
        edge_of,
        edge_he,
        vert_he,
        valence,
        bnd_rank,
    })
}

/// The scalar part of a [`Topology`] (its arrays live in the scratch): with the scratch of a
/// built or derived topology it rebuilds the same view in `O(1)` ([`Topology::from_parts`]),
/// so a multi-level call can keep a topology across loop iterations without borrowing it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Counts {
    pub(crate) n_edges: usize,
    pub(crate) n_boundary_edges: usize,
    pub(crate) n_boundary_vertices: usize,
    pub(crate) n_isolated: usize,
    pub(crate) interior_spokes: usize,
    pub(crate) boundary_spokes: usize,
    pub(crate) max_face: usize,
    pub(crate) min_face: usize,
}

/// The arrays of a [`Topology`] ([`Topology::raw`]); see the module docs for their meaning.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Raw<'m, 's> {
    pub(crate) offsets: &'m [u32],
    pub(crate) indices: &'m [u32],
    pub(crate) face_of: &'s [u32],
    pub(crate) twin: &'s [u32],
    pub(crate) edge_of: &'s [u32],
    pub(crate) edge_he: &'s [u32],
    pub(crate) vert_he: &'s [u32],
    pub(crate) valence: &'s [u32],
    pub(crate) bnd_rank: &'s [u32],
    /// Every face is a quad, so face `f` is corners `4f..4f + 4` (every level of
    /// Catmull–Clark and Kobbelt after the first).
    pub(crate) quads: bool,
    /// Every face is a triangle, so face `f` is corners `3f..3f + 3` (Loop, Butterfly).
    pub(crate) triangles: bool,
}

impl Raw<'_, '_> {
    /// `(next(h), prev(h), face(h))` from one face lookup (none on an all-quad mesh).
    #[inline]
    pub(crate) fn next_prev_face(&self, h: u32) -> Result<(u32, u32, u32)> {
        if self.quads {
            let base = h & !3;
            return Ok((
                base | (h.wrapping_add(1) & 3),
                base | (h.wrapping_add(3) & 3),
                h >> 2,
            ));
        }
        if self.triangles {
            let f = h / 3;
            let base = 3 * f;
            let (next, prev) = match h - base {
                0 => (h + 1, h + 2),
                1 => (h + 1, h - 1),
                _ => (base, h - 1),
            };
            return Ok((next, prev, f));
        }
        let f = get(self.face_of, h as usize)?;
        let start = get(self.offsets, f as usize)?;
        let end = get(self.offsets, f as usize + 1)?;
        let next = if h + 1 == end { start } else { h + 1 };
        let prev = if h == start {
            end.wrapping_sub(1)
        } else {
            h.wrapping_sub(1)
        };
        Ok((next, prev, f))
    }
}

/// One spoke of a vertex star: an edge from the centre to a neighbour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Spoke {
    /// The neighbour vertex.
    pub neighbour: u32,
    /// The edge id of the spoke.
    pub edge: u32,
    /// The half-edge from the centre to the neighbour, or [`NONE`] for the closing spoke of a
    /// boundary star (its edge exists only as the incoming boundary half-edge).
    pub half_edge: u32,
    /// The face between this spoke and the next one counter-clockwise, or [`NONE`] after the
    /// last spoke of a boundary star.
    pub face: u32,
}

/// Iterator over the spokes of a vertex star, counter-clockwise (see the module docs).
#[derive(Clone, Debug)]
pub struct Star<'t, 'm, 's> {
    topo: &'t Topology<'m, 's>,
    cur: u32,
    closing: u32,
    remaining: u32,
}

impl Iterator for Star<'_, '_, '_> {
    type Item = Spoke;

    fn next(&mut self) -> Option<Spoke> {
        if self.remaining == 0 {
            return None;
        }
        self.remaining -= 1;
        let t = self.topo;
        if self.cur == NONE {
            // Closing spoke of a boundary star: the incoming boundary half-edge b1 -> v.
            let p = self.closing;
            self.remaining = 0;
            return Some(Spoke {
                neighbour: t.origin(p).ok()?,
                edge: t.edge(p).ok()?,
                half_edge: NONE,
                face: NONE,
            });
        }
        let h = self.cur;
        // One face lookup gives the spoke's face, its end (next corner) and the previous
        // corner, whose twin is the next spoke.
        let f = get(t.face_of, h as usize).ok()?;
        let start = get(t.mesh.offsets, f as usize).ok()?;
        let end = get(t.mesh.offsets, f as usize + 1).ok()?;
        let next = if h + 1 == end { start } else { h + 1 };
        let p = if h == start {
            end.wrapping_sub(1)
        } else {
            h.wrapping_sub(1)
        };
        let spoke = Spoke {
            neighbour: get(t.mesh.indices, next as usize).ok()?,
            edge: get(t.edge_of, h as usize).ok()?,
            half_edge: h,
            face: f,
        };
        let tw = get(t.twin, p as usize).ok()?;
        if tw == NONE {
            self.cur = NONE;
            self.closing = p;
        } else {
            self.cur = tw;
        }
        Some(spoke)
    }
}

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

/// `next(h)` from the offsets and the face of each half-edge.
fn next_in(offsets: &[u32], face_of: &[u32], h: u32) -> Result<u32> {
    let f = get(face_of, h as usize)? as usize;
    let end = get(offsets, f + 1)?;
    if h + 1 == end {
        get(offsets, f)
    } else {
        Ok(h + 1)
    }
}

/// `prev(h)` from the offsets and the face of each half-edge.
fn prev_in(offsets: &[u32], face_of: &[u32], h: u32) -> Result<u32> {
    let f = get(face_of, h as usize)? as usize;
    let start = get(offsets, f)?;
    if h == start {
        Ok(get(offsets, f + 1)?.wrapping_sub(1))
    } else {
        Ok(h - 1)
    }
}

impl<'m, 's> Topology<'m, 's> {
    /// Validates `mesh` (see the module docs for the order of checks) and builds its topology
    /// in `scratch`, which must hold [`topology_scratch_len`] entries.
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
        let nf = mesh.num_faces();
        let Regions {
            face_of,
            twin,
            edge_of,
            edge_he,
            vert_he,
            valence,
            bnd_rank,
        } = regions(scratch, nv, nh)?;

        let offsets = mesh.offsets;
        let indices = mesh.indices;
        let mut max_face = 0usize;
        let mut min_face = if nf == 0 { 0 } else { usize::MAX };
        // Face of every half-edge, and its end vertex in the edge_of region (read by the
        // sort and the edge scan below; each entry is overwritten by its edge id after its
        // last read).
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

        // Directed-edge table: half-edge ids sorted by (min, max, half-edge), in the edge_he
        // region. Two stable counting sorts (least significant key first): by the larger
        // endpoint into the twin region, then by the smaller one into edge_he; the counts
        // live in the still unused vertex region. Linear time, no comparisons, and the same
        // total order as one global sort.
        let face_of_ro: &[u32] = face_of;
        let by_max = indices
            .iter()
            .zip(edge_of.iter())
            .enumerate()
            .map(|(h, (&a, &b))| (h as u32, a.max(b)));
        counting_sort(by_max, twin, vert_he)?;
        let by_min = twin.iter().map(|&h| {
            let (a, b) = ends_in(indices, edge_of, h);
            (h, a.min(b))
        });
        counting_sort(by_min, edge_he, vert_he)?;

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
            let last_face = get(face_of_ro, last as usize)?;
            if len >= 2 {
                // Duplicate faces among the first four faces on this edge.
                let m = len.min(4);
                for i in 0..m {
                    for j in i + 1..m {
                        let hi = get(edge_he, s + i)?;
                        let fi = get(face_of_ro, hi as usize)?;
                        let fj = get(face_of_ro, get(edge_he, s + j)? as usize)?;
                        if same_vertex_set(&mesh, fi, fj, hi) {
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

        // Pillows: a face all of whose edges are shared with one and the same other face.
        for f in 0..nf {
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
                let g = get(face_of_ro, t as usize)?;
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

        // Vertices: star start, out-degree, manifoldness (one disk or one half-disk).
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
                let p = prev_in(offsets, face_of_ro, h)?;
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

        let mut n_boundary_vertices = 0usize;
        let mut n_isolated = 0usize;
        let mut interior_spokes = 0usize;
        let mut boundary_spokes = 0usize;
        for v in 0..nv {
            let start = get(vert_he, v)?;
            let out = get(valence, v)?;
            set(bnd_rank, v, NONE)?;
            if start == NONE {
                n_isolated += 1;
                continue;
            }
            let val = if get(twin, start as usize)? == NONE {
                set(bnd_rank, v, n_boundary_vertices as u32)?;
                n_boundary_vertices += 1;
                boundary_spokes += out as usize + 1;
                out + 1
            } else {
                interior_spokes += out as usize;
                out
            };
            if val as usize > MAX_VALENCE {
                return Err(Error::at(Status::ValenceTooHigh, v as u32));
            }
            set(valence, v, val)?;
        }

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
            n_boundary_vertices,
            n_isolated,
            interior_spokes,
            boundary_spokes,
            max_face,
            min_face,
        })
    }

    /// The arrays of this topology, read-only, for the hot loops of the patterns and the
    /// linear drivers (the same data the queries read, without a call per lookup).
    pub(crate) fn raw(&self) -> Raw<'m, 's> {
        Raw {
            offsets: self.mesh.offsets,
            indices: self.mesh.indices,
            face_of: self.face_of,
            twin: self.twin,
            edge_of: self.edge_of,
            edge_he: self.edge_he,
            vert_he: self.vert_he,
            valence: self.valence,
            bnd_rank: self.bnd_rank,
            quads: self.min_face == 4 && self.max_face == 4,
            triangles: self.min_face == 3 && self.max_face == 3,
        }
    }

    /// The scalar part of this topology, for [`Topology::from_parts`].
    pub(crate) fn counts(&self) -> Counts {
        Counts {
            n_edges: self.edge_he.len(),
            n_boundary_edges: self.n_boundary_edges,
            n_boundary_vertices: self.n_boundary_vertices,
            n_isolated: self.n_isolated,
            interior_spokes: self.interior_spokes,
            boundary_spokes: self.boundary_spokes,
            max_face: self.max_face,
            min_face: self.min_face,
        }
    }

    /// The topology of `mesh` whose arrays [`Topology::build`] (or a derivation of
    /// `refine::child_topology`) left in `scratch`, with the `counts` it returned: the same view again in
    /// `O(1)`, nothing re-validated. Only the regions' lengths are checked.
    pub(crate) fn from_parts(
        mesh: Mesh<'m>,
        scratch: &'s mut [u32],
        counts: Counts,
    ) -> Result<Self> {
        // The scratch was sized for this mesh when the arrays were written: short is a bug.
        let Regions {
            face_of,
            twin,
            edge_of,
            edge_he,
            vert_he,
            valence,
            bnd_rank,
        } = regions(scratch, mesh.num_vertices(), mesh.num_corners()).map_err(|_| internal())?;
        let edge_he: &'s [u32] = edge_he;
        Ok(Topology {
            mesh,
            face_of,
            twin,
            edge_of,
            edge_he: edge_he.get(..counts.n_edges).ok_or(internal())?,
            vert_he,
            valence,
            bnd_rank,
            n_boundary_edges: counts.n_boundary_edges,
            n_boundary_vertices: counts.n_boundary_vertices,
            n_isolated: counts.n_isolated,
            interior_spokes: counts.interior_spokes,
            boundary_spokes: counts.boundary_spokes,
            max_face: counts.max_face,
            min_face: counts.min_face,
        })
    }

    /// The mesh this topology describes.
    pub fn mesh(&self) -> Mesh<'m> {
        self.mesh
    }

    /// Number of vertices, isolated ones included.
    pub fn num_vertices(&self) -> usize {
        self.mesh.num_vertices()
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.mesh.num_faces()
    }

    /// Number of half-edges (= corners).
    pub fn num_half_edges(&self) -> usize {
        self.mesh.num_corners()
    }

    /// Number of edges.
    pub fn num_edges(&self) -> usize {
        self.edge_he.len()
    }

    /// Number of boundary edges (edges with one face).
    pub fn num_boundary_edges(&self) -> usize {
        self.n_boundary_edges
    }

    /// Number of interior edges (edges with two faces).
    pub fn num_interior_edges(&self) -> usize {
        self.num_edges() - self.n_boundary_edges
    }

    /// Number of boundary vertices (= boundary edges on a manifold mesh).
    pub fn num_boundary_vertices(&self) -> usize {
        self.n_boundary_vertices
    }

    /// Number of isolated (unreferenced) vertices.
    pub fn num_isolated_vertices(&self) -> usize {
        self.n_isolated
    }

    /// Number of interior vertices (referenced and not on the boundary).
    pub fn num_interior_vertices(&self) -> usize {
        self.num_vertices() - self.n_boundary_vertices - self.n_isolated
    }

    /// Sum of the valences of all interior vertices.
    pub fn interior_valence_sum(&self) -> usize {
        self.interior_spokes
    }

    /// Sum of the valences of all boundary vertices.
    pub fn boundary_valence_sum(&self) -> usize {
        self.boundary_spokes
    }

    /// Largest face size (0 for a mesh without faces).
    pub fn max_face_size(&self) -> usize {
        self.max_face
    }

    /// Smallest face size (0 for a mesh without faces).
    pub fn min_face_size(&self) -> usize {
        self.min_face
    }

    /// Euler characteristic `V − E + F`, isolated vertices counted (each is a component with
    /// χ = 1).
    pub fn euler_characteristic(&self) -> i64 {
        self.num_vertices() as i64 - self.num_edges() as i64 + self.num_faces() as i64
    }

    /// The corners (= half-edges) of face `f`, `offsets[f]..offsets[f + 1]`.
    pub fn face_half_edges(&self, f: u32) -> Result<core::ops::Range<u32>> {
        let a = get(self.mesh.offsets, f as usize)?;
        let b = get(self.mesh.offsets, f as usize + 1)?;
        Ok(a..b)
    }

    /// The vertices of face `f`.
    pub fn face_vertices(&self, f: u32) -> Result<&'m [u32]> {
        self.mesh.face(f as usize).ok_or(internal())
    }

    /// Number of corners of face `f`.
    pub fn face_size(&self, f: u32) -> Result<usize> {
        Ok(self.face_vertices(f)?.len())
    }

    /// Position of vertex `v`.
    pub fn position(&self, v: u32) -> Result<Point> {
        self.mesh.position(v).ok_or(internal())
    }

    /// Start vertex of half-edge `h`.
    pub fn origin(&self, h: u32) -> Result<u32> {
        get(self.mesh.indices, h as usize)
    }

    /// End vertex of half-edge `h`.
    pub fn dest(&self, h: u32) -> Result<u32> {
        self.origin(self.next(h)?)
    }

    /// Next half-edge of the same face.
    pub fn next(&self, h: u32) -> Result<u32> {
        next_in(self.mesh.offsets, self.face_of, h)
    }

    /// Previous half-edge of the same face.
    pub fn prev(&self, h: u32) -> Result<u32> {
        prev_in(self.mesh.offsets, self.face_of, h)
    }

    /// Face of half-edge `h`.
    pub fn face(&self, h: u32) -> Result<u32> {
        get(self.face_of, h as usize)
    }

    /// Opposite half-edge, or [`NONE`] on the boundary.
    pub fn twin(&self, h: u32) -> Result<u32> {
        get(self.twin, h as usize)
    }

    /// Edge id of half-edge `h`.
    pub fn edge(&self, h: u32) -> Result<u32> {
        get(self.edge_of, h as usize)
    }

    /// Representative half-edge of edge `e` (from `min` to `max` when it exists).
    pub fn edge_half_edge(&self, e: u32) -> Result<u32> {
        get(self.edge_he, e as usize)
    }

    /// The two vertices `(min, max)` of edge `e`.
    pub fn edge_vertices(&self, e: u32) -> Result<(u32, u32)> {
        let h = self.edge_half_edge(e)?;
        let (a, b) = (self.origin(h)?, self.dest(h)?);
        Ok((a.min(b), a.max(b)))
    }

    /// Whether edge `e` has a single face.
    pub fn is_boundary_edge(&self, e: u32) -> Result<bool> {
        Ok(self.twin(self.edge_half_edge(e)?)? == NONE)
    }

    /// Number of neighbours of `v` (0 for an isolated vertex).
    pub fn valence(&self, v: u32) -> Result<usize> {
        Ok(get(self.valence, v as usize)? as usize)
    }

    /// Number of faces around `v`: the valence, minus one on the boundary.
    pub fn vertex_face_count(&self, v: u32) -> Result<usize> {
        let n = self.valence(v)?;
        Ok(if self.is_boundary_vertex(v)? {
            n - 1
        } else {
            n
        })
    }

    /// The first outgoing half-edge of `v`'s star, [`NONE`] for an isolated vertex.
    pub fn vertex_half_edge(&self, v: u32) -> Result<u32> {
        get(self.vert_he, v as usize)
    }

    /// Whether `v` lies on the boundary.
    pub fn is_boundary_vertex(&self, v: u32) -> Result<bool> {
        let h = self.vertex_half_edge(v)?;
        Ok(h != NONE && self.twin(h)? == NONE)
    }

    /// The rank of boundary vertex `v` among the boundary vertices in index order (`0..`
    /// [`num_boundary_vertices`](Self::num_boundary_vertices)), [`NONE`] for other vertices.
    /// Dual patterns number their boundary points with it.
    pub fn boundary_vertex_rank(&self, v: u32) -> Result<u32> {
        get(self.bnd_rank, v as usize)
    }

    /// Whether `v` is referenced by no face.
    pub fn is_isolated(&self, v: u32) -> Result<bool> {
        Ok(self.vertex_half_edge(v)? == NONE)
    }

    /// The spokes of `v`'s star, counter-clockwise (module docs).
    pub fn star<'t>(&'t self, v: u32) -> Star<'t, 'm, 's> {
        let cur = self.vertex_half_edge(v).unwrap_or(NONE);
        let remaining = if cur == NONE {
            0
        } else {
            get(self.valence, v as usize).unwrap_or(0)
        };
        Star {
            topo: self,
            cur,
            closing: NONE,
            remaining,
        }
    }

    /// The spokes of `v`'s star collected in a fixed-capacity array.
    pub fn spokes(&self, v: u32) -> Result<ArrayVec<Spoke, MAX_VALENCE>> {
        let mut out = ArrayVec::new();
        self.spokes_into(v, &mut out)?;
        Ok(out)
    }

    /// [`Topology::spokes`] into a reused buffer (the drivers: no 2 KB array returned per
    /// vertex).
    pub(crate) fn spokes_into(&self, v: u32, out: &mut ArrayVec<Spoke, MAX_VALENCE>) -> Result<()> {
        out.clear();
        for s in self.star(v) {
            out.try_push(s)
                .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
        }
        if out.len() != self.valence(v)? {
            return Err(internal());
        }
        Ok(())
    }

    /// The neighbours of `v`, counter-clockwise (the star's order).
    pub fn ring(&self, v: u32) -> Result<ArrayVec<u32, MAX_VALENCE>> {
        let mut out = ArrayVec::new();
        for s in self.spokes(v)? {
            out.try_push(s.neighbour)
                .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
        }
        Ok(out)
    }

    /// For a boundary vertex, its two boundary neighbours `(b0, b1)`: `b0` at the end of its
    /// outgoing boundary half-edge, `b1` at the start of its incoming one.
    pub fn boundary_neighbours(&self, v: u32) -> Result<(u32, u32)> {
        let h = self.vertex_half_edge(v)?;
        if h == NONE || self.twin(h)? != NONE {
            return Err(Error::at(Status::InvalidArgument, v));
        }
        let b0 = self.dest(h)?;
        let incoming = self.prev_boundary(h)?;
        Ok((b0, self.origin(incoming)?))
    }

    /// For a boundary half-edge `h`, the next boundary half-edge along its loop (it starts
    /// where `h` ends).
    pub fn next_boundary(&self, h: u32) -> Result<u32> {
        self.vertex_half_edge(self.dest(h)?)
    }

    /// For a boundary half-edge `h`, the previous boundary half-edge along its loop.
    pub fn prev_boundary(&self, h: u32) -> Result<u32> {
        // Walk clockwise around origin(h) from h to the incoming boundary half-edge.
        let mut p = self.prev(h)?;
        for _ in 0..=MAX_VALENCE {
            let t = self.twin(p)?;
            if t == NONE {
                return Ok(p);
            }
            p = self.prev(t)?;
        }
        Err(internal())
    }

    /// Labels every boundary half-edge with its loop id in `mark` (at least
    /// [`num_half_edges`](Self::num_half_edges) entries; [`NONE`] for interior half-edges) and
    /// returns the number of boundary loops. Loops are numbered in the order of their
    /// lowest half-edge.
    pub fn boundary_loops(&self, mark: &mut [u32]) -> Result<usize> {
        let nh = self.num_half_edges();
        let mark = mark.get_mut(..nh).ok_or(Error::too_small(nh))?;
        for m in mark.iter_mut() {
            *m = NONE;
        }
        let mut loops = 0usize;
        for h in 0..nh as u32 {
            if self.twin(h)? != NONE || get(mark, h as usize)? != NONE {
                continue;
            }
            let mut g = h;
            for _ in 0..=nh {
                set(mark, g as usize, loops as u32)?;
                g = self.next_boundary(g)?;
                if g == h {
                    break;
                }
            }
            loops += 1;
        }
        Ok(loops)
    }
}
