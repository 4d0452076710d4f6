#!/usr/bin/env python3
"""Side-by-side timings in one run, single-threaded: our linear and Möbius schemes and the
peers' linear schemes on the rows of DESIGN.md "Performance" (best of 3 runs each, or of
BENCH_REPS; the time of the subdivision itself, excluding file I/O: for the peers, building
their mesh, subdividing and reading it back; for ours, one multi-level call with its buffers:
validation, topology and every level).

  scripts/bench_peers.py PEER_BIN OURS_BIN [MESH_DIR]

Prints two markdown tables: times (the ratio column is (fastest peer) / (ours, linear)), and
peak memory: the maximum resident set of each process (/usr/bin/time -v; it includes reading
the input and streaming the output OFF, in both harnesses), and for ours the exact bytes the
kernel touches, output buffers + the scratch of the plan (from subdivide_off's stderr).
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


# Runs per cell (best of); BENCH_REPS raises it on a loaded machine, where the minimum of
# more runs is nearer the unloaded time.
REPS = int(os.environ.get("BENCH_REPS", "3"))


def timed(cmd):
    """(best time_ms of REPS runs, max RSS in MB of the best run, stderr of the best run)."""
    best = None
    for _ in range(REPS):
        r = subprocess.run(["/usr/bin/time", "-v"] + cmd, capture_output=True, text=True)
        if r.returncode != 0:
            return None
        m = re.search(r"time_ms=([0-9.]+)", r.stderr)
        rss = re.search(r"Maximum resident set size \(kbytes\): ([0-9]+)", r.stderr)
        if m:
            t = float(m.group(1))
            if best is None or t < best[0]:
                best = (t, int(rss.group(1)) / 1024 if rss else None, r.stderr)
    return best


def main():
    peer_bin, ours_bin = sys.argv[1], sys.argv[2]
    here = os.path.dirname(os.path.abspath(__file__))
    mesh_dir = sys.argv[3] if len(sys.argv) > 3 else os.path.join(here, "..", "..", "shared", "data", "meshes")
    out = os.path.join(tempfile.mkdtemp(), "o.off")
    print("| mesh | scheme | levels | OpenMesh ms | CGAL ms | OpenSubdiv ms | ours ms | ours Möbius ms | fastest peer / ours | Möbius / ours |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    mem = []
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
        t = lambda c: None if c is None else c[0]
        fastest = min([t(c) for c in cells.values() if c is not None], default=None)
        fmt = lambda v: "—" if v is None else f"{v:.1f}"
        ratio = "—" if fastest is None or not ours else f"{fastest / t(ours):.2f}"
        mratio = "—" if not mob or not ours else f"{t(mob) / t(ours):.2f}"
        print(f"| {name} | {scheme} | {levels} | {fmt(t(cells['openmesh']))} | {fmt(t(cells['cgal']))} | {fmt(t(cells['osd']))} | {fmt(t(ours))} | {fmt(t(mob))} | {ratio} | {mratio} |")
        kernel = "—"
        if ours:
            o = re.search(r"output_bytes=([0-9]+) scratch_bytes=([0-9]+)", ours[2])
            if o:
                ob, sb = int(o.group(1)) / 2**20, int(o.group(2)) / 2**20
                kernel = f"{ob:.1f} + {sb:.1f}"
        r = lambda c: "—" if c is None or c[1] is None else f"{c[1]:.1f}"
        mem.append(f"| {name} | {scheme} | {levels} | {r(cells['openmesh'])} | {r(cells['cgal'])} | {r(cells['osd'])} | {r(ours)} | {r(mob)} | {kernel} |")
    print()
    print("| mesh | scheme | levels | OpenMesh max RSS MB | CGAL MB | OpenSubdiv MB | ours MB | ours Möbius MB | ours kernel MB: output + scratch |")
    print("|---|---|---|---|---|---|---|---|---|")
    for line in mem:
        print(line)


if __name__ == "__main__":
    sys.exit(main())
