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
//! midpoints, every vertex has a face, and the Euler characteristic is preserved. (Without
//! this, the mid-edge boundary would never be refined and the dual would drop its boundary
//! ring and leave stray face points.)
//!
//! The dual patterns ([`CornerCut`](Pattern::CornerCut), [`MidEdge`](Pattern::MidEdge),
//! [`Dual`](Pattern::Dual), and [`DualTruncation`](Pattern::DualTruncation), whose truncation
//! polygons are dual faces) need every interior vertex to have valence ≥ 3 (its face would be
//! a 2-gon): an interior vertex of valence 2 is [`Status::FaceTooSmall`] naming the vertex.
//! [`Dual`](Pattern::Dual) and [`DualTruncation`](Pattern::DualTruncation) join the face points
//! of neighbouring faces; two faces that share two edges would give a double edge, so such a
//! face is [`Status::UnsupportedFaceType`] naming the later face.

use super::{cadd, cmul, get, idx, set, MeshSizes, Topology, NONE};
use crate::error::{Error, Result, Status};
use crate::{MAX_FACE_SIZE, MAX_VALENCE};

/// A refinement pattern (connectivity of one step; see the module table).
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

/// [`Status::UnsupportedFaceType`] for the first face sharing two edges with one neighbour.
fn no_double_neighbours(topo: &Topology<'_, '_>) -> Result<()> {
    for f in 0..topo.num_faces() as u32 {
        let r = topo.face_half_edges(f)?;
        for h in r.clone() {
            let t = topo.twin(h)?;
            if t == NONE {
                continue;
            }
            let g = topo.face(t)?;
            for h2 in r.start..h {
                let t2 = topo.twin(h2)?;
                if t2 != NONE && topo.face(t2)? == g {
                    return Err(Error::at(Status::UnsupportedFaceType, f.max(g)));
                }
            }
        }
    }
    Ok(())
}

/// Checks the vertex faces of a dual pattern: interior vertices need valence ≥ 3
/// ([`Status::FaceTooSmall`]); a boundary vertex's face has `valence + extra` corners, at most
/// [`MAX_FACE_SIZE`] ([`Status::ValenceTooHigh`]). Both name the vertex.
fn dual_face_sizes(topo: &Topology<'_, '_>, extra: usize) -> Result<()> {
    for v in 0..topo.num_vertices() as u32 {
        let n = topo.valence(v)?;
        if n == 0 {
            continue;
        }
        if topo.is_boundary_vertex(v)? {
            if n + extra > MAX_FACE_SIZE {
                return Err(Error::at(Status::ValenceTooHigh, v));
            }
        } else if n < 3 {
            return Err(Error::at(Status::FaceTooSmall, v));
        }
    }
    Ok(())
}

