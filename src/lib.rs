//! # nlsubdiv
//!
//! Deterministic, allocation-free **nonlinear subdivision** of curves and polygon meshes:
//!
//! * canonical Möbius subdivision (Vaxman, Müller, Weber 2018, `seeds/000`): quaternionic
//!   cross-ratios, canonical forms of vertex stars, the Möbius-invariant blends F4 and F6;
//! * differential-space subdivision (`seeds/001`);
//! * spherelike interpolating subdivision from circle-blend curve rules (`seeds/003`).
//!
//! The crate is `#![no_std]` without `alloc`: every call works on caller-provided slices.
//! Fallible calls return [`Result`] with an [`Error`] carrying a stable [`Status`] code and
//! the element at fault; outputs are only meaningful on `Ok`. Mathematics comes from `libm`
//! and plain IEEE arithmetic without fused multiply-add, so the same input gives the same
//! bits on every run.
//!
//! Layers depend one way, top to bottom: [`quat`] (quaternions, cross-ratio, corner
//! tangents) → [`mobius`] (Möbius maps, canonical forms) → [`blend`] (F4, F6) →
//! [`metrics`], [`curve`] (curve subdivision: linear, Möbius, circle blend, differential);
//! [`stencil`] (linear rules on one neighbourhood) → [`mesh`] (caller-buffer meshes,
//! validation, half-edge topology in scratch, refinement patterns) → [`scheme`] (the mesh
//! schemes: one options value, one plan, one subdivide call; [`scheme::mobius`] the canonical
//! Möbius version of every scheme, seed 000 §4, and its star rules for hosts with their own
//! connectivity) → [`differential`] (differential-space subdivision, the same shape).
//!
//! # Subdividing a mesh
//!
//! One path for every mesh scheme, linear or Möbius, one level or many: an [`Options`]
//! value, [`plan`] for the exact sizes of the output and the scratch, then [`subdivide`].
//! Parameters come in the order input, options, scratch, output; sizes are counted in
//! elements of the buffer they size (points, `u32` entries, faces).
//!
//! ```
//! use nlsubdiv::{plan, plan_scratch_size, subdivide, Mesh, MeshOut, Options, Scheme, Scratch};
//! // One quad, two Catmull–Clark levels into caller buffers.
//! let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
//! let mesh = Mesh::new(&p, &[0, 4], &[0, 1, 2, 3]);
//! let opts = Options::new(Scheme::CatmullClark).levels(2);
//! // Sizes: the plan validates the mesh in `plan_scratch_size` u32 entries.
//! let mut u32s = [0u32; 256];
//! assert!(plan_scratch_size(&mesh).unwrap() <= u32s.len());
//! let plan = plan(mesh, &opts, &mut u32s).unwrap();
//! let o = plan.output();
//! assert_eq!((o.vertices, o.faces, o.indices), (25, 16, 64));
//! assert!(plan.scratch.u32s <= u32s.len());
//! let mut points = [[0.0; 3]; 64];
//! assert!(plan.scratch.points <= points.len());
//! // The call: input, options, scratch, output.
//! let (mut pos, mut offs, mut idx) = ([[0.0; 3]; 25], [0u32; 17], [0u32; 64]);
//! let mut out = MeshOut::new(&mut pos, &mut offs, &mut idx);
//! let report = subdivide(mesh, &opts, Scratch::new(&mut u32s, &mut points), &mut out).unwrap();
//! assert_eq!(report.sizes, o);
//! assert!(pos.iter().all(|q| q[2] == 0.0)); // a planar quad stays in its plane
//! assert_eq!(pos[8], [0.5, 0.5, 0.0]); // the centre, by symmetry
//! // The Möbius version: the same sizes, more point scratch (candidates).
//! let mobius = Options::new(Scheme::CatmullClark).mobius(true).levels(2);
//! let mp = nlsubdiv::plan(mesh, &mobius, &mut u32s).unwrap();
//! assert_eq!(mp.output(), o);
//! assert!(mp.scratch.points > plan.scratch.points);
//! ```
//!
//! ```
//! use nlsubdiv::blend::f4;
//! // Four points on the unit circle: the new point is on the circle, between b and c.
//! let on = |t: f64| [libm::cos(t), libm::sin(t), 0.0];
//! let p = f4(on(0.0), on(0.5), on(1.0), on(1.5)).unwrap();
//! assert!((p[0] * p[0] + p[1] * p[1] - 1.0).abs() < 1e-14);
//! ```
//!
//! # Cargo features
//!
//! One per scheme family, all on by default: `loop`, `catmull-clark`, `butterfly`,
//! `kobbelt`, `doo-sabin`, `simplest`, `akleman` (dual, vertex insertion, dual truncation),
//! `spherelike`; `mobius` for the canonical Möbius forms of the schemes built (and the Möbius
//! curve schemes); `curves` for [`curve::subdivide`]; `differential` for
//! [`differential`] subdivision (it brings `loop`). The scheme is a run-time argument, so a
//! firmware that calls one scheme builds with `default-features = false` and that scheme's
//! features, and links it alone; a scheme or form left out is [`Status::SchemeNotBuilt`]
//! from the plan and the call ([`Scheme::is_built`], `docs/firmware.md`, "Link only what you
//! use"). Everything called by name (the primitives, the star rules) is in every build.
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod blend;
mod caps;
pub mod curve;
pub mod differential;
pub mod error;
pub mod exec;
pub mod mesh;
pub mod metrics;
pub mod mobius;
pub mod point;
pub mod quat;
pub mod scheme;
mod sqrt;
pub mod stencil;

pub use error::{Error, Result, Status, NO_ELEMENT};
pub use mesh::{Mesh, MeshOut, MeshSizes};
pub use point::Point;
pub use quat::Quat;
pub use scheme::{
    plan, plan_scratch_size, plan_scratch_size_tagged, plan_tagged, plan_weighted, subdivide,
    subdivide_tagged, subdivide_weighted, subdivide_with, CreaseMethod, Options, Plan, Report,
    Scheme, Scratch, ScratchSizes, Tags, VertexWeights, MAX_LEVELS,
};

/// The largest vertex valence (number of edge neighbours) any rule accepts: 128 unless the
/// build sets `NLSUBDIV_MAX_VALENCE` (8 to 4096; `docs/firmware.md`, "Capacities"). Some
/// rules hold a star in a fixed-capacity stack array of this size; larger stars give
/// [`Status::ValenceTooHigh`].
pub const MAX_VALENCE: usize = caps::MAX_VALENCE;

/// The largest number of corners of a face: 128 unless the build sets
/// `NLSUBDIV_MAX_FACE_SIZE` (8 to 4096); larger faces give [`Status::ValenceTooHigh`].
pub const MAX_FACE_SIZE: usize = caps::MAX_FACE_SIZE;

/// The crate version, `MAJOR.MINOR.PATCH`.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
