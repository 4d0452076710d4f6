//! Exports of the Möbius primitives: quaternions, cross-ratio, corner tangent, F4, F6 and
//! the vertex-star measures (seed 000 §3–4.4).
//!
//! Every output may alias an input: inputs are read completely before anything is written.

use nlsubdiv::{blend, metrics, quat, Quat, Status};

use crate::guard::{check_fp_env, check_out, points, read_point, read_quat, status_of, write};

/// Runs an export body and folds its result into a status. Host floating-point traps are
/// masked for the body and restored after it ([`crate::guard::FpTrapGuard`]).
pub(crate) fn run(body: impl FnOnce() -> Result<(), Status>) -> Status {
    let _traps = crate::guard::FpTrapGuard::mask_traps();
    match body() {
        Ok(()) => Status::Ok,
        Err(s) => s,
    }
}

/// The quaternionic cross-ratio `cr[a, b, c, d] = (b − a)(c − b)⁻¹(d − c)(a − d)⁻¹`
/// (seed 000 §3.2), written as `w, x, y, z`. It is real iff the points are cocircular.
///
/// Errors: `NLS_STATUS_NULL_PARAMETER`, `NLS_STATUS_MISALIGNED_POINTER`,
/// `NLS_STATUS_NON_FINITE_INPUT`, `NLS_STATUS_DEGENERATE_GEOMETRY` (`b = c` or `d = a`),
/// `NLS_STATUS_FP_ENVIRONMENT`.
///
/// Stack on Cortex-M4F: at most 1,536 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[a;3], [b;3], [c;3], [d;3], [out_wxyz;4]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_cross_ratio(
    a: *const f64,
    b: *const f64,
    c: *const f64,
    d: *const f64,
    out_wxyz: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or three readable doubles per point.
        let (a, b, c, d) = unsafe {
            (
                read_point(a)?,
                read_point(b)?,
                read_point(c)?,
                read_point(d)?,
            )
        };
        check_out(out_wxyz, 4)?;
        check_fp_env()?;
        let q = status_of(quat::cross_ratio(a, b, c, d))?;
        // SAFETY: checked above; four writable doubles by contract.
        unsafe { write(out_wxyz, q.to_array()) };
        Ok(())
    })
}

/// The four-point blend `F4(a, b, c, d)` (seed 000 §4.4.1, Eq. (3)): the Möbius-invariant
/// point between `b` and `c`. Cocircular inputs (with `(a, d)` not separated by `(b, c)`)
/// give a point on their circle, cospherical inputs a point on their sphere;
/// `F4(a, b, c, d) = F4(d, c, b, a)`.
///
/// Coincident inputs give the defined results `b = c → b`, `a = b → b`, `c = d → c`,
/// `a = c → c`, `b = d → b` (tolerance 1e-13 × the diameter of the points).
///
/// Errors: `NLS_STATUS_NULL_PARAMETER`, `NLS_STATUS_MISALIGNED_POINTER`,
/// `NLS_STATUS_NON_FINITE_INPUT`, `NLS_STATUS_DEGENERATE_GEOMETRY` (the point is at
/// infinity), `NLS_STATUS_NUMERICAL_FAILURE`, `NLS_STATUS_FP_ENVIRONMENT`.
///
/// Stack on Cortex-M4F: at most 3,072 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[a;3], [b;3], [c;3], [d;3], [out;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_f4(
    a: *const f64,
    b: *const f64,
    c: *const f64,
    d: *const f64,
    out: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or three readable doubles per point.
        let (a, b, c, d) = unsafe {
            (
                read_point(a)?,
                read_point(b)?,
                read_point(c)?,
                read_point(d)?,
            )
        };
        check_out(out, 3)?;
        check_fp_env()?;
        let p = status_of(blend::f4(a, b, c, d))?;
        // SAFETY: checked above; three writable doubles by contract.
        unsafe { write(out, p) };
        Ok(())
    })
}

