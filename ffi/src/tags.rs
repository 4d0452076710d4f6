//! Exports of sharp-feature subdivision (`nlsubdiv::scheme::{plan_tagged, subdivide_tagged}`):
//! the mesh path of `mesh.rs` with crease and corner tags, OpenSubdiv's conventions.
//!
//! Tags name edges by their two vertices, so a host passes its own feature lines without
//! knowing the library's edge numbering. They are data of the input mesh, like its index
//! arrays, and travel in their own read-only struct (`nls_tags`) next to the mesh view; the
//! options struct stays plain values. The tagged calls with no tags are the untagged calls,
//! bit for bit.

use nlsubdiv::mesh::MAX_COUNT;
use nlsubdiv::scheme::{CreaseMethod, Tags};
use nlsubdiv::Status;

use crate::guard::check_ptr;
use crate::mesh::{
    nls_mesh_buffers, nls_mesh_sizes, nls_mesh_view, nls_plan, nls_scratch, nls_subdivide_options,
    nls_subdivide_report, plan_body, read_arg, slice, store, subdivide_body, RawMesh, Span,
};
use crate::primitives::run;

/// Crease method: every semi-sharp value decreases by one per level (OpenSubdiv
/// `Sdc::Options::CREASE_UNIFORM`; the default).
pub const NLS_CREASE_UNIFORM: u32 = 0;
/// Crease method: Chaikin's rule, an edge's child takes 3/4 of its value and 1/4 of the mean
/// of the other semi-sharp edges at the shared vertex, minus one (OpenSubdiv
/// `Sdc::Options::CREASE_CHAIKIN`).
pub const NLS_CREASE_CHAIKIN: u32 = 1;

/// Sharp-feature tags of a mesh, read only: crease edges as vertex pairs with their
/// sharpness, corner vertices with theirs, and the crease method. Sharpness follows
/// OpenSubdiv: 0 smooth, positive semi-sharp (the feature fades over about that many
/// levels), 10 or more infinitely sharp; finite and non-negative, stored in single precision.
/// Zero-initialised, the struct holds no tags and the uniform method.
///
/// Errors name a tag by its index: crease `i` is element `i`, corner `j` is element
/// `crease_count + j`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct nls_tags {
    /// `2 * crease_count` vertex indices: crease `i` joins `crease_vertices[2 i]` and
    /// `crease_vertices[2 i + 1]` (either order), which must be the two ends of an edge.
    pub crease_vertices: *const u32,
    /// `crease_count` sharpness values.
    pub crease_sharpness: *const f64,
    /// Number of tagged edges.
    pub crease_count: usize,
    /// `corner_count` vertex indices.
    pub corner_vertices: *const u32,
    /// `corner_count` sharpness values.
    pub corner_sharpness: *const f64,
    /// Number of tagged vertices.
    pub corner_count: usize,
    /// `NLS_CREASE_UNIFORM` or `NLS_CREASE_CHAIKIN`.
    pub method: u32,
}

/// The tags of a call, read from the caller's struct.
#[derive(Clone, Copy)]
pub(crate) struct RawTags {
    tags: nls_tags,
    method: CreaseMethod,
}

impl RawTags {
    /// Reads the struct and its method.
    ///
    /// # Safety
    /// `p` is NULL or points to a readable `nls_tags`.
    unsafe fn read(p: *const nls_tags) -> Result<RawTags, Status> {
        // SAFETY: by the caller's contract.
        let tags = unsafe { read_arg(p) }?;
        // The method and the counts are checked by `check_tags`, after the out-pointers: a
        // refusal here would write `out_element` before it is known to point outside the
        // call's buffers.
        let method = match tags.method {
            NLS_CREASE_CHAIKIN => CreaseMethod::Chaikin,
            _ => CreaseMethod::Uniform,
        };
        Ok(RawTags { tags, method })
    }

