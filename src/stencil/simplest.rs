//! Peters and Reif's "simplest" subdivision scheme (1997), the mid-edge scheme: every new
//! vertex is the midpoint of an old edge; the new faces are the face-faces and vertex-faces
//! of [`crate::mesh::refine::Pattern::MidEdge`].
//!
//! On the boundary the new boundary is the polygon of the boundary-edge midpoints, the
//! mid-edge (corner cutting at 1/2) curve rule.

pub use super::midpoint as edge_point;
