//! Refinement patterns: the connectivity of one subdivision step, its exact sizes, and the
//! numbering of the new vertices. Positions are the schemes' business ([`crate::scheme`]).
//!
//! Notation: `V, E, F, H` vertices, edges, faces, half-edges (corners) of the input; `I`
//! isolated vertices; `E_i` interior edges; `V_i` interior vertices; `Σ_i` the sum of the
//! valences of the interior vertices. Edges are numbered in `(min, max)` key order
//! ([`Topology`]). All faces keep the input orientation (counter-clockwise from outside).
//!
//! | pattern | vertices (in this order) | faces (in this order) |
//! |---|---|---|
//! | [`Split1To4`](Pattern::Split1To4) (triangles only) | `V` old, `E` edge points | triangle `f` → `4f..4f+4`: `(v0,e0,e2) (v1,e1,e0) (v2,e2,e1) (e0,e1,e2)`, `e_i` on corner `i`'s edge `(v_i, v_{i+1})` |
//! | [`Quads`](Pattern::Quads) | `V` old, `E` edge points, `F` face points | corner `h` of face `f` → quad `h`: `(v_i, e_i, f, e_{i−1})` |
//! | [`CornerCut`](Pattern::CornerCut) (Doo–Sabin) | `H` corner points (corner `h` → point `h`), then the `I` isolated vertices | `F` F-faces (corners in face order), `E_i` E-faces in edge order `(c(next h), c(h), c(next t), c(t))` with `h` the `min→max` half-edge and `t` its twin, `V_i` V-faces in vertex order (corners of the star, CCW) |
//! | [`MidEdge`](Pattern::MidEdge) (Simplest) | `E` edge midpoints, then the `V_b` boundary vertices (in index order), then the `I` isolated vertices | `F` face-faces (the midpoints of the face's edges, in corner order), then one vertex-face per referenced vertex, in vertex order: the midpoints of its spokes (CCW), closed on the boundary by the vertex itself |
//! | [`Dual`](Pattern::Dual) | `F` face points, then the midpoints of the `V_b` outgoing boundary edges of the boundary vertices, then the `V_b` boundary vertices (both in vertex index order), then the `I` isolated vertices | one face per referenced vertex, in vertex order: the face points of its star (CCW); on the boundary `(m(v→b0), c_0, …, c_{k−1}, m(b1→v), v)` |
//! | [`VertexInsertion`](Pattern::VertexInsertion) | `V` old, `F` face points | corner `h = (a → b)` of face `f` → triangle `h`: `(a, b, f)` |
//! | [`DualTruncation`](Pattern::DualTruncation) | `V` old, `F` face points | per edge, in edge order: interior `h = (a → b)` in `f`, twin in `g`: `(a, g, f)` and `(b, f, g)`; boundary `(a → b)` in `f`: `(a, b, f)` |
//!
//! Boundaries: [`CornerCut`](Pattern::CornerCut) makes faces only around interior edges and
//! vertices (CGAL's `DQQ_1step`), so its new boundary runs through the corner points of the
//! boundary faces. [`MidEdge`](Pattern::MidEdge) and [`Dual`](Pattern::Dual) close the face of
//! every boundary vertex with the vertex itself (and, for the dual, the midpoints of its two
//! boundary edges): the new boundary is the old boundary polygon refined at its edge
//! midpoints, every vertex has a face, and the Euler characteristic is preserved (otherwise
//! the mid-edge boundary would never be refined and the dual would drop its boundary ring
//! and leave stray face points).
//!
//! The dual patterns ([`CornerCut`](Pattern::CornerCut), [`MidEdge`](Pattern::MidEdge),
//! [`Dual`](Pattern::Dual), and [`DualTruncation`](Pattern::DualTruncation), whose truncation
//! polygons are dual faces) need every interior vertex to have valence ≥ 3 (its face would be
//! a 2-gon): an interior vertex of valence 2 is [`Status::FaceTooSmall`] naming the vertex.
//! [`Dual`](Pattern::Dual) and [`DualTruncation`](Pattern::DualTruncation) join the face points
//! of neighbouring faces; two faces that share two edges would give a double edge, so such a
//! face is [`Status::UnsupportedFaceType`] naming the later face.

//! # Where things are
//!
//! One file per pattern, each owning what the pattern decides: its output sizes (`size`), the
//! faces it writes (`write`), the counts of the next level for multi-level plans (`next`; the
//! counts in `counts.rs`), and for [`Pattern::Split1To4`], [`Pattern::Quads`] and
//! [`Pattern::CornerCut`] the derivation of the child topology from the parent's (`derive`;
//! the shared parts and the tests in `derive.rs`; Doo–Sabin's in its own file,
//! `corner_cut_topology.rs`). Also shared: `face_writer.rs` (the CSR cursor), `dual_checks.rs` (the
//! preconditions of the dual patterns).

