//! Face points from the face candidates of the corners' stars (seed 000 §4.4.3, "Blending
//! face points"): the face's corners and candidates go to the sorted F4/F6 chain of
//! [`blend::face_point_with_ids`]; a face with a missing candidate, or whose chain fails,
//! takes its linear centroid, counted as a fallback.

use super::driver::{chunk_fallback, Driver};
use super::form::{present, FacePts};
use super::slots::slot_of;
use crate::blend;
use crate::error::Result;
use crate::exec::pass;
use crate::mesh::gather::face_points_into;
use crate::mesh::{get, internal};
use crate::point::Point;
use crate::stencil::centroid;

impl Driver<'_, '_, '_, '_> {
    /// Blends the face candidates into face points written at `start + f`: one pass over the
    /// faces, split into face ranges ([`crate::exec`]).
    pub(super) fn blend_faces(&mut self, start: usize) -> Result<()> {
        let topo = self.topo;
        let nf = topo.num_faces();
        let face_c: &[Point] = self.face_c;
        let slots: &[f64] = self.slots;
        let strict = self.strict;
        let out = self.pos.get_mut(start..start + nf).ok_or(internal())?;
        let t = pass(self.exec, out, |first, out, tally| {
            let mut verts = FacePts::new();
            let mut cands = FacePts::new();
            for (f, o) in (first as u32..).zip(out.iter_mut()) {
                face_points_into(topo, f, &mut verts)?;
                cands.clear();
                for h in topo.face_half_edges(f)? {
                    cands
                        .try_push(get(face_c, slot_of(slots, h)?)?)
                        .map_err(|_| internal())?;
                }
                let p = if cands.iter().all(present) {
                    // Ties of the §4.4.3 sort go by vertex id, so the face point does not
                    // depend on which corner the face is listed from (docs/DECISIONS.md).
                    blend::face_point_with_ids(&verts, &cands, topo.face_vertices(f)?).ok()
                } else {
                    None
                };
                *o = match p {
                    Some(p) => p,
                    None => {
                        chunk_fallback(strict, tally, start + f as usize)?;
                        centroid(&verts)?
                    }
                };
            }
            Ok(())
        })?;
        self.add_fallbacks(t);
        Ok(())
    }
}
