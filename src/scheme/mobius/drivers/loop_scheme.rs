//! Möbius Loop (seed 000 §4.3): the vertex pass gives every interior vertex its vertex point
//! and every spoke its edge candidate ([`loop_star_in_form`]); interior edges blend their two
//! candidates, boundary loops follow the Möbius approximating curve rule.

use super::super::driver::Driver;
use super::super::form::{Ring, MISSING};
use super::super::rules::loop_star_in_form;
use crate::error::Result;
use crate::mesh::gather::{apex, ring_points};
use crate::mesh::set;
use crate::point::Point;
use crate::stencil::loop_scheme;
use crate::MAX_VALENCE;

pub(in crate::scheme::mobius) fn run(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    let nv = topo.num_vertices();
    d.clear_vertex_points()?;
    let mut ring = Ring::new();
    let mut cands = [MISSING; MAX_VALENCE];
    d.vertex_pass(|d, star| {
        if star.ring_images(topo, &mut ring)? {
            // The apexes of spoke j's triangles are ring[j ± 1] (stars are CCW).
            let form = &*star.form;
            let vertex = loop_star_in_form(&ring, !star.boundary, form, &mut cands)?;
            d.keep_edge_candidates(star.spokes, &cands)?;
            if let Some(q) = vertex {
                set(d.pos, star.v as usize, q)?;
            }
        }
        Ok(())
    })?;
    d.finish_vertex_points(false, |t, v, p| {
        loop_scheme::vertex_interior(p, &ring_points(t, v)?)
    })?;
    let linear = |d: &Driver<'_, '_, '_, '_>, e: u32| -> Result<Point> {
        let t = d.topo;
        let h = t.edge_half_edge(e)?;
        Ok(loop_scheme::edge_interior(
            t.position(t.origin(h)?)?,
            t.position(t.dest(h)?)?,
            t.position(apex(t, h)?)?,
            t.position(apex(t, t.twin(h)?)?)?,
        ))
    };
    d.blend_interior_edges(nv, &linear)?;
    d.boundary_edges(nv, |_, a, b, _| loop_scheme::edge_boundary(a, b))?;
    d.boundary_vertices_approximating(nv)
}
