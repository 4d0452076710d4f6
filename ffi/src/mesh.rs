//! Exports of whole-mesh subdivision (`nlsubdiv::scheme`): the linear schemes and their
//! canonical Möbius versions (seed 000 §4), one level or several, over caller buffers.
//!
//! Buffers follow meshoptimizer: positions `double[3*vertex_count]` (packed `x, y, z`), faces
//! in CSR form, `offsets[face_count + 1]` and `indices[index_count]`, counter-clockwise seen
//! from outside. Scratch comes from the caller in two arrays: `uint32_t` entries (the
//! half-edge topology) and points (`double[3*n]`, the candidates of the Möbius schemes and the
//! intermediate levels of a multi-level call). No buffer is allocated, none is kept.

use core::mem::size_of;

use nlsubdiv::mesh::{topology_scratch_size, Mesh, MeshOut, MeshSizes, MAX_COUNT};
use nlsubdiv::scheme::{self, Options, Report, Scheme, Scratch};
use nlsubdiv::{Error, Point, Status, NO_ELEMENT};

use crate::guard::{check_fp_env, check_ptr};
use crate::primitives::run;

/// Mesh scheme: Loop (triangles only; 1→4; approximating).
pub const NLS_SCHEME_LOOP: u32 = 0;
/// Mesh scheme: Catmull–Clark (any polygons → quads; approximating; boundary = cubic
/// B-spline crease rule).
pub const NLS_SCHEME_CATMULL_CLARK: u32 = 1;
/// Mesh scheme: Modified Butterfly (triangles only; 1→4; interpolating).
pub const NLS_SCHEME_MODIFIED_BUTTERFLY: u32 = 2;
/// Mesh scheme: Kobbelt's interpolatory quad scheme (quads only; interpolating).
pub const NLS_SCHEME_KOBBELT: u32 = 3;
/// Mesh scheme: Doo–Sabin (any polygons; dual, corner cutting).
pub const NLS_SCHEME_DOO_SABIN: u32 = 4;
/// Mesh scheme: Peters–Reif simplest (mid-edge) scheme (any polygons).
pub const NLS_SCHEME_SIMPLEST: u32 = 5;
/// Mesh scheme: Akleman's dual (any polygons).
pub const NLS_SCHEME_DUAL: u32 = 6;
/// Mesh scheme: Akleman's vertex insertion (any polygons → triangles; interpolating).
pub const NLS_SCHEME_VERTEX_INSERTION: u32 = 7;
/// Mesh scheme: Akleman's dual truncation (any polygons → triangles, √3 connectivity).
pub const NLS_SCHEME_DUAL_TRUNCATION: u32 = 8;
/// Mesh scheme: spherelike interpolating subdivision (seed 003 §3; any polygons → quads;
/// interpolating; circle-blend rules keep rows of cocircular points on their circles). It
/// has no Möbius form: with `NLS_SUBDIVIDE_MOBIUS` the call is `NLS_STATUS_INVALID_ARGUMENT`.
/// Coincident points or a spike the circle rule cannot bend through give
/// `NLS_STATUS_DEGENERATE_GEOMETRY` naming the output vertex (no fallback).
pub const NLS_SCHEME_SPHERELIKE: u32 = 9;

/// Subdivision flag: the canonical Möbius version of the scheme (seed 000 §4): every vertex
/// star is evaluated in its canonical form, candidates are blended with F4/F6. Möbius
/// equivariant; cospherical meshes stay on their sphere.
pub const NLS_SUBDIVIDE_MOBIUS: u32 = 1u32 << 0;
/// Subdivision flag: an element that needs the documented linear fallback (degenerate
/// neighbourhood) is an error, `NLS_STATUS_FALLBACK_IN_STRICT_MODE`, instead of a count in the
/// report. The linear schemes never fall back.
pub const NLS_SUBDIVIDE_STRICT: u32 = 1u32 << 1;

/// `out_element` on `NLS_STATUS_BUFFER_TOO_SMALL`: the `uint32_t` scratch is short.
pub const NLS_MESH_BUFFER_SCRATCH_U32: u32 = 0;
/// `out_element` on `NLS_STATUS_BUFFER_TOO_SMALL`: the point scratch is short.
pub const NLS_MESH_BUFFER_SCRATCH_POINTS: u32 = 1;
/// `out_element` on `NLS_STATUS_BUFFER_TOO_SMALL`: `out_positions` is short.
pub const NLS_MESH_BUFFER_POSITIONS: u32 = 2;
/// `out_element` on `NLS_STATUS_BUFFER_TOO_SMALL`: `out_offsets` is short.
pub const NLS_MESH_BUFFER_OFFSETS: u32 = 3;
/// `out_element` on `NLS_STATUS_BUFFER_TOO_SMALL`: `out_indices` is short.
pub const NLS_MESH_BUFFER_INDICES: u32 = 4;

/// The largest number of levels of one [`nls_mesh_subdivide_levels`] call.
pub const NLS_MAX_LEVELS: u32 = 16;

/// What a subdivision call had to do besides the rules of the scheme: the elements that took
/// the documented linear fallback (Möbius schemes on degenerate neighbourhoods: coincident
/// points, a star without canonical form, a blend at infinity). Plain old data.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct nls_subdivide_report {
    /// Output vertices that took their linear rule (all levels of a multi-level call).
    pub fallbacks: u32,
    /// The first such output vertex (of level `first_fallback_level`), or `UINT32_MAX`
    /// (`NLS_NO_ELEMENT`) when there was none.
    pub first_fallback: u32,
    /// The level of `first_fallback`, counted from 1 (always 1 for a one-level call), or 0
    /// when there was no fallback.
    pub first_fallback_level: u32,
}

