//! [`Pattern::VertexInsertion`](super::Pattern::VertexInsertion) (Akleman et al. 2005): each n-gon
//! becomes n triangles to a new face point, corner `h = (a → b)` of face `f` → triangle `h`: `(a,
//! b, f)`; the old edges stay. Output vertices: the `V` old vertices, the `F` face points.

use super::counts::LevelCounts;
use super::face_writer::FaceWriter;
use super::Parent;
use crate::error::{Error, Result, Status};
use crate::mesh::{cadd, cmul, internal, MeshSizes, Topology};
use crate::MAX_VALENCE;

/// The output sizes: `V + F` vertices, one triangle per corner; [`Status::ValenceTooHigh`]
/// naming an old vertex whose valence would exceed [`MAX_VALENCE`] (it gains one neighbour
/// per face).
pub(super) fn size(topo: &Topology<'_, '_>) -> Result<MeshSizes> {
    let (v, f, h) = (topo.num_vertices(), topo.num_faces(), topo.num_half_edges());
    for vi in 0..v as u32 {
        let n = topo.valence(vi)?;
        let k = topo.vertex_face_count(vi)?;
        if n + k > MAX_VALENCE {
            return Err(Error::at(Status::ValenceTooHigh, vi));
        }
    }
    Ok(MeshSizes {
        vertices: cadd(v, f)?,
        faces: h,
        indices: cmul(h, 3)?,
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
    for f in 0..n.f {
        for h in topo.face_half_edges(f)? {
            w.face(&[topo.origin(h)?, topo.dest(h)?, n.v + f])?;
        }
    }
    w.finish(sizes)
}

/// The counts of the next level. Old interior vertices double their valence, boundary ones
/// go to 2n − 1; face points are interior with valence n. Old edges stay, plus one per
/// corner.
pub(super) fn next(s: &LevelCounts) -> Result<LevelCounts> {
    Ok(LevelCounts {
        v: cadd(s.v, s.f)?,
        f: s.h,
        h: cmul(s.h, 3)?,
        e: cadd(s.e, s.h)?,
        eb: s.eb,
        iso: s.iso,
        si: cadd(cmul(s.si, 2)?, s.h)?,
        sb: cmul(s.sb, 2)?.checked_sub(s.eb).ok_or(internal())?,
        max_vi: cmul(s.max_vi, 2)?.max(s.max_face),
        max_vb: cmul(s.max_vb, 2)?.saturating_sub(1),
        max_face: 3,
        max_dt: 6,
    })
}
