# Sourced, not run: the bookkeeping that scripts/test-all.sh and scripts/test-quick.sh share,
# so that both count, log, skip and close the same way, and the steps both run.
#
#   . scripts/lib-test.sh
#   run_begin NAME             # NAME: the closing line's word; logs go to $OUT
#   step "what it checks" COMMAND [ARG...]
#   skip "what" "why it cannot run here"
#   run_end                    # the skip list and the closing line; returns the run's status
#
# A step's output goes to $OUT/<step name>.log; the terminal gets one PASS/FAIL/SKIP line per
# step, the summary lines of its log, and the last 25 lines of the log of a failing step.
#
# Tests that need the shared test meshes and cannot find them (tests/common/shared_data.rs,
# skip_test below) append "SKIP <test>: <what is missing>" to $NLS_SKIP_LOG, which run_begin
# points into $OUT. run_end lists them and counts each test once (the debug and the release
# run of one test are one test):
#
#   <NAME>: K skipped = S steps + T tests for missing shared data
#   <NAME>: N passed, M failed, K skipped        <- the closing line: N, M count steps
#
# The closing line stays exactly "NAME: N passed, M failed, K skipped" (nothing after it),
# the form that CI and other tools read; the breakdown of K is the line above it.
#
# Environment: NLS_TEST_OUT (the run's folder, default target/NAME), NLS_SHARED_DATA (the
# shared meshes folder), NLS_REQUIRE_SHARED_DATA=1 (missing shared data fails instead of
# skipping).

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
CFLAGS_STRICT="-std=c99 -Wall -Wextra -Wpedantic -Werror"
SAN="-g -O1 -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all"
CTESTS=("$ROOT"/ffi_tests/test_*.c)

# The shared meshes folder, by the rule of tests/common/shared_data.rs: $NLS_SHARED_DATA, else
# shared/data/meshes in the folder that holds the repository.
shared_meshes_dir() {
    echo "${NLS_SHARED_DATA:-$(dirname "$ROOT")/shared/data/meshes}"
}

# skip_test TEST WHAT: TEST (a name like `integrations::test_cgal`) did not check something for
# want of shared data. Prints and logs the SKIP line as the Rust tests do; under
# NLS_REQUIRE_SHARED_DATA=1 prints it as a failure and returns 1.
skip_test() {
    local line="SKIP $1: $2"
    if [ "${NLS_REQUIRE_SHARED_DATA:-}" = 1 ]; then
        echo "$line (NLS_REQUIRE_SHARED_DATA=1: missing shared data is a failure)" >&2
        return 1
    fi
    echo "$line" >&2
    if [ -n "${NLS_SKIP_LOG:-}" ]; then echo "$line" >> "$NLS_SKIP_LOG"; fi
}

run_begin() { # run_begin NAME
    RUN_NAME=$1
    OUT=${NLS_TEST_OUT:-$ROOT/target/$RUN_NAME}
    mkdir -p "$OUT"
    OUT=$(cd "$OUT" && pwd)
    # Step logs of an earlier run (perhaps under an older step name) must not feed this run's
    # summary or dashboard.
    rm -f "$OUT"/*.log
    export NLS_SKIP_LOG=$OUT/skipped-tests.txt
    : > "$NLS_SKIP_LOG"
    export CARGO_TERM_COLOR=never
    passed=0; failed=0; failures=(); skipped_steps=()
}

step() { # step NAME COMMAND...
    local name=$1; shift
    local log
    log="$OUT/$(echo "$name" | tr ' /' '__').log"
    local t0=$SECONDS
    if "$@" >"$log" 2>&1; then
        passed=$((passed+1)); echo "PASS  $name ($((SECONDS-t0)) s)"
    else
        failed=$((failed+1)); failures+=("$name"); echo "FAIL  $name ($((SECONDS-t0)) s) — last lines of $log:"
        tail -n 25 "$log" | sed 's/^/      /'
    fi
    grep -hE "^[^ ]+: [0-9]+ passed, [0-9]+ failed|^test result:|^\| [a-z-]+ \| [a-z]+ \| [0-9.e+-]+ \|$" "$log" | sed 's/^/      /' | tail -n 12
}

skip() { # skip NAME WHY
    skipped_steps+=("$1 — $2"); echo "SKIP  $1 — $2"
}

# needs_shared_meshes NAME: whether the shared meshes are there for step NAME. When not, NAME
# is recorded as skipped (as failed under NLS_REQUIRE_SHARED_DATA=1) and the answer is no.
needs_shared_meshes() {
    local dir
    dir=$(shared_meshes_dir)
    [ -d "$dir" ] && return 0
    if [ "${NLS_REQUIRE_SHARED_DATA:-}" = 1 ]; then
        step "$1" sh -c 'echo "shared meshes folder $0 not found and NLS_REQUIRE_SHARED_DATA=1"; exit 1' "$dir"
    else
        skip "$1" "shared meshes folder $dir not found (set NLS_SHARED_DATA to it)"
    fi
    return 1
}

run_end() {
    local tests=() line
    # One line per test, however many runs (debug, release) reported it.
    while IFS= read -r line; do tests+=("$line"); done < <(sort -u "$NLS_SKIP_LOG")
    local s=${#skipped_steps[@]} t=${#tests[@]}
    echo
    if [ "$s" -gt 0 ]; then
        echo "skipped steps ($s):"
        printf '  %s\n' "${skipped_steps[@]}"
    fi
    if [ "$t" -gt 0 ]; then
        echo "tests skipped for missing shared data ($t; $NLS_SKIP_LOG):"
        printf '  %s\n' "${tests[@]}"
    fi
    if [ "$failed" -gt 0 ]; then
        echo "failed steps ($failed):"
        printf '  %s\n' "${failures[@]}"
    fi
    echo "$RUN_NAME: $((s+t)) skipped = $s steps + $t tests for missing shared data"
    echo "$RUN_NAME: $passed passed, $failed failed, $((s+t)) skipped"
    [ "$failed" -eq 0 ]
}

# ---- steps both commands run ----------------------------------------------------------------

header_fresh() { # include/nlsubdiv.h is what cbindgen 0.29.4 generates from ffi/
    local tmp="$OUT/nlsubdiv.h.generated"
    cbindgen --config ffi/cbindgen.toml --crate nlsubdiv-ffi --output "$tmp" ffi 2>/dev/null || return 1
    diff -u include/nlsubdiv.h "$tmp"
}

header_fresh_step() {
    if command -v cbindgen >/dev/null && cbindgen --version | grep -q "0.29.4"; then
        step "header is what cbindgen 0.29.4 generates" header_fresh
    else
        skip "header freshness" "cbindgen 0.29.4 not installed (cargo install cbindgen --version 0.29.4 --locked)"
    fi
}

c_asan() { # every C suite against target/release/libnlsubdiv.a, gcc ASan+UBSan
    local rc=0 t
    for t in "${CTESTS[@]}"; do
        local exe
        exe="$OUT/asan_$(basename "$t" .c)"
        gcc $CFLAGS_STRICT $SAN -Iinclude -Iffi_tests "$t" target/release/libnlsubdiv.a -Wl,--gc-sections -lm -o "$exe" || return 1
        "$exe" || rc=1
    done
    return $rc
}
