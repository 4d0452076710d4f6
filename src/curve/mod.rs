//! Curve subdivision over caller slices: open and closed polylines in R³, `k` levels,
//! exact sizes, no allocation.
//!
//! # Schemes
//!
//! | [`CurveScheme`] | kind | rule (one level) | source |
//! |---|---|---|---|
//! | [`FourPoint`](CurveScheme::FourPoint) | linear, interpolating | `E = 9/16 (P_i + P_{i+1}) − 1/16 (P_{i−1} + P_{i+2})` | Dyn–Levin–Gregory, `w = 1/16` ([`four_point`]) |
//! | [`BSpline`](CurveScheme::BSpline) | linear, approximating | `E = (P_i + P_{i+1})/2`, `P'_i = 3/4 P_i + 1/8 (P_{i−1} + P_{i+1})` | cubic B-spline ([`bspline`]) |
//! | [`MobiusInterpolating`](CurveScheme::MobiusInterpolating) | Möbius, interpolating | `E = F4(P_{i−1}, P_i, P_{i+1}, P_{i+2})` | seed 000 §4.4.1 ([`mobius`]) |
//! | [`MobiusApproximating`](CurveScheme::MobiusApproximating) | Möbius, approximating | `E` as above, `P'_i = F4(P_{i−1}, E_{i−½}, E_{i+½}, P_{i+1})` | seed 000 §4.4.1 ([`mobius`]) |
//! | [`CircleBlend`](CurveScheme::CircleBlend) | circle preserving, interpolating | middle of the arc with the averaged tangent | seed 003 §2 ([`circle_blend`]) |
//! | [`DifferentialFourPoint`](CurveScheme::DifferentialFourPoint), [`DifferentialBSpline`](CurveScheme::DifferentialBSpline) | linear, global | subdivide `δ_i = v_i − (v_{i−1} + v_{i+1})/2`, reconstruct | seed 001 §3.5 Eq. (8), App. A ([`differential`]) |
//!
//! # Topology and output order
//!
//! One level maps `n` points to
//! * `2n` points for a **closed** curve (`n` vertex points and `n` edge points; the edge
//!   point `i` lies between `P_i` and `P_{(i+1) mod n}`);
//! * `2n − 1` points for an **open** curve (`n` vertex points, `n − 1` edge points), for
//!   every scheme: approximating schemes keep the two end points (DESIGN.md, "Curves").
//!
//! The output is interleaved: the vertex point of `P_i` at index `2i`, the edge point of the
//! segment `P_i P_{i+1}` at index `2i + 1`. For interpolating schemes the even entries are
//! the old points, bit for bit; after `k` levels input point `i` is at index `2^k i`.
//! [`refined_len`] gives the exact size after `k` levels; it is the same for every scheme.
//!
//! A closed curve needs at least 3 points, an open one at least 2 (two points give the
//! midpoint, for every scheme). `levels = 0` copies the input.
//!
//! # Buffers
//!
//! [`subdivide`] writes the final level into `out` (at least [`refined_len`] points) and
//! ping-pongs the intermediate levels between `out` and `scratch` (at least
//! [`scratch_len`] points), so that the last level lands in `out`. Nothing is allocated.
//!
//! # Errors
//!
//! Every failure is reported before the first level is computed where it can be:
//! [`Status::TooFewPoints`], [`Status::SizeOverflow`] (checked size arithmetic),
//! [`Status::BufferTooSmall`] (with [`Error::needed`], `out` checked before `scratch`),
//! [`Status::NonFiniteInput`] (element = point index). Geometry failures during a level
//! ([`Status::DegenerateGeometry`], [`Status::NumericalFailure`]) name the input point that
//! starts the input segment in which the failing point lies (`⌊j / 2^ℓ⌋` for point `j` of
//! level `ℓ`). The contents of `out` and `scratch` are unspecified after an error.
//!
//! Repeated consecutive points: the linear schemes (4-point, B-spline, differential) are
//! defined for any input. The Möbius schemes apply F4's defined coincident rules
//! ([`crate::blend::f4`]: `b = c → b`, `a = b → b`, `c = d → c`, `a = c → c`, `b = d → b`;
//! the open-end rule likewise, see [`mobius::end_edge_point`]), so a repeated point is kept
//! and never an error. The circle blend needs three distinct points for each circle and gives
//! [`Status::DegenerateGeometry`] (see [`circle_blend`]).
//!
//! ```
//! use nlsubdiv::curve::{self, CurveScheme};
//! // Four points on the unit circle, closed, 3 levels of the circle blend.
//! let pts = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]];
//! let n = curve::refined_len(pts.len(), true, 3).unwrap();
//! let s = curve::scratch_len(CurveScheme::CircleBlend, pts.len(), true, 3).unwrap();
//! let mut out = [[0.0; 3]; 32];
//! let mut scratch = [[0.0; 3]; 16];
//! assert_eq!((n, s), (32, 16));
//! let written =
//!     curve::subdivide(CurveScheme::CircleBlend, &pts, true, 3, &mut out, &mut scratch).unwrap();
//! assert_eq!(written, 32);
//! for p in &out {
//!     let r = libm::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
//!     assert!((r - 1.0).abs() < 1e-14);
//! }
//! ```

