//! The four-point blend F4 (seed 000 §4.4.1, Eq. (3), Lemma 4.1).
//!
//! `F4(a, b, c, d)` is the point `p` with `cr[c, a, b, p] = −√cr[c, a, b, d]`: the Möbius
//! analogue of the 4-point rule's edge point between `b` and `c`. It is the edge rule of the
//! Möbius curve schemes and of every Möbius mesh scheme, and the first step of a face point.
//!
//! The evaluation, in order: the coincidence rules ([`coincidence_rule`]); the cross-ratio
//! `ρ = cr[c, a, b, d]`; the order to solve in (Lemma 4.1 lets F4 solve the mirrored
//! quadruplet `(d, c, b, a)` where that is better conditioned, [`solve_order`]); the root χ
//! ([`chi`], with the axis of a hint in the negative-real case, [`hint_axis`]); Eq. (3).

use super::frame::{
    self, max_of, normalised, pair_squares, Normalised, DIFFERENCES_MAX_SQ, DIFFERENCES_MIN_SQ,
};
use super::roots::{is_negative_real_with_abs, plane_normal, sqrt_snapped_with_abs};
use super::solve::solve_by_difference;
use super::{COINCIDENT_TOLERANCE, NEGATIVE_REAL_TOLERANCE};
use crate::error::{Error, Result, Status};
use crate::point::{self, sub, Point};
use crate::quat::{cross_ratio, cross_ratio_from_prefix, CrossRatio, Quat};

/// The four-point blend `F4(a, b, c, d)`: the point `p` with `cr[c, a, b, p] = −√cr[c, a, b, d]`
/// (seed 000 §4.4.1, Eq. (3)).
///
/// Möbius-equivariant, sphere preserving, circle preserving when `(a, d)` is not separated by
/// `(b, c)`, symmetric: `F4(a, b, c, d) = F4(d, c, b, a)` (Lemma 4.1). On a line with equal
/// spacing it is the midpoint of `b` and `c`.
///
/// Defined results where the formula is singular, tested in this order with a tolerance of
/// 1e-13 × the diameter of the four points ([`super::COINCIDENT_TOLERANCE`]): `b = c` → `b`;
/// `a = b` → `b`; `c = d` → `c`; `a = c` → `c`; `b = d` → `b` (the formula divides by these
/// differences; the rules keep a repeated point of a curve where it is). A negative real
/// cross-ratio `ρ` (the pair `(b, c)` separates `(a, d)`) takes `χ = √|ρ| [0, n]` with `n` the
/// unit normal of `(a − b) × (c − b)`, as printed; the result then stays in the plane but
/// leaves the circle, and the rule is not Möbius-equivariant there (a documented
/// discontinuity; [`f4_hinted`] removes it where a fifth point is known).
///
/// # Errors
/// [`Status::NonFiniteInput`] for a non-finite coordinate; [`Status::DegenerateGeometry`] when
/// the new point is at infinity; [`Status::NumericalFailure`] when finite inputs overflow
/// (points more than `f64::MAX` apart, or a result beyond it).
pub fn f4(a: Point, b: Point, c: Point, d: Point) -> Result<Point> {
    f4_impl(a, b, c, d, None).map(|r| r.point)
}

/// [`f4`] with a fifth point `x` of the surface that decides the negative-real case: when
/// `ρ = cr[c, a, b, d]` is a negative real (the four points are cocircular and `(b, c)`
/// separates `(a, d)`), `χ = √|ρ| [0, n]` takes `n` along `Im cr[c, a, b, x]` instead of the
/// normal of the circle's plane. By Lemma A.1 the new point then lies on the sphere through
/// `a, b, c, x`, and since both cross-ratios start at `c` the choice is Möbius-equivariant
/// (§3.2). The mesh drivers pass a vertex of the 1-ring, so a spherical mesh stays on its
/// sphere even in this case, which the printed rule leaves (docs/DECISIONS.md). When `x` is
/// cocircular with `a, b, c` the printed rule applies. Elsewhere identical to [`f4`].
///
/// # Errors
/// As [`f4`]; a non-finite `x` is [`Status::NonFiniteInput`].
pub fn f4_hinted(a: Point, b: Point, c: Point, d: Point, x: Point) -> Result<Point> {
    if !point::is_finite(&x) {
        return Err(Error::new(Status::NonFiniteInput));
    }
    f4_impl(a, b, c, d, Some(x)).map(|r| r.point)
}

