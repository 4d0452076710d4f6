//! The arrays of a [`Topology`] in caller scratch: their layout ([`Regions`], `4·corners +
//! 3·vertices` entries), their read-only view for the hot loops of the patterns and the
//! drivers ([`Raw`]), and the scalar counts ([`Counts`]) with which a multi-level call
//! rebuilds the view of a topology whose arrays are already in scratch.

use super::{topology_scratch_size, Topology};
use crate::error::{Error, Result};
use crate::mesh::{get, internal, Mesh};

/// The seven regions of a topology scratch ([`Topology::build`]'s layout).
pub(crate) struct Regions<'s> {
    pub(crate) face_of: &'s mut [u32],
    pub(crate) twin: &'s mut [u32],
    pub(crate) edge_of: &'s mut [u32],
    pub(crate) edge_he: &'s mut [u32],
    pub(crate) vert_he: &'s mut [u32],
    pub(crate) valence: &'s mut [u32],
    pub(crate) bnd_rank: &'s mut [u32],
}

/// The regions of a scratch for `nv` vertices and `nh` half-edges;
/// [`crate::Status::BufferTooSmall`] with the needed length when it is short.
pub(crate) fn regions(scratch: &mut [u32], nv: usize, nh: usize) -> Result<Regions<'_>> {
    let need = topology_scratch_size(nv, nh)?;
    if scratch.len() < need {
        return Err(Error::too_small(need));
    }
    let (face_of, rest) = scratch.split_at_mut_checked(nh).ok_or(internal())?;
    let (twin, rest) = rest.split_at_mut_checked(nh).ok_or(internal())?;
    let (edge_of, rest) = rest.split_at_mut_checked(nh).ok_or(internal())?;
    let (edge_he, rest) = rest.split_at_mut_checked(nh).ok_or(internal())?;
    let (vert_he, rest) = rest.split_at_mut_checked(nv).ok_or(internal())?;
    let (valence, rest) = rest.split_at_mut_checked(nv).ok_or(internal())?;
    let (bnd_rank, _) = rest.split_at_mut_checked(nv).ok_or(internal())?;
    Ok(Regions {
        face_of,
        twin,
        edge_of,
        edge_he,
        vert_he,
        valence,
        bnd_rank,
    })
}

/// The scalar part of a [`Topology`] (its arrays live in the scratch): with the scratch of a
/// built or derived topology it rebuilds the same view in `O(1)` ([`Topology::from_parts`]),
/// so a multi-level call can keep a topology across loop iterations without borrowing it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Counts {
    pub(crate) n_edges: usize,
    pub(crate) n_boundary_edges: usize,
    pub(crate) n_boundary_vertices: usize,
    pub(crate) n_isolated: usize,
    pub(crate) interior_spokes: usize,
    pub(crate) boundary_spokes: usize,
    pub(crate) max_face: usize,
    pub(crate) min_face: usize,
}

/// The arrays of a [`Topology`] ([`Topology::raw`]); see the module docs for their meaning.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Raw<'m, 's> {
    pub(crate) offsets: &'m [u32],
    pub(crate) indices: &'m [u32],
    pub(crate) face_of: &'s [u32],
    pub(crate) twin: &'s [u32],
    pub(crate) edge_of: &'s [u32],
    pub(crate) edge_he: &'s [u32],
    pub(crate) vert_he: &'s [u32],
    pub(crate) valence: &'s [u32],
    pub(crate) bnd_rank: &'s [u32],
    /// Every face is a quad, so face `f` is corners `4f..4f + 4` (every level of
    /// Catmull–Clark and Kobbelt after the first).
    pub(crate) quads: bool,
    /// Every face is a triangle, so face `f` is corners `3f..3f + 3` (Loop, Butterfly).
    pub(crate) triangles: bool,
}

impl Raw<'_, '_> {
    /// `(next(h), prev(h), face(h))` from one face lookup (none on an all-quad mesh).
    #[inline]
    pub(crate) fn next_prev_face(&self, h: u32) -> Result<(u32, u32, u32)> {
        if self.quads {
            let base = h & !3;
            return Ok((
                base | (h.wrapping_add(1) & 3),
                base | (h.wrapping_add(3) & 3),
                h >> 2,
            ));
        }
        if self.triangles {
            let f = h / 3;
            let base = 3 * f;
            let (next, prev) = match h - base {
                0 => (h + 1, h + 2),
                1 => (h + 1, h - 1),
                _ => (base, h - 1),
            };
            return Ok((next, prev, f));
        }
        let f = get(self.face_of, h as usize)?;
        let start = get(self.offsets, f as usize)?;
        let end = get(self.offsets, f as usize + 1)?;
        let next = if h + 1 == end { start } else { h + 1 };
        let prev = if h == start {
            end.wrapping_sub(1)
        } else {
            h.wrapping_sub(1)
        };
        Ok((next, prev, f))
    }
}

impl<'m, 's> Topology<'m, 's> {
    /// The arrays of this topology, read-only, for the hot loops of the patterns and the
    /// linear drivers (the same data the queries read, without a call per lookup).
    pub(crate) fn raw(&self) -> Raw<'m, 's> {
        Raw {
            offsets: self.mesh.offsets,
            indices: self.mesh.indices,
            face_of: self.face_of,
            twin: self.twin,
            edge_of: self.edge_of,
            edge_he: self.edge_he,
            vert_he: self.vert_he,
            valence: self.valence,
            bnd_rank: self.bnd_rank,
            quads: self.min_face == 4 && self.max_face == 4,
            triangles: self.min_face == 3 && self.max_face == 3,
        }
    }

    /// The scalar part of this topology, for [`Topology::from_parts`].
    pub(crate) fn counts(&self) -> Counts {
        Counts {
            n_edges: self.edge_he.len(),
            n_boundary_edges: self.n_boundary_edges,
            n_boundary_vertices: self.n_boundary_vertices,
            n_isolated: self.n_isolated,
            interior_spokes: self.interior_spokes,
            boundary_spokes: self.boundary_spokes,
            max_face: self.max_face,
            min_face: self.min_face,
        }
    }

    /// The topology of `mesh` whose arrays [`Topology::build`] (or a derivation of
    /// `refine::child_topology`) left in `scratch`, with the `counts` it returned: the same view
    /// again in `O(1)`, nothing re-validated. Only the regions' lengths are checked.
    pub(crate) fn from_parts(
        mesh: Mesh<'m>,
        scratch: &'s mut [u32],
        counts: Counts,
    ) -> Result<Self> {
        // The scratch was sized for this mesh when the arrays were written: short is a bug.
        let Regions {
            face_of,
            twin,
            edge_of,
            edge_he,
            vert_he,
            valence,
            bnd_rank,
        } = regions(scratch, mesh.num_vertices(), mesh.num_corners()).map_err(|_| internal())?;
        let edge_he: &'s [u32] = edge_he;
        Ok(Topology {
            mesh,
            face_of,
            twin,
            edge_of,
            edge_he: edge_he.get(..counts.n_edges).ok_or(internal())?,
            vert_he,
            valence,
            bnd_rank,
            n_boundary_edges: counts.n_boundary_edges,
            n_boundary_vertices: counts.n_boundary_vertices,
            n_isolated: counts.n_isolated,
            interior_spokes: counts.interior_spokes,
            boundary_spokes: counts.boundary_spokes,
            max_face: counts.max_face,
            min_face: counts.min_face,
        })
    }
}
