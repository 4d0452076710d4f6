//! Boundary loops as curves (seed 000 §4.3 "Boundary curves", §4.4.1): every boundary loop is
//! subdivided as a closed curve through its vertices, with the Möbius approximating curve
//! rule for approximating schemes (odd `E_{i+½} = F4(P_{i−1}, P_i, P_{i+1}, P_{i+2})`, even
//! `P'_i = F4(P_{i−1}, E_{i−½}, E_{i+½}, P_{i+1})`) and the interpolating rule (odd points
//! only) for the others, the Möbius counterparts of the linear schemes' boundary curves (the
//! cubic B-spline crease rule, the 4-point rule).
//!
//! With sharp features the driver runs on the mesh cut along its sharp edges (`crease.rs`):
//! the crease curves are then boundary loops, and a loop vertex marked as a *corner* ends
//! its curve there. Next to a corner the open-curve rules of [`crate::curve::mobius`] apply
//! (the end edge point `E` with `cr[P_2, P_1, P_0, E] = 1/3`; the midpoint between two
//! corners), and an approximating scheme keeps the corner, exactly as an open Möbius curve
//! through the same points. Without corners every loop is closed, as above.

use super::driver::Driver;
use super::toward_linear::toward_linear;
use super::trust::{curve_turn_trust, f4_trust};
use crate::blend::f4;
use crate::curve::four_point::virtual_end_point;
use crate::curve::mobius::end_edge_point;
use crate::error::Result;
use crate::mesh::{get, set, NONE};
use crate::point::{midpoint, Point};

impl Driver<'_, '_, '_, '_> {
    /// The boundary neighbours of boundary half-edge `h = (a → b)`: `(P_{i−1}, P_{i+2})`.
    pub(super) fn boundary_outer(&self, h: u32) -> Result<(u32, u32)> {
        let topo = self.topo;
        Ok((
            topo.origin(topo.prev_boundary(h)?)?,
            topo.dest(topo.next_boundary(h)?)?,
        ))
    }

    /// Whether vertex `v` is a corner: its boundary loop is an open curve ending there
    /// (module docs). Never without sharp features.
    pub(super) fn is_corner(&self, v: u32) -> bool {
        self.corners.get(v as usize).is_some_and(|&c| c != 0)
    }

    /// Whether the origin and the end of boundary half-edge `h` are corners.
    pub(super) fn corner_ends(&self, h: u32) -> Result<(bool, bool)> {
        let topo = self.topo;
        Ok((
            self.is_corner(topo.origin(h)?),
            self.is_corner(topo.dest(h)?),
        ))
    }

    /// The curve segment of boundary half-edge `h = (a → b)`: the four points
    /// `[P_{i−1}, a, b, P_{i+2}]` of the linear fallback (past a corner the 4-point rule's
    /// virtual end point `2a − b`), and the Möbius edge point — `F4` of the four points, the
    /// open-curve end rule next to a corner, the midpoint between two corners (module docs).
    pub(super) fn boundary_segment(&self, h: u32) -> Result<([Point; 4], Result<Point>)> {
        let topo = self.topo;
        let (i0, i3) = self.boundary_outer(h)?;
        let (a, b) = (
            topo.position(topo.origin(h)?)?,
            topo.position(topo.dest(h)?)?,
        );
        let (before, after) = (topo.position(i0)?, topo.position(i3)?);
        let (ca, cb) = self.corner_ends(h)?;
        let q = match (ca, cb) {
            (false, false) => f4(before, a, b, after),
            (true, false) => end_edge_point(a, b, after),
            (false, true) => end_edge_point(b, a, before),
            (true, true) => Ok(midpoint(a, b)),
        };
        let p0 = if ca { virtual_end_point(a, b) } else { before };
        let p3 = if cb { virtual_end_point(b, a) } else { after };
        Ok(([p0, a, b, p3], q))
    }

