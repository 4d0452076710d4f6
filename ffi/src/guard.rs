//! Pointer checks and the floating-point-environment guard shared by every export
//! (NULL → alignment → size → overlap → only then form slices).

use core::mem::{align_of, size_of};

use nlsubdiv::{Point, Status};

// The floating-point environment of the calling thread (docs/DECISIONS.md, "Host
// floating-point traps"; docs/firmware.md, "Floating-point environment", for each
// architecture).
//
// * Modes that change results (flush-to-zero, denormals-are-zero, default-NaN, a rounding
//   mode other than to nearest) are refused with `NLS_STATUS_FP_ENVIRONMENT`: the documented
//   bits would not come out. [`fp_env_is_default`] reads them.
// * Unmasked exception traps (a host that called `feenableexcept`) do not change any result
//   — a masked exception gives the IEEE default result, which is what the library computes
//   with and then checks (an overflow becomes `NLS_STATUS_NUMERICAL_FAILURE`, never a
//   signal). So every export masks them for the length of the call and restores the host's
//   register afterwards ([`FpTrapGuard`]): the host keeps its traps for its own code, and
//   the exceptions the library raises (and handles) internally never reach it, neither as
//   a SIGFPE nor as sticky flags.

/// MXCSR (x86_64, and 32-bit x86 with SSE2, whose `f64` arithmetic is SSE): exception masks
/// bits 7-12, denormals-are-zero bit 6, rounding bits 13-14, flush-to-zero bit 15.
#[cfg(any(
    target_arch = "x86_64",
    all(target_arch = "x86", target_feature = "sse2")
))]
mod fpcr {
    pub(crate) type Reg = u32;
    /// All six exception masks set: no traps.
    pub(crate) const TRAPS_MASKED: Reg = 0x1F80;
    /// Rounding control, flush-to-zero, denormals-are-zero.
    const MODE_BITS: Reg = 0xE040;

    pub(crate) fn modes_set(csr: Reg) -> bool {
        csr & MODE_BITS != 0
    }

    pub(crate) fn read() -> Reg {
        let mut csr: u32 = 0;
        // SAFETY: `stmxcsr` stores the 32-bit MXCSR register to the given, valid, aligned
        // location; it has no other effect.
        unsafe {
            core::arch::asm!("stmxcsr [{}]", in(reg) &mut csr, options(nostack, preserves_flags));
        }
        csr
    }

    pub(crate) fn write(csr: Reg) {
        // SAFETY: `ldmxcsr` loads MXCSR from the given, valid, aligned location. Callers only
        // write a value read from the register with exception bits changed, or the value
        // they read back (reserved bits unchanged, so no #GP).
        unsafe {
            core::arch::asm!("ldmxcsr [{}]", in(reg) &csr, options(nostack, preserves_flags));
        }
    }

    /// The register with every exception trap masked.
    pub(crate) fn masked(csr: Reg) -> Reg {
        csr | TRAPS_MASKED
    }

    pub(crate) fn traps_unmasked(csr: Reg) -> bool {
        csr & TRAPS_MASKED != TRAPS_MASKED
    }

    /// SSE computes every `f64` operation, so a mode bit that is set applies to them.
    pub(crate) fn modes_reach_f64() -> bool {
        true
    }
}

/// FPCR (aarch64): trap enables IOE, DZE, OFE, UFE, IXE (bits 8-12) and IDE (bit 15);
/// rounding mode RMode bits 22-23, flush-to-zero FZ bit 24, default-NaN DN bit 25 (a NaN
/// result is the default NaN instead of the operand's payload), and, on cores with
/// FEAT_AFP, FIZ bit 0 (flush denormal inputs) and AH bit 1 (alternate NaN and denormal
/// handling), which read as zero elsewhere. The half-precision FZ16 (bit 19) is not a mode
/// of `f64`. Most cores do not implement the trap enables (they read as zero, as they do
/// under QEMU), which this code handles the same way. Tested under QEMU by the firmware
/// harness (docs/firmware.md): FZ, DN and each rounding mode are refused; FIZ, AH and the
/// trap enables are not implemented there.
#[cfg(target_arch = "aarch64")]
mod fpcr {
    pub(crate) type Reg = u64;
    const TRAP_ENABLES: Reg = 0x9F00;
    const MODE_BITS: Reg = 0x03C0_0003;

    pub(crate) fn modes_set(v: Reg) -> bool {
        v & MODE_BITS != 0
    }

    pub(crate) fn read() -> Reg {
        let v: u64;
        // SAFETY: reading FPCR has no side effect.
        unsafe {
            core::arch::asm!("mrs {}, fpcr", out(reg) v, options(nomem, nostack, preserves_flags))
        };
        v
    }

