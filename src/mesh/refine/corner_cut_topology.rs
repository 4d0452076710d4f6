//! The child topology of [`Pattern::CornerCut`](super::Pattern::CornerCut) (Doo–Sabin) derived
//! from its parent's: the arrays [`Topology::build`] gives on the child, array for array
//! (`derive.rs` states the contract; tested there against `build`), without its sorts and
//! with every pass but one cheap prefix sum split into disjoint output ranges.
//!
//! Child vertex `c < H` is the point of parent corner `c`, at vertex `a = origin(c)`. Its
//! neighbours are `next(c)` and `prev(c)` (its F-face), `next(twin c)` and `twin(prev c)` (the
//! corners at `a` of the faces across `c`'s edge and across `prev(c)`'s). The child's
//! half-edges (module docs of [`super`] for the faces):
//!
//! * F-face: half-edge `c` runs `c → next(c)`;
//! * E-face of an interior edge `e` with `h` its `min → max` half-edge and `t` the twin, from
//!   corner `B(e) = H + 4·(interior edges before e)` on: `B + 0: next h → h`, `B + 1: h → next t`
//!   (at `origin h`), `B + 2: next t → t`, `B + 3: t → next h` (at `origin t`);
//! * V-face of an interior vertex `a`, from corner `W(a) = H + 4·E_i + (the valences of the
//!   interior vertices before a)` on: `W(a) + j: s_j → s_{j+1}`, with `s_0, s_1, …` the spokes
//!   of `a`'s star (`s_{j+1} = twin(prev s_j)`).
//!
//! **Twins.** F-face `c` and `B(edge c) + 0` (`c = h`) or `+ 2` (`c = t`); none on a boundary
//! edge. `B + 1` and the V-face half-edge of `origin h` that leaves `next t`, `B + 3` and the
//! one of `origin t` that leaves `next h`; none at a boundary vertex, which has no V-face. So
//! the V-face half-edge leaving `s_j` is the twin of `B(edge(prev s_j)) + 3` when `prev s_j`
//! is its edge's `h`, else of `+ 1`.
//!
//! **Edges** are numbered in `(min, max)` order ([`Topology`]): by the smaller point, then
//! the larger. A point has at most four neighbours, so edge `(p, q)`, `p < q`, is `E0(p)` plus
//! the rank of `q` among `p`'s larger neighbours, `E0` the prefix sum of the numbers of larger
//! neighbours (each chunk sums its range, the chunks' totals are summed in order). One pass
//! over the points keeps, besides `E0`, each point's four ranks (its *rank code*, one field
//! per neighbour slot), so a child half-edge finds its edge from the slot it leaves by: the
//! neighbour of `p` in slot `next` has `p` in slot `prev`, in slot `next(twin ·)` it has `p`
//! in slot `twin(prev ·)`, and back. An edge's representative is the half-edge `p → q`, or
//! `q → p` on a boundary edge where only that one exists.
//!
//! **Stars.** A point at an interior vertex is interior, valence 4, and its star starts at
//! its F-face half-edge `c`, the lowest of its outgoing half-edges (E- and V-faces come
//! after the F-faces). A point at a boundary vertex is on the boundary: valence `2 +` the
//! interior edges among its two F-face edges, star from its outgoing boundary half-edge (`c`
//! on a boundary edge, else `c`'s E-face half-edge `B + 1` or `B + 3`, which has no V-face
//! across). The isolated vertices follow, as in the parent.
//!
//! The per-edge `B(e)` and per-vertex `W(a)` are prefix sums over the parent (one serial pass
//! over its edges and vertices, the cheap part); they and `E0` live in the child's vertex
//! arrays until the last pass overwrites those, the rank codes in its `edge_he` until the
//! representatives overwrite them. Every child corner the derivation relies on
//! is checked against the written faces: a mismatch is an internal error.

use arrayvec::ArrayVec;

use super::derive::check_eq;
use crate::error::Result;
use crate::exec::{self, Executor, MAX_CHUNKS};
use crate::mesh::topology::{regions, Counts, Raw, Regions};
use crate::mesh::{cadd, cmul, get, idx, internal, Mesh, Topology, MAX_COUNT, NONE};

