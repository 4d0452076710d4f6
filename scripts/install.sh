#!/usr/bin/env bash
# Installs nlsubdiv for C and C++ users into PREFIX:
#
#   scripts/install.sh PREFIX
#
#   PREFIX/include/nlsubdiv.h                       the C ABI (C99 and C++)
#   PREFIX/include/nlsubdiv/openmesh/*.hh           header-only OpenMesh subdividers
#   PREFIX/include/nlsubdiv/cgal/*.h                header-only CGAL masks and functions
#   PREFIX/lib/libnlsubdiv.a                        static library (no native dependencies)
#   PREFIX/lib/libnlsubdiv.so.X.Y.Z, .so.X, .so     shared library, SONAME libnlsubdiv.so.X
#   PREFIX/lib/pkgconfig/nlsubdiv.pc                pkg-config --cflags --libs nlsubdiv
#   PREFIX/lib/cmake/nlsubdiv/                      find_package(nlsubdiv CONFIG REQUIRED)
#
# The libraries are built with cargo into target/install-build (the soname is a link argument
# of that build only, so the target/release artifacts the test suites use are unchanged).
# Environment: NLS_INSTALL_LIBDIR (default lib).
set -euo pipefail
if [[ $# -ne 1 || "$1" == -* ]]; then
    echo "usage: $0 PREFIX" >&2
    exit 1
fi
cd "$(dirname "$0")/.."
ROOT=$PWD
mkdir -p "$1"
PREFIX=$(cd "$1" && pwd)
LIBDIR=${NLS_INSTALL_LIBDIR:-lib}
VERSION=$(sed -n 's/^#define NLS_VERSION_STRING "\(.*\)"/\1/p' include/nlsubdiv.h)
MAJOR=${VERSION%%.*}
[[ -n "$VERSION" ]] || { echo "install.sh: no NLS_VERSION_STRING in include/nlsubdiv.h" >&2; exit 1; }

build=target/install-build
cargo rustc -q --release --locked -p nlsubdiv-ffi --target-dir "$build" -- \
    -C link-arg=-Wl,-soname,libnlsubdiv.so.$MAJOR
lib="$build/release"

install -d "$PREFIX/include/nlsubdiv/openmesh" "$PREFIX/include/nlsubdiv/cgal" \
    "$PREFIX/$LIBDIR/pkgconfig" "$PREFIX/$LIBDIR/cmake/nlsubdiv"
install -p -m 644 include/nlsubdiv.h "$PREFIX/include/"
for f in integrations/openmesh/*.hh; do [[ -f $f ]] && install -p -m 644 "$f" "$PREFIX/include/nlsubdiv/openmesh/"; done
install -d "$PREFIX/include/nlsubdiv/common"
install -p -m 644 integrations/common/nlsubdiv_flat.hh "$PREFIX/include/nlsubdiv/common/"
for f in integrations/cgal/*.h; do [[ -f $f ]] && install -p -m 644 "$f" "$PREFIX/include/nlsubdiv/cgal/"; done
install -p -m 644 "$lib/libnlsubdiv.a" "$PREFIX/$LIBDIR/"
install -p -m 755 "$lib/libnlsubdiv.so" "$PREFIX/$LIBDIR/libnlsubdiv.so.$VERSION"
ln -sf "libnlsubdiv.so.$VERSION" "$PREFIX/$LIBDIR/libnlsubdiv.so.$MAJOR"
ln -sf "libnlsubdiv.so.$MAJOR" "$PREFIX/$LIBDIR/libnlsubdiv.so"

subst() { sed -e "s|@PREFIX@|$PREFIX|g" -e "s|@LIBDIR@|$LIBDIR|g" -e "s|@VERSION@|$VERSION|g" -e "s|@MAJOR@|$MAJOR|g" "$1" > "$2"; }
subst packaging/nlsubdiv.pc.in "$PREFIX/$LIBDIR/pkgconfig/nlsubdiv.pc"
subst packaging/nlsubdiv-static.pc.in "$PREFIX/$LIBDIR/pkgconfig/nlsubdiv-static.pc"
subst packaging/nlsubdivConfig.cmake.in "$PREFIX/$LIBDIR/cmake/nlsubdiv/nlsubdivConfig.cmake"
subst packaging/nlsubdivConfigVersion.cmake.in "$PREFIX/$LIBDIR/cmake/nlsubdiv/nlsubdivConfigVersion.cmake"

soname=$(readelf -d "$PREFIX/$LIBDIR/libnlsubdiv.so.$VERSION" 2>/dev/null | sed -n 's/.*SONAME.*\[\(.*\)\]/\1/p')
echo "install.sh: nlsubdiv $VERSION installed in $PREFIX (soname ${soname:-?})"