    pub(crate) fn write(v: Reg) {
        // SAFETY: writes a value read from FPCR with only trap-enable bits changed, or the
        // value read back.
        unsafe {
            core::arch::asm!("msr fpcr, {}", in(reg) v, options(nomem, nostack, preserves_flags))
        };
    }

    pub(crate) fn masked(v: Reg) -> Reg {
        v & !TRAP_ENABLES
    }

    pub(crate) fn traps_unmasked(v: Reg) -> bool {
        v & TRAP_ENABLES != 0
    }

    /// The FPU computes every `f64` operation (AArch64 always has double precision).
    pub(crate) fn modes_reach_f64() -> bool {
        true
    }
}

/// FPSCR (32-bit Arm with a hardware-float ABI, `eabihf`: an FPU is present): the same
/// RMode, FZ and DN bits as aarch64's FPCR (bits 22-25); trap enables at bits 8-12 and 15
/// on A/R-profile cores that implement trapping, reserved (zero) on M-profile cores.
///
/// Whether those modes reach `f64` depends on how this library was compiled, not on the
/// chip: `thumbv7em-none-eabihf` for a Cortex-M4F (single-precision FPU) computes `f64` in
/// software (compiler-builtins), which FPSCR does not affect, while `-C
/// target-cpu=cortex-m7` (double-precision FPU) computes it on the FPU. Stable Rust exposes
/// no `cfg` for double-precision VFP on this architecture, so when a mode bit is set the
/// guard asks the arithmetic itself ([`f64_follows_ieee_defaults`]): refused if `f64`
/// results change, accepted (with the same bits) if they cannot.
#[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
mod fpcr {
    pub(crate) type Reg = u32;
    const TRAP_ENABLES: Reg = 0x9F00;
    const MODE_BITS: Reg = 0x03C0_0000;

    pub(crate) fn modes_set(v: Reg) -> bool {
        v & MODE_BITS != 0
    }

    pub(crate) fn read() -> Reg {
        let v: u32;
        // SAFETY: reading FPSCR has no side effect; the eabihf ABI guarantees an FPU.
        unsafe { core::arch::asm!("vmrs {}, fpscr", out(reg) v, options(nomem, nostack)) };
        v
    }

    pub(crate) fn write(v: Reg) {
        // SAFETY: writes a value read from FPSCR with only trap-enable bits changed, or the
        // value read back.
        unsafe { core::arch::asm!("vmsr fpscr, {}", in(reg) v, options(nomem, nostack)) };
    }

    pub(crate) fn masked(v: Reg) -> Reg {
        v & !TRAP_ENABLES
    }

    pub(crate) fn traps_unmasked(v: Reg) -> bool {
        v & TRAP_ENABLES != 0
    }

    pub(crate) fn modes_reach_f64() -> bool {
        !super::f64_follows_ieee_defaults()
    }
}

/// Other targets: no register this crate knows how to read; the default environment is
/// assumed (documented in docs/DECISIONS.md). Soft-float targets (riscv32imac, thumbv6m,
/// Arm `eabi`) have no floating-point state at all.
#[cfg(not(any(
    target_arch = "x86_64",
    all(target_arch = "x86", target_feature = "sse2"),
    target_arch = "aarch64",
    all(target_arch = "arm", target_abi = "eabihf")
)))]
mod fpcr {
    pub(crate) type Reg = u32;
    pub(crate) fn modes_set(_: Reg) -> bool {
        false
    }
    pub(crate) fn read() -> Reg {
        0
    }
    pub(crate) fn write(_: Reg) {}
    pub(crate) fn masked(v: Reg) -> Reg {
        v
    }
    pub(crate) fn traps_unmasked(_: Reg) -> bool {
        false
    }
    pub(crate) fn modes_reach_f64() -> bool {
        false
    }
}

/// Whether `f64` arithmetic, as this build performs it, gives the IEEE default results in
/// the current environment: round to nearest, subnormals kept, NaN payloads propagated.
/// Each operand goes through `black_box`, so the operations run now, not at compile time.
#[cfg(any(test, all(target_arch = "arm", target_abi = "eabihf")))]
fn f64_follows_ieee_defaults() -> bool {
    use core::hint::black_box;
    let one = black_box(1.0_f64);
    let three_quarter_ulp = black_box(0.75 * f64::EPSILON);
    // 1 + ¾ulp and −1 − ¾ulp round away from 1 to nearest; each directed mode (toward +∞,
    // −∞ or zero) rounds at least one of them back to ±1.
    let up = one + three_quarter_ulp;
    let down = -one - three_quarter_ulp;
    let to_nearest = up.to_bits() == (1.0 + f64::EPSILON).to_bits()
        && down.to_bits() == (-(1.0 + f64::EPSILON)).to_bits();
    // Flush-to-zero: the smallest normal halved is a subnormal, and two of them add back to
    // the smallest normal (a flushed output gives 0, a flushed input 0 as well).
    let half_min = black_box(f64::MIN_POSITIVE) * black_box(0.5);
    let subnormals = half_min.to_bits() == 1 << 51
        && (black_box(half_min) + black_box(half_min)).to_bits() == f64::MIN_POSITIVE.to_bits();
    // Default-NaN: a quiet NaN operand's payload (1) survives an addition.
    let nan = black_box(f64::from_bits(0x7FF8_0000_0000_0001)) + one;
    let payload = nan.to_bits() & 0x0007_FFFF_FFFF_FFFF == 1;
    to_nearest && subnormals && payload
}

