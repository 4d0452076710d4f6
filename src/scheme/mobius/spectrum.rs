//! The fold guard's fallback: a star's canonical form interpolated toward a similarity by the
//! star's trust `τ` (`trust.rs`), the Möbius–linear spectrum of seed 000 §7.2 taken per star:
//!
//! `m_τ(x) = −((x − v)⁻¹ − τ c)⁻¹`, with inverse `P ↦ v + (τ c − P⁻¹)⁻¹`,
//!
//! where `v` is the centre and `c` the centre of the star's tangent polygon (seed 000 §4.2).
//!
//! * At `τ = 1` it is the normalised canonical form `x ↦ −r (T − c)⁻¹` divided by `r`, a
//!   scale that affine stencils ignore: the paper's rule.
//! * At `τ = 0` it is the point reflection `x ↦ v − x`, on which every affine stencil gives
//!   the linear rule.
//! * For every `τ` it is a Möbius map sending `v` to the origin; its pole `v + (τ c)⁻¹`
//!   recedes to infinity as `τ → 0`, so the rule moves continuously from the paper's to the
//!   linear one, and `τ` is continuous in the star's geometry.
//!
//! The stencils, the back map and the blends (F4, the face chain) are those of the paper; only
//! the frame changes. `m_τ` is equivariant under the similarities only (`τ c` does not follow
//! the translation part of a Möbius map's action on `T`): any rule that ends at the linear
//! scheme must give up Möbius equivariance in proportion to `1 − τ`, since the linear scheme
//! has only similarity equivariance. Trusted stars (`τ = 1`) never come here: they keep the
//! canonical form's own maps, bit for bit.

use super::form::{MapBack, ORIGIN};
use crate::error::{Error, Result, Status};
use crate::point::{self, add, cross, dot, scale, sub, Point};
use crate::quat::inverse_point;

/// `m_τ` of one star (module docs).
pub(super) struct Spectrum {
    /// The centre vertex `v`.
    v: Point,
    /// `τ c`.
    tc: Point,
}

impl Spectrum {
    /// `m_τ` of the star centred at `v` whose tangent polygon `tangents` has centre `c`
    /// (module docs: `τ c` moves toward `c₀`, the foot of the perpendicular from the origin
    /// onto the polygon's plane, as far as the polygon is planar).
    pub(super) fn new(v: Point, c: Point, tangents: &[Point], tau: f64) -> Spectrum {
        let c0 = scale(sphere_foot(c, tangents), 1.0 - tau);
        Spectrum {
            v,
            tc: add(scale(c, tau), c0),
        }
    }

    /// `m_τ(x)`: `v ↦` the origin; [`Status::DegenerateGeometry`] for the pole or a
    /// non-finite result.
    pub(super) fn to(&self, x: Point) -> Result<Point> {
        let bad = Error::new(Status::DegenerateGeometry);
        if x == self.v {
            return Ok(ORIGIN);
        }
        let t = inverse_point(sub(x, self.v)).ok_or(bad)?;
        let y = inverse_point(sub(t, self.tc)).ok_or(bad)?;
        let y = scale(y, -1.0);
        if point::is_finite(&y) {
            Ok(y)
        } else {
            Err(bad)
        }
    }
}

impl MapBack for Spectrum {
    /// `m_τ⁻¹(p) = v + (τ c − p⁻¹)⁻¹`: the origin `↦ v`.
    fn back(&self, p: Point) -> Result<Point> {
        let bad = Error::new(Status::DegenerateGeometry);
        if p == ORIGIN {
            return Ok(self.v);
        }
        let pinv = inverse_point(p).ok_or(bad)?;
        let t = inverse_point(sub(self.tc, pinv)).ok_or(bad)?;
        let x = add(self.v, t);
        if point::is_finite(&x) {
            Ok(x)
        } else {
            Err(bad)
        }
    }
}

