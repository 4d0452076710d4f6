//! The fold guard's fallback: a star's canonical form interpolated toward a similarity by the
//! star's trust `τ` (`trust.rs`), the Möbius–linear spectrum of seed 000 §7.2 taken per star:
//!
//! `m_τ(x) = −((x − v)⁻¹ − c_τ)⁻¹`, with inverse `P ↦ v + (c_τ − P⁻¹)⁻¹`, `c_τ = τ c`,
//!
//! where `v` is the centre and `c` the centre of the star's tangent polygon (seed 000 §4.2).
//!
//! **Spherical stars.** When the vertex and its neighbours lie on one sphere (the tangent
//! polygon is planar, `trust::sphericity`), `c_τ = τ c + (1 − τ) c₀` with `c₀` the foot of the
//! perpendicular from the origin onto the polygon's plane: `c_τ` stays in that plane, so every
//! `m_τ` sends the sphere to a plane through the origin, the affine stencils stay in it, and
//! their images stay on the sphere (sphere reproduction, seed 000 Lemma A.1). `m_0` is then
//! the inversion about the antipode of `v` on its sphere (a stereographic projection); for a
//! planar star `c₀ = 0`. `c₀` is weighted by the sphericity, so the frame stays continuous in
//! the star's geometry.
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
use super::trust::{newell, sphericity};
use crate::error::{Error, Result, Status};
use crate::point::{self, add, dot, scale, sub, Point};
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
    /// (module docs: `c_τ = τ c + (1 − τ) s c₀`).
    pub(super) fn new(v: Point, c: Point, tangents: &[Point], tau: f64) -> Spectrum {
        let s = sphericity(tangents, c);
        let mut foot = [0.0; 3];
        if s > 0.0 {
            let n = newell(tangents);
            let nn = dot(n, n);
            if nn > 0.0 && nn.is_finite() {
                foot = scale(n, s * dot(n, c) / nn);
            }
        }
        let tc = add(scale(c, tau), scale(foot, 1.0 - tau));
        Spectrum {
            v,
            tc: if point::is_finite(&tc) {
                tc
            } else {
                scale(c, tau)
            },
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
            let m = Spectrum::new(V, cf.c, &[], tau);
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
        let one = Spectrum::new(V, cf.c, &[], 1.0);
        let zero = Spectrum::new(V, cf.c, &[], 0.0);
        for x in RING {
            let n = scale(cf.to_normalised(x).unwrap(), 1.0 / cf.r);
            assert!(norm(sub(one.to(x).unwrap(), n)) < 1e-12 * norm(n));
            let r = sub(V, x);
            assert!(norm(sub(zero.to(x).unwrap(), r)) < 1e-14);
        }
    }
}
