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
//! Decisions where the sources are silent:
//!
//! * Interior vertex of valence 4: the virtual point is the real opposite neighbour.
//! * Interior vertex of valence `n ≠ 4` (neighbours `q_i`, diagonal vertices `d_i` between
//!   `q_i` and `q_{i+1}`): the virtual point opposite `q_j` is [`virtual_point`],
//!   `r_j = 4/n Σ q_i − (q_{j−1} + q_j + q_{j+1}) + ŵ (d_{j−2} + d_{j−1} + d_j + d_{j+1})
//!   − 4ŵ/n Σ d_i` with **`ŵ = w / (1/2 + w)`** (`= 1/9` at `w = 1/16`).
//!
//!   *Why this rule.* Kobbelt designs the virtual points "in such a way that the face point
//!   can be computed in either direction of the quad mesh, horizontally or vertically (i.e.,
//!   as tensor product of the 4-point scheme)" (seed 000 §4.4.3, "Blending face points",
//!   describing Kobbelt 1996). Writing out the two directional face points of a face
//!   `(v, q_j, d_j, q_{j+1})` (Fig. 14) with everything else regular, all points cancel
//!   except `w(1/2 + w)(r_{j+1} − r_j + q_{j+2} − q_{j−1}) − w² (d_{j+2} − d_{j−2})`, so the
//!   two agree exactly iff `r_{j+1} − r_j = q_{j−1} − q_{j+2} + ŵ (d_{j+2} − d_{j−2})` with
//!   `ŵ = w/(1/2 + w)`. The cyclic sum of the right side vanishes, so this fixes the `r_j` up
//!   to one common offset; the rule above is the solution with `mean_j r_j = mean_i q_i`.
//!   It equals `q_{j+2}` for `n = 4` (the real opposite neighbour), is affine (its weights
//!   sum to one) and symmetric about `q_j`; `tests/kobbelt_virtual_points.rs` checks the direction
//!   independence on meshes, the planar `n`-star, and the eigenvalues of the local
//!   subdivision matrix.
//!
//!   *Provenance.* Kobbelt, L., "Interpolatory subdivision on open quadrilateral nets with
//!   arbitrary topology", Computer Graphics Forum 15(3) (Eurographics '96), 409–420,
//!   doi:10.1111/1467-8659.1530409. Its text was not available to us (docs/DECISIONS.md lists what
//!   was searched): the rule is *derived* from the property above, not transcribed. A public
//!   geometry-central-based C++ implementation of the same form uses `ŵ = ω/(4 + ω)` with its
//!   4-point rule written `(8 + ω)/16, −ω/16` (`ω = 16 w`), i.e. `1/5`; the same form in `w`,
//!   `w/(4+w)`, gives `1/65`. Neither makes the two directions agree (mismatch `∝ d_{j+2} −
//!   d_{j−2}`), so neither is used. The common offset (`mean r = mean q`) is the one of that
//!   implementation and is not pinned by the property; it only moves the rotation-invariant
//!   (`k = 0`) eigenvalues of the local subdivision matrix.
//! * Boundary vertex (any valence): the line through `(v, x)` ends at `v`; the virtual point
//!   is the 4-point curve's end extrapolation `2v − x` (the open-end rule of the 4-point
//!   curve, `P_−1 = 2P_0 − P_1`).
//! * Boundary edges: the 4-point rule along the boundary loop, as a closed curve through all
//!   its vertices (every scheme subdivides its boundary loops as curves).
//! * A face edge on the boundary has no face beyond it: the outer edge point of the face rule
//!   is extrapolated the same way, `2 e − e_opposite`.

use super::cyclic;
use crate::error::{Error, Result, Status};
use crate::point::{add, lin2, scale, sub, sum, Point};

/// The tension of the 4-point rule, `w = 1/16` (weights `−w, 1/2 + w, 1/2 + w, −w`).
pub const W: f64 = 1.0 / 16.0;

/// The weight of the diagonal correction of [`virtual_point`], `ŵ = w/(1/2 + w) = 1/9`: the
/// one value for which both directional face points next to an extraordinary vertex agree
/// (module docs).
pub const W_HAT: f64 = W / (0.5 + W);

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
    let q = |k: isize| cyclic(ring, j, k);
    let d = |k: isize| cyclic(diagonals, j, k);
    Ok(VirtualParts {
        n,
        ring_sum: sum(ring),
        diagonal_sum: sum(diagonals),
        near_q: [q(-1)?, q(0)?, q(1)?],
        opposite: q(2)?,
        near_d: [d(-2)?, d(-1)?, d(0)?, d(1)?],
    }
    .point())
}

/// What [`virtual_point`] reads of a star with the line's neighbour `q_j`: a driver gathers
/// these in one walk around the star (no arrays of ring and diagonal points) and gets the
/// same bits.
#[derive(Clone, Copy, Debug)]
pub(crate) struct VirtualParts {
    /// The valence (≥ 1).
    pub(crate) n: usize,
    /// `Σ q_i`, left to right from the star's first spoke (as [`sum`]).
    pub(crate) ring_sum: Point,
    /// `Σ d_i`, likewise.
    pub(crate) diagonal_sum: Point,
    /// `q_{j−1}, q_j, q_{j+1}` (indices mod n).
    pub(crate) near_q: [Point; 3],
    /// `q_{j+2}`: the virtual point at valence 4.
    pub(crate) opposite: Point,
    /// `d_{j−2}, d_{j−1}, d_j, d_{j+1}`.
    pub(crate) near_d: [Point; 4],
}

impl VirtualParts {
    /// The virtual point (module docs).
    pub(crate) fn point(&self) -> Point {
        if self.n == 4 {
            return self.opposite;
        }
        let nf = self.n as f64;
        let wh = W_HAT;
        let [q0, q1, q2] = self.near_q;
        let [d0, d1, d2, d3] = self.near_d;
        let near_q = add(add(q0, q1), q2);
        let near_d = add(add(d0, d1), add(d2, d3));
        let q_part = sub(scale(self.ring_sum, 4.0 / nf), near_q);
        let d_part = sub(scale(near_d, wh), scale(self.diagonal_sum, 4.0 * wh / nf));
        add(q_part, d_part)
    }
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
