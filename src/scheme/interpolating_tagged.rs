//! The interpolating schemes with sharp-feature tags, Modified Butterfly and Kobbelt
//! (`docs/creases.md`): a sharp edge is refined by the scheme's own curve rule, the 4-point
//! rule along the crease polyline (the rule the scheme already takes on its boundary), and
//! the smooth rules treat a crease like a boundary. Untagged meshes never come here, so their
//! bits and speed are those of [`super::linear`]; old vertices are kept (interpolating).
//!
//! * **Crease chain.** The neighbours of a sharp edge along its crease are the other sharp
//!   edge at each endpoint when that endpoint *continues* the crease: no vertex sharpness and
//!   exactly two sharp incident edges (boundary edges count as infinitely sharp). At any
//!   other endpoint (a corner tag, one sharp edge, three or more) the crease ends and the
//!   4-point rule takes the virtual point `2 v − w` of the open 4-point curve
//!   ([`crate::curve::four_point::virtual_end_point`]). An untagged boundary loop never
//!   ends, so it keeps its rule bit for bit.
//! * **Smooth edges next to a crease** see it as a boundary: a vertex with two or more sharp
//!   edges is treated like a boundary vertex (its valence is not examined, Zorin's stencil is
//!   not taken there, Kobbelt's point beyond it is extrapolated), and Butterfly's wing across
//!   a sharp edge is the reflection `u + w − z`, Kobbelt's edge point across a sharp edge in
//!   a face point the extrapolation, that the scheme takes across a boundary edge. So the
//!   two sides of an infinitely sharp crease are refined independently, exactly as if the
//!   mesh were cut open along it.
//! * **Semi-sharp edges.** While an edge's sharpness is positive it is a crease for its
//!   neighbours; its own edge point is `w · crease + (1 − w) · smooth`, `w` OpenSubdiv's edge
//!   weight ([`crease::edge_weight`]: 1 while both child edges stay sharp, else the
//!   sharpness), `smooth` the rule the edge takes when it alone is untagged. The values
//!   decay per level as for Loop ([`super::tags::carry`]).

use super::linear::{self, butterfly_zorin, kobbelt_beyond};
use super::linear_tagged::edge_crease_weight;
use super::tags::Sharpness;
use crate::curve::four_point::virtual_end_point;
use crate::error::Result;
use crate::mesh::gather::apex;
use crate::mesh::{get, internal, set, Topology, NONE};
use crate::point::{midpoint, Point};
use crate::stencil::{butterfly, crease, kobbelt};

/// Whether edge `e` is sharp in this level (boundary edges are), `skip` counting as smooth.
fn sharp_edge(topo: &Topology<'_, '_>, sharp: &Sharpness<'_>, e: u32, skip: u32) -> Result<bool> {
    Ok(e != skip && crease::is_sharp(sharp.edge(topo, e)?))
}

/// The number of sharp edges at `v`, `skip` counting as smooth.
fn sharp_count(topo: &Topology<'_, '_>, sharp: &Sharpness<'_>, v: u32, skip: u32) -> Result<usize> {
    let mut n = 0;
    for s in topo.star(v) {
        if sharp_edge(topo, sharp, s.edge, skip)? {
            n += 1;
        }
    }
    Ok(n)
}

/// The point beyond `v` on the crease through the sharp edge `(other, v)`: the far end of
/// the other sharp edge at `v` when `v` continues the crease, else the virtual end point.
fn crease_beyond(
    topo: &Topology<'_, '_>,
    sharp: &Sharpness<'_>,
    v: u32,
    other: u32,
) -> Result<Point> {
    let p = topo.position(v)?;
    if !crease::is_sharp(sharp.vertex(v)?) && sharp_count(topo, sharp, v, NONE)? == 2 {
        for s in topo.star(v) {
            if s.neighbour != other && sharp_edge(topo, sharp, s.edge, NONE)? {
                return topo.position(s.neighbour);
            }
        }
    }
    Ok(virtual_end_point(p, topo.position(other)?))
}

