#!/usr/bin/env bash
# Build the peer reference harness (peer_subdivide) into OUTDIR.
#
#   peers/build.sh [--sanitize] OUTDIR
#
# Needs g++ (C++17) and the Debian packages libopenmesh-dev (OpenMesh 9.0),
# libcgal-dev (CGAL 5.5, header-only; pulls in boost, gmp, mpfr) and
# libosd-dev (OpenSubdiv 3.5). CI: apt-get install -y g++ pkg-config
# libopenmesh-dev libcgal-dev libosd-dev.
#
# The four translation units compile in parallel into OUTDIR/obj[-san] and are
# rebuilt only when a source in peers/ is newer than the object, so a second
# run only relinks if needed. Environment: CXX (default g++), PEERS_JOBS
# (default: nproc), PEERS_CXXFLAGS (extra flags appended).
# --sanitize builds OUTDIR/peer_subdivide_san with ASan+UBSan and
# _GLIBCXX_ASSERTIONS (see reliability-anchors.md 4.3) instead.
set -euo pipefail

sanitize=0
if [[ "${1:-}" == "--sanitize" ]]; then sanitize=1; shift; fi
if [[ $# -ne 1 || "$1" == -* ]]; then
  echo "usage: $0 [--sanitize] OUTDIR" >&2
  exit 1
fi
outdir=$1
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
CXX=${CXX:-g++}
jobs=${PEERS_JOBS:-$(nproc 2>/dev/null || echo 2)}

say() { printf 'build.sh: %s\n' "$*"; }
die() { printf 'build.sh: ERROR: %s\n' "$*" >&2; exit 1; }

# ---- prerequisites, with the package to install when missing
command -v "$CXX" >/dev/null 2>&1 || die "compiler '$CXX' not found (apt-get install g++)"
need_header() {  # header package
  [[ -f "/usr/include/$1" ]] || die "missing /usr/include/$1 (apt-get install $2)"
}
need_lib() {  # libname package
  local f
  f=$("$CXX" -print-file-name="lib$1.so")
  [[ "$f" == /* && -e "$f" ]] || die "missing lib$1.so (apt-get install $2)"
}
need_header OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh libopenmesh-dev
need_header OpenMesh/Tools/Subdivider/Uniform/LoopT.hh libopenmesh-dev
need_lib OpenMeshCore libopenmesh-dev
need_header CGAL/subdivision_method_3.h libcgal-dev
need_header boost/version.hpp libboost-dev
need_header opensubdiv/far/topologyRefinerFactory.h libosd-dev
need_lib osdCPU libosd-dev

# Include/link flags: pkg-config for OpenMesh when available, explicit otherwise.
om_cflags="" ; om_libs="-lOpenMeshCore"
if command -v pkg-config >/dev/null 2>&1 && pkg-config --exists openmesh 2>/dev/null; then
  om_cflags=$(pkg-config --cflags openmesh)
  say "OpenMesh $(pkg-config --modversion openmesh) (pkg-config)"
else
  say "OpenMesh (no pkg-config file; using -lOpenMeshCore)"
fi
cgal_ver=$(sed -n 's/^#define CGAL_VERSION \([0-9.]*\).*/\1/p' /usr/include/CGAL/version.h 2>/dev/null | head -1)
osd_ver=$(sed -n 's/^#define OPENSUBDIV_VERSION_NUMBER \([0-9]*\).*/\1/p' /usr/include/opensubdiv/version.h 2>/dev/null | head -1)
say "CGAL ${cgal_ver:-?}, OpenSubdiv ${osd_ver:-?}, compiler $("$CXX" -dumpfullversion 2>/dev/null || echo '?') ($CXX)"

base_flags="-std=c++17 -Wall -Wextra -Wno-unused-parameter -Wno-maybe-uninitialized -ffp-contract=off"
if [[ $sanitize -eq 1 ]]; then
  flags="$base_flags -g -O1 -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all -D_GLIBCXX_ASSERTIONS"
  objdir="$outdir/obj-san"; exe="$outdir/peer_subdivide_san"
else
  flags="$base_flags -O2"
  objdir="$outdir/obj"; exe="$outdir/peer_subdivide"
fi
flags="$flags ${PEERS_CXXFLAGS:-}"
mkdir -p "$objdir"
# a flags change forces a rebuild
if [[ ! -f "$objdir/flags" || "$(cat "$objdir/flags")" != "$CXX $flags $om_cflags" ]]; then
  rm -f "$objdir"/*.o
  printf '%s' "$CXX $flags $om_cflags" > "$objdir/flags"
fi

units=(peer_subdivide peer_openmesh peer_cgal peer_osd)
t0=$(date +%s%N)
pids=() ; names=()
for u in "${units[@]}"; do
  src="$here/$u.cpp" ; obj="$objdir/$u.o"
  if [[ -f "$obj" && "$obj" -nt "$src" && "$obj" -nt "$here/peer_common.hpp" ]]; then
    say "up to date: $u.o"
    continue
  fi
  while [[ $(jobs -rp | wc -l) -ge $jobs ]]; do wait -n || true; done
  say "compile $u.cpp"
  # shellcheck disable=SC2086
  ( "$CXX" $flags $om_cflags -c "$src" -o "$obj.tmp" 2> "$objdir/$u.log" && mv "$obj.tmp" "$obj" ) &
  pids+=($!) ; names+=("$u")
done
fail=0
for i in "${!pids[@]}"; do
  if ! wait "${pids[$i]}"; then
    echo "build.sh: ERROR: compiling ${names[$i]}.cpp failed:" >&2
    cat "$objdir/${names[$i]}.log" >&2
    fail=1
  elif [[ -s "$objdir/${names[$i]}.log" ]]; then
    echo "build.sh: warnings in ${names[$i]}.cpp (see $objdir/${names[$i]}.log):" >&2
    head -20 "$objdir/${names[$i]}.log" >&2
  fi
done
[[ $fail -eq 0 ]] || die "compilation failed"

objs=() ; for u in "${units[@]}"; do objs+=("$objdir/$u.o"); done
relink=1
if [[ -x "$exe" ]]; then
  relink=0
  for o in "${objs[@]}"; do [[ "$o" -nt "$exe" ]] && relink=1; done
fi
if [[ $relink -eq 1 ]]; then
  say "link $exe"
  # shellcheck disable=SC2086
  "$CXX" $flags "${objs[@]}" -o "$exe.tmp" $om_libs -losdCPU -lgmp -lmpfr || die "link failed"
  mv "$exe.tmp" "$exe"
else
  say "up to date: $exe"
fi
t1=$(date +%s%N)
ms=$(( (t1 - t0) / 1000000 ))
say "done in $((ms / 1000)).$(printf '%03d' $((ms % 1000))) s: $exe"
