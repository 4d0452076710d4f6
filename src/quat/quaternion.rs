//! Quaternions on H with points of R³ as imaginary quaternions (seed 000 §3.1).
//!
//! A point `(x, y, z)` is the quaternion `[0, (x, y, z)]`. The product is
//! `[r, v]·[s, w] = [rs − ⟨v, w⟩, rw + sv + v × w]`, the conjugate `[r, −v]`, the inverse
//! `q̄ / |q|²`. Every operation is written out in plain `f64` arithmetic: no fused
//! multiply-add, transcendental functions from `libm`, so results are bit-identical on every
//! run and platform. The inverse and the absolute value avoid overflow and underflow of
//! `|q|²` by scaling outside a fast path, because the Möbius rules invert differences of
//! points that may be very close or very far apart.

use core::ops::{Add, Mul, Neg, Sub};

use crate::point::{self, Point};

/// Below this sum of squares the fast paths of [`Quat::abs`] and [`Quat::inverse`] give way to
/// scaled evaluation (far above the subnormal range, so no precision is lost).
pub(crate) const SAFE_MIN: f64 = 1e-250;
/// Above this sum of squares [`Quat::inverse`] scales first (its result would be tiny).
const SAFE_MAX: f64 = 1e250;

/// A quaternion `w + xi + yj + zk`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Quat {
    /// Real part.
    pub w: f64,
    /// First imaginary component.
    pub x: f64,
    /// Second imaginary component.
    pub y: f64,
    /// Third imaginary component.
    pub z: f64,
}

impl Quat {
    /// Zero.
    pub const ZERO: Quat = Quat::new(0.0, 0.0, 0.0, 0.0);
    /// One.
    pub const ONE: Quat = Quat::new(1.0, 0.0, 0.0, 0.0);

    /// The quaternion `w + xi + yj + zk`.
    pub const fn new(w: f64, x: f64, y: f64, z: f64) -> Quat {
        Quat { w, x, y, z }
    }

    /// The real quaternion `s`.
    pub const fn real(s: f64) -> Quat {
        Quat::new(s, 0.0, 0.0, 0.0)
    }

    /// The imaginary quaternion `[0, p]` of a point of R³.
    pub const fn from_point(p: Point) -> Quat {
        Quat::new(0.0, p[0], p[1], p[2])
    }

    pub(crate) const fn from_parts(w: f64, v: Point) -> Quat {
        Quat::new(w, v[0], v[1], v[2])
    }

    /// The imaginary part as a point of R³ (the real part is dropped).
    pub const fn to_point(self) -> Point {
        [self.x, self.y, self.z]
    }

    /// `[w, x, y, z]`, the layout of the C ABI.
    pub const fn to_array(self) -> [f64; 4] {
        [self.w, self.x, self.y, self.z]
    }

    /// The quaternion of `[w, x, y, z]`.
    pub const fn from_array(a: [f64; 4]) -> Quat {
        Quat::new(a[0], a[1], a[2], a[3])
    }

    pub(crate) const fn im(self) -> Point {
        [self.x, self.y, self.z]
    }

    /// Real part `Re q`.
    pub const fn re(self) -> f64 {
        self.w
    }

    /// Conjugate `q̄ = [w, −v]`.
    pub fn conj(self) -> Quat {
        Quat::new(self.w, -self.x, -self.y, -self.z)
    }

    /// `|q|²`.
    #[inline(always)]
    pub fn norm_sq(self) -> f64 {
        self.w * self.w + self.x * self.x + self.y * self.y + self.z * self.z
    }

    /// `|q|`, computed without overflow or underflow of the squares.
    #[inline(always)]
    pub fn abs(self) -> f64 {
        // Fast path: the plain sum of squares is exact enough whenever it neither overflows
        // nor enters the subnormal range; otherwise scale by the largest component first.
        let n = self.norm_sq();
        if n.is_finite() && n > SAFE_MIN {
            return crate::sqrt::sqrt(n);
        }
        self.abs_scaled()
    }

