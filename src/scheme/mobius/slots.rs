//! Where the vertex pass keeps its candidates (seed 000 §4.1 step 3): one slot per half-edge,
//! in *vertex-major* order. The slots of vertex `v` are contiguous and follow its star: the
//! candidate of spoke `j` of `v` (the half-edge `h` from `v`, counter-clockwise from the
//! star's first spoke, [`super::memo::star_into`]) lives at `slot(first(v)) + j`, and the
//! vertices' slot ranges follow each other in vertex order. So a range of vertices owns a
//! contiguous range of slots, and the vertex pass splits into vertex ranges whose chunks
//! write disjoint sub-slices ([`crate::exec::parts`]); the blends read a half-edge's slot
//! through the map.
//!
//! The map lives in the point scratch as `f64` values whose bit patterns are the slot numbers
//! (`f64::from_bits`; no arithmetic ever touches them): one value per half-edge, written once
//! per step by one walk over the stars. Reading a bit pattern back is a move, where converting
//! a float to an integer (the map's first form) took a saturating conversion in every lookup
//! of every blend: 12 M instructions of a 690 M Möbius Loop call (epcot, 4 levels).

use crate::error::Result;
use crate::mesh::{get, internal, set, Topology, NONE};

/// The slot of half-edge `h` (`slots` from [`write`]).
#[inline(always)]
pub(super) fn slot_of(slots: &[f64], h: u32) -> Result<usize> {
    let s = get(slots, h as usize)?.to_bits();
    // Only what `write` stored: a number below the number of half-edges.
    if s < slots.len() as u64 {
        Ok(s as usize)
    } else {
        Err(internal())
    }
}

/// The first slot of the star of `v`, `None` for an isolated vertex (no half-edge).
#[inline(always)]
pub(super) fn first_slot(topo: &Topology<'_, '_>, slots: &[f64], v: u32) -> Result<Option<usize>> {
    let h = topo.vertex_half_edge(v)?;
    if h == NONE {
        return Ok(None);
    }
    slot_of(slots, h).map(Some)
}

/// The first slot of the vertices from `v` on: that of the first non-isolated one, or the
/// number of half-edges (the end of the slots) when there is none.
pub(super) fn slot_at_or_after(topo: &Topology<'_, '_>, slots: &[f64], v: usize) -> Result<usize> {
    for u in v..topo.num_vertices() {
        if let Some(s) = first_slot(topo, slots, u as u32)? {
            return Ok(s);
        }
    }
    Ok(topo.num_half_edges())
}

/// Writes the slot of every half-edge into `slots[..H]`: the vertices in order, each star's
/// outgoing half-edges counter-clockwise from the first spoke (the walk of
/// [`super::memo::star_into`]: `h ← twin(prev(h))` until the star closes or reaches the
/// boundary).
pub(super) fn write(topo: &Topology<'_, '_>, slots: &mut [f64]) -> Result<()> {
    let r = topo.raw();
    let nh = topo.num_half_edges();
    let mut k = 0usize;
    for v in 0..topo.num_vertices() {
        let first = get(r.vert_he, v)?;
        if first == NONE {
            continue;
        }
        let mut cur = first;
        for _ in 0..get(r.valence, v)? {
            set(slots, cur as usize, f64::from_bits(k as u64))?;
            k += 1;
            let (_, prev, _) = r.next_prev_face(cur)?;
            cur = get(r.twin, prev as usize)?;
            if cur == NONE || cur == first {
                break;
            }
        }
    }
    // Every half-edge has exactly one origin, so the stars cover the slots once.
    if k != nh {
        return Err(internal());
    }
    Ok(())
}
