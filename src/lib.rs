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
//! [`stencil`] (linear rules on one neighbourhood) → [`mesh`] (caller-buffer
//! meshes, validation, half-edge topology in scratch, refinement patterns) → [`scheme`]
//! (drivers: one level per call, multi-level plans; [`scheme::mobius`] the canonical Möbius
//! version of every scheme, seed 000 §4).
//!
//! ```
//! use nlsubdiv::mesh::{Mesh, MeshOut};
//! use nlsubdiv::scheme::{self, Scheme};
//! // One quad, one Catmull–Clark step into caller buffers.
//! let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
//! let mesh = Mesh::new(&p, &[0, 4], &[0, 1, 2, 3]);
//! let mut scratch = [0u32; 64];
//! assert!(scheme::scratch_len(&mesh).unwrap() <= scratch.len());
//! let sizes = scheme::subdivide_mesh_size(Scheme::CatmullClark, mesh, &mut scratch).unwrap();
//! let (mut pos, mut offs, mut idx) = ([[0.0; 3]; 9], [0u32; 5], [0u32; 16]);
//! let mut out = MeshOut::new(&mut pos, &mut offs, &mut idx);
//! let written = scheme::subdivide_mesh(Scheme::CatmullClark, mesh, &mut scratch, &mut out).unwrap();
//! assert_eq!((written, sizes.vertices, sizes.faces), (sizes, 9, 4));
//! assert_eq!(pos[8], [0.5, 0.5, 0.0]); // the face point
//! ```
//!
//! ```
//! use nlsubdiv::blend::f4;
//! // Four points on the unit circle: the new point is on the circle, between b and c.
//! let on = |t: f64| [libm::cos(t), libm::sin(t), 0.0];
//! let p = f4(on(0.0), on(0.5), on(1.0), on(1.5)).unwrap();
//! assert!((p[0] * p[0] + p[1] * p[1] - 1.0).abs() < 1e-14);
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod blend;
pub mod curve;
pub mod differential;
pub mod error;
pub mod mesh;
pub mod metrics;
pub mod mobius;
pub mod point;
pub mod quat;
pub mod scheme;
pub mod stencil;

pub use error::{Error, Result, Status, NO_ELEMENT};
pub use point::Point;
pub use quat::Quat;

/// The largest vertex valence (number of edge neighbours) any rule accepts. Stars are held
/// in fixed-capacity stack arrays of this size; larger ones give [`Status::ValenceTooHigh`].
pub const MAX_VALENCE: usize = 128;

/// The largest number of corners of a face.
pub const MAX_FACE_SIZE: usize = 128;

/// The crate version, `MAJOR.MINOR.PATCH`.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