/// The noncircularity `1 − |Re ρ| / |ρ|` of the quadruplet `(a, b, c, d)` with the cross-ratio
/// `ρ = cr[c, a, b, d]` that [`f4`] uses: 0 for cocircular points (seed 000 §4.4.3 (ii)).
///
/// # Errors
/// As [`crate::quat::cross_ratio`].
pub fn noncircularity(a: Point, b: Point, c: Point, d: Point) -> Result<f64> {
    let rho = cross_ratio(c, a, b, d)?;
    let m = rho.abs();
    if m == 0.0 {
        return Ok(0.0);
    }
    Ok(1.0 - rho.w.abs() / m)
}

/// What [`f4_impl`] found besides the point.
#[derive(Clone, Copy)]
pub(super) struct F4Eval {
    /// `F4(a, b, c, d)`.
    pub(super) point: Point,
    /// The noncircularity `1 − |Re ρ|/|ρ|` of `ρ = cr[c, a, b, d]` (in working coordinates,
    /// the same number up to rounding: similarities keep cross-ratios), when the formula ran.
    pub(super) noncircularity: Option<f64>,
    /// Whether the point is also `F4(d, c, b, a)` by Lemma 4.1: the formula ran (no
    /// coincidence rule, which prefers `b` or `c` by position) and `ρ` is not a negative real
    /// (whose printed rule depends on the order). Read only for evaluations without a hint:
    /// [`f4_hinted`]'s axis snapping depends on the order.
    pub(super) reversible: bool,
}

/// F4 with an optional hint ([`f4_hinted`]): chooses the working coordinates (`frame.rs`) and
/// runs [`f4_in`] in them.
pub(super) fn f4_impl(
    a: Point,
    b: Point,
    c: Point,
    d: Point,
    hint: Option<Point>,
) -> Result<F4Eval> {
    let pts = [a, b, c, d];
    if !pts.iter().all(point::is_finite) {
        return Err(Error::new(Status::NonFiniteInput));
    }
    let sq = pair_squares(&pts);
    let max_sq = max_of(&sq);
    if (DIFFERENCES_MIN_SQ..=DIFFERENCES_MAX_SQ).contains(&max_sq) {
        return f4_in(pts, pts, sq, max_sq, hint);
    }
    // Copies for the cold call: borrowing `pts` and `sq` themselves would keep them in
    // memory on the hot path above (measured: +10 % instructions in `f4_impl`).
    match normalised(&{ pts }, &{ sq })? {
        None => f4_in(pts, pts, [0.0; 6], 0.0, hint),
        Some(Normalised {
            frame,
            local,
            local_sq,
        }) => {
            let hint = hint.map(|x| frame.to_local(x));
            let mut r = f4_in(pts, local, local_sq, max_of(&local_sq), hint)?;
            if r.noncircularity.is_some() {
                r.point = frame::to_world(Some(frame), r.point)?;
            }
            Ok(r)
        }
    }
}