pub mod bspline;
pub mod circle_blend;
pub mod differential;
pub mod four_point;
pub mod mobius;

use crate::error::{Error, Result, Status};
use crate::point::{self, dot, Point};

/// A curve subdivision scheme. The discriminants are stable codes of the C ABI
/// (`NLS_CURVE_*`), never reused.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CurveScheme {
    /// The linear interpolating 4-point scheme of Dyn, Levin and Gregory with `w = 1/16`
    /// ([`four_point`]).
    FourPoint = 0,
    /// The cubic B-spline scheme (Chaikin–Lane–Riesenfeld, degree 3), end points kept on open
    /// curves ([`bspline`]).
    BSpline = 1,
    /// The Möbius interpolating scheme of seed 000 §4.4.1: edge points by F4 ([`mobius`]).
    MobiusInterpolating = 2,
    /// The Möbius approximating scheme of seed 000 §4.4.1: edge points by F4, vertex points
    /// by F4 of the two old neighbours and the two new edge points ([`mobius`]).
    MobiusApproximating = 3,
    /// The circle blend of seed 003 §2 ([`circle_blend`]).
    CircleBlend = 4,
    /// Differential-space subdivision (seed 001 §3.5) with the 4-point scheme on the
    /// differential polygon ([`differential`]).
    DifferentialFourPoint = 5,
    /// Differential-space subdivision (seed 001 §3.5) with the cubic B-spline scheme on the
    /// differential polygon ([`differential`]).
    DifferentialBSpline = 6,
}

impl CurveScheme {
    /// Every scheme, in code order.
    pub const ALL: [CurveScheme; 7] = [
        CurveScheme::FourPoint,
        CurveScheme::BSpline,
        CurveScheme::MobiusInterpolating,
        CurveScheme::MobiusApproximating,
        CurveScheme::CircleBlend,
        CurveScheme::DifferentialFourPoint,
        CurveScheme::DifferentialBSpline,
    ];

    /// The stable numeric code.
    pub const fn code(self) -> u32 {
        self as u32
    }

    /// The scheme of a numeric code, or `None` for an unassigned code.
    pub fn from_code(code: u32) -> Option<CurveScheme> {
        CurveScheme::ALL.iter().copied().find(|s| s.code() == code)
    }

