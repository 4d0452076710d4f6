//! Measures of vertex stars: the discrete Willmore energy (tangent-polygon planarity,
//! seed 000 §3.3 and Fig. 9) and Möbius regularity (§3.3, Fig. 15).
//!
//! Both are Möbius invariants: the tangent polygons of Möbius-equivalent stars are similar
//! (Lemma 3.2), and the cross-ratios `cr[v, u_{i−1}, u_i, u_{i+1}]` of one star are all
//! conjugated by the same rotation under a Möbius map (§3.2).

use crate::error::{Error, Result, Status};
use crate::point::{cross, div, dot, norm, sub, Point};
use crate::quat::{cross_ratio, tangent_polygon_vertex, Quat};
use crate::MAX_VALENCE;

/// Planarity of the quadrilateral `(p0, p1, p2, p3)`: the distance between the lines of its
/// diagonals `p0p2` and `p1p3` divided by the mean diagonal length (seed 000 Fig. 9 caption,
/// as a fraction rather than a percentage). 0 for a planar quad.
pub fn quad_planarity(p0: Point, p1: Point, p2: Point, p3: Point) -> f64 {
    // The measure is scale invariant: divide by the largest coordinate first, so that the
    // cross product below neither overflows (tangent polygons of stars with a neighbour very
    // close to the centre reach 1e300) nor underflows.
    let m = [p0, p1, p2, p3]
        .iter()
        .flatten()
        .fold(0.0f64, |m, c| m.max(c.abs()));
    let [p0, p1, p2, p3] = if m > 0.0 && m.is_finite() {
        [p0, p1, p2, p3].map(|p| div(p, m))
    } else {
        [p0, p1, p2, p3]
    };
    let d1 = sub(p2, p0);
    let d2 = sub(p3, p1);
    let mean = 0.5 * (norm(d1) + norm(d2));
    if mean == 0.0 {
        return 0.0;
    }
    let n = cross(d1, d2);
    let nl = norm(n);
    if nl <= 1e-15 * norm(d1) * norm(d2) {
        // Parallel diagonals lie in one plane.
        return 0.0;
    }
    let w = sub(p1, p0);
    let dist = dot(w, n).abs() / nl;
    dist / mean
}

/// Vertex `i mod n` of the star's tangent polygon (Eq. (2)), computed where it is read rather
/// than held in an array: the stack does not grow with the valence (`docs/firmware.md`).
fn tangent_vertex(v: Point, ring: &[Point], i: usize) -> Result<Point> {
    let k = i
        .checked_rem(ring.len())
        .ok_or(Error::new(Status::TooFewPoints))?;
    let u = ring
        .get(k)
        .copied()
        .ok_or(Error::new(Status::InvalidArgument))?;
    tangent_polygon_vertex(v, u).map_err(|e| e.with_element(k as u32))
}

/// The discrete Willmore energy of the star `v ring…`: the root mean square of the planarity
/// of every four consecutive vertices of its tangent polygon (seed 000 Fig. 9). 0 iff the star
/// is cospherical. `closed` says whether the ring is cyclic (an interior vertex) or runs from
/// one boundary neighbour to the other. Stars with fewer than four neighbours are always
/// cospherical and give 0.
///
/// # Errors
/// [`Status::DegenerateGeometry`] when a neighbour coincides with `v`; [`Status::NonFiniteInput`];
/// [`Status::ValenceTooHigh`]; [`Status::NumericalFailure`] when the energy overflows
/// (neighbours at wildly different scales).
pub fn willmore_energy(v: Point, ring: &[Point], closed: bool) -> Result<f64> {
    let n = ring.len();
    if n > MAX_VALENCE {
        return Err(Error::new(Status::ValenceTooHigh));
    }
    // Every tangent-polygon vertex first, so the error reported is the first neighbour's in
    // ring order, whatever the valence.
    for i in 0..n {
        tangent_vertex(v, ring, i)?;
    }
    if n < 4 {
        return Ok(0.0);
    }
    let count = if closed { n } else { n - 3 };
    let mut sum = 0.0;
    for i in 0..count {
        let q = |k: usize| tangent_vertex(v, ring, i + k);
        let p = quad_planarity(q(0)?, q(1)?, q(2)?, q(3)?);
        sum += p * p;
    }
    let energy = crate::sqrt::sqrt(sum / count as f64);
    if energy.is_finite() {
        Ok(energy)
    } else {
        Err(Error::new(Status::NumericalFailure))
    }
}

