//! Queries on a [`Topology`]: its counts, and the elements around a face, a half-edge, an
//! edge or a vertex. `O(1)` each; they return `Result` only to stay panic-free: on a built
//! topology they cannot fail for indices in range.

use super::Topology;
use crate::error::Result;
use crate::mesh::{get, internal, Mesh, NONE};
use crate::point::Point;

/// `next(h)` from the offsets and the face of each half-edge.
pub(super) fn next_in(offsets: &[u32], face_of: &[u32], h: u32) -> Result<u32> {
    let f = get(face_of, h as usize)? as usize;
    let end = get(offsets, f + 1)?;
    if h + 1 == end {
        get(offsets, f)
    } else {
        Ok(h + 1)
    }
}

/// `prev(h)` from the offsets and the face of each half-edge.
pub(super) fn prev_in(offsets: &[u32], face_of: &[u32], h: u32) -> Result<u32> {
    let f = get(face_of, h as usize)? as usize;
    let start = get(offsets, f)?;
    if h == start {
        Ok(get(offsets, f + 1)?.wrapping_sub(1))
    } else {
        Ok(h - 1)
    }
}

impl<'m, 's> Topology<'m, 's> {
    /// The mesh this topology describes.
    pub fn mesh(&self) -> Mesh<'m> {
        self.mesh
    }

    /// Number of vertices, isolated ones included.
    pub fn num_vertices(&self) -> usize {
        self.mesh.num_vertices()
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.mesh.num_faces()
    }

    /// Number of half-edges (= corners).
    pub fn num_half_edges(&self) -> usize {
        self.mesh.num_corners()
    }

    /// Number of edges.
    pub fn num_edges(&self) -> usize {
        self.edge_he.len()
    }

    /// Number of boundary edges (edges with one face).
    pub fn num_boundary_edges(&self) -> usize {
        self.n_boundary_edges
    }

    /// Number of interior edges (edges with two faces).
    pub fn num_interior_edges(&self) -> usize {
        self.num_edges() - self.n_boundary_edges
    }

    /// Number of boundary vertices (= boundary edges on a manifold mesh).
    pub fn num_boundary_vertices(&self) -> usize {
        self.n_boundary_vertices
    }

    /// Number of isolated (unreferenced) vertices.
    pub fn num_isolated_vertices(&self) -> usize {
        self.n_isolated
    }

    /// Number of interior vertices (referenced and not on the boundary).
    pub fn num_interior_vertices(&self) -> usize {
        self.num_vertices() - self.n_boundary_vertices - self.n_isolated
    }

    /// Sum of the valences of all interior vertices.
    pub fn interior_valence_sum(&self) -> usize {
        self.interior_spokes
    }

    /// Sum of the valences of all boundary vertices.
    pub fn boundary_valence_sum(&self) -> usize {
        self.boundary_spokes
    }

    /// Largest face size (0 for a mesh without faces).
    pub fn max_face_size(&self) -> usize {
        self.max_face
    }

    /// Smallest face size (0 for a mesh without faces).
    pub fn min_face_size(&self) -> usize {
        self.min_face
    }

    /// Euler characteristic `V − E + F`, isolated vertices counted (each is a component with
    /// χ = 1).
    pub fn euler_characteristic(&self) -> i64 {
        self.num_vertices() as i64 - self.num_edges() as i64 + self.num_faces() as i64
    }

    /// The corners (= half-edges) of face `f`, `offsets[f]..offsets[f + 1]`.
    pub fn face_half_edges(&self, f: u32) -> Result<core::ops::Range<u32>> {
        let a = get(self.mesh.offsets, f as usize)?;
        let b = get(self.mesh.offsets, f as usize + 1)?;
        Ok(a..b)
    }

    /// The vertices of face `f`.
    pub fn face_vertices(&self, f: u32) -> Result<&'m [u32]> {
        self.mesh.face(f as usize).ok_or(internal())
    }

    /// Number of corners of face `f`.
    pub fn face_size(&self, f: u32) -> Result<usize> {
        Ok(self.face_vertices(f)?.len())
    }

    /// Position of vertex `v`.
    pub fn position(&self, v: u32) -> Result<Point> {
        self.mesh.position(v).ok_or(internal())
    }

    /// Start vertex of half-edge `h`.
    pub fn origin(&self, h: u32) -> Result<u32> {
        get(self.mesh.indices, h as usize)
    }

    /// End vertex of half-edge `h`.
    pub fn dest(&self, h: u32) -> Result<u32> {
        self.origin(self.next(h)?)
    }

    /// Next half-edge of the same face.
    pub fn next(&self, h: u32) -> Result<u32> {
        next_in(self.mesh.offsets, self.face_of, h)
    }

    /// Previous half-edge of the same face.
    pub fn prev(&self, h: u32) -> Result<u32> {
        prev_in(self.mesh.offsets, self.face_of, h)
    }

    /// Face of half-edge `h`.
    pub fn face(&self, h: u32) -> Result<u32> {
        get(self.face_of, h as usize)
    }

    /// Opposite half-edge, or [`NONE`] on the boundary.
    pub fn twin(&self, h: u32) -> Result<u32> {
        get(self.twin, h as usize)
    }

    /// Edge id of half-edge `h`.
    pub fn edge(&self, h: u32) -> Result<u32> {
        get(self.edge_of, h as usize)
    }

    /// Representative half-edge of edge `e` (from `min` to `max` when it exists).
    pub fn edge_half_edge(&self, e: u32) -> Result<u32> {
        get(self.edge_he, e as usize)
    }

    /// The two vertices `(min, max)` of edge `e`.
    pub fn edge_vertices(&self, e: u32) -> Result<(u32, u32)> {
        let h = self.edge_half_edge(e)?;
        let (a, b) = (self.origin(h)?, self.dest(h)?);
        Ok((a.min(b), a.max(b)))
    }

    /// Whether edge `e` has a single face.
    pub fn is_boundary_edge(&self, e: u32) -> Result<bool> {
        Ok(self.twin(self.edge_half_edge(e)?)? == NONE)
    }

    /// Number of neighbours of `v` (0 for an isolated vertex).
    pub fn valence(&self, v: u32) -> Result<usize> {
        Ok(get(self.valence, v as usize)? as usize)
    }

    /// Number of faces around `v`: the valence, minus one on the boundary.
    pub fn vertex_face_count(&self, v: u32) -> Result<usize> {
        let n = self.valence(v)?;
        Ok(if self.is_boundary_vertex(v)? {
            n - 1
        } else {
            n
        })
    }

    /// The first outgoing half-edge of `v`'s star, [`NONE`] for an isolated vertex.
    pub fn vertex_half_edge(&self, v: u32) -> Result<u32> {
        get(self.vert_he, v as usize)
    }

    /// Whether `v` lies on the boundary.
    pub fn is_boundary_vertex(&self, v: u32) -> Result<bool> {
        let h = self.vertex_half_edge(v)?;
        Ok(h != NONE && self.twin(h)? == NONE)
    }

    /// The rank of boundary vertex `v` among the boundary vertices in index order (`0..`
    /// [`num_boundary_vertices`](Self::num_boundary_vertices)), [`NONE`] for other vertices.
    /// Dual patterns number their boundary points with it.
    pub fn boundary_vertex_rank(&self, v: u32) -> Result<u32> {
        get(self.bnd_rank, v as usize)
    }

    /// Whether `v` is referenced by no face.
    pub fn is_isolated(&self, v: u32) -> Result<bool> {
        Ok(self.vertex_half_edge(v)? == NONE)
    }
}
