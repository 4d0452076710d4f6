//! Exports of differential-space subdivision (`nlsubdiv::differential`, seed 001): the
//! differential coordinates of a triangle mesh are subdivided (Loop, Modified Butterfly, or
//! DirMag on top of Modified Butterfly) and the surface is reconstructed once at the last
//! level by an iterative least-squares solve on caller scratch (`docs/differential.md`).
//!
//! A child module of the mesh exports so that it shares their structs and buffer checks
//! (mesh view, aliasing, `out_element`, sizes) without widening their visibility.

use nlsubdiv::differential::solve::SolveOptions;
use nlsubdiv::differential::{self as diff, DifferentialOptions, DifferentialReport, Stencil};
use nlsubdiv::mesh::MeshSizes;
use nlsubdiv::{Point, Status};

use super::{
    check_optional, check_out_pointers, named, nls_mesh_buffers, nls_mesh_sizes, nls_mesh_view,
    nls_plan, nls_scratch, out_raw_spans, read_arg, run_with_element, scratch_raw_spans, sizes_of,
    slice, store, too_small, Fail, RawMesh, RawOut, Span, NLS_MESH_BUFFER_SCRATCH_POINTS,
    NLS_MESH_BUFFER_SCRATCH_U32,
};
use crate::guard::{check_fp_env, check_ptr};
use crate::primitives::run;

/// Differential scheme: Loop on the differential coordinates (§3.3).
pub const NLS_DIFFERENTIAL_LOOP: u32 = 0;
/// Differential scheme: Modified Butterfly on the differential coordinates (the paper's
/// preferred stencil, §4.2).
pub const NLS_DIFFERENTIAL_BUTTERFLY: u32 = 1;
/// Differential scheme: DirMag (§3.4; mean-curvature magnitudes subdivided linearly, normals
/// on the sphere by normalised averaging) with the Modified Butterfly stencil for the first
/// `dirmag_levels` levels, plain Modified Butterfly on `Δ` after that.
pub const NLS_DIFFERENTIAL_DIRMAG: u32 = 2;

/// Options of `nls_differential_plan` and `nls_differential_subdivide`. Start from
/// `nls_differential_default_options`; later versions append fields whose defaults keep the
/// behaviour of this one. Plain data; the edit arrays are read, never kept.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct nls_differential_options {
    /// `NLS_DIFFERENTIAL_LOOP`, `_BUTTERFLY` or `_DIRMAG`.
    pub scheme: u32,
    /// Subdivision levels `k`, at most `NLS_MAX_LEVELS` (0 reconstructs the control mesh).
    pub levels: u32,
    /// `NLS_DIFFERENTIAL_DIRMAG` only: the first this many levels use DirMag (at least 1;
    /// the paper uses 1 or 2; values above `levels` act as `levels`). Must be 0 otherwise.
    pub dirmag_levels: u32,
    /// Iteration cap of the reconstruction (default 100); reaching it is
    /// `NLS_STATUS_NOT_CONVERGED`.
    pub max_iterations: u32,
    /// Relative residual of the reconstruction's normal equations to reach (default 1e-10);
    /// finite and ≥ 0.
    pub tolerance: f64,
    /// §4.4 editing: NULL, or `vertex_count` factors on the control vertices' mean curvatures.
    pub curvature_scale: *const f64,
    /// §4.4 editing: NULL, or `3*vertex_count` replacement normal directions of the control
    /// vertices (normalised by the library; a zero vector keeps the vertex's own normal).
    pub normals: *const f64,
    /// 0 or 1. With edits: a folded output (see the report's `folded_faces` and
    /// `folded_edges`) is `NLS_STATUS_FOLDED_SURFACE` naming the first folded face. Without
    /// edits it has no effect. Default 0.
    pub strict: u32,
}

/// What `nls_differential_subdivide` did. Written on success, on `NLS_STATUS_NOT_CONVERGED`
/// (then it says how far the solver got) and on `NLS_STATUS_FOLDED_SURFACE`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct nls_differential_report {
    /// Outer solver iterations run.
    pub iterations: u32,
    /// 1 when `relative_residual ≤ tolerance`, else 0.
    pub converged: u32,
    /// Anchor rows (one per closed component, boundary loop and isolated vertex).
    pub anchors: u32,
    /// DirMag outputs whose subdivided normal was too short to normalise.
    pub dirmag_degenerate: u32,
    /// Relative residual of the returned positions, recomputed at the end.
    pub relative_residual: f64,
    /// Relative residual of the warm start (the spatial subdivision).
    pub initial_residual: f64,
    /// With edits: output faces whose normal turned by more than 90° from the same face of
    /// the unedited reconstruction; 0 without edits.
    pub folded_faces: u32,
    /// The lowest such face, or `NLS_NO_ELEMENT`.
    pub first_folded_face: u32,
    /// With edits: interior output edges whose two faces' normals are more than 90° apart
    /// where they are not in the unedited reconstruction; 0 without edits.
    pub folded_edges: u32,
    /// The lowest such edge as its two vertices `a < b`, or `NLS_NO_ELEMENT` twice.
    pub first_folded_edge: [u32; 2],
}