/// A scheme code and flag bits, parsed into the options of the Rust path (one level; the
/// multi-level exports set their levels).
fn options(scheme: u32, flags: u32) -> Result<Options, Status> {
    let scheme = Scheme::from_code(scheme).ok_or(Status::InvalidArgument)?;
    if flags & !(NLS_SUBDIVIDE_MOBIUS | NLS_SUBDIVIDE_STRICT) != 0 {
        return Err(Status::InvalidArgument);
    }
    if flags & NLS_SUBDIVIDE_MOBIUS != 0 && !scheme.has_mobius_form() {
        return Err(Status::InvalidArgument);
    }
    Ok(Options::new(scheme)
        .mobius(flags & NLS_SUBDIVIDE_MOBIUS != 0)
        .strict(flags & NLS_SUBDIVIDE_STRICT != 0))
}

/// A failure: the status and the element written to `out_element`.
struct Fail {
    status: Status,
    element: u32,
}

impl From<Status> for Fail {
    fn from(status: Status) -> Fail {
        Fail {
            status,
            element: NO_ELEMENT,
        }
    }
}

impl From<Error> for Fail {
    fn from(e: Error) -> Fail {
        Fail {
            status: e.status,
            element: e.element,
        }
    }
}

fn too_small(buffer: u32) -> Fail {
    Fail {
        status: Status::BufferTooSmall,
        element: buffer,
    }
}

/// Runs an export body; on failure writes the element to `out_element` when it is a valid
/// pointer (the one exception to "written only on success", as in `nls_curve_subdivide`).
fn run_with_element(out_element: *mut u32, body: impl FnOnce() -> Result<(), Fail>) -> Status {
    let _traps = crate::guard::FpTrapGuard::mask_traps();
    match body() {
        Ok(()) => Status::Ok,
        Err(f) => {
            if !out_element.is_null() && out_element.is_aligned() {
                // SAFETY: non-NULL and aligned; writable by the caller's contract. Every slice
                // formed from the caller's buffers is gone by now.
                unsafe { out_element.write(f.element) };
            }
            f.status
        }
    }
}

/// Checks an optional out-parameter (NULL allowed).
fn check_optional<T>(p: *mut T) -> Result<(), Status> {
    check_ptr(p.cast_const(), usize::from(!p.is_null()))
}

/// # Safety
/// `p` passed `check_ptr(p, 1)` (non-NULL, aligned) and points to a writable `T`.
unsafe fn store<T>(p: *mut T, v: T) {
    // SAFETY: by the caller's contract.
    unsafe { p.write(v) };
}

/// A byte range of a caller buffer, for the overlap checks.
#[derive(Clone, Copy)]
struct Span {
    start: usize,
    bytes: usize,
}

impl Span {
    /// `count` elements of `T` at `p` (`check_ptr` bounds the byte size by `isize::MAX`).
    fn of<T>(p: *const T, count: usize) -> Span {
        Span {
            start: p as usize,
            bytes: count.saturating_mul(size_of::<T>()),
        }
    }

    fn overlaps(self, other: Span) -> bool {
        self.bytes > 0
            && other.bytes > 0
            && self.start < other.start.saturating_add(other.bytes)
            && other.start < self.start.saturating_add(self.bytes)
    }
}

/// The input mesh as the caller passed it.
#[derive(Clone, Copy)]
struct RawMesh {
    positions: *const f64,
    vertex_count: usize,
    offsets: *const u32,
    face_count: usize,
    indices: *const u32,
    index_count: usize,
}

impl RawMesh {
    /// Checks the three input pointers and returns their byte ranges.
    fn check(&self) -> Result<[Span; 3], Status> {
        let offsets_len = self.face_count.checked_add(1).ok_or(Status::SizeOverflow)?;
        check_ptr(self.positions.cast::<Point>(), self.vertex_count)?;
        check_ptr(self.offsets, offsets_len)?;
        check_ptr(self.indices, self.index_count)?;
        Ok([
            Span::of(self.positions.cast::<Point>(), self.vertex_count),
            Span::of(self.offsets, offsets_len),
            Span::of(self.indices, self.index_count),
        ])
    }

    /// The core's view of the mesh.
    ///
    /// # Safety
    /// [`RawMesh::check`] passed, and the three buffers are readable for their counts and not
    /// written while the view lives.
    unsafe fn view<'a>(&self) -> Mesh<'a> {
        // SAFETY: by the caller's contract (checked, readable, unaliased by writes).
        unsafe {
            Mesh::new(
                slice(self.positions.cast::<Point>(), self.vertex_count),
                slice(self.offsets, self.face_count.saturating_add(1)),
                slice(self.indices, self.index_count),
            )
        }
    }
}

/// # Safety
/// `p` passed `check_ptr(p, count)` and is readable for `count` elements during `'a`.
unsafe fn slice<'a, T>(p: *const T, count: usize) -> &'a [T] {
    if count == 0 {
        return &[];
    }
    // SAFETY: non-NULL, aligned, byte size ≤ isize::MAX (checked), readable (contract).
    unsafe { core::slice::from_raw_parts(p, count) }
}

/// # Safety
/// `p` passed `check_ptr(p, count)`, is writable for `count` elements and overlaps no other
/// slice alive during `'a`.
unsafe fn slice_mut<'a, T>(p: *mut T, count: usize) -> &'a mut [T] {
    if count == 0 {
        return &mut [];
    }
    // SAFETY: non-NULL, aligned, byte size ≤ isize::MAX (checked), writable and unaliased
    // (contract and the overlap checks).
    unsafe { core::slice::from_raw_parts_mut(p, count) }
}

