//! Möbius maps of R³ ∪ {∞}: `q ↦ (aq + b)(cq + d)⁻¹` (seed 000 §3.2, Eq. (1)).
//!
//! A Möbius map is stored as the quaternionic 2×2 matrix `[[a, b], [c, d]]` acting on
//! `[q; 1]` by left multiplication, with the right scalar `(cq + d)⁻¹`; so composition is the
//! matrix product and the inverse map is the matrix inverse in M₂(H). The crate's rules never
//! need a map to compute a point (they use cross-ratios and canonical forms); maps are here to
//! state and test Möbius equivariance, and for the C ABI.

use crate::error::{Error, Result, Status};
use crate::point::{self, Point};
use crate::quat::Quat;

/// A Möbius transformation of R³ ∪ {∞}, `q ↦ (aq + b)(cq + d)⁻¹` (seed 000 Eq. (1)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MobiusMap {
    /// Coefficient `a`.
    pub a: Quat,
    /// Coefficient `b`.
    pub b: Quat,
    /// Coefficient `c`.
    pub c: Quat,
    /// Coefficient `d`.
    pub d: Quat,
}

impl MobiusMap {
    /// The identity map.
    pub const IDENTITY: MobiusMap = MobiusMap {
        a: Quat::ONE,
        b: Quat::ZERO,
        c: Quat::ZERO,
        d: Quat::ONE,
    };

    /// The translation `q ↦ q + t`.
    pub fn translation(t: Point) -> MobiusMap {
        MobiusMap {
            b: Quat::from_point(t),
            ..MobiusMap::IDENTITY
        }
    }

    /// The uniform scaling `q ↦ s q` about the origin (`s ≠ 0`; a negative `s` is the point
    /// reflection composed with scaling).
    pub fn scaling(s: f64) -> MobiusMap {
        MobiusMap {
            a: Quat::real(s),
            ..MobiusMap::IDENTITY
        }
    }

    /// The rotation `q ↦ u q u⁻¹` by the angle `angle` about the unit axis `axis`.
    pub fn rotation(axis: Point, angle: f64) -> MobiusMap {
        let (s, c) = (libm::sin(0.5 * angle), libm::cos(0.5 * angle));
        let u = Quat::new(c, axis[0] * s, axis[1] * s, axis[2] * s);
        MobiusMap {
            a: u,
            b: Quat::ZERO,
            c: Quat::ZERO,
            d: u,
        }
    }

    /// The inversion in the sphere of centre `m` and radius `r`:
    /// `q ↦ m + r² (q − m)/|q − m|² = m − r² (q − m)⁻¹`.
    pub fn inversion(m: Point, r: f64) -> MobiusMap {
        let mq = Quat::from_point(m);
        MobiusMap {
            a: mq,
            b: -(mq * mq) - Quat::real(r * r),
            c: Quat::ONE,
            d: -mq,
        }
    }

    /// The map `q ↦ (q − v)⁻¹` that sends a vertex star to its tangent polygon
    /// (`m_{B→T}`, seed 000 Lemma 3.1).
    pub fn star_to_tangent(v: Point) -> MobiusMap {
        MobiusMap {
            a: Quat::ZERO,
            b: Quat::ONE,
            c: Quat::ONE,
            d: -Quat::from_point(v),
        }
    }

    /// `self ∘ other`: first `other`, then `self`.
    pub fn compose(&self, other: &MobiusMap) -> MobiusMap {
        MobiusMap {
            a: self.a * other.a + self.b * other.c,
            b: self.a * other.b + self.b * other.d,
            c: self.c * other.a + self.d * other.c,
            d: self.c * other.b + self.d * other.d,
        }
    }

