//! The one-solve reconstruction of seed 001 §3.5 step 4, allocation-free on caller scratch.
//!
//! # The system
//!
//! Step 4 asks for the least-squares solution of the stacked system
//! `[4ᵏ L_k ; anchor rows] V = [Δ_k ; anchor values]` through its normal equations
//! `(AᵀA) V = Aᵀb` (DESIGN.md "Differential space"). Divided by `16ᵏ` (an exact power of
//! two) this is
//!
//! ```text
//! (L_kᵀ L_k + w Σ_a e_a e_aᵀ) V = L_kᵀ (4⁻ᵏ Δ_k) + w Σ_a e_a x_a
//! ```
//!
//! with one row `w (v_a − x_a)` per anchor `a`. The anchors only remove the null space of
//! `L_k` (translations of each closed component, of each boundary loop): the `L_k` part of the
//! least-squares objective does not change along that null space, so every anchor row is
//! satisfied exactly at the minimum and the solution does not depend on `w` (we take
//! `w = 1`, the size of the diagonal of `LᵀL`, for conditioning). The matrix is symmetric
//! positive definite; `b` and `x` hold the three coordinates, solved as three systems with one
//! shared matrix–vector product. `LᵀL` is never formed: `A x = Lᵀ(L x) + anchors`.
//!
//! # The solver
//!
//! Flexible preconditioned conjugate gradients (Notay 2000; the Polak–Ribière form of β, which
//! is plain CG for a fixed preconditioner and tolerates the inexact coarse solve below).
//! Preconditioner: for interior rows `L = D⁻¹ K`, `K = D − A` the graph Laplacian, so
//! `LᵀL = K D⁻² K` and `(LᵀL)⁻¹ = K⁻¹ D² K⁻¹`; we apply `M⁻¹ = B D² B` with `B` one multigrid
//! V-cycle for `K + w·anchors` (symmetric, so `M⁻¹` is SPD; on boundary rows `D = 2`, the
//! Eq. (8) weights, and `K` keeps the full ring — an approximation only there). This avoids
//! multigrid on the bi-Laplacian `LᵀL` itself, whose Jacobi smoothing is too weak (its
//! high-frequency half spans a factor 16 of the spectrum, not 4). The V-cycle runs over the
//! subdivision hierarchy itself: level `j` is the mesh after `j` steps, nested in level
//! `j + 1` (old vertices first, then one point per edge), so
//!
//! * prolongation `P` is linear interpolation: an old vertex keeps its value, an edge point
//!   takes the mean of its edge's two ends; restriction is `Pᵀ`;
//! * the coarse operator is the rediscretised graph Laplacian `K_j` plus the same anchor rows
//!   (anchors are old vertices, present at every level); a 2-D graph Laplacian needs no level
//!   scaling (`Pᵀ K_{j+1} P ≈ K_j`);
//! * the smoother is Jacobi damped by 2/3, [`NU`] sweeps before and after the coarse
//!   correction (symmetric);
//! * the coarsest level (the control mesh) is solved by Jacobi-preconditioned CG to a loose
//!   relative tolerance ([`SolveOptions::coarse_tolerance`]) — hence the flexible outer CG.
//!
//! Convergence is declared when `‖b − A x‖_F ≤ tolerance · ‖b‖_F` (Frobenius norm over the
//! three coordinates, so a flat model with `z ≡ 0` does not stall); the reported residual is
//! recomputed from scratch at the end, not the recursively updated one. Every sum runs in a
//! fixed order: the same input gives the same bits.

use arrayvec::ArrayVec;

use super::laplacian::Laplacian;
use crate::error::{Error, Result, Status};
use crate::mesh::{get, internal};
use crate::quat::Point;

/// Most levels of a hierarchy (the input and [`crate::scheme::MAX_LEVELS`] steps).
pub const MAX_HIERARCHY: usize = crate::scheme::MAX_LEVELS + 1;

/// Smoothing sweeps before and after each coarse correction.
const NU: usize = 2;

/// One level of the hierarchy.
#[derive(Clone, Copy, Debug)]
pub struct SolveLevel<'a> {
    /// The level's Laplacian.
    pub lap: Laplacian<'a>,
    /// The level's edges as `(a, b)` pairs in edge-id order (the parents of the next level's
    /// edge points); unused at the finest level.
    pub edges: &'a [u32],
}

