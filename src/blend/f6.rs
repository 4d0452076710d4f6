//! The six-point blend F6 (seed 000 §4.4.2, Lemma 4.2, Appendix A).
//!
//! `F6(a, b, c, d, e, f)` blends two chains of three points, `a, b, c` and `d, e, f`, into one
//! point near their middles `b` and `e`: Kobbelt's face point (two grid lines through a face)
//! and each step of the face-point chain of §4.4.3. All its cross-ratios start at `e`, which is
//! what makes the blend and the choice of axis on the negative reals Möbius-equivariant.

use super::frame::{
    self, dist_sq, max_of, normalised, pair_squares, pair_squares_bound, Normalised,
    DIFFERENCES_MAX_SQ, DIFFERENCES_MIN_SQ,
};
use super::roots::{imaginary_axis, plane_normal, sqrt_with_lazy_axis};
use super::solve::solve_by_difference;
use super::COINCIDENT_TOLERANCE;
use crate::error::{Error, Result, Status};
use crate::point::{self, sub, Point};
use crate::quat::{cross_ratio_from_prefix, CrossRatio};

/// Coordinates within ±`BOUNDED` are less than `f64::MAX` apart (`2√3 · 1e300`).
const BOUNDED: f64 = 1e300;

/// The six-point blend `F6(a, b, c, d, e, f)` of the chains `a, b, c` and `d, e, f`
/// (seed 000 §4.4.2): the point `p` with `cr[e, a, b, p] = χ`,
/// `χ = −√X · √r`, `r = (√X)⁻¹ Y (√Z)⁻¹`, `X = cr[e, a, b, d]`, `Y = cr[e, a, b, f]`,
/// `Z = cr[e, c, b, f]`.
///
/// Möbius-equivariant (all cross-ratios start at `e`), sphere preserving for six cospherical
/// points (Lemma 4.2). `b = e` (within 1e-13 × the diameter of the six points) gives `b`.
/// A negative-real `X`, `Z` or `r` takes the root `√|·| [0, n]` with `n` the unit imaginary
/// part of whichever of `X`, `Y`, `Z` is farthest from real (largest `|Im|/|·|`, first in
/// that order on ties). All three start at `e`, so a Möbius map turns their imaginary parts
/// by one and the same rotation (seed 000 §3.2), and for cospherical points they all point
/// along the sphere's normal at `e` (Appendix A, Lemma A.1): this keeps F6 Möbius-equivariant
/// and sphere preserving there. Only when all three are real (the six points cocircular in
/// pairs of four) is `n` the normal of the plane through `a, b, e`, as F4 does, with the
/// same documented discontinuity. The real part of the solution, zero for cospherical
/// points and observed to be zero otherwise (the paper has no proof), is dropped.
///
/// # Errors
/// [`Status::NonFiniteInput`]; [`Status::DegenerateGeometry`] when a cross-ratio is undefined
/// (`a = b`, `d = e`, `b = c`, `e = f`), `X` or `Z` is zero, or `p` is at infinity;
/// [`Status::NumericalFailure`] when finite inputs overflow (points more than `f64::MAX`
/// apart, or a result beyond it).
pub fn f6(a: Point, b: Point, c: Point, d: Point, e: Point, f: Point) -> Result<Point> {
    let pts = [a, b, c, d, e, f];
    if !pts.iter().all(point::is_finite) {
        return Err(Error::new(Status::NonFiniteInput));
    }
    if b == e && pts.iter().all(|p| p.iter().all(|x| x.abs() <= BOUNDED)) {
        // The rule `b = e → b` below, without the squares: coordinates within ±1e300 put
        // every pair less than f64::MAX apart, so the rule applies. (The face-point chain
        // meets this whenever a quadruplet's F4 is reused.)
        return Ok(b);
    }
    // The common case without the 15 pair squares: if `|b − e|²` is at least the lower end of
    // the difference range, the bounding box's bound (`pair_squares_bound`, at least the
    // largest pair square) at most the upper end, and `|b − e|²` above the coincidence
    // tolerance times the bound (so above it times the largest pair: a product with a
    // positive constant rounds monotonically), then the careful path below takes the
    // difference range and passes the rule `b = e`: it runs the formula on `pts`, as here.
    let be = dist_sq(b, e);
    let bound = pair_squares_bound(&pts);
    if be >= DIFFERENCES_MIN_SQ
        && bound <= DIFFERENCES_MAX_SQ
        && be > COINCIDENT_TOLERANCE * COINCIDENT_TOLERANCE * bound
    {
        return f6_fast(&pts);
    }
    f6_careful(&pts)
}

