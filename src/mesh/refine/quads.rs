//! [`Pattern::Quads`](super::Pattern::Quads) (Catmull–Clark, Kobbelt, spherelike): every n-gon
//! becomes n quads, one per corner, `(v_i, e_i, f, e_{i−1})` with the edge points of the corner's
//! two edges and the face point. Output vertices: the `V` old vertices, the `E` edge points, the
//! `F` face points.

use super::counts::{some, LevelCounts};
use super::derive::{check_eq, face_spans, next_fast, old_vertices, spoke_edges};
use super::Parent;
use crate::error::Result;
use crate::exec::Executor;
use crate::mesh::topology::{regions, Counts};
use crate::mesh::{
    cadd, cmul, get, idx, internal, set, Mesh, MeshSizes, Topology, MAX_COUNT, NONE,
};
use crate::MAX_VALENCE;

/// The output sizes: `V + E + F` vertices, one quad per corner.
pub(super) fn size(topo: &Topology<'_, '_>) -> Result<MeshSizes> {
    let (v, e, f, h) = (
        topo.num_vertices(),
        topo.num_edges(),
        topo.num_faces(),
        topo.num_half_edges(),
    );
    Ok(MeshSizes {
        vertices: cadd(cadd(v, e)?, f)?,
        faces: h,
        indices: cmul(h, 4)?,
    })
}

/// The faces (module docs) of the parent faces `faces` without a call per corner: corner
/// `h` of face `f` is quad `h` = `(v, E(h), F(f), E(prev h))`, corners `4h..4h + 4`.
/// `offsets` and `indices` are the output's entries from those of the range's first face on
/// ([`super::Span`]); the closing offset of the last face is the caller's.
pub(super) fn write_faces(
    topo: &Topology<'_, '_>,
    n: Parent,
    faces: (usize, usize),
    offsets: &mut [u32],
    indices: &mut [u32],
) -> Result<()> {
    let (nv, ne) = (n.v, n.e);
    let r = topo.raw();
    let (f0, f1) = faces;
    let parent_offsets = r.offsets.get(f0..=f1).ok_or(internal())?;
    let h0 = *parent_offsets.first().ok_or(internal())? as usize;
    for (f, w) in (f0..).zip(parent_offsets.windows(2)) {
        let &[a, b] = w else {
            return Err(internal());
        };
        let (a, b) = (a as usize, b as usize);
        let fp = nv + ne + f as u32;
        let corners = r.indices.get(a..b).ok_or(internal())?;
        let edges = r.edge_of.get(a..b).ok_or(internal())?;
        let mut prev = nv + *edges.last().ok_or(internal())?;
        let (a0, b0) = (a.checked_sub(h0), b.checked_sub(h0));
        let (Some(a0), Some(b0)) = (a0, b0) else {
            return Err(internal());
        };
        let out = indices.get_mut(4 * a0..4 * b0).ok_or(internal())?;
        for ((q, &v), &e) in out.chunks_exact_mut(4).zip(corners).zip(edges) {
            let cur = nv + e;
            if let [q0, q1, q2, q3] = q {
                (*q0, *q1, *q2, *q3) = (v, cur, fp, prev);
            }
            prev = cur;
        }
    }
    let h1 = *parent_offsets.last().ok_or(internal())? as usize;
    let offs = offsets
        .get_mut(..h1.checked_sub(h0).ok_or(internal())?)
        .ok_or(internal())?;
    for (h, o) in (h0..).zip(offs.iter_mut()) {
        *o = idx(4 * h)?;
    }
    Ok(())
}

/// Where the output of parent face `f` starts: its first quad and first corner (the quads
/// are numbered by the parent's corners).
pub(super) fn first_output(topo: &Topology<'_, '_>, f: usize) -> Result<(usize, usize)> {
    let h = get(topo.raw().offsets, f)? as usize;
    Ok((h, 4 * h))
}

/// The counts of the next level. Edge points: interior valence 4, boundary 3; face points
/// interior, valence n.
pub(super) fn next(s: &LevelCounts) -> Result<LevelCounts> {
    let ei = s.ei();
    Ok(LevelCounts {
        v: cadd(cadd(s.v, s.e)?, s.f)?,
        f: s.h,
        h: cmul(s.h, 4)?,
        e: cadd(cmul(s.e, 2)?, s.h)?,
        eb: cmul(s.eb, 2)?,
        iso: s.iso,
        si: cadd(cadd(s.si, cmul(ei, 4)?)?, s.h)?,
        sb: cadd(s.sb, cmul(s.eb, 3)?)?,
        max_vi: s.max_vi.max(some(ei > 0, 4)).max(s.max_face),
        max_vb: s.max_vb.max(some(s.eb > 0, 3)),
        max_face: 4,
        max_dt: 8,
    })
}