/// The caller's scratch and output buffers (capacities as passed: points, faces, entries).
#[derive(Clone, Copy)]
struct RawOut {
    scratch_u32: *mut u32,
    scratch_u32_capacity: usize,
    scratch_points: *mut f64,
    scratch_point_capacity: usize,
    positions: *mut f64,
    vertex_capacity: usize,
    offsets: *mut u32,
    face_capacity: usize,
    indices: *mut u32,
    index_capacity: usize,
}

impl RawOut {
    /// Checks every pointer and that no buffer overlaps an input or another buffer.
    fn check(&self, inputs: &[Span; 3]) -> Result<(), Status> {
        let offsets_len = self
            .face_capacity
            .checked_add(1)
            .ok_or(Status::SizeOverflow)?;
        check_ptr(self.scratch_u32.cast_const(), self.scratch_u32_capacity)?;
        check_ptr(
            self.scratch_points.cast_const().cast::<Point>(),
            self.scratch_point_capacity,
        )?;
        check_ptr(
            self.positions.cast_const().cast::<Point>(),
            self.vertex_capacity,
        )?;
        check_ptr(self.offsets.cast_const(), offsets_len)?;
        check_ptr(self.indices.cast_const(), self.index_capacity)?;
        let spans = [
            Span::of(self.scratch_u32.cast_const(), self.scratch_u32_capacity),
            Span::of(
                self.scratch_points.cast_const().cast::<Point>(),
                self.scratch_point_capacity,
            ),
            Span::of(
                self.positions.cast_const().cast::<Point>(),
                self.vertex_capacity,
            ),
            Span::of(self.offsets.cast_const(), offsets_len),
            Span::of(self.indices.cast_const(), self.index_capacity),
        ];
        for (i, a) in spans.iter().enumerate() {
            let clash = inputs.iter().any(|b| a.overlaps(*b))
                || spans.iter().skip(i + 1).any(|b| a.overlaps(*b));
            if clash {
                return Err(Status::AliasingBuffers);
            }
        }
        Ok(())
    }

    /// `NLS_STATUS_BUFFER_TOO_SMALL` naming the first output buffer that cannot hold `sizes`
    /// (positions, offsets, indices).
    fn check_sizes(&self, sizes: &MeshSizes) -> Result<(), Fail> {
        if self.vertex_capacity < sizes.vertices {
            return Err(too_small(NLS_MESH_BUFFER_POSITIONS));
        }
        if self.face_capacity < sizes.faces {
            return Err(too_small(NLS_MESH_BUFFER_OFFSETS));
        }
        if self.index_capacity < sizes.indices {
            return Err(too_small(NLS_MESH_BUFFER_INDICES));
        }
        Ok(())
    }

    /// The five buffers as slices: `(scratch_u32, scratch_points, outputs)`.
    ///
    /// # Safety
    /// [`RawOut::check`] passed and the buffers are writable for their capacities during
    /// `'a`; no other reference to them is alive.
    unsafe fn slices<'a>(&self) -> (&'a mut [u32], &'a mut [Point], MeshOut<'a>) {
        // SAFETY: checked (NULL, alignment, size) and pairwise disjoint (RawOut::check);
        // writable by the caller's contract.
        unsafe {
            (
                slice_mut(self.scratch_u32, self.scratch_u32_capacity),
                slice_mut(
                    self.scratch_points.cast::<Point>(),
                    self.scratch_point_capacity,
                ),
                MeshOut::new(
                    slice_mut(self.positions.cast::<Point>(), self.vertex_capacity),
                    slice_mut(self.offsets, self.face_capacity.saturating_add(1)),
                    slice_mut(self.indices, self.index_capacity),
                ),
            )
        }
    }
}

/// Checks the `uint32_t` scratch of the size queries: pointer, and no overlap with the mesh.
fn check_scratch_u32(p: *mut u32, capacity: usize, inputs: &[Span; 3]) -> Result<(), Status> {
    check_ptr(p.cast_const(), capacity)?;
    let span = Span::of(p.cast_const(), capacity);
    if inputs.iter().any(|b| span.overlaps(*b)) {
        return Err(Status::AliasingBuffers);
    }
    Ok(())
}

/// The three count out-parameters.
#[derive(Clone, Copy)]
struct Counts {
    vertices: *mut usize,
    faces: *mut usize,
    indices: *mut usize,
}

impl Counts {
    fn check(&self) -> Result<(), Status> {
        check_ptr(self.vertices.cast_const(), 1)?;
        check_ptr(self.faces.cast_const(), 1)?;
        check_ptr(self.indices.cast_const(), 1)
    }

    /// # Safety
    /// [`Counts::check`] passed; the three pointers are writable.
    unsafe fn write(&self, s: &MeshSizes) {
        // SAFETY: checked non-NULL and aligned; writable by the caller's contract.
        unsafe {
            store(self.vertices, s.vertices);
            store(self.faces, s.faces);
            store(self.indices, s.indices);
        }
    }
}

/// The `uint32_t` scratch of one level: the topology of the input.
fn topology_need(mesh: &RawMesh) -> Result<usize, Status> {
    if mesh.vertex_count > MAX_COUNT || mesh.index_count > MAX_COUNT {
        return Err(Status::SizeOverflow);
    }
    topology_scratch_size(mesh.vertex_count, mesh.index_count).map_err(|e| e.status)
}