mod corner_cut;
mod corner_cut_topology;
pub(crate) mod counts;
pub(crate) mod derive;
mod dual;
mod dual_checks;
mod dual_truncation;
mod face_writer;
mod mid_edge;
mod quads;
mod split_1to4;
mod vertex_insertion;

/// Meshes the unit tests of the patterns share.
#[cfg(test)]
pub(crate) mod fixtures {
    use crate::point::Point;

    /// `N` points on a grid four points wide, in the plane `z = 0`.
    pub(crate) fn grid_positions<const N: usize>() -> [Point; N] {
        core::array::from_fn(|v| [(v % 4) as f64, (v / 4) as f64, 0.0])
    }

    /// Quads, triangles and a pentagon with a boundary, three interior vertices (5, 6, 9, each
    /// of valence at least 3, as the dual patterns need) and two isolated ones (3, 15):
    /// positions, offsets, indices.
    pub(crate) fn mixed_open_dual() -> ([Point; 16], [u32; 9], [u32; 31]) {
        let idx = [
            0, 1, 5, 4, 1, 2, 6, 5, 2, 7, 6, 4, 5, 9, 8, 5, 6, 10, 9, 6, 7, 11, 10, 9, 10, 14, 13,
            12, 8, 9, 12,
        ];
        (
            grid_positions::<16>(),
            [0, 4, 8, 11, 15, 19, 23, 28, 31],
            idx,
        )
    }

    /// The unit cube as six outward quads: positions, offsets, indices.
    pub(crate) fn cube() -> ([Point; 8], [u32; 7], [u32; 24]) {
        let pos =
            core::array::from_fn(|v| [(v & 1) as f64, ((v >> 1) & 1) as f64, (v >> 2) as f64]);
        let idx = [
            0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5,
        ];
        (pos, [0, 4, 8, 12, 16, 20, 24], idx)
    }
}

pub(crate) use counts::LevelCounts;

use arrayvec::ArrayVec;

use super::topology::Counts;
use super::{get, idx, internal, set, Mesh, MeshSizes, Topology};
use crate::error::{Error, Result, Status};
use crate::exec::{self, Executor, Serial, MAX_CHUNKS};
use crate::{MAX_FACE_SIZE, MAX_VALENCE};

/// A refinement pattern (connectivity of one step; see the module table).
///
/// `#[non_exhaustive]`: a later version may add a variant, so a `match` outside this crate
/// needs a wildcard arm.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pattern {
    /// Triangle 1→4 split (Loop, Modified Butterfly).
    Split1To4,
    /// n-gon → n quads (Catmull–Clark, Kobbelt).
    Quads,
    /// Corner cutting with F-, E- and V-faces (Doo–Sabin).
    CornerCut,
    /// Mid-edge: face-faces and vertex-faces of edge midpoints (Peters–Reif Simplest).
    MidEdge,
    /// Dual mesh: face points joined around interior vertices (Akleman et al. 2005).
    Dual,
    /// Each n-gon → n triangles to a face point, old edges kept (Akleman et al. 2005).
    VertexInsertion,
    /// Truncation followed by the dual: a face point per face, each old edge replaced by the
    /// edge between its two face points (the √3 connectivity; Akleman et al. 2005).
    DualTruncation,
}

impl Pattern {
    /// Whether the old vertices are kept at their indices (primal patterns).
    pub fn keeps_old_vertices(self) -> bool {
        matches!(
            self,
            Pattern::Split1To4
                | Pattern::Quads
                | Pattern::VertexInsertion
                | Pattern::DualTruncation
        )
    }
}

/// The first index of each group of the parent's elements as output vertex numbers: `v`
/// vertices, `e` edges, `f` faces (checked to fit a `u32`).
#[derive(Clone, Copy, Debug)]
struct Parent {
    v: u32,
    e: u32,
    f: u32,
}

/// The exact output sizes of `pattern` on `topo`, checked: [`crate::Status::SizeOverflow`]
/// when a count exceeds [`super::MAX_COUNT`], [`crate::Status::UnsupportedFaceType`] (naming
/// the face) for [`Pattern::Split1To4`] on a non-triangle, [`crate::Status::ValenceTooHigh`]
/// when a vertex of the output would exceed [`crate::MAX_VALENCE`] (naming the old vertex, or
/// for [`Pattern::DualTruncation`] face points, the face); the preconditions of the dual
/// patterns (module docs).
pub fn pattern_size(pattern: Pattern, topo: &Topology<'_, '_>) -> Result<MeshSizes> {
    let sizes = match pattern {
        Pattern::Split1To4 => split_1to4::size(topo)?,
        Pattern::Quads => quads::size(topo)?,
        Pattern::CornerCut => corner_cut::size(topo)?,
        Pattern::MidEdge => mid_edge::size(topo)?,
        Pattern::Dual => dual::size(topo)?,
        Pattern::VertexInsertion => vertex_insertion::size(topo)?,
        Pattern::DualTruncation => dual_truncation::size(topo)?,
    };
    sizes.check()
}

