//! Coordinate-wise vector arithmetic on arrays of points for the solver: the x, y and z
//! coordinates are three independent linear systems with one matrix, so inner products, step
//! lengths and CG coefficients are triples, each summed in a fixed order (deterministic bits).

use crate::error::Result;
use crate::exec::{pass, Executor};
use crate::mesh::internal;
use crate::point::Point;

/// `dst = src` element-wise over the common length (no length-mismatch panic path).
#[inline]
pub(super) fn copy(dst: &mut [Point], src: &[Point]) {
    for (d, s) in dst.iter_mut().zip(src) {
        *d = *s;
    }
}

/// The coordinate-wise inner products `(Σ aᵢ·x bᵢ·x, Σ aᵢ·y bᵢ·y, Σ aᵢ·z bᵢ·z)`.
#[inline]
pub(super) fn dots(a: &[Point], b: &[Point]) -> [f64; 3] {
    let mut s = [0.0; 3];
    for (p, q) in a.iter().zip(b) {
        s = [s[0] + p[0] * q[0], s[1] + p[1] * q[1], s[2] + p[2] * q[2]];
    }
    s
}

/// The Frobenius norm `‖a‖_F` (all three coordinates).
#[inline]
pub(super) fn frob(a: &[Point]) -> f64 {
    let d = dots(a, a);
    crate::sqrt::sqrt(d[0] + d[1] + d[2])
}

/// `a / b` per coordinate, 0 where the quotient is not finite (a breakdown of CG on one
/// coordinate stops that coordinate instead of spreading a NaN).
#[inline]
pub(super) fn ratio(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    let d = |x: f64, y: f64| {
        if y != 0.0 && (x / y).is_finite() {
            x / y
        } else {
            0.0
        }
    };
    [d(a[0], b[0]), d(a[1], b[1]), d(a[2], b[2])]
}

/// `y = y + a x` per coordinate.
#[inline]
pub(super) fn axpy(y: &mut [Point], a: [f64; 3], x: &[Point]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi = [
            yi[0] + a[0] * xi[0],
            yi[1] + a[1] * xi[1],
            yi[2] + a[2] * xi[2],
        ];
    }
}

/// `p = z + β p`.
#[inline]
pub(super) fn xpby(p: &mut [Point], z: &[Point], beta: [f64; 3]) {
    for (pi, zi) in p.iter_mut().zip(z) {
        *pi = [
            zi[0] + beta[0] * pi[0],
            zi[1] + beta[1] * pi[1],
            zi[2] + beta[2] * pi[2],
        ];
    }
}

/// [`axpy`] with the entries split into disjoint ranges run by `exec` (the same bits).
pub(super) fn axpy_with(
    y: &mut [Point],
    a: [f64; 3],
    x: &[Point],
    exec: &dyn Executor,
) -> Result<()> {
    let n = y.len().min(x.len());
    let y = y.get_mut(..n).ok_or(internal())?;
    pass(exec, y, |start, out, _| {
        let xs = x.get(start..start + out.len()).ok_or(internal())?;
        axpy(out, a, xs);
        Ok(())
    })?;
    Ok(())
}

/// [`xpby`] with the entries split into disjoint ranges run by `exec` (the same bits).
pub(super) fn xpby_with(
    p: &mut [Point],
    z: &[Point],
    beta: [f64; 3],
    exec: &dyn Executor,
) -> Result<()> {
    let n = p.len().min(z.len());
    let p = p.get_mut(..n).ok_or(internal())?;
    pass(exec, p, |start, out, _| {
        let zs = z.get(start..start + out.len()).ok_or(internal())?;
        xpby(out, zs, beta);
        Ok(())
    })?;
    Ok(())
}
