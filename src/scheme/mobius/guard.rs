//! The fold guard of the Möbius drivers (Loop, Modified Butterfly, Catmull–Clark, and dual
//! truncation in its driver; Kobbelt, Doo–Sabin, Simplest, Akleman's dual and vertex insertion
//! run steps 1–4 and 7 of it, in their drivers):
//! seed 000
//! §7.1 notes that canonical Möbius subdivision can fold a mesh; `docs/folds.md` traces the
//! folds to ill-conditioned canonical forms. The guard keeps the paper's rules wherever the
//! star's trust `τ_v` (`trust.rs`) is 1 and evaluates the other stars' rules in the form
//! interpolated toward the linear rule by `τ_v` (`spectrum.rs`, seed 000 §7.2).
//!
//! One step runs, in order:
//! 1. the vertex pass of the paper (`vertex_pass.rs`), each star's rules left in the
//!    normalised frame (`form::Normalised`) long enough to read the spread and candidate
//!    terms of its trust ([`Driver::trust_star`]) and to keep its form's centre and radius,
//!    then mapped back as the paper does;
//! 2. the paper's blends (F4, the face chain): the paper's output of the step;
//! 3. the F4-angle term over the interior edges between two interior stars, from the
//!    candidates of step 1 ([`Driver::trust_edges`]), and the output audit (`audit.rs`): the
//!    paper's output seen from each interior star's frame, where child faces that fold or
//!    collapse lower the trust of the star and its neighbours; on a level cut along its
//!    sharp edges, the interior edges with an end on a crease (whose boundary stars are
//!    exempt) are judged as elements ([`Driver::trust_edges`]);
//! 4. spherical stars of valence 4 or more have their trust raised toward 1 by their
//!    sphericity (`trust::sphericity`: on a sphere the paper's rules keep the sphere and
//!    commute with every Möbius map);
//! 5. for every star with `τ_v < 1`, in vertex order, the same rules again in `m_τ`,
//!    overwriting that star's candidates and vertex point ([`Driver::guarded_pass`]);
//! 6. when step 5 evaluated any star, the blends again, on the guarded candidates, of the
//!    edges and faces next to a star of trust below 1 (of every one when the step has
//!    counted a fallback; [`Driver::rewind_for_blends_again`]);
//! 7. every point near a distrusted star, and every distrusted edge at a crease, moves
//!    toward the linear rule's point by `1 − τ²` (`toward_linear.rs`), so that a fully
//!    distrusted element is the linear rule; these points are counted (or the first refused
//!    in strict mode);
//! 8. on a level cut along its sharp edges (Loop, Butterfly, Catmull–Clark, Kobbelt), the
//!    crease curves' points toward the linear curve rule by the trust of their segments'
//!    cross-ratios and of their crease stars (`boundary.rs`, [`Driver::guard_curves`]).
//!
//! The trust is decided on the paper's candidates and output only (steps 1–3), never on
//! re-evaluated ones, so it does not depend on the order of the stars and stays
//! Möbius-invariant. A mesh without a distrusted star gets the paper's output bit for bit
//! (steps 4–7 do nothing).

use arrayvec::ArrayVec;

use super::driver::Driver;
use super::form::{present, Frame, Spokes};
use super::memo::StarForm;
use super::slots::{first_slot, slot_of};
use super::spectrum::Spectrum;
use super::trust::{f4_trust, position_trust, ramp, sphericity, sphericity_with, spread_trust};
use super::vertex_pass::{retarget, Arrays, Part, Star};
use super::MobiusReport;
use crate::error::Result;
use crate::exec::{
    chunk_count, chunk_range, own_frame, parts, take_front, Executor, Tally, MAX_CHUNKS,
};
use crate::mesh::{get, internal, set, Topology, NONE};
use crate::mobius::{CanonicalForm, StarKind};
use crate::point::Point;

/// Distance (over the spoke's length) of a partial candidate from its place on a
/// Möbius-regular star, at or below which an edge from a corner trusts it
/// ([`partial_trust`]).
const PARTIAL_TRUSTED: f64 = 0.1;
/// The same distance at or above which it takes the linear rule.
const PARTIAL_DISTRUSTED: f64 = 0.2;

