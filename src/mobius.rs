//! Möbius maps `q ↦ (aq + b)(cq + d)⁻¹` and canonical forms of vertex stars
//! (seed 000 §3.2 Eq. (1) and §4.2).
//!
//! A Möbius map is stored as the quaternionic 2×2 matrix `[[a, b], [c, d]]` acting on
//! `[q; 1]` by left multiplication, with the right scalar `(cq + d)⁻¹`; so composition is the
//! matrix product and the inverse map is the matrix inverse in M₂(H).

use arrayvec::ArrayVec;

use crate::error::{Error, Result, Status};
use crate::point::{self, add, norm, scale, sub, Point};
use crate::quat::{inverse_point, Quat};
use crate::MAX_VALENCE;

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

/// Which construction of seed 000 §4.2 a canonical form uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StarKind {
    /// A closed star: `c` is the barycentre of the tangent polygon.
    Interior,
    /// An open star ordered from one boundary neighbour to the other: `c` is the mean of the
    /// images of the two boundary neighbours.
    Boundary,
    /// A valence-2 boundary vertex with one face: the star is the face's other vertices,
    /// from one boundary neighbour to the other; `c` as for [`StarKind::Boundary`].
    Ear,
}

/// The canonical form `C_v` of a vertex star `v u_1 … u_n` (seed 000 §4.2, Fig. 7).
///
/// `m_{B→C} = m_{T→C} ∘ m_{B→T}` with `m_{B→T}(q) = (q − v)⁻¹` (star to tangent polygon) and
/// `m_{T→C}(q) = r² (c − q)⁻¹ + c`, the inversion in the sphere of centre `c(T_v)` and radius
/// `r(T_v)` (DESIGN.md: `c` the barycentre of `T`, or the mean of the two boundary neighbours'
/// images on the boundary; `r` the mean of `|T_i − c|` over all `i`). The centre `v` goes to
/// `c`. Möbius-equivalent stars have similar canonical forms (Lemma 3.2), and a Möbius-regular
/// star has a regular canonical form.
#[derive(Clone, Debug, PartialEq)]
pub struct CanonicalForm {
    /// The centre vertex `v` of the star.
    pub v: Point,
    /// The centre `c(T_v)`, which is also the image of `v`.
    pub c: Point,
    /// The radius `r(T_v)` of the inversion.
    pub r: f64,
    /// The construction used.
    pub kind: StarKind,
}

impl CanonicalForm {
    /// The canonical form of the star `v ring[0] … ring[n−1]`.
    ///
    /// For [`StarKind::Interior`] the ring is cyclic; for [`StarKind::Boundary`] and
    /// [`StarKind::Ear`] it runs from one boundary neighbour to the other; n ≥ 2 for all.
    ///
    /// # Errors
    /// [`Status::TooFewPoints`] for a ring too short for its kind; [`Status::ValenceTooHigh`]
    /// above [`MAX_VALENCE`]; [`Status::NonFiniteInput`]; [`Status::DegenerateGeometry`] when
    /// a neighbour coincides with `v` (element = ring index) or the tangent polygon has zero
    /// radius about `c`.
    pub fn new(v: Point, ring: &[Point], kind: StarKind) -> Result<CanonicalForm> {
        let mut t: ArrayVec<Point, MAX_VALENCE> = ArrayVec::new();
        CanonicalForm::new_with_tangents(v, ring, kind, &mut t)
    }

    /// [`CanonicalForm::new`], leaving the tangent polygon `T_i = (ring[i] − v)⁻¹` in `t`
    /// (the drivers map the ring into the form from it: [`CanonicalForm::to_normalised`]
    /// computes the same `T_i` again).
    pub(crate) fn new_with_tangents(
        v: Point,
        ring: &[Point],
        kind: StarKind,
        t: &mut ArrayVec<Point, MAX_VALENCE>,
    ) -> Result<CanonicalForm> {
        let n = ring.len();
        // Two neighbours suffice for every kind: an interior valence-2 vertex (two faces
        // glued along two edges) has a digon as tangent polygon, centred at its midpoint.
        if n < 2 {
            return Err(Error::new(Status::TooFewPoints));
        }
        if n > MAX_VALENCE {
            return Err(Error::new(Status::ValenceTooHigh));
        }
        if !point::is_finite(&v) {
            return Err(Error::new(Status::NonFiniteInput));
        }
        t.clear();
        for (i, u) in ring.iter().enumerate() {
            let ti = CanonicalForm::tangent(v, *u)
                .ok_or_else(|| tangent_error(*u).with_element(i as u32))?;
            t.try_push(ti)
                .map_err(|_| Error::new(Status::ValenceTooHigh))?;
        }
        CanonicalForm::from_tangents(v, t, kind)
    }