/// The common case of [`f6`]: the formula in world coordinates. Out of line, as
/// [`f6_careful`] is, so that `f6`'s own frame holds neither path's temporaries and the
/// deepest stack is one path's, not the sum of both (`docs/firmware.md`, "Stack"); a call
/// per blend costs nothing measurable next to the formula.
#[inline(never)]
fn f6_fast(pts: &[Point; 6]) -> Result<Point> {
    f6_formula(*pts).and_then(|p| frame::to_world(None, p))
}

/// [`f6`] on finite points with the largest pair square computed: the difference range or the
/// normalised frame (`frame.rs`), then the rule `b = e → b` or the formula.
#[inline(never)]
fn f6_careful(pts: &[Point; 6]) -> Result<Point> {
    let b = pts[1];
    let sq = pair_squares(pts);
    let max_sq = max_of(&sq);
    let (found, frame) = if (DIFFERENCES_MIN_SQ..=DIFFERENCES_MAX_SQ).contains(&max_sq) {
        (f6_in(pts, &sq, max_sq)?, None)
    } else {
        match normalised(pts, &sq)? {
            None => (None, None),
            Some(Normalised {
                frame,
                local,
                local_sq,
            }) => (f6_in(&local, &local_sq, max_of(&local_sq))?, Some(frame)),
        }
    };
    match found {
        None => Ok(b),
        Some(p) => frame::to_world(frame, p),
    }
}

/// F6 on six finite points with pairwise squares `sq` (pairs in lexicographic order) whose
/// largest is `max_sq`, in world or normalised-frame coordinates: `None` for the rule
/// `b = e → b`, else the solved point.
fn f6_in(pts: &[Point; 6], sq: &[f64; 15], max_sq: f64) -> Result<Option<Point>> {
    // Pair (b, e) is the 8th: ab ac ad ae af bc bd be.
    let be = sq.get(7).copied().unwrap_or(f64::INFINITY);
    if be <= COINCIDENT_TOLERANCE * COINCIDENT_TOLERANCE * max_sq {
        return Ok(None);
    }
    f6_formula(*pts).map(Some)
}

/// The formula of [`f6`] on six finite points (world or normalised-frame coordinates) with
/// `b ≠ e`: the cross-ratios, their roots and the solve of Eq. (3).
#[inline(always)]
fn f6_formula([a, b, c, d, e, f]: [Point; 6]) -> Result<Point> {
    let degenerate = Error::new(Status::DegenerateGeometry);
    // X = cr[e, a, b, d] = q_ea q_ab⁻¹ q_bd q_de⁻¹ and Y = cr[e, a, b, f] share the prefix
    // (a − e)(b − a)⁻¹, which is also the M of the solve; Z = cr[e, c, b, f].
    let cx = CrossRatio::from_differences(sub(a, e), sub(b, a), sub(d, b), sub(e, d))?;
    let x = cx.value()?;
    let y = cross_ratio_from_prefix(cx.prefix, e, b, f)?;
    // Z = cr[e, c, b, f] from its differences: the inputs are finite (`f6`), so this is
    // `cross_ratio(e, c, b, f)` bit for bit without its finiteness tests.
    let z = CrossRatio::from_differences(sub(c, e), sub(b, c), sub(f, b), sub(e, f))?.value()?;
    let abs = [x.abs(), y.abs(), z.abs()];
    // The axis n for the negative-real case (and whether to snap to it): the most imaginary
    // of X, Y, Z, else the plane normal. It is read only by a root of a quaternion with
    // negative real part, so it is searched for only then (`sqrt_with_lazy_axis`: the same
    // bits; a few calls in ten thousand on the meshes of docs/RESULTS.md).
    let mut axis = None;
    let find = || {
        let found = imaginary_axis(&[x, y, z], &abs);
        (
            found.unwrap_or_else(|| plane_normal(a, b, e)),
            found.is_some(),
        )
    };
    let sx = sqrt_with_lazy_axis(x, abs[0], &mut axis, find).ok_or(degenerate)?;
    let sz = sqrt_with_lazy_axis(z, abs[2], &mut axis, find).ok_or(degenerate)?;
    let r = sx.inverse().ok_or(degenerate)? * y * sz.inverse().ok_or(degenerate)?;
    let sr = sqrt_with_lazy_axis(r, r.abs(), &mut axis, find).ok_or(degenerate)?;
    let chi = -(sx * sr);
    solve_by_difference(cx.prefix, b, e, chi)
}