/// Options of [`solve`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveOptions {
    /// Relative residual `‖b − A x‖ / ‖b‖` to reach. Default `1e-10`.
    pub tolerance: f64,
    /// Outer iteration cap. Default 200.
    pub max_iterations: u32,
    /// Relative tolerance of the coarsest-level solve inside the preconditioner. Default 1e-10:
    /// a loose coarse solve makes the preconditioner too nonlinear (outer CG stalls; measured).
    pub coarse_tolerance: f64,
    /// Iteration cap of the coarsest-level solve. Default 2000.
    pub coarse_max_iterations: u32,
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            tolerance: 1e-10,
            max_iterations: 200,
            coarse_tolerance: 1e-10,
            coarse_max_iterations: 2000,
        }
    }
}

/// What [`solve`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SolveReport {
    /// Outer iterations run.
    pub iterations: u32,
    /// `‖b − A x‖_F / ‖b‖_F` of the returned `x`, recomputed at the end.
    pub relative_residual: f64,
    /// The same for the warm start.
    pub initial_residual: f64,
    /// Whether `relative_residual ≤ tolerance`.
    pub converged: bool,
}

/// The system `LᵀL + w anchors` at the finest level and the hierarchy of its preconditioner.
#[derive(Clone, Copy, Debug)]
pub struct System<'a> {
    /// Coarsest first; the last level is the one solved.
    pub levels: &'a [SolveLevel<'a>],
    /// Anchored vertices (indices valid at every level).
    pub anchors: &'a [u32],
    /// Weight `w` of the anchor rows.
    pub anchor_weight: f64,
}

/// Points of scratch [`solve`] needs for a hierarchy with the given vertex counts (coarsest
/// first): four vectors per level, three more at the coarsest, five at the finest.
///
/// # Errors
/// [`Status::SizeOverflow`].
pub fn solve_scratch_len(counts: &[usize]) -> Result<usize> {
    let mut s = 0usize;
    for &n in counts {
        s = s.checked_add(n.checked_mul(4).ok_or(ovf())?).ok_or(ovf())?;
    }
    let first = counts.first().copied().unwrap_or(0);
    let last = counts.last().copied().unwrap_or(0);
    s = s
        .checked_add(first.checked_mul(3).ok_or(ovf())?)
        .ok_or(ovf())?;
    s.checked_add(last.checked_mul(5).ok_or(ovf())?)
        .ok_or(ovf())
}

const fn ovf() -> Error {
    Error::new(Status::SizeOverflow)
}

/// Parameters of the coarsest-level solve.
#[derive(Clone, Copy)]
struct Coarse {
    tol: f64,
    max: u32,
}

/// Per-level work vectors of the V-cycle.
struct Work<'a> {
    b: &'a mut [Point],
    x: &'a mut [Point],
    r: &'a mut [Point],
    t: &'a mut [Point],
}

fn take<'a>(s: &mut &'a mut [Point], n: usize) -> Result<&'a mut [Point]> {
    let whole = core::mem::take(s);
    if whole.len() < n {
        return Err(Error::too_small(n));
    }
    let (a, b) = whole.split_at_mut(n);
    *s = b;
    Ok(a)
}

#[inline]
fn dots(a: &[Point], b: &[Point]) -> [f64; 3] {
    let mut s = [0.0; 3];
    for (p, q) in a.iter().zip(b) {
        s = [s[0] + p[0] * q[0], s[1] + p[1] * q[1], s[2] + p[2] * q[2]];
    }
    s
}

#[inline]
fn frob(a: &[Point]) -> f64 {
    let d = dots(a, a);
    libm::sqrt(d[0] + d[1] + d[2])
}

