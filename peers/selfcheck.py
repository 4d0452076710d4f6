#!/usr/bin/env python3
"""Cross-check of the peer libraries against each other (driver of selfcheck.sh).

    selfcheck.py --bin PEER_SUBDIVIDE [--meshes DIR] [--jobs N] [--tol T]
                 [--level2-max-faces N] [--no-bad] OUTDIR

For every mesh DIR/*.off at levels 1 and 2 it runs, through peer_subdivide:

* Loop on OpenMesh, CGAL and OpenSubdiv, compared pairwise (must agree);
* Catmull-Clark on CGAL and OpenSubdiv (must agree), and OpenMesh against
  both on closed meshes (must agree); on meshes with boundary the OpenMesh
  rows are informational (its boundary rule is 2/3, 1/6, see README.md);
* sqrt3 on OpenMesh and CGAL (must agree);
* Butterfly (OpenMesh only) and Doo-Sabin (CGAL only), single-peer rows.

"Agree" means compare_off: max_rel_dist <= tol and identical face sets. Every
output is also checked against the element counts the scheme must produce
(e.g. Loop V' = V + E, F' = 4F), computed from the level below. A pair is
skipped when a peer rejects the mesh (reason shown). A peer that crashes
(killed by a signal or an unexpected exit code) is a failure. The bad/ folder
is swept for crashes at level 1 with every library and scheme.

Prints the table, the per-library run times and a final line "N passed, M
failed". Exit status 0 when nothing failed. Outputs and logs go to OUTDIR.
"""

import argparse
import concurrent.futures as cf
import json
import os
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare_off  # noqa: E402

LIBS_OF = {
    "loop": ["openmesh", "cgal", "osd"],
    "catmull-clark": ["openmesh", "cgal", "osd"],
    "sqrt3": ["openmesh", "cgal"],
    "butterfly": ["openmesh"],
    "doo-sabin": ["cgal"],
}
SCHEMES = ["loop", "catmull-clark", "sqrt3", "butterfly", "doo-sabin"]
TRI_ONLY = {"loop", "sqrt3", "butterfly"}
LEVELS = (1, 2)


# ----------------------------------------------------------------- topology

def topo(mesh):
    """V, F, E, boundary edges Eb, interior vertices Vint, sum of face sizes S,
    closed. Edges are counted from directed half-edges, so that the multiple
    edges of a two-vertex face (CGAL Doo-Sabin) count as separate edges:
    between a and b there are max(#a->b, #b->a) edges, |#a->b - #b->a| of them
    on the boundary."""
    dirc = {}
    for f in mesh.faces:
        n = len(f)
        for k in range(n):
            e = (f[k], f[(k + 1) % n])
            dirc[e] = dirc.get(e, 0) + 1
    E = Eb = 0
    bverts = set()
    for (a, b), c in dirc.items():
        r = dirc.get((b, a), 0)
        if r and a > b:
            continue  # pair counted from (b, a)
        E += max(c, r)
        if c != r:
            Eb += abs(c - r)
            bverts.add(a)
            bverts.add(b)
    return {
        "V": mesh.nv, "F": mesh.nf, "E": E, "Eb": Eb,
        "Vint": mesh.nv - len(bverts), "S": sum(len(f) for f in mesh.faces),
        "closed": Eb == 0,
    }


def expected_counts(scheme, level, t):
    """(V, F) one step of `scheme` must produce from a mesh with topology t
    (the step is number `level` of one call, which matters for sqrt3)."""
    if scheme in ("loop", "butterfly"):
        return t["V"] + t["E"], 4 * t["F"]
    if scheme == "catmull-clark":
        return t["V"] + t["E"] + t["F"], t["S"]
    if scheme == "doo-sabin":
        return t["S"], t["F"] + (t["E"] - t["Eb"]) + t["Vint"]
    if scheme == "sqrt3":
        if level % 2 == 1:
            return t["V"] + t["F"], 3 * t["F"]
        # even steps: boundary faces are split into a fan without a centre
        # point, each boundary edge gets 2 points
        return t["V"] + t["F"] + t["Eb"], 3 * t["F"]
    return None


# ----------------------------------------------------------------- running

def run_peer(binpath, lib, scheme, level, src, dst, timeout):
    t0 = time.perf_counter()
    try:
        p = subprocess.run([binpath, lib, scheme, str(level), src, dst],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                           timeout=timeout)
        rc, err = p.returncode, p.stderr.decode("utf-8", "replace")
    except subprocess.TimeoutExpired:
        rc, err = "timeout", f"timed out after {timeout} s"
    dt = time.perf_counter() - t0
    lines = [l for l in err.strip().splitlines() if l.strip()]
    # the last "rejected:" line is the reason; OpenMesh/CGAL chatter comes first
    reason = ""
    for l in lines:
        if "rejected:" in l:
            reason = l.split("rejected:", 1)[1].strip()
    if not reason and lines:
        reason = lines[-1]
    return {"lib": lib, "rc": rc, "time": dt, "reason": reason, "out": dst}


