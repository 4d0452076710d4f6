//! The quaternionic cross-ratio of four points (seed 000 §3.2).
//!
//! `cr[qi, qj, qk, ql] = q_ij q_jk⁻¹ q_kl q_li⁻¹` with `q_ij = q_j − q_i`: real exactly for
//! cocircular points, and its real part and `|Im|` are Möbius invariants, which is why the
//! blends of §4.4 are built from it. Besides the public [`cross_ratio`] the module keeps its
//! factors ([`CrossRatio`]) so that the blends can reuse them bit for bit.

use super::quaternion::{im_mul_im, inverse_point, Quat};
use crate::error::{Error, Result, Status};
use crate::point::{self, sub, Point};

/// `b − a`: the difference quaternion `q_ab = [0, b − a]` of seed 000 §3.2 as a point.
#[inline]
fn diff_point(a: Point, b: Point) -> Point {
    sub(b, a)
}

/// `q_ab⁻¹` ([`inverse_point`] of [`diff_point`]).
#[inline]
pub(super) fn diff_inverse(a: Point, b: Point) -> Option<Point> {
    inverse_point(diff_point(a, b))
}

/// The quaternionic cross-ratio `cr[qi, qj, qk, ql] = q_ij q_jk⁻¹ q_kl q_li⁻¹` with
/// `q_ij = q_j − q_i` (seed 000 §3.2), exactly as printed.
///
/// It is real iff the four points are cocircular; `Re` and `|Im|` are Möbius invariants.
///
/// # Errors
/// [`Status::NonFiniteInput`] for a non-finite coordinate; [`Status::DegenerateGeometry`]
/// when `qj = qk` or `ql = qi` (an inverse of zero) or the result is not finite.
pub fn cross_ratio(qi: Point, qj: Point, qk: Point, ql: Point) -> Result<Quat> {
    CrossRatio::new(qi, qj, qk, ql)?.value()
}

/// The factors of `cr[qi, qj, qk, ql] = ((q_ij q_jk⁻¹) q_kl) q_li⁻¹`, evaluated in that
/// order by [`cross_ratio`], kept so that the blends can reuse them bit for bit: the prefix
/// `q_ij q_jk⁻¹` is the `M` of the solve of Eq. (3) and starts every cross-ratio with the
/// same first three points; the double transposition `cr[qk, ql, qi, qj]` (F4's mirrored
/// order) is the same four factors in another order.
#[derive(Clone, Copy)]
pub(crate) struct CrossRatio {
    /// `q_ij q_jk⁻¹`.
    pub(crate) prefix: Quat,
    /// `q_ij` (imaginary).
    ij: Point,
    /// `q_jk⁻¹` (imaginary).
    inv_jk: Point,
    /// `q_kl` (imaginary).
    kl: Point,
    /// `q_li⁻¹` (imaginary).
    inv_li: Point,
}

impl CrossRatio {
    /// The factors, with the checks of [`cross_ratio`] in its order (all but the finiteness
    /// of the product, which [`CrossRatio::value`] checks).
    #[inline]
    pub(crate) fn new(qi: Point, qj: Point, qk: Point, ql: Point) -> Result<CrossRatio> {
        if ![qi, qj, qk, ql].iter().all(point::is_finite) {
            return Err(Error::new(Status::NonFiniteInput));
        }
        let inv_jk = diff_inverse(qj, qk).ok_or(Error::new(Status::DegenerateGeometry))?;
        let inv_li = diff_inverse(ql, qi).ok_or(Error::new(Status::DegenerateGeometry))?;
        let ij = diff_point(qi, qj);
        Ok(CrossRatio {
            prefix: im_mul_im(ij, inv_jk),
            ij,
            inv_jk,
            kl: diff_point(qk, ql),
            inv_li,
        })
    }

    /// The factors from the four differences `q_ij`, `q_jk`, `q_kl`, `q_li` (computed by the
    /// caller, whose inputs are finite): the translation-free entry of the blends.
    #[inline(always)]
    pub(crate) fn from_differences(
        ij: Point,
        jk: Point,
        kl: Point,
        li: Point,
    ) -> Result<CrossRatio> {
        let inv_jk = inverse_point(jk).ok_or(Error::new(Status::DegenerateGeometry))?;
        let inv_li = inverse_point(li).ok_or(Error::new(Status::DegenerateGeometry))?;
        Ok(CrossRatio {
            prefix: im_mul_im(ij, inv_jk),
            ij,
            inv_jk,
            kl,
            inv_li,
        })
    }

    /// `cr[qi, qj, qk, ql]`, bit for bit [`cross_ratio`].
    #[inline(always)]
    pub(crate) fn value(&self) -> Result<Quat> {
        finite_or_degenerate(self.prefix.mul_im(self.kl).mul_im(self.inv_li))
    }

    /// `cr[qk, ql, qi, qj] = ((q_kl q_li⁻¹) q_ij) q_jk⁻¹`, bit for bit
    /// `cross_ratio(qk, ql, qi, qj)` (the same differences and inverses).
    #[inline(always)]
    pub(crate) fn transposed(&self) -> Result<Quat> {
        finite_or_degenerate(self.transposed_prefix().mul_im(self.ij).mul_im(self.inv_jk))
    }

    /// `q_kl q_li⁻¹`, the prefix of [`CrossRatio::transposed`].
    #[inline(always)]
    pub(crate) fn transposed_prefix(&self) -> Quat {
        im_mul_im(self.kl, self.inv_li)
    }
}

/// `cr[qi, qj, qk, ql]` from its prefix `q_ij q_jk⁻¹` (computed for another cross-ratio that
/// starts with the same `qi, qj, qk`, whose checks passed), bit for bit [`cross_ratio`]: the
/// remaining checks in its order.
#[inline]
pub(crate) fn cross_ratio_from_prefix(
    prefix: Quat,
    qi: Point,
    qk: Point,
    ql: Point,
) -> Result<Quat> {
    if !point::is_finite(&ql) {
        return Err(Error::new(Status::NonFiniteInput));
    }
    let inv_li = diff_inverse(ql, qi).ok_or(Error::new(Status::DegenerateGeometry))?;
    finite_or_degenerate(prefix.mul_im(diff_point(qk, ql)).mul_im(inv_li))
}

#[inline]
fn finite_or_degenerate(q: Quat) -> Result<Quat> {
    if q.is_finite() {
        Ok(q)
    } else {
        Err(Error::new(Status::DegenerateGeometry))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cross_ratio_is_real_exactly_for_cocircular_points() {
        let on_circle = |t: f64| [libm::cos(t), libm::sin(t), 0.0];
        let cr = cross_ratio(
            on_circle(0.1),
            on_circle(1.0),
            on_circle(2.5),
            on_circle(4.0),
        )
        .unwrap();
        assert!(cr.abs_im() < 1e-15 * cr.abs());
        let cr2 = cross_ratio(
            on_circle(0.1),
            on_circle(1.0),
            on_circle(2.5),
            [0.0, 0.0, 1.0],
        )
        .unwrap();
        assert!(cr2.abs_im() > 1e-3);
        assert_eq!(
            cross_ratio([0.0; 3], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0])
                .unwrap_err()
                .status,
            Status::DegenerateGeometry
        );
        assert_eq!(
            cross_ratio(
                [f64::NAN, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [3.0; 3]
            )
            .unwrap_err()
            .status,
            Status::NonFiniteInput
        );
    }
}