    /// The tangent-polygon vertex `(u − v)⁻¹`: `tangent_polygon_vertex(v, u)` bit for bit for
    /// a finite `v`, `None` where it fails. Its inverse only succeeds for a finite non-zero
    /// `u − v`, so `u` needs no check of its own (the callers check `v` once per star).
    #[inline]
    pub(crate) fn tangent(v: Point, u: Point) -> Option<Point> {
        inverse_point(sub(u, v))
    }

    /// The canonical form of the star of the finite point `v` whose tangent polygon is `t`
    /// (`t[i] = (ring[i] − v)⁻¹`, [`CanonicalForm::tangent`]); the errors of
    /// [`CanonicalForm::new`] for a ring too short or too long and for a zero radius.
    pub(crate) fn from_tangents(v: Point, t: &[Point], kind: StarKind) -> Result<CanonicalForm> {
        let n = t.len();
        if n < 2 {
            return Err(Error::new(Status::TooFewPoints));
        }
        if n > MAX_VALENCE {
            return Err(Error::new(Status::ValenceTooHigh));
        }
        let c = match kind {
            StarKind::Interior => {
                let mut s = [0.0; 3];
                for ti in t.iter() {
                    s = add(s, *ti);
                }
                scale(s, 1.0 / n as f64)
            }
            StarKind::Boundary | StarKind::Ear => match (t.first(), t.last()) {
                (Some(f), Some(l)) => scale(add(*f, *l), 0.5),
                _ => return Err(Error::new(Status::TooFewPoints)),
            },
        };
        let mut r = 0.0;
        for ti in t.iter() {
            r += norm(sub(*ti, c));
        }
        r /= n as f64;
        if !(r > 0.0 && r.is_finite() && point::is_finite(&c)) {
            return Err(Error::new(Status::DegenerateGeometry));
        }
        Ok(CanonicalForm { v, c, r, kind })
    }

    /// The map `m_{B→C}` from the star to its canonical form.
    pub fn map(&self) -> MobiusMap {
        MobiusMap::inversion(self.c, self.r).compose(&MobiusMap::star_to_tangent(self.v))
    }

    /// The map `m_{C→B} = m_{B→C}⁻¹` back from the canonical form to the star:
    /// `C ↦ v + (c − r²(C − c)⁻¹)⁻¹` (the inversion is an involution).
    pub fn inverse_map(&self) -> MobiusMap {
        let back = MobiusMap {
            a: Quat::from_point(self.v),
            b: Quat::ONE,
            c: Quat::ONE,
            d: Quat::ZERO,
        }; // T ↦ (vT + 1)T⁻¹ = v + T⁻¹
        back.compose(&MobiusMap::inversion(self.c, self.r))
    }

    /// Sends a point of the star's neighbourhood to the canonical form:
    /// `x ↦ c − r² (T − c)⁻¹` with `T = (x − v)⁻¹`; `v` itself goes to `c`.
    ///
    /// # Errors
    /// [`Status::DegenerateGeometry`] when `x` is sent to ∞ (it lies on the inverse image of
    /// `c`); [`Status::NonFiniteInput`].
    pub fn to_canonical(&self, x: Point) -> Result<Point> {
        if !point::is_finite(&x) {
            return Err(Error::new(Status::NonFiniteInput));
        }
        if x == self.v {
            return Ok(self.c);
        }
        let t = crate::quat::tangent_polygon_vertex(self.v, x)?;
        invert_in_sphere(t, self.c, self.r)
    }

