#!/usr/bin/env bash
# The C/C++ integrations against Debian's libopenmesh-dev (OpenMesh 9) and libcgal-dev
# (CGAL 5.5), and the packaging (one step of scripts/test-all.sh):
#
#   scripts/test-integrations.sh [OUTDIR]      (default target/integrations)
#
# 1. scripts/install.sh into OUTDIR/prefix (header, libnlsubdiv.a, .so with soname, pkg-config,
#    CMake package, the C++ headers, the command and its manual page); the exported symbols of
#    both libraries, the soname, the command's version and the page's rendering are checked;
# 2. integrations/tests/test_openmesh (linked statically through pkg-config nlsubdiv-static)
#    and test_cgal (shared, pkg-config nlsubdiv), built once against the installed headers
#    (-O1; rebuilt only when a source or the library changes), run on the shared test meshes
#    ($NLS_SHARED_DATA, as for the Rust tests; without them only their in-memory cases run
#    and each is reported as a skipped test, scripts/lib-test.sh): every plugin/function = the driver,
#    OpenMesh LoopT/ModifiedButterflyT/CatmullClarkT and CGAL Loop_subdivision, bad meshes;
# 3. integrations/cmake-consumer configured and built out of tree against the prefix, run;
# 4. every c_examples/*.c built with `pkg-config --cflags --libs nlsubdiv` (and once static)
#    against the prefix, run.
# Exit 77 when OpenMesh, CGAL, cmake or pkg-config is missing (the caller reports SKIP).
# Last line: "test-integrations: N passed, M failed".
set -uo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
OUT=${1:-$ROOT/target/integrations}
. scripts/lib-test.sh
MESHES=$(shared_meshes_dir)
mkdir -p "$OUT"

