#!/usr/bin/env python3
"""Order-independent comparison of two OFF meshes (Python 3 standard library only).

    compare_off.py [--tol T] [--ignore-unreferenced] [-v] A.off B.off

Every vertex of A is matched to its exact nearest vertex of B (Euclidean).
The largest such distance, divided by the diagonal of A's bounding box, is
``max_rel_dist``. The faces of A, with their vertices replaced by the matched
vertices of B, must then be the faces of B as a multiset, each face compared
up to cyclic rotation with its orientation kept. Prints one line

    max_rel_dist=<%.3e> faces=identical|DIFFER

and exits 0 when max_rel_dist <= tol (default 1e-12), both meshes have the
same vertex and face counts and the faces are identical; 1 otherwise; 2 when a
file cannot be read. ``-v`` prints details (counts, worst vertex, why faces
differ) on stderr.

Nearest neighbours are exact: a fine hash grid answers a query when the best
candidate in the query's own cell is closer than that cell's walls; the rest
go to a hierarchy of coarser grids searched over 3x3x3 blocks (a block answers
when the best distance is at most its cell size). Points that coincide in B
(ties) are resolved by adjacency, so duplicated positions do not produce a
spurious DIFFER.

As a module::

    import compare_off
    a = compare_off.read_off("a.off"); b = compare_off.read_off("b.off")
    r = compare_off.compare_meshes(a, b, tol=1e-12)
    r.max_rel_dist, r.faces_identical, r.ok, r.summary(), r.details
    compare_off.compare_files("a.off", "b.off").ok

``compare_meshes`` caches B's search grids on the Mesh object, so comparing
several meshes against the same B is cheaper.
"""

import functools
import gc
import math
import sys
from collections import Counter

__all__ = ["Mesh", "OffError", "read_off", "compare_meshes", "compare_files", "Comparison", "main"]


def _no_gc(fn):
    """Runs fn with the cyclic garbage collector paused: these functions build
    millions of small tuples and lists (no cycles), and gc passes over them
    would double the run time."""
    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        was = gc.isenabled()
        gc.disable()
        try:
            return fn(*args, **kwargs)
        finally:
            if was:
                gc.enable()
    return wrapper


class OffError(Exception):
    """The file is not a readable ASCII OFF mesh."""


class Mesh:
    """Vertices as three coordinate lists and faces as tuples of vertex indices."""

    __slots__ = ("xs", "ys", "zs", "faces", "path", "_cache")

    def __init__(self, xs, ys, zs, faces, path=None):
        self.xs, self.ys, self.zs, self.faces, self.path = xs, ys, zs, faces, path
        self._cache = {}

    @property
    def nv(self):
        return len(self.xs)

    @property
    def nf(self):
        return len(self.faces)

    def bbox(self):
        if not self.xs:
            return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
        return ((min(self.xs), min(self.ys), min(self.zs)),
                (max(self.xs), max(self.ys), max(self.zs)))

    def diag(self):
        lo, hi = self.bbox()
        return math.sqrt(sum((h - l) ** 2 for l, h in zip(lo, hi)))

    def drop_unreferenced(self):
        """A copy without vertices that no face uses (indices renumbered in order)."""
        used = bytearray(self.nv)
        for f in self.faces:
            for v in f:
                used[v] = 1
        if all(used):
            return self
        remap, xs, ys, zs = [-1] * self.nv, [], [], []
        for v in range(self.nv):
            if used[v]:
                remap[v] = len(xs)
                xs.append(self.xs[v]); ys.append(self.ys[v]); zs.append(self.zs[v])
        faces = [tuple(remap[v] for v in f) for f in self.faces]
        return Mesh(xs, ys, zs, faces, self.path)


_HEADERS = {"OFF", "COFF", "NOFF", "CNOFF", "STOFF", "STCOFF", "STNOFF", "STCNOFF"}


