//! Exports of differential-space subdivision (`nlsubdiv::differential`, seed 001): the
//! differential coordinates of a triangle mesh are subdivided (Loop, Modified Butterfly, or
//! DirMag on top of Modified Butterfly) and the surface is reconstructed once at the last
//! level by an iterative least-squares solve on caller scratch (`docs/differential.md`).
//!
//! A child module of [`crate::mesh`] so that it shares that module's buffer checks (mesh
//! layout, aliasing, `out_element`, counts) without widening their visibility.

use nlsubdiv::differential::solve::SolveOptions;
use nlsubdiv::differential::{self as diff, DifferentialOptions, DifferentialReport, Stencil};
use nlsubdiv::mesh::MeshSizes;
use nlsubdiv::{Point, Status};

use super::{
    check_optional, check_scratch_u32, run_with_element, slice, store, too_small, Counts, Fail,
    RawMesh, RawOut, Span, NLS_MESH_BUFFER_SCRATCH_POINTS, NLS_MESH_BUFFER_SCRATCH_U32,
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

/// Options of [`nls_differential_plan`] and [`nls_differential_subdivide`]. Start from
/// [`nls_differential_default_options`]. Plain data; the edit arrays are read, never kept.
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
}

/// What [`nls_differential_subdivide`] did. Written on success and on
/// `NLS_STATUS_NOT_CONVERGED` (then it says how far the solver got).
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
}

fn report_of(r: &DifferentialReport) -> nls_differential_report {
    nls_differential_report {
        iterations: r.solve.iterations,
        converged: u32::from(r.solve.converged),
        anchors: r.anchors,
        dirmag_degenerate: r.dirmag_degenerate,
        relative_residual: r.solve.relative_residual,
        initial_residual: r.solve.initial_residual,
    }
}

/// Writes the defaults: Loop, 1 level, no DirMag, 100 iterations, tolerance 1e-10, no edits.
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
    p: *const nls_differential_options,
    vertex_count: usize,
) -> Result<Parsed<'a>, Status> {
    check_ptr(p, 1)?;
    // SAFETY: checked non-NULL and aligned; readable by the caller's contract.
    let o = unsafe { p.read() };
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
            // The 0.1 options struct has no strict flag: edits are never refused here.
            strict: false,
        },
        edits: [
            Span::of(o.curvature_scale, scale_n),
            Span::of(o.normals.cast::<Point>(), normal_n),
        ],
    })
}

/// The `uint32_t` scratch [`nls_differential_plan`] needs for a mesh of `vertex_count`
/// vertices and `index_count` corners (its half-edge topology): `*out_scratch_u32` entries.
///
/// Errors: `NLS_STATUS_SIZE_OVERFLOW`, `NLS_STATUS_NULL_PARAMETER`,
/// `NLS_STATUS_MISALIGNED_POINTER`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_differential_scratch_size(
    vertex_count: usize,
    index_count: usize,
    out_scratch_u32: *mut usize,
) -> Status {
    run(|| {
        check_ptr(out_scratch_u32.cast_const(), 1)?;
        let mesh = RawMesh {
            positions: core::ptr::null(),
            vertex_count,
            offsets: core::ptr::null(),
            face_count: 0,
            indices: core::ptr::null(),
            index_count,
        };
        let u = super::topology_need(&mesh)?;
        // SAFETY: checked above.
        unsafe { store(out_scratch_u32, u) };
        Ok(())
    })
}