/// The exact output sizes of `pattern` on `topo`, checked: [`Status::SizeOverflow`] when a
/// count exceeds [`super::MAX_COUNT`], [`Status::UnsupportedFaceType`] (naming the face) for
/// [`Pattern::Split1To4`] on a non-triangle, [`Status::ValenceTooHigh`] when a vertex of the
/// output would exceed [`MAX_VALENCE`] (naming the old vertex, or for
/// [`Pattern::DualTruncation`] face points, the face).
pub fn pattern_size(pattern: Pattern, topo: &Topology<'_, '_>) -> Result<MeshSizes> {
    let v = topo.num_vertices();
    let e = topo.num_edges();
    let f = topo.num_faces();
    let h = topo.num_half_edges();
    let iso = topo.num_isolated_vertices();
    let sizes = match pattern {
        Pattern::Split1To4 => {
            // All triangles when the smallest and largest face are; otherwise name the first
            // face that is not.
            let all = topo.min_face_size() == 3 && topo.max_face_size() == 3;
            for face in (0..f as u32).filter(|_| !all) {
                if topo.face_size(face)? != 3 {
                    return Err(Error::at(Status::UnsupportedFaceType, face));
                }
            }
            MeshSizes {
                vertices: cadd(v, e)?,
                faces: cmul(f, 4)?,
                indices: cmul(f, 12)?,
            }
        }
        Pattern::Quads => MeshSizes {
            vertices: cadd(cadd(v, e)?, f)?,
            faces: h,
            indices: cmul(h, 4)?,
        },
        Pattern::CornerCut => {
            dual_face_sizes(topo, 0)?;
            MeshSizes {
                vertices: cadd(h, iso)?,
                faces: cadd(
                    cadd(f, topo.num_interior_edges())?,
                    topo.num_interior_vertices(),
                )?,
                indices: cadd(
                    cadd(h, cmul(topo.num_interior_edges(), 4)?)?,
                    topo.interior_valence_sum(),
                )?,
            }
        }
        Pattern::MidEdge => {
            dual_face_sizes(topo, 1)?;
            let vb = topo.num_boundary_vertices();
            MeshSizes {
                vertices: cadd(cadd(e, vb)?, iso)?,
                faces: cadd(cadd(f, topo.num_interior_vertices())?, vb)?,
                indices: cadd(
                    cadd(h, topo.interior_valence_sum())?,
                    cadd(topo.boundary_valence_sum(), vb)?,
                )?,
            }
        }
        Pattern::Dual => {
            dual_face_sizes(topo, 2)?;
            no_double_neighbours(topo)?;
            let vb = topo.num_boundary_vertices();
            MeshSizes {
                vertices: cadd(cadd(f, cmul(vb, 2)?)?, iso)?,
                faces: cadd(topo.num_interior_vertices(), vb)?,
                indices: cadd(
                    topo.interior_valence_sum(),
                    cadd(topo.boundary_valence_sum(), cmul(vb, 2)?)?,
                )?,
            }
        }
        Pattern::VertexInsertion => {
            for vi in 0..v as u32 {
                let n = topo.valence(vi)?;
                let k = topo.vertex_face_count(vi)?;
                if n + k > MAX_VALENCE {
                    return Err(Error::at(Status::ValenceTooHigh, vi));
                }
            }
            MeshSizes {
                vertices: cadd(v, f)?,
                faces: h,
                indices: cmul(h, 3)?,
            }
        }
        Pattern::DualTruncation => {
            dual_face_sizes(topo, 0)?;
            no_double_neighbours(topo)?;
            for vi in 0..v as u32 {
                // Interior: its face points; boundary: face points and both boundary neighbours.
                let k = topo.vertex_face_count(vi)?;
                let n = if topo.is_boundary_vertex(vi)? {
                    k + 2
                } else {
                    k
                };
                if n > MAX_VALENCE {
                    return Err(Error::at(Status::ValenceTooHigh, vi));
                }
            }
            for fi in 0..f as u32 {
                let mut n = 0usize;
                for he in topo.face_half_edges(fi)? {
                    n += if topo.twin(he)? == NONE { 1 } else { 2 };
                }
                if n > MAX_VALENCE {
                    return Err(Error::at(Status::ValenceTooHigh, fi));
                }
            }
            let faces = cadd(
                cmul(topo.num_interior_edges(), 2)?,
                topo.num_boundary_edges(),
            )?;
            MeshSizes {
                vertices: cadd(v, f)?,
                faces,
                indices: cmul(faces, 3)?,
            }
        }
    };
    sizes.check()
}

/// Writes one face into the CSR output and advances the cursors.
struct FaceWriter<'a> {
    offsets: &'a mut [u32],
    indices: &'a mut [u32],
    face: usize,
    corner: usize,
}

impl<'a> FaceWriter<'a> {
    fn new(offsets: &'a mut [u32], indices: &'a mut [u32]) -> Result<Self> {
        set(offsets, 0, 0)?;
        Ok(FaceWriter {
            offsets,
            indices,
            face: 0,
            corner: 0,
        })
    }

    fn push(&mut self, v: u32) -> Result<()> {
        set(self.indices, self.corner, v)?;
        self.corner += 1;
        Ok(())
    }

    fn end_face(&mut self) -> Result<()> {
        self.face += 1;
        set(self.offsets, self.face, idx(self.corner)?)
    }

    fn face(&mut self, vs: &[u32]) -> Result<()> {
        for &v in vs {
            self.push(v)?;
        }
        self.end_face()
    }

