//! The canonical Möbius Loop rules at one vertex star (seed 000 §4.1 steps 1–3, §4.3 "Loop":
//! a 1-ring scheme): Loop's vertex and edge stencils ([`crate::stencil::loop_scheme`]) on the
//! 1-ring mapped into the star's canonical form.

use super::super::form::{interior_spoke, present, star_form, MapBack, Ring, MISSING, ORIGIN};
use crate::error::{Error, Result, Status};
use crate::mesh::{get, set};
use crate::point::Point;
use crate::stencil::loop_scheme;

/// The Loop rules in a star's canonical form (normalised frame, centre at the origin): the vertex
/// point of a closed star, and the edge candidate of every interior spoke `j`, `edge_interior(0,
/// r_j, r_{j+1}, r_{j−1})` (the two apexes of a triangle fan are the ring neighbours of the spoke),
/// each mapped back with `form`. `ring` holds the images of the neighbours; a rule whose value
/// cannot be mapped back leaves its slot [`MISSING`] (`None` for the vertex point). The driver and
/// [`loop_star`] both evaluate the star here.
#[inline(always)]
pub(in crate::scheme::mobius) fn loop_star_in_form(
    ring: &[Point],
    closed: bool,
    form: &impl MapBack,
    edge_candidates: &mut [Point],
) -> Result<Option<Point>> {
    let n = ring.len();
    let vertex = if closed {
        loop_scheme::vertex_interior(ORIGIN, ring)
            .and_then(|p| form.back(p))
            .ok()
    } else {
        None
    };
    for j in 0..n {
        let c = if interior_spoke(closed, j, n) {
            let b = get(ring, j)?;
            let c = get(ring, (j + 1) % n)?;
            let d = get(ring, (j + n - 1) % n)?;
            form.back(loop_scheme::edge_interior(ORIGIN, b, c, d))
                .unwrap_or(MISSING)
        } else {
            MISSING
        };
        set(edge_candidates, j, c)?;
    }
    Ok(vertex)
}

/// The canonical Möbius Loop rules at one vertex star (seed 000 §4.1 steps 1–3), exactly as
/// the Möbius mesh driver ([`crate::scheme::subdivide`]) evaluates them for
/// [`crate::scheme::Scheme::Loop`]: the canonical form of `v ring…` (`closed`: a cyclic ring
/// of an interior vertex; otherwise the
/// ring runs from one boundary neighbour to the other, counter-clockwise), Loop's stencils on
/// the mapped 1-ring, the results mapped back.
///
/// Returns the vertex point of an interior vertex (`None` for a boundary vertex, whose
/// vertex point is the boundary curve rule, or when it cannot be mapped back), and writes
/// `edge_candidates[j]`, the candidate of the edge to `ring[j]`, for every interior spoke; the
/// other slots (boundary spokes, candidates at infinity) are NaN. An edge point is then
/// `F4(a, e_a, e_b, b)` of the candidates of both end points ([`crate::blend::f4_hinted`],
/// hint the apex of the triangle on the left of `a → b`), the single candidate when only one
/// exists, or the linear rule when none does.
///
/// Bit-identical to the driver when `ring` starts at the same spoke (the driver's star
/// starts at the vertex's lowest-numbered outgoing half-edge, see
/// [`crate::mesh::Topology::star`]); another rotation changes the last bits only.
///
/// # Errors
/// [`Status::BufferTooSmall`] when `edge_candidates` is shorter than `ring`; the errors of
/// [`crate::mobius::CanonicalForm::new`] (the star has no canonical form: the driver takes
/// the linear rule for everything this star would give); [`Status::DegenerateGeometry`]
/// naming the ring index of a neighbour the form sends to infinity.
/// Nothing is written to the output buffers when an error is returned.
pub fn loop_star(
    v: Point,
    ring: &[Point],
    closed: bool,
    edge_candidates: &mut [Point],
) -> Result<Option<Point>> {
    if edge_candidates.len() < ring.len() {
        return Err(Error::too_small(ring.len()));
    }
    let mut images = Ring::new();
    let cf = star_form(v, ring, closed, &mut images)?;
    if let Some(i) = images.iter().position(|p| !present(p)) {
        // The driver takes no candidate from a star with a neighbour at infinity.
        return Err(Error::at(Status::DegenerateGeometry, i as u32));
    }
    loop_star_in_form(&images, closed, &cf, edge_candidates)
}
