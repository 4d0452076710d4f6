//! The one-solve reconstruction of seed 001 §3.5 step 4, allocation-free on caller scratch.
//!
//! # The system
//!
//! Step 4 asks for the least-squares solution of the stacked system
//! `[4ᵏ L_k ; anchor rows] V = [Δ_k ; anchor values]` through its normal equations
//! `(AᵀA) V = Aᵀb`. Divided by `16ᵏ` (an exact power of two) this is
//!
//! ```text
//! (L_kᵀ L_k + w Σ_a e_a e_aᵀ) V = L_kᵀ δ + w Σ_a e_a x_a,     δ = 4⁻ᵏ Δ_k,
//! ```
//!
//! with one row `w (v_a − x_a)` per anchor `a`. The anchors only remove the null space of
//! `L_k` (one vector per closed component and per boundary loop), so every anchor row is
//! satisfied exactly at the minimum and the solution does not depend on `w` (`w = 1`). This
//! matrix `N` is what the tolerance is measured on: convergence is declared when
//! `‖b − N x‖_F ≤ tolerance · ‖b‖_F` for the system written in coordinates relative to the
//! warm start's centroid (so the test does not depend on where the model sits in space), and
//! the reported residual is recomputed from scratch at the end.
//!
//! # How it is solved: the structure of `L` (decision)
//!
//! CG on `N` itself needs a preconditioner for a fourth-order operator; a multigrid built for
//! `N` with Jacobi smoothing stalls, and `B D² B` (`B` a graph-Laplacian V-cycle) is not
//! spectrally equivalent (iterations grow with the mesh; rocker_arm does not converge, see
//! docs/differential.md). Instead we use what `L` is. Write `L = D⁻¹ G`, `D` the Eq. (2)/(8)
//! degrees, and order the vertices interior first:
//!
//! ```text
//! G = [ K_II  K_IB ]     K = D − A the graph Laplacian of the full rings,
//!     [  0    C_BB ]     C the cycle Laplacian of each boundary loop (Eq. (8)).
//! ```
//!
//! * Boundary rows see only boundary vertices, so each loop is the closed-curve problem
//!   `min ‖½ C x_B − δ_B‖`, whose solutions are `C x_B = 2(δ_B − mean δ_B)`; with the loop's
//!   anchor fixed it is one tridiagonal (path) system, solved exactly (Thomas algorithm).
//! * Given `x_B`, the interior rows of a component with boundary are satisfied *exactly* by
//!   the Dirichlet problem `K_II x_I = D_I δ_I − K_IB x_B` (`K_II` is nonsingular), so the
//!   least-squares residual is the boundary part alone and this `x` is the minimiser.
//! * On a closed component `LᵀL = K D⁻² K` and `Lᵀδ = K D⁻¹ δ`, so the normal equations are
//!   `K (D⁻² K x − D⁻¹ δ) = 0`, i.e. `K x = D δ + c D² 1` with the one `c` that makes the
//!   right-hand side sum to zero (`c = −Σ dᵢδᵢ / Σ dᵢ²`); its anchor is a Dirichlet vertex.
//!
//! What is left is one symmetric positive definite graph-Laplacian (Poisson) problem on the
//! free vertices, with the boundary loops and anchors as Dirichlet values. It is solved by
//! flexible preconditioned CG (Notay 2000, Polak–Ribière `β`, plain CG for a fixed
//! preconditioner) with one multigrid V-cycle over the subdivision hierarchy as the
//! preconditioner:
//!
//! * level `j` is the mesh after `j` steps, nested in level `j + 1` (old vertices first, then
//!   one point per edge). The uniform graph Laplacian is `√3 ×` the P1 finite-element
//!   stiffness of the surface made of equilateral triangles, which midpoint refinement leaves
//!   unchanged, so with linear interpolation `P` (an edge point takes the mean of its ends)
//!   and restriction `Pᵀ`, the rediscretised `K_j` *is* the Galerkin operator `Pᵀ K_{j+1} P`
//!   on the free vertices (Dirichlet vertices are nested too: boundary stays boundary,
//!   anchors are old vertices);
//! * smoother: `NU` Gauss–Seidel sweeps, forward before and backward after the coarse
//!   correction (a symmetric cycle);
//! * the coarsest level (the control mesh) is solved by Jacobi-preconditioned CG to
//!   [`SolveOptions::coarse_tolerance`] — inexact, hence the flexible outer CG.
//!
//! The outer iteration stops on the residual of `N` above (computed every iteration, two
//! sparse products), not on the Poisson residual. Every sum runs in a fixed order: the same
//! input gives the same bits.
//!
//! # Files
//!
//! This file holds the system, the outer iteration ([`solve`]) and its steps;
//! `multigrid.rs` the operator `K̃`, its Gauss–Seidel smoother, the V-cycle and the coarse
//! solve; `boundary_loop.rs` the exact solve of a boundary loop; `vectors.rs` the
//! coordinate-wise vector arithmetic (the three coordinates are three independent systems
//! sharing one matrix, so every scalar of CG is a triple).

