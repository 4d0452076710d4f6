//! The multigrid preconditioner of the solve: one V-cycle for the Dirichlet graph Laplacian
//! `K̃` over the subdivision hierarchy (the [module documentation](super), "How it is solved").
//!
//! Level `j` is the mesh after `j` subdivision steps; the edge points of level `j + 1`
//! interpolate linearly from their edge's ends (`P`), residuals restrict by `Pᵀ`, and the
//! rediscretised `K_j` is the Galerkin operator of the finer one, so no coarse matrix is
//! formed. The coarsest level (the control mesh) is solved by Jacobi-preconditioned CG.

use super::vectors::{axpy, copy, dots, frob, ratio, xpby};
use super::{SolveLevel, System};
use crate::differential::laplacian::Laplacian;
use crate::error::Result;
use crate::exec::{pass, Executor, Serial};
use crate::mesh::{get, internal, set};
use crate::point::{add, scale, sub, Point};

/// Gauss–Seidel sweeps before and after each coarse correction.
const NU: usize = 1;

/// Parameters of the coarsest-level solve.
#[derive(Clone, Copy)]
pub(super) struct Coarse {
    /// Relative residual to reach.
    pub(super) tol: f64,
    /// Iteration cap.
    pub(super) max: u32,
}

/// Per-level work vectors of the V-cycle.
pub(super) struct Work<'a> {
    /// Right-hand side.
    pub(super) b: &'a mut [Point],
    /// Solution.
    pub(super) x: &'a mut [Point],
    /// Residual.
    pub(super) r: &'a mut [Point],
    /// A temporary.
    pub(super) t: &'a mut [Point],
}

/// Row `i` of `K̃ x`: `(K x)_i = dᵢ xᵢ − Σ_ring x_j` on a free row, 0 on a fixed row.
#[inline]
fn k_row(lap: &Laplacian<'_>, x: &[Point], i: usize) -> Result<Point> {
    if lap.is_fixed(i)? {
        return Ok([0.0; 3]);
    }
    let r = lap.ring(i)?;
    let mut s = [0.0; 3];
    for &j in r {
        s = add(s, get(x, j as usize)?);
    }
    Ok(sub(scale(get(x, i)?, r.len() as f64), s))
}

/// `y = K̃ x` at one level, the rows split into disjoint ranges run by `exec` (every row
/// computed alone, so the same bits for every chunking).
pub(super) fn apply_k(
    lap: &Laplacian<'_>,
    x: &[Point],
    y: &mut [Point],
    exec: &dyn Executor,
) -> Result<()> {
    let n = lap.len().min(y.len());
    let y = y.get_mut(..n).ok_or(internal())?;
    pass(exec, y, |start, out, _| {
        for (k, yi) in out.iter_mut().enumerate() {
            *yi = k_row(lap, x, start + k)?;
        }
        Ok(())
    })?;
    Ok(())
}

/// `r = b − K̃ x` (0 on fixed rows), by rows as [`apply_k`].
fn residual(lap: &Laplacian<'_>, w: &mut Work<'_>, exec: &dyn Executor) -> Result<()> {
    let n = lap.len().min(w.r.len()).min(w.b.len());
    let (x, b) = (&*w.x, &*w.b);
    let r = w.r.get_mut(..n).ok_or(internal())?;
    pass(exec, r, |start, out, _| {
        for (k, ri) in out.iter_mut().enumerate() {
            let i = start + k;
            *ri = sub(get(b, i)?, k_row(lap, x, i)?);
        }
        Ok(())
    })?;
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

    /// One V-cycle for `K̃` at the last level of `work`: `x ≈ K̃⁻¹ b`.
    ///
    /// A loop down the hierarchy (smooth, restrict the residual) to the control mesh's solve,
    /// then a loop up (prolong the correction, smooth): the recursive V-cycle's operations in
    /// its order, with one frame on the stack whatever the number of levels
    /// (`docs/firmware.md`, "Stack").
    pub(super) fn vcycle(
        &self,
        work: &mut [Work<'_>],
        coarse: &mut [&mut [Point]; 3],
        c: Coarse,
        exec: &dyn Executor,
    ) -> Result<()> {
        let top = work.len().checked_sub(1).ok_or(internal())?;
        for j in (1..=top).rev() {
            self.restrict(work.get_mut(..=j).ok_or(internal())?, exec)?;
        }
        let lap = self.level(0)?.lap;
        coarse_solve(&lap, work.first_mut().ok_or(internal())?, coarse, c)?;
        for j in 1..=top {
            self.prolong(work.get_mut(..=j).ok_or(internal())?, exec)?;
        }
        Ok(())
    }

    /// The way down at the last level `j ≥ 1` of `work`: `x = 0`, pre-smoothing, and the
    /// residual restricted by `Pᵀ` to the right-hand side of level `j − 1`.
    fn restrict(&self, work: &mut [Work<'_>], exec: &dyn Executor) -> Result<()> {
        let Some((cur, below)) = work.split_last_mut() else {
            return Err(internal());
        };
        let j = below.len();
        let lap = self.level(j)?.lap;
        let n = lap.len();
        for xi in cur.x.iter_mut() {
            *xi = [0.0; 3];
        }
        for _ in 0..NU {
            gauss_seidel(&lap, cur.b, cur.x, true)?;
        }
        residual(&lap, cur, exec)?;
        let lc = self.level(j.checked_sub(1).ok_or(internal())?)?;
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
        Ok(())
    }

    /// The way up at the last level `j ≥ 1` of `work`: level `j − 1`'s correction
    /// prolonged, then post-smoothing.
    fn prolong(&self, work: &mut [Work<'_>], exec: &dyn Executor) -> Result<()> {
        let Some((cur, below)) = work.split_last_mut() else {
            return Err(internal());
        };
        let j = below.len();
        let lap = self.level(j)?.lap;
        let n = lap.len();
        let lc = self.level(j.checked_sub(1).ok_or(internal())?)?;
        let nc = lc.lap.len();
        // Prolongation, by rows: an old vertex adds its coarse value, an edge point the mean
        // of its edge's ends.
        let cx = &*below.last().ok_or(internal())?.x;
        let edges = lc.edges;
        let x = cur.x.get_mut(..n).ok_or(internal())?;
        pass(exec, x, |start, out, _| {
            for (k, p) in out.iter_mut().enumerate() {
                let i = start + k;
                *p = if i < nc {
                    add(*p, get(cx, i)?)
                } else {
                    let e = i - nc;
                    let a = get(cx, get(edges, 2 * e)? as usize)?;
                    let b = get(cx, get(edges, 2 * e + 1)? as usize)?;
                    add(*p, scale(add(a, b), 0.5))
                };
            }
            Ok(())
        })?;
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
        apply_k(lap, p, q, &Serial)?;
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