    /// Whether boundary half-edge `h` lies on a short crease curve — a closed loop of three
    /// segments (with or without a corner on it), or an open curve of two or three segments
    /// between corners — on a level cut along its sharp edges with the fold guard on (module
    /// docs). Any three points are Möbius images of any other three, so the Möbius curve
    /// rules cannot tell a thin triangle of crease edges from a fat one and put its curve on
    /// its circumcircle, far off the edges of a thin one; an open curve of four points is
    /// made by those rules almost alone, since each end segment's rule (`end_edge_point`)
    /// sees only its three first points, and on a scanned mesh such curves turn back sharply
    /// at their inner points (docs/creases.md, "Folds next to corners"). Such a curve takes
    /// the linear curve rule, counted as guarded. The decision depends on the tags only, so
    /// it is the same on every Möbius image.
    pub(super) fn short_curve(&self, h: u32) -> Result<bool> {
        if !self.guard || self.corners.is_empty() {
            return Ok(false);
        }
        let topo = self.topo;
        Ok(match self.corner_ends(h)? {
            (true, true) => false,
            (true, false) => {
                // a → b → c: c a corner, the loop a → b → c → a closing at the corner a, or
                // a → b → c → d with d a corner.
                let n = topo.next_boundary(h)?;
                let c = topo.dest(n)?;
                let d = topo.dest(topo.next_boundary(n)?)?;
                self.is_corner(c) || d == topo.origin(h)? || self.is_corner(d)
            }
            (false, true) => {
                let p = topo.prev_boundary(h)?;
                let c = topo.origin(p)?;
                let d = topo.origin(topo.prev_boundary(p)?)?;
                self.is_corner(c) || d == topo.dest(h)? || self.is_corner(d)
            }
            (false, false) => {
                // The loop of three, or the middle segment of i0 → a → b → i3 between corners.
                let (i0, i3) = self.boundary_outer(h)?;
                i0 == i3 || (self.is_corner(i0) && self.is_corner(i3))
            }
        })
    }

    /// The fold guard's trust of the Möbius curve segment of boundary half-edge `h` on a
    /// crease curve (a level cut along its sharp edges, the default mode; 1 otherwise): the
    /// least of the F4-angle term ([`f4_trust`]) and the turn term ([`curve_turn_trust`]) of
    /// the segment `(P_{i−1}, a, b, P_{i+2})` whose blend `F4(P_{i−1}, a, b, P_{i+2})` makes
    /// the edge point, both functions of its cross-ratio and so Möbius-invariant. Next to a
    /// corner the end rule reads three points only, which a Möbius map can send to any other
    /// three, so the segment after it on the curve (the same three points and one more)
    /// judges it. A short curve ([`Driver::short_curve`]), which takes the linear rule
    /// whole, is 1 here.
    ///
    /// Why: a 30° crease angle on a scanned mesh tags noise, and its crease curves turn back
    /// on themselves (angles of 17°–40° between consecutive crease edges on `cow`). The
    /// circle through such a hairpin is small, and the curve rules put their points on it,
    /// most of an edge length off the polyline, where the faces beside the crease fold
    /// (docs/creases.md, "Folds next to corners").
    pub(super) fn curve_trust(&self, h: u32) -> Result<f64> {
        if !self.guard || self.corners.is_empty() || self.short_curve(h)? {
            return Ok(1.0);
        }
        let topo = self.topo;
        let segment = match self.corner_ends(h)? {
            (false, false) => h,
            (true, false) => topo.next_boundary(h)?,
            (false, true) => topo.prev_boundary(h)?,
            (true, true) => return Ok(1.0),
        };
        if self.corner_ends(segment)? != (false, false) {
            return Ok(1.0);
        }
        let (i0, i3) = self.boundary_outer(segment)?;
        if i0 == i3 {
            return Ok(1.0);
        }
        let (p0, p1, p2, p3) = (
            topo.position(i0)?,
            topo.position(topo.origin(segment)?)?,
            topo.position(topo.dest(segment)?)?,
            topo.position(i3)?,
        );
        Ok(f4_trust(p0, p1, p2, p3).min(curve_turn_trust(p0, p1, p2, p3)))
    }