#[cfg(test)]
mod tests {
    use super::super::is_negative_real;
    use super::super::roots::sqrt_snapped_with_abs;
    use super::super::solve::solve_cross_ratio;
    use super::super::testing::lcg_points;
    use super::*;
    use crate::point::distance;
    use crate::quat::cross_ratio;

    /// [`f6_in`] as it is printed in seed 000 §4.4.2, every step taken: all inputs tested for
    /// finiteness by `cross_ratio`, the axis searched before any root. The reference that
    /// `f6_in`'s shortcuts (lazy axis, `Z` from differences) must match bit for bit.
    fn f6_in_eager(
        [a, b, c, d, e, f]: [Point; 6],
        sq: [f64; 15],
        max_sq: f64,
    ) -> Result<Option<Point>> {
        let be = sq[7];
        if be <= COINCIDENT_TOLERANCE * COINCIDENT_TOLERANCE * max_sq {
            return Ok(None);
        }
        let degenerate = Error::new(Status::DegenerateGeometry);
        let cx = CrossRatio::new(e, a, b, d)?;
        let x = cx.value()?;
        let y = cross_ratio_from_prefix(cx.prefix, e, b, f)?;
        let z = cross_ratio(e, c, b, f)?;
        let abs = [x.abs(), y.abs(), z.abs()];
        let axis = imaginary_axis(&[x, y, z], &abs);
        let snap = axis.is_some();
        let n = axis.unwrap_or_else(|| plane_normal(a, b, e));
        let sx = sqrt_snapped_with_abs(x, abs[0], n, snap).ok_or(degenerate)?;
        let sz = sqrt_snapped_with_abs(z, abs[2], n, snap).ok_or(degenerate)?;
        let r = sx.inverse().ok_or(degenerate)? * y * sz.inverse().ok_or(degenerate)?;
        let sr = sqrt_snapped_with_abs(r, r.abs(), n, snap).ok_or(degenerate)?;
        let chi = -(sx * sr);
        solve_by_difference(cx.prefix, b, e, chi).map(Some)
    }

    /// Bitwise equality of two results (points by bits, errors by status).
    fn same(p: Result<Option<Point>>, q: Result<Option<Point>>) -> bool {
        match (p, q) {
            (Ok(Some(p)), Ok(Some(q))) => p.iter().zip(q).all(|(x, y)| x.to_bits() == y.to_bits()),
            (Ok(None), Ok(None)) => true,
            (Err(p), Err(q)) => p.status == q.status,
            _ => false,
        }
    }

    /// Bitwise equality of two results of `f6`.
    fn same_point(p: Result<Point>, q: Result<Point>) -> bool {
        same(p.map(Some), q.map(Some))
    }