    /// The method and the counts: `InvalidArgument` for an unknown method, `SizeOverflow`
    /// for a count above `MAX_COUNT`.
    fn check_values(&self) -> Result<(), Status> {
        if !matches!(self.tags.method, NLS_CREASE_UNIFORM | NLS_CREASE_CHAIKIN) {
            return Err(Status::InvalidArgument);
        }
        if self.tags.crease_count > MAX_COUNT || self.tags.corner_count > MAX_COUNT {
            return Err(Status::SizeOverflow);
        }
        Ok(())
    }

    fn is_empty(&self) -> bool {
        self.tags.crease_count == 0 && self.tags.corner_count == 0
    }

    /// `2 * crease_count` (at most `2 * MAX_COUNT`: no overflow).
    fn pair_entries(&self) -> usize {
        self.tags.crease_count.saturating_mul(2)
    }
}

/// The byte ranges of the four tag arrays (empty without tags, or for an array that fails its
/// check), for the overlap checks of the calls.
pub(crate) fn tag_spans(tags: Option<&RawTags>) -> [Span; 4] {
    let Some(r) = tags else {
        return [Span::of::<u32>(core::ptr::null(), 0); 4];
    };
    let t = &r.tags;
    [
        Span::checked(t.crease_vertices, r.pair_entries()),
        Span::checked(t.crease_sharpness, t.crease_count),
        Span::checked(t.corner_vertices, t.corner_count),
        Span::checked(t.corner_sharpness, t.corner_count),
    ]
}

/// The byte ranges of the four tag arrays as given (see [`Span::raw`]), for the out-element
/// decision; none without tags.
pub(crate) fn tag_raw_spans(tags: &Option<RawTags>) -> [Span; 4] {
    let Some(r) = tags else {
        return [Span::EMPTY; 4];
    };
    let t = &r.tags;
    [
        Span::raw(t.crease_vertices, r.pair_entries()),
        Span::raw(t.crease_sharpness, t.crease_count),
        Span::raw(t.corner_vertices, t.corner_count),
        Span::raw(t.corner_sharpness, t.corner_count),
    ]
}

/// Checks the method, the counts and the four tag pointers (NULL with a non-zero count,
/// alignment, size).
pub(crate) fn check_tags(tags: Option<&RawTags>) -> Result<(), Status> {
    let Some(r) = tags else {
        return Ok(());
    };
    r.check_values()?;
    let t = &r.tags;
    check_ptr(t.crease_vertices, r.pair_entries())?;
    check_ptr(t.crease_sharpness, t.crease_count)?;
    check_ptr(t.corner_vertices, t.corner_count)?;
    check_ptr(t.corner_sharpness, t.corner_count)
}

/// The `uint32_t` scratch of planning `mesh` with `tags`, from the counts alone: the
/// topology's, plus one entry per vertex and per corner to find repeated tags when there is
/// a tag (`scheme::plan_scratch_size_tagged`).
pub(crate) fn plan_need(mesh: &RawMesh, tags: Option<&RawTags>) -> Result<usize, Status> {
    let topo = mesh.topology_need()?;
    match tags {
        Some(t) if !t.is_empty() => topo
            .checked_add(mesh.vertex_count())
            .and_then(|n| n.checked_add(mesh.index_count()))
            .ok_or(Status::SizeOverflow),
        _ => Ok(topo),
    }
}

/// The core's tags.
///
/// # Safety
/// [`check_tags`] passed, and the arrays are readable and not written while the tags live.
pub(crate) unsafe fn tags_of<'a>(tags: Option<&RawTags>) -> Result<Tags<'a>, Status> {
    let Some(r) = tags else {
        return Ok(Tags::new());
    };
    let t = &r.tags;
    // SAFETY: checked (NULL, alignment, size) and readable by the caller's contract; a pair
    // of `uint32_t` has the layout of `[u32; 2]` (size 8, alignment 4), so the pair array is
    // `crease_count` such pairs.
    let (pairs, crease_s, corners, corner_s) = unsafe {
        (
            slice(t.crease_vertices.cast::<[u32; 2]>(), t.crease_count),
            slice(t.crease_sharpness, t.crease_count),
            slice(t.corner_vertices, t.corner_count),
            slice(t.corner_sharpness, t.corner_count),
        )
    };
    Ok(Tags::new()
        .creases(pairs, crease_s)
        .corners(corners, corner_s)
        .method(r.method))
}

