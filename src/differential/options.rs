//! What a differential-space subdivision is asked to do and what it reports: the stencil on
//! the differential mesh (seed 001 §4.2), the DirMag levels (§3.4), the solver options
//! (§3.5 step 4) and the curvature edits of §4.4.

use super::solve::{SolveOptions, SolveReport};
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
    /// §4.4 editing: per control vertex, a factor on its mean curvature `H_i` (length = the
    /// control vertex count).
    pub curvature_scale: Option<&'a [f64]>,
    /// §4.4 editing: per control vertex, a replacement normal direction (normalised here);
    /// a zero vector keeps the vertex's own normal. Length = the control vertex count.
    pub normals: Option<&'a [Point]>,
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
        }
    }
}

/// What [`subdivide`](super::subdivide) did (also written when it returns
/// [`Status::NotConverged`](crate::Status::NotConverged)).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DifferentialReport {
    /// The reconstruction's solver report.
    pub solve: SolveReport,
    /// DirMag outputs whose subdivided normal was too short to normalise.
    pub dirmag_degenerate: u32,
    /// Number of anchor rows (closed components + boundary loops + isolated vertices).
    pub anchors: u32,
}