/// The parent's arrays with the few queries the derivation makes of them.
#[derive(Clone, Copy)]
struct Parent<'a, 'm, 's> {
    raw: Raw<'m, 's>,
    /// `B(e)` of every parent edge (module docs), boundary edges included (the `B` of the
    /// next interior edge).
    e_base: &'a [u32],
    /// `W(a)` of every parent vertex (the next interior vertex's for the others).
    w_base: &'a [u32],
}

impl Parent<'_, '_, '_> {
    fn next_prev(&self, h: u32) -> Result<(u32, u32)> {
        let (n, p, _) = self.raw.next_prev_face(h)?;
        Ok((n, p))
    }

    fn twin(&self, h: u32) -> Result<u32> {
        get(self.raw.twin, h as usize)
    }

    /// Whether `h` is its edge's representative (`min → max` on an interior edge).
    fn is_rep(&self, h: u32) -> Result<bool> {
        Ok(get(
            self.raw.edge_he,
            get(self.raw.edge_of, h as usize)? as usize,
        )? == h)
    }

    /// `B(edge h)`.
    fn b(&self, h: u32) -> Result<u32> {
        get(self.e_base, get(self.raw.edge_of, h as usize)? as usize)
    }

    /// Whether vertex `a` is interior: its star starts at a half-edge with a twin (`false`
    /// for an isolated vertex).
    fn interior(&self, a: u32) -> Result<bool> {
        let s = get(self.raw.vert_he, a as usize)?;
        Ok(s != NONE && self.twin(s)? != NONE)
    }

    /// The position `j` of spoke `x` in the star of its vertex `a` (from the star's first
    /// spoke, counter-clockwise): the V-face of `a` has point `x` at its corner `W(a) + j`.
    /// `O(valence)`; only the first level has valences above 4.
    fn star_pos(&self, a: u32, x: u32) -> Result<u32> {
        let mut s = get(self.raw.vert_he, a as usize)?;
        for j in 0..get(self.raw.valence, a as usize)? {
            if s == x {
                return Ok(j);
            }
            s = self.twin(self.next_prev(s)?.1)?;
            if s == NONE {
                break;
            }
        }
        Err(internal())
    }

    /// The neighbours of point `c` in its four slots (module docs): [`NEXT`] `next c`,
    /// [`PREV`] `prev c`, [`ACROSS`] `next(twin c)` and [`ACROSS_PREV`] `twin(prev c)`,
    /// [`NONE`] where that twin does not exist.
    fn neighbours(&self, c: u32) -> Result<[u32; 4]> {
        let (nx, pv) = self.next_prev(c)?;
        let t = self.twin(c)?;
        let across = if t == NONE {
            NONE
        } else {
            self.next_prev(t)?.0
        };
        Ok([nx, pv, across, self.twin(pv)?])
    }
}

/// The neighbour slots of a point (module docs): the neighbour across its F-face edge
/// forward, back, and across the E-faces of its two edges.
const NEXT: u32 = 0;
const PREV: u32 = 1;
const ACROSS: u32 = 2;
const ACROSS_PREV: u32 = 3;

/// A slot's field of a [`rank_code`] when its neighbour is smaller than the point or absent.
const SMALLER: u32 = 0xf;

/// The slot of `p` among the neighbours of its neighbour in `slot`: `q = next p` has `p` as
/// its `prev`, `q = next(twin p)` has `p = twin(prev q)`, and back.
const fn dual(slot: u32) -> u32 {
    slot ^ 1
}

/// For each neighbour slot of point `c` (4 bits per slot, slot 0 lowest), the rank of that
/// neighbour among `c`'s larger neighbours, or [`SMALLER`]. Two equal neighbours (not the
/// child of a valid corner cut) are an internal error.
fn rank_code(c: u32, n: &[u32; 4]) -> Result<u32> {
    let mut code = 0;
    for (slot, &q) in n.iter().enumerate() {
        let mut r = SMALLER;
        if q != NONE && q > c {
            r = 0;
            for (j, &x) in n.iter().enumerate() {
                if x == q && j != slot {
                    return Err(internal());
                }
                r += u32::from(x != NONE && x > c && x < q);
            }
        }
        code |= r << (4 * slot);
    }
    Ok(code)
}