/// Validates the mesh (triangles only) and the options and plans
/// [`nls_differential_subdivide`]: the exact output sizes (`*out_vertex_count`,
/// `*out_face_count`, `*out_index_count`; those of the spatial Loop/Butterfly subdivision) and
/// the scratch it needs, `*out_scratch_u32` entries and `*out_scratch_points` points
/// (`3*` that many doubles).
///
/// Mesh buffers as in `nls_mesh_subdivide_size`; `scratch_u32` holds at least
/// `*out_scratch_u32` of [`nls_differential_scratch_size`] and must not overlap the mesh.
///
/// Errors: the validation errors of `nls_mesh_subdivide_size`;
/// `NLS_STATUS_UNSUPPORTED_FACE_TYPE` naming the first face that is not a triangle;
/// `NLS_STATUS_INVALID_ARGUMENT` (unknown scheme, `dirmag_levels` not matching the scheme,
/// more than `NLS_MAX_LEVELS` levels, a tolerance that is not finite and ≥ 0); `NLS_STATUS_NON_FINITE_INPUT` naming the vertex of a non-finite
/// edit value; `NLS_STATUS_BUFFER_TOO_SMALL` (`NLS_MESH_BUFFER_SCRATCH_U32`);
/// `NLS_STATUS_NULL_PARAMETER`, `NLS_STATUS_MISALIGNED_POINTER`,
/// `NLS_STATUS_ALIASING_BUFFERS`, `NLS_STATUS_FP_ENVIRONMENT`. `out_element` (may be NULL)
/// as for `nls_mesh_subdivide_size`. Outputs are written on success only.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn nls_differential_plan(
    positions: *const f64,
    vertex_count: usize,
    offsets: *const u32,
    face_count: usize,
    indices: *const u32,
    index_count: usize,
    options: *const nls_differential_options,
    scratch_u32: *mut u32,
    scratch_u32_capacity: usize,
    out_vertex_count: *mut usize,
    out_face_count: *mut usize,
    out_index_count: *mut usize,
    out_scratch_u32: *mut usize,
    out_scratch_points: *mut usize,
    out_element: *mut u32,
) -> Status {
    run_with_element(out_element, || {
        let counts = Counts {
            vertices: out_vertex_count,
            faces: out_face_count,
            indices: out_index_count,
        };
        counts.check()?;
        check_ptr(out_scratch_u32.cast_const(), 1)?;
        check_ptr(out_scratch_points.cast_const(), 1)?;
        check_optional(out_element)?;
        let mesh = RawMesh {
            positions,
            vertex_count,
            offsets,
            face_count,
            indices,
            index_count,
        };
        let spans = mesh.check()?;
        // SAFETY: `options` and its arrays are readable by the caller's contract.
        let parsed = unsafe { parse(options, vertex_count) }?;
        check_scratch_u32(scratch_u32, scratch_u32_capacity, &spans)?;
        let su = Span::of(scratch_u32.cast_const(), scratch_u32_capacity);
        if parsed.edits.iter().any(|e| e.overlaps(su)) {
            return Err(Status::AliasingBuffers.into());
        }
        if scratch_u32_capacity < super::topology_need(&mesh)? {
            return Err(too_small(NLS_MESH_BUFFER_SCRATCH_U32));
        }
        check_fp_env()?;
        // SAFETY: inputs checked; scratch checked and disjoint from them.
        let (view, scratch) = unsafe {
            (
                mesh.view(),
                super::slice_mut(scratch_u32, scratch_u32_capacity),
            )
        };
        let plan = diff::plan(view, &parsed.opts, scratch)?;
        // SAFETY: checked above.
        unsafe {
            counts.write(&plan.output());
            store(out_scratch_u32, plan.scratch_u32);
            store(out_scratch_points, plan.scratch_points);
        }
        Ok(())
    })
}

