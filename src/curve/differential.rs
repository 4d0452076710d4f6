//! Differential-space curve subdivision (seed 001 §3.5 "Curve case", Eq. (8), Appendix A).
//!
//! 1. The differential polygon `Δ⁰ = {δ_i}` of the control polygon, Eq. (8):
//!    `δ_i = v_i − (v_{i−1} + v_{i+1})/2` ([`differential_polygon`]).
//! 2. `Δ⁰` is subdivided `k` times with a linear curve scheme — the 4-point scheme or the
//!    cubic B-spline scheme ("the cubic spline algorithm or the four-point interpolatory
//!    scheme, are performed on Δ") — giving `Δᵏ` on the topology of the `k`-th level.
//! 3. The curve is reconstructed from `4ᵏ L Ṽᵏ = Δᵏ` ("the scaling factor is still (1/4)ᵏ"),
//!    `L` the combinatorial Laplacian of the refined polygon (`(L V)_i = v_i − (v_{i−1} +
//!    v_{i+1})/2`), with fixed vertices ([`reconstruct`]). The result satisfies Eq. (A.1) at
//!    every level: `4 D_k P_k = S_k D_{k−1} P_{k−1}`, `D` the second-difference operator, i.e.
//!    the second differences of the output are the subdivided differential polygon scaled
//!    by `−2 · 4⁻ᵏ` (tested).
//!
//! By Prop. 2 the limit is two orders smoother than the scheme used on `Δ` (C³ with the
//! 4-point scheme, C⁴ with the B-spline scheme). The scheme is linear but not local, and
//! neither interpolating nor circle preserving.
//!
//! # Closed curves
//!
//! `Σ δ_i = 0` for a closed polygon, and both schemes map a zero-sum polygon to a zero-sum
//! polygon (each old point contributes with total weight 2), so `L Ṽ = 4⁻ᵏ Δᵏ` is
//! consistent: the least-squares solution of the paper's stacked system
//! `[4ᵏ L; anchor] V = [Δᵏ; anchor]` is its exact solution with the anchor.
//! The anchor is the Dirichlet condition of Prop. 1 ("fixing one vertex of the closed curve"):
//! output point 0 is input point 0 (the paper puts it at the origin; we keep the curve where
//! it was). The solve is direct and O(n): with `g_i = −2 · 4⁻ᵏ δ_i` and `d_i = v_{i+1} − v_i`,
//! `d_i = d_0 + Σ_{j=1..i} g_j`, and `Σ d_i = 0` fixes `d_0`.
//!
//! # Open curves
//!
//! Decision (the paper treats closed curves only): Eq. (8) defines `δ_i` at the interior
//! points; the end values of `Δ⁰` are extrapolated linearly, `δ_0 = 2δ_1 − δ_2` and
//! `δ_{n−1} = 2δ_{n−2} − δ_{n−3}` (constant for three points, zero for two), and `Δ⁰` is
//! subdivided as an open polygon with the scheme's own end rules. The reconstruction keeps
//! both end points (`v_0 = P_0`, `v_{m−1} = P_{n−1}`, the "end points kept" rule of the other
//! approximating schemes) and imposes Eq. (8) at the `m − 2` interior points: a Dirichlet
//! problem with a unique solution, `d_0` fixed by `Σ d_i = P_{n−1} − P_0`. With this choice
//! a polyline sampled uniformly from a cubic polynomial is reproduced exactly (its second
//! differences are linear, which the extrapolation and both schemes keep): the open scheme
//! has cubic precision.
//!
//! # Buffers
//!
//! `Δ` lives in the same ping-pong buffers as the points: `Δ⁰` goes to `scratch` when `k` is
//! odd and to `out` when it is even, each level to the other buffer, `Δᵏ` to `out`, where it
//! is replaced by the curve in place. [`crate::curve::scratch_size`] is therefore the size of
//! level `k − 1` already for `k = 1`.

use super::levels::{run_levels, to_input_element, Level0, LevelRule};
use super::polygon::{at, check_finite, finite};
use super::{bspline, four_point, refined_size};
use crate::error::{Error, Result, Status};
use crate::point::{add, scale, sub, Point};

