#!/usr/bin/env bash
# Installs what the test suites need on a fresh Debian machine (run as root, or with sudo
# available): compilers and tools from Debian, and the pinned cbindgen from crates.io.
set -euo pipefail
pkgs=(gcc g++ make cmake pkg-config valgrind libopenmesh-dev libcgal-dev libosd-dev libeigen3-dev python3
    # the Debian packages (scripts/test-packages.sh), the manual page, the C API reference
    dpkg-dev debhelper lintian man-db doxygen)
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