def crashed(rc):
    return rc == "timeout" or (isinstance(rc, int) and (rc < 0 or rc not in (0, 1, 2, 3)))


def rc_text(rc):
    if isinstance(rc, int) and rc < 0:
        try:
            return "killed by " + signal.Signals(-rc).name
        except ValueError:
            return f"signal {-rc}"
    return f"exit {rc}"


def group_task(args):
    """One (mesh, scheme): run every peer at every level, compare, check counts."""
    (binpath, mesh_path, scheme, outdir, tol, levels, timeout) = args
    name = os.path.splitext(os.path.basename(mesh_path))[0]
    libs = LIBS_OF[scheme]
    d = os.path.join(outdir, "runs", name)
    os.makedirs(d, exist_ok=True)
    rows, runs = [], []
    try:
        src_mesh = compare_off.read_off(mesh_path).drop_unreferenced()
        src_topo = topo(src_mesh)
    except compare_off.OffError as e:
        return [dict(mesh=name, scheme=scheme, level="-", libs="-", dist=None,
                     verdict="FAIL", note=f"cannot read input: {e}")], []
    if scheme in TRI_ONLY and any(len(f) != 3 for f in src_mesh.faces):
        return [dict(mesh=name, scheme=scheme, level="-", libs="+".join(libs), dist=None,
                     verdict="n/a", note="not a triangle mesh")], []
    prev_topo = {lib: src_topo for lib in libs}
    for level in levels:
        res = {}
        for lib in libs:
            dst = os.path.join(d, f"{scheme}_L{level}_{lib}.off")
            r = run_peer(binpath, lib, scheme, level, mesh_path, dst, timeout)
            r.update(mesh=name, scheme=scheme, level=level)
            runs.append(r)
            res[lib] = r
        meshes = {}
        for lib in libs:
            r = res[lib]
            if crashed(r["rc"]):
                rows.append(dict(mesh=name, scheme=scheme, level=level, libs=lib, dist=None,
                                 verdict="FAIL", note=f"CRASH: {rc_text(r['rc'])}: {r['reason']}"))
            elif r["rc"] == 0:
                try:
                    m = compare_off.read_off(r["out"])
                except compare_off.OffError as e:
                    rows.append(dict(mesh=name, scheme=scheme, level=level, libs=lib, dist=None,
                                     verdict="FAIL", note=f"unreadable output: {e}"))
                    continue
                meshes[lib] = m
                t = topo(m)
                exp = expected_counts(scheme, level, prev_topo[lib]) if prev_topo.get(lib) else None
                if exp is not None and (t["V"], t["F"]) != exp:
                    rows.append(dict(mesh=name, scheme=scheme, level=level, libs=lib, dist=None,
                                     verdict="FAIL",
                                     note=f"counts V={t['V']} F={t['F']}, expected V={exp[0]} F={exp[1]}"))
                prev_topo[lib] = t
            else:
                prev_topo[lib] = None
        # comparisons
        if len(libs) == 1:
            lib = libs[0]
            r = res[lib]
            if lib in meshes:
                rows.append(dict(mesh=name, scheme=scheme, level=level, libs=lib, dist=None,
                                 verdict="ok", note="single peer: ran, counts ok"))
            elif not crashed(r["rc"]):
                rows.append(dict(mesh=name, scheme=scheme, level=level, libs=lib, dist=None,
                                 verdict="skip", note=f"{lib} rejected: {r['reason']}"))
            continue
        for i in range(len(libs)):
            for j in range(i + 1, len(libs)):
                la, lb = libs[i], libs[j]
                pair = f"{la}-{lb}"
                informational = (scheme == "catmull-clark" and "openmesh" in (la, lb)
                                 and not src_topo["closed"])
                missing = [l for l in (la, lb) if l not in meshes]
                if missing:
                    if all(crashed(res[l]["rc"]) for l in missing):
                        continue  # already a FAIL row
                    why = "; ".join(f"{l} rejected: {res[l]['reason']}" for l in missing
                                    if not crashed(res[l]["rc"]))
                    rows.append(dict(mesh=name, scheme=scheme, level=level, libs=pair, dist=None,
                                     verdict="skip", note=why))
                    continue
                c = compare_off.compare_meshes(meshes[la], meshes[lb], tol)
                agree = c.ok
                if informational:
                    verdict = "info"
                    note = ("differs as expected (OpenMesh CC boundary rule 2/3,1/6)" if not agree
                            else "agrees (boundary vertices happen to be neighbour midpoints)")
                else:
                    verdict = "agree" if agree else "FAIL"
                    note = "" if agree else "; ".join(c.details[:2])
                if not c.faces_identical:
                    note = (note + "; " if note else "") + "faces DIFFER"
                rows.append(dict(mesh=name, scheme=scheme, level=level, libs=pair,
                                 dist=c.max_rel_dist, verdict=verdict, note=note))
    return rows, runs


