#!/usr/bin/env python3
"""Unit tests of compare_off.py (stdlib unittest; no peers needed).

    python3 peers/test_compare_off.py
"""

import math
import os
import random
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import compare_off as C  # noqa: E402


def grid_mesh(n=6, quads=False):
    """A wavy n x n grid, triangles or quads, vertex i = (x, y)."""
    xs, ys, zs, faces = [], [], [], []
    for j in range(n + 1):
        for i in range(n + 1):
            xs.append(i / n); ys.append(j / n); zs.append(0.1 * math.sin(3 * i / n + j / n))
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 2, a + n + 1
            if quads:
                faces.append((a, b, c, d))
            else:
                faces += [(a, b, c), (a, c, d)]
    return C.Mesh(xs, ys, zs, faces)


def permuted(m, seed=1, rotate_faces=True, shuffle_faces=True):
    rnd = random.Random(seed)
    perm = list(range(m.nv))
    rnd.shuffle(perm)  # old index v -> new index perm[v]
    inv = [0] * m.nv
    for old, new in enumerate(perm):
        inv[new] = old
    faces = [tuple(perm[v] for v in f) for f in m.faces]
    if rotate_faces:
        faces = [f[k:] + f[:k] for f in faces for k in (rnd.randrange(len(f)),)]
    if shuffle_faces:
        rnd.shuffle(faces)
    return C.Mesh([m.xs[inv[i]] for i in range(m.nv)], [m.ys[inv[i]] for i in range(m.nv)],
                  [m.zs[inv[i]] for i in range(m.nv)], faces)


def write_off(path, m, fmt="%.17g"):
    with open(path, "w") as fh:
        fh.write(f"OFF\n{m.nv} {m.nf} 0\n")
        for x, y, z in zip(m.xs, m.ys, m.zs):
            fh.write(f"{fmt % x} {fmt % y} {fmt % z}\n")
        for f in m.faces:
            fh.write(f"{len(f)} " + " ".join(map(str, f)) + "\n")


