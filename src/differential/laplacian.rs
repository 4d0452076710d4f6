//! The combinatorial Laplacian of seed 001 §3.1 Eqs. (1)–(3) with the curve form Eq. (8) on
//! the boundary, stored as a neighbour list (CSR) in caller scratch.
//!
//! Row `i` of `L` is `(L V)_i = v_i − (1/|N_i|) Σ_{j ∈ N_i} v_j` with
//!
//! * `N_i` the 1-ring of an interior vertex (Eq. (2): `ω_ij = 1/d_i`);
//! * `N_i = {b0, b1}`, the two boundary neighbours, for a boundary vertex (Eq. (8), "we propose
//!   to use the previous curve version of differential coordinates (8) as a substitute for
//!   the discrete mean-curvature normals on the boundary", §3.5 "Boundary treatment");
//! * `N_i = ∅` for an isolated vertex: its row is zero (it carries no differential
//!   information; the reconstruction keeps it where the spatial subdivision puts it).
//!
//! Every row of `L` sums to zero (translations are in its null space). Because boundary rows
//! only see boundary vertices, the boundary loops decouple: each loop is the closed
//! differential curve of `crate::curve::differential`, and the interior follows from them.
//! Row `i` is stored as `cols[rows[i] .. rows[i+1]]`; its weight is `1/len` (no weights
//! stored).

use crate::error::{Error, Result, Status};
use crate::exec::{pass, Executor};
use crate::mesh::{get, internal, set, Topology};
use crate::point::{add, scale, sub, Point};

/// A level's Laplacian as neighbour lists: row `i`'s full 1-ring is
/// `cols[rows[i]..rows[i + 1]]` (counter-clockwise; a boundary vertex's ring runs from `b0`
/// to `b1`, [`Topology::star`]), `boundary[i] ≠ 0` marks a boundary row, whose Eq. (8)
/// neighbours are the first and last ring entries.
#[derive(Clone, Copy, Debug)]
pub struct Laplacian<'a> {
    /// `n + 1` row starts.
    pub rows: &'a [u32],
    /// Ring entries.
    pub cols: &'a [u32],
    /// `n` flags: bit 0 ([`BOUNDARY`]) marks boundary rows, bit 1 ([`PINNED`]) an anchor
    /// that the reconstruction keeps fixed ([`super::solve`]).
    pub boundary: &'a [u32],
}

/// Flag bit of a boundary row.
pub const BOUNDARY: u32 = 1;
/// Flag bit of a pinned (anchor) vertex.
pub const PINNED: u32 = 2;

/// The number of ring entries of `topo`: Σ valence = 2 · edges.
pub fn laplacian_nnz(topo: &Topology<'_, '_>) -> Result<usize> {
    topo.num_edges()
        .checked_mul(2)
        .ok_or(Error::new(Status::SizeOverflow))
}

/// Writes the rings of `topo` into `rows` (`n + 1`), `cols` (≥ [`laplacian_nnz`]) and the
/// boundary flags (`n`); returns the entries used.
///
/// # Errors
/// [`Status::BufferTooSmall`] with the needed length.
pub fn build(
    topo: &Topology<'_, '_>,
    rows: &mut [u32],
    cols: &mut [u32],
    boundary: &mut [u32],
) -> Result<usize> {
    let n = topo.num_vertices();
    if rows.len() < n + 1 {
        return Err(Error::too_small(n + 1));
    }
    if boundary.len() < n {
        return Err(Error::too_small(n));
    }
    let nnz = laplacian_nnz(topo)?;
    if cols.len() < nnz {
        return Err(Error::too_small(nnz));
    }
    let mut k = 0usize;
    set(rows, 0, 0)?;
    for v in 0..n as u32 {
        let b = topo.is_boundary_vertex(v)?;
        set(boundary, v as usize, u32::from(b))?;
        for s in topo.star(v) {
            set(cols, k, s.neighbour)?;
            k += 1;
        }
        set(rows, v as usize + 1, crate::mesh::idx(k)?)?;
    }
    if k != nnz {
        return Err(internal());
    }
    Ok(k)
}