/// The child edge of the half-edge from point `p` to its neighbour in `slot`, `q`:
/// `E0(min)` + the rank of `max` in `min`'s [`rank_code`].
#[inline]
fn edge_id(e0: &[u32], codes: &[u32], p: u32, slot: u32, q: u32) -> Result<u32> {
    let (m, s) = if p < q { (p, slot) } else { (q, dual(slot)) };
    let r = (get(codes, m as usize)? >> (4 * s)) & 0xf;
    if r == SMALLER {
        return Err(internal());
    }
    Ok(get(e0, m as usize)? + r)
}

/// See the module docs; `mesh` is what [`super::write_pattern`] wrote from `parent`.
pub(super) fn derive(
    parent: &Topology<'_, '_>,
    mesh: &Mesh<'_>,
    scratch: &mut [u32],
    exec: &dyn Executor,
) -> Result<Counts> {
    let raw = parent.raw();
    let (nv, ne, nf, nh) = (
        parent.num_vertices(),
        parent.num_edges(),
        parent.num_faces(),
        parent.num_half_edges(),
    );
    let (ei, vi, sigma) = (
        parent.num_interior_edges(),
        parent.num_interior_vertices(),
        parent.interior_valence_sum(),
    );
    // The plan has checked these sizes; checked again so that no bug can wrap them.
    let nv2 = cadd(nh, parent.num_isolated_vertices())?;
    let nh2 = cadd(cadd(nh, cmul(4, ei)?)?, sigma)?;
    let nf2 = cadd(cadd(nf, ei)?, vi)?;
    if nv2 > MAX_COUNT
        || nh2 > MAX_COUNT
        || mesh.num_vertices() != nv2
        || mesh.num_corners() != nh2
        || mesh.num_faces() != nf2
    {
        return Err(internal());
    }
    check_eq(get(mesh.offsets, 0)?, 0)?;
    check_eq(get(mesh.offsets, nf2)?, nh2 as u32)?;
    let Regions {
        face_of,
        twin,
        edge_of,
        edge_he,
        vert_he,
        valence,
        bnd_rank,
    } = regions(scratch, nv2, nh2)?;
    let k = exec::chunk_count(exec, nh);
    // B(e) in the child's `vert_he`, W(a) in its `bnd_rank` (ne ≤ H and V ≤ H + I entries).
    let (v_faces, (min_vi, max_vi)) = bases(&raw, nh, ei, k, vert_he, bnd_rank)?;
    let par = Parent {
        raw,
        e_base: vert_he.get(..ne).ok_or(internal())?,
        w_base: bnd_rank.get(..nv).ok_or(internal())?,
    };
    // E0 in the child's `valence`, the points' rank codes in its `edge_he` (H ≤ its length),
    // which the edges' representatives overwrite last.
    let e0 = valence.get_mut(..nh).ok_or(internal())?;
    let codes = edge_he.get_mut(..nh).ok_or(internal())?;
    let n_edges = first_edges(&par, e0, codes, k, exec)?;
    if n_edges != nh + 2 * ei {
        return Err(internal());
    }
    let (e0, codes): (&[u32], &[u32]) = (e0, codes);
    let cx = Ctx {
        par,
        e0,
        codes,
        mesh,
        nh,
        nf,
        ei,
    };
    half_edges(&cx, &v_faces, k, exec, twin, face_of, edge_of)?;
    let twin: &[u32] = twin;
    let reps = edge_he.get_mut(..n_edges).ok_or(internal())?;
    edge_representatives(&par, twin, e0, nh, k, exec, reps)?;
    stars(parent, twin, k, exec, vert_he, valence, bnd_rank)?;
    let (sb, eb) = (parent.boundary_valence_sum(), parent.num_boundary_edges());
    let nb = parent.num_boundary_vertices();
    let face_max = parent.max_face_size().max(if ei > 0 { 4 } else { 0 });
    let face_min = if nf == 0 {
        0
    } else {
        let m = parent.min_face_size();
        let m = if ei > 0 { m.min(4) } else { m };
        if vi > 0 {
            m.min(min_vi)
        } else {
            m
        }
    };
    Ok(Counts {
        n_edges,
        // One boundary edge leaves each corner point at a boundary vertex (the old boundary
        // edges' F-face edges, and one E-face edge per pair of an interior edge and a
        // boundary end): as many as those points, `Σ_b (valence − 1) = sb − nb`.
        n_boundary_edges: sb.checked_sub(nb).ok_or(internal())?,
        n_boundary_vertices: sb.checked_sub(nb).ok_or(internal())?,
        n_isolated: parent.num_isolated_vertices(),
        interior_spokes: cmul(4, sigma)?,
        // Σ_b of the valences 2 + (interior F-face edges) of a boundary vertex's `k` points:
        // 2k + 2(k − 1) = 4k − 2 (`corner_cut::next`), and eb = nb on a manifold boundary.
        boundary_spokes: cmul(4, sb)?.checked_sub(cmul(6, eb)?).ok_or(internal())?,
        max_face: face_max.max(max_vi),
        min_face: face_min,
    })
}

