//! Loop subdivision (Loop 1987) with the original weights, as OpenMesh `LoopT`, CGAL
//! `Loop_mask_3` and OpenSubdiv `loopScheme`: not Warren's β. Seed 000 §4.3 converts it to
//! its Möbius version (a 1-ring scheme).

use crate::error::{Error, Result, Status};
use crate::point::{add, lin2, midpoint, scale, sum, Point};

pub use super::crease_vertex as vertex_boundary;

/// Loop's `α_n = 5/8 − (3/8 + 1/4 cos(2π/n))²`; the vertex keeps `1 − α_n` and each neighbour
/// gets `α_n / n`. `n = 6` is exact (`3/8`, so `β = 1/16`), as CGAL and OpenSubdiv hard-code.
pub fn alpha(n: usize) -> f64 {
    if n == 6 {
        return 0.375;
    }
    let c = 0.375 + 0.25 * libm::cos(2.0 * core::f64::consts::PI / n as f64);
    0.625 - c * c
}

/// Interior vertex point `(1 − α_n) v + (α_n / n) Σ q_i` for the ring `q` (any start).
///
/// # Errors
/// [`Status::TooFewPoints`] for an empty ring.
pub fn vertex_interior(v: Point, ring: &[Point]) -> Result<Point> {
    vertex_interior_sum(v, ring.len(), sum(ring))
}

/// [`vertex_interior`] from the ring's valence `n` and its sum ([`crate::point::sum`]'s
/// left-to-right order): the drivers accumulate the sum while walking the star, with no
/// array of ring points, and get the same bits.
///
/// # Errors
/// [`Status::TooFewPoints`] for `n = 0`.
pub(crate) fn vertex_interior_sum(v: Point, n: usize, ring_sum: Point) -> Result<Point> {
    if n == 0 {
        return Err(Error::new(Status::TooFewPoints));
    }
    let a = alpha(n);
    Ok(lin2(1.0 - a, v, a / n as f64, ring_sum))
}

/// Interior edge point `3/8 (a + b) + 1/8 (c + d)`, `c`, `d` the opposite vertices of the two
/// triangles.
pub fn edge_interior(a: Point, b: Point, c: Point, d: Point) -> Point {
    add(scale(add(a, b), 0.375), scale(add(c, d), 0.125))
}

/// Boundary edge point: the midpoint.
pub fn edge_boundary(a: Point, b: Point) -> Point {
    midpoint(a, b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alpha_matches_peer_table() {
        // β = α/n, the peers' values (OpenSubdiv `loopScheme`, CGAL `Loop_mask_3`).
        let table = [
            (3, 0.1875),
            (4, 0.121094),
            (5, 0.084093),
            (6, 0.0625),
            (7, 0.049025),
            (8, 0.040068),
            (12, 0.022927),
        ];
        for (n, beta) in table {
            assert!((alpha(n) / n as f64 - beta).abs() < 1e-6, "n = {n}");
        }
        assert_eq!(alpha(6) / 6.0, 0.0625);
    }

    #[test]
    fn rules_are_affine() {
        let ring = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]];
        let p = vertex_interior([2.0, 2.0, 2.0], &ring).unwrap();
        let q = vertex_interior([3.0, 2.0, 2.0], &ring.map(|r| add(r, [1.0, 0.0, 0.0]))).unwrap();
        assert!((q[0] - p[0] - 1.0).abs() < 1e-15);
        assert_eq!(
            edge_interior([1.0; 3], [1.0; 3], [1.0; 3], [1.0; 3]),
            [1.0; 3]
        );
        assert!(vertex_interior([0.0; 3], &[]).is_err());
    }
}
