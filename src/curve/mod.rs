//! Curve subdivision over caller slices: open and closed polylines in R³, `k` levels,
//! exact sizes, no allocation.
//!
//! # Schemes
//!
//! | [`CurveScheme`] | kind | rule (one level) | source |
//! |---|---|---|---|
//! | [`FourPoint`](CurveScheme::FourPoint) | linear, interpolating | `E = 9/16 (P_i + P_{i+1}) − 1/16 (P_{i−1} + P_{i+2})` | Dyn–Levin–Gregory, `w = 1/16` ([`four_point`]) |
//! | [`BSpline`](CurveScheme::BSpline) | linear, approximating | `E = (P_i + P_{i+1})/2`, `P'_i = 3/4 P_i + 1/8 (P_{i−1} + P_{i+1})` | cubic B-spline ([`bspline`]) |
//! | [`MobiusInterpolating`](CurveScheme::MobiusInterpolating) | Möbius, interpolating | `E = F4(P_{i−1}, P_i, P_{i+1}, P_{i+2})` | seed 000 §4.4.1 ([`mobius`]) |
//! | [`MobiusApproximating`](CurveScheme::MobiusApproximating) | Möbius, approximating | `E` as above, `P'_i = F4(P_{i−1}, E_{i−½}, E_{i+½}, P_{i+1})` | seed 000 §4.4.1 ([`mobius`]) |
//! | [`CircleBlend`](CurveScheme::CircleBlend) | circle preserving, interpolating | middle of the arc with the averaged tangent | seed 003 §2 ([`circle_blend`]) |
//! | [`DifferentialFourPoint`](CurveScheme::DifferentialFourPoint), [`DifferentialBSpline`](CurveScheme::DifferentialBSpline) | linear, global | subdivide `δ_i = v_i − (v_{i−1} + v_{i+1})/2`, reconstruct | seed 001 §3.5 Eq. (8), App. A ([`differential`]) |
//!
//! # Topology and output order
//!
//! One level maps `n` points to
//! * `2n` points for a **closed** curve (`n` vertex points and `n` edge points; the edge
//!   point `i` lies between `P_i` and `P_{(i+1) mod n}`);
//! * `2n − 1` points for an **open** curve (`n` vertex points, `n − 1` edge points), for
//!   every scheme: approximating schemes keep the two end points, so that an open curve
//!   keeps its ends as a B-spline curve with clamped ends does.
//!
//! The output is interleaved: the vertex point of `P_i` at index `2i`, the edge point of the
//! segment `P_i P_{i+1}` at index `2i + 1`. For interpolating schemes the even entries are
//! the old points, bit for bit; after `k` levels input point `i` is at index `2^k i`.
//! [`refined_size`] gives the exact size after `k` levels; it is the same for every scheme.
//!
//! A closed curve needs at least 3 points, an open one at least 2 (two points give the
//! midpoint, for every scheme). `levels = 0` copies the input.
//!
//! # Buffers
//!
//! [`subdivide`] writes the final level into `out` (at least [`refined_size`] points) and
//! ping-pongs the intermediate levels between `out` and `scratch` (at least
//! [`scratch_size`] points), so that the last level lands in `out`. Nothing is allocated.
//!
//! # Errors
//!
//! Every failure is reported before the first level is computed where it can be:
//! [`Status::TooFewPoints`], [`Status::SizeOverflow`] (checked size arithmetic),
//! [`Status::BufferTooSmall`] (with [`Error::needed`], `out` checked before `scratch`),
//! [`Status::NonFiniteInput`] (element = point index). Geometry failures during a level
//! ([`Status::DegenerateGeometry`], [`Status::NumericalFailure`]) name the input point that
//! starts the input segment in which the failing point lies (`⌊j / 2^ℓ⌋` for point `j` of
//! level `ℓ`). The contents of `out` and `scratch` are unspecified after an error.
//!
//! Repeated consecutive points: the linear schemes (4-point, B-spline, differential) are
//! defined for any input. The Möbius schemes apply F4's defined coincident rules
//! ([`crate::blend::f4`]: `b = c → b`, `a = b → b`, `c = d → c`, `a = c → c`, `b = d → b`;
//! the open-end rule likewise, see [`mobius::end_edge_point`]), so a repeated point is kept
//! and never an error. The circle blend needs three distinct points for each circle and gives
//! [`Status::DegenerateGeometry`] (see [`circle_blend`]).
//!
//! ```
//! use nlsubdiv::curve::{self, CurveScheme};
//! // Four points on the unit circle, closed, 3 levels of the circle blend.
//! let pts = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]];
//! let n = curve::refined_size(pts.len(), true, 3).unwrap();
//! let s = curve::scratch_size(CurveScheme::CircleBlend, pts.len(), true, 3).unwrap();
//! let mut out = [[0.0; 3]; 32];
//! let mut scratch = [[0.0; 3]; 16];
//! assert_eq!((n, s), (32, 16));
//! let written =
//!     curve::subdivide(CurveScheme::CircleBlend, &pts, true, 3, &mut out, &mut scratch).unwrap();
//! assert_eq!(written, 32);
//! for p in &out {
//!     let r = libm::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
//!     assert!((r - 1.0).abs() < 1e-14);
//! }
//! ```

pub mod bspline;
pub mod circle_blend;
pub mod differential;
pub mod four_point;
pub mod mobius;

mod levels;
mod polygon;
mod scheme;
mod sizes;

// The errors the documentation names.
#[cfg(doc)]
use crate::error::{Error, Status};

pub use levels::subdivide;
pub use scheme::CurveScheme;
pub use sizes::{min_points, refined_size, refined_size_once, scratch_size};
