#!/usr/bin/env python3
"""Side by side in one interleaved run: the peers' linear schemes (single-threaded), our
linear and Möbius schemes on one thread, and our Möbius schemes on BENCH_THREADS threads
(default 2), on the benchmark rows (README "Performance").

  scripts/bench_peers.py PEER_BIN OURS_BIN [MESH_DIR]

OURS_BIN is `target/release/examples/subdivide_off`; the multi-thread column runs
`subdivide_off_threads` from the same directory (`cargo build --release -p
nlsubdiv-threads --example subdivide_off_threads`) and is left out, said so, when it is
missing.

Interleaved: each repetition runs every cell of a row once, in turn (A B C A B C ...), and a
cell's figure is its best of BENCH_REPS (default 3) repetitions, so that load that comes and
goes hits every cell alike. What is timed, excluding file I/O: for the peers, building their
mesh, subdividing and reading it back; for ours, one multi-level call as a host makes it in a
fresh process (plan, buffers, validation, topology and every level: the "cold" figure).

Prints three markdown tables:
1. times, with the ratios (fastest peer) / (ours linear) and (ours Möbius on the threads) /
   (fastest peer);
2. ours cold against warm: the warm figure is the best of 3 further calls in the same
   process into the same, already touched, buffers (`--repeat 3`: no page faults, caches
   warm; what a host that subdivides again and again sees);
3. peak memory: each process's maximum resident set (/usr/bin/time -v; both harnesses read
   the input and stream the output OFF) and, for ours, the exact bytes the kernel touches
   (output buffers + the plan's scratch, from subdivide_off's stderr), linear and Möbius.
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
PEERS = ["openmesh", "cgal", "osd"]

REPS = int(os.environ.get("BENCH_REPS", "3"))
THREADS = int(os.environ.get("BENCH_THREADS", "2"))


def once(cmd):
    """(time_ms, max RSS MB, warm_ms or None, stderr) of one run, or None when it failed."""
    r = subprocess.run(["/usr/bin/time", "-v"] + cmd, capture_output=True, text=True)
    m = re.search(r"time_ms=([0-9.]+)", r.stderr)
    if r.returncode != 0 or not m:
        return None
    rss = re.search(r"Maximum resident set size \(kbytes\): ([0-9]+)", r.stderr)
    warm = re.search(r"warm_ms=([0-9.]+)", r.stderr)
    return (float(m.group(1)), int(rss.group(1)) / 1024 if rss else None,
            float(warm.group(1)) if warm else None, r.stderr)


def best(a, b):
    """The faster of two runs; the warm figure is the best over both."""
    if a is None or b is None:
        return a or b
    fast = a if a[0] <= b[0] else b
    warms = [w for w in (a[2], b[2]) if w is not None]
    return (fast[0], fast[1], min(warms) if warms else None, fast[3])


def main():
    peer_bin, ours_bin = sys.argv[1], sys.argv[2]
    threads_bin = os.path.join(os.path.dirname(ours_bin), "subdivide_off_threads")
    have_threads = os.path.exists(threads_bin)
    here = os.path.dirname(os.path.abspath(__file__))
    mesh_dir = sys.argv[3] if len(sys.argv) > 3 else os.path.join(here, "..", "..", "shared", "data", "meshes")
    out = os.path.join(tempfile.mkdtemp(), "o.off")
    t_col = f"ours Möbius {THREADS} threads ms" if have_threads else "ours Möbius, threads: SKIP (no subdivide_off_threads)"
    times = [f"| mesh | scheme | levels | OpenMesh ms | CGAL ms | OpenSubdiv ms | ours ms | ours Möbius ms | {t_col} | fastest peer / ours | Möbius {THREADS} threads / fastest peer |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    warm = ["| mesh | scheme | levels | ours cold ms | ours warm ms | ours Möbius cold ms | ours Möbius warm ms |",
            "|---|---|---|---|---|---|---|"]
    mem = [f"| mesh | scheme | levels | OpenMesh max RSS MB | CGAL MB | OpenSubdiv MB | ours MB | ours Möbius MB | ours Möbius {THREADS} threads MB | ours kernel MB: output + scratch | ours Möbius kernel MB |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, scheme, levels, peers in ROWS:
        src = os.path.join(mesh_dir, name)
        if not os.path.exists(src):
            times.append(f"| {name} | {scheme} | {levels} | SKIP: {src} not found |")
            continue
        cells = {lib: [peer_bin, lib, scheme, str(levels), src, out] for lib in peers}
        cells["ours"] = [ours_bin, scheme, str(levels), src, out, "--repeat", "3"]
        cells["mob"] = [ours_bin, scheme, str(levels), src, out, "--mobius", "--repeat", "3"]
        if have_threads:
            cells["mobt"] = [threads_bin, scheme, str(levels), src, out, "--mobius", "--threads", str(THREADS)]
        res = {k: None for k in cells}
        failed = set()
        for _ in range(REPS):
            for k, cmd in cells.items():
                if k in failed:
                    continue
                r = once(cmd)
                if r is None:
                    failed.add(k)
                    res[k] = None
                else:
                    res[k] = best(res[k], r)
        t = lambda k: None if res.get(k) is None else res[k][0]
        fmt = lambda v: "—" if v is None else f"{v:.1f}"
        fastest = min([t(p) for p in peers if t(p) is not None], default=None)
        ratio = "—" if fastest is None or not t("ours") else f"{fastest / t('ours'):.2f}"
        tratio = "—" if fastest is None or not t("mobt") else f"{t('mobt') / fastest:.2f}"
        peer_cells = " | ".join(fmt(t(p)) for p in PEERS)
        times.append(f"| {name} | {scheme} | {levels} | {peer_cells} | {fmt(t('ours'))} | {fmt(t('mob'))} | {fmt(t('mobt'))} | {ratio} | {tratio} |")
        w = lambda k: "—" if res.get(k) is None else fmt(res[k][2])
        warm.append(f"| {name} | {scheme} | {levels} | {fmt(t('ours'))} | {w('ours')} | {fmt(t('mob'))} | {w('mob')} |")
        def kernel(k):
            o = res[k] and re.search(r"output_bytes=([0-9]+) scratch_bytes=([0-9]+)", res[k][3])
            return f"{int(o.group(1)) / 2**20:.1f} + {int(o.group(2)) / 2**20:.1f}" if o else "—"
        r = lambda k: "—" if res.get(k) is None or res[k][1] is None else f"{res[k][1]:.1f}"
        mem.append(f"| {name} | {scheme} | {levels} | {' | '.join(r(p) for p in PEERS)} | {r('ours')} | {r('mob')} | {r('mobt')} | {kernel('ours')} | {kernel('mob')} |")
    print(f"Best of {REPS}, interleaved; load average before: {os.getloadavg()[0]:.2f}")
    print("\n".join(times))
    print()
    print("\n".join(warm))
    print()
    print("\n".join(mem))
    print(f"\nload average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    sys.exit(main())
