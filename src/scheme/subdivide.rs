//! The one call that subdivides a mesh: any scheme, linear or Möbius, one level or many,
//! into caller buffers sized by [`super::plan`].

use super::levels::run;
use super::tags::Tags;
use super::weights::VertexWeights;
use super::Options;
#[cfg(doc)]
use crate::error::Status;
use crate::error::{Result, NO_ELEMENT};
use crate::exec::{Executor, Serial};
use crate::mesh::{Mesh, MeshOut, MeshSizes};
use crate::point::Point;

/// Caller scratch of [`subdivide`]: two typed buffers, `u32` entries (topologies and the
/// connectivity of intermediate levels) and points (positions of intermediate levels and
/// Möbius candidates), sized by [`Plan::scratch`](super::Plan::scratch). Two arrays rather
/// than one byte buffer: one byte buffer would need casts and an alignment rule (unsafe code
/// in the core) for no gain. Contents are unspecified after a call.
#[derive(Debug)]
pub struct Scratch<'a> {
    /// At least [`ScratchSizes::u32s`](super::ScratchSizes::u32s) entries.
    pub u32s: &'a mut [u32],
    /// At least [`ScratchSizes::points`](super::ScratchSizes::points) points.
    pub points: &'a mut [Point],
}

impl<'a> Scratch<'a> {
    /// Bundles the two scratch buffers.
    pub fn new(u32s: &'a mut [u32], points: &'a mut [Point]) -> Self {
        Scratch { u32s, points }
    }
}

/// What [`subdivide`] wrote and what the Möbius steps had to do besides the paper's rules.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Report {
    /// The sizes written (those of [`Plan::output`](super::Plan::output)).
    pub sizes: MeshSizes,
    /// Output vertices that took their linear rule (a degenerate neighbourhood of a Möbius
    /// step: coincident points, a star without a canonical form, a blend at infinity),
    /// summed over the levels; 0 for the linear schemes.
    pub fallbacks: u32,
    /// The first such vertex of the first level that had one (an index into that level), or
    /// [`NO_ELEMENT`].
    pub first_fallback: u32,
    /// That level, counted from 1, or 0 when there was no fallback.
    pub first_fallback_level: u32,
    /// Output vertices the fold guard changed (elements of a star whose canonical form is
    /// ill-conditioned, evaluated in a form interpolated toward the linear rule: seed 000
    /// §7.1, §7.2; [`Options::literal`]), summed over the levels; 0 for the literal and the
    /// linear schemes.
    pub guarded: u32,
    /// The first such vertex of the first level that had one, or [`NO_ELEMENT`].
    pub first_guarded: u32,
    /// That level, counted from 1, or 0 when the guard changed nothing.
    pub first_guarded_level: u32,
}

impl Report {
    /// The report of a call that wrote `sizes` without fallbacks.
    pub(crate) const fn empty(sizes: MeshSizes) -> Report {
        Report {
            sizes,
            fallbacks: 0,
            first_fallback: NO_ELEMENT,
            first_fallback_level: 0,
            guarded: 0,
            first_guarded: NO_ELEMENT,
            first_guarded_level: 0,
        }
    }
}

/// Subdivides `mesh` with `opts`: [`Options::levels`] steps of [`Options::scheme`], linear or
/// canonical Möbius ([`Options::mobius`]), the intermediate levels in `scratch`, the last in
/// `out`; zero levels validate the mesh and copy it. The result of `k` levels equals `k`
/// calls of one level, bit for bit. Buffer sizes come from [`plan`](super::plan()) with the
/// same `mesh` and `opts`; nothing is written to `out` before every size has been checked.
///
/// Output vertex order, faces and the per-scheme refusals are those of the module
/// documentation ([`crate::scheme`]).
///
/// # Errors
/// Those of [`plan`](super::plan()) (options, validation, the scheme's refusals, sizes), with
/// `scratch.u32s` as its scratch; then [`Status::BufferTooSmall`] with the needed size,
/// checked in the order `out.positions`, `out.offsets`, `out.indices`, `scratch.u32s`,
/// `scratch.points`; during a step: [`Status::FallbackInStrictMode`] (with
/// [`Options::strict`]) naming the output vertex of the level being computed,
/// [`Status::DegenerateGeometry`] ([`super::Scheme::Spherelike`]: coincident points of one
/// circle, or a spike) naming the output vertex, [`Status::NumericalFailure`] naming the
/// first output vertex that is not finite (coordinates near the ends of the `f64` range).
/// Contents of `out` and `scratch` are unspecified on error.
pub fn subdivide(
    mesh: Mesh<'_>,
    opts: &Options,
    scratch: Scratch<'_>,
    out: &mut MeshOut<'_>,
) -> Result<Report> {
    run(mesh, opts, &Tags::new(), None, scratch, out, &Serial)
}

