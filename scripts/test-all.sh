#!/usr/bin/env bash
# Every test suite of nlsubdiv, in one command (the README's test command; about 20 minutes
# on 2 cores). scripts/test-quick.sh is the few-minute subset.
#
#   scripts/test-all.sh            # everything available on this machine
#
# Each step prints PASS/FAIL/SKIP; the logs are in target/test-all/ (NLS_TEST_OUT elsewhere).
# Tests that cannot find the shared test meshes are listed and counted as skipped; the last
# line is "test-all: N passed, M failed, K skipped" (scripts/lib-test.sh says how they count;
# NLS_SHARED_DATA names the meshes folder, NLS_REQUIRE_SHARED_DATA=1 fails without it).
# The last step writes the robustness table of the run to target/test-all/robustness.md.
# Needs: cargo (stable), gcc/g++, valgrind, cbindgen 0.29.4 (for the header check).
# Optional: nightly toolchain (ASan-instrumented Rust staticlib), Debian's
# libopenmesh-dev, libcgal-dev, libosd-dev (peer comparisons).
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/lib-test.sh
run_begin test-all

# Every C suite appends the statuses its CHECK_STATUS calls verified (ffi_tests/check.h);
# scripts/dashboard.py reads them at the end of the run.
export NLS_STATUS_LOG="$OUT/c-statuses.log"
rm -f "$NLS_STATUS_LOG"

# --- Rust ---------------------------------------------------------------------------
step "cargo fmt --check" cargo fmt --all -- --check
step "cargo clippy -D warnings" cargo clippy --workspace --all-targets --locked -- -D warnings
step "cargo test (debug)" cargo test --workspace --locked --no-fail-fast
step "cargo test (release)" cargo test --workspace --locked --release --no-fail-fast
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
header_fresh_step
header_alone() {
    printf '#include "nlsubdiv.h"\nint main(void) { return (int)nls_version() < 0; }\n' > "$OUT/header_alone.c"
    cp "$OUT/header_alone.c" "$OUT/header_alone.cpp"
    gcc $CFLAGS_STRICT -Iinclude -fsyntax-only "$OUT/header_alone.c" &&
    g++ -std=c++17 -Wall -Wextra -Wpedantic -Werror -Iinclude -fsyntax-only "$OUT/header_alone.cpp"
}
step "header compiles alone as C99 and C++17" header_alone

# --- C ABI: tests ---------------------------------------------------------------------------
step "build libnlsubdiv.a / .so (release)" cargo build --release --locked -p nlsubdiv-ffi
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

# --- fuzzing ---------------------------------------------------------------------------------
# cargo-fuzz targets over the C ABI (fuzz/), ASan, 60 s per target; needs nightly + cargo-fuzz.
if ! rustup toolchain list 2>/dev/null | grep -q nightly; then
    skip "fuzz (mesh, curve, primitives, differential, parsers)" "no nightly toolchain (ASan fuzzing needs it)"
elif ! cargo fuzz --version >/dev/null 2>&1; then
    skip "fuzz (mesh, curve, primitives, differential, parsers)" "cargo-fuzz not installed (scripts/setup.sh installs it)"
else
    step "fuzz: mesh, curve, primitives, differential, parsers, tags under ASan (nightly), 3 × ${NLS_FUZZ_SECONDS:-60} s shared" scripts/fuzz.sh "${NLS_FUZZ_SECONDS:-60}"
fi

# --- the papers' figures that are cheap enough for every run ----------------------------------
# Seed 001 Fig. 9: Gaussian curvature near a convex valence-12 vertex (spatial Butterfly ripples,
# differential Butterfly stays positive); the example exits 1 when that is not reproduced.
step "paper figure: seed 001 Fig. 9 (Gaussian curvature at a valence-12 vertex, 4 levels)" cargo run -q --release --locked --example differential_fig9 -- 4
# Seed 001 Fig. 4: when i^1.5 h_i decreases (h_i the Hausdorff distance between levels): the
# contraction rates predicted by the highest valence and the decrease they imply, on an
# icosahedron and a valence-16 bipyramid (generated, 5 levels); the example exits 1 when a
# statement of docs/differential.md "Convergence of the levels" fails.
step "paper figure: seed 001 Fig. 4 (when i^1.5 h_i decreases, 2 meshes x 5 levels)" cargo run -q --release --locked --example differential_fig4_check

