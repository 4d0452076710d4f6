//! The linear schemes' position rules: each driver walks the topology, gathers one
//! neighbourhood at a time ([`crate::mesh::gather`]) and evaluates the rule of
//! [`crate::stencil`] on it (the Möbius schemes evaluate the same rules on canonical forms).
//! See each stencil module for the rule and its source. The connectivity is the pattern's
//! ([`crate::mesh::refine`]), written by the step ([`super::subdivide`]) before the
//! positions.
//!
//! Order of evaluation, fixed for determinism: passes over the output in the order their
//! rules read each other (Catmull–Clark: face points, then vertex and edge points; Kobbelt:
//! vertex and edge points, then face points), each pass split into disjoint output ranges
//! ([`crate::exec`]); a rule that needs face or edge points reads them back from the output
//! buffer of an earlier pass. Within a pass the output order is the error order.
//!
//! No rule here holds a neighbourhood in an array: each one walks the star or the face and
//! accumulates what the rule reads (sums, the few points next to a given spoke) in the
//! rule's own order, through the streaming forms of [`crate::stencil`], which give the same
//! bits as the slice forms. The stack a driver needs is therefore a few hundred bytes
//! whatever the valence or face size (`docs/firmware.md`, "Stack").

use super::carry::{append_isolated, boundary_vertices};
use super::Scheme;
use crate::error::Result;
use crate::exec::{pass, Executor};
use crate::mesh::gather::{apex, boundary_beyond, face_sum, ring_sum};
use crate::mesh::{get, internal, set, Topology, NONE};
use crate::point::{add, Point};
use crate::stencil::{
    akleman, butterfly, catmull_clark, centroid_of_sum, doo_sabin, kobbelt, loop_scheme, simplest,
};

/// Writes the positions of one step of the linear `scheme` on `topo` into `pos` (the sizes of
/// the scheme's pattern); an internal error for [`Scheme::Spherelike`], which is not linear
/// ([`super::spherelike`]). The passes are split into chunks run by `exec` ([`crate::exec`]): the same bits for
/// every executor and chunking.
pub(crate) fn positions(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    pos: &mut [Point],
    exec: &dyn Executor,
) -> Result<()> {
    match scheme {
        Scheme::Loop => loop_positions(topo, pos, exec),
        Scheme::CatmullClark => catmull_clark_positions(topo, pos, exec),
        Scheme::ModifiedButterfly => butterfly_positions(topo, pos, exec),
        Scheme::Kobbelt => kobbelt_positions(topo, pos, exec),
        Scheme::DooSabin => doo_sabin_positions(topo, pos, exec),
        Scheme::Simplest => simplest_positions(topo, pos),
        Scheme::Dual => dual_positions(topo, pos),
        Scheme::VertexInsertion => vertex_insertion_positions(topo, pos, exec),
        Scheme::DualTruncation => dual_truncation_positions(topo, pos, exec),
        Scheme::Spherelike => Err(internal()),
    }
}

/// Splits the chunk `out` (output indices `start..start + out.len()`) at output index
/// `at`: the part below `at` and the part from it.
pub(crate) fn split_chunk(
    start: usize,
    out: &mut [Point],
    at: usize,
) -> Result<(&mut [Point], &mut [Point])> {
    let k = at.saturating_sub(start).min(out.len());
    out.split_at_mut_checked(k).ok_or(internal())
}

// ---- Loop ----

/// Loop: vertex points (vertex order), then edge points (edge order), each rule of
/// [`loop_scheme`] on its neighbourhood, in one pass over the output (each point reads only
/// the input). The loops read the topology's arrays directly ([`Topology::raw`]) and hand
/// the rules the points of the queries (`star`, `apex`), in their order.
fn loop_positions(topo: &Topology<'_, '_>, pos: &mut [Point], exec: &dyn Executor) -> Result<()> {
    let nv = topo.num_vertices();
    pass(exec, pos, |start, out, _| {
        let (vpos, epos) = split_chunk(start, out, nv)?;
        loop_vertices(topo, start, vpos)?;
        loop_edges(topo, start.saturating_sub(nv), epos)
    })
    .map(|_| ())
}

