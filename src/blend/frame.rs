//! The coordinates the blends compute in: the inputs themselves, or their image in a
//! normalised frame (seed 000 §4.4, Eq. (3)).
//!
//! Every quantity of Eq. (3) except the final offset is a ratio of lengths (cross-ratios, `M`,
//! `χ`), so a blend may run on any similar copy of its inputs: similarities are Möbius maps.
//! Inputs of moderate diameter ([`DIFFERENCES_MIN_SQ`]..=[`DIFFERENCES_MAX_SQ`]) are used as
//! they are, reading only their differences; others are moved to the frame with centroid at
//! the origin and unit diameter ([`normalised`]), solved there, and the point moved back
//! ([`to_world`]). The frame divides by its size and never multiplies by `1/size`, and a
//! centroid whose sum overflows is averaged from scaled points instead: subnormal and
//! near-`f64::MAX` inputs are finite and must give finite results.

use crate::error::{Error, Result, Status};
use crate::point::{self, add, norm, scale, sub, Point};
use crate::quat::Quat;

/// A similarity frame: `x ↦ (x − centre) / size`.
#[derive(Clone, Copy)]
pub(super) struct Frame {
    centre: Point,
    size: f64,
}

/// `|p − q|²` as [`norm`] forms it (so that its square root is `norm(sub(p, q))` bit for bit).
#[inline]
pub(super) fn dist_sq(p: Point, q: Point) -> f64 {
    Quat::from_point(sub(p, q)).norm_sq()
}

/// Above this largest squared distance the size is the square root of the largest squared
/// distance. A distance in the scaled range of [`norm`] (squares up to `SAFE_MIN` = 1e-250)
/// is then below 1.1e-125 < 1e-120, so it cannot be the maximum, and the square root being
/// monotone and correctly rounded, the result equals the largest of the distances bit for bit.
const SIZE_BY_SQUARES_MIN: f64 = 1e-240;

impl Frame {
    /// The frame of `points` whose pairwise squared distances (`dist_sq`, pairs `(i, j)`,
    /// `i < j`, in that order) are `sq`: centroid and diameter.
    fn from_squares(points: &[Point], sq: &[f64]) -> Frame {
        let inv_n = 1.0 / points.len() as f64;
        let mut centre = [0.0; 3];
        for p in points {
            centre = add(centre, *p);
        }
        centre = scale(centre, inv_n);
        if !point::is_finite(&centre) {
            // The sum overflowed (coordinates near f64::MAX): average the scaled points instead.
            centre = [0.0; 3];
            for p in points {
                centre = add(centre, scale(*p, inv_n));
            }
        }
        // One square root of the largest square instead of one per pair (same bits, see
        // SIZE_BY_SQUARES_MIN); the pairwise loop where that argument does not hold.
        // (The squares of finite points are never NaN, so `>` is `f64::max` here.)
        let mut max_sq = 0.0;
        for &x in sq {
            if x > max_sq {
                max_sq = x;
            }
        }
        let size = if max_sq.is_finite() && max_sq > SIZE_BY_SQUARES_MIN {
            crate::sqrt::sqrt(max_sq)
        } else {
            let mut size: f64 = 0.0;
            for (i, p) in points.iter().enumerate() {
                for q in points.iter().skip(i + 1) {
                    size = size.max(norm(sub(*p, *q)));
                }
            }
            size
        };
        Frame { centre, size }
    }

    /// The image of a world point in the frame.
    pub(super) fn to_local(self, p: Point) -> Point {
        // Divide (rather than multiply by 1/size, which overflows for a subnormal size).
        let d = sub(p, self.centre);
        [d[0] / self.size, d[1] / self.size, d[2] / self.size]
    }

    /// The world point of a point of the frame.
    fn to_world(self, p: Point) -> Point {
        add(self.centre, scale(p, self.size))
    }
}

