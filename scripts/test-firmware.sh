#!/usr/bin/env bash
# Cross-architecture bit-identity of nlsubdiv (docs/firmware.md). The harness of firmware/
# (368 cases over the public C ABI: primitives, every curve scheme, every mesh scheme linear
# and Möbius, tags linear and Möbius, the Möbius options, spherelike, differential, star rules;
# plus the FP-environment tests) is built
# for x86_64 (the reference) and run there, then built and run for:
#
#   aarch64  Linux, under qemu-aarch64
#   m4f      Cortex-M4F (f64 in software), bare metal under qemu-system-arm -M mps2-an386
#   m7       Cortex-M7 (double-precision FPU), bare metal under qemu-system-arm -M mps2-an500
#   riscv32  RV32IMAC (no FPU), bare metal under qemu-system-riscv32 -M virt
#   example  c_examples/bare-metal built with its Makefile and run on the Cortex-M4F
#
# Each run must end with "harness: N cases, P passed, 0 failed", and its case lines (one
# output hash per case) must equal the x86_64 ones. The M4F run also measures each case's
# stack high-water mark; the table per entry point goes to target/firmware/stack-m4f.md, and
# every entry point listed in firmware/stack-bounds.txt must be in the run and within its
# bound (the "stack" check, counted like a target). The static call-graph bound of each entry
# point (firmware/stack_bound.py, on a nightly build with -Z emit-stack-sizes) must be at least
# that mark and at most its ceiling in firmware/stack-static-bounds.txt (the "static stack
# bound" check, counted like a target; skipped without nightly). The C header must state each
# measured export's stack ceiling (firmware/header_stack.py, one more check), and with m4f the
# code-size table at opt-level 3 is regenerated (firmware/size.sh; one-scheme images must be
# smaller than the image with every scheme). The bare-metal targets are built for one core
# (NLSUBDIV_MAX_CHUNKS=1, firmware/build.sh).
#
# A target whose tools are missing is SKIPPED (scripts/setup.sh installs them); nothing is
# installed here. The last line is "test-firmware: N passed, M failed, K skipped" (one per
# target); the exit status is non-zero only when something ran and failed.
#
#   scripts/test-firmware.sh [target...]      # default: every target
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
OUT=$ROOT/target/firmware
mkdir -p "$OUT"
export PATH="$HOME/.cargo/bin:$PATH"
t_start=$SECONDS
passed=0; failed=0; skipped=0
m4f_ok=0

# have_std TRIPLE: the Rust standard library for TRIPLE is installed (rustup target add).
have_std() {
    local dir
    dir=$(rustc --print target-libdir --target "$1" 2>/dev/null) || return 1
    compgen -G "$dir/libcore-*.rlib" >/dev/null
}

# missing TARGET: prints what TARGET lacks (empty when everything is there).
missing() {
    local m=()
    case "$1" in
        x86_64) command -v gcc >/dev/null || m+=(gcc) ;;
        aarch64)
            have_std aarch64-unknown-linux-gnu || m+=("rustup target aarch64-unknown-linux-gnu")
            command -v aarch64-linux-gnu-gcc >/dev/null || m+=(gcc-aarch64-linux-gnu)
            command -v qemu-aarch64 >/dev/null || m+=("qemu-user (qemu-aarch64)") ;;
        m4f|m7|example)
            have_std thumbv7em-none-eabihf || m+=("rustup target thumbv7em-none-eabihf")
            command -v arm-none-eabi-gcc >/dev/null || m+=(gcc-arm-none-eabi)
            if command -v arm-none-eabi-gcc >/dev/null; then
                [ -f "$(arm-none-eabi-gcc -print-file-name=rdimon.specs)" ] || m+=(libnewlib-arm-none-eabi)
            fi
            command -v qemu-system-arm >/dev/null || m+=(qemu-system-arm) ;;
        riscv32)
            have_std riscv32imac-unknown-none-elf || m+=("rustup target riscv32imac-unknown-none-elf")
            command -v riscv64-unknown-elf-gcc >/dev/null || m+=(gcc-riscv64-unknown-elf)
            if command -v riscv64-unknown-elf-gcc >/dev/null; then
                [ -f "$(riscv64-unknown-elf-gcc -print-file-name=picolibc.specs)" ] || m+=(picolibc-riscv64-unknown-elf)
            fi
            command -v qemu-system-riscv32 >/dev/null || m+=("qemu-system-misc (qemu-system-riscv32)") ;;
    esac
    echo "${m[*]}"
}

