//! Edge points from the edge candidates of the two end points' stars (seed 000 §4.4.3):
//! `F4(v_j, e_j, e_k, v_k)` with the apex as hint ([`f4_hinted`]: the negative-real case
//! takes its axis from a 1-ring vertex, so the point stays on the sphere of the surface,
//! Lemma A.1). An edge with a single candidate takes it; an edge with none, or whose blend
//! fails, takes its linear rule, counted as a fallback.

use arrayvec::ArrayVec;

use super::driver::{chunk_fallback, Driver};
use super::form::{present, MISSING};
use super::slots::slot_of;
use crate::blend::f4_hinted;
use crate::error::Result;
use crate::exec::pass;
use crate::mesh::{get, internal, set, Topology, NONE};
use crate::point::{self, Point};

/// Edges gathered per batch by [`Driver::blend_interior_edges`]: 128 bytes each on the
/// stack. 12 keeps the batch at 1.5 KiB (docs/firmware.md, "Stack"); larger batches measured
/// no faster (one thread, interleaved best of 11, Loop / Butterfly on epcot, 4 levels: 16
/// edges 104.6 / 196.1 ms, 12 edges 100.9 / 185.2 ms; 32 against 16, Loop: 103.7 against
/// 102.9 ms).
const EDGE_CHUNK: usize = 8;

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

/// The linear rule of an interior edge, the fallback of its blend.
pub(super) type LinearEdge<'f> = dyn Fn(&Topology<'_, '_>, u32) -> Result<Point> + Sync + 'f;

impl Driver<'_, '_, '_, '_> {
    /// Blends the interior edges' candidates with `F4(v_j, e_j, e_k, v_k)` into `start + e`;
    /// an edge with a single candidate takes it; `linear(e)` is the fallback when neither star
    /// gives one. One pass over the edges, split into edge ranges ([`crate::exec`]).
    pub(super) fn blend_interior_edges(
        &mut self,
        start: usize,
        linear: &LinearEdge<'_>,
    ) -> Result<()> {
        self.blend_edges(start, linear, false)
    }

    /// [`Driver::blend_interior_edges`] again after the fold guard's re-evaluation (step 6
    /// of `guard.rs`). With `near_distrusted` (see [`Driver::rewind_for_blends_again`]) only
    /// the edges with an end whose trust is below 1 are blended: the guarded pass rewrote
    /// the candidates of such stars only, so every other edge reads the same inputs as in
    /// the first blends and keeps their point, bit for bit.
    pub(super) fn blend_interior_edges_again(
        &mut self,
        start: usize,
        linear: &LinearEdge<'_>,
        near_distrusted: bool,
    ) -> Result<()> {
        self.blend_edges(start, linear, near_distrusted)
    }

    fn blend_edges(
        &mut self,
        start: usize,
        linear: &LinearEdge<'_>,
        near_distrusted: bool,
    ) -> Result<()> {
        let topo = self.topo;
        let ne = topo.num_edges();
        let edge_c: &[Point] = self.edge_c;
        let slots: &[f64] = self.slots;
        let corners: &[u32] = self.corners;
        let only: Option<&[f64]> = near_distrusted.then_some(&*self.trust);
        let strict = self.strict;
        let out = self.pos.get_mut(start..start + ne).ok_or(internal())?;
        let t = pass(self.exec, out, |first, out, tally| {
            let mut f = |k: usize| chunk_fallback(strict, tally, start + k);
            let inputs = EdgeSources {
                edge_c,
                slots,
                corners,
                only,
            };
            blend_edge_range(topo, inputs, first, out, &mut f, linear)
        })?;
        self.add_fallbacks(t);
        Ok(())
    }
}

/// What [`blend_edge_range`] reads besides the topology: the edge candidates and their
/// slots, the corner flags, and with `only` the star trusts that pick the edges to blend
/// (an edge with an end below 1).
#[derive(Clone, Copy)]
struct EdgeSources<'a> {
    edge_c: &'a [Point],
    slots: &'a [f64],
    corners: &'a [u32],
    only: Option<&'a [f64]>,
}

/// The interior edge points of edges `first..first + out.len()` (boundary edges untouched,
/// and with `src.only` the edges whose ends both have trust 1 or more), `fallback(e)`
/// counting an edge that takes `linear(e)`.
fn blend_edge_range(
    topo: &Topology<'_, '_>,
    src: EdgeSources<'_>,
    first: usize,
    out: &mut [Point],
    fallback: &mut dyn FnMut(usize) -> Result<()>,
    linear: &LinearEdge<'_>,
) -> Result<()> {
    // Gather, then blend, `EDGE_CHUNK` edges at a time: the gathering reads the twin and the
    // two candidates of each edge at scattered addresses, and in one loop of short
    // independent iterations those cache misses overlap; between two F4 evaluations
    // (hundreds of instructions each) they would not. The same blends in the same order,
    // the same fallbacks; only a failing topology lookup (an internal error, never a
    // fallback) is reported before a strict-mode fallback earlier in its batch. Batches end
    // at multiples of `EDGE_CHUNK` edge ids whatever the range, so that order does not depend
    // on the chunking either.
    let mut batch = ArrayVec::<EdgeInputs, EDGE_CHUNK>::new();
    let end = first + out.len();
    let mut lo = first;
    while lo < end {
        let hi = end.min((lo / EDGE_CHUNK + 1) * EDGE_CHUNK);
        batch.clear();
        for e in lo as u32..hi as u32 {
            let h = topo.edge_half_edge(e)?;
            let t = topo.twin(h)?;
            if t == NONE {
                continue;
            }
            let (va, vb) = (topo.origin(h)?, topo.dest(h)?);
            if let Some(trust) = src.only {
                if get(trust, va as usize)? >= 1.0 && get(trust, vb as usize)? >= 1.0 {
                    continue;
                }
            }
            let EdgeSources {
                edge_c,
                slots,
                corners,
                ..
            } = src;
            // Next to a corner of a sharp feature (`crease.rs`), the other end's candidate
            // alone where it has one (unless it is a corner too): a corner is no smooth
            // point, and its sector's form extrapolates one (docs/creases.md).
            let corner = |v: u32| corners.get(v as usize).is_some_and(|&c| c != 0);
            let (mut ca, mut cb) = (
                get(edge_c, slot_of(slots, h)?)?,
                get(edge_c, slot_of(slots, t)?)?,
            );
            if corner(va) && !corner(vb) && present(&cb) {
                ca = MISSING;
            } else if corner(vb) && !corner(va) && present(&ca) {
                cb = MISSING;
            }
            batch
                .try_push(EdgeInputs {
                    e,
                    a: topo.position(va)?,
                    b: topo.position(vb)?,
                    ca,
                    cb,
                    hint: topo.position(topo.dest(topo.next(h)?)?)?,
                })
                .map_err(|_| internal())?;
        }
        for x in &batch {
            let EdgeInputs {
                e,
                a,
                b,
                ca,
                cb,
                hint,
            } = *x;
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
                    fallback(e as usize)?;
                    linear(topo, e)?
                }
            };
            set(out, e as usize - first, p)?;
        }
        lo = hi;
    }
    Ok(())
}
