//! Ears: boundary vertices with one face. The paper's canonical form of an ear's star is
//! singular at every square or cocircular corner (it sends the face's opposite corner to
//! infinity), which would break every quad grid with corners. So anything an ear would
//! contribute to its face (a face candidate, a Doo–Sabin corner point) is evaluated in the
//! canonical form of the first non-ear corner of the face at offset `h, h+1, h−1, h+2, …`
//! (`h = ⌊d/2⌋`): still Möbius-invariant, and exact on Möbius images of regular grids. A face
//! of ears only takes its linear rule, counted as a fallback (docs/DECISIONS.md).

use super::driver::Driver;
use super::form::{Frame, MapBack, Spokes};
use super::memo::StarForm;
use crate::error::Result;
use crate::mesh::{get, set, NONE};
use crate::point::Point;

impl Driver<'_, '_, '_, '_> {
    /// A boundary vertex with one face (valence 2), from two lookups: its first spoke has no
    /// twin exactly when it is on the boundary (`Topology::is_boundary_vertex`), and a
    /// boundary vertex has one face fewer than neighbours.
    pub(super) fn is_ear(&self, v: u32) -> Result<bool> {
        let topo = self.topo;
        let h = topo.vertex_half_edge(v)?;
        Ok(h != NONE && topo.twin(h)? == NONE && topo.valence(v)? == 2)
    }

    /// The vertex whose canonical form evaluates corner `i` of face `f`: the corner's own
    /// vertex, or for an ear the first non-ear corner at offset `h, h+1, h−1, h+2, …`.
    pub(super) fn form_vertex(&self, f: u32, i: usize) -> Result<Option<u32>> {
        let verts = self.topo.face_vertices(f)?;
        let d = verts.len();
        let own = get(verts, i)?;
        if !self.is_ear(own)? {
            return Ok(Some(own));
        }
        let h = d / 2;
        for k in 0..d {
            // offsets h, h+1, h−1, h+2, h−2, …
            let step = k.div_ceil(2);
            let off = if k % 2 == 1 { h + step } else { h + d - step };
            let j = (i + off) % d.max(1);
            let u = get(verts, j)?;
            if !self.is_ear(u)? {
                return Ok(Some(u));
            }
        }
        Ok(None)
    }

    /// The face candidates of the ears' corners (the face centroid in the substitute
    /// vertex's form).
    pub(super) fn ear_face_candidates(&mut self) -> Result<()> {
        // The substitute forms' tangent polygons in the star workspace (no pass holds it now).
        let tangents = core::mem::take(&mut self.work);
        let spoke_work = core::mem::take(&mut self.spoke_work);
        let r = self.ear_face_candidates_into(tangents, Spokes::new(&mut *spoke_work));
        self.work = tangents;
        self.spoke_work = spoke_work;
        r
    }

    /// [`Driver::ear_face_candidates`] with the star workspace `tangents` taken out.
    fn ear_face_candidates_into(
        &mut self,
        tangents: &mut [Point],
        mut spokes: Spokes<'_>,
    ) -> Result<()> {
        let topo = self.topo;
        let mut form = StarForm::blank();
        for f in 0..topo.num_faces() as u32 {
            for (i, h) in topo.face_half_edges(f)?.enumerate() {
                let v = topo.origin(h)?;
                if !self.is_ear(v)? {
                    continue;
                }
                let Some(u) = self.form_vertex(f, i)? else {
                    continue;
                };
                if !self.local_into(u, &mut form, &mut spokes, tangents)? {
                    continue;
                }
                if let Ok(c) = form.face_centroid(topo, f).and_then(|c| form.back(c)) {
                    set(self.face_c, self.slot(h)?, c)?;
                }
            }
        }
        Ok(())
    }
}
