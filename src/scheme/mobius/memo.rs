//! The canonical form of a mesh vertex's star with a memo of the canonical images of its
//! neighbourhood (seed 000 §4.1 steps 1–2): the drivers map the 1-ring, the corners of the
//! faces around the vertex and (Butterfly, Kobbelt) parts of the 2-ring into the form, and
//! several rules read the same vertex, so each image is computed once per form.
//!
//! One [`StarForm`] lives per driver loop and is re-targeted per vertex: it is about 1 KiB
//! (the memo; the tangent polygon is the caller's), and a fresh one per vertex would be
//! moved several times per vertex (measured with callgrind: those copies cost half of Möbius
//! Catmull–Clark's instructions).

use super::form::{Frame, MapBack, Spokes, ORIGIN};
use crate::error::{Error, Result, Status};
use crate::mesh::{get, internal, Spoke, Topology, NONE};
use crate::mobius::{CanonicalForm, StarKind};
use crate::point::{self, Point};

/// A vertex's canonical form with a small cache of mapped points of its neighbourhood.
pub(super) struct StarForm {
    v: u32,
    cf: CanonicalForm,
    /// Direct-mapped memo of [`StarForm::canon`]: vertex `u` lives in slot
    /// [`memo_slot`]`(u)`, valid while its stamp is `stamp` (re-targeting bumps the stamp
    /// instead of clearing the slots). A collision only overwrites: the evicted image is
    /// recomputed bit for bit.
    memo: [(u32, u32, Point); MEMO_SLOTS],
    stamp: u32,
}

/// Slots of [`StarForm::memo`] (`2^MEMO_BITS`): more than the vertices a driver maps in one
/// star of the usual valences (the 1-ring and the faces' other corners; Butterfly's wings).
/// 32 bytes a slot, on the stack of every pass that holds a form: 32 slots keep it at 1 KiB
/// (docs/firmware.md, "Stack"); a larger star only evicts more often, and an evicted image is
/// recomputed bit for bit. Measured against 64 slots (callgrind, one thread): +0.1 % (Loop
/// epcot 3 levels) to +0.8 % (Kobbelt spot_quad 2) instructions, for 1 KiB less stack.
const MEMO_BITS: u32 = 5;
const MEMO_SLOTS: usize = 1 << MEMO_BITS;

/// The memo slot of vertex `u`: Fibonacci hashing, whose top bits spread the nearby ids of
/// one star over the table.
#[inline]
fn memo_slot(u: u32) -> usize {
    (u.wrapping_mul(0x9E37_79B9) >> (32 - MEMO_BITS)) as usize
}

/// [`Topology::spokes_into`] spoke for spoke, walked on the topology's arrays: one
/// `next_prev_face` per spoke (arithmetic on all-triangle and all-quad meshes, every level of
/// Loop, Butterfly, Catmull–Clark and Doo–Sabin after the first) instead of the star
/// iterator's face lookups. `v` is not isolated. The same errors: [`Status::ValenceTooHigh`]
/// naming `v`, an internal error for arrays that disagree with the valence.
pub(super) fn star_into(topo: &Topology<'_, '_>, v: u32, out: &mut Spokes<'_>) -> Result<()> {
    let r = topo.raw();
    out.clear();
    let n = get(r.valence, v as usize)? as usize;
    let mut cur = get(r.vert_he, v as usize)?;
    for _ in 0..n {
        if cur == NONE {
            // Only for arrays that disagree (the walk stops at a boundary below).
            return Err(internal());
        }
        let (next, prev, f) = r.next_prev_face(cur)?;
        out.try_push(Spoke {
            neighbour: get(r.indices, next as usize)?,
            edge: get(r.edge_of, cur as usize)?,
            half_edge: cur,
            face: f,
        })
        .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
        let tw = get(r.twin, prev as usize)?;
        if tw == NONE {
            // Closing spoke of a boundary star: the incoming boundary half-edge `prev`.
            if out.len() < n {
                out.try_push(Spoke {
                    neighbour: get(r.indices, prev as usize)?,
                    edge: get(r.edge_of, prev as usize)?,
                    half_edge: NONE,
                    face: NONE,
                })
                .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
            }
            break;
        }
        cur = tw;
    }
    if out.len() != n {
        return Err(internal());
    }
    Ok(())
}

impl StarForm {
    /// A memo holding no form yet (`v = NONE`).
    pub(super) fn blank() -> StarForm {
        StarForm {
            v: NONE,
            cf: CanonicalForm {
                v: ORIGIN,
                c: ORIGIN,
                r: 0.0,
                kind: StarKind::Interior,
            },
            memo: [(NONE, 0, ORIGIN); MEMO_SLOTS],
            stamp: 0,
        }
    }

    /// The canonical form (meaningful after a successful [`StarForm::reset`]).
    pub(super) fn form(&self) -> &CanonicalForm {
        &self.cf
    }

    /// The centre `c` of the tangent polygon (after a successful [`StarForm::reset`]).
    pub(super) fn centre(&self) -> Point {
        self.cf.c
    }

