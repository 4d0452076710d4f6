//! The subdivision schemes over whole meshes: the drivers own the topology walk and call a
//! rule on each neighbourhood, the linear rules of [`crate::stencil`] or their canonical
//! Möbius versions (seed 000 §4, [`mobius`]). The rules see one neighbourhood and never a
//! mesh, so a host mesh library with its own connectivity can call them directly; the
//! drivers are for callers whose mesh is a pair of index arrays.
//!
//! One level per call over caller buffers: [`subdivide_size`] gives the exact output sizes
//! before the call, [`subdivide`] writes one level. [`subdivide_mesh`] and
//! [`subdivide_mesh_size`] take the raw mesh slices and a scratch buffer
//! ([`scratch_len`]) for callers that do not keep a [`Topology`]; [`plan`] and
//! [`subdivide_levels`] run several levels, [`subdivide_levels_mobius`] several levels of the
//! Möbius version ([`mobius`]), through the same level loop. [`Scheme::Spherelike`] (seed 003
//! §3, [`spherelike`]) runs through the same one-level and multi-level entry points.
//!
//! Output vertex order, fixed so that hosts can map old vertices and know where each new point
//! comes from: primal schemes write the old vertices first at the same indices, then edge points in
//! edge-id order (edges sorted by `(min, max)` vertex key), then face points in face order; dual
//! schemes document their own order ([`crate::mesh::refine`]). Contents of the output buffers are
//! unspecified on error.
//!
//! # Where things are
//!
//! `size.rs` (the exact sizes of one step), `step.rs` (one step, and the internal step both
//! level paths call), `linear.rs` (the linear position rules), `spherelike.rs`,
//! `mobius/`, `levels.rs` (plans and the level loop), `carry.rs` (old vertices carried
//! through).

mod carry;
mod levels;
mod linear;
pub mod mobius;
mod size;
pub mod spherelike;
mod step;

pub use levels::{
    plan, plan_scratch_len, subdivide_levels, subdivide_levels_mobius, LevelPlan, LevelsReport,
    MAX_LEVELS,
};
pub use size::subdivide_size;
pub use step::subdivide;

use crate::error::Result;
use crate::mesh::refine::Pattern;
use crate::mesh::{topology_scratch_len, Mesh, MeshOut, MeshSizes, Topology};

/// A subdivision scheme. Codes are stable (the C ABI passes them as `uint32_t`).
#[repr(u32)]
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

    /// Whether the scheme has a canonical Möbius version (seed 000 §4; [`mobius`]). The
    /// spherelike scheme has none: its circle-blend rules keep circles by construction and
    /// are not built from a linear stencil that a canonical form could carry.
    pub const fn has_mobius_form(self) -> bool {
        !matches!(self, Scheme::Spherelike)
    }
}

/// Scratch (`u32` entries) that [`subdivide_mesh`] and [`subdivide_mesh_size`] need for
/// `mesh`: the topology of [`Topology::build`].
///
/// # Errors
/// [`crate::Status::SizeOverflow`].
pub fn scratch_len(mesh: &Mesh<'_>) -> Result<usize> {
    topology_scratch_len(mesh.num_vertices(), mesh.num_corners())
}

/// Validates `mesh` and returns the exact output sizes of one step of `scheme`.
///
/// # Errors
/// Any validation error of [`Topology::build`], then those of [`subdivide_size`].
pub fn subdivide_mesh_size(
    scheme: Scheme,
    mesh: Mesh<'_>,
    scratch: &mut [u32],
) -> Result<MeshSizes> {
    let topo = Topology::build(mesh, scratch)?;
    subdivide_size(scheme, &topo)
}

/// Validates `mesh` and writes one step of `scheme` into `out`; returns the sizes written.
/// This is the entry point for callers holding plain slices (an OFF reader, the C ABI).
///
/// # Errors
/// Any validation error of [`Topology::build`], then those of [`subdivide`].
pub fn subdivide_mesh(
    scheme: Scheme,
    mesh: Mesh<'_>,
    scratch: &mut [u32],
    out: &mut MeshOut<'_>,
) -> Result<MeshSizes> {
    let topo = Topology::build(mesh, scratch)?;
    subdivide(scheme, &topo, out)
}