/// The Loop vertex points of vertices `first..first + out.len()`.
fn loop_vertices(topo: &Topology<'_, '_>, first: usize, out: &mut [Point]) -> Result<()> {
    let r = topo.raw();
    let mesh = topo.mesh();
    let position = |v: u32| mesh.position(v).ok_or(internal());
    for (v, out) in (first as u32..).zip(out.iter_mut()) {
        let p = position(v)?;
        let start = get(r.vert_he, v as usize)?;
        *out = if start == NONE {
            p
        } else if get(r.twin, start as usize)? == NONE {
            let (b0, b1) = topo.boundary_neighbours(v)?;
            loop_scheme::vertex_boundary(p, position(b0)?, position(b1)?)
        } else {
            // The interior star from its first spoke (`Topology::star`): h -> twin(prev(h)),
            // the ring summed as it is walked.
            let n = get(r.valence, v as usize)? as usize;
            let mut ring = [0.0; 3];
            let mut h = start;
            for _ in 0..n {
                let (next, prev, _) = r.next_prev_face(h)?;
                ring = add(ring, position(get(r.indices, next as usize)?)?);
                h = get(r.twin, prev as usize)?;
            }
            if h != start {
                return Err(internal());
            }
            loop_scheme::vertex_interior_sum(p, n, ring)?
        };
    }
    Ok(())
}

/// The Loop edge points of edges `first..first + out.len()`.
fn loop_edges(topo: &Topology<'_, '_>, first: usize, out: &mut [Point]) -> Result<()> {
    let r = topo.raw();
    let mesh = topo.mesh();
    let position = |v: u32| mesh.position(v).ok_or(internal());
    let edge_he = r.edge_he.get(first..).unwrap_or(&[]);
    if edge_he.len() < out.len() {
        return Err(internal());
    }
    for (&h, out) in edge_he.iter().zip(out.iter_mut()) {
        // Triangles: the apex of h (`apex`, the end of next(h)) is the origin of prev(h).
        let (next, prev, _) = r.next_prev_face(h)?;
        let a = position(get(r.indices, h as usize)?)?;
        let b = position(get(r.indices, next as usize)?)?;
        let t = get(r.twin, h as usize)?;
        *out = if t == NONE {
            loop_scheme::edge_boundary(a, b)
        } else {
            let c = position(get(r.indices, prev as usize)?)?;
            let (_, prev_t, _) = r.next_prev_face(t)?;
            let d = position(get(r.indices, prev_t as usize)?)?;
            loop_scheme::edge_interior(a, b, c, d)
        };
    }
    Ok(())
}

// ---- Catmull–Clark ----

/// Catmull–Clark: face points (face order), then vertex points (vertex order) and edge
/// points (edge order) in one pass over the output (they read the input and the face
/// points), each rule of [`catmull_clark`] on its neighbourhood gathered in the star's order.
/// The loops read the topology's arrays directly ([`Topology::raw`]); the points handed to
/// the rules, and their order, are those of the queries (`face_vertices`, `star`).
fn catmull_clark_positions(
    topo: &Topology<'_, '_>,
    pos: &mut [Point],
    exec: &dyn Executor,
) -> Result<()> {
    let nv = topo.num_vertices();
    let ne = topo.num_edges();
    let (ve, fpos) = pos.split_at_mut_checked(nv + ne).ok_or(internal())?;
    pass(exec, fpos, |start, out, _| {
        catmull_clark_faces(topo, start, out)
    })?;
    let fpos: &[Point] = fpos;
    pass(exec, ve, |start, out, _| {
        let (vpos, epos) = split_chunk(start, out, nv)?;
        catmull_clark_vertices(topo, fpos, start, vpos)?;
        catmull_clark_edges(topo, fpos, start.saturating_sub(nv), epos)
    })
    .map(|_| ())
}