fn report_of(r: &DifferentialReport) -> nls_differential_report {
    nls_differential_report {
        iterations: r.solve.iterations,
        converged: u32::from(r.solve.converged),
        anchors: r.anchors,
        dirmag_degenerate: r.dirmag_degenerate,
        relative_residual: r.solve.relative_residual,
        initial_residual: r.solve.initial_residual,
        folded_faces: r.folded_faces,
        first_folded_face: r.first_folded_face,
        folded_edges: r.folded_edges,
        first_folded_edge: r.first_folded_edge,
    }
}

/// Writes the defaults: Loop, 1 level, no DirMag, 100 iterations, tolerance 1e-10, no edits,
/// not strict.
/// `NLS_STATUS_NULL_PARAMETER` / `NLS_STATUS_MISALIGNED_POINTER` for a bad `out_options`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_differential_default_options(
    out_options: *mut nls_differential_options,
) -> Status {
    run(|| {
        check_ptr(out_options.cast_const(), 1)?;
        let d = SolveOptions::default();
        // SAFETY: checked non-NULL and aligned; writable by the caller's contract.
        unsafe {
            store(
                out_options,
                nls_differential_options {
                    scheme: NLS_DIFFERENTIAL_LOOP,
                    levels: 1,
                    dirmag_levels: 0,
                    max_iterations: d.max_iterations,
                    tolerance: d.tolerance,
                    curvature_scale: core::ptr::null(),
                    normals: core::ptr::null(),
                    strict: 0,
                },
            )
        };
        Ok(())
    })
}

/// The parsed options and the byte ranges of the edit arrays.
struct Parsed<'a> {
    opts: DifferentialOptions<'a>,
    edits: [Span; 2],
}

/// Checks and converts the options.
///
/// # Safety
/// `p` is NULL or points to a readable `nls_differential_options` whose edit pointers, when
/// not NULL, are readable for `vertex_count` (`3*vertex_count`) doubles during `'a`.
unsafe fn parse<'a>(
    o: Result<nls_differential_options, Status>,
    vertex_count: usize,
) -> Result<Parsed<'a>, Status> {
    let o = o?;
    let (stencil, dirmag) = match o.scheme {
        NLS_DIFFERENTIAL_LOOP => (Stencil::Loop, false),
        NLS_DIFFERENTIAL_BUTTERFLY => (Stencil::ModifiedButterfly, false),
        NLS_DIFFERENTIAL_DIRMAG => (Stencil::ModifiedButterfly, true),
        _ => return Err(Status::InvalidArgument),
    };
    if dirmag != (o.dirmag_levels > 0) {
        return Err(Status::InvalidArgument);
    }
    if o.levels > super::NLS_MAX_LEVELS || !(o.tolerance.is_finite() && o.tolerance >= 0.0) {
        return Err(Status::InvalidArgument);
    }
    let scale_n = if o.curvature_scale.is_null() {
        0
    } else {
        vertex_count
    };
    let normal_n = if o.normals.is_null() { 0 } else { vertex_count };
    let strict = crate::guard::flag(o.strict)?;
    check_ptr(o.curvature_scale, scale_n)?;
    check_ptr(o.normals.cast::<Point>(), normal_n)?;
    // SAFETY: checked (alignment, size); readable by the caller's contract.
    let (scale, normals) = unsafe {
        (
            slice(o.curvature_scale, scale_n),
            slice(o.normals.cast::<Point>(), normal_n),
        )
    };
    let solve = SolveOptions {
        tolerance: o.tolerance,
        max_iterations: o.max_iterations,
        ..SolveOptions::default()
    };
    Ok(Parsed {
        opts: DifferentialOptions {
            stencil,
            levels: o.levels as usize,
            dirmag_levels: o.dirmag_levels as usize,
            solve,
            curvature_scale: (!o.curvature_scale.is_null()).then_some(scale),
            normals: (!o.normals.is_null()).then_some(normals),
            strict,
        },
        edits: [
            Span::of(o.curvature_scale, scale_n),
            Span::of(o.normals.cast::<Point>(), normal_n),
        ],
    })
}