/// Writes the faces of `pattern` (see the module table) into `offsets` and `indices`, which
/// must hold `sizes` from [`pattern_size`] (checked: [`crate::Status::BufferTooSmall`]).
pub fn write_pattern(
    pattern: Pattern,
    topo: &Topology<'_, '_>,
    offsets: &mut [u32],
    indices: &mut [u32],
) -> Result<MeshSizes> {
    write_pattern_with(pattern, topo, offsets, indices, &Serial)
}

/// [`write_pattern`] with the faces of [`Pattern::Split1To4`], [`Pattern::Quads`] and
/// [`Pattern::CornerCut`] written in ranges run by `exec` ([`crate::exec`]): every output face
/// of the first two is a function of one parent face, at an output position known from the
/// parent's offsets, so the parent-face ranges are disjoint and the result is the same for
/// every executor. [`Pattern::CornerCut`] writes its F-faces the same way and its E-faces and
/// V-faces in edge and vertex ranges, placed after the interior edges and valences of the
/// ranges before (counted per chunk, then summed in chunk order: `corner_cut.rs`). The other
/// patterns are written on the calling thread (their output positions are running counts).
pub(crate) fn write_pattern_with(
    pattern: Pattern,
    topo: &Topology<'_, '_>,
    offsets: &mut [u32],
    indices: &mut [u32],
    exec: &dyn Executor,
) -> Result<MeshSizes> {
    let sizes = pattern_size(pattern, topo)?;
    if offsets.len() < sizes.offsets()? {
        return Err(Error::too_small(sizes.offsets()?));
    }
    if indices.len() < sizes.indices {
        return Err(Error::too_small(sizes.indices));
    }
    let n = Parent {
        v: idx(topo.num_vertices())?,
        e: idx(topo.num_edges())?,
        f: topo.num_faces() as u32,
    };
    match pattern {
        Pattern::Split1To4 | Pattern::Quads => {
            write_face_ranges(pattern, topo, n, offsets, indices, exec)?;
            // The closing offset (each range writes the offsets of its own faces).
            set(offsets, sizes.faces, idx(sizes.indices)?)?;
        }
        Pattern::CornerCut => {
            corner_cut::write(topo, &sizes, offsets, indices, exec)?;
            set(offsets, sizes.faces, idx(sizes.indices)?)?;
        }
        Pattern::MidEdge => mid_edge::write(topo, n, &sizes, offsets, indices)?,
        Pattern::Dual => dual::write(topo, n, &sizes, offsets, indices)?,
        Pattern::VertexInsertion => vertex_insertion::write(topo, n, &sizes, offsets, indices)?,
        Pattern::DualTruncation => dual_truncation::write(topo, n, &sizes, offsets, indices)?,
    }
    // The output numbering must stay within the vertex count (checked, never trusted).
    let used = indices.get(..sizes.indices).ok_or(internal())?;
    // The largest index, in the chunks of `exec` (one vectorised pass each).
    let largest = exec::largest(exec, used)?;
    if !used.is_empty() && largest as usize >= sizes.vertices {
        return Err(internal());
    }
    let _ = get(offsets, sizes.faces)?;
    Ok(sizes)
}

/// A range of parent faces `[faces.0, faces.1)` and the output's offsets and indices from
/// the first output face and corner of that range on (what one chunk of
/// [`write_face_ranges`] writes).
#[derive(Debug)]
pub(super) struct Span<'a> {
    faces: (usize, usize),
    offsets: &'a mut [u32],
    indices: &'a mut [u32],
}

/// Where the output of parent face `f` starts in `pattern` ([`Pattern::Split1To4`] or
/// [`Pattern::Quads`]): its first output face and first output corner.
fn first_output(pattern: Pattern, topo: &Topology<'_, '_>, f: usize) -> Result<(usize, usize)> {
    match pattern {
        Pattern::Split1To4 => Ok(split_1to4::first_output(f)),
        _ => quads::first_output(topo, f),
    }
}

/// The faces of one [`Span`] of `pattern`.
fn write_span(
    pattern: Pattern,
    topo: &Topology<'_, '_>,
    n: Parent,
    s: &mut Span<'_>,
) -> Result<()> {
    match pattern {
        Pattern::Split1To4 => split_1to4::write_faces(topo, n, s.faces, s.offsets, s.indices),
        _ => quads::write_faces(topo, n, s.faces, s.offsets, s.indices),
    }
}

