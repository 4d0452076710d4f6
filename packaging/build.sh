#!/usr/bin/env bash
# Builds what scripts/install.sh and debian/rules install, into one cargo target directory:
#
#   packaging/build.sh [TARGET_DIR]        (default target/install-build)
#
#   TARGET_DIR/release/libnlsubdiv.a       the static library
#   TARGET_DIR/release/libnlsubdiv.so      the shared library, SONAME from packaging/version.sh
#   TARGET_DIR/release/nlsubdiv            the command
#   TARGET_DIR/release/nlsubdiv.1          its manual page (packaging/manpage.py)
#
# The soname is a link argument of this build only (cargo has no soname setting), so the
# target/release/libnlsubdiv.so that the test suites load by LD_LIBRARY_PATH keeps none;
# the static library is the same as cargo's.
# Crates: with a vendor/ folder at the root (`cargo vendor --locked vendor`) the build is
# offline from it; otherwise cargo takes the versions Cargo.lock pins from its registry.
set -euo pipefail
cd "$(dirname "$0")/.."
target=${1:-target/install-build}
soname=$(packaging/version.sh soname)
cargo_args=(--release --locked --target-dir "$target")
# The same bits from any build folder: the paths that end up in the command (panic locations
# of the crates) name the source tree and cargo's home relative to themselves.
export RUSTFLAGS="${RUSTFLAGS:-} --remap-path-prefix=$PWD=nlsubdiv --remap-path-prefix=${CARGO_HOME:-$HOME/.cargo}=cargo"
if [ -d vendor ]; then
    cargo_args+=(--offline --config 'source.crates-io.replace-with="vendored-sources"'
        --config "source.vendored-sources.directory=\"$PWD/vendor\"")
fi
# -lc: the no_std library calls memcpy and memset, which only the C library defines; without
# it the .so has no NEEDED entry for libc and relies on the program to have loaded one.
cargo rustc -q "${cargo_args[@]}" -p nlsubdiv-ffi -- -C link-arg=-Wl,-soname,"$soname" -C link-arg=-lc
cargo build -q "${cargo_args[@]}" -p nlsubdiv-cli
python3 packaging/manpage.py "$target/release/nlsubdiv" "$target/release/nlsubdiv.1"