/// The pairwise squared distances of `N` points, pairs `(i, j)` with `i < j` in
/// lexicographic order (`M = N (N − 1) / 2`).
pub(super) fn pair_squares<const N: usize, const M: usize>(p: &[Point; N]) -> [f64; M] {
    let mut out = [0.0; M];
    let mut k = 0;
    for (i, a) in p.iter().enumerate() {
        for b in p.iter().skip(i + 1) {
            if let Some(o) = out.get_mut(k) {
                *o = dist_sq(*a, *b);
            }
            k += 1;
        }
    }
    out
}

/// An upper bound of every [`pair_squares`] entry of finite points: [`dist_sq`] of the corners
/// of their bounding box. Every operation of [`dist_sq`] is correctly rounded and so monotone
/// in each argument: a coordinate difference is at most the box's extent before rounding, so
/// also after, and the same holds for its square and the sums, in the same order. Six points
/// take 15 squared distances but only one here: F6 compares this bound instead of the largest
/// pair where that decides the same way (`f6`). `+∞` when the extent overflows.
#[inline(always)]
pub(super) fn pair_squares_bound<const N: usize>(p: &[Point; N]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for q in p {
        for ((&x, l), h) in q.iter().zip(&mut lo).zip(&mut hi) {
            // Finite inputs, no NaN: the comparisons are `min` and `max`.
            if x < *l {
                *l = x;
            }
            if x > *h {
                *h = x;
            }
        }
    }
    dist_sq(hi, lo)
}

/// Squared diameters between which the blends work on the input coordinates themselves:
/// diameters in [1e-100, 1e100]. Every quantity of Eq. (3) except the final offset is a ratio
/// of lengths (cross-ratios, `M`, `χ`), the solve reads only the difference `b − e`
/// ([`super::solve::solve_by_difference`]), and a pair tested for coincidence that is not
/// coincident is at least 1e-13 × 1e-100 apart, so its square and inverse stay in
/// `[SAFE_MIN, SAFE_MAX]`; other pairs (F6's `a, b`, `d, e`, `c, b`, `e, f`, a hint's
/// difference, `M + χ`) can leave it, and go through the scaled slow paths of the inverses.
/// The blends then read only differences of the inputs, each rounded once. Outside, the inputs
/// are moved to the normalised frame first.
pub(super) const DIFFERENCES_MIN_SQ: f64 = 1e-200;
/// The upper end of the range of [`DIFFERENCES_MIN_SQ`].
pub(super) const DIFFERENCES_MAX_SQ: f64 = 1e200;

/// The largest of `sq` (squares of finite points: never NaN, so `>` is `f64::max`).
pub(super) fn max_of(sq: &[f64]) -> f64 {
    let mut m = 0.0;
    for &x in sq {
        if x > m {
            m = x;
        }
    }
    m
}

/// The normalised frame of points whose diameter is outside
/// `[DIFFERENCES_MIN_SQ, DIFFERENCES_MAX_SQ]`, with the points and their pairwise squares in
/// it; `None` when all points are equal (the coincidence rules then answer on zero squares).
/// Out of line and cold: the common path stays small.
#[cold]
#[inline(never)]
pub(super) fn normalised<const N: usize, const M: usize>(
    pts: &[Point; N],
    sq: &[f64; M],
) -> Result<Option<Normalised<N, M>>> {
    let frame = Frame::from_squares(pts, sq);
    if !frame.size.is_finite() {
        return Err(Error::new(Status::NumericalFailure));
    }
    if frame.size == 0.0 {
        return Ok(None);
    }
    let local = pts.map(|p| frame.to_local(p));
    Ok(Some(Normalised {
        frame,
        local,
        local_sq: pair_squares(&local),
    }))
}

/// Points in their normalised frame ([`normalised`]).
pub(super) struct Normalised<const N: usize, const M: usize> {
    /// The frame.
    pub(super) frame: Frame,
    /// The points in the frame.
    pub(super) local: [Point; N],
    /// Their pairwise squared distances, as [`pair_squares`].
    pub(super) local_sq: [f64; M],
}

