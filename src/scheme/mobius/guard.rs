//! The fold guard of the Möbius drivers (Loop, Modified Butterfly, Catmull–Clark): seed 000
//! §7.1 notes that canonical Möbius subdivision can fold a mesh; `docs/folds.md` traces the
//! folds to ill-conditioned canonical forms. The guard keeps the paper's rules wherever the
//! star's trust `τ_v` (`trust.rs`) is 1 and evaluates the other stars' rules in the form
//! interpolated toward the linear rule by `τ_v` (`spectrum.rs`, seed 000 §7.2).
//!
//! One step runs, in order:
//! 1. the vertex pass of the paper (`vertex_pass.rs`), each star's rules left in the
//!    normalised frame (`form::Normalised`) long enough to read the spread and candidate
//!    terms of its trust ([`Driver::trust_star`]), then mapped back as the paper does;
//! 2. the F4-angle term over the interior edges between two interior stars, from the
//!    candidates of step 1 ([`Driver::trust_edges`]);
//! 3. spherical stars of valence 4 or more have their trust raised toward 1 by their
//!    sphericity (`trust::sphericity`: on a sphere the paper's rules keep the sphere and
//!    commute with every Möbius map);
//! 4. for every star with `τ_v < 1`, in vertex order, the same rules again in `m_τ`,
//!    overwriting that star's candidates and vertex point ([`Driver::guarded_pass`]); the
//!    output vertices this changes are counted (or refused in strict mode);
//! 5. the paper's blends (F4, the face chain, the boundary curves), unchanged.
//!
//! The trust is decided on the paper's candidates only (steps 1–3), never on re-evaluated
//! ones, so it does not depend on the order of the stars. A mesh without a distrusted star
//! gets the paper's output bit for bit (step 3 does nothing).

use super::driver::Driver;
use super::form::{present, FacePts, Frame, Spokes};
use super::memo::StarForm;
use super::spectrum::Spectrum;
use super::trust::{f4_trust, position_trust, sphericity, spread_trust};
use super::vertex_pass::Star;
use crate::error::Result;
use crate::mesh::{get, internal, set, Topology, NONE};
use crate::point::Point;
use crate::stencil::centroid;

/// The trust of a boundary star: above 1, so that it keeps the paper's rules and the
/// F4-angle term ([`Driver::trust_edges`]) can tell it from an interior star without a
/// topology query.
const EXEMPT: f64 = 2.0;

impl Frame for Spectrum {
    const CANONICAL: bool = false;

    fn image(&mut self, topo: &Topology<'_, '_>, u: u32) -> Result<Point> {
        self.to(topo.position(u)?)
    }

    fn face_centroid(
        &mut self,
        topo: &Topology<'_, '_>,
        f: u32,
        pts: &mut FacePts,
    ) -> Result<Point> {
        pts.clear();
        for &u in topo.face_vertices(f)? {
            pts.try_push(self.image(topo, u)?).map_err(|_| internal())?;
        }
        centroid(pts)
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

impl Driver<'_, '_, '_, '_> {
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
            return set(self.trust, star.v as usize, EXEMPT);
        }
        let mut tau = spread_trust(ring);
        for (c, e) in ring.iter().zip(normalised.iter()) {
            if present(e) {
                tau = tau.min(position_trust(*e, *c));
            }
        }
        set(self.trust, star.v as usize, tau)
    }

    /// Step 2 (module docs): lowers the trust of both end stars of every interior edge
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
            let (ca, cb) = (get(self.edge_c, h as usize)?, get(self.edge_c, t as usize)?);
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

    /// Steps 3 and 4 (module docs): runs `rule` on every star with `τ_v < 1` in its interpolated
    /// form `m_τ`, in vertex order, after counting the output vertices `out` says the star
    /// changes (or refusing the first in strict mode). Without the guard, nothing.
    pub(super) fn guarded_pass(
        &mut self,
        out: Outputs,
        mut rule: impl FnMut(&mut Self, &mut Star<'_, Spectrum>) -> Result<()>,
    ) -> Result<()> {
        if !self.guard {
            return Ok(());
        }
        let topo = self.topo;
        let mut form = StarForm::blank();
        let mut spokes = Spokes::new();
        // Spherical stars of valence 4 or more keep the paper's rule (`trust::sphericity`),
        // before anything is counted: the counts read the neighbours' final trust.
        for v in 0..topo.num_vertices() as u32 {
            let tau = get(self.trust, v as usize)?;
            if tau >= 1.0 || self.retarget(v, &mut form, &mut spokes)?.is_none() {
                continue;
            }
            if spokes.len() >= 4 {
                let s = sphericity(form.tangents(), form.centre());
                set(self.trust, v as usize, tau + (1.0 - tau) * s)?;
            }
        }
        for v in 0..topo.num_vertices() as u32 {
            let tau = get(self.trust, v as usize)?;
            if tau >= 1.0 {
                continue;
            }
            // Only interior stars with a form are ever distrusted (`trust_star`).
            let Some(boundary) = self.retarget(v, &mut form, &mut spokes)? else {
                continue;
            };
            self.count_guarded(v, &spokes, out)?;
            let cf = form.form();
            let mut frame = Spectrum::new(cf.v, cf.c, form.tangents(), tau);
            let mut star = Star {
                v,
                boundary,
                spokes: &spokes,
                form: &mut frame,
            };
            rule(self, &mut star)?;
        }
        Ok(())
    }

    /// Counts the output vertices a distrusted star `v` changes: its vertex point, the points
    /// of its interior edges (once per edge: at the lower distrusted end), the points of its
    /// faces (once per face: at the first distrusted corner in face order).
    fn count_guarded(&mut self, v: u32, spokes: &Spokes, out: Outputs) -> Result<()> {
        let topo = self.topo;
        let distrusted = |d: &Self, u: u32| -> Result<bool> { Ok(get(d.trust, u as usize)? < 1.0) };
        if out.vertex {
            self.guarded(v as usize)?;
        }
        for s in spokes.iter() {
            if s.half_edge == NONE || topo.twin(s.half_edge)? == NONE {
                continue;
            }
            if !distrusted(self, s.neighbour)? || v < s.neighbour {
                self.guarded(out.edges + s.edge as usize)?;
            }
        }
        if let Some(start) = out.faces {
            for s in spokes.iter() {
                if s.face == NONE {
                    continue;
                }
                let mut first = NONE;
                for &u in topo.face_vertices(s.face)? {
                    if distrusted(self, u)? {
                        first = u;
                        break;
                    }
                }
                if first == v {
                    self.guarded(start + s.face as usize)?;
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
        for (s, c) in star.spokes.iter().zip(normalised.iter()) {
            if s.half_edge != NONE && present(c) {
                if let Ok(b) = star.form.back(*c) {
                    if present(&b) {
                        set(self.edge_c, s.half_edge as usize, b)?;
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
            set(self.pos, star.v as usize, q)?;
        }
        Ok(())
    }
}
