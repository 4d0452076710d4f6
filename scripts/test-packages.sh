#!/usr/bin/env bash
# The Debian packages, built, installed, used and removed (one step of scripts/test-all.sh):
#
#   scripts/test-packages.sh [OUTDIR]      (default target/packages)
#
# 1. the working tree (tracked and untracked files, not the ignored ones) is copied to
#    OUTDIR/src/nlsubdiv, its crates vendored (cargo vendor --locked), and
#    `dpkg-buildpackage -us -uc` builds the source package and libnlsubdiv0.2, libnlsubdiv-dev
#    and nlsubdiv there offline (CARGO_NET_OFFLINE; cargo's target folder OUTDIR/cargo-target
#    is kept between runs); debian/copyright must name the crates of Cargo.lock;
# 2. lintian on the source and binary packages: no error and no warning;
# 3. the three packages are installed with apt-get (this machine: root) and used as a
#    program would, without LD_LIBRARY_PATH, PKG_CONFIG_PATH or CMAKE_PREFIX_PATH:
#    c_examples/*.c through pkg-config (shared, nlsubdiv-static, fully static),
#    integrations/cmake-consumer through find_package, the OpenMesh and CGAL tests of
#    integrations/tests on the installed headers, `nlsubdiv --version`, `man nlsubdiv`;
# 4. the packages are purged, whatever failed, and the list of installed packages must be the
#    one of the start.
# Exit 77 (the caller reports SKIP) when a tool is missing or this is not root; fails at once
# when a package of the same names is installed already (it would be removed).
# Last line: "test-packages: N passed, M failed".
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
ROOT=$PWD
OUT=${1:-$ROOT/target/packages}
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
MESHES=$ROOT/../shared/data/meshes
VERSION=$(packaging/version.sh version) || exit 1
LIBPKG=$(packaging/version.sh libpackage)
SONAME=$(packaging/version.sh soname)
PACKAGES=("$LIBPKG" libnlsubdiv-dev nlsubdiv)
MA=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || echo x86_64-linux-gnu)

missing=()
for tool in dpkg-buildpackage dh lintian apt-get cmake pkg-config gcc g++ man cargo python3; do
    command -v "$tool" >/dev/null || missing+=("$tool")