missing=()
[ -f /usr/include/OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh ] || missing+=(libopenmesh-dev)
[ -f /usr/include/CGAL/Subdivision_method_3/subdivision_hosts_3.h ] || missing+=(libcgal-dev)
command -v cmake >/dev/null || missing+=(cmake)
command -v pkg-config >/dev/null || missing+=(pkg-config)
if [ ${#missing[@]} -gt 0 ]; then
    echo "test-integrations: SKIP, not installed: ${missing[*]} (scripts/setup.sh installs them)"
    exit 77
fi

passed=0; failed=0
check() { # check NAME COMMAND...
    local name=$1; shift
    local t0=$SECONDS
    if "$@"; then passed=$((passed+1)); echo "  ok    $name ($((SECONDS-t0)) s)"
    else failed=$((failed+1)); echo "  FAIL  $name ($((SECONDS-t0)) s)"; fi
}

PREFIX=$OUT/prefix
rm -rf "$PREFIX"
check "install into $PREFIX" scripts/install.sh "$PREFIX"
export PKG_CONFIG_PATH=$PREFIX/lib/pkgconfig

symbols() {
    # The static library exports the nls_* functions and Rust's compiler-builtins helpers
    # (all "__"-prefixed); no libm name may be defined in it (a C++ link that lists
    # libnlsubdiv.a before -lm would take it from there), nothing weak besides compiler-rt's
    # abort hook. The shared library exports nls_* only.
    local a=$PREFIX/lib/libnlsubdiv.a so=$PREFIX/lib/libnlsubdiv.so
    local others libm weak sonls sooth soname
    others=$(nm -g --defined-only "$a" 2>/dev/null | awk 'NF==3 && $3 !~ /^nls_/ {print $3}' | sort -u)
    libm=$(printf '%s\n' "$others" | grep -xE '(a?(sin|cos|tan)h?|atan2|exp2?|expm1|log(2|10|1p)?|pow|sqrt|cbrt|hypot|fmod|floor|ceil|round|trunc|fma|fmin|fmax|copysign|scalbn|ldexp|frexp|modf|remainder)f?' || true)
    weak=$(nm -g --defined-only "$a" 2>/dev/null | awk 'NF==3 && ($2=="W" || $2=="V") {print $3}' | sort -u | grep -v '^__compilerrt_abort_impl$' || true)
    sonls=$(nm -D --defined-only "$so" | awk '$3 ~ /^nls_/' | wc -l)
    sooth=$(nm -D --defined-only "$so" | awk '$3 !~ /^nls_/' | wc -l)
    soname=$(readelf -d "$so" | sed -n 's/.*SONAME.*\[\(.*\)\]/\1/p')
    echo "    libnlsubdiv.a: $(nm -g --defined-only "$a" 2>/dev/null | awk 'NF==3 && $3 ~ /^nls_/' | wc -l) nls_* exports, $(printf '%s\n' "$others" | grep -c . ) other global symbols (all __-prefixed compiler builtins: $(printf '%s\n' "$others" | grep -vc '^__' || true) not), libm names: ${libm:-none}, weak: ${weak:-none}"
    echo "    libnlsubdiv.so: soname $soname, $sonls nls_* exports, $sooth others"
    [ -z "$libm" ] && [ -z "$weak" ] && [ "$sooth" -eq 0 ] && [ "$soname" = "$(packaging/version.sh soname)" ] &&
        [ "$(printf '%s\n' "$others" | grep -vc '^__' || true)" -eq 0 ]
}
check "exported symbols of the installed libraries" symbols
installed_command() {
    # The command reports Cargo.toml's version; its manual page renders without a warning.
    local v warnings
    v=$("$PREFIX/bin/nlsubdiv" --version) || return 1
    warnings=$(MANWIDTH=80 man --warnings -E UTF-8 -l "$PREFIX/share/man/man1/nlsubdiv.1" 2>&1 >/dev/null)
    echo "    $v; man page: ${warnings:-no warnings}"
    [ "$v" = "nlsubdiv $(packaging/version.sh version)" ] && [ -z "$warnings" ]
}
check "installed command and manual page" installed_command

# ---- C++ tests, compiled once (objects reused while sources and library are unchanged) ----
CXXFLAGS="-std=c++17 -O1 -Wall -Wextra -Wno-unused-parameter -Wno-maybe-uninitialized -ffp-contract=off"
build_test() { # build_test NAME LIBS...
    local name=$1; shift
    local exe=$OUT/$name src=integrations/tests/$name.cpp
    local newest
    newest=$(ls -t "$src" integrations/tests/common.hpp integrations/openmesh/*.hh integrations/cgal/*.h \
        integrations/common/*.hh include/nlsubdiv.h "$PREFIX/lib/libnlsubdiv.a" 2>/dev/null | head -1)
    if [ -x "$exe" ] && [ "$exe" -nt "$newest" ]; then echo "    $name up to date"; return 0; fi
    # shellcheck disable=SC2046,SC2086
    g++ $CXXFLAGS $(pkg-config --cflags nlsubdiv) "$src" -o "$exe.tmp" "$@" > "$OUT/$name.build.log" 2>&1 &&
        mv "$exe.tmp" "$exe" || { tail -n 30 "$OUT/$name.build.log"; return 1; }
}

build_test test_openmesh $(pkg-config --libs nlsubdiv-static) -lOpenMeshCore &
p1=$!
build_test test_cgal $(pkg-config --libs nlsubdiv) -Wl,-rpath,"$PREFIX/lib" -lgmp -lmpfr &
p2=$!
wait $p1; r1=$?; wait $p2; r2=$?
check "build test_openmesh (static lib, C++ link order) and test_cgal (shared lib)" [ $r1 -eq 0 -a $r2 -eq 0 ]

run_test() { # run_test NAME: runs it on the shared meshes, prints its summary lines
    local log=$OUT/$1.log
    "$OUT/$1" "$MESHES" > "$log" 2>&1
    local rc=$?
    grep -E "^FAIL|^SKIP|worst max_rel_dist|^bad meshes|^$1:" "$log" | sed 's/^/    /'
    return $rc
}
if [ ! -d "$MESHES" ]; then
    # Counted by the caller from $NLS_SKIP_LOG; a failure under NLS_REQUIRE_SHARED_DATA=1.
    for t in test_openmesh test_cgal; do
        skip_test "integrations::$t" "shared meshes folder $MESHES not found (set NLS_SHARED_DATA to it); only the in-memory cases run" 2>&1 |
            sed 's/^/    /'
        [ "${PIPESTATUS[0]}" -eq 0 ] || failed=$((failed+1))
    done
fi
check "OpenMesh subdividers (log $OUT/test_openmesh.log)" run_test test_openmesh
check "CGAL masks and functions (log $OUT/test_cgal.log)" run_test test_cgal

# ---- packaging consumers ----
cmake_consumer() {
    local b=$OUT/cmake-consumer
    rm -rf "$b"
    cmake -S integrations/cmake-consumer -B "$b" -DCMAKE_PREFIX_PATH="$PREFIX" -DCMAKE_BUILD_TYPE=Release > "$OUT/cmake-consumer.log" 2>&1 &&
        cmake --build "$b" >> "$OUT/cmake-consumer.log" 2>&1 || { tail -n 20 "$OUT/cmake-consumer.log"; return 1; }
    grep "nlsubdiv 0" "$OUT/cmake-consumer.log" | sed 's/^/    /'
    "$b/consumer" && "$b/consumer_static"
}
check "CMake consumer: find_package(nlsubdiv CONFIG) out of tree, shared and static" cmake_consumer
pkgconfig_examples() {
    local ex exe d=$OUT/c_examples
    rm -rf "$d"; mkdir -p "$d"
    echo "    pkg-config --cflags --libs nlsubdiv: $(pkg-config --cflags --libs nlsubdiv)"
    for ex in c_examples/*.c; do
        exe=$d/$(basename "$ex" .c)
        # shellcheck disable=SC2046
        gcc -std=c99 -Wall -Wextra -Wpedantic -Werror $(pkg-config --cflags nlsubdiv) "$ex" -o "$exe" \
            $(pkg-config --libs nlsubdiv) -Wl,-rpath,"$PREFIX/lib" -lm || return 1
        # shellcheck disable=SC2046
        gcc -std=c99 $(pkg-config --cflags nlsubdiv-static) "$ex" -o "$exe.static" $(pkg-config --libs nlsubdiv-static) || return 1
        (cd "$d" && "$exe" > "$exe.out" && "$exe.static" > "$exe.static.out") || { echo "    $ex failed"; return 1; }
        echo "    $(basename "$ex"): $(ldd "$exe" | grep -o 'libnlsubdiv[^ ]*' | head -1) and static: ok"
    done
}
check "c_examples via pkg-config against the prefix (shared and static)" pkgconfig_examples

echo "test-integrations: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