    /// The name used by the command line and in reports (DESIGN.md, "The `nlsubdiv`
    /// command"): `four-point`, `bspline`, `mobius-interpolating`, `mobius-approximating`,
    /// `circle-blend`, `differential-four-point`, `differential-bspline`.
    pub const fn name(self) -> &'static str {
        match self {
            CurveScheme::FourPoint => "four-point",
            CurveScheme::BSpline => "bspline",
            CurveScheme::MobiusInterpolating => "mobius-interpolating",
            CurveScheme::MobiusApproximating => "mobius-approximating",
            CurveScheme::CircleBlend => "circle-blend",
            CurveScheme::DifferentialFourPoint => "differential-four-point",
            CurveScheme::DifferentialBSpline => "differential-bspline",
        }
    }

    /// The scheme of a name from [`CurveScheme::name`]; `differential` is accepted as
    /// [`CurveScheme::DifferentialFourPoint`].
    pub fn from_name(name: &str) -> Option<CurveScheme> {
        if name == "differential" {
            return Some(CurveScheme::DifferentialFourPoint);
        }
        CurveScheme::ALL.iter().copied().find(|s| s.name() == name)
    }

    /// Whether the scheme keeps the old points (bit for bit) at the even output indices.
    pub const fn is_interpolating(self) -> bool {
        matches!(
            self,
            CurveScheme::FourPoint | CurveScheme::MobiusInterpolating | CurveScheme::CircleBlend
        )
    }

    /// Whether points of a circle stay on that circle (up to rounding).
    pub const fn is_circle_preserving(self) -> bool {
        matches!(
            self,
            CurveScheme::MobiusInterpolating
                | CurveScheme::MobiusApproximating
                | CurveScheme::CircleBlend
        )
    }
}

/// The smallest number of points of a curve: 3 for a closed curve, 2 for an open one
/// (the same for every scheme).
pub const fn min_points(closed: bool) -> usize {
    if closed {
        3
    } else {
        2
    }
}

/// The number of points after one level: `2n` (closed) or `2n − 1` (open).
///
/// # Errors
/// [`Status::TooFewPoints`] below [`min_points`]; [`Status::SizeOverflow`].
pub fn refined_len_once(n: usize, closed: bool) -> Result<usize> {
    if n < min_points(closed) {
        return Err(Error::new(Status::TooFewPoints));
    }
    let twice = n.checked_mul(2).ok_or(Error::new(Status::SizeOverflow))?;
    if closed {
        Ok(twice)
    } else {
        twice.checked_sub(1).ok_or(Error::new(Status::SizeOverflow))
    }
}

/// The exact number of output points after `levels` levels of any scheme:
/// `n·2^k` (closed) or `(n − 1)·2^k + 1` (open).
///
/// # Errors
/// [`Status::TooFewPoints`] when `n` is below [`min_points`]; [`Status::SizeOverflow`] when
/// the size does not fit in `usize`.
pub fn refined_len(n: usize, closed: bool, levels: u32) -> Result<usize> {
    if n < min_points(closed) {
        return Err(Error::new(Status::TooFewPoints));
    }
    let mut len = n;
    for _ in 0..levels {
        len = refined_len_once(len, closed)?;
    }
    Ok(len)
}

/// The number of scratch points [`subdivide`] needs: the size of level `k − 1` for the
/// local schemes when `k ≥ 2` (0 for `k ≤ 1`); for the differential schemes the size of
/// level `k − 1` when `k ≥ 1` (the differential polygon `Δ⁰` also needs a buffer), 0 for
/// `k = 0`.
///
/// # Errors
/// As [`refined_len`].
pub fn scratch_len(scheme: CurveScheme, n: usize, closed: bool, levels: u32) -> Result<usize> {
    // Validate the final size first, so that an overflow is reported for every query.
    refined_len(n, closed, levels)?;
    let differential = matches!(
        scheme,
        CurveScheme::DifferentialFourPoint | CurveScheme::DifferentialBSpline
    );
    let first = if differential { 1 } else { 2 };
    if levels < first {
        return Ok(0);
    }
    refined_len(n, closed, levels - 1)
}