/// Differential-space subdivision of the mesh (buffers as in `nls_mesh_subdivide`) with
/// `options`, written to `out_positions` / `out_offsets` / `out_indices` (capacities as in
/// `nls_mesh_subdivide`; output order and faces those of the spatial Loop or Modified
/// Butterfly subdivision). Scratch: at least the sizes of [`nls_differential_plan`].
///
/// Placement (documented choice): each boundary loop and each closed component is anchored
/// at one vertex of the spatial subdivision, then every connected component is translated so
/// its centroid equals that of the spatial subdivision. `levels = 0` returns the control mesh
/// up to the tolerance; translating the input translates the output.
///
/// On success the counts receive the sizes written and `*out_report` (may be NULL) the solver
/// report. `NLS_STATUS_NOT_CONVERGED`: the solver reached `max_iterations`; the report is
/// written (the one exception to "outputs on success only"), the counts are not, the output
/// buffers hold no result. `NLS_STATUS_BUFFER_TOO_SMALL`: `*out_element` names the first
/// short buffer (`NLS_MESH_BUFFER_*`, order scratch_u32, scratch_points, positions, offsets,
/// indices) and the counts receive the output sizes; nothing is written to the outputs.
/// After any other error the output and scratch contents are unspecified.
///
/// Errors: those of [`nls_differential_plan`]; `NLS_STATUS_BUFFER_TOO_SMALL`;
/// `NLS_STATUS_NOT_CONVERGED`; `NLS_STATUS_NUMERICAL_FAILURE` (a non-finite iterate or
/// result, naming the vertex when known).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn nls_differential_subdivide(
    positions: *const f64,
    vertex_count: usize,
    offsets: *const u32,
    face_count: usize,
    indices: *const u32,
    index_count: usize,
    options: *const nls_differential_options,
    scratch_u32: *mut u32,
    scratch_u32_capacity: usize,
    scratch_points: *mut f64,
    scratch_point_capacity: usize,
    out_positions: *mut f64,
    out_vertex_capacity: usize,
    out_offsets: *mut u32,
    out_face_capacity: usize,
    out_indices: *mut u32,
    out_index_capacity: usize,
    out_vertex_count: *mut usize,
    out_face_count: *mut usize,
    out_index_count: *mut usize,
    out_report: *mut nls_differential_report,
    out_element: *mut u32,
) -> Status {
    let mut needed: Option<MeshSizes> = None;
    let mut partial: Option<nls_differential_report> = None;
    let counts = Counts {
        vertices: out_vertex_count,
        faces: out_face_count,
        indices: out_index_count,
    };
    let status = run_with_element(out_element, || {
        counts.check()?;
        check_optional(out_report)?;
        check_optional(out_element)?;
        let mesh = RawMesh {
            positions,
            vertex_count,
            offsets,
            face_count,
            indices,
            index_count,
        };
        let [a, b, c] = mesh.check()?;
        // SAFETY: `options` and its arrays are readable by the caller's contract.
        let parsed = unsafe { parse(options, vertex_count) }?;
        let raw = RawOut {
            scratch_u32,
            scratch_u32_capacity,
            scratch_points,
            scratch_point_capacity,
            positions: out_positions,
            vertex_capacity: out_vertex_capacity,
            offsets: out_offsets,
            face_capacity: out_face_capacity,
            indices: out_indices,
            index_capacity: out_index_capacity,
        };
        raw.check(&[a, b, c])?;
        let [e0, e1] = parsed.edits;
        raw.check(&[e0, e1, e1])?;
        if scratch_u32_capacity < super::topology_need(&mesh)? {
            return Err(too_small(NLS_MESH_BUFFER_SCRATCH_U32));
        }
        check_fp_env()?;
        // SAFETY: every buffer was checked (NULL, alignment, size) and the writable ones
        // overlap nothing; the caller guarantees readability and writability.
        let (view, (su, sp, mut out)) = unsafe { (mesh.view(), raw.slices()) };
        let plan = {
            let need = diff::plan_scratch_len(&view)?;
            let s = su
                .get_mut(..need)
                .ok_or(too_small(NLS_MESH_BUFFER_SCRATCH_U32))?;
            diff::plan(view, &parsed.opts, s)?
        };
        let sizes = plan.output();
        let short = if scratch_u32_capacity < plan.scratch_u32 {
            Some(NLS_MESH_BUFFER_SCRATCH_U32)
        } else if scratch_point_capacity < plan.scratch_points {
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
                    counts.write(&written);
                    if !out_report.is_null() {
                        store(out_report, report_of(&rep));
                    }
                }
                Ok(())
            }
            Err(e) => {
                if e.status == Status::NotConverged {
                    partial = Some(report_of(&rep));
                }
                Err(Fail::from(e))
            }
        }
    });
    if let (Status::BufferTooSmall, Some(sizes)) = (status, needed) {
        // SAFETY: the counts were checked before the sizes were computed.
        unsafe { counts.write(&sizes) };
    }
    if let (Status::NotConverged, Some(r)) = (status, partial) {
        if !out_report.is_null() {
            // SAFETY: checked (optional, aligned) before the solve ran.
            unsafe { store(out_report, r) };
        }
    }
    status
}