/// Whether the modes that change results are the IEEE defaults: round to nearest, no
/// flush-to-zero, no denormals-are-zero, no default-NaN (exception masks and sticky flags
/// are not modes) — or, where a mode bit is set, whether it cannot reach this build's `f64`
/// arithmetic (32-bit Arm with `f64` in software). Hosts compiled with `-ffast-math` start
/// with FTZ/DAZ set, which silently changes results; the library refuses to compute rather
/// than return different bits.
pub(crate) fn fp_env_is_default() -> bool {
    !fpcr::modes_set(fpcr::read()) || !fpcr::modes_reach_f64()
}

/// Masks every floating-point exception trap for its lifetime and then restores the
/// host's control register exactly (traps and sticky flags as they were on entry). Does
/// nothing — not even a register write — when no trap is unmasked, the usual case.
#[derive(Debug)]
pub(crate) struct FpTrapGuard {
    saved: Option<fpcr::Reg>,
}

impl FpTrapGuard {
    /// Masks the traps if the host unmasked any.
    pub(crate) fn mask_traps() -> FpTrapGuard {
        let r = fpcr::read();
        if fpcr::traps_unmasked(r) {
            fpcr::write(fpcr::masked(r));
            FpTrapGuard { saved: Some(r) }
        } else {
            FpTrapGuard { saved: None }
        }
    }
}

impl Drop for FpTrapGuard {
    fn drop(&mut self) {
        if let Some(r) = self.saved {
            fpcr::write(r);
        }
    }
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

/// Borrows `count` packed points `double[3*count]` mutably.
///
/// # Safety
/// `p` passed `check_ptr::<Point>(p, count)`, points to `3*count` writable doubles, and the
/// range overlaps no other slice alive for `'a`.
pub(crate) unsafe fn points_mut<'a>(p: *mut f64, count: usize) -> &'a mut [Point] {
    if count == 0 {
        return &mut [];
    }
    // SAFETY: non-NULL, aligned, byte size ≤ isize::MAX (checked by the caller), writable and
    // unaliased by the caller's contract.
    unsafe { core::slice::from_raw_parts_mut(p.cast::<Point>(), count) }
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

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    /// The probe that 32-bit Arm builds run when a mode bit is set: true in the default
    /// environment, false under each mode that changes `f64` results (here set in MXCSR,
    /// which the same arithmetic obeys).
    #[test]
    fn the_f64_probe_sees_every_mode() {
        let saved = fpcr::read();
        assert!(super::f64_follows_ieee_defaults());
        // FTZ, DAZ, round down, round up, round toward zero.
        for bits in [1 << 15, 1 << 6, 1 << 13, 2 << 13, 3 << 13] {
            fpcr::write(saved | bits);
            let seen = super::f64_follows_ieee_defaults();
            fpcr::write(saved);
            assert!(!seen, "MXCSR bits {bits:#x} not seen");
        }
    }

    use super::fpcr;
    use nlsubdiv::Status;

    /// With the overflow, invalid and divide-by-zero traps unmasked (as `feenableexcept` does),
    /// an export body that overflows completes (the trap is masked inside the call) and the
    /// host's register, traps and flags, is exactly as before afterwards. Fails with SIGFPE
    /// when the guard does not mask, and on the comparison when it does not restore.
    #[test]
    fn traps_are_masked_for_a_call_and_restored() {
        let saved = fpcr::read();
        // IM (bit 7), ZM (9), OM (10) cleared: those exceptions trap.
        let unmasked = saved & !((1 << 7) | (1 << 9) | (1 << 10));
        fpcr::write(unmasked);
        let status = crate::primitives::run(|| {
            let x = core::hint::black_box(1e308f64);
            let y = core::hint::black_box(x * 10.0); // overflow
            let z = core::hint::black_box(y - y); // invalid: inf − inf
            if y.is_infinite() && z.is_nan() {
                Ok(())
            } else {
                Err(Status::NumericalFailure)
            }
        });
        let after = fpcr::read();
        fpcr::write(saved);
        assert_eq!(status, Status::Ok);
        assert_eq!(after, unmasked, "the host's MXCSR was not restored");
    }
}