/// What the passes over child half-edges read.
struct Ctx<'a, 'm, 's> {
    par: Parent<'a, 'm, 's>,
    e0: &'a [u32],
    codes: &'a [u32],
    mesh: &'a Mesh<'a>,
    nh: usize,
    nf: usize,
    ei: usize,
}

/// The serial pass over the parent's edges and vertices: `B(e)` into `e_base`, `W(a)` into
/// `w_base`. Returns, for each of the `k` vertex chunks, the index of its first V-face, and
/// the least and the largest interior valence (0 when there is none).
fn bases(
    raw: &Raw<'_, '_>,
    nh: usize,
    ei: usize,
    k: usize,
    e_base: &mut [u32],
    w_base: &mut [u32],
) -> Result<(ArrayVec<u32, MAX_CHUNKS>, (usize, usize))> {
    let mut b = nh as u32;
    for (slot, &h) in e_base.iter_mut().zip(raw.edge_he) {
        *slot = b;
        if get(raw.twin, h as usize)? != NONE {
            b += 4;
        }
    }
    if b as usize != nh + 4 * ei {
        return Err(internal());
    }
    let nv = raw.vert_he.len();
    let nf = raw.offsets.len().checked_sub(1).ok_or(internal())?;
    let mut v_faces = ArrayVec::<u32, MAX_CHUNKS>::new();
    let (mut w, mut face) = (b, (nf + ei) as u32);
    let (mut lo, mut hi) = (usize::MAX, 0usize);
    let slots = w_base.get_mut(..nv).ok_or(internal())?;
    for i in 0..k {
        v_faces.try_push(face).map_err(|_| internal())?;
        let (v0, v1) = exec::chunk_range(nv, k, i);
        for v in v0..v1 {
            *slots.get_mut(v).ok_or(internal())? = w;
            let s = get(raw.vert_he, v)?;
            if s != NONE && get(raw.twin, s as usize)? != NONE {
                let n = get(raw.valence, v)?;
                w += n;
                face += 1;
                lo = lo.min(n as usize);
                hi = hi.max(n as usize);
            }
        }
    }
    Ok((v_faces, (if hi == 0 { 0 } else { lo }, hi)))
}

/// `E0` of every point into `e0` and its [`rank_code`] into `codes` (module docs); the
/// number of edges. Per chunk of points the running sum of its own larger-neighbour counts,
/// then each chunk adds the totals of the chunks before it.
fn first_edges(
    par: &Parent<'_, '_, '_>,
    e0: &mut [u32],
    codes: &mut [u32],
    k: usize,
    exec: &dyn Executor,
) -> Result<usize> {
    struct Part<'a> {
        first: u32,
        out: &'a mut [u32],
        codes: &'a mut [u32],
        total: u32,
    }
    let nh = e0.len();
    let mut parts = ArrayVec::<Part<'_>, MAX_CHUNKS>::new();
    let (mut rest, mut rest_codes): (&mut [u32], &mut [u32]) = (e0, codes);
    for i in 0..k {
        let (p0, p1) = exec::chunk_range(nh, k, i);
        parts
            .try_push(Part {
                first: p0 as u32,
                out: exec::take_front(&mut rest, p1 - p0)?,
                codes: exec::take_front(&mut rest_codes, p1 - p0)?,
                total: 0,
            })
            .map_err(|_| internal())?;
    }
    exec::parts(
        exec,
        &mut parts,
        |p| p.out.len(),
        |p, _| {
            let mut sum = 0u32;
            let rows = p.out.iter_mut().zip(p.codes.iter_mut());
            for (c, (slot, code)) in (p.first..).zip(rows) {
                *slot = sum;
                let n = par.neighbours(c)?;
                *code = rank_code(c, &n)?;
                sum += n.iter().filter(|&&q| q != NONE && q > c).count() as u32;
            }
            p.total = sum;
            Ok(())
        },
    )?;
    let mut acc = 0u32;
    for p in &mut parts {
        (p.first, acc) = (acc, acc.checked_add(p.total).ok_or(internal())?);
    }
    if k > 1 {
        exec::parts(
            exec,
            &mut parts,
            |p| p.out.len(),
            |p, _| {
                for slot in p.out.iter_mut() {
                    *slot += p.first;
                }
                Ok(())
            },
        )?;
    }
    Ok(acc as usize)
}

