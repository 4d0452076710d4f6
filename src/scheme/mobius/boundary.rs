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
