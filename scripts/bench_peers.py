#!/usr/bin/env python3
"""Side-by-side timings in one run, single-threaded: our linear and Möbius schemes and the
peers' linear schemes on the rows of DESIGN.md "Performance" (best of 3 runs each; the time
of the subdivision itself, excluding file I/O: for the peers, building their mesh,
subdividing and reading it back; for ours, validation, topology and every level).

  scripts/bench_peers.py PEER_BIN OURS_BIN [MESH_DIR]

Prints a markdown table; the ratio column is (fastest peer) / (ours, linear).
"""
import os
import re
import subprocess
import sys
import tempfile

ROWS = [
    ("epcot.off", "loop", 4, ["openmesh", "cgal", "osd"]),
    ("epcot.off", "butterfly", 4, ["openmesh"]),
    ("cube.off", "catmull-clark", 8, ["openmesh", "cgal", "osd"]),
    ("spot_quad.off", "catmull-clark", 3, ["openmesh", "cgal", "osd"]),
    ("cube.off", "doo-sabin", 8, ["cgal"]),
    ("spot_quad.off", "kobbelt", 3, []),
]


def timed(cmd):
    best = None
    for _ in range(3):
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            return None
        m = re.search(r"time_ms=([0-9.]+)", r.stderr)
        if m:
            t = float(m.group(1))
            best = t if best is None else min(best, t)
    return best


def main():
    peer_bin, ours_bin = sys.argv[1], sys.argv[2]
    here = os.path.dirname(os.path.abspath(__file__))
    mesh_dir = sys.argv[3] if len(sys.argv) > 3 else os.path.join(here, "..", "..", "shared", "data", "meshes")
    out = os.path.join(tempfile.mkdtemp(), "o.off")
    print("| mesh | scheme | levels | OpenMesh ms | CGAL ms | OpenSubdiv ms | ours ms | ours Möbius ms | fastest peer / ours | Möbius / ours |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, scheme, levels, peers in ROWS:
        src = os.path.join(mesh_dir, name)
        if not os.path.exists(src):
            print(f"| {name} | {scheme} | {levels} | SKIP: not found |")
            continue
        cells = {}
        for lib in ["openmesh", "cgal", "osd"]:
            cells[lib] = timed([peer_bin, lib, scheme, str(levels), src, out]) if lib in peers else None
        ours = timed([ours_bin, scheme, str(levels), src, out])
        mob = timed([ours_bin, scheme, str(levels), src, out, "--mobius"])
        fastest = min([t for t in cells.values() if t is not None], default=None)
        fmt = lambda t: "—" if t is None else f"{t:.1f}"
        ratio = "—" if fastest is None or not ours else f"{fastest / ours:.2f}"
        mratio = "—" if not mob or not ours else f"{mob / ours:.2f}"
        print(f"| {name} | {scheme} | {levels} | {fmt(cells['openmesh'])} | {fmt(cells['cgal'])} | {fmt(cells['osd'])} | {fmt(ours)} | {fmt(mob)} | {ratio} | {mratio} |")


if __name__ == "__main__":
    sys.exit(main())
