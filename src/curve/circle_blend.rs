//! The circle-blend curve scheme of seed 003 §2 ("The curve scheme"), after Séquin and Yen's
//! circular subdivision. The paper states it in the plane; in R³ the arc of each step lies in
//! the plane of its chord and the averaged tangent (below), which is the plane of the circle
//! whenever the four points are cocircular.
//!
//! For the segment `P_1 P_2` with neighbours `P_0`, `P_3`:
//! 1. `t_1` is the tangent at `P_1` of the circle `C_1` through `P_0, P_1, P_2`, `t_2` the
//!    tangent at `P_1` of the circle `C_2` through `P_1, P_2, P_3`, both oriented along the
//!    curve ([`circle_tangent`], [`circle_tangent_at_start`]: the tangent at `b` of the circle
//!    `(a, b, c)` is `(b − a)/|b − a|² + (c − b)/|c − b|²`);
//! 2. their average `t = t_1/|t_1| + t_2/|t_2|` ("First we calculate the tangent vectors t1 and
//!    t2 in P1, and their average t");
//! 3. the arc through `P_1` and `P_2` with tangent `t` at `P_1` lies in the plane of the chord
//!    and `t`; the new point `S` is its middle ([`arc_midpoint`]):
//!    `S = (P_1 + P_2)/2 + (|P_1 P_2|/2) · tan(θ/2) · N`, with `θ` the angle between `t` and
//!    the chord and `N` the unit part of `t` orthogonal to the chord.
//!
//! The paper writes the same point as `S = P_1 + cos φ · f · P_12 + sin φ · f · N` with
//! Séquin's `f(u) = b sin(u θ)/sin θ`, `φ(u) = (1 − u) θ` at `u = ½` (`b = |P_1 P_2|`,
//! `P_12` the unit chord): `f cos(θ/2) = b/2` and `f sin(θ/2) = (b/2) tan(θ/2)`, so the two
//! forms agree (tested). The tangent form needs no trigonometric function and stays accurate
//! for small `θ`.
//!
//! Interpolating; points of one circle give `t_1 = t_2` = the circle's tangent, so `S` is
//! the middle of the circle's arc `P_1 P_2`: circles are reproduced. The tangents at `P_2`
//! would give the same `S` (the reflection in the bisector plane of the chord maps each
//! circle through `P_1, P_2` to itself), so the rule is symmetric under reversal.
//!
//! Open curves: the end segment uses its only circle (so a circular arc stays on its circle up
//! to the ends): `P_0 P_1` the circle through `P_0, P_1, P_2` with its tangent at `P_0`,
//! `P_{n−2} P_{n−1}` the circle through `P_{n−3}, P_{n−2}, P_{n−1}` with its tangent at
//! `P_{n−2}`. Two points give the midpoint.
//!
//! # Degenerate input
//!
//! Each circle needs three distinct points: two points of a circle closer than 1e-13 × the
//! diameter of the points in use ([`blend_point`]: `P_0 … P_3`), a blended tangent that
//! vanishes (`t_1 = −t_2`) or points backwards along the chord (`S` at infinity) give
//! [`Status::DegenerateGeometry`], naming the first point of the segment.

use super::polygon::{at, check_level, cyclic, finite, index_u32, level_out, norm};
use crate::blend::COINCIDENT_TOLERANCE;
use crate::error::{Error, Result, Status};
use crate::point::{self, add, dot, midpoint, scale, sub, Point};

/// The cosine of the smallest angle between the blended tangent and the backward chord:
/// closer than that (`S` beyond 1e12 chord lengths) the new point counts as at infinity.
const BACKWARD_TOLERANCE: f64 = 1e-12;

/// The tangent at `b` of the circle through `a, b, c`, oriented `a → b → c`:
/// `(b − a)/|b − a|² + (c − b)/|c − b|²` (seed 000 §3.3's corner tangent `q_ab⁻¹ + q_bc⁻¹` up
/// to sign, which is the circle's tangent in R³ without computing the circle). On a line it points from `a` to `c`. Not normalised.
#[inline]
pub fn circle_tangent(a: Point, b: Point, c: Point) -> Point {
    let (u, w) = (sub(b, a), sub(c, b));
    add(scale(u, 1.0 / dot(u, u)), scale(w, 1.0 / dot(w, w)))
}

/// The tangent at `a` of the circle through `a, b, c`, oriented `a → b → c`:
/// `(b − a)/|b − a|² − (c − a)/|c − a|²` (the inversion centred at `a` maps the circle to the
/// line through the images `(b − a)/|b − a|²`, `(c − a)/|c − a|²`, which is parallel to the
/// tangent at `a`). Not normalised.
#[inline]
pub fn circle_tangent_at_start(a: Point, b: Point, c: Point) -> Point {
    let (u, w) = (sub(b, a), sub(c, a));
    sub(scale(u, 1.0 / dot(u, u)), scale(w, 1.0 / dot(w, w)))
}