/// One chunk's share of the child half-edges of one face group.
struct Span<'a> {
    /// The child half-edge of `twin[0]`.
    first: usize,
    twin: &'a mut [u32],
    face_of: &'a mut [u32],
    edge_of: &'a mut [u32],
}

impl Span<'_> {
    fn put(&mut self, x: u32, twin: u32, face: u32, edge: u32) -> Result<()> {
        let i = (x as usize).checked_sub(self.first).ok_or(internal())?;
        let (Some(t), Some(f), Some(e)) = (
            self.twin.get_mut(i),
            self.face_of.get_mut(i),
            self.edge_of.get_mut(i),
        ) else {
            return Err(internal());
        };
        (*t, *f, *e) = (twin, face, edge);
        Ok(())
    }
}

/// What one chunk of [`half_edges`] writes: the F-face half-edges of its parent corners, the
/// E-faces of its parent edges, the V-faces of its parent vertices (its first V-face).
struct HalfEdgePart<'a> {
    corners: (usize, usize),
    edges: (usize, usize),
    vertices: (usize, usize),
    v_face: u32,
    f: Span<'a>,
    e: Span<'a>,
    v: Span<'a>,
}

/// The twin, face and edge of every child half-edge, in the chunks of `exec`.
fn half_edges(
    cx: &Ctx<'_, '_, '_>,
    v_faces: &[u32],
    k: usize,
    exec: &dyn Executor,
    twin: &mut [u32],
    face_of: &mut [u32],
    edge_of: &mut [u32],
) -> Result<()> {
    let par = &cx.par;
    let (nh, ne, nv) = (cx.nh, par.e_base.len(), par.w_base.len());
    let e_end = (nh + 4 * cx.ei) as u32;
    let nh2 = twin.len();
    let at = |s: &[u32], i: usize, end: u32| if i == s.len() { Ok(end) } else { get(s, i) };
    let (mut t, mut f, mut e): (&mut [u32], &mut [u32], &mut [u32]) = (twin, face_of, edge_of);
    let (mut ft, mut ff, mut fe) = (
        exec::take_front(&mut t, nh)?,
        exec::take_front(&mut f, nh)?,
        exec::take_front(&mut e, nh)?,
    );
    let ne4 = e_end as usize - nh;
    let (mut et, mut ef, mut ee) = (
        exec::take_front(&mut t, ne4)?,
        exec::take_front(&mut f, ne4)?,
        exec::take_front(&mut e, ne4)?,
    );
    let (mut vt, mut vf, mut ve) = (t, f, e);
    let mut parts = ArrayVec::<HalfEdgePart<'_>, MAX_CHUNKS>::new();
    for i in 0..k {
        let corners = exec::chunk_range(nh, k, i);
        let edges = exec::chunk_range(ne, k, i);
        let vertices = exec::chunk_range(nv, k, i);
        let (eb0, eb1) = (
            at(par.e_base, edges.0, e_end)?,
            at(par.e_base, edges.1, e_end)?,
        );
        let (w0, w1) = (
            at(par.w_base, vertices.0, nh2 as u32)?,
            at(par.w_base, vertices.1, nh2 as u32)?,
        );
        let nc = corners.1 - corners.0;
        let nee = eb1.checked_sub(eb0).ok_or(internal())? as usize;
        let nvv = w1.checked_sub(w0).ok_or(internal())? as usize;
        parts
            .try_push(HalfEdgePart {
                corners,
                edges,
                vertices,
                v_face: get(v_faces, i)?,
                f: Span {
                    first: corners.0,
                    twin: exec::take_front(&mut ft, nc)?,
                    face_of: exec::take_front(&mut ff, nc)?,
                    edge_of: exec::take_front(&mut fe, nc)?,
                },
                e: Span {
                    first: eb0 as usize,
                    twin: exec::take_front(&mut et, nee)?,
                    face_of: exec::take_front(&mut ef, nee)?,
                    edge_of: exec::take_front(&mut ee, nee)?,
                },
                v: Span {
                    first: w0 as usize,
                    twin: exec::take_front(&mut vt, nvv)?,
                    face_of: exec::take_front(&mut vf, nvv)?,
                    edge_of: exec::take_front(&mut ve, nvv)?,
                },
            })
            .map_err(|_| internal())?;
    }
    if !(ft.is_empty() && et.is_empty() && vt.is_empty()) {
        return Err(internal());
    }
    exec::parts(
        exec,
        &mut parts,
        |p| p.f.twin.len() + p.e.twin.len() + p.v.twin.len(),
        |p, _| {
            f_faces(cx, p.corners, &mut p.f)?;
            e_faces(cx, p.edges, &mut p.e)?;
            v_faces_of(cx, p.vertices, p.v_face, &mut p.v)
        },
    )
    .map(|_| ())
}