/// The trust of Modified Butterfly's partial candidate `e` of the spoke whose neighbour's
/// image is `c`, both in the star's normalised frame (seed 000 §4.3: the star's half of the
/// stencil, doubled), by its distance from `¾ c` over `|c|`. On a Möbius-regular star (a
/// regular hexagon in that frame) the doubled half stencil lands exactly at `¾ c` (and the
/// other end's at `¼ c`: their mean is the midpoint); ratios of lengths in the normalised
/// frame are Möbius-invariant (`trust.rs`).
fn partial_trust(e: Point, c: Point) -> f64 {
    let m = crate::point::sub(e, crate::point::scale(c, 0.75));
    let d = crate::sqrt::sqrt(crate::point::dot(m, m) / crate::point::dot(c, c));
    ramp(d, PARTIAL_DISTRUSTED, PARTIAL_TRUSTED)
}

/// The trust of a boundary star: above 1, so that it keeps the paper's rules and the
/// F4-angle term ([`Driver::trust_edges`]) can tell it from an interior star without a
/// topology query.
const EXEMPT: f64 = 2.0;

impl Frame for Spectrum {
    const CANONICAL: bool = false;

    fn canonical(&self) -> Option<&CanonicalForm> {
        None
    }

    fn image(&mut self, topo: &Topology<'_, '_>, u: u32) -> Result<Point> {
        self.to(topo.position(u)?)
    }
}

/// How a scheme blends an interior edge's two candidates, which the F4-angle term of
/// [`Driver::trust_edges`] reads: `e_a` is the candidate kept at the slot of the half-edge
/// leaving `a`, `e_b` that of its twin.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum EdgeBlend {
    /// `F4(a, e_a, e_b, b)`, two candidates of the edge point (Loop, Modified Butterfly,
    /// Catmull–Clark; seed 000 §4.4.3).
    Candidates,
    /// `F4(e_a, a, b, e_b)`, the points beyond both ends on the edge's grid line (Kobbelt's
    /// 4-point rule, seed 000 §4.3): on a regular grid the four points lie on a line in this
    /// order and `arg ρ = 0`.
    Beyond,
}

/// Which interior edges with an end on a crease the guard judges as elements
/// ([`Driver::trust_edges`]), per scheme.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum CreaseEdges {
    /// None (Catmull–Clark).
    Off,
    /// The F4-angle term of the edges that blend two candidates (Loop).
    F4Angle,
    /// That, and the place of the single partial candidate of an edge from a corner to a
    /// non-corner (Modified Butterfly, whose partial candidate is half a stencil).
    ButterflyCorners,
}

/// Which output vertices a scheme computes from a star's frame, which the guard moves toward
/// the linear rule and counts (`toward_linear.rs`): the vertex point (`vertex`), the edge
/// points at `edges + e` (`None`: no edge points), the face points at `faces + f` (`None`: no
/// face points), the corner points at `h` of every half-edge `h` (`corners`: Doo–Sabin's, made
/// in the form of `h`'s origin), and how many rings around a distrusted star that reaches
/// (`rings`, `vertex_rings` for the vertex points, measured per scheme).
#[derive(Clone, Copy)]
pub(super) struct Outputs {
    pub(super) vertex: bool,
    pub(super) edges: Option<usize>,
    pub(super) faces: Option<usize>,
    pub(super) corners: bool,
    /// Whether the boundary edge points move too (the simplest scheme, whose boundary stars
    /// are audited); otherwise the boundary curves keep the paper's points.
    pub(super) boundary_edges: bool,
    /// 0 to 3 rings: 1 for most schemes, 2 for Loop and Butterfly, 3 for Akleman's dual.
    pub(super) rings: u8,
    /// How many rings around a distrusted star the vertex points reach: `rings` for every
    /// scheme but dual truncation, whose vertex points take two rings, the least trust of
    /// the face points around them (`docs/folds.md` section 12).
    pub(super) vertex_rings: u8,
    /// On a level cut along its sharp edges: whether an interior edge point with an end on
    /// a boundary loop (a crease, or the mesh's boundary) also takes the least `τ` of the
    /// face points of its two faces (Kobbelt; `toward_linear.rs`).
    pub(super) crease_edge_faces: bool,
}

