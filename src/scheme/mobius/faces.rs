//! Face points from the face candidates of the corners' stars (seed 000 §4.4.3, "Blending
//! face points"): the face's corners and candidates go to the sorted F4/F6 chain of
//! [`blend::face_point_with_ids`]; a face with a missing candidate, or whose chain fails,
//! takes its linear centroid, counted as a fallback.

use super::driver::{chunk_fallback, Driver};
use super::slots::slot_of;
use crate::blend::{self, FaceCorners};
use crate::error::{Result, Status};
use crate::exec::{
    chunk_count, chunk_range, own_frame, parts, take_front, Executor, Tally, MAX_CHUNKS,
};
use crate::mesh::{get, internal, Topology};
use crate::point::{self, Point};
use crate::stencil::centroid_of_sum;
use arrayvec::ArrayVec;

/// A face of the level read in place for [`blend::face_point_in_place`]: its corners'
/// positions and the face candidates of their stars (seed 000 §4.4.3), where they are.
struct MeshFace<'a, 'm, 's> {
    topo: &'a Topology<'m, 's>,
    /// The face's vertices, in face order.
    verts: &'a [u32],
    /// The half-edge of the first corner (corner `i`'s is `first + i`).
    first: u32,
    face_c: &'a [Point],
    slots: &'a [f64],
}

impl FaceCorners for MeshFace<'_, '_, '_> {
    fn len(&self) -> usize {
        self.verts.len()
    }
    fn vertex(&self, i: usize) -> Option<Point> {
        self.topo.position(*self.verts.get(i)?).ok()
    }
    fn candidate(&self, i: usize) -> Option<Point> {
        let h = self.first.checked_add(u32::try_from(i).ok()?)?;
        get(self.face_c, slot_of(self.slots, h).ok()?).ok()
    }
}

/// One face range of the face blends: its first face, its face points, its share of the star
/// workspace (the chain's arrays, `workspace.rs`).
struct FacePart<'a> {
    first: usize,
    out: &'a mut [Point],
    work: &'a mut [Point],
}

impl Driver<'_, '_, '_, '_> {
    /// Blends the face candidates into face points written at `start + f`: one pass over the
    /// faces, split into face ranges ([`crate::exec`]). Each face is read in place, and the
    /// chain's arrays are the range's share of the star workspace (nothing sized by the
    /// face-size cap on the stack, `docs/firmware.md`).
    pub(super) fn blend_faces(&mut self, start: usize) -> Result<()> {
        self.blend_faces_where(start, false)
    }

    /// [`Driver::blend_faces`] again after the fold guard's re-evaluation (step 6 of
    /// `guard.rs`). With `near_distrusted` (see [`Driver::rewind_for_blends_again`]) only
    /// the faces with a corner whose trust is below 1 are blended: the guarded pass rewrote
    /// the candidates of such stars only, so every other face reads the same inputs as in
    /// the first blends and keeps its point, bit for bit.
    pub(super) fn blend_faces_again(&mut self, start: usize, near_distrusted: bool) -> Result<()> {
        self.blend_faces_where(start, near_distrusted)
    }

    fn blend_faces_where(&mut self, start: usize, near_distrusted: bool) -> Result<()> {
        let topo = self.topo;
        let nf = topo.num_faces();
        let face_c: &[Point] = self.face_c;
        let slots: &[f64] = self.slots;
        let only: Option<&[f64]> = near_distrusted.then_some(&*self.trust);
        let strict = self.strict;
        let run = |part: &mut FacePart<'_>, tally: &mut Tally| -> Result<()> {
            for (f, o) in (part.first as u32..).zip(part.out.iter_mut()) {
                let verts = topo.face_vertices(f)?;
                if let Some(trust) = only {
                    let mut all_trusted = true;
                    for &u in verts {
                        all_trusted &= get(trust, u as usize)? >= 1.0;
                    }
                    if all_trusted {
                        continue;
                    }
                }
                let face = MeshFace {
                    topo,
                    verts,
                    first: topo.face_half_edges(f)?.start,
                    face_c,
                    slots,
                };
                // A missing candidate is not finite: the chain refuses it, and the face takes
                // its centroid. Ties of the §4.4.3 sort go by vertex id, so the face point
                // does not depend on which corner the face is listed from
                // (docs/DECISIONS.md).
                *o = match blend::face_point_in_place(&face, verts, part.work) {
                    Ok(p) => p,
                    // Only a read of the face or a short workspace can fail so (F4 and F6
                    // never do): an internal error, never a fallback.
                    Err(e)
                        if matches!(e.status, Status::InvalidArgument | Status::BufferTooSmall) =>
                    {
                        return Err(internal())
                    }
                    Err(_) => {
                        chunk_fallback(strict, tally, start + f as usize)?;
                        // `centroid` of the corners, summed in face order as it does.
                        let mut s = [0.0; 3];
                        for &u in verts {
                            s = point::add(s, topo.position(u)?);
                        }
                        centroid_of_sum(s, verts.len())?
                    }
                };
            }
            Ok(())
        };
        let out = self.pos.get_mut(start..start + nf).ok_or(internal())?;
        let work = &mut *self.work;
        let k = chunk_count(self.exec, nf);
        let t = if k <= 1 {
            own_frame(|| {
                let mut t = Tally::new();
                run(
                    &mut FacePart {
                        first: 0,
                        out,
                        work,
                    },
                    &mut t,
                )?;
                Ok::<_, crate::error::Error>(t)
            })?
        } else {
            split_faces(self.exec, k, out, work, &run)?
        };
        self.add_fallbacks(t);
        Ok(())
    }
}

/// [`Driver::blend_faces`] in `k ≥ 2` face ranges, each with its share of the star workspace
/// `work` (out of line: the serial path keeps a small stack frame).
#[inline(never)]
fn split_faces(
    exec: &dyn Executor,
    k: usize,
    mut out: &mut [Point],
    mut work: &mut [Point],
    run: &(dyn Fn(&mut FacePart<'_>, &mut Tally) -> Result<()> + Sync),
) -> Result<Tally> {
    let nf = out.len();
    let share = work.len() / k.max(1);
    let mut ranges = ArrayVec::<FacePart<'_>, MAX_CHUNKS>::new();
    for i in 0..k {
        let (f0, f1) = chunk_range(nf, k, i);
        let part = FacePart {
            first: f0,
            out: take_front(&mut out, f1 - f0)?,
            work: take_front(&mut work, share)?,
        };
        ranges.try_push(part).map_err(|_| internal())?;
    }
    parts(exec, &mut ranges, |p| p.out.len(), run)
}
