//! Möbius Loop (seed 000 §4.3): the vertex pass gives every interior vertex its vertex point
//! and every spoke its edge candidate ([`loop_star_in_form`]); interior edges blend their two
//! candidates, boundary loops follow the Möbius approximating curve rule.

use super::super::audit::Children;
use super::super::driver::Driver;
use super::super::form::{Frame, Normalised};
use super::super::guard::{CreaseEdges, EdgeBlend, Outputs};
use super::super::rules::loop_star_in_form;
use super::super::toward_linear::{face_centroid, no_corner, LinearRules};
use super::super::vertex_pass::{Part, Star};
use super::super::workspace::take;
use crate::error::Result;
use crate::mesh::gather::{apex, ring_sum};
use crate::mesh::Topology;
use crate::point::Point;
use crate::stencil::loop_scheme;

/// How far around a distrusted star the fold guard's blend toward the linear rule reaches
/// (`toward_linear.rs`): two rings, measured (`docs/folds.md` section 8: with one ring, epcot
/// still folds 24 edges at levels 1 and 2 where the linear scheme folds none).
const RINGS: u8 = 2;

pub(in crate::scheme::mobius) fn run(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    let nv = topo.num_vertices();
    d.clear_vertex_points()?;
    d.vertex_pass(true, || (), star_rule)?;
    let linear_vertex = |t: &Topology<'_, '_>, v: u32, p: Point| -> Result<Point> {
        // The ring's sum as the star is walked (no 3 KB array of ring points on the stack).
        let (n, ring) = ring_sum(t, v)?;
        loop_scheme::vertex_interior_sum(p, n, ring)
    };
    d.finish_vertex_points(false, linear_vertex)?;
    let linear = |t: &Topology<'_, '_>, e: u32| -> Result<Point> {
        let h = t.edge_half_edge(e)?;
        Ok(loop_scheme::edge_interior(
            t.position(t.origin(h)?)?,
            t.position(t.dest(h)?)?,
            t.position(apex(t, h)?)?,
            t.position(apex(t, t.twin(h)?)?)?,
        ))
    };
    // The boundary curves before the blends: the audit reads every output point of the
    // step, and the blends may run twice (their fallbacks are rewound, these stay).
    d.boundary_edges(nv, |_, a, b, _| loop_scheme::edge_boundary(a, b))?;
    d.boundary_vertices_approximating(nv)?;
    let before = d.report;
    d.blend_interior_edges(nv, &linear)?;
    if d.guard {
        // The fold guard (`guard.rs`): judge the paper's output, re-evaluate the distrusted
        // stars, blend again.
        d.trust_edges(EdgeBlend::Candidates, CreaseEdges::F4Angle)?;
        d.audit(Children::Triangles {
            edges: nv,
            middles: false,
        })?;
        let out = Outputs {
            vertex: true,
            edges: Some(nv),
            faces: None,
            corners: false,
            boundary_edges: false,
            rings: RINGS,
            vertex_rings: RINGS,
            crease_edge_faces: false,
        };
        let again = d.guarded_pass(out, || (), star_rule)?;
        if again {
            let near = d.rewind_for_blends_again(before);
            d.blend_interior_edges_again(nv, &linear, near)?;
        }
        let curves = d.curve_terms_into_trust()?;
        if again || curves || d.any_crease_edge_term() {
            d.blend_toward_linear(
                out,
                LinearRules {
                    vertex: &linear_vertex,
                    edge: &linear,
                    face: &face_centroid,
                    corner: &no_corner,
                },
                true,
            )?;
        }
        // The crease curves (`boundary.rs`), on a level cut along its sharp edges.
        d.guard_curves(
            nv,
            |_, a, b, _| loop_scheme::edge_boundary(a, b),
            true,
            RINGS,
            false,
        )?;
    }
    Ok(())
}

/// The Loop rules of one star in its frame (the canonical form, or the guard's `m_τ`): the
/// vertex point and the edge candidates, measured for the guard's trust while still in the
/// frame, then mapped back. A star whose ring is not all in the frame gives nothing. The
/// two arrays are the chunk's star workspace (`workspace.rs`).
fn star_rule<F: Frame>(p: &mut Part<'_, '_, '_>, star: &mut Star<'_, F>, _: &mut ()) -> Result<()> {
    p.with_work(|p, mut work| {
        let n = star.spokes.len();
        let ring = take(&mut work, n)?;
        if !star.ring_images(p.topo, ring)? {
            return Ok(());
        }
        // Every entry is written by the rule before it is read.
        let cands = take(&mut work, n)?;
        // The apexes of spoke j's triangles are ring[j ± 1] (stars are CCW).
        let vertex = loop_star_in_form(ring, !star.boundary, &Normalised, cands)?;
        p.trust_star(star, ring, cands, true)?;
        p.keep_edges_from(star, cands)?;
        p.keep_vertex_from(star, vertex)
    })
}
