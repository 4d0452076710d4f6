#!/usr/bin/env bash
# Instruction counts (valgrind callgrind, repeatable on a loaded machine) of one multi-level
# call per benchmark row, linear and Möbius: `benches/icount.sh BENCH_BIN [OUTDIR]`, where
# BENCH_BIN is the benches/mesh.rs binary (cargo bench --bench mesh --no-run). Counts include
# reading the small input OFF file (the same for both modes). OUTDIR keeps the callgrind.out
# files for callgrind_annotate.
set -u
bin=${1:?usage: benches/icount.sh BENCH_BIN [OUTDIR]}
out=${2:-$(mktemp -d)}
mkdir -p "$out"
meshes=$(cd "$(dirname "$0")/.." && pwd)/../shared/data/meshes
rows="epcot:loop:4 epcot:butterfly:4 cube:catmull-clark:8 spot_quad:catmull-clark:3 cube:doo-sabin:8 spot_quad:kobbelt:3"
printf '| mesh | scheme | levels | linear Ir (M) | Möbius Ir (M) | Möbius / linear |\n|---|---|---|---|---|---|\n'
for r in $rows; do
  IFS=: read -r m s l <<<"$r"
  ir() {
    valgrind --tool=callgrind --callgrind-out-file="$out/$m.$s.$1.cg" "$bin" "$s" "$l" "$meshes/$m.off" $2 \
      2>&1 | sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
  }
  a=$(ir lin "")
  b=$(ir mob --mobius)
  python3 -c "print(f'| $m | $s | $l | {$a/1e6:,.0f} | {$b/1e6:,.0f} | {$b/$a:.2f} |')"
done
