//! Running `k` levels of a curve scheme into caller buffers: the public [`subdivide`] and the
//! ping-pong loop of the local rules.
//!
//! A local rule reads one polygon and writes the next, so `k` levels need two buffers: the
//! levels alternate between `out` and `scratch`, starting in whichever makes the last level
//! land in `out`. The differential schemes are global (seed 001 §3.5: subdivide `Δ`, then
//! reconstruct once) and run their own driver on the same buffers.

use super::differential::{self, DifferentialBase};
use super::polygon::check_finite;
use super::{bspline, circle_blend, four_point, mobius};
use super::{refined_size, refined_size_once, scratch_size, CurveScheme};
use crate::error::{Error, Result, Status};
use crate::point::Point;

/// Subdivides the curve `points` `levels` times with `scheme` into `out` and returns the
/// number of points written (= [`refined_size`]). See the [module documentation](super) for the
/// output order, the buffers and the errors.
///
/// # Errors
/// [`Status::SchemeNotBuilt`] first, for a scheme this build does not contain
/// ([`CurveScheme::is_built`]); [`Status::TooFewPoints`], [`Status::SizeOverflow`],
/// [`Status::BufferTooSmall`] (`out`
/// below [`refined_size`], then `scratch` below [`scratch_size`]), [`Status::NonFiniteInput`]
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
    if !scheme.is_built() {
        return Err(Error::new(Status::SchemeNotBuilt));
    }
    let n = points.len();
    let total = refined_size(n, closed, levels)?;
    let need_scratch = scratch_size(scheme, n, closed, levels)?;
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
    match driver(scheme)? {
        Driver::Local(rule) => {
            run_levels(rule, Level0::Input(points), closed, out, scratch, levels)?
        }
        Driver::Differential(base) => {
            differential::run(base, points, closed, out, scratch, levels)?
        }
    }
    Ok(total)
}

/// How a scheme computes its levels.
enum Driver {
    /// One local rule per level ([`run_levels`]).
    Local(LevelRule),
    /// The global differential driver on the given linear scheme.
    Differential(DifferentialBase),
}

/// The driver of `scheme`, when this build contains it ([`CurveScheme::is_built`]): an arm
/// of a scheme left out has a constant `false` guard, so the optimiser removes it and the
/// linker its rule.
fn driver(scheme: CurveScheme) -> Result<Driver> {
    let (curves, mobius) = (cfg!(feature = "curves"), cfg!(feature = "mobius"));
    Ok(match scheme {
        CurveScheme::FourPoint if curves => Driver::Local(four_point::refine_level),
        CurveScheme::BSpline if curves => Driver::Local(bspline::refine_level),
        CurveScheme::MobiusInterpolating if curves && mobius => {
            Driver::Local(mobius::refine_interpolating_level)
        }
        CurveScheme::MobiusApproximating if curves && mobius => {
            Driver::Local(mobius::refine_approximating_level)
        }
        CurveScheme::CircleBlend if curves => Driver::Local(circle_blend::refine_level),
        CurveScheme::DifferentialFourPoint if curves => {
            Driver::Differential(DifferentialBase::FourPoint)
        }
        CurveScheme::DifferentialBSpline if curves => {
            Driver::Differential(DifferentialBase::BSpline)
        }
        _ => return Err(Error::new(Status::SchemeNotBuilt)),
    })
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
        let next = refined_size_once(len, closed)?;
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
