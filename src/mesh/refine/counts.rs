//! The counts of a level that determine the counts of the next (vertices, faces, corners,
//! edges, boundary edges, isolated vertices, valence sums and maxima): for every pattern the
//! counts of level `k + 1` are exact functions of those of level `k` (each pattern's `next`;
//! [`LevelCounts::next`] dispatches), so a multi-level plan knows the size of every level
//! without building any ([`crate::scheme::plan`]).

use crate::error::Result;
use crate::mesh::{cadd, MeshSizes, Topology, NONE};

/// Counts that determine the next level's counts.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LevelCounts {
    pub(super) v: usize,
    pub(super) f: usize,
    pub(super) h: usize,
    pub(super) e: usize,
    pub(super) eb: usize,
    pub(super) iso: usize,
    /// Σ valence of interior vertices.
    pub(super) si: usize,
    /// Σ valence of boundary vertices.
    pub(super) sb: usize,
    pub(super) max_vi: usize,
    pub(super) max_vb: usize,
    pub(super) max_face: usize,
    /// max over faces of (corners + interior edges): dual-truncation face-point valence.
    pub(super) max_dt: usize,
}

impl LevelCounts {
    /// The number of edges.
    pub(crate) fn edges(&self) -> usize {
        self.e
    }

    /// The largest face size (as [`Topology::max_face_size`] for a built level).
    pub(crate) fn max_face(&self) -> usize {
        self.max_face
    }

    /// The largest valence (an upper bound for a derived level, exact for a built one).
    pub(crate) fn max_valence(&self) -> usize {
        self.max_vi.max(self.max_vb)
    }

    /// The counts of a built topology.
    pub(crate) fn of(topo: &Topology<'_, '_>) -> Result<LevelCounts> {
        let mut s = LevelCounts {
            v: topo.num_vertices(),
            f: topo.num_faces(),
            h: topo.num_half_edges(),
            e: topo.num_edges(),
            eb: topo.num_boundary_edges(),
            iso: topo.num_isolated_vertices(),
            si: topo.interior_valence_sum(),
            sb: 0,
            max_vi: 0,
            max_vb: 0,
            max_face: topo.max_face_size(),
            max_dt: 0,
        };
        for v in 0..s.v as u32 {
            let n = topo.valence(v)?;
            if topo.is_boundary_vertex(v)? {
                s.sb = cadd(s.sb, n)?;
                s.max_vb = s.max_vb.max(n);
            } else {
                s.max_vi = s.max_vi.max(n);
            }
        }
        for f in 0..s.f as u32 {
            let mut n = 0usize;
            for h in topo.face_half_edges(f)? {
                n += if topo.twin(h)? == NONE { 1 } else { 2 };
            }
            s.max_dt = s.max_dt.max(n);
        }
        Ok(s)
    }

    /// Interior vertices (boundary vertices = boundary edges on a manifold mesh).
    pub(super) fn vi(&self) -> usize {
        self.v.saturating_sub(self.eb).saturating_sub(self.iso)
    }

    /// Interior edges.
    pub(super) fn ei(&self) -> usize {
        self.e.saturating_sub(self.eb)
    }

    /// The mesh sizes of this level.
    pub(crate) fn sizes(&self) -> MeshSizes {
        MeshSizes {
            vertices: self.v,
            faces: self.f,
            indices: self.h,
        }
    }
}

/// `x` when `c`, else 0 (a count that exists only when its elements do).
pub(super) fn some(c: bool, x: usize) -> usize {
    if c {
        x
    } else {
        0
    }
}
