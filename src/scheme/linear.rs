//! The linear schemes' position rules: each driver walks the topology, gathers one
//! neighbourhood at a time ([`crate::mesh::gather`]) and evaluates the rule of
//! [`crate::stencil`] on it (the Möbius schemes evaluate the same rules on canonical forms).
//! See each stencil module for the rule and its source. The connectivity is the pattern's
//! ([`crate::mesh::refine`]), written by the step ([`super::subdivide`]) before the
//! positions.
//!
//! Order of evaluation, fixed for determinism: face points (face order), edge points
//! (edge-id order), vertex points (vertex order); a rule that needs face or edge points reads
//! them back from the output buffer.

use super::carry::{append_isolated, boundary_vertices, copy_old};
use super::Scheme;
use crate::error::{Error, Result, Status};
use crate::mesh::gather::{
    apex, boundary_beyond, face_points_into, ring_points_into, FacePts, Ring,
};
use crate::mesh::{get, internal, set, Topology, NONE};
use crate::point::Point;
use crate::stencil::{
    akleman, butterfly, catmull_clark, doo_sabin, kobbelt, loop_scheme, simplest,
};

/// Writes the positions of one step of the linear `scheme` on `topo` into `pos` (the sizes of
/// the scheme's pattern); an internal error for [`Scheme::Spherelike`], which is not linear
/// ([`super::spherelike`]).
pub(crate) fn positions(scheme: Scheme, topo: &Topology<'_, '_>, pos: &mut [Point]) -> Result<()> {
    match scheme {
        Scheme::Loop => loop_positions(topo, pos),
        Scheme::CatmullClark => catmull_clark_positions(topo, pos),
        Scheme::ModifiedButterfly => butterfly_positions(topo, pos),
        Scheme::Kobbelt => kobbelt_positions(topo, pos),
        Scheme::DooSabin => doo_sabin_positions(topo, pos),
        Scheme::Simplest => simplest_positions(topo, pos),
        Scheme::Dual => dual_positions(topo, pos),
        Scheme::VertexInsertion => vertex_insertion_positions(topo, pos),
        Scheme::DualTruncation => dual_truncation_positions(topo, pos),
        Scheme::Spherelike => Err(internal()),
    }
}

// ---- Loop ----