/// The middle `S` of the circular arc from `p1` to `p2` whose tangent at `p1` is `t`:
/// `S = (p1 + p2)/2 + (|p1 p2|/2) tan(θ/2) N` (seed 003 §2), `θ` the angle between `t` and the
/// chord, `N` the unit part of `t` orthogonal to the chord.
///
/// With `u = t · ĉ` (`ĉ` the unit chord) and `w⃗ = t − u ĉ`: `tan(θ/2) N = w⃗ / (|t| + u)`,
/// evaluated as `(|t| − u) w⃗ / |w⃗|²` when `u < 0` to avoid cancellation. A tangent along the
/// chord gives the midpoint.
///
/// # Errors
/// [`Status::DegenerateGeometry`] when `p1 = p2`, `t = 0`, or `t` points backwards along the
/// chord (the arc is a full circle: `S` at infinity); [`Status::NumericalFailure`] on
/// overflow.
pub fn arc_midpoint(p1: Point, p2: Point, t: Point) -> Result<Point> {
    let c = sub(p2, p1);
    arc_midpoint_with(p1, p2, c, norm(c), t, norm(t))
}

/// [`arc_midpoint`] with the chord `c = p2 − p1`, its length and `|t|` already known.
fn arc_midpoint_with(p1: Point, p2: Point, c: Point, len: f64, t: Point, tl: f64) -> Result<Point> {
    let degenerate = Error::new(Status::DegenerateGeometry);
    if !(len > 0.0 && tl > 0.0) {
        return Err(degenerate);
    }
    let chat = scale(c, 1.0 / len);
    let u = dot(t, chat);
    let w = sub(t, scale(chat, u));
    let factor = if u >= 0.0 {
        0.5 * len / (tl + u)
    } else {
        let w2 = dot(w, w);
        if w2 <= (BACKWARD_TOLERANCE * tl) * (BACKWARD_TOLERANCE * tl) {
            return Err(degenerate);
        }
        0.5 * len * (tl - u) / w2
    };
    let s = add(midpoint(p1, p2), scale(w, factor));
    if point::is_finite(&s) {
        Ok(s)
    } else {
        Err(Error::new(Status::NumericalFailure))
    }
}

/// `t / |t|`, or `DegenerateGeometry` for a zero or non-finite `t`.
fn unit(t: Point) -> Result<Point> {
    let l = norm(t);
    if l > 0.0 && l.is_finite() {
        Ok(scale(t, 1.0 / l))
    } else {
        Err(Error::new(Status::DegenerateGeometry))
    }
}

/// Whether any of the given pairs coincide within 1e-13 × the largest of their distances.
/// Compares squared distances (no square roots) while they are safely representable.
fn any_coincident<const N: usize>(pairs: [(Point, Point); N]) -> bool {
    let sq = pairs.map(|(a, b)| {
        let d = sub(a, b);
        dot(d, d)
    });
    let max_sq = sq.iter().fold(0.0_f64, |m, x| m.max(*x));
    if max_sq.is_finite() && max_sq >= 1e-250 {
        let tol = COINCIDENT_TOLERANCE * COINCIDENT_TOLERANCE * max_sq;
        return sq.iter().any(|x| *x <= tol);
    }
    let d = pairs.map(|(a, b)| norm(sub(a, b)));
    let tol = COINCIDENT_TOLERANCE * d.iter().fold(0.0_f64, |m, x| m.max(*x));
    d.iter().any(|x| *x <= tol)
}

/// The circle-blend point of the segment `p1 p2` with neighbours `p0`, `p3` (seed 003 §2):
/// the middle of the arc through `p1`, `p2` whose tangent at `p1` is the average of the unit
/// tangents at `p1` of the circles `(p0, p1, p2)` and `(p1, p2, p3)`.
///
/// # Errors
/// [`Status::DegenerateGeometry`] when two points of one circle coincide (within 1e-13 × the
/// largest of their distances) or the blended tangent vanishes or points backwards along the
/// chord; [`Status::NonFiniteInput`]; [`Status::NumericalFailure`].
pub fn blend_point(p0: Point, p1: Point, p2: Point, p3: Point) -> Result<Point> {
    if ![p0, p1, p2, p3].iter().all(point::is_finite) {
        return Err(Error::new(Status::NonFiniteInput));
    }
    if any_coincident([(p0, p1), (p1, p2), (p0, p2), (p2, p3), (p1, p3)]) {
        return Err(Error::new(Status::DegenerateGeometry));
    }
    // Tangent directions only: scale the differences to the segment length first, so that
    // 1/|·|² neither overflows nor underflows.
    let chord = sub(p2, p1);
    let len = norm(chord);
    let s = 1.0 / len;
    let local = |p: Point| scale(sub(p, p1), s);
    let (q0, q2, q3) = (local(p0), scale(chord, s), local(p3));
    let origin = [0.0; 3];
    let t1 = unit(circle_tangent(q0, origin, q2))?;
    let t2 = unit(circle_tangent_at_start(origin, q2, q3))?;
    let t = add(t1, t2);
    let tl = norm(t);
    if tl <= BACKWARD_TOLERANCE {
        return Err(Error::new(Status::DegenerateGeometry));
    }
    arc_midpoint_with(p1, p2, chord, len, t, tl)
}

