//! Exports of Möbius maps and canonical forms of vertex stars (seed 000 §3.2, §4.2).

use nlsubdiv::mobius::{CanonicalForm, MobiusMap, StarKind};
use nlsubdiv::{Quat, Status};

use crate::guard::{check_fp_env, check_out, points, read_point, status_of, write};
use crate::primitives::run;

/// A Möbius map `q ↦ (aq + b)(cq + d)⁻¹` of R³ ∪ {∞} (seed 000 Eq. (1)); quaternions as
/// `w, x, y, z`. Build one with the `nls_mobius_*` constructors.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct nls_mobius {
    /// Coefficient `a`.
    pub a: [f64; 4],
    /// Coefficient `b`.
    pub b: [f64; 4],
    /// Coefficient `c`.
    pub c: [f64; 4],
    /// Coefficient `d`.
    pub d: [f64; 4],
}

impl From<MobiusMap> for nls_mobius {
    fn from(m: MobiusMap) -> Self {
        nls_mobius {
            a: m.a.to_array(),
            b: m.b.to_array(),
            c: m.c.to_array(),
            d: m.d.to_array(),
        }
    }
}

impl From<nls_mobius> for MobiusMap {
    fn from(m: nls_mobius) -> Self {
        MobiusMap {
            a: Quat::from_array(m.a),
            b: Quat::from_array(m.b),
            c: Quat::from_array(m.c),
            d: Quat::from_array(m.d),
        }
    }
}

/// Star kind: interior vertex, cyclic ring (seed 000 §4.2).
pub const NLS_STAR_INTERIOR: u32 = 0;
/// Star kind: boundary vertex, ring from one boundary neighbour to the other.
pub const NLS_STAR_BOUNDARY: u32 = 1;
/// Star kind: valence-2 "ear" vertex with one face; the ring is the face's other vertices.
pub const NLS_STAR_EAR: u32 = 2;

/// The canonical form of a vertex star (seed 000 §4.2): the star is sent to its tangent
/// polygon by `q ↦ (q − v)⁻¹`, then inverted in the sphere of centre `c` and radius `r`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct nls_canonical_form {
    /// The centre vertex of the star.
    pub v: [f64; 3],
    /// The centre of the tangent polygon, also the image of `v`.
    pub c: [f64; 3],
    /// The radius of the inversion.
    pub r: f64,
    /// `NLS_STAR_INTERIOR`, `NLS_STAR_BOUNDARY` or `NLS_STAR_EAR`.
    pub kind: u32,
}

fn kind_of(code: u32) -> Result<StarKind, Status> {
    match code {
        NLS_STAR_INTERIOR => Ok(StarKind::Interior),
        NLS_STAR_BOUNDARY => Ok(StarKind::Boundary),
        NLS_STAR_EAR => Ok(StarKind::Ear),
        _ => Err(Status::InvalidArgument),
    }
}

fn code_of(kind: StarKind) -> u32 {
    match kind {
        StarKind::Interior => NLS_STAR_INTERIOR,
        StarKind::Boundary => NLS_STAR_BOUNDARY,
        StarKind::Ear => NLS_STAR_EAR,
        // A kind of a later core version without a C code yet: never produced by this
        // version (the test `star_kinds_all_have_codes` walks `StarKind::ALL`).
        _ => u32::MAX,
    }
}

/// # Safety
/// `p` is NULL or points to a readable, aligned `T`.
unsafe fn read<T: Copy>(p: *const T) -> Result<T, Status> {
    crate::guard::check_ptr(p, 1)?;
    // SAFETY: checked non-NULL and aligned; readable by the caller's contract.
    Ok(unsafe { p.read() })
}

/// # Safety
/// `p` was checked with `check_ptr(p, 1)` and points to a writable `T`.
unsafe fn store<T>(p: *mut T, v: T) {
    // SAFETY: by the caller's contract.
    unsafe { p.write(v) };
}