# run TARGET PROGRAM: runs the harness, output (stdout and stderr: picolibc's semihosting
# writes to QEMU's stderr) to $OUT/TARGET/run.txt; returns the program's exit status.
run() {
    local log=$OUT/$1/run.txt
    case "$1" in
        x86_64) timeout 300 "$2" ;;
        aarch64) timeout 300 qemu-aarch64 "$2" ;;
        m4f) timeout 300 qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none -semihosting -kernel "$2" ;;
        m7) timeout 300 qemu-system-arm -M mps2-an500 -nographic -monitor none -serial none -semihosting -kernel "$2" ;;
        riscv32) timeout 300 qemu-system-riscv32 -M virt -bios none -nographic -monitor none -serial none \
            -semihosting-config enable=on,target=native -kernel "$2" ;;
    esac >"$log" 2>&1
}

cases_of() { grep '^case ' "$OUT/$1/run.txt"; }

# The bare-metal example: its own Makefile, the harness's M4F cargo directory (cargo rebuilds
# only the ffi crate, with the example's features: the schemes it calls), exit status 0 when
# its results are on their circle and sphere.
example() {
    local t0=$SECONDS lacking log=$OUT/example/run.txt
    lacking=$(missing example)
    if [ -n "$lacking" ]; then
        echo "SKIP  example — missing: $lacking (scripts/setup.sh installs it)"
        skipped=$((skipped+1)); return
    fi
    mkdir -p "$OUT/example"
    if make -s -C c_examples/bare-metal run CARGO_TARGET_DIR="$OUT/cargo-o3" OUT="$OUT/example" >"$log" 2>&1 &&
        grep -q "largest distance from the sphere" "$log"; then
        echo "PASS  example ($((SECONDS-t0)) s): $(grep -c . "$log") lines, exit status 0 (results on their circle and sphere)"
        passed=$((passed+1))
    else
        echo "FAIL  example ($((SECONDS-t0)) s); last lines of $log:"
        tail -n 15 "$log" | sed 's/^/      /'
        failed=$((failed+1))
    fi
}