mod boundary_loop;
mod multigrid;
mod vectors;

use arrayvec::ArrayVec;

use super::laplacian::Laplacian;
use crate::error::{Error, Result, Status};
use crate::exec::{pass, Executor, Serial};
use crate::mesh::{get, internal};
use crate::point::{add, scale, sub, Point};
use boundary_loop::solve_loop;
use multigrid::{apply_k, Coarse, Work};
use vectors::{axpy_with, copy, dots, frob, ratio, xpby_with};

/// Most levels of a hierarchy (the input and [`crate::scheme::MAX_LEVELS`] steps).
pub const MAX_HIERARCHY: usize = crate::scheme::MAX_LEVELS + 1;

/// One level of the hierarchy.
#[derive(Clone, Copy, Debug)]
pub struct SolveLevel<'a> {
    /// The level's Laplacian; its flags mark the Dirichlet vertices
    /// ([`Laplacian::is_fixed`]).
    pub lap: Laplacian<'a>,
    /// The level's edges as `(a, b)` pairs in edge-id order (the parents of the next level's
    /// edge points); unused at the finest level.
    pub edges: &'a [u32],
}

/// Options of [`solve`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveOptions {
    /// Relative residual `‖b − N x‖ / ‖b‖` to reach (module docs). Default `1e-10`.
    pub tolerance: f64,
    /// Outer iteration cap. Default 100.
    pub max_iterations: u32,
    /// Relative tolerance of the coarsest-level solve inside the preconditioner. Default 1e-3.
    pub coarse_tolerance: f64,
    /// Iteration cap of the coarsest-level solve. Default 2000.
    pub coarse_max_iterations: u32,
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            tolerance: 1e-10,
            max_iterations: 100,
            coarse_tolerance: 1e-3,
            coarse_max_iterations: 2000,
        }
    }
}

/// What [`solve`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SolveReport {
    /// Outer iterations run.
    pub iterations: u32,
    /// `‖b − N x‖_F / ‖b‖_F` of the returned `x`, recomputed at the end.
    pub relative_residual: f64,
    /// The same for the warm start.
    pub initial_residual: f64,
    /// Whether `relative_residual ≤ tolerance`.
    pub converged: bool,
}

/// The system at the finest level and the hierarchy of its preconditioner.
#[derive(Clone, Copy, Debug)]
pub struct System<'a> {
    /// Coarsest first; the last level is the one solved.
    pub levels: &'a [SolveLevel<'a>],
    /// Anchored vertices (indices valid at every level); the first
    /// [`System::loop_anchors`] are one vertex of each boundary loop.
    pub anchors: &'a [u32],
    /// How many leading anchors are boundary-loop anchors.
    pub loop_anchors: usize,
    /// Weight `w` of the anchor rows.
    pub anchor_weight: f64,
    /// Per finest-level vertex, its connected component (a control-vertex index).
    pub components: &'a [u32],
    /// Per control-vertex index used in `components`: non-zero when that component has a
    /// boundary (its interior problem is then nonsingular without a compatibility constant).
    pub open: &'a [u32],
}

/// Points of scratch [`solve`] needs for a hierarchy with the given vertex counts (coarsest
/// first): four vectors per level, three more at the coarsest, six at the finest.
///
/// # Errors
/// [`Status::SizeOverflow`].
pub fn solve_scratch_size(counts: &[usize]) -> Result<usize> {
    let mut s = 0usize;
    for &n in counts {
        s = s.checked_add(n.checked_mul(4).ok_or(ovf())?).ok_or(ovf())?;
    }
    let first = counts.first().copied().unwrap_or(0);
    let last = counts.last().copied().unwrap_or(0);
    s = s
        .checked_add(first.checked_mul(3).ok_or(ovf())?)
        .ok_or(ovf())?;
    s.checked_add(last.checked_mul(6).ok_or(ovf())?)
        .ok_or(ovf())
}

const fn ovf() -> Error {
    Error::new(Status::SizeOverflow)
}

