//! The canonical Möbius Modified Butterfly rule at one vertex star (seed 000 §4.3, Fig. 11
//! right, "partial candidates"): the Butterfly stencil reaches into the 2-ring, which no
//! single canonical form holds regularly, so each end point of an edge contributes the part
//! of the stencil its own star sees, in its own form.
//!
//! For spoke `j` of the star of `v` (the edge to `ring[j]`):
//! * `v` interior and irregular (valence ≠ 6): Zorin's stencil of `v`
//!   ([`butterfly::zorin_stencil`]), ring from `ring[j]`;
//! * else, when `ring[j]` is an interior vertex of valence ≠ 6: no candidate from this star
//!   (only the singular ring contributes, §4.3);
//! * else `v`'s half of the 8-point stencil, doubled ([`butterfly::edge_half`]): `v`,
//!   `ring[j]`, the opposite vertices `ring[j ± 1]` and `v`'s wings `ring[j ± 2]`, a wing
//!   across a boundary edge replaced by the reflection `u + w − z` as OpenMesh does
//!   ([`butterfly::reflect`]).

use super::super::form::{interior_spoke, present, star_form, Ring, MISSING, ORIGIN};
use crate::error::{Error, Result, Status};
use crate::mesh::set;
use crate::point::Point;
use crate::stencil::butterfly;

/// `p[(j + k) mod n]` for a signed offset `k`, [`MISSING`] for an empty ring.
fn cyc(p: &[Point], j: usize, k: isize) -> Point {
    let n = p.len() as isize;
    if n == 0 {
        return MISSING;
    }
    let i = (j as isize + k).rem_euclid(n) as usize;
    p.get(i).copied().unwrap_or(MISSING)
}

/// The candidate of spoke `j` of a star in its canonical form (module docs): `images` are
/// the ring's images in the normalised frame (centre at the origin), `closed` whether the
/// star is closed, `neighbour_irregular` whether `ring[j]` is an interior vertex of valence
/// ≠ 6. `None` when the rule gives no candidate or an image it needs is [`MISSING`]. The
/// result is in the normalised frame (not yet mapped back). The driver and
/// [`butterfly_star`] both evaluate each spoke here.
#[inline(always)]
pub(in crate::scheme::mobius) fn butterfly_star_in_form(
    images: &[Point],
    closed: bool,
    j: usize,
    neighbour_irregular: bool,
) -> Option<Point> {
    let n = images.len();
    let o = ORIGIN;
    if closed && n != 6 {
        // The ring rotated to start at spoke `j`, read in place (no rotated copy on the
        // stack): `zorin_stencil` of the rotated ring bit for bit.
        let rotated = |k: usize| cyc(images, j, k as isize);
        if !(0..n).all(|k| present(&rotated(k))) {
            return None;
        }
        return butterfly::zorin_stencil_of(o, n, (0..n).map(|k| Ok(rotated(k)))).ok();
    }
    if neighbour_irregular {
        return None;
    }
    let a1 = cyc(images, j, 0);
    let b0 = cyc(images, j, 1);
    let b1 = cyc(images, j, -1);
    // The wings across the triangle edges at the centre: (v, ring[j+1]) and (v, ring[j−1]);
    // in an open star the first and last spokes are boundary edges.
    let c0 = if !closed && j + 2 == n {
        butterfly::reflect(b0, o, a1)
    } else {
        cyc(images, j, 2)
    };
    let c1 = if !closed && j == 1 {
        butterfly::reflect(o, b1, a1)
    } else {
        cyc(images, j, -2)
    };
    if ![a1, b0, b1, c0, c1].iter().all(present) {
        return None;
    }
    Some(butterfly::edge_half(o, a1, b0, b1, c0, c1))
}

/// The canonical Möbius Modified Butterfly rule at the vertex star `v ring…` (`ring` and
/// `closed` as for [`super::loop_star`]; the faces are triangles), exactly as
/// the Möbius mesh driver ([`crate::scheme::subdivide`]) evaluates it for
/// [`crate::scheme::Scheme::ModifiedButterfly`]: the star's canonical form, then for each
/// interior spoke `j` the candidate of the edge to `ring[j]` by the module's rule, mapped
/// back. `irregular_neighbours[j]` says whether `ring[j]` is an interior vertex of valence
/// ≠ 6; an empty slice means none is.
///
/// Writes `edge_candidates[j]` for every spoke: NaN for boundary spokes, the skipped spokes,
/// a rule that needs a point the form sends to infinity, and every spoke of an *ear* (a
/// boundary star of one face), to which the driver gives no form. Old vertices keep their
/// positions (the scheme interpolates); edge points are
/// [`crate::blend::f4_hinted`]`(a, e_a, e_b, b, x)` of both end points' candidates (hint: the
/// third vertex of the triangle on the left of `a → b`, `a` the smaller index), the one
/// candidate when the other is NaN; boundary edges `F4(P_{i−1}, P_i, P_{i+1}, P_{i+2})`; what
/// has no value takes the linear rule (the driver's fallback).
///
/// Bit-identical to the driver for any rotation of the ring (each spoke's rule reads the
/// ring relative to that spoke), as long as the images are those of the driver's form, which
/// does not depend on where the ring starts.
///
/// # Errors
/// [`Status::BufferTooSmall`] when `edge_candidates` is shorter than `ring`;
/// [`Status::InvalidArgument`] when `irregular_neighbours` is neither empty nor as long as
/// `ring`; [`Status::TooFewPoints`] for fewer than 2 neighbours; the errors of
/// [`crate::mobius::CanonicalForm::new`] (the star has no canonical form: the driver takes
/// the linear rule for everything this star gives).
/// Nothing is written to the output buffers when an error is returned.
pub fn butterfly_star(
    v: Point,
    ring: &[Point],
    closed: bool,
    irregular_neighbours: &[bool],
    edge_candidates: &mut [Point],
) -> Result<()> {
    let n = ring.len();
    if edge_candidates.len() < n {
        return Err(Error::too_small(n));
    }
    if !irregular_neighbours.is_empty() && irregular_neighbours.len() != n {
        return Err(Error::new(Status::InvalidArgument));
    }
    if n < 2 {
        return Err(Error::new(Status::TooFewPoints));
    }
    let out = edge_candidates.get_mut(..n).ok_or(Error::too_small(n))?;
    // An ear (open star of one face): the driver gives it no form, so no candidates.
    if !closed && n == 2 {
        out.fill(MISSING);
        return Ok(());
    }
    // The form first, so that nothing is written when the star has none.
    let mut images = Ring::new();
    let cf = star_form(v, ring, closed, &mut images)?;
    out.fill(MISSING);
    for j in 0..n {
        if !interior_spoke(closed, j, n) {
            continue;
        }
        let irregular = irregular_neighbours.get(j).copied().unwrap_or(false);
        if let Some(p) = butterfly_star_in_form(&images, closed, j, irregular) {
            set(out, j, cf.from_normalised(p).unwrap_or(MISSING))?;
        }
    }
    Ok(())
}