# --- peers: OpenMesh, CGAL, OpenSubdiv (Debian packages) ------------------------------------
if [ -f /usr/include/OpenMesh/Core/Mesh/PolyMeshT.hh ] && [ -d /usr/include/CGAL ] && [ -d /usr/include/opensubdiv ]; then
    peers_selftest() { python3 peers/test_compare_off.py; }
    step "peer tools: compare_off unit tests" peers_selftest
    peer_compare() {
        peers/build.sh "$OUT/peers" || return 1
        cargo build -q --release --locked --example subdivide_off || return 1
        NLS_SHARED_DATA=$(shared_meshes_dir) python3 scripts/peer_compare.py "$OUT/peers/peer_subdivide" target/release/examples/subdivide_off "$OUT/peer-compare"
    }
    # The comparison runs on the shared meshes only.
    if needs_shared_meshes "linear schemes equal OpenMesh / CGAL / OpenSubdiv (<= 1e-12)"; then
        step "linear schemes equal OpenMesh / CGAL / OpenSubdiv (<= 1e-12)" peer_compare
    fi
else
    skip "peer comparison" "libopenmesh-dev, libcgal-dev or libosd-dev not installed (scripts/setup.sh installs them)"
fi

# --- C/C++ integrations and packaging (scripts/test-integrations.sh) ----------------------------
# OpenMesh subdividers and CGAL masks/functions = the driver, OpenMesh LoopT/ModifiedButterflyT,
# bad meshes; install prefix, CMake consumer, c_examples via pkg-config.
if [ -f /usr/include/OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh ] && [ -f /usr/include/CGAL/Subdivision_method_3/subdivision_hosts_3.h ] &&
    command -v cmake >/dev/null && command -v pkg-config >/dev/null; then
    step "integrations: OpenMesh/CGAL = driver, install prefix, CMake + pkg-config consumers" scripts/test-integrations.sh "$OUT/integrations"
else
    skip "integrations (OpenMesh, CGAL, packaging)" "libopenmesh-dev, libcgal-dev, cmake or pkg-config not installed (scripts/setup.sh installs them)"
fi

# --- Debian packages (scripts/test-packages.sh): build, lintian, install, consumers, purge ---
if [ "$(id -u)" -eq 0 ] && command -v dpkg-buildpackage >/dev/null && command -v dh >/dev/null && command -v lintian >/dev/null; then
    step "packages: dpkg-buildpackage, lintian, apt install, C/CMake/OpenMesh/CGAL consumers, man, purge" scripts/test-packages.sh "$OUT/packages"
else
    skip "packages (Debian)" "not root, or debhelper/lintian not installed (scripts/setup.sh installs them)"
fi

# --- Cross-architecture bit identity (scripts/test-firmware.sh, docs/firmware.md) ----------------
# The firmware harness over the C ABI on x86_64 (the reference), aarch64 Linux, Cortex-M4F,
# Cortex-M7 and riscv32imac under QEMU, case hashes compared; the M4F stack table; the
# bare-metal example. A target whose tools are missing is reported SKIP by the script.
step "firmware: same bits on x86_64, aarch64, Cortex-M4F, Cortex-M7, riscv32imac; M4F stack table" scripts/test-firmware.sh

# --- Cargo features (scripts/test-features.sh, docs/firmware.md "Link only what you use") -------
# The default build and builds that leave schemes out: clippy -D warnings, and in each the
# schemes left out are SchemeNotBuilt through the Rust API and the C ABI.
step "scheme features: default, loop+mobius, catmull-clark, loop, none build; left out is SCHEME_NOT_BUILT" scripts/test-features.sh

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

# --- robustness dashboard ----------------------------------------------------------------------
# Last step: the table of what this run verified, from its logs, into $OUT/robustness.md (never
# into a tracked file); fails when a class of docs/bad-input-catalogue.md is not covered.
step "dashboard: robustness table from this run's logs" python3 scripts/dashboard.py "$OUT"
if [ -f "$OUT/robustness.md" ]; then
    echo "      $OUT/robustness.md:"
    grep '^|' "$OUT/robustness.md" | sed 's/^/      /'
fi

run_end
