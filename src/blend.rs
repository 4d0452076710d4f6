//! The Möbius-invariant blends F4 and F6 (seed 000 §4.4.1–4.4.2, Eq. (3), Appendix A).
//!
//! Both solve `cr[e, a, b, p] = χ` for `p` (with `e = c` for F4):
//! `p = (M + χ)⁻¹ (χ e + M b)` with `M = (a − e)(b − a)⁻¹`, which is Eq. (3) multiplied
//! out (`M = ((a − b)(c − a)⁻¹)⁻¹`). Every quantity but the last is a ratio of lengths, and
//! the solve is evaluated as `p = e + (M + χ)⁻¹ M (b − e)`, so for inputs of diameter in
//! [1e-100, 1e100] the blends read only differences of the inputs, each rounded once
//! (`f4_in`, `f6_in`). Outside that range the inputs are first moved
//! to a normalised frame (centroid at the origin, unit diameter; similarities are Möbius
//! maps, so this changes nothing in exact arithmetic) that keeps intermediates far from
//! overflow and underflow.

use crate::error::{Error, Result, Status};
use crate::point::{self, add, cross, norm, scale, sub, Point};
use crate::quat::{cross_ratio, cross_ratio_from_prefix, CrossRatio, Quat};

/// Relative distance below which two inputs count as coincident (DESIGN.md).
pub const COINCIDENT_TOLERANCE: f64 = 1e-13;

/// Relative size of `Im ρ` below which a cross-ratio with negative real part counts as a
/// negative real (DESIGN.md).
pub const NEGATIVE_REAL_TOLERANCE: f64 = 1e-12;

/// Coordinates within ±`BOUNDED` are less than `f64::MAX` apart (`2√3 · 1e300`).
const BOUNDED: f64 = 1e300;

/// A similarity frame: `x ↦ (x − centre) / size`.
#[derive(Clone, Copy)]
struct Frame {
    centre: Point,
    size: f64,
}

/// `|p − q|²` as [`norm`] forms it (so that its square root is `norm(sub(p, q))` bit for bit).
#[inline]
fn dist_sq(p: Point, q: Point) -> f64 {
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
            libm::sqrt(max_sq)
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
    fn to_local(self, p: Point) -> Point {
        // Divide (rather than multiply by 1/size, which overflows for a subnormal size).
        let d = sub(p, self.centre);
        [d[0] / self.size, d[1] / self.size, d[2] / self.size]
    }
    fn to_world(self, p: Point) -> Point {
        add(self.centre, scale(p, self.size))
    }
}