/// The byte ranges of the two edit arrays as given, for the out-element decision: their
/// length is the vertex count of the view at `mesh`, so an edit array cannot be named when
/// the view cannot be read (see [`named`]).
///
/// # Safety
/// `mesh` is NULL or points to a readable `nls_mesh_view`.
unsafe fn edit_raw_spans(
    p: *const nls_differential_options,
    opts: &Result<nls_differential_options, Status>,
    mesh: *const nls_mesh_view,
) -> [Option<Span>; 2] {
    let Ok(o) = opts else {
        return named(p, opts, |_| [Span::EMPTY; 2]);
    };
    // SAFETY: by the caller's contract.
    let view = unsafe { read_arg(mesh) };
    let array = |q: *const f64, per_vertex: usize| match (q.is_null(), &view) {
        (true, _) => Some(Span::EMPTY),
        (false, Ok(v)) => Some(Span::raw(q, v.vertex_count.saturating_mul(per_vertex))),
        (false, Err(_)) => None,
    };
    [array(o.curvature_scale, 1), array(o.normals, 3)]
}

/// Validates the mesh (triangles only) and the options and plans `nls_differential_subdivide`:
/// the exact output sizes (those of the spatial Loop or Modified Butterfly subdivision) and
/// the exact scratch it needs.
///
/// `scratch_u32` holds at least the entries of `nls_mesh_plan_scratch_size` (the input's
/// topology) and must not overlap the mesh or the edit arrays.
///
/// @param mesh the input mesh (positions may be strided).
/// @param options the differential options.
/// @param scratch_u32 `uint32_t` scratch for the validation.
/// @param scratch_u32_capacity entries of `scratch_u32`.
/// @param out_plan receives the plan, on success only.
/// @param out_element may be NULL; otherwise receives, on failure only, the element at fault
/// (as for `nls_mesh_plan`), `NLS_MESH_BUFFER_SCRATCH_U32` on `NLS_STATUS_BUFFER_TOO_SMALL`,
/// or `NLS_NO_ELEMENT`.
/// @return `NLS_STATUS_OK`; the validation errors of `nls_mesh_plan`;
/// `NLS_STATUS_UNSUPPORTED_FACE_TYPE` naming the first face that is not a triangle;
/// `NLS_STATUS_INVALID_ARGUMENT` (unknown scheme, `dirmag_levels` not matching the scheme,
/// more than `NLS_MAX_LEVELS` levels, a tolerance that is not finite and ≥ 0, `strict` not 0
/// or 1, a bad stride); `NLS_STATUS_SCHEME_NOT_BUILT` when this build of the library leaves
/// out differential-space subdivision or the scheme of `options.scheme` (Cargo features
/// `differential` and `butterfly`); `NLS_STATUS_NON_FINITE_INPUT` naming the vertex of a
/// non-finite edit value; `NLS_STATUS_NUMERICAL_FAILURE` for a mesh whose size the normal equations cannot
/// represent (largest bounding-box side below 1e-140, or a coordinate above 1e140);
/// `NLS_STATUS_BUFFER_TOO_SMALL`; `NLS_STATUS_NULL_PARAMETER`,
/// `NLS_STATUS_MISALIGNED_POINTER`, `NLS_STATUS_ALIASING_BUFFERS` (also an out-pointer into a
/// buffer of the call), `NLS_STATUS_FP_ENVIRONMENT`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_differential_plan(
    mesh: *const nls_mesh_view,
    options: *const nls_differential_options,
    scratch_u32: *mut u32,
    scratch_u32_capacity: usize,
    out_plan: *mut nls_plan,
    out_element: *mut u32,
) -> Status {
    run_with_element(out_element, |element| {
        // SAFETY: the caller passes NULL or readable structs.
        let (mesh_r, opts_r) = unsafe { (RawMesh::read(mesh), read_arg(options)) };
        // SAFETY: the caller passes NULL or a readable view.
        let [a, b, c] = unsafe { RawMesh::named(mesh, &mesh_r) };
        // SAFETY: the caller passes NULL or a readable view.
        let [d, e] = unsafe { edit_raw_spans(options, &opts_r, mesh) };
        let su = Some(Span::raw(scratch_u32.cast_const(), scratch_u32_capacity));
        element.close_unless_clear(&[Span::of_one(out_plan)], &[a, b, c, d, e, su]);
        let mesh = mesh_r?;
        check_ptr(out_plan.cast_const(), 1)?;
        check_optional(out_element)?;
        // SAFETY: the option's arrays are readable by the caller's contract.
        let parsed = unsafe { parse(opts_r, mesh.vertex_count()) }?;
        let [a, b, c] = mesh.spans();
        let [e0, e1] = parsed.edits;
        let su = Span::checked(scratch_u32.cast_const(), scratch_u32_capacity);
        check_out_pointers(
            &[Span::of(out_plan.cast_const(), 1)],
            element,
            &[a, b, c, e0, e1, su],
        )?;
        mesh.check()?;
        check_ptr(scratch_u32.cast_const(), scratch_u32_capacity)?;
        if [a, b, c, e0, e1].iter().any(|i| su.overlaps(*i)) {
            return Err(Status::AliasingBuffers.into());
        }
        if scratch_u32_capacity < mesh.topology_need()? {
            return Err(too_small(NLS_MESH_BUFFER_SCRATCH_U32));
        }
        check_fp_env()?;
        // SAFETY: inputs checked; scratch checked and disjoint from them.
        let (view, scratch) = unsafe {
            (
                mesh.mesh()?,
                super::slice_mut(scratch_u32, scratch_u32_capacity),
            )
        };
        let plan = diff::plan(view, &parsed.opts, scratch)?;
        let plan = nls_plan {
            output: sizes_of(&plan.output()),
            scratch_u32: plan.scratch_u32,
            scratch_points: plan.scratch_points,
        };
        // SAFETY: checked above.
        unsafe { store(out_plan, plan) };
        Ok(())
    })
}

