//! Boundary loops as curves (seed 000 §4.3 "Boundary curves", §4.4.1): every boundary loop is
//! subdivided as a closed curve through its vertices, with the Möbius approximating curve
//! rule for approximating schemes (odd `E_{i+½} = F4(P_{i−1}, P_i, P_{i+1}, P_{i+2})`, even
//! `P'_i = F4(P_{i−1}, E_{i−½}, E_{i+½}, P_{i+1})`) and the interpolating rule (odd points
//! only) for the others, the Möbius counterparts of the linear schemes' boundary curves (the
//! cubic B-spline crease rule, the 4-point rule).

use super::driver::Driver;
use crate::blend::f4;
use crate::error::Result;
use crate::mesh::{get, set, NONE};
use crate::point::Point;

impl Driver<'_, '_, '_, '_> {
    /// The boundary neighbours of boundary half-edge `h = (a → b)`: `(P_{i−1}, P_{i+2})`.
    pub(super) fn boundary_outer(&self, h: u32) -> Result<(u32, u32)> {
        let topo = self.topo;
        Ok((
            topo.origin(topo.prev_boundary(h)?)?,
            topo.dest(topo.next_boundary(h)?)?,
        ))
    }

    /// Odd points of every boundary loop by the Möbius curve rule
    /// `F4(P_{i−1}, P_i, P_{i+1}, P_{i+2})` into `start + edge`; fallback `linear(p0, a, b, p1)`.
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
            let (i0, i3) = self.boundary_outer(h)?;
            let p = [
                topo.position(i0)?,
                topo.position(topo.origin(h)?)?,
                topo.position(topo.dest(h)?)?,
                topo.position(i3)?,
            ];
            let k = start + e as usize;
            let q = match f4(p[0], p[1], p[2], p[3]) {
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
    /// `start + edge`; fallback `3/4 v + 1/8 (b0 + b1)`.
    pub(super) fn boundary_vertices_approximating(&mut self, start: usize) -> Result<()> {
        let topo = self.topo;
        for v in 0..topo.num_vertices() as u32 {
            if !topo.is_boundary_vertex(v)? {
                continue;
            }
            let out_h = topo.vertex_half_edge(v)?; // v → b0
            let in_h = topo.prev_boundary(out_h)?; // b1 → v
            let (b0, b1) = (topo.dest(out_h)?, topo.origin(in_h)?);
            let e_out = get(self.pos, start + topo.edge(out_h)? as usize)?;
            let e_in = get(self.pos, start + topo.edge(in_h)? as usize)?;
            let (p0, p1) = (topo.position(b1)?, topo.position(b0)?);
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