@_no_gc
def read_off(path):
    """Reads an ASCII OFF file tolerantly: '#' comments, blank lines, CRLF, counts on
    the header line, COFF/NOFF extras after x y z (ignored), wrapped records."""
    try:
        with open(path, "rb") as fh:
            data = fh.read()
    except OSError as e:
        raise OffError(f"cannot read {path}: {e}") from None
    m = _read_off_tokens(path, data)
    if m is not None:
        return m
    text = data.decode("utf-8", errors="replace")
    if text.startswith("\ufeff"):
        text = text[1:]
    lines = text.splitlines()
    if "#" in text:
        lines = [l.split("#", 1)[0] for l in lines]
    lines = [l for l in lines if l and not l.isspace()]
    if not lines:
        raise OffError(f"{path}: empty file")
    head = lines[0].split()
    if head[0] not in _HEADERS:
        raise OffError(f"{path}: not an ASCII OFF file (header {head[0][:20]!r})")
    pos = 1
    counts = head[1:]
    if not counts:
        if len(lines) < 2:
            raise OffError(f"{path}: missing counts")
        counts = lines[1].split()
        pos = 2
    try:
        nv, nf = int(counts[0]), int(counts[1])
    except (ValueError, IndexError):
        raise OffError(f"{path}: bad counts line") from None
    if nv < 0 or nf < 0:
        raise OffError(f"{path}: negative counts")

    # fast path: one record per line
    vrows = [l.split() for l in lines[pos:pos + nv]]
    if len(vrows) == nv and all(len(r) >= 3 for r in vrows):
        try:
            xs = [float(r[0]) for r in vrows]
            ys = [float(r[1]) for r in vrows]
            zs = [float(r[2]) for r in vrows]
        except ValueError:
            raise OffError(f"{path}: bad vertex coordinate") from None
        fpos = pos + nv
        frows = [l.split() for l in lines[fpos:fpos + nf]]
        faces = None
        if len(frows) == nf:
            try:
                faces = [tuple(map(int, r[1:1 + int(r[0])])) for r in frows]
                if any(len(f) != int(r[0]) for f, r in zip(faces, frows)):
                    faces = None
            except ValueError:
                faces = None
        if faces is None:
            faces = _read_faces_slow(path, lines, fpos, nf)
    else:
        xs, ys, zs, fpos = _read_vertices_slow(path, lines, pos, nv)
        faces = _read_faces_slow(path, lines, fpos, nf)
    for f in faces:
        for v in f:
            if v < 0 or v >= nv:
                raise OffError(f"{path}: face index {v} out of range [0, {nv})")
    return Mesh(xs, ys, zs, faces, path)


def _read_off_tokens(path, data):
    """Fast path for plain 'OFF' files without comments or extras: the whole file
    as one token stream, accepted only if it is consumed exactly."""
    if b"#" in data[:1 << 20] and b"#" in data:
        return None
    head = data[:512].split(b"\n", 2)
    first = head[0].split()
    if first == [b"OFF"]:
        if len(head) < 2 or len(head[1].split()) != 3:
            return None
    elif not (len(first) == 4 and first[0] == b"OFF"):
        return None
    toks = data.split()
    try:
        nv, nf = int(toks[1]), int(toks[2])
        if nv < 0 or nf < 0 or 4 + 3 * nv > len(toks):
            return None
        vals = list(map(float, toks[4:4 + 3 * nv]))
        ints = list(map(int, toks[4 + 3 * nv:]))
    except ValueError:
        return None
    faces = cols = None
    n_ints = len(ints)
    for n in (3, 4):  # uniform triangle / quad meshes: slice instead of looping
        if n_ints == (n + 1) * nf and ints[0::n + 1].count(n) == nf:
            cols = [ints[k::n + 1] for k in range(1, n + 1)]
            faces = list(zip(*cols))
            break
    if faces is None:
        faces = []
        append = faces.append
        p = 0
        for _ in range(nf):
            if p >= n_ints:
                return None
            n = ints[p]
            if n < 0:
                return None
            append(tuple(ints[p + 1:p + 1 + n]))
            p += n + 1
        if p != n_ints:
            return None  # extras (face colours) or garbage: use the line-based reader
    if ints and (min(ints) < 0 or max(ints) >= nv):
        for f in faces:
            if f and (min(f) < 0 or max(f) >= nv):
                raise OffError(f"{path}: face index out of range [0, {nv})")
    mesh = Mesh(vals[0::3], vals[1::3], vals[2::3], faces, path)
    if cols is not None:
        mesh._cache["cols"] = cols
    return mesh


def _gather(path, lines, pos, toks, need):
    out = list(toks[:need])
    while len(out) < need:
        if pos >= len(lines):
            raise OffError(f"{path}: file ends inside a record")
        out.extend(lines[pos].split()[: need - len(out)])
        pos += 1
    return out, pos