/// The first `n` entries of `*s`, leaving the rest in `*s`.
fn take<'a>(s: &mut &'a mut [Point], n: usize) -> Result<&'a mut [Point]> {
    let whole = core::mem::take(s);
    if whole.len() < n {
        return Err(Error::too_small(n));
    }
    let (a, b) = whole.split_at_mut_checked(n).ok_or(Error::too_small(n))?;
    *s = b;
    Ok(a)
}

impl System<'_> {
    /// `y = N x = (LᵀL + w anchors) x` at the finest level (`t` a temporary).
    fn apply_normal(
        &self,
        x: &[Point],
        t: &mut [Point],
        y: &mut [Point],
        exec: &dyn Executor,
    ) -> Result<()> {
        let lv = self.levels.last().ok_or(internal())?;
        let n = lv.lap.len();
        lv.lap.apply_with(x, 1.0, t, exec)?;
        for yi in y.iter_mut().take(n) {
            *yi = [0.0; 3];
        }
        lv.lap.apply_transpose_add(t, y)?;
        let w = self.anchor_weight;
        for &a in self.anchors {
            let xa = get(x, a as usize)?;
            let ya = y.get_mut(a as usize).ok_or(internal())?;
            *ya = add(*ya, scale(xa, w));
        }
        Ok(())
    }

    /// `‖b − N x‖_F` (`t`, `y` temporaries).
    fn normal_residual(
        &self,
        b: &[Point],
        x: &[Point],
        t: &mut [Point],
        y: &mut [Point],
        exec: &dyn Executor,
    ) -> Result<f64> {
        self.apply_normal(x, t, y, exec)?;
        let mut s = [0.0; 3];
        for (yi, bi) in y.iter().zip(b) {
            let d = sub(*bi, *yi);
            s = [s[0] + d[0] * d[0], s[1] + d[1] * d[1], s[2] + d[2] * d[2]];
        }
        Ok(crate::sqrt::sqrt(s[0] + s[1] + s[2]))
    }
}

/// Solves the [module](self)'s system at its finest level from the warm start in `x`,
/// overwriting it; `delta` is `4⁻ᵏ Δ_k`. `scratch` holds at least [`solve_scratch_size`]
/// points. The anchors keep their warm-start values (they are the anchor values).
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
    delta: &[Point],
    x: &mut [Point],
    scratch: &mut [Point],
    opts: &SolveOptions,
) -> Result<SolveReport> {
    solve_with(sys, delta, x, scratch, opts, &Serial)
}

/// [`solve`] with the row-wise sparse products (`K̃ x` at every level, `L x`, the residuals,
/// the prolongation) and the vector updates split into disjoint row ranges run by `exec`
/// ([`crate::exec`]). Every row is computed as in [`solve`]; the reductions (inner products,
/// norms), the Gauss–Seidel sweeps, the restriction and `Lᵀ t` (scatters) stay serial. The
/// result and the report are those of [`solve`], bit for bit, for every executor and
/// chunking.
///
/// # Errors
/// Those of [`solve`].
pub fn solve_with(
    sys: &System<'_>,
    delta: &[Point],
    x: &mut [Point],
    scratch: &mut [Point],
    opts: &SolveOptions,
    exec: &dyn Executor,
) -> Result<SolveReport> {
    let counts = hierarchy_counts(sys, opts, scratch.len())?;
    let n = counts.last().copied().unwrap_or(0);
    let delta = delta.get(..n).ok_or(Error::too_small(n))?;
    let x = x.get_mut(..n).ok_or(Error::too_small(n))?;
    let fine = sys.levels.last().ok_or(internal())?.lap;
    let mut b = Buffers::carve(scratch, &counts)?;
    let c = Coarse {
        tol: opts.coarse_tolerance,
        max: opts.coarse_max_iterations,
    };

    // Centre (translation-free residual test, smaller rounding in the differences).
    let centre = subtract_centroid(x);
    sys.normal_rhs(&fine, delta, x, b.bne)?;
    let bnorm = frob(b.bne);
    let mut report = SolveReport::default();
    if bnorm == 0.0 {
        for xi in x.iter_mut() {
            *xi = centre;
        }
        report.converged = true;
        return Ok(report);
    }
    {
        let fw = b.work.last_mut().ok_or(internal())?;
        report.initial_residual = sys.normal_residual(b.bne, x, fw.t, fw.b, exec)? / bnorm;
    }

    // Boundary loops: exact.
    for &a in sys.anchors.get(..sys.loop_anchors).ok_or(internal())? {
        solve_loop(&fine, a, delta, x, b.z, b.z_old)?;
    }
    sys.poisson_residual(&fine, delta, x, &mut b.coarse, b.r, exec)?;
    let rel = {
        let fw = b.work.last_mut().ok_or(internal())?;
        sys.normal_residual(b.bne, x, fw.t, fw.b, exec)? / bnorm
    };
    if rel > opts.tolerance {
        report.iterations = sys.flexible_pcg(&fine, &mut b, x, c, bnorm, opts, exec)?;
    }
    let fw = b.work.last_mut().ok_or(internal())?;
    report.relative_residual = sys.normal_residual(b.bne, x, fw.t, fw.b, exec)? / bnorm;
    if !report.relative_residual.is_finite() {
        return Err(Error::new(Status::NumericalFailure));
    }
    report.converged = report.relative_residual <= opts.tolerance;
    for p in x.iter_mut() {
        *p = add(*p, centre);
    }
    Ok(report)
}