impl Part<'_, '_, '_> {
    /// Step 1 (module docs): the spread and candidate-position terms of the trust of `star`,
    /// from its ring's images `ring` and its edge candidates `normalised` (spoke order,
    /// normalised frame, not yet mapped back). Interior stars in the canonical frame only;
    /// without the guard, nothing.
    pub(super) fn trust_star<F: Frame>(
        &mut self,
        star: &Star<'_, F>,
        ring: &[Point],
        normalised: &[Point],
        keep_boundary_form: bool,
    ) -> Result<()> {
        if !self.guard || !F::CANONICAL {
            return Ok(());
        }
        let form = star.form.canonical().map(|cf| (cf.c, cf.r));
        if star.boundary {
            // Exempt; its form kept only for a scheme whose output audit reads open stars
            // (`audit.rs`).
            return self.set_trust(star.v, EXEMPT, form.filter(|_| keep_boundary_form));
        }
        let mut tau = spread_trust(ring);
        for (c, e) in ring.iter().zip(normalised.iter()) {
            if present(e) {
                tau = tau.min(position_trust(*e, *c));
            }
        }
        self.set_trust(star.v, tau, form)
    }
}

impl Driver<'_, '_, '_, '_> {
    /// Step 3 (module docs): lowers the trust of both end stars of every interior edge
    /// between two interior stars to the F4-angle term of the blend of their candidates
    /// ([`f4_trust`]; no cross-ratio formed).
    /// Only between interior stars: a boundary star's candidate can vanish exactly (the
    /// paper's rule drops a candidate at infinity) and reappear in a Möbius image.
    pub(super) fn trust_edges(
        &mut self,
        blend: EdgeBlend,
        crease_edges: CreaseEdges,
    ) -> Result<()> {
        // Two passes over disjoint output ranges, so that both run on the executor's threads
        // (a pass that lowers both ends of each edge would write scattered vertices): the
        // F4-angle term of every edge into `edge_trust` (edge ranges), then every interior
        // star's trust lowered to the least term of its spokes (vertex ranges). An edge with
        // a boundary end (`EXEMPT`) or a missing candidate gets the neutral 1. Each trust is the least of the same terms, and `f64::min` of values
        // below 1 (never NaN, never −0: `ramp`) does not depend on their order, so the trust
        // is the same bits for every chunking.
        let topo = self.topo;
        let ne = topo.num_edges();
        let g_all = core::mem::take(&mut self.edge_trust);
        let (edge_c, trust) = (&*self.edge_c, &*self.trust);
        let slots = self.slots;
        let slot = |h: u32| -> Result<usize> { slot_of(slots, h) };
        let edge_terms = |e0: usize, out: &mut [f64]| -> Result<()> {
            for (i, ge) in out.iter_mut().enumerate() {
                let e = (e0 + i) as u32;
                *ge = 1.0;
                let h = topo.edge_half_edge(e)?;
                let t = topo.twin(h)?;
                if t == NONE {
                    continue;
                }
                let (ca, cb) = (get(edge_c, slot(h)?)?, get(edge_c, slot(t)?)?);
                if !present(&ca) || !present(&cb) {
                    continue;
                }
                // The twin starts where `h` ends (no walk around `h`'s face for `dest`).
                let (a, b) = (topo.origin(h)?, topo.origin(t)?);
                if get(trust, a as usize)? > 1.0 || get(trust, b as usize)? > 1.0 {
                    continue; // a boundary star (`EXEMPT`)
                }
                let (pa, pb) = (topo.position(a)?, topo.position(b)?);
                *ge = match blend {
                    EdgeBlend::Candidates => f4_trust(pa, ca, cb, pb),
                    EdgeBlend::Beyond => f4_trust(ca, pa, pb, cb),
                };
            }
            Ok(())
        };
        f64_ranges(
            self.exec,
            g_all.get_mut(..ne).ok_or(internal())?,
            &edge_terms,
        )?;
        let g: &[f64] = g_all.get(..ne).ok_or(internal())?;
        let nv = topo.num_vertices();
        let r = topo.raw();
        let least_terms = |v0: usize, out: &mut [f64]| -> Result<()> {
            for (i, tv) in out.iter_mut().enumerate() {
                let first = get(r.vert_he, v0 + i)?;
                if *tv > 1.0 || first == NONE {
                    continue;
                }
                // Every interior edge at `v` has a half-edge leaving `v`: the outgoing
                // half-edges of the star (as `slots::write` walks them) meet them all.
                let mut cur = first;
                for _ in 0..get(r.valence, v0 + i)? {
                    let ge = get(g, get(r.edge_of, cur as usize)? as usize)?;
                    if ge < 1.0 {
                        *tv = tv.min(ge);
                    }
                    let (_, prev, _) = r.next_prev_face(cur)?;
                    cur = get(r.twin, prev as usize)?;
                    if cur == NONE || cur == first {
                        break;
                    }
                }
            }
            Ok(())
        };
        f64_ranges(
            self.exec,
            self.trust.get_mut(..nv).ok_or(internal())?,
            &least_terms,
        )?;
        self.edge_trust = g_all;
        self.crease_edge_terms(crease_edges)
    }