/// The scratch sizes of [`nls_mesh_scratch_size`], from the counts alone: the scratch of a
/// one-level plan ([`scheme::Plan::scratch`]), which is the input's topology (`u32`) and, for
/// the Möbius version, two candidate points per corner (an edge and a face candidate per
/// half-edge, seed 000 §4.1); the tests check it against the plan.
fn scratch_need(opts: Options, mesh: &RawMesh) -> Result<(usize, usize), Status> {
    let u = topology_need(mesh)?;
    let p = if opts.mobius {
        mesh.index_count
            .checked_mul(2)
            .ok_or(Status::SizeOverflow)?
    } else {
        0
    };
    Ok((u, p))
}

/// The C report of a Rust one.
fn report_of(r: &Report) -> nls_subdivide_report {
    nls_subdivide_report {
        fallbacks: r.fallbacks,
        first_fallback: r.first_fallback,
        first_fallback_level: r.first_fallback_level,
    }
}

/// The one call of the Rust path ([`scheme::subdivide`]) behind [`nls_mesh_subdivide`] and
/// [`nls_mesh_subdivide_levels`]. On `NLS_STATUS_BUFFER_TOO_SMALL` the plan (computed again,
/// on the error path only) names the first short buffer in the order `scratch_u32`,
/// `scratch_points`, positions, offsets, indices, and `needed` receives the output sizes when
/// the short buffer is an output buffer.
fn subdivide_call(
    view: Mesh<'_>,
    opts: &Options,
    su: &mut [u32],
    sp: &mut [Point],
    out: &mut MeshOut<'_>,
    raw: &RawOut,
    needed: &mut Option<MeshSizes>,
) -> Result<Report, Fail> {
    match scheme::subdivide(view, opts, Scratch::new(&mut *su, &mut *sp), out) {
        Ok(report) => Ok(report),
        Err(e) if e.status == Status::BufferTooSmall => {
            let plan = scheme::plan(view, opts, su)?;
            if su.len() < plan.scratch.u32s {
                return Err(too_small(NLS_MESH_BUFFER_SCRATCH_U32));
            }
            if sp.len() < plan.scratch.points {
                return Err(too_small(NLS_MESH_BUFFER_SCRATCH_POINTS));
            }
            if let Err(f) = raw.check_sizes(&plan.output()) {
                *needed = Some(plan.output());
                return Err(f);
            }
            // Every buffer holds the plan: the error was not a buffer's.
            Err(e.into())
        }
        Err(e) => Err(e.into()),
    }
}

/// The scratch that [`nls_mesh_subdivide_size`] and [`nls_mesh_subdivide`] need for a mesh of
/// `vertex_count` vertices and `index_count` corners (the length of its `indices`):
/// `*out_scratch_u32` `uint32_t` entries (its half-edge topology, `4·index_count +
/// 3·vertex_count`) and `*out_scratch_points` points, i.e. `3*` that many doubles (two
/// candidates per corner with `NLS_SUBDIVIDE_MOBIUS`, else 0). Depends on the counts only.
///
/// Errors: `NLS_STATUS_INVALID_ARGUMENT` (unknown scheme or flag bits),
/// `NLS_STATUS_SIZE_OVERFLOW` (a count above `UINT32_MAX − 1`), `NLS_STATUS_NULL_PARAMETER`,
/// `NLS_STATUS_MISALIGNED_POINTER`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mesh_scratch_size(
    scheme: u32,
    flags: u32,
    vertex_count: usize,
    index_count: usize,
    out_scratch_u32: *mut usize,
    out_scratch_points: *mut usize,
) -> Status {
    run(|| {
        let opts = options(scheme, flags)?;
        check_ptr(out_scratch_u32.cast_const(), 1)?;
        check_ptr(out_scratch_points.cast_const(), 1)?;
        let mesh = RawMesh {
            positions: core::ptr::null(),
            vertex_count,
            offsets: core::ptr::null(),
            face_count: 0,
            indices: core::ptr::null(),
            index_count,
        };
        let (u, p) = scratch_need(opts, &mesh)?;
        // SAFETY: checked above.
        unsafe {
            store(out_scratch_u32, u);
            store(out_scratch_points, p);
        }
        Ok(())
    })
}

