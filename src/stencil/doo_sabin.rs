//! Doo–Sabin corner cutting (Doo and Sabin 1978) exactly as CGAL `DooSabin_mask_3` with
//! `DQQ_1step`, the only peer: one point per (face, corner), no boundary rule. Seed 000 §4.3
//! evaluates each corner point in its vertex's canonical form.

use crate::error::{Error, Result, Status};
use crate::point::{add, scale, Point};

/// Weight `a_k` of vertex `v_{i+k}` in the corner point of corner `i` of an n-gon:
/// `a_0 = 1/4 + 5/(4n)`, `a_k = (3 + 2 cos(2πk/n)) / (4n)`; quads exactly `(9, 3, 1, 3)/16`
/// (CGAL special-cases them).
pub fn weight(n: usize, k: usize) -> f64 {
    let nf = n as f64;
    if n == 4 {
        return [0.5625, 0.1875, 0.0625, 0.1875]
            .get(k)
            .copied()
            .unwrap_or(0.0);
    }
    if k == 0 {
        0.25 + 5.0 / (4.0 * nf)
    } else {
        (3.0 + 2.0 * libm::cos(2.0 * core::f64::consts::PI * k as f64 / nf)) / (4.0 * nf)
    }
}

/// The corner point `Σ_k a_k v_{i+k}` of corner `i` of `face`.
///
/// # Errors
/// [`Status::TooFewPoints`] for an empty face; [`Status::InvalidArgument`] for `i` out of
/// range.
pub fn corner_point(face: &[Point], i: usize) -> Result<Point> {
    corner_point_by(face.len(), i, |c| {
        face.get(c)
            .copied()
            .ok_or(Error::new(Status::InvalidArgument))
    })
}

/// [`corner_point`] of corner `i` of an n-gon whose corner `c` is `corner(c)`: the drivers
/// read the corners straight from the mesh (no array of face points), in the same order and
/// with the same bits.
///
/// # Errors
/// [`Status::TooFewPoints`] for `n = 0`; [`Status::InvalidArgument`] for `i` out of range;
/// any error of `corner`.
pub(crate) fn corner_point_by(
    n: usize,
    i: usize,
    mut corner: impl FnMut(usize) -> Result<Point>,
) -> Result<Point> {
    if n == 0 {
        return Err(Error::new(Status::TooFewPoints));
    }
    if i >= n {
        return Err(Error::new(Status::InvalidArgument));
    }
    let mut acc = [0.0; 3];
    for k in 0..n {
        acc = add(acc, scale(corner((i + k) % n)?, weight(n, k)));
    }
    Ok(acc)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one() {
        for n in 3..50 {
            let s: f64 = (0..n).map(|k| weight(n, k)).sum();
            assert!((s - 1.0).abs() < 1e-14, "n = {n}");
        }
        // The general formula at n = 4 gives the quad weights.
        let g = |k: usize| (3.0 + 2.0 * libm::cos(core::f64::consts::PI * k as f64 / 2.0)) / 16.0;
        for k in 1..4 {
            assert!((weight(4, k) - g(k)).abs() < 1e-15);
        }
    }
}