/// [`Pattern::Quads`](super::Pattern::Quads): corner `h` of face `f` becomes quad `h`, half-edges
/// `4h..4h+4`: `v → E(h)`, `E(h) → F(f)`, `F(f) → E(prev h)`, `E(prev h) → v`.
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
    let nv2 = nv + ne + nf;
    let nh2 = nh.checked_mul(4).ok_or(internal())?;
    if nv2 > MAX_COUNT
        || nh2 > MAX_COUNT
        || mesh.num_vertices() != nv2
        || mesh.num_corners() != nh2
        || mesh.num_faces() != nh
    {
        return Err(internal());
    }
    let mut r = regions(scratch, nv2, nh2)?;
    let (nv32, ne32) = (nv as u32, ne as u32);
    let offsets = par.offsets;
    let indices = par.indices;
    let (new_offsets, new_indices) = (mesh.offsets, mesh.indices);
    check_eq(get(new_offsets, 0)?, 0)?;
    // Twins and faces of the child half-edges, by parent face (corner h of the parent is
    // child half-edges 4h..4h + 4), in the chunks of `exec`.
    let child_he = |f: usize| Ok(4 * get(offsets, f)? as usize);
    face_spans(nf, &mut r, child_he, exec, |s| {
        for f in s.faces.0..s.faces.1 {
            let a = get(offsets, f)?;
            let b = get(offsets, f + 1)?;
            let fp = nv32 + ne32 + f as u32;
            for h in a..b {
                let nx = if h + 1 == b { a } else { h + 1 };
                let p = if h == a { b - 1 } else { h - 1 };
                let t = get(par.twin, h as usize)?;
                let tp = get(par.twin, p as usize)?;
                let q = 4 * h as usize;
                let across = if t == NONE {
                    NONE
                } else {
                    4 * next_fast(&par, t)? + 3
                };
                let back = if tp == NONE { NONE } else { 4 * tp };
                let ql = q.checked_sub(s.first).ok_or(internal())?;
                let Some([t0, t1, t2, t3]) = s.twin.get_mut(ql..ql + 4) else {
                    return Err(internal());
                };
                (*t0, *t1, *t2, *t3) = (across, 4 * nx + 2, 4 * p + 1, back);
                for x in s.face_of.get_mut(ql..ql + 4).ok_or(internal())? {
                    *x = h;
                }
                let Some(&[c0, c1, c2, c3]) = new_indices.get(q..q + 4) else {
                    return Err(internal());
                };
                check_eq(c0, get(indices, h as usize)?)?;
                check_eq(c1, nv32 + get(par.edge_of, h as usize)?)?;
                check_eq(c2, fp)?;
                check_eq(c3, nv32 + get(par.edge_of, p as usize)?)?;
                check_eq(get(new_offsets, h as usize + 1)?, 4 * h + 4)?;
            }
        }
        Ok(())
    })?;
    // Edges (v, E): v -> E is 4h, E -> dest(h) is 4 next(h) + 3.
    let mut id = spoke_edges(
        parent,
        &mut r,
        |h| Ok(4 * h),
        |h| Ok(4 * next_fast(&par, h)? + 3),
    )?;
    // Edges (E, F) in parent-edge order, each pair by face id; edge points' stars.
    let mut rank = parent.num_boundary_vertices() as u32;
    for (e, &h) in par.edge_he.iter().enumerate() {
        let t = get(par.twin, h as usize)?;
        let nxh = next_fast(&par, h)?;
        let v2 = nv + e;
        let mut put = |x: u32, id: usize| -> Result<()> {
            let x1 = 4 * x + 1;
            set(r.edge_of, x1 as usize, id as u32)?;
            set(r.edge_of, (4 * next_fast(&par, x)? + 2) as usize, id as u32)?;
            set(r.edge_he, id, x1)
        };
        if t == NONE {
            put(h, id)?;
            id += 1;
            set(r.vert_he, v2, 4 * nxh + 3)?;
            set(r.valence, v2, 3)?;
            set(r.bnd_rank, v2, rank)?;
            rank += 1;
        } else {
            let (x, y) = if get(par.face_of, h as usize)? < get(par.face_of, t as usize)? {
                (h, t)
            } else {
                (t, h)
            };
            put(x, id)?;
            put(y, id + 1)?;
            id += 2;
            let nxt = next_fast(&par, t)?;
            let start = (4 * h + 1).min(4 * nxh + 3).min(4 * t + 1).min(4 * nxt + 3);
            set(r.vert_he, v2, start)?;
            set(r.valence, v2, 4)?;
            set(r.bnd_rank, v2, NONE)?;
        }
    }
    if id != 2 * ne + nh {
        return Err(internal());
    }
    old_vertices(parent, &mut r, |h| Ok(4 * h))?;
    for f in 0..nf {
        let a = get(offsets, f)?;
        let n = get(offsets, f + 1)? - a;
        let v2 = nv + ne + f;
        if n as usize > MAX_VALENCE {
            return Err(internal());
        }
        set(r.vert_he, v2, 4 * a + 2)?;
        set(r.valence, v2, n)?;
        set(r.bnd_rank, v2, NONE)?;
    }
    let eb = parent.num_boundary_edges();
    let face = if nh > 0 { 4 } else { 0 };
    Ok(Counts {
        n_edges: id,
        n_boundary_edges: 2 * eb,
        n_boundary_vertices: parent.num_boundary_vertices() + eb,
        n_isolated: parent.num_isolated_vertices(),
        interior_spokes: parent.interior_valence_sum() + 4 * (ne - eb) + nh,
        boundary_spokes: parent.boundary_valence_sum() + 3 * eb,
        max_face: face,
        min_face: face,
    })
}
