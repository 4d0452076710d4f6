//! The Möbius-invariant curve rules of seed 000 §4.4.1 ("Curve subdivision"), built on the
//! four-point blend [`f4`] (Eq. (3)).
//!
//! * **Interpolating**: `P'_{2i} = P_i`, `P'_{2i+1} = E_{i+½} = F4(P_{i−1}, P_i, P_{i+1}, P_{i+2})`
//!   — the Möbius form of the 4-point scheme.
//! * **Approximating**: edge points as above; vertex points
//!   `P'_{2i} = F4(P_{i−1}, E_{i−½}, E_{i+½}, P_{i+1})` ("applying F4 to the even vertices as
//!   well, with the two original even neighbors and the two new odd edge points"; the paper
//!   leaves the order of the arguments open, this one is the curve order, which keeps the rule
//!   symmetric under reversal) — the Möbius form of the cubic B-spline scheme.
//!
//! Both commute with every Möbius map `M` of R³ ∪ {∞} (`S(M P) = M S(P)` wherever the points
//! stay finite), keep points of a sphere on that sphere and points of a circle on that circle
//! (Lemma 4.1: consecutive points of a circle are never separated in the sense of F4).
//!
//! # Open curves
//!
//! The end segment `P_0 P_1` needs a point before `P_0`, which the paper does not define. We
//! fix the virtual end point `P_{−1}` by the Möbius-invariant extrapolation `cr[P_2, P_1, P_0, P_{−1}] = −1/3`:
//! the point of the circle through `P_0, P_1, P_2` (the line, for collinear points) that a
//! Möbius map taking `P_2, P_1, P_0` to `2, 1, 0` on a line takes to `−1`
//! ([`virtual_end_point`]). The end edge point is then `F4(P_{−1}, P_0, P_1, P_2)`. Because F4
//! is Möbius-equivariant and `F4(−1, 0, 1, 2) = 1/2`, that point is the point `E` of the same
//! circle with `cr[P_2, P_1, P_0, E] = cr[2, 1, 0, ½] = 1/3`, which [`end_edge_point`]
//! computes directly. The direct form is the same point in exact arithmetic (tested), stays
//! finite when `P_{−1}` is at infinity (on a line with `|P_1 P_2| = |P_0 P_1|/3`, for
//! instance), and never meets F4's negative-real branch (`cr[P_1, P_{−1}, P_0, P_2] = 4`).
//! The approximating rule keeps both end points (`P'_0 = P_0`). Two points give the midpoint.
//!
//! # Coincident points
//!
//! F4's defined coincident rules apply ([`f4`]: `b = c → b`, `a = b → b`, `c = d → c`,
//! `a = c → c`, `b = d → b`, within 1e-13 × the diameter of the four points), so a repeated
//! point is reproduced and never an error. [`end_edge_point`] follows the same rules for
//! `(P_{−1}, P_0, P_1, P_2)`: `P_0 = P_1 → P_0`, `P_1 = P_2 → P_1`, `P_0 = P_2 → P_0`.
//! [`crate::Status::DegenerateGeometry`] remains for a new point at infinity (possible for
//! Möbius rules: e.g. an end edge point when `P_2` lies on the chord `P_0 P_1` at one third
//! of its length from `P_1`, the configuration that a Möbius map sends to `0, 1, 2`).

use super::polygon::{at, check_level, cyclic, finite, index_u32, level_out, norm};
use crate::blend::{f4, COINCIDENT_TOLERANCE};
use crate::error::{Error, Result, Status};
use crate::point::{self, midpoint, sub, Point};
use crate::quat::Quat;

/// The cross-ratio `cr[P_2, P_1, P_0, P_{−1}]` of the virtual end point (module docs):
/// `cr[2, 1, 0, −1]` of four equally spaced points of a line.
pub const VIRTUAL_END_CROSS_RATIO: f64 = -1.0 / 3.0;

/// The cross-ratio `cr[P_2, P_1, P_0, E]` of the end edge point: `cr[2, 1, 0, ½]`.
pub const END_EDGE_CROSS_RATIO: f64 = 1.0 / 3.0;

/// The point `p` of the circle (or line) through `b, a, e` with `cr[e, a, b, p] = chi`
/// (`chi` real), `p = (M + χ)⁻¹ (χ e + M b)` with `M = (a − e)(b − a)⁻¹` (the solution used
/// by [`f4`], seed 000 Eq. (3)), evaluated in the frame centred at `b` with unit diameter.
/// The three points must be distinct.
fn solve_real_cross_ratio(e: Point, a: Point, b: Point, chi: f64) -> Result<Point> {
    let degenerate = Error::new(Status::DegenerateGeometry);
    let size = norm(sub(a, b)).max(norm(sub(e, b))).max(norm(sub(e, a)));
    if !(size > 0.0 && size.is_finite()) {
        return Err(degenerate);
    }
    let inv = 1.0 / size;
    let local = |p: Point| {
        Quat::new(
            0.0,
            (p[0] - b[0]) * inv,
            (p[1] - b[1]) * inv,
            (p[2] - b[2]) * inv,
        )
    };
    let (qe, qa) = (local(e), local(a));
    // b is the origin of the frame: M = (a − e)(0 − a)⁻¹, p = (M + χ)⁻¹ (χ e).
    let m = (qa - qe) * (-qa).inverse().ok_or(degenerate)?;
    let x = Quat::real(chi);
    let den = m + x;
    // A solution beyond 1e14 diameters is a point at infinity that rounding made finite.
    if den.abs() <= 1e-14 * (m.abs() + chi.abs()) {
        return Err(degenerate);
    }
    let p = (den.inverse().ok_or(degenerate)? * (x * qe)).to_point();
    let out = [b[0] + p[0] * size, b[1] + p[1] * size, b[2] + p[2] * size];
    if point::is_finite(&out) {
        Ok(out)
    } else {
        Err(degenerate)
    }
}

