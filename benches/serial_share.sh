#!/usr/bin/env bash
# The serial share of the benchmark rows at 2 threads, in instructions (valgrind callgrind
# with --separate-threads; an instruction count does not depend on the machine's load):
#
#   cargo build --release -p nlsubdiv-threads --examples && benches/serial_share.sh
#
# For each row, one multi-level call of examples/subdivide_off_threads on 2 threads
# (nlsubdiv_threads::Threads: passes shorter than 2 × MIN_CHUNK elements run on the calling
# thread, as they do in use). The serial part is the calling thread's share of the kernel's
# call (`kernel_call` of the example: the plan's checks, every level's topology and step, no
# file I/O) outside the executor's runs (`Threads::run`); the total is that plus every other
# thread's instructions. Prints the
# share and what Amdahl's law, S(n) = 1 / ((1 − p) + p / n), then allows on n cores at best
# (memory bandwidth and the passes' barriers come on top).
set -u
here=$(cd "$(dirname "$0")/.." && pwd)
bin=$here/target/release/examples/subdivide_off_threads
meshes=${NLS_SHARED_DATA:-$here/../shared/data/meshes}
rows=${ROWS:-"epcot:loop:4 epcot:butterfly:4 cube:catmull-clark:8 spot_quad:catmull-clark:3 cube:doo-sabin:8 spot_quad:kobbelt:3"}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
count() { # count FILE PATTERN: the inclusive instructions of the first function matching
  callgrind_annotate --inclusive=yes --show-percs=no "$1" 2>/dev/null |
    awk -v pat="$2" '$0 ~ pat {gsub(",", "", $1); print $1; exit}'
}
printf '| row | mode | serial (M instr.) | total (M instr.) | serial share | S(2) | S(8) | S(16) | S(64) |\n'
printf '|---|---|---:|---:|---:|---:|---:|---:|---:|\n'
for r in $rows; do
  IFS=: read -r m s l <<<"$r"
  [ -f "$meshes/$m.off" ] || { echo "SKIP $m (not found)"; continue; }
  for mode in linear mobius; do
    flag=; [ $mode = mobius ] && flag=--mobius
    rm -f "$tmp"/cg*
    valgrind --tool=callgrind --separate-threads=yes --callgrind-out-file="$tmp/cg" \
      "$bin" "$s" "$l" "$meshes/$m.off" "$tmp/out.off" $flag --threads 2 >/dev/null 2>&1
    main=$(count "$tmp/cg-01" '::kernel_call \[')
    inpool=$(count "$tmp/cg-01" 'Threads as nlsubdiv::exec::Executor>::run \[')
    others=0
    for f in "$tmp"/cg-*; do
      [ "$f" = "$tmp/cg-01" ] && continue
      n=$(callgrind_annotate --show-percs=no "$f" 2>/dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}')
      others=$((others + ${n:-0}))
    done
    python3 - "$m" "$s" "$l" "$mode" "${main:-0}" "${inpool:-0}" "$others" <<'PY'
import sys
m, s, l, mode = sys.argv[1:5]
main, inpool, others = (int(x) for x in sys.argv[5:8])
serial, total = main - inpool, main + others
q = serial / total
S = lambda n: 1 / (q + (1 - q) / n)
print(f"| {s} {m} {l} | {mode} | {serial/1e6:.1f} | {total/1e6:.1f} | {100*q:.1f} % | {S(2):.2f} | {S(8):.2f} | {S(16):.2f} | {S(64):.1f} |")
PY
  done
done