/// Writes the positions of one tagged Modified Butterfly step on `topo` into `pos`.
pub(crate) fn butterfly_positions(
    topo: &Topology<'_, '_>,
    sharp: &Sharpness<'_>,
    pos: &mut [Point],
) -> Result<()> {
    let nv = topo.num_vertices();
    for v in 0..nv as u32 {
        set(pos, v as usize, topo.position(v)?)?;
    }
    for e in 0..topo.num_edges() as u32 {
        set(pos, nv + e as usize, butterfly_edge(topo, sharp, e)?)?;
    }
    Ok(())
}

/// The tagged Modified Butterfly edge point of edge `e`.
pub(crate) fn butterfly_edge(
    topo: &Topology<'_, '_>,
    sharp: &Sharpness<'_>,
    e: u32,
) -> Result<Point> {
    let h = topo.edge_half_edge(e)?;
    let (i0, i1) = (topo.origin(h)?, topo.dest(h)?);
    let s = sharp.edge(topo, e)?;
    if !crease::is_sharp(s) {
        return butterfly_smooth(topo, sharp, e);
    }
    let (a0, a1) = (topo.position(i0)?, topo.position(i1)?);
    let p0 = crease_beyond(topo, sharp, i0, i1)?;
    let p1 = crease_beyond(topo, sharp, i1, i0)?;
    let curve = butterfly::edge_boundary(p0, a0, a1, p1);
    let w = edge_crease_weight(topo, sharp, e, i0, i1)?;
    if w == 1.0 {
        return Ok(curve);
    }
    Ok(crease::blend(w, curve, butterfly_smooth(topo, sharp, e)?))
}

/// The vertex across the outer edge `g` of a triangle whose third vertex is `z`, or the
/// reflection `u + w − z` when `g` is a boundary or sharp edge.
fn butterfly_across(
    topo: &Topology<'_, '_>,
    sharp: &Sharpness<'_>,
    g: u32,
    z: u32,
) -> Result<Point> {
    let t = topo.twin(g)?;
    if t == NONE || sharp_edge(topo, sharp, topo.edge(g)?, NONE)? {
        Ok(butterfly::reflect(
            topo.position(topo.origin(g)?)?,
            topo.position(topo.dest(g)?)?,
            topo.position(z)?,
        ))
    } else {
        topo.position(apex(topo, t)?)
    }
}

/// The smooth Modified Butterfly rule of interior edge `e` with the other edges' tags: the
/// untagged rule ([`linear::butterfly_edge`]) with every vertex on two or more sharp edges
/// taken as a boundary vertex and every sharp outer edge as a boundary edge. `e` itself
/// counts as smooth (the smooth part of a semi-sharp edge).
fn butterfly_smooth(topo: &Topology<'_, '_>, sharp: &Sharpness<'_>, e: u32) -> Result<Point> {
    let h = topo.edge_half_edge(e)?;
    let t = topo.twin(h)?;
    let (i0, i1) = (topo.origin(h)?, topo.dest(h)?);
    if t == NONE {
        return linear::butterfly_boundary_edge(topo, i0, i1);
    }
    let irr0 = sharp_count(topo, sharp, i0, e)? < 2 && topo.valence(i0)? != 6;
    let irr1 = sharp_count(topo, sharp, i1, e)? < 2 && topo.valence(i1)? != 6;
    Ok(match (irr0, irr1) {
        (false, false) => {
            let (a0, a1) = (topo.position(i0)?, topo.position(i1)?);
            let b0 = topo.position(apex(topo, h)?)?;
            let b1 = topo.position(apex(topo, t)?)?;
            let (nh, ph) = (topo.next(h)?, topo.prev(h)?);
            let (nt, pt) = (topo.next(t)?, topo.prev(t)?);
            let c = [
                butterfly_across(topo, sharp, nh, i0)?,
                butterfly_across(topo, sharp, ph, i1)?,
                butterfly_across(topo, sharp, nt, i1)?,
                butterfly_across(topo, sharp, pt, i0)?,
            ];
            butterfly::edge_regular(a0, a1, b0, b1, c)
        }
        (true, false) => butterfly_zorin(topo, i0, i1)?,
        (false, true) => butterfly_zorin(topo, i1, i0)?,
        (true, true) => midpoint(
            butterfly_zorin(topo, i0, i1)?,
            butterfly_zorin(topo, i1, i0)?,
        ),
    })
}