/// Validates a mesh and gives the exact sizes of one level of `scheme` (`NLS_SCHEME_*`) with
/// `flags` (`NLS_SUBDIVIDE_*`; the Möbius version has the same sizes): `*out_vertex_count`
/// points, `*out_face_count` faces (the offsets buffer holds one more entry) and
/// `*out_index_count` corners.
///
/// The mesh: `positions[3*vertex_count]` (`x, y, z` per vertex), `offsets[face_count + 1]`
/// (`offsets[0] = 0`, non-decreasing, `offsets[face_count] = index_count`; never NULL, an
/// empty mesh is `{0}`) and `indices[index_count]`, faces counter-clockwise seen from outside.
/// `scratch_u32` holds `scratch_u32_capacity` entries, at least `*out_scratch_u32` of
/// [`nls_mesh_scratch_size`]; it must not overlap the mesh. Its contents are unspecified
/// afterwards.
///
/// Validation, topology first and before anything else is computed (the first failure wins):
/// `NLS_STATUS_SIZE_OVERFLOW` (a count above `UINT32_MAX − 1`), `NLS_STATUS_BAD_OFFSETS`,
/// `NLS_STATUS_FACE_TOO_SMALL`, `NLS_STATUS_VALENCE_TOO_HIGH` (a face above 128 corners),
/// `NLS_STATUS_INDEX_OUT_OF_RANGE`, `NLS_STATUS_REPEATED_VERTEX` (each naming the face),
/// `NLS_STATUS_DUPLICATE_FACE`, `NLS_STATUS_INCONSISTENT_ORIENTATION`,
/// `NLS_STATUS_NON_MANIFOLD_EDGE` (naming the later face on the edge),
/// `NLS_STATUS_NON_MANIFOLD_VERTEX` (bow-tie), `NLS_STATUS_VALENCE_TOO_HIGH` (a vertex above
/// 128 neighbours), `NLS_STATUS_NON_FINITE_INPUT` (each naming the vertex), then the scheme's
/// own: `NLS_STATUS_UNSUPPORTED_FACE_TYPE` (Loop and Modified Butterfly accept triangles,
/// Kobbelt quads; naming the face), `NLS_STATUS_FACE_TOO_SMALL` naming an interior valence-2
/// vertex (dual schemes), `NLS_STATUS_VALENCE_TOO_HIGH` (an output vertex or face above the
/// capacity).
///
/// `out_element` may be NULL. Otherwise it receives, on failure only, the element named
/// above, the short buffer (`NLS_MESH_BUFFER_SCRATCH_U32`) on `NLS_STATUS_BUFFER_TOO_SMALL`,
/// or `NLS_NO_ELEMENT`. The counts are written on success only.
///
/// Other errors: `NLS_STATUS_INVALID_ARGUMENT` (unknown scheme or flag bits),
/// `NLS_STATUS_NULL_PARAMETER`, `NLS_STATUS_MISALIGNED_POINTER`,
/// `NLS_STATUS_ALIASING_BUFFERS`, `NLS_STATUS_FP_ENVIRONMENT`.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn nls_mesh_subdivide_size(
    scheme: u32,
    flags: u32,
    positions: *const f64,
    vertex_count: usize,
    offsets: *const u32,
    face_count: usize,
    indices: *const u32,
    index_count: usize,
    scratch_u32: *mut u32,
    scratch_u32_capacity: usize,
    out_vertex_count: *mut usize,
    out_face_count: *mut usize,
    out_index_count: *mut usize,
    out_element: *mut u32,
) -> Status {
    run_with_element(out_element, || {
        let opts = options(scheme, flags)?;
        let counts = Counts {
            vertices: out_vertex_count,
            faces: out_face_count,
            indices: out_index_count,
        };
        counts.check()?;
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
        check_scratch_u32(scratch_u32, scratch_u32_capacity, &spans)?;
        if scratch_u32_capacity < topology_need(&mesh)? {
            return Err(too_small(NLS_MESH_BUFFER_SCRATCH_U32));
        }
        check_fp_env()?;
        // SAFETY: inputs checked; scratch checked and disjoint from them.
        let (view, scratch) =
            unsafe { (mesh.view(), slice_mut(scratch_u32, scratch_u32_capacity)) };
        let sizes = scheme::plan(view, &opts, scratch)?.output();
        // SAFETY: checked above.
        unsafe { counts.write(&sizes) };
        Ok(())
    })
}

/// One level of `scheme` (`NLS_SCHEME_*`) with `flags` (`NLS_SUBDIVIDE_*`) on the mesh
/// (buffers as in [`nls_mesh_subdivide_size`]), written to `out_positions` (room for
/// `out_vertex_capacity` points, `3*` that many doubles), `out_offsets`
/// (`out_face_capacity + 1` entries) and `out_indices` (`out_index_capacity` entries).
///
/// Scratch: `scratch_u32` (`scratch_u32_capacity` entries) and `scratch_points`
/// (`scratch_point_capacity` points), at least what [`nls_mesh_scratch_size`] gives (NULL with
/// capacity 0 when that is 0). No buffer may overlap another one or the input
/// (`NLS_STATUS_ALIASING_BUFFERS`, checked before anything is read): in-place calls are not
/// supported.
///
/// Output order (DESIGN.md): primal schemes write the old vertices first at the same
/// indices, then the edge points in edge order (edges sorted by their `(min, max)` vertex
/// pair), then the face points in face order; the dual schemes as documented in
/// `docs/mesh-and-linear-schemes.md`. The Möbius version has the connectivity and order of the
/// linear one. Interpolating schemes keep the old vertices bit for bit.
///
/// On success the three counts receive the sizes written and `*out_report` (may be NULL) the
/// fallbacks. On `NLS_STATUS_BUFFER_TOO_SMALL` nothing is written to the output buffers,
/// `*out_element` names the first short buffer (`NLS_MESH_BUFFER_*`, checked in the order
/// scratch_u32, scratch_points, positions, offsets, indices) and, when it is an output buffer,
/// the three counts receive the exact sizes needed (a scratch buffer is checked before the
/// mesh is validated, against the sizes of [`nls_mesh_scratch_size`]: the counts are not
/// written then). After any other error the contents of the output and scratch buffers are
/// unspecified and the counts and report are not written.
///
/// `out_element` may be NULL. Otherwise it receives, on failure only: the element of a
/// validation error (see [`nls_mesh_subdivide_size`]), the output vertex for
/// `NLS_STATUS_FALLBACK_IN_STRICT_MODE`, `NLS_STATUS_NUMERICAL_FAILURE` and
/// `NLS_STATUS_DEGENERATE_GEOMETRY` (`NLS_SCHEME_SPHERELIKE`), the buffer for
/// `NLS_STATUS_BUFFER_TOO_SMALL`, else `NLS_NO_ELEMENT`.
///
/// Errors: those of [`nls_mesh_subdivide_size`]; `NLS_STATUS_BUFFER_TOO_SMALL`;
/// `NLS_STATUS_INVALID_ARGUMENT` (unknown scheme or flag, or `NLS_SUBDIVIDE_MOBIUS` with a
/// scheme without Möbius form: `NLS_SCHEME_SPHERELIKE`); `NLS_STATUS_DEGENERATE_GEOMETRY`
/// (`NLS_SCHEME_SPHERELIKE`: coincident points of one circle, or a spike);
/// `NLS_STATUS_FALLBACK_IN_STRICT_MODE` (`NLS_SUBDIVIDE_STRICT`); `NLS_STATUS_NUMERICAL_FAILURE`
/// (an output vertex would not be finite: coordinates near the ends of the double range).
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn nls_mesh_subdivide(
    scheme: u32,
    flags: u32,
    positions: *const f64,
    vertex_count: usize,
    offsets: *const u32,
    face_count: usize,
    indices: *const u32,
    index_count: usize,
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
    out_report: *mut nls_subdivide_report,
    out_element: *mut u32,
) -> Status {
    let mut needed: Option<MeshSizes> = None;
    let counts = Counts {
        vertices: out_vertex_count,
        faces: out_face_count,
        indices: out_index_count,
    };
    let status = run_with_element(out_element, || {
        let opts = options(scheme, flags)?;
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
        let spans = mesh.check()?;
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
        raw.check(&spans)?;
        let (need_u, need_p) = scratch_need(opts, &mesh)?;
        if scratch_u32_capacity < need_u {
            return Err(too_small(NLS_MESH_BUFFER_SCRATCH_U32));
        }
        if scratch_point_capacity < need_p {
            return Err(too_small(NLS_MESH_BUFFER_SCRATCH_POINTS));
        }
        check_fp_env()?;
        // SAFETY: every buffer was checked (NULL, alignment, size) and the writable ones
        // overlap nothing; the caller guarantees readability and writability.
        let (view, (su, sp, mut out)) = unsafe { (mesh.view(), raw.slices()) };
        let report = subdivide_call(view, &opts, su, sp, &mut out, &raw, &mut needed)?;
        let (written, report) = (report.sizes, report_of(&report));
        // SAFETY: checked above.
        unsafe {
            counts.write(&written);
            if !out_report.is_null() {
                store(out_report, report);
            }
        }
        Ok(())
    });
    if let (Status::BufferTooSmall, Some(sizes)) = (status, needed) {
        // SAFETY: the counts were checked before the sizes were computed.
        unsafe { counts.write(&sizes) };
    }
    status
}

