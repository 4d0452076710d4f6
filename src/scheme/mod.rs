//! The subdivision schemes over whole meshes: the drivers own the topology walk and call a
//! rule on each neighbourhood, the linear rules of [`crate::stencil`] or their canonical
//! Möbius versions (seed 000 §4, [`mobius`]). The rules see one neighbourhood and never a
//! mesh, so a host mesh library with its own connectivity can call them directly (the star
//! rules of [`mobius`]); the drivers are for callers whose mesh is a pair of index arrays.
//!
//! # One path: options → plan → subdivide
//!
//! [`Options`] names the scheme, linear or Möbius ([`Options::mobius`]), strictness about
//! Möbius fallbacks and the number of levels. [`plan`] validates the mesh (its topology in
//! [`plan_scratch_size`] `u32` entries of scratch) and returns a [`Plan`]: the exact sizes of
//! every level and the exact scratch ([`ScratchSizes`]) of [`subdivide`], which then writes
//! the last level into the caller's [`MeshOut`](crate::mesh::MeshOut), the intermediate
//! levels in the caller's [`Scratch`], and returns a [`Report`]. Parameters come in the order
//! input, options, scratch, output. [`Scheme::Spherelike`] (seed 003 §3, [`spherelike`]) runs
//! through the same path. A mesh with sharp-feature tags ([`Tags`]: creases and corners with
//! OpenSubdiv's conventions, for Loop, Catmull–Clark, Modified Butterfly and Kobbelt, linear
//! or Möbius) takes
//! [`plan_tagged`] and [`subdivide_tagged`], the same path with the tags next to the mesh.
//!
//! Sizes are counted in elements of the buffer they size (points, `u32` entries, faces); a
//! function named `…_size` returns an exact size, one named `…_bound` a worst case.
//!
//! Output vertex order, fixed so that hosts can map old vertices and know where each new point
//! comes from: primal schemes write the old vertices first at the same indices, then edge points in
//! edge-id order (edges sorted by `(min, max)` vertex key), then face points in face order; dual
//! schemes document their own order ([`crate::mesh::refine`]). Contents of the output buffers are
//! unspecified on error.
//!
//! # Where things are
//!
//! The public path: `options.rs` ([`Options`]), `plan.rs` ([`plan`], [`Plan`],
//! [`ScratchSizes`]), `subdivide.rs` ([`subdivide`], [`Scratch`], [`Report`]), `built.rs`
//! (which schemes this build contains: the Cargo features, [`Scheme::is_built`]). Behind it:
//! `levels.rs` (the level loop and where it keeps the levels in the scratch), `step.rs` (one
//! step on a built topology, the one function every level goes through), `size.rs` (the
//! exact sizes of one step), `linear.rs` (the linear position rules), `spherelike.rs`,
//! `mobius/`, `carry.rs` (old vertices carried through), `tags.rs` (sharp-feature tags:
//! validation, the sharpness of each level), `linear_tagged.rs` (Loop and Catmull–Clark
//! with sharp features), `interpolating_tagged.rs` (Modified Butterfly and Kobbelt with sharp
//! features).

mod built;
mod carry;
mod interpolating_tagged;
mod levels;
mod linear;
mod linear_tagged;
pub mod mobius;
mod options;
mod plan;
mod size;
pub mod spherelike;
mod step;
mod subdivide;
mod tags;
mod weights;

pub use crate::stencil::crease::CreaseMethod;
pub use levels::MAX_LEVELS;
pub use options::Options;
pub use plan::{
    plan, plan_scratch_size, plan_scratch_size_tagged, plan_tagged, plan_weighted, Plan,
    ScratchSizes,
};
pub use subdivide::{
    subdivide, subdivide_tagged, subdivide_weighted, subdivide_with, Report, Scratch,
};
pub use tags::Tags;
pub use weights::VertexWeights;

pub(crate) use plan::plan_levels;
pub(crate) use step::linear_with as step_linear_with;

use crate::error::Result;
use crate::mesh::refine::Pattern;
use crate::mesh::Mesh;