    /// The trust of every interior edge with an end on a crease (a boundary vertex of a
    /// level cut along its sharp edges, `crease.rs`), kept per edge in `edge_trust` for the
    /// blend toward the linear rule (`toward_linear.rs`), which moves such an edge point
    /// alone, by `1 − τ²`; 1 for every other edge, and for every edge of an untagged level
    /// or with [`CreaseEdges::Off`]. The boundary stars at a crease are exempt from the
    /// star trust (`trust.rs`), so an edge between two crease vertices, or from a crease
    /// vertex into the smooth region, is judged here as an element (docs/creases.md,
    /// "Folds next to corners"):
    ///
    /// * with [`CreaseEdges::ButterflyCorners`] (Modified Butterfly), an edge from a corner to
    ///   a non-corner: the corner rule of `edges.rs` leaves it the other end's partial
    ///   candidate alone, half of the Butterfly stencil doubled (seed 000 §4.3: the edge
    ///   point is the blend of both halves). On a Möbius-regular star that half lands at ¾
    ///   of the spoke, a fixed place the scheme's output tolerates; where it lands far from
    ///   there ([`partial_trust`], in the star's normalised frame) it folded planar faces
    ///   next to reflex corners (fandisk), and the edge moves to the linear rule (the blend
    ///   with the corner's own half folded as much). A non-corner without a kept form (a
    ///   crease vertex), or of valence other than 6 (Zorin's whole stencil), keeps 1;
    /// * an edge whose two ends and the two apexes of its faces all lie on creases takes 0:
    ///   every star its point is made from is an open fan of a piece whose vertices are all
    ///   on its crease (a face enclosed by crease edges, once refined), which the crease
    ///   curves alone shape;
    /// * another edge that blends two candidates takes the F4-angle term of the blend
    ///   ([`f4_trust`]): the two stars' candidates disagree, whatever their forms;
    /// * an edge that takes a single candidate (the corner rule, a missing candidate) keeps
    ///   1.
    ///
    /// The second decision depends on the tags and the connectivity only; the others read
    /// the paper's candidates (before the guarded pass) in a star's normalised frame, or the
    /// cross-ratio of the blend, whose `arg ρ` is a Möbius invariant (`trust.rs`). So which
    /// edges move, and by how much, is the same on every Möbius image; the moved points,
    /// like every fallback toward the linear rule, are equivariant under similarities only.
    fn crease_edge_terms(&mut self, crease_edges: CreaseEdges) -> Result<()> {
        let topo = self.topo;
        let ne = topo.num_edges();
        let tagged = crease_edges != CreaseEdges::Off && !self.corners.is_empty();
        let butterfly_corners = crease_edges == CreaseEdges::ButterflyCorners;
        let edge_c: &[Point] = self.edge_c;
        let slots = self.slots;
        let corners: &[u32] = self.corners;
        let (trust, centre, radius): (&[f64], &[Point], &[f64]) =
            (self.trust, self.centre, self.radius);
        let corner = |v: u32| corners.get(v as usize).is_some_and(|&c| c != 0);
        let terms = |e0: usize, out: &mut [f64]| -> Result<()> {
            for (i, ge) in out.iter_mut().enumerate() {
                *ge = 1.0;
                if !tagged {
                    continue;
                }
                let e = (e0 + i) as u32;
                let h = topo.edge_half_edge(e)?;
                let t = topo.twin(h)?;
                if t == NONE {
                    continue;
                }
                let (a, b) = (topo.origin(h)?, topo.dest(h)?);
                if !topo.is_boundary_vertex(a)? && !topo.is_boundary_vertex(b)? {
                    continue;
                }
                if corner(a) != corner(b) {
                    if butterfly_corners {
                        // The candidate the corner rule takes: the non-corner's, at the
                        // position along its spoke to the corner in its own frame.
                        let (u, w, hu) = if corner(a) { (b, a, t) } else { (a, b, h) };
                        let cu = get(edge_c, slot_of(slots, hu)?)?;
                        let r = get(radius, u as usize)?;
                        // An interior star with a kept form, of valence 6: an irregular
                        // one gives Zorin's whole stencil, the paper's rule for an edge to
                        // a singular vertex.
                        let partial =
                            r != 0.0 && get(trust, u as usize)? <= 1.0 && topo.valence(u)? == 6;
                        if present(&cu) && partial {
                            let cf = CanonicalForm {
                                v: topo.position(u)?,
                                c: get(centre, u as usize)?,
                                r,
                                kind: StarKind::Interior,
                            };
                            *ge = match (cf.to_normalised(cu), cf.to_normalised(topo.position(w)?))
                            {
                                (Ok(e), Ok(c)) => partial_trust(e, c),
                                _ => 0.0,
                            };
                        }
                    }
                    continue;
                }
                if topo.is_boundary_vertex(a)?
                    && topo.is_boundary_vertex(b)?
                    && topo.is_boundary_vertex(topo.dest(topo.next(h)?)?)?
                    && topo.is_boundary_vertex(topo.dest(topo.next(t)?)?)?
                {
                    *ge = 0.0;
                    continue;
                }
                let (ca, cb) = (
                    get(edge_c, slot_of(slots, h)?)?,
                    get(edge_c, slot_of(slots, t)?)?,
                );
                if !present(&ca) || !present(&cb) {
                    continue;
                }
                *ge = f4_trust(topo.position(a)?, ca, cb, topo.position(b)?);
            }
            Ok(())
        };
        f64_ranges(
            self.exec,
            self.edge_trust.get_mut(..ne).ok_or(internal())?,
            &terms,
        )
    }

