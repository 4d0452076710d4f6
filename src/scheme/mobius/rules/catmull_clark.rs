//! The canonical Möbius Catmull–Clark rules at one vertex star (seed 000 §4.1 steps 1–3,
//! §4.3: a 1-ring scheme whose face points enter the edge and vertex rules): the face
//! centroids, edge and vertex stencils of [`crate::stencil::catmull_clark`] on the 1-ring and
//! the faces around the vertex, all mapped into the star's canonical form.

use super::super::form::{interior_spoke, present, star_form, MapBack, Ring, MISSING, ORIGIN};
use super::StarFaces;
use crate::error::{Error, Result};
use crate::mesh::{get, internal, set};
use crate::point::{self, Point};
use crate::stencil::{catmull_clark, centroid_of_sum};

/// The Catmull–Clark rules in a star's canonical form: `ring` and `faces` hold the images of the
/// neighbours and the canonical centroids of the faces after each spoke ([`MISSING`] when not
/// available). Writes the edge candidate `edge_interior(0, r_j, f_{j−1}, f_j)` of every interior
/// spoke and returns the vertex point of a closed star, all mapped back with `form`.
#[inline(always)]
pub(in crate::scheme::mobius) fn catmull_clark_star_in_form(
    ring: &[Point],
    faces: &[Point],
    closed: bool,
    form: &impl MapBack,
    edge_candidates: &mut [Point],
) -> Result<Option<Point>> {
    let n = ring.len();
    for j in 0..n {
        let mut c = MISSING;
        if interior_spoke(closed, j, n) {
            let b = get(ring, j)?;
            let f0 = get(faces, (j + n - 1) % n)?;
            let f1 = get(faces, j)?;
            if present(&b) && present(&f0) && present(&f1) {
                c = form
                    .back(catmull_clark::edge_interior(ORIGIN, b, f0, f1))
                    .unwrap_or(MISSING);
            }
        }
        set(edge_candidates, j, c)?;
    }
    let all = |s: &[Point]| s.iter().take(n).all(present);
    if closed && all(ring) && all(faces) {
        let faces = faces.get(..n).ok_or(internal())?;
        Ok(catmull_clark::vertex_interior(ORIGIN, ring, faces)
            .and_then(|p| form.back(p))
            .ok())
    } else {
        Ok(None)
    }
}

/// The canonical Möbius Catmull–Clark rules at one vertex star, exactly as the Möbius mesh
/// driver ([`crate::scheme::subdivide`]) evaluates them for
/// [`crate::scheme::Scheme::CatmullClark`]. `ring` as for [`super::loop_star`]; face `j`
/// (`face_corners[face_offsets[j]..face_offsets[j + 1]]`) is the face between spoke `j` and
/// spoke `j + 1` counter-clockwise, given by the positions of all its corners in face order
/// (`v` included, anywhere in the cycle): `ring.len()` faces for a closed star, one fewer for
/// an open one.
///
/// Returns the vertex point of an interior vertex (`None` as for [`super::loop_star`]);
/// writes the edge candidate of every interior spoke to `edge_candidates[j]` and the face
/// candidate (the face's centroid taken in this star's form) to `face_candidates[j]`; NaN
/// where there is none. Face points are then [`crate::blend::face_point_with_ids`] of a
/// face's corners and the candidates of its corners' stars; edge points as for
/// [`super::loop_star`] (hint: the corner after `b` in the face on the left of `a → b`).
///
/// Bit-identical to the driver when `ring` starts at the driver's first spoke and each face
/// lists its corners from the face's first corner in the mesh.
///
/// # Errors
/// [`crate::Status::BufferTooSmall`] for short candidate buffers;
/// [`crate::Status::InvalidArgument`] when the number of faces does not fit the ring;
/// [`crate::Status::BadOffsets`], [`crate::Status::FaceTooSmall`],
/// [`crate::Status::ValenceTooHigh`] (more than [`crate::MAX_FACE_SIZE`] corners) naming the face;
/// the errors of [`crate::mobius::CanonicalForm::new`]; [`crate::Status::NonFiniteInput`]
/// and [`crate::Status::InvalidArgument`] (a face that does not contain `v`) naming the face.
/// Unlike [`super::loop_star`], a neighbour sent to infinity only removes the rules that use
/// it, as in the driver.
/// Nothing is written to the output buffers when an error is returned.
pub fn catmull_clark_star(
    v: Point,
    ring: &[Point],
    closed: bool,
    face_offsets: &[u32],
    face_corners: &[Point],
    edge_candidates: &mut [Point],
    face_candidates: &mut [Point],
) -> Result<Option<Point>> {
    let n = ring.len();
    let nf = StarFaces::count(n, closed, face_offsets)?;
    if edge_candidates.len() < n {
        return Err(Error::too_small(n));
    }
    if face_candidates.len() < nf {
        return Err(Error::too_small(nf));
    }
    let faces = StarFaces::new(face_offsets, face_corners)?;
    let mut images = Ring::new();
    let cf = star_form(v, ring, closed, &mut images)?;
    faces.check_corners(v)?;
    // Nothing can fail from here on (the offsets, sizes and corners are checked), so the
    // caller's buffers hold the work: `face_candidates` first holds the canonical centroids,
    // which the edge and vertex rules read, and is mapped back in place after them (the same
    // operations as with an array of centroids, with no such array on the stack,
    // `docs/firmware.md`, "Stack").
    let centroids = face_candidates.get_mut(..nf).ok_or(internal())?;
    for (j, c) in centroids.iter_mut().enumerate() {
        // The images summed as the face is walked: `centroid` of them bit for bit, with no
        // array of the face's points on the stack.
        let corners = faces.face(j)?;
        let mut sum = ORIGIN;
        let mut ok = true;
        for p in corners {
            match cf.to_normalised(*p) {
                Ok(q) => sum = point::add(sum, q),
                Err(_) => ok = false,
            }
        }
        *c = if ok {
            centroid_of_sum(sum, corners.len())?
        } else {
            MISSING
        };
    }
    // A closed star has a face after every spoke; an open one has none after its last spoke,
    // which no interior spoke reads (`catmull_clark_star_in_form` reads the faces of interior
    // spokes and, closed, all of them).
    let vertex = catmull_clark_star_in_form(&images, centroids, closed, &cf, edge_candidates)?;
    for c in centroids.iter_mut() {
        // A centroid that is not finite (its images' sum overflowed) has no candidate.
        *c = if present(c) {
            cf.from_normalised(*c).unwrap_or(MISSING)
        } else {
            MISSING
        };
    }
    Ok(vertex)
}