/// The point of the first segment `p0 p1` of an open curve: the middle of the arc `p0 p1` of
/// the circle through `p0, p1, p2` (its only circle).
///
/// # Errors
/// As [`blend_point`].
pub fn end_blend_point(p0: Point, p1: Point, p2: Point) -> Result<Point> {
    if ![p0, p1, p2].iter().all(point::is_finite) {
        return Err(Error::new(Status::NonFiniteInput));
    }
    if any_coincident([(p0, p1), (p1, p2), (p0, p2)]) {
        return Err(Error::new(Status::DegenerateGeometry));
    }
    let s = 1.0 / norm(sub(p1, p0));
    let local = |p: Point| scale(sub(p, p0), s);
    let t = circle_tangent_at_start([0.0; 3], local(p1), local(p2));
    arc_midpoint(p0, p1, t)
}

/// The point of the last segment `p1 p2` of an open curve: the middle of the arc `p1 p2` of
/// the circle through `p0, p1, p2`, from its tangent at `p1`.
///
/// # Errors
/// As [`blend_point`].
fn last_blend_point(p0: Point, p1: Point, p2: Point) -> Result<Point> {
    if any_coincident([(p0, p1), (p1, p2), (p0, p2)]) {
        return Err(Error::new(Status::DegenerateGeometry));
    }
    let s = 1.0 / norm(sub(p2, p1));
    let local = |p: Point| scale(sub(p, p1), s);
    let t = circle_tangent(local(p0), [0.0; 3], local(p2));
    arc_midpoint(p1, p2, t)
}

/// The new point of segment `i`.
fn edge_point(p: &[Point], closed: bool, i: usize) -> Result<Point> {
    let n = p.len();
    let e = if closed {
        blend_point(
            cyclic(p, i, -1)?,
            at(p, i)?,
            cyclic(p, i, 1)?,
            cyclic(p, i, 2)?,
        )
    } else if n == 2 {
        Ok(midpoint(at(p, 0)?, at(p, 1)?))
    } else if i == 0 {
        end_blend_point(at(p, 0)?, at(p, 1)?, at(p, 2)?)
    } else if i + 2 == n {
        last_blend_point(at(p, i - 1)?, at(p, i)?, at(p, i + 1)?)
    } else {
        blend_point(at(p, i - 1)?, at(p, i)?, at(p, i + 1)?, at(p, i + 2)?)
    };
    finite(e.map_err(|e| e.with_element(index_u32(i)))?, i)
}

/// One level of the circle blend; returns the number of points written (`2n` closed,
/// `2n − 1` open).
///
/// # Errors
/// [`Status::TooFewPoints`] (fewer than 3 closed / 2 open points), [`Status::SizeOverflow`],
/// [`Status::BufferTooSmall`], [`Status::NonFiniteInput`] (element = point index),
/// [`Status::DegenerateGeometry`] (element = first point of the segment, see the
/// [module documentation](self)), [`Status::NumericalFailure`].
pub fn refine(points: &[Point], closed: bool, out: &mut [Point]) -> Result<usize> {
    let next = check_level(points, closed, out)?;
    refine_level(points, closed, out)?;
    Ok(next)
}

/// One level on validated input.
pub(crate) fn refine_level(p: &[Point], closed: bool, out: &mut [Point]) -> Result<()> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::point::distance;

    #[test]
    fn tangents_of_the_unit_circle() {
        let (a, b, c) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]);
        let t = unit(circle_tangent(a, b, c)).unwrap();
        assert!(distance(t, [-1.0, 0.0, 0.0]) < 1e-15, "{t:?}");
        let t = unit(circle_tangent_at_start(a, b, c)).unwrap();
        assert!(distance(t, [0.0, 1.0, 0.0]) < 1e-15, "{t:?}");
    }

    #[test]
    fn quarter_circle_midpoint() {
        let s = arc_midpoint([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 1.0, 0.0]).unwrap();
        let h = crate::sqrt::sqrt(0.5);
        assert!(distance(s, [h, h, 0.0]) < 1e-15, "{s:?}");
        // Three quarters of a circle: tangent (0, −1) at (1, 0), chord to (0, 1).
        let s = arc_midpoint([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0]).unwrap();
        assert!(distance(s, [-h, -h, 0.0]) < 1e-15, "{s:?}");
        // Backwards: a full circle, S at infinity.
        let e = arc_midpoint([0.0; 3], [1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]).unwrap_err();
        assert_eq!(e.status, Status::DegenerateGeometry);
    }

    #[test]
    fn repeated_points_are_degenerate() {
        let p = [[0.0; 3], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 1.0, 0.0]];
        let mut out = [[0.0; 3]; 8];
        let e = refine(&p, true, &mut out).unwrap_err();
        assert_eq!(e.status, Status::DegenerateGeometry);
        assert_eq!(e.element, 0); // segment 0 uses P1 = P2 in its second circle
    }
}