def _read_vertices_slow(path, lines, pos, nv):
    xs, ys, zs = [], [], []
    for i in range(nv):
        if pos >= len(lines):
            raise OffError(f"{path}: file ends in vertex {i} of {nv}")
        rec, pos = _gather(path, lines, pos + 1, lines[pos].split(), 3)
        try:
            x, y, z = float(rec[0]), float(rec[1]), float(rec[2])
        except ValueError:
            raise OffError(f"{path}: bad coordinate in vertex {i}") from None
        xs.append(x); ys.append(y); zs.append(z)
    return xs, ys, zs, pos


def _read_faces_slow(path, lines, pos, nf):
    faces = []
    for i in range(nf):
        if pos >= len(lines):
            raise OffError(f"{path}: file ends in face {i} of {nf}")
        toks = lines[pos].split()
        try:
            n = int(toks[0])
            rec, pos = _gather(path, lines, pos + 1, toks[1:], n)
            faces.append(tuple(int(t) for t in rec))
        except ValueError:
            raise OffError(f"{path}: bad face {i}") from None
    return faces


# --------------------------------------------------------------------------- nearest

def _keys(xs, ys, zs, h, origin):
    """Cell coordinates of every point: the scaled coordinates (p - origin) / h
    per axis, their floors per axis, and the (kx, ky, kz) keys."""
    ox, oy, oz = origin
    inv = 1.0 / h
    floor = math.floor
    fx = [(x - ox) * inv for x in xs]
    fy = [(y - oy) * inv for y in ys]
    fz = [(z - oz) * inv for z in zs]
    kx, ky, kz = list(map(floor, fx)), list(map(floor, fy)), list(map(floor, fz))
    return (fx, fy, fz), (kx, ky, kz), list(zip(kx, ky, kz))


def _cells(b, h, origin):
    """Hash grid of b's vertices: cell key -> vertex index (int), or a list of
    indices for cells holding several vertices."""
    keys = _keys(b.xs, b.ys, b.zs, h, origin)[2]
    g = dict(zip(keys, range(len(keys))))
    if len(g) < len(keys):
        multi = {k: [] for k, c in Counter(keys).items() if c > 1}
        for i, k in enumerate(keys):
            lst = multi.get(k)
            if lst is not None:
                lst.append(i)
        g.update(multi)
    return g


def _fine_grid(b, h, origin):
    key = ("fine", h, origin)
    g = b._cache.get(key)
    if g is None:
        g = b._cache[key] = _cells(b, h, origin)
    return g


class _CoarseGrids:
    """Grids of cell size h0 * 3^k up to the first one >= top, built on demand."""

    def __init__(self, b, h0, top, origin):
        self.b, self.origin, self.sizes, self.grids = b, origin, [], {}
        h = h0
        while True:
            self.sizes.append(h)
            if h >= top:
                break
            h *= 3.0

    def grid(self, k):
        g = self.grids.get(k)
        if g is None:
            g = self.grids[k] = _cells(self.b, self.sizes[k], self.origin)
        return g


def _coarse_grids(b, h0, top, origin):
    key = ("coarse", h0, top, origin)
    gs = b._cache.get(key)
    if gs is None:
        gs = b._cache[key] = _CoarseGrids(b, h0, top, origin)
    return gs


_OFFS = [(dx, dy, dz) for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)]


def _block_search(g, kx, ky, kz, x, y, z, bx, by, bz):
    best, bj = math.inf, -1
    get = g.get
    for ex, ey, ez in _OFFS:
        cand = get((kx + ex, ky + ey, kz + ez))
        if cand is None:
            continue
        for j in ((cand,) if cand.__class__ is int else cand):
            dx = bx[j] - x; dy = by[j] - y; dz = bz[j] - z
            d = dx * dx + dy * dy + dz * dz
            if d < best:
                best, bj = d, j
    return best, bj


