//! The fold census of an edited result (seed 001 §4.4 editing; the decision is in
//! docs/differential.md "Editing"): what an edit did to the orientation of the surface,
//! measured against the unedited reconstruction of the same call.
//!
//! * A **folded face** is an output face whose normal turned by more than 90° from the same
//!   face of the unedited result (`n_edited · n_unedited < 0`): the face is turned over.
//! * A **folded edge** is an interior edge whose two faces' normals are more than 90° apart
//!   (`n_f · n_g < 0`: the surface doubles back across the edge), where they are not in the
//!   unedited result. Edges already that sharp without the edit are not the edit's doing.
//!
//! Faces with a zero normal (zero area) have no orientation and count as neither. The counts
//! and the first element of each go to the report; with the `strict` option a fold is an
//! error ([`Status::FoldedSurface`](crate::Status::FoldedSurface)).

use crate::error::{Result, NO_ELEMENT};
use crate::mesh::{internal, Topology, NONE};
use crate::point::{add, cross, dot, sub, Point};

/// The folds found by [`census`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Folds {
    /// Folded faces.
    pub(super) faces: u32,
    /// The lowest folded face, or [`NO_ELEMENT`].
    pub(super) first_face: u32,
    /// Folded edges.
    pub(super) edges: u32,
    /// The folded edge with the lowest `(a, b)`, `a < b`, or `[NO_ELEMENT; 2]`.
    pub(super) first_edge: [u32; 2],
    /// The lower face of that edge, or [`NO_ELEMENT`].
    pub(super) first_edge_face: u32,
}

impl Folds {
    /// The face a strict-mode error names: the first folded face, else the lower face of the
    /// first folded edge; `None` without folds.
    pub(super) fn culprit(&self) -> Option<u32> {
        if self.faces > 0 {
            Some(self.first_face)
        } else if self.edges > 0 {
            Some(self.first_edge_face)
        } else {
            None
        }
    }
}

/// The (unnormalised) normal of face `f` of `topo` with the positions `pos`: the sum of its
/// fan triangles' cross products (for a triangle, `(b − a) × (c − a)`).
fn face_normal(topo: &Topology<'_, '_>, pos: &[Point], f: u32) -> Result<Point> {
    let vs = topo.face_vertices(f)?;
    let at = |k: usize| -> Result<Point> {
        let v = *vs.get(k).ok_or(internal())?;
        pos.get(v as usize).copied().ok_or(internal())
    };
    let p0 = at(0)?;
    let mut n = [0.0; 3];
    for k in 1..vs.len().saturating_sub(1) {
        n = add(n, cross(sub(at(k)?, p0), sub(at(k + 1)?, p0)));
    }
    Ok(n)
}

/// Counts the folds of `edited` against `reference` on the connectivity of `topo` (both
/// position arrays are indexed by `topo`'s vertices).
pub(super) fn census(
    topo: &Topology<'_, '_>,
    edited: &[Point],
    reference: &[Point],
) -> Result<Folds> {
    let mut r = Folds {
        faces: 0,
        first_face: NO_ELEMENT,
        edges: 0,
        first_edge: [NO_ELEMENT; 2],
        first_edge_face: NO_ELEMENT,
    };
    for f in 0..topo.num_faces() as u32 {
        let a = face_normal(topo, edited, f)?;
        let b = face_normal(topo, reference, f)?;
        if dot(a, b) < 0.0 {
            r.faces += 1;
            r.first_face = r.first_face.min(f);
        }
    }
    for e in 0..topo.num_edges() as u32 {
        let h = topo.edge_half_edge(e)?;
        let t = topo.twin(h)?;
        if t == NONE {
            continue;
        }
        let (f, g) = (topo.face(h)?, topo.face(t)?);
        let sharp = |pos: &[Point]| -> Result<bool> {
            Ok(dot(face_normal(topo, pos, f)?, face_normal(topo, pos, g)?) < 0.0)
        };
        if sharp(edited)? && !sharp(reference)? {
            r.edges += 1;
            let (a, b) = topo.edge_vertices(e)?;
            let pair = [a.min(b), a.max(b)];
            if r.first_edge[0] == NO_ELEMENT || pair < r.first_edge {
                r.first_edge = pair;
                r.first_edge_face = f.min(g);
            }
        }
    }
    Ok(r)
}
