//! The rules of the Möbius schemes at one vertex star (tier 1): for a host mesh library
//! (OpenMesh, CGAL, a CAD kernel) that owns the connectivity and drives the schemes itself.
//!
//! Each scheme's file holds two functions: the public rule, which takes the star as points
//! (`v`, its ring counter-clockwise, for some schemes the faces or the diagonals), builds the
//! star's canonical form (seed 000 §4.2) and maps the ring into it; and the rule *in form*,
//! which evaluates the scheme's linear stencils of [`crate::stencil`] on the images and maps
//! the results back (seed 000 §4.1 steps 2–3). The Möbius mesh driver
//! ([`crate::scheme::subdivide`] with [`Options::mobius`](crate::scheme::Options::mobius))
//! calls the same in-form rule on the images its memo holds, so a host that gives a star in the
//! driver's order gets the driver's bits (`tests/mesh_mobius.rs`
//! `star_rules_reproduce_the_driver_bit_for_bit`).
//!
//! What a host then does with the candidates (seed 000 §4.1 step 4), as the driver does:
//! an interior edge point is `F4(a, e_a, e_b, b)` of the candidates of both end points
//! ([`crate::blend::f4_hinted`], hint the corner after `b` in the face on the left of
//! `a → b`), the single candidate when only one exists, the linear rule when none does; a
//! face point is [`crate::blend::face_point_with_ids`] of the face's corners and their
//! stars' face candidates; boundary loops are curves (the Möbius curve rules); whatever has
//! no value takes its linear rule.

mod butterfly;
mod catmull_clark;
mod doo_sabin;
mod kobbelt;
mod loop_scheme;

pub use butterfly::butterfly_star;
pub(super) use butterfly::butterfly_star_in_form;
pub use catmull_clark::catmull_clark_star;
pub(super) use catmull_clark::catmull_clark_star_in_form;
pub use doo_sabin::doo_sabin_star;
pub(super) use kobbelt::kobbelt_beyond_in_form;
pub use kobbelt::kobbelt_star;
pub use loop_scheme::loop_star;
pub(super) use loop_scheme::loop_star_in_form;

use crate::error::{Error, Result, Status};
use crate::point::{self, Point};
use crate::MAX_FACE_SIZE;

/// The faces of a star given as lists of corner points in CSR form (face `j` is
/// `corners[offsets[j]..offsets[j + 1]]`, the face between spoke `j` and spoke `j + 1`
/// counter-clockwise), as [`catmull_clark_star`] and [`doo_sabin_star`] take them.
struct StarFaces<'a> {
    offsets: &'a [u32],
    corners: &'a [Point],
}

impl<'a> StarFaces<'a> {
    /// The number of faces of a star of `n` spokes: `n` when `closed`, one fewer otherwise;
    /// [`Status::InvalidArgument`] when `offsets` does not hold one more entry.
    fn count(n: usize, closed: bool, offsets: &[u32]) -> Result<usize> {
        let nf = if closed { n } else { n.saturating_sub(1) };
        if offsets.len() != nf + 1 {
            return Err(Error::new(Status::InvalidArgument));
        }
        Ok(nf)
    }

    /// The face lists, checked before any computation: [`Status::BadOffsets`] (element 0)
    /// unless the offsets run from 0 to `corners.len()`; then per face [`Status::BadOffsets`],
    /// [`Status::FaceTooSmall`], [`Status::ValenceTooHigh`] (more than [`MAX_FACE_SIZE`]
    /// corners) naming the face.
    fn new(offsets: &'a [u32], corners: &'a [Point]) -> Result<Self> {
        let first = offsets.first().copied();
        let last = offsets.last().map(|&o| o as usize);
        if first != Some(0) || last != Some(corners.len()) {
            return Err(Error::at(Status::BadOffsets, 0));
        }
        let faces = StarFaces { offsets, corners };
        for j in 0..offsets.len().saturating_sub(1) {
            faces.face(j)?;
        }
        Ok(faces)
    }

    /// The corners of face `j` (the errors of [`StarFaces::new`]).
    fn face(&self, j: usize) -> Result<&'a [Point]> {
        let bad = |s: Status| Error::at(s, j as u32);
        let a = *self.offsets.get(j).ok_or(crate::mesh::internal())? as usize;
        let b = *self.offsets.get(j + 1).ok_or(crate::mesh::internal())? as usize;
        let corners = self.corners.get(a..b).ok_or(bad(Status::BadOffsets))?;
        if corners.len() < 3 {
            return Err(bad(Status::FaceTooSmall));
        }
        if corners.len() > MAX_FACE_SIZE {
            return Err(bad(Status::ValenceTooHigh));
        }
        Ok(corners)
    }

    /// [`Status::NonFiniteInput`] for a face with a non-finite corner, then
    /// [`Status::InvalidArgument`] for a face that does not contain `v`, naming the face.
    fn check_corners(&self, v: Point) -> Result<()> {
        for j in 0..self.offsets.len().saturating_sub(1) {
            let corners = self.face(j)?;
            if !corners.iter().all(point::is_finite) {
                return Err(Error::at(Status::NonFiniteInput, j as u32));
            }
            if !corners.contains(&v) {
                return Err(Error::at(Status::InvalidArgument, j as u32));
            }
        }
        Ok(())
    }
}
