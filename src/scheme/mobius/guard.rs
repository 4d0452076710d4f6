//! The fold guard of the Möbius drivers (Loop, Modified Butterfly, Catmull–Clark): seed 000
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
//!    collapse lower the trust of the star and its neighbours;
//! 4. spherical stars of valence 4 or more have their trust raised toward 1 by their
//!    sphericity (`trust::sphericity`: on a sphere the paper's rules keep the sphere and
//!    commute with every Möbius map);
//! 5. for every star with `τ_v < 1`, in vertex order, the same rules again in `m_τ`,
//!    overwriting that star's candidates and vertex point ([`Driver::guarded_pass`]); the
//!    output vertices this changes are counted (or refused in strict mode);
//! 6. when step 5 evaluated any star, the blends again, on the guarded candidates, and the
//!    boundary curves.
//!
//! The trust is decided on the paper's candidates and output only (steps 1–3), never on
//! re-evaluated ones, so it does not depend on the order of the stars and stays
//! Möbius-invariant. A mesh without a distrusted star gets the paper's output bit for bit
//! (steps 4–6 do nothing).

use arrayvec::ArrayVec;

use super::driver::{chunk_fallback, Driver};
use super::edges::LinearEdge;
use super::form::{present, Frame, Spokes};
use super::memo::StarForm;
use super::slots::first_slot;
use super::spectrum::Spectrum;
use super::trust::{f4_trust, position_trust, sphericity, spread_trust};
use super::vertex_pass::{retarget, Arrays, Part, Star};
use super::MobiusReport;
use crate::error::Result;
use crate::exec::{chunk_count, parts, pass, Tally, MAX_CHUNKS};
use crate::mesh::{get, internal, set, Topology, NONE};
use crate::mobius::CanonicalForm;
use crate::point::{lin2, Point};

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