/// Checks the options and the scratch size; the vertex counts of the hierarchy, coarsest
/// first.
fn hierarchy_counts(
    sys: &System<'_>,
    opts: &SolveOptions,
    scratch_size: usize,
) -> Result<ArrayVec<usize, MAX_HIERARCHY>> {
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
    let need = solve_scratch_size(&counts)?;
    if scratch_size < need {
        return Err(Error::too_small(need));
    }
    Ok(counts)
}

/// The scratch of [`solve`], carved in the order of [`solve_scratch_size`].
struct Buffers<'a> {
    /// The V-cycle's vectors, one set per level, coarsest first.
    work: ArrayVec<Work<'a>, MAX_HIERARCHY>,
    /// The coarse solve's three CG vectors (first the compatibility sums).
    coarse: [&'a mut [Point]; 3],
    /// The outer iteration's residual `r = f − K̃ x` of the Poisson problem.
    r: &'a mut [Point],
    /// The preconditioned residual, and the previous one (flexible CG).
    z: &'a mut [Point],
    z_old: &'a mut [Point],
    /// The search direction and `K̃ p`.
    p: &'a mut [Point],
    q: &'a mut [Point],
    /// The right-hand side `Lᵀδ + w x_a` of the normal equations.
    bne: &'a mut [Point],
}

impl<'a> Buffers<'a> {
    fn carve(scratch: &'a mut [Point], counts: &[usize]) -> Result<Buffers<'a>> {
        let n = counts.last().copied().unwrap_or(0);
        let n0 = counts.first().copied().unwrap_or(0);
        let mut rest: &mut [Point] = scratch;
        let mut work = ArrayVec::<Work<'_>, MAX_HIERARCHY>::new();
        for &c in counts {
            let w = Work {
                b: take(&mut rest, c)?,
                x: take(&mut rest, c)?,
                r: take(&mut rest, c)?,
                t: take(&mut rest, c)?,
            };
            work.try_push(w).map_err(|_| internal())?;
        }
        let coarse = [
            take(&mut rest, n0)?,
            take(&mut rest, n0)?,
            take(&mut rest, n0)?,
        ];
        Ok(Buffers {
            work,
            coarse,
            r: take(&mut rest, n)?,
            z: take(&mut rest, n)?,
            z_old: take(&mut rest, n)?,
            p: take(&mut rest, n)?,
            q: take(&mut rest, n)?,
            bne: take(&mut rest, n)?,
        })
    }
}

/// Subtracts the centroid of `x` from every point and returns it.
fn subtract_centroid(x: &mut [Point]) -> Point {
    let n = x.len();
    let mut centre = [0.0; 3];
    for p in x.iter() {
        centre = add(centre, *p);
    }
    if n > 0 {
        centre = scale(centre, 1.0 / n as f64);
    }
    for p in x.iter_mut() {
        *p = sub(*p, centre);
    }
    centre
}

impl System<'_> {
    /// `bne = Lᵀδ + w x_a`, the right-hand side of the normal equations.
    fn normal_rhs(
        &self,
        fine: &Laplacian<'_>,
        delta: &[Point],
        x: &[Point],
        bne: &mut [Point],
    ) -> Result<()> {
        for bi in bne.iter_mut() {
            *bi = [0.0; 3];
        }
        fine.apply_transpose_add(delta, bne)?;
        for &a in self.anchors {
            let xa = get(x, a as usize)?;
            let ba = bne.get_mut(a as usize).ok_or(internal())?;
            *ba = add(*ba, scale(xa, self.anchor_weight));
        }
        Ok(())
    }