class CompareTests(unittest.TestCase):
    def test_identical_under_permutation_and_rotation(self):
        for quads in (False, True):
            m = grid_mesh(quads=quads)
            r = C.compare_meshes(m, permuted(m))
            self.assertTrue(r.ok, r.details)
            self.assertEqual(r.max_rel_dist, 0.0)

    def test_orientation_matters(self):
        m = grid_mesh()
        flipped = C.Mesh(m.xs, m.ys, m.zs, [tuple(reversed(f)) for f in m.faces])
        r = C.compare_meshes(m, flipped)
        self.assertFalse(r.faces_identical)
        self.assertFalse(r.ok)

    def test_small_perturbation_within_and_beyond_tol(self):
        m = grid_mesh()
        p = permuted(m)
        p.xs[3] += 1e-14
        r = C.compare_meshes(m, p, tol=1e-12)
        self.assertTrue(r.ok)
        self.assertGreater(r.max_rel_dist, 0.0)
        p.ys[5] += 1e-6
        r = C.compare_meshes(m, p, tol=1e-12)
        self.assertFalse(r.ok)
        self.assertTrue(r.faces_identical)
        self.assertAlmostEqual(r.max_rel_dist, 1e-6 / m.diag(), delta=1e-9)

    def test_counts_differ(self):
        m = grid_mesh()
        sub = C.Mesh(m.xs, m.ys, m.zs, m.faces[:-1])
        r = C.compare_meshes(m, sub)
        self.assertFalse(r.ok)
        self.assertFalse(r.faces_identical)

    def test_different_triangulation(self):
        m = grid_mesh()
        faces = []
        for (a, b, c), (_, _, d) in zip(m.faces[0::2], m.faces[1::2]):
            faces += [(a, b, d), (b, c, d)]  # the other diagonal of each quad
        r = C.compare_meshes(m, C.Mesh(m.xs, m.ys, m.zs, faces))
        self.assertEqual(r.max_rel_dist, 0.0)
        self.assertFalse(r.faces_identical)
        self.assertFalse(r.ok)

    def test_coincident_vertices_resolved(self):
        # two triangles sharing no vertex but with a duplicated position
        m = C.Mesh([0.0, 1.0, 0.0, 1.0, 1.0, 2.0], [0.0, 0.0, 1.0, 0.0, 1.0, 0.0],
                   [0.0] * 6, [(0, 1, 2), (3, 5, 4)])
        p = permuted(m, seed=3)
        r = C.compare_meshes(m, p)
        self.assertTrue(r.ok, r.details)

    def test_nearest_is_exact(self):
        rnd = random.Random(5)
        for trial in range(30):
            n = rnd.choice([1, 3, 40, 200])
            s = 10 ** rnd.uniform(-5, 5)
            b = C.Mesh([rnd.uniform(0, s) for _ in range(n)], [rnd.uniform(0, s) for _ in range(n)],
                       [rnd.choice([0.0, rnd.uniform(0, s)]) for _ in range(n)], [])
            eps = 10 ** rnd.uniform(-17, 0) * s
            a = C.Mesh([x + rnd.gauss(0, eps) for x in b.xs], [y + rnd.gauss(0, eps) for y in b.ys],
                       [z + rnd.gauss(0, eps) for z in b.zs], [])
            m, d2 = C._nearest(a, b, max(a.diag(), b.diag()) or 1.0)
            for i in range(a.nv):
                best = min((bx - a.xs[i]) * (bx - a.xs[i]) + (by - a.ys[i]) * (by - a.ys[i])
                           + (bz - a.zs[i]) * (bz - a.zs[i]) for bx, by, bz in zip(b.xs, b.ys, b.zs))
                self.assertEqual(d2[i], best)

    def test_reader_variants_and_cli(self):
        m = grid_mesh(3)
        with tempfile.TemporaryDirectory() as d:
            a = os.path.join(d, "a.off")
            write_off(a, m)
            b = os.path.join(d, "b.off")
            with open(b, "w", newline="") as fh:  # comments, CRLF, COFF colours, wrapped face
                fh.write("COFF # header comment\r\n\r\n# counts\r\n")
                fh.write(f"{m.nv} {m.nf} 0\r\n")
                for x, y, z in zip(m.xs, m.ys, m.zs):
                    fh.write(f"{x!r} {y!r} {z!r} 0.5 0.5 0.5 1\r\n")
                for k, f in enumerate(m.faces):
                    if k == 0:
                        fh.write(f"{len(f)} {f[0]}\r\n  " + " ".join(map(str, f[1:])) + "\r\n")
                    else:
                        fh.write(f"{len(f)} " + " ".join(map(str, f)) + " 255 0 0\r\n")
            mb = C.read_off(b)
            self.assertEqual((mb.nv, mb.nf), (m.nv, m.nf))
            self.assertEqual(mb.faces, m.faces)
            out = subprocess.run([sys.executable, os.path.join(HERE, "compare_off.py"), a, b],
                                 capture_output=True, text=True)
            self.assertEqual(out.returncode, 0, out.stderr)
            self.assertEqual(out.stdout.strip(), "max_rel_dist=0.000e+00 faces=identical")
            c = os.path.join(d, "c.off")
            p = permuted(m)
            p.zs[0] += 1e-3
            write_off(c, p)
            out = subprocess.run([sys.executable, os.path.join(HERE, "compare_off.py"), a, c],
                                 capture_output=True, text=True)
            self.assertEqual(out.returncode, 1)
            self.assertTrue(out.stdout.startswith("max_rel_dist="))
            self.assertIn("faces=identical", out.stdout)
            bad = os.path.join(d, "bad.off")
            with open(bad, "w") as fh:
                fh.write("OFF\n3 1 0\n0 0 0\n1 0 0\n")
            out = subprocess.run([sys.executable, os.path.join(HERE, "compare_off.py"), a, bad],
                                 capture_output=True, text=True)
            self.assertEqual(out.returncode, 2)


if __name__ == "__main__":
    unittest.main(verbosity=1)
