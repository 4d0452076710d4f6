//! The per-vertex pass of every Möbius driver (seed 000 §4.1 steps 1–3): for each vertex,
//! the canonical form of its star ([`StarForm`]), the images of its 1-ring (and of whatever
//! else the scheme's rule reads), the scheme's rule in that form, the results mapped back and
//! kept as candidates for the blends, or as vertex points.
//!
//! Isolated vertices, *ears* (boundary vertices with one face, whose form sends the opposite
//! corner of a quad to infinity: their contributions come from another corner's form,
//! [`super::ears`]) and stars without a canonical form are skipped; what they would have
//! given takes its linear rule later, counted as a fallback.
//!
//! The pass is split into vertex ranges ([`crate::exec::parts`]). A star writes only its own
//! vertex's values and the candidates of its own half-edges, whose slots are contiguous and
//! follow the vertex order (`slots.rs`), so each range owns a [`Part`]: disjoint sub-slices
//! of every array the pass writes. Each chunk re-targets its own [`StarForm`] (the memo only
//! ever caches bit-identical images), so no value depends on the chunking; the lowest failing
//! chunk's error is the serial first error.

use arrayvec::ArrayVec;

use super::driver::{chunk_fallback, Driver};
use super::form::{present, Frame, Spokes, MISSING};
use super::memo::StarForm;
use super::slots::{first_slot, slot_at_or_after};
use super::workspace::STAR_ARRAYS;
use crate::error::Result;
use crate::exec::{chunk_count, chunk_range, own_frame, parts, pass, Tally, MAX_CHUNKS};
use crate::mesh::{internal, Topology, NONE};
use crate::point::Point;

/// One vertex star with the frame its rules are evaluated in (its canonical form, or the
/// fold guard's interpolated form), as the pass hands it to a driver's rule.
pub(super) struct Star<'p, F: Frame = StarForm> {
    /// The centre vertex.
    pub(super) v: u32,
    /// Whether `v` lies on the boundary (its star is open).
    pub(super) boundary: bool,
    /// The slot of the candidates of the star's first spoke (`slots.rs`); spoke `j`'s is
    /// `slot + j`.
    pub(super) slot: usize,
    /// The spokes of `v`, counter-clockwise from the star's first spoke
    /// ([`Topology::star`]).
    pub(super) spokes: &'p Spokes<'p>,
    /// The frame of the star (the canonical form with its memo, for the paper's rules).
    pub(super) form: &'p mut F,
}

impl<F: Frame> Star<'_, F> {
    /// The images of the ring neighbours in star order into `ring`, one per spoke
    /// ([`MISSING`] for one the form sends to infinity); whether all exist.
    #[inline(always)]
    pub(super) fn ring_images(
        &mut self,
        topo: &Topology<'_, '_>,
        ring: &mut [Point],
    ) -> Result<bool> {
        if ring.len() != self.spokes.len() {
            return Err(internal());
        }
        let mut all = true;
        for (s, r) in self.spokes.iter().zip(ring.iter_mut()) {
            *r = match self.form.image(topo, s.neighbour) {
                Ok(c) => c,
                Err(_) => {
                    all = false;
                    MISSING
                }
            };
        }
        Ok(all)
    }

    /// The centroids, taken in the form, of the faces after each spoke into `centroids`, one
    /// per spoke ([`MISSING`] after the last spoke of an open star and where a corner is at
    /// infinity).
    pub(super) fn face_centroids(
        &mut self,
        topo: &Topology<'_, '_>,
        centroids: &mut [Point],
    ) -> Result<()> {
        if centroids.len() != self.spokes.len() {
            return Err(internal());
        }
        for (s, c) in self.spokes.iter().zip(centroids.iter_mut()) {
            *c = if s.face == NONE {
                MISSING
            } else {
                self.form.face_centroid(topo, s.face).unwrap_or(MISSING)
            };
        }
        Ok(())
    }
}

