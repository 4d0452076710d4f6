//! The canonical Möbius Doo–Sabin rule at one vertex star (seed 000 §4.3: Doo–Sabin's new
//! points are corner points, each a stencil on one face): the corner point of each corner of
//! `v` ([`doo_sabin::corner_point`]) is evaluated on the face mapped into `v`'s canonical form,
//! so every new point comes from exactly one form and needs no blend.

use super::super::form::{star_form, MapBack, Ring, MISSING};
use super::StarFaces;
use crate::error::{Error, Result, Status};
use crate::mesh::set;
use crate::point::Point;
use crate::stencil::doo_sabin;
use crate::MAX_FACE_SIZE;

use arrayvec::ArrayVec;

/// The corner point of corner `i` of a face given by its corners' images in a star's canonical
/// form, mapped back with `form`. The driver and [`doo_sabin_star`] both evaluate every corner
/// here.
#[inline(always)]
pub(in crate::scheme::mobius) fn doo_sabin_corner_in_form(
    face: &[Point],
    i: usize,
    form: &impl MapBack,
) -> Result<Point> {
    doo_sabin::corner_point(face, i).and_then(|p| form.back(p))
}

/// The canonical Möbius Doo–Sabin rule at the vertex star `v ring…`, exactly as the Möbius
/// mesh driver ([`crate::scheme::subdivide`]) evaluates it for
/// [`crate::scheme::Scheme::DooSabin`]: `ring` and `closed` as for [`super::loop_star`], the
/// faces as for [`super::catmull_clark_star`]
/// (face `j` between spoke `j` and spoke `j + 1`, all its corners in face order, `v`
/// included). Writes `corner_points[j]`, the new point of `v`'s corner in face `j`, computed
/// on face `j` mapped into the star's canonical form and mapped back; NaN where a corner of
/// the face is sent to infinity or the result cannot be mapped back (the driver's fallback
/// is then the linear corner point), and for the one face of an *ear* (a boundary star of
/// one face): the driver gives an ear no form and evaluates its corner in the form of
/// another corner of the face (the first non-ear corner at offset `h, h+1, h−1, …`,
/// `h = ⌊d/2⌋`).
///
/// Bit-identical to the driver when each face lists its corners from its first corner in the
/// mesh (the corner index decides the weights' rotation); the ring's start does not matter.
///
/// # Errors
/// Those of [`super::catmull_clark_star`] for the arguments (`corner_points` shorter than
/// the number of faces is [`Status::BufferTooSmall`]); the errors of
/// [`crate::mobius::CanonicalForm::new`].
pub fn doo_sabin_star(
    v: Point,
    ring: &[Point],
    closed: bool,
    face_offsets: &[u32],
    face_corners: &[Point],
    corner_points: &mut [Point],
) -> Result<()> {
    let n = ring.len();
    let nf = StarFaces::count(n, closed, face_offsets)?;
    if corner_points.len() < nf {
        return Err(Error::too_small(nf));
    }
    let faces = StarFaces::new(face_offsets, face_corners)?;
    for j in 0..nf {
        set(corner_points, j, MISSING)?;
    }
    // An ear (open star of one face): the driver gives it no form of its own.
    if !closed && n == 2 {
        faces.check_corners(v)?;
        return Ok(());
    }
    let cf = star_form(v, ring, closed, &mut Ring::new())?;
    faces.check_corners(v)?;
    let mut pts: ArrayVec<Point, MAX_FACE_SIZE> = ArrayVec::new();
    for j in 0..nf {
        let corners = faces.face(j)?;
        let i = corners
            .iter()
            .position(|p| *p == v)
            .ok_or(Error::at(Status::InvalidArgument, j as u32))?;
        pts.clear();
        let mut ok = true;
        for p in corners {
            match cf.to_normalised(*p) {
                Ok(q) => pts.try_push(q).map_err(|_| crate::mesh::internal())?,
                Err(_) => ok = false,
            }
        }
        if ok {
            if let Ok(q) = doo_sabin_corner_in_form(&pts, i, &cf) {
                set(corner_points, j, q)?;
            }
        }
    }
    Ok(())
}