/// The Möbius regularity defect of the star `v ring…`: the sum of squared differences of
/// consecutive cross-ratios `cr_i = cr[v, u_{i−1}, u_i, u_{i+1}]` around the star
/// (seed 000 Fig. 15, "MR"). By Eq. (2), `cr_i` is the quaternionic ratio of two consecutive
/// edges of the tangent polygon, so the defect is 0 iff the tangent polygon is Euclidean
/// regular, i.e. iff the star is Möbius regular. For a boundary star (`closed = false`) only
/// the interior ratios are compared.
///
/// # Errors
/// [`Status::TooFewPoints`] for fewer than 3 neighbours (closed) or 3 (open);
/// [`Status::ValenceTooHigh`] above [`MAX_VALENCE`]; [`Status::DegenerateGeometry`] when
/// consecutive points coincide; [`Status::NonFiniteInput`]; [`Status::NumericalFailure`] when
/// the defect overflows (cross-ratios beyond about 1e154, from neighbours at wildly different
/// scales).
pub fn mobius_regularity(v: Point, ring: &[Point], closed: bool) -> Result<f64> {
    let n = ring.len();
    if n < 3 {
        return Err(Error::new(Status::TooFewPoints));
    }
    if n > MAX_VALENCE {
        return Err(Error::new(Status::ValenceTooHigh));
    }
    let at = |i: usize| ring.get(i % n).copied().unwrap_or_default();
    // The cross-ratios in ring order, each compared with the one before as it comes (and the
    // last with the first of a closed star): the same sum, in the same order, as over an
    // array of them, with no array (the stack does not grow with the valence).
    let (first, last) = if closed { (0, n) } else { (1, n - 1) };
    let mut sum = 0.0;
    let mut ends: Option<(Quat, Quat)> = None;
    for i in first..last {
        let cr = cross_ratio(v, at(i + n - 1), at(i), at(i + 1))
            .map_err(|e| e.with_element(i as u32))?;
        ends = Some(match ends {
            None => (cr, cr),
            Some((first_cr, prev)) => {
                sum += (cr - prev).norm_sq();
                (first_cr, cr)
            }
        });
    }
    if let (true, Some((first_cr, last_cr))) = (closed, ends) {
        sum += (first_cr - last_cr).norm_sq();
    }
    if sum.is_finite() {
        Ok(sum)
    } else {
        Err(Error::new(Status::NumericalFailure))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use arrayvec::ArrayVec;

    fn regular_ring(n: usize, z: f64) -> ArrayVec<Point, 16> {
        (0..n)
            .map(|i| {
                let t = 2.0 * core::f64::consts::PI * i as f64 / n as f64;
                [libm::cos(t), libm::sin(t), z]
            })
            .collect()
    }

    #[test]
    fn planar_and_spherical_stars_have_zero_willmore_energy() {
        let ring = regular_ring(6, 0.0);
        assert!(willmore_energy([0.0; 3], &ring, true).unwrap() < 1e-15);
        // A star on the unit sphere with uneven neighbours.
        let s = |th: f64, ph: f64| {
            [
                libm::sin(th) * libm::cos(ph),
                libm::sin(th) * libm::sin(ph),
                libm::cos(th),
            ]
        };
        let ring = [
            s(0.5, 0.1),
            s(0.4, 1.3),
            s(0.7, 2.9),
            s(0.3, 4.0),
            s(0.6, 5.2),
        ];
        assert!(willmore_energy([0.0, 0.0, 1.0], &ring, true).unwrap() < 1e-12);
        // A saddle is not.
        let saddle = [
            [1.0, 0.0, 0.3],
            [0.0, 1.0, -0.3],
            [-1.0, 0.0, 0.3],
            [0.0, -1.0, -0.3],
            [0.7, -0.7, 0.0],
        ];
        assert!(willmore_energy([0.0; 3], &saddle, true).unwrap() > 1e-3);
    }

    #[test]
    fn stars_at_the_ends_of_the_f64_range_give_no_nan() {
        // A neighbour 5e-324 from the centre puts a tangent-polygon vertex near 1e300: the
        // planarity products must not overflow into NaN, and an overflowing sum is an error.
        let v = [0.0, 1e-300, 1e-300];
        let ring = [
            [1.0, 1.0, 1.0],
            [2.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            [5e-324, 0.0, 0.0],
            [0.0, 1.0, 0.5],
        ];
        match willmore_energy(v, &ring, true) {
            Ok(w) => assert!(w.is_finite(), "{w}"),
            Err(e) => assert_eq!(e.status, Status::NumericalFailure),
        }
        let ring = [
            [1e300, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [f64::MIN_POSITIVE, 0.0, 0.0],
            [-1e300, 1e300, 0.0],
            [1e-310, 2e-310, -3e-310],
        ];
        match mobius_regularity([1e-300, 0.0, 0.0], &ring, true) {
            Ok(m) => assert!(m.is_finite(), "{m}"),
            Err(e) => assert_eq!(e.status, Status::NumericalFailure),
        }
        // Scaling does not change planarity.
        let q = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.1],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.2],
        ];
        let p1 = quad_planarity(q[0], q[1], q[2], q[3]);
        let big = q.map(|p| [p[0] * 1e300, p[1] * 1e300, p[2] * 1e300]);
        let p2 = quad_planarity(big[0], big[1], big[2], big[3]);
        assert!(p1 > 0.01 && (p1 - p2).abs() < 1e-15 * p1, "{p1} {p2}");
    }

    #[test]
    fn regular_star_is_mobius_regular() {
        for n in [3, 4, 5, 6, 8] {
            let ring = regular_ring(n, 0.0);
            assert!(mobius_regularity([0.0; 3], &ring, true).unwrap() < 1e-28);
        }
        let mut ring = regular_ring(6, 0.0);
        ring[2][0] += 0.1;
        assert!(mobius_regularity([0.0; 3], &ring, true).unwrap() > 1e-4);
    }
}