/// The Catmull–Clark face points of faces `first..first + out.len()`.
fn catmull_clark_faces(topo: &Topology<'_, '_>, first: usize, out: &mut [Point]) -> Result<()> {
    let r = topo.raw();
    let mesh = topo.mesh();
    let position = |v: u32| mesh.position(v).ok_or(internal());
    if r.quads {
        // Every face a quad: corners 4f..4f + 4, gathered without a growing buffer.
        let quads = r
            .indices
            .get(4 * first..)
            .ok_or(internal())?
            .chunks_exact(4);
        if quads.len() < out.len() {
            return Err(internal());
        }
        for (q, out) in quads.zip(out.iter_mut()) {
            let &[a, b, c, d] = q else {
                return Err(internal());
            };
            let pts = [position(a)?, position(b)?, position(c)?, position(d)?];
            *out = catmull_clark::face_point(&pts)?;
        }
    } else {
        // The face point is the centroid (`catmull_clark::face_point`), summed as the face
        // is walked.
        let offsets = r.offsets.get(first..).ok_or(internal())?;
        if offsets.len() <= out.len() {
            return Err(internal());
        }
        for (w, out) in offsets.windows(2).zip(out.iter_mut()) {
            let &[a, b] = w else {
                return Err(internal());
            };
            let corners = r.indices.get(a as usize..b as usize).ok_or(internal())?;
            let mut sum = [0.0; 3];
            for &v in corners {
                sum = add(sum, position(v)?);
            }
            *out = centroid_of_sum(sum, corners.len())?;
        }
    }
    Ok(())
}

/// The Catmull–Clark edge points of edges `first..first + out.len()`.
fn catmull_clark_edges(
    topo: &Topology<'_, '_>,
    fpos: &[Point],
    first: usize,
    out: &mut [Point],
) -> Result<()> {
    let r = topo.raw();
    let mesh = topo.mesh();
    let position = |v: u32| mesh.position(v).ok_or(internal());
    let edge_he = r.edge_he.get(first..).unwrap_or(&[]);
    if edge_he.len() < out.len() {
        return Err(internal());
    }
    for (&h, out) in edge_he.iter().zip(out.iter_mut()) {
        let (next, _, f) = r.next_prev_face(h)?;
        let a = position(get(r.indices, h as usize)?)?;
        let b = position(get(r.indices, next as usize)?)?;
        let t = get(r.twin, h as usize)?;
        *out = if t == NONE {
            catmull_clark::edge_boundary(a, b)
        } else {
            let f0 = get(fpos, f as usize)?;
            let f1 = get(fpos, get(r.face_of, t as usize)? as usize)?;
            catmull_clark::edge_interior(a, b, f0, f1)
        };
    }
    Ok(())
}

/// The Catmull–Clark vertex points of vertices `first..first + out.len()`.
fn catmull_clark_vertices(
    topo: &Topology<'_, '_>,
    fpos: &[Point],
    first: usize,
    out: &mut [Point],
) -> Result<()> {
    let r = topo.raw();
    let mesh = topo.mesh();
    let position = |v: u32| mesh.position(v).ok_or(internal());
    for (v, out) in (first as u32..).zip(out.iter_mut()) {
        let p = position(v)?;
        let start = get(r.vert_he, v as usize)?;
        *out = if start == NONE {
            p
        } else if get(r.twin, start as usize)? == NONE {
            let (b0, b1) = topo.boundary_neighbours(v)?;
            catmull_clark::vertex_boundary(p, position(b0)?, position(b1)?)
        } else {
            // The interior star, counter-clockwise from its first spoke (`Topology::star`):
            // h -> twin(prev(h)), one spoke per neighbour; the ring and the face points
            // summed as it is walked.
            let n = get(r.valence, v as usize)? as usize;
            let mut ring = [0.0; 3];
            let mut faces = [0.0; 3];
            let mut h = start;
            for _ in 0..n {
                let (next, prev, f) = r.next_prev_face(h)?;
                ring = add(ring, position(get(r.indices, next as usize)?)?);
                faces = add(faces, get(fpos, f as usize)?);
                h = get(r.twin, prev as usize)?;
            }
            if h != start {
                return Err(internal());
            }
            catmull_clark::vertex_interior_sums(p, n, ring, faces)?
        };
    }
    Ok(())
}

