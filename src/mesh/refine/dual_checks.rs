//! Preconditions of the dual patterns ([`super::Pattern::CornerCut`],
//! [`super::Pattern::MidEdge`], [`super::Pattern::Dual`], [`super::Pattern::DualTruncation`]):
//! a vertex becomes a face, so an interior vertex of valence 2 would become a 2-gon; and the
//! patterns that join the face points of neighbouring faces would make a double edge between
//! two faces sharing two edges.

use crate::error::{Error, Result, Status};
use crate::mesh::{Topology, NONE};
use crate::MAX_FACE_SIZE;

/// [`Status::UnsupportedFaceType`] for the first face sharing two edges with one neighbour.
pub(super) fn no_double_neighbours(topo: &Topology<'_, '_>) -> Result<()> {
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
pub(super) fn dual_face_sizes(topo: &Topology<'_, '_>, extra: usize) -> Result<()> {
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