/// The `uint32_t` scratch `nls_mesh_plan_tagged` needs for `mesh` with `tags`: that of
/// `nls_mesh_plan_scratch_size`, plus `vertex_count + index_count` entries when there is a
/// tag. Depends on the counts only: no array of the mesh or the tags is read.
///
/// @param mesh the input mesh.
/// @param tags the tags.
/// @param out_scratch_u32 receives the number of `uint32_t` entries.
/// @return `NLS_STATUS_SIZE_OVERFLOW` (a count above `UINT32_MAX − 1`),
/// `NLS_STATUS_INVALID_ARGUMENT` (a bad stride or crease method), `NLS_STATUS_NULL_PARAMETER`,
/// `NLS_STATUS_MISALIGNED_POINTER`, else `NLS_STATUS_OK`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mesh_plan_scratch_size_tagged(
    mesh: *const nls_mesh_view,
    tags: *const nls_tags,
    out_scratch_u32: *mut usize,
) -> Status {
    run(|| {
        check_ptr(out_scratch_u32.cast_const(), 1)?;
        // SAFETY: the caller passes NULL or readable structs.
        let (mesh, tags) = unsafe { (RawMesh::read(mesh)?, RawTags::read(tags)?) };
        tags.check_values()?;
        let need = plan_need(&mesh, Some(&tags))?;
        // SAFETY: checked above.
        unsafe { store(out_scratch_u32, need) };
        Ok(())
    })
}

/// `nls_mesh_plan` for a mesh with sharp-feature tags: Loop and Catmull–Clark, linear, with
/// OpenSubdiv's rules for creases, corners and darts (boundary edges stay infinitely sharp,
/// `VTX_BOUNDARY_EDGE_ONLY`); Modified Butterfly and Kobbelt, linear, with their 4-point
/// boundary rule along the creases (`docs/creases.md`). `scratch_u32` holds at least what
/// `nls_mesh_plan_scratch_size_tagged` gives and overlaps neither the mesh nor the tags. With
/// no tags (both counts 0) this is `nls_mesh_plan`.
///
/// Errors, in this order: `NLS_STATUS_NULL_PARAMETER` / `NLS_STATUS_MISALIGNED_POINTER` for
/// the structs; `NLS_STATUS_ALIASING_BUFFERS` for an out-pointer into a buffer of the call
/// (the tag arrays included); the options (`NLS_STATUS_INVALID_ARGUMENT`, then
/// `NLS_STATUS_SCHEME_NOT_BUILT` for a scheme or form left out of this build); the mesh's
/// pointers; `NLS_STATUS_INVALID_ARGUMENT` for an unknown crease method,
/// `NLS_STATUS_SIZE_OVERFLOW` for a tag count above `UINT32_MAX − 1`, the tag arrays'
/// pointers; a tag array that overlaps the scratch (`NLS_STATUS_ALIASING_BUFFERS`); then
/// `NLS_STATUS_TAGS_NOT_SUPPORTED` (no element) for tags with a scheme other than Loop,
/// Catmull–Clark, Modified Butterfly and Kobbelt (linear, or Möbius with
/// `NLS_SUBDIVIDE_MOBIUS`); then the
/// validation of the mesh (as `nls_mesh_plan`); then, tag by tag, creases first (the
/// element names the tag: crease `i` is `i`, corner `j` is `crease_count + j`):
/// `NLS_STATUS_INDEX_OUT_OF_RANGE` (a vertex not below `vertex_count`),
/// `NLS_STATUS_INVALID_SHARPNESS` (NaN, negative or infinite),
/// `NLS_STATUS_TAG_NOT_AN_EDGE` (the two vertices of a crease share no edge),
/// `NLS_STATUS_REPEATED_TAG` (an edge or vertex tagged twice).
///
/// @param mesh the input mesh.
/// @param options scheme, flags, levels.
/// @param tags the tags (read only).
/// @param scratch_u32 `uint32_t` scratch for the validation.
/// @param scratch_u32_capacity entries of `scratch_u32`.
/// @param out_plan receives the plan, on success only.
/// @param out_element may be NULL; otherwise receives, on failure only, the element named
/// above or by `nls_mesh_plan`, or `NLS_NO_ELEMENT`.
/// @return `NLS_STATUS_OK` or an error above.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mesh_plan_tagged(
    mesh: *const nls_mesh_view,
    options: *const nls_subdivide_options,
    tags: *const nls_tags,
    scratch_u32: *mut u32,
    scratch_u32_capacity: usize,
    out_plan: *mut nls_plan,
    out_element: *mut u32,
) -> Status {
    // SAFETY: the contract of `nls_mesh_plan`, with the tags read.
    unsafe {
        plan_body(
            mesh,
            options,
            Some(tags),
            scratch_u32,
            scratch_u32_capacity,
            out_plan,
            out_element,
        )
    }
}