/// The faces of [`Pattern::Split1To4`] or [`Pattern::Quads`] in the parent-face chunks of
/// `exec` (one chunk: inline, without building the chunk list).
fn write_face_ranges(
    pattern: Pattern,
    topo: &Topology<'_, '_>,
    n: Parent,
    offsets: &mut [u32],
    indices: &mut [u32],
    exec: &dyn Executor,
) -> Result<()> {
    let nf = topo.num_faces();
    let k = exec::chunk_count(exec, nf);
    if k <= 1 {
        let mut all = Span {
            faces: (0, nf),
            offsets,
            indices,
        };
        return exec::own_frame(|| write_span(pattern, topo, n, &mut all));
    }
    split_face_ranges(pattern, topo, n, offsets, indices, exec, k)
}

/// [`write_face_ranges`] in `k ≥ 2` chunks (out of line: the one-chunk path keeps a small
/// stack frame).
#[inline(never)]
fn split_face_ranges(
    pattern: Pattern,
    topo: &Topology<'_, '_>,
    n: Parent,
    mut offsets: &mut [u32],
    mut indices: &mut [u32],
    exec: &dyn Executor,
    k: usize,
) -> Result<()> {
    let nf = topo.num_faces();
    let mut spans = ArrayVec::<Span<'_>, MAX_CHUNKS>::new();
    for i in 0..k {
        let (f0, f1) = exec::chunk_range(nf, k, i);
        let (o0, i0) = first_output(pattern, topo, f0)?;
        let (o1, i1) = first_output(pattern, topo, f1)?;
        spans
            .try_push(Span {
                faces: (f0, f1),
                offsets: exec::take_front(&mut offsets, o1.checked_sub(o0).ok_or(internal())?)?,
                indices: exec::take_front(&mut indices, i1.checked_sub(i0).ok_or(internal())?)?,
            })
            .map_err(|_| internal())?;
    }
    exec::parts(
        exec,
        &mut spans,
        |s| s.faces.1 - s.faces.0,
        |s, _| write_span(pattern, topo, n, s),
    )
    .map(|_| ())
}

impl LevelCounts {
    /// The counts of the next level of `pattern` (derivations in each pattern's `next`);
    /// [`Status::ValenceTooHigh`] (no element: the vertex does not exist yet) when a valence
    /// or a face size would exceed the capacity, [`Status::SizeOverflow`].
    pub(crate) fn next(&self, pattern: Pattern) -> Result<LevelCounts> {
        let n = match pattern {
            Pattern::Split1To4 => split_1to4::next(self)?,
            Pattern::Quads => quads::next(self)?,
            Pattern::CornerCut => corner_cut::next(self)?,
            Pattern::VertexInsertion => vertex_insertion::next(self)?,
            Pattern::DualTruncation => dual_truncation::next(self)?,
            Pattern::Dual => dual::next(self)?,
            Pattern::MidEdge => mid_edge::next(self)?,
        };
        if n.max_vi > MAX_VALENCE || n.max_vb > MAX_VALENCE || n.max_face > MAX_FACE_SIZE {
            return Err(Error::new(Status::ValenceTooHigh));
        }
        n.sizes().check()?;
        Ok(n)
    }
}

/// Whether [`child_topology`] derives the child topology of `pattern`.
pub(crate) fn derivable(pattern: Pattern) -> bool {
    matches!(
        pattern,
        Pattern::Quads | Pattern::Split1To4 | Pattern::CornerCut
    )
}

/// The child topology of `pattern` ([`derivable`]) on `mesh`, the level that [`write_pattern`]
/// wrote from `parent`, in `scratch` ([`crate::mesh::topology_scratch_size`] of the child): the
/// same arrays as [`Topology::build`] on `mesh` (`derive.rs`), for every executor `exec`
/// (the per-face part runs in its chunks).
///
/// # Errors
/// [`Status::BufferTooSmall`] with the needed length; an internal error when `mesh` is not
/// this pattern's child or the pattern is not derivable.
pub(crate) fn child_topology<'m2, 's2>(
    parent: &Topology<'_, '_>,
    pattern: Pattern,
    mesh: Mesh<'m2>,
    scratch: &'s2 mut [u32],
    exec: &dyn Executor,
) -> Result<Topology<'m2, 's2>> {
    let counts: Counts = match pattern {
        Pattern::Quads => quads::derive(parent, &mesh, scratch, exec)?,
        Pattern::Split1To4 => split_1to4::derive(parent, &mesh, scratch, exec)?,
        Pattern::CornerCut => corner_cut_topology::derive(parent, &mesh, scratch, exec)?,
        _ => return Err(internal()),
    };
    Topology::from_parts(mesh, scratch, counts)
}
