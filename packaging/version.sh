#!/bin/sh
# The version of nlsubdiv and the names derived from it, for the installers (scripts/install.sh,
# debian/rules, scripts/test-packages.sh):
#
#   packaging/version.sh version      0.2.0      [workspace.package] version of Cargo.toml
#   packaging/version.sh soversion    0.2        the ABI part of the shared library's name
#   packaging/version.sh soname       libnlsubdiv.so.0.2
#   packaging/version.sh libpackage   libnlsubdiv0.2   (Debian's name of the runtime package)
#
# Cargo.toml is the one source of the version. The ABI rule is Cargo's: before 1.0 every minor
# release (0.2 -> 0.3) may change the C ABI incompatibly, so the soname carries MAJOR.MINOR;
# from 1.0 on it carries MAJOR only. A program linked against libnlsubdiv.so.0.2 therefore never
# loads a 0.3 library whose signatures differ; patch releases (0.2.0 -> 0.2.1) keep the ABI.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
version=$(awk '
    /^\[/ { in_ws = ($0 == "[workspace.package]") }
    in_ws && /^version[ \t]*=/ { gsub(/^version[ \t]*=[ \t]*"|".*$/, ""); print; exit }
' "$root/Cargo.toml")
case $version in
    [0-9]*.[0-9]*.[0-9]*) ;;
    *) echo "packaging/version.sh: no [workspace.package] version in $root/Cargo.toml" >&2; exit 1 ;;
esac
major=${version%%.*}
rest=${version#*.}
minor=${rest%%.*}
if [ "$major" = 0 ]; then soversion=0.$minor; else soversion=$major; fi
case ${1:-version} in
    version) echo "$version" ;;
    soversion) echo "$soversion" ;;
    soname) echo "libnlsubdiv.so.$soversion" ;;
    libpackage) echo "libnlsubdiv$soversion" ;;
    *) echo "usage: $0 [version|soversion|soname|libpackage]" >&2; exit 1 ;;
esac