/// One vertex range's share of what the vertex pass writes: the vertex points and the fold
/// guard's per-vertex values of vertices `v0..v1`, and the candidate slots `k0..` of their
/// stars. The guard's re-evaluation writes through a part spanning every vertex.
pub(super) struct Part<'a, 'm, 's> {
    pub(super) topo: &'a Topology<'m, 's>,
    /// Whether the fold guard runs (its trust is measured in the paper's pass).
    pub(super) guard: bool,
    v0: usize,
    v1: usize,
    k0: usize,
    /// The vertex points of `v0..v1` (empty for a pass that writes none).
    pos: &'a mut [Point],
    trust: &'a mut [f64],
    centre: &'a mut [Point],
    radius: &'a mut [f64],
    edge_c: &'a mut [Point],
    face_c: &'a mut [Point],
    /// This range's star workspace (`workspace.rs`), taken by [`Part::with_work`].
    work: &'a mut [Point],
    /// This range's spoke workspace (`workspace.rs`), taken by [`Part::take_stars`].
    spoke_work: &'a mut [u32],
}

/// The work of one vertex range of the vertex pass.
type PartFn<'f> = dyn Fn(&mut Part<'_, '_, '_>, &mut Tally) -> Result<()> + Sync + 'f;

/// The first `n` elements of `*s`, which keeps the rest.
fn split_off<'a, T>(s: &mut &'a mut [T], n: usize) -> Result<&'a mut [T]> {
    let (a, b) = core::mem::take(s)
        .split_at_mut_checked(n)
        .ok_or(internal())?;
    *s = b;
    Ok(a)
}

/// The arrays a vertex-range pass writes, whole: the vertex points (`V` of them, or none),
/// the fold guard's per-vertex values (`V` each, or none), the candidate slots (`H` each),
/// and the star workspace (`workspace.rs`), shared equally by the ranges.
pub(super) struct Arrays<'a> {
    pub(super) pos: &'a mut [Point],
    pub(super) trust: &'a mut [f64],
    pub(super) centre: &'a mut [Point],
    pub(super) radius: &'a mut [f64],
    pub(super) edge_c: &'a mut [Point],
    pub(super) face_c: &'a mut [Point],
    pub(super) work: &'a mut [Point],
    pub(super) spoke_work: &'a mut [u32],
}

/// The first `n` elements of `*s`, or none when `*s` is empty (an array the pass does not
/// write).
fn split_per_vertex<'a, T>(s: &mut &'a mut [T], n: usize) -> Result<&'a mut [T]> {
    let n = if s.is_empty() { 0 } else { n };
    split_off(s, n)
}

impl<'a, 'm, 's> Part<'a, 'm, 's> {
    /// One part over every vertex and slot.
    pub(super) fn whole(topo: &'a Topology<'m, 's>, guard: bool, a: Arrays<'a>) -> Self {
        Part {
            topo,
            guard,
            v0: 0,
            v1: topo.num_vertices(),
            k0: 0,
            pos: a.pos,
            trust: a.trust,
            centre: a.centre,
            radius: a.radius,
            edge_c: a.edge_c,
            face_c: a.face_c,
            work: a.work,
            spoke_work: a.spoke_work,
        }
    }

    /// `a` split into the `k` vertex ranges of [`crate::exec::chunk_range`] and the slot
    /// ranges of their stars (`slots.rs`).
    pub(super) fn ranges(
        topo: &'a Topology<'m, 's>,
        slots: &[f64],
        guard: bool,
        k: usize,
        a: Arrays<'a>,
    ) -> Result<ArrayVec<Self, MAX_CHUNKS>> {
        let nv = topo.num_vertices();
        let Arrays {
            mut pos,
            mut trust,
            mut centre,
            mut radius,
            mut edge_c,
            mut face_c,
            mut work,
            mut spoke_work,
        } = a;
        // Each range's share of the workspaces: at least one chunk's (`k ≤ MAX_CHUNKS`).
        let share = work.len() / k.max(1);
        let spoke_share = spoke_work.len() / k.max(1);
        let mut ranges = ArrayVec::new();
        let mut k0 = 0;
        for i in 0..k {
            let (v0, v1) = chunk_range(nv, k, i);
            let k1 = slot_at_or_after(topo, slots, v1)?;
            let nk = k1.checked_sub(k0).ok_or(internal())?;
            let n = v1 - v0;
            let part = Part {
                topo,
                guard,
                v0,
                v1,
                k0,
                pos: split_per_vertex(&mut pos, n)?,
                trust: split_per_vertex(&mut trust, n)?,
                centre: split_per_vertex(&mut centre, n)?,
                radius: split_per_vertex(&mut radius, n)?,
                edge_c: split_off(&mut edge_c, nk)?,
                face_c: split_off(&mut face_c, nk)?,
                work: split_off(&mut work, share)?,
                spoke_work: split_off(&mut spoke_work, spoke_share)?,
            };
            ranges.try_push(part).map_err(|_| internal())?;
            k0 = k1;
        }
        Ok(ranges)
    }