// ---- Modified Butterfly ----

/// The vertex across the outer edge `g` of a triangle whose third vertex is `z`, or the
/// reflection `u + w − z` when `g` is a boundary edge (OpenMesh).
fn butterfly_across(topo: &Topology<'_, '_>, g: u32, z: u32) -> Result<Point> {
    let t = topo.twin(g)?;
    if t == NONE {
        Ok(butterfly::reflect(
            topo.position(topo.origin(g)?)?,
            topo.position(topo.dest(g)?)?,
            topo.position(z)?,
        ))
    } else {
        topo.position(apex(topo, t)?)
    }
}

/// Zorin's stencil of interior vertex `v` for its edge to `other` (ring starts at `other`):
/// the star walked twice, once to find `other`, then from it around (no ring array).
pub(crate) fn butterfly_zorin(topo: &Topology<'_, '_>, v: u32, other: u32) -> Result<Point> {
    let n = topo.valence(v)?;
    let j = topo
        .star(v)
        .position(|s| s.neighbour == other)
        .ok_or(internal())?;
    let ring = topo
        .star(v)
        .chain(topo.star(v))
        .skip(j)
        .take(n)
        .map(|s| topo.position(s.neighbour));
    butterfly::zorin_stencil_of(topo.position(v)?, n, ring).map_err(|e| e.with_element(v))
}

/// The old vertices, then the edge points, in one pass over the output.
fn butterfly_positions(
    topo: &Topology<'_, '_>,
    pos: &mut [Point],
    exec: &dyn Executor,
) -> Result<()> {
    let nv = topo.num_vertices();
    pass(exec, pos, |start, out, _| {
        let (vpos, epos) = split_chunk(start, out, nv)?;
        copy_range(topo, start, vpos)?;
        for (e, out) in (start.saturating_sub(nv) as u32..).zip(epos.iter_mut()) {
            *out = butterfly_edge(topo, e)?;
        }
        Ok(())
    })
    .map(|_| ())
}

/// The old vertices `first..first + out.len()` (primal patterns keep them at their index).
fn copy_range(topo: &Topology<'_, '_>, first: usize, out: &mut [Point]) -> Result<()> {
    for (v, out) in (first as u32..).zip(out.iter_mut()) {
        *out = topo.position(v)?;
    }
    Ok(())
}

/// The Modified Butterfly edge point of edge `e` (OpenMesh `ModifiedButterflyT`).
pub(crate) fn butterfly_edge(topo: &Topology<'_, '_>, e: u32) -> Result<Point> {
    let h = topo.edge_half_edge(e)?;
    let (i0, i1) = (topo.origin(h)?, topo.dest(h)?);
    let a0 = topo.position(i0)?;
    let a1 = topo.position(i1)?;
    let t = topo.twin(h)?;
    if t == NONE {
        return butterfly_boundary_edge(topo, i0, i1);
    }
    // The valence of a boundary endpoint is never examined (OpenMesh).
    let irr0 = !topo.is_boundary_vertex(i0)? && topo.valence(i0)? != 6;
    let irr1 = !topo.is_boundary_vertex(i1)? && topo.valence(i1)? != 6;
    Ok(match (irr0, irr1) {
        (false, false) => {
            let b0 = topo.position(apex(topo, h)?)?;
            let b1 = topo.position(apex(topo, t)?)?;
            let (nh, ph) = (topo.next(h)?, topo.prev(h)?);
            let (nt, pt) = (topo.next(t)?, topo.prev(t)?);
            let c = [
                butterfly_across(topo, nh, i0)?,
                butterfly_across(topo, ph, i1)?,
                butterfly_across(topo, nt, i1)?,
                butterfly_across(topo, pt, i0)?,
            ];
            butterfly::edge_regular(a0, a1, b0, b1, c)
        }
        (true, false) => butterfly_zorin(topo, i0, i1)?,
        (false, true) => butterfly_zorin(topo, i1, i0)?,
        (true, true) => {
            let s0 = butterfly_zorin(topo, i0, i1)?;
            let s1 = butterfly_zorin(topo, i1, i0)?;
            crate::point::midpoint(s0, s1)
        }
    })
}

