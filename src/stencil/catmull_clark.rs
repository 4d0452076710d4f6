//! Catmull–Clark subdivision (Catmull and Clark 1978) as OpenMesh `CatmullClarkT`, CGAL
//! `CatmullClark_mask_3` and OpenSubdiv `catmarkScheme` on closed meshes; the boundary is the
//! cubic B-spline crease rule of CGAL and OpenSubdiv `EDGE_ONLY` (OpenMesh's 2/3, 1/6
//! boundary variant is not the standard). Seed 000 §4.3 converts it (face points by the
//! F4/F6 algorithm of §4.4.3).

use super::centroid;
use crate::error::{Error, Result, Status};
use crate::point::{add, lin2, midpoint, scale, sum, Point};

pub use super::crease_vertex as vertex_boundary;

/// Face point: the average of the face's vertices (any n-gon).
///
/// # Errors
/// [`Status::TooFewPoints`] for an empty face.
pub fn face_point(face: &[Point]) -> Result<Point> {
    centroid(face)
}

/// Interior edge point `(a + b + f0 + f1) / 4`, `f0`, `f1` the face points of its faces.
pub fn edge_interior(a: Point, b: Point, f0: Point, f1: Point) -> Point {
    scale(add(add(a, b), add(f0, f1)), 0.25)
}

/// Boundary edge point: the midpoint.
pub fn edge_boundary(a: Point, b: Point) -> Point {
    midpoint(a, b)
}

/// Interior vertex point `(n − 2)/n v + 1/n² Σ q_i + 1/n² Σ f_j` (OpenMesh and OpenSubdiv
/// form), `q` the ring and `f` the face points of the `n` faces around `v`.
///
/// # Errors
/// [`Status::TooFewPoints`] for an empty ring; [`Status::InvalidArgument`] when `ring` and
/// `faces` differ in length.
pub fn vertex_interior(v: Point, ring: &[Point], faces: &[Point]) -> Result<Point> {
    let n = ring.len();
    if n == 0 {
        return Err(Error::new(Status::TooFewPoints));
    }
    if faces.len() != n {
        return Err(Error::new(Status::InvalidArgument));
    }
    vertex_interior_sums(v, n, sum(ring), sum(faces))
}

/// [`vertex_interior`] from the valence `n` and the sums of the ring and of the face points
/// (each left to right, as [`crate::point::sum`]): the drivers accumulate both while walking
/// the star, with no arrays, and get the same bits.
///
/// # Errors
/// [`Status::TooFewPoints`] for `n = 0`.
pub(crate) fn vertex_interior_sums(
    v: Point,
    n: usize,
    ring_sum: Point,
    face_sum: Point,
) -> Result<Point> {
    if n == 0 {
        return Err(Error::new(Status::TooFewPoints));
    }
    let nf = n as f64;
    Ok(lin2(
        (nf - 2.0) / nf,
        v,
        1.0 / (nf * nf),
        add(ring_sum, face_sum),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regular_grid_vertex_is_bspline() {
        // Valence 4 on the plane z = 0 grid: v stays put for a symmetric ring.
        let ring = [
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
        ];
        let faces = [
            [0.5, 0.5, 0.0],
            [-0.5, 0.5, 0.0],
            [-0.5, -0.5, 0.0],
            [0.5, -0.5, 0.0],
        ];
        assert_eq!(vertex_interior([0.0; 3], &ring, &faces).unwrap(), [0.0; 3]);
        assert!(vertex_interior([0.0; 3], &ring, &faces[..3]).is_err());
    }
}
