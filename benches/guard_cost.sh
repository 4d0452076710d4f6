#!/usr/bin/env bash
# Cost of the Möbius fold guard (the default) against the paper's literal rules
# (`--literal`), on meshes the guard distrusts nothing in (its output is then the literal
# one bit for bit, so only the measuring costs) and on meshes it changes:
#
#   cargo build --release --example subdivide_off && benches/guard_cost.sh [REPS]
#
# Runs are interleaved (literal, default, literal, default, …) so that a change of machine
# load hits both alike; prints the median core time of each (subdivide_off's time_ms: plan,
# topology and every level, no file I/O) and their ratio, and the load average before and
# after.
#
# With ICOUNT=1 it counts instructions instead (valgrind callgrind, one thread; an
# instruction count does not depend on the machine's load): the inclusive count of
# `scheme::levels::run`, the core's work without file I/O, once per mode (docs/folds.md,
# "Cost").
set -u
reps=${1:-9}
here=$(cd "$(dirname "$0")/.." && pwd)
bin=$here/target/release/examples/subdivide_off
meshes=${NLS_SHARED_DATA:-$here/../shared/data/meshes}
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
run() { "$bin" "$1" "$3" "$meshes/$2.off" /tmp/guard_cost.$$.off --mobius $4 2>&1 >/dev/null |
        sed -n 's/.*time_ms=//p'; }
if [ "${ICOUNT:-0}" = 1 ]; then
  run() {
    local cg=/tmp/guard_cost.$$.cg
    valgrind --tool=callgrind --callgrind-out-file=$cg "$bin" "$1" "$3" "$meshes/$2.off" \
      /tmp/guard_cost.$$.off --mobius --threads 1 $4 >/dev/null 2>&1
    callgrind_annotate --inclusive=yes $cg 2>/dev/null |
      awk '/levels::run::\{\{closure\}\}/ {gsub(",", "", $1); printf "%.1f\n", $1 / 1e6; exit}'
    rm -f $cg
  }
  reps=1
  unit=Mi
fi
printf '%-14s %-28s %6s %10s %10s %7s\n' scheme mesh levels "literal_${unit:-ms}" "default_${unit:-ms}" ratio
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
while read -r s m l; do
  [ -f "$meshes/$m.off" ] || { echo "SKIP $m (not found)"; continue; }
  lit=(); def=()
  for _ in $(seq "$reps"); do
    lit+=("$(run "$s" "$m" "$l" --literal)")
    def+=("$(run "$s" "$m" "$l" "")")
  done
  a=$(printf '%s\n' "${lit[@]}" | median); b=$(printf '%s\n' "${def[@]}" | median)
  printf '%-14s %-28s %6s %10s %10s %7.3f\n' "$s" "$m" "$l" "$a" "$b" "$(echo "$b / $a" | bc -l)"
done <<'ROWS'
loop fandisk 2
loop sphere_icosphere2_perturbed 4
catmull-clark sphere_cube_quads_perturbed 3
catmull-clark torus_quad 3
butterfly sphere_octahedron_perturbed 5
loop rocker_arm 2
catmull-clark helmet_quad 3
kobbelt sphere_cube_quads_perturbed 3
kobbelt torus_quad 3
kobbelt spot_quad 2
doo-sabin sphere_cube_quads_perturbed 3
doo-sabin spot_quad 2
simplest sphere_cube_quads_perturbed 3
simplest spot_quad 2
vertex-insertion sphere_icosphere2_perturbed 3
vertex-insertion bunny 2
dual-truncation sphere_icosphere2_perturbed 3
dual-truncation bunny 2
ROWS
rm -f /tmp/guard_cost.$$.off
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
