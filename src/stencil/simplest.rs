//! Peters and Reif's "simplest" subdivision scheme (1997), the mid-edge scheme: every new
//! vertex is the midpoint of an old edge; the new faces are the face-faces and vertex-faces
//! of [`crate::mesh::refine::Pattern::MidEdge`].
//!
//! On the boundary, each boundary vertex keeps its position and closes its vertex-face, so the
//! new boundary is the old boundary polygon refined at its edge midpoints (the linear
//! interpolating curve rule; the mid-edge polygon alone would never refine a boundary loop,
//! it has as many points as edges).

pub use crate::point::midpoint as edge_point;