/// The Modified Butterfly point of the boundary edge from `i0` to `i1`: the 4-point rule along
/// the boundary loop. Its own function so that the tagged rule's boundary case
/// (`interpolating_tagged.rs`) does not take the whole untagged rule's stack frame
/// (`docs/firmware.md`, "Stack").
pub(crate) fn butterfly_boundary_edge(topo: &Topology<'_, '_>, i0: u32, i1: u32) -> Result<Point> {
    let p0 = topo.position(boundary_beyond(topo, i0, i1)?)?;
    let p1 = topo.position(boundary_beyond(topo, i1, i0)?)?;
    Ok(butterfly::edge_boundary(
        p0,
        topo.position(i0)?,
        topo.position(i1)?,
        p1,
    ))
}

// ---- Kobbelt ----

/// The point beyond `v` on the grid line from `toward` through `v` (seed 000 §4.3 "virtual
/// points"; decisions in [`crate::stencil::kobbelt`]).
pub(crate) fn kobbelt_beyond(topo: &Topology<'_, '_>, v: u32, toward: u32) -> Result<Point> {
    let pv = topo.position(v)?;
    if topo.is_boundary_vertex(v)? {
        return Ok(kobbelt::extrapolate(pv, topo.position(toward)?));
    }
    // The star walked twice: once to find `toward` (spoke j), then to sum the neighbours
    // q_i and the diagonals d_i and keep the few next to q_j (no ring arrays).
    let n = topo.valence(v)?;
    let j = topo
        .star(v)
        .position(|s| s.neighbour == toward)
        .ok_or(internal())?;
    let at = |k: isize| (j as isize + k).rem_euclid(n.max(1) as isize) as usize;
    let mut parts = kobbelt::VirtualParts {
        n,
        ring_sum: [0.0; 3],
        diagonal_sum: [0.0; 3],
        near_q: [[0.0; 3]; 3],
        opposite: [0.0; 3],
        near_d: [[0.0; 3]; 4],
    };
    let mut count = 0;
    for (i, s) in topo.star(v).enumerate() {
        let q = topo.position(s.neighbour)?;
        let d = topo.position(apex(topo, s.half_edge)?)?;
        parts.ring_sum = add(parts.ring_sum, q);
        parts.diagonal_sum = add(parts.diagonal_sum, d);
        for (k, slot) in (-1..=1).zip(parts.near_q.iter_mut()) {
            if i == at(k) {
                *slot = q;
            }
        }
        if i == at(2) {
            parts.opposite = q;
        }
        for (k, slot) in (-2..=1).zip(parts.near_d.iter_mut()) {
            if i == at(k) {
                *slot = d;
            }
        }
        count += 1;
    }
    if count != n || n == 0 {
        return Err(internal());
    }
    Ok(parts.point())
}

