//! Canonical forms of vertex stars (seed 000 §4.2, Fig. 7, Lemma 3.2).
//!
//! The canonical form of a star `v u_1 … u_n` is its image under the Möbius map that sends
//! the star to its tangent polygon `T_i = (u_i − v)⁻¹` and then inverts in the sphere of
//! centre `c(T)` and radius `r(T)`. Möbius-equivalent stars have similar canonical forms, so a
//! linear stencil evaluated in the form and mapped back is a Möbius-invariant rule: this is
//! how every Möbius scheme computes its candidates (§4.3).

use arrayvec::ArrayVec;

use super::MobiusMap;
use crate::error::{Error, Result, Status};
use crate::point::{self, add, norm, scale, sub, Point};
use crate::quat::{inverse_point, Quat};
use crate::MAX_VALENCE;

/// Which construction of seed 000 §4.2 a canonical form uses.
///
/// `#[non_exhaustive]`: a later version may add a variant, so a `match` outside this crate
/// needs a wildcard arm; [`StarKind::ALL`] lists every kind.
#[non_exhaustive]
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

impl StarKind {
    /// Every kind (for callers that map kinds to codes of their own, such as the C ABI).
    pub const ALL: [StarKind; 3] = [StarKind::Interior, StarKind::Boundary, StarKind::Ear];
}

/// The canonical form `C_v` of a vertex star `v u_1 … u_n` (seed 000 §4.2, Fig. 7).
///
/// `m_{B→C} = m_{T→C} ∘ m_{B→T}` with `m_{B→T}(q) = (q − v)⁻¹` (star to tangent polygon) and
/// `m_{T→C}(q) = r² (c − q)⁻¹ + c`, the inversion in the sphere of centre `c(T_v)` and radius
/// `r(T_v)`. As the paper does in practice (§4.2), `c` is the barycentre of `T` (the centre of
/// its best-fit circle for a regular polygon, which is what Möbius-regularity needs), or on the
/// boundary the mean of the two boundary neighbours' images; `r` is the mean of `|T_i − c|` over
/// all `i`. The centre `v` goes to `c`. Möbius-equivalent stars have similar canonical forms (Lemma 3.2), and a Möbius-regular
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

    /// [`CanonicalForm::to_normalised`] with every failure as a NaN point, inlined: the fold
    /// guard's output audit maps the child points around every star of a level and only
    /// asks whether each could be mapped (the call and its `Result` through memory were a
    /// third of its cost). The same bits as `to_normalised` where that succeeds (tested).
    #[inline(always)]
    pub(crate) fn to_normalised_or_nan(&self, x: Point) -> Point {
        let mapped = match inverse_point(sub(x, self.v)) {
            Some(t) => inverse_point(sub(t, self.c)).map(|inv| scale(inv, -self.r)),
            // `to_normalised`'s `v ↦ 0`, only for finite values.
            None if x == self.v && point::is_finite(&x) => Some([0.0; 3]),
            None => None,
        };
        match mapped {
            Some(y) if finite3(&y) => y,
            _ => [f64::NAN; 3],
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
    use crate::point::distance;

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
            assert!(distance(c1, c2) < 1e-13, "{c1:?} {c2:?}");
            let back = cf.from_canonical(c1).unwrap();
            assert!(distance(back, u) < 1e-13);
            assert!(distance(mi.apply(c1).unwrap(), u) < 1e-13);
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
            assert!(distance(c, scale(*u, -1.0)) < 1e-15);
        }
    }

    #[test]
    fn the_audit_map_is_to_normalised_or_nan() {
        let v = [0.1, 0.0, 0.2];
        let ring = [[1.0, 0.1, 0.0], [0.3, 1.0, 0.2], [-0.9, 0.4, 0.1]];
        let cf = CanonicalForm::new(v, &ring, StarKind::Interior).unwrap();
        let check = |x: Point| {
            let lean = cf.to_normalised_or_nan(x);
            match cf.to_normalised(x) {
                Ok(y) => assert_eq!(lean.map(f64::to_bits), y.map(f64::to_bits), "{x:?}"),
                Err(_) => assert!(lean.iter().all(|c| c.is_nan()), "{x:?} {lean:?}"),
            }
        };
        // The pole (`T = c`), points next to it, at `v`, far, tiny, subnormal, non-finite.
        let pole = add(v, inverse_point(cf.c).unwrap());
        for p in [
            v,
            pole,
            add(pole, [1e-300, 0.0, 0.0]),
            add(pole, [1e-12, 0.0, 0.0]),
            add(v, [1e-310, 0.0, 0.0]),
            add(v, [1e-160, 0.0, 0.0]),
            [1e300, 1e300, 0.0],
            [f64::NAN, 0.0, 0.0],
            [0.0, f64::INFINITY, 0.0],
            [f64::NEG_INFINITY, 0.0, 1.0],
        ] {
            check(p);
        }
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..2000 {
            let mut p = [0.0; 3];
            for c in &mut p {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                *c = ((x >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 4.0;
            }
            check(p);
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