/// `nls_f4` with a fifth point `x` that decides the one case where F4 is not
/// Möbius-equivariant: when `ρ = cr[c, a, b, d]` is a negative real (the four points are
/// cocircular and `(b, c)` separates `(a, d)`), the new point is taken on the sphere through
/// `a, b, c, x` instead of in the plane of the circle. Elsewhere identical to `nls_f4`.
///
/// This is the edge blend of the Möbius mesh schemes: the edge point of an interior edge
/// `a → b` (the half-edge from the smaller to the larger vertex index) is
/// `F4(a, e_a, e_b, b)` with `e_a`, `e_b` the edge candidates of the two end points' stars
/// (`nls_mobius_loop_star`, `nls_mobius_catmull_clark_star`) and `x` the corner after `b` in
/// the face on the left of `a → b` (the third vertex of a triangle), so a spherical mesh
/// stays on its sphere in the cocircular case too.
///
/// Errors: as `nls_f4`; a non-finite `x` is `NLS_STATUS_NON_FINITE_INPUT`.
///
/// Stack on Cortex-M4F: at most 3,072 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[a;3], [b;3], [c;3], [d;3], [x;3], [out;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_f4_hinted(
    a: *const f64,
    b: *const f64,
    c: *const f64,
    d: *const f64,
    x: *const f64,
    out: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or three readable doubles per point.
        let (a, b, c, d, x) = unsafe {
            (
                read_point(a)?,
                read_point(b)?,
                read_point(c)?,
                read_point(d)?,
                read_point(x)?,
            )
        };
        check_out(out, 3)?;
        check_fp_env()?;
        let p = status_of(blend::f4_hinted(a, b, c, d, x))?;
        // SAFETY: checked above; three writable doubles by contract.
        unsafe { write(out, p) };
        Ok(())
    })
}

/// The six-point blend `F6(a, b, c, d, e, f)` of the chains `a, b, c` and `d, e, f`
/// (seed 000 §4.4.2). Sphere preserving for cospherical points; `b = e` gives `b`.
///
/// Errors: as `nls_f4`; `NLS_STATUS_DEGENERATE_GEOMETRY` also when a cross-ratio of the
/// construction is undefined (`a = b`, `d = e`, `b = c`, `e = f`).
///
/// Stack on Cortex-M4F: at most 3,584 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[a;3], [b;3], [c;3], [d;3], [e;3], [f;3], [out;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_f6(
    a: *const f64,
    b: *const f64,
    c: *const f64,
    d: *const f64,
    e: *const f64,
    f: *const f64,
    out: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or three readable doubles per point.
        let (a, b, c, d, e, f) = unsafe {
            (
                read_point(a)?,
                read_point(b)?,
                read_point(c)?,
                read_point(d)?,
                read_point(e)?,
                read_point(f)?,
            )
        };
        check_out(out, 3)?;
        check_fp_env()?;
        let p = status_of(blend::f6(a, b, c, d, e, f))?;
        // SAFETY: checked above; three writable doubles by contract.
        unsafe { write(out, p) };
        Ok(())
    })
}

/// The noncircularity `1 − |Re ρ|/|ρ|` of the quadruplet `(a, b, c, d)` with
/// `ρ = cr[c, a, b, d]`, the cross-ratio F4 uses (seed 000 §4.4.3 (ii)); 0 for cocircular
/// points.
///
/// Stack on Cortex-M4F: at most 1,536 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[a;3], [b;3], [c;3], [d;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_noncircularity(
    a: *const f64,
    b: *const f64,
    c: *const f64,
    d: *const f64,
    out: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or three readable doubles per point.
        let (a, b, c, d) = unsafe {
            (
                read_point(a)?,
                read_point(b)?,
                read_point(c)?,
                read_point(d)?,
            )
        };
        check_out(out, 1)?;
        check_fp_env()?;
        let v = status_of(blend::noncircularity(a, b, c, d))?;
        // SAFETY: checked above.
        unsafe { write(out, [v]) };
        Ok(())
    })
}

/// The corner tangent `t[a, b, c] = (b − a)⁻¹ + (c − b)⁻¹` (seed 000 §3.3): a vector tangent
/// at `b` to the circle through `a, b, c`.
///
/// Stack on Cortex-M4F: at most 1,536 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[a;3], [b;3], [c;3], [out;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_corner_tangent(
    a: *const f64,
    b: *const f64,
    c: *const f64,
    out: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or three readable doubles per point.
        let (a, b, c) = unsafe { (read_point(a)?, read_point(b)?, read_point(c)?) };
        check_out(out, 3)?;
        check_fp_env()?;
        let t = status_of(quat::corner_tangent(a, b, c))?;
        // SAFETY: checked above.
        unsafe { write(out, t) };
        Ok(())
    })
}

