#!/usr/bin/env bash
# Cost of sharp-feature tags, and of the code that carries them for untagged input:
#
#   cargo build --release -p nlsubdiv-cli && benches/crease_cost.sh [REPS] [OLD_NLSUBDIV]
#
# 1. Tags: `subdivide` with and without `--crease-angle 30` (linear and Möbius Loop on
#    fandisk, Catmull–Clark on polycastle_quad), interleaved (untagged, tagged, untagged, …)
#    so that a change of machine load hits both alike. The time is the summary's kernel time
#    ("subdivision X ms": plan, topology and every level of the one library call, no file
#    I/O), on one thread (the tagged call runs on the calling thread).
# 2. With OLD_NLSUBDIV (a `nlsubdiv` binary built from an earlier commit): the untagged runs
#    of that binary and of this one, interleaved, so that a cost the tags add to untagged
#    input shows as a ratio above 1.
# Prints the median of each and the ratio, and the load average before and after.
set -u
reps=${1:-9}
old=${2:-}
here=$(cd "$(dirname "$0")/.." && pwd)
bin=$here/target/release/nlsubdiv
meshes=${NLS_SHARED_DATA:-$here/../shared/data/meshes}
out=/tmp/crease_cost.$$.off
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
ms() { "$@" 2>&1 >/dev/null | sed -n 's/.*(subdivision \([0-9.]*\) ms.*/\1/p'; }
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
printf '%-22s %-16s %6s %12s %12s %7s\n' scheme mesh levels untagged_ms tagged_ms ratio
rows='loop fandisk 2
mobius-loop fandisk 2
catmull-clark polycastle_quad 3
mobius-catmull-clark polycastle_quad 3'
while read -r s m l; do
  [ -f "$meshes/$m.off" ] || { echo "SKIP $m (not found)"; continue; }
  a=(); b=()
  for _ in $(seq "$reps"); do
    a+=("$(ms "$bin" subdivide --threads 1 --scheme "$s" --levels "$l" "$meshes/$m.off" "$out")")
    b+=("$(ms "$bin" subdivide --threads 1 --scheme "$s" --levels "$l" --crease-angle 30 "$meshes/$m.off" "$out")")
  done
  x=$(printf '%s\n' "${a[@]}" | median); y=$(printf '%s\n' "${b[@]}" | median)
  printf '%-22s %-16s %6s %12s %12s %7.3f\n' "$s" "$m" "$l" "$x" "$y" "$(echo "$y / $x" | bc -l)"
done <<< "$rows"
if [ -n "$old" ]; then
  printf '\n%-22s %-16s %6s %12s %12s %7s\n' scheme mesh levels old_ms new_ms ratio
  while read -r s m l; do
    [ -f "$meshes/$m.off" ] || continue
    a=(); b=()
    for _ in $(seq "$reps"); do
      a+=("$(ms "$old" subdivide --threads 1 --scheme "$s" --levels "$l" "$meshes/$m.off" "$out")")
      b+=("$(ms "$bin" subdivide --threads 1 --scheme "$s" --levels "$l" "$meshes/$m.off" "$out")")
    done
    x=$(printf '%s\n' "${a[@]}" | median); y=$(printf '%s\n' "${b[@]}" | median)
    printf '%-22s %-16s %6s %12s %12s %7.3f\n' "$s" "$m" "$l" "$x" "$y" "$(echo "$y / $x" | bc -l)"
  done <<< "$rows
mobius-butterfly bunny 2
mobius-loop rocker_arm 2"
fi
rm -f "$out"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