/// Out-of-plane spread of the tangent polygon (over its in-plane spread) at or below which the
/// star counts as spherical (`c₀` is the foot of the perpendicular), and at or above which
/// it counts as not (`c₀ = 0`); linear between.
const PLANAR: f64 = 1e-6;
const NOT_PLANAR: f64 = 1e-4;

/// `c₀` of the module docs: the foot of the perpendicular from the origin onto the plane of
/// the tangent polygon (through its centre `c`, Newell normal), scaled by how planar the
/// polygon is. A planar tangent polygon is a star whose vertex and neighbours lie on one
/// sphere (or plane): `x ↦ (x − v)⁻¹` sends that sphere to the polygon's plane. With `c₀`
/// in that plane, every `m_τ` sends the sphere to a plane through the origin, so the affine
/// stencils stay on it and their images on the sphere (sphere reproduction, seed 000
/// Lemma A.1); `m_0` is then the inversion about the antipode of `v` on the sphere (a
/// stereographic projection), and a plane's `c₀` is 0. The planarity is a ratio of lengths
/// of `T`, which a Möbius map of the input changes by a similarity only (seed 000 Lemma 3.2),
/// so `c₀`'s choice is Möbius-invariant.
fn sphere_foot(c: Point, tangents: &[Point]) -> Point {
    let mut n = [0.0; 3];
    for (i, t) in tangents.iter().enumerate() {
        let u = tangents.get((i + 1) % tangents.len()).copied().unwrap_or(*t);
        n = add(n, cross(*t, u));
    }
    let nn = dot(n, n);
    if !(nn.is_finite() && nn > 0.0) {
        return [0.0; 3];
    }
    let (mut off, mut spread) = (0.0f64, 0.0f64);
    for t in tangents {
        let d = sub(*t, c);
        let h = dot(d, n);
        off = off.max(h * h / nn);
        spread = spread.max(dot(d, d));
    }
    let planarity = libm::sqrt(off / spread);
    let w = if planarity <= PLANAR {
        1.0
    } else if planarity < NOT_PLANAR {
        (NOT_PLANAR - planarity) / (NOT_PLANAR - PLANAR)
    } else {
        0.0
    };
    let foot = scale(n, w * dot(n, c) / nn);
    if point::is_finite(&foot) {
        foot
    } else {
        [0.0; 3]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mobius::{CanonicalForm, StarKind};
    use crate::point::norm;

    const V: Point = [0.3, -0.2, 0.1];
    const RING: [Point; 5] = [
        [1.3, -0.2, 0.1],
        [0.6, 0.9, 0.3],
        [-0.9, 0.5, 0.0],
        [-0.4, -1.4, 0.2],
        [0.9, -1.0, -0.1],
    ];

    /// `m_τ⁻¹ ∘ m_τ` is the identity, for every `τ`.
    #[test]
    fn round_trip() {
        let cf = CanonicalForm::new(V, &RING, StarKind::Interior).unwrap();
        for tau in [0.0, 0.3, 1.0] {
            let m = Spectrum::new(V, cf.c, tau);
            for x in RING {
                let y = m.back(m.to(x).unwrap()).unwrap();
                assert!(norm(sub(x, y)) < 1e-13, "{tau}: {x:?} {y:?}");
            }
            assert_eq!(m.to(V).unwrap(), ORIGIN);
            assert_eq!(m.back(ORIGIN).unwrap(), V);
        }
    }

    /// `τ = 1`: the normalised canonical form divided by `r`; `τ = 0`: the point reflection.
    #[test]
    fn ends() {
        let cf = CanonicalForm::new(V, &RING, StarKind::Interior).unwrap();
        let one = Spectrum::new(V, cf.c, 1.0);
        let zero = Spectrum::new(V, cf.c, 0.0);
        for x in RING {
            let n = scale(cf.to_normalised(x).unwrap(), 1.0 / cf.r);
            assert!(norm(sub(one.to(x).unwrap(), n)) < 1e-12 * norm(n));
            let r = sub(V, x);
            assert!(norm(sub(zero.to(x).unwrap(), r)) < 1e-14);
        }
    }
}
