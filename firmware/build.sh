#!/usr/bin/env bash
# Builds the cross-architecture harness (firmware/harness/) for one target, with the Rust
# staticlib for that target, into target/firmware/<target>/harness[.elf].
#
#   firmware/build.sh x86_64|aarch64|m4f|m7|riscv32|m4f-stack-sizes|m4f-llvm-ir [opt-level]
#
# opt-level (default 3) is the Rust release profile's; each (target, opt-level) has its own
# cargo target directory under target/firmware/, so repeated runs rebuild nothing.
# Prints the path of the built program. Needs the target's Rust standard library (rustup
# target add) and C toolchain; scripts/test-firmware.sh checks for them first.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
target=${1:?usage: firmware/build.sh x86_64|aarch64|m4f|m7|riscv32|m4f-stack-sizes|m4f-llvm-ir [opt-level]}
opt=${2:-3}
out=$ROOT/target/firmware/$target
mkdir -p "$out"

# Harness C flags shared by every target: no contraction of a*b+c into an FMA (GCC contracts
# by default, and the inputs and checks must be the same IEEE operations everywhere).
CFLAGS_COMMON="-std=c99 -O2 -ffp-contract=off -Wall -Wextra -Wpedantic -Werror -I$ROOT/include -I$ROOT/firmware/harness"
SOURCES=("$ROOT"/firmware/harness/*.c)

# staticlib TRIPLE CARGO_DIR [RUSTFLAGS [TOOLCHAIN]]: builds libnlsubdiv.a for TRIPLE (with the
# rustup TOOLCHAIN when given), prints its path.
staticlib() {
    local triple=$1 dir=$2 flags=${3:-} toolchain=${4:-}
    RUSTFLAGS="$flags" CARGO_PROFILE_RELEASE_OPT_LEVEL="$opt" \
        cargo ${toolchain:+"+$toolchain"} rustc -q --release --locked -p nlsubdiv-ffi --target "$triple" \
        --target-dir "$dir" --crate-type staticlib >&2
    echo "$dir/$triple/release/libnlsubdiv.a"
}

# The Cortex-M link: startup code and linker script of c_examples/bare-metal (the example a
# firmware engineer copies), newlib with semihosting (rdimon), a 256 KiB stack for the
# painted stack measurement.
BARE=$ROOT/c_examples/bare-metal
cortex_m() {
    local cpu_flags=$1 lib=$2
    arm-none-eabi-gcc $cpu_flags $CFLAGS_COMMON -DFW_BARE_METAL -ffunction-sections -fdata-sections \
        "${SOURCES[@]}" "$BARE/startup.c" -nostartfiles -T "$BARE/link.ld" \
        -Wl,--defsym=STACK_SIZE=0x40000 --specs=rdimon.specs -Wl,--gc-sections \
        "$lib" -lm -o "$out/harness.elf"
    echo "$out/harness.elf"
}

# The bare-metal targets are single-core parts that run every pass on the calling thread: their
# library is built with NLSUBDIV_MAX_CHUNKS=1 (docs/firmware.md, "Stack"), so the paths that
# split a pass into chunks are not in it and the static stack bound is that of the code a
# firmware build runs. The output bits do not depend on it; the Linux targets keep the
# default. An NLSUBDIV_MAX_CHUNKS in the environment wins (to measure another setting).
case "$target" in
    m4f|m4f-stack-sizes|m4f-llvm-ir|m7|riscv32) export NLSUBDIV_MAX_CHUNKS=${NLSUBDIV_MAX_CHUNKS:-1} ;;
esac

case "$target" in
    x86_64)
        lib=$(staticlib x86_64-unknown-linux-gnu "$ROOT/target/firmware/cargo-o$opt")
        gcc $CFLAGS_COMMON "${SOURCES[@]}" "$lib" -lm -o "$out/harness"
        echo "$out/harness" ;;
    aarch64)
        lib=$(staticlib aarch64-unknown-linux-gnu "$ROOT/target/firmware/cargo-o$opt")
        aarch64-linux-gnu-gcc -static $CFLAGS_COMMON "${SOURCES[@]}" "$lib" -lm -o "$out/harness"
        echo "$out/harness" ;;
    m4f)
        # Cortex-M4F: single-precision FPU, so f64 is computed in software (compiler-builtins in
        # the Rust library, libgcc in C). The target's default CPU is what a firmware build gets.
        lib=$(staticlib thumbv7em-none-eabihf "$ROOT/target/firmware/cargo-o$opt")
        # The library the harness links, kept beside it: the bare-metal example later builds
        # into the same cargo directory, and the static bound compares its LLVM IR's library
        # with the one this ELF was linked from (scripts/test-firmware.sh).
        cp "$lib" "$out/libnlsubdiv.a"
        cortex_m "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard" "$lib" ;;
    m4f-stack-sizes)
        # The M4F build for the static stack bound (firmware/stack_bound.py): the same sources
        # and flags as m4f, but the Rust library is compiled by nightly with -Z emit-stack-sizes,
        # so that every Rust function's frame size is in the ELF's .stack_sizes section. Its own
        # target directory: the m4f build that runs and is measured stays the stable one.
        lib=$(staticlib thumbv7em-none-eabihf "$ROOT/target/firmware/cargo-nightly-stack-sizes-o$opt" \
            "-Z emit-stack-sizes" nightly)
        cortex_m "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard" "$lib" ;;
    m4f-llvm-ir)
        # The LLVM IR of the m4f build's Rust library, after LTO (its functions are the ELF's,
        # inlining done), for the static stack bound's resolution of indirect calls by type
        # (firmware/stack_bound.py --llvm-ir). The same stable compiler, flags and profile as
        # m4f: --emit only adds an output (of the final crate, which LTO has merged with the
        # core's). Its own target directory; prints the path of the .ll file.
        dir=$ROOT/target/firmware/cargo-llvm-ir-o$opt
        CARGO_PROFILE_RELEASE_OPT_LEVEL="$opt" cargo rustc -q --release --locked -p nlsubdiv-ffi \
            --target thumbv7em-none-eabihf --target-dir "$dir" --crate-type staticlib \
            -- --emit=llvm-ir,link >&2
        ls -t "$dir"/thumbv7em-none-eabihf/release/deps/nlsubdiv-*.ll | head -n 1 ;;
    m7)
        # Cortex-M7 with the double-precision FPU (FPv5-D16): -C target-cpu=cortex-m7 lets LLVM
        # use it for f64; its own target directory, since RUSTFLAGS differ from m4f's.
        lib=$(staticlib thumbv7em-none-eabihf "$ROOT/target/firmware/cargo-m7-o$opt" "-C target-cpu=cortex-m7")
        cortex_m "-mcpu=cortex-m7 -mthumb -mfpu=fpv5-d16 -mfloat-abi=hard" "$lib" ;;
    riscv32)
        # RV32IMAC: no FPU, f64 in software. picolibc with semihosting (its own start-up code
        # and linker script), on QEMU's virt board: RAM from 0x80000000.
        lib=$(staticlib riscv32imac-unknown-none-elf "$ROOT/target/firmware/cargo-o$opt")
        riscv64-unknown-elf-gcc -march=rv32imac -mabi=ilp32 $CFLAGS_COMMON -DFW_BARE_METAL \
            -ffunction-sections -fdata-sections "${SOURCES[@]}" \
            --specs=picolibc.specs --oslib=semihost --crt0=semihost \
            -Wl,--defsym=__flash=0x80000000 -Wl,--defsym=__flash_size=0x00400000 \
            -Wl,--defsym=__ram=0x80400000 -Wl,--defsym=__ram_size=0x00400000 \
            -Wl,--defsym=__stack_size=0x40000 -Wl,--gc-sections "$lib" -lm -o "$out/harness.elf"
        echo "$out/harness.elf" ;;
    *)
        echo "unknown target $target" >&2; exit 2 ;;
esac
