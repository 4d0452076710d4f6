//! Boundaries: the two boundary neighbours of a boundary vertex and the boundary loops, which
//! follow the boundary half-edges (face on their left). The schemes subdivide every boundary
//! loop as a curve.

use super::Topology;
use crate::error::{Error, Result, Status};
use crate::mesh::{get, internal, set, NONE};
use crate::MAX_VALENCE;

impl Topology<'_, '_> {
    /// For a boundary vertex, its two boundary neighbours `(b0, b1)`: `b0` at the end of its
    /// outgoing boundary half-edge, `b1` at the start of its incoming one.
    pub fn boundary_neighbours(&self, v: u32) -> Result<(u32, u32)> {
        let h = self.vertex_half_edge(v)?;
        if h == NONE || self.twin(h)? != NONE {
            return Err(Error::at(Status::InvalidArgument, v));
        }
        let b0 = self.dest(h)?;
        let incoming = self.prev_boundary(h)?;
        Ok((b0, self.origin(incoming)?))
    }

    /// For a boundary half-edge `h`, the next boundary half-edge along its loop (it starts
    /// where `h` ends).
    pub fn next_boundary(&self, h: u32) -> Result<u32> {
        self.vertex_half_edge(self.dest(h)?)
    }

    /// For a boundary half-edge `h`, the previous boundary half-edge along its loop.
    pub fn prev_boundary(&self, h: u32) -> Result<u32> {
        // Walk clockwise around origin(h) from h to the incoming boundary half-edge.
        let mut p = self.prev(h)?;
        for _ in 0..=MAX_VALENCE {
            let t = self.twin(p)?;
            if t == NONE {
                return Ok(p);
            }
            p = self.prev(t)?;
        }
        Err(internal())
    }

    /// Labels every boundary half-edge with its loop id in `mark` (at least
    /// [`num_half_edges`](Self::num_half_edges) entries; [`NONE`] for interior half-edges) and
    /// returns the number of boundary loops. Loops are numbered in the order of their
    /// lowest half-edge.
    pub fn boundary_loops(&self, mark: &mut [u32]) -> Result<usize> {
        let nh = self.num_half_edges();
        let mark = mark.get_mut(..nh).ok_or(Error::too_small(nh))?;
        for m in mark.iter_mut() {
            *m = NONE;
        }
        let mut loops = 0usize;
        for h in 0..nh as u32 {
            if self.twin(h)? != NONE || get(mark, h as usize)? != NONE {
                continue;
            }
            let mut g = h;
            for _ in 0..=nh {
                set(mark, g as usize, loops as u32)?;
                g = self.next_boundary(g)?;
                if g == h {
                    break;
                }
            }
            loops += 1;
        }
        Ok(loops)
    }
}