    /// The inverse map (the inverse matrix in M₂(H), by Schur complements with the larger of
    /// `a`, `d` as pivot).
    ///
    /// # Errors
    /// [`Status::DegenerateGeometry`] when the matrix is singular (not a Möbius map).
    pub fn inverse(&self) -> Result<MobiusMap> {
        let singular = Error::new(Status::DegenerateGeometry);
        let MobiusMap { a, b, c, d } = *self;
        let by_a = || -> Option<MobiusMap> {
            let ai = a.inverse()?;
            let s = d - c * ai * b;
            let si = s.inverse()?;
            Some(MobiusMap {
                a: ai + ai * b * si * c * ai,
                b: -(ai * b * si),
                c: -(si * c * ai),
                d: si,
            })
        };
        let by_d = || -> Option<MobiusMap> {
            let di = d.inverse()?;
            let t = a - b * di * c;
            let ti = t.inverse()?;
            Some(MobiusMap {
                a: ti,
                b: -(ti * b * di),
                c: -(di * c * ti),
                d: di + di * c * ti * b * di,
            })
        };
        let anti = || -> Option<MobiusMap> {
            // a = d = 0: [[0, b], [c, 0]]⁻¹ = [[0, c⁻¹], [b⁻¹, 0]].
            if a != Quat::ZERO || d != Quat::ZERO {
                return None;
            }
            Some(MobiusMap {
                a: Quat::ZERO,
                b: c.inverse()?,
                c: b.inverse()?,
                d: Quat::ZERO,
            })
        };
        let inv = if a.abs() >= d.abs() {
            by_a().or_else(by_d)
        } else {
            by_d().or_else(by_a)
        }
        .or_else(anti)
        .ok_or(singular)?;
        let finite = inv.a.is_finite() && inv.b.is_finite() && inv.c.is_finite();
        if finite && inv.d.is_finite() {
            Ok(inv)
        } else {
            Err(singular)
        }
    }

    /// The image of the point `p`. The real part of `(ap + b)(cp + d)⁻¹`, zero in exact
    /// arithmetic for a map of R³, is dropped.
    ///
    /// # Errors
    /// [`Status::DegenerateGeometry`] when `p` is sent to ∞; [`Status::NonFiniteInput`].
    pub fn apply(&self, p: Point) -> Result<Point> {
        if !point::is_finite(&p) {
            return Err(Error::new(Status::NonFiniteInput));
        }
        let q = Quat::from_point(p);
        let den = (self.c * q + self.d)
            .inverse()
            .ok_or(Error::new(Status::DegenerateGeometry))?;
        let w = ((self.a * q + self.b) * den).to_point();
        if point::is_finite(&w) {
            Ok(w)
        } else {
            Err(Error::new(Status::DegenerateGeometry))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::point::{distance, norm};

    #[test]
    fn elementary_maps() {
        let p = [0.5, -1.0, 2.0];
        let t = MobiusMap::translation([1.0, 2.0, 3.0]).apply(p).unwrap();
        assert_eq!(t, [1.5, 1.0, 5.0]);
        let s = MobiusMap::scaling(2.0).apply(p).unwrap();
        assert_eq!(s, [1.0, -2.0, 4.0]);
        let r = MobiusMap::rotation([0.0, 0.0, 1.0], core::f64::consts::FRAC_PI_2)
            .apply([1.0, 0.0, 0.0])
            .unwrap();
        assert!(distance(r, [0.0, 1.0, 0.0]) < 1e-15);
        // Inversion in the sphere (m, r): |x − m| |x' − m| = r², same ray.
        let m = [0.2, 0.1, -0.3];
        let x = MobiusMap::inversion(m, 2.0).apply(p).unwrap();
        assert!((distance(x, m) * distance(p, m) - 4.0).abs() < 1e-13);
        assert_eq!(
            MobiusMap::inversion(m, 2.0).apply(m).unwrap_err().status,
            Status::DegenerateGeometry
        );
    }

    #[test]
    fn compose_and_inverse() {
        let m1 = MobiusMap::inversion([0.3, 1.0, -0.5], 1.7);
        let m2 = MobiusMap::rotation([0.6, 0.0, 0.8], 0.9)
            .compose(&MobiusMap::translation([1.0, -2.0, 0.5]))
            .compose(&MobiusMap::scaling(0.3));
        let m = m1.compose(&m2);
        let mi = m.inverse().unwrap();
        for p in [[0.1, 0.2, 0.3], [-4.0, 1.0, 2.5], [10.0, -3.0, 0.0]] {
            let direct = m1.apply(m2.apply(p).unwrap()).unwrap();
            let comp = m.apply(p).unwrap();
            assert!(distance(direct, comp) < 1e-12 * (1.0 + norm(direct)));
            let back = mi.apply(comp).unwrap();
            assert!(
                distance(back, p) < 1e-12 * (1.0 + norm(p)),
                "{back:?} {p:?}"
            );
        }
        let singular = MobiusMap {
            a: Quat::ONE,
            b: Quat::ONE,
            c: Quat::ONE,
            d: Quat::ONE,
        };
        assert_eq!(
            singular.inverse().unwrap_err().status,
            Status::DegenerateGeometry
        );
        // a = d = 0 branch.
        let anti = MobiusMap::star_to_tangent([0.0; 3]);
        let ai = anti.inverse().unwrap();
        let p = [0.3, -0.2, 0.9];
        assert!(distance(ai.apply(anti.apply(p).unwrap()).unwrap(), p) < 1e-15);
    }
}