    /// Forgets the form and every memo entry (`v = NONE`).
    pub(super) fn clear(&mut self) {
        self.v = NONE;
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            // Stamps wrapped: entries of 2³² re-targets ago would look valid again.
            for e in self.memo.iter_mut() {
                e.1 = 0;
            }
            self.stamp = 1;
        }
    }

    /// Re-targets the memo to the canonical form of `v`'s star: [`StarKind::Interior`] for
    /// a closed star, [`StarKind::Boundary`] for an open one (`boundary`; ring from one
    /// boundary neighbour to the other). `Ok(false)` when the form does not exist (a
    /// degenerate star: the caller's fallback); the memo then holds no form (`v = NONE`).
    /// `Err` only for a failure of the topology queries, which is an error, never a fallback.
    /// `spokes` receives the star of `v` (as [`Topology::spokes_into`]), which the drivers
    /// then walk instead of walking the star again, and the first `spokes.len()` points of
    /// `tangents` its tangent polygon `T_i = (u_i − v)⁻¹` (the guard's sphericity reads it).
    /// `tangents` is the caller's (a part of the star workspace, `workspace.rs`), so that the
    /// form's size does not grow with the valence cap; shorter than the valence is an
    /// internal error (the workspace is sized by the level's largest valence).
    ///
    /// The images of the ring neighbours are cached at once, from the tangent polygon the
    /// form was made of: [`CanonicalForm::to_normalised`] would compute the same `T_i` again
    /// (bit for bit the same images; a neighbour whose image fails is left to `canon`, which
    /// fails the same way).
    pub(super) fn reset(
        &mut self,
        topo: &Topology<'_, '_>,
        v: u32,
        boundary: bool,
        spokes: &mut Spokes<'_>,
        tangents: &mut [Point],
    ) -> Result<bool> {
        self.clear();
        star_into(topo, v, spokes)?;
        let tangents = tangents.get_mut(..spokes.len()).ok_or(internal())?;
        let kind = if boundary {
            StarKind::Boundary
        } else {
            StarKind::Interior
        };
        let centre = topo.position(v)?;
        // The tangent polygon straight from the mesh: `CanonicalForm::new` of the ring's
        // positions bit for bit (same checks: a finite centre, every `T_i` defined).
        let mut ok = point::is_finite(&centre);
        for (s, t) in spokes.iter().zip(tangents.iter_mut()) {
            match CanonicalForm::tangent(centre, topo.position(s.neighbour)?) {
                Some(ti) => *t = ti,
                None => ok = false,
            }
        }
        if !ok {
            return Ok(false);
        }
        self.cf = match CanonicalForm::from_tangents(centre, tangents, kind) {
            Ok(cf) => cf,
            Err(_) => return Ok(false),
        };
        self.v = v;
        let stamp = self.stamp;
        for (s, t) in spokes.iter().zip(tangents.iter()) {
            if let Ok(p) = self.cf.normalised_from_tangent(*t) {
                if let Some(e) = self.memo.get_mut(memo_slot(s.neighbour)) {
                    *e = (s.neighbour, stamp, p);
                }
            }
        }
        Ok(true)
    }

    /// The image of vertex `u` in the canonical form, in its normalised frame
    /// ([`CanonicalForm::to_normalised`]: `v` itself goes to the origin).
    #[inline(always)]
    pub(super) fn canon(&mut self, topo: &Topology<'_, '_>, u: u32) -> Result<Point> {
        if u == self.v {
            return Ok(ORIGIN);
        }
        let slot = memo_slot(u);
        if let Some(&(k, st, p)) = self.memo.get(slot) {
            if k == u && st == self.stamp {
                return Ok(p);
            }
        }
        let p = self.cf.to_normalised(topo.position(u)?)?;
        if let Some(e) = self.memo.get_mut(slot) {
            *e = (u, self.stamp, p);
        }
        Ok(p)
    }
}

impl MapBack for StarForm {
    #[inline(always)]
    fn back(&self, p: Point) -> Result<Point> {
        self.cf.from_normalised(p)
    }
}

impl Frame for StarForm {
    const CANONICAL: bool = true;

    fn canonical(&self) -> Option<&CanonicalForm> {
        Some(&self.cf)
    }

    #[inline(always)]
    fn image(&mut self, topo: &Topology<'_, '_>, u: u32) -> Result<Point> {
        self.canon(topo, u)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{topology_scratch_size, Mesh};

    /// The drivers' star walk is [`Topology::spokes_into`] spoke for spoke, on all-triangle,
    /// all-quad and mixed meshes with boundaries and on a closed one (the walk's arithmetic
    /// fast paths and the general one).
    #[test]
    fn star_walk_matches_the_topology() {
        // A 3×3 grid of vertices: four quads; eight triangles; three quads and two triangles.
        let mut grid = [[0.0; 3]; 9];
        for (i, p) in grid.iter_mut().enumerate() {
            *p = [(i % 3) as f64, (i / 3) as f64, 0.0];
        }
        let octa = [
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ];
        let tri_offs = [0, 3, 6, 9, 12, 15, 18, 21, 24];
        let cases: [(&[Point], &[u32], &[u32]); 4] = [
            (
                &grid,
                &[0, 4, 8, 12, 16],
                &[0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 7],
            ),
            (
                &grid,
                &tri_offs,
                &[
                    0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4, 3, 4, 7, 3, 7, 6, 4, 5, 8, 4, 8, 7,
                ],
            ),
            (
                &grid,
                &[0, 4, 8, 12, 15, 18],
                &[0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6, 4, 5, 8, 4, 8, 7],
            ),
            (
                &octa,
                &tri_offs,
                &[
                    0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5,
                ],
            ),
        ];
        let mut buf = [0u32; 1024];
        for (p, offs, idx) in cases {
            let mesh = Mesh::new(p, offs, idx);
            let scratch = &mut buf[..topology_scratch_size(p.len(), idx.len()).unwrap()];
            let topo = Topology::build(mesh, scratch).unwrap();
            let mut spoke_buf = [0u32; 4 * 16];
            let mut b = Spokes::new(&mut spoke_buf);
            for v in 0..p.len() as u32 {
                let a = topo.spokes(v).unwrap();
                star_into(&topo, v, &mut b).unwrap();
                assert!(a.iter().copied().eq(b.iter()), "vertex {v}");
                assert!(b.len() > 0);
            }
        }
    }
}
