//! [`Pattern::MidEdge`](super::Pattern::MidEdge) (Peters–Reif Simplest): one new point per edge
//! (its midpoint), then the `V_b` boundary vertices (in index order), then the isolated vertices.
//! Faces: the `F` face-faces (the points of the face's edges, in corner order), then one
//! vertex-face per referenced vertex in vertex order (the points of its spokes, counter-clockwise),
//! closed on the boundary by the vertex itself, so that the boundary polygon is refined at its edge
//! midpoints and the Euler characteristic is preserved.

use super::counts::{some, LevelCounts};
use super::dual_checks::dual_face_sizes;
use super::face_writer::FaceWriter;
use super::Parent;
use crate::error::Result;
use crate::mesh::{cadd, cmul, MeshSizes, Topology, NONE};

/// The output sizes: `E + V_b + I` vertices; `F + V_i + V_b` faces.
pub(super) fn size(topo: &Topology<'_, '_>) -> Result<MeshSizes> {
    dual_face_sizes(topo, 1)?;
    let (e, f, h, iso) = (
        topo.num_edges(),
        topo.num_faces(),
        topo.num_half_edges(),
        topo.num_isolated_vertices(),
    );
    let vb = topo.num_boundary_vertices();
    Ok(MeshSizes {
        vertices: cadd(cadd(e, vb)?, iso)?,
        faces: cadd(cadd(f, topo.num_interior_vertices())?, vb)?,
        indices: cadd(
            cadd(h, topo.interior_valence_sum())?,
            cadd(topo.boundary_valence_sum(), vb)?,
        )?,
    })
}

/// The faces (module docs).
pub(super) fn write(
    topo: &Topology<'_, '_>,
    n: Parent,
    sizes: &MeshSizes,
    offsets: &mut [u32],
    indices: &mut [u32],
) -> Result<()> {
    let mut w = FaceWriter::new(offsets, indices)?;
    for f in 0..n.f {
        for h in topo.face_half_edges(f)? {
            w.push(topo.edge(h)?)?;
        }
        w.end_face()?;
    }
    for v in 0..n.v {
        if topo.is_isolated(v)? {
            continue;
        }
        for s in topo.star(v) {
            w.push(s.edge)?;
        }
        let r = topo.boundary_vertex_rank(v)?;
        if r != NONE {
            w.push(n.e + r)?;
        }
        w.end_face()?;
    }
    w.finish(sizes)
}

/// The counts of the next level. Interior edge midpoints: interior, valence 4; boundary edge
/// midpoints: valence 4; old boundary vertices: valence 2.
pub(super) fn next(s: &LevelCounts) -> Result<LevelCounts> {
    let (ei, vi) = (s.ei(), s.vi());
    Ok(LevelCounts {
        v: cadd(cadd(s.e, s.eb)?, s.iso)?,
        f: cadd(cadd(s.f, vi)?, s.eb)?,
        h: cadd(cadd(s.h, s.si)?, cadd(s.sb, s.eb)?)?,
        e: cadd(s.h, cmul(s.eb, 2)?)?,
        eb: cmul(s.eb, 2)?,
        iso: s.iso,
        si: cmul(ei, 4)?,
        sb: cmul(s.eb, 6)?,
        max_vi: some(ei > 0, 4),
        max_vb: some(s.eb > 0, 4),
        max_face: s.max_face.max(s.max_vi).max(some(s.eb > 0, s.max_vb + 1)),
        max_dt: 0,
    })
}
