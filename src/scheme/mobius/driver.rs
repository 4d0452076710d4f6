//! The state of one Möbius subdivision step: the topology, the output positions, the
//! candidates the vertex pass leaves for the blends, and the report of fallbacks.
//!
//! Candidates live per half-edge: half-edge `h` starts at the vertex whose canonical form
//! produced them (seed 000 §4.1 step 3), so each slot has exactly one writer and the blends
//! (step 4) read the candidates of an edge's two ends, or of a face's corners, by
//! half-edge. The slots are in vertex-major order (`slots.rs`), so that a vertex range
//! owns a contiguous range of them.

use super::form::MISSING;
use super::guard::f64_ranges;
use super::slots::slot_of;
use super::{MobiusOptions, MobiusReport};
use crate::error::{Error, Result, Status, NO_ELEMENT};
use crate::exec::{pass, Executor, Tally};
use crate::mesh::Topology;
use crate::point::Point;

/// One step of a Möbius scheme in progress.
pub(super) struct Driver<'t, 'm, 's, 'o> {
    pub(super) topo: &'t Topology<'m, 's>,
    /// The output positions of the step (the sizes of the scheme's pattern).
    pub(super) pos: &'o mut [Point],
    /// At slot `slot(h)` of half-edge `h`: the candidate of `edge(h)` from the form of
    /// `origin(h)`.
    pub(super) edge_c: &'o mut [Point],
    /// At slot `slot(h)` of half-edge (corner) `h`: the candidate of `face(h)` from the form
    /// of `origin(h)`.
    pub(super) face_c: &'o mut [Point],
    /// Per half-edge: its slot in `edge_c` and `face_c` (`slots.rs`).
    pub(super) slots: &'o [f64],
    /// Per vertex: the fold guard's trust in its star (`trust.rs`), 1 where the paper's
    /// rules are kept.
    pub(super) trust: &'o mut [f64],
    /// Per vertex: the centre `c` and radius `r` of an interior star's canonical form, kept
    /// by the vertex pass for the fold guard's output audit (`audit.rs`); `r = 0` where
    /// there is none. After the audit (which keeps its own trust in the centres' first
    /// coordinates), the blend toward the linear rule keeps there the least trust of each
    /// closed 1-ring (radii) and 2-ring (centres) (`toward_linear.rs`).
    pub(super) centre: &'o mut [Point],
    pub(super) radius: &'o mut [f64],
    pub(super) report: MobiusReport,
    pub(super) strict: bool,
    /// Whether the fold guard runs (`guard.rs`).
    pub(super) guard: bool,
    /// Runs the passes that write disjoint output ranges (the blends, the vertex points'
    /// completion; [`crate::exec`]).
    pub(super) exec: &'o dyn Executor,
    /// Per vertex: non-zero where a boundary loop ends as an open curve (a corner of a
    /// sharp feature, `crease.rs`); empty without sharp features (`boundary.rs`).
    pub(super) corners: &'o [u32],
    /// The level before the cut (`crease.rs`; the half-edge ids of the cut level are those
    /// of the uncut one), so that the twin there of a boundary half-edge of a crease names
    /// the crease's half-edge on the other side, and the fold guard can take the linear rule
    /// with the level's tags (`drivers/butterfly.rs`); `None` on a level without tags (on a
    /// tagged level where nothing is cut, the level itself).
    pub(super) uncut: Option<super::crease::Uncut<'o>>,
    /// The star workspace of the vertex pass (`workspace.rs`): per chunk, the per-star
    /// arrays of the scheme's rule.
    pub(super) work: &'o mut [Point],
    /// The spoke workspace (`workspace.rs`): per chunk, the spokes of one star
    /// ([`super::form::Spokes`]).
    pub(super) spoke_work: &'o mut [u32],
    /// Per edge: the fold guard's F4-angle term, between the two passes of
    /// [`Driver::trust_edges`]; empty without the guard's scratch.
    pub(super) edge_trust: &'o mut [f64],
}

