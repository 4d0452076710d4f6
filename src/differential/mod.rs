//! Differential-space subdivision of triangle meshes (seed 001 §3, "Differential space
//! subdivision"; Zhu, Wang et al. 2011).
//!
//! Instead of the positions, the *differential coordinates* (discrete mean-curvature
//! normals) are subdivided, and the surface is reconstructed from them once, at the last
//! level (§4.1 "Computation in the reconstruction": one linear system, not `k`):
//!
//! 1. `Δ⁰ = L₀ V⁰` with the combinatorial Laplacian, Eq. (2)–(3), and the curve form Eq. (8)
//!    on the boundary ([`laplacian`]); optionally edited (§4.4, [`DifferentialOptions`]).
//! 2. `Δ⁰` is subdivided `k` times with Loop or Modified Butterfly — the crate's own linear
//!    drivers ([`crate::scheme::subdivide`]) run on a mesh whose "positions" are the
//!    differential coordinates — or with DirMag (§3.4, [`dirmag`]) for the first
//!    [`DifferentialOptions::dirmag_levels`] levels ("we only perform the DirMag subdivision
//!    in the first one or two iterations").
//! 3. The geometry of level `k` is the least-squares solution of `4ᵏ L_k Ṽᵏ = Δᵏ` with anchor
//!    rows (§3.5 step 4), solved by [`solve`]: the boundary loops exactly (tridiagonal), the
//!    rest as the equivalent Dirichlet graph-Laplacian problem by multigrid-preconditioned CG,
//!    warm-started from the spatial subdivision of the same stencil; the tolerance is checked
//!    on the residual of the normal equations.
//!
//! # Placement (decision)
//!
//! The paper fixes the translation with one handle, `v₀ = (0, 0, 0)`. That moves the result
//! away from the control mesh, and one handle does not fix a mesh with several components or
//! boundary loops (each boundary loop is a closed differential curve with its own free
//! translation: `L` has one null vector per closed component and per boundary loop). We
//! anchor the lowest-index vertex of every closed component and of every boundary loop (and
//! every isolated vertex) at its position in the spatial subdivision, then translate each
//! connected component so that its centroid (the mean of its vertices) equals the centroid of
//! the same component of the spatial subdivision. Translations do not change the
//! least-squares residual of the Laplacian rows, so this is one of the paper's solutions; for
//! a closed connected mesh it is the paper's solution translated by a constant vector.
//! Consequences: `k = 0` returns the control mesh (up to the solver tolerance); translating
//! the input translates the output.
//!
//! # Buffers
//!
//! Output order and faces are those of the spatial Loop/Butterfly subdivision
//! ([`crate::scheme`]). Scratch sizes come from [`plan()`]; contents of every buffer are
//! unspecified on error. [`Status::NotConverged`](crate::Status::NotConverged) is returned
//! when the solver stops at its iteration cap; the report still says how far it got.
//!
//! # Files
//!
//! `options.rs` (what is asked and reported), `plan.rs` (validation and sizes), `driver.rs`
//! ([`subdivide`]), `edit.rs` (§4.4), `placement.rs` (anchors and translation); the public
//! building blocks [`laplacian`], [`dirmag`], [`solve`] and [`metrics`].

pub mod dirmag;
pub mod laplacian;
pub mod metrics;
pub mod solve;

mod driver;
mod edit;
mod folds;
mod normal_edit;
mod options;
mod placement;
mod plan;

pub use driver::{subdivide, subdivide_with};
pub use options::{DifferentialOptions, DifferentialReport, Stencil};
pub use plan::{plan, plan_scratch_size, DifferentialPlan};
