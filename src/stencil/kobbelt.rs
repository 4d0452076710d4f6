//! Kobbelt's interpolatory quad scheme (Kobbelt 1996, "Interpolatory subdivision on open
//! quadrilateral nets with arbitrary topology"), the tensor product of the 4-point rule with
//! `w = 1/16`, with virtual points at extraordinary vertices (seed 000 §4.3, "Kobbelt
//! scheme", Fig. 11 and 14).
//!
//! * Edge point of `(v_j, v_k)`: the 4-point rule on `(v_i, v_j, v_k, v_l)`, `v_i`, `v_l` the
//!   next points along the grid line, or **virtual points** where the line does not continue.
//! * Face point: the 4-point rule on edge points across the face in each of the two
//!   directions (Fig. 14: `w1..w4` and `w5..w8`); the linear rule averages the two results,
//!   which are equal on regular grids (tensor product).
//!
//! Decisions (written down as DESIGN.md asks):
//!
//! * Interior vertex of valence 4: the virtual point is the real opposite neighbour.
//! * Interior vertex of valence `n ≠ 4` (neighbours `q_i`, diagonal vertices `d_i` between
//!   `q_i` and `q_{i+1}`): the virtual point opposite `q_j` is [`virtual_point`],
//!   `r_j = 4/n Σ q_i − (q_{j−1} + q_j + q_{j+1}) + ŵ (d_{j−2} + d_{j−1} + d_j + d_{j+1})
//!   − 4ŵ/n Σ d_i` with `ŵ = w / (4 + w)`: the regular relation `q_{j+2} = Σ q − q_{j−1} − q_j
//!   − q_{j+1}` with the ring sums rescaled to four terms, plus a diagonal correction that
//!   vanishes on regular rings. It equals `q_{j+2}` for `n = 4`, is affine (weights sum to 1),
//!   symmetric about `q_j`, and `mean_j r_j = mean_i q_i`. **Provenance**: Kobbelt 1996 was not
//!   at hand; this form is the one of a public implementation of the scheme, and the sign of
//!   the diagonal term was kept because it made the two directional face points (below) agree
//!   better at valences 3, 6, 7 in a numerical experiment. Check it against the paper before
//!   relying on bit-compatibility with another Kobbelt implementation at extraordinary
//!   vertices; regular regions are exact either way.
//! * Boundary vertex (any valence): the line through `(v, x)` ends at `v`; the virtual point
//!   is the 4-point curve's end extrapolation `2v − x` (DESIGN.md, "Open ends": `P_−1 = 2P_0 −
//!   P_1`).
//! * Boundary edges: the 4-point rule along the boundary loop, as a closed curve through all
//!   its vertices (DESIGN.md "Mesh boundaries").
//! * A face edge on the boundary has no face beyond it: the outer edge point of the face rule
//!   is extrapolated the same way, `2 e − e_opposite`.

use super::{add, cyclic, lin2, scale, sub, sum};
use crate::error::{Error, Result, Status};
use crate::quat::Point;

/// The tension of the 4-point rule, `w = 1/16` (weights `−w, 1/2 + w, 1/2 + w, −w`).
pub const W: f64 = 1.0 / 16.0;

/// The 4-point rule `(1/2 + w)(b + c) − w (a + d)` with `w = 1/16`.
pub fn four_point(a: Point, b: Point, c: Point, d: Point) -> Point {
    lin2(0.5 + W, add(b, c), -W, add(a, d))
}

/// The end extrapolation `2v − x` of an open 4-point curve ending at `v` after `x`.
pub fn extrapolate(v: Point, x: Point) -> Point {
    sub(scale(v, 2.0), x)
}

/// The virtual point of an interior vertex opposite its neighbour `q[j]` (module docs):
/// `ring` are the neighbours `q_i` counter-clockwise, `diagonals` the vertices `d_i` across
/// the quads `(v, q_i, d_i, q_{i+1})`. For valence 4 it returns `q[j + 2]` exactly.
///
/// # Errors
/// [`Status::TooFewPoints`] for an empty ring; [`Status::InvalidArgument`] when the slices
/// differ in length or `j` is out of range.
pub fn virtual_point(ring: &[Point], diagonals: &[Point], j: usize) -> Result<Point> {
    let n = ring.len();
    if n == 0 {
        return Err(Error::new(Status::TooFewPoints));
    }
    if diagonals.len() != n || j >= n {
        return Err(Error::new(Status::InvalidArgument));
    }
    if n == 4 {
        return cyclic(ring, j, 2);
    }
    let nf = n as f64;
    let wh = W / (4.0 + W);
    let near_q = add(
        add(cyclic(ring, j, -1)?, cyclic(ring, j, 0)?),
        cyclic(ring, j, 1)?,
    );
    let near_d = add(
        add(cyclic(diagonals, j, -2)?, cyclic(diagonals, j, -1)?),
        add(cyclic(diagonals, j, 0)?, cyclic(diagonals, j, 1)?),
    );
    let q_part = sub(scale(sum(ring), 4.0 / nf), near_q);
    let d_part = sub(scale(near_d, wh), scale(sum(diagonals), 4.0 * wh / nf));
    Ok(add(q_part, d_part))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_point_reproduces_cubics() {
        let p = |t: f64| [t * t * t - 2.0 * t, t * t, 1.0];
        let e = four_point(p(-1.0), p(0.0), p(1.0), p(2.0));
        let x = p(0.5);
        for i in 0..3 {
            assert!((e[i] - x[i]).abs() < 1e-15);
        }
    }

    #[test]
    fn virtual_point_is_exact_at_valence_four() {
        let q = [
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
        ];
        let d = [
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
        ];
        for j in 0..4 {
            assert_eq!(virtual_point(&q, &d, j).unwrap(), q[(j + 2) % 4]);
        }
        assert!(virtual_point(&q, &d[..3], 0).is_err());
        assert!(virtual_point(&q, &d, 4).is_err());
    }

    #[test]
    fn virtual_point_mean_is_ring_mean() {
        // Σ_j r_j = Σ q (the diagonal terms cancel), for any valence.
        for n in [3usize, 5, 6, 9] {
            let q: [Point; 9] = core::array::from_fn(|i| [i as f64, (i * i) as f64, 1.0]);
            let d: [Point; 9] = core::array::from_fn(|i| [-(i as f64), 2.0, i as f64]);
            let mut s = [0.0; 3];
            for j in 0..n {
                s = add(s, virtual_point(&q[..n], &d[..n], j).unwrap());
            }
            let m = sum(&q[..n]);
            for i in 0..3 {
                assert!((s[i] - m[i]).abs() < 1e-11, "n = {n}");
            }
        }
    }
}