impl Laplacian<'_> {
    /// Number of rows.
    pub fn len(&self) -> usize {
        self.rows.len().saturating_sub(1)
    }

    /// Whether there are no rows.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The full ring of row `i`.
    #[inline]
    pub fn ring(&self, i: usize) -> Result<&[u32]> {
        let a = get(self.rows, i)? as usize;
        let b = get(self.rows, i + 1)? as usize;
        self.cols.get(a..b).ok_or(internal())
    }

    /// The neighbours of row `i` in `L` (Eq. (2) ring, or Eq. (8) pair on the boundary) as
    /// `(first, middle, last)` pieces: for a boundary row the middle is empty.
    #[inline]
    fn row_parts(&self, i: usize) -> Result<(&[u32], bool)> {
        let r = self.ring(i)?;
        Ok((r, get(self.boundary, i)? & BOUNDARY != 0 && r.len() >= 2))
    }

    /// Whether row `i` is a boundary (Eq. (8)) row.
    #[inline]
    pub fn is_boundary(&self, i: usize) -> Result<bool> {
        Ok(get(self.boundary, i)? & BOUNDARY != 0)
    }

    /// Whether vertex `i` is a Dirichlet vertex of the reconstruction's interior problem:
    /// on the boundary, pinned, or isolated (empty ring).
    #[inline]
    pub fn is_fixed(&self, i: usize) -> Result<bool> {
        Ok(get(self.boundary, i)? != 0 || get(self.rows, i + 1)? == get(self.rows, i)?)
    }

    /// `y = c · L x` (x, y at least [`Laplacian::len`] long).
    pub fn apply(&self, x: &[Point], c: f64, y: &mut [Point]) -> Result<()> {
        for (i, yi) in y.iter_mut().enumerate().take(self.len()) {
            *yi = self.apply_row(x, c, i)?;
        }
        Ok(())
    }

    /// [`Laplacian::apply`] with the rows split into disjoint ranges run by `exec`
    /// ([`crate::exec`]): every row is computed as there, so the bits are the same for every
    /// executor and chunking.
    pub fn apply_with(
        &self,
        x: &[Point],
        c: f64,
        y: &mut [Point],
        exec: &dyn Executor,
    ) -> Result<()> {
        let n = self.len();
        let y = y.get_mut(..n).ok_or(Error::too_small(n))?;
        pass(exec, y, |start, out, _| {
            for (k, yi) in out.iter_mut().enumerate() {
                *yi = self.apply_row(x, c, start + k)?;
            }
            Ok(())
        })?;
        Ok(())
    }

    /// Row `i` of `c · L x`.
    #[inline]
    fn apply_row(&self, x: &[Point], c: f64, i: usize) -> Result<Point> {
        let (r, bnd) = self.row_parts(i)?;
        if r.is_empty() {
            return Ok([0.0; 3]);
        }
        let (s, w) = if bnd {
            let a = get(x, *r.first().ok_or(internal())? as usize)?;
            let b = get(x, *r.last().ok_or(internal())? as usize)?;
            (add(a, b), 0.5)
        } else {
            let mut s = [0.0; 3];
            for &j in r {
                let p = get(x, j as usize)?;
                s = add(s, p);
            }
            (s, 1.0 / r.len() as f64)
        };
        let xi = get(x, i)?;
        Ok(scale(sub(xi, scale(s, w)), c))
    }

    /// `y += Lᵀ t` (scatter in row order, so deterministic).
    pub fn apply_transpose_add(&self, t: &[Point], y: &mut [Point]) -> Result<()> {
        for i in 0..self.len() {
            let (r, bnd) = self.row_parts(i)?;
            if r.is_empty() {
                continue;
            }
            let ti = get(t, i)?;
            let yi = y.get_mut(i).ok_or(internal())?;
            *yi = add(*yi, ti);
            let mut subtract = |j: u32, w: f64| -> Result<()> {
                let yj = y.get_mut(j as usize).ok_or(internal())?;
                *yj = sub(*yj, scale(ti, w));
                Ok(())
            };
            if bnd {
                subtract(*r.first().ok_or(internal())?, 0.5)?;
                subtract(*r.last().ok_or(internal())?, 0.5)?;
            } else {
                let w = 1.0 / r.len() as f64;
                for &j in r {
                    subtract(j, w)?;
                }
            }
        }
        Ok(())
    }

    /// `y = K x` with `K = D − A` the symmetric graph Laplacian of the full rings (the
    /// preconditioner's operator, [`super::solve`]).
    pub fn apply_graph(&self, x: &[Point], y: &mut [Point]) -> Result<()> {
        for (i, yi) in y.iter_mut().enumerate().take(self.len()) {
            let r = self.ring(i)?;
            let mut s = [0.0; 3];
            for &j in r {
                let p = get(x, j as usize)?;
                s = add(s, p);
            }
            let d = r.len() as f64;
            let xi = get(x, i)?;
            *yi = sub(scale(xi, d), s);
        }
        Ok(())
    }

    /// The degree (ring length) of row `i`.
    #[inline]
    pub fn degree(&self, i: usize) -> Result<f64> {
        Ok((get(self.rows, i + 1)? - get(self.rows, i)?) as f64)
    }
}
