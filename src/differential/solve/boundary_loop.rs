//! The exact solve of one boundary loop (the [module documentation](super): boundary rows of
//! `L` see only the loop, so each loop is the closed-curve problem of seed 001 Eq. (8), one
//! tridiagonal system once its anchor is fixed).

use crate::differential::laplacian::Laplacian;
use crate::error::Result;
use crate::mesh::{get, internal, set};
use crate::point::{add, scale, sub, Point};

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
pub(super) fn solve_loop(
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
