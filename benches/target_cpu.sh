#!/usr/bin/env bash
# A build for the host CPU (`-C target-cpu=native`: AVX and later encodings) against the
# baseline x86_64 build, for the same source: the native build must be no slower. Before the
# kernel took its square root from src/sqrt.rs, libm's inline-assembly `sqrtsd` (legacy SSE)
# sat between VEX-encoded instructions in a native build and made F4 several times slower;
# with BASELINE_REV set, the same comparison is made for that revision too (a git worktree
# in target/target-cpu/), to show the hazard it had.
#
#   benches/target_cpu.sh [REPS] [BASELINE_REV]
#
# Builds examples/subdivide_off four (or two) times into target/target-cpu/ and runs the rows
# interleaved (baseline, native, baseline, native, …) on one thread; prints the median core
# time of each (subdivide_off's time_ms: plan, topology and every level, no file I/O), their
# ratio, and the load before and after. The outputs of the two builds are compared byte for
# byte (the same bits for every compiler flag that keeps IEEE semantics).
set -u
reps=${1:-7}
rev=${2:-}
here=$(cd "$(dirname "$0")/.." && pwd)
meshes=${NLS_SHARED_DATA:-$here/../shared/data/meshes}
out=$here/target/target-cpu
mkdir -p "$out"
build() { # build SRC_DIR TARGET_DIR RUSTFLAGS
    (cd "$1" && RUSTFLAGS="$3" cargo build -q --release --locked --example subdivide_off \
        --target-dir "$2") || exit 1
}
build "$here" "$out/base" ""
build "$here" "$out/native" "-C target-cpu=native"
bins=("$out/base/release/examples/subdivide_off" "$out/native/release/examples/subdivide_off")
names=("this base" "this native")
if [ -n "$rev" ]; then
    # The revision's source stays in target/target-cpu/src-REV (a git worktree; `git worktree
    # prune` after deleting it), so that a second run reuses its builds.
    [ -d "$out/src-$rev" ] || git -C "$here" worktree add -q --detach "$out/src-$rev" "$rev" || exit 1
    build "$out/src-$rev" "$out/rev-base" ""
    build "$out/src-$rev" "$out/rev-native" "-C target-cpu=native"
    bins+=("$out/rev-base/release/examples/subdivide_off" "$out/rev-native/release/examples/subdivide_off")
    names+=("$rev base" "$rev native")
fi
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
run() { "$1" "$2" "$4" "$meshes/$3.off" "$5" --mobius 2>&1 >/dev/null | sed -n 's/.*time_ms=//p'; }
printf '%-14s %-12s %3s' scheme mesh lv
for n in "${names[@]}"; do printf ' %14s' "$n"; done
printf ' %8s' "native/base"; [ -n "$rev" ] && printf ' %8s' "rev n/b"
echo
while read -r s m l; do
    [ -f "$meshes/$m.off" ] || { echo "SKIP $m (not found)"; continue; }
    declare -a t=()
    for i in "${!bins[@]}"; do t[$i]=""; done
    for _ in $(seq "$reps"); do
        for i in "${!bins[@]}"; do t[$i]+="$(run "${bins[$i]}" "$s" "$m" "$l" "$out/o$i.off") "; done
    done
    cmp -s "$out/o0.off" "$out/o1.off" || { echo "  $s $m: the native build's output differs"; exit 1; }
    printf '%-14s %-12s %3s' "$s" "$m" "$l"
    med=()
    for i in "${!bins[@]}"; do
        med[$i]=$(printf '%s\n' ${t[$i]} | median)
        printf ' %14s' "${med[$i]}"
    done
    printf ' %8.3f' "$(echo "${med[1]} / ${med[0]}" | bc -l)"
    [ -n "$rev" ] && printf ' %8.3f' "$(echo "${med[3]} / ${med[2]}" | bc -l)"
    echo
done <<'ROWS'
catmull-clark spot_quad 3
loop epcot 3
butterfly epcot 3
doo-sabin cube 6
ROWS
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
