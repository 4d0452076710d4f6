//! Face points from the face candidates of the corners' stars (seed 000 §4.4.3, "Blending
//! face points"): the face's corners and candidates go to the sorted F4/F6 chain of
//! [`blend::face_point_with_ids`]; a face with a missing candidate, or whose chain fails,
//! takes its linear centroid, counted as a fallback.

use super::driver::Driver;
use super::form::{present, FacePts};
use crate::blend;
use crate::error::Result;
use crate::mesh::gather::face_points_into;
use crate::mesh::{get, internal, set};
use crate::stencil::centroid;

impl Driver<'_, '_, '_, '_> {
    /// Blends the face candidates into face points written at `start + f`.
    pub(super) fn blend_faces(&mut self, start: usize) -> Result<()> {
        let topo = self.topo;
        let mut verts = FacePts::new();
        let mut cands = FacePts::new();
        for f in 0..topo.num_faces() as u32 {
            face_points_into(topo, f, &mut verts)?;
            cands.clear();
            for h in topo.face_half_edges(f)? {
                cands
                    .try_push(get(self.face_c, h as usize)?)
                    .map_err(|_| internal())?;
            }
            let k = start + f as usize;
            let p = if cands.iter().all(present) {
                // Ties of the §4.4.3 sort go by vertex id, so the face point does not depend
                // on which corner the face is listed from (docs/DECISIONS.md).
                blend::face_point_with_ids(&verts, &cands, topo.face_vertices(f)?).ok()
            } else {
                None
            };
            let p = match p {
                Some(p) => p,
                None => {
                    self.fallback(k)?;
                    centroid(&verts)?
                }
            };
            set(self.pos, k, p)?;
        }
        Ok(())
    }
}
