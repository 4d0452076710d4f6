//! The linear interpolating 4-point scheme of Dyn, Levin and Gregory (1987), `w = 1/16`
//! (seed 003 §1, reference Dyn87; the linear rule that seed 000 §4.4.1 converts into the Möbius
//! interpolating rule).
//!
//! One level, output interleaved as in [`crate::curve`]:
//! * vertex points: `P'_{2i} = P_i` (interpolating, bit for bit);
//! * edge points: `P'_{2i+1} = 9/16 (P_i + P_{i+1}) − 1/16 (P_{i−1} + P_{i+2})`, which
//!   reproduces cubic polynomials on uniformly sampled data.
//!
//! Open curves use the virtual points `P_{−1} = 2P_0 − P_1` and `P_n = 2P_{n−1} − P_{n−2}`
//! (linear extrapolation, the linear counterpart of the Möbius rules' virtual end point); the
//! end segments then reproduce linear data only. Two points give
//! the midpoint (which the virtual points produce by themselves).

use super::polygon::{at, check_level, cyclic, finite, level_out};
use crate::error::Result;
use crate::point::{add, scale, sub, Point};

/// Weight of the two inner points, `1/2 + w` with `w = 1/16`.
pub const INNER_WEIGHT: f64 = 0.5625;
/// Weight of the two outer points, `−w`.
pub const OUTER_WEIGHT: f64 = -0.0625;

/// The 4-point edge point `9/16 (b + c) − 1/16 (a + d)` of the segment `b c`.
#[inline]
pub fn edge_point(a: Point, b: Point, c: Point, d: Point) -> Point {
    add(
        scale(add(b, c), INNER_WEIGHT),
        scale(add(a, d), OUTER_WEIGHT),
    )
}

/// The virtual point before `p0` on an open curve: `2 p0 − p1`.
#[inline]
pub fn virtual_end_point(p0: Point, p1: Point) -> Point {
    sub(scale(p0, 2.0), p1)
}

/// One level of the 4-point scheme; returns the number of points written (`2n` closed,
/// `2n − 1` open).
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
    for (i, pair) in out.chunks_mut(2).enumerate().take(n) {
        let pi = at(p, i)?;
        match pair {
            [even, odd] => {
                *even = pi;
                let e = if closed {
                    edge_point(cyclic(p, i, -1)?, pi, cyclic(p, i, 1)?, cyclic(p, i, 2)?)
                } else {
                    let p1 = at(p, i + 1)?;
                    let a = if i == 0 {
                        virtual_end_point(pi, p1)
                    } else {
                        at(p, i - 1)?
                    };
                    let d = if i + 2 < n {
                        at(p, i + 2)?
                    } else {
                        virtual_end_point(p1, pi)
                    };
                    edge_point(a, pi, p1, d)
                };
                *odd = finite(e, i)?;
            }
            [even] => *even = pi,
            _ => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mask_is_the_textbook_one() {
        // An impulse on a closed 8-gon: the edge points carry the mask −1/16, 9/16, 9/16, −1/16.
        let mut p = [[0.0; 3]; 8];
        p[3] = [1.0, 0.0, 0.0];
        let mut out = [[0.0; 3]; 16];
        assert_eq!(refine(&p, true, &mut out).unwrap(), 16);
        let xs: [f64; 16] = core::array::from_fn(|i| out[i][0]);
        let mut expected = [0.0; 16];
        expected[6] = 1.0;
        expected[3] = -1.0 / 16.0;
        expected[5] = 9.0 / 16.0;
        expected[7] = 9.0 / 16.0;
        expected[9] = -1.0 / 16.0;
        assert_eq!(xs, expected);
    }

    #[test]
    fn two_points_give_the_midpoint() {
        let mut out = [[0.0; 3]; 3];
        refine(&[[0.0, 0.0, 0.0], [2.0, 4.0, -6.0]], false, &mut out).unwrap();
        assert_eq!(out, [[0.0, 0.0, 0.0], [1.0, 2.0, -3.0], [2.0, 4.0, -6.0]]);
    }
}
