#!/usr/bin/env python3
"""Checks that the C header states each export's stack ceiling on Cortex-M4F.

Every export that the firmware harness measures (the entry points of
firmware/stack-static-bounds.txt) carries in its documentation in include/nlsubdiv.h the line

    Stack on Cortex-M4F: at most N bytes (`docs/firmware.md`, "Stack").

where N is the largest ceiling of the static stack bound among the entry points that call the
export (scripts/test-firmware.sh checks those ceilings against the static bound and the painted
marks of the same run). Exit status 1, with the export named, when a line is missing or its N
differs; --write prints the expected line of every export instead.

    firmware/header_stack.py [--bounds firmware/stack-static-bounds.txt] [--header include/nlsubdiv.h]
"""
import argparse
import re
import sys

# Harness entry point -> the exports it calls (an entry point not listed here is an export of
# its own name).
GROUPS = [
    (re.compile(r"^mesh .* tagged \((linear|Möbius)\)$"), ["nls_mesh_subdivide_tagged"]),
    (re.compile(r"^mesh "), ["nls_mesh_subdivide"]),
    (re.compile(r"^star rules$"),
     ["nls_mobius_loop_star", "nls_mobius_catmull_clark_star", "nls_mobius_butterfly_star"]),
    (re.compile(r"^differential subdivide$"), ["nls_differential_subdivide"]),
    (re.compile(r"^curve subdivide$"), ["nls_curve_subdivide"]),
]

LINE = re.compile(r"Stack on Cortex-M4F: at most ([0-9,]+) bytes")


def exports_of(entry):
    for pattern, exports in GROUPS:
        if pattern.search(entry):
            return exports
    return [entry]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bounds", default="firmware/stack-static-bounds.txt")
    ap.add_argument("--header", default="include/nlsubdiv.h")
    ap.add_argument("--write", action="store_true", help="print the expected line of every export")
    args = ap.parse_args()

    want = {}
    for line in open(args.bounds, encoding="utf-8"):
        if line.startswith("#") or "\t" not in line:
            continue
        entry, ceiling = line.rstrip("\n").split("\t")
        if not ceiling.isdigit():
            continue  # UNKNOWN: no figure to state
        for export in exports_of(entry):
            want[export] = max(want.get(export, 0), int(ceiling))
    if args.write:
        for export, n in sorted(want.items()):
            print(f"{export}: Stack on Cortex-M4F: at most {n:,} bytes")
        return 0

    text = open(args.header, encoding="utf-8").read()
    problems = []
    for export, n in sorted(want.items()):
        # The declaration and the documentation comment right above it.
        m = re.search(r"/\*\*((?:(?!\*/).)*)\*/\s*(?:[A-Za-z_][\w \*]*?)\b" + re.escape(export) + r"\(",
                      text, re.S)
        if not m:
            problems.append(f"{export}: no documented declaration in {args.header}")
            continue
        found = LINE.findall(m.group(1))
        if not found:
            problems.append(f"{export}: no 'Stack on Cortex-M4F: at most {n:,} bytes' line")
        elif int(found[-1].replace(",", "")) != n:
            problems.append(f"{export}: the header says {found[-1]} bytes, the ceiling is {n:,}")
    for p in problems:
        print(f"header_stack: {p}")
    print(f"header_stack: {len(want) - len(problems)} of {len(want)} exports state their stack ceiling")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