/// The Kobbelt edge point of edge `e`: the 4-point rule on the two endpoints and the points
/// beyond them (virtual points at irregular vertices, boundary neighbours on the boundary).
pub(crate) fn kobbelt_edge(topo: &Topology<'_, '_>, e: u32) -> Result<Point> {
    let h = topo.edge_half_edge(e)?;
    let (i0, i1) = (topo.origin(h)?, topo.dest(h)?);
    let a0 = topo.position(i0)?;
    let a1 = topo.position(i1)?;
    let (r0, r1) = if topo.twin(h)? == NONE {
        (
            topo.position(boundary_beyond(topo, i0, i1)?)?,
            topo.position(boundary_beyond(topo, i1, i0)?)?,
        )
    } else {
        (kobbelt_beyond(topo, i0, i1)?, kobbelt_beyond(topo, i1, i0)?)
    };
    Ok(kobbelt::four_point(r0, a0, a1, r1))
}

/// The old vertices and the edge points in one pass, then the face points (which read the
/// edge points back).
fn kobbelt_positions(
    topo: &Topology<'_, '_>,
    pos: &mut [Point],
    exec: &dyn Executor,
) -> Result<()> {
    let nv = topo.num_vertices();
    let ne = topo.num_edges();
    let (ve, fpos) = pos.split_at_mut_checked(nv + ne).ok_or(internal())?;
    pass(exec, ve, |start, out, _| {
        let (vpos, epos) = split_chunk(start, out, nv)?;
        copy_range(topo, start, vpos)?;
        for (e, out) in (start.saturating_sub(nv) as u32..).zip(epos.iter_mut()) {
            *out = kobbelt_edge(topo, e)?;
        }
        Ok(())
    })?;
    let pos: &[Point] = ve;
    let ep = |h: u32| -> Result<Point> { get(pos, nv + topo.edge(h)? as usize) };
    pass(exec, fpos, |start, out, _| {
        for (f, out) in (start as u32..).zip(out.iter_mut()) {
            *out = kobbelt_face_by(topo, f, &ep)?;
        }
        Ok(())
    })
    .map(|_| ())
}

/// Kobbelt's face point of quad `f` from the new edge points `ep(h)` (of the edge of
/// half-edge `h`): the 4-point rule along each of the face's two grid lines of edge points,
/// the two results averaged; past a boundary edge the line is extrapolated.
fn kobbelt_face_by(
    topo: &Topology<'_, '_>,
    f: u32,
    ep: &dyn Fn(u32) -> Result<Point>,
) -> Result<Point> {
    // The edge point beyond edge `hx` of a quad, away from its opposite edge `hy`.
    let outer = |hx: u32, hy: u32| -> Result<Point> {
        let t = topo.twin(hx)?;
        if t == NONE {
            Ok(kobbelt::extrapolate(ep(hx)?, ep(hy)?))
        } else {
            ep(topo.next(topo.next(t)?)?)
        }
    };
    let r = topo.face_half_edges(f)?;
    let (h0, h1, h2, h3) = (r.start, r.start + 1, r.start + 2, r.start + 3);
    let fa = kobbelt::four_point(outer(h0, h2)?, ep(h0)?, ep(h2)?, outer(h2, h0)?);
    let fb = kobbelt::four_point(outer(h1, h3)?, ep(h1)?, ep(h3)?, outer(h3, h1)?);
    Ok(crate::point::midpoint(fa, fb))
}

/// The linear Kobbelt face point of quad `f`, its edge points evaluated where they are read
/// ([`kobbelt_edge`]): the linear scheme's face point without its level's edge points.
pub(crate) fn kobbelt_face(topo: &Topology<'_, '_>, f: u32) -> Result<Point> {
    kobbelt_face_by(topo, f, &|h| kobbelt_edge(topo, topo.edge(h)?))
}

// ---- Doo–Sabin, Simplest, Akleman ----