def _nearest(a, b, scale):
    """For each vertex of a: (index of the nearest vertex of b, squared distance)."""
    bx, by, bz = b.xs, b.ys, b.zs
    ax, ay, az = a.xs, a.ys, a.zs
    nb = len(bx)
    if nb == 0:
        return None, None
    h = scale * 2.0 ** -20 if scale > 0 else 1.0
    origin = b.bbox()[0]
    grid = _fine_grid(b, h, origin)
    (fxs, fys, fzs), (kxs, kys, kzs), keys = _keys(ax, ay, az, h, origin)
    cands = list(map(grid.get, keys))
    # Fast path, vectorised: cells holding exactly one vertex of b, accepted
    # when that vertex is closer than half the distance to the cell's walls
    # (nothing outside the cell can then be closer).
    single = [c if c.__class__ is int else 0 for c in cands]
    dx = [bx[c] - x for c, x in zip(single, ax)]
    dy = [by[c] - y for c, y in zip(single, ay)]
    dz = [bz[c] - z for c, z in zip(single, az)]
    d2 = [u * u + v * v + w * w for u, v, w in zip(dx, dy, dz)]
    ux = [f - k for f, k in zip(fxs, kxs)]
    uy = [f - k for f, k in zip(fys, kys)]
    uz = [f - k for f, k in zip(fzs, kzs)]
    wall = list(map(min, ux, uy, uz, [1.0 - u for u in ux], [1.0 - u for u in uy],
                    [1.0 - u for u in uz]))
    wmin = 1e-6
    h2 = h * h
    q = 0.25 * h2
    accept = [c.__class__ is int and w > wmin and d < q * w * w
              for c, w, d in zip(cands, wall, d2)]
    match = single
    d2s = d2
    rest = []
    for i in [i for i, ok in enumerate(accept) if not ok]:
        x, y, z = ax[i], ay[i], az[i]
        c = cands[i]
        if c is not None and c.__class__ is not int:
            best, bj = math.inf, -1
            for j in c:
                ex = bx[j] - x; ey = by[j] - y; ez = bz[j] - z
                d = ex * ex + ey * ey + ez * ez
                if d < best:
                    best, bj = d, j
            w = wall[i]
            if w > wmin and best < q * w * w:
                match[i] = bj
                d2s[i] = best
                continue
        # second chance on the same grid: the 3x3x3 block around the cell
        # answers when the best distance is at most one cell
        kx, ky, kz = keys[i]
        best, bj = _block_search(grid, kx, ky, kz, x, y, z, bx, by, bz)
        if bj >= 0 and best <= h2 * (1.0 - 1e-6):
            match[i] = bj
            d2s[i] = best
            continue
        rest.append(i)
    if rest:
        _nearest_coarse(a, b, rest, match, d2s, scale)
    return match, d2s


def _nearest_coarse(a, b, idx, match, d2s, scale):
    bx, by, bz = b.xs, b.ys, b.zs
    nb = len(bx)
    lo_b, hi_b = b.bbox()
    lo_a, hi_a = a.bbox()
    ext = max(max(hi_a[k], hi_b[k]) - min(lo_a[k], lo_b[k]) for k in range(3))
    if not ext > 0:
        ext = 1.0
    h0 = max(scale, ext) / max(1.0, math.sqrt(nb))
    origin = lo_b
    ox, oy, oz = origin
    grids = _coarse_grids(b, h0, 2.0 * ext, origin)
    floor = math.floor
    for i in idx:
        x, y, z = a.xs[i], a.ys[i], a.zs[i]
        done = False
        best, bj = math.inf, -1
        for k, h in enumerate(grids.sizes):
            inv = 1.0 / h
            kx, ky, kz = floor((x - ox) * inv), floor((y - oy) * inv), floor((z - oz) * inv)
            best, bj = _block_search(grids.grid(k), kx, ky, kz, x, y, z, bx, by, bz)
            # the point lies in the central cell: everything outside the 3x3x3
            # block is at least h away
            if bj >= 0 and best <= h * h * (1.0 - 1e-6):
                done = True
                break
        if not done:  # cannot happen (the last grid covers everything); be exact anyway
            best, bj = math.inf, -1
            for j in range(nb):
                dx = bx[j] - x; dy = by[j] - y; dz = bz[j] - z
                d = dx * dx + dy * dy + dz * dz
                if d < best:
                    best, bj = d, j
        match[i] = bj
        d2s[i] = best


# --------------------------------------------------------------------------- faces

def _canon(f):
    """Rotation of face f starting at its smallest index (orientation kept)."""
    m = min(f)
    if f.count(m) == 1:
        i = f.index(m)
        return f[i:] + f[:i]
    return min(f[i:] + f[:i] for i in range(len(f)))


def _canon_all(faces):
    """_canon of every face, fast: rotations start at the first smallest index
    (faces with a repeated index may then differ by rotation; compare_meshes
    retries with _canon when the fast forms disagree)."""
    return [f[i:] + f[:i] for f in faces for i in (f.index(min(f)),)]