/// The F-face half-edges of parent corners `corners`.
fn f_faces(cx: &Ctx<'_, '_, '_>, corners: (usize, usize), s: &mut Span<'_>) -> Result<()> {
    let par = &cx.par;
    for c in corners.0 as u32..corners.1 as u32 {
        let (nx, _, f) = par.raw.next_prev_face(c)?;
        check_eq(get(cx.mesh.indices, c as usize)?, c)?;
        if get(par.raw.offsets, f as usize)? == c {
            check_eq(get(cx.mesh.offsets, f as usize)?, c)?;
        }
        let tw = if par.twin(c)? == NONE {
            NONE
        } else {
            par.b(c)? + if par.is_rep(c)? { 0 } else { 2 }
        };
        s.put(c, tw, f, edge_id(cx.e0, cx.codes, c, NEXT, nx)?)?;
    }
    Ok(())
}

/// The E-faces of the interior edges among parent edges `edges`.
fn e_faces(cx: &Ctx<'_, '_, '_>, edges: (usize, usize), s: &mut Span<'_>) -> Result<()> {
    let par = &cx.par;
    let (indices, offsets) = (cx.mesh.indices, cx.mesh.offsets);
    for e in edges.0..edges.1 {
        let h = get(par.raw.edge_he, e)?;
        let t = par.twin(h)?;
        if t == NONE {
            continue;
        }
        let b = get(par.e_base, e)?;
        let k = (b as usize).checked_sub(cx.nh).ok_or(internal())? / 4;
        let face = idx(cx.nf + k)?;
        check_eq(get(offsets, face as usize)?, b)?;
        let (nh_, nt) = (par.next_prev(h)?.0, par.next_prev(t)?.0);
        let Some(&[c0, c1, c2, c3]) = indices.get(b as usize..b as usize + 4) else {
            return Err(internal());
        };
        check_eq(c0, nh_)?;
        check_eq(c1, h)?;
        check_eq(c2, nt)?;
        check_eq(c3, t)?;
        // Across the edges at `origin h` and `origin t`: the V-faces there, if interior.
        let across = |v: u32, from: u32| -> Result<u32> {
            if par.interior(v)? {
                Ok(get(par.w_base, v as usize)? + par.star_pos(v, from)?)
            } else {
                Ok(NONE)
            }
        };
        let (a, bv) = (
            get(par.raw.indices, h as usize)?,
            get(par.raw.indices, t as usize)?,
        );
        let id = |p: u32, slot: u32, q: u32| edge_id(cx.e0, cx.codes, p, slot, q);
        s.put(b, h, face, id(nh_, PREV, h)?)?;
        s.put(b + 1, across(a, nt)?, face, id(h, ACROSS, nt)?)?;
        s.put(b + 2, t, face, id(nt, PREV, t)?)?;
        s.put(b + 3, across(bv, nh_)?, face, id(t, ACROSS, nh_)?)?;
    }
    Ok(())
}