# check TARGET: builds and runs TARGET; compares with the reference unless TARGET is it.
check() {
    local t=$1 t0=$SECONDS prog rc closing lacking
    lacking=$(missing "$t")
    if [ -n "$lacking" ]; then
        echo "SKIP  $t — missing: $lacking (scripts/setup.sh installs it)"
        skipped=$((skipped+1)); return 2
    fi
    mkdir -p "$OUT/$t"
    if ! prog=$(firmware/build.sh "$t" 2>"$OUT/$t/build.log"); then
        echo "FAIL  $t — build failed; last lines of $OUT/$t/build.log:"
        tail -n 15 "$OUT/$t/build.log" | sed 's/^/      /'
        failed=$((failed+1)); return 1
    fi
    run "$t" "$prog"; rc=$?
    closing=$(grep '^harness: [0-9]* cases' "$OUT/$t/run.txt" || true)
    local problems=()
    [ "$rc" -eq 0 ] || problems+=("exit status $rc")
    [ -n "$closing" ] || problems+=("no closing line (crash or time-out)")
    grep -q '^FAIL' "$OUT/$t/run.txt" && problems+=("$(grep -c '^FAIL' "$OUT/$t/run.txt") FAIL lines")
    if [ "$t" != x86_64 ] && [ -f "$OUT/x86_64/run.txt" ]; then
        local ndiff
        ndiff=$(diff <(cases_of x86_64) <(cases_of "$t") | grep -c '^[<>]')
        [ "$ndiff" -eq 0 ] || problems+=("$ndiff case lines differ from x86_64")
        [ "$(cases_of "$t" | wc -l)" -gt 0 ] || problems+=("no case lines")
    fi
    if [ ${#problems[@]} -eq 0 ]; then
        [ "$t" = m4f ] && m4f_ok=1
        echo "PASS  $t ($((SECONDS-t0)) s): ${closing#harness: }; $( [ "$t" = x86_64 ] && echo "reference" || echo "case hashes identical to x86_64")"
        passed=$((passed+1)); return 0
    fi
    echo "FAIL  $t ($((SECONDS-t0)) s): ${problems[*]}; log $OUT/$t/run.txt"
    grep '^FAIL' "$OUT/$t/run.txt" | head -n 10 | sed 's/^/      /'
    if [ "$t" != x86_64 ] && [ -f "$OUT/x86_64/run.txt" ]; then
        diff <(cases_of x86_64) <(cases_of "$t") | head -n 10 | sed 's/^/      /'
    fi
    failed=$((failed+1)); return 1
}

# The stack table of the M4F run: per entry point, the largest high-water mark of its cases.
stack_table() {
    local log=$OUT/m4f/run.txt table=$OUT/stack-m4f.md
    [ -f "$log" ] || return 0
    {
        echo "| entry point | cases | high-water mark (bytes) | deepest case |"
        echo "|---|---:|---:|---|"
        grep '^stack ' "$log" | sed 's/^stack //' | awk -F'\t' '
            { n[$1]++; if (!($1 in max) || $3 > max[$1]) { max[$1] = $3; at[$1] = $2 } order[$1] = order[$1] ? order[$1] : ++k }
            END { for (e in n) printf "| %s | %d | %d | %s |\n", e, n[e], max[e], at[e] }' | sort -t'|' -k4 -n -r
    } > "$table"
    echo "stack high-water marks on Cortex-M4F (bytes below the case's stack pointer; $table):"
    sed 's/^/      /' "$table"
}

# The stack bounds of firmware/stack-bounds.txt against this invocation's M4F run: each listed
# entry point's largest high-water mark must be at most its bound, and it must have run.
stack_bounds() {
    local log=$OUT/m4f/run.txt bounds=firmware/stack-bounds.txt over
    [ "$m4f_ok" -eq 1 ] || return 0
    over=$(grep '^stack ' "$log" | sed 's/^stack //' | awk -F'\t' '
        NR == FNR { if ($0 !~ /^#/ && NF == 2) { bound[$1] = $2; order[++k] = $1 } next }
        { if (!($1 in max) || $3 + 0 > max[$1]) max[$1] = $3 + 0 }
        END {
            for (i = 1; i <= k; i++) {
                e = order[i]
                if (!(e in max)) printf "%s: not in the run\n", e
                else if (max[e] < 0 || max[e] > bound[e]) printf "%s: %d bytes, bound %d\n", e, max[e], bound[e]
            }
        }' "$bounds" -)
    if [ -z "$over" ]; then
        echo "PASS  stack: $(grep -c $'^[^#].*\t' "$bounds") entry points within their bounds ($bounds)"
        passed=$((passed+1))
    else
        echo "FAIL  stack: over the bounds of $bounds:"
        echo "$over" | sed 's/^/      /'
        failed=$((failed+1))
    fi
}

# The static call-graph bound (firmware/stack_bound.py) of the same entry points, on the M4F
# harness the run measured, its frame-size method checked on the same harness built by nightly
# with -Z emit-stack-sizes (firmware/build.sh m4f-stack-sizes): each
# bound must be at least this run's measured high-water mark and at most its ceiling in
# firmware/stack-static-bounds.txt (UNKNOWN there: an entry point the analysis cannot bound
# yet, listed as such). SKIPPED, visibly, without nightly or its thumbv7em library.
static_bound() {
    local log=$OUT/m4f-stack-sizes/build.log table=$OUT/stack-static-m4f.md elf ir lacking=() summary
    [ "$m4f_ok" -eq 1 ] || return 0
    rustup run nightly rustc --version >/dev/null 2>&1 || lacking+=("the nightly toolchain")
    if [ ${#lacking[@]} -eq 0 ]; then
        local dir
        dir=$(rustup run nightly rustc --print target-libdir --target thumbv7em-none-eabihf 2>/dev/null)
        compgen -G "$dir/libcore-*.rlib" >/dev/null || lacking+=("nightly's thumbv7em-none-eabihf library")
    fi
    command -v python3 >/dev/null || lacking+=(python3)
    command -v arm-none-eabi-objdump >/dev/null || lacking+=(arm-none-eabi-objdump)
    if [ ${#lacking[@]} -gt 0 ]; then
        echo "SKIP static stack bound: missing ${lacking[*]} (scripts/setup.sh installs it)"
        skipped=$((skipped+1)); return
    fi
    mkdir -p "$OUT/m4f-stack-sizes"
    if ! elf=$(firmware/build.sh m4f-stack-sizes 2>"$log"); then
        echo "FAIL  static stack bound — build failed; last lines of $log:"
        tail -n 15 "$log" | sed 's/^/      /'
        failed=$((failed+1)); return
    fi
    # The LLVM IR of the measured build's Rust library: the indirect calls resolved by type.
    if ! ir=$(firmware/build.sh m4f-llvm-ir 2>>"$log"); then
        echo "FAIL  static stack bound — LLVM IR build failed; last lines of $log:"
        tail -n 15 "$log" | sed 's/^/      /'
        failed=$((failed+1)); return
    fi
    # The IR must be of the code the run measured: its build's library must disassemble to
    # the m4f build's instruction for instruction (else a candidate the IR lacks could be
    # missed). Same compiler, flags and profile, so they agree; a difference fails the check.
    # The measured library is the copy firmware/build.sh m4f kept beside the harness (the
    # bare-metal example rebuilds the cargo directory's own copy with its own options).
    local lib=thumbv7em-none-eabihf/release/libnlsubdiv.a
    if ! cmp -s <(arm-none-eabi-objdump -d "$OUT/m4f/libnlsubdiv.a" | sed 1,3d) \
                <(arm-none-eabi-objdump -d "$OUT/cargo-llvm-ir-o3/$lib" | sed 1,3d); then
        echo "FAIL  static stack bound — the LLVM IR's library ($OUT/cargo-llvm-ir-o3/$lib) is not the measured one's code"
        failed=$((failed+1)); return
    fi
    # The bound is of the ELF the run measured (the stable build); the nightly one checks the
    # prologue method of frame sizes against the compiler's .stack_sizes.
    if python3 firmware/stack_bound.py "$OUT/m4f/harness.elf" --stack-sizes-elf "$elf" --llvm-ir "$ir" \
        --run "$OUT/m4f/run.txt" --bounds firmware/stack-static-bounds.txt >"$table" 2>&1; then
        summary=$(tail -n 1 "$table")
        echo "PASS  static stack bound: ${summary#stack_bound: }; each at least the measured mark ($table)"
        passed=$((passed+1))
    else
        echo "FAIL  static stack bound ($table):"
        grep -E '^(problem|stack_bound|Traceback)' "$table" | sed 's/^/      /'
        failed=$((failed+1))
    fi
}

# The C header states each measured export's stack ceiling (the largest of its entry points'
# static-bound ceilings above): firmware/header_stack.py fails on a missing or different line.
header_stack() {
    local log=$OUT/header-stack.txt summary
    if python3 firmware/header_stack.py >"$log" 2>&1; then
        summary=$(tail -n 1 "$log")
        echo "PASS  ${summary#header_stack: } in include/nlsubdiv.h"
        passed=$((passed+1))
    else
        echo "FAIL  header's stack figures ($log):"
        sed 's/^/      /' "$log"
        failed=$((failed+1))
    fi
}

# The code-size table at opt-level 3 (firmware/size.sh, docs/firmware.md "Code size") into
# target/firmware/size-m4f.md; fails unless every one-scheme image is smaller than the image
# with every scheme (link only what you use). Runs with the M4F target.
size_table() {
    local t0=$SECONDS lacking table=$OUT/size-m4f.md
    lacking=$(missing m4f)
    if [ -n "$lacking" ]; then
        echo "SKIP  size table — missing: $lacking (scripts/setup.sh installs it)"
        skipped=$((skipped+1)); return
    fi
    if SIZE_OPTS=3 SIZE_CHECK=1 firmware/size.sh >"$table" 2>&1; then
        echo "PASS  size table ($((SECONDS-t0)) s): $(tail -n 1 "$table" | sed 's/^size check: //') ($table)"
        passed=$((passed+1))
    else
        echo "FAIL  size table ($table):"
        tail -n 15 "$table" | sed 's/^/      /'
        failed=$((failed+1))
    fi
}

targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(x86_64 aarch64 m4f m7 riscv32 example)
# The reference first: every other target is compared with it.
if [[ " ${targets[*]} " != *" x86_64 "* ]]; then targets=(x86_64 "${targets[@]}"); fi
for t in "${targets[@]}"; do
    if [ "$t" = example ]; then example; continue; fi
    check "$t"
    if [ "$t" = x86_64 ] && [ ! -f "$OUT/x86_64/run.txt" ]; then
        echo "SKIP  every other target — no x86_64 reference"
        skipped=$((skipped+${#targets[@]}-1)); break
    fi
done
stack_table
stack_bounds
static_bound
header_stack
[[ " ${targets[*]} " == *" m4f "* ]] && size_table
echo "test-firmware: $((SECONDS-t_start)) s"
echo "test-firmware: $passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]