    /// The vertices of this part.
    pub(super) fn vertices(&self) -> core::ops::Range<u32> {
        self.v0 as u32..self.v1 as u32
    }

    /// The spokes and the tangent-polygon array of this part's star forms, taken out of the
    /// part for its pass: its spoke workspace, and the last [`STAR_ARRAYS`]th of its star
    /// workspace (`workspace.rs`; each at least the level's largest valence). The rule's
    /// arrays are the rest ([`Part::with_work`]).
    pub(super) fn take_stars(&mut self) -> Result<(Spokes<'a>, &'a mut [Point])> {
        let work = core::mem::take(&mut self.work);
        let n = work.len() / STAR_ARRAYS;
        let (rest, tangents) = work
            .split_at_mut_checked(work.len() - n)
            .ok_or(internal())?;
        self.work = rest;
        let spokes = Spokes::new(core::mem::take(&mut self.spoke_work));
        Ok((spokes, tangents))
    }

    /// Runs `f` with this part's star workspace (`workspace.rs`) taken out of it, so that
    /// `f` can write the part while it reads and writes the workspace.
    #[inline(always)]
    pub(super) fn with_work<R>(
        &mut self,
        f: impl FnOnce(&mut Self, &mut [Point]) -> Result<R>,
    ) -> Result<R> {
        let work = core::mem::take(&mut self.work);
        let r = f(self, &mut *work);
        self.work = work;
        r
    }
}

