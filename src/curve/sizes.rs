//! Exact output and scratch sizes of curve subdivision: one level maps `n` points to `2n`
//! (closed) or `2n − 1` (open), for every scheme, so sizes are known before any point is
//! computed and the caller can provide every buffer.

use super::CurveScheme;
use crate::error::{Error, Result, Status};

/// The smallest number of points of a curve: 3 for a closed curve, 2 for an open one
/// (the same for every scheme).
pub const fn min_points(closed: bool) -> usize {
    if closed {
        3
    } else {
        2
    }
}

/// The number of points after one level: `2n` (closed) or `2n − 1` (open).
///
/// # Errors
/// [`Status::TooFewPoints`] below [`min_points`]; [`Status::SizeOverflow`].
pub fn refined_size_once(n: usize, closed: bool) -> Result<usize> {
    if n < min_points(closed) {
        return Err(Error::new(Status::TooFewPoints));
    }
    let twice = n.checked_mul(2).ok_or(Error::new(Status::SizeOverflow))?;
    if closed {
        Ok(twice)
    } else {
        twice.checked_sub(1).ok_or(Error::new(Status::SizeOverflow))
    }
}

/// The exact number of output points after `levels` levels of any scheme:
/// `n·2^k` (closed) or `(n − 1)·2^k + 1` (open).
///
/// # Errors
/// [`Status::TooFewPoints`] when `n` is below [`min_points`]; [`Status::SizeOverflow`] when
/// the size does not fit in `usize`.
pub fn refined_size(n: usize, closed: bool, levels: u32) -> Result<usize> {
    if n < min_points(closed) {
        return Err(Error::new(Status::TooFewPoints));
    }
    let mut len = n;
    for _ in 0..levels {
        len = refined_size_once(len, closed)?;
    }
    Ok(len)
}

/// The number of scratch points [`super::subdivide`] needs: the size of level `k − 1` for the
/// local schemes when `k ≥ 2` (0 for `k ≤ 1`); for the differential schemes the size of
/// level `k − 1` when `k ≥ 1` (the differential polygon `Δ⁰` also needs a buffer), 0 for
/// `k = 0`.
///
/// # Errors
/// As [`refined_size`].
pub fn scratch_size(scheme: CurveScheme, n: usize, closed: bool, levels: u32) -> Result<usize> {
    // Validate the final size first, so that an overflow is reported for every query.
    refined_size(n, closed, levels)?;
    let differential = matches!(
        scheme,
        CurveScheme::DifferentialFourPoint | CurveScheme::DifferentialBSpline
    );
    let first = if differential { 1 } else { 2 };
    if levels < first {
        return Ok(0);
    }
    refined_size(n, closed, levels - 1)
}
