//! [`Pattern::Split1To4`](super::Pattern::Split1To4) (Loop, Modified Butterfly; triangles only):
//! every triangle becomes four, `(v0, e0, e2) (v1, e1, e0) (v2, e2, e1) (e0, e1, e2)` with `e_i`
//! the edge point of corner `i`'s edge `(v_i, v_{i+1})`. Output vertices: the `V` old vertices, the
//! `E` edge points.

use super::counts::{some, LevelCounts};
use super::derive::{check_eq, face_spans, old_vertices, spoke_edges};
use super::Parent;
use crate::error::{Error, Result, Status};
use crate::exec::Executor;
use crate::mesh::topology::{regions, Counts};
use crate::mesh::{
    cadd, cmul, get, idx, internal, set, Mesh, MeshSizes, Topology, MAX_COUNT, NONE,
};

/// The output sizes: `V + E` vertices, four triangles per triangle;
/// [`Status::UnsupportedFaceType`] naming the first face that is not a triangle.
pub(super) fn size(topo: &Topology<'_, '_>) -> Result<MeshSizes> {
    let (v, e, f) = (topo.num_vertices(), topo.num_edges(), topo.num_faces());
    // All triangles when the smallest and largest face are; otherwise name the first
    // face that is not.
    let all = topo.min_face_size() == 3 && topo.max_face_size() == 3;
    for face in (0..f as u32).filter(|_| !all) {
        if topo.face_size(face)? != 3 {
            return Err(Error::at(Status::UnsupportedFaceType, face));
        }
    }
    Ok(MeshSizes {
        vertices: cadd(v, e)?,
        faces: cmul(f, 4)?,
        indices: cmul(f, 12)?,
    })
}

/// The faces (module docs) of the parent triangles `faces` without a call per face:
/// triangle `f` (corners `3f..3f + 3`, every face a triangle) is faces `4f..4f + 4`,
/// corners `12f..12f + 12`. `offsets` and `indices` are the output's entries from those of
/// the range's first face on ([`super::Span`]); the closing offset of the last face is the
/// caller's.
pub(super) fn write_faces(
    topo: &Topology<'_, '_>,
    n: Parent,
    faces: (usize, usize),
    offsets: &mut [u32],
    indices: &mut [u32],
) -> Result<()> {
    let nv = n.v;
    let r = topo.raw();
    let (f0, f1) = faces;
    let corners = r.indices.get(3 * f0..3 * f1).ok_or(internal())?;
    let edges = r.edge_of.get(3 * f0..3 * f1).ok_or(internal())?;
    let out = indices.get_mut(..12 * (f1 - f0)).ok_or(internal())?;
    for ((q, c), e) in out
        .chunks_exact_mut(12)
        .zip(corners.chunks_exact(3))
        .zip(edges.chunks_exact(3))
    {
        let (&[v0, v1, v2], &[e0, e1, e2]) = (c, e) else {
            return Err(internal());
        };
        let (e0, e1, e2) = (nv + e0, nv + e1, nv + e2);
        let face = [v0, e0, e2, v1, e1, e0, v2, e2, e1, e0, e1, e2];
        for (d, s) in q.iter_mut().zip(face) {
            *d = s;
        }
    }
    // Every face a triangle (checked by `pattern_size`): face f is corners 3f..3f + 3.
    let parent_offsets = r.offsets.get(f0..=f1).ok_or(internal())?;
    for (f, w) in (f0..).zip(parent_offsets.windows(2)) {
        if w != [3 * f as u32, 3 * f as u32 + 3] {
            return Err(internal());
        }
    }
    let offs = offsets.get_mut(..4 * (f1 - f0)).ok_or(internal())?;
    for (k, o) in (4 * f0..).zip(offs.iter_mut()) {
        *o = idx(3 * k)?;
    }
    Ok(())
}

/// Where the output of parent triangle `f` starts: its first face and first corner.
pub(super) fn first_output(f: usize) -> (usize, usize) {
    (4 * f, 12 * f)
}