/// Which output vertices a scheme computes from a star's frame, for counting what the guard
/// changes: the vertex point (`vertex`), the edge points at `edges + e`, the face points at
/// `faces + f` (`None`: no face points).
#[derive(Clone, Copy)]
pub(super) struct Outputs {
    pub(super) vertex: bool,
    pub(super) edges: usize,
    pub(super) faces: Option<usize>,
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
    ) -> Result<()> {
        if !self.guard || !F::CANONICAL {
            return Ok(());
        }
        if star.boundary {
            return self.set_trust(star.v, EXEMPT, None);
        }
        let form = star.form.canonical().map(|cf| (cf.c, cf.r));
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
    /// ([`f4_trust`]; one pass over the edges, no cross-ratio formed).
    /// Only between interior stars: a boundary star's candidate can vanish exactly (the
    /// paper's rule drops a candidate at infinity) and reappear in a Möbius image.
    pub(super) fn trust_edges(&mut self) -> Result<()> {
        let topo = self.topo;
        for e in 0..topo.num_edges() as u32 {
            let h = topo.edge_half_edge(e)?;
            let t = topo.twin(h)?;
            if t == NONE {
                continue;
            }
            let (ca, cb) = (
                get(self.edge_c, self.slot(h)?)?,
                get(self.edge_c, self.slot(t)?)?,
            );
            if !present(&ca) || !present(&cb) {
                continue;
            }
            let (a, b) = (topo.origin(h)?, topo.dest(h)?);
            let (ta, tb) = (get(self.trust, a as usize)?, get(self.trust, b as usize)?);
            if ta > 1.0 || tb > 1.0 {
                continue; // a boundary star (`EXEMPT`)
            }
            let g = f4_trust(topo.position(a)?, ca, cb, topo.position(b)?);
            if g < 1.0 {
                set(self.trust, a as usize, ta.min(g))?;
                set(self.trust, b as usize, tb.min(g))?;
            }
        }
        Ok(())
    }

    /// Steps 4 and 5 (module docs): runs `rule` on every star with `τ_v < 1` in its interpolated
    /// form `m_τ`, after counting the output vertices `out` says the star changes (or
    /// refusing the first in strict mode), with buffers from `bufs` (one set per chunk).
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
        let topo = self.topo;
        self.spherical_trust()?;
        let (slots, strict) = (self.slots, self.strict);
        let run = |g: &mut Guarded<'_, '_, '_>, tally: &mut Tally| -> Result<()> {
            let mut form = StarForm::blank();
            let mut spokes = Spokes::new();
            let mut b = bufs();
            for v in g.part.vertices() {
                let tau = get(g.trust, v as usize)?;
                if tau >= 1.0 {
                    continue;
                }
                // Only interior stars with a form are ever distrusted (`trust_star`).
                let Some(boundary) = retarget(topo, v, &mut form, &mut spokes)? else {
                    continue;
                };
                count_guarded(topo, g.trust, v, &spokes, out, strict, tally)?;
                let slot = first_slot(topo, slots, v)?.ok_or(internal())?;
                let cf = form.form();
                let mut frame = Spectrum::new(cf.v, cf.c, form.tangents(), tau);
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
        let (t, any) = if k <= 1 {
            let trust: &[f64] = self.trust;
            let a = Arrays {
                pos: self.pos,
                trust: &mut [],
                centre: &mut [],
                radius: &mut [],
                edge_c: self.edge_c,
                face_c: self.face_c,
            };
            let mut g = Guarded {
                part: Part::whole(topo, self.guard, a),
                trust,
                any: false,
            };
            let mut t = Tally::new();
            run(&mut g, &mut t)?;
            (t, g.any)
        } else {
            self.split_guarded_pass(k, out.vertex, &run)?
        };
        let r = &mut self.report;
        let merged = Tally {
            count: r.guarded,
            first: r.first_guarded,
        }
        .merge(t);
        r.guarded = merged.count;
        r.first_guarded = merged.first;
        Ok(any)
    }

    /// Spherical stars of valence 4 or more keep the paper's rule (`trust::sphericity`),
    /// before anything is counted: the counts read the neighbours' final trust. Out of line,
    /// so that its star form is off the stack before the re-evaluation makes its own.
    #[inline(never)]
    fn spherical_trust(&mut self) -> Result<()> {
        let mut form = StarForm::blank();
        let mut spokes = Spokes::new();
        for v in 0..self.topo.num_vertices() as u32 {
            let tau = get(self.trust, v as usize)?;
            if tau >= 1.0 || self.retarget(v, &mut form, &mut spokes)?.is_none() {
                continue;
            }
            if spokes.len() >= 4 {
                let s = sphericity(form.tangents(), form.centre());
                set(self.trust, v as usize, tau + (1.0 - tau) * s)?;
            }
        }
        Ok(())
    }

    /// The re-evaluation of [`Driver::guarded_pass`] in `k ≥ 2` vertex ranges (out of line:
    /// the serial path keeps a small stack frame): the guarded tally and whether any star was
    /// evaluated.
    #[inline(never)]
    fn split_guarded_pass(
        &mut self,
        k: usize,
        vertex_points: bool,
        run: &GuardedFn<'_>,
    ) -> Result<(Tally, bool)> {
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
        let t = parts(exec, &mut ranges, |g| g.part.vertices().len(), run)?;
        Ok((t, ranges.iter().any(|g| g.any)))
    }

    /// Keeps the fallbacks the blends of the paper's candidates counted out of the report
    /// before they run again on the guarded candidates: `before` is the report from before
    /// the first blends, and the guard's own counts stay.
    pub(super) fn rewind_fallbacks(&mut self, before: MobiusReport) {
        self.report.fallbacks = before.fallbacks;
        self.report.first_fallback = before.first_fallback;
    }
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

/// Counts, in `tally`, the output vertices a distrusted star `v` changes: its vertex point,
/// the points of its interior edges (once per edge: at the lower distrusted end), the points
/// of its faces (once per face: at the first distrusted corner in face order); in strict mode
/// the first is refused (the guard is a fallback toward the linear rule, so it shares the
/// fallback's status).
fn count_guarded(
    topo: &Topology<'_, '_>,
    trust: &[f64],
    v: u32,
    spokes: &Spokes,
    out: Outputs,
    strict: bool,
    tally: &mut Tally,
) -> Result<()> {
    let distrusted = |u: u32| -> Result<bool> { Ok(get(trust, u as usize)? < 1.0) };
    if out.vertex {
        chunk_fallback(strict, tally, v as usize)?;
    }
    for s in spokes.iter() {
        if s.half_edge == NONE || topo.twin(s.half_edge)? == NONE {
            continue;
        }
        if !distrusted(s.neighbour)? || v < s.neighbour {
            chunk_fallback(strict, tally, out.edges + s.edge as usize)?;
        }
    }
    if let Some(start) = out.faces {
        for s in spokes.iter() {
            if s.face == NONE {
                continue;
            }
            let mut first = NONE;
            for &u in topo.face_vertices(s.face)? {
                if distrusted(u)? {
                    first = u;
                    break;
                }
            }
            if first == v {
                chunk_fallback(strict, tally, start + s.face as usize)?;
            }
        }
    }
    Ok(())
}

impl Driver<'_, '_, '_, '_> {
    /// Modified Butterfly's second fallback, after the guarded blends: every interior edge
    /// point whose end stars are distrusted moves toward the linear rule's point,
    /// `τ² p + (1 − τ²) p_lin` with `τ` the lesser trust of the two ends. The interpolated
    /// form alone cannot reach the linear scheme's fold count on Butterfly (`docs/folds.md`):
    /// an edge next to an irregular vertex takes that vertex's single partial candidate
    /// (seed 000 §4.3), which no blend corrects. The weight `τ²` rather than `τ` is measured
    /// (fertility, 2 levels: 60 folded edges with `τ`, 58 with `τ²`, linear 59). The edges
    /// changed are those the guarded pass counted (`Outputs::edges`); nothing changes where
    /// every star is trusted. One pass over the edges, split into edge ranges
    /// ([`crate::exec`]): an edge point depends only on itself and the trust.
    pub(super) fn blend_edges_toward_linear(
        &mut self,
        start: usize,
        linear: &LinearEdge<'_>,
    ) -> Result<()> {
        let topo = self.topo;
        let trust: &[f64] = self.trust;
        let ne = topo.num_edges();
        let out = self.pos.get_mut(start..start + ne).ok_or(internal())?;
        pass(self.exec, out, |first, out, _| {
            for (e, o) in (first as u32..).zip(out.iter_mut()) {
                let h = topo.edge_half_edge(e)?;
                if topo.twin(h)? == NONE {
                    continue;
                }
                let (a, b) = (topo.origin(h)?, topo.dest(h)?);
                let tau = get(trust, a as usize)?.min(get(trust, b as usize)?);
                if tau < 1.0 {
                    let w = tau * tau;
                    *o = lin2(w, *o, 1.0 - w, linear(topo, e)?);
                }
            }
            Ok(())
        })?;
        Ok(())
    }
}