/// Whether two of three points coincide within `1e-13` × their diameter, as
/// `(p0 = p1, p1 = p2, p0 = p2)`.
fn coincidences(p0: Point, p1: Point, p2: Point) -> (bool, bool, bool) {
    let (d01, d12, d02) = (norm(sub(p0, p1)), norm(sub(p1, p2)), norm(sub(p0, p2)));
    let tol = COINCIDENT_TOLERANCE * d01.max(d12).max(d02);
    (d01 <= tol, d12 <= tol, d02 <= tol)
}

/// The virtual end point `P_{−1}` before `P_0` of an open curve: the point of the circle
/// through `P_0, P_1, P_2` (the line, for collinear points) with
/// `cr[P_2, P_1, P_0, P_{−1}] = −1/3` (module docs, "Open curves"). Equally spaced points of a line
/// give `2 P_0 − P_1`.
///
/// The curve rules use [`end_edge_point`], which equals `F4(P_{−1}, P_0, P_1, P_2)` without
/// forming `P_{−1}`; this function documents and tests that construction.
///
/// # Errors
/// [`Status::NonFiniteInput`]; [`Status::DegenerateGeometry`] when two of the points
/// coincide or `P_{−1}` is at infinity.
pub fn virtual_end_point(p0: Point, p1: Point, p2: Point) -> Result<Point> {
    if ![p0, p1, p2].iter().all(point::is_finite) {
        return Err(Error::new(Status::NonFiniteInput));
    }
    let (a, b, c) = coincidences(p0, p1, p2);
    if a || b || c {
        return Err(Error::new(Status::DegenerateGeometry));
    }
    solve_real_cross_ratio(p2, p1, p0, VIRTUAL_END_CROSS_RATIO)
}

/// The edge point of the end segment `P_0 P_1` of an open curve:
/// `F4(P_{−1}, P_0, P_1, P_2)` with the [`virtual_end_point`] `P_{−1}`, computed as the point
/// `E` of the circle through `P_0, P_1, P_2` with `cr[P_2, P_1, P_0, E] = 1/3` (see the
/// [module documentation](self)). On a circle it lies on the arc from `P_0` to `P_1` that
/// avoids `P_2`; equally spaced points of a line give the midpoint.
///
/// Coincident points (within 1e-13 × the diameter) follow F4's rules: `P_0 = P_1 → P_0`,
/// `P_1 = P_2 → P_1`, `P_0 = P_2 → P_0`.
///
/// # Errors
/// [`Status::NonFiniteInput`]; [`Status::DegenerateGeometry`] when `E` is at infinity.
pub fn end_edge_point(p0: Point, p1: Point, p2: Point) -> Result<Point> {
    if ![p0, p1, p2].iter().all(point::is_finite) {
        return Err(Error::new(Status::NonFiniteInput));
    }
    let (c01, c12, c02) = coincidences(p0, p1, p2);
    if c01 {
        return Ok(p0);
    }
    if c12 {
        return Ok(p1);
    }
    if c02 {
        return Ok(p0);
    }
    solve_real_cross_ratio(p2, p1, p0, END_EDGE_CROSS_RATIO)
}

/// The edge point `E_{i+½}` of segment `i` (see the module documentation).
fn edge_point(p: &[Point], closed: bool, i: usize) -> Result<Point> {
    let n = p.len();
    let e = if closed {
        f4(
            cyclic(p, i, -1)?,
            at(p, i)?,
            cyclic(p, i, 1)?,
            cyclic(p, i, 2)?,
        )
    } else if n == 2 {
        Ok(midpoint(at(p, 0)?, at(p, 1)?))
    } else if i == 0 {
        end_edge_point(at(p, 0)?, at(p, 1)?, at(p, 2)?)
    } else if i + 2 == n {
        end_edge_point(at(p, i + 1)?, at(p, i)?, at(p, i - 1)?)
    } else {
        f4(at(p, i - 1)?, at(p, i)?, at(p, i + 1)?, at(p, i + 2)?)
    };
    finite(e.map_err(|e| e.with_element(index_u32(i)))?, i)
}

