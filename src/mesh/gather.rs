//! Neighbourhood gathers: the points a rule reads around a vertex, a face or an edge, in the
//! order the rules expect them (stars counter-clockwise from their first spoke, faces in face
//! order). Every driver, linear, spherelike and Möbius, gathers through these, so one
//! neighbourhood is read the same way everywhere.

use arrayvec::ArrayVec;

use super::Topology;
use crate::error::Result;
use crate::point::{add, Point};
use crate::MAX_VALENCE;

/// Points of a vertex ring, one per spoke.
pub(crate) type Ring = ArrayVec<Point, MAX_VALENCE>;

/// The number of `v`'s neighbours and the sum of their positions, counter-clockwise from
/// the star's first spoke and left to right ([`crate::point::sum`] of the ring's points):
/// the linear rules that read a ring only through its sum take this, with no array.
pub(crate) fn ring_sum(topo: &Topology<'_, '_>, v: u32) -> Result<(usize, Point)> {
    let mut n = 0;
    let mut s = [0.0; 3];
    for spoke in topo.star(v) {
        s = add(s, topo.position(spoke.neighbour)?);
        n += 1;
    }
    Ok((n, s))
}

/// The number of corners of face `f` and the sum of their positions, in face order and left
/// to right ([`crate::point::sum`] of the face's points).
pub(crate) fn face_sum(topo: &Topology<'_, '_>, f: u32) -> Result<(usize, Point)> {
    let corners = topo.face_vertices(f)?;
    let mut s = [0.0; 3];
    for &v in corners {
        s = add(s, topo.position(v)?);
    }
    Ok((corners.len(), s))
}

/// The other boundary neighbour of boundary vertex `v` (not `other`): the next point along
/// the boundary loop beyond `v`, away from `other`.
pub(crate) fn boundary_beyond(topo: &Topology<'_, '_>, v: u32, other: u32) -> Result<u32> {
    let (b0, b1) = topo.boundary_neighbours(v)?;
    Ok(if b0 == other { b1 } else { b0 })
}

/// The corner after `dest(h)` in the face of half-edge `h`: the third vertex of a
/// triangle, the corner opposite `origin(h)` in a quad.
pub(crate) fn apex(topo: &Topology<'_, '_>, h: u32) -> Result<u32> {
    topo.dest(topo.next(h)?)
}
