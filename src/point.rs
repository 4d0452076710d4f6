//! Points of R³ and their arithmetic: the one place every layer takes its vector operations
//! from.
//!
//! A point is a plain `[f64; 3]`, the layout of a C `double[3]`, so caller buffers are read and
//! written in place (no conversion at the C ABI, no alignment beyond `f64`'s). The operations
//! are written out component by component in plain IEEE arithmetic, without fused
//! multiply-add, in a fixed order, so their results are the same bits on every platform and
//! at every optimisation level. Argument order is always *points first, scalars last*
//! (`scale(a, s)`), and every function is a free function so that a rule reads like its
//! formula in the paper.

/// A point (or vector) of R³.
pub type Point = [f64; 3];

/// Below this squared length [`norm`] scales before squaring (far above the subnormal range,
/// so no precision is lost on the fast path).
pub(crate) const NORM_SAFE_MIN: f64 = 1e-250;

/// `a + b`.
#[inline]
pub fn add(a: Point, b: Point) -> Point {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a − b`.
#[inline]
pub fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `s · a` (each component multiplied, `a[i] · s`).
#[inline]
pub fn scale(a: Point, s: f64) -> Point {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// `a / s`, each component divided (not multiplied by `1/s`, which differs in the last bit and
/// overflows for subnormal `s`).
#[inline]
pub fn div(a: Point, s: f64) -> Point {
    [a[0] / s, a[1] / s, a[2] / s]
}

/// `wa · a + wb · b`.
#[inline]
pub fn lin2(wa: f64, a: Point, wb: f64, b: Point) -> Point {
    add(scale(a, wa), scale(b, wb))
}

/// The sum of `points`, left to right (zero for an empty slice).
pub fn sum(points: &[Point]) -> Point {
    points.iter().fold([0.0; 3], |acc, &p| add(acc, p))
}

/// The midpoint `(a + b) / 2`, as `(a + b) · 0.5`.
#[inline]
pub fn midpoint(a: Point, b: Point) -> Point {
    scale(add(a, b), 0.5)
}

/// The dot product `a₀b₀ + a₁b₁ + a₂b₂`, summed left to right.
#[inline]
pub fn dot(a: Point, b: Point) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The cross product `a × b`.
#[inline]
pub fn cross(a: Point, b: Point) -> Point {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `|a| = √(a·a)` without the guard of [`norm`]: overflows above ~1e154 and loses precision
/// below ~1e-154. For rules whose inputs are known to be in range (normals, unit vectors).
#[inline]
pub fn norm_unscaled(a: Point) -> f64 {
    crate::sqrt::sqrt(dot(a, a))
}

/// `|a|`, computed without overflow or underflow of the squares: `√(a·a)` while the sum of
/// squares is finite and above `NORM_SAFE_MIN` (1e-250), otherwise scaled by the largest
/// component first. The same bits as the absolute value of the imaginary quaternion `[0, a]`
/// (`Quat::abs`), which the Möbius rules compare with.
#[inline]
pub fn norm(a: Point) -> f64 {
    let n = dot(a, a);
    if n.is_finite() && n > NORM_SAFE_MIN {
        return crate::sqrt::sqrt(n);
    }
    norm_scaled(a)
}

/// [`norm`] outside its fast path, out of line (the fast path is inlined in hot loops).
#[cold]
#[inline(never)]
fn norm_scaled(a: Point) -> f64 {
    // The maximum starts from the zero real part of `[0, a]` so that the result is that of
    // `Quat::abs` bit for bit, NaN components included (`f64::max` ignores a NaN).
    let m = 0.0f64.max(a[0].abs()).max(a[1].abs()).max(a[2].abs());
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    // Divide (rather than multiply by 1/m, which overflows for subnormal m).
    let s = div(a, m);
    m * crate::sqrt::sqrt(dot(s, s))
}

/// The distance `|a − b|` ([`norm`] of the difference).
#[inline]
pub fn distance(a: Point, b: Point) -> f64 {
    norm(sub(a, b))
}

/// Whether every coordinate of `p` is finite.
#[inline]
pub fn is_finite(p: &Point) -> bool {
    p.iter().all(|c| c.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quat::Quat;

    #[test]
    fn norm_is_the_quaternion_absolute_value_bit_for_bit() {
        // Fast path, both scaled ranges, zeros, infinities and NaN components.
        let values = [
            0.0,
            -0.0,
            1.0,
            -3.5,
            1e-300,
            1e-170,
            1e-126,
            1e150,
            1e160,
            1e300,
            5e-324,
            f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        for &x in &values {
            for &y in &values {
                for &z in &values {
                    let p = [x, y, z];
                    let a = norm(p);
                    let b = Quat::from_point(p).abs();
                    assert!(
                        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                        "{p:?}: {a:e} vs {b:e}"
                    );
                }
            }
        }
    }

    #[test]
    fn norm_does_not_overflow_or_underflow() {
        let big = norm([3e200, 4e200, 0.0]);
        let small = norm([3e-200, 4e-200, 0.0]);
        assert!((big / 5e200 - 1.0).abs() < 1e-15, "{big:e}");
        assert!((small / 5e-200 - 1.0).abs() < 1e-15, "{small:e}");
        assert!(norm_unscaled([3e200, 4e200, 0.0]).is_infinite());
    }

    #[test]
    fn cross_and_dot_of_the_standard_basis() {
        let (x, y, z) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        assert_eq!(cross(x, y), z);
        assert_eq!(cross(y, z), x);
        assert_eq!(cross(z, x), y);
        assert_eq!(dot(add(x, y), sub(y, z)), 1.0);
        assert_eq!(div([1.0, 2.0, 3.0], 2.0), scale([1.0, 2.0, 3.0], 0.5));
    }
}