/// Writes the positions of one tagged Kobbelt step on `topo` into `pos`: the old vertices
/// and the edge points, then the face points (which read the edge points back).
pub(crate) fn kobbelt_positions(
    topo: &Topology<'_, '_>,
    sharp: &Sharpness<'_>,
    pos: &mut [Point],
) -> Result<()> {
    let nv = topo.num_vertices();
    let ne = topo.num_edges();
    let (ve, fpos) = pos.split_at_mut_checked(nv + ne).ok_or(internal())?;
    for v in 0..nv as u32 {
        set(ve, v as usize, topo.position(v)?)?;
    }
    for e in 0..ne as u32 {
        set(ve, nv + e as usize, kobbelt_edge(topo, sharp, e)?)?;
    }
    let ve: &[Point] = ve;
    let ep = |h: u32| -> Result<Point> { get(ve, nv + topo.edge(h)? as usize) };
    // The edge point beyond edge `hx` of a quad, away from its opposite edge `hy`: across a
    // boundary or sharp edge the open curve's virtual point.
    let outer = |hx: u32, hy: u32| -> Result<Point> {
        let t = topo.twin(hx)?;
        if t == NONE || sharp_edge(topo, sharp, topo.edge(hx)?, NONE)? {
            Ok(kobbelt::extrapolate(ep(hx)?, ep(hy)?))
        } else {
            ep(topo.next(topo.next(t)?)?)
        }
    };
    for (f, out) in (0u32..).zip(fpos.iter_mut()) {
        let r = topo.face_half_edges(f)?;
        let (h0, h1, h2, h3) = (r.start, r.start + 1, r.start + 2, r.start + 3);
        let fa = kobbelt::four_point(outer(h0, h2)?, ep(h0)?, ep(h2)?, outer(h2, h0)?);
        let fb = kobbelt::four_point(outer(h1, h3)?, ep(h1)?, ep(h3)?, outer(h3, h1)?);
        *out = midpoint(fa, fb);
    }
    Ok(())
}

/// The tagged Kobbelt edge point of edge `e`.
fn kobbelt_edge(topo: &Topology<'_, '_>, sharp: &Sharpness<'_>, e: u32) -> Result<Point> {
    let h = topo.edge_half_edge(e)?;
    let (i0, i1) = (topo.origin(h)?, topo.dest(h)?);
    if !crease::is_sharp(sharp.edge(topo, e)?) {
        return kobbelt_smooth(topo, sharp, e);
    }
    let (a0, a1) = (topo.position(i0)?, topo.position(i1)?);
    let p0 = crease_beyond(topo, sharp, i0, i1)?;
    let p1 = crease_beyond(topo, sharp, i1, i0)?;
    let curve = kobbelt::four_point(p0, a0, a1, p1);
    let w = edge_crease_weight(topo, sharp, e, i0, i1)?;
    if w == 1.0 {
        return Ok(curve);
    }
    Ok(crease::blend(w, curve, kobbelt_smooth(topo, sharp, e)?))
}

/// The smooth Kobbelt rule of edge `e` with the other edges' tags: the untagged rule
/// ([`linear::kobbelt_edge`]) with every vertex on two or more sharp edges taken as a
/// boundary vertex (the point beyond it extrapolated). `e` itself counts as smooth.
fn kobbelt_smooth(topo: &Topology<'_, '_>, sharp: &Sharpness<'_>, e: u32) -> Result<Point> {
    let h = topo.edge_half_edge(e)?;
    if topo.twin(h)? == NONE {
        return linear::kobbelt_edge(topo, e);
    }
    let (i0, i1) = (topo.origin(h)?, topo.dest(h)?);
    let (a0, a1) = (topo.position(i0)?, topo.position(i1)?);
    let beyond = |v: u32, a: Point, toward: u32, b: Point| -> Result<Point> {
        if sharp_count(topo, sharp, v, e)? >= 2 {
            Ok(kobbelt::extrapolate(a, b))
        } else {
            kobbelt_beyond(topo, v, toward)
        }
    };
    let r0 = beyond(i0, a0, i1, a1)?;
    let r1 = beyond(i1, a1, i0, a0)?;
    Ok(kobbelt::four_point(r0, a0, a1, r1))
}
