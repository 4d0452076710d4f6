//! Per-vertex weights of the Möbius–linear spectrum (seed 000 §7.2) in the C ABI:
//! `nls_subdivide_options.linear_weights`, `vertex_count` doubles, the weight `u` of the
//! linear result at each input vertex (the convention of `linear_weight`, which they
//! replace). NULL keeps the global weight. The array is an input: it may overlap the other
//! inputs but no output, scratch or out-pointer. The values are checked by the core
//! (`nlsubdiv::scheme::VertexWeights::Linear`): NaN or outside `[0, 1]` is
//! `NLS_STATUS_INVALID_ARGUMENT` naming the vertex.

use nlsubdiv::scheme::VertexWeights;
use nlsubdiv::Status;

use crate::guard::check_ptr;
use crate::mesh::{nls_subdivide_options, slice, RawMesh, Span};

/// The weights' byte range as given, for the out-element decision: empty without weights
/// (or without options, which describe no buffer then), `None` when it cannot be named (the
/// options struct or the mesh view could not be read, so the length is unknown).
pub(crate) fn weight_raw_span(
    options: *const nls_subdivide_options,
    opts: &Result<nls_subdivide_options, Status>,
    mesh: &Result<RawMesh, Status>,
) -> Option<Span> {
    match (opts, mesh) {
        (Ok(o), _) if o.linear_weights.is_null() => Some(Span::EMPTY),
        (Ok(o), Ok(m)) => Some(Span::raw(o.linear_weights, m.vertex_count())),
        (Err(_), _) if options.is_null() => Some(Span::EMPTY),
        _ => None,
    }
}

/// The weights' byte range when it is a valid buffer (see [`Span::checked`]).
pub(crate) fn weight_span(opts: &nls_subdivide_options, mesh: &RawMesh) -> Span {
    Span::checked(opts.linear_weights, mesh.vertex_count())
}

/// Checks the weights pointer (alignment, size; NULL is no weights).
pub(crate) fn check_weights(opts: &nls_subdivide_options, mesh: &RawMesh) -> Result<(), Status> {
    if opts.linear_weights.is_null() {
        return Ok(());
    }
    check_ptr(opts.linear_weights, mesh.vertex_count())
}

/// The core's weights, `None` for NULL.
///
/// # Safety
/// [`check_weights`] passed, and the array is readable and not written while the weights
/// live.
pub(crate) unsafe fn weights_of<'a>(
    opts: &nls_subdivide_options,
    mesh: &RawMesh,
) -> Option<VertexWeights<'a>> {
    if opts.linear_weights.is_null() {
        return None;
    }
    // SAFETY: checked (alignment, size) and readable by the caller's contract.
    Some(VertexWeights::Linear(unsafe {
        slice(opts.linear_weights, mesh.vertex_count())
    }))
}
