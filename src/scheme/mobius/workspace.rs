//! The star workspace of the vertex pass: the per-star arrays of a scheme's rule (the
//! images of the ring, the centroids of the faces around the star, the candidates in the
//! normalised frame; seed 000 §4.1 steps 2–3) and the tangent polygon of its canonical form
//! (§4.2) live in the caller's point scratch rather than on the stack, so that the depth of
//! a Möbius step does not grow with the valence cap (docs/firmware.md, "Stack").
//!
//! Each chunk of the vertex pass owns [`STAR_ARRAYS`] arrays of the level's largest valence;
//! each chunk of the face blends, the F4 points and sort keys of its largest face's
//! face-point chain (seed 000 §4.4.3) in the same share; a pass has at most
//! [`crate::exec::MAX_CHUNKS`] chunks and never more than it has elements
//! ([`crate::exec::chunk_count`]), so a small mesh's workspace is small.
//! [`workspace_points`] is what the scratch-size queries add for it, and [`spoke_u32s`] the
//! spoke workspace of the `u32` scratch (a star's spokes, per chunk). The arrays are scratch,
//! overwritten star by star: a rule writes every entry it reads, so no value depends on the
//! scratch's contents or on the chunking.

use crate::error::{Error, Result, Status};
use crate::exec::MAX_CHUNKS;
use crate::mesh::{internal, Topology};
use crate::point::Point;

use super::form::SPOKE_U32S;

/// The per-star arrays one chunk holds: the tangent polygon of the star's canonical form
/// (the last, [`super::vertex_pass::Part::take_stars`]; seed 000 §4.2) and the rule's:
/// Catmull–Clark's ring images, face centroids and candidates (Loop and Butterfly use two,
/// Akleman's operators one). A pass that runs alone on the step (the guard's sphericity
/// pass, the ears, Doo–Sabin's missing corners) holds the whole workspace.
pub(super) const STAR_ARRAYS: usize = 4;

/// The points of the star workspace of a step on a level whose largest valence is
/// `max_valence`, whose largest face has `max_face` corners and which has at most
/// `elements` vertices and faces: for each of at most `min(`[`MAX_CHUNKS`]`, elements)`
/// chunks (the most chunks a pass over the level's vertices or faces makes,
/// [`crate::exec::chunk_count`]), [`STAR_ARRAYS`] arrays of the valence for the vertex
/// pass, or the face-point chain's arrays of the largest face for the face blends
/// ([`crate::blend::work_points`]), whichever is larger.
///
/// # Errors
/// [`Status::SizeOverflow`].
pub(crate) fn workspace_points(
    max_valence: usize,
    max_face: usize,
    elements: usize,
) -> Result<usize> {
    let chunks = elements.clamp(1, MAX_CHUNKS);
    let star = max_valence
        .checked_mul(STAR_ARRAYS)
        .ok_or(Error::new(Status::SizeOverflow))?;
    // `max_face` is at most the face-size cap, so the sum cannot overflow.
    let face = crate::blend::work_points(max_face.min(crate::MAX_FACE_SIZE));
    star.max(face)
        .checked_mul(chunks)
        .ok_or(Error::new(Status::SizeOverflow))
}

/// The `u32` entries of the spoke workspace of a step on a level of at most `vertices`
/// vertices whose largest valence is `max_valence`: the spokes of one star
/// ([`super::form::Spokes`], [`SPOKE_U32S`] entries a spoke) for each chunk, as
/// [`workspace_points`] counts them.
///
/// # Errors
/// [`Status::SizeOverflow`].
pub(crate) fn spoke_u32s(max_valence: usize, vertices: usize) -> Result<usize> {
    let chunks = vertices.clamp(1, MAX_CHUNKS);
    max_valence
        .checked_mul(SPOKE_U32S * chunks)
        .ok_or(Error::new(Status::SizeOverflow))
}

/// The largest valence of `topo` (0 without vertices), which sizes its step's workspace.
pub(super) fn max_valence(topo: &Topology<'_, '_>) -> Result<usize> {
    let mut m = 0;
    for v in 0..topo.num_vertices() as u32 {
        m = m.max(topo.valence(v)?);
    }
    Ok(m)
}

/// The first `n` points of `*work`, which keeps the rest; an internal error when it is
/// shorter (the step's size check makes every chunk's share long enough).
pub(super) fn take<'a>(work: &mut &'a mut [Point], n: usize) -> Result<&'a mut [Point]> {
    let (a, b) = core::mem::take(work)
        .split_at_mut_checked(n)
        .ok_or(internal())?;
    *work = b;
    Ok(a)
}
