//! [`Pattern::CornerCut`](super::Pattern::CornerCut) (Doo–Sabin): one new point per corner (corner
//! `h` → point `h`), then the isolated vertices. Faces: the `F` F-faces (a face's corner points in
//! face order), the E-faces of the interior edges in edge order `(c(next h), c(h), c(next t),
//! c(t))` with `h` the `min → max` half-edge and `t` its twin, the V-faces of the interior vertices
//! in vertex order (the corners of the star, counter-clockwise). No faces around boundary edges and
//! vertices (CGAL's `DQQ_1step`), so the new boundary runs through the corner points of the
//! boundary faces.

use super::counts::{some, LevelCounts};
use super::dual_checks::dual_face_sizes;
use super::face_writer::FaceWriter;
use super::Parent;
use crate::error::Result;
use crate::mesh::{cadd, cmul, internal, MeshSizes, Topology, NONE};

/// The output sizes: `H + I` vertices; `F + E_i + V_i` faces.
pub(super) fn size(topo: &Topology<'_, '_>) -> Result<MeshSizes> {
    dual_face_sizes(topo, 0)?;
    let (f, h, iso) = (
        topo.num_faces(),
        topo.num_half_edges(),
        topo.num_isolated_vertices(),
    );
    Ok(MeshSizes {
        vertices: cadd(h, iso)?,
        faces: cadd(
            cadd(f, topo.num_interior_edges())?,
            topo.num_interior_vertices(),
        )?,
        indices: cadd(
            cadd(h, cmul(topo.num_interior_edges(), 4)?)?,
            topo.interior_valence_sum(),
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
            w.push(h)?;
        }
        w.end_face()?;
    }
    for e in 0..n.e {
        let h = topo.edge_half_edge(e)?;
        let t = topo.twin(h)?;
        if t == NONE {
            continue;
        }
        w.face(&[topo.next(h)?, h, topo.next(t)?, t])?;
    }
    for v in 0..n.v {
        if topo.is_isolated(v)? || topo.is_boundary_vertex(v)? {
            continue;
        }
        for s in topo.star(v) {
            w.push(s.half_edge)?;
        }
        w.end_face()?;
    }
    w.finish(sizes)
}

/// The counts of the next level. Corner points at interior vertices: interior, valence 4.
/// At a boundary vertex with k faces: valence 2 + (interior edges of the face at the
/// vertex), which sums to 2k + 2(k − 1). New boundary edges: the old ones plus one per
/// interior edge at a boundary vertex (Σ_b (valence − 2)).
pub(super) fn next(s: &LevelCounts) -> Result<LevelCounts> {
    let (ei, vi) = (s.ei(), s.vi());
    let sb4 = cmul(s.sb, 4)?;
    let eb6 = cmul(s.eb, 6)?;
    Ok(LevelCounts {
        v: cadd(s.h, s.iso)?,
        f: cadd(cadd(s.f, ei)?, vi)?,
        h: cadd(cadd(s.h, cmul(ei, 4)?)?, s.si)?,
        e: cadd(s.h, cmul(ei, 2)?)?,
        eb: s.sb.checked_sub(s.eb).ok_or(internal())?,
        iso: s.iso,
        si: cmul(s.si, 4)?,
        sb: sb4.checked_sub(eb6).ok_or(internal())?,
        max_vi: some(s.si > 0, 4),
        max_vb: some(s.eb > 0, 4),
        max_face: s.max_face.max(some(ei > 0, 4)).max(some(vi > 0, s.max_vi)),
        max_dt: 0,
    })
}
