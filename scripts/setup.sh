#!/usr/bin/env bash
# Installs what the test suites need on a fresh Debian machine (run as root, or with sudo
# available): compilers and tools from Debian, and the pinned cbindgen from crates.io.
set -euo pipefail
pkgs=(gcc g++ make cmake pkg-config valgrind libopenmesh-dev libcgal-dev libosd-dev libeigen3-dev python3
    # the Debian packages (scripts/test-packages.sh), the manual page, the C API reference
    dpkg-dev debhelper lintian man-db doxygen
    # scripts/test-firmware.sh: cross compilers, C libraries and emulators for aarch64 Linux,
    # Cortex-M4F/M7 (newlib with semihosting) and riscv32imac (picolibc)
    gcc-aarch64-linux-gnu libc6-dev-arm64-cross qemu-user gcc-arm-none-eabi libnewlib-arm-none-eabi
    qemu-system-arm gcc-riscv64-unknown-elf picolibc-riscv64-unknown-elf qemu-system-misc)
missing=()
for p in "${pkgs[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
    echo "setup: installing ${missing[*]}"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# The Rust standard libraries of the firmware targets (scripts/test-firmware.sh).
if command -v rustup >/dev/null; then
    fw_targets=(thumbv7em-none-eabihf aarch64-unknown-linux-gnu riscv32imac-unknown-none-elf)
    installed=$(rustup target list --installed)
    for t in "${fw_targets[@]}"; do
        if ! grep -qx "$t" <<<"$installed"; then
            echo "setup: rustup target add $t"
            rustup target add "$t"
        fi
    done
    # The static stack bound (firmware/stack_bound.py) builds the M4F library with nightly's
    # -Z emit-stack-sizes: a minimal nightly and its thumbv7em library, nothing else.
    if ! rustup run nightly rustc --version >/dev/null 2>&1; then
        echo "setup: rustup toolchain install nightly --profile minimal"
        rustup toolchain install nightly --profile minimal ||
            echo "setup: no nightly toolchain; the static stack bound will be SKIPPED"
    fi
    if rustup run nightly rustc --version >/dev/null 2>&1 &&
        ! rustup target list --installed --toolchain nightly | grep -qx thumbv7em-none-eabihf; then
        echo "setup: rustup target add thumbv7em-none-eabihf --toolchain nightly"
        rustup target add thumbv7em-none-eabihf --toolchain nightly ||
            echo "setup: no nightly thumbv7em library; the static stack bound will be SKIPPED"
    fi
fi
if ! (command -v cbindgen >/dev/null && cbindgen --version | grep -q "0.29.4"); then
    echo "setup: installing cbindgen 0.29.4"
    cargo install cbindgen --version 0.29.4 --locked --quiet
fi
# cargo-fuzz for scripts/fuzz.sh (the fuzz targets run on nightly; 0.13.2 builds with the
# stable toolchain here: about 51 s on this machine).
if ! (cargo fuzz --version 2>/dev/null | grep -q "0.13.2"); then
    echo "setup: installing cargo-fuzz 0.13.2"
    cargo install cargo-fuzz --version 0.13.2 --locked --quiet
fi
echo "setup: ok ($(rustc --version); $(cbindgen --version); gcc $(gcc -dumpfullversion); $(cargo fuzz --version))"
