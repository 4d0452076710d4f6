//! The quaternionic geometry of seed 000 §3, on which every Möbius rule is built.
//!
//! Points of R³ are imaginary quaternions, and Möbius maps act on them as quaternionic
//! fractional linear maps (§3.2 Eq. (1)), so the invariants the papers' rules rely on are
//! quaternion expressions in differences of points:
//!
//! * [`Quat`] (§3.1): the quaternion algebra, with a principal square root, logarithm and
//!   exponential, all overflow-safe and deterministic (`quaternion.rs`);
//! * [`cross_ratio()`] (§3.2): the cross-ratio of four points, real exactly for cocircular
//!   points, its real part and `|Im|` Möbius invariants (`cross_ratio.rs`);
//! * [`corner_tangent`], [`tangent_polygon`] (§3.3, Lemma 3.1): the circle tangents of a
//!   polyline and the tangent polygon of a vertex star (`tangent.rs`).

mod cross_ratio;
mod quaternion;
mod tangent;

pub use cross_ratio::cross_ratio;
pub(crate) use cross_ratio::{cross_ratio_from_prefix, CrossRatio};
pub(crate) use quaternion::inverse_point;
pub use quaternion::Quat;
pub use tangent::{corner_tangent, tangent_polygon, tangent_polygon_vertex};

/// Test helpers shared by the quaternion modules.
#[cfg(test)]
pub(crate) mod testing {
    use super::Quat;

    /// `a` and `b` agree to `tol` relative to `1 + max(|a|, |b|)`.
    pub(crate) fn close(a: Quat, b: Quat, tol: f64) -> bool {
        (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
    }
}
