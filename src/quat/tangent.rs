//! Corner tangents and the tangent polygon of a vertex star (seed 000 §3.3, Lemma 3.1).
//!
//! The corner tangent `t[qi, qj, qk] = q_ij⁻¹ + q_jk⁻¹` is the tangent at `qj` of the circle
//! through three points; the tangent polygon `T_i = (u_i − v)⁻¹` of a star `v u_1 … u_n` has
//! the corner tangents as edges and is Möbius equivalent to the star's boundary polygon. The
//! canonical forms of §4.2 and the star measures (Willmore energy, Möbius regularity) are
//! built on it.

use super::cross_ratio::diff_inverse;
use crate::error::{Error, Result, Status};
use crate::point::{self, add, Point};

/// The corner tangent `t[qi, qj, qk] = q_ij⁻¹ + q_jk⁻¹` (seed 000 §3.3): tangent at `qj` to the
/// circle through the three points.
///
/// # Errors
/// [`Status::NonFiniteInput`], or [`Status::DegenerateGeometry`] when consecutive points
/// coincide.
pub fn corner_tangent(qi: Point, qj: Point, qk: Point) -> Result<Point> {
    if ![qi, qj, qk].iter().all(point::is_finite) {
        return Err(Error::new(Status::NonFiniteInput));
    }
    let a = diff_inverse(qi, qj).ok_or(Error::new(Status::DegenerateGeometry))?;
    let b = diff_inverse(qj, qk).ok_or(Error::new(Status::DegenerateGeometry))?;
    let t = add(a, b);
    if point::is_finite(&t) {
        Ok(t)
    } else {
        Err(Error::new(Status::DegenerateGeometry))
    }
}

/// The vertex `T_i = (u_i − v)⁻¹` of the tangent polygon of the star `v u_1 … u_n`
/// (seed 000 §3.3). Consecutive differences are the corner tangents:
/// `T_{i+1} − T_i = t[u_i, v, u_{i+1}]`.
///
/// # Errors
/// [`Status::DegenerateGeometry`] when `u = v`; [`Status::NonFiniteInput`].
pub fn tangent_polygon_vertex(v: Point, u: Point) -> Result<Point> {
    if !point::is_finite(&v) || !point::is_finite(&u) {
        return Err(Error::new(Status::NonFiniteInput));
    }
    diff_inverse(v, u).ok_or(Error::new(Status::DegenerateGeometry))
}

/// Writes the tangent polygon `T_i = (u_i − v)⁻¹` of the star `v u_1 … u_n` into `out`
/// (seed 000 §3.3, Lemma 3.1: it is Möbius equivalent to the boundary polygon `B_v`).
///
/// # Errors
/// [`Status::BufferTooSmall`] if `out` is shorter than `ring`; [`Status::DegenerateGeometry`]
/// (element = ring index) when a neighbour coincides with `v`; [`Status::NonFiniteInput`].
pub fn tangent_polygon(v: Point, ring: &[Point], out: &mut [Point]) -> Result<()> {
    if out.len() < ring.len() {
        return Err(Error::too_small(ring.len()));
    }
    for (i, (u, t)) in ring.iter().zip(out.iter_mut()).enumerate() {
        *t = tangent_polygon_vertex(v, *u).map_err(|e| e.with_element(i as u32))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::testing::close;
    use super::super::{cross_ratio, Quat};
    use super::*;

    #[test]
    fn cross_ratio_equals_corner_tangent_form() {
        // Eq. (2): cr[qi,qj,qk,ql] = t[qk,qi,qj]⁻¹ · t[qk,qi,ql].
        let (a, b, c, d) = (
            [0.3, -1.0, 2.0],
            [1.5, 0.2, -0.7],
            [-0.4, 2.2, 1.1],
            [2.0, 1.0, 0.5],
        );
        let cr = cross_ratio(a, b, c, d).unwrap();
        let t1 = Quat::from_point(corner_tangent(c, a, b).unwrap())
            .inverse()
            .unwrap();
        let t2 = Quat::from_point(corner_tangent(c, a, d).unwrap());
        assert!(close(cr, t1 * t2, 1e-13), "{cr:?} {:?}", t1 * t2);
    }

    #[test]
    fn tangent_polygon_edges_are_corner_tangents() {
        let v = [0.1, 0.2, 0.3];
        let ring = [
            [1.0, 0.0, 0.1],
            [0.2, 1.1, 0.0],
            [-1.0, 0.3, -0.2],
            [0.0, -1.0, 0.4],
        ];
        let mut t = [[0.0; 3]; 4];
        tangent_polygon(v, &ring, &mut t).unwrap();
        for i in 0..4 {
            let ct = corner_tangent(ring[i], v, ring[(i + 1) % 4]).unwrap();
            let e = [
                t[(i + 1) % 4][0] - t[i][0],
                t[(i + 1) % 4][1] - t[i][1],
                t[(i + 1) % 4][2] - t[i][2],
            ];
            for k in 0..3 {
                assert!((ct[k] - e[k]).abs() < 1e-14);
            }
        }
        let mut small = [[0.0; 3]; 3];
        assert_eq!(
            tangent_polygon(v, &ring, &mut small).unwrap_err(),
            Error::too_small(4)
        );
        let bad = [v, [1.0, 0.0, 0.0]];
        let e = tangent_polygon(v, &bad, &mut t).unwrap_err();
        assert_eq!((e.status, e.element), (Status::DegenerateGeometry, 0));
    }
}