    /// Sends a point of the canonical form back to the star: `C ↦ v + T⁻¹` with
    /// `T = c − r² (C − c)⁻¹`; `c` itself goes back to `v`.
    ///
    /// # Errors
    /// [`Status::DegenerateGeometry`] when `C` is sent to ∞; [`Status::NonFiniteInput`].
    pub fn from_canonical(&self, p: Point) -> Result<Point> {
        if !point::is_finite(&p) {
            return Err(Error::new(Status::NonFiniteInput));
        }
        if p == self.c {
            return Ok(self.v);
        }
        let t = invert_in_sphere(p, self.c, self.r)?;
        let back = inverse_point(t).ok_or(Error::new(Status::DegenerateGeometry))?;
        let x = add(self.v, back);
        if point::is_finite(&x) {
            Ok(x)
        } else {
            Err(Error::new(Status::DegenerateGeometry))
        }
    }

    /// The canonical form in its normalised frame, `z ↦ (z − c)/r` composed after
    /// [`CanonicalForm::to_canonical`]: `x ↦ −r (T − c)⁻¹` with `T = (x − v)⁻¹`, and `v ↦ 0`.
    ///
    /// The similarity changes nothing for affine stencils (their weights sum to 1) but avoids
    /// the cancellation in `c − r²(T − c)⁻¹` when `|c| ≫ |C − c|` (stars with very uneven
    /// edges), so the drivers evaluate their stencils in this frame.
    ///
    /// # Errors
    /// As [`CanonicalForm::to_canonical`].
    #[inline]
    pub fn to_normalised(&self, x: Point) -> Result<Point> {
        // The hot path of the drivers (a mesh vertex of the star's neighbourhood): one
        // inverse. Its fast path only passes for a finite non-zero `x − v`, so the input
        // checks of `to_canonical` wait for its failure (`x − v = 0` iff `x = v` for finite
        // values: subtraction never underflows to zero), with the same statuses.
        match inverse_point(sub(x, self.v)) {
            Some(t) => self.normalised_from_tangent(t),
            None if !point::is_finite(&x) || !point::is_finite(&self.v) => {
                Err(Error::new(Status::NonFiniteInput))
            }
            None if x == self.v => Ok([0.0; 3]),
            None => Err(Error::new(Status::DegenerateGeometry)),
        }
    }

    /// [`CanonicalForm::to_normalised`] of the point whose tangent-polygon vertex
    /// `(x − v)⁻¹` is `t`: `−r (t − c)⁻¹`.
    #[inline]
    pub(crate) fn normalised_from_tangent(&self, t: Point) -> Result<Point> {
        let inv = inverse_point(sub(t, self.c)).ok_or(Error::new(Status::DegenerateGeometry))?;
        let y = scale(inv, -self.r);
        if finite3(&y) {
            Ok(y)
        } else {
            Err(Error::new(Status::DegenerateGeometry))
        }
    }

    /// The inverse of [`CanonicalForm::to_normalised`]: `P ↦ v + T⁻¹` with `T = c − r P⁻¹`,
    /// and `0 ↦ v`.
    ///
    /// # Errors
    /// As [`CanonicalForm::from_canonical`].
    // Inlined into the drivers' back maps: the call and its 32-byte `Result` through memory
    // were a fifth of its cost (Catmull–Clark and Doo–Sabin take one per corner).
    #[inline(always)]
    pub fn from_normalised(&self, p: Point) -> Result<Point> {
        // `0 ↦ v` first: a NaN `p` compares unequal and fails the inverse below, whose fast
        // path passes only finite non-zero points; the input check waits for that failure.
        if p == [0.0; 3] {
            return Ok(self.v);
        }
        let Some(pinv) = inverse_point(p) else {
            return Err(Error::new(if point::is_finite(&p) {
                Status::DegenerateGeometry
            } else {
                Status::NonFiniteInput
            }));
        };
        let t = sub(self.c, scale(pinv, self.r));
        let back = inverse_point(t).ok_or(Error::new(Status::DegenerateGeometry))?;
        let x = add(self.v, back);
        if finite3(&x) {
            Ok(x)
        } else {
            Err(Error::new(Status::DegenerateGeometry))
        }
    }

