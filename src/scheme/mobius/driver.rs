//! The state of one Möbius subdivision step: the topology, the output positions, the
//! candidates the vertex pass leaves for the blends, and the report of fallbacks.
//!
//! Candidates live per half-edge: half-edge `h` starts at the vertex whose canonical form
//! produced them (seed 000 §4.1 step 3), so each slot has exactly one writer and the blends
//! (step 4) read the candidates of an edge's two ends, or of a face's corners, by
//! half-edge.

use super::form::MISSING;
use super::{MobiusOptions, MobiusReport};
use crate::error::{Error, Result, Status, NO_ELEMENT};
use crate::mesh::Topology;
use crate::point::Point;

/// One step of a Möbius scheme in progress.
pub(super) struct Driver<'t, 'm, 's, 'o> {
    pub(super) topo: &'t Topology<'m, 's>,
    /// The output positions of the step (the sizes of the scheme's pattern).
    pub(super) pos: &'o mut [Point],
    /// Per half-edge `h`: the candidate of `edge(h)` from the form of `origin(h)`.
    pub(super) edge_c: &'o mut [Point],
    /// Per half-edge (corner) `h`: the candidate of `face(h)` from the form of `origin(h)`.
    pub(super) face_c: &'o mut [Point],
    /// Per vertex: the fold guard's trust in its star (`trust.rs`), 1 where the paper's
    /// rules are kept.
    pub(super) trust: &'o mut [f64],
    pub(super) report: MobiusReport,
    pub(super) strict: bool,
    /// Whether the fold guard runs (`guard.rs`).
    pub(super) guard: bool,
}

impl<'t, 'm, 's, 'o> Driver<'t, 'm, 's, 'o> {
    /// A driver with every candidate [`MISSING`].
    pub(super) fn new(
        topo: &'t Topology<'m, 's>,
        pos: &'o mut [Point],
        edge_c: &'o mut [Point],
        face_c: &'o mut [Point],
        trust: &'o mut [f64],
        opts: MobiusOptions,
    ) -> Self {
        for c in edge_c.iter_mut().chain(face_c.iter_mut()) {
            *c = MISSING;
        }
        for t in trust.iter_mut() {
            *t = 1.0;
        }
        Driver {
            topo,
            pos,
            edge_c,
            face_c,
            trust,
            report: MobiusReport::default(),
            strict: opts.strict,
            guard: opts.guard,
        }
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