    /// Steps 4 and 5 (module docs): runs `rule` on every star with `τ_v < 1` in its interpolated
    /// form `m_τ`, with buffers from `bufs` (one set per chunk); the points this changes are
    /// counted by the blend toward the linear rule that follows (step 7).
    /// Whether any star was evaluated (the drivers then blend again). Without the guard,
    /// nothing. The re-evaluation is split into vertex ranges as the vertex pass is: the
    /// trust is only read by then, and a star writes only its own vertex point and slots.
    pub(super) fn guarded_pass<B>(
        &mut self,
        out: Outputs,
        bufs: impl Fn() -> B + Sync,
        rule: impl Fn(&mut Part<'_, '_, '_>, &mut Star<'_, Spectrum>, &mut B) -> Result<()> + Sync,
    ) -> Result<bool> {
        if !self.guard {
            return Ok(false);
        }
        // Spherical stars of valence 4 or more keep the paper's rule (`trust::sphericity`),
        // before any star is evaluated again.
        self.raise_spherical(|valence| valence >= 4)?;
        self.reevaluate(out, bufs, rule)
    }

    /// Step 5 (module docs) alone, on the trust as it stands: [`Driver::guarded_pass`]
    /// without its raise of spherical stars, for a driver that raised them already
    /// (dual truncation, by [`Driver::raise_spherical_quads`]; raising twice would move the
    /// trust the audit decided). Whether any star was evaluated; without the guard, nothing.
    pub(super) fn reevaluate<B>(
        &mut self,
        out: Outputs,
        bufs: impl Fn() -> B + Sync,
        rule: impl Fn(&mut Part<'_, '_, '_>, &mut Star<'_, Spectrum>, &mut B) -> Result<()> + Sync,
    ) -> Result<bool> {
        if !self.guard {
            return Ok(false);
        }
        let topo = self.topo;
        let slots = self.slots;
        let run = |g: &mut Guarded<'_, '_, '_>, _: &mut Tally| -> Result<()> {
            let mut form = StarForm::blank();
            let (mut spokes, tangents) = g.part.take_stars()?;
            let mut b = bufs();
            for v in g.part.vertices() {
                let tau = get(g.trust, v as usize)?;
                if tau >= 1.0 {
                    continue;
                }
                // Only interior stars with a form are ever distrusted (`trust_star`).
                // Interior stars only: a boundary star is distrusted only by the audit of a
                // level cut along its sharp edges, and keeps its rules (its crease curves are
                // the paper's); the blend toward the linear rule moves the points around it.
                let Some(false) = retarget(topo, v, &mut form, &mut spokes, tangents)? else {
                    continue;
                };
                let boundary = false;
                let slot = first_slot(topo, slots, v)?.ok_or(internal())?;
                let cf = form.form();
                let t = tangents.get(..spokes.len()).ok_or(internal())?;
                let mut frame = Spectrum::new(cf.v, cf.c, t, tau);
                let mut star = Star {
                    v,
                    boundary,
                    slot,
                    spokes: &spokes,
                    form: &mut frame,
                };
                rule(&mut g.part, &mut star, &mut b)?;
                g.any = true;
            }
            Ok(())
        };
        let k = chunk_count(self.exec, topo.num_vertices());
        let any = if k <= 1 {
            let trust: &[f64] = self.trust;
            let a = Arrays {
                pos: self.pos,
                trust: &mut [],
                centre: &mut [],
                radius: &mut [],
                edge_c: self.edge_c,
                face_c: self.face_c,
                work: &mut *self.work,
                spoke_work: &mut *self.spoke_work,
            };
            let mut g = Guarded {
                part: Part::whole(topo, self.guard, a),
                trust,
                any: false,
            };
            own_frame(|| run(&mut g, &mut Tally::new()))?;
            g.any
        } else {
            self.split_guarded_pass(k, out.vertex, &run)?
        };
        Ok(any)
    }

    /// Raises the trust of every distrusted star whose valence `pick` selects toward 1 by its
    /// sphericity, `τ ← τ + (1 − τ)·s` (`trust::sphericity`; step 4 of the module docs), and
    /// says whether it changed any trust. Each star reads and writes only its own trust, so
    /// the vertex ranges of `exec` give the same values in any order.
    /// Out of line, so that its star form is off the stack before the re-evaluation makes
    /// its own.
    #[inline(never)]
    pub(super) fn raise_spherical(&mut self, pick: impl Fn(usize) -> bool + Sync) -> Result<bool> {
        let k = chunk_count(self.exec, self.topo.num_vertices());
        if k > 1 {
            return self.split_raise_spherical(k, &pick);
        }
        let mut form = StarForm::blank();
        let mut raised = false;
        // The spokes and tangent polygons in the workspaces (no other pass holds them now).
        let spoke_work = core::mem::take(&mut self.spoke_work);
        let mut spokes = Spokes::new(&mut *spoke_work);
        let tangents = core::mem::take(&mut self.work);
        let r = (|| {
            for v in 0..self.topo.num_vertices() as u32 {
                let tau = get(self.trust, v as usize)?;
                if tau >= 1.0
                    || self
                        .retarget(v, &mut form, &mut spokes, tangents)?
                        .is_none()
                {
                    continue;
                }
                if pick(spokes.len()) {
                    let t = tangents.get(..spokes.len()).ok_or(internal())?;
                    let s = sphericity(t, form.centre());
                    let raised_tau = tau + (1.0 - tau) * s;
                    raised |= raised_tau != tau;
                    set(self.trust, v as usize, raised_tau)?;
                }
            }
            Ok(raised)
        })();
        self.work = tangents;
        self.spoke_work = spoke_work;
        r
    }

    /// The trust and the star workspaces split into the `k` vertex ranges of the sphericity
    /// raises ([`Part::ranges`]; the candidate slots come along, unused).
    fn trust_ranges(&mut self, k: usize) -> Result<ArrayVec<Part<'_, '_, '_>, MAX_CHUNKS>> {
        let a = Arrays {
            pos: &mut [],
            trust: &mut *self.trust,
            centre: &mut [],
            radius: &mut [],
            edge_c: &mut *self.edge_c,
            face_c: &mut *self.face_c,
            work: &mut *self.work,
            spoke_work: &mut *self.spoke_work,
        };
        Part::ranges(self.topo, self.slots, self.guard, k, a)
    }

    /// [`Driver::raise_spherical`] in `k ≥ 2` vertex ranges, each with its share of the star
    /// workspaces (out of line: the serial path keeps a small stack frame).
    #[inline(never)]
    fn split_raise_spherical(
        &mut self,
        k: usize,
        pick: &(dyn Fn(usize) -> bool + Sync),
    ) -> Result<bool> {
        let (topo, exec) = (self.topo, self.exec);
        let mut ranges = ArrayVec::<(Part<'_, '_, '_>, bool), MAX_CHUNKS>::new();
        for part in self.trust_ranges(k)? {
            ranges.try_push((part, false)).map_err(|_| internal())?;
        }
        parts(
            exec,
            &mut ranges,
            |(p, _)| p.vertices().len(),
            |(part, raised), _| {
                let mut form = StarForm::blank();
                let (mut spokes, tangents) = part.take_stars()?;
                for v in part.vertices() {
                    let tau = part.trust(v)?;
                    if tau >= 1.0 || retarget(topo, v, &mut form, &mut spokes, tangents)?.is_none()
                    {
                        continue;
                    }
                    if pick(spokes.len()) {
                        let t = tangents.get(..spokes.len()).ok_or(internal())?;
                        let s = sphericity(t, form.centre());
                        let raised_tau = tau + (1.0 - tau) * s;
                        *raised |= raised_tau != tau;
                        part.set_trust(v, raised_tau, None)?;
                    }
                }
                Ok(())
            },
        )?;
        Ok(ranges.iter().any(|r| r.1))
    }

    /// [`Driver::raise_spherical`] for every distrusted star, with the diagonals of its quads
    /// (the corners opposite `v`) as further evidence of its sphere
    /// ([`trust::sphericity_with`](super::trust::sphericity_with)): Kobbelt, whose rules read
    /// them (seed 000 §4.3), and whose fallback is the blend toward the linear rule alone, so
    /// that a star of valence 3 on a sphere must keep the paper's rules by this evidence.
    /// In the vertex ranges of `exec`, as [`Driver::raise_spherical`].
    #[inline(never)]
    pub(super) fn raise_spherical_quads(&mut self) -> Result<()> {
        let k = chunk_count(self.exec, self.topo.num_vertices());
        if k > 1 {
            return self.split_raise_spherical_quads(k);
        }
        let mut form = StarForm::blank();
        let spoke_work = core::mem::take(&mut self.spoke_work);
        let mut spokes = Spokes::new(&mut *spoke_work);
        let tangents = core::mem::take(&mut self.work);
        let topo = self.topo;
        let r = (|| {
            for v in 0..topo.num_vertices() as u32 {
                let tau = get(self.trust, v as usize)?;
                if tau >= 1.0
                    || self
                        .retarget(v, &mut form, &mut spokes, tangents)?
                        .is_none()
                {
                    continue;
                }
                let t = tangents.get(..spokes.len()).ok_or(internal())?;
                let s = quad_sphericity(topo, v, t, form.centre())?;
                set(self.trust, v as usize, tau + (1.0 - tau) * s)?;
            }
            Ok(())
        })();
        self.work = tangents;
        self.spoke_work = spoke_work;
        r
    }

    /// [`Driver::raise_spherical_quads`] in `k ≥ 2` vertex ranges, each with its share of the
    /// star workspaces (out of line: the serial path keeps a small stack frame).
    #[inline(never)]
    fn split_raise_spherical_quads(&mut self, k: usize) -> Result<()> {
        let (topo, exec) = (self.topo, self.exec);
        let mut ranges = self.trust_ranges(k)?;
        parts(
            exec,
            &mut ranges,
            |p| p.vertices().len(),
            |part, _| {
                let mut form = StarForm::blank();
                let (mut spokes, tangents) = part.take_stars()?;
                for v in part.vertices() {
                    let tau = part.trust(v)?;
                    if tau >= 1.0 || retarget(topo, v, &mut form, &mut spokes, tangents)?.is_none()
                    {
                        continue;
                    }
                    let t = tangents.get(..spokes.len()).ok_or(internal())?;
                    let s = quad_sphericity(topo, v, t, form.centre())?;
                    part.set_trust(v, tau + (1.0 - tau) * s, None)?;
                }
                Ok(())
            },
        )?;
        Ok(())
    }

    /// Adds the points the guard moved ([`Driver::blend_toward_linear`]) to the report.
    pub(super) fn add_guarded(&mut self, t: Tally) {
        let r = &mut self.report;
        let merged = Tally {
            count: r.guarded,
            first: r.first_guarded,
        }
        .merge(t);
        r.guarded = merged.count;
        r.first_guarded = merged.first;
    }

    /// The re-evaluation of [`Driver::guarded_pass`] in `k ≥ 2` vertex ranges (out of line:
    /// the serial path keeps a small stack frame): whether any star was evaluated.
    #[inline(never)]
    fn split_guarded_pass(
        &mut self,
        k: usize,
        vertex_points: bool,
        run: &GuardedFn<'_>,
    ) -> Result<bool> {
        let (topo, slots, guard, exec) = (self.topo, self.slots, self.guard, self.exec);
        let trust: &[f64] = self.trust;
        let nv = topo.num_vertices();
        let pos: &mut [Point] = if vertex_points {
            self.pos.get_mut(..nv).ok_or(internal())?
        } else {
            &mut []
        };
        let a = Arrays {
            pos,
            trust: &mut [],
            centre: &mut [],
            radius: &mut [],
            edge_c: self.edge_c,
            face_c: self.face_c,
            work: &mut *self.work,
            spoke_work: &mut *self.spoke_work,
        };
        let mut ranges = ArrayVec::<Guarded<'_, '_, '_>, MAX_CHUNKS>::new();
        for part in Part::ranges(topo, slots, guard, k, a)? {
            ranges
                .try_push(Guarded {
                    part,
                    trust,
                    any: false,
                })
                .map_err(|_| internal())?;
        }
        parts(exec, &mut ranges, |g| g.part.vertices().len(), run)?;
        Ok(ranges.iter().any(|g| g.any))
    }

    /// Keeps the fallbacks the blends of the paper's candidates counted out of the report
    /// before they run again on the guarded candidates: `before` is the report from before
    /// the first blends, and the guard's own counts stay.
    /// Before the blends run again on the guarded candidates (step 6): rewinds the
    /// fallbacks to `before` (the report before the first blends) and says whether the
    /// blends again may skip the elements next to no star of trust below 1
    /// (`blend_interior_edges_again`, `blend_faces_again`). They may when the first blends
    /// and the guarded pass counted no fallback: a skipped element then reads the inputs it
    /// read the first time, where it was no fallback, so the report after the blends again
    /// (the fallbacks among the blended elements) is the report of blending every element,
    /// count and first element alike. Otherwise every element is blended again.
    pub(super) fn rewind_for_blends_again(&mut self, before: MobiusReport) -> bool {
        let none_since = self.report.fallbacks == before.fallbacks;
        self.rewind_fallbacks(before);
        none_since
    }

    pub(super) fn rewind_fallbacks(&mut self, before: MobiusReport) {
        self.report.fallbacks = before.fallbacks;
        self.report.first_fallback = before.first_fallback;
    }
}

