//! [`Pattern::DualTruncation`](super::Pattern::DualTruncation) (Akleman et al. 2005): truncation
//! followed by the dual, the √3 connectivity. One new point per face; each old interior edge is
//! replaced by the edge between its two face points. Faces, per edge in edge order: interior `h =
//! (a → b)` in `f`, twin in `g`: `(a, g, f)` and `(b, f, g)`; boundary `(a → b)` in `f`: `(a, b,
//! f)`. Output vertices: the `V` old vertices, the `F` face points.

use super::counts::{some, LevelCounts};
use super::dual_checks::{dual_face_sizes, no_double_neighbours};
use super::face_writer::FaceWriter;
use super::Parent;
use crate::error::{Error, Result, Status};
use crate::mesh::{cadd, cmul, MeshSizes, Topology, NONE};
use crate::MAX_VALENCE;

/// The output sizes: `V + F` vertices, `2 E_i + E_b` triangles; [`Status::ValenceTooHigh`]
/// naming an old vertex, or a face, whose new valence would exceed [`MAX_VALENCE`].
pub(super) fn size(topo: &Topology<'_, '_>) -> Result<MeshSizes> {
    dual_face_sizes(topo, 0)?;
    no_double_neighbours(topo)?;
    let (v, f) = (topo.num_vertices(), topo.num_faces());
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
    Ok(MeshSizes {
        vertices: cadd(v, f)?,
        faces,
        indices: cmul(faces, 3)?,
    })
}

/// The faces (module docs).
pub(super) fn write(
    topo: &Topology<'_, '_>,
    n: Parent,
    sizes: &MeshSizes,
    offsets: &mut [u32],
    indices: &mut [u32],
) -> Result<()> {
    let mut w = FaceWriter::new(offsets, indices)?;
    for e in 0..n.e {
        let h = topo.edge_half_edge(e)?;
        let (a, b) = (topo.origin(h)?, topo.dest(h)?);
        let f = n.v + topo.face(h)?;
        let t = topo.twin(h)?;
        if t == NONE {
            w.face(&[a, b, f])?;
        } else {
            let g = n.v + topo.face(t)?;
            w.face(&[a, g, f])?;
            w.face(&[b, f, g])?;
        }
    }
    w.finish(sizes)
}

/// The counts of the next level. Interior vertices keep their valence, boundary ones gain
/// one; face points are interior with valence n + (interior edges of the face). Edges: one
/// per corner, one per interior edge (between face points), the boundary edges.
pub(super) fn next(s: &LevelCounts) -> Result<LevelCounts> {
    let ei = s.ei();
    Ok(LevelCounts {
        v: cadd(s.v, s.f)?,
        f: cadd(cmul(ei, 2)?, s.eb)?,
        h: cmul(cadd(cmul(ei, 2)?, s.eb)?, 3)?,
        e: cadd(s.h, s.e)?,
        eb: s.eb,
        iso: s.iso,
        si: cadd(cadd(s.si, s.h)?, cmul(ei, 2)?)?,
        sb: cadd(s.sb, s.eb)?,
        max_vi: s.max_vi.max(s.max_dt),
        max_vb: s.max_vb + some(s.eb > 0, 1),
        max_face: 3,
        max_dt: 6,
    })
}