/// Sets every candidate [`MISSING`] and each `f64` array to its value, in the chunks of
/// `exec`, before a step builds its [`Driver`]: the candidate arrays are two points per
/// half-edge, tens of megabytes on a large level, and filling them was the largest serial
/// write of a step. Out of line, so that the passes' frames are not part of the step's
/// (`docs/firmware.md`, "Stack").
#[inline(never)]
pub(super) fn clear(
    exec: &dyn Executor,
    cands: [&mut [Point]; 2],
    values: [(&mut [f64], f64); 2],
) -> Result<()> {
    for c in cands {
        pass(exec, c, |_, out, _| {
            out.fill(MISSING);
            Ok(())
        })?;
    }
    for (out, v) in values {
        f64_ranges(exec, out, &|_, out: &mut [f64]| {
            out.fill(v);
            Ok(())
        })?;
    }
    Ok(())
}

impl<'t, 'm, 's, 'o> Driver<'t, 'm, 's, 'o> {
    /// A driver on `cands`, the edge and face candidates (every one [`MISSING`], by
    /// [`clear`]) and their slots (`slots.rs`), and `form`, the per-vertex trust (1), centres
    /// and radii (0) of the fold guard.
    pub(super) fn new(
        topo: &'t Topology<'m, 's>,
        pos: &'o mut [Point],
        cands: (&'o mut [Point], &'o mut [Point], &'o [f64]),
        form: (&'o mut [f64], &'o mut [Point], &'o mut [f64]),
        opts: MobiusOptions,
        exec: &'o dyn Executor,
    ) -> Self {
        let (edge_c, face_c, slots) = cands;
        let (trust, centre, radius) = form;
        Driver {
            topo,
            pos,
            edge_c,
            face_c,
            slots,
            trust,
            centre,
            radius,
            report: MobiusReport::default(),
            strict: opts.strict,
            guard: opts.guard,
            exec,
            corners: &[],
            uncut: None,
            work: &mut [],
            spoke_work: &mut [],
            edge_trust: &mut [],
        }
    }

    /// The slot of half-edge `h` in `edge_c` and `face_c`.
    #[inline(always)]
    pub(super) fn slot(&self, h: u32) -> Result<usize> {
        slot_of(self.slots, h)
    }

    /// Adds the fallbacks a pass counted ([`crate::exec::pass`]) to the report.
    pub(super) fn add_fallbacks(&mut self, t: Tally) {
        let r = &mut self.report;
        let merged = Tally {
            count: r.fallbacks,
            first: r.first_fallback,
        }
        .merge(t);
        r.fallbacks = merged.count;
        r.first_fallback = merged.first;
    }

    /// Counts a fallback at output vertex `element`, or fails in strict mode.
    pub(super) fn fallback(&mut self, element: usize) -> Result<()> {
        let e = element as u32;
        if self.strict {
            return Err(Error::at(Status::FallbackInStrictMode, e));
        }
        self.report.fallbacks = self.report.fallbacks.saturating_add(1);
        if self.report.first_fallback == NO_ELEMENT || e < self.report.first_fallback {
            self.report.first_fallback = e;
        }
        Ok(())
    }

    /// Counts output vertex `element` as changed by the fold guard, or fails in strict mode
    /// (the guard is a fallback toward the linear rule, so it shares the fallback's status).
    pub(super) fn guarded(&mut self, element: usize) -> Result<()> {
        let e = element as u32;
        if self.strict {
            return Err(Error::at(Status::FallbackInStrictMode, e));
        }
        self.report.guarded = self.report.guarded.saturating_add(1);
        if self.report.first_guarded == NO_ELEMENT || e < self.report.first_guarded {
            self.report.first_guarded = e;
        }
        Ok(())
    }
}

/// Counts a fallback at output vertex `element` in the tally of one chunk of a pass, or fails
/// in strict mode ([`Driver::fallback`] for a pass split into chunks).
pub(super) fn chunk_fallback(strict: bool, t: &mut Tally, element: usize) -> Result<()> {
    let e = element as u32;
    if strict {
        return Err(Error::at(Status::FallbackInStrictMode, e));
    }
    t.add(e);
    Ok(())
}