fn finite_map(m: &nls_mobius) -> bool {
    [m.a, m.b, m.c, m.d].iter().flatten().all(|x| x.is_finite())
}

fn canonical_form_of(cf: &nls_canonical_form) -> Result<CanonicalForm, Status> {
    let kind = kind_of(cf.kind)?;
    let ok = cf.v.iter().chain(cf.c.iter()).all(|x| x.is_finite());
    if !(ok && cf.r > 0.0 && cf.r.is_finite()) {
        return Err(Status::InvalidArgument);
    }
    Ok(CanonicalForm {
        v: cf.v,
        c: cf.c,
        r: cf.r,
        kind,
    })
}

/// The identity map.
///
/// Stack on Cortex-M4F: at most 1,536 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mobius_identity(out: *mut nls_mobius) -> Status {
    run(|| {
        crate::guard::check_ptr(out.cast_const(), 1)?;
        // SAFETY: checked above.
        unsafe { store(out, MobiusMap::IDENTITY.into()) };
        Ok(())
    })
}

/// The similarity `q ↦ s·R(q) + t`: rotation `R` by `angle` radians about the unit vector
/// `axis` (normalised here; it may be zero only when `angle` is 0), scaling by `scale ≠ 0`,
/// translation by `t`.
/// Errors: `NLS_STATUS_NON_FINITE_INPUT`, `NLS_STATUS_INVALID_ARGUMENT` (`scale = 0`, or a
/// zero axis with a non-zero angle), `NLS_STATUS_NUMERICAL_FAILURE` (a coefficient would
/// not be finite: inputs near the end of the double range). Nothing is written on error.
///
/// Stack on Cortex-M4F: at most 2,560 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[axis;3], [t;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mobius_similarity(
    axis: *const f64,
    angle: f64,
    scale: f64,
    t: *const f64,
    out: *mut nls_mobius,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or three readable doubles.
        let (axis, t) = unsafe { (read_point(axis)?, read_point(t)?) };
        crate::guard::check_ptr(out.cast_const(), 1)?;
        check_fp_env()?;
        let finite = axis.iter().chain(t.iter()).all(|x| x.is_finite());
        if !finite || !angle.is_finite() || !scale.is_finite() {
            return Err(Status::NonFiniteInput);
        }
        if scale == 0.0 {
            return Err(Status::InvalidArgument);
        }
        let len = Quat::from_point(axis).abs();
        let rot = if angle == 0.0 {
            MobiusMap::IDENTITY
        } else if len > 0.0 {
            MobiusMap::rotation([axis[0] / len, axis[1] / len, axis[2] / len], angle)
        } else {
            return Err(Status::InvalidArgument);
        };
        let m: nls_mobius = MobiusMap::translation(t)
            .compose(&MobiusMap::scaling(scale))
            .compose(&rot)
            .into();
        // Finite inputs far out in the double range can overflow a coefficient (found by
        // the `primitives` fuzz target): refuse rather than return an infinite map.
        if !finite_map(&m) {
            return Err(Status::NumericalFailure);
        }
        // SAFETY: checked above.
        unsafe { store(out, m) };
        Ok(())
    })
}