    /// Writes the canonical images of `ring` into `out` (`out[i] = to_canonical(ring[i])`).
    ///
    /// # Errors
    /// [`Status::BufferTooSmall`]; the errors of [`CanonicalForm::to_canonical`] with the ring
    /// index as element.
    pub fn ring_to_canonical(&self, ring: &[Point], out: &mut [Point]) -> Result<()> {
        if out.len() < ring.len() {
            return Err(Error::too_small(ring.len()));
        }
        for (i, (u, o)) in ring.iter().zip(out.iter_mut()).enumerate() {
            *o = self
                .to_canonical(*u)
                .map_err(|e| e.with_element(i as u32))?;
        }
        Ok(())
    }
}

/// The inversion `x ↦ c − r² (x − c)⁻¹ = c + r² (x − c)/|x − c|²`.
fn invert_in_sphere(x: Point, c: Point, r: f64) -> Result<Point> {
    let inv = inverse_point(sub(x, c)).ok_or(Error::new(Status::DegenerateGeometry))?;
    let y = sub(c, scale(inv, r * r));
    if point::is_finite(&y) {
        Ok(y)
    } else {
        Err(Error::new(Status::DegenerateGeometry))
    }
}

/// The error of `tangent_polygon_vertex(v, u)` for a finite `v` whose inverse failed.
fn tangent_error(u: Point) -> Error {
    Error::new(if point::is_finite(&u) {
        Status::DegenerateGeometry
    } else {
        Status::NonFiniteInput
    })
}