impl Part<'_, '_, '_> {
    /// The index of vertex `v` in this part's per-vertex slices.
    #[inline(always)]
    fn vertex(&self, v: u32) -> Result<usize> {
        let v = v as usize;
        if v < self.v0 || v >= self.v1 {
            return Err(internal());
        }
        Ok(v - self.v0)
    }

    /// The index of the candidate of spoke `j` of `star` in this part's candidate slices.
    #[inline(always)]
    fn spoke<F: Frame>(&self, star: &Star<'_, F>, j: usize) -> Result<usize> {
        (star.slot + j).checked_sub(self.k0).ok_or(internal())
    }

    /// Writes the vertex point of `v`.
    pub(super) fn set_vertex(&mut self, v: u32, p: Point) -> Result<()> {
        let i = self.vertex(v)?;
        *self.pos.get_mut(i).ok_or(internal())? = p;
        Ok(())
    }

    /// Writes the edge candidate of spoke `j` of `star` (which has an outgoing half-edge).
    pub(super) fn set_edge<F: Frame>(
        &mut self,
        star: &Star<'_, F>,
        j: usize,
        p: Point,
    ) -> Result<()> {
        let i = self.spoke(star, j)?;
        *self.edge_c.get_mut(i).ok_or(internal())? = p;
        Ok(())
    }

    /// The fold guard's trust of vertex `v` (a part that holds the trust).
    pub(super) fn trust(&self, v: u32) -> Result<f64> {
        self.trust.get(self.vertex(v)?).copied().ok_or(internal())
    }

    /// Writes the fold guard's values of vertex `v`: its trust and, when given, the centre
    /// and radius of its canonical form.
    pub(super) fn set_trust(&mut self, v: u32, tau: f64, form: Option<(Point, f64)>) -> Result<()> {
        let i = self.vertex(v)?;
        if let Some((c, r)) = form {
            *self.centre.get_mut(i).ok_or(internal())? = c;
            *self.radius.get_mut(i).ok_or(internal())? = r;
        }
        *self.trust.get_mut(i).ok_or(internal())? = tau;
        Ok(())
    }

    /// Keeps the face candidates of a star: `centroids[j]` (in the form, from
    /// [`Star::face_centroids`]) mapped back, for every face that has one.
    pub(super) fn keep_face_candidates<F: Frame>(
        &mut self,
        star: &Star<'_, F>,
        centroids: &[Point],
    ) -> Result<()> {
        for (j, (s, c)) in star.spokes.iter().zip(centroids.iter()).enumerate() {
            if s.face != NONE && present(c) {
                if let Ok(b) = star.form.back(*c) {
                    let i = self.spoke(star, j)?;
                    *self.face_c.get_mut(i).ok_or(internal())? = b;
                }
            }
        }
        Ok(())
    }

    /// Keeps the edge candidates `normalised[j]` (frame of `star`, spoke order) mapped back
    /// with the star's frame, for every spoke that has an outgoing half-edge and a candidate.
    pub(super) fn keep_edges_from<F: Frame>(
        &mut self,
        star: &Star<'_, F>,
        normalised: &[Point],
    ) -> Result<()> {
        for (j, (s, c)) in star.spokes.iter().zip(normalised.iter()).enumerate() {
            if s.half_edge != NONE && present(c) {
                if let Ok(b) = star.form.back(*c) {
                    if present(&b) {
                        self.set_edge(star, j, b)?;
                    }
                }
            }
        }
        Ok(())
    }

    /// Writes the vertex point `normalised` (frame of `star`) mapped back, when it exists.
    pub(super) fn keep_vertex_from<F: Frame>(
        &mut self,
        star: &Star<'_, F>,
        normalised: Option<Point>,
    ) -> Result<()> {
        if let Some(q) = normalised.and_then(|p| star.form.back(p).ok()) {
            self.set_vertex(star.v, q)?;
        }
        Ok(())
    }
}

/// Re-targets `form` to the canonical form of a non-ear, non-isolated vertex; `None` (and
/// `form` holds no form) when `v` is isolated or an ear or its form does not exist
/// (degenerate star), else whether `v` lies on the boundary. With a form, `spokes` holds
/// `v`'s star and `tangents` begins with its tangent polygon ([`StarForm::reset`]).
#[inline(always)]
pub(super) fn retarget(
    topo: &Topology<'_, '_>,
    v: u32,
    form: &mut StarForm,
    spokes: &mut Spokes<'_>,
    tangents: &mut [Point],
) -> Result<Option<bool>> {
    // `is_isolated`, `is_boundary_vertex` and `is_ear` from one look at the first spoke.
    let h = topo.vertex_half_edge(v)?;
    let boundary = h != NONE && topo.twin(h)? == NONE;
    if h == NONE || (boundary && topo.valence(v)? == 2) {
        form.clear();
        return Ok(None);
    }
    Ok(form
        .reset(topo, v, boundary, spokes, tangents)?
        .then_some(boundary))
}

impl<'m, 's> Driver<'_, 'm, 's, '_> {
    /// Re-targets `form` to the canonical form of a non-ear, non-isolated vertex; `false`
    /// (and `form` holds no form) when `v` is isolated or an ear or its form does not exist
    /// (degenerate star). With a form, `spokes` holds `v`'s star and `tangents` begins with
    /// its tangent polygon.
    pub(super) fn local_into(
        &self,
        v: u32,
        form: &mut StarForm,
        spokes: &mut Spokes<'_>,
        tangents: &mut [Point],
    ) -> Result<bool> {
        Ok(self.retarget(v, form, spokes, tangents)?.is_some())
    }

    /// [`retarget`] on this step's topology.
    #[inline(always)]
    pub(super) fn retarget(
        &self,
        v: u32,
        form: &mut StarForm,
        spokes: &mut Spokes<'_>,
        tangents: &mut [Point],
    ) -> Result<Option<bool>> {
        retarget(self.topo, v, form, spokes, tangents)
    }