/// Validates the mesh and plans `levels` levels (at most `NLS_MAX_LEVELS`; 0 copies the
/// mesh) of [`nls_mesh_subdivide_levels`]: the exact sizes of the last level
/// (`*out_vertex_count`, `*out_face_count`, `*out_index_count`) and the scratch the call needs,
/// `*out_scratch_u32` entries and `*out_scratch_points` points (the intermediate levels, their
/// topology and, with `NLS_SUBDIVIDE_MOBIUS`, the candidates of the largest step). The sizes
/// of every level are exact functions of a few counts of the input, so nothing is subdivided
/// here.
///
/// `scratch_u32` is needed for the validation itself: at least `*out_scratch_u32` of
/// [`nls_mesh_scratch_size`].
///
/// Errors: those of [`nls_mesh_subdivide_size`] for the first level;
/// `NLS_STATUS_INVALID_ARGUMENT` for more than `NLS_MAX_LEVELS` levels;
/// `NLS_STATUS_SIZE_OVERFLOW` when a level has more than `UINT32_MAX − 1` vertices, faces or
/// corners; `NLS_STATUS_VALENCE_TOO_HIGH` (no element) when a later level would exceed the
/// valence or face-size capacity. `out_element` as for [`nls_mesh_subdivide_size`].
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn nls_mesh_subdivide_levels_size(
    scheme: u32,
    flags: u32,
    positions: *const f64,
    vertex_count: usize,
    offsets: *const u32,
    face_count: usize,
    indices: *const u32,
    index_count: usize,
    levels: u32,
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
        let opts = options(scheme, flags)?;
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
        check_scratch_u32(scratch_u32, scratch_u32_capacity, &spans)?;
        if scratch_u32_capacity < topology_need(&mesh)? {
            return Err(too_small(NLS_MESH_BUFFER_SCRATCH_U32));
        }
        check_fp_env()?;
        // SAFETY: inputs checked; scratch checked and disjoint from them.
        let (view, scratch) =
            unsafe { (mesh.view(), slice_mut(scratch_u32, scratch_u32_capacity)) };
        let plan = scheme::plan(view, &opts.levels(levels as usize), scratch)?;
        // SAFETY: checked above.
        unsafe {
            counts.write(&plan.output());
            store(out_scratch_u32, plan.scratch.u32s);
            store(out_scratch_points, plan.scratch.points);
        }
        Ok(())
    })
}

