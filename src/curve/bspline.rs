//! The cubic B-spline curve scheme (Lane–Riesenfeld, degree 3): the linear approximating
//! rule that seed 000 §4.4.1 converts into the Möbius approximating rule, and the boundary
//! rule of Loop and Catmull–Clark (the mesh drivers subdivide every boundary loop as a
//! closed curve with this rule, as CGAL and OpenSubdiv do).
//!
//! One level, output interleaved as in [`crate::curve`]:
//! * edge points: `P'_{2i+1} = (P_i + P_{i+1}) / 2`;
//! * vertex points: `P'_{2i} = 3/4 P_i + 1/8 (P_{i−1} + P_{i+1})`, the mask `(1, 6, 1)/8`.
//!
//! Open curves keep both end points (`P'_0 = P_0`, `P'_{2n−2} = P_{n−1}`), the crease rule
//! of CGAL and OpenSubdiv, so that a curve's ends stay where the user put them; linear data
//! stays linear. Two points give the
//! midpoint.

use super::polygon::{at, check_level, cyclic, finite, level_out};
use crate::error::Result;
use crate::point::{add, midpoint, scale, Point};

/// The weight of the old point in a vertex point, `6/8`.
pub const VERTEX_WEIGHT: f64 = 0.75;
/// The weight of each neighbour in a vertex point, `1/8`.
pub const NEIGHBOUR_WEIGHT: f64 = 0.125;

/// The vertex point `3/4 b + 1/8 (a + c)` of `b` with neighbours `a`, `c`.
#[inline]
pub fn vertex_point(a: Point, b: Point, c: Point) -> Point {
    add(scale(b, VERTEX_WEIGHT), scale(add(a, c), NEIGHBOUR_WEIGHT))
}

/// One level of the cubic B-spline scheme; returns the number of points written (`2n`
/// closed, `2n − 1` open).
///
/// # Errors
/// [`crate::Status::TooFewPoints`] (fewer than 3 closed / 2 open points),
/// [`crate::Status::SizeOverflow`], [`crate::Status::BufferTooSmall`],
/// [`crate::Status::NonFiniteInput`] (element = point index),
/// [`crate::Status::NumericalFailure`] on overflow.
pub fn refine(points: &[Point], closed: bool, out: &mut [Point]) -> Result<usize> {
    let next = check_level(points, closed, out)?;
    refine_level(points, closed, out)?;
    Ok(next)
}

/// One level on validated input (see `LevelRule` in `levels.rs`).
pub(crate) fn refine_level(p: &[Point], closed: bool, out: &mut [Point]) -> Result<()> {
    let out = level_out(p, closed, out)?;
    let n = p.len();
    for (i, pair) in out.chunks_mut(2).enumerate() {
        let pi = at(p, i)?;
        let (even, odd) = match pair {
            [even, odd] => (even, Some(odd)),
            [even] => (even, None),
            _ => continue,
        };
        *even = if closed {
            finite(vertex_point(cyclic(p, i, -1)?, pi, cyclic(p, i, 1)?), i)?
        } else if i == 0 || i + 1 == n {
            pi
        } else {
            finite(vertex_point(at(p, i - 1)?, pi, at(p, i + 1)?), i)?
        };
        if let Some(odd) = odd {
            let next = if closed {
                cyclic(p, i, 1)?
            } else {
                at(p, i + 1)?
            };
            *odd = finite(midpoint(pi, next), i)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mask_is_the_textbook_one() {
        // An impulse on a closed 8-gon gives the mask 1/8, 1/2, 3/4, 1/2, 1/8.
        let mut p = [[0.0; 3]; 8];
        p[3] = [1.0, 0.0, 0.0];
        let mut out = [[0.0; 3]; 16];
        assert_eq!(refine(&p, true, &mut out).unwrap(), 16);
        let xs: [f64; 16] = core::array::from_fn(|i| out[i][0]);
        let mut expected = [0.0; 16];
        expected[4] = 0.125;
        expected[5] = 0.5;
        expected[6] = 0.75;
        expected[7] = 0.5;
        expected[8] = 0.125;
        assert_eq!(xs, expected);
    }

    #[test]
    fn open_ends_are_kept() {
        let p = [[0.0, 0.0, 0.0], [1.0, 2.0, 0.0], [3.0, 1.0, 1.0]];
        let mut out = [[0.0; 3]; 5];
        refine(&p, false, &mut out).unwrap();
        assert_eq!(out[0], p[0]);
        assert_eq!(out[4], p[2]);
        assert_eq!(out[1], [0.5, 1.0, 0.0]);
        assert_eq!(out[2], [1.125, 1.625, 0.125]);
    }
}