/// The V-faces of the interior vertices among parent vertices `vertices`, the first of them
/// face `face`.
fn v_faces_of(
    cx: &Ctx<'_, '_, '_>,
    vertices: (usize, usize),
    mut face: u32,
    s: &mut Span<'_>,
) -> Result<()> {
    let par = &cx.par;
    for v in vertices.0 as u32..vertices.1 as u32 {
        if !par.interior(v)? {
            continue;
        }
        let w = get(par.w_base, v as usize)?;
        check_eq(get(cx.mesh.offsets, face as usize)?, w)?;
        let start = get(par.raw.vert_he, v as usize)?;
        let mut sj = start;
        for j in 0..get(par.raw.valence, v as usize)? {
            check_eq(get(cx.mesh.indices, (w + j) as usize)?, sj)?;
            let p = par.next_prev(sj)?.1;
            let next = par.twin(p)?;
            let tw = par.b(p)? + if par.is_rep(p)? { 3 } else { 1 };
            s.put(
                w + j,
                tw,
                face,
                edge_id(cx.e0, cx.codes, sj, ACROSS_PREV, next)?,
            )?;
            sj = next;
        }
        check_eq(sj, start)?;
        face += 1;
    }
    Ok(())
}

/// Each edge's representative half-edge, by ranges of the smaller point (the edges of
/// points `[p0, p1)` are `[E0(p0), E0(p1))`).
fn edge_representatives(
    par: &Parent<'_, '_, '_>,
    twin: &[u32],
    e0: &[u32],
    nh: usize,
    k: usize,
    exec: &dyn Executor,
    edge_he: &mut [u32],
) -> Result<()> {
    struct Part<'a> {
        points: (usize, usize),
        out: &'a mut [u32],
    }
    let n_edges = edge_he.len() as u32;
    let mut rest: &mut [u32] = edge_he;
    let mut parts = ArrayVec::<Part<'_>, MAX_CHUNKS>::new();
    for i in 0..k {
        let (p0, p1) = exec::chunk_range(nh, k, i);
        let first = |p: usize| if p == nh { Ok(n_edges) } else { get(e0, p) };
        let len = first(p1)?.checked_sub(first(p0)?).ok_or(internal())?;
        parts
            .try_push(Part {
                points: (p0, p1),
                out: exec::take_front(&mut rest, len as usize)?,
            })
            .map_err(|_| internal())?;
    }
    exec::parts(
        exec,
        &mut parts,
        |p| p.points.1 - p.points.0,
        |p, _| {
            let mut at = 0usize;
            // The neighbours and ranks again (the rank codes were in the array this pass
            // writes).
            for c in p.points.0 as u32..p.points.1 as u32 {
                let (nx, pv) = par.next_prev(c)?;
                let (t, tp) = (par.twin(c)?, par.twin(pv)?);
                let across = if t == NONE { NONE } else { par.next_prev(t)?.0 };
                let n = [nx, pv, across, tp];
                let mut up = 0;
                for (slot, &q) in (0u32..).zip(n.iter()) {
                    if q == NONE || q <= c {
                        continue;
                    }
                    // Its rank among the larger neighbours (distinct: checked by rank_code).
                    let r = n.iter().filter(|&&x| x != NONE && x > c && x < q).count();
                    let x = representative(par, twin, c, slot, (pv, t, tp))?;
                    *p.out.get_mut(at + r).ok_or(internal())? = x;
                    up += 1;
                }
                at += up;
            }
            if at != p.out.len() {
                return Err(internal());
            }
            Ok(())
        },
    )
    .map(|_| ())
}

/// The child half-edge from point `c` to its neighbour in `slot`, or from that neighbour to
/// `c` where that is the only one (a boundary edge of the child); `(prev c, twin c,
/// twin(prev c))` as the caller has them, `twin` the child's (complete by now).
fn representative(
    par: &Parent<'_, '_, '_>,
    twin: &[u32],
    c: u32,
    slot: u32,
    around: (u32, u32, u32),
) -> Result<u32> {
    let (pv, t, tp) = around;
    // The twin of child half-edge `x`, or `x` itself on a boundary edge.
    let reverse = |x: u32| -> Result<u32> {
        let r = get(twin, x as usize)?;
        Ok(if r == NONE { x } else { r })
    };
    match slot {
        // The F-face edge c → next c.
        NEXT => Ok(c),
        // c → prev c, the twin of the F-face's prev c → c (in the E-face of prev c's edge);
        // on a boundary edge only that one.
        PREV => reverse(pv),
        // c → next(twin c) in the E-face of c's edge.
        ACROSS if t != NONE => Ok(par.b(c)? + if par.is_rep(c)? { 1 } else { 3 }),
        // c → twin(prev c), the twin of the E-face's twin(prev c) → next(twin(twin(prev c)))
        // = c (in the V-face of c's vertex); at a boundary vertex only that one.
        ACROSS_PREV if tp != NONE => reverse(par.b(tp)? + if par.is_rep(tp)? { 1 } else { 3 }),
        _ => Err(internal()),
    }
}

