//! Square roots of cross-ratios with the branch of seed 000 §4.4.1 and the choice of axis on
//! the negative real axis (§4.4.1–4.4.2, Appendix A).
//!
//! The blends need `√q` of a cross-ratio `q`. Off the negative reals this is the principal root
//! (`Re √q ≥ 0`, [`Quat::sqrt`]). A negative real `q` has a whole sphere of roots `√|q| [0, n]`,
//! one per unit axis `n`; the paper prints the normal of the points' plane. The functions here
//! decide when `q` counts as a negative real ([`is_negative_real`]), which axis is taken
//! (the plane normal, or the imaginary direction of a cross-ratio that starts at the same
//! point, which keeps the result Möbius-equivariant and on the inputs' sphere by Lemma A.1),
//! and remove rounding noise across that axis before the root divides by `|Im q|`.

use super::NEGATIVE_REAL_TOLERANCE;
use crate::point::{cross, norm, scale, sub, Point};
use crate::quat::Quat;

/// Whether `q` counts as a negative real: `Re q < 0` and `|Im q| ≤ 1e-12 |q|`
/// ([`NEGATIVE_REAL_TOLERANCE`]).
pub fn is_negative_real(q: Quat) -> bool {
    q.w < 0.0 && q.abs_im() <= NEGATIVE_REAL_TOLERANCE * q.abs()
}

/// [`is_negative_real`] with `r = q.abs()` known.
#[inline(always)]
pub(super) fn is_negative_real_with_abs(q: Quat, r: f64) -> bool {
    q.w < 0.0 && q.abs_im() <= NEGATIVE_REAL_TOLERANCE * r
}

/// The unit normal of the plane through `a, b, c` (`(a − b) × (c − b)` normalised); for
/// collinear points a fixed unit vector orthogonal to `c − b` (or `a − b`), chosen by the
/// smallest coordinate so that the choice is deterministic.
pub(super) fn plane_normal(a: Point, b: Point, c: Point) -> Point {
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
/// half-plane it first removes rounding noise from the direction of `Im q`: there
/// `Im √q = n·t` divides by `|Im q|`, so noise of size `ε|q|` across the reference axis `n`
/// turns a point that should lie on a sphere into one off it by `ε|q|/|Im q|` (seed 000
/// Lemma A.1: for cospherical points every cross-ratio starting at the same point has its
/// imaginary part along one axis). A component across `n` below `1e-12 |q|` is dropped; larger
/// ones are kept, so nothing changes for points that are not cospherical.
///
/// `r = q.abs()` is computed by the caller (F4 has it from the noncircularity). `|Im q|` is needed only for a negative real part (the negative-real test
/// and the root's lower half-space formula); with `Re q ≥ 0` the root reads only whether
/// `Im q` is zero, which is whether its three components are (`abs_im` is zero exactly
/// then), so the common case takes two square roots fewer. The same bits as computing both
/// norms first.
#[inline(always)]
pub(super) fn sqrt_snapped_with_abs(q: Quat, r: f64, n: Point, snap: bool) -> Option<Quat> {
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
            let t = crate::sqrt::sqrt(r);
            return Some(Quat::new(0.0, n[0] * t, n[1] * t, n[2] * t));
        }
        return q.sqrt_given(r, vi);
    }
    q.sqrt_upper(r)
}

/// [`sqrt_snapped_with_abs`] with the axis found only when it is read: `axis` is filled from
/// `find` on the first root of a quaternion with negative real part and reused after. With
/// `Re q ≥ 0` (or NaN) [`sqrt_snapped_with_abs`] reads neither the axis nor `snap` and is
/// [`Quat::sqrt_upper`], so this gives the same bits while F6 skips its axis search
/// ([`imaginary_axis`], three norms and six divisions) in the common case where all of its
/// roots are taken in the right half-space (seed 000 §4.4.2). `find` returns the axis and
/// whether to snap to it.
#[inline(always)]
pub(super) fn sqrt_with_lazy_axis(
    q: Quat,
    r: f64,
    axis: &mut Option<(Point, bool)>,
    find: impl FnOnce() -> (Point, bool),
) -> Option<Quat> {
    if q.w < 0.0 {
        let (n, snap) = *axis.get_or_insert_with(find);
        return sqrt_snapped_with_abs(q, r, n, snap);
    }
    q.sqrt_upper(r)
}

/// The unit imaginary part of the quaternion of `qs` farthest from real (largest
/// `|Im q| / |q|`, the first on ties), or `None` when all are real.
/// `abs[i] = qs[i].abs()` is computed by the caller (F6 reuses it for the roots).
#[inline(always)]
pub(super) fn imaginary_axis(qs: &[Quat], abs: &[f64]) -> Option<Point> {
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