    /// Lowers the trust of every crease vertex (a boundary vertex of a level cut along its
    /// sharp edges, the default mode) to the curve terms of its two crease segments
    /// ([`Driver::curve_trust`]), before the blend toward the linear rule of the interior
    /// points (`toward_linear.rs`), which then moves the interior points within the scheme's
    /// reach of such a vertex with it; whether any trust was lowered. Nothing on an untagged
    /// level or in literal mode.
    ///
    /// Why: the crease points move toward the linear curve rule by these terms
    /// ([`Driver::guard_curves`]), but the boundary stars are exempt from the a-priori star
    /// terms (`trust.rs`), so without this the interior points next to a moved crease point
    /// kept the paper's points: the reverse of the seam `Driver::crease_near_trust` closes,
    /// which folded next to the corners of tagged scanned meshes (`docs/creases.md`, "Folds
    /// next to corners"). The terms are functions of cross-ratios of the input, so the
    /// decision stays Möbius-invariant. A short curve ([`Driver::short_curve`]) keeps 1 here
    /// although its points take the linear curve rule: measured with 0 instead, the guard
    /// moved three to thirteen times the points on CAD meshes (polycastle_quad, fandisk),
    /// which fold no more than linear without it.
    pub(super) fn curve_terms_into_trust(&mut self) -> Result<bool> {
        if !self.guard || self.corners.is_empty() {
            return Ok(false);
        }
        let topo = self.topo;
        let mut lowered = false;
        for v in 0..topo.num_vertices() as u32 {
            if !topo.is_boundary_vertex(v)? {
                continue;
            }
            let out_h = topo.vertex_half_edge(v)?; // v → b0
            let in_h = topo.prev_boundary(out_h)?; // b1 → v
            let tau = self.curve_trust(out_h)?.min(self.curve_trust(in_h)?);
            let t = get(self.trust, v as usize)?;
            if tau < t {
                set(self.trust, v as usize, tau)?;
                lowered = true;
            }
        }
        Ok(lowered)
    }

    /// The trust the step's guard gave star `v` (`guard.rs`), at most 1: on a cut level the
    /// audit (`audit.rs`) judges a crease vertex's star as an open fan of its child faces,
    /// crease points included, and lowers its trust where they fold or collapse in its
    /// frame. 1 for a star that was not judged.
    fn star_trust(&self, v: u32) -> f64 {
        self.trust.get(v as usize).copied().unwrap_or(1.0).min(1.0)
    }

    /// The least trust of the elements near crease vertex `v` (an end of a crease edge
    /// point, or a crease vertex point): of the stars within `rings` rings of `v` (`v`
    /// included; [`Driver::star_trust`]), the reach of the blend toward the linear rule of the
    /// scheme's interior points (`toward_linear.rs`), and of the edges at those stars (their
    /// crease edge terms, `Driver::crease_edge_terms`, which move those edges' points). So a
    /// crease point moves with the interior points around it instead of keeping the paper's
    /// point between linear ones, a seam that folded next to the corners of tagged scanned
    /// meshes (`docs/creases.md`, "Folds next to corners"). Walked per point: only crease
    /// points ask, and only when some element is distrusted.
    fn crease_near_trust(&self, v: u32, rings: u8) -> Result<f64> {
        // Nested walks rather than recursion: the firmware's static stack bound needs a call
        // graph without cycles (`docs/firmware.md`). `rings` is at most 2 (`Outputs::rings`).
        let mut t = self.star_and_edges_trust(v)?;
        if rings > 0 {
            for s in self.topo.star(v) {
                t = t.min(self.star_and_edges_trust(s.neighbour)?);
                if rings > 1 {
                    for s2 in self.topo.star(s.neighbour) {
                        t = t.min(self.star_and_edges_trust(s2.neighbour)?);
                    }
                }
            }
        }
        Ok(t)
    }

    /// The half-edge on the other side of the crease from boundary half-edge `h` of a cut
    /// level, itself a boundary half-edge of the cut level (its twin on `Driver::uncut`);
    /// `NONE` on a boundary of the uncut level or without sharp features.
    fn across(&self, h: u32) -> u32 {
        self.uncut.and_then(|u| u.topo.twin(h).ok()).unwrap_or(NONE)
    }