/// Doo–Sabin: every corner point by the rule of [`doo_sabin`] on its face (one pass over the
/// corners; a chunk that starts or ends inside a face gathers that face for its own corners),
/// then the isolated vertices. Kept out of line: inlined into the step it compiled to 0.5 %
/// more instructions (callgrind, `benches/icount.sh`).
#[inline(never)]
fn doo_sabin_positions(
    topo: &Topology<'_, '_>,
    pos: &mut [Point],
    exec: &dyn Executor,
) -> Result<()> {
    let nh = topo.num_half_edges();
    let (corners, _) = pos.split_at_mut_checked(nh).ok_or(internal())?;
    pass(exec, corners, |start, out, _| {
        let end = start + out.len();
        let mut h = start;
        while h < end {
            let f = topo.face(h as u32)?;
            // The corners read from the mesh by the rule, in its order (no face array).
            let face = topo.face_vertices(f)?;
            let corner = |c: usize| topo.position(get(face, c)?);
            let r = topo.face_half_edges(f)?;
            let first = r.start as usize;
            let stop = (r.end as usize).min(end);
            if stop <= h {
                return Err(internal());
            }
            for k in h..stop {
                let p = doo_sabin::corner_point_by(face.len(), k - first, corner)?;
                set(out, k - start, p)?;
            }
            h = stop;
        }
        Ok(())
    })?;
    append_isolated(topo, pos, nh)
}

fn simplest_positions(topo: &Topology<'_, '_>, pos: &mut [Point]) -> Result<()> {
    let ne = topo.num_edges();
    for e in 0..ne as u32 {
        let (a, b) = topo.edge_vertices(e)?;
        let m = simplest::edge_point(topo.position(a)?, topo.position(b)?);
        set(pos, e as usize, m)?;
    }
    boundary_vertices(topo, pos, ne)?;
    append_isolated(topo, pos, ne + topo.num_boundary_vertices())
}

/// The face centroids (`akleman::face_point`, summed as each face is walked).
fn face_centroids(topo: &Topology<'_, '_>, pos: &mut [Point], start: usize) -> Result<()> {
    for f in 0..topo.num_faces() as u32 {
        let (n, sum) = face_sum(topo, f)?;
        set(pos, start + f as usize, centroid_of_sum(sum, n)?)?;
    }
    Ok(())
}

fn dual_positions(topo: &Topology<'_, '_>, pos: &mut [Point]) -> Result<()> {
    let nf = topo.num_faces();
    let vb = topo.num_boundary_vertices();
    face_centroids(topo, pos, 0)?;
    for v in 0..topo.num_vertices() as u32 {
        let r = topo.boundary_vertex_rank(v)?;
        if r != NONE {
            let (b0, _) = topo.boundary_neighbours(v)?;
            let m = akleman::boundary_edge_point(topo.position(v)?, topo.position(b0)?);
            set(pos, nf + r as usize, m)?;
        }
    }
    boundary_vertices(topo, pos, nf + vb)?;
    append_isolated(topo, pos, nf + 2 * vb)
}

/// The old vertices, then the face centroids, in one pass.
fn vertex_insertion_positions(
    topo: &Topology<'_, '_>,
    pos: &mut [Point],
    exec: &dyn Executor,
) -> Result<()> {
    let nv = topo.num_vertices();
    pass(exec, pos, |start, out, _| {
        let (vpos, fpos) = split_chunk(start, out, nv)?;
        copy_range(topo, start, vpos)?;
        centroid_range(topo, start.saturating_sub(nv), fpos)
    })
    .map(|_| ())
}

/// The centroids of faces `first..first + out.len()` (`akleman::face_point`, summed as each
/// face is walked).
fn centroid_range(topo: &Topology<'_, '_>, first: usize, out: &mut [Point]) -> Result<()> {
    for (f, out) in (first as u32..).zip(out.iter_mut()) {
        let (n, sum) = face_sum(topo, f)?;
        *out = centroid_of_sum(sum, n)?;
    }
    Ok(())
}