    #[test]
    fn f6_shortcut_is_the_careful_path_bit_for_bit() {
        // `f6` decides from the bounding box where `f6_careful` takes the largest of the 15
        // pair squares. Random chains at scales around both ends of the difference range
        // (diameters 1e-100 and 1e100, where the bound and the largest pair straddle an end),
        // with `b − e` around the coincidence tolerance (1e-13 of the diameter), and far out.
        let mut state = 5;
        let (mut shortcut, mut careful, mut coincident) = (0, 0, 0);
        let scaled = |p: Point, s: f64| p.map(|x| x * s);
        for i in 0..60_000u64 {
            let mut pts: [Point; 6] = lcg_points(&mut state);
            let s = [1.0, 1e-100, 2e-100, 0.6e100, 1e100, 1e150, 1e-160][(i % 7) as usize];
            pts = pts.map(|p| scaled(p, s));
            if i % 3 == 1 {
                // b − e of 0.3 to 3 times the tolerance of the chain's extent.
                let t = (0.3 + (i % 11) as f64 * 0.27) * COINCIDENT_TOLERANCE * s;
                pts[4] = [pts[1][0] + t, pts[1][1], pts[1][2]];
            }
            if i % 13 == 0 {
                // Coordinates far from the origin, small spread: the subtractions round.
                pts = pts.map(|p| [p[0] + 3e7 * s, p[1] - 1e7 * s, p[2]]);
            }
            let [a, b, c, d, e, f] = pts;
            let fast = f6(a, b, c, d, e, f);
            let slow = f6_careful(&pts);
            assert!(
                same_point(fast, slow),
                "{pts:?}: {:?} vs {:?}",
                fast.ok(),
                slow.ok()
            );
            let bound = pair_squares_bound(&pts);
            let be = dist_sq(b, e);
            if be >= DIFFERENCES_MIN_SQ
                && bound <= DIFFERENCES_MAX_SQ
                && be > COINCIDENT_TOLERANCE * COINCIDENT_TOLERANCE * bound
            {
                shortcut += 1;
            } else {
                careful += 1;
            }
            if slow.is_ok_and(|p| p == b) {
                coincident += 1;
            }
        }
        // Both branches and the rule `b = e` are exercised.
        assert!(
            shortcut > 10_000 && careful > 10_000,
            "{shortcut} / {careful}"
        );
        assert!(coincident > 1_000, "{coincident}");
    }

    #[test]
    fn pair_squares_bound_bounds_every_pair() {
        let mut state = 3;
        for i in 0..20_000u64 {
            let s = libm::ldexp(1.0, (i % 41) as i32 * 50 - 1000);
            let pts: [Point; 6] = lcg_points(&mut state);
            let pts = pts.map(|p| p.map(|x| x * s + 1e3 * s));
            let sq: [f64; 15] = pair_squares(&pts);
            assert!(max_of(&sq) <= pair_squares_bound(&pts), "{pts:?}");
        }
    }

    #[test]
    fn f6_in_is_the_eager_evaluation_bit_for_bit() {
        // Random chains, chains on a sphere (X, Y, Z imaginary along one axis: snapping),
        // on a circle (all real: the plane normal), across the negative-real cut (a rotated
        // copy of the chain a, b, c, d, e, f of the test below, nudged by a few ulps to both
        // sides), and with coincident pairs (degenerate cross-ratios).
        let mut state = 11;
        let mut negative = 0;
        let mut compared = 0;
        let on_sphere = |p: Point| {
            let n = crate::point::norm(p);
            [p[0] / n, p[1] / n, p[2] / n]
        };
        let nudge = |p: Point, k: u64| p.map(|x| f64::from_bits(x.to_bits().wrapping_add(k)));
        let base: [Point; 6] = [
            [-1.0, 0.1, 0.0],
            [0.0; 3],
            [1.0, -0.05, 0.0],
            [-0.8, -1.3, 0.0],
            [-1.987, 0.7, 0.0],
            [-2.0, -2.0, 0.0],
        ];
        for i in 0..40_000u64 {
            let random: [Point; 6] = lcg_points(&mut state);
            let pts = match i % 5 {
                0 => random,
                1 => random.map(on_sphere),
                2 => random.map(|p| on_sphere([p[0], p[1], 0.0])),
                3 => {
                    let [u, ..] = random;
                    base.map(|p| nudge([p[0] + 1e-9 * u[0], p[1], p[2] + 1e-9 * u[2]], i % 7))
                }
                _ => {
                    let mut p = random;
                    let (from, to) = ((i / 5 % 6) as usize, (i / 30 % 6) as usize);
                    p[to] = nudge(p[from], i % 3);
                    p
                }
            };
            let sq = pair_squares(&pts);
            let max_sq = max_of(&sq);
            let [a, b, _, d, e, _] = pts;
            if let (Ok(x), Ok(z)) = (cross_ratio(e, a, b, d), cross_ratio(e, pts[2], b, pts[5])) {
                if x.w < 0.0 || z.w < 0.0 {
                    negative += 1;
                }
            }
            let (fast, eager) = (f6_in(&pts, &sq, max_sq), f6_in_eager(pts, sq, max_sq));
            assert!(
                same(fast, eager),
                "{pts:?}: {:?} vs {:?}",
                fast.ok(),
                eager.ok()
            );
            compared += 1;
        }
        assert_eq!(compared, 40_000);
        // The lazy branch (an axis needed) is exercised, not only the shortcut.
        assert!(negative > 1_000, "{negative} negative-real-part cases");
    }