/// The counts of the next level. Edge points: interior valence 6, boundary 4; old vertices
/// keep theirs.
pub(super) fn next(s: &LevelCounts) -> Result<LevelCounts> {
    let ei = s.ei();
    Ok(LevelCounts {
        v: cadd(s.v, s.e)?,
        f: cmul(s.f, 4)?,
        h: cmul(s.h, 4)?,
        e: cadd(cmul(s.e, 2)?, cmul(s.f, 3)?)?,
        eb: cmul(s.eb, 2)?,
        iso: s.iso,
        si: cadd(s.si, cmul(ei, 6)?)?,
        sb: cadd(s.sb, cmul(s.eb, 4)?)?,
        max_vi: s.max_vi.max(some(ei > 0, 6)),
        max_vb: s.max_vb.max(some(s.eb > 0, 4)),
        max_face: 3,
        max_dt: 6,
    })
}

/// [`Pattern::Split1To4`](super::Pattern::Split1To4): corner `i` of triangle `f` (half-edge `h`)
/// becomes triangle `4f + i`, half-edges `A(h) = 12f + 3i ..`: `v_i → e_i`, `e_i → e_{i−1}`,
/// `e_{i−1} → v_i`; the middle triangle `4f + 3`, half-edges `C(f) + i = 12f + 9 + i`: `e_i →
/// e_{i+1}`.
pub(super) fn derive(
    parent: &Topology<'_, '_>,
    mesh: &Mesh<'_>,
    scratch: &mut [u32],
    exec: &dyn Executor,
) -> Result<Counts> {
    let par = parent.raw();
    let (nv, ne, nf, nh) = (
        parent.num_vertices(),
        parent.num_edges(),
        parent.num_faces(),
        parent.num_half_edges(),
    );
    let nv2 = nv + ne;
    let nh2 = nh.checked_mul(4).ok_or(internal())?;
    if nh != 3 * nf
        || nv2 > MAX_COUNT
        || nh2 > MAX_COUNT
        || mesh.num_vertices() != nv2
        || mesh.num_corners() != nh2
        || mesh.num_faces() != 4 * nf
    {
        return Err(internal());
    }
    // Triangles only (nh = 3 nf and every face ≥ 3 corners): offsets[f] = 3f, so the
    // face of h is h / 3 and its corner h % 3.
    let mut r = regions(scratch, nv2, nh2)?;
    let nv32 = nv as u32;
    let indices = par.indices;
    let (new_offsets, new_indices) = (mesh.offsets, mesh.indices);
    let big_a = |h: u32| 12 * (h / 3) + 3 * (h % 3);
    let big_c = |h: u32| 12 * (h / 3) + 9 + h % 3;
    let next = |h: u32| if h % 3 == 2 { h - 2 } else { h + 1 };
    let prev = |h: u32| if h % 3 == 0 { h + 2 } else { h - 1 };
    check_eq(get(new_offsets, 0)?, 0)?;
    // Twins and faces of the child half-edges, by parent triangle (triangle f is child
    // half-edges 12f..12f + 12), in the chunks of `exec`.
    face_spans(
        nf,
        &mut r,
        |f| Ok(12 * f),
        exec,
        |s| {
            for f in s.faces.0 as u32..s.faces.1 as u32 {
                check_eq(get(par.offsets, f as usize + 1)?, 3 * f + 3)?;
                for i in 0..3u32 {
                    let h = 3 * f + i;
                    let (nx, p) = (next(h), prev(h));
                    let t = get(par.twin, h as usize)?;
                    let tp = get(par.twin, p as usize)?;
                    let q = big_a(h) as usize;
                    let c = big_c(h) as usize;
                    let (Some(ql), Some(cl)) = (q.checked_sub(s.first), c.checked_sub(s.first))
                    else {
                        return Err(internal());
                    };
                    let across = if t == NONE { NONE } else { big_a(next(t)) + 2 };
                    let back = if tp == NONE { NONE } else { big_a(tp) };
                    let Some([t0, t1, t2]) = s.twin.get_mut(ql..ql + 3) else {
                        return Err(internal());
                    };
                    (*t0, *t1, *t2) = (across, big_c(p), back);
                    set(s.twin, cl, big_a(nx) + 1)?;
                    for x in s.face_of.get_mut(ql..ql + 3).ok_or(internal())? {
                        *x = 4 * f + i;
                    }
                    set(s.face_of, cl, 4 * f + 3)?;
                    let Some(&[c0, c1, c2]) = new_indices.get(q..q + 3) else {
                        return Err(internal());
                    };
                    let eh = nv32 + get(par.edge_of, h as usize)?;
                    check_eq(c0, get(indices, h as usize)?)?;
                    check_eq(c1, eh)?;
                    check_eq(c2, nv32 + get(par.edge_of, p as usize)?)?;
                    check_eq(get(new_indices, c)?, eh)?;
                    check_eq(
                        get(new_offsets, (4 * f + i) as usize + 1)?,
                        12 * f + 3 * i + 3,
                    )?;
                }
                check_eq(get(new_offsets, 4 * f as usize + 4)?, 12 * f + 12)?;
            }
            Ok(())
        },
    )?;
    // Edges (v, E): v -> E is A(h), E -> dest(h) is A(next h) + 2.
    let mut id = spoke_edges(parent, &mut r, |h| Ok(big_a(h)), |h| Ok(big_a(next(h)) + 2))?;
    // Edges (E(e), E(e')) with e < e' in parent-edge order, sorted by e' (at most four:
    // two per face of e; two faces never share two edges of a valid triangle mesh).
    let mut rank = parent.num_boundary_vertices() as u32;
    for (e, &h) in par.edge_he.iter().enumerate() {
        let e32 = e as u32;
        let t = get(par.twin, h as usize)?;
        let v2 = nv + e;
        // (other edge, representative e -> e', its twin).
        let mut cand = [(NONE, NONE, NONE); 4];
        let mut n = 0usize;
        for x in [h, t] {
            if x == NONE {
                continue;
            }
            let en = get(par.edge_of, next(x) as usize)?;
            if en > e32 {
                set(&mut cand, n, (en, big_c(x), big_a(next(x)) + 1))?;
                n += 1;
            }
            let ep = get(par.edge_of, prev(x) as usize)?;
            if ep > e32 {
                set(&mut cand, n, (ep, big_a(x) + 1, big_c(prev(x))))?;
                n += 1;
            }
        }
        let cand = cand.get_mut(..n).ok_or(internal())?;
        // Insertion sort of at most four distinct keys.
        for i in 1..cand.len() {
            let mut j = i;
            while j > 0 {
                let (Some(&lo), Some(&hi)) = (cand.get(j - 1), cand.get(j)) else {
                    return Err(internal());
                };
                if lo.0 <= hi.0 {
                    break;
                }
                cand.swap(j - 1, j);
                j -= 1;
            }
        }
        for &(_, rep, other) in cand.iter() {
            set(r.edge_of, rep as usize, id as u32)?;
            set(r.edge_of, other as usize, id as u32)?;
            set(r.edge_he, id, rep)?;
            id += 1;
        }
        let nxh = next(h);
        if t == NONE {
            set(r.vert_he, v2, big_a(nxh) + 2)?;
            set(r.valence, v2, 4)?;
            set(r.bnd_rank, v2, rank)?;
            rank += 1;
        } else {
            // Outgoing: A(next h) + 2, A(next t) + 2 (to the ends), A(h) + 1, C(h),
            // A(t) + 1, C(t) (to edge points); C(x) > A(x) + 1 (the middle triangle's
            // half-edges follow the corner triangles' of the same face).
            let start = (big_a(nxh) + 2)
                .min(big_a(next(t)) + 2)
                .min(big_a(h) + 1)
                .min(big_a(t) + 1);
            set(r.vert_he, v2, start)?;
            set(r.valence, v2, 6)?;
            set(r.bnd_rank, v2, NONE)?;
        }
    }
    if id != 2 * ne + 3 * nf {
        return Err(internal());
    }
    old_vertices(parent, &mut r, |h| Ok(big_a(h)))?;
    let eb = parent.num_boundary_edges();
    let face = if nf > 0 { 3 } else { 0 };
    Ok(Counts {
        n_edges: id,
        n_boundary_edges: 2 * eb,
        n_boundary_vertices: parent.num_boundary_vertices() + eb,
        n_isolated: parent.num_isolated_vertices(),
        interior_spokes: parent.interior_valence_sum() + 6 * (ne - eb),
        boundary_spokes: parent.boundary_valence_sum() + 4 * eb,
        max_face: face,
        min_face: face,
    })
}