/// The linear scheme used on the differential polygon.
///
/// `#[non_exhaustive]`: a later version may add a variant, so a `match` outside this crate
/// needs a wildcard arm.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DifferentialBase {
    /// The 4-point scheme ([`four_point`]).
    FourPoint,
    /// The cubic B-spline scheme ([`bspline`]).
    BSpline,
}

impl DifferentialBase {
    fn rule(self) -> LevelRule {
        match self {
            DifferentialBase::FourPoint => four_point::refine_level,
            DifferentialBase::BSpline => bspline::refine_level,
        }
    }
}

/// `δ = v − (a + b)/2` (seed 001 Eq. (8)).
#[inline]
fn delta(a: Point, v: Point, b: Point) -> Point {
    sub(v, scale(add(a, b), 0.5))
}

/// Writes the differential polygon `Δ⁰` of `points` into `out[..n]` (seed 001 Eq. (8)); for
/// open curves with the extrapolated end values of the [module documentation](self).
///
/// # Errors
/// [`Status::TooFewPoints`], [`Status::BufferTooSmall`], [`Status::NonFiniteInput`],
/// [`Status::NumericalFailure`] on overflow.
pub fn differential_polygon(points: &[Point], closed: bool, out: &mut [Point]) -> Result<()> {
    let n = points.len();
    refined_size(n, closed, 0)?;
    if out.len() < n {
        return Err(Error::too_small(n));
    }
    check_finite(points)?;
    differential_polygon_unchecked(points, closed, out)
}

fn differential_polygon_unchecked(p: &[Point], closed: bool, out: &mut [Point]) -> Result<()> {
    let n = p.len();
    for (i, slot) in out.iter_mut().enumerate().take(n) {
        let d = if closed {
            let before = if i == 0 { n - 1 } else { i - 1 };
            let after = if i + 1 == n { 0 } else { i + 1 };
            delta(at(p, before)?, at(p, i)?, at(p, after)?)
        } else if i == 0 || i + 1 == n {
            continue; // end values below
        } else {
            delta(at(p, i - 1)?, at(p, i)?, at(p, i + 1)?)
        };
        *slot = finite(d, i)?;
    }
    if !closed {
        let ends = match n {
            0..=2 => ([0.0; 3], [0.0; 3]),
            3 => (at(out, 1)?, at(out, 1)?),
            _ => {
                let (d1, d2) = (at(out, 1)?, at(out, 2)?);
                let (e1, e2) = (at(out, n - 2)?, at(out, n - 3)?);
                (sub(scale(d1, 2.0), d2), sub(scale(e1, 2.0), e2))
            }
        };
        let first = out.first_mut().ok_or(Error::too_small(n))?;
        *first = finite(ends.0, 0)?;
        let last = out.get_mut(n - 1).ok_or(Error::too_small(n))?;
        *last = finite(ends.1, n - 1)?;
    }
    Ok(())
}