def _face_keys(mesh, m, n_code):
    """Sorted canonical keys of mesh's faces with vertex v renamed m[v] (m may be
    None). Uniform triangle/quad meshes use integer keys (base n_code), others
    tuples."""
    faces = mesh.faces
    sizes = set(map(len, faces))
    if len(sizes) == 1 and sizes <= {3, 4}:
        k = next(iter(sizes))
        cols = mesh._cache.get("cols")
        if cols is None:
            cols = mesh._cache["cols"] = [[f[i] for f in faces] for i in range(k)]
        if m is not None:
            cols = [list(map(m.__getitem__, c)) for c in cols]
        N = n_code
        if k == 3:
            keys = [(p * N + q) * N + r if (p < q and p < r) else
                    ((q * N + r) * N + p if q < r else (r * N + p) * N + q)
                    for p, q, r in zip(*cols)]
        else:
            keys = [((p * N + q) * N + r) * N + s if mn == p else
                    (((q * N + r) * N + s) * N + p if mn == q else
                     (((r * N + s) * N + p) * N + q if mn == r else
                      ((s * N + p) * N + q) * N + r))
                    for p, q, r, s in zip(*cols) for mn in (min(p, q, r, s),)]
    else:
        if m is not None:
            faces = [tuple([m[v] for v in f]) for f in faces]
        keys = _canon_all(faces)
    keys.sort()
    return keys


def _adjacency(mesh):
    adj = mesh._cache.get("adj")
    if adj is None:
        adj = [set() for _ in range(mesh.nv)]
        for f in mesh.faces:
            n = len(f)
            for k in range(n):
                a, b = f[k], f[(k + 1) % n]
                adj[a].add(b)
                adj[b].add(a)
        mesh._cache["adj"] = adj
    return adj


def _resolve_ties(a, b, match, d2s):
    """Makes the A->B map injective where several A vertices picked the same B vertex
    (coincident points): reassign them to unused B vertices at (almost) the same
    place, preferring the one whose B neighbours best match their mapped neighbours."""
    count = Counter(match)
    shared = {j for j, c in count.items() if c > 1}
    if not shared:
        return 0
    used = set(count)
    free = [j for j in range(b.nv) if j not in used]
    if not free:
        return 0
    adj_a, adj_b = _adjacency(a), _adjacency(b)
    conflicted = [i for i, j in enumerate(match) if j in shared]
    # candidate B vertices for each conflicted A vertex: the shared target and
    # free B vertices within a small radius of the A point
    bx, by, bz = b.xs, b.ys, b.zs
    scale = max(a.diag(), 1e-300)
    taken = set()
    fixed = 0
    # neighbours of conflicted vertices that are themselves unambiguous
    conflicted_set = set(conflicted)
    by_target = {}
    for i in conflicted:
        by_target.setdefault(match[i], []).append(i)
    for j, group in by_target.items():
        x0, y0, z0 = bx[j], by[j], bz[j]
        rad2 = max(max(d2s[i] for i in group) * 4.0, (scale * 1e-9) ** 2)
        cands = [j] + [k for k in free if k not in taken and
                       (bx[k] - x0) ** 2 + (by[k] - y0) ** 2 + (bz[k] - z0) ** 2 <= rad2]
        # greedy: best neighbourhood agreement first
        scored = []
        for i in group:
            nb_mapped = {match[n] for n in adj_a[i] if n not in conflicted_set}
            for k in cands:
                scored.append((-len(nb_mapped & adj_b[k]), i, k))
        scored.sort()
        done_i, done_k = set(), set()
        for _, i, k in scored:
            if i in done_i or k in done_k:
                continue
            done_i.add(i); done_k.add(k)
            if match[i] != k:
                match[i] = k
                dx = bx[k] - a.xs[i]; dy = by[k] - a.ys[i]; dz = bz[k] - a.zs[i]
                d2s[i] = dx * dx + dy * dy + dz * dz
                fixed += 1
        taken |= done_k
    return fixed


def _all_finite(m):
    for c in (m.xs, m.ys, m.zs):
        if not math.isfinite(sum(c)):  # fast; overflow of the sum: check one by one
            if not all(map(math.isfinite, c)):
                return False
    return True


class Comparison:
    """Result of compare_meshes."""

    def __init__(self):
        self.max_rel_dist = math.nan
        self.faces_identical = False
        self.counts_equal = False
        self.tol = 1e-12
        self.details = []
        self.worst_vertex = None

    @property
    def ok(self):
        return (self.counts_equal and self.faces_identical
                and self.max_rel_dist <= self.tol)  # NaN compares False

    def summary(self):
        return "max_rel_dist=%.3e faces=%s" % (
            self.max_rel_dist, "identical" if self.faces_identical else "DIFFER")

    def __repr__(self):
        return "<Comparison %s ok=%s>" % (self.summary(), self.ok)


