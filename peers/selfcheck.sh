#!/usr/bin/env bash
# Cross-check OpenMesh, CGAL and OpenSubdiv against each other on the test
# meshes (see selfcheck.py and README.md). Builds peer_subdivide first.
#
#   peers/selfcheck.sh OUTDIR [selfcheck.py options...]
#
# Environment: PEERS_MESHES (default /work/shared/data/meshes), plus the
# build.sh variables. Exit status 0 when nothing failed.
set -euo pipefail
if [[ $# -lt 1 || "$1" == -* ]]; then
  echo "usage: $0 OUTDIR [--jobs N] [--tol T] [--level2-max-faces N] [--no-bad]" >&2
  exit 1
fi
outdir=$1; shift
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mkdir -p "$outdir"
t0=$(date +%s)
"$here/build.sh" "$outdir/bin"
echo "selfcheck.sh: running the cross-check (outputs in $outdir/runs)"
set +e
python3 "$here/selfcheck.py" --bin "$outdir/bin/peer_subdivide" "$@" "$outdir"
rc=$?
set -e
echo "selfcheck.sh: total $(( $(date +%s) - t0 )) s, exit $rc"
exit $rc