/// The pairwise squared distances of `N` points, pairs `(i, j)` with `i < j` in
/// lexicographic order (`M = N (N − 1) / 2`).
fn pair_squares<const N: usize, const M: usize>(p: &[Point; N]) -> [f64; M] {
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

/// Whether `q` is a negative real in the sense of DESIGN.md: `Re q < 0` and
/// `|Im q| ≤ 1e-12 |q|`.
pub fn is_negative_real(q: Quat) -> bool {
    q.w < 0.0 && q.abs_im() <= NEGATIVE_REAL_TOLERANCE * q.abs()
}

/// [`is_negative_real`] with `r = q.abs()` known.
#[inline(always)]
fn is_negative_real_with_abs(q: Quat, r: f64) -> bool {
    q.w < 0.0 && q.abs_im() <= NEGATIVE_REAL_TOLERANCE * r
}

/// The unit normal of the plane through `a, b, c` (`(a − b) × (c − b)` normalised); for
/// collinear points a fixed unit vector orthogonal to `c − b` (or `a − b`), chosen by the
/// smallest coordinate so that the choice is deterministic.
fn plane_normal(a: Point, b: Point, c: Point) -> Point {
    let u = sub(a, b);
    let w = sub(c, b);
    let n = cross(u, w);
    let len = norm(n);
    if len > 0.0 && len.is_finite() {
        return scale(n, 1.0 / len);
    }
    let d = if norm(w) > 0.0 { w } else { u };
    let axis = if d[0].abs() <= d[1].abs() && d[0].abs() <= d[2].abs() {
        [1.0, 0.0, 0.0]
    } else if d[1].abs() <= d[2].abs() {
        [0.0, 1.0, 0.0]
    } else {
        [0.0, 0.0, 1.0]
    };
    let n = cross(d, axis);
    let len = norm(n);
    if len > 0.0 {
        scale(n, 1.0 / len)
    } else {
        [0.0, 0.0, 1.0]
    }
}

/// `√q` with the branch of the paper; for a negative real `q` the root `√|q| [0, n]` (the
/// printed rule of seed 000 §4.4.1 with the axis `n`). With `snap` and `q` in the left
/// half-plane it first removes rounding noise from the direction of `Im q`: there `Im √q = n·t` divides by `|Im q|`,
/// so noise of size `ε|q|` across the reference axis `n` turns a point that should lie on a
/// sphere into one off it by `ε|q|/|Im q|` (seed 000 Lemma A.1: for cospherical points every
/// cross-ratio starting at the same point has its imaginary part along one axis). A component
/// across `n` below `1e-12 |q|` is dropped; larger ones are kept, so nothing changes for
/// points that are not cospherical.
#[inline(always)]
fn sqrt_snapped(q: Quat, n: Point, snap: bool) -> Option<Quat> {
    sqrt_snapped_with_abs(q, q.abs(), n, snap)
}

/// [`sqrt_snapped`] with `r = q.abs()` computed by the caller (F4 has it from the
/// noncircularity). `|Im q|` is needed only for a negative real part (the negative-real test
/// and the root's lower half-space formula); with `Re q ≥ 0` the root reads only whether
/// `Im q` is zero, which is whether its three components are (`abs_im` is zero exactly
/// then), so the common case takes two square roots fewer. The same bits as computing both
/// norms first.
#[inline(always)]
fn sqrt_snapped_with_abs(q: Quat, r: f64, n: Point, snap: bool) -> Option<Quat> {
    let (q, r) = if snap && q.w < 0.0 {
        let along = q.x * n[0] + q.y * n[1] + q.z * n[2];
        let across = [q.x - along * n[0], q.y - along * n[1], q.z - along * n[2]];
        if norm(across) <= NEGATIVE_REAL_TOLERANCE * r {
            let snapped = Quat::new(q.w, along * n[0], along * n[1], along * n[2]);
            (snapped, snapped.abs())
        } else {
            (q, r)
        }
    } else {
        (q, r)
    };
    if q.w < 0.0 {
        // The negative-real test, then the lower half-space root, with |Im q| computed once.
        let vi = q.abs_im();
        if vi <= NEGATIVE_REAL_TOLERANCE * r {
            let t = libm::sqrt(r);
            return Some(Quat::new(0.0, n[0] * t, n[1] * t, n[2] * t));
        }
        return q.sqrt_given(r, vi);
    }
    q.sqrt_upper(r)
}

/// The unit imaginary part of the quaternion of `qs` farthest from real (largest
/// `|Im q| / |q|`, the first on ties), or `None` when all are real.
/// `abs[i] = qs[i].abs()` is computed by the caller (F6 reuses it for the roots).
#[inline(always)]
fn imaginary_axis(qs: &[Quat], abs: &[f64]) -> Option<Point> {
    let mut best: Option<(f64, Quat, f64)> = None;
    for (q, &abs) in qs.iter().zip(abs) {
        let im = q.abs_im();
        // Real within the tolerance of `is_negative_real`: for cocircular points `Im q` is
        // rounding noise whose sign would pick the axis.
        if !(im > NEGATIVE_REAL_TOLERANCE * abs && abs.is_finite()) {
            continue;
        }
        let ratio = im / abs;
        if best.is_none_or(|(r, _, _)| ratio > r) {
            best = Some((ratio, *q, im));
        }
    }
    let (_, q, im) = best?;
    Some([q.x / im, q.y / im, q.z / im])
}

/// Solves `cr[e, a, b, p] = χ` for `p` (tests).
#[cfg(test)]
fn solve_cross_ratio(a: Point, b: Point, e: Point, chi: Quat) -> Result<Point> {
    let degenerate = Error::new(Status::DegenerateGeometry);
    let (qa, qb, qe) = (
        Quat::from_point(a),
        Quat::from_point(b),
        Quat::from_point(e),
    );
    let m = (qa - qe) * (qb - qa).inverse().ok_or(degenerate)?;
    solve_by_difference(m, b, e, chi)
}

/// The four-point blend `F4(a, b, c, d)`: the point `p` with `cr[c, a, b, p] = −√cr[c, a, b, d]`
/// (seed 000 §4.4.1, Eq. (3)).
///
/// Möbius-equivariant, sphere preserving, circle preserving when `(a, d)` is not separated by
/// `(b, c)`, symmetric: `F4(a, b, c, d) = F4(d, c, b, a)` (Lemma 4.1). On a line with equal
/// spacing it is the midpoint of `b` and `c`.
///
/// Defined results where the formula is singular (DESIGN.md), tested in this order with a
/// tolerance of 1e-13 × the diameter of the four points: `b = c` → `b`; `a = b` → `b`;
/// `c = d` → `c`; `a = c` → `c`; `b = d` → `b`. A negative real cross-ratio `ρ` (the pair
/// `(b, c)` separates `(a, d)`) takes `χ = √|ρ| [0, n]` with `n` the unit normal of
/// `(a − b) × (c − b)`, as printed; the result then stays in the plane but leaves the circle,
/// and the rule is not Möbius-equivariant there (a documented discontinuity).
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

/// What [`f4_impl`] found besides the point.
#[derive(Clone, Copy)]
struct F4Eval {
    /// `F4(a, b, c, d)`.
    point: Point,
    /// The noncircularity `1 − |Re ρ|/|ρ|` of `ρ = cr[c, a, b, d]` (in working coordinates,
    /// the same number up to rounding: similarities keep cross-ratios), when the formula ran.
    noncircularity: Option<f64>,
    /// Whether the point is also `F4(d, c, b, a)` by Lemma 4.1: the formula ran (no
    /// coincidence rule, which prefers `b` or `c` by position) and `ρ` is not a negative real
    /// (whose printed rule depends on the order). Read only for evaluations without a hint:
    /// [`f4_hinted`]'s axis snapping depends on the order.
    reversible: bool,
}

fn f4_impl(a: Point, b: Point, c: Point, d: Point, hint: Option<Point>) -> Result<F4Eval> {
    let pts = [a, b, c, d];
    if !pts.iter().all(point::is_finite) {
        return Err(Error::new(Status::NonFiniteInput));
    }
    let sq = pair_squares(&pts);
    let max_sq = max_of(&sq);
    if (DIFFERENCES_MIN_SQ..=DIFFERENCES_MAX_SQ).contains(&max_sq) {
        return f4_in(pts, pts, sq, max_sq, hint);
    }
    match normalised(pts, sq)? {
        None => f4_in(pts, pts, [0.0; 6], 0.0, hint),
        Some(Normalised {
            frame,
            local,
            local_sq,
        }) => {
            let hint = hint.map(|x| frame.to_local(x));
            let mut r = f4_in(pts, local, local_sq, max_of(&local_sq), hint)?;
            if r.noncircularity.is_some() {
                r.point = to_world(Some(frame), r.point)?;
            }
            Ok(r)
        }
    }
}

/// Squared diameters between which the blends work on the input coordinates themselves:
/// diameters in [1e-100, 1e100]. Every quantity of Eq. (3) except the final offset is a ratio
/// of lengths (cross-ratios, `M`, `χ`), the solve reads only the difference `b − e`
/// ([`solve_by_difference`]), and a pair tested for coincidence that is not coincident is at
/// least 1e-13 × 1e-100 apart, so its square and inverse stay in `[SAFE_MIN, SAFE_MAX]`;
/// other pairs (F6's `a, b`, `d, e`, `c, b`, `e, f`, a hint's difference, `M + χ`) can leave
/// it, and go through the scaled slow paths of the inverses. The blends then read only
/// differences of the inputs, each rounded once. Outside, the inputs are moved to the
/// normalised frame first.
const DIFFERENCES_MIN_SQ: f64 = 1e-200;
const DIFFERENCES_MAX_SQ: f64 = 1e200;

/// The largest of `sq` (squares of finite points: never NaN, so `>` is `f64::max`).
fn max_of(sq: &[f64]) -> f64 {
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
fn normalised<const N: usize, const M: usize>(
    pts: [Point; N],
    sq: [f64; M],
) -> Result<Option<Normalised<N, M>>> {
    let frame = Frame::from_squares(&pts, &sq);
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
struct Normalised<const N: usize, const M: usize> {
    frame: Frame,
    local: [Point; N],
    local_sq: [f64; M],
}

/// A solved point in working coordinates back in the world: [`Status::NumericalFailure`] when
/// it lies beyond the range of `f64`.
#[inline]
fn to_world(frame: Option<Frame>, p: Point) -> Result<Point> {
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

/// `p = e + (M + χ)⁻¹ M (b − e)`: the solution of `cr[e, a, b, p] = χ` with
/// `M = (a − e)(b − a)⁻¹`, which is `(M + χ)⁻¹ (χ e + M b)` (Eq. (3)) with `χ e + M b`
/// split as `(M + χ) e + M (b − e)`: it reads only the difference `b − e`, so it needs no
/// frame. A new point at infinity — an offset that is not finite in f64, which the normalised
/// frame could in rare cases still have represented and reported as
/// [`Status::NumericalFailure`] — is [`Status::DegenerateGeometry`]; a finite offset from a
/// point so far out that the sum overflows is [`Status::NumericalFailure`].
#[inline(always)]
fn solve_by_difference(m: Quat, b: Point, e: Point, chi: Quat) -> Result<Point> {
    let degenerate = Error::new(Status::DegenerateGeometry);
    let offset = ((m + chi).inverse().ok_or(degenerate)? * m.mul_im(sub(b, e))).to_point();
    if !point::is_finite(&offset) {
        return Err(degenerate);
    }
    let p = add(e, offset);
    if point::is_finite(&p) {
        Ok(p)
    } else {
        Err(Error::new(Status::NumericalFailure))
    }
}

/// F4 on four finite points `work` with pairwise squares `sq` (pairs ab, ac, ad, bc, bd, cd)
/// whose largest is `max_sq`: the coincidence rules (`|p − q|² ≤ 1e-26 · diameter²`, in the
/// order of [`f4`]), which answer with a point of `world` exactly, then Eq. (3) on
/// differences of `work`, whose point is in `work`'s coordinates. Cross-ratios are invariant
/// under translations and scalings, so `work` may be `world` itself or its image in the
/// normalised frame.
#[inline(always)]
fn f4_in(
    world: [Point; 4],
    [a, b, c, d]: [Point; 4],
    sq: [f64; 6],
    max_sq: f64,
    hint: Option<Point>,
) -> Result<F4Eval> {
    let [ab, ac, _, bc, bd, cd] = sq;
    let tol_sq = COINCIDENT_TOLERANCE * COINCIDENT_TOLERANCE * max_sq;
    let [_, wb, wc, _] = world;
    let early = |point: Point| {
        Ok(F4Eval {
            point,
            noncircularity: None,
            reversible: false,
        })
    };
    if bc <= tol_sq || ab <= tol_sq {
        return early(wb);
    }
    if cd <= tol_sq || ac <= tol_sq {
        return early(wc);
    }
    if bd <= tol_sq {
        return early(wb);
    }
    // ρ = cr[c, a, b, d] = q_ca q_ab⁻¹ q_bd q_dc⁻¹.
    let cr = CrossRatio::from_differences(sub(a, c), sub(b, a), sub(d, b), sub(c, d))?;
    let mut rho = cr.value()?;
    let rho_abs = rho.abs();
    let noncircularity = if rho_abs == 0.0 {
        0.0
    } else {
        1.0 - rho.w.abs() / rho_abs
    };
    let reversible = !is_negative_real_with_abs(rho, rho_abs);
    // |ρ| of the cross-ratio the solve uses (the mirrored one's below).
    let mut r = rho_abs;
    let (mut la, mut lb, mut lc) = (a, b, c);
    // M = (a − c)(b − a)⁻¹ of the solve: the prefix of ρ.
    let mut m = cr.prefix;
    // F4(a, b, c, d) = F4(d, c, b, a) (Lemma 4.1). The solve divides by b − a, so when b is
    // nearer to a than c is to d, the mirrored order is better conditioned: use it. (Not in
    // the negative-real case, whose printed rule depends on the order.) Both orders give
    // the same point in exact arithmetic, and since `|b − a|²` and `|c − d|²` are the same
    // sums in the mirrored call, the choice makes F4 bit-symmetric (unless they are equal). The mirrored
    // cross-ratio cr[b, d, c, a] is the double transposition of ρ: the same differences and
    // inverses.
    if reversible && ab < cd {
        (la, lb, lc) = (d, c, b);
        rho = cr.transposed()?;
        r = rho.abs();
        m = cr.transposed_prefix();
    }
    let mut axis = None;
    let mut snap = false;
    if let Some(x) = hint {
        if rho.w < 0.0 {
            // The sphere's axis at c from the fifth point (Lemma A.1): decides the
            // negative-real case and cleans the direction of Im ρ near it. cr[c, a, b, x]
            // shares its prefix with ρ.
            if let Ok(q) = cross_ratio_from_prefix(m, lc, lb, x) {
                let im = q.abs_im();
                if im > NEGATIVE_REAL_TOLERANCE * q.abs() && im.is_finite() {
                    axis = Some([q.x / im, q.y / im, q.z / im]);
                    snap = true;
                }
            }
        }
    }
    let negative_real = is_negative_real_with_abs(rho, r);
    // The plane's normal is only read for a negative real (after snapping).
    let axis = match axis {
        Some(n) => n,
        None if rho.w < 0.0 => plane_normal(la, lb, lc),
        None => [0.0, 0.0, 1.0],
    };
    let root =
        sqrt_snapped_with_abs(rho, r, axis, snap).ok_or(Error::new(Status::DegenerateGeometry))?;
    // The negative-real case uses χ = +√|ρ|[0, n] as printed; otherwise χ = −√ρ.
    let chi = if negative_real { root } else { -root };
    Ok(F4Eval {
        point: solve_by_difference(m, lb, lc, chi)?,
        noncircularity: Some(noncircularity),
        reversible,
    })
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
    let sq = pair_squares(&pts);
    let max_sq = max_of(&sq);
    let (found, frame) = if (DIFFERENCES_MIN_SQ..=DIFFERENCES_MAX_SQ).contains(&max_sq) {
        (f6_in(pts, sq, max_sq)?, None)
    } else {
        match normalised(pts, sq)? {
            None => (None, None),
            Some(Normalised {
                frame,
                local,
                local_sq,
            }) => (f6_in(local, local_sq, max_of(&local_sq))?, Some(frame)),
        }
    };
    match found {
        None => Ok(b),
        Some(p) => to_world(frame, p),
    }
}

/// F6 on six finite points with pairwise squares `sq` (pairs in lexicographic order) whose
/// largest is `max_sq`, in world or normalised-frame coordinates (as [`f4_in`]): `None` for
/// the rule `b = e → b`, else the solved point.
fn f6_in([a, b, c, d, e, f]: [Point; 6], sq: [f64; 15], max_sq: f64) -> Result<Option<Point>> {
    // Pair (b, e) is the 8th: ab ac ad ae af bc bd be.
    let be = sq.get(7).copied().unwrap_or(f64::INFINITY);
    if be <= COINCIDENT_TOLERANCE * COINCIDENT_TOLERANCE * max_sq {
        return Ok(None);
    }
    let degenerate = Error::new(Status::DegenerateGeometry);
    // X = cr[e, a, b, d] = q_ea q_ab⁻¹ q_bd q_de⁻¹ and Y = cr[e, a, b, f] share the prefix
    // (a − e)(b − a)⁻¹, which is also the M of the solve; Z = cr[e, c, b, f].
    let cx = CrossRatio::from_differences(sub(a, e), sub(b, a), sub(d, b), sub(e, d))?;
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
    let sr = sqrt_snapped(r, n, snap).ok_or(degenerate)?;
    let chi = -(sx * sr);
    solve_by_difference(cx.prefix, b, e, chi).map(Some)
}

/// The face point of a `d`-gon from its vertices `v_i` and the candidates `v_{f,i}` computed
/// in the canonical forms of the vertices' stars (seed 000 §4.4.3, "Blending face points"):
///
/// 1. quadruplets `(v_i, v_{f,i}, v_{f,i+h}, v_{i+h})`, `h = ⌊d/2⌋`, in face order;
/// 2. a stable sort by ascending noncircularity `1 − |Re ρ|/|ρ|` (the `ρ` that F4 uses on the
///    quadruplet; keys rounded to 12 decimals so that rounding noise cannot reorder ties);
/// 3. `p_l = F4(a_l, b_l, c_l, d_l)`;
/// 4. `v_f = p_1`, then `v_f := F6(a_{l−1}, v_f, d_{l−1}, a_l, p_l, d_l)` for `l = 2 … d`.
///
/// Step 4 chains the *opposite vertices* `a`, `d` of the quadruplets (DESIGN.md: the printed
/// `c_{l−1}, c_l` are candidates, with which F6 is singular exactly in the Möbius-regular
/// case). When all candidates agree (a Möbius-regular neighbourhood) every F4 and F6 returns
/// that point, so `v_f` equals it. In an even face, where quadruplets `i` and `i + h` are the
/// same points reversed, each chain `(a_l, d_l)` is oriented by the face: its start follows
/// the previous chain's start in face order, less than half a turn on (F6 is unchanged when
/// both chains reverse, so this relative orientation is all that enters; docs/DECISIONS.md).
///
/// Evaluation (docs/RESULTS.md, "Möbius arithmetic"): steps 2 and 3 share their cross-ratio
/// (the key is the noncircularity of the `ρ` F4 computes); for an
/// even face quadruplet `i + h` is quadruplet `i` reversed: the one of the pair whose `v_i`
/// has the smaller id (then the earlier in face order) is evaluated and its partner takes its
/// F4 point and key (Lemma 4.1; both are evaluated where F4 is not symmetric); a step onto the reversed
/// partner of the previous quadruplet is F6 with `Y = 1`, `Z = X⁻¹`, evaluated as the F4 it
/// equals (`f6_of_reversed_chain`).
///
/// Ties of the sort (equal rounded keys) keep face order, as the paper's stable sort does. The
/// F6 chain depends on the order of different quadruplets, which tie in symmetric faces, so
/// the result can depend on which corner the face lists first — by up to 4 % of the face on a
/// regular tetrahedron. Drivers use [`face_point_with_ids`], whose ties go by vertex id and so
/// do not depend on the start.
///
/// # Errors
/// [`Status::InvalidArgument`] when the slices differ in length; [`Status::TooFewPoints`] for
/// fewer than 3 corners; [`Status::ValenceTooHigh`] above [`crate::MAX_FACE_SIZE`];
/// [`Status::NonFiniteInput`] for a non-finite corner or candidate; the errors of [`f4`] and
/// [`f6`] (the caller's degenerate-neighbourhood policy decides what to do). When several
/// quadruplets' F4s fail, the one reported is `NumericalFailure` before `DegenerateGeometry`,
/// so it does not depend on where the face starts.
pub fn face_point(vertices: &[Point], candidates: &[Point]) -> Result<Point> {
    face_point_ordered(vertices, candidates, None)
}

/// [`face_point`] with ties of the noncircularity sort broken by the vertex ids `ids[i]` of the
/// quadruplets' first corners `v_i` (then by face order, for repeated ids). The quadruplets of
/// a face and their ids are the same whichever corner the face starts at, so the face point
/// is too, bit for bit; ids are untouched by Möbius maps, so Möbius equivariance is kept (a
/// tie-break by coordinates would lose it). This is the rule every Möbius driver uses, with
/// the mesh's vertex indices (docs/DECISIONS.md).
///
/// # Errors
/// Those of [`face_point`]; [`Status::InvalidArgument`] when `ids` differs in length.
pub fn face_point_with_ids(vertices: &[Point], candidates: &[Point], ids: &[u32]) -> Result<Point> {
    if ids.len() != vertices.len() {
        return Err(Error::new(Status::InvalidArgument));
    }
    face_point_ordered(vertices, candidates, Some(ids))
}

/// `F6(a, b, c, c, e, a)`: F6 whose second chain joins the ends of the first in reverse, as
/// the chain of an even face meets when quadruplet `i` or `i + h` follows the chain of its
/// pair (either orientation: `F6(a, b, c, a, e, c)` is `F4(a, b, e, c)` too, off the negative
/// reals).
///
/// There `X = cr[e, a, b, c]`, `Y = cr[e, a, b, a] = q_ea q_ab⁻¹ (−q_ab)(−q_ea)⁻¹ = 1` and
/// `Z = cr[e, c, b, a] = X⁻¹` (the four factors of `X⁻¹` are those of `Z`, each negated), so
/// `r = (√X)⁻¹ (√(X⁻¹))⁻¹ = 1` for the principal root (`√(X⁻¹) = (√X)⁻¹` off the negative
/// reals) and `χ = −√X`: the point with `cr[e, a, b, p] = −√cr[e, a, b, c]`, which is
/// `F4(a, b, e, c)` — one cross-ratio instead of three, and no rounding of `Y` away from 1.
/// Where F4 does not run its formula (a coincidence rule) or `X` is a negative real (where
/// F6 takes `√r = n`, not 1) this is F6 itself.
fn f6_of_reversed_chain(a: Point, b: Point, c: Point, e: Point) -> Result<Point> {
    if b == e {
        // A reused F4 (the step onto the partner of the previous quadruplet): F6's `b = e`
        // rule, before F4's coincidence rule would decline.
        return f6(a, b, c, c, e, a);
    }
    match f4_impl(a, b, e, c, None) {
        Ok(r) if r.reversible => Ok(r.point),
        _ => f6(a, b, c, c, e, a),
    }
}

/// `F4(a, b, c, d)` with its §4.4.3 sort key and [`F4Eval::reversible`]: the noncircularity
/// of the cross-ratio F4 uses, rounded to 12 decimals (so that rounding noise cannot reorder
/// ties); when a coincidence rule answered (F4 computed no ρ), that of the input points. A
/// quadruplet whose cross-ratio is undefined (coincident candidates) is as circular as it
/// gets (key 0).
fn f4_keyed(a: Point, b: Point, c: Point, d: Point) -> Result<(Point, i64, bool)> {
    let r = f4_impl(a, b, c, d, None)?;
    let key = match r.noncircularity {
        Some(k) => k,
        None => noncircularity(a, b, c, d).unwrap_or(0.0),
    };
    Ok((r.point, libm::round(key * 1e12) as i64, r.reversible))
}

/// The order in which [`face_point_ordered`] reports the failures of its quadruplets' F4s
/// (lowest first): a fixed order of statuses, so the report does not depend on evaluation order.
fn failure_rank(status: Status) -> u8 {
    match status {
        Status::NonFiniteInput => 0,
        Status::NumericalFailure => 1,
        Status::DegenerateGeometry => 2,
        // F4 returns none of the other statuses today; they would tie here.
        _ => 3,
    }
}

fn face_point_ordered(
    vertices: &[Point],
    candidates: &[Point],
    ids: Option<&[u32]>,
) -> Result<Point> {
    let d = vertices.len();
    if candidates.len() != d {
        return Err(Error::new(Status::InvalidArgument));
    }
    if d < 3 {
        return Err(Error::new(Status::TooFewPoints));
    }
    if d > crate::MAX_FACE_SIZE {
        return Err(Error::new(Status::ValenceTooHigh));
    }
    // A shortcut: a non-finite corner or candidate is `NonFiniteInput` (the ranking below
    // would report it too, after evaluating every quadruplet).
    if !vertices.iter().chain(candidates).all(point::is_finite) {
        return Err(Error::new(Status::NonFiniteInput));
    }
    let h = d / 2;
    let at = |s: &[Point], i: usize| {
        i.checked_rem(d)
            .and_then(|k| s.get(k).copied())
            .ok_or(Error::new(Status::InvalidArgument))
    };
    let quad = |i: usize| -> Result<[Point; 4]> {
        Ok([
            at(vertices, i)?,
            at(candidates, i)?,
            at(candidates, i + h)?,
            at(vertices, i + h)?,
        ])
    };
    let id = |i: usize| -> Result<u32> {
        match ids {
            Some(ids) => ids
                .get(i)
                .copied()
                .ok_or(Error::new(Status::InvalidArgument)),
            None => Ok(0),
        }
    };
    // p_l = F4(quadruplet l) and its rounded sort key, per quadruplet in face order.
    let mut p: arrayvec::ArrayVec<(Point, i64), { crate::MAX_FACE_SIZE }> =
        arrayvec::ArrayVec::new();
    let eval = |i: usize| -> Result<(Point, i64, bool)> {
        let [a, b, c, e] = quad(i)?;
        f4_keyed(a, b, c, e)
    };
    for _ in 0..d {
        p.try_push(([0.0; 3], 0))
            .map_err(|_| Error::new(Status::ValenceTooHigh))?;
    }
    let mut put = |i: usize, v: (Point, i64)| -> Result<()> {
        *p.get_mut(i).ok_or(Error::new(Status::InvalidArgument))? = v;
        Ok(())
    };
    // The quadruplets are evaluated in face order, so the first failing one depends on where
    // the face starts: every one is evaluated and the failure reported is the one of
    // `failure_rank` (then the first), the same for every start.
    let mut failure: Option<Error> = None;
    let mut eval = |i: usize| -> (Point, i64, bool) {
        match eval(i) {
            Ok(r) => r,
            Err(e) => {
                if failure.is_none_or(|f| failure_rank(e.status) < failure_rank(f.status)) {
                    failure = Some(e);
                }
                ([0.0; 3], 0, false)
            }
        }
    };
    if d % 2 == 0 {
        // Quadruplet i + h is quadruplet i reversed, and F4(a, b, c, d) = F4(d, c, b, a)
        // (Lemma 4.1), noncircularity included: one evaluation serves both. It is the one
        // whose v_i has the smaller id (then the first in face order), so the face point
        // stays independent of the face start bit for bit. Where F4 is not symmetric (a
        // coincidence rule or a negative-real ρ) both are evaluated.
        for i in 0..h {
            let (first, second) = if id(i + h)? < id(i)? {
                (i + h, i)
            } else {
                (i, i + h)
            };
            let (pt, key, reversible) = eval(first);
            put(first, (pt, key))?;
            if reversible {
                put(second, (pt, key))?;
            } else {
                let (pt2, key2, _) = eval(second);
                put(second, (pt2, key2))?;
            }
        }
    } else {
        for i in 0..d {
            let (pt, key, _) = eval(i);
            put(i, (pt, key))?;
        }
    }
    if let Some(e) = failure {
        return Err(e);
    }
    // (quadruplet start i, (rounded key, tie-break)), sorted stably with an insertion sort (d
    // is small, and the sort must be stable and panic-free). The tie-break is the id of `v_i`
    // when given, else 0 (face order).
    let mut order: arrayvec::ArrayVec<(usize, (i64, u32)), { crate::MAX_FACE_SIZE }> =
        arrayvec::ArrayVec::new();
    for (i, &(_, key)) in p.iter().enumerate() {
        order
            .try_push((i, (key, id(i)?)))
            .map_err(|_| Error::new(Status::ValenceTooHigh))?;
        let mut j = order.len() - 1;
        while j > 0 {
            // Swap through `get_mut` on the pair: `slice::swap` keeps a bounds-check panic.
            match order.get_mut(j - 1..=j) {
                Some([prev, cur]) if prev.1 > cur.1 => {
                    core::mem::swap(prev, cur);
                    j -= 1;
                }
                _ => break,
            }
        }
    }
    let point = |i: usize| {
        p.get(i)
            .map(|x| x.0)
            .ok_or(Error::new(Status::InvalidArgument))
    };
    let mut it = order.iter();
    let first = it.next().ok_or(Error::new(Status::TooFewPoints))?.0;
    let mut vf = point(first)?;
    let mut prev = first;
    let (mut a_prev, mut d_prev) = (at(vertices, first)?, at(vertices, first + h)?);
    for &(i, _) in it {
        let p = point(i)?;
        if d % 2 == 0 && h > 0 && i % h == prev % h {
            // The reversed partner of the previous chain: F6(a, b, c, c, e, a), which is
            // F6(a, b, c, a, e, c) too (both are F4(a, b, e, c)), so the step does not depend
            // on how the chain is oriented, and the chain (with `prev`, its start) stays.
            vf = f6_of_reversed_chain(a_prev, vf, d_prev, p)?;
            continue;
        }
        // An even face's chain is oriented relative to the previous one by the face alone:
        // of quadruplets i and i + h (the same F4 point), the one whose start follows the
        // previous start in face order, less than half a turn on. F6 is unchanged when both of
        // its chains are reversed (F6(a, b, c, d, e, f) = F6(c, b, a, f, e, d), to rounding),
        // so only this relative orientation enters, and which member of a reversed pair the
        // sort put first — by vertex id, as they always tie — no longer matters: the result
        // does not depend on vertex numbering there. (The other relative orientation is
        // worse conditioned: sphere reproduction on sphere_uv_mixed_pole16 4.3e-10 against
        // < 1e-12; docs/DECISIONS.md.) F6 reads only the chain's ends and the point, so the
        // rule holds where F4 is not symmetric too (a coincidence rule, a negative-real ρ).
        // The identities hold off the negative reals (principal roots: √(q⁻¹) = (√q)⁻¹ fails
        // there), so on exactly cocircular data the numbering can still enter.
        let j = if d % 2 == 0 && (i + d - prev) % d > h {
            (i + h) % d
        } else {
            i
        };
        let (a, e) = (at(vertices, j)?, at(vertices, j + h)?);
        vf = f6(a_prev, vf, d_prev, a, p, e)?;
        (a_prev, d_prev, prev) = (a, e, j);
    }
    Ok(vf)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dist(a: Point, b: Point) -> f64 {
        norm(sub(a, b))
    }

    #[test]
    fn f4_on_a_line_is_the_midpoint() {
        let p = f4([0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [3.0, 0.0, 0.0]).unwrap();
        assert!(dist(p, [1.5, 0.0, 0.0]) < 1e-15, "{p:?}");
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
        assert!(dist(q, on(1.5)) < 1e-14);
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

    #[test]
    fn face_point_of_equal_candidates_is_that_candidate() {
        let square = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let c = [0.5, 0.5, 0.0];
        assert_eq!(face_point(&square, &[c; 4]).unwrap(), c);
        let tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let g = [1.0 / 3.0, 1.0 / 3.0, 0.0];
        assert_eq!(face_point(&tri, &[g; 3]).unwrap(), g);
        assert_eq!(
            face_point(&tri, &[g; 2]).unwrap_err().status,
            Status::InvalidArgument
        );
        assert_eq!(
            face_point(&tri[..2], &[g; 2]).unwrap_err().status,
            Status::TooFewPoints
        );
    }

    #[test]
    fn face_point_with_ids_does_not_depend_on_the_face_start() {
        // A regular-looking quad and hexagon with distinct candidates: every rotation of the
        // corner list (ids rotated with it) gives the same bits.
        let quad = [
            [1.02, 0.03, 0.01],
            [-0.04, 0.97, -0.02],
            [-1.01, 0.05, 0.03],
            [0.02, -0.99, -0.01],
        ];
        let qc = [
            [0.01, -0.02, 0.31],
            [-0.015, 0.02, 0.29],
            [0.02, 0.01, 0.305],
            [-0.01, -0.02, 0.295],
        ];
        let hex: [Point; 6] = core::array::from_fn(|i| {
            let t = i as f64 * core::f64::consts::PI / 3.0;
            [libm::cos(t), libm::sin(t), 0.0]
        });
        let hc: [Point; 6] = core::array::from_fn(|i| [0.01 * i as f64, 0.0, 0.5]);
        let ids = [9u32, 4, 7, 1, 30, 2];
        for (v, c) in [(&quad[..], &qc[..]), (&hex[..], &hc[..])] {
            let n = v.len();
            let reference = face_point_with_ids(v, c, &ids[..n]).unwrap();
            for s in 1..n {
                let rot = |a: &[Point]| -> [Point; 6] {
                    core::array::from_fn(|i| if i < n { a[(i + s) % n] } else { [0.0; 3] })
                };
                let (rv, rc) = (rot(v), rot(c));
                let rid: [u32; 6] = core::array::from_fn(|i| ids[(i + s) % n]);
                let p = face_point_with_ids(&rv[..n], &rc[..n], &rid[..n]).unwrap();
                assert_eq!(p, reference, "n = {n}, start {s}");
            }
        }
        assert_eq!(
            face_point_with_ids(&quad, &qc, &ids[..3])
                .unwrap_err()
                .status,
            Status::InvalidArgument
        );
    }

    #[test]
    fn face_point_with_ids_does_not_depend_on_the_numbering_of_generic_faces() {
        // Different quadruplets of a generic face never tie, and the reversed pairs of an
        // even face are oriented by the face, so permuting the ids changes nothing but the
        // rounding of which pair member is evaluated.
        let mut state = 11;
        let mut worst: f64 = 0.0;
        for n in [4usize, 5, 6, 8] {
            for _ in 0..300 {
                let base: [Point; 8] = lcg_points(&mut state);
                let jitter: [Point; 8] = lcg_points(&mut state);
                let v: arrayvec::ArrayVec<Point, 8> = (0..n)
                    .map(|i| {
                        let t = 2.0 * core::f64::consts::PI * i as f64 / n as f64;
                        let j = base.get(i).copied().unwrap_or([0.0; 3]);
                        [
                            libm::cos(t) + 0.2 * j[0],
                            libm::sin(t) + 0.2 * j[1],
                            0.2 * j[2],
                        ]
                    })
                    .collect();
                let c: arrayvec::ArrayVec<Point, 8> = (0..n)
                    .map(|i| {
                        let j = jitter.get(i).copied().unwrap_or([0.0; 3]);
                        [0.1 * j[0], 0.1 * j[1], 0.1 * j[2]]
                    })
                    .collect();
                let ids: arrayvec::ArrayVec<u32, 8> = (0..n as u32).collect();
                let perm: arrayvec::ArrayVec<u32, 8> =
                    (0..n as u32).map(|i| (i * 5 + 3) % n as u32).collect();
                let rev: arrayvec::ArrayVec<u32, 8> = (0..n as u32).rev().collect();
                let (Ok(p), Ok(q), Ok(r)) = (
                    face_point_with_ids(&v, &c, &ids),
                    face_point_with_ids(&v, &c, &perm),
                    face_point_with_ids(&v, &c, &rev),
                ) else {
                    continue;
                };
                worst = worst.max(dist(p, q)).max(dist(p, r));
            }
        }
        // Orienting the chains by ids instead (the previous rule) moves these face points by
        // 1.6e-7.
        assert!(
            worst < 1e-13,
            "renumbering moves a generic face point by {worst:e}"
        );
    }

    #[test]
    fn face_point_failure_does_not_depend_on_the_face_start() {
        // One candidate is NaN and another quadruplet overflows (points f64::MAX apart): the
        // status must be the same from every start (found by the primitives fuzz target,
        // fuzz/regressions/primitives/face-point-status-start). Then two finite failures:
        // an overflowing quadruplet and well-behaved ones.
        let m = f64::MAX;
        let verts = [
            [0.9 * m, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-0.9 * m, 0.0, 0.0],
            [0.0, -1.0, 0.0],
        ];
        let mut cands = [
            [0.1, 0.0, 0.0],
            [0.0, 0.1, 0.0],
            [-0.1, 0.0, 0.0],
            [0.0, -0.1, 0.0],
        ];
        let ids = [3u32, 1, 2, 0];
        for (nan, want) in [
            (true, Status::NonFiniteInput),
            (false, Status::NumericalFailure),
        ] {
            if nan {
                cands[1] = [f64::NAN, 0.0, 0.0];
            } else {
                cands[1] = [0.0, 0.1, 0.0];
            }
            for s in 0..4 {
                let rot = |a: &[Point]| -> [Point; 4] { core::array::from_fn(|i| a[(i + s) % 4]) };
                let rid: [u32; 4] = core::array::from_fn(|i| ids[(i + s) % 4]);
                let got = face_point_with_ids(&rot(&verts), &rot(&cands), &rid)
                    .unwrap_err()
                    .status;
                assert_eq!(got, want, "start {s}, NaN candidate: {nan}");
            }
        }
    }

    #[test]
    fn face_point_of_a_spherical_face_is_on_the_sphere() {
        // A pentagon on the unit sphere with distinct candidates on the sphere.
        let s = |th: f64, ph: f64| {
            [
                libm::sin(th) * libm::cos(ph),
                libm::sin(th) * libm::sin(ph),
                libm::cos(th),
            ]
        };
        let verts = [
            s(0.5, 0.0),
            s(0.55, 1.3),
            s(0.45, 2.5),
            s(0.6, 3.8),
            s(0.5, 5.0),
        ];
        let cands = [
            s(0.1, 0.2),
            s(0.12, 1.1),
            s(0.09, 2.0),
            s(0.11, 3.0),
            s(0.1, 4.4),
        ];
        let p = face_point(&verts, &cands).unwrap();
        assert!((norm(p) - 1.0).abs() < 1e-12, "{}", norm(p));
    }

    /// Deterministic points in the unit cube (a 64-bit LCG; tests only).
    fn lcg_points<const N: usize>(state: &mut u64) -> [Point; N] {
        let mut next = || {
            *state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (*state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        [[0.0; 3]; N].map(|_| [next(), next(), next()])
    }

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
                worst = worst.max(dist(framed, p) / size);
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
            (dist(q, centre) - big_r).abs() < 1e-13,
            "{q:?} off the sphere"
        );
        assert!(dist(q, inv.apply(p).unwrap()) < 1e-13, "{q:?}");
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
