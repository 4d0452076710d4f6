//! Möbius Simplest (Peters–Reif mid-edge; seed 000 §4.3): every interior edge blends the
//! midpoints taken in its two end points' forms (`F4(v_j, e_j, e_k, v_k)`), boundary edges
//! follow the Möbius interpolating curve rule; boundary and isolated vertices are carried
//! through in the linear layout.

use super::super::driver::Driver;
use super::super::form::{MapBack, ORIGIN};
use crate::error::Result;
use crate::mesh::{Topology, NONE};
use crate::point::{midpoint, Point};
use crate::scheme::carry::{append_isolated, boundary_vertices};
use crate::stencil::simplest;

pub(in crate::scheme::mobius) fn run(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    d.vertex_pass(
        false,
        || (),
        |p, star, ()| {
            for (j, s) in star.spokes.iter().enumerate() {
                if s.half_edge == NONE || topo.twin(s.half_edge)? == NONE {
                    continue;
                }
                let form = &mut *star.form;
                if let Ok(c) = form
                    .canon(topo, s.neighbour)
                    .and_then(|b| form.back(simplest::edge_point(ORIGIN, b)))
                {
                    p.set_edge(star, j, c)?;
                }
            }
            Ok(())
        },
    )?;
    let linear = |t: &Topology<'_, '_>, e: u32| -> Result<Point> {
        let (a, b) = t.edge_vertices(e)?;
        Ok(simplest::edge_point(t.position(a)?, d.topo.position(b)?))
    };
    d.blend_interior_edges(0, &linear)?;
    d.boundary_edges(0, |_, a, b, _| midpoint(a, b))?;
    // Then the boundary vertices and the isolated vertices, as the linear layout.
    let ne = topo.num_edges();
    boundary_vertices(topo, d.pos, ne)?;
    append_isolated(topo, d.pos, ne + topo.num_boundary_vertices())
}