/// The inversion in the sphere of centre `centre` and radius `radius > 0`:
/// `q ↦ centre + radius² (q − centre)/|q − centre|²`.
/// Errors: `NLS_STATUS_NON_FINITE_INPUT`, `NLS_STATUS_INVALID_ARGUMENT` (`radius ≤ 0`),
/// `NLS_STATUS_NUMERICAL_FAILURE` (a coefficient would not be finite: a centre or radius
/// near the end of the double range). Nothing is written on error.
///
/// Stack on Cortex-M4F: at most 1,536 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[centre;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mobius_inversion(
    centre: *const f64,
    radius: f64,
    out: *mut nls_mobius,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or three readable doubles.
        let m = unsafe { read_point(centre)? };
        crate::guard::check_ptr(out.cast_const(), 1)?;
        check_fp_env()?;
        if !m.iter().all(|x| x.is_finite()) || !radius.is_finite() {
            return Err(Status::NonFiniteInput);
        }
        if radius <= 0.0 {
            return Err(Status::InvalidArgument);
        }
        let m: nls_mobius = MobiusMap::inversion(m, radius).into();
        // A centre or radius near the end of the double range overflows `|c|² − r²` (found
        // by the `primitives` fuzz target, fuzz/regressions/primitives/).
        if !finite_map(&m) {
            return Err(Status::NumericalFailure);
        }
        // SAFETY: checked above.
        unsafe { store(out, m) };
        Ok(())
    })
}

/// The composition `outer ∘ inner` (first `inner`, then `outer`).
///
/// Stack on Cortex-M4F: at most 2,048 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mobius_compose(
    outer: *const nls_mobius,
    inner: *const nls_mobius,
    out: *mut nls_mobius,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or readable maps.
        let (o, i) = unsafe { (read(outer)?, read(inner)?) };
        crate::guard::check_ptr(out.cast_const(), 1)?;
        check_fp_env()?;
        if !finite_map(&o) || !finite_map(&i) {
            return Err(Status::NonFiniteInput);
        }
        let m: nls_mobius = MobiusMap::from(o).compose(&MobiusMap::from(i)).into();
        if !finite_map(&m) {
            return Err(Status::NumericalFailure);
        }
        // SAFETY: checked above.
        unsafe { store(out, m) };
        Ok(())
    })
}

/// The inverse map. Errors: `NLS_STATUS_DEGENERATE_GEOMETRY` for a singular matrix.
///
/// Stack on Cortex-M4F: at most 2,048 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mobius_invert(m: *const nls_mobius, out: *mut nls_mobius) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or a readable map.
        let m = unsafe { read(m)? };
        crate::guard::check_ptr(out.cast_const(), 1)?;
        check_fp_env()?;
        if !finite_map(&m) {
            return Err(Status::NonFiniteInput);
        }
        let inv = status_of(MobiusMap::from(m).inverse())?;
        // SAFETY: checked above.
        unsafe { store(out, inv.into()) };
        Ok(())
    })
}

/// The image of the point `p`. Errors: `NLS_STATUS_DEGENERATE_GEOMETRY` when `p` is sent to
/// infinity.
///
/// Stack on Cortex-M4F: at most 1,536 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[p;3], [out;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mobius_apply(
    m: *const nls_mobius,
    p: *const f64,
    out: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or readable memory.
        let (m, p) = unsafe { (read(m)?, read_point(p)?) };
        check_out(out, 3)?;
        check_fp_env()?;
        if !finite_map(&m) {
            return Err(Status::NonFiniteInput);
        }
        let w = status_of(MobiusMap::from(m).apply(p))?;
        // SAFETY: checked above.
        unsafe { write(out, w) };
        Ok(())
    })
}

/// The canonical form of the vertex star `v ring[0..ring_count]` (seed 000 §4.2). `kind` is
/// `NLS_STAR_INTERIOR` (cyclic ring), `NLS_STAR_BOUNDARY` or `NLS_STAR_EAR` (ring from one
/// boundary neighbour to the other); at least 2 neighbours.
///
/// Errors: `NLS_STATUS_INVALID_ARGUMENT` (unknown kind), `NLS_STATUS_TOO_FEW_POINTS`,
/// `NLS_STATUS_VALENCE_TOO_HIGH`, `NLS_STATUS_NON_FINITE_INPUT`,
/// `NLS_STATUS_DEGENERATE_GEOMETRY` (a neighbour coincides with `v`, or zero radius).
///
/// Stack on Cortex-M4F: at most 4,608 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[v;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_canonical_form_new(
    v: *const f64,
    ring: *const f64,
    ring_count: usize,
    kind: u32,
    out: *mut nls_canonical_form,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or readable memory of the documented sizes.
        let (v, ring) = unsafe { (read_point(v)?, points(ring, ring_count)?) };
        crate::guard::check_ptr(out.cast_const(), 1)?;
        let kind = kind_of(kind)?;
        check_fp_env()?;
        let cf = status_of(CanonicalForm::new(v, ring, kind))?;
        let c = nls_canonical_form {
            v: cf.v,
            c: cf.c,
            r: cf.r,
            kind: code_of(cf.kind),
        };
        // SAFETY: checked above.
        unsafe { store(out, c) };
        Ok(())
    })
}