/// Subdivides the curve `points` `levels` times with `scheme` into `out` and returns the
/// number of points written (= [`refined_len`]). See the [module documentation](self) for the
/// output order, the buffers and the errors.
///
/// # Errors
/// [`Status::TooFewPoints`], [`Status::SizeOverflow`], [`Status::BufferTooSmall`] (`out`
/// below [`refined_len`], then `scratch` below [`scratch_len`]), [`Status::NonFiniteInput`]
/// (element = point index), [`Status::DegenerateGeometry`] and [`Status::NumericalFailure`]
/// (element = input point starting the segment at fault).
pub fn subdivide(
    scheme: CurveScheme,
    points: &[Point],
    closed: bool,
    levels: u32,
    out: &mut [Point],
    scratch: &mut [Point],
) -> Result<usize> {
    let n = points.len();
    let total = refined_len(n, closed, levels)?;
    let need_scratch = scratch_len(scheme, n, closed, levels)?;
    if out.len() < total {
        return Err(Error::too_small(total));
    }
    if scratch.len() < need_scratch {
        return Err(Error::too_small(need_scratch));
    }
    check_finite(points)?;
    let out = out.get_mut(..total).ok_or(Error::too_small(total))?;
    if levels == 0 {
        for (o, p) in out.iter_mut().zip(points) {
            *o = *p;
        }
        return Ok(total);
    }
    match scheme {
        CurveScheme::FourPoint => run_levels(
            four_point::refine_level,
            Level0::Input(points),
            closed,
            out,
            scratch,
            levels,
        )?,
        CurveScheme::BSpline => run_levels(
            bspline::refine_level,
            Level0::Input(points),
            closed,
            out,
            scratch,
            levels,
        )?,
        CurveScheme::MobiusInterpolating => run_levels(
            mobius::refine_interpolating_level,
            Level0::Input(points),
            closed,
            out,
            scratch,
            levels,
        )?,
        CurveScheme::MobiusApproximating => run_levels(
            mobius::refine_approximating_level,
            Level0::Input(points),
            closed,
            out,
            scratch,
            levels,
        )?,
        CurveScheme::CircleBlend => run_levels(
            circle_blend::refine_level,
            Level0::Input(points),
            closed,
            out,
            scratch,
            levels,
        )?,
        CurveScheme::DifferentialFourPoint => differential::run(
            differential::DifferentialBase::FourPoint,
            points,
            closed,
            out,
            scratch,
            levels,
        )?,
        CurveScheme::DifferentialBSpline => differential::run(
            differential::DifferentialBase::BSpline,
            points,
            closed,
            out,
            scratch,
            levels,
        )?,
    }
    Ok(total)
}

/// One level of a local rule: reads a polygon, writes exactly its refined size. The
/// polygon is known to be long enough and finite; errors name an index of that polygon.
pub(crate) type LevelRule = fn(&[Point], bool, &mut [Point]) -> Result<()>;

/// Where level 0 of a ping-pong run is.
pub(crate) enum Level0<'a> {
    /// The caller's input.
    Input(&'a [Point]),
    /// The first `n` entries of the buffer that level 1 is *not* written to (`scratch` when
    /// `levels` is odd, `out` when it is even).
    InBuffer(usize),
}

/// Runs `levels ≥ 1` levels of `rule`, level `ℓ` into `out` when `levels − ℓ` is even and
/// into `scratch` otherwise, so the last level lands in `out`. The level before a level
/// written to `out` comes from `scratch` and vice versa.
pub(crate) fn run_levels(
    rule: LevelRule,
    level0: Level0<'_>,
    closed: bool,
    out: &mut [Point],
    scratch: &mut [Point],
    levels: u32,
) -> Result<()> {
    let mut len = match level0 {
        Level0::Input(p) => p.len(),
        Level0::InBuffer(n) => n,
    };
    for level in 1..=levels {
        let next = refined_len_once(len, closed)?;
        let to_out = (levels - level) % 2 == 0;
        let result = match (level, &level0) {
            (1, Level0::Input(points)) => {
                let buf: &mut [Point] = if to_out { &mut *out } else { &mut *scratch };
                let dst = buf.get_mut(..next).ok_or(Error::too_small(next))?;
                rule(points, closed, dst)
            }
            _ if to_out => {
                let src = scratch.get(..len).ok_or(Error::too_small(len))?;
                let dst = out.get_mut(..next).ok_or(Error::too_small(next))?;
                rule(src, closed, dst)
            }
            _ => {
                let src = out.get(..len).ok_or(Error::too_small(len))?;
                let dst = scratch.get_mut(..next).ok_or(Error::too_small(next))?;
                rule(src, closed, dst)
            }
        };
        result.map_err(|e| to_input_element(e, level - 1))?;
        len = next;
    }
    Ok(())
}