    /// [`Quat::abs`] outside the fast path's range, out of line: the blends inline the fast
    /// path many times.
    #[cold]
    #[inline(never)]
    fn abs_scaled(self) -> f64 {
        let m = self
            .w
            .abs()
            .max(self.x.abs())
            .max(self.y.abs())
            .max(self.z.abs());
        if m == 0.0 || !m.is_finite() {
            return m;
        }
        // Divide (rather than multiply by 1/m, which overflows for subnormal m).
        let s = Quat::new(self.w / m, self.x / m, self.y / m, self.z / m);
        m * crate::sqrt::sqrt(s.norm_sq())
    }

    /// `|Im q|`.
    #[inline(always)]
    pub fn abs_im(self) -> f64 {
        Quat::new(0.0, self.x, self.y, self.z).abs()
    }

    /// `s·q` for a real `s`.
    pub fn scale(self, s: f64) -> Quat {
        Quat::new(self.w * s, self.x * s, self.y * s, self.z * s)
    }

    /// Whether all four components are finite.
    #[inline(always)]
    pub fn is_finite(self) -> bool {
        self.w.is_finite() && self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }

    /// The inverse `q⁻¹ = q̄ / |q|²`, or `None` when `q` is zero, not finite, or so small or
    /// large that the inverse is not a finite, non-zero quaternion.
    #[inline(always)]
    pub fn inverse(self) -> Option<Quat> {
        let n = self.norm_sq();
        if n > SAFE_MIN && n < SAFE_MAX {
            // Fast path: q̄ / |q|² with a result far from overflow and underflow. A finite
            // |q|² in range implies finite components (a NaN or ∞ component makes |q|² NaN or
            // ∞, which fails both comparisons), so the finiteness test waits for the slow path.
            return Some(Quat::new(self.w / n, -self.x / n, -self.y / n, -self.z / n));
        }
        self.inverse_scaled()
    }

    /// [`Quat::inverse`] outside the fast path's range, out of line (as [`Quat::abs_scaled`]).
    #[cold]
    #[inline(never)]
    fn inverse_scaled(self) -> Option<Quat> {
        if !self.is_finite() {
            return None;
        }
        let m = self
            .w
            .abs()
            .max(self.x.abs())
            .max(self.y.abs())
            .max(self.z.abs());
        if m == 0.0 {
            return None;
        }
        // Scale to unit size first so that |q|² neither overflows nor underflows.
        let s = Quat::new(self.w / m, self.x / m, self.y / m, self.z / m);
        let k = s.norm_sq() * m;
        let c = s.conj();
        let inv = Quat::new(c.w / k, c.x / k, c.y / k, c.z / k);
        (inv.is_finite() && inv != Quat::ZERO).then_some(inv)
    }

    /// Polar form `q = |q|·[cos θ, n sin θ]` with `θ ∈ [0, π]` and `|n| = 1`
    /// (seed 000 §3.1). For a real `q` the axis is undefined and returned as `None`.
    pub fn polar(self) -> (f64, f64, Option<Point>) {
        let r = self.abs();
        let vi = self.abs_im();
        let theta = libm::atan2(vi, self.w);
        if vi == 0.0 {
            return (r, theta, None);
        }
        let n = point::div(self.im(), vi);
        (r, theta, Some(n))
    }

    /// The principal square root, `√q = √|q|·[cos θ/2, n sin θ/2]`, whose real part is never
    /// negative (seed 000 §3.1: the branch the blends of §4.4 are stated with).
    ///
    /// Computed with half-angle formulas that stay accurate in both half spaces. Returns
    /// `None` for a negative real `q` (the root is then any `√|q|·[0, n]`: callers choose `n`)
    /// and for non-finite input.
    pub fn sqrt(self) -> Option<Quat> {
        if !self.is_finite() {
            return None;
        }
        self.sqrt_given(self.abs(), self.abs_im())
    }