/// A solved point in working coordinates back in the world: [`Status::NumericalFailure`] when
/// it lies beyond the range of `f64`.
#[inline]
pub(super) fn to_world(frame: Option<Frame>, p: Point) -> Result<Point> {
    let out = match frame {
        Some(frame) => frame.to_world(p),
        None => p,
    };
    if point::is_finite(&out) {
        Ok(out)
    } else {
        Err(Error::new(Status::NumericalFailure))
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::lcg_points;
    use super::super::{f4, f4_hinted, f6};
    use crate::error::Result;
    use crate::point::{self, distance, norm, Point};

    #[test]
    fn difference_path_agrees_with_the_framed_path_and_scales_exactly() {
        // Diameters inside [1e-100, 1e100] take the difference path, outside the normalised
        // frame. Scaling by a power of two is exact, so (a) within the difference path the
        // result scales bit for bit, and (b) the framed path on points scaled by 2^-400
        // (diameter ~1e-120) must give the same point to rounding.
        let scaled = |p: Point, k: i32| p.map(|x| libm::ldexp(x, k));
        let mut state = 7;
        let mut worst: f64 = 0.0;
        for _ in 0..2000 {
            let pts: [Point; 6] = lcg_points(&mut state);
            let [a, b, c, d, e, f] = pts;
            type AtScale<'a> = &'a dyn Fn(i32) -> Result<Point>;
            let cases: [(Result<Point>, AtScale); 3] = [
                (f4_hinted(a, b, c, d, e), &|k| {
                    f4_hinted(
                        scaled(a, k),
                        scaled(b, k),
                        scaled(c, k),
                        scaled(d, k),
                        scaled(e, k),
                    )
                }),
                (f4(a, b, c, d), &|k| {
                    f4(scaled(a, k), scaled(b, k), scaled(c, k), scaled(d, k))
                }),
                (f6(a, b, c, d, e, f), &|k| {
                    f6(
                        scaled(a, k),
                        scaled(b, k),
                        scaled(c, k),
                        scaled(d, k),
                        scaled(e, k),
                        scaled(f, k),
                    )
                }),
            ];
            for (base, at_scale) in cases {
                let Ok(p) = base else {
                    continue;
                };
                let p_up = at_scale(60).unwrap();
                assert_eq!(scaled(p_up, -60), p, "difference path not scale-exact");
                let framed = scaled(at_scale(-400).unwrap(), 400);
                let size = 1.0 + norm(p);
                worst = worst.max(distance(framed, p) / size);
            }
        }
        // Both paths round a few times per step: observed 3.7e-15 of (1 + |p|).
        assert!(worst <= 1e-13, "difference vs framed path: {worst:e}");
    }

    #[test]
    fn f4_at_the_ends_of_the_f64_range() {
        // Subnormal coordinates: the frame size is subnormal and 1/size overflows; the inputs
        // are finite, so the answer must not be NonFiniteInput.
        let t = 5e-324;
        let p = f4([0.0; 3], [0.0, t, 0.0], [t, 0.0, 0.0], [0.0, 0.0, t]).unwrap();
        assert!(point::is_finite(&p));
        // Coordinates near f64::MAX whose sum overflows but whose spread does not.
        let m = f64::MAX;
        let (a, b, c, d) = (
            [0.9 * m, 0.0, 0.0],
            [0.8 * m, 0.1 * m, 0.0],
            [0.7 * m, 0.1 * m, 0.1 * m],
            [0.6 * m, 0.0, 0.1 * m],
        );
        let p = f4(a, b, c, d).unwrap();
        assert!(point::is_finite(&p));
        let q = f6(
            a,
            b,
            c,
            d,
            [0.8 * m, 0.05 * m, 0.0],
            [0.75 * m, 0.0, 0.05 * m],
        )
        .unwrap();
        assert!(point::is_finite(&q));
    }
}
