//! Möbius Modified Butterfly (seed 000 §4.3, Fig. 11 right, "partial candidates"): old
//! vertices stay (interpolating); every interior spoke of a star with a form gets the
//! candidate of [`butterfly_star_in_form`], interior edges blend the candidates of their two
//! end points (or take the single one next to an irregular vertex), boundary loops follow the
//! Möbius interpolating curve rule.

use super::super::audit::Children;
use super::super::driver::Driver;
use super::super::form::{Frame, MISSING};
use super::super::guard::{CreaseEdges, EdgeBlend, Outputs};
use super::super::rules::butterfly_star_in_form;
use super::super::toward_linear::{face_centroid, no_corner, LinearRules};
use super::super::vertex_pass::{Part, Star};
use super::super::workspace::take;
use crate::error::Result;
use crate::mesh::{Topology, NONE};
use crate::point::Point;
use crate::scheme::carry::copy_old;
use crate::scheme::interpolating_tagged::butterfly_edge as butterfly_edge_tagged;
use crate::scheme::linear::butterfly_edge;
use crate::stencil::butterfly;

/// How far around a distrusted star the fold guard's blend toward the linear rule reaches
/// (`toward_linear.rs`): two rings, measured (`docs/folds.md` section 8: with only the
/// star's own edges, cow folds 160 / 181 edges at levels 2 / 3 where linear Butterfly folds
/// 155 / 179, and camelhead 4 at level 3 where it folds none).
const RINGS: u8 = 2;

pub(in crate::scheme::mobius) fn run(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    let nv = topo.num_vertices();
    copy_old(topo, d.pos)?;
    d.vertex_pass(false, || (), star_rule)?;
    let linear = |t: &Topology<'_, '_>, e: u32| -> Result<Point> { butterfly_edge(t, e) };
    // The boundary curves before the blends: the audit reads every output point of the
    // step, and the blends may run twice (their fallbacks are rewound, these stay).
    d.boundary_edges(nv, butterfly::edge_boundary)?;
    let before = d.report;
    d.blend_interior_edges(nv, &linear)?;
    if d.guard {
        // The fold guard (`guard.rs`): judge the paper's output, re-evaluate the distrusted
        // stars, blend again.
        d.trust_edges(EdgeBlend::Candidates, CreaseEdges::ButterflyCorners)?;
        d.audit(Children::Triangles {
            edges: nv,
            middles: true,
        })?;
        let out = Outputs {
            vertex: false,
            edges: Some(nv),
            faces: None,
            corners: false,
            boundary_edges: false,
            rings: RINGS,
            vertex_rings: RINGS,
            crease_edge_faces: false,
        };
        // The linear rule the guard moves toward (and a fallback of the second blends takes):
        // on a tagged level, the linear rule with the level's tags (`interpolating_tagged.rs`)
        // on the uncut level, the values read in whole levels as the cut reads them
        // (`crease::Uncut`). The cut level's own linear rule differs from it only at the
        // chains the cut gives up as darts, which it refines smooth, and which fold there as
        // untagged linear Butterfly does (`docs/creases.md`, "Folds next to corners", (g)).
        // Which points move and their weights τ come from the trusts alone, never from this
        // rule.
        let uncut = d.uncut;
        let tagged = |t: &Topology<'_, '_>, e: u32| -> Result<Point> {
            match uncut {
                Some(u) => {
                    let e = u.topo.edge(t.edge_half_edge(e)?)?;
                    butterfly_edge_tagged(u.topo, u.sharp, e)
                }
                None => butterfly_edge(t, e),
            }
        };
        let again = d.guarded_pass(out, || (), star_rule)?;
        if again {
            let near = d.rewind_for_blends_again(before);
            d.blend_interior_edges_again(nv, &tagged, near)?;
        }
        let curves = d.curve_terms_into_trust()?;
        if again || curves || d.any_crease_edge_term() {
            d.blend_toward_linear(
                out,
                LinearRules {
                    vertex: &|_, _, p| Ok(p),
                    edge: &tagged,
                    face: &face_centroid,
                    corner: &no_corner,
                },
                true,
            )?;
        }
        // The crease curves (`boundary.rs`), on a level cut along its sharp edges.
        d.guard_curves(nv, butterfly::edge_boundary, false, RINGS, false)?;
    }
    Ok(())
}

/// The Butterfly candidates of one star in its frame (the canonical form, or the guard's
/// `m_τ`), measured for the guard's trust while still in the frame, then mapped back. The
/// two arrays are the chunk's star workspace (`workspace.rs`).
fn star_rule<F: Frame>(p: &mut Part<'_, '_, '_>, star: &mut Star<'_, F>, _: &mut ()) -> Result<()> {
    p.with_work(|p, work| star_rule_in(p, star, work))
}

/// [`star_rule`] with the chunk's star workspace.
#[inline(always)]
fn star_rule_in<F: Frame>(
    p: &mut Part<'_, '_, '_>,
    star: &mut Star<'_, F>,
    mut work: &mut [Point],
) -> Result<()> {
    let n = star.spokes.len();
    let ring = take(&mut work, n)?;
    let cands = take(&mut work, n)?;
    let topo = p.topo;
    star.ring_images(topo, ring)?;
    for (j, (s, c)) in star.spokes.iter().zip(cands.iter_mut()).enumerate() {
        *c = MISSING;
        let h = s.half_edge;
        if h == NONE || topo.twin(h)? == NONE {
            continue;
        }
        let other = s.neighbour;
        let other_irregular = !topo.is_boundary_vertex(other)? && topo.valence(other)? != 6;
        if let Some(p) = butterfly_star_in_form(ring, !star.boundary, j, other_irregular) {
            *c = p;
        }
    }
    p.trust_star(star, ring, cands, true)?;
    p.keep_edges_from(star, cands)
}