done
[ -f /usr/include/OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh ] || missing+=(libopenmesh-dev)
[ -f /usr/include/CGAL/Subdivision_method_3/subdivision_hosts_3.h ] || missing+=(libcgal-dev)
if [ ${#missing[@]} -gt 0 ]; then
    echo "test-packages: SKIP, not installed: ${missing[*]} (scripts/setup.sh installs them)"
    exit 77
fi
if [ "$(id -u)" -ne 0 ]; then
    echo "test-packages: SKIP, installing packages needs root"
    exit 77
fi
installed() { dpkg-query -W -f='${Package} ${Status}\n' "$@" 2>/dev/null | awk '$NF == "installed" {print $1}'; }
if [ -n "$(installed "${PACKAGES[@]}")" ]; then
    echo "test-packages: FAIL, already installed: $(installed "${PACKAGES[@]}" | tr '\n' ' ')(this step installs"
    echo "and then purges them: remove them first with apt-get purge)"
    exit 1
fi
for f in /usr/include/nlsubdiv.h /usr/local/include/nlsubdiv.h /usr/local/lib/pkgconfig/nlsubdiv.pc; do
    if [ -e "$f" ]; then
        echo "test-packages: FAIL, $f exists outside the packages: it would shadow or mix with them"
        exit 1
    fi
done

passed=0; failed=0
T0=$SECONDS
check() { # check NAME COMMAND...
    local name=$1; shift
    local t0=$SECONDS
    if "$@"; then passed=$((passed+1)); echo "  ok    $name ($((SECONDS-t0)) s)"
    else failed=$((failed+1)); echo "  FAIL  $name ($((SECONDS-t0)) s)"; fi
}

# ---- 1. build ----
SRC=$OUT/src/nlsubdiv
build() {
    local log=$OUT/build.log
    rm -rf "$SRC" "$OUT"/src/*.deb "$OUT"/src/*.changes "$OUT"/src/*.buildinfo "$OUT"/src/*.dsc "$OUT"/src/*.tar.*
    mkdir -p "$SRC" "$OUT/cargo-target"
    # tar keeps the files' times, so cargo's fingerprints in the kept target folder stay valid.
    git ls-files -z -co --exclude-standard | xargs -0 -r ls -d 2>/dev/null | tar -cf - -T - | tar -xf - -C "$SRC" || return 1
    ln -s "$OUT/cargo-target" "$SRC/target"
    (cd "$SRC" && { cargo vendor --locked --offline vendor >/dev/null 2>&1 || cargo vendor --locked vendor >/dev/null; }) || return 1
    (cd "$SRC" && python3 packaging/copyright-crates.py --check) | sed 's/^/    /' || return 1
    echo "    vendor/: $(find "$SRC/vendor" -mindepth 1 -maxdepth 1 -type d | wc -l) crates, $(du -sh "$SRC/vendor" | cut -f1)"
    # -z1: the source tarball carries the vendored crates; the test needs it made, not small.
    (cd "$SRC" && CARGO_NET_OFFLINE=true dpkg-buildpackage -us -uc -z1) > "$log" 2>&1 || { tail -n 30 "$log"; return 1; }
    grep -E "dpkg-(shlibdeps|gencontrol|source): warning" "$log" | sed 's/^/    /'
    for p in "${PACKAGES[@]}"; do
        ls "$OUT/src/${p}_${VERSION}_"*.deb > /dev/null || return 1
    done
    ls -1 "$OUT"/src/*.deb "$OUT"/src/*.dsc | sed "s|^$OUT/src/|    |"
}
check "dpkg-buildpackage: source and ${PACKAGES[*]} $VERSION, offline from vendor/ (log $OUT/build.log)" build
if [ "$failed" -gt 0 ]; then
    echo "test-packages: $passed passed, $failed failed"
    exit 1
fi

lint() {
    local changes log=$OUT/lintian.log
    changes=$(ls "$OUT"/src/nlsubdiv_"$VERSION"_*.changes 2>/dev/null | head -1)
    [ -n "$changes" ] || return 1
    lintian --info --fail-on error,warning "$changes" > "$log" 2>&1
    local rc=$?
    if grep -qE "^[EWI]:" "$log"; then
        grep -E "^[EWI]:" "$log" | sort | uniq -c | sed 's/^/    /'
    else
        echo "    lintian: no error, warning or info tag"
    fi
    return $rc
}
check "lintian: no error and no warning (log $OUT/lintian.log)" lint

# ---- 2. install, use, remove ----
BEFORE=$OUT/dpkg-before.txt
dpkg-query -W -f='${Package} ${Version}\n' | sort > "$BEFORE"
purge() {
    local left
    left=$(installed "${PACKAGES[@]}")
    [ -z "$left" ] || DEBIAN_FRONTEND=noninteractive apt-get purge -y -qq $left > "$OUT/purge.log" 2>&1
}
trap purge EXIT

install_packages() {
    local debs=() p
    for p in "${PACKAGES[@]}"; do debs+=("$(ls "$OUT/src/${p}_${VERSION}_"*.deb)"); done
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${debs[@]}" > "$OUT/install.log" 2>&1 ||
        { tail -n 20 "$OUT/install.log"; return 1; }
    dpkg -L "${PACKAGES[@]}" | grep -E "\.so|\.a$|\.pc$|\.cmake$|bin/|man1|\.h$|\.hh$" | sed 's/^/    /'
}
check "apt-get install the three packages" install_packages

# A program's view: nothing points at the build tree.
unset LD_LIBRARY_PATH PKG_CONFIG_PATH CMAKE_PREFIX_PATH CPATH LIBRARY_PATH
W=$OUT/consumers
rm -rf "$W"; mkdir -p "$W"

uses_installed_library() { # uses_installed_library EXE...: each loads the package's library
    # (ld.so may name it /lib/MA/..., the same file when /lib links to usr/lib).
    local exe path
    for exe in "$@"; do
        path=$(ldd "$exe" | awk -v so="$SONAME" '$1 == so {print $3}')
        [ -n "$path" ] && [ "$(readlink -f "$path")" = "$(readlink -f "/usr/lib/$MA/$SONAME")" ] ||
            { echo "    $exe: $(ldd "$exe" | grep nlsubdiv || echo "no $SONAME")"; return 1; }
    done
}
pkgconfig_consumers() {
    local ex exe
    echo "    pkg-config --cflags --libs nlsubdiv: '$(pkg-config --cflags --libs nlsubdiv)'; nlsubdiv-static: '$(pkg-config --libs nlsubdiv-static)'; --static nlsubdiv: '$(pkg-config --static --libs nlsubdiv)'"
    [ "$(pkg-config --modversion nlsubdiv)" = "$VERSION" ] || return 1
    for ex in c_examples/*.c; do
        exe=$W/$(basename "$ex" .c)
        # shellcheck disable=SC2046
        gcc -std=c99 -Wall -Wextra -Wpedantic -Werror $(pkg-config --cflags nlsubdiv) "$ex" -o "$exe" $(pkg-config --libs nlsubdiv) -lm &&
            gcc -std=c99 $(pkg-config --cflags nlsubdiv-static) "$ex" -o "$exe.static" $(pkg-config --libs nlsubdiv-static) &&
            gcc -std=c99 -static $(pkg-config --cflags nlsubdiv) "$ex" -o "$exe.fullstatic" $(pkg-config --static --libs nlsubdiv) || return 1
        uses_installed_library "$exe" || return 1
        if readelf -d "$exe.static" | grep -q "libnlsubdiv"; then echo "    $exe.static needs the shared library"; return 1; fi
        if readelf -d "$exe.fullstatic" | grep -q NEEDED; then echo "    $exe.fullstatic is not static"; return 1; fi
        (cd "$W" && "$exe" > "$exe.out" && "$exe.static" > "$exe.static.out" && "$exe.fullstatic" > "$exe.fullstatic.out") ||
            { echo "    $ex failed"; return 1; }
        cmp -s "$exe.out" "$exe.static.out" && cmp -s "$exe.out" "$exe.fullstatic.out" || { echo "    $ex: outputs differ"; return 1; }
    done
    echo "    $(ls c_examples/*.c | wc -l) examples: shared (loads /usr/lib/$MA/$SONAME), nlsubdiv-static, gcc -static: same output"
}
check "C consumers via pkg-config: c_examples/*.c shared, nlsubdiv-static, --static" pkgconfig_consumers

cmake_consumer() { # cmake_consumer NAME [env...]: configures with the given PATH-like environment
    local b=$W/$1 log=$W/$1.log; shift
    env "$@" cmake -S integrations/cmake-consumer -B "$b" -DCMAKE_BUILD_TYPE=Release > "$log" 2>&1 &&
        cmake --build "$b" >> "$log" 2>&1 || { tail -n 20 "$log"; return 1; }
    grep "nlsubdiv $VERSION from" "$log" | sed 's/^ *-- /    /'
    uses_installed_library "$b/consumer" || return 1
    if readelf -d "$b/consumer" | grep -qE "RPATH|RUNPATH"; then echo "    $b/consumer has an rpath"; return 1; fi
    "$b/consumer" | sed 's/^/    /' && "$b/consumer_static" | sed 's/^/    /'
}
# Twice: CMake also derives prefixes from PATH, and with /bin first (merged /usr: /bin -> usr/bin)
# it finds the package under /lib/MA/cmake, a symbolic link.
check "CMake consumer: find_package(nlsubdiv) from the installed package" cmake_consumer cmake-consumer
check "CMake consumer, PATH=/bin first (package found through /lib -> usr/lib)" \
    cmake_consumer cmake-consumer-bin "PATH=/bin:/usr/bin:$PATH"

# The OpenMesh and CGAL tests of integrations/tests, against the installed headers (the
# nlsubdiv/openmesh and nlsubdiv/cgal folders of libnlsubdiv-dev), on six small meshes and the
# broken ones (all the meshes are the integrations step's).
MINI=$W/meshes
mkdir -p "$MINI"
for m in tetrahedron cube icosahedron house_pentagons torus_quad sphere_octahedron_perturbed; do
    [ -f "$MESHES/$m.off" ] && ln -sf "$MESHES/$m.off" "$MINI/"
done
[ -d "$MESHES/bad" ] && ln -sfn "$MESHES/bad" "$MINI/bad"  # 21 small broken meshes
[ -n "$(ls "$MINI")" ] || echo "    SKIP: $MESHES is absent: only the in-memory cases of the OpenMesh and CGAL tests run"
CXXFLAGS="-std=c++17 -O1 -Wall -Wextra -Wno-unused-parameter -Wno-maybe-uninitialized -ffp-contract=off"
build_cxx() { # build_cxx NAME LIBS...
    local name=$1; shift
    # shellcheck disable=SC2046,SC2086
    g++ $CXXFLAGS $(pkg-config --cflags nlsubdiv) "integrations/tests/$name.cpp" -o "$W/$name" "$@" > "$W/$name.build.log" 2>&1 ||
        { tail -n 20 "$W/$name.build.log"; return 1; }
}
run_cxx() {
    local log=$W/$1.log
    "$W/$1" "$MINI" > "$log" 2>&1
    local rc=$?
    grep -E "^FAIL|worst max_rel_dist|^$1:" "$log" | sed 's/^/    /'
    return $rc
}
build_both() { # the two in parallel (each about a minute of CGAL or OpenMesh templates)
    local p1 p2 r1 r2
    # shellcheck disable=SC2046
    build_cxx test_openmesh $(pkg-config --libs nlsubdiv) -lOpenMeshCore &
    p1=$!
    # shellcheck disable=SC2046
    build_cxx test_cgal $(pkg-config --libs nlsubdiv) -lgmp -lmpfr &
    p2=$!
    wait $p1; r1=$?; wait $p2; r2=$?
    [ "$r1" -eq 0 ] && [ "$r2" -eq 0 ] && uses_installed_library "$W/test_openmesh" "$W/test_cgal"
}
check "OpenMesh and CGAL tests built on the installed headers and library" build_both
check "OpenMesh consumer: integrations/tests/test_openmesh (log $W/test_openmesh.log)" run_cxx test_openmesh
check "CGAL consumer: integrations/tests/test_cgal (log $W/test_cgal.log)" run_cxx test_cgal

command_and_manual() {
    local v where warnings
    where=$(command -v nlsubdiv)
    v=$(/usr/bin/nlsubdiv --version) || return 1
    echo "    /usr/bin/nlsubdiv --version: $v (first on PATH: $where)"
    [ "$v" = "nlsubdiv $VERSION" ] || return 1
    dpkg -S /usr/bin/nlsubdiv | grep -q "^nlsubdiv:" || return 1
    /usr/bin/nlsubdiv demo --out "$W/demo" --levels 2 -q > "$W/demo.log" && [ -s "$W/demo/demo.png" ] || return 1
    echo "    man -w nlsubdiv: $(man -w nlsubdiv)"
    [ "$(man -w nlsubdiv)" = /usr/share/man/man1/nlsubdiv.1.gz ] || return 1
    warnings=$(MANWIDTH=80 man --warnings -E UTF-8 nlsubdiv 2>&1 >/dev/null)
    [ -z "$warnings" ] || { echo "    man nlsubdiv: $warnings"; return 1; }
    warnings=$(MANWIDTH=80 man --warnings -E UTF-8 -l /usr/share/man/man1/nlsubdiv.1.gz 2>&1 >/dev/null)
    [ -z "$warnings" ] || { echo "    man -l: $warnings"; return 1; }
    # Every command of --help has its section in the page.
    local c
    for c in $(/usr/bin/nlsubdiv --help | awk '/^Commands:/ {on=1; next} /^[^ ]/ {on=0} on && NF {print $1}' | grep -vx help); do
        MANWIDTH=200 man nlsubdiv 2>/dev/null | grep -q "^   nlsubdiv $c\$" || { echo "    man nlsubdiv: no section for '$c'"; return 1; }
    done
    echo "    man nlsubdiv: renders without warnings, a section for each command; demo: $(ls "$W/demo" | tr '\n' ' ')"
}
check "the command: nlsubdiv --version, demo, man nlsubdiv" command_and_manual

remove_packages() {
    purge || { tail -n 20 "$OUT/purge.log"; return 1; }
    dpkg-query -W -f='${Package} ${Version}\n' | sort > "$OUT/dpkg-after.txt"
    diff "$BEFORE" "$OUT/dpkg-after.txt" || return 1
    local f
    for f in /usr/include/nlsubdiv.h /usr/bin/nlsubdiv "/usr/lib/$MA/$SONAME" "/usr/lib/$MA/cmake/nlsubdiv"; do
        [ ! -e "$f" ] || { echo "    $f is left"; return 1; }
    done
    echo "    purged; the installed packages are those of the start ($(wc -l < "$BEFORE"))"
}
check "apt-get purge: the machine as it was" remove_packages
trap - EXIT

echo "test-packages: $((SECONDS-T0)) s"
echo "test-packages: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
