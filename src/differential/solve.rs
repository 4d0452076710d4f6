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
//! `N` with Jacobi smoothing stalled, and `B D² B` (`B` a graph-Laplacian V-cycle) was not
//! spectrally equivalent (iterations grew with the mesh; rocker_arm did not converge, see
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

use arrayvec::ArrayVec;

use super::laplacian::Laplacian;
use crate::error::{Error, Result, Status};
use crate::mesh::{get, internal, set};
use crate::point::{add, scale, sub, Point};

/// Most levels of a hierarchy (the input and [`crate::scheme::MAX_LEVELS`] steps).
pub const MAX_HIERARCHY: usize = crate::scheme::MAX_LEVELS + 1;

/// Gauss–Seidel sweeps before and after each coarse correction.
const NU: usize = 1;

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
    s.checked_add(last.checked_mul(6).ok_or(ovf())?)
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
    let (a, b) = whole.split_at_mut_checked(n).ok_or(Error::too_small(n))?;
    *s = b;
    Ok(a)
}

/// `dst = src` element-wise over the common length (no length-mismatch panic path).
#[inline]
fn copy(dst: &mut [Point], src: &[Point]) {
    for (d, s) in dst.iter_mut().zip(src) {
        *d = *s;
    }
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

/// `y = K̃ x` at one level: `(K x)_i = dᵢ xᵢ − Σ_ring x_j` on free rows, 0 on fixed rows.
fn apply_k(lap: &Laplacian<'_>, x: &[Point], y: &mut [Point]) -> Result<()> {
    for (i, yi) in y.iter_mut().enumerate().take(lap.len()) {
        if lap.is_fixed(i)? {
            *yi = [0.0; 3];
            continue;
        }
        let r = lap.ring(i)?;
        let mut s = [0.0; 3];
        for &j in r {
            s = add(s, get(x, j as usize)?);
        }
        *yi = sub(scale(get(x, i)?, r.len() as f64), s);
    }
    Ok(())
}

/// `r = b − K̃ x` (0 on fixed rows).
fn residual(lap: &Laplacian<'_>, w: &mut Work<'_>) -> Result<()> {
    apply_k(lap, w.x, w.r)?;
    for (ri, bi) in w.r.iter_mut().zip(w.b.iter()) {
        *ri = sub(*bi, *ri);
    }
    Ok(())
}

/// One Gauss–Seidel sweep for `K̃ x = b`, forward or backward (fixed entries stay 0).
fn gauss_seidel(lap: &Laplacian<'_>, b: &[Point], x: &mut [Point], forward: bool) -> Result<()> {
    let n = lap.len();
    for s in 0..n {
        let i = if forward { s } else { n - 1 - s };
        if lap.is_fixed(i)? {
            continue;
        }
        let r = lap.ring(i)?;
        let mut acc = get(b, i)?;
        for &j in r {
            acc = add(acc, get(x, j as usize)?);
        }
        set(x, i, scale(acc, 1.0 / r.len() as f64))?;
    }
    Ok(())
}

/// `z = D⁻¹ r` on free rows, 0 on fixed rows.
fn jacobi(lap: &Laplacian<'_>, r: &[Point], z: &mut [Point]) -> Result<()> {
    for (i, zi) in z.iter_mut().enumerate().take(lap.len()) {
        *zi = if lap.is_fixed(i)? {
            [0.0; 3]
        } else {
            scale(get(r, i)?, 1.0 / lap.degree(i)?)
        };
    }
    Ok(())
}

impl System<'_> {
    fn level(&self, j: usize) -> Result<&SolveLevel<'_>> {
        self.levels.get(j).ok_or(internal())
    }

    /// `y = N x = (LᵀL + w anchors) x` at the finest level (`t` a temporary).
    fn apply_normal(&self, x: &[Point], t: &mut [Point], y: &mut [Point]) -> Result<()> {
        let lv = self.levels.last().ok_or(internal())?;
        let n = lv.lap.len();
        lv.lap.apply(x, 1.0, t)?;
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
    ) -> Result<f64> {
        self.apply_normal(x, t, y)?;
        let mut s = [0.0; 3];
        for (yi, bi) in y.iter().zip(b) {
            let d = sub(*bi, *yi);
            s = [s[0] + d[0] * d[0], s[1] + d[1] * d[1], s[2] + d[2] * d[2]];
        }
        Ok(libm::sqrt(s[0] + s[1] + s[2]))
    }

    /// One V-cycle for `K̃` at the last level of `work`: `x ≈ K̃⁻¹ b`.
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
        let lap = self.level(j)?.lap;
        if j == 0 {
            return coarse_solve(&lap, cur, coarse, c);
        }
        let n = lap.len();
        for xi in cur.x.iter_mut() {
            *xi = [0.0; 3];
        }
        for _ in 0..NU {
            gauss_seidel(&lap, cur.b, cur.x, true)?;
        }
        residual(&lap, cur)?;
        let lc = self.level(j - 1)?;
        let nc = lc.lap.len();
        let cw = below.last_mut().ok_or(internal())?;
        for i in 0..nc {
            set(cw.b, i, get(cur.r, i)?)?;
        }
        for e in 0..(n - nc) {
            let a = get(lc.edges, 2 * e)? as usize;
            let b = get(lc.edges, 2 * e + 1)? as usize;
            let h = scale(get(cur.r, nc + e)?, 0.5);
            for v in [a, b] {
                let p = cw.b.get_mut(v).ok_or(internal())?;
                *p = add(*p, h);
            }
        }
        for i in 0..nc {
            if lc.lap.is_fixed(i)? {
                set(cw.b, i, [0.0; 3])?;
            }
        }
        self.vcycle(below, coarse, c)?;
        let cw = below.last().ok_or(internal())?;
        for i in 0..nc {
            let p = cur.x.get_mut(i).ok_or(internal())?;
            *p = add(*p, get(cw.x, i)?);
        }
        for e in 0..(n - nc) {
            let a = get(cw.x, get(lc.edges, 2 * e)? as usize)?;
            let b = get(cw.x, get(lc.edges, 2 * e + 1)? as usize)?;
            let p = cur.x.get_mut(nc + e).ok_or(internal())?;
            *p = add(*p, scale(add(a, b), 0.5));
        }
        for _ in 0..NU {
            gauss_seidel(&lap, cur.b, cur.x, false)?;
        }
        Ok(())
    }
}