/// The truncated vertices, then the face centroids, in one pass.
fn dual_truncation_positions(
    topo: &Topology<'_, '_>,
    pos: &mut [Point],
    exec: &dyn Executor,
) -> Result<()> {
    let nv = topo.num_vertices();
    pass(exec, pos, |start, out, _| {
        let (vpos, fpos) = split_chunk(start, out, nv)?;
        for (v, out) in (start as u32..).zip(vpos.iter_mut()) {
            let p = topo.position(v)?;
            *out = if topo.is_isolated(v)? || topo.is_boundary_vertex(v)? {
                p
            } else {
                let (n, sum) = ring_sum(topo, v)?;
                akleman::truncated_vertex_sum(p, n, sum)?
            };
        }
        centroid_range(topo, start.saturating_sub(nv), fpos)
    })
    .map(|_| ())
}

#[cfg(test)]
mod tests {
    //! The walking rules against the slice forms of [`crate::stencil`] on gathered arrays
    //! (the public tier-1 rules, the reference): the same bits at every valence, including
    //! 3, where the spokes next to the line's neighbour wrap onto each other.
    use super::*;
    use crate::mesh::{topology_scratch_size, Mesh};
    use arrayvec::ArrayVec;

    /// A bipyramid over an `N`-gon, with irregular coordinates: apexes of valence `N`, the
    /// equator of valence 4.
    fn bipyramid<const N: usize>(
        pos: &mut ArrayVec<Point, 16>,
        offs: &mut ArrayVec<u32, 32>,
        idx: &mut ArrayVec<u32, 96>,
    ) {
        for i in 0..N {
            let t = 2.0 * core::f64::consts::PI * i as f64 / N as f64 + 0.1 * (i * i) as f64;
            pos.try_push([libm::cos(t), libm::sin(t), 0.05 * i as f64])
                .unwrap();
        }
        pos.try_extend_from_slice(&[[0.1, -0.2, 1.3], [-0.15, 0.05, -0.9]])
            .unwrap();
        let (top, bottom) = (N as u32, N as u32 + 1);
        offs.try_push(0).unwrap();
        for i in 0..N as u32 {
            let j = (i + 1) % N as u32;
            for face in [[i, j, top], [j, i, bottom]] {
                idx.try_extend_from_slice(&face).unwrap();
                offs.try_push(idx.len() as u32).unwrap();
            }
        }
    }

    fn check<const N: usize>() {
        let (mut pos, mut offs, mut idx) = (ArrayVec::new(), ArrayVec::new(), ArrayVec::new());
        bipyramid::<N>(&mut pos, &mut offs, &mut idx);
        let mesh = Mesh::new(&pos, &offs, &idx);
        let mut scratch = [0u32; 1024];
        let need = topology_scratch_size(pos.len(), idx.len()).unwrap();
        let topo = Topology::build(mesh, &mut scratch[..need]).unwrap();
        for v in 0..pos.len() as u32 {
            let spokes = topo.spokes(v).unwrap();
            let q: ArrayVec<Point, 16> = spokes
                .iter()
                .map(|s| topo.position(s.neighbour).unwrap())
                .collect();
            let d: ArrayVec<Point, 16> = spokes
                .iter()
                .map(|s| topo.position(apex(&topo, s.half_edge).unwrap()).unwrap())
                .collect();
            for (j, s) in spokes.iter().enumerate() {
                let reference = kobbelt::virtual_point(&q, &d, j).unwrap();
                let walked = kobbelt_beyond(&topo, v, s.neighbour).unwrap();
                assert_eq!(walked.map(f64::to_bits), reference.map(f64::to_bits));
                let from_j: ArrayVec<Point, 16> =
                    (0..q.len()).map(|k| q[(j + k) % q.len()]).collect();
                let reference = butterfly::zorin_stencil(topo.position(v).unwrap(), &from_j);
                let walked = butterfly_zorin(&topo, v, s.neighbour).unwrap();
                assert_eq!(
                    walked.map(f64::to_bits),
                    reference.unwrap().map(f64::to_bits)
                );
            }
        }
    }

    #[test]
    fn walked_stars_equal_the_slice_rules() {
        check::<3>();
        check::<4>();
        check::<5>();
        check::<7>();
    }
}
