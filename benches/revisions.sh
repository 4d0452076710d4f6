#!/usr/bin/env bash
# The working tree's build against an earlier revision's, on the benchmark rows of the Möbius
# schemes (one thread, default mode): for a speed change that must keep every output bit.
#
#   benches/revisions.sh REV [REPS]
#
# Builds examples/subdivide_off of REV in a git worktree (target/revisions/REV) and of the
# working tree, runs each row REPS times interleaved (REV, now, REV, now, …) so that a change
# of machine load hits both alike, and prints the fastest and the median core time of each
# (subdivide_off's time_ms: plan, topology and every level, no file I/O), their ratios, and
# the load average before and after. The two builds' output files are compared byte for byte
# (`{:?}` coordinates: equal files are equal bits).
set -u
rev=${1:?usage: benches/revisions.sh REV [REPS]}
reps=${2:-9}
here=$(cd "$(dirname "$0")/.." && pwd)
meshes=${NLS_SHARED_DATA:-$here/../shared/data/meshes}
sha=$(git -C "$here" rev-parse --short "$rev") || exit 2
old=$here/target/revisions/$sha
if [ ! -d "$old" ]; then
  git -C "$here" worktree add -q --detach "$old" "$sha" || exit 2
fi
(cd "$old" && cargo build -q --release --example subdivide_off) || exit 2
(cd "$here" && cargo build -q --release --example subdivide_off) || exit 2
bins=("$old/target/release/examples/subdivide_off" "$here/target/release/examples/subdivide_off")
out=$(mktemp -d)
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '| row | %s fastest / median ms | now fastest / median ms | now / %s (fastest, median) |\n|---|---|---|---|\n' "$sha" "$sha"
status=0
for row in loop:epcot:4 butterfly:epcot:4 catmull-clark:cube:8 catmull-clark:spot_quad:3 \
           doo-sabin:cube:8 kobbelt:spot_quad:3; do
  IFS=: read -r s m l <<<"$row"
  [ -f "$meshes/$m.off" ] || { echo "SKIP $row: $meshes/$m.off not found"; continue; }
  times=("" "")
  for _ in $(seq "$reps"); do
    for i in 0 1; do
      t=$("${bins[$i]}" "$s" "$l" "$meshes/$m.off" "$out/$i.off" --mobius --threads 1 2>&1 \
          >/dev/null | sed -n 's/.*time_ms=\([0-9.]*\).*/\1/p')
      times[$i]="${times[$i]} $t"
    done
  done
  if ! cmp -s "$out/0.off" "$out/1.off"; then
    echo "DIFFERENT OUTPUT: $row"
    status=1
  fi
  python3 - "$row" "${times[0]}" "${times[1]}" <<'EOF'
import statistics, sys
row, a, b = sys.argv[1], [float(x) for x in sys.argv[2].split()], [float(x) for x in sys.argv[3].split()]
print(f"| {row} | {min(a):.1f} / {statistics.median(a):.1f} | {min(b):.1f} / {statistics.median(b):.1f} "
      f"| {min(b) / min(a):.3f}, {statistics.median(b) / statistics.median(a):.3f} |")
EOF
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
rm -rf "$out"
exit $status