/// Loop: vertex points (vertex order), then edge points (edge order), each rule of
/// [`loop_scheme`] on its neighbourhood; the loops read the topology's arrays directly
/// ([`Topology::raw`]) and hand the rules the points of the queries (`star`, `apex`), in
/// their order.
fn loop_positions(topo: &Topology<'_, '_>, pos: &mut [Point]) -> Result<()> {
    let r = topo.raw();
    let mesh = topo.mesh();
    let position = |v: u32| mesh.position(v).ok_or(internal());
    let nv = topo.num_vertices();
    let (vpos, epos) = pos.split_at_mut_checked(nv).ok_or(internal())?;
    let mut ring = Ring::new();
    for (v, out) in (0u32..).zip(vpos.iter_mut()) {
        let p = position(v)?;
        let start = get(r.vert_he, v as usize)?;
        *out = if start == NONE {
            p
        } else if get(r.twin, start as usize)? == NONE {
            let (b0, b1) = topo.boundary_neighbours(v)?;
            loop_scheme::vertex_boundary(p, position(b0)?, position(b1)?)
        } else {
            // The interior star from its first spoke (`Topology::star`): h -> twin(prev(h)).
            ring.clear();
            let mut h = start;
            for _ in 0..get(r.valence, v as usize)? {
                let (next, prev, _) = r.next_prev_face(h)?;
                ring.try_push(position(get(r.indices, next as usize)?)?)
                    .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
                h = get(r.twin, prev as usize)?;
            }
            if h != start {
                return Err(internal());
            }
            loop_scheme::vertex_interior(p, &ring)?
        };
    }
    for (&h, out) in r.edge_he.iter().zip(epos.iter_mut()) {
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

/// Catmull–Clark: face points (face order), edge points (edge order), vertex points (vertex
/// order), each rule of [`catmull_clark`] on its neighbourhood gathered in the star's order.
/// The loops read the topology's arrays directly ([`Topology::raw`]); the points handed to
/// the rules, and their order, are those of the queries (`face_vertices`, `star`).
fn catmull_clark_positions(topo: &Topology<'_, '_>, pos: &mut [Point]) -> Result<()> {
    let r = topo.raw();
    let mesh = topo.mesh();
    let position = |v: u32| mesh.position(v).ok_or(internal());
    let nv = topo.num_vertices();
    let ne = topo.num_edges();
    let (vpos, rest) = pos.split_at_mut_checked(nv).ok_or(internal())?;
    let (epos, fpos) = rest.split_at_mut_checked(ne).ok_or(internal())?;
    if r.quads {
        // Every face a quad: corners 4f..4f + 4, gathered without a growing buffer.
        let quads = r.indices.chunks_exact(4);
        for (q, out) in quads.zip(fpos.iter_mut()) {
            let &[a, b, c, d] = q else {
                return Err(internal());
            };
            let pts = [position(a)?, position(b)?, position(c)?, position(d)?];
            *out = catmull_clark::face_point(&pts)?;
        }
    } else {
        let mut pts = FacePts::new();
        for (w, out) in r.offsets.windows(2).zip(fpos.iter_mut()) {
            let &[a, b] = w else {
                return Err(internal());
            };
            pts.clear();
            for &v in r.indices.get(a as usize..b as usize).ok_or(internal())? {
                pts.try_push(position(v)?).map_err(|_| internal())?;
            }
            *out = catmull_clark::face_point(&pts)?;
        }
    }
    let fpos: &[Point] = fpos;
    for (&h, out) in r.edge_he.iter().zip(epos.iter_mut()) {
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
    let mut ring = Ring::new();
    let mut faces = Ring::new();
    for (v, out) in (0u32..).zip(vpos.iter_mut()) {
        let p = position(v)?;
        let start = get(r.vert_he, v as usize)?;
        *out = if start == NONE {
            p
        } else if get(r.twin, start as usize)? == NONE {
            let (b0, b1) = topo.boundary_neighbours(v)?;
            catmull_clark::vertex_boundary(p, position(b0)?, position(b1)?)
        } else {
            // The interior star, counter-clockwise from its first spoke (`Topology::star`):
            // h -> twin(prev(h)), one spoke per neighbour.
            ring.clear();
            faces.clear();
            let mut h = start;
            for _ in 0..get(r.valence, v as usize)? {
                let (next, prev, f) = r.next_prev_face(h)?;
                ring.try_push(position(get(r.indices, next as usize)?)?)
                    .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
                faces
                    .try_push(get(fpos, f as usize)?)
                    .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
                h = get(r.twin, prev as usize)?;
            }
            if h != start {
                return Err(internal());
            }
            catmull_clark::vertex_interior(p, &ring, &faces)?
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

/// Zorin's stencil of interior vertex `v` for its edge to `other` (ring starts at `other`).
fn butterfly_zorin(topo: &Topology<'_, '_>, v: u32, other: u32) -> Result<Point> {
    let spokes = topo.spokes(v)?;
    let j = spokes
        .iter()
        .position(|s| s.neighbour == other)
        .ok_or(internal())?;
    let mut ring = Ring::new();
    for k in 0..spokes.len() {
        let s = spokes.get((j + k) % spokes.len()).ok_or(internal())?;
        ring.try_push(topo.position(s.neighbour)?)
            .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
    }
    butterfly::zorin_stencil(topo.position(v)?, &ring).map_err(|e| e.with_element(v))
}

fn butterfly_positions(topo: &Topology<'_, '_>, pos: &mut [Point]) -> Result<()> {
    copy_old(topo, pos)?;
    let nv = topo.num_vertices();
    for e in 0..topo.num_edges() as u32 {
        set(pos, nv + e as usize, butterfly_edge(topo, e)?)?;
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
        let p0 = topo.position(boundary_beyond(topo, i0, i1)?)?;
        let p1 = topo.position(boundary_beyond(topo, i1, i0)?)?;
        return Ok(butterfly::edge_boundary(p0, a0, a1, p1));
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

// ---- Kobbelt ----

/// The point beyond `v` on the grid line from `toward` through `v` (seed 000 §4.3 "virtual
/// points"; decisions in [`crate::stencil::kobbelt`]).
fn kobbelt_beyond(topo: &Topology<'_, '_>, v: u32, toward: u32) -> Result<Point> {
    let pv = topo.position(v)?;
    if topo.is_boundary_vertex(v)? {
        return Ok(kobbelt::extrapolate(pv, topo.position(toward)?));
    }
    let spokes = topo.spokes(v)?;
    let j = spokes
        .iter()
        .position(|s| s.neighbour == toward)
        .ok_or(internal())?;
    let mut q = Ring::new();
    let mut d = Ring::new();
    for s in &spokes {
        q.try_push(topo.position(s.neighbour)?)
            .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
        d.try_push(topo.position(apex(topo, s.half_edge)?)?)
            .map_err(|_| Error::at(Status::ValenceTooHigh, v))?;
    }
    kobbelt::virtual_point(&q, &d, j).map_err(|e| e.with_element(v))
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

fn kobbelt_positions(topo: &Topology<'_, '_>, pos: &mut [Point]) -> Result<()> {
    copy_old(topo, pos)?;
    let nv = topo.num_vertices();
    let ne = topo.num_edges();
    for e in 0..ne as u32 {
        set(pos, nv + e as usize, kobbelt_edge(topo, e)?)?;
    }
    let ep = |pos: &[Point], h: u32| -> Result<Point> { get(pos, nv + topo.edge(h)? as usize) };
    // The edge point beyond edge `hx` of a quad, away from its opposite edge `hy`.
    let outer = |pos: &[Point], hx: u32, hy: u32| -> Result<Point> {
        let t = topo.twin(hx)?;
        if t == NONE {
            Ok(kobbelt::extrapolate(ep(pos, hx)?, ep(pos, hy)?))
        } else {
            ep(pos, topo.next(topo.next(t)?)?)
        }
    };
    for f in 0..topo.num_faces() as u32 {
        let r = topo.face_half_edges(f)?;
        let (h0, h1, h2, h3) = (r.start, r.start + 1, r.start + 2, r.start + 3);
        let fa = kobbelt::four_point(
            outer(pos, h0, h2)?,
            ep(pos, h0)?,
            ep(pos, h2)?,
            outer(pos, h2, h0)?,
        );
        let fb = kobbelt::four_point(
            outer(pos, h1, h3)?,
            ep(pos, h1)?,
            ep(pos, h3)?,
            outer(pos, h3, h1)?,
        );
        set(pos, nv + ne + f as usize, crate::point::midpoint(fa, fb))?;
    }
    Ok(())
}

// ---- Doo–Sabin, Simplest, Akleman ----

/// Doo–Sabin: every corner point by the rule of [`doo_sabin`] on its face, then the isolated
/// vertices. Kept out of line: inlined into the step it compiled to 0.5 % more instructions
/// (callgrind, `benches/icount.sh`).
#[inline(never)]
fn doo_sabin_positions(topo: &Topology<'_, '_>, pos: &mut [Point]) -> Result<()> {
    let mut pts = FacePts::new();
    for f in 0..topo.num_faces() as u32 {
        face_points_into(topo, f, &mut pts)?;
        for (i, h) in topo.face_half_edges(f)?.enumerate() {
            set(pos, h as usize, doo_sabin::corner_point(&pts, i)?)?;
        }
    }
    append_isolated(topo, pos, topo.num_half_edges())
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

fn face_centroids(topo: &Topology<'_, '_>, pos: &mut [Point], start: usize) -> Result<()> {
    let mut pts = FacePts::new();
    for f in 0..topo.num_faces() as u32 {
        face_points_into(topo, f, &mut pts)?;
        let c = akleman::face_point(&pts)?;
        set(pos, start + f as usize, c)?;
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

fn vertex_insertion_positions(topo: &Topology<'_, '_>, pos: &mut [Point]) -> Result<()> {
    copy_old(topo, pos)?;
    face_centroids(topo, pos, topo.num_vertices())
}

fn dual_truncation_positions(topo: &Topology<'_, '_>, pos: &mut [Point]) -> Result<()> {
    let mut ring = Ring::new();
    for v in 0..topo.num_vertices() as u32 {
        let p = topo.position(v)?;
        let q = if topo.is_isolated(v)? || topo.is_boundary_vertex(v)? {
            p
        } else {
            ring_points_into(topo, v, &mut ring)?;
            akleman::truncated_vertex(p, &ring)?
        };
        set(pos, v as usize, q)?;
    }
    face_centroids(topo, pos, topo.num_vertices())
}
