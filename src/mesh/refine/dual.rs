//! [`Pattern::Dual`](super::Pattern::Dual) (Akleman et al. 2005): one new point per face, then the
//! points of the `V_b` outgoing boundary edges of the boundary vertices, then the `V_b` boundary
//! vertices (both in vertex index order), then the isolated vertices. Faces: one per referenced
//! vertex in vertex order, the face points of its star counter-clockwise; on the boundary
//! `(m(v→b0), c_0, …, c_{k−1}, m(b1→v), v)`, so that the boundary polygon is kept, refined at its
//! edge points, and the Euler characteristic is preserved.

use super::counts::{some, LevelCounts};
use super::dual_checks::{dual_face_sizes, no_double_neighbours};
use super::face_writer::FaceWriter;
use super::Parent;
use crate::error::Result;
use crate::mesh::{cadd, cmul, idx, MeshSizes, Topology, NONE};

/// The output sizes: `F + 2 V_b + I` vertices; `V_i + V_b` faces.
pub(super) fn size(topo: &Topology<'_, '_>) -> Result<MeshSizes> {
    dual_face_sizes(topo, 2)?;
    no_double_neighbours(topo)?;
    let (f, iso) = (topo.num_faces(), topo.num_isolated_vertices());
    let vb = topo.num_boundary_vertices();
    Ok(MeshSizes {
        vertices: cadd(cadd(f, cmul(vb, 2)?)?, iso)?,
        faces: cadd(topo.num_interior_vertices(), vb)?,
        indices: cadd(
            topo.interior_valence_sum(),
            cadd(topo.boundary_valence_sum(), cmul(vb, 2)?)?,
        )?,
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
    let vb = idx(topo.num_boundary_vertices())?;
    for v in 0..n.v {
        if topo.is_isolated(v)? {
            continue;
        }
        let r = topo.boundary_vertex_rank(v)?;
        if r == NONE {
            for s in topo.star(v) {
                w.push(s.face)?;
            }
        } else {
            w.push(n.f + r)?;
            let mut b1 = NONE;
            for s in topo.star(v) {
                if s.face == NONE {
                    b1 = s.neighbour;
                } else {
                    w.push(s.face)?;
                }
            }
            w.push(n.f + topo.boundary_vertex_rank(b1)?)?;
            w.push(n.f + vb + r)?;
        }
        w.end_face()?;
    }
    w.finish(sizes)
}

/// The counts of the next level. Face points are interior with valence n. Boundary: edge
/// points (valence 3) and the old boundary vertices (valence 2).
pub(super) fn next(s: &LevelCounts) -> Result<LevelCounts> {
    let (ei, vi) = (s.ei(), s.vi());
    Ok(LevelCounts {
        v: cadd(cadd(s.f, cmul(s.eb, 2)?)?, s.iso)?,
        f: cadd(vi, s.eb)?,
        h: cadd(cadd(s.si, s.sb)?, cmul(s.eb, 2)?)?,
        e: cadd(ei, cmul(s.eb, 3)?)?,
        eb: cmul(s.eb, 2)?,
        iso: s.iso,
        si: s.h,
        sb: cmul(s.eb, 5)?,
        max_vi: s.max_face,
        max_vb: some(s.eb > 0, 3),
        max_face: s.max_vi.max(some(s.eb > 0, s.max_vb + 2)),
        max_dt: 0,
    })
}
