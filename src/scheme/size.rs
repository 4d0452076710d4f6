//! The exact output sizes of one step, checked before anything is written: the sizes of the
//! scheme's refinement pattern ([`crate::mesh::refine::pattern_size`]) on the faces the scheme
//! accepts.

use super::Scheme;
use crate::error::{Error, Result, Status};
use crate::mesh::refine::pattern_size;
use crate::mesh::{MeshSizes, Topology};

/// The exact output sizes of one step of `scheme` on `topo`, checked before anything is
/// written.
///
/// # Errors
/// [`Status::UnsupportedFaceType`] naming the first face the scheme does not accept (Loop and
/// Modified Butterfly: non-triangles; Kobbelt: non-quads); [`Status::SizeOverflow`];
/// [`Status::ValenceTooHigh`] for an output vertex above [`crate::MAX_VALENCE`]
/// ([`crate::mesh::refine::pattern_size`]).
pub(crate) fn step_size(scheme: Scheme, topo: &Topology<'_, '_>) -> Result<MeshSizes> {
    if scheme == Scheme::Kobbelt {
        for f in 0..topo.num_faces() as u32 {
            if topo.face_size(f)? != 4 {
                return Err(Error::at(Status::UnsupportedFaceType, f));
            }
        }
    }
    pattern_size(scheme.pattern(), topo)
}