/// The sphericity of the star of `v` with its quads' far corners as further evidence
/// ([`Driver::raise_spherical_quads`]): `t` its tangent polygon, `centre` its form's centre.
fn quad_sphericity(topo: &Topology<'_, '_>, v: u32, t: &[Point], centre: Point) -> Result<f64> {
    let pv = topo.position(v)?;
    let mut diagonals = topo.star(v).filter(|s| s.half_edge != NONE).map(|s| {
        crate::mesh::gather::apex(topo, s.half_edge)
            .and_then(|a| topo.position(a))
            .ok()
            .and_then(|d| CanonicalForm::tangent(pv, d))
    });
    Ok(sphericity_with(t, centre, &mut diagonals))
}

/// One vertex range of the guard's re-evaluation: its share of the arrays, the trust of every
/// vertex (read only), whether a star of the range was evaluated.
struct Guarded<'a, 'm, 's> {
    part: Part<'a, 'm, 's>,
    trust: &'a [f64],
    any: bool,
}

/// The work of one vertex range of the guard's re-evaluation.
type GuardedFn<'f> = dyn Fn(&mut Guarded<'_, '_, '_>, &mut Tally) -> Result<()> + Sync + 'f;

/// The work of one range of an `f64` pass: its first index and its values.
pub(super) type F64Fn<'f> = dyn Fn(usize, &mut [f64]) -> Result<()> + Sync + 'f;

