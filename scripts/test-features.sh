#!/usr/bin/env bash
# The Cargo features of nlsubdiv and nlsubdiv-ffi (one per scheme family, `mobius`,
# `differential`, `curves`; docs/firmware.md, "Link only what you use"): every combination
# the documentation names builds without a warning (clippy -D warnings, library and tests),
# and in each one the scheme and form tests pass: what is built computes, what is left out
# is SchemeNotBuilt through the Rust API (tests/scheme_features.rs) and the C ABI (the ffi
# unit test schemes_left_out_of_the_build_give_scheme_not_built), and from C against a
# library built with only `loop` (ffi_tests/features/loop_only.c).
#
# Debug builds (a few seconds each after the first); the last line is
# "test-features: N passed, M failed".
#
#   scripts/test-features.sh
set -uo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"
passed=0; failed=0

# The combinations: the default, and builds that leave schemes out.
combos=(
    ""
    "--no-default-features --features loop,mobius"
    "--no-default-features --features catmull-clark"
    "--no-default-features --features loop"
    "--no-default-features"
)

check() { # check WHAT COMMAND...
    local what=$1; shift
    if "$@"; then
        passed=$((passed+1)); echo "ok    $what"
    else
        failed=$((failed+1)); echo "FAIL  $what"
    fi
}

for c in "${combos[@]}"; do
    # shellcheck disable=SC2086  # the flags are words
    {
        name=${c:-default features}
        check "clippy nlsubdiv ($name)" cargo clippy -q --locked -p nlsubdiv --lib --tests $c -- -D warnings
        check "clippy nlsubdiv-ffi ($name)" cargo clippy -q --locked -p nlsubdiv-ffi --lib --tests $c -- -D warnings
        check "tests/scheme_features.rs ($name)" cargo test -q --locked -p nlsubdiv --test scheme_features $c
        check "C ABI: schemes left out ($name)" cargo test -q --locked -p nlsubdiv-ffi --lib $c \
            schemes_left_out_of_the_build_give_scheme_not_built
    }
done
# The C ABI of a library built with only `loop`, from C (ffi_tests/features/loop_only.c; its
# verified statuses go to $NLS_STATUS_LOG like those of every C suite), under ASan+UBSan.
# With `panic-never` the link also proves that no panic path is reachable in this build (as
# the test-all step "panic-freedom link proof" does for the default one). Its own target
# folder, so that the release library of the other steps stays the default one.
loop_only_c() {
    local dir=target/features-loop
    cargo build -q --locked --release -p nlsubdiv-ffi --no-default-features \
        --features loop,panic-never --target-dir "$dir" || return 1
    gcc -std=c99 -Wall -Wextra -Wpedantic -Werror -g -O1 -fsanitize=address,undefined \
        -fno-sanitize-recover=all -Iinclude -Iffi_tests ffi_tests/features/loop_only.c \
        "$dir/release/libnlsubdiv.a" -Wl,--gc-sections -lm -o "$dir/loop_only" || {
        echo "loop_only.c does not link (with panic-never: a panic path is reachable)"
        return 1
    }
    "$dir/loop_only"
}
check "C program against a loop-only libnlsubdiv.a" loop_only_c

# Build-time capacities (docs/firmware.md, "Capacities"): at NLSUBDIV_MAX_VALENCE = 12 and
# NLSUBDIV_MAX_FACE_SIZE = 12 the tests written against the caps pass (stars and faces at the
# caps are accepted by every scheme, linear and Möbius, one more is ValenceTooHigh naming the
# element; the tests that read the shared meshes, whose valences reach 12 and more, are left
# out), and a cap outside 8..4096 stops the build. Their own target folder.
caps_small() {
    NLSUBDIV_MAX_VALENCE=12 NLSUBDIV_MAX_FACE_SIZE=12 cargo test -q --locked -p nlsubdiv \
        --target-dir target/caps --test mesh_validation --test primitives_props &&
    NLSUBDIV_MAX_VALENCE=12 NLSUBDIV_MAX_FACE_SIZE=12 cargo test -q --locked -p nlsubdiv \
        --target-dir target/caps --test mesh_topology -- --skip shared_meshes &&
    NLSUBDIV_MAX_VALENCE=12 NLSUBDIV_MAX_FACE_SIZE=12 cargo test -q --locked -p nlsubdiv \
        --target-dir target/caps --test mesh_schemes schemes_at_the_valence_capacity &&
    NLSUBDIV_MAX_VALENCE=12 NLSUBDIV_MAX_FACE_SIZE=12 cargo test -q --locked -p nlsubdiv \
        --target-dir target/caps --lib caps
}
check "capacities 12 / 12: the tests at the caps" caps_small
caps_refused() {
    local v out
    for v in 7 4097 12x ""; do
        out=$(NLSUBDIV_MAX_VALENCE="$v" cargo check -q --locked -p nlsubdiv --target-dir target/caps 2>&1) && {
            echo "NLSUBDIV_MAX_VALENCE='$v' built"; return 1; }
        grep -q "NLSUBDIV_MAX_VALENCE must be a decimal number from 8 to 4096" <<<"$out" || {
            echo "NLSUBDIV_MAX_VALENCE='$v': no message"; return 1; }
    done
}
check "capacities outside 8..4096 stop the build with a message" caps_refused

# One chunk per pass (NLSUBDIV_MAX_CHUNKS=1, the firmware configuration: docs/firmware.md,
# "Stack"): the Möbius and threading tests pass (every executor then runs each pass in one
# chunk, and the plan's scratch holds one chunk's workspaces), and a value outside 1..64
# stops the build. Their own target folder.
chunks_one() {
    NLSUBDIV_MAX_CHUNKS=1 cargo test -q --locked --release -p nlsubdiv --target-dir target/chunks1 \
        --test mesh_mobius --test parallel --test mesh_schemes
}
check "NLSUBDIV_MAX_CHUNKS=1: the Möbius, parallel and scheme tests" chunks_one
chunks_refused() {
    local v out
    for v in 0 65 8x ""; do
        out=$(NLSUBDIV_MAX_CHUNKS="$v" cargo check -q --locked -p nlsubdiv --target-dir target/caps 2>&1) && {
            echo "NLSUBDIV_MAX_CHUNKS='$v' built"; return 1; }
        grep -q "NLSUBDIV_MAX_CHUNKS must be a decimal number from 1 to 64" <<<"$out" || {
            echo "NLSUBDIV_MAX_CHUNKS='$v': no message"; return 1; }
    done
}
check "NLSUBDIV_MAX_CHUNKS outside 1..64 stops the build with a message" chunks_refused

echo "test-features: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