@_no_gc
def compare_meshes(a, b, tol=1e-12):
    """Compares Mesh a against Mesh b; see the module docstring."""
    r = Comparison()
    r.tol = tol
    r.counts_equal = (a.nv == b.nv and a.nf == b.nf)
    if not r.counts_equal:
        r.details.append(f"counts differ: A has V={a.nv} F={a.nf}, B has V={b.nv} F={b.nf}")
    if not (_all_finite(a) and _all_finite(b)):
        r.details.append("non-finite coordinates")
        return r
    if a.nv == 0 or b.nv == 0:
        r.details.append("a mesh has no vertices")
        r.max_rel_dist = 0.0 if a.nv == b.nv else math.inf
        r.faces_identical = a.nf == b.nf == 0
        return r
    diag = a.diag()
    scale = diag if diag > 0 else 1.0
    match, d2s = _nearest(a, b, max(scale, b.diag()))
    if len(set(match)) != len(match):
        n = _resolve_ties(a, b, match, d2s)
        if n:
            r.details.append(f"{n} coincident-vertex ties resolved by adjacency")
    worst = max(range(len(d2s)), key=d2s.__getitem__)
    r.worst_vertex = worst
    r.max_rel_dist = math.sqrt(d2s[worst]) / scale
    injective = len(set(match)) == len(match)
    if not injective:
        r.details.append(f"{len(match) - len(set(match))} vertices of A share a nearest vertex in B")
    # B -> A direction: equal to A -> B's maximum when the map is a bijection;
    # otherwise measure it too so that the reported distance is symmetric.
    if not (injective and a.nv == b.nv):
        m2, d2b = _nearest(b, a, max(scale, b.diag()))
        back = math.sqrt(max(d2b)) / scale
        if back > r.max_rel_dist:
            r.details.append(f"B->A distance {back:.3e} exceeds A->B")
            r.max_rel_dist = back
    if r.counts_equal:
        n_code = max(a.nv, b.nv, 1)
        fa = _face_keys(a, match, n_code)
        ck = ("facekeys", n_code)
        fb = b._cache.get(ck)
        if fb is None:
            fb = b._cache[ck] = _face_keys(b, None, n_code)
        r.faces_identical = fa == fb
        if not r.faces_identical:
            # exact canonical forms (the fast ones are not canonical for faces
            # with a repeated index), and a count of the differences
            ca = Counter(_canon(tuple([match[v] for v in f])) for f in a.faces)
            cb = Counter(map(_canon, b.faces))
            r.faces_identical = dict.__eq__(ca, cb)
            if not r.faces_identical:
                only_a = sum((ca - cb).values())
                only_b = sum((cb - ca).values())
                r.details.append(f"faces: {only_a} of A (mapped) not in B, {only_b} of B not in A")
    d_abs = math.sqrt(d2s[worst])
    r.details.append(
        f"A: V={a.nv} F={a.nf} diag={diag:.6g}; B: V={b.nv} F={b.nf}; worst A vertex {worst} "
        f"({a.xs[worst]!r}, {a.ys[worst]!r}, {a.zs[worst]!r}) -> B vertex {match[worst]} "
        f"at {d_abs:.3e}; vertices over tol: {sum(1 for d in d2s if d > (tol * scale) ** 2)}")
    return r


def compare_files(path_a, path_b, tol=1e-12, ignore_unreferenced=False):
    a, b = read_off(path_a), read_off(path_b)
    if ignore_unreferenced:
        a, b = a.drop_unreferenced(), b.drop_unreferenced()
    return compare_meshes(a, b, tol)


def main(argv=None):
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--tol", type=float, default=1e-12,
                    help="largest accepted max_rel_dist (default 1e-12)")
    ap.add_argument("--ignore-unreferenced", action="store_true",
                    help="drop vertices that no face uses from both meshes first")
    ap.add_argument("-v", "--verbose", action="store_true", help="details on stderr")
    args = ap.parse_args(argv)
    try:
        r = compare_files(args.a, args.b, args.tol, args.ignore_unreferenced)
    except OffError as e:
        print(f"compare_off: {e}", file=sys.stderr)
        return 2
    print(r.summary())
    if args.verbose or not r.ok:
        for d in r.details:
            print("compare_off: " + d, file=sys.stderr)
    return 0 if r.ok else 1


if __name__ == "__main__":
    sys.exit(main())