/// Runs `f(first, range)` over the disjoint ranges of `out` that `exec` asks for
/// ([`crate::exec::chunk_range`]); one range runs inline.
pub(super) fn f64_ranges(exec: &dyn Executor, out: &mut [f64], f: &F64Fn<'_>) -> Result<()> {
    let k = chunk_count(exec, out.len());
    if k <= 1 {
        return own_frame(|| f(0, out));
    }
    split_f64_ranges(exec, out, k, f)
}

/// [`f64_ranges`] in `k ≥ 2` ranges (out of line: the serial path keeps a small stack frame,
/// `docs/firmware.md`).
#[inline(never)]
fn split_f64_ranges(exec: &dyn Executor, out: &mut [f64], k: usize, f: &F64Fn<'_>) -> Result<()> {
    let n = out.len();
    let mut rest = out;
    let mut ranges = ArrayVec::<(usize, &mut [f64]), MAX_CHUNKS>::new();
    for i in 0..k {
        let (a, b) = chunk_range(n, k, i);
        let range = take_front(&mut rest, b - a)?;
        ranges.try_push((a, range)).map_err(|_| internal())?;
    }
    parts(
        exec,
        &mut ranges,
        |p| p.1.len(),
        |(a, range), _| f(*a, range),
    )?;
    Ok(())
}
