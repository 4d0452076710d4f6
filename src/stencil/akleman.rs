//! Akleman, Srinivasan and Mandal's remeshing operators (2005), cited in seed 000 §4.3 as
//! 1-ring "subdivision-like operators", with their linear rules. The patterns are
//! [`crate::mesh::refine::Pattern::Dual`], `VertexInsertion` and `DualTruncation`.
//!
//! Decisions where the paper is silent:
//!
//! * **Dual**: one vertex per face, its centroid; one face per interior vertex joining the
//!   centroids of its faces counter-clockwise. A boundary vertex keeps its position and gets
//!   the face `(m0, c_0, …, c_{k−1}, m1, v)` with `m0`, `m1` the midpoints of its boundary
//!   edges ([`boundary_edge_point`]): the boundary polygon is kept, refined at its midpoints
//!   (the linear interpolating curve rule), and the Euler characteristic is preserved.
//! * **Vertex insertion**: one vertex per face, its centroid; each n-gon becomes n triangles
//!   `(v_i, v_{i+1}, c)`; old vertices and old edges stay.
//! * **Dual truncation**: truncation cuts every corner at `t = 1/3` of its edges (each vertex
//!   of valence n becomes an n-gon, each n-gon a 2n-gon), then the dual is taken. The dual
//!   vertex of an old interior vertex is the centroid of its truncation polygon,
//!   `(1 − t) v + t · mean(q_i)` ([`truncated_vertex`]; `t = 1/3` equals √3's vertex rule at
//!   valence 6); the dual vertex of a face is the centroid of its 2n-gon, which is the face
//!   centroid for every `t`. The connectivity is √3's: every old interior edge is replaced by
//!   the edge joining the centroids of its two faces. Boundary vertices stay where they are and
//!   boundary edges are kept (their triangle `(a, b, c_f)`), so the boundary curve is
//!   unchanged.

use super::{centroid, centroid_of_sum};
use crate::error::Result;
use crate::point::{lin2, midpoint, sum, Point};

/// The truncation parameter `t = 1/3` of dual truncation.
pub const TRUNCATION: f64 = 1.0 / 3.0;

/// A face point of all three operators: the centroid of the face.
///
/// # Errors
/// [`crate::Status::TooFewPoints`] for an empty face.
pub fn face_point(face: &[Point]) -> Result<Point> {
    centroid(face)
}

/// The dual-truncation point of an interior vertex, `(1 − t) v + t · mean(ring)`, `t = 1/3`.
///
/// # Errors
/// [`crate::Status::TooFewPoints`] for an empty ring.
pub fn truncated_vertex(v: Point, ring: &[Point]) -> Result<Point> {
    truncated_vertex_sum(v, ring.len(), sum(ring))
}

/// [`truncated_vertex`] from the ring's valence `n` and its sum (left to right, as
/// [`sum`]): the same bits without an array of ring points.
///
/// # Errors
/// [`crate::Status::TooFewPoints`] for `n = 0`.
pub(crate) fn truncated_vertex_sum(v: Point, n: usize, ring_sum: Point) -> Result<Point> {
    Ok(lin2(
        1.0 - TRUNCATION,
        v,
        TRUNCATION,
        centroid_of_sum(ring_sum, n)?,
    ))
}

/// The dual's point on a boundary edge `(a, b)`: its midpoint.
pub fn boundary_edge_point(a: Point, b: Point) -> Point {
    midpoint(a, b)
}
