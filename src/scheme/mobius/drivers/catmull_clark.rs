//! Möbius Catmull–Clark (seed 000 §4.3): the vertex pass maps every face around a vertex into
//! its form once, keeping the face centroids as face candidates and feeding them to the edge
//! and vertex rules ([`catmull_clark_star_in_form`]); face points blend the face candidates
//! (§4.4.3), interior edges their two edge candidates, boundary loops follow the Möbius
//! approximating curve rule. Ears take their face candidates from a substitute's form.

use super::super::driver::Driver;
use super::super::form::{FacePts, Ring, MISSING};
use super::super::rules::catmull_clark_star_in_form;
use crate::error::Result;
use crate::mesh::gather::face_points;
use crate::mesh::{internal, set};
use crate::point::Point;
use crate::stencil::{catmull_clark, centroid};
use crate::MAX_VALENCE;

pub(in crate::scheme::mobius) fn run(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    let nv = topo.num_vertices();
    let fp0 = nv + topo.num_edges();
    // Ears first (substitute forms); every other corner's candidate comes from the vertex
    // pass below, which maps each face into the corner's form once.
    d.ear_face_candidates()?;
    d.clear_vertex_points()?;
    let mut ring = Ring::new();
    let mut fc = Ring::new();
    let mut pts = FacePts::new();
    let mut cands = [MISSING; MAX_VALENCE];
    d.vertex_pass(|d, star| {
        // Canonical centroids of the faces after each spoke and images of the neighbours
        // ([`MISSING`] when unavailable).
        star.face_centroids(topo, &mut fc, &mut pts)?;
        d.keep_face_candidates(star, &fc)?;
        star.ring_images(topo, &mut ring)?;
        let form = &*star.form;
        let vertex = catmull_clark_star_in_form(&ring, &fc, !star.boundary, form, &mut cands)?;
        d.keep_edge_candidates(star.spokes, &cands)?;
        if let Some(q) = vertex {
            set(d.pos, star.v as usize, q)?;
        }
        Ok(())
    })?;
    d.finish_vertex_points(false, |t, v, p| {
        let mut ring = Ring::new();
        let mut faces = Ring::new();
        for s in t.star(v) {
            ring.try_push(t.position(s.neighbour)?)
                .map_err(|_| internal())?;
            faces
                .try_push(centroid(&face_points(t, s.face)?)?)
                .map_err(|_| internal())?;
        }
        catmull_clark::vertex_interior(p, &ring, &faces)
    })?;
    d.blend_faces(fp0)?;
    let linear = |d: &Driver<'_, '_, '_, '_>, e: u32| -> Result<Point> {
        let t = d.topo;
        let h = t.edge_half_edge(e)?;
        Ok(catmull_clark::edge_interior(
            t.position(t.origin(h)?)?,
            t.position(t.dest(h)?)?,
            centroid(&face_points(t, t.face(h)?)?)?,
            centroid(&face_points(t, t.face(t.twin(h)?)?)?)?,
        ))
    };
    d.blend_interior_edges(nv, &linear)?;
    d.boundary_edges(nv, |_, a, b, _| catmull_clark::edge_boundary(a, b))?;
    d.boundary_vertices_approximating(nv)
}
