#!/usr/bin/env bash
# A fuzz campaign beyond the test command's smoke run: every fuzz target for at least RUNS
# executions (default 1,000,000) under AddressSanitizer, from the regenerated seeds plus the
# pinned regressions, one target after the other. Prints one line per target
#   campaign: target=T executions=N seconds=S exec_per_sec=R findings=F
# and a Markdown table of them at the end (docs/fuzzing.md keeps the table of a documented
# run). A finding fails the run; its input is left in target/fuzz-artifacts/campaign-<T>/ to be
# pinned in fuzz/regressions/<T>/ once fixed.
#
#   scripts/fuzz-campaign.sh [RUNS] [TARGET...]
#
# Needs what scripts/fuzz.sh needs (nightly, cargo-fuzz). Not part of the test command: it
# takes about half an hour of one core.
set -uo pipefail
cd "$(dirname "$0")/.."
RUNS=${1:-1000000}
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(mesh curve primitives differential parsers tags)
if ! cargo fuzz --version >/dev/null 2>&1 || ! rustup toolchain list 2>/dev/null | grep -q nightly; then
    echo "SKIP fuzz campaign — needs the nightly toolchain and cargo-fuzz (scripts/setup.sh)"
    exit 0
fi
python3 fuzz/make_corpus.py || exit 1
TD=target/fuzz
cargo +nightly fuzz build --no-trace-compares --target-dir "$TD" >"$TD-build.log" 2>&1 ||
    { echo "fuzz campaign: build failed (see $TD-build.log)"; tail -n 20 "$TD-build.log"; exit 1; }
BIN=$TD/x86_64-unknown-linux-gnu/release
echo "fuzz campaign: $(date -u +%Y-%m-%dT%H:%MZ), $(cargo fuzz --version), $(rustc +nightly --version), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $RUNS runs per target"
rc=0
rows=()
for t in "${TARGETS[@]}"; do
    art=target/fuzz-artifacts/campaign-$t
    rm -rf "$art"; mkdir -p "$art" "fuzz/corpus/$t"
    inputs=("fuzz/corpus/$t")
    [ -d "fuzz/regressions/$t" ] && inputs+=("fuzz/regressions/$t")
    log=$art/run.log
    # -runs counts the executions after the seeds are loaded; a copy of the corpus directory is
    # not needed: new inputs land in fuzz/corpus (gitignored).
    "$BIN/$t" -runs="$RUNS" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
        -artifact_prefix="$art/" "${inputs[@]}" >"$log" 2>&1
    status=$?
    execs=$(grep -oE "stat::number_of_executed_units: [0-9]+" "$log" | grep -oE "[0-9]+$" | tail -n 1)
    secs=$(grep -oE "Done [0-9]+ runs in [0-9]+ second" "$log" | grep -oE "in [0-9]+" | grep -oE "[0-9]+" | tail -n 1)
    rate=$(grep -oE "stat::average_exec_per_sec: +[0-9]+" "$log" | grep -oE "[0-9]+$" | tail -n 1)
    cov=$(grep -oE "cov: [0-9]+" "$log" | tail -n 1 | grep -oE "[0-9]+")
    findings=$(find "$art" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'timeout-*' -o -name 'oom-*' -o -name 'leak-*' \) | wc -l)
    if [ "$status" -ne 0 ] && [ "$findings" -eq 0 ]; then findings=1; fi
    echo "campaign: target=$t executions=${execs:-0} seconds=${secs:-?} exec_per_sec=${rate:-0} coverage=${cov:-?} findings=$findings"
    rows+=("| $t | ${execs:-0} | ${secs:-?} | ${rate:-0} | ${cov:-?} | $findings |")
    if [ "$findings" -gt 0 ]; then
        echo "FAIL campaign $t: finding(s) in $art/"
        grep -E "panicked|ERROR|SUMMARY|Test unit written" -A2 "$log" | head -n 20
        rc=1
    fi
done
echo
echo "| target | executions | seconds | executions/s | coverage (edges) | findings |"
echo "|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
exit $rc