/// Maps an element index of the polygon of level `level` to the input point starting the
/// input segment that contains it: `⌊j / 2^level⌋`.
pub(crate) fn to_input_element(e: Error, level: u32) -> Error {
    if e.element == crate::error::NO_ELEMENT {
        return e;
    }
    Error {
        element: e.element.checked_shr(level).unwrap_or(0),
        ..e
    }
}

/// [`Status::NonFiniteInput`] naming the first point with a NaN or infinite coordinate.
pub(crate) fn check_finite(points: &[Point]) -> Result<()> {
    match points.iter().position(|p| !point::is_finite(p)) {
        Some(i) => Err(Error::at(Status::NonFiniteInput, index_u32(i))),
        None => Ok(()),
    }
}

/// Validation shared by the public one-level functions of the scheme modules: enough
/// points, an output of at least the refined size, finite input. Returns the refined size.
pub(crate) fn check_level(points: &[Point], closed: bool, out: &[Point]) -> Result<usize> {
    let next = refined_len_once(points.len(), closed)?;
    if out.len() < next {
        return Err(Error::too_small(next));
    }
    check_finite(points)?;
    Ok(next)
}

/// An element index as `u32` (saturating: indices beyond `u32::MAX − 1` are reported as
/// `u32::MAX − 1`, never as "no element").
pub(crate) fn index_u32(i: usize) -> u32 {
    u32::try_from(i).unwrap_or(u32::MAX - 1).min(u32::MAX - 1)
}

/// The point `points[i]`, or [`Status::TooFewPoints`] if the index is out of range
/// (unreachable after validation; there to keep the kernel free of panics).
#[inline]
pub(crate) fn at(points: &[Point], i: usize) -> Result<Point> {
    points
        .get(i)
        .copied()
        .ok_or(Error::new(Status::TooFewPoints))
}

/// `points[(i + k) mod n]` for a small offset `k ∈ {−1, 1, 2}` on a closed polygon.
#[inline]
pub(crate) fn cyclic(points: &[Point], i: usize, k: isize) -> Result<Point> {
    let n = points.len();
    let j = match k {
        -1 => {
            if i == 0 {
                n.wrapping_sub(1)
            } else {
                i - 1
            }
        }
        _ => {
            let j = i.wrapping_add(k.unsigned_abs());
            if j >= n {
                j.wrapping_sub(n)
            } else {
                j
            }
        }
    };
    at(points, j)
}

/// `p` if finite, else [`Status::NumericalFailure`] naming `element`.
#[inline]
pub(crate) fn finite(p: Point, element: usize) -> Result<Point> {
    if point::is_finite(&p) {
        Ok(p)
    } else {
        Err(Error::at(Status::NumericalFailure, index_u32(element)))
    }
}

/// The length of a curve vector: `√(a·a)` down to a squared length of 1e-280 (every square
/// there is still a normal number, so the plain root loses nothing), below that and on
/// overflow the scaled [`crate::point::norm`]. The curve rules keep this wider fast path of
/// their own; the branch depends only on `a`, so the result is deterministic.
#[inline]
pub(crate) fn norm(a: Point) -> f64 {
    let s = dot(a, a);
    if s.is_finite() && s >= 1e-280 {
        libm::sqrt(s)
    } else {
        crate::point::norm(a)
    }
}

/// The first `refined_len_once(p.len())` entries of `out`: the exact output of one level.
#[inline]
pub(crate) fn level_out<'a>(
    p: &[Point],
    closed: bool,
    out: &'a mut [Point],
) -> Result<&'a mut [Point]> {
    let next = refined_len_once(p.len(), closed)?;
    out.get_mut(..next).ok_or(Error::too_small(next))
}