/// `levels` levels (at most `NLS_MAX_LEVELS`; 0 copies the mesh) of `scheme` with `flags` in
/// one call: the intermediate levels live in the scratch, the last one is written to the
/// output buffers. Buffers as for [`nls_mesh_subdivide`]; the scratch and output sizes come
/// from [`nls_mesh_subdivide_levels_size`]. The result equals `levels` calls of
/// [`nls_mesh_subdivide`], bit for bit.
///
/// The report sums the fallbacks of all levels; its `first_fallback` is a vertex of level
/// `first_fallback_level`. With `NLS_SUBDIVIDE_STRICT`, `*out_element` receives the output
/// vertex of the level being computed.
///
/// `NLS_STATUS_BUFFER_TOO_SMALL` as for [`nls_mesh_subdivide`]: `scratch_u32` below the
/// input's topology (checked before validation); then, after planning, `scratch_u32`,
/// `scratch_points`, the output buffers in this order (the counts receive the exact sizes
/// when an output buffer is short).
///
/// Errors: those of [`nls_mesh_subdivide_levels_size`] and [`nls_mesh_subdivide`].
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn nls_mesh_subdivide_levels(
    scheme: u32,
    flags: u32,
    positions: *const f64,
    vertex_count: usize,
    offsets: *const u32,
    face_count: usize,
    indices: *const u32,
    index_count: usize,
    levels: u32,
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
    out_report: *mut nls_subdivide_report,
    out_element: *mut u32,
) -> Status {
    let mut needed: Option<MeshSizes> = None;
    let counts = Counts {
        vertices: out_vertex_count,
        faces: out_face_count,
        indices: out_index_count,
    };
    let status = run_with_element(out_element, || {
        let opts = options(scheme, flags)?;
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
        let spans = mesh.check()?;
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
        raw.check(&spans)?;
        if scratch_u32_capacity < topology_need(&mesh)? {
            return Err(too_small(NLS_MESH_BUFFER_SCRATCH_U32));
        }
        check_fp_env()?;
        // SAFETY: every buffer was checked (NULL, alignment, size) and the writable ones
        // overlap nothing; the caller guarantees readability and writability.
        let (view, (su, sp, mut out)) = unsafe { (mesh.view(), raw.slices()) };
        let opts = opts.levels(levels as usize);
        let report = subdivide_call(view, &opts, su, sp, &mut out, &raw, &mut needed)?;
        let (written, report) = (report.sizes, report_of(&report));
        // SAFETY: checked above.
        unsafe {
            counts.write(&written);
            if !out_report.is_null() {
                store(out_report, report);
            }
        }
        Ok(())
    });
    if let (Status::BufferTooSmall, Some(sizes)) = (status, needed) {
        // SAFETY: the counts were checked before the sizes were computed.
        unsafe { counts.write(&sizes) };
    }
    status
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_match_the_core() {
        let pairs = [
            (NLS_SCHEME_LOOP, Scheme::Loop),
            (NLS_SCHEME_CATMULL_CLARK, Scheme::CatmullClark),
            (NLS_SCHEME_MODIFIED_BUTTERFLY, Scheme::ModifiedButterfly),
            (NLS_SCHEME_KOBBELT, Scheme::Kobbelt),
            (NLS_SCHEME_DOO_SABIN, Scheme::DooSabin),
            (NLS_SCHEME_SIMPLEST, Scheme::Simplest),
            (NLS_SCHEME_DUAL, Scheme::Dual),
            (NLS_SCHEME_VERTEX_INSERTION, Scheme::VertexInsertion),
            (NLS_SCHEME_DUAL_TRUNCATION, Scheme::DualTruncation),
            (NLS_SCHEME_SPHERELIKE, Scheme::Spherelike),
        ];
        assert_eq!(pairs.len(), Scheme::ALL.len());
        for (code, scheme) in pairs {
            assert_eq!(code, scheme.code());
        }
        assert_eq!(NLS_MAX_LEVELS as usize, scheme::MAX_LEVELS);
        assert_eq!((NLS_SUBDIVIDE_MOBIUS, NLS_SUBDIVIDE_STRICT), (1, 2));
    }

    /// The counts-only scratch of `nls_mesh_scratch_size` is the scratch of a one-level plan
    /// of the Rust path, for every scheme, linear and Möbius.
    #[test]
    fn counts_only_scratch_is_the_one_level_plan() {
        // A triangle fan, a quad strip and a pentagon: every scheme accepts some of them.
        let p: [[f64; 3]; 7] = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.2],
            [0.0, 1.0, 0.0],
            [-1.0, 0.5, 0.1],
            [-0.5, -0.8, 0.0],
            [2.0, 0.5, 0.3],
        ];
        let meshes: [(&[u32], &[u32]); 3] = [
            (&[0, 3, 6, 9], &[0, 1, 2, 0, 2, 3, 0, 3, 4]),
            (&[0, 4, 8], &[0, 1, 2, 3, 5, 1, 0, 4]),
            (&[0, 5], &[0, 5, 1, 6, 2]),
        ];
        let mut checked = 0;
        for (offsets, indices) in meshes {
            let view = Mesh::new(&p, offsets, indices);
            let raw = RawMesh {
                positions: p.as_ptr().cast(),
                vertex_count: p.len(),
                offsets: offsets.as_ptr(),
                face_count: offsets.len() - 1,
                indices: indices.as_ptr(),
                index_count: indices.len(),
            };
            for s in Scheme::ALL {
                for flags in [0, NLS_SUBDIVIDE_MOBIUS] {
                    let Ok(opts) = options(s.code(), flags) else {
                        continue;
                    };
                    let mut su = vec![0u32; scheme::plan_scratch_size(&view).unwrap()];
                    let Ok(plan) = scheme::plan(view, &opts, &mut su) else {
                        continue;
                    };
                    let (u, q) = scratch_need(opts, &raw).unwrap();
                    assert_eq!((u, q), (plan.scratch.u32s, plan.scratch.points), "{s:?}");
                    checked += 1;
                }
            }
        }
        assert!(checked >= 20, "{checked}");
    }

    #[test]
    fn one_quad_through_the_abi() {
        let p: [f64; 12] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0];
        let (off, idx) = ([0u32, 4], [0u32, 1, 2, 3]);
        let (mut su, mut sp) = (0usize, 0usize);
        let s = unsafe {
            nls_mesh_scratch_size(
                NLS_SCHEME_CATMULL_CLARK,
                NLS_SUBDIVIDE_MOBIUS,
                4,
                4,
                &mut su,
                &mut sp,
            )
        };
        assert_eq!((s, su, sp), (Status::Ok, 28, 8));
        let mut scratch = vec![0u32; su];
        let mut pts = vec![0.0; 3 * sp];
        let (mut op, mut oo, mut oi) = (vec![0.0; 27], vec![0u32; 5], vec![0u32; 16]);
        let (mut nv, mut nf, mut ni) = (0usize, 0usize, 0usize);
        let mut rep = nls_subdivide_report {
            fallbacks: 9,
            first_fallback: 9,
            first_fallback_level: 9,
        };
        let mut element = 7u32;
        let s = unsafe {
            nls_mesh_subdivide(
                NLS_SCHEME_CATMULL_CLARK,
                NLS_SUBDIVIDE_MOBIUS,
                p.as_ptr(),
                4,
                off.as_ptr(),
                1,
                idx.as_ptr(),
                4,
                scratch.as_mut_ptr(),
                su,
                pts.as_mut_ptr(),
                sp,
                op.as_mut_ptr(),
                9,
                oo.as_mut_ptr(),
                4,
                oi.as_mut_ptr(),
                16,
                &mut nv,
                &mut nf,
                &mut ni,
                &mut rep,
                &mut element,
            )
        };
        assert_eq!(s, Status::Ok);
        assert_eq!((nv, nf, ni, element), (9, 4, 16, 7));
        // A face of ears only (DESIGN.md) takes its linear centroid: one fallback, the face
        // point.
        let r = (rep.fallbacks, rep.first_fallback, rep.first_fallback_level);
        assert_eq!(r, (1, 8, 1));
        assert_eq!(&op[24..27], &[0.5, 0.5, 0.0]);
        // One face short: the counts give the sizes, the element the buffer.
        let s = unsafe {
            nls_mesh_subdivide(
                NLS_SCHEME_CATMULL_CLARK,
                0,
                p.as_ptr(),
                4,
                off.as_ptr(),
                1,
                idx.as_ptr(),
                4,
                scratch.as_mut_ptr(),
                su,
                core::ptr::null_mut(),
                0,
                op.as_mut_ptr(),
                9,
                oo.as_mut_ptr(),
                3,
                oi.as_mut_ptr(),
                16,
                &mut nv,
                &mut nf,
                &mut ni,
                core::ptr::null_mut(),
                &mut element,
            )
        };
        assert_eq!(s, Status::BufferTooSmall);
        assert_eq!((nv, nf, ni, element), (9, 4, 16, NLS_MESH_BUFFER_OFFSETS));
    }

    /// Zero levels copy the mesh but validate it into the `u32` scratch: the size query
    /// reports that scratch (the topology, `4·corners + 3·vertices`, as
    /// `nls_mesh_scratch_size`), an exact-size buffer is enough, one entry less is refused.
    #[test]
    fn zero_levels_scratch_through_the_abi() {
        let p: [f64; 12] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0];
        let (off, idx) = ([0u32, 4], [0u32, 1, 2, 3]);
        for flags in [0, NLS_SUBDIVIDE_MOBIUS] {
            let (mut su0, mut sp0) = (0usize, 0usize);
            let s = unsafe {
                nls_mesh_scratch_size(NLS_SCHEME_CATMULL_CLARK, flags, 4, 4, &mut su0, &mut sp0)
            };
            assert_eq!((s, su0), (Status::Ok, 28));
            let mut scratch = vec![0u32; su0];
            let (mut nv, mut nf, mut ni, mut su, mut sp) = (0usize, 0usize, 0usize, 9usize, 9usize);
            let s = unsafe {
                nls_mesh_subdivide_levels_size(
                    NLS_SCHEME_CATMULL_CLARK,
                    flags,
                    p.as_ptr(),
                    4,
                    off.as_ptr(),
                    1,
                    idx.as_ptr(),
                    4,
                    0,
                    scratch.as_mut_ptr(),
                    su0,
                    &mut nv,
                    &mut nf,
                    &mut ni,
                    &mut su,
                    &mut sp,
                    core::ptr::null_mut(),
                )
            };
            assert_eq!(s, Status::Ok);
            assert_eq!((nv, nf, ni, su, sp), (4, 1, 4, su0, 0), "flags {flags}");
            for (cap, want) in [(su, Status::Ok), (su - 1, Status::BufferTooSmall)] {
                let mut scratch = vec![0u32; cap];
                let (mut op, mut oo, mut oi) = (vec![9.0; 12], vec![9u32; 2], vec![9u32; 4]);
                let (mut nv, mut nf, mut ni) = (0usize, 0usize, 0usize);
                let mut element = 7u32;
                let s = unsafe {
                    nls_mesh_subdivide_levels(
                        NLS_SCHEME_CATMULL_CLARK,
                        flags,
                        p.as_ptr(),
                        4,
                        off.as_ptr(),
                        1,
                        idx.as_ptr(),
                        4,
                        0,
                        scratch.as_mut_ptr(),
                        cap,
                        core::ptr::null_mut(),
                        0,
                        op.as_mut_ptr(),
                        4,
                        oo.as_mut_ptr(),
                        1,
                        oi.as_mut_ptr(),
                        4,
                        &mut nv,
                        &mut nf,
                        &mut ni,
                        core::ptr::null_mut(),
                        &mut element,
                    )
                };
                assert_eq!(s, want, "flags {flags}, scratch {cap}");
                if want == Status::Ok {
                    assert_eq!((nv, nf, ni), (4, 1, 4));
                    assert_eq!((&op[..], &oo[..], &oi[..]), (&p[..], &off[..], &idx[..]));
                } else {
                    assert_eq!(element, NLS_MESH_BUFFER_SCRATCH_U32);
                }
            }
        }
    }
}

// Differential-space subdivision (seed 001) shares this module's buffer checks.
#[path = "differential.rs"]
pub mod differential;