/// The tangent polygon `T_i = (u_i − v)⁻¹` of the vertex star `v u_0 … u_{n−1}`
/// (seed 000 §3.3, Lemma 3.1). `ring` holds `3*ring_count` doubles; `out` must hold
/// `3*ring_count` doubles and must not overlap `ring`.
///
/// Errors: also `NLS_STATUS_DEGENERATE_GEOMETRY` when a neighbour coincides with `v`.
///
/// Stack on Cortex-M4F: at most 1,536 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[v;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_tangent_polygon(
    v: *const f64,
    ring: *const f64,
    ring_count: usize,
    out: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or readable memory of the documented sizes.
        let (v, ring) = unsafe { (read_point(v)?, points(ring, ring_count)?) };
        let n3 = ring_count.checked_mul(3).ok_or(Status::SizeOverflow)?;
        check_out(out, n3)?;
        if ring_count > 0 && crate::guard::overlaps(ring.as_ptr().cast(), n3, out.cast_const(), n3)
        {
            return Err(Status::AliasingBuffers);
        }
        check_fp_env()?;
        for (i, u) in ring.iter().enumerate() {
            // Validate everything before the first write: no partial results.
            status_of(quat::tangent_polygon_vertex(v, *u).map_err(|e| e.with_element(i as u32)))?;
        }
        for (i, u) in ring.iter().enumerate() {
            let t = status_of(quat::tangent_polygon_vertex(v, *u))?;
            // SAFETY: `i < ring_count`, and `out` holds `3*ring_count` writable doubles.
            unsafe { write(out.add(3 * i), t) };
        }
        Ok(())
    })
}

fn quat_op(
    p: *const f64,
    out: *mut f64,
    op: impl FnOnce(Quat) -> Option<Quat>,
) -> Result<(), Status> {
    // SAFETY: the caller passes NULL or four readable doubles.
    let q = Quat::from_array(unsafe { read_quat(p)? });
    check_out(out, 4)?;
    check_fp_env()?;
    if !q.is_finite() {
        return Err(Status::NonFiniteInput);
    }
    let r = op(q).ok_or(Status::DegenerateGeometry)?;
    if !r.is_finite() {
        return Err(Status::NumericalFailure);
    }
    // SAFETY: checked above.
    unsafe { write(out, r.to_array()) };
    Ok(())
}

/// The Hamilton product `p·q` of two quaternions given as `w, x, y, z`.
///
/// Stack on Cortex-M4F: at most 1,536 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[p;4], [q;4], [out;4]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_quat_mul(p: *const f64, q: *const f64, out: *mut f64) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or four readable doubles.
        let a = Quat::from_array(unsafe { read_quat(p)? });
        quat_op(q, out, |b| Some(a * b))
    })
}

/// The inverse `q⁻¹ = q̄/|q|²`. Errors: `NLS_STATUS_DEGENERATE_GEOMETRY` for `q = 0` (or an
/// inverse that is not a finite, non-zero quaternion).
///
/// Stack on Cortex-M4F: at most 1,536 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[q;4], [out;4]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_quat_inverse(q: *const f64, out: *mut f64) -> Status {
    run(|| quat_op(q, out, Quat::inverse))
}

/// The principal square root (non-negative real part, seed 000 §3.1). Errors:
/// `NLS_STATUS_DEGENERATE_GEOMETRY` for a negative real `q`, whose root is not unique.
///
/// Stack on Cortex-M4F: at most 1,536 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[q;4], [out;4]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_quat_sqrt(q: *const f64, out: *mut f64) -> Status {
    run(|| quat_op(q, out, Quat::sqrt))
}

/// The principal logarithm `[ln|q|, n θ]`. Errors: `NLS_STATUS_DEGENERATE_GEOMETRY` for zero
/// or a negative real `q`.
///
/// Stack on Cortex-M4F: at most 1,536 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[q;4], [out;4]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_quat_log(q: *const f64, out: *mut f64) -> Status {
    run(|| quat_op(q, out, Quat::log))
}

/// The exponential `e^w [cos|v|, v/|v| sin|v|]`. Errors: `NLS_STATUS_NUMERICAL_FAILURE` on
/// overflow.
///
/// Stack on Cortex-M4F: at most 2,048 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[q;4], [out;4]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_quat_exp(q: *const f64, out: *mut f64) -> Status {
    run(|| quat_op(q, out, |q| Some(q.exp())))
}