    /// The trust of the crease edge point of boundary half-edge `h` seen from `h`'s side of
    /// the crease: the least of its segment's curve terms ([`Driver::curve_trust`]) and of
    /// the elements near its two ends ([`Driver::crease_near_trust`]); 1 for `NONE`.
    fn crease_edge_trust(&self, h: u32, rings: u8) -> Result<f64> {
        if h == NONE {
            return Ok(1.0);
        }
        let topo = self.topo;
        Ok(self
            .curve_trust(h)?
            .min(self.crease_near_trust(topo.origin(h)?, rings)?)
            .min(self.crease_near_trust(topo.dest(h)?, rings)?))
    }

    /// The least of star `v`'s trust and of the crease edge terms of the edges at `v`.
    fn star_and_edges_trust(&self, v: u32) -> Result<f64> {
        let mut t = self.star_trust(v);
        for s in self.topo.star(v) {
            t = t.min(self.edge_trust.get(s.edge as usize).copied().unwrap_or(1.0));
        }
        Ok(t)
    }

    /// The fold guard of the crease curves, after the rest of the step's guard (whose audit
    /// has read the paper's curve points): every edge point of a crease curve moves toward
    /// the linear curve rule `linear(P_{i−1}, a, b, P_{i+2})`, and with `approximating`
    /// every vertex point that is no corner toward the linear crease vertex rule
    /// `¾ v + ⅛ (b_0 + b_1)`, by `τ` as `toward_linear.rs` blends interior points
    /// (`τ² p + (1 − τ²) p_lin`: the linear rule at `τ = 0`, the paper's point at `τ = 1`,
    /// continuous between). `τ` of an edge point is the least of its segment's trust
    /// ([`Driver::curve_trust`]) and its two ends' star trusts, of a vertex point the least
    /// of its two segments' and its own star's: the crease points are the corners of the
    /// child faces the audit judged in those stars' frames. Every decision is a function of
    /// cross-ratios and of the audit's trusts, so it is the same on every Möbius image. The
    /// points it moves are counted as guarded (strict mode refuses the first). Nothing
    /// happens on an untagged level (the bits of the untagged step) or in literal mode; short
    /// curves keep the linear rule they took.
    ///
    /// With `both_sides` (Kobbelt), `τ` of an edge point is the least of the terms read
    /// from either side of its crease (`Driver::across`). Each side of the cut level
    /// computes the crease's edge point, with the trusts of its own side, and the uncut level
    /// reads one side's point back (`crease.rs`): where only the other side's interior points
    /// had moved toward the linear rule, the point kept the paper's place between them, a
    /// seam on that side. On horse_quad (30° tags) such an edge point lay 0.04 edge lengths
    /// off the linear one, nearly on the line from its crease neighbour to the face point of
    /// a thin quad beside it, and two levels folded that quad's corner
    /// (`docs/creases.md`, "Folds next to corners"). Both sides' terms are trusts of the
    /// audit and cross-ratios, so the decision stays Möbius-invariant. Measured on Loop and
    /// Butterfly it folded more at three levels of cow, and on Catmull–Clark it changed no
    /// count, so only Kobbelt takes it.
    pub(super) fn guard_curves(
        &mut self,
        start: usize,
        linear: fn(Point, Point, Point, Point) -> Point,
        approximating: bool,
        rings: u8,
        both_sides: bool,
    ) -> Result<()> {
        if !self.guard || self.corners.is_empty() {
            return Ok(());
        }
        // Without a distrusted star or edge every term is 1: no walks.
        let rings = if self.trust.iter().all(|&t| t >= 1.0) && !self.any_crease_edge_term() {
            0
        } else {
            rings
        };
        let topo = self.topo;
        if approximating {
            for v in 0..topo.num_vertices() as u32 {
                if !topo.is_boundary_vertex(v)? || self.is_corner(v) {
                    continue;
                }
                let out_h = topo.vertex_half_edge(v)?; // v → b0
                let in_h = topo.prev_boundary(out_h)?; // b1 → v
                if self.short_curve(out_h)? {
                    continue;
                }
                let tau = self
                    .curve_trust(out_h)?
                    .min(self.curve_trust(in_h)?)
                    .min(self.crease_near_trust(v, rings)?);
                if tau < 1.0 {
                    self.guarded(v as usize)?;
                    let (b0, b1) = (topo.dest(out_h)?, topo.origin(in_h)?);
                    let lin = crate::stencil::crease_vertex(
                        topo.position(v)?,
                        topo.position(b0)?,
                        topo.position(b1)?,
                    );
                    let p = get(self.pos, v as usize)?;
                    set(self.pos, v as usize, toward_linear(tau, p, lin))?;
                }
            }
        }
        for e in 0..topo.num_edges() as u32 {
            let h = topo.edge_half_edge(e)?;
            // A short curve, and a segment between two corners (its midpoint, `boundary_segment`),
            // already take the linear curve rule.
            if topo.twin(h)? != NONE || self.short_curve(h)? || self.corner_ends(h)? == (true, true)
            {
                continue;
            }
            let across = if both_sides { self.across(h) } else { NONE };
            let tau = self
                .crease_edge_trust(h, rings)?
                .min(self.crease_edge_trust(across, rings)?);
            if tau < 1.0 {
                let k = start + e as usize;
                self.guarded(k)?;
                let p = self.boundary_segment(h)?.0;
                let q = get(self.pos, k)?;
                set(
                    self.pos,
                    k,
                    toward_linear(tau, q, linear(p[0], p[1], p[2], p[3])),
                )?;
            }
        }
        Ok(())
    }