/// F4 on four finite points `work` with pairwise squares `sq` (pairs ab, ac, ad, bc, bd, cd)
/// whose largest is `max_sq`: the coincidence rules, which answer with a point of `world`
/// exactly, then Eq. (3) on differences of `work`, whose point is in `work`'s coordinates.
/// Cross-ratios are invariant under translations and scalings, so `work` may be `world` itself
/// or its image in the normalised frame.
#[inline(always)]
fn f4_in(
    world: [Point; 4],
    [a, b, c, d]: [Point; 4],
    sq: [f64; 6],
    max_sq: f64,
    hint: Option<Point>,
) -> Result<F4Eval> {
    if let Some(point) = coincidence_rule(world, sq, max_sq) {
        return Ok(F4Eval {
            point,
            noncircularity: None,
            reversible: false,
        });
    }
    // ρ = cr[c, a, b, d] = q_ca q_ab⁻¹ q_bd q_dc⁻¹.
    let cr = CrossRatio::from_differences(sub(a, c), sub(b, a), sub(d, b), sub(c, d))?;
    let rho = cr.value()?;
    let rho_abs = rho.abs();
    let noncircularity = if rho_abs == 0.0 {
        0.0
    } else {
        1.0 - rho.w.abs() / rho_abs
    };
    let reversible = !is_negative_real_with_abs(rho, rho_abs);
    let [ab, _, _, _, _, cd] = sq;
    let s = solve_order(&cr, rho, rho_abs, [a, b, c, d], reversible && ab < cd)?;
    let chi = chi(&s, hint_axis(&s, hint))?;
    Ok(F4Eval {
        point: solve_by_difference(s.m, s.b, s.c, chi)?,
        noncircularity: Some(noncircularity),
        reversible,
    })
}

/// The coincidence rules of [`f4`] (`|p − q|² ≤ 1e-26 · diameter²`, in its order), answering
/// with a point of `world` exactly; `None` when no pair coincides.
#[inline(always)]
fn coincidence_rule(world: [Point; 4], sq: [f64; 6], max_sq: f64) -> Option<Point> {
    let [ab, ac, _, bc, bd, cd] = sq;
    let tol_sq = COINCIDENT_TOLERANCE * COINCIDENT_TOLERANCE * max_sq;
    let [_, wb, wc, _] = world;
    if bc <= tol_sq || ab <= tol_sq {
        return Some(wb);
    }
    if cd <= tol_sq || ac <= tol_sq {
        return Some(wc);
    }
    if bd <= tol_sq {
        return Some(wb);
    }
    None
}

/// The quadruplet F4 solves, in the order it solves it: `(a, b, c)` and `ρ = cr[c, a, b, d]`,
/// or their mirror images `(d, c, b)` and `cr[b, d, c, a]`.
struct SolveOrder {
    /// The cross-ratio of the solve.
    rho: Quat,
    /// `|ρ|`.
    r: f64,
    /// `M = (a − c)(b − a)⁻¹`, the prefix of ρ.
    m: Quat,
    /// The first three points of the solve.
    a: Point,
    b: Point,
    c: Point,
}

/// The order of the solve. `F4(a, b, c, d) = F4(d, c, b, a)` (Lemma 4.1). The solve divides by
/// `b − a`, so when `b` is nearer to `a` than `c` is to `d` (`mirror`), the mirrored order is
/// better conditioned: use it. (Not in the negative-real case, whose printed rule depends on
/// the order: the caller passes `mirror = false` there.) Both orders give the same point in
/// exact arithmetic, and since `|b − a|²` and `|c − d|²` are the same sums in the mirrored
/// call, the choice makes F4 bit-symmetric (unless they are equal). The mirrored cross-ratio
/// `cr[b, d, c, a]` is the double transposition of ρ: the same differences and inverses.
#[inline(always)]
fn solve_order(
    cr: &CrossRatio,
    rho: Quat,
    rho_abs: f64,
    [a, b, c, d]: [Point; 4],
    mirror: bool,
) -> Result<SolveOrder> {
    if mirror {
        let rho = cr.transposed()?;
        return Ok(SolveOrder {
            rho,
            r: rho.abs(),
            m: cr.transposed_prefix(),
            a: d,
            b: c,
            c: b,
        });
    }
    Ok(SolveOrder {
        rho,
        r: rho_abs,
        m: cr.prefix,
        a,
        b,
        c,
    })
}