/// Jacobi-PCG for `K̃₀` from `x = 0` to the coarse tolerance.
fn coarse_solve(
    lap: &Laplacian<'_>,
    w: &mut Work<'_>,
    v: &mut [&mut [Point]; 3],
    c: Coarse,
) -> Result<()> {
    let n = lap.len();
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
    jacobi(lap, w.r, z)?;
    copy(p, z);
    let mut rz = dots(w.r, z);
    for _ in 0..c.max {
        apply_k(lap, p, q)?;
        let alpha = ratio(rz, dots(p, q));
        axpy(w.x, alpha, p);
        axpy(w.r, [-alpha[0], -alpha[1], -alpha[2]], q);
        if frob(w.r) <= c.tol * b0 {
            break;
        }
        jacobi(lap, w.r, z)?;
        let rz_new = dots(w.r, z);
        let beta = ratio(rz_new, rz);
        rz = rz_new;
        xpby(p, z, beta);
    }
    Ok(())
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

/// `p = z + β p`.
#[inline]
fn xpby(p: &mut [Point], z: &[Point], beta: [f64; 3]) {
    for (pi, zi) in p.iter_mut().zip(z) {
        *pi = [
            zi[0] + beta[0] * pi[0],
            zi[1] + beta[1] * pi[1],
            zi[2] + beta[2] * pi[2],
        ];
    }
}

/// The boundary neighbour of boundary vertex `v` that is not `from`.
fn along(lap: &Laplacian<'_>, v: u32, from: u32) -> Result<u32> {
    let r = lap.ring(v as usize)?;
    let f = *r.first().ok_or(internal())?;
    let l = *r.last().ok_or(internal())?;
    Ok(if f != from { f } else { l })
}

/// The exact least-squares solution of the boundary loop through anchor `a` (module docs):
/// `C x = 2(δ − mean δ)` on the loop with `x_a` kept, by the Thomas algorithm along the path
/// that starts after `a` (`cp`, `dp` per-vertex temporaries).
fn solve_loop(
    lap: &Laplacian<'_>,
    a: u32,
    delta: &[Point],
    x: &mut [Point],
    cp: &mut [Point],
    dp: &mut [Point],
) -> Result<()> {
    let n = lap.len();
    if !lap.is_boundary(a as usize)? {
        return Err(internal());
    }
    // Length and mean of δ.
    let (mut prev, mut cur) = (a, *lap.ring(a as usize)?.first().ok_or(internal())?);
    let mut m = 1usize;
    let mut mean = get(delta, a as usize)?;
    while cur != a {
        if m > n {
            return Err(internal());
        }
        mean = add(mean, get(delta, cur as usize)?);
        m += 1;
        let nxt = along(lap, cur, prev)?;
        prev = cur;
        cur = nxt;
    }
    if m < 3 {
        return Err(internal());
    }
    mean = scale(mean, 1.0 / m as f64);
    let xa = get(x, a as usize)?;
    // Forward elimination: rows −y_{t−1} + 2 y_t − y_{t+1} = g_t, y_0 = y_m = x_a.
    let (mut prev, mut cur) = (a, *lap.ring(a as usize)?.first().ok_or(internal())?);
    let (mut c_prev, mut d_prev) = (0.0f64, xa);
    let mut last = cur;
    while cur != a {
        let nxt = along(lap, cur, prev)?;
        let mut g = scale(sub(get(delta, cur as usize)?, mean), 2.0);
        g = add(g, d_prev);
        if nxt == a {
            g = add(g, xa);
        }
        let den = 2.0 + c_prev;
        let c = -1.0 / den;
        let d = scale(g, 1.0 / den);
        set(cp, cur as usize, [c, 0.0, 0.0])?;
        set(dp, cur as usize, d)?;
        c_prev = c;
        d_prev = d;
        last = cur;
        prev = cur;
        cur = nxt;
    }
    // Back substitution from the last path vertex towards a.
    let (mut from, mut cur) = (a, last);
    let mut y_next = [0.0; 3];
    let mut first = true;
    while cur != a {
        let c = get(cp, cur as usize)?[0];
        let d = get(dp, cur as usize)?;
        let y = if first { d } else { sub(d, scale(y_next, c)) };
        first = false;
        set(x, cur as usize, y)?;
        y_next = y;
        let nxt = along(lap, cur, from)?;
        from = cur;
        cur = nxt;
    }
    Ok(())
}

/// Solves the [module](self)'s system at its finest level from the warm start in `x`,
/// overwriting it; `delta` is `4⁻ᵏ Δ_k`. `scratch` holds at least [`solve_scratch_len`]
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
    let delta = delta.get(..n).ok_or(Error::too_small(n))?;
    let x = x.get_mut(..n).ok_or(Error::too_small(n))?;
    let fine = sys.levels.last().ok_or(internal())?.lap;
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
    let bne = take(&mut rest, n)?;
    let c = Coarse {
        tol: opts.coarse_tolerance,
        max: opts.coarse_max_iterations,
    };

    // Centre (translation-free residual test, smaller rounding in the differences).
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

    // b = Lᵀδ + w x_a.
    for bi in bne.iter_mut() {
        *bi = [0.0; 3];
    }
    fine.apply_transpose_add(delta, bne)?;
    for &a in sys.anchors {
        let xa = get(x, a as usize)?;
        let ba = bne.get_mut(a as usize).ok_or(internal())?;
        *ba = add(*ba, scale(xa, sys.anchor_weight));
    }
    let bnorm = frob(bne);
    let mut report = SolveReport::default();
    let finish = |x: &mut [Point]| {
        for p in x.iter_mut() {
            *p = add(*p, centre);
        }
    };
    if bnorm == 0.0 {
        for xi in x.iter_mut() {
            *xi = centre;
        }
        report.converged = true;
        return Ok(report);
    }
    {
        let fw = work.last_mut().ok_or(internal())?;
        report.initial_residual = sys.normal_residual(bne, x, fw.t, fw.b)? / bnorm;
    }

    // Boundary loops: exact.
    for &a in sys.anchors.get(..sys.loop_anchors).ok_or(internal())? {
        solve_loop(&fine, a, delta, x, z, z_old)?;
    }
    // Compatibility constants of the closed components: Σ dᵢδᵢ and Σ dᵢ².
    {
        let [sd, sdd, _] = &mut coarse;
        for (a, b) in sd.iter_mut().zip(sdd.iter_mut()) {
            *a = [0.0; 3];
            *b = [0.0; 3];
        }
        for i in 0..n {
            let l = get(sys.components, i)? as usize;
            if get(sys.open, l)? != 0 {
                continue;
            }
            let d = fine.degree(i)?;
            let s = sd.get_mut(l).ok_or(internal())?;
            *s = add(*s, scale(get(delta, i)?, d));
            sdd.get_mut(l).ok_or(internal())?[0] += d * d;
        }
        // r = f − K x on free rows, f = Dδ (+ c D² on closed components).
        for (i, ri) in r.iter_mut().enumerate() {
            if fine.is_fixed(i)? {
                *ri = [0.0; 3];
                continue;
            }
            let d = fine.degree(i)?;
            let mut f = scale(get(delta, i)?, d);
            let l = get(sys.components, i)? as usize;
            if get(sys.open, l)? == 0 {
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
    }

    let precondition = |work: &mut ArrayVec<Work<'_>, MAX_HIERARCHY>,
                        coarse: &mut [&mut [Point]; 3],
                        r: &[Point],
                        z: &mut [Point]|
     -> Result<()> {
        let fw = work.last_mut().ok_or(internal())?;
        copy(fw.b, r);
        sys.vcycle(work, coarse, c)?;
        let fw = work.last().ok_or(internal())?;
        copy(z, fw.x);
        Ok(())
    };
    let mut rel = {
        let fw = work.last_mut().ok_or(internal())?;
        sys.normal_residual(bne, x, fw.t, fw.b)? / bnorm
    };
    if rel > opts.tolerance {
        precondition(&mut work, &mut coarse, r, z)?;
        copy(p, z);
        let mut rz = dots(r, z);
        while report.iterations < opts.max_iterations {
            apply_k(&fine, p, q)?;
            let alpha = ratio(rz, dots(p, q));
            axpy(x, alpha, p);
            axpy(r, [-alpha[0], -alpha[1], -alpha[2]], q);
            report.iterations += 1;
            let fw = work.last_mut().ok_or(internal())?;
            rel = sys.normal_residual(bne, x, fw.t, fw.b)? / bnorm;
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
            let beta = ratio(sub(rz_new, cross), rz);
            rz = rz_new;
            xpby(p, z, beta);
        }
    }
    let fw = work.last_mut().ok_or(internal())?;
    report.relative_residual = sys.normal_residual(bne, x, fw.t, fw.b)? / bnorm;
    if !report.relative_residual.is_finite() {
        return Err(Error::new(Status::NumericalFailure));
    }
    report.converged = report.relative_residual <= opts.tolerance;
    finish(x);
    Ok(report)
}