/// Sends a point of the star's neighbourhood to the canonical form (`v` goes to `c`).
/// Errors: `NLS_STATUS_INVALID_ARGUMENT` for a malformed `cf`,
/// `NLS_STATUS_DEGENERATE_GEOMETRY` when the point is sent to infinity.
///
/// cbindgen:ptrs-as-arrays=[[p;3], [out;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_canonical_form_to_canonical(
    cf: *const nls_canonical_form,
    p: *const f64,
    out: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or readable memory.
        let (cf, p) = unsafe { (read(cf)?, read_point(p)?) };
        check_out(out, 3)?;
        check_fp_env()?;
        let w = status_of(canonical_form_of(&cf)?.to_canonical(p))?;
        // SAFETY: checked above.
        unsafe { write(out, w) };
        Ok(())
    })
}

/// Sends a point of the canonical form back to the star (`c` goes back to `v`).
///
/// cbindgen:ptrs-as-arrays=[[p;3], [out;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_canonical_form_from_canonical(
    cf: *const nls_canonical_form,
    p: *const f64,
    out: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or readable memory.
        let (cf, p) = unsafe { (read(cf)?, read_point(p)?) };
        check_out(out, 3)?;
        check_fp_env()?;
        let w = status_of(canonical_form_of(&cf)?.from_canonical(p))?;
        // SAFETY: checked above.
        unsafe { write(out, w) };
        Ok(())
    })
}

/// The Möbius map of a canonical form:
/// with `inverse = 0` the forward map `m_{B→C}`, with `inverse = 1` the map back `m_{C→B}`.
/// Errors: `NLS_STATUS_INVALID_ARGUMENT` (a malformed `cf`, `inverse` not 0 or 1),
/// `NLS_STATUS_NUMERICAL_FAILURE` (a coefficient would not be finite),
/// `NLS_STATUS_FP_ENVIRONMENT`. Nothing is written on error.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_canonical_form_map(
    cf: *const nls_canonical_form,
    inverse: u32,
    out: *mut nls_mobius,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or a readable canonical form.
        let cf = unsafe { read(cf)? };
        crate::guard::check_ptr(out.cast_const(), 1)?;
        let inverse = crate::guard::flag(inverse)?;
        check_fp_env()?;
        let cf = canonical_form_of(&cf)?;
        let m: nls_mobius = if inverse { cf.inverse_map() } else { cf.map() }.into();
        // A form far out in the double range overflows a coefficient: refuse.
        if !finite_map(&m) {
            return Err(Status::NumericalFailure);
        }
        // SAFETY: checked above.
        unsafe { store(out, m) };
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every star kind of the core has a C code and comes back from it: the wildcard arm of
    /// `code_of` (the core's enum is `#[non_exhaustive]`) never hides a kind.
    #[test]
    fn star_kinds_all_have_codes() {
        let codes = [NLS_STAR_INTERIOR, NLS_STAR_BOUNDARY, NLS_STAR_EAR];
        assert_eq!(StarKind::ALL.len(), codes.len());
        for (kind, code) in StarKind::ALL.into_iter().zip(codes) {
            assert_eq!(code_of(kind), code);
            assert_eq!(kind_of(code), Ok(kind));
        }
    }
}
