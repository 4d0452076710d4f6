#!/usr/bin/env bash
# Every test suite of nlsubdiv, in one command (the README's test command).
#
#   scripts/test-all.sh            # everything available on this machine
#
# Each step prints PASS/FAIL/SKIP; the last line is "N passed, M failed, K skipped".
# Needs: cargo (stable), gcc/g++, valgrind, cbindgen 0.29.4 (for the header check).
# Optional: nightly toolchain (ASan-instrumented Rust staticlib), Debian's
# libopenmesh-dev, libcgal-dev, libosd-dev (peer comparisons).
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
OUT=${NLS_TEST_OUT:-$ROOT/target/test-all}
mkdir -p "$OUT"
# Step logs of an earlier run (perhaps under an older step name) must not feed this run's
# dashboard.
rm -f "$OUT"/*.log
export CARGO_TERM_COLOR=never

passed=0; failed=0; skipped=0; failures=()
step() { # step NAME COMMAND...
    local name=$1; shift
    local log="$OUT/$(echo "$name" | tr ' /' '__').log"
    local t0=$SECONDS
    if "$@" >"$log" 2>&1; then
        passed=$((passed+1)); echo "PASS  $name ($((SECONDS-t0)) s)"
    else
        failed=$((failed+1)); failures+=("$name"); echo "FAIL  $name ($((SECONDS-t0)) s) — last lines of $log:"
        tail -n 25 "$log" | sed 's/^/      /'
    fi
    grep -hE "^[^ ]+: [0-9]+ passed, [0-9]+ failed|^test result:|^\| [a-z-]+ \| [a-z]+ \| [0-9.e+-]+ \|$" "$log" | sed 's/^/      /' | tail -n 12
}
skip() { skipped=$((skipped+1)); echo "SKIP  $1 — $2"; }

CFLAGS_STRICT="-std=c99 -Wall -Wextra -Wpedantic -Werror"
SAN="-g -O1 -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all"

# === issue 10: statuses verified at run time (begin) ========================================
# Every C suite appends the statuses its CHECK_STATUS calls verified (ffi_tests/check.h);
# scripts/dashboard.py reads them at the end of the run.
export NLS_STATUS_LOG="$OUT/c-statuses.log"
rm -f "$NLS_STATUS_LOG"
# === issue 10: statuses verified at run time (end) ==========================================

# --- Rust ---------------------------------------------------------------------------
step "cargo fmt --check" cargo fmt --all -- --check
step "cargo clippy -D warnings" cargo clippy --workspace --all-targets --locked -- -D warnings
step "cargo test (debug)" cargo test --workspace --locked
step "cargo test (release)" cargo test --workspace --locked --release
step "cargo doc (no broken links)" env RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked

# --- determinism -----------------------------------------------------------------------
determinism() {
    local h1 h2 h3 h4 h5
    h1=$(cargo run -q --locked --example det_hash) || return 1
    h2=$(cargo run -q --locked --release --example det_hash) || return 1
    h3=$(cargo run -q --locked --release --example det_hash) || return 1
    h4=$(CARGO_PROFILE_RELEASE_OPT_LEVEL=1 cargo run -q --locked --release --example det_hash --target-dir target/det-o1) || return 1
    h5=$(RUSTFLAGS="-C target-cpu=native" cargo run -q --locked --release --example det_hash --target-dir target/det-native) || return 1
    printf 'debug            %s\nrelease          %s\nrelease again    %s\nopt-level=1      %s\ntarget-cpu=native %s\n' "$h1" "$h2" "$h3" "$h4" "$h5"
    [ "$h1" = "$h2" ] && [ "$h2" = "$h3" ] && [ "$h3" = "$h4" ] && [ "$h4" = "$h5" ]
}
step "determinism: same bits in debug, release, opt-level 1, target-cpu=native" determinism
reproducible() {
    # Two clean builds of the staticlib in different directories are byte-identical.
    local a="$OUT/repro-a" b="$OUT/repro-b"
    rm -rf "$a" "$b"; mkdir -p "$a" "$b"
    git ls-files -z | tar --null -T - -cf - | tar -xf - -C "$a"
    git ls-files -z | tar --null -T - -cf - | tar -xf - -C "$b"
    local flags="--remap-path-prefix=$a=/nlsubdiv --remap-path-prefix=$b=/nlsubdiv --remap-path-prefix=${CARGO_HOME:-$HOME/.cargo}=/cargo"
    (cd "$a" && RUSTFLAGS="$flags" cargo build -q --release --locked -p nlsubdiv-ffi) || return 1
    (cd "$b" && RUSTFLAGS="$flags" cargo build -q --release --locked -p nlsubdiv-ffi) || return 1
    sha256sum "$a/target/release/libnlsubdiv.a" "$b/target/release/libnlsubdiv.a" "$a/target/release/libnlsubdiv.so" "$b/target/release/libnlsubdiv.so"
    cmp "$a/target/release/libnlsubdiv.a" "$b/target/release/libnlsubdiv.a" &&
    cmp "$a/target/release/libnlsubdiv.so" "$b/target/release/libnlsubdiv.so" || return 1
    local leaks
    leaks=$(strings "$a/target/release/libnlsubdiv.a" | grep -c -e "$a" -e "${CARGO_HOME:-$HOME/.cargo}" || true)
    echo "absolute build paths left in libnlsubdiv.a: $leaks"
    [ "$leaks" -eq 0 ] && rm -rf "$a" "$b"
}
step "reproducible build: libnlsubdiv.a/.so byte-identical from two directories" reproducible

# --- no_std proof -----------------------------------------------------------------------
nostd_probe() {
    cargo build --release --locked -p nlsubdiv-nostd-probe || return 1
    printf '#include <stdio.h>\ndouble nls_probe_f4_midpoint(void);\nint main(void){double x=nls_probe_f4_midpoint();printf("probe: F4 midpoint = %%g\\n",x);return x==1.5?0:1;}\n' > "$OUT/probe.c"
    gcc -O1 "$OUT/probe.c" target/release/libnlsubdiv_nostd_probe.a -Wl,--gc-sections -lm -o "$OUT/probe" && "$OUT/probe"
}
step "no_std probe (core links without std/alloc)" nostd_probe

# --- C ABI: header ------------------------------------------------------------------------
header_fresh() {
    local tmp="$OUT/nlsubdiv.h.generated"
    cbindgen --config ffi/cbindgen.toml --crate nlsubdiv-ffi --output "$tmp" ffi 2>/dev/null || return 1
    diff -u include/nlsubdiv.h "$tmp"
}
if command -v cbindgen >/dev/null && cbindgen --version | grep -q "0.29.4"; then
    step "header is what cbindgen 0.29.4 generates" header_fresh
else
    skip "header freshness" "cbindgen 0.29.4 not installed (cargo install cbindgen --version 0.29.4 --locked)"
fi
header_alone() {
    printf '#include "nlsubdiv.h"\nint main(void) { return (int)nls_version() < 0; }\n' > "$OUT/header_alone.c"
    cp "$OUT/header_alone.c" "$OUT/header_alone.cpp"
    gcc $CFLAGS_STRICT -Iinclude -fsyntax-only "$OUT/header_alone.c" &&
    g++ -std=c++17 -Wall -Wextra -Wpedantic -Werror -Iinclude -fsyntax-only "$OUT/header_alone.cpp"
}
step "header compiles alone as C99 and C++17" header_alone

# --- C ABI: tests ---------------------------------------------------------------------------
step "build libnlsubdiv.a / .so (release)" cargo build --release --locked -p nlsubdiv-ffi
CTESTS=(ffi_tests/test_*.c)
c_asan() {
    local rc=0 t
    for t in "${CTESTS[@]}"; do
        local exe="$OUT/asan_$(basename "$t" .c)"
        gcc $CFLAGS_STRICT $SAN -Iinclude -Iffi_tests "$t" target/release/libnlsubdiv.a -Wl,--gc-sections -lm -o "$exe" || return 1
        "$exe" || rc=1
    done
    return $rc
}
step "C tests under ASan+UBSan (gcc)" c_asan
c_shared() {
    local t exe
    for t in "${CTESTS[@]}"; do
        exe="$OUT/so_$(basename "$t" .c)"
        gcc $CFLAGS_STRICT -O1 -Iinclude -Iffi_tests "$t" -Ltarget/release -lnlsubdiv -lm -o "$exe" || return 1
        LD_LIBRARY_PATH=target/release NLS_TEST_UNDER_VALGRIND=1 "$exe" >/dev/null || return 1
    done
    echo "C tests link and pass against libnlsubdiv.so"
}
step "C tests against the shared library" c_shared
if command -v valgrind >/dev/null; then
    c_valgrind() {
        local rc=0 t
        for t in "${CTESTS[@]}"; do
            local exe="$OUT/plain_$(basename "$t" .c)"
            gcc $CFLAGS_STRICT -g -O1 -Iinclude -Iffi_tests "$t" target/release/libnlsubdiv.a -Wl,--gc-sections -lm -o "$exe" || return 1
            NLS_TEST_UNDER_VALGRIND=1 valgrind -q --error-exitcode=99 --leak-check=full "$exe" || rc=1
        done
        return $rc
    }
    step "C tests under valgrind memcheck" c_valgrind
else
    skip "valgrind" "valgrind not installed"
fi
panic_never() {
    cargo build --release --locked -p nlsubdiv-ffi --features panic-never --target-dir target/panic-never || return 1
    local t
    for t in "${CTESTS[@]}"; do
        gcc -std=c99 -O1 -Iinclude -Iffi_tests "$t" target/panic-never/release/libnlsubdiv.a -Wl,--gc-sections -lm \
            -o "$OUT/pn_$(basename "$t" .c)" || { echo "a panic path is reachable from an export"; return 1; }
    done
    echo "no panic path reachable from any export used by the C tests"
}
step "panic-freedom link proof" panic_never
if rustup toolchain list 2>/dev/null | grep -q nightly; then
    c_asan_rust() {
        RUSTFLAGS="-Zsanitizer=address" cargo +nightly build --release -p nlsubdiv-ffi \
            --target x86_64-unknown-linux-gnu --target-dir target/asan || return 1
        local lib=target/asan/x86_64-unknown-linux-gnu/release/libnlsubdiv.a rc=0 t
        for t in "${CTESTS[@]}"; do
            local exe="$OUT/rasan_$(basename "$t" .c)"
            gcc $CFLAGS_STRICT $SAN -Iinclude -Iffi_tests "$t" "$lib" -Wl,--gc-sections -lm -o "$exe" || return 1
            "$exe" || rc=1
        done
        # Proof that the Rust side really is instrumented.
        local n
        n=$(objdump -d --no-show-raw-insn "$OUT/rasan_test_primitives" | awk '/<nls_tangent_polygon>:/,/^$/' | grep -c __asan_report)
        echo "__asan_report calls inside nls_tangent_polygon: $n"
        [ "$n" -gt 0 ] || return 1
        return $rc
    }
    step "C tests against an ASan-instrumented Rust staticlib (nightly)" c_asan_rust
else
    skip "ASan-instrumented Rust staticlib" "no nightly toolchain"
fi

# === issue 10: fuzzing (begin) ================================================================
# cargo-fuzz targets over the C ABI (fuzz/), ASan, 60 s per target; needs nightly + cargo-fuzz.
if ! rustup toolchain list 2>/dev/null | grep -q nightly; then
    skip "fuzz (mesh, curve, primitives, differential)" "no nightly toolchain (ASan fuzzing needs it)"
elif ! cargo fuzz --version >/dev/null 2>&1; then
    skip "fuzz (mesh, curve, primitives, differential)" "cargo-fuzz not installed (scripts/setup.sh installs it)"
else
    step "fuzz: mesh, curve, primitives, differential under ASan (nightly), 3 × ${NLS_FUZZ_SECONDS:-60} s shared" scripts/fuzz.sh "${NLS_FUZZ_SECONDS:-60}"
fi
# === issue 10: fuzzing (end) ==================================================================

# --- peers: OpenMesh, CGAL, OpenSubdiv (Debian packages) ------------------------------------
if [ -f /usr/include/OpenMesh/Core/Mesh/PolyMeshT.hh ] && [ -d /usr/include/CGAL ] && [ -d /usr/include/opensubdiv ]; then
    peers_selftest() { python3 peers/test_compare_off.py; }
    step "peer tools: compare_off unit tests" peers_selftest
    peer_compare() {
        peers/build.sh "$OUT/peers" || return 1
        cargo build -q --release --locked --example subdivide_off || return 1
        python3 scripts/peer_compare.py "$OUT/peers/peer_subdivide" target/release/examples/subdivide_off "$OUT/peer-compare"
    }
    step "linear schemes equal OpenMesh / CGAL / OpenSubdiv (<= 1e-12)" peer_compare
else
    skip "peer comparison" "libopenmesh-dev, libcgal-dev or libosd-dev not installed (scripts/setup.sh installs them)"
fi

# --- C/C++ integrations and packaging (issue 8; scripts/test-integrations.sh) ----------------
# OpenMesh subdividers and CGAL masks/functions = the driver, OpenMesh LoopT/ModifiedButterflyT,
# bad meshes; install prefix, CMake consumer, c_examples via pkg-config.
if [ -f /usr/include/OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh ] && [ -f /usr/include/CGAL/Subdivision_method_3/subdivision_hosts_3.h ] &&
    command -v cmake >/dev/null && command -v pkg-config >/dev/null; then
    step "integrations: OpenMesh/CGAL = driver, install prefix, CMake + pkg-config consumers" scripts/test-integrations.sh "$OUT/integrations"
else
    skip "integrations (OpenMesh, CGAL, packaging)" "libopenmesh-dev, libcgal-dev, cmake or pkg-config not installed (scripts/setup.sh installs them)"
fi
# --- end of the integrations step ---------------------------------------------------------------

# --- C examples -------------------------------------------------------------------------------
c_examples() {
    local ex
    for ex in c_examples/*.c; do
        local exe="$OUT/example_$(basename "$ex" .c)"
        gcc $CFLAGS_STRICT -Iinclude "$ex" target/release/libnlsubdiv.a -Wl,--gc-sections -lm -o "$exe" || return 1
        (cd "$OUT" && "$exe") || return 1
    done
}
step "C examples build and run" c_examples

# === issue 10: dashboard (begin) ==============================================================
# Last step: the README table from this run's logs; fails when a catalogue class is not covered.
step "dashboard: README table from this run's logs" python3 scripts/dashboard.py "$OUT"
sed -n '/dashboard:begin/,/dashboard:end/p' "$OUT/dashboard:_README_table_from_this_run's_logs.log" | grep '^|' | sed 's/^/      /'
# === issue 10: dashboard (end) ================================================================

echo
if [ "$failed" -gt 0 ]; then echo "failed steps: ${failures[*]}"; fi
echo "test-all: $passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
