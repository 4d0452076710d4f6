//! The canonical Möbius Kobbelt rule at one vertex star (seed 000 §4.3, Fig. 11 left,
//! "virtual points"): Kobbelt's 4-point edge rule needs, at each end of an edge, the next
//! point along the grid line; at an extraordinary vertex that point is virtual, and the star
//! gives it in its canonical form.
//!
//! For spoke `j` of the star of `v` (the grid line from `ring[j]` through `v`), the point
//! beyond `v`:
//! * interior `v`: Kobbelt's virtual point [`kobbelt::virtual_point`] of the ring and the
//!   diagonals (the real opposite neighbour at valence 4; the rule and its derivation are in
//!   [`crate::stencil::kobbelt`]);
//! * boundary `v`: the end extrapolation `2v − u` of the 4-point curve
//!   ([`kobbelt::extrapolate`]), evaluated in `v`'s boundary form so that it is
//!   Möbius-invariant, for every interior spoke (boundary edges follow their boundary loop).
//!
//! The edge point of `(a, b)` is then `F4(r_a, a, b, r_b)` ([`crate::blend::f4_hinted`], hint
//! the corner after `b` in the face on the left of `a → b`), `r_a` the point beyond `a` on
//! the line from `b` and `r_b` the point beyond `b` on the line from `a`.

use super::super::form::{interior_spoke, present, star_form, MapBack, Ring, MISSING, ORIGIN};
use crate::error::{Error, Result, Status};
use crate::mesh::set;
use crate::point::{self, Point};
use crate::stencil::kobbelt;

/// The point beyond the centre of a star in its canonical form on the grid line of spoke `j`
/// (module docs), mapped back with `form`; `None` where there is none. `ring` and `diagonals`
/// are the images of the neighbours and of the corners opposite the centre in the quads
/// after each spoke ([`MISSING`] where not available; `diagonals` read for a closed star
/// only); `complete` says whether every image of a closed star exists (a closed star gives
/// no points otherwise). The driver and [`kobbelt_star`] both evaluate every spoke here.
#[inline(always)]
pub(in crate::scheme::mobius) fn kobbelt_beyond_in_form(
    ring: &[Point],
    diagonals: &[Point],
    closed: bool,
    complete: bool,
    j: usize,
    form: &impl MapBack,
) -> Option<Point> {
    if closed {
        if !complete {
            return None;
        }
        return kobbelt::virtual_point(ring, diagonals, j)
            .and_then(|p| form.back(p))
            .ok();
    }
    let u = ring.get(j).copied().filter(present)?;
    if !interior_spoke(closed, j, ring.len()) {
        return None;
    }
    form.back(kobbelt::extrapolate(ORIGIN, u)).ok()
}

/// The canonical Möbius Kobbelt rule at the vertex star `v ring…` (`ring` and `closed` as
/// for [`super::loop_star`]; the faces are quads), exactly as the Möbius mesh driver
/// ([`crate::scheme::subdivide`]) evaluates it for [`crate::scheme::Scheme::Kobbelt`]: for
/// every spoke `j`, the point beyond
/// `v` on the grid line from `ring[j]` through `v` (module docs), computed in the star's
/// canonical form and mapped back. `diagonals[j]` is the corner opposite `v` in the quad
/// between spoke `j` and spoke `j + 1`; a closed star needs `ring.len()` of them, an open star
/// reads none (pass an empty slice).
///
/// Writes `beyond[j]` for every spoke: NaN for the two boundary spokes of an open star, for
/// every spoke of an *ear* (a boundary star of one face, to which the driver gives no form),
/// for every spoke of a closed star when an image it needs is at infinity, and where a value
/// cannot be mapped back. Old vertices keep their positions (the scheme interpolates); edge
/// points as in the module docs; the face points blend the new edge points of the two grid
/// lines through the face with F6 (seed 000 §4.4.3, Fig. 14).
///
/// Bit-identical to the driver when `ring` starts at the driver's first spoke.
///
/// # Errors
/// [`Status::BufferTooSmall`] when `beyond` is shorter than `ring`;
/// [`Status::InvalidArgument`] when a closed star's `diagonals` is not as long as `ring`;
/// [`Status::NonFiniteInput`] naming a non-finite diagonal; the errors of
/// [`crate::mobius::CanonicalForm::new`] (the star has no canonical form: the driver takes
/// the linear rule for the edges this star would give).
pub fn kobbelt_star(
    v: Point,
    ring: &[Point],
    closed: bool,
    diagonals: &[Point],
    beyond: &mut [Point],
) -> Result<()> {
    let n = ring.len();
    if beyond.len() < n {
        return Err(Error::too_small(n));
    }
    if closed && diagonals.len() != n {
        return Err(Error::new(Status::InvalidArgument));
    }
    let diagonals = if closed { diagonals } else { &[] };
    if let Some(i) = diagonals.iter().position(|d| !point::is_finite(d)) {
        return Err(Error::at(Status::NonFiniteInput, i as u32));
    }
    // An ear (open star of one face): the driver gives it no form, so no points.
    if !closed && n == 2 {
        for j in 0..n {
            set(beyond, j, MISSING)?;
        }
        return Ok(());
    }
    let mut images = Ring::new();
    let cf = star_form(v, ring, closed, &mut images)?;
    let mut diag = Ring::new();
    for d in diagonals {
        diag.try_push(cf.to_normalised(*d).unwrap_or(MISSING))
            .map_err(|_| Error::new(Status::ValenceTooHigh))?;
    }
    let complete = images.iter().all(present) && diag.iter().all(present);
    for j in 0..n {
        let p = kobbelt_beyond_in_form(&images, &diag, closed, complete, j, &cf);
        set(beyond, j, p.unwrap_or(MISSING))?;
    }
    Ok(())
}
