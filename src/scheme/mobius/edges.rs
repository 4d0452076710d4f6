//! Edge points from the edge candidates of the two end points' stars (seed 000 §4.4.3):
//! `F4(v_j, e_j, e_k, v_k)` with the apex as hint ([`f4_hinted`]: the negative-real case
//! takes its axis from a 1-ring vertex, so the point stays on the sphere of the surface,
//! Lemma A.1). An edge with a single candidate takes it; an edge with none, or whose blend
//! fails, takes its linear rule, counted as a fallback.

use arrayvec::ArrayVec;

use super::driver::Driver;
use super::form::present;
use crate::blend::f4_hinted;
use crate::error::Result;
use crate::mesh::{get, internal, set, NONE};
use crate::point::{self, Point};

/// Edges gathered per batch by [`Driver::blend_interior_edges`].
const EDGE_CHUNK: usize = 32;

/// What the F4 of one interior edge `e = (a, b)` reads: its end points, the candidates of the
/// stars of `a` and `b`, and the hint (the apex of the face on the left of `a → b`).
#[derive(Clone, Copy)]
struct EdgeInputs {
    e: u32,
    a: Point,
    b: Point,
    ca: Point,
    cb: Point,
    hint: Point,
}

impl Driver<'_, '_, '_, '_> {
    /// Blends the interior edges' candidates with `F4(v_j, e_j, e_k, v_k)` into `start + e`;
    /// an edge with a single candidate takes it; `linear(e)` is the fallback when neither star
    /// gives one.
    pub(super) fn blend_interior_edges(
        &mut self,
        start: usize,
        linear: &dyn Fn(&Self, u32) -> Result<Point>,
    ) -> Result<()> {
        let topo = self.topo;
        let ne = topo.num_edges() as u32;
        // Gather, then blend, `EDGE_CHUNK` edges at a time: the gathering reads the twin and
        // the two candidates of each edge at scattered addresses, and in one loop of short
        // independent iterations those cache misses overlap; between two F4 evaluations
        // (hundreds of instructions each) they would not. The same blends in the same order,
        // the same fallbacks; only a failing topology lookup (an internal error, never a
        // fallback) is reported before a strict-mode fallback earlier in its batch.
        let mut chunk = ArrayVec::<EdgeInputs, EDGE_CHUNK>::new();
        let mut first = 0;
        while first < ne {
            let last = ne.min(first.saturating_add(EDGE_CHUNK as u32));
            chunk.clear();
            for e in first..last {
                let h = topo.edge_half_edge(e)?;
                let t = topo.twin(h)?;
                if t == NONE {
                    continue;
                }
                chunk
                    .try_push(EdgeInputs {
                        e,
                        a: topo.position(topo.origin(h)?)?,
                        b: topo.position(topo.dest(h)?)?,
                        ca: get(self.edge_c, h as usize)?,
                        cb: get(self.edge_c, t as usize)?,
                        hint: topo.position(topo.dest(topo.next(h)?)?)?,
                    })
                    .map_err(|_| internal())?;
            }
            for x in &chunk {
                let EdgeInputs {
                    e,
                    a,
                    b,
                    ca,
                    cb,
                    hint,
                } = *x;
                let k = start + e as usize;
                let p = if present(&ca) && present(&cb) {
                    f4_hinted(a, ca, cb, b, hint).ok()
                } else if present(&ca) {
                    // One star gave no candidate (Butterfly next to an irregular vertex, §4.3;
                    // or a star whose form sends a needed vertex to infinity, like a square
                    // corner): the other star's candidate, Möbius-invariant like the ear rule.
                    Some(ca)
                } else if present(&cb) {
                    Some(cb)
                } else {
                    None
                };
                let p = match p {
                    Some(p) if point::is_finite(&p) => p,
                    _ => {
                        self.fallback(k)?;
                        linear(self, e)?
                    }
                };
                set(self.pos, k, p)?;
            }
            first = last;
        }
        Ok(())
    }
}