    /// [`Quat::sqrt`] of a finite `self` with `r = self.abs()` and `vi = self.abs_im()`
    /// already computed by the caller (the blends test for a negative real with them first).
    pub(crate) fn sqrt_given(self, r: f64, vi: f64) -> Option<Quat> {
        if !self.is_finite() {
            return None;
        }
        if vi == 0.0 {
            if self.w >= 0.0 {
                return Some(Quat::real(crate::sqrt::sqrt(self.w)));
            }
            return None;
        }
        if self.w >= 0.0 {
            // Re √q = √((r + w)/2) is accurate; Im = v / (2 Re).
            let s = crate::sqrt::sqrt(0.5 * (r + self.w));
            Some(Quat::from_parts(s, point::div(self.im(), 2.0 * s)))
        } else {
            // |Im √q| = √((r − w)/2) is accurate; Re = |v| / (2 |Im|).
            let n = point::div(self.im(), vi);
            let t = crate::sqrt::sqrt(0.5 * (r - self.w));
            Some(Quat::from_parts(vi / (2.0 * t), point::scale(n, t)))
        }
    }

    /// [`Quat::sqrt_given`] with `r = self.abs()`, bit for bit, for any `q`; it saves `|Im q|`
    /// for a finite `q` with `Re q ≥ 0`: in that half space the root reads only whether
    /// `Im q` is zero, and `abs_im` is zero exactly when its three components are. Otherwise
    /// it computes `|Im q|` and calls [`Quat::sqrt_given`].
    #[inline(always)]
    pub(crate) fn sqrt_upper(self, r: f64) -> Option<Quat> {
        if self.w >= 0.0 && self.is_finite() {
            if self.x == 0.0 && self.y == 0.0 && self.z == 0.0 {
                return Some(Quat::real(crate::sqrt::sqrt(self.w)));
            }
            let s = crate::sqrt::sqrt(0.5 * (r + self.w));
            return Some(Quat::from_parts(s, point::div(self.im(), 2.0 * s)));
        }
        self.sqrt_given(r, self.abs_im())
    }

    /// `√q` with a caller-chosen axis for a negative real `q`: `√|q|·[0, axis]`
    /// (`axis` must be a unit vector).
    pub fn sqrt_with_axis(self, axis: Point) -> Option<Quat> {
        match self.sqrt() {
            Some(s) => Some(s),
            None if self.is_finite() => {
                let t = crate::sqrt::sqrt(-self.w);
                Some(Quat::new(0.0, axis[0] * t, axis[1] * t, axis[2] * t))
            }
            None => None,
        }
    }

    /// The principal logarithm `log q = [ln |q|, n θ]`, or `None` for zero, a negative real
    /// (axis undefined) or non-finite `q`.
    pub fn log(self) -> Option<Quat> {
        if !self.is_finite() || self == Quat::ZERO {
            return None;
        }
        let (r, theta, n) = self.polar();
        match n {
            Some(n) => Some(Quat::new(
                libm::log(r),
                n[0] * theta,
                n[1] * theta,
                n[2] * theta,
            )),
            None if self.w > 0.0 => Some(Quat::real(libm::log(r))),
            None => None,
        }
    }

    /// The exponential `exp [w, v] = e^w [cos |v|, v/|v| sin |v|]`.
    pub fn exp(self) -> Quat {
        let e = libm::exp(self.w);
        let vi = self.abs_im();
        if vi == 0.0 {
            return Quat::real(e);
        }
        let s = e * libm::sin(vi) / vi;
        Quat::new(e * libm::cos(vi), self.x * s, self.y * s, self.z * s)
    }
}