/// The sphere's axis at `c` from the hint `x` (Lemma A.1): the unit `Im cr[c, a, b, x]`, which
/// decides the negative-real case and cleans the direction of `Im ρ` near it; `None` without a
/// hint, for `Re ρ ≥ 0`, and when `x` is cocircular with `a, b, c`. `cr[c, a, b, x]` shares its
/// prefix with ρ.
#[inline(always)]
fn hint_axis(s: &SolveOrder, hint: Option<Point>) -> Option<Point> {
    let x = hint?;
    if s.rho.w < 0.0 {
        if let Ok(q) = cross_ratio_from_prefix(s.m, s.c, s.b, x) {
            let im = q.abs_im();
            if im > NEGATIVE_REAL_TOLERANCE * q.abs() && im.is_finite() {
                return Some([q.x / im, q.y / im, q.z / im]);
            }
        }
    }
    None
}

/// `χ = −√ρ`, or `χ = +√|ρ| [0, n]` as printed when ρ is a negative real, `n` the hint's axis
/// (then also snapped to, [`sqrt_snapped_with_abs`]) or the normal of the plane `a, b, c`.
#[inline(always)]
fn chi(s: &SolveOrder, hint_axis: Option<Point>) -> Result<Quat> {
    let negative_real = is_negative_real_with_abs(s.rho, s.r);
    let snap = hint_axis.is_some();
    // The plane's normal is only read for a negative real (after snapping).
    let axis = match hint_axis {
        Some(n) => n,
        None if s.rho.w < 0.0 => plane_normal(s.a, s.b, s.c),
        None => [0.0, 0.0, 1.0],
    };
    let root = sqrt_snapped_with_abs(s.rho, s.r, axis, snap)
        .ok_or(Error::new(Status::DegenerateGeometry))?;
    Ok(if negative_real { root } else { -root })
}

#[cfg(test)]
mod tests {
    use super::super::is_negative_real;
    use super::*;
    use crate::point::{distance, norm};

    #[test]
    fn f4_on_a_line_is_the_midpoint() {
        let p = f4([0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [3.0, 0.0, 0.0]).unwrap();
        assert!(distance(p, [1.5, 0.0, 0.0]) < 1e-15, "{p:?}");
    }

    #[test]
    fn f4_on_a_circle_stays_on_the_circle() {
        let on = |t: f64| [2.0 * libm::cos(t), 2.0 * libm::sin(t), 0.0];
        let p = f4(on(0.0), on(0.7), on(1.1), on(2.5)).unwrap();
        assert!((norm(p) - 2.0).abs() < 1e-14);
        // Between b and c.
        let ang = libm::atan2(p[1], p[0]);
        assert!(ang > 0.7 && ang < 1.1, "{ang}");
        // Equally spaced: exactly the middle of the arc.
        let q = f4(on(0.0), on(1.0), on(2.0), on(3.0)).unwrap();
        assert!(distance(q, on(1.5)) < 1e-14);
    }

    #[test]
    fn f4_coincident_rules() {
        let (a, b, c, d) = ([0.0; 3], [1.0, 0.0, 0.0], [2.0, 1.0, 0.0], [3.0, 0.0, 1.0]);
        assert_eq!(f4(a, b, b, d).unwrap(), b);
        assert_eq!(f4(b, b, c, d).unwrap(), b);
        assert_eq!(f4(a, b, c, c).unwrap(), c);
        assert_eq!(f4(c, b, c, d).unwrap(), c); // a = c → c
        assert_eq!(f4(a, b, c, b).unwrap(), b);
        assert_eq!(f4(a, a, a, a).unwrap(), a);
        assert_eq!(
            f4([f64::NAN, 0.0, 0.0], b, c, d).unwrap_err().status,
            Status::NonFiniteInput
        );
    }

    #[test]
    fn f4_negative_real_case_stays_in_the_plane() {
        // (b, c) separates (a, d) on the unit circle: a, b, d, c in circular order.
        let on = |t: f64| [libm::cos(t), libm::sin(t), 0.0];
        let (a, b, c, d) = (on(0.0), on(1.0), on(3.0), on(2.0));
        let rho = cross_ratio(c, a, b, d).unwrap();
        assert!(is_negative_real(rho));
        let p = f4(a, b, c, d).unwrap();
        assert!(p[2].abs() < 1e-14 && point::is_finite(&p));
    }
}
