//! Old vertices a scheme carries through unchanged, written where the scheme's pattern numbers
//! them ([`crate::mesh::refine`]): primal patterns keep every old vertex at its own index;
//! dual patterns number the kept boundary vertices by rank and append the isolated vertices
//! after their own points.

use crate::error::Result;
use crate::mesh::{set, Topology, NONE};
use crate::point::Point;

/// Every old vertex at its own index (primal patterns).
pub(crate) fn copy_old(topo: &Topology<'_, '_>, pos: &mut [Point]) -> Result<()> {
    for (v, p) in topo.mesh().positions().enumerate() {
        set(pos, v, p)?;
    }
    Ok(())
}

/// Every boundary vertex at `start + rank` (boundary points of the dual patterns).
pub(crate) fn boundary_vertices(
    topo: &Topology<'_, '_>,
    pos: &mut [Point],
    start: usize,
) -> Result<()> {
    for v in 0..topo.num_vertices() as u32 {
        let r = topo.boundary_vertex_rank(v)?;
        if r != NONE {
            set(pos, start + r as usize, topo.position(v)?)?;
        }
    }
    Ok(())
}

/// The isolated vertices, in index order, from `start` (dual patterns).
pub(crate) fn append_isolated(
    topo: &Topology<'_, '_>,
    pos: &mut [Point],
    start: usize,
) -> Result<()> {
    let mut k = start;
    for v in 0..topo.num_vertices() as u32 {
        if topo.is_isolated(v)? {
            set(pos, k, topo.position(v)?)?;
            k += 1;
        }
    }
    Ok(())
}
