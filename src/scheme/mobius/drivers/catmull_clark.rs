//! Möbius Catmull–Clark (seed 000 §4.3): the vertex pass maps every face around a vertex into
//! its form once, keeping the face centroids as face candidates and feeding them to the edge
//! and vertex rules ([`catmull_clark_star_in_form`]); face points blend the face candidates
//! (§4.4.3), interior edges their two edge candidates, boundary loops follow the Möbius
//! approximating curve rule. Ears take their face candidates from a substitute's form.

use super::super::audit::Children;
use super::super::driver::Driver;
use super::super::form::{Frame, Normalised};
use super::super::guard::{CreaseEdges, EdgeBlend, Outputs};
use super::super::rules::catmull_clark_star_in_form;
use super::super::toward_linear::{face_centroid, no_corner, LinearRules};
use super::super::vertex_pass::{Part, Star};
use super::super::workspace::take;
use crate::error::Result;
use crate::mesh::Topology;
use crate::point::{add, Point};
use crate::stencil::catmull_clark;

/// How far around a distrusted star the fold guard's blend toward the linear rule reaches
/// (`toward_linear.rs`): one ring, measured (`docs/folds.md` section 8: with two rings,
/// polycastle_quad folds 4 edges at level 1 where the linear scheme folds none).
const RINGS: u8 = 1;

pub(in crate::scheme::mobius) fn run(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    let nv = topo.num_vertices();
    let fp0 = nv + topo.num_edges();
    // Ears first (substitute forms); every other corner's candidate comes from the vertex
    // pass below, which maps each face into the corner's form once.
    d.ear_face_candidates()?;
    d.clear_vertex_points()?;
    d.vertex_pass(true, || (), star_rule)?;
    let linear_vertex = |t: &Topology<'_, '_>, v: u32, p: Point| -> Result<Point> {
        // The ring and the face points summed as the star is walked, as the linear scheme
        // does (no arrays of points on the stack; the same bits as the slice form).
        let (mut n, mut ring, mut faces) = (0, [0.0; 3], [0.0; 3]);
        for s in t.star(v) {
            ring = add(ring, t.position(s.neighbour)?);
            faces = add(faces, face_centroid(t, s.face)?);
            n += 1;
        }
        catmull_clark::vertex_interior_sums(p, n, ring, faces)
    };
    d.finish_vertex_points(false, linear_vertex)?;
    let linear = |t: &Topology<'_, '_>, e: u32| -> Result<Point> {
        let h = t.edge_half_edge(e)?;
        Ok(catmull_clark::edge_interior(
            t.position(t.origin(h)?)?,
            t.position(t.dest(h)?)?,
            face_centroid(t, t.face(h)?)?,
            face_centroid(t, t.face(t.twin(h)?)?)?,
        ))
    };
    // The boundary curves before the blends: the audit reads every output point of the
    // step, and the blends may run twice (their fallbacks are rewound, these stay).
    d.boundary_edges(nv, |_, a, b, _| catmull_clark::edge_boundary(a, b))?;
    d.boundary_vertices_approximating(nv)?;
    let before = d.report;
    d.blend_faces(fp0)?;
    d.blend_interior_edges(nv, &linear)?;
    if d.guard {
        // The fold guard (`guard.rs`): judge the paper's output, re-evaluate the distrusted
        // stars, blend again.
        d.trust_edges(EdgeBlend::Candidates, CreaseEdges::Off)?;
        d.audit(Children::Quads {
            edges: nv,
            faces: fp0,
            edge_places: false,
        })?;
        let out = Outputs {
            vertex: true,
            edges: Some(nv),
            faces: Some(fp0),
            corners: false,
            boundary_edges: false,
            rings: RINGS,
            vertex_rings: RINGS,
            crease_edge_faces: false,
        };
        let again = d.guarded_pass(out, || (), star_rule)?;
        if again {
            let near = d.rewind_for_blends_again(before);
            d.blend_faces_again(fp0, near)?;
            d.blend_interior_edges_again(nv, &linear, near)?;
        }
        let curves = d.curve_terms_into_trust()?;
        if again || curves {
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
            |_, a, b, _| catmull_clark::edge_boundary(a, b),
            true,
            RINGS,
            false,
        )?;
    }
    Ok(())
}

/// The Catmull–Clark rules of one star in its frame (the canonical form, or the guard's
/// `m_τ`): the canonical centroids of the faces after each spoke and the images of the
/// neighbours ([`MISSING`] when unavailable), the face candidates, edge candidates (measured
/// for the guard's trust while still in the frame) and the vertex point, mapped back. The
/// three arrays are the chunk's star workspace (`workspace.rs`).
fn star_rule<F: Frame>(p: &mut Part<'_, '_, '_>, star: &mut Star<'_, F>, _: &mut ()) -> Result<()> {
    p.with_work(|p, mut work| {
        let topo = p.topo;
        let n = star.spokes.len();
        let fc = take(&mut work, n)?;
        let ring = take(&mut work, n)?;
        // Every entry is written by the rules below before it is read.
        let cands = take(&mut work, n)?;
        star.face_centroids(topo, fc)?;
        p.keep_face_candidates(star, fc)?;
        star.ring_images(topo, ring)?;
        let vertex = catmull_clark_star_in_form(ring, fc, !star.boundary, &Normalised, cands)?;
        p.trust_star(star, ring, cands, true)?;
        p.keep_edges_from(star, cands)?;
        p.keep_vertex_from(star, vertex)
    })
}