impl System<'_> {
    fn level(&self, j: usize) -> Result<&SolveLevel<'_>> {
        self.levels.get(j).ok_or(internal())
    }

    fn add_anchors(&self, x: &[Point], y: &mut [Point]) -> Result<()> {
        let w = self.anchor_weight;
        for &a in self.anchors {
            let xa = get(x, a as usize)?;
            let ya = y.get_mut(a as usize).ok_or(internal())?;
            *ya = [ya[0] + w * xa[0], ya[1] + w * xa[1], ya[2] + w * xa[2]];
        }
        Ok(())
    }

    /// `y = (LᵀL + w anchors) x` at the finest level (`t` a temporary).
    fn apply(&self, x: &[Point], t: &mut [Point], y: &mut [Point]) -> Result<()> {
        let lv = self.levels.last().ok_or(internal())?;
        let n = lv.lap.len();
        lv.lap.apply(x, 1.0, t)?;
        for yi in y.iter_mut().take(n) {
            *yi = [0.0; 3];
        }
        lv.lap.apply_transpose_add(t, y)?;
        self.add_anchors(x, y)
    }

    /// `y = (K_j + w anchors) x`.
    fn apply_k(&self, j: usize, x: &[Point], y: &mut [Point]) -> Result<()> {
        self.level(j)?.lap.apply_graph(x, y)?;
        self.add_anchors(x, y)
    }

    /// `z (+)= ω D_j⁻¹ r`, `D_j` the diagonal of `K_j + w anchors`; `ω = 2/3` when
    /// smoothing, 1 as the coarse CG's preconditioner.
    fn jacobi(&self, j: usize, r: &[Point], z: &mut [Point], add: bool, omega: f64) -> Result<()> {
        let lap = &self.level(j)?.lap;
        let n = lap.len();
        for (i, zi) in z.iter_mut().enumerate().take(n) {
            let d = lap.degree(i)?;
            let ri = get(r, i)?;
            let q = if d > 0.0 {
                let f = omega / d;
                [f * ri[0], f * ri[1], f * ri[2]]
            } else {
                [0.0; 3]
            };
            *zi = if add {
                [zi[0] + q[0], zi[1] + q[1], zi[2] + q[2]]
            } else {
                q
            };
        }
        let w = self.anchor_weight;
        for &a in self.anchors {
            let i = a as usize;
            let d = lap.degree(i)?;
            let ri = get(r, i)?;
            let f = omega / (d + w);
            let g = if d > 0.0 { omega / d } else { 0.0 };
            let zi = z.get_mut(i).ok_or(internal())?;
            let base = if add {
                [zi[0] - g * ri[0], zi[1] - g * ri[1], zi[2] - g * ri[2]]
            } else {
                [0.0; 3]
            };
            *zi = [
                base[0] + f * ri[0],
                base[1] + f * ri[1],
                base[2] + f * ri[2],
            ];
        }
        Ok(())
    }

    /// One V-cycle for `K` at the last level of `work`: `x ≈ K⁻¹ b`.
    fn vcycle(
        &self,
        work: &mut [Work<'_>],
        coarse: &mut [&mut [Point]; 3],
        c: Coarse,
    ) -> Result<()> {
        let Some((cur, below)) = work.split_last_mut() else {
            return Err(internal());
        };
        let j = below.len();
        let n = self.level(j)?.lap.len();
        if j == 0 {
            return self.coarse_solve(cur, coarse, c);
        }
        const OMEGA: f64 = 2.0 / 3.0;
        self.jacobi(j, cur.b, cur.x, false, OMEGA)?;
        for _ in 1..NU {
            self.residual(j, cur)?;
            self.jacobi(j, cur.r, cur.x, true, OMEGA)?;
        }
        self.residual(j, cur)?;
        let lc = self.level(j - 1)?;
        let nc = lc.lap.len();
        let cw = below.last_mut().ok_or(internal())?;
        for i in 0..nc {
            crate::mesh::set(cw.b, i, get(cur.r, i)?)?;
        }
        for e in 0..(n - nc) {
            let a = get(lc.edges, 2 * e)? as usize;
            let b = get(lc.edges, 2 * e + 1)? as usize;
            let re = get(cur.r, nc + e)?;
            let h = [0.5 * re[0], 0.5 * re[1], 0.5 * re[2]];
            for v in [a, b] {
                let p = cw.b.get_mut(v).ok_or(internal())?;
                *p = [p[0] + h[0], p[1] + h[1], p[2] + h[2]];
            }
        }
        self.vcycle(below, coarse, c)?;
        let cw = below.last().ok_or(internal())?;
        for i in 0..nc {
            let c = get(cw.x, i)?;
            let p = cur.x.get_mut(i).ok_or(internal())?;
            *p = [p[0] + c[0], p[1] + c[1], p[2] + c[2]];
        }
        for e in 0..(n - nc) {
            let a = get(cw.x, get(lc.edges, 2 * e)? as usize)?;
            let b = get(cw.x, get(lc.edges, 2 * e + 1)? as usize)?;
            let p = cur.x.get_mut(nc + e).ok_or(internal())?;
            *p = [
                p[0] + 0.5 * (a[0] + b[0]),
                p[1] + 0.5 * (a[1] + b[1]),
                p[2] + 0.5 * (a[2] + b[2]),
            ];
        }
        for _ in 0..NU {
            self.residual(j, cur)?;
            self.jacobi(j, cur.r, cur.x, true, OMEGA)?;
        }
        Ok(())
    }

    /// `r = b − K x` at level `j`.
    fn residual(&self, j: usize, w: &mut Work<'_>) -> Result<()> {
        self.apply_k(j, w.x, w.r)?;
        for (ri, bi) in w.r.iter_mut().zip(w.b.iter()) {
            *ri = [bi[0] - ri[0], bi[1] - ri[1], bi[2] - ri[2]];
        }
        Ok(())
    }

    /// Jacobi-PCG for `K_0` from `x = 0` to the coarse tolerance.
    fn coarse_solve(&self, w: &mut Work<'_>, v: &mut [&mut [Point]; 3], c: Coarse) -> Result<()> {
        let n = self.level(0)?.lap.len();
        let [p, q, z] = v;
        let (p, q, z) = (
            p.get_mut(..n).ok_or(internal())?,
            q.get_mut(..n).ok_or(internal())?,
            z.get_mut(..n).ok_or(internal())?,
        );
        for (x, (r, b)) in w.x.iter_mut().zip(w.r.iter_mut().zip(w.b.iter())) {
            *x = [0.0; 3];
            *r = *b;
        }
        let b0 = frob(w.b);
        if b0 == 0.0 {
            return Ok(());
        }
        self.jacobi(0, w.r, z, false, 1.0)?;
        p.copy_from_slice(z);
        let mut rz = dots(w.r, z);
        for _ in 0..c.max {
            self.apply_k(0, p, q)?;
            let alpha = ratio(rz, dots(p, q));
            axpy(w.x, alpha, p);
            axpy(w.r, [-alpha[0], -alpha[1], -alpha[2]], q);
            if frob(w.r) <= c.tol * b0 {
                break;
            }
            self.jacobi(0, w.r, z, false, 1.0)?;
            let rz_new = dots(w.r, z);
            let beta = ratio(rz_new, rz);
            rz = rz_new;
            for (pi, zi) in p.iter_mut().zip(z.iter()) {
                *pi = [
                    zi[0] + beta[0] * pi[0],
                    zi[1] + beta[1] * pi[1],
                    zi[2] + beta[2] * pi[2],
                ];
            }
        }
        Ok(())
    }
}

