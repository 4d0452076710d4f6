//! The per-vertex pass of every Möbius driver (seed 000 §4.1 steps 1–3): for each vertex in
//! index order, the canonical form of its star ([`StarForm`]), the images of its 1-ring (and
//! of whatever else the scheme's rule reads), the scheme's rule in that form, the results
//! mapped back and kept as candidates for the blends, or as vertex points.
//!
//! Isolated vertices, *ears* (boundary vertices with one face, whose form sends the opposite
//! corner of a quad to infinity: their contributions come from another corner's form,
//! [`super::ears`]) and stars without a canonical form are skipped; what they would have
//! given takes its linear rule later, counted as a fallback.

use super::driver::{chunk_fallback, Driver};
use super::form::{present, FacePts, Frame, Ring, Spokes, MISSING};
use super::memo::StarForm;
use crate::error::Result;
use crate::exec::pass;
use crate::mesh::{internal, set, Topology, NONE};
use crate::point::Point;

/// One vertex star with the frame its rules are evaluated in (its canonical form, or the
/// fold guard's interpolated form), as the pass hands it to a driver's rule.
pub(super) struct Star<'p, F: Frame = StarForm> {
    /// The centre vertex.
    pub(super) v: u32,
    /// Whether `v` lies on the boundary (its star is open).
    pub(super) boundary: bool,
    /// The spokes of `v`, counter-clockwise from the star's first spoke
    /// ([`Topology::star`]).
    pub(super) spokes: &'p Spokes,
    /// The frame of the star (the canonical form with its memo, for the paper's rules).
    pub(super) form: &'p mut F,
}

impl<F: Frame> Star<'_, F> {
    /// The images of the ring neighbours in star order into `ring` ([`MISSING`] for one the
    /// form sends to infinity); whether all exist.
    #[inline(always)]
    pub(super) fn ring_images(&mut self, topo: &Topology<'_, '_>, ring: &mut Ring) -> Result<bool> {
        ring.clear();
        let mut all = true;
        for s in self.spokes {
            let c = match self.form.image(topo, s.neighbour) {
                Ok(c) => c,
                Err(_) => {
                    all = false;
                    MISSING
                }
            };
            ring.try_push(c).map_err(|_| internal())?;
        }
        Ok(all)
    }

    /// The centroids, taken in the form, of the faces after each spoke into `centroids`
    /// ([`MISSING`] after the last spoke of an open star and where a corner is at infinity);
    /// `pts` is scratch.
    pub(super) fn face_centroids(
        &mut self,
        topo: &Topology<'_, '_>,
        centroids: &mut Ring,
        pts: &mut FacePts,
    ) -> Result<()> {
        centroids.clear();
        for s in self.spokes {
            let c = if s.face == NONE {
                MISSING
            } else {
                self.form
                    .face_centroid(topo, s.face, pts)
                    .unwrap_or(MISSING)
            };
            centroids.try_push(c).map_err(|_| internal())?;
        }
        Ok(())
    }
}

impl Driver<'_, '_, '_, '_> {
    /// Re-targets `form` to the canonical form of a non-ear, non-isolated vertex; `false`
    /// (and `form` holds no form) when `v` is isolated or an ear or its form does not exist
    /// (degenerate star). With a form, `spokes` holds `v`'s star.
    pub(super) fn local_into(
        &self,
        v: u32,
        form: &mut StarForm,
        spokes: &mut Spokes,
    ) -> Result<bool> {
        Ok(self.retarget(v, form, spokes)?.is_some())
    }

    /// [`Driver::local_into`], returning with a form whether `v` lies on the boundary.
    #[inline(always)]
    pub(super) fn retarget(
        &self,
        v: u32,
        form: &mut StarForm,
        spokes: &mut Spokes,
    ) -> Result<Option<bool>> {
        let topo = self.topo;
        // `is_isolated`, `is_boundary_vertex` and `is_ear` from one look at the first spoke.
        let h = topo.vertex_half_edge(v)?;
        let boundary = h != NONE && topo.twin(h)? == NONE;
        if h == NONE || (boundary && topo.valence(v)? == 2) {
            form.clear();
            return Ok(None);
        }
        Ok(form.reset(topo, v, boundary, spokes)?.then_some(boundary))
    }

    /// Runs `rule` on the star of every vertex that has a canonical form, in vertex order
    /// (module docs).
    #[inline(always)]
    pub(super) fn vertex_pass(
        &mut self,
        mut rule: impl FnMut(&mut Self, &mut Star<'_>) -> Result<()>,
    ) -> Result<()> {
        let topo = self.topo;
        let mut form = StarForm::blank();
        let mut spokes = Spokes::new();
        for v in 0..topo.num_vertices() as u32 {
            let Some(boundary) = self.retarget(v, &mut form, &mut spokes)? else {
                continue;
            };
            let mut star = Star {
                v,
                boundary,
                spokes: &spokes,
                form: &mut form,
            };
            rule(self, &mut star)?;
        }
        Ok(())
    }

    /// Keeps the face candidates of a star: `centroids[j]` (in the form, from
    /// [`Star::face_centroids`]) mapped back, for every face that has one.
    pub(super) fn keep_face_candidates<F: Frame>(
        &mut self,
        star: &Star<'_, F>,
        centroids: &[Point],
    ) -> Result<()> {
        for (s, c) in star.spokes.iter().zip(centroids.iter()) {
            if present(c) {
                if let Ok(b) = star.form.back(*c) {
                    set(self.face_c, s.half_edge as usize, b)?;
                }
            }
        }
        Ok(())
    }

    /// Sets the vertex points of the first `V` outputs to [`MISSING`], for a pass that writes
    /// those it can compute and [`Driver::finish_vertex_points`].
    pub(super) fn clear_vertex_points(&mut self) -> Result<()> {
        let nv = self.topo.num_vertices();
        for p in self.pos.get_mut(..nv).ok_or(internal())? {
            *p = MISSING;
        }
        Ok(())
    }

    /// Completes the vertex points after the pass: isolated vertices keep their position;
    /// boundary vertices keep theirs when `keep_boundary` (otherwise the boundary curve rule
    /// writes them later); an interior vertex whose point the pass left [`MISSING`] takes
    /// `linear(v, position)`, counted as a fallback.
    /// One pass over the vertices, split into vertex ranges ([`crate::exec`]).
    pub(super) fn finish_vertex_points(
        &mut self,
        keep_boundary: bool,
        linear: impl Fn(&Topology<'_, '_>, u32, Point) -> Result<Point> + Sync,
    ) -> Result<()> {
        let topo = self.topo;
        let strict = self.strict;
        let nv = topo.num_vertices();
        let out = self.pos.get_mut(..nv).ok_or(internal())?;
        let t = pass(self.exec, out, |first, out, tally| {
            for (v, o) in (first as u32..).zip(out.iter_mut()) {
                let p = topo.position(v)?;
                if topo.is_isolated(v)? {
                    *o = p;
                    continue;
                }
                if topo.is_boundary_vertex(v)? {
                    if keep_boundary {
                        *o = p;
                    }
                    continue;
                }
                if !present(o) {
                    chunk_fallback(strict, tally, v as usize)?;
                    *o = linear(topo, v, p)?;
                }
            }
            Ok(())
        })?;
        self.add_fallbacks(t);
        Ok(())
    }
}