/// [`point::is_finite`] in fewer instructions: `0·a` is `±0` for a finite `a` and NaN for ±∞
/// and NaN, and a sum of zeros is zero while a NaN term makes it NaN (IEEE arithmetic, no
/// fast-math: the compiler may not fold `0·a`).
#[inline]
fn finite3(p: &Point) -> bool {
    p[0] * 0.0 + p[1] * 0.0 + p[2] * 0.0 == 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dist(a: Point, b: Point) -> f64 {
        norm(sub(a, b))
    }

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
        assert!(dist(r, [0.0, 1.0, 0.0]) < 1e-15);
        // Inversion in the sphere (m, r): |x − m| |x' − m| = r², same ray.
        let m = [0.2, 0.1, -0.3];
        let x = MobiusMap::inversion(m, 2.0).apply(p).unwrap();
        assert!((dist(x, m) * dist(p, m) - 4.0).abs() < 1e-13);
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
            assert!(dist(direct, comp) < 1e-12 * (1.0 + norm(direct)));
            let back = mi.apply(comp).unwrap();
            assert!(dist(back, p) < 1e-12 * (1.0 + norm(p)), "{back:?} {p:?}");
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
        assert!(dist(ai.apply(anti.apply(p).unwrap()).unwrap(), p) < 1e-15);
    }

    #[test]
    fn canonical_form_round_trip_and_centre() {
        let v = [0.1, 0.0, 0.2];
        let ring = [
            [1.0, 0.1, 0.0],
            [0.3, 1.0, 0.2],
            [-0.9, 0.4, 0.1],
            [-0.5, -1.1, 0.0],
            [0.6, -0.8, -0.1],
        ];
        let cf = CanonicalForm::new(v, &ring, StarKind::Interior).unwrap();
        assert_eq!(cf.to_canonical(v).unwrap(), cf.c);
        let m = cf.map();
        let mi = cf.inverse_map();
        for u in ring {
            let c1 = cf.to_canonical(u).unwrap();
            let c2 = m.apply(u).unwrap();
            assert!(dist(c1, c2) < 1e-13, "{c1:?} {c2:?}");
            let back = cf.from_canonical(c1).unwrap();
            assert!(dist(back, u) < 1e-13);
            assert!(dist(mi.apply(c1).unwrap(), u) < 1e-13);
        }
    }

    #[test]
    fn regular_star_has_regular_canonical_form() {
        // A Euclidean-regular planar star: T is a regular polygon, c its centre, r its
        // circumradius, so the inversion fixes T: C_i = T_i.
        let n = 7;
        let v = [0.0; 3];
        let ring: ArrayVec<Point, 8> = (0..n)
            .map(|i| {
                let t = 2.0 * core::f64::consts::PI * i as f64 / n as f64;
                [libm::cos(t), libm::sin(t), 0.0]
            })
            .collect();
        let cf = CanonicalForm::new(v, &ring, StarKind::Interior).unwrap();
        assert!(norm(cf.c) < 1e-15);
        assert!((cf.r - 1.0).abs() < 1e-15);
        for u in &ring {
            let c = cf.to_canonical(*u).unwrap();
            assert!(dist(c, scale(*u, -1.0)) < 1e-15);
        }
    }

    #[test]
    fn normalised_frame_statuses() {
        // The input checks of the normalised maps run only when an inverse fails; the
        // statuses are those of `to_canonical` / `from_canonical`.
        let v = [0.1, 0.0, 0.2];
        let ring = [[1.0, 0.1, 0.0], [0.3, 1.0, 0.2], [-0.9, 0.4, 0.1]];
        let cf = CanonicalForm::new(v, &ring, StarKind::Interior).unwrap();
        assert_eq!(cf.to_normalised(v).unwrap(), [0.0; 3]);
        assert_eq!(cf.from_normalised([0.0; 3]).unwrap(), v);
        for bad in [
            [f64::NAN, 0.0, 0.0],
            [0.0, f64::INFINITY, 0.0],
            [0.0, 0.0, f64::NEG_INFINITY],
        ] {
            let e = cf.to_normalised(bad).unwrap_err();
            assert_eq!(e.status, Status::NonFiniteInput);
            let e = cf.from_normalised(bad).unwrap_err();
            assert_eq!(e.status, Status::NonFiniteInput);
            let e =
                CanonicalForm::new(v, &[ring[0], bad, ring[2]], StarKind::Interior).unwrap_err();
            assert_eq!((e.status, e.element), (Status::NonFiniteInput, 1));
        }
        // x − v overflows: no inverse, finite inputs.
        let far = CanonicalForm {
            v: [-1e308, 0.0, 0.0],
            ..cf.clone()
        };
        let e = far.to_normalised([1e308, 0.0, 0.0]).unwrap_err();
        assert_eq!(e.status, Status::DegenerateGeometry);
        // A result beyond f64: an error, never a non-finite success.
        let huge = CanonicalForm {
            v: [f64::MAX, 0.0, 0.0],
            ..cf.clone()
        };
        for p in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.5, 0.0]] {
            if let Ok(x) = huge.from_normalised(p) {
                assert!(point::is_finite(&x));
            }
        }
        let nan_r = CanonicalForm {
            r: f64::NAN,
            ..cf.clone()
        };
        assert!(nan_r.to_normalised(ring[0]).is_err());
        assert!(nan_r.from_normalised([1.0, 0.0, 0.0]).is_err());
        for (p, f) in [
            ([1.0, -2.0, 3.0], true),
            ([f64::MAX, -f64::MAX, 0.0], true),
            ([f64::NAN, 0.0, 0.0], false),
            ([0.0, 0.0, f64::INFINITY], false),
            ([f64::INFINITY, f64::NEG_INFINITY, 0.0], false),
        ] {
            assert_eq!(finite3(&p), f);
            assert_eq!(point::is_finite(&p), f);
        }
    }

    #[test]
    fn degenerate_stars() {
        let v = [0.0; 3];
        let e = CanonicalForm::new(v, &[[1.0, 0.0, 0.0]], StarKind::Interior).unwrap_err();
        assert_eq!(e.status, Status::TooFewPoints);
        let e = CanonicalForm::new(
            v,
            &[[1.0, 0.0, 0.0], v, [0.0, 1.0, 0.0]],
            StarKind::Interior,
        )
        .unwrap_err();
        assert_eq!((e.status, e.element), (Status::DegenerateGeometry, 1));
        let e = CanonicalForm::new(
            [f64::INFINITY, 0.0, 0.0],
            &[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            StarKind::Interior,
        )
        .unwrap_err();
        assert_eq!(e.status, Status::NonFiniteInput);
        // All neighbours at one point: r = 0.
        let p = [1.0, 1.0, 0.0];
        let e = CanonicalForm::new(v, &[p, p, p], StarKind::Interior).unwrap_err();
        assert_eq!(e.status, Status::DegenerateGeometry);
        let big = [[1.0, 0.0, 0.0]; MAX_VALENCE + 1];
        let e = CanonicalForm::new(v, &big, StarKind::Interior).unwrap_err();
        assert_eq!(e.status, Status::ValenceTooHigh);
    }
}
