#!/usr/bin/env python3
"""Side-by-side benchmark of the differential-space reconstruction (seed 001 Table 1 layout).

One run: `cargo run --release --example differential_bench` times the stages (compute
Delta, subdivide, reconstruct) at 3 levels on fertility and rocker_arm and exports each
reconstruction system; `benches/direct_solvers.cpp` then solves the same system with CHOLMOD's
supernodal Cholesky (libsuitesparse-dev) and, as the accuracy reference, by sparse QR of the
least-squares system (SuiteSparseQR), single-threaded; the table prints all three.

Usage: python3 scripts/bench_differential.py [MESH_DIR] [--no-qr]
"""
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TARGET = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
OUT = os.path.join(TARGET, "bench_differential")


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    mesh_dir = args[0] if args else os.path.join(ROOT, "..", "shared", "data", "meshes")
    os.makedirs(OUT, exist_ok=True)
    exe = os.path.join(OUT, "direct_solvers")
    subprocess.run(["g++", "-O2", "-DNDEBUG", "-I/usr/include/eigen3", "-I/usr/include/suitesparse",
                    os.path.join(ROOT, "benches", "direct_solvers.cpp"), "-lcholmod", "-lspqr",
                    "-o", exe], check=True)
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    extra = ["--no-qr"] if "--no-qr" in sys.argv else []
    r = subprocess.run(["cargo", "run", "--release", "--locked", "--quiet", "--example",
                        "differential_bench", "--", OUT, mesh_dir],
                       cwd=ROOT, check=True, capture_output=True, text=True)
    sys.stdout.write(r.stdout)
    rows = []
    for line in r.stdout.splitlines():
        if not line.startswith("TABLE "):
            continue
        _, name, n0, nk, td, ts, tr, tt, it, res = line.split()
        e = subprocess.run([exe, os.path.join(OUT, name + ".sys")] + extra, check=True,
                           capture_output=True, text=True, env=env).stdout
        sys.stdout.write(e)
        kv = dict(re.findall(r"(\w+(?:\(\w\))?)=(\S+)", e))
        rows.append((name, n0, nk, td, ts, tr, tt, it, res, kv))
    print()
    print("| mesh | V0 → V3 | Δ (s) | subdivide (s) | reconstruct (s) | total (s) | CG it. | "
          "residual | CHOLMOD analyse+factorise+solve (s) | CHOLMOD residual | "
          "ours − QR / diag | CHOLMOD − QR / diag | QR (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, n0, nk, td, ts, tr, tt, it, res, kv in rows:
        print(f"| {name} | {n0} → {nk} | {td} | {2 * float(ts):.3f} | {tr} | {tt} | {it} | {res} | "
              f"{kv.get('cholmod_total')} (+{kv.get('form')} forming N) | {kv.get('cholmod_residual')} | "
              f"{kv.get('ours_vs_qr', '—')} | {kv.get('cholmod_vs_qr', '—')} | {kv.get('qr_total', '—')} |")


if __name__ == "__main__":
    main()