impl Add for Quat {
    type Output = Quat;
    fn add(self, o: Quat) -> Quat {
        Quat::new(self.w + o.w, self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl Sub for Quat {
    type Output = Quat;
    fn sub(self, o: Quat) -> Quat {
        Quat::new(self.w - o.w, self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Neg for Quat {
    type Output = Quat;
    fn neg(self) -> Quat {
        Quat::new(-self.w, -self.x, -self.y, -self.z)
    }
}

impl Mul for Quat {
    type Output = Quat;
    /// The Hamilton product `[r, v]·[s, w] = [rs − ⟨v, w⟩, rw + sv + v × w]`.
    #[inline(always)]
    fn mul(self, o: Quat) -> Quat {
        Quat::new(
            self.w * o.w - self.x * o.x - self.y * o.y - self.z * o.z,
            self.w * o.x + self.x * o.w + self.y * o.z - self.z * o.y,
            self.w * o.y - self.x * o.z + self.y * o.w + self.z * o.x,
            self.w * o.z + self.x * o.y - self.y * o.x + self.z * o.w,
        )
    }
}

impl Quat {
    /// `self · [0, p]`, the Hamilton product with an imaginary quaternion, without the
    /// products by its zero real part: `[w, v]·[0, p] = [−⟨v, p⟩, w p + v × p]`. The remaining
    /// terms are summed in the order of [`Mul`], so the result equals `self * [0, p]` bit for
    /// bit except possibly the sign of a component that is exactly zero (adding the dropped
    /// `±0` terms changes nothing else).
    #[inline(always)]
    pub(crate) fn mul_im(self, p: Point) -> Quat {
        Quat::new(
            -(self.x * p[0]) - self.y * p[1] - self.z * p[2],
            self.w * p[0] + self.y * p[2] - self.z * p[1],
            self.w * p[1] - self.x * p[2] + self.z * p[0],
            self.w * p[2] + self.x * p[1] - self.y * p[0],
        )
    }
}

/// `[0, a]·[0, b] = [−⟨a, b⟩, a × b]`, as [`Quat::mul_im`] (the same bits as the full product
/// up to the sign of an exactly zero component).
#[inline]
pub(crate) fn im_mul_im(a: Point, b: Point) -> Quat {
    Quat::new(
        -(a[0] * b[0]) - a[1] * b[1] - a[2] * b[2],
        a[1] * b[2] - a[2] * b[1],
        -(a[0] * b[2]) + a[2] * b[0],
        a[0] * b[1] - a[1] * b[0],
    )
}

/// `Quat::from_point(p).inverse().map(Quat::to_point)` bit for bit, for the inverse of an
/// imaginary quaternion `[0, p]⁻¹ = [0, −p/|p|²]` that nearly every Möbius rule takes: with a
/// zero real part `|q|²` is the same sum of three squares (`0 + x² = x²` exactly) and the real
/// part of the result is `+0`, so the fast path needs three divisions instead of four and no
/// quaternion.
#[inline]
pub(crate) fn inverse_point(p: Point) -> Option<Point> {
    let n = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    if n > SAFE_MIN && n < SAFE_MAX {
        return Some([-p[0] / n, -p[1] / n, -p[2] / n]);
    }
    Quat::from_point(p).inverse().map(Quat::to_point)
}

#[cfg(test)]
mod tests {
    use super::super::testing::close;
    use super::*;

    #[test]
    fn hamilton_units() {
        let i = Quat::new(0.0, 1.0, 0.0, 0.0);
        let j = Quat::new(0.0, 0.0, 1.0, 0.0);
        let k = Quat::new(0.0, 0.0, 0.0, 1.0);
        assert_eq!(i * j, k);
        assert_eq!(j * k, i);
        assert_eq!(k * i, j);
        assert_eq!(i * i, Quat::real(-1.0));
        assert_eq!(i * j * k, Quat::real(-1.0));
    }

    #[test]
    fn inverse_and_conjugate() {
        let q = Quat::new(1.5, -2.0, 0.25, 3.0);
        let qi = q.inverse().unwrap();
        assert!(close(q * qi, Quat::ONE, 1e-15));
        assert!(close(qi * q, Quat::ONE, 1e-15));
        // conj(pq) = conj(q) conj(p)
        let p = Quat::new(-0.5, 1.0, 2.0, -1.0);
        assert!(close((p * q).conj(), q.conj() * p.conj(), 1e-15));
        assert_eq!(Quat::ZERO.inverse(), None);
        assert_eq!(Quat::new(f64::NAN, 0.0, 0.0, 0.0).inverse(), None);
        // Tiny and huge quaternions invert without under/overflow of |q|².
        let t = Quat::new(0.0, 1e-200, 0.0, 0.0).inverse().unwrap();
        assert!((t.x + 1e200).abs() < 1e186);
        let h = Quat::new(0.0, 1e200, 1e200, 0.0).inverse().unwrap();
        assert!(h.is_finite() && h != Quat::ZERO);
    }

    #[test]
    fn sqrt_upper_is_sqrt_given_bit_for_bit() {
        // The blends' shortcut must not change a bit: every sign of every part, zero and
        // negative-zero imaginary parts, tiny (scaled-path) and huge components, non-finite.
        let vals = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.37,
            -2.5e-3,
            1e-170,
            -3e-200,
            4e200,
            f64::MIN_POSITIVE / 8.0,
            f64::INFINITY,
            f64::NAN,
        ];
        let same = |a: Option<Quat>, b: Option<Quat>| match (a, b) {
            (None, None) => true,
            (Some(a), Some(b)) => a
                .to_array()
                .iter()
                .zip(b.to_array())
                .all(|(x, y)| x.to_bits() == y.to_bits()),
            _ => false,
        };
        let mut n = 0;
        for &w in &vals {
            for &x in &vals {
                for &y in &vals[..6] {
                    for &z in &vals[..8] {
                        let q = Quat::new(w, x, y, z);
                        let r = q.abs();
                        assert!(same(q.sqrt_upper(r), q.sqrt_given(r, q.abs_im())), "{q:?}");
                        n += 1;
                    }
                }
            }
        }
        assert_eq!(n, 12 * 12 * 6 * 8);
    }

    #[test]
    fn sqrt_is_principal_and_squares_back() {
        let cases = [
            Quat::new(1.0, 2.0, -3.0, 0.5),
            Quat::new(-4.0, 1e-9, 0.0, 0.0),
            Quat::new(-1.0, 0.0, 2.0, 0.0),
            Quat::new(9.0, 0.0, 0.0, 0.0),
            Quat::new(1e-300, 1e-300, 0.0, 0.0),
        ];
        for q in cases {
            let s = q.sqrt().unwrap();
            assert!(s.w >= 0.0, "{s:?}");
            assert!(close(s * s, q, 1e-14), "{q:?} {s:?}");
        }
        assert_eq!(Quat::real(-4.0).sqrt(), None);
        let s = Quat::real(-4.0).sqrt_with_axis([0.0, 0.0, 1.0]).unwrap();
        assert_eq!(s, Quat::new(0.0, 0.0, 0.0, 2.0));
        assert!(close(s * s, Quat::real(-4.0), 0.0));
    }

    #[test]
    fn log_exp_round_trip() {
        for q in [
            Quat::new(1.0, 2.0, -3.0, 0.5),
            Quat::new(-2.0, 0.1, 0.0, 0.0),
            Quat::real(3.0),
        ] {
            let l = q.log().unwrap();
            assert!(close(l.exp(), q, 1e-14), "{q:?}");
        }
        assert_eq!(Quat::real(-1.0).log(), None);
        assert_eq!(Quat::ZERO.log(), None);
    }

    #[test]
    fn polar_form() {
        let q = Quat::new(1.0, 0.0, 1.0, 0.0);
        let (r, th, n) = q.polar();
        assert!((r - crate::sqrt::sqrt(2.0)).abs() < 1e-15);
        assert!((th - core::f64::consts::FRAC_PI_4).abs() < 1e-15);
        assert_eq!(n, Some([0.0, 1.0, 0.0]));
    }
}