    /// The arrays of the vertex pass: with the vertex points of the first `V` outputs when
    /// `vertex_points`, with the fold guard's per-vertex values when `guard_values`.
    pub(super) fn arrays(&mut self, vertex_points: bool, guard_values: bool) -> Result<Arrays<'_>> {
        let nv = self.topo.num_vertices();
        let pos: &mut [Point] = if vertex_points {
            self.pos.get_mut(..nv).ok_or(internal())?
        } else {
            &mut []
        };
        let (trust, centre, radius): (&mut [f64], &mut [Point], &mut [f64]) = if guard_values {
            (self.trust, self.centre, self.radius)
        } else {
            (&mut [], &mut [], &mut [])
        };
        Ok(Arrays {
            pos,
            trust,
            centre,
            radius,
            edge_c: self.edge_c,
            face_c: self.face_c,
            work: &mut *self.work,
            spoke_work: &mut *self.spoke_work,
        })
    }

    /// Runs `rule` on the star of every vertex that has a canonical form (module docs), with
    /// buffers from `bufs` (one set per chunk); `vertex_points` when the rule writes the
    /// vertex points of the first `V` outputs. Split into vertex ranges by the executor.
    pub(super) fn vertex_pass<B>(
        &mut self,
        vertex_points: bool,
        bufs: impl Fn() -> B + Sync,
        rule: impl Fn(&mut Part<'_, '_, '_>, &mut Star<'_>, &mut B) -> Result<()> + Sync,
    ) -> Result<()> {
        let topo = self.topo;
        let slots = self.slots;
        let run = |part: &mut Part<'_, '_, '_>, _: &mut Tally| -> Result<()> {
            let mut form = StarForm::blank();
            let (mut spokes, tangents) = part.take_stars()?;
            let mut b = bufs();
            for v in part.v0 as u32..part.v1 as u32 {
                let Some(boundary) = retarget(topo, v, &mut form, &mut spokes, tangents)? else {
                    continue;
                };
                let slot = first_slot(topo, slots, v)?.ok_or(internal())?;
                let mut star = Star {
                    v,
                    boundary,
                    slot,
                    spokes: &spokes,
                    form: &mut form,
                };
                rule(part, &mut star, &mut b)?;
            }
            Ok(())
        };
        let nv = topo.num_vertices();
        let k = chunk_count(self.exec, nv);
        let guard = self.guard;
        if k <= 1 {
            let mut part = Part::whole(topo, guard, self.arrays(vertex_points, true)?);
            return own_frame(|| run(&mut part, &mut Tally::new()));
        }
        self.split_vertex_pass(k, vertex_points, &run)
    }

    /// [`Driver::vertex_pass`] in `k ≥ 2` vertex ranges (out of line: the serial path keeps
    /// a small stack frame).
    #[inline(never)]
    fn split_vertex_pass(&mut self, k: usize, vertex_points: bool, run: &PartFn<'_>) -> Result<()> {
        let (topo, slots, guard, exec) = (self.topo, self.slots, self.guard, self.exec);
        let mut ranges = Part::ranges(topo, slots, guard, k, self.arrays(vertex_points, true)?)?;
        parts(exec, &mut ranges, |p| p.v1 - p.v0, run)?;
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
        self.finish_vertex_points_counted(keep_boundary, linear)?;
        Ok(())
    }

    /// [`Driver::finish_vertex_points`], which also returns the fallbacks it counted: a
    /// driver that blends its face points again after the fold guard's re-evaluation
    /// (dual truncation, whose face blends run before its vertex pass) rewinds the report to
    /// before its first face blends and adds these back.
    pub(super) fn finish_vertex_points_counted(
        &mut self,
        keep_boundary: bool,
        linear: impl Fn(&Topology<'_, '_>, u32, Point) -> Result<Point> + Sync,
    ) -> Result<Tally> {
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
        Ok(t)
    }
}