/// The discrete Willmore energy of the vertex star `v ring…`: the RMS planarity of every
/// four consecutive vertices of its tangent polygon (seed 000 §3.3, Fig. 9). 0 iff the star
/// is cospherical. `closed` is 1 for an interior vertex (cyclic ring), 0 for a boundary
/// vertex (ring from one boundary neighbour to the other); other values are
/// `NLS_STATUS_INVALID_ARGUMENT`.
///
/// Stack on Cortex-M4F: at most 1,536 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[v;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_star_willmore_energy(
    v: *const f64,
    ring: *const f64,
    ring_count: usize,
    closed: u32,
    out: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or readable memory of the documented sizes.
        let (v, ring) = unsafe { (read_point(v)?, points(ring, ring_count)?) };
        check_out(out, 1)?;
        let closed = crate::guard::flag(closed)?;
        check_fp_env()?;
        let w = status_of(metrics::willmore_energy(v, ring, closed))?;
        // SAFETY: checked above.
        unsafe { write(out, [w]) };
        Ok(())
    })
}

/// The Möbius-regularity defect of the vertex star `v ring…`: the sum of squared differences
/// of consecutive cross-ratios `cr[v, u_{i−1}, u_i, u_{i+1}]` (seed 000 Fig. 15); 0 iff the
/// star is Möbius regular. `closed` as for `nls_star_willmore_energy`.
///
/// Stack on Cortex-M4F: at most 1,536 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[v;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_star_mobius_regularity(
    v: *const f64,
    ring: *const f64,
    ring_count: usize,
    closed: u32,
    out: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or readable memory of the documented sizes.
        let (v, ring) = unsafe { (read_point(v)?, points(ring, ring_count)?) };
        check_out(out, 1)?;
        let closed = crate::guard::flag(closed)?;
        check_fp_env()?;
        let m = status_of(metrics::mobius_regularity(v, ring, closed))?;
        // SAFETY: checked above.
        unsafe { write(out, [m]) };
        Ok(())
    })
}

/// The Möbius-invariant face point of a `count`-gon from its vertices and the candidate face
/// points computed in the canonical forms of the vertices' stars (seed 000 §4.4.3): F4 on
/// the quadruplets `(v_i, v_{f,i}, v_{f,i+h}, v_{i+h})` sorted by noncircularity, chained with
/// F6 (in an even face each chain oriented by the face: its start follows the previous
/// chain's start in face order; docs/DECISIONS.md). `vertices` and `candidates` hold
/// `3*count` doubles each.
///
/// Errors: `NLS_STATUS_TOO_FEW_POINTS` (`count < 3`), `NLS_STATUS_VALENCE_TOO_HIGH`, and
/// those of `nls_f4` and `nls_f6`.
///
/// Stack on Cortex-M4F: at most 8,192 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[out;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_face_point(
    vertices: *const f64,
    candidates: *const f64,
    count: usize,
    out: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or readable memory of the documented sizes.
        let (v, c) = unsafe { (points(vertices, count)?, points(candidates, count)?) };
        check_out(out, 3)?;
        check_fp_env()?;
        let p = status_of(blend::face_point(v, c))?;
        // SAFETY: checked above.
        unsafe { write(out, p) };
        Ok(())
    })
}

/// `nls_face_point` with ties of the noncircularity sort broken by the vertex ids `ids[i]`
/// (`count` of them, the host's indices of the face's corners): the face point is then the
/// same, bit for bit, whichever corner the face is listed from, and stays Möbius-equivariant.
/// This is what `nls_mesh_subdivide` uses for its Möbius face points; a host driving the
/// tier-1 rules should call it with its own vertex indices.
///
/// Errors: those of `nls_face_point`.
///
/// Stack on Cortex-M4F: at most 8,192 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[out;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_face_point_with_ids(
    vertices: *const f64,
    candidates: *const f64,
    ids: *const u32,
    count: usize,
    out: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or readable memory of the documented sizes.
        let (v, c) = unsafe { (points(vertices, count)?, points(candidates, count)?) };
        crate::guard::check_ptr(ids, count)?;
        let ids: &[u32] = if count == 0 {
            &[]
        } else {
            // SAFETY: non-NULL, aligned, byte size ≤ isize::MAX (check_ptr), readable for
            // `count` ids (contract).
            unsafe { core::slice::from_raw_parts(ids, count) }
        };
        check_out(out, 3)?;
        check_fp_env()?;
        let p = status_of(blend::face_point_with_ids(v, c, ids))?;
        // SAFETY: checked above.
        unsafe { write(out, p) };
        Ok(())
    })
}
