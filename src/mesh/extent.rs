//! The range of sizes a method's arithmetic can represent.
//!
//! Differential-space subdivision (seed 001) solves a least-squares system whose normal
//! equations hold squared lengths, and the spherelike circle blend (seed 003 §3) measures
//! squared distances and radii: at a size near `1e-160` those squares are subnormal (or
//! zero) and near `1e155` they overflow, so the arithmetic loses the mesh's shape — a
//! result that would come back with a success status and a wrong shape. Those methods take
//! meshes whose extent lies in [`MIN_EXTENT`, `MAX_EXTENT`] and refuse the others with
//! [`Status::NumericalFailure`]; the range leaves a margin of 10¹⁰ on either side of where
//! `tests/extreme_scales.rs` measured the first wrong result. Inside it every method is
//! scale-covariant (the same test). The other mesh schemes, linear and Möbius, are
//! scale-covariant over the whole range of `f64` (measured there too) and do not check.

use super::Mesh;
use crate::error::{Error, Result, Status, NO_ELEMENT};

/// The smallest extent (largest bounding-box side) the squared-distance methods accept.
pub const MIN_EXTENT: f64 = 1e-140;
/// The largest coordinate magnitude and extent the squared-distance methods accept.
pub const MAX_EXTENT: f64 = 1e140;

/// Checks that `mesh`'s bounding box has a largest side of at least [`MIN_EXTENT`] (or is a
/// single point, which the methods' own degeneracy checks handle) and that no coordinate
/// exceeds [`MAX_EXTENT`] in magnitude.
///
/// # Errors
/// [`Status::NumericalFailure`] naming the vertex of the largest coordinate when it is too
/// large, or no element when the mesh is too small. Non-finite coordinates are left to
/// validation ([`Status::NonFiniteInput`]).
pub fn check_extent(mesh: &Mesh<'_>) -> Result<()> {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let (mut largest, mut at) = (0.0f64, NO_ELEMENT);
    for (v, p) in mesh.positions().enumerate() {
        for ((&x, l), h) in p.iter().zip(&mut lo).zip(&mut hi) {
            if !x.is_finite() {
                return Ok(());
            }
            *l = l.min(x);
            *h = h.max(x);
            if x.abs() > largest {
                largest = x.abs();
                at = v as u32;
            }
        }
    }
    if largest > MAX_EXTENT {
        return Err(Error::at(Status::NumericalFailure, at));
    }
    let side = hi
        .iter()
        .zip(&lo)
        .map(|(h, l)| h - l)
        .fold(0.0f64, f64::max);
    if side > 0.0 && side < MIN_EXTENT {
        return Err(Error::new(Status::NumericalFailure));
    }
    Ok(())
}