/// One level of the Möbius interpolating scheme; returns the number of points written
/// (`2n` closed, `2n − 1` open).
///
/// # Errors
/// [`Status::TooFewPoints`] (fewer than 3 closed / 2 open points), [`Status::SizeOverflow`],
/// [`Status::BufferTooSmall`], [`Status::NonFiniteInput`] (element = point index),
/// [`Status::DegenerateGeometry`] / [`Status::NumericalFailure`] (element = first point of
/// the segment) when a new point is at infinity.
pub fn refine_interpolating(points: &[Point], closed: bool, out: &mut [Point]) -> Result<usize> {
    let next = check_level(points, closed, out)?;
    refine_interpolating_level(points, closed, out)?;
    Ok(next)
}

/// One level of the Möbius approximating scheme; returns the number of points written.
///
/// # Errors
/// As [`refine_interpolating`]; a failing vertex point names its old point.
pub fn refine_approximating(points: &[Point], closed: bool, out: &mut [Point]) -> Result<usize> {
    let next = check_level(points, closed, out)?;
    refine_approximating_level(points, closed, out)?;
    Ok(next)
}

/// One level of the interpolating rule on validated input.
pub(crate) fn refine_interpolating_level(
    p: &[Point],
    closed: bool,
    out: &mut [Point],
) -> Result<()> {
    let out = level_out(p, closed, out)?;
    for (i, pair) in out.chunks_mut(2).enumerate() {
        match pair {
            [even, odd] => {
                *even = at(p, i)?;
                *odd = edge_point(p, closed, i)?;
            }
            [even] => *even = at(p, i)?,
            _ => {}
        }
    }
    Ok(())
}

/// One level of the approximating rule on validated input: edge points first (odd slots),
/// then vertex points from them.
pub(crate) fn refine_approximating_level(
    p: &[Point],
    closed: bool,
    out: &mut [Point],
) -> Result<()> {
    let out = level_out(p, closed, out)?;
    let n = p.len();
    for (i, pair) in out.chunks_mut(2).enumerate() {
        if let [_, odd] = pair {
            *odd = edge_point(p, closed, i)?;
        }
    }
    let m = out.len();
    for i in 0..n {
        let pi = at(p, i)?;
        let v = if closed {
            let before = if i == 0 { m - 1 } else { 2 * i - 1 };
            f4(
                cyclic(p, i, -1)?,
                at(out, before)?,
                at(out, 2 * i + 1)?,
                cyclic(p, i, 1)?,
            )
        } else if i == 0 || i + 1 == n {
            Ok(pi)
        } else {
            f4(
                at(p, i - 1)?,
                at(out, 2 * i - 1)?,
                at(out, 2 * i + 1)?,
                at(p, i + 1)?,
            )
        };
        let v = finite(v.map_err(|e| e.with_element(index_u32(i)))?, i)?;
        let slot = out.get_mut(2 * i).ok_or(Error::too_small(m))?;
        *slot = v;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::point::distance;

    #[test]
    fn virtual_end_point_on_a_line() {
        let p = virtual_end_point([0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]).unwrap();
        assert!(distance(p, [-1.0, 0.0, 0.0]) < 1e-15, "{p:?}");
        let e = end_edge_point([0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]).unwrap();
        assert!(distance(e, [0.5, 0.0, 0.0]) < 1e-15, "{e:?}");
        // |P1 P2| = |P0 P1| / 3: the virtual point is at infinity, the edge point is not.
        let far = virtual_end_point([0.0; 3], [3.0, 0.0, 0.0], [4.0, 0.0, 0.0]);
        assert_eq!(far.unwrap_err().status, Status::DegenerateGeometry);
        let e = end_edge_point([0.0; 3], [3.0, 0.0, 0.0], [4.0, 0.0, 0.0]).unwrap();
        // p = (3s x0 + x2)/(3s + 1) with s = 1/3: 4/2 = 2.
        assert!(distance(e, [2.0, 0.0, 0.0]) < 1e-14, "{e:?}");
    }

    #[test]
    fn end_edge_point_is_f4_with_the_virtual_point() {
        let on = |t: f64| [2.0 * libm::cos(t), 2.0 * libm::sin(t), 0.5];
        let (p0, p1, p2) = (on(0.1), on(0.5), on(1.4));
        let v = virtual_end_point(p0, p1, p2).unwrap();
        let a = f4(v, p0, p1, p2).unwrap();
        let b = end_edge_point(p0, p1, p2).unwrap();
        assert!(distance(a, b) < 1e-14, "{a:?} {b:?}");
        // On the circle, between P0 and P1.
        assert!((libm::hypot(b[0], b[1]) - 2.0).abs() < 1e-14);
        let t = libm::atan2(b[1], b[0]);
        assert!(t > 0.1 && t < 0.5, "{t}");
    }

    #[test]
    fn coincident_end_points_follow_f4() {
        let (a, b) = ([0.0, 0.0, 1.0], [1.0, 2.0, 3.0]);
        assert_eq!(end_edge_point(a, a, b).unwrap(), a);
        assert_eq!(end_edge_point(a, b, b).unwrap(), b);
        assert_eq!(end_edge_point(a, b, a).unwrap(), a);
        assert_eq!(end_edge_point(a, a, a).unwrap(), a);
    }
}