    fn finish(&self, sizes: &MeshSizes) -> Result<()> {
        if self.face == sizes.faces && self.corner == sizes.indices {
            Ok(())
        } else {
            Err(super::internal())
        }
    }
}

/// Writes the faces of `pattern` (see the module table) into `offsets` and `indices`, which
/// must hold `sizes` from [`pattern_size`] (checked: [`Status::BufferTooSmall`]).
pub fn write_pattern(
    pattern: Pattern,
    topo: &Topology<'_, '_>,
    offsets: &mut [u32],
    indices: &mut [u32],
) -> Result<MeshSizes> {
    let sizes = pattern_size(pattern, topo)?;
    if offsets.len() < sizes.offsets()? {
        return Err(Error::too_small(sizes.offsets()?));
    }
    if indices.len() < sizes.indices {
        return Err(Error::too_small(sizes.indices));
    }
    let nv = idx(topo.num_vertices())?;
    let ne = idx(topo.num_edges())?;
    let nf = topo.num_faces() as u32;
    match pattern {
        Pattern::Quads => write_quads(topo, nv, ne, offsets, indices)?,
        Pattern::Split1To4 => write_split(topo, nv, offsets, indices)?,
        _ => write_faces(pattern, topo, nv, ne, nf, &sizes, offsets, indices)?,
    }
    // The output numbering must stay within the vertex count (checked, never trusted).
    let used = indices.get(..sizes.indices).ok_or(super::internal())?;
    // One branch-free pass (the largest index), vectorised by the compiler.
    let largest = used.iter().fold(0u32, |m, &i| m.max(i));
    if !used.is_empty() && largest as usize >= sizes.vertices {
        return Err(super::internal());
    }
    let _ = get(offsets, sizes.faces)?;
    Ok(sizes)
}

/// [`Pattern::Quads`] (module table) without a call per corner: corner `h` of face `f` is
/// quad `h` = `(v, E(h), F(f), E(prev h))`, corners `4h..4h + 4`.
fn write_quads(
    topo: &Topology<'_, '_>,
    nv: u32,
    ne: u32,
    offsets: &mut [u32],
    indices: &mut [u32],
) -> Result<()> {
    let r = topo.raw();
    let nh = r.indices.len();
    for (f, w) in r.offsets.windows(2).enumerate() {
        let &[a, b] = w else {
            return Err(super::internal());
        };
        let (a, b) = (a as usize, b as usize);
        let fp = nv + ne + f as u32;
        let corners = r.indices.get(a..b).ok_or(super::internal())?;
        let edges = r.edge_of.get(a..b).ok_or(super::internal())?;
        let mut prev = nv + *edges.last().ok_or(super::internal())?;
        let out = indices.get_mut(4 * a..4 * b).ok_or(super::internal())?;
        for ((q, &v), &e) in out.chunks_exact_mut(4).zip(corners).zip(edges) {
            let cur = nv + e;
            if let [q0, q1, q2, q3] = q {
                (*q0, *q1, *q2, *q3) = (v, cur, fp, prev);
            }
            prev = cur;
        }
    }
    let offs = offsets.get_mut(..nh + 1).ok_or(super::internal())?;
    for (h, o) in offs.iter_mut().enumerate() {
        *o = idx(4 * h)?;
    }
    Ok(())
}

/// [`Pattern::Split1To4`] (module table) without a call per face: triangle `f` (corners
/// `3f..3f + 3`, every face a triangle) is faces `4f..4f + 4`, corners `12f..12f + 12`.
fn write_split(
    topo: &Topology<'_, '_>,
    nv: u32,
    offsets: &mut [u32],
    indices: &mut [u32],
) -> Result<()> {
    let r = topo.raw();
    let nf = r.offsets.len().saturating_sub(1);
    let corners = r.indices.get(..3 * nf).ok_or(super::internal())?;
    let edges = r.edge_of.get(..3 * nf).ok_or(super::internal())?;
    let out = indices.get_mut(..12 * nf).ok_or(super::internal())?;
    for ((q, c), e) in out
        .chunks_exact_mut(12)
        .zip(corners.chunks_exact(3))
        .zip(edges.chunks_exact(3))
    {
        let (&[v0, v1, v2], &[e0, e1, e2]) = (c, e) else {
            return Err(super::internal());
        };
        let (e0, e1, e2) = (nv + e0, nv + e1, nv + e2);
        let face = [v0, e0, e2, v1, e1, e0, v2, e2, e1, e0, e1, e2];
        for (d, s) in q.iter_mut().zip(face) {
            *d = s;
        }
    }
    // Every face a triangle (checked by `pattern_size`): face f is corners 3f..3f + 3.
    for (f, w) in r.offsets.windows(2).enumerate() {
        if w != [3 * f as u32, 3 * f as u32 + 3] {
            return Err(super::internal());
        }
    }
    let offs = offsets.get_mut(..4 * nf + 1).ok_or(super::internal())?;
    for (k, o) in offs.iter_mut().enumerate() {
        *o = idx(3 * k)?;
    }
    Ok(())
}

