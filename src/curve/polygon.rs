//! The polygon of one level as the curve rules read and write it: bounds-checked and cyclic
//! indexing, the checks of a one-level call, and the element index a failure names. Every
//! access returns a [`Result`] instead of panicking, so the kernel stays panic-free.

use super::refined_size_once;
use crate::error::{Error, Result, Status};
use crate::point::{self, dot, Point};

/// [`Status::NonFiniteInput`] naming the first point with a NaN or infinite coordinate.
pub(crate) fn check_finite(points: &[Point]) -> Result<()> {
    match points.iter().position(|p| !point::is_finite(p)) {
        Some(i) => Err(Error::at(Status::NonFiniteInput, index_u32(i))),
        None => Ok(()),
    }
}

/// Validation shared by the public one-level functions of the scheme modules: enough
/// points, an output of at least the refined size, finite input. Returns the refined size.
pub(crate) fn check_level(points: &[Point], closed: bool, out: &[Point]) -> Result<usize> {
    let next = refined_size_once(points.len(), closed)?;
    if out.len() < next {
        return Err(Error::too_small(next));
    }
    check_finite(points)?;
    Ok(next)
}

/// An element index as `u32` (saturating: indices beyond `u32::MAX − 1` are reported as
/// `u32::MAX − 1`, never as "no element").
pub(crate) fn index_u32(i: usize) -> u32 {
    u32::try_from(i).unwrap_or(u32::MAX - 1).min(u32::MAX - 1)
}

/// The point `points[i]`, or [`Status::TooFewPoints`] if the index is out of range
/// (unreachable after validation; there to keep the kernel free of panics).
#[inline]
pub(crate) fn at(points: &[Point], i: usize) -> Result<Point> {
    points
        .get(i)
        .copied()
        .ok_or(Error::new(Status::TooFewPoints))
}

/// `points[(i + k) mod n]` for a small offset `k ∈ {−1, 1, 2}` on a closed polygon.
#[inline]
pub(crate) fn cyclic(points: &[Point], i: usize, k: isize) -> Result<Point> {
    let n = points.len();
    let j = match k {
        -1 => {
            if i == 0 {
                n.wrapping_sub(1)
            } else {
                i - 1
            }
        }
        _ => {
            let j = i.wrapping_add(k.unsigned_abs());
            if j >= n {
                j.wrapping_sub(n)
            } else {
                j
            }
        }
    };
    at(points, j)
}

/// `p` if finite, else [`Status::NumericalFailure`] naming `element`.
#[inline]
pub(crate) fn finite(p: Point, element: usize) -> Result<Point> {
    if point::is_finite(&p) {
        Ok(p)
    } else {
        Err(Error::at(Status::NumericalFailure, index_u32(element)))
    }
}

/// The length of a curve vector: `√(a·a)` down to a squared length of 1e-280 (every square
/// there is still a normal number, so the plain root loses nothing), below that and on
/// overflow the scaled [`crate::point::norm`]. The curve rules keep this wider fast path of
/// their own; the branch depends only on `a`, so the result is deterministic.
#[inline]
pub(crate) fn norm(a: Point) -> f64 {
    let s = dot(a, a);
    if s.is_finite() && s >= 1e-280 {
        crate::sqrt::sqrt(s)
    } else {
        crate::point::norm(a)
    }
}

/// The first `refined_size_once(p.len())` entries of `out`: the exact output of one level.
#[inline]
pub(crate) fn level_out<'a>(
    p: &[Point],
    closed: bool,
    out: &'a mut [Point],
) -> Result<&'a mut [Point]> {
    let next = refined_size_once(p.len(), closed)?;
    out.get_mut(..next).ok_or(Error::too_small(next))
}
