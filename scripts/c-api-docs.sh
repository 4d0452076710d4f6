#!/usr/bin/env bash
# The C API reference: HTML from include/nlsubdiv.h by Doxygen (docs/Doxyfile).
#
#   scripts/c-api-docs.sh [OUTDIR]      (default target/c-api)
#
#   OUTDIR/html/index.html      the reference (start with Files -> nlsubdiv.h)
#   OUTDIR/warnings.log         Doxygen's warnings: undocumented or misrendered parts
#
# Needs doxygen (Debian: apt-get install doxygen). Prints the number of warnings; exits 1
# only when Doxygen fails, since the warnings concern the header's comments, not the API.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v doxygen >/dev/null || { echo "c-api-docs: doxygen is not installed (apt-get install doxygen)" >&2; exit 1; }
OUT=${1:-target/c-api}
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
rm -rf "$OUT/html" "$OUT/warnings.log"
NLS_VERSION=$(packaging/version.sh version) NLS_DOC_OUT=$OUT doxygen docs/Doxyfile
[ -f "$OUT/html/index.html" ] || { echo "c-api-docs: no $OUT/html/index.html" >&2; exit 1; }
echo "c-api-docs: $OUT/html/index.html, the header at $OUT/html/nlsubdiv_8h.html ($(doxygen --version)); $(grep -c 'warning:' "$OUT/warnings.log" || true) warnings in $OUT/warnings.log"
