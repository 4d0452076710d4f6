//! Linear subdivision rules on one neighbourhood, given as slices of points. Nothing here
//! knows a mesh, so a host with its own connectivity can call them: the drivers in
//! [`crate::scheme`] gather the neighbourhoods, and the Möbius schemes evaluate the same
//! rules on canonical forms of vertex stars (seed 000 §4.1, §4.3).
//!
//! The weights are exactly those of the peer libraries (OpenMesh, CGAL, OpenSubdiv), so that
//! results can be compared with theirs; each module names its peer and cites its rule. Sums run in
//! the documented order of their arguments, in plain `f64` arithmetic without fused multiply-add,
//! so results are deterministic.
//!
//! Rings are counter-clockwise seen from outside and, unless a function says otherwise,
//! may start anywhere.

pub mod akleman;
pub mod butterfly;
pub mod catmull_clark;
pub mod crease;
pub mod doo_sabin;
pub mod kobbelt;
pub mod loop_scheme;
pub mod simplest;

use crate::error::{Error, Result, Status};
use crate::point::{add, lin2, scale, sum, Point};

/// The average of `points`.
///
/// # Errors
/// [`Status::TooFewPoints`] for an empty slice.
pub fn centroid(points: &[Point]) -> Result<Point> {
    centroid_of_sum(sum(points), points.len())
}

/// [`centroid`] from the sum of `n` points (left to right, as [`sum`]): the drivers
/// accumulate it while walking a face or a star, with no array of points, and get the same
/// bits.
///
/// # Errors
/// [`Status::TooFewPoints`] for `n = 0`.
pub(crate) fn centroid_of_sum(s: Point, n: usize) -> Result<Point> {
    if n == 0 {
        return Err(Error::new(Status::TooFewPoints));
    }
    Ok(scale(s, 1.0 / n as f64))
}

/// The crease (boundary) vertex rule of the cubic B-spline, `3/4 v + 1/8 (b0 + b1)`: the
/// boundary rule of Loop and of Catmull–Clark as CGAL and OpenSubdiv (`EDGE_ONLY`) apply it,
/// one-face corners included: every boundary loop is subdivided as a closed cubic B-spline
/// curve through its vertices.
#[inline]
pub fn crease_vertex(v: Point, b0: Point, b1: Point) -> Point {
    lin2(0.75, v, 0.125, add(b0, b1))
}

/// `ring[(j + k) mod n]` for a signed offset `k`.
#[inline]
pub(crate) fn cyclic(ring: &[Point], j: usize, k: isize) -> Result<Point> {
    let n = ring.len() as isize;
    if n == 0 {
        return Err(Error::new(Status::TooFewPoints));
    }
    let i = (j as isize + k).rem_euclid(n) as usize;
    ring.get(i)
        .copied()
        .ok_or(Error::new(Status::InvalidArgument))
}