    /// Odd points of every boundary loop by the Möbius curve rule
    /// `F4(P_{i−1}, P_i, P_{i+1}, P_{i+2})` (open-curve rules next to corners,
    /// [`Driver::boundary_segment`]) into `start + edge`; fallback `linear(p0, a, b, p1)`.
    pub(super) fn boundary_edges(
        &mut self,
        start: usize,
        linear: fn(Point, Point, Point, Point) -> Point,
    ) -> Result<()> {
        let topo = self.topo;
        for e in 0..topo.num_edges() as u32 {
            let h = topo.edge_half_edge(e)?;
            if topo.twin(h)? != NONE {
                continue;
            }
            let (p, q) = self.boundary_segment(h)?;
            let k = start + e as usize;
            let q = match q {
                Ok(_) if self.short_curve(h)? => {
                    self.guarded(k)?;
                    linear(p[0], p[1], p[2], p[3])
                }
                Ok(q) => q,
                Err(_) => {
                    self.fallback(k)?;
                    linear(p[0], p[1], p[2], p[3])
                }
            };
            set(self.pos, k, q)?;
        }
        Ok(())
    }

    /// Even points of the boundary loops by the Möbius approximating rule
    /// `P'_i = F4(P_{i−1}, E_{i−½}, E_{i+½}, P_{i+1})`, reading the odd points from
    /// `start + edge`; fallback `3/4 v + 1/8 (b0 + b1)`. A corner keeps its position.
    pub(super) fn boundary_vertices_approximating(&mut self, start: usize) -> Result<()> {
        let topo = self.topo;
        for v in 0..topo.num_vertices() as u32 {
            if !topo.is_boundary_vertex(v)? {
                continue;
            }
            if self.is_corner(v) {
                set(self.pos, v as usize, topo.position(v)?)?;
                continue;
            }
            let out_h = topo.vertex_half_edge(v)?; // v → b0
            let in_h = topo.prev_boundary(out_h)?; // b1 → v
            let (b0, b1) = (topo.dest(out_h)?, topo.origin(in_h)?);
            let e_out = get(self.pos, start + topo.edge(out_h)? as usize)?;
            let e_in = get(self.pos, start + topo.edge(in_h)? as usize)?;
            let (p0, p1) = (topo.position(b1)?, topo.position(b0)?);
            if self.short_curve(out_h)? {
                self.guarded(v as usize)?;
                let q = crate::stencil::crease_vertex(topo.position(v)?, p1, p0);
                set(self.pos, v as usize, q)?;
                continue;
            }
            let q = match f4(p0, e_in, e_out, p1) {
                Ok(q) => q,
                Err(_) => {
                    self.fallback(v as usize)?;
                    crate::stencil::crease_vertex(topo.position(v)?, p1, p0)
                }
            };
            set(self.pos, v as usize, q)?;
        }
        Ok(())
    }
}
