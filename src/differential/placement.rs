//! Where the reconstructed surface is put: anchors and per-component translation (the
//! placement decision of the [module documentation](super)).
//!
//! The Laplacian determines the surface only up to one translation per closed component and
//! per boundary loop (its null vectors). The paper fixes one handle at the origin; we anchor
//! the lowest-index vertex of every closed component, of every boundary loop and every isolated
//! vertex at its position in the spatial subdivision ([`components_and_anchors`]), and after the
//! solve translate each connected component so that its centroid is that of the same component
//! of the spatial subdivision ([`place`]). Translations do not change the least-squares
//! residual, so the result is one of the paper's solutions, and it stays where the control mesh
//! is.

use crate::error::{Error, Result, Status};
use crate::mesh::{get, internal, set, Topology, NONE};
use crate::point::{self, add, Point};

/// The anchors found by [`components_and_anchors`].
#[derive(Clone, Copy, Debug)]
pub(super) struct Anchors {
    /// Number of anchors: boundary loops, then closed components and isolated vertices.
    pub(super) count: usize,
    /// How many of them (the first) are boundary-loop anchors.
    pub(super) loops: usize,
}

/// Union–find root with path halving (deterministic).
fn find(parent: &mut [u32], mut v: u32) -> Result<u32> {
    for _ in 0..parent.len() + 1 {
        let p = get(parent, v as usize)?;
        if p == v {
            return Ok(v);
        }
        let gp = get(parent, p as usize)?;
        set(parent, v as usize, gp)?;
        v = gp;
    }
    Err(internal())
}

/// The connected components of the control mesh and its anchors.
///
/// Writes `labels[v]` = the lowest vertex of `v`'s component for the `n0` control vertices;
/// `anchors` = the lowest vertex of every boundary loop (in loop order), then the lowest vertex
/// of every component without boundary (closed components and isolated vertices);
/// `open[root] ≠ 0` exactly for the components with a boundary. `loop_mark` is the scratch of
/// [`Topology::boundary_loops`].
pub(super) fn components_and_anchors(
    topo: &Topology<'_, '_>,
    n0: usize,
    labels: &mut [u32],
    open: &mut [u32],
    anchors: &mut [u32],
    loop_mark: &mut [u32],
) -> Result<Anchors> {
    // Components (union–find over edges).
    let parent = labels.get_mut(..n0).ok_or(internal())?;
    for (v, p) in parent.iter_mut().enumerate() {
        *p = v as u32;
    }
    for e in 0..topo.num_edges() as u32 {
        let (a, b) = topo.edge_vertices(e)?;
        let (ra, rb) = (find(parent, a)?, find(parent, b)?);
        if ra != rb {
            let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
            set(parent, hi as usize, lo)?;
        }
    }
    for v in 0..n0 as u32 {
        let r = find(parent, v)?;
        set(parent, v as usize, r)?;
    }
    // Anchors: one per boundary loop, then one per component that has none (`open[root]` is 1
    // for a component with a boundary loop, 2 for a closed one whose anchor is taken).
    for a in open.iter_mut() {
        *a = 0;
    }
    let loops = topo.boundary_loops(loop_mark)?;
    for a in anchors.iter_mut().take(loops) {
        *a = NONE;
    }
    for (h, &m) in loop_mark.iter().enumerate() {
        if m == NONE {
            continue;
        }
        let v = topo.origin(h as u32)?;
        let slot = anchors.get_mut(m as usize).ok_or(internal())?;
        *slot = (*slot).min(v);
        set(open, get(parent, v as usize)? as usize, 1)?;
    }
    let mut count = loops;
    for v in 0..n0 {
        let r = get(parent, v)? as usize;
        if get(open, r)? == 0 {
            set(open, r, 2)?;
            set(anchors, count, v as u32)?;
            count += 1;
        }
    }
    // From here on `open[root] ≠ 0` means "this component has a boundary".
    for a in open.iter_mut() {
        *a = u32::from(*a == 1);
    }
    Ok(Anchors { count, loops })
}

/// Clears the per-component sums and accumulates the sum of the positions and the vertex count
/// of every component of the spatial subdivision `spatial` (the warm start, before the solve
/// overwrites it) into `sums_spatial` and `counts` (`counts[l][0]`). `sums_solved` is cleared
/// for [`place`].
pub(super) fn spatial_centroid_sums(
    labels: &[u32],
    spatial: &[Point],
    sums_solved: &mut [Point],
    sums_spatial: &mut [Point],
    counts: &mut [Point],
) -> Result<()> {
    for ((a, b), c) in sums_solved
        .iter_mut()
        .zip(sums_spatial.iter_mut())
        .zip(counts.iter_mut())
    {
        *a = [0.0; 3];
        *b = [0.0; 3];
        *c = [0.0; 3];
    }
    for (v, p) in spatial.iter().enumerate() {
        let l = get(labels, v)? as usize;
        let s = sums_spatial.get_mut(l).ok_or(internal())?;
        *s = add(*s, *p);
        counts.get_mut(l).ok_or(internal())?[0] += 1.0;
    }
    Ok(())
}

/// Translates every component of the solved positions `pos` so that its centroid is that of
/// the spatial subdivision ([`spatial_centroid_sums`]).
///
/// # Errors
/// [`Status::NumericalFailure`] naming the first vertex whose placed position is not finite.
pub(super) fn place(
    labels: &[u32],
    pos: &mut [Point],
    sums_solved: &mut [Point],
    sums_spatial: &[Point],
    counts: &[Point],
) -> Result<()> {
    for (v, p) in pos.iter().enumerate() {
        let l = get(labels, v)? as usize;
        let s = sums_solved.get_mut(l).ok_or(internal())?;
        *s = add(*s, *p);
    }
    for (v, p) in pos.iter_mut().enumerate() {
        let l = get(labels, v)? as usize;
        let n = get(counts, l)?[0];
        let (a, b) = (get(sums_spatial, l)?, get(sums_solved, l)?);
        let q = [
            p[0] + (a[0] - b[0]) / n,
            p[1] + (a[1] - b[1]) / n,
            p[2] + (a[2] - b[2]) / n,
        ];
        if !point::is_finite(&q) {
            return Err(Error::at(Status::NumericalFailure, v as u32));
        }
        *p = q;
    }
    Ok(())
}