/// The child's stars, valences and boundary ranks (module docs), by ranges of child
/// vertices; boundary ranks continue the counts of the ranges before.
fn stars(
    parent: &Topology<'_, '_>,
    twin: &[u32],
    k: usize,
    exec: &dyn Executor,
    vert_he: &mut [u32],
    valence: &mut [u32],
    bnd_rank: &mut [u32],
) -> Result<()> {
    struct Part<'a> {
        first: usize,
        rank: u32,
        vert_he: &'a mut [u32],
        valence: &'a mut [u32],
        bnd_rank: &'a mut [u32],
    }
    let raw = parent.raw();
    let nh = parent.num_half_edges();
    let nv2 = vert_he.len();
    let boundary = |c: usize| -> Result<bool> {
        let s = get(raw.vert_he, get(raw.indices, c)? as usize)?;
        Ok(get(raw.twin, s as usize)? == NONE)
    };
    // The boundary rank of each range's first point: the boundary points of the ranges
    // before it, counted per range (none on a closed parent).
    let mut ranks = ArrayVec::<(usize, usize, u32), MAX_CHUNKS>::new();
    for i in 0..k {
        let (p0, p1) = exec::chunk_range(nv2, k, i);
        ranks
            .try_push((p0, p1.min(nh).max(p0), 0))
            .map_err(|_| internal())?;
    }
    if parent.num_boundary_vertices() > 0 {
        exec::parts(
            exec,
            &mut ranks,
            |r| r.1 - r.0,
            |r, _| {
                for c in r.0..r.1 {
                    r.2 += u32::from(boundary(c)?);
                }
                Ok(())
            },
        )?;
    }
    let mut acc = 0u32;
    for r in &mut ranks {
        (r.2, acc) = (acc, acc + r.2);
    }
    let (mut a, mut b, mut c) = (vert_he, valence, bnd_rank);
    let mut parts = ArrayVec::<Part<'_>, MAX_CHUNKS>::new();
    for i in 0..k {
        let (p0, p1) = exec::chunk_range(nv2, k, i);
        parts
            .try_push(Part {
                first: p0,
                rank: ranks.get(i).ok_or(internal())?.2,
                vert_he: exec::take_front(&mut a, p1 - p0)?,
                valence: exec::take_front(&mut b, p1 - p0)?,
                bnd_rank: exec::take_front(&mut c, p1 - p0)?,
            })
            .map_err(|_| internal())?;
    }
    exec::parts(
        exec,
        &mut parts,
        |p| p.vert_he.len(),
        |p, _| {
            let mut rank = p.rank;
            let rows = p
                .vert_he
                .iter_mut()
                .zip(p.valence.iter_mut())
                .zip(p.bnd_rank.iter_mut());
            for (cc, ((vh, val), br)) in (p.first..).zip(rows) {
                if cc >= nh {
                    (*vh, *val, *br) = (NONE, 0, NONE);
                    continue;
                }
                if !boundary(cc)? {
                    (*vh, *val, *br) = (cc as u32, 4, NONE);
                    continue;
                }
                let c32 = cc as u32;
                let (_, pv, _) = raw.next_prev_face(c32)?;
                let t = get(raw.twin, cc)?;
                let tp = get(raw.twin, pv as usize)?;
                // On a boundary edge the F-face half-edge; else c's E-face half-edge
                // (B + 1 or B + 3), one past its twin's partner B + 0 or B + 2.
                *vh = if t == NONE { c32 } else { get(twin, cc)? + 1 };
                *val = 2 + u32::from(t != NONE) + u32::from(tp != NONE);
                *br = rank;
                rank += 1;
            }
            Ok(())
        },
    )
    .map(|_| ())
}
