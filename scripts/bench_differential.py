#!/usr/bin/env python3
"""Side-by-side benchmark of the differential-space reconstruction (seed 001 Table 1 layout).

One run: `cargo run --release --example differential_bench` times the stages (compute
Delta, subdivide, reconstruct) at 3 levels on fertility and rocker_arm and exports each
reconstruction system; `benches/eigen_ldlt.cpp` (Eigen SimplicialLDLT, libeigen3-dev) then
solves the same system, and the table prints both.

Usage: python3 scripts/bench_differential.py [MESH_DIR]
"""
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TARGET = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
OUT = os.path.join(TARGET, "bench_differential")


def main():
    mesh_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "..", "shared", "data", "meshes")
    os.makedirs(OUT, exist_ok=True)
    exe = os.path.join(OUT, "eigen_ldlt")
    subprocess.run(["g++", "-O2", "-DNDEBUG", "-I/usr/include/eigen3",
                    os.path.join(ROOT, "benches", "eigen_ldlt.cpp"), "-o", exe], check=True)
    r = subprocess.run(["cargo", "run", "--release", "--locked", "--quiet", "--example",
                        "differential_bench", "--", OUT, mesh_dir],
                       cwd=ROOT, check=True, capture_output=True, text=True)
    sys.stdout.write(r.stdout)
    rows = []
    for line in r.stdout.splitlines():
        if not line.startswith("TABLE "):
            continue
        _, name, n0, nk, td, ts, tr, tt, it, res = line.split()
        e = subprocess.run([exe, os.path.join(OUT, name + ".sys")], check=True,
                           capture_output=True, text=True).stdout
        sys.stdout.write(e)
        kv = dict(re.findall(r"(\w+(?:\(\w\))?)=(\S+)", e))
        rows.append((name, n0, nk, td, ts, tr, tt, it, res, kv))
    print()
    print("| mesh | V0 → V3 | Δ (s) | subdivide (s) | reconstruct (s) | total (s) | CG it. | "
          "residual | Eigen LDLT analyze+factorize+solve (s) | Eigen residual | "
          "max |ours − Eigen| / diag |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for name, n0, nk, td, ts, tr, tt, it, res, kv in rows:
        print(f"| {name} | {n0} → {nk} | {td} | {2 * float(ts):.3f} | {tr} | {tt} | {it} | {res} | "
              f"{kv.get('ldlt_total')} (+{kv.get('form')} forming N) | {kv.get('residual')} | "
              f"{kv.get('max_diff_over_diag')} |")


if __name__ == "__main__":
    main()
