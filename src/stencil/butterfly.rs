//! Modified Butterfly (Dyn, Levin, Gregory 1990; Zorin, Schröder, Sweldens 1996) exactly as
//! OpenMesh `ModifiedButterflyT`, the only peer: no tension parameter (w = 0), Zorin's
//! stencils at interior extraordinary vertices, the 4-point rule on boundary edges, and
//! reflected points across boundary edges. Seed 000 §4.3 converts it with partial
//! candidates (each end point's half of the stencil, [`edge_half`]).
//!
//! Old vertices keep their positions (interpolating).

use crate::error::{Error, Result, Status};
use crate::point::{add, lin2, scale, sub, sum, Point};
use crate::MAX_VALENCE;

/// Boundary edge point, the 4-point rule `9/16 (a0 + a1) − 1/16 (p0 + p1)`, `p0`, `p1` the
/// boundary neighbours of `a0`, `a1` beyond the edge.
pub fn edge_boundary(p0: Point, a0: Point, a1: Point, p1: Point) -> Point {
    lin2(0.5625, add(a0, a1), -0.0625, add(p0, p1))
}

/// Weight of each end point of the edge in the regular 8-point stencil.
pub const W_END: f64 = 0.5;
/// Weight of each opposite vertex (the third corners of the edge's two triangles).
pub const W_OPPOSITE: f64 = 0.125;
/// Weight of each of the four wings (the vertices across the triangles' outer edges).
pub const W_WING: f64 = -0.0625;

/// The regular 8-point butterfly `1/2 (a0 + a1) + 1/8 (b0 + b1) − 1/16 (c0 + c1 + c2 + c3)`:
/// `b` the opposite vertices of the edge's two triangles, `c` the vertices across their four
/// outer edges (use [`reflect`] across a boundary edge).
pub fn edge_regular(a0: Point, a1: Point, b0: Point, b1: Point, c: [Point; 4]) -> Point {
    add(
        lin2(W_END, add(a0, a1), W_OPPOSITE, add(b0, b1)),
        scale(sum(&c), W_WING),
    )
}

/// One end point's half of the regular 8-point stencil, doubled: the end points `a0`, `a1`
/// and the opposite vertices `b0`, `b1` with their weights of [`edge_regular`], and the two
/// wings `c0`, `c1` on `a0`'s side with twice theirs, `−1/8`. The two halves of an edge,
/// one per end point, average to [`edge_regular`]. The Möbius Modified Butterfly evaluates
/// each half in its end point's canonical form, which sees only that end point's wings
/// (seed 000 §4.3, "partial candidates").
pub fn edge_half(a0: Point, a1: Point, b0: Point, b1: Point, c0: Point, c1: Point) -> Point {
    let wing = -2.0 * W_WING;
    [
        a0[0] * W_END + a1[0] * W_END + (b0[0] + b1[0]) * W_OPPOSITE - (c0[0] + c1[0]) * wing,
        a0[1] * W_END + a1[1] * W_END + (b0[1] + b1[1]) * W_OPPOSITE - (c0[1] + c1[1]) * wing,
        a0[2] * W_END + a1[2] * W_END + (b0[2] + b1[2]) * W_OPPOSITE - (c0[2] + c1[2]) * wing,
    ]
}

/// The point standing in for the vertex across a boundary edge `(u, w)` of the triangle
/// `(u, w, z)`: the reflection `u + w − z` (OpenMesh).
pub fn reflect(u: Point, w: Point, z: Point) -> Point {
    sub(add(u, w), z)
}

/// Zorin's weight `s_j` of ring vertex `j` (ring starting at the edge's other endpoint) for an
/// interior vertex of valence `n ≥ 3`: `n = 3`: `(5/12, −1/12, −1/12)`; `n = 4`:
/// `(3/8, 0, −1/8, 0)`; `n ≥ 5`: `(1/4 + cos(2πj/n) + 1/2 cos(4πj/n)) / n`.
pub fn zorin_weight(n: usize, j: usize) -> f64 {
    match (n, j) {
        (3, 0) => 5.0 / 12.0,
        (3, _) => -1.0 / 12.0,
        (4, 0) => 0.375,
        (4, 2) => -0.125,
        (4, _) => 0.0,
        _ => {
            let t = 2.0 * core::f64::consts::PI * j as f64 / n as f64;
            (0.25 + libm::cos(t) + 0.5 * libm::cos(2.0 * t)) / n as f64
        }
    }
}

/// Zorin's stencil of one extraordinary interior endpoint `v` with ring `q` starting at the
/// edge's other endpoint: `c v + Σ s_j q_j`, `c = 3/4` for `n = 3, 4` and `1 − Σ s_j` for
/// `n ≥ 5` (OpenMesh stores it that way).
///
/// # Errors
/// [`Status::TooFewPoints`] for a ring of fewer than 3 points;
/// [`Status::ValenceTooHigh`] above [`MAX_VALENCE`].
pub fn zorin_stencil(v: Point, ring: &[Point]) -> Result<Point> {
    zorin_stencil_of(v, ring.len(), ring.iter().map(|&q| Ok(q)))
}

/// [`zorin_stencil`] of a ring of `n` points given one at a time, from the edge's other
/// endpoint on: the drivers walk the star (no array of ring points) and get the same bits.
///
/// # Errors
/// Those of [`zorin_stencil`]; [`Status::InvalidArgument`] when `ring` does not give exactly
/// `n` points; any error of `ring`.
pub(crate) fn zorin_stencil_of(
    v: Point,
    n: usize,
    ring: impl Iterator<Item = Result<Point>>,
) -> Result<Point> {
    if n < 3 {
        return Err(Error::new(Status::TooFewPoints));
    }
    if n > MAX_VALENCE {
        return Err(Error::new(Status::ValenceTooHigh));
    }
    let mut acc = [0.0; 3];
    let mut wsum = 0.0;
    let mut count = 0;
    for (j, q) in ring.enumerate() {
        let w = zorin_weight(n, j);
        wsum += w;
        acc = add(acc, scale(q?, w));
        count += 1;
    }
    if count != n {
        return Err(Error::new(Status::InvalidArgument));
    }
    let c = if n <= 4 { 0.75 } else { 1.0 - wsum };
    Ok(add(scale(v, c), acc))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zorin_weights_sum_to_a_quarter() {
        for n in 3..40 {
            let s: f64 = (0..n).map(|j| zorin_weight(n, j)).sum();
            assert!((s - 0.25).abs() < 1e-14, "n = {n}: {s}");
        }
    }

    #[test]
    fn regular_rules_reproduce_constants() {
        let p = [1.0, 2.0, 3.0];
        assert_eq!(edge_boundary(p, p, p, p), p);
        assert_eq!(edge_regular(p, p, p, p, [p; 4]), p);
        let z = zorin_stencil(p, &[p; 7]).unwrap();
        assert!((z[0] - 1.0).abs() < 1e-15 && (z[2] - 3.0).abs() < 1e-15);
        assert!(zorin_stencil(p, &[p; 2]).is_err());
    }
}