/// Reconstructs the curve in place from the subdivided differential polygon `Δᵏ` in `buf`:
/// solves `4^levels · L V = Δᵏ` (seed 001 §3.5 step 4, Eq. (A.1)) with `v_0 = first` and,
/// for open curves, `v_{m−1} = last` (see the [module documentation](self)). Direct, O(m),
/// two passes.
///
/// # Errors
/// [`Status::TooFewPoints`] for fewer than 3 (closed) / 2 (open) points;
/// [`Status::NumericalFailure`] on overflow.
pub fn reconstruct(
    buf: &mut [Point],
    closed: bool,
    levels: u32,
    first: Point,
    last: Point,
) -> Result<()> {
    let m = buf.len();
    refined_size(m, closed, 0)?;
    // g_i = c · δ_i with c = −2 · 4^−k, exact (a power of two) until it underflows.
    let mut c = -2.0;
    for _ in 0..levels {
        c *= 0.25;
    }
    // Pass 1: S = Σ_{i=0}^{last} G_i with G_i = Σ_{j=1..i} g_j; for a closed curve the sum
    // runs over all m differences, for an open one over the m − 1 segments. All running
    // sums are compensated (Kahan), so that the result does not drift over a million points.
    let terms = if closed { m } else { m - 1 };
    let mut g_sum = Kahan::default();
    let mut s = Kahan::default();
    for d in buf.iter().take(terms).skip(1) {
        g_sum.add(scale(*d, c));
        s.add(g_sum.value());
    }
    let d0 = if closed {
        scale(s.value(), -1.0 / m as f64)
    } else {
        scale(sub(sub(last, first), s.value()), 1.0 / (m - 1) as f64)
    };
    // Pass 2: v_i = v_0 + Σ_{j<i} d_j, d_i = d_0 + G_i, reading δ_i before overwriting it.
    let mut v = Kahan::default();
    let mut g = Kahan::default();
    for (i, slot) in buf.iter_mut().enumerate() {
        if i == 0 {
            *slot = first;
            continue;
        }
        let delta_i = *slot;
        v.add(add(d0, g.value()));
        g.add(scale(delta_i, c));
        *slot = finite(add(first, v.value()), i)?;
    }
    if !closed {
        if let Some(end) = buf.last_mut() {
            *end = last;
        }
    }
    finite(add(d0, g.value()), 0)?;
    Ok(())
}

/// A compensated (Kahan) running sum of points: plain IEEE operations in a fixed order, so
/// deterministic.
#[derive(Clone, Copy, Default)]
struct Kahan {
    sum: Point,
    carry: Point,
}

impl Kahan {
    #[inline]
    fn add(&mut self, x: Point) {
        for ((s, c), x) in self.sum.iter_mut().zip(self.carry.iter_mut()).zip(x) {
            let y = x - *c;
            let t = *s + y;
            *c = (t - *s) - y;
            *s = t;
        }
    }
    #[inline]
    fn value(&self) -> Point {
        sub(self.sum, self.carry)
    }
}

/// Differential-space subdivision of `points`, `levels` levels, into `out` with the
/// ping-pong `scratch`; returns the number of points written. Sizes as
/// [`crate::curve::refined_size`] and [`crate::curve::scratch_size`] (with a differential
/// scheme).
///
/// # Errors
/// As [`crate::curve::subdivide`].
pub fn subdivide(
    base: DifferentialBase,
    points: &[Point],
    closed: bool,
    levels: u32,
    out: &mut [Point],
    scratch: &mut [Point],
) -> Result<usize> {
    let scheme = match base {
        DifferentialBase::FourPoint => crate::curve::CurveScheme::DifferentialFourPoint,
        DifferentialBase::BSpline => crate::curve::CurveScheme::DifferentialBSpline,
    };
    crate::curve::subdivide(scheme, points, closed, levels, out, scratch)
}

/// The differential driver on validated input and buffers, `levels ≥ 1`; `out` is exactly
/// the final size.
pub(crate) fn run(
    base: DifferentialBase,
    points: &[Point],
    closed: bool,
    out: &mut [Point],
    scratch: &mut [Point],
    levels: u32,
) -> Result<()> {
    let n = points.len();
    let (first, last) = match (points.first(), points.last()) {
        (Some(f), Some(l)) => (*f, *l),
        _ => return Err(Error::new(Status::TooFewPoints)),
    };
    // Δ⁰ goes to the buffer that level 1 is not written to.
    let buf: &mut [Point] = if levels % 2 == 0 {
        &mut *out
    } else {
        &mut *scratch
    };
    let d0 = buf.get_mut(..n).ok_or(Error::too_small(n))?;
    differential_polygon_unchecked(points, closed, d0)?;
    run_levels(
        base.rule(),
        Level0::InBuffer(n),
        closed,
        out,
        scratch,
        levels,
    )?;
    let m = refined_size(n, closed, levels)?;
    let v = out.get_mut(..m).ok_or(Error::too_small(m))?;
    reconstruct(v, closed, levels, first, last).map_err(|e| to_input_element(e, levels))
}