/// A subdivision scheme. Codes are stable (the C ABI passes them as `uint32_t`).
///
/// `#[non_exhaustive]`: a later version may add a scheme (a new code, never a changed one), so
/// a `match` outside this crate needs a wildcard arm; [`Scheme::ALL`] lists every scheme.
#[repr(u32)]
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Scheme {
    /// Loop (triangles; 1→4; approximating).
    Loop = 0,
    /// Catmull–Clark (any polygons → quads; approximating).
    CatmullClark = 1,
    /// Modified Butterfly (triangles; 1→4; interpolating).
    ModifiedButterfly = 2,
    /// Kobbelt's interpolatory quad scheme (quads; interpolating).
    Kobbelt = 3,
    /// Doo–Sabin (any polygons; dual, corner cutting).
    DooSabin = 4,
    /// Peters–Reif simplest (mid-edge) scheme (any polygons).
    Simplest = 5,
    /// Akleman's dual (any polygons).
    Dual = 6,
    /// Akleman's vertex insertion (any polygons → triangles).
    VertexInsertion = 7,
    /// Akleman's dual truncation (any polygons → triangles, √3 connectivity).
    DualTruncation = 8,
    /// Spherelike interpolating subdivision (seed 003 §3): circle-blend edge and face rules,
    /// any polygons → quads; interpolating; no Möbius form ([`spherelike`]).
    Spherelike = 9,
}

impl Scheme {
    /// Every scheme, in code order.
    pub const ALL: [Scheme; 10] = [
        Scheme::Loop,
        Scheme::CatmullClark,
        Scheme::ModifiedButterfly,
        Scheme::Kobbelt,
        Scheme::DooSabin,
        Scheme::Simplest,
        Scheme::Dual,
        Scheme::VertexInsertion,
        Scheme::DualTruncation,
        Scheme::Spherelike,
    ];

    /// The stable numeric code.
    pub const fn code(self) -> u32 {
        self as u32
    }

    /// The scheme of a code, `None` for an unknown one.
    pub fn from_code(code: u32) -> Option<Scheme> {
        Scheme::ALL.iter().copied().find(|s| s.code() == code)
    }

    /// The command-line name (the scheme names of the `nlsubdiv` command and of the docs).
    pub const fn name(self) -> &'static str {
        match self {
            Scheme::Loop => "loop",
            Scheme::CatmullClark => "catmull-clark",
            Scheme::ModifiedButterfly => "butterfly",
            Scheme::Kobbelt => "kobbelt",
            Scheme::DooSabin => "doo-sabin",
            Scheme::Simplest => "simplest",
            Scheme::Dual => "dual",
            Scheme::VertexInsertion => "vertex-insertion",
            Scheme::DualTruncation => "dual-truncation",
            Scheme::Spherelike => "spherelike",
        }
    }

    /// The scheme of a command-line name.
    pub fn from_name(name: &str) -> Option<Scheme> {
        Scheme::ALL.iter().copied().find(|s| s.name() == name)
    }

    /// The refinement pattern of one step.
    pub const fn pattern(self) -> Pattern {
        match self {
            Scheme::Loop | Scheme::ModifiedButterfly => Pattern::Split1To4,
            Scheme::CatmullClark | Scheme::Kobbelt | Scheme::Spherelike => Pattern::Quads,
            Scheme::DooSabin => Pattern::CornerCut,
            Scheme::Simplest => Pattern::MidEdge,
            Scheme::Dual => Pattern::Dual,
            Scheme::VertexInsertion => Pattern::VertexInsertion,
            Scheme::DualTruncation => Pattern::DualTruncation,
        }
    }

    /// Whether old vertices keep their positions bit for bit.
    pub const fn is_interpolating(self) -> bool {
        matches!(
            self,
            Scheme::ModifiedButterfly
                | Scheme::Kobbelt
                | Scheme::VertexInsertion
                | Scheme::Spherelike
        )
    }

    /// Whether the scheme takes sharp-feature tags ([`plan_tagged`], `docs/creases.md`):
    /// Loop and Catmull–Clark (OpenSubdiv's rules), Modified Butterfly and Kobbelt (their
    /// 4-point boundary rule along the creases); their Möbius versions too (the Möbius curve
    /// rules along the creases, [`mobius`]).
    pub const fn takes_tags(self) -> bool {
        matches!(
            self,
            Scheme::Loop | Scheme::CatmullClark | Scheme::ModifiedButterfly | Scheme::Kobbelt
        )
    }

    /// Whether the scheme has a canonical Möbius version (seed 000 §4; [`mobius`]). The
    /// spherelike scheme has none: its circle-blend rules keep circles by construction and
    /// are not built from a linear stencil that a canonical form could carry.
    pub const fn has_mobius_form(self) -> bool {
        !matches!(self, Scheme::Spherelike)
    }
}

/// The `u32` scratch of [`plan`] ([`plan_scratch_size`]), under the name differential-space
/// subdivision calls.
pub(crate) fn scratch_size(mesh: &Mesh<'_>) -> Result<usize> {
    plan_scratch_size(mesh)
}
