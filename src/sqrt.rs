//! The square root of the kernel: the correctly rounded IEEE-754 `√x`, whatever the target.
//!
//! Every other function of the kernel's arithmetic comes from `libm`, the same code on every
//! target. Square root is an IEEE-754 basic operation, correctly rounded by definition, so
//! any correct implementation gives the same bits; the only question is speed. On x86 and
//! x86_64 `libm::sqrt` is an inline-assembly `sqrtsd`, which the compiler cannot re-encode:
//! in a build for a CPU with AVX (`-C target-cpu=native`, `x86-64-v3`) that legacy-SSE
//! instruction sits between VEX-encoded code, and the SSE/AVX transitions made F4 several
//! times slower than in the baseline build. There the square root comes from the SSE2
//! intrinsic through `safe_arch` (a maintained crate of safe wrappers; the kernel itself stays
//! free of `unsafe`), which the compiler encodes as `sqrtsd` or `vsqrtsd` to match the code
//! around it. Elsewhere it is `libm::sqrt` (a hardware instruction on aarch64 and on a
//! double-precision FPU, software on the Cortex-M4F and riscv32imac).

/// `√x`, correctly rounded (IEEE-754): NaN for `x < 0` and for NaN, `x` for ±0 and +∞.
#[cfg(all(
    any(target_arch = "x86", target_arch = "x86_64"),
    target_feature = "sse2"
))]
#[inline(always)]
pub(crate) fn sqrt(x: f64) -> f64 {
    use safe_arch::{get_f64_from_m128d_s, m128d, set_m128d_s, sqrt_m128d_s};
    get_f64_from_m128d_s(sqrt_m128d_s(m128d::default(), set_m128d_s(x)))
}

/// `√x`, correctly rounded (IEEE-754): NaN for `x < 0` and for NaN, `x` for ±0 and +∞.
#[cfg(not(all(
    any(target_arch = "x86", target_arch = "x86_64"),
    target_feature = "sse2"
)))]
#[inline(always)]
pub(crate) fn sqrt(x: f64) -> f64 {
    libm::sqrt(x)
}

#[cfg(test)]
mod tests {
    use super::sqrt;

    fn same(x: f64) {
        let (a, b) = (sqrt(x), libm::sqrt(x));
        assert!(
            a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
            "{x:e}: {a:e} vs {b:e}"
        );
    }

    /// The same bits as `libm::sqrt` (both correctly rounded) on the special values, exact
    /// squares, subnormals, and 100,000 positive doubles spread over every exponent.
    #[test]
    fn equals_libm_bit_for_bit() {
        let special = [
            0.0,
            -0.0,
            1.0,
            2.0,
            0.5,
            4.0,
            9.0,
            1e-310,
            f64::MIN_POSITIVE,
            f64::MIN_POSITIVE / 4.0,
            f64::MAX,
            f64::INFINITY,
            -1.0,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        special.into_iter().for_each(same);
        assert_eq!(sqrt(-0.0).to_bits(), (-0.0f64).to_bits());
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..100_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            same(f64::from_bits(state & 0x7fef_ffff_ffff_ffff));
        }
    }
}
