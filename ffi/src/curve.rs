//! Exports of curve subdivision (`nlsubdiv::curve`): exact sizes and the multi-level driver
//! over caller buffers (seed 000 §4.4.1, seed 001 §3.5, seed 003 §2).
//!
//! Points are packed `double[3*count]`. One level maps `n` points to `2n` (closed) or
//! `2n − 1` (open); the output is interleaved: the vertex point of `P_i` at index `2i`, the
//! edge point of the segment `P_i P_{i+1}` at index `2i + 1`. Interpolating schemes keep the
//! old points bit for bit; after `k` levels input point `i` is at index `2^k i`.

use nlsubdiv::curve::{self, CurveScheme};
use nlsubdiv::{Point, Status, NO_ELEMENT};

use crate::guard::{check_fp_env, check_ptr, flag, overlaps, points, points_mut};
use crate::mesh::{is_clear, named, read_arg, Span};
use crate::primitives::run;

/// Curve scheme: the linear interpolating 4-point scheme (Dyn–Levin–Gregory, `w = 1/16`).
pub const NLS_CURVE_FOUR_POINT: u32 = 0;
/// Curve scheme: the cubic B-spline scheme (mask `(1, 6, 1)/8`, midpoints); open curves keep
/// their end points.
pub const NLS_CURVE_BSPLINE: u32 = 1;
/// Curve scheme: Möbius interpolating, edge points `F4(P_{i−1}, P_i, P_{i+1}, P_{i+2})`
/// (seed 000 §4.4.1). Circle and sphere preserving, Möbius-equivariant.
pub const NLS_CURVE_MOBIUS_INTERPOLATING: u32 = 2;
/// Curve scheme: Möbius approximating, edge points as above, vertex points
/// `F4(P_{i−1}, E_{i−½}, E_{i+½}, P_{i+1})` (seed 000 §4.4.1).
pub const NLS_CURVE_MOBIUS_APPROXIMATING: u32 = 3;
/// Curve scheme: the circle blend of seed 003 §2 (interpolating, circle preserving).
pub const NLS_CURVE_CIRCLE_BLEND: u32 = 4;
/// Curve scheme: differential-space subdivision (seed 001 §3.5) with the 4-point scheme on
/// the differential polygon.
pub const NLS_CURVE_DIFFERENTIAL_FOUR_POINT: u32 = 5;
/// Curve scheme: differential-space subdivision (seed 001 §3.5) with the cubic B-spline
/// scheme on the differential polygon.
pub const NLS_CURVE_DIFFERENTIAL_BSPLINE: u32 = 6;

/// "No element" in `out_element`: the failure names no element.
pub const NLS_NO_ELEMENT: u32 = 0xFFFF_FFFF;

/// An input curve, read only: `count` points packed `x, y, z` (`3 * count` doubles), closed
/// (`closed = 1`) or open (`closed = 0`). Plain data; nothing is kept.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct nls_curve_view {
    /// The points, `3 * count` doubles.
    pub points: *const f64,
    /// Number of points.
    pub count: usize,
    /// 1 for a closed polygon, 0 for an open polyline.
    pub closed: u32,
}

fn scheme_of(code: u32) -> Result<CurveScheme, Status> {
    CurveScheme::from_code(code).ok_or(Status::InvalidArgument)
}

/// # Safety
/// `p` was checked with `check_ptr(p, 1)` and points to a writable `T`.
unsafe fn store<T>(p: *mut T, v: T) {
    // SAFETY: by the caller's contract.
    unsafe { p.write(v) };
}

/// The exact number of points after `levels` levels of any curve scheme:
/// `count·2^levels` (closed) or `(count − 1)·2^levels + 1` (open). `closed` is 0 or 1.
///
/// Errors: `NLS_STATUS_TOO_FEW_POINTS` (fewer than 3 points closed, 2 open),
/// `NLS_STATUS_SIZE_OVERFLOW`, `NLS_STATUS_INVALID_ARGUMENT` (`closed` not 0 or 1),
/// `NLS_STATUS_NULL_PARAMETER`, `NLS_STATUS_MISALIGNED_POINTER`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_curve_refined_size(
    count: usize,
    closed: u32,
    levels: u32,
    out_size: *mut usize,
) -> Status {
    run(|| {
        check_ptr(out_size.cast_const(), 1)?;
        let closed = flag(closed)?;
        let n = curve::refined_size(count, closed, levels).map_err(|e| e.status)?;
        // SAFETY: checked above.
        unsafe { store(out_size, n) };
        Ok(())
    })
}