#[inline]
fn ratio(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    let d = |x: f64, y: f64| {
        if y != 0.0 && (x / y).is_finite() {
            x / y
        } else {
            0.0
        }
    };
    [d(a[0], b[0]), d(a[1], b[1]), d(a[2], b[2])]
}

#[inline]
fn axpy(y: &mut [Point], a: [f64; 3], x: &[Point]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi = [
            yi[0] + a[0] * xi[0],
            yi[1] + a[1] * xi[1],
            yi[2] + a[2] * xi[2],
        ];
    }
}

/// Solves `A x = b` (the [module](self)'s system at its finest level) from the warm start in
/// `x`, overwriting it. `scratch` holds at least [`solve_scratch_len`] points.
///
/// Returns the report also when the tolerance was not reached (`converged == false`, `x` the
/// last iterate); the caller decides (the drivers return [`Status::NotConverged`]).
///
/// # Errors
/// [`Status::BufferTooSmall`]; [`Status::InvalidArgument`] for a tolerance that is not a
/// finite non-negative number or an empty hierarchy; [`Status::NumericalFailure`] when an
/// iterate is not finite.
pub fn solve(
    sys: &System<'_>,
    b: &[Point],
    x: &mut [Point],
    scratch: &mut [Point],
    opts: &SolveOptions,
) -> Result<SolveReport> {
    let ok = |t: f64| t.is_finite() && t >= 0.0;
    if !ok(opts.tolerance) || !ok(opts.coarse_tolerance) {
        return Err(Error::new(Status::InvalidArgument));
    }
    if sys.levels.is_empty() {
        return Err(Error::new(Status::InvalidArgument));
    }
    let mut counts = ArrayVec::<usize, MAX_HIERARCHY>::new();
    for lv in sys.levels {
        counts
            .try_push(lv.lap.len())
            .map_err(|_| Error::new(Status::InvalidArgument))?;
    }
    let need = solve_scratch_len(&counts)?;
    if scratch.len() < need {
        return Err(Error::too_small(need));
    }
    let n = counts.last().copied().unwrap_or(0);
    let n0 = counts.first().copied().unwrap_or(0);
    let b = b.get(..n).ok_or(Error::too_small(n))?;
    let x = x.get_mut(..n).ok_or(Error::too_small(n))?;
    let mut rest: &mut [Point] = scratch;
    let mut work = ArrayVec::<Work<'_>, MAX_HIERARCHY>::new();
    for &c in &counts {
        let w = Work {
            b: take(&mut rest, c)?,
            x: take(&mut rest, c)?,
            r: take(&mut rest, c)?,
            t: take(&mut rest, c)?,
        };
        work.try_push(w).map_err(|_| internal())?;
    }
    let mut coarse = [
        take(&mut rest, n0)?,
        take(&mut rest, n0)?,
        take(&mut rest, n0)?,
    ];
    let r = take(&mut rest, n)?;
    let mut z = take(&mut rest, n)?;
    let mut z_old = take(&mut rest, n)?;
    let p = take(&mut rest, n)?;
    let q = take(&mut rest, n)?;
    let c = Coarse {
        tol: opts.coarse_tolerance,
        max: opts.coarse_max_iterations,
    };
    let precondition = |work: &mut ArrayVec<Work<'_>, MAX_HIERARCHY>,
                        coarse: &mut [&mut [Point]; 3],
                        r: &[Point],
                        z: &mut [Point]|
     -> Result<()> {
        let lap = sys.levels.last().ok_or(internal())?.lap;
        let fine = work.last_mut().ok_or(internal())?;
        fine.b.copy_from_slice(r);
        sys.vcycle(work, coarse, c)?;
        let fine = work.last_mut().ok_or(internal())?;
        for (i, (bi, xi)) in fine.b.iter_mut().zip(fine.x.iter()).enumerate() {
            let d = if get(lap.boundary, i)? != 0 {
                2.0
            } else {
                lap.degree(i)?
            };
            let d2 = d * d;
            *bi = [d2 * xi[0], d2 * xi[1], d2 * xi[2]];
        }
        sys.vcycle(work, coarse, c)?;
        let fine = work.last().ok_or(internal())?;
        z.copy_from_slice(fine.x);
        Ok(())
    };
    let bnorm = frob(b);
    let mut report = SolveReport::default();
    // r = b − A x0 (q is the temporary of A).
    sys.apply(x, q, r)?;
    for (ri, bi) in r.iter_mut().zip(b) {
        *ri = [bi[0] - ri[0], bi[1] - ri[1], bi[2] - ri[2]];
    }
    if bnorm == 0.0 {
        for xi in x.iter_mut() {
            *xi = [0.0; 3];
        }
        report.converged = true;
        return Ok(report);
    }
    report.initial_residual = frob(r) / bnorm;
    let mut rel = report.initial_residual;
    if rel > opts.tolerance {
        precondition(&mut work, &mut coarse, r, z)?;
        p.copy_from_slice(z);
        let mut rz = dots(r, z);
        while report.iterations < opts.max_iterations {
            let t = &mut work.last_mut().ok_or(internal())?.t;
            sys.apply(p, t, q)?;
            let alpha = ratio(rz, dots(p, q));
            axpy(x, alpha, p);
            axpy(r, [-alpha[0], -alpha[1], -alpha[2]], q);
            report.iterations += 1;
            rel = frob(r) / bnorm;
            if !rel.is_finite() {
                return Err(Error::new(Status::NumericalFailure));
            }
            if rel <= opts.tolerance {
                break;
            }
            core::mem::swap(&mut z, &mut z_old);
            precondition(&mut work, &mut coarse, r, z)?;
            // Flexible (Polak–Ribière) β = rᵀ(z − z_old) / rz_old.
            let rz_new = dots(r, z);
            let cross = dots(r, z_old);
            let beta = ratio(
                [
                    rz_new[0] - cross[0],
                    rz_new[1] - cross[1],
                    rz_new[2] - cross[2],
                ],
                rz,
            );
            rz = rz_new;
            for (pi, zi) in p.iter_mut().zip(z.iter()) {
                *pi = [
                    zi[0] + beta[0] * pi[0],
                    zi[1] + beta[1] * pi[1],
                    zi[2] + beta[2] * pi[2],
                ];
            }
        }
    }
    // The true residual of the returned x.
    sys.apply(x, q, r)?;
    for (ri, bi) in r.iter_mut().zip(b) {
        *ri = [bi[0] - ri[0], bi[1] - ri[1], bi[2] - ri[2]];
    }
    report.relative_residual = frob(r) / bnorm;
    if !report.relative_residual.is_finite() {
        return Err(Error::new(Status::NumericalFailure));
    }
    report.converged = report.relative_residual <= opts.tolerance;
    Ok(report)
}