def bad_task(args):
    binpath, path, outdir, timeout = args
    name = os.path.splitext(os.path.basename(path))[0]
    out = []
    d = os.path.join(outdir, "runs", "bad")
    os.makedirs(d, exist_ok=True)
    for scheme in SCHEMES:
        for lib in LIBS_OF[scheme]:
            r = run_peer(binpath, lib, scheme, 1, path,
                         os.path.join(d, f"{name}_{scheme}_{lib}.off"), timeout)
            r.update(mesh="bad/" + name, scheme=scheme, level=1)
            out.append(r)
    return out


# ----------------------------------------------------------------- main

def fmt_dist(x):
    return "-" if x is None else f"{x:.2e}"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("outdir")
    ap.add_argument("--bin", required=True, help="path of peer_subdivide")
    ap.add_argument("--meshes", default=os.environ.get("PEERS_MESHES", "/work/shared/data/meshes"))
    ap.add_argument("--jobs", type=int, default=min(2, os.cpu_count() or 1))
    ap.add_argument("--tol", type=float, default=1e-12)
    ap.add_argument("--level2-max-faces", type=int, default=15000,
                    help="skip level 2 for inputs with more faces (0 = never skip)")
    ap.add_argument("--timeout", type=float, default=120.0, help="per peer run, seconds")
    ap.add_argument("--no-bad", action="store_true", help="skip the bad/ crash sweep")
    args = ap.parse_args(argv)
    t_start = time.perf_counter()
    os.makedirs(args.outdir, exist_ok=True)

    if not os.path.isdir(args.meshes):
        print(f"SKIP: mesh folder {args.meshes} is absent; nothing cross-checked")
        print("0 passed, 0 failed")
        return 0
    meshes = sorted(os.path.join(args.meshes, f) for f in os.listdir(args.meshes)
                    if f.endswith(".off"))
    if not meshes:
        print(f"SKIP: no .off files in {args.meshes}")
        print("0 passed, 0 failed")
        return 0

    tasks, l2_skipped = [], []
    for m in meshes:
        try:
            nf = compare_off.read_off(m).nf
        except compare_off.OffError:
            nf = 0
        levels = LEVELS
        if args.level2_max_faces and nf > args.level2_max_faces:
            levels = (1,)
            l2_skipped.append((os.path.basename(m), nf))
        for scheme in SCHEMES:
            cost = nf * (16 if 2 in levels else 4) * len(LIBS_OF[scheme])
            tasks.append((cost, (args.bin, m, scheme, args.outdir, args.tol, levels,
                                 args.timeout)))
    tasks.sort(key=lambda t: -t[0])  # largest first: better packing on N workers

    rows, runs = [], []
    with cf.ProcessPoolExecutor(max_workers=args.jobs) as ex:
        futs = [ex.submit(group_task, t) for _, t in tasks]
        bad_futs = []
        bad_dir = os.path.join(args.meshes, "bad")
        if not args.no_bad and os.path.isdir(bad_dir):
            for f in sorted(os.listdir(bad_dir)):
                if f.endswith(".off"):
                    bad_futs.append(ex.submit(bad_task, (args.bin, os.path.join(bad_dir, f),
                                                         args.outdir, args.timeout)))
        for f in futs:
            r, ru = f.result()
            rows += r
            runs += ru
        bad_runs = [r for f in bad_futs for r in f.result()]

    order = {s: i for i, s in enumerate(SCHEMES)}
    na = [r for r in rows if r["verdict"] == "n/a"]
    rows = [r for r in rows if r["verdict"] != "n/a"]
    rows.sort(key=lambda r: (r["mesh"], order[r["scheme"]], str(r["level"]), r["libs"]))

    # ---- table
    w_mesh = max(len(r["mesh"]) for r in rows)
    hdr = f"{'mesh':<{w_mesh}}  {'scheme':<13} {'L':<3} {'libraries':<15} {'max_rel_dist':>12}  verdict"
    print(hdr)
    print("-" * len(hdr))
    for r in rows:
        note = f"  ({r['note']})" if r["note"] else ""
        print(f"{r['mesh']:<{w_mesh}}  {r['scheme']:<13} {str(r['level']):<3} {r['libs']:<15} "
              f"{fmt_dist(r['dist']):>12}  {r['verdict']}{note}")
    print()
    if na:
        print(f"NOTE: {len(na)} (mesh, triangle-only scheme) combinations not run: "
              f"{len(set(r['mesh'] for r in na))} meshes are not all-triangle")
    for name, nf in l2_skipped:
        print(f"NOTE: level 2 skipped for {name} ({nf} faces > --level2-max-faces "
              f"{args.level2_max_faces})")

    # ---- summaries
    passed = sum(1 for r in rows if r["verdict"] in ("agree", "ok"))
    failed = [r for r in rows if r["verdict"] == "FAIL"]
    skipped = [r for r in rows if r["verdict"] == "skip"]
    info = [r for r in rows if r["verdict"] == "info"]
    by_scheme = {}
    for r in rows:
        if r["verdict"] == "agree":
            s = by_scheme.setdefault((r["scheme"], r["libs"]), [0, 0.0, ""])
            s[0] += 1
            if r["dist"] > s[1]:
                s[1], s[2] = r["dist"], f"{r['mesh']} L{r['level']}"
    print("agreement by scheme and pair (count, worst max_rel_dist, where):")
    for (s, p), (n, w, where) in sorted(by_scheme.items(), key=lambda x: (order[x[0][0]], x[0][1])):
        print(f"  {s:<13} {p:<15} {n:3d} agree, worst {w:.2e} ({where})")
    if info:
        worst = max(info, key=lambda r: r["dist"])
        nd = sum(1 for r in info if "expected" in r["note"])
        print(f"  catmull-clark OpenMesh on open meshes (info): {nd} of {len(info)} differ, "
              f"largest {worst['dist']:.2e} ({worst['mesh']} L{worst['level']} {worst['libs']})")
    if skipped:
        print("skipped (a peer rejects the mesh):")
        seen = set()
        for r in skipped:
            key = (r["mesh"], r["note"])
            if key not in seen:
                seen.add(key)
                print(f"  {r['mesh']}: {r['note']}")

    # ---- run times
    print("peer run times (s): library/scheme: runs, total, max (mesh L)")
    agg = {}
    for r in runs:
        if r["rc"] != 0:
            continue
        a = agg.setdefault((r["lib"], r["scheme"]), [0, 0.0, 0.0, ""])
        a[0] += 1
        a[1] += r["time"]
        if r["time"] > a[2]:
            a[2], a[3] = r["time"], f"{r['mesh']} L{r['level']}"
    for (lib, s), (n, tot, mx, where) in sorted(agg.items()):
        print(f"  {lib:<9} {s:<13} {n:3d} runs, {tot:7.2f} total, {mx:6.2f} max ({where})")

    # ---- robustness sweep
    bad_fail = [r for r in bad_runs if crashed(r["rc"])]
    if bad_runs:
        n_ok = sum(1 for r in bad_runs if r["rc"] == 0)
        n_rej = sum(1 for r in bad_runs if r["rc"] == 2)
        n_uns = sum(1 for r in bad_runs if r["rc"] == 3)
        print(f"bad/ sweep: {len(bad_runs)} runs: {n_ok} accepted, {n_rej} rejected (exit 2), "
              f"{n_uns} unsupported, {len(bad_fail)} crashed")
        for r in bad_fail:
            print(f"  FAIL {r['mesh']} {r['lib']} {r['scheme']}: {rc_text(r['rc'])}: {r['reason']}")
    elif not args.no_bad:
        print("SKIP: no bad/ folder; robustness sweep not run")

    with open(os.path.join(args.outdir, "selfcheck.json"), "w") as fh:
        json.dump({"rows": rows, "runs": runs, "bad_runs": bad_runs}, fh, indent=1, default=str)

    n_fail = len(failed) + len(bad_fail)
    n_pass = passed + (len(bad_runs) - len(bad_fail))
    print(f"elapsed {time.perf_counter() - t_start:.1f} s; details in "
          f"{os.path.join(args.outdir, 'selfcheck.json')}")
    print(f"cross-check: {passed} pairs/runs agree or ok, {len(failed)} failed, "
          f"{len(skipped)} skipped, {len(info)} informational; bad/ sweep: "
          f"{len(bad_runs) - len(bad_fail)} clean, {len(bad_fail)} crashed")
    print(f"{n_pass} passed, {n_fail} failed")
    return 0 if n_fail == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