    /// The residual `r = f − K x` of the Poisson problem on free rows (0 on fixed rows), with
    /// `f = Dδ`, and on closed components `f = Dδ + c D² 1` with the compatibility constant
    /// `c = −Σ dᵢδᵢ / Σ dᵢ²` (module docs; its sums per component in `coarse[0]`,
    /// `coarse[1][·][0]`).
    fn poisson_residual(
        &self,
        fine: &Laplacian<'_>,
        delta: &[Point],
        x: &[Point],
        coarse: &mut [&mut [Point]; 3],
        r: &mut [Point],
        exec: &dyn Executor,
    ) -> Result<()> {
        let n = x.len();
        let [sd, sdd, _] = coarse;
        for (a, b) in sd.iter_mut().zip(sdd.iter_mut()) {
            *a = [0.0; 3];
            *b = [0.0; 3];
        }
        for i in 0..n {
            let l = get(self.components, i)? as usize;
            if get(self.open, l)? != 0 {
                continue;
            }
            let d = fine.degree(i)?;
            let s = sd.get_mut(l).ok_or(internal())?;
            *s = add(*s, scale(get(delta, i)?, d));
            sdd.get_mut(l).ok_or(internal())?[0] += d * d;
        }
        let (sd, sdd) = (&**sd, &**sdd);
        pass(exec, r, |start, out, _| {
            for (k, ri) in out.iter_mut().enumerate() {
                let i = start + k;
                if fine.is_fixed(i)? {
                    *ri = [0.0; 3];
                    continue;
                }
                let d = fine.degree(i)?;
                let mut f = scale(get(delta, i)?, d);
                let l = get(self.components, i)? as usize;
                if get(self.open, l)? == 0 {
                    let den = get(sdd, l)?[0];
                    if den > 0.0 {
                        f = sub(f, scale(get(sd, l)?, d * d / den));
                    }
                }
                let mut s = [0.0; 3];
                for &j in fine.ring(i)? {
                    s = add(s, get(x, j as usize)?);
                }
                *ri = add(f, sub(s, scale(get(x, i)?, d)));
            }
            Ok(())
        })?;
        Ok(())
    }

    /// `z ≈ K̃⁻¹ r` by one V-cycle.
    fn precondition(
        &self,
        work: &mut ArrayVec<Work<'_>, MAX_HIERARCHY>,
        coarse: &mut [&mut [Point]; 3],
        c: Coarse,
        r: &[Point],
        z: &mut [Point],
        exec: &dyn Executor,
    ) -> Result<()> {
        let fw = work.last_mut().ok_or(internal())?;
        copy(fw.b, r);
        self.vcycle(work, coarse, c, exec)?;
        let fw = work.last().ok_or(internal())?;
        copy(z, fw.x);
        Ok(())
    }

    /// Flexible preconditioned CG (Notay 2000, Polak–Ribière `β`) on the Poisson problem from
    /// `x` and its residual `b.r`, stopped on the relative residual of the normal equations
    /// (norm of their right-hand side `bnorm`) or at `opts.max_iterations`. Returns the
    /// iterations run.
    ///
    /// # Errors
    /// [`Status::NumericalFailure`] when the residual is not finite.
    #[allow(clippy::too_many_arguments)]
    fn flexible_pcg(
        &self,
        fine: &Laplacian<'_>,
        b: &mut Buffers<'_>,
        x: &mut [Point],
        c: Coarse,
        bnorm: f64,
        opts: &SolveOptions,
        exec: &dyn Executor,
    ) -> Result<u32> {
        let mut iterations = 0;
        self.precondition(&mut b.work, &mut b.coarse, c, b.r, b.z, exec)?;
        copy(b.p, b.z);
        let mut rz = dots(b.r, b.z);
        while iterations < opts.max_iterations {
            apply_k(fine, b.p, b.q, exec)?;
            let alpha = ratio(rz, dots(b.p, b.q));
            axpy_with(x, alpha, b.p, exec)?;
            axpy_with(b.r, [-alpha[0], -alpha[1], -alpha[2]], b.q, exec)?;
            iterations += 1;
            let fw = b.work.last_mut().ok_or(internal())?;
            let rel = self.normal_residual(b.bne, x, fw.t, fw.b, exec)? / bnorm;
            if !rel.is_finite() {
                return Err(Error::new(Status::NumericalFailure));
            }
            if rel <= opts.tolerance {
                break;
            }
            core::mem::swap(&mut b.z, &mut b.z_old);
            self.precondition(&mut b.work, &mut b.coarse, c, b.r, b.z, exec)?;
            // Flexible (Polak–Ribière) β = rᵀ(z − z_old) / rz_old.
            let rz_new = dots(b.r, b.z);
            let cross = dots(b.r, b.z_old);
            let beta = ratio(sub(rz_new, cross), rz);
            rz = rz_new;
            xpby_with(b.p, b.z, beta, exec)?;
        }
        Ok(iterations)
    }
}
