#!/usr/bin/env bash
# Installs nlsubdiv (the C library for C and C++ users, and the command) into PREFIX:
#
#   scripts/install.sh PREFIX
#   DESTDIR=STAGE scripts/install.sh /usr      # packagers: files under STAGE/usr, paths say /usr
#
#   PREFIX/bin/nlsubdiv                              the command
#   PREFIX/share/man/man1/nlsubdiv.1                 its manual page
#   PREFIX/include/nlsubdiv.h                        the C ABI (C99 and C++)
#   PREFIX/include/nlsubdiv_pool.h                   a header-only POSIX-threads pool for it
#   PREFIX/include/nlsubdiv/openmesh/*.hh            header-only OpenMesh subdividers
#   PREFIX/include/nlsubdiv/cgal/*.h                 header-only CGAL masks and functions
#   PREFIX/include/nlsubdiv/common/*.hh              what both of them share
#   PREFIX/LIBDIR/libnlsubdiv.a                      static library (no native dependencies)
#   PREFIX/LIBDIR/libnlsubdiv.so.X.Y.Z               shared library, SONAME libnlsubdiv.so.S,
#   PREFIX/LIBDIR/libnlsubdiv.so.S -> .so.X.Y.Z        S = X.Y before 1.0, X from 1.0 on
#   PREFIX/LIBDIR/libnlsubdiv.so -> .so.S              (packaging/version.sh says why)
#   PREFIX/LIBDIR/pkgconfig/nlsubdiv.pc              pkg-config --cflags --libs nlsubdiv
#   PREFIX/LIBDIR/pkgconfig/nlsubdiv-static.pc       the same with libnlsubdiv.a
#   PREFIX/LIBDIR/cmake/nlsubdiv/                    find_package(nlsubdiv CONFIG REQUIRED)
#
# The version is Cargo.toml's (packaging/version.sh). The files are built by packaging/build.sh
# into target/install-build. The CMake package finds the prefix from its own location (the
# installed tree can be moved); the pkg-config files name PREFIX.
# Environment: NLS_INSTALL_LIBDIR (default lib; Debian's multiarch layout is
# lib/$(dpkg-architecture -qDEB_HOST_MULTIARCH)), DESTDIR (default empty).
set -euo pipefail
if [[ $# -ne 1 || "$1" == -* ]]; then
    echo "usage: $0 PREFIX    (environment: NLS_INSTALL_LIBDIR, DESTDIR)" >&2
    exit 1
fi
cd "$(dirname "$0")/.."
DESTDIR=${DESTDIR:-}
if [[ -n "$DESTDIR" ]]; then
    [[ "$1" == /* ]] || { echo "install.sh: with DESTDIR, PREFIX must be absolute" >&2; exit 1; }
    PREFIX=${1%/}
    mkdir -p "$DESTDIR"
    DESTDIR=$(cd "$DESTDIR" && pwd)
else
    mkdir -p "$1"
    PREFIX=$(cd "$1" && pwd)
fi
LIBDIR=${NLS_INSTALL_LIBDIR:-lib}
LIBDIR=${LIBDIR%/}
if [[ "$LIBDIR" == /* || "$LIBDIR" == *..* || -z "$LIBDIR" ]]; then
    echo "install.sh: NLS_INSTALL_LIBDIR must be a relative path below PREFIX (e.g. lib or lib/x86_64-linux-gnu)" >&2
    exit 1
fi
VERSION=$(packaging/version.sh version)
SOVERSION=$(packaging/version.sh soversion)
SONAME=$(packaging/version.sh soname)

build=target/install-build
packaging/build.sh "$build"
rel="$build/release"

D=$DESTDIR$PREFIX
install -d "$D/bin" "$D/share/man/man1" "$D/include/nlsubdiv/openmesh" "$D/include/nlsubdiv/cgal" \
    "$D/include/nlsubdiv/common" "$D/$LIBDIR/pkgconfig" "$D/$LIBDIR/cmake/nlsubdiv"
install -p -m 755 "$rel/nlsubdiv" "$D/bin/"
install -p -m 644 "$rel/nlsubdiv.1" "$D/share/man/man1/"
install -p -m 644 include/nlsubdiv.h include/nlsubdiv_pool.h "$D/include/"
install -p -m 644 integrations/openmesh/*.hh "$D/include/nlsubdiv/openmesh/"
install -p -m 644 integrations/cgal/*.h "$D/include/nlsubdiv/cgal/"
install -p -m 644 integrations/common/*.hh "$D/include/nlsubdiv/common/"
install -p -m 644 "$rel/libnlsubdiv.a" "$D/$LIBDIR/"
install -p -m 644 "$rel/libnlsubdiv.so" "$D/$LIBDIR/libnlsubdiv.so.$VERSION"
ln -sfn "libnlsubdiv.so.$VERSION" "$D/$LIBDIR/$SONAME"
ln -sfn "$SONAME" "$D/$LIBDIR/libnlsubdiv.so"

# The CMake package lives in LIBDIR/cmake/nlsubdiv: as many ".." as that path has components
# lead back to the prefix (3 for lib, 4 for lib/x86_64-linux-gnu).
depth=$(($(tr -cd / <<<"$LIBDIR" | wc -c) + 3))
up=$(printf '/..%.0s' $(seq "$depth")); up=${up#/}
subst() {
    sed -e "s|@PREFIX@|$PREFIX|g" -e "s|@LIBDIR@|$LIBDIR|g" -e "s|@VERSION@|$VERSION|g" \
        -e "s|@SOVERSION@|$SOVERSION|g" -e "s|@SONAME@|$SONAME|g" -e "s|@PREFIX_FROM_CMAKEDIR@|$up|g" "$1" > "$2"
    chmod 644 "$2"
}
subst packaging/nlsubdiv.pc.in "$D/$LIBDIR/pkgconfig/nlsubdiv.pc"
subst packaging/nlsubdiv-static.pc.in "$D/$LIBDIR/pkgconfig/nlsubdiv-static.pc"
subst packaging/nlsubdivConfig.cmake.in "$D/$LIBDIR/cmake/nlsubdiv/nlsubdivConfig.cmake"
subst packaging/nlsubdivConfigVersion.cmake.in "$D/$LIBDIR/cmake/nlsubdiv/nlsubdivConfigVersion.cmake"

soname=$(readelf -d "$D/$LIBDIR/libnlsubdiv.so.$VERSION" | sed -n 's/.*SONAME.*\[\(.*\)\]/\1/p')
[[ "$soname" == "$SONAME" ]] || { echo "install.sh: the library's soname is '$soname', not $SONAME" >&2; exit 1; }
echo "install.sh: nlsubdiv $VERSION installed in $DESTDIR$PREFIX (libdir $LIBDIR, soname $soname)"
