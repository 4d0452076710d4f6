//! Möbius Simplest (Peters–Reif mid-edge; seed 000 §4.3): every interior edge blends the
//! midpoints taken in its two end points' forms (`F4(v_j, e_j, e_k, v_k)`), boundary edges
//! follow the Möbius interpolating curve rule; boundary and isolated vertices are carried
//! through in the linear layout.

use super::super::audit::Children;
use super::super::driver::Driver;
use super::super::edges::LinearEdge;
use super::super::form::{MapBack, ORIGIN};
use super::super::guard::{CreaseEdges, EdgeBlend, Outputs};
use super::super::toward_linear::{no_corner, LinearRules};
use super::super::workspace::take;
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
            // The fold guard's spread term, from the ring's images (`guard.rs`); the form's
            // memo keeps them for the midpoints below.
            if p.guard {
                p.with_work(|p, mut work| {
                    let ring = take(&mut work, star.spokes.len())?;
                    star.ring_images(topo, ring)?;
                    p.trust_star(star, ring, &[], true)
                })?;
            }
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
    // Then the boundary vertices and the isolated vertices, as the linear layout. Before the
    // fold guard: its audit reads a boundary star's own output vertex, which closes the
    // star's V-face.
    let ne = topo.num_edges();
    boundary_vertices(topo, d.pos, ne)?;
    append_isolated(topo, d.pos, ne + topo.num_boundary_vertices())?;
    if d.guard {
        fold_guard(d, &linear)?;
    }
    Ok(())
}

/// How far around a distrusted star the fold guard's blend toward the linear rule reaches
/// (`toward_linear.rs`), measured (`docs/folds.md` section 11).
const RINGS: u8 = 1;

/// The fold guard (`guard.rs`) on the paper's output of the step: the spread term of every
/// interior star (kept by the vertex pass), the F4-angle term of every interior edge's blend
/// of its two midpoints (as Loop's), and the output audit of each star's V-face and the
/// F-faces around it (`audit.rs`, [`Children::MidEdges`]); spherical stars keep the paper's
/// rules (`Driver::raise_spherical_quads`); then every interior edge point within one ring of
/// a distrusted star moves toward the edge's midpoint (`toward_linear.rs`). A star's only
/// rule is the midpoint in its form, which an interpolated form would only move toward the
/// same blend, so there is no re-evaluation in `m_τ`.
#[inline(never)]
fn fold_guard(d: &mut Driver<'_, '_, '_, '_>, linear: &LinearEdge<'_>) -> Result<()> {
    d.trust_edges(EdgeBlend::Candidates, CreaseEdges::Off)?;
    d.audit(Children::MidEdges { edges: 0 })?;
    d.raise_spherical_quads()?;
    if d.trust.iter().all(|&t| t >= 1.0) {
        return Ok(());
    }
    let out = Outputs {
        vertex: false,
        edges: Some(0),
        faces: None,
        corners: false,
        boundary_edges: true,
        rings: RINGS,
        vertex_rings: RINGS,
        crease_edge_faces: false,
    };
    let rules = LinearRules {
        vertex: &|_, _, p| Ok(p),
        edge: linear,
        face: &|_, _| Err(crate::mesh::internal()),
        corner: &no_corner,
    };
    d.blend_toward_linear(out, rules, false)
}