    #[test]
    fn f6_with_a_negative_real_r_stays_on_the_sphere_and_commutes() {
        // Six coplanar points with r = (√X)⁻¹ Y (√Z)⁻¹ = −1 exactly: d is solved from
        // √X = −Y (√Z)⁻¹ (real part > 0 for these points).
        let (a, b, c) = ([-1.0, 0.1, 0.0], [0.0; 3], [1.0, -0.05, 0.0]);
        let (e, f) = ([-1.987, 0.7, 0.0], [-2.0, -2.0, 0.0]);
        let y = cross_ratio(e, a, b, f).unwrap();
        let sz = cross_ratio(e, c, b, f).unwrap().sqrt().unwrap();
        let sx = -(y * sz.inverse().unwrap());
        assert!(sx.w > 0.1);
        let d = solve_cross_ratio(a, b, e, sx * sx).unwrap();
        let x = cross_ratio(e, a, b, d).unwrap();
        let r = x.sqrt().unwrap().inverse().unwrap() * y * sz.inverse().unwrap();
        assert!(is_negative_real(r), "{r:?}");
        let p = f6(a, b, c, d, e, f).unwrap();
        assert!(p[2].abs() < 1e-15, "{p:?}");
        // An inversion maps the plane z = 0 to a sphere through its centre m; r stays a
        // negative real, and the new point must stay on that sphere and commute with the map.
        let (m, rad) = ([0.3, -0.2, 0.7], 0.9);
        let inv = crate::mobius::MobiusMap::inversion(m, rad);
        let im = [a, b, c, d, e, f].map(|q| inv.apply(q).unwrap());
        let q = f6(im[0], im[1], im[2], im[3], im[4], im[5]).unwrap();
        let big_r = rad * rad / (2.0 * m[2]);
        let centre = [m[0], m[1], m[2] - big_r];
        assert!(
            (distance(q, centre) - big_r).abs() < 1e-13,
            "{q:?} off the sphere"
        );
        assert!(distance(q, inv.apply(p).unwrap()) < 1e-13, "{q:?}");
    }

    #[test]
    fn f6_with_b_equal_e_returns_b() {
        let b = [0.5, 0.5, 0.1];
        let p = f6(
            [0.0; 3],
            b,
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            b,
            [1.0, 1.0, 0.0],
        )
        .unwrap();
        assert_eq!(p, b);
    }

    #[test]
    fn f6_on_a_planar_regular_grid_gives_the_centre() {
        // Kobbelt face point of a unit square cell of a regular grid: two chains through the
        // edge points meet at the cell centre (seed 000 Fig. 14).
        let p = f6(
            [0.0, 0.5, 0.0],
            [0.5, 0.5, 0.0],
            [1.0, 0.5, 0.0],
            [0.5, 0.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.5, 1.0, 0.0],
        )
        .unwrap();
        assert_eq!(p, [0.5, 0.5, 0.0]);
    }
}