/// `nls_mesh_subdivide` for a mesh with sharp-feature tags (see `nls_mesh_plan_tagged`): the
/// tags are carried to the child edges and vertices level by level inside the call (child
/// edges of a crease take the decayed sharpness, a corner's vertex its decremented value), so
/// `k` levels of a tagged mesh are one call of `k` levels. Buffer sizes come from
/// `nls_mesh_plan_tagged` with the same arguments; no buffer may overlap the mesh, the tags
/// or another buffer. With no tags this is `nls_mesh_subdivide`, bit for bit.
///
/// @param mesh the input mesh.
/// @param options scheme, flags, levels.
/// @param tags the tags (read only).
/// @param scratch at least the scratch of `nls_mesh_plan_tagged`.
/// @param out the output buffers, at least the plan's output sizes.
/// @param out_sizes receives the sizes written (and the sizes needed on
/// `NLS_STATUS_BUFFER_TOO_SMALL` for an output buffer).
/// @param out_report may be NULL; receives the report (no fallbacks for the linear rules).
/// @param out_element may be NULL; otherwise receives, on failure only, the element of the
/// error (see `nls_mesh_plan_tagged` and `nls_mesh_subdivide`), or `NLS_NO_ELEMENT`.
/// @return `NLS_STATUS_OK`, the errors of `nls_mesh_plan_tagged` and of
/// `nls_mesh_subdivide`.
///
/// Stack on Cortex-M4F: at most 8,192 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mesh_subdivide_tagged(
    mesh: *const nls_mesh_view,
    options: *const nls_subdivide_options,
    tags: *const nls_tags,
    scratch: *const nls_scratch,
    out: *const nls_mesh_buffers,
    out_sizes: *mut nls_mesh_sizes,
    out_report: *mut nls_subdivide_report,
    out_element: *mut u32,
) -> Status {
    // SAFETY: the contract of `nls_mesh_subdivide`, with the tags read.
    unsafe {
        subdivide_body(
            mesh,
            options,
            Some(tags),
            scratch,
            out,
            out_sizes,
            out_report,
            out_element,
        )
    }
}

/// The tags of a tagged export (`Some`), read; `None` for the untagged exports.
///
/// # Safety
/// A `Some` pointer is NULL or points to a readable `nls_tags`.
pub(crate) unsafe fn read_tags(p: Option<*const nls_tags>) -> Result<Option<RawTags>, Status> {
    match p {
        // SAFETY: by the caller's contract.
        Some(p) => unsafe { RawTags::read(p) }.map(Some),
        None => Ok(None),
    }
}
