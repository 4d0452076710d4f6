#!/usr/bin/env bash
# Output bits of every scheme, linear and Möbius, on a fixed set of shared meshes, for
# checking that a speed change does not change a single output bit:
#
#   benches/identical.sh OUTDIR        # writes OUTDIR/<mesh>.<scheme>.<lin|mob|defN>.off + det_hash
#   cmp -s / diff -r OUTDIR_BEFORE OUTDIR_AFTER
#
# Uses target/release/examples/subdivide_off and det_hash (build them first:
# cargo build --release --examples). OFF coordinates are written with `{:?}` (shortest
# round-trip form), so equal files mean equal bits. A rejected mesh records its exit status.
set -u
out=${1:?usage: benches/identical.sh OUTDIR}
here=$(cd "$(dirname "$0")/.." && pwd)
bin=$here/target/release/examples
meshes=$here/../shared/data/meshes
mkdir -p "$out"
schemes="loop catmull-clark butterfly kobbelt doo-sabin simplest dual vertex-insertion dual-truncation"
for m in epcot cube spot_quad house_pentagons pyramid_mixed cylinder_tri_pole20 torus_quad \
         vase_quad pawn_tri sphere_uv_mixed_pole16 hexagon_pyramid dome_polygon_pattern; do
  [ -f "$meshes/$m.off" ] || { echo "SKIP $m (not found)"; continue; }
  for s in $schemes; do
    for mode in lin mob; do
      # The Möbius rows run the paper's literal rules (the fold guard is the default).
      flags=; [ $mode = mob ] && flags="--mobius --literal"
      f=$out/$m.$s.$mode.off
      "$bin/subdivide_off" "$s" 2 "$meshes/$m.off" "$f" $flags 2>/dev/null
      echo "exit $?" > "$f.status"
    done
  done
done
# The Möbius default mode (the fold guard) on meshes it distrusts nothing in and on meshes it
# changes: OUTDIR/<mesh>.<scheme>.def<levels>.off.
for m in fandisk rocker_arm bunny cow camelhead epcot helmet_quad spot_quad horse_quad \
         polycastle_quad pawn_tri sphere_icosphere2_perturbed sphere_cube_quads_perturbed \
         sphere_octahedron_perturbed torus_quad; do
  [ -f "$meshes/$m.off" ] || { echo "SKIP $m (not found)"; continue; }
  for s in loop catmull-clark butterfly kobbelt doo-sabin; do
    # Three levels on the small meshes only (the large ones give outputs of 100 MB there).
    levels=2; [ "$(wc -c < "$meshes/$m.off")" -lt 60000 ] && levels="2 3"
    for l in $levels; do
      f=$out/$m.$s.def$l.off
      "$bin/subdivide_off" "$s" $l "$meshes/$m.off" "$f" --mobius 2>/dev/null
      echo "exit $?" > "$f.status"
    done
  done
done
"$bin/det_hash" > "$out/det_hash.txt"
echo "identical.sh: $(ls "$out" | grep -c '\.off$') outputs in $out"
