//! The Möbius-invariant blends F4 and F6 and the face-point chain built from them
//! (seed 000 §4.4, Eq. (3), Appendix A).
//!
//! A Möbius scheme computes a new point in the canonical form of each nearby star (the
//! *candidates*) and then blends those candidates into one point with a rule that commutes with
//! Möbius maps, so that the scheme does too:
//!
//! * [`f4()`] (§4.4.1) blends four points: edge points of the Möbius curve and mesh schemes;
//! * [`f6()`] (§4.4.2) blends two chains of three points: Kobbelt's face points and the steps
//!   of the face-point chain;
//! * [`face_point()`] and [`face_point_with_ids`] (§4.4.3) chain F4 and F6 over the quadruplets
//!   of a face.
//!
//! Both blends solve `cr[e, a, b, p] = χ` for `p` (with `e = c` for F4), where χ is a square
//! root of cross-ratios of the inputs. Multiplied out, Eq. (3) is
//! `p = (M + χ)⁻¹ (χ e + M b)` with `M = (a − e)(b − a)⁻¹` (`M = ((a − b)(c − a)⁻¹)⁻¹` in the
//! paper's notation); it is evaluated as `p = e + (M + χ)⁻¹ M (b − e)` (`solve.rs`), so for
//! inputs whose diameter is in [1e-100, 1e100] the blends read only differences of the inputs,
//! each rounded once. Outside that range the inputs are first moved to a normalised frame
//! (`frame.rs`: centroid at the origin, unit diameter). Similarities are Möbius maps, so this
//! changes nothing in exact arithmetic, and it keeps intermediates far from overflow and
//! underflow.
//!
//! Where the paper's formulas are singular (coincident inputs, a cross-ratio on the negative
//! real axis, where the square root has no principal value) the blends return defined results,
//! documented on each function; `roots.rs` holds the branch and axis choices.
//!
//! Files: `frame.rs` (the working coordinates), `roots.rs` (square roots of cross-ratios),
//! `solve.rs` (Eq. (3) for `p`), `f4.rs`, `f6.rs`, `face_point.rs` (the public blends).

mod f4;
mod f6;
mod face_point;
mod frame;
mod roots;
mod solve;

pub use f4::{f4, f4_hinted, noncircularity};
pub use f6::f6;
pub use face_point::{face_point, face_point_with_ids};
pub(crate) use face_point::{face_point_in_place, work_points, FaceCorners};
pub use roots::is_negative_real;

/// Relative distance below which two inputs count as coincident: `|p − q| ≤ 1e-13 × the
/// diameter of the blend's inputs`. The coincidence rules of [`f4()`] and [`f6()`] answer there
/// instead of the formula, which divides by such differences; 1e-13 is a few hundred ulps, so
/// distinct inputs that merely round close are not caught, while the formula's result would be
/// noise.
pub const COINCIDENT_TOLERANCE: f64 = 1e-13;

/// Relative size of `Im ρ` below which a cross-ratio with negative real part counts as a
/// negative real: `|Im ρ| ≤ 1e-12 |ρ|`. For cocircular points `Im ρ` is rounding noise whose
/// direction is arbitrary, so the root takes a defined axis there ([`is_negative_real`]).
pub const NEGATIVE_REAL_TOLERANCE: f64 = 1e-12;

/// Deterministic test data shared by the blends' unit tests.
#[cfg(test)]
pub(crate) mod testing {
    use crate::point::Point;

    /// Deterministic points in the unit cube (a 64-bit LCG).
    pub(crate) fn lcg_points<const N: usize>(state: &mut u64) -> [Point; N] {
        let mut next = || {
            *state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (*state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        [[0.0; 3]; N].map(|_| [next(), next(), next()])
    }
}