/// Differential-space subdivision of the mesh with `options`, written to `out` (output order
/// and faces those of the spatial Loop or Modified Butterfly subdivision). Scratch: at least
/// the sizes of `nls_differential_plan`.
///
/// Placement (documented choice): each boundary loop and each closed component is anchored
/// at one vertex of the spatial subdivision, then every connected component is translated so
/// its centroid equals that of the spatial subdivision. `levels = 0` returns the control mesh
/// up to the tolerance; translating the input translates the output.
///
/// `NLS_STATUS_NOT_CONVERGED`: the solver reached `max_iterations`; `NLS_STATUS_FOLDED_SURFACE`
/// (`strict` with edits): an edit folded the output. In both cases the report is written (the
/// exception to "outputs on success only"), `*out_sizes` is not, and the output buffers hold
/// no result. `NLS_STATUS_BUFFER_TOO_SMALL`: `*out_element` names the first short buffer
/// (`NLS_MESH_BUFFER_*`, order `scratch->u32s`, `scratch->points`, positions, offsets,
/// indices) and `*out_sizes` receives the output sizes; nothing is written to the outputs.
/// After any other error the output and scratch contents are unspecified.
///
/// @param mesh the input mesh (positions may be strided).
/// @param options the differential options.
/// @param scratch at least the scratch of `nls_differential_plan`.
/// @param out the output buffers.
/// @param out_sizes receives the sizes written (and see `NLS_STATUS_BUFFER_TOO_SMALL`).
/// @param out_report may be NULL; receives the solver report.
/// @param out_element may be NULL; otherwise receives, on failure only, the element at fault
/// (for `NLS_STATUS_FOLDED_SURFACE` the first folded face), the buffer on
/// `NLS_STATUS_BUFFER_TOO_SMALL`, or `NLS_NO_ELEMENT`.
/// @return `NLS_STATUS_OK`; the errors of `nls_differential_plan`;
/// `NLS_STATUS_BUFFER_TOO_SMALL`; `NLS_STATUS_NOT_CONVERGED`; `NLS_STATUS_FOLDED_SURFACE`;
/// `NLS_STATUS_NUMERICAL_FAILURE` (a non-finite iterate or result, naming the vertex when
/// known); `NLS_STATUS_DEGENERATE_GEOMETRY` (a normal edit at a control vertex whose surface
/// normal is zero, naming the vertex); `NLS_STATUS_ALIASING_BUFFERS` also when an out-pointer points into a buffer of the
/// call or into another out-pointer.
///
/// Stack on Cortex-M4F: at most 8,192 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_differential_subdivide(
    mesh: *const nls_mesh_view,
    options: *const nls_differential_options,
    scratch: *const nls_scratch,
    out: *const nls_mesh_buffers,
    out_sizes: *mut nls_mesh_sizes,
    out_report: *mut nls_differential_report,
    out_element: *mut u32,
) -> Status {
    let mut needed: Option<MeshSizes> = None;
    let mut partial: Option<nls_differential_report> = None;
    let mut outs_ok = false;
    let status = run_with_element(out_element, |element| {
        // SAFETY: the caller passes NULL or readable structs.
        let (mesh_r, opts_r, scratch_r, out_r) = unsafe {
            (
                RawMesh::read(mesh),
                read_arg(options),
                read_arg(scratch),
                read_arg(out),
            )
        };
        // SAFETY: the caller passes NULL or a readable view.
        let [a, b, c] = unsafe { RawMesh::named(mesh, &mesh_r) };
        // SAFETY: the caller passes NULL or a readable view.
        let [d, e] = unsafe { edit_raw_spans(options, &opts_r, mesh) };
        let [f, g] = named(scratch, &scratch_r, scratch_raw_spans);
        let [h, i, j] = named(out, &out_r, out_raw_spans);
        element.close_unless_clear(
            &[Span::of_one(out_sizes), Span::of_one(out_report)],
            &[a, b, c, d, e, f, g, h, i, j],
        );
        let mesh = mesh_r?;
        let raw = RawOut {
            scratch: scratch_r?,
            out: out_r?,
        };
        check_ptr(out_sizes.cast_const(), 1)?;
        check_optional(out_report)?;
        check_optional(out_element)?;
        // SAFETY: the option's arrays are readable by the caller's contract.
        let parsed = unsafe { parse(opts_r, mesh.vertex_count()) }?;
        let [a, b, c] = mesh.spans();
        let [e0, e1] = parsed.edits;
        let [s0, s1, s2, s3, s4] = raw.spans();
        check_out_pointers(
            &[
                Span::of(out_sizes.cast_const(), 1),
                Span::of(out_report.cast_const(), usize::from(!out_report.is_null())),
            ],
            element,
            &[a, b, c, e0, e1, s0, s1, s2, s3, s4],
        )?;
        outs_ok = true;
        mesh.check()?;
        raw.check(&[a, b, c, e0, e1])?;
        if raw.scratch.u32_capacity < mesh.topology_need()? {
            return Err(too_small(NLS_MESH_BUFFER_SCRATCH_U32));
        }
        check_fp_env()?;
        // SAFETY: every buffer was checked (NULL, alignment, size) and the writable ones
        // overlap nothing; the caller guarantees readability and writability.
        let (view, (su, sp, mut out)) = unsafe { (mesh.mesh()?, raw.slices()) };
        let plan = {
            let need = diff::plan_scratch_size(&view)?;
            let s = su
                .get_mut(..need)
                .ok_or(too_small(NLS_MESH_BUFFER_SCRATCH_U32))?;
            diff::plan(view, &parsed.opts, s)?
        };
        let sizes = plan.output();
        let short = if raw.scratch.u32_capacity < plan.scratch_u32 {
            Some(NLS_MESH_BUFFER_SCRATCH_U32)
        } else if raw.scratch.point_capacity < plan.scratch_points {
            Some(NLS_MESH_BUFFER_SCRATCH_POINTS)
        } else {
            None
        };
        if let Some(buf) = short {
            needed = Some(sizes);
            return Err(too_small(buf));
        }
        if let Err(f) = raw.check_sizes(&sizes) {
            needed = Some(sizes);
            return Err(f);
        }
        let mut rep = DifferentialReport::default();
        match diff::subdivide(view, &parsed.opts, su, sp, &mut out, &mut rep) {
            Ok(written) => {
                // SAFETY: checked above.
                unsafe {
                    store(out_sizes, sizes_of(&written));
                    if !out_report.is_null() {
                        store(out_report, report_of(&rep));
                    }
                }
                Ok(())
            }
            Err(e) => {
                if matches!(e.status, Status::NotConverged | Status::FoldedSurface) {
                    partial = Some(report_of(&rep));
                }
                Err(Fail::from(e))
            }
        }
    });
    if let (Status::BufferTooSmall, Some(sizes), true) = (status, needed, outs_ok) {
        // SAFETY: checked before the sizes were computed.
        unsafe { store(out_sizes, sizes_of(&sizes)) };
    }
    if let (Some(r), true) = (partial, outs_ok) {
        if !out_report.is_null() {
            // SAFETY: checked (optional, aligned, outside every buffer) before the solve ran.
            unsafe { store(out_report, r) };
        }
    }
    status
}