/// The other patterns, face by face through a [`FaceWriter`].
#[allow(clippy::too_many_arguments)]
fn write_faces(
    pattern: Pattern,
    topo: &Topology<'_, '_>,
    nv: u32,
    ne: u32,
    nf: u32,
    sizes: &MeshSizes,
    offsets: &mut [u32],
    indices: &mut [u32],
) -> Result<()> {
    let mut w = FaceWriter::new(offsets, indices)?;
    match pattern {
        // Written by `write_quads` and `write_split`.
        Pattern::Quads | Pattern::Split1To4 => return Err(super::internal()),
        Pattern::CornerCut => {
            for f in 0..nf {
                for h in topo.face_half_edges(f)? {
                    w.push(h)?;
                }
                w.end_face()?;
            }
            for e in 0..ne {
                let h = topo.edge_half_edge(e)?;
                let t = topo.twin(h)?;
                if t == NONE {
                    continue;
                }
                w.face(&[topo.next(h)?, h, topo.next(t)?, t])?;
            }
            for v in 0..nv {
                if topo.is_isolated(v)? || topo.is_boundary_vertex(v)? {
                    continue;
                }
                for s in topo.star(v) {
                    w.push(s.half_edge)?;
                }
                w.end_face()?;
            }
        }
        Pattern::MidEdge => {
            for f in 0..nf {
                for h in topo.face_half_edges(f)? {
                    w.push(topo.edge(h)?)?;
                }
                w.end_face()?;
            }
            for v in 0..nv {
                if topo.is_isolated(v)? {
                    continue;
                }
                for s in topo.star(v) {
                    w.push(s.edge)?;
                }
                let r = topo.boundary_vertex_rank(v)?;
                if r != NONE {
                    w.push(ne + r)?;
                }
                w.end_face()?;
            }
        }
        Pattern::Dual => {
            let vb = idx(topo.num_boundary_vertices())?;
            for v in 0..nv {
                if topo.is_isolated(v)? {
                    continue;
                }
                let r = topo.boundary_vertex_rank(v)?;
                if r == NONE {
                    for s in topo.star(v) {
                        w.push(s.face)?;
                    }
                } else {
                    w.push(nf + r)?;
                    let mut b1 = NONE;
                    for s in topo.star(v) {
                        if s.face == NONE {
                            b1 = s.neighbour;
                        } else {
                            w.push(s.face)?;
                        }
                    }
                    w.push(nf + topo.boundary_vertex_rank(b1)?)?;
                    w.push(nf + vb + r)?;
                }
                w.end_face()?;
            }
        }
        Pattern::VertexInsertion => {
            for f in 0..nf {
                for h in topo.face_half_edges(f)? {
                    w.face(&[topo.origin(h)?, topo.dest(h)?, nv + f])?;
                }
            }
        }
        Pattern::DualTruncation => {
            for e in 0..ne {
                let h = topo.edge_half_edge(e)?;
                let (a, b) = (topo.origin(h)?, topo.dest(h)?);
                let f = nv + topo.face(h)?;
                let t = topo.twin(h)?;
                if t == NONE {
                    w.face(&[a, b, f])?;
                } else {
                    let g = nv + topo.face(t)?;
                    w.face(&[a, g, f])?;
                    w.face(&[b, f, g])?;
                }
            }
        }
    }
    w.finish(sizes)
}