/// The number of scratch points `nls_curve_subdivide` needs: the size of level
/// `levels − 1` when `levels ≥ 2` (0 below) for the local schemes, and already for
/// `levels = 1` for the differential schemes (their differential polygon needs a buffer).
///
/// Errors: as `nls_curve_refined_size`; `NLS_STATUS_INVALID_ARGUMENT` for an unknown scheme.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_curve_scratch_size(
    scheme: u32,
    count: usize,
    closed: u32,
    levels: u32,
    out_size: *mut usize,
) -> Status {
    run(|| {
        check_ptr(out_size.cast_const(), 1)?;
        let scheme = scheme_of(scheme)?;
        let closed = flag(closed)?;
        let n = curve::scratch_size(scheme, count, closed, levels).map_err(|e| e.status)?;
        // SAFETY: checked above.
        unsafe { store(out_size, n) };
        Ok(())
    })
}

/// Subdivides the curve (`curve->points[0..count]`, packed `x, y, z`, closed or open)
/// `levels` times with `scheme` (`NLS_CURVE_*`).
///
/// The final level is written to `out`, which holds `out_capacity` points
/// (`3*out_capacity` doubles, at least `nls_curve_refined_size`); intermediate levels
/// ping-pong between `out` and `scratch` (`scratch_capacity` points, at least
/// `nls_curve_scratch_size`; NULL with capacity 0 when that is 0). No buffer may overlap
/// another: in-place calls are not supported. `levels = 0` copies the input.
///
/// The local schemes give the same bits as `levels` calls of one level. The differential
/// schemes are global (the differential polygon is subdivided `levels` times and the curve
/// reconstructed once): `levels` calls of one level agree with one call only up to rounding.
///
/// On success `*out_count` is the number of points written. On `NLS_STATUS_BUFFER_TOO_SMALL`
/// `*out_count` is the size needed by the first buffer that is too small (`out` is checked
/// before `scratch`). Otherwise `*out_count` is not written. The contents of `out` and
/// `scratch` are unspecified after an error.
///
/// `out_count` and `out_element` must not point into the input, `out` or `scratch`, nor into
/// each other (`NLS_STATUS_ALIASING_BUFFERS`; `out_element` is then not written).
///
/// `out_element` may be NULL. Otherwise it receives, on failure only (the one exception to
/// "written only on success"), the element at fault or `NLS_NO_ELEMENT`: for
/// `NLS_STATUS_NON_FINITE_INPUT` the index of the point; for `NLS_STATUS_DEGENERATE_GEOMETRY`
/// and `NLS_STATUS_NUMERICAL_FAILURE` the input point that starts the input segment in which
/// the failure arose.
///
/// Repeated consecutive points: the linear and differential schemes accept them, the Möbius
/// schemes reproduce them (F4's coincident rules), the circle blend returns
/// `NLS_STATUS_DEGENERATE_GEOMETRY`.
///
/// Errors: `NLS_STATUS_INVALID_ARGUMENT` (unknown scheme, `closed` not 0 or 1),
/// `NLS_STATUS_SCHEME_NOT_BUILT` (a scheme this build of the library leaves out: its Cargo
/// feature `curves`, and `mobius` for the Möbius schemes, was off),
/// `NLS_STATUS_NULL_PARAMETER`, `NLS_STATUS_MISALIGNED_POINTER`, `NLS_STATUS_SIZE_OVERFLOW`,
/// `NLS_STATUS_TOO_FEW_POINTS`, `NLS_STATUS_BUFFER_TOO_SMALL`, `NLS_STATUS_ALIASING_BUFFERS`,
/// `NLS_STATUS_FP_ENVIRONMENT`, `NLS_STATUS_NON_FINITE_INPUT`,
/// `NLS_STATUS_DEGENERATE_GEOMETRY`, `NLS_STATUS_NUMERICAL_FAILURE`.
///
/// Stack on Cortex-M4F: at most 4,096 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_curve_subdivide(
    scheme: u32,
    curve: *const nls_curve_view,
    levels: u32,
    out: *mut f64,
    out_capacity: usize,
    scratch: *mut f64,
    scratch_capacity: usize,
    out_count: *mut usize,
    out_element: *mut u32,
) -> Status {
    let mut element = NO_ELEMENT;
    // SAFETY: the caller passes NULL or a readable view.
    let view_r = unsafe { read_arg(curve) };
    // Decided before any check can fail: an early failure never writes `out_element` into a
    // buffer of the call (see `ElementSlot::close_unless_clear`).
    let [input] = named(curve, &view_r, |v| {
        [Span::raw(v.points.cast::<Point>(), v.count)]
    });
    let mut element_ok = !out_element.is_null()
        && out_element.is_aligned()
        && is_clear(
            Span::of_one(out_element),
            &[Span::of_one(out_count)],
            &[
                input,
                Some(Span::raw(out.cast_const().cast::<Point>(), out_capacity)),
                Some(Span::raw(
                    scratch.cast_const().cast::<Point>(),
                    scratch_capacity,
                )),
            ],
        );
    let status = run(|| {
        let view = view_r?;
        let (points_xyz, count) = (view.points, view.count);
        check_ptr(out_count.cast_const(), 1)?;
        check_ptr(
            out_element.cast_const(),
            usize::from(!out_element.is_null()),
        )?;
        // The out-pointers must not point into a buffer of the call (arithmetic only: the
        // buffers are checked below).
        let range = |p: usize, bytes: usize| (p, p.saturating_add(bytes));
        let buffers = [
            range(points_xyz as usize, count.saturating_mul(24)),
            range(out as usize, out_capacity.saturating_mul(24)),
            range(scratch as usize, scratch_capacity.saturating_mul(24)),
            range(out_count as usize, core::mem::size_of::<usize>()),
        ];
        let hits = |(a, b): (usize, usize)| {
            buffers
                .iter()
                .any(|&(c, d)| a < b && c < d && a < d && c < b)
        };
        let oc = range(out_count as usize, core::mem::size_of::<usize>());
        let oe = range(
            out_element as usize,
            4 * usize::from(!out_element.is_null()),
        );
        if hits(oe) {
            element_ok = false;
            return Err(Status::AliasingBuffers);
        }
        if buffers
            .iter()
            .take(3)
            .any(|&(c, d)| c < d && c < oc.1 && oc.0 < d)
        {
            return Err(Status::AliasingBuffers);
        }
        let scheme = scheme_of(scheme)?;
        let closed = flag(view.closed)?;
        check_ptr(points_xyz.cast::<Point>(), count)?;
        check_ptr(out.cast_const().cast::<Point>(), out_capacity)?;
        check_ptr(scratch.cast_const().cast::<Point>(), scratch_capacity)?;
        let need = curve::refined_size(count, closed, levels).map_err(|e| e.status)?;
        let need_scratch =
            curve::scratch_size(scheme, count, closed, levels).map_err(|e| e.status)?;
        for (capacity, needed) in [(out_capacity, need), (scratch_capacity, need_scratch)] {
            if capacity < needed {
                // SAFETY: checked above.
                unsafe { store(out_count, needed) };
                return Err(Status::BufferTooSmall);
            }
        }
        // Byte sizes are below isize::MAX (check_ptr), so these products cannot overflow.
        let (n3, o3, s3) = (
            count.saturating_mul(3),
            out_capacity.saturating_mul(3),
            scratch_capacity.saturating_mul(3),
        );
        let (p, o, s) = (points_xyz, out.cast_const(), scratch.cast_const());
        let overlap = |a: *const f64, na: usize, b: *const f64, nb: usize| {
            na > 0 && nb > 0 && overlaps(a, na, b, nb)
        };
        if overlap(p, n3, o, o3) || overlap(p, n3, s, s3) || overlap(o, o3, s, s3) {
            return Err(Status::AliasingBuffers);
        }
        check_fp_env()?;
        // SAFETY: all three ranges were checked (NULL, alignment, size) and are disjoint.
        let (input, out_slice, scratch_slice) = unsafe {
            (
                points(points_xyz, count)?,
                points_mut(out, out_capacity),
                points_mut(scratch, scratch_capacity),
            )
        };
        match curve::subdivide(scheme, input, closed, levels, out_slice, scratch_slice) {
            Ok(written) => {
                // SAFETY: checked above.
                unsafe { store(out_count, written) };
                Ok(())
            }
            Err(e) => {
                element = e.element;
                Err(e.status)
            }
        }
    });
    if status != Status::Ok && element_ok {
        // SAFETY: non-NULL, aligned and outside every buffer of the call; writable by the
        // caller's contract.
        unsafe { store(out_element, element) };
    }
    status
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_match_the_core() {
        let pairs = [
            (NLS_CURVE_FOUR_POINT, CurveScheme::FourPoint),
            (NLS_CURVE_BSPLINE, CurveScheme::BSpline),
            (
                NLS_CURVE_MOBIUS_INTERPOLATING,
                CurveScheme::MobiusInterpolating,
            ),
            (
                NLS_CURVE_MOBIUS_APPROXIMATING,
                CurveScheme::MobiusApproximating,
            ),
            (NLS_CURVE_CIRCLE_BLEND, CurveScheme::CircleBlend),
            (
                NLS_CURVE_DIFFERENTIAL_FOUR_POINT,
                CurveScheme::DifferentialFourPoint,
            ),
            (
                NLS_CURVE_DIFFERENTIAL_BSPLINE,
                CurveScheme::DifferentialBSpline,
            ),
        ];
        assert_eq!(pairs.len(), CurveScheme::ALL.len());
        for (code, scheme) in pairs {
            assert_eq!(code, scheme.code());
        }
        assert_eq!(NLS_NO_ELEMENT, u32::MAX);
    }

    #[test]
    fn subdivide_through_the_abi() {
        let p: [f64; 12] = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0, 0.0];
        let mut need = 0usize;
        let mut scratch_need = 0usize;
        unsafe {
            assert_eq!(nls_curve_refined_size(4, 1, 3, &mut need), Status::Ok);
            assert_eq!(
                nls_curve_scratch_size(NLS_CURVE_CIRCLE_BLEND, 4, 1, 3, &mut scratch_need),
                Status::Ok
            );
        }
        assert_eq!((need, scratch_need), (32, 16));
        let mut out = vec![0.0; 3 * need];
        let mut scratch = vec![0.0; 3 * scratch_need];
        let mut written = 0usize;
        let mut element = 0u32;
        let s = unsafe {
            nls_curve_subdivide(
                NLS_CURVE_CIRCLE_BLEND,
                &nls_curve_view {
                    points: p.as_ptr(),
                    count: 4,
                    closed: 1,
                },
                3,
                out.as_mut_ptr(),
                need,
                scratch.as_mut_ptr(),
                scratch_need,
                &mut written,
                &mut element,
            )
        };
        assert_eq!(s, Status::Ok);
        assert_eq!(written, 32);
        assert_eq!(element, 0, "out_element is written on failure only");
        for q in out.chunks(3) {
            let r = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
            assert!((r - 1.0).abs() < 1e-14);
        }
        // Aliasing: the output overlapping the input.
        let s = unsafe {
            nls_curve_subdivide(
                NLS_CURVE_FOUR_POINT,
                &nls_curve_view {
                    points: out.as_ptr(),
                    count: 4,
                    closed: 1,
                },
                1,
                out.as_mut_ptr().add(3),
                8,
                core::ptr::null_mut(),
                0,
                &mut written,
                &mut element,
            )
        };
        assert_eq!(s, Status::AliasingBuffers);
        assert_eq!(element, NLS_NO_ELEMENT);
        // The count pointing into the output: refused, the output untouched.
        let before = out.clone();
        let s = unsafe {
            nls_curve_subdivide(
                NLS_CURVE_CIRCLE_BLEND,
                &nls_curve_view {
                    points: p.as_ptr(),
                    count: 4,
                    closed: 1,
                },
                3,
                out.as_mut_ptr(),
                need,
                scratch.as_mut_ptr(),
                scratch_need,
                out.as_mut_ptr().add(6).cast(),
                out.as_mut_ptr().add(9).cast(),
            )
        };
        assert_eq!(s, Status::AliasingBuffers);
        assert_eq!(
            out.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            before.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
        );
    }
}
