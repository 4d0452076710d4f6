//! What a differential-space subdivision is asked to do and what it reports: the stencil on
//! the differential mesh (seed 001 §4.2), the DirMag levels (§3.4), the solver options
//! (§3.5 step 4), the curvature and normal edits of §4.4 and the folds an edit made.

use super::solve::{SolveOptions, SolveReport};
use crate::error::NO_ELEMENT;
use crate::point::Point;
use crate::scheme::Scheme;

/// The linear stencil used on the differential mesh (and for the warm start).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stencil {
    /// Loop (approximating).
    Loop = 0,
    /// Modified Butterfly (interpolating; the paper's preferred choice, §4.2).
    ModifiedButterfly = 1,
}

impl Stencil {
    /// The stencil of a code.
    pub fn from_code(c: u32) -> Option<Stencil> {
        match c {
            0 => Some(Stencil::Loop),
            1 => Some(Stencil::ModifiedButterfly),
            _ => None,
        }
    }

    /// The linear mesh scheme of the stencil.
    pub(super) const fn scheme(self) -> Scheme {
        match self {
            Stencil::Loop => Scheme::Loop,
            Stencil::ModifiedButterfly => Scheme::ModifiedButterfly,
        }
    }

    /// Whether this build contains differential-space subdivision with this stencil: the
    /// crate's `differential` feature and the stencil's scheme ([`Scheme::is_built`]; normal
    /// editing steps with Loop, which the `differential` feature brings). Without it,
    /// [`plan`](super::plan()) and [`subdivide`](super::subdivide) return
    /// [`Status::SchemeNotBuilt`](crate::Status::SchemeNotBuilt) before reading anything,
    /// and the optimiser drops the method from the build.
    pub const fn is_built(self) -> bool {
        cfg!(feature = "differential") && self.scheme().is_built()
    }

    /// [`Status::SchemeNotBuilt`](crate::Status::SchemeNotBuilt) unless
    /// [`Stencil::is_built`].
    pub(super) fn check_built(self) -> crate::Result<()> {
        if self.is_built() {
            Ok(())
        } else {
            Err(crate::Error::new(crate::Status::SchemeNotBuilt))
        }
    }
}

/// Options of [`plan`](super::plan()) and [`subdivide`](super::subdivide).
#[derive(Clone, Copy, Debug)]
pub struct DifferentialOptions<'a> {
    /// The stencil on the differential mesh.
    pub stencil: Stencil,
    /// Subdivision levels `k` (at most [`MAX_LEVELS`](crate::scheme::MAX_LEVELS)).
    pub levels: usize,
    /// The first this many levels use DirMag (§3.4) with `stencil`; 0 for plain linear
    /// subdivision of `Δ`. Values above `levels` act as `levels`.
    pub dirmag_levels: usize,
    /// Solver tolerance and caps.
    pub solve: SolveOptions,
    /// §4.4 editing: per control vertex, a factor on its mean curvature `H_i`, applied to
    /// its differential coordinate before subdivision (`δ_i ← s_i δ_i`). Length = the control
    /// vertex count; finite values.
    pub curvature_scale: Option<&'a [f64]>,
    /// §4.4 editing: per control vertex, the surface normal it should have in the output (any
    /// finite length; normalised here). The vertex's neighbourhood is turned so that the
    /// surface normal at the vertex — the angle-weighted normal of its star in the output —
    /// is this direction (`normal_edit.rs`; docs/differential.md "Editing"). A zero vector
    /// leaves the vertex unedited. Length = the control vertex count.
    pub normals: Option<&'a [Point]>,
    /// With edits: turn folds ([`DifferentialReport::folded_faces`],
    /// [`DifferentialReport::folded_edges`]) into [`Status::FoldedSurface`](crate::Status)
    /// naming the first folded face of the output. Without edits it has no effect.
    pub strict: bool,
}

impl Default for DifferentialOptions<'_> {
    fn default() -> Self {
        DifferentialOptions {
            stencil: Stencil::Loop,
            levels: 1,
            dirmag_levels: 0,
            solve: SolveOptions::default(),
            curvature_scale: None,
            normals: None,
            strict: false,
        }
    }
}

/// What [`subdivide`](super::subdivide) did (also written when it returns
/// [`Status::NotConverged`](crate::Status::NotConverged) or
/// [`Status::FoldedSurface`](crate::Status::FoldedSurface)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DifferentialReport {
    /// The reconstruction's solver report (with edits: of the last, edited, solve).
    pub solve: SolveReport,
    /// DirMag outputs whose subdivided normal was too short to normalise.
    pub dirmag_degenerate: u32,
    /// Number of anchor rows (closed components + boundary loops + isolated vertices).
    pub anchors: u32,
    /// With edits: the solver report of the unedited reconstruction, which the edits are
    /// measured against (the fold census, and the normals a normal edit turns). Default
    /// (zero) without edits.
    pub reference_solve: SolveReport,
    /// With edits: output faces whose normal turned by more than 90° from the same face of
    /// the unedited reconstruction. 0 without edits.
    pub folded_faces: u32,
    /// The lowest such face, or [`NO_ELEMENT`].
    pub first_folded_face: u32,
    /// With edits: interior output edges whose two faces' normals are more than 90° apart,
    /// where they are not in the unedited reconstruction. 0 without edits.
    pub folded_edges: u32,
    /// The lowest such edge as its two vertices `[a, b]`, `a < b`, lowest in the order of
    /// `(a, b)`; `[NO_ELEMENT; 2]` when there is none.
    pub first_folded_edge: [u32; 2],
}

impl Default for DifferentialReport {
    fn default() -> Self {
        DifferentialReport {
            solve: SolveReport::default(),
            dirmag_degenerate: 0,
            anchors: 0,
            reference_solve: SolveReport::default(),
            folded_faces: 0,
            first_folded_face: NO_ELEMENT,
            folded_edges: 0,
            first_folded_edge: [NO_ELEMENT; 2],
        }
    }
}