/// [`subdivide`] with the passes of every step split into disjoint output ranges run by
/// `exec` ([`crate::exec`]): the std layer's threads, or a host's own pool. The output, the
/// report and the errors are those of [`subdivide`], bit for bit, for every executor and
/// every chunking; the core stays single-threaded (it only hands `exec` the chunks).
///
/// # Errors
/// Those of [`subdivide`].
pub fn subdivide_with(
    mesh: Mesh<'_>,
    opts: &Options,
    scratch: Scratch<'_>,
    out: &mut MeshOut<'_>,
    exec: &dyn Executor,
) -> Result<Report> {
    run(mesh, opts, &Tags::new(), None, scratch, out, exec)
}

/// [`subdivide`] for a mesh with sharp-feature tags ([`Tags`]): Loop and Catmull–Clark,
/// linear, with OpenSubdiv's rules for creases, corners and darts ([`crate::stencil::crease`]),
/// and linear Modified Butterfly and Kobbelt with their 4-point rule along the creases
/// (`docs/creases.md`), the tags carried to the child edges and vertices level by level.
/// Buffer sizes come from [`plan_tagged`](super::plan_tagged) with the same arguments. Empty
/// tags are [`subdivide`] exactly, bit for bit. The child levels' sharpness lives only
/// inside the call: `k` levels of a tagged mesh are one call of `k` levels (`k` calls of one
/// level would have to tag every intermediate level themselves).
///
/// # Errors
/// Those of [`plan_tagged`](super::plan_tagged) and [`subdivide`].
pub fn subdivide_tagged(
    mesh: Mesh<'_>,
    opts: &Options,
    tags: &Tags<'_>,
    scratch: Scratch<'_>,
    out: &mut MeshOut<'_>,
) -> Result<Report> {
    run(mesh, opts, tags, None, scratch, out, &Serial)
}

/// [`subdivide`] with everything a mesh may bring: sharp-feature tags (empty: none, as
/// [`subdivide_tagged`]), per-vertex weights of the Möbius–linear spectrum, and an executor
/// (as [`subdivide_with`]; [`Serial`](crate::exec::Serial) for the calling thread). Buffer
/// sizes come from [`plan_weighted`](super::plan_weighted) with the same arguments.
///
/// `weights` (seed 000 §7.2, [`VertexWeights`]): with [`Options::mobius`], a weight in
/// `[0, 1]` at every input vertex, of the Möbius result (`w`, [`VertexWeights::Mobius`]) or
/// of the linear one (`u = 1 − w`, [`VertexWeights::Linear`]), replacing the global
/// [`Options::spectrum`]. They are carried to every output vertex of every level like a
/// vertex attribute (an old vertex keeps its weight, an edge point takes the mean of its
/// edge's ends, a face point the mean of its corners, a Doo–Sabin corner point its parent
/// vertex's weight; the mean is exact for equal weights) and every output vertex of every
/// level is `w · (Möbius point) + (1 − w) · (linear point)` of that level's input. All 1 is
/// the Möbius result bit for bit, all 0 the linear one, all equal to `w` the global weight
/// `w`; an output vertex of weight exactly 0 or 1 takes the linear or the Möbius point of its
/// level exactly; the result is continuous in the weights. `None` is the global weight,
/// bit for bit. Checked, and without effect, for the linear schemes.
///
/// # Errors
/// Those of [`plan_weighted`](super::plan_weighted) and [`subdivide`]; nothing is written
/// before the weights are checked.
#[allow(clippy::too_many_arguments)] // the input, its three optional companions, the buffers
pub fn subdivide_weighted(
    mesh: Mesh<'_>,
    opts: &Options,
    tags: &Tags<'_>,
    weights: Option<VertexWeights<'_>>,
    scratch: Scratch<'_>,
    out: &mut MeshOut<'_>,
    exec: &dyn Executor,
) -> Result<Report> {
    run(mesh, opts, tags, weights, scratch, out, exec)
}
