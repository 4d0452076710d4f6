//! Eq. (3) of seed 000 solved for the new point: `cr[e, a, b, p] = χ` ⇔
//! `p = (M + χ)⁻¹ (χ e + M b)` with `M = (a − e)(b − a)⁻¹`.
//!
//! Both blends end here once they have chosen χ; only the way they find χ differs (§4.4.1,
//! §4.4.2). The solve is written so that it reads the inputs only through one difference, which
//! is what lets the blends skip the normalised frame for inputs of moderate size
//! (`frame.rs`).

use crate::error::{Error, Result, Status};
use crate::point::{self, add, sub, Point};
use crate::quat::Quat;

/// `p = e + (M + χ)⁻¹ M (b − e)`: the solution of `cr[e, a, b, p] = χ` with
/// `M = (a − e)(b − a)⁻¹`, which is `(M + χ)⁻¹ (χ e + M b)` (Eq. (3)) with `χ e + M b`
/// split as `(M + χ) e + M (b − e)`: it reads only the difference `b − e`, so it needs no
/// frame. A new point at infinity — an offset that is not finite in f64, which the normalised
/// frame could in rare cases still have represented and reported as
/// [`Status::NumericalFailure`] — is [`Status::DegenerateGeometry`]; a finite offset from a
/// point so far out that the sum overflows is [`Status::NumericalFailure`].
#[inline(always)]
pub(super) fn solve_by_difference(m: Quat, b: Point, e: Point, chi: Quat) -> Result<Point> {
    let degenerate = Error::new(Status::DegenerateGeometry);
    let offset = ((m + chi).inverse().ok_or(degenerate)? * m.mul_im(sub(b, e))).to_point();
    if !point::is_finite(&offset) {
        return Err(degenerate);
    }
    let p = add(e, offset);
    if point::is_finite(&p) {
        Ok(p)
    } else {
        Err(Error::new(Status::NumericalFailure))
    }
}

/// Solves `cr[e, a, b, p] = χ` for `p` from the points themselves (tests: it builds inputs
/// with a prescribed cross-ratio).
#[cfg(test)]
pub(super) fn solve_cross_ratio(a: Point, b: Point, e: Point, chi: Quat) -> Result<Point> {
    let degenerate = Error::new(Status::DegenerateGeometry);
    let (qa, qb, qe) = (
        Quat::from_point(a),
        Quat::from_point(b),
        Quat::from_point(e),
    );
    let m = (qa - qe) * (qb - qa).inverse().ok_or(degenerate)?;
    solve_by_difference(m, b, e, chi)
}
