//! Pointer checks and the floating-point-environment guard shared by every export
//! (reliability-anchors §6: NULL → alignment → size → overlap → only then form slices).

use core::mem::{align_of, size_of};

use nlsubdiv::{Point, Status};

/// Whether the x86 MXCSR register is in its IEEE default state (round to nearest, no
/// flush-to-zero, no denormals-are-zero; exception masks and sticky flags are ignored).
/// Hosts compiled with `-ffast-math` start with FTZ/DAZ set, which silently changes
/// results; we refuse to compute rather than return different bits.
#[cfg(target_arch = "x86_64")]
pub(crate) fn fp_env_is_default() -> bool {
    let mut csr: u32 = 0;
    // SAFETY: `stmxcsr` stores the 32-bit MXCSR register to the given, valid, aligned
    // location; it has no other effect.
    unsafe {
        core::arch::asm!("stmxcsr [{}]", in(reg) &mut csr, options(nostack, preserves_flags));
    }
    // Bits 13-14 rounding control, bit 15 FTZ, bit 6 DAZ must be zero.
    csr & 0xE040 == 0
}

#[cfg(not(target_arch = "x86_64"))]
pub(crate) fn fp_env_is_default() -> bool {
    true
}

/// Fails with `FpEnvironment` unless the floating-point environment is the default one.
pub(crate) fn check_fp_env() -> Result<(), Status> {
    if fp_env_is_default() {
        Ok(())
    } else {
        Err(Status::FpEnvironment)
    }
}

/// Checks a pointer to `count` elements of `T`: NULL only with `count == 0`, aligned, and
/// `count * size_of::<T>() ≤ isize::MAX`.
pub(crate) fn check_ptr<T>(p: *const T, count: usize) -> Result<(), Status> {
    if count == 0 {
        return Ok(());
    }
    if p.is_null() {
        return Err(Status::NullParameter);
    }
    if (p as usize) % align_of::<T>() != 0 {
        return Err(Status::MisalignedPointer);
    }
    match count.checked_mul(size_of::<T>()) {
        Some(bytes) if bytes <= isize::MAX as usize => Ok(()),
        _ => Err(Status::SizeOverflow),
    }
}

/// Reads the point `p[0..3]`.
///
/// # Safety
/// `p` is NULL or points to three readable `double`s.
pub(crate) unsafe fn read_point(p: *const f64) -> Result<Point, Status> {
    check_ptr(p, 3)?;
    // SAFETY: checked non-NULL and aligned; the caller guarantees three readable doubles.
    Ok(unsafe { [p.read(), p.add(1).read(), p.add(2).read()] })
}

/// Reads the quaternion `p[0..4]` (`w, x, y, z`).
///
/// # Safety
/// `p` is NULL or points to four readable `double`s.
pub(crate) unsafe fn read_quat(p: *const f64) -> Result<[f64; 4], Status> {
    check_ptr(p, 4)?;
    // SAFETY: checked non-NULL and aligned; the caller guarantees four readable doubles.
    Ok(unsafe { [p.read(), p.add(1).read(), p.add(2).read(), p.add(3).read()] })
}

/// Checks an output pointer for `count` doubles before any computation.
pub(crate) fn check_out(p: *mut f64, count: usize) -> Result<(), Status> {
    check_ptr(p.cast_const(), count)
}

/// Writes `values` to `out[0..N]`.
///
/// # Safety
/// `out` was checked with [`check_out`] for `N` doubles and points to `N` writable doubles.
pub(crate) unsafe fn write<const N: usize>(out: *mut f64, values: [f64; N]) {
    for (i, v) in values.into_iter().enumerate() {
        // SAFETY: `i < N` and the caller guarantees `N` writable doubles at `out`.
        unsafe { out.add(i).write(v) };
    }
}

/// Borrows `count` packed points `double[3*count]` as a slice.
///
/// # Safety
/// `p` is NULL (then `count` must be 0) or points to `3*count` readable doubles that stay
/// valid and unmodified for `'a`.
pub(crate) unsafe fn points<'a>(p: *const f64, count: usize) -> Result<&'a [Point], Status> {
    check_ptr(p.cast::<Point>(), count)?;
    if count == 0 {
        return Ok(&[]);
    }
    // SAFETY: non-NULL, aligned for `[f64; 3]` (alignment of f64), byte size ≤ isize::MAX,
    // and the caller guarantees the memory is readable for `count` points.
    Ok(unsafe { core::slice::from_raw_parts(p.cast::<Point>(), count) })
}

/// Turns a core result into the status and, on success, the value.
pub(crate) fn status_of<T>(r: nlsubdiv::Result<T>) -> Result<T, Status> {
    r.map_err(|e| e.status)
}

/// Whether the byte ranges of `a[0..na]` and `b[0..nb]` (counts of doubles) intersect.
pub(crate) fn overlaps(a: *const f64, na: usize, b: *const f64, nb: usize) -> bool {
    let (a0, b0) = (a as usize, b as usize);
    let a1 = a0.saturating_add(na.saturating_mul(8));
    let b1 = b0.saturating_add(nb.saturating_mul(8));
    a0 < b1 && b0 < a1
}

/// A C boolean flag: 0 or 1; anything else is `InvalidArgument`.
pub(crate) fn flag(v: u32) -> Result<bool, Status> {
    match v {
        0 => Ok(false),
        1 => Ok(true),
        _ => Err(Status::InvalidArgument),
    }
}
