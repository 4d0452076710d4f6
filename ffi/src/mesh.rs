//! Exports of whole-mesh subdivision (`nlsubdiv::scheme`): the linear schemes and their
//! canonical Möbius versions (seed 000 §4), one level or several, over caller buffers.
//!
//! Buffers follow meshoptimizer: positions `x, y, z` per vertex (packed, or with a byte
//! stride in the input), faces in CSR form, `offsets[face_count + 1]` and
//! `indices[index_count]`, counter-clockwise seen from outside. Scratch comes from the caller
//! in two arrays: `uint32_t` entries (the half-edge topology) and points (`double[3*n]`, the
//! candidates of the Möbius schemes and the intermediate levels of a multi-level call). No
//! buffer is allocated, none is kept.
//!
//! The arguments travel in plain-data structs (`nls_mesh_view`, `nls_mesh_buffers`,
//! `nls_scratch`, `nls_subdivide_options`), so that no export needs more than ten
//! parameters and the same description of a mesh serves every call.

use core::mem::size_of;
use core::ptr::null;

use nlsubdiv::exec::{Executor, Serial};
use nlsubdiv::mesh::{Mesh, MeshOut, MeshSizes, MAX_COUNT};
use nlsubdiv::scheme::{self, Options, Report, Scheme, Scratch, Tags, VertexWeights};
use nlsubdiv::{Error, Point, Status, NO_ELEMENT};

use crate::executor::{nls_executor, HostExecutor};
use crate::guard::{check_fp_env, check_ptr};
use crate::primitives::run;
use crate::tags::{
    check_tags, nls_tags, plan_need, read_tags, tag_raw_spans, tag_spans, tags_of, RawTags,
};
use crate::weights::{check_weights, weight_raw_span, weight_span, weights_of};

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
/// Subdivision flag (with `NLS_SUBDIVIDE_MOBIUS`): the paper's Möbius rules exactly (seed
/// 000 §4), without the fold guard. By default a star whose canonical form is
/// ill-conditioned (a Möbius-invariant test) is evaluated in a form interpolated toward the
/// linear rule, which removes most folds on real meshes; the report counts those elements
/// (`guarded`), and `NLS_SUBDIVIDE_STRICT` refuses the first one.
pub const NLS_SUBDIVIDE_LITERAL: u32 = 1u32 << 2;

/// `out_element` on `NLS_STATUS_BUFFER_TOO_SMALL`: the `uint32_t` scratch is short.
pub const NLS_MESH_BUFFER_SCRATCH_U32: u32 = 0;
/// `out_element` on `NLS_STATUS_BUFFER_TOO_SMALL`: the point scratch is short.
pub const NLS_MESH_BUFFER_SCRATCH_POINTS: u32 = 1;
/// `out_element` on `NLS_STATUS_BUFFER_TOO_SMALL`: the output positions are short.
pub const NLS_MESH_BUFFER_POSITIONS: u32 = 2;
/// `out_element` on `NLS_STATUS_BUFFER_TOO_SMALL`: the output offsets are short.
pub const NLS_MESH_BUFFER_OFFSETS: u32 = 3;
/// `out_element` on `NLS_STATUS_BUFFER_TOO_SMALL`: the output indices are short.
pub const NLS_MESH_BUFFER_INDICES: u32 = 4;

/// The largest number of levels of one `nls_mesh_subdivide` or `nls_differential_subdivide`
/// call.
pub const NLS_MAX_LEVELS: u32 = 16;

/// An input mesh, read only. Plain data: the library reads the struct and the arrays it
/// points to during a call and keeps nothing.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct nls_mesh_view {
    /// Vertex `v` is `x, y, z` at byte offset `v * positions_stride` (other attributes may
    /// follow each vertex; they are not read).
    pub positions: *const f64,
    /// Number of vertices (referenced or not).
    pub vertex_count: usize,
    /// Bytes from one vertex to the next: 0 means packed (24 bytes); any other value must be
    /// a multiple of 8 and at least 24, else `NLS_STATUS_INVALID_ARGUMENT`.
    pub positions_stride: usize,
    /// `face_count + 1` entries: `offsets[0] = 0`, non-decreasing,
    /// `offsets[face_count] = index_count` (never NULL; an empty mesh is `{0}`).
    pub offsets: *const u32,
    /// Number of faces.
    pub face_count: usize,
    /// The corners of all faces, face after face (`offsets[face_count]` entries).
    pub indices: *const u32,
    /// Number of corners (entries of `indices`).
    pub index_count: usize,
}

/// Output buffers and their capacities (positions always packed: 3 doubles per vertex).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct nls_mesh_buffers {
    /// Room for `vertex_capacity` points (`3 * vertex_capacity` doubles).
    pub positions: *mut f64,
    /// Points `positions` holds.
    pub vertex_capacity: usize,
    /// Room for `face_capacity + 1` entries.
    pub offsets: *mut u32,
    /// Faces `offsets` can describe.
    pub face_capacity: usize,
    /// Room for `index_capacity` entries.
    pub indices: *mut u32,
    /// Entries `indices` holds.
    pub index_capacity: usize,
}

/// The sizes of a mesh: what a call writes, or must be able to write.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct nls_mesh_sizes {
    /// Number of vertices (points).
    pub vertex_count: usize,
    /// Number of faces (the offsets buffer holds one more entry).
    pub face_count: usize,
    /// Number of corners (entries of the indices buffer).
    pub index_count: usize,
}

/// Caller scratch: `uint32_t` entries and points. The contents are unspecified after a call.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct nls_scratch {
    /// Room for `u32_capacity` entries.
    pub u32s: *mut u32,
    /// Entries `u32s` holds.
    pub u32_capacity: usize,
    /// Room for `point_capacity` points (`3 * point_capacity` doubles).
    pub points: *mut f64,
    /// Points `points` holds.
    pub point_capacity: usize,
}

/// What `nls_mesh_plan` and `nls_mesh_subdivide` are asked to do. Start from
/// `nls_subdivide_default_options`; later versions append fields whose defaults keep the
/// behaviour of this one.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct nls_subdivide_options {
    /// `NLS_SCHEME_*`.
    pub scheme: u32,
    /// `NLS_SUBDIVIDE_MOBIUS`, `NLS_SUBDIVIDE_STRICT`, `NLS_SUBDIVIDE_LITERAL`; other bits
    /// are `NLS_STATUS_INVALID_ARGUMENT`.
    pub flags: u32,
    /// Levels, 0 to `NLS_MAX_LEVELS` (0 validates the mesh and copies it).
    pub levels: u32,
    /// With `NLS_SUBDIVIDE_MOBIUS`: the weight `u` of the linear result in the Möbius–linear
    /// spectrum of seed 000 §7.2, in [0, 1]; each level's output is
    /// `(1 − u) · Möbius + u · linear`, so 0 (the default, and what a zero-initialised
    /// struct holds) is the Möbius result and 1 the linear one, bit for bit. NaN or outside
    /// [0, 1] is `NLS_STATUS_INVALID_ARGUMENT`.
    pub linear_weight: f64,
    /// NULL (the default): every pass on the calling thread. Otherwise the host's thread pool
    /// (`nls_executor`): each pass of a level is split into at most `max_tasks` disjoint
    /// output ranges that `run` executes on the host's threads. The output, the report and the
    /// errors are bit for bit those of a NULL executor, for every task count and order. Read by
    /// `nls_mesh_subdivide` and `nls_mesh_subdivide_tagged` (planning runs on the calling
    /// thread; with tags the executor is checked but the tagged rules run on the calling
    /// thread).
    /// What is split: the positions of the linear and spherelike rules, the Möbius vertex
    /// pass and the fold guard's re-evaluation (the canonical forms and the rules in them,
    /// by vertex ranges), blends and vertex points, the finiteness checks; the rest of a
    /// level is serial (`docs/architecture.md`).
    pub executor: *const nls_executor,
    /// NULL (the default, and what a zero-initialised struct holds): every vertex takes
    /// `linear_weight`. Otherwise, with `NLS_SUBDIVIDE_MOBIUS`, `mesh.vertex_count` doubles:
    /// the weight `u ∈ [0, 1]` of the linear result at each input vertex (the convention of
    /// `linear_weight`, which they replace). Each output vertex of each level takes a weight
    /// carried from its parents like a vertex attribute (an old vertex keeps its weight, an
    /// edge point takes the mean of its edge's ends, a face point the mean of its face's
    /// corners, a Doo–Sabin corner point its vertex's weight; equal weights stay exactly
    /// equal) and is `(1 − u) · Möbius + u · linear` of its level: all 0 is the Möbius
    /// result, all 1 the linear one, all equal to `linear_weight` the global weight, bit for
    /// bit; a vertex of weight exactly 0 or 1 takes the Möbius or the linear point of its
    /// level exactly (`docs/folds.md`, "The spectrum"). A weight that is NaN or outside
    /// [0, 1] is `NLS_STATUS_INVALID_ARGUMENT` with `out_element` = the vertex, found by
    /// `nls_mesh_plan` too, before anything is written. Read (and checked) without
    /// `NLS_SUBDIVIDE_MOBIUS` too, without effect. An input: it may overlap the other inputs,
    /// no output or scratch buffer (`NLS_STATUS_ALIASING_BUFFERS`); a misaligned array is
    /// `NLS_STATUS_MISALIGNED_POINTER`.
    pub linear_weights: *const f64,
}

/// What a subdivision call needs, from `nls_mesh_plan` or `nls_differential_plan` (the struct
/// is `nls_plan`: C has one name space for functions and types).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct nls_plan {
    /// The exact sizes of the output: what the output buffers must hold.
    pub output: nls_mesh_sizes,
    /// The exact `uint32_t` scratch of the subdivision call (entries).
    pub scratch_u32: usize,
    /// The exact point scratch of the subdivision call (points, 3 doubles each).
    pub scratch_points: usize,
}

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
    /// The level of `first_fallback`, counted from 1, or 0 when there was no fallback.
    pub first_fallback_level: u32,
    /// Output vertices the Möbius fold guard changed (all levels; 0 with
    /// `NLS_SUBDIVIDE_LITERAL` and for the linear schemes).
    pub guarded: u32,
    /// The first such output vertex (of level `first_guarded_level`), or `NLS_NO_ELEMENT`.
    pub first_guarded: u32,
    /// The level of `first_guarded`, counted from 1, or 0 when the guard changed nothing.
    pub first_guarded_level: u32,
}

/// The Rust path's spectrum weight `w` (of the Möbius result) from the C struct's weight of
/// the linear result, `w = 1 − u`: exact at both ends, so 0 and 1 give the Möbius and the
/// linear results bit for bit.
fn spectrum_of(u: f64) -> Result<f64, Status> {
    if u.is_nan() || !(0.0..=1.0).contains(&u) {
        return Err(Status::InvalidArgument);
    }
    Ok(1.0 - u)
}

/// The options struct as the Rust path's options.
pub(crate) fn parse_options(o: &nls_subdivide_options) -> Result<Options, Status> {
    let scheme = Scheme::from_code(o.scheme).ok_or(Status::InvalidArgument)?;
    let flags = o.flags;
    if flags & !(NLS_SUBDIVIDE_MOBIUS | NLS_SUBDIVIDE_STRICT | NLS_SUBDIVIDE_LITERAL) != 0 {
        return Err(Status::InvalidArgument);
    }
    if flags & NLS_SUBDIVIDE_MOBIUS != 0 && !scheme.has_mobius_form() {
        return Err(Status::InvalidArgument);
    }
    if o.levels > NLS_MAX_LEVELS {
        return Err(Status::InvalidArgument);
    }
    Ok(Options::new(scheme)
        .mobius(flags & NLS_SUBDIVIDE_MOBIUS != 0)
        .strict(flags & NLS_SUBDIVIDE_STRICT != 0)
        .literal(flags & NLS_SUBDIVIDE_LITERAL != 0)
        .spectrum(spectrum_of(o.linear_weight)?)
        .levels(o.levels as usize))
}

/// A failure: the status and the element written to `out_element`.
pub(crate) struct Fail {
    pub(crate) status: Status,
    pub(crate) element: u32,
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

pub(crate) fn too_small(buffer: u32) -> Fail {
    Fail {
        status: Status::BufferTooSmall,
        element: buffer,
    }
}

/// Whether `out_element` may be written on failure: set to false by [`check_out_pointers`]
/// when it points into a buffer of the call (the write would corrupt it).
pub(crate) struct ElementSlot {
    ptr: *mut u32,
    writable: bool,
}

/// Runs an export body; on failure writes the element to `out_element` when it is a valid
/// pointer that points into no buffer of the call (the one exception to "written only on
/// success").
pub(crate) fn run_with_element(
    out_element: *mut u32,
    body: impl FnOnce(&mut ElementSlot) -> Result<(), Fail>,
) -> Status {
    let _traps = crate::guard::FpTrapGuard::mask_traps();
    let mut slot = ElementSlot {
        ptr: out_element,
        writable: !out_element.is_null() && out_element.is_aligned(),
    };
    match body(&mut slot) {
        Ok(()) => Status::Ok,
        Err(f) => {
            if slot.writable {
                // SAFETY: non-NULL, aligned, outside every buffer of the call; writable by the
                // caller's contract. Every slice formed from the caller's buffers is gone.
                unsafe { slot.ptr.write(f.element) };
            }
            f.status
        }
    }
}

impl ElementSlot {
    /// Closes the slot unless the call can name every caller buffer and `out_element` lies in
    /// none of them nor in another out-pointer. Runs before any check can fail, so an early
    /// failure (a NULL or misaligned struct, a bad stride, a misaligned out-pointer) never
    /// writes into a caller's buffer. `named` holds one entry per argument that describes
    /// buffers: `None` when they cannot be named (see [`named`]). Where the slot is closed,
    /// `out_element` keeps the caller's value.
    pub(crate) fn close_unless_clear(&mut self, outs: &[Span], named: &[Option<Span>]) {
        if !is_clear(Span::of_one(self.ptr), outs, named) {
            self.writable = false;
        }
    }
}

/// Whether the out-element range `e` lies in no out-pointer of `outs` and in no buffer of
/// `named`, every one of which could be named (see [`ElementSlot::close_unless_clear`]).
pub(crate) fn is_clear(e: Span, outs: &[Span], named: &[Option<Span>]) -> bool {
    named.iter().all(|n| n.is_some_and(|b| !e.overlaps(b))) && !outs.iter().any(|o| e.overlaps(*o))
}

/// The buffers described by a struct argument `p`, read (or refused) as `r`: their byte
/// ranges as given (not yet checked) when it was read; none when `p` is NULL (a NULL struct
/// describes no buffer); `None` each when they cannot be named (a misaligned struct, or a
/// mesh view whose stride or size is invalid).
pub(crate) fn named<P, T, const N: usize>(
    p: *const P,
    r: &Result<T, Status>,
    spans: impl Fn(&T) -> [Span; N],
) -> [Option<Span>; N] {
    match r {
        Ok(v) => spans(v).map(Some),
        Err(_) if p.is_null() => [Some(Span::EMPTY); N],
        Err(_) => [None; N],
    }
}

/// Checks an optional out-parameter (NULL allowed).
pub(crate) fn check_optional<T>(p: *mut T) -> Result<(), Status> {
    check_ptr(p.cast_const(), usize::from(!p.is_null()))
}

/// Reads a struct argument.
///
/// # Safety
/// `p` is NULL or points to a readable `T`.
pub(crate) unsafe fn read_arg<T: Copy>(p: *const T) -> Result<T, Status> {
    check_ptr(p, 1)?;
    // SAFETY: checked non-NULL and aligned; readable by the caller's contract.
    Ok(unsafe { p.read() })
}

/// # Safety
/// `p` passed `check_ptr(p, 1)` (non-NULL, aligned) and points to a writable `T`.
pub(crate) unsafe fn store<T>(p: *mut T, v: T) {
    // SAFETY: by the caller's contract.
    unsafe { p.write(v) };
}

/// A byte range of a caller buffer, for the overlap checks.
#[derive(Clone, Copy)]
pub(crate) struct Span {
    start: usize,
    bytes: usize,
}

impl Span {
    /// No bytes.
    pub(crate) const EMPTY: Span = Span { start: 0, bytes: 0 };

    /// `count` elements of `T` at `p` as given, for the out-element decision, which must
    /// count a misaligned buffer too: empty when `p` is NULL or the size exceeds `isize::MAX`
    /// bytes (no object is that large; the buffer's own check refuses it).
    pub(crate) fn raw<T>(p: *const T, count: usize) -> Span {
        match count.checked_mul(size_of::<T>()) {
            Some(bytes) if !p.is_null() && bytes <= isize::MAX as usize => Span::of(p, count),
            _ => Span::EMPTY,
        }
    }

    /// `count` elements of `T` at `p` (saturating: the pointer checks bound real sizes).
    pub(crate) fn of<T>(p: *const T, count: usize) -> Span {
        Span {
            start: p as usize,
            bytes: count.saturating_mul(size_of::<T>()),
        }
    }

    /// `count` elements of `T` at `p` when that is a valid buffer (`check_ptr`), else nothing:
    /// a buffer that fails its own check is reported as such, never as an overlap.
    pub(crate) fn checked<T>(p: *const T, count: usize) -> Span {
        match check_ptr(p, count) {
            Ok(()) => Span::of(p, count),
            Err(_) => Span::EMPTY,
        }
    }

    /// One `T` at `p` when `p` is not NULL, else nothing.
    pub(crate) fn of_one<T>(p: *mut T) -> Span {
        Span::of(p.cast_const(), usize::from(!p.is_null()))
    }

    pub(crate) fn overlaps(self, other: Span) -> bool {
        self.bytes > 0
            && other.bytes > 0
            && self.start < other.start.saturating_add(other.bytes)
            && other.start < self.start.saturating_add(self.bytes)
    }
}

/// The out-pointers of a call (`out_sizes`, `out_report`, `out_plan`, `out_element`: each
/// one value) must not point into any buffer of the call nor into each other: a write
/// through one would corrupt an input, an output or scratch (`NLS_STATUS_ALIASING_BUFFERS`).
/// `out_element` is then not written either.
pub(crate) fn check_out_pointers(
    outs: &[Span],
    element: &mut ElementSlot,
    buffers: &[Span],
) -> Result<(), Status> {
    let e = Span::of_one(element.ptr);
    let all_outs = || outs.iter().copied().chain(core::iter::once(e));
    for (i, o) in all_outs().enumerate() {
        let clash =
            buffers.iter().any(|b| o.overlaps(*b)) || all_outs().skip(i + 1).any(|b| o.overlaps(b));
        if clash {
            if buffers.iter().any(|b| e.overlaps(*b)) || outs.iter().any(|b| e.overlaps(*b)) {
                element.writable = false;
            }
            return Err(Status::AliasingBuffers);
        }
    }
    Ok(())
}

/// The input mesh of a call, with its positions described as `f64`s.
#[derive(Clone, Copy)]
pub(crate) struct RawMesh {
    view: nls_mesh_view,
    /// Stride in `f64`s (3 when packed).
    stride: usize,
    /// `f64`s from the first coordinate to the last one read.
    coords: usize,
}

impl RawMesh {
    /// Reads the view and its stride rule.
    ///
    /// # Safety
    /// `p` is NULL or points to a readable `nls_mesh_view`.
    pub(crate) unsafe fn read(p: *const nls_mesh_view) -> Result<RawMesh, Status> {
        // SAFETY: by the caller's contract.
        let view = unsafe { read_arg(p) }?;
        let stride = match view.positions_stride {
            0 => 3,
            s if s % 8 == 0 && s >= 24 => s / 8,
            _ => return Err(Status::InvalidArgument),
        };
        let coords = match view.vertex_count {
            0 => 0,
            n => (n - 1)
                .checked_mul(stride)
                .and_then(|c| c.checked_add(3))
                .ok_or(Status::SizeOverflow)?,
        };
        Ok(RawMesh {
            view,
            stride,
            coords,
        })
    }

    /// The byte ranges of the three input arrays as given (see [`Span::raw`]).
    pub(crate) fn raw_spans(&self) -> [Span; 3] {
        let v = &self.view;
        [
            Span::raw(v.positions, self.coords),
            Span::raw(v.offsets, v.face_count.saturating_add(1)),
            Span::raw(v.indices, v.index_count),
        ]
    }

    /// The three input arrays of the view at `p`, read as `r`, for the out-element decision
    /// (see [`named`]). A view refused for its stride names its positions `None` (their
    /// extent is unknown); one refused because the extent overflows names them as no memory
    /// (no object is that large); its offsets and indices are named either way.
    ///
    /// # Safety
    /// `p` is NULL or points to a readable `nls_mesh_view`.
    pub(crate) unsafe fn named(
        p: *const nls_mesh_view,
        r: &Result<RawMesh, Status>,
    ) -> [Option<Span>; 3] {
        // SAFETY: by the caller's contract.
        let view = match (r, unsafe { read_arg(p) }) {
            (Ok(m), _) => return m.raw_spans().map(Some),
            (Err(_), Ok(view)) => view,
            (Err(_), Err(_)) => return named(p, r, |_| [Span::EMPTY; 3]),
        };
        let positions = match r {
            Err(Status::SizeOverflow) => Some(Span::EMPTY),
            _ => None,
        };
        [
            positions,
            Some(Span::raw(view.offsets, view.face_count.saturating_add(1))),
            Some(Span::raw(view.indices, view.index_count)),
        ]
    }

    /// The byte ranges of the three input arrays (empty for an array that fails its check).
    pub(crate) fn spans(&self) -> [Span; 3] {
        let v = &self.view;
        [
            Span::checked(v.positions, self.coords),
            Span::checked(v.offsets, v.face_count.saturating_add(1)),
            Span::checked(v.indices, v.index_count),
        ]
    }

    /// Checks the three input pointers (NULL, alignment, size).
    pub(crate) fn check(&self) -> Result<(), Status> {
        let v = &self.view;
        let offsets_len = v.face_count.checked_add(1).ok_or(Status::SizeOverflow)?;
        check_ptr(v.positions, self.coords)?;
        check_ptr(v.offsets, offsets_len)?;
        check_ptr(v.indices, v.index_count)
    }

    pub(crate) fn vertex_count(&self) -> usize {
        self.view.vertex_count
    }

    pub(crate) fn index_count(&self) -> usize {
        self.view.index_count
    }

    /// The `uint32_t` scratch of the input's topology (the validation), from the counts.
    pub(crate) fn topology_need(&self) -> Result<usize, Status> {
        let v = &self.view;
        if v.vertex_count > MAX_COUNT || v.index_count > MAX_COUNT {
            return Err(Status::SizeOverflow);
        }
        nlsubdiv::mesh::topology_scratch_size(v.vertex_count, v.index_count).map_err(|e| e.status)
    }

    /// The core's view of the mesh; strided positions are read in place.
    ///
    /// # Safety
    /// [`RawMesh::check`] passed, and the three buffers are readable for their counts and not
    /// written while the view lives.
    pub(crate) unsafe fn mesh<'a>(&self) -> Result<Mesh<'a>, Status> {
        let v = &self.view;
        // SAFETY: by the caller's contract (checked, readable, unaliased by writes).
        let (coords, offsets, indices) = unsafe {
            (
                slice(v.positions, self.coords),
                slice(v.offsets, v.face_count.saturating_add(1)),
                slice(v.indices, v.index_count),
            )
        };
        Mesh::with_stride(coords, self.stride, v.vertex_count, offsets, indices)
            .map_err(|e| e.status)
    }
}

/// # Safety
/// `p` passed `check_ptr(p, count)` and is readable for `count` elements during `'a`.
pub(crate) unsafe fn slice<'a, T>(p: *const T, count: usize) -> &'a [T] {
    if count == 0 {
        return &[];
    }
    // SAFETY: non-NULL, aligned, byte size ≤ isize::MAX (checked), readable (contract).
    unsafe { core::slice::from_raw_parts(p, count) }
}

/// # Safety
/// `p` passed `check_ptr(p, count)`, is writable for `count` elements and overlaps no other
/// slice alive during `'a`.
pub(crate) unsafe fn slice_mut<'a, T>(p: *mut T, count: usize) -> &'a mut [T] {
    if count == 0 {
        return &mut [];
    }
    // SAFETY: non-NULL, aligned, byte size ≤ isize::MAX (checked), writable and unaliased
    // (contract and the overlap checks).
    unsafe { core::slice::from_raw_parts_mut(p, count) }
}

/// The caller's scratch and output buffers of a subdivision call.
#[derive(Clone, Copy)]
pub(crate) struct RawOut {
    pub(crate) scratch: nls_scratch,
    pub(crate) out: nls_mesh_buffers,
}

/// The byte ranges of the scratch struct's two buffers as given (see [`Span::raw`]).
pub(crate) fn scratch_raw_spans(s: &nls_scratch) -> [Span; 2] {
    [
        Span::raw(s.u32s.cast_const(), s.u32_capacity),
        Span::raw(s.points.cast_const().cast::<Point>(), s.point_capacity),
    ]
}

/// The byte ranges of the output struct's three buffers as given (see [`Span::raw`]).
pub(crate) fn out_raw_spans(o: &nls_mesh_buffers) -> [Span; 3] {
    [
        Span::raw(o.positions.cast_const().cast::<Point>(), o.vertex_capacity),
        Span::raw(o.offsets.cast_const(), o.face_capacity.saturating_add(1)),
        Span::raw(o.indices.cast_const(), o.index_capacity),
    ]
}

impl RawOut {
    /// The byte ranges of the five buffers (empty for a buffer that fails its check).
    pub(crate) fn spans(&self) -> [Span; 5] {
        let (s, o) = (&self.scratch, &self.out);
        [
            Span::checked(s.u32s.cast_const(), s.u32_capacity),
            Span::checked(s.points.cast_const().cast::<Point>(), s.point_capacity),
            Span::checked(o.positions.cast_const().cast::<Point>(), o.vertex_capacity),
            Span::checked(o.offsets.cast_const(), o.face_capacity.saturating_add(1)),
            Span::checked(o.indices.cast_const(), o.index_capacity),
        ]
    }

    /// Checks every pointer and that no buffer overlaps an input or another buffer.
    pub(crate) fn check(&self, inputs: &[Span]) -> Result<(), Status> {
        let (s, o) = (&self.scratch, &self.out);
        let offsets_len = o.face_capacity.checked_add(1).ok_or(Status::SizeOverflow)?;
        check_ptr(s.u32s.cast_const(), s.u32_capacity)?;
        check_ptr(s.points.cast_const().cast::<Point>(), s.point_capacity)?;
        check_ptr(o.positions.cast_const().cast::<Point>(), o.vertex_capacity)?;
        check_ptr(o.offsets.cast_const(), offsets_len)?;
        check_ptr(o.indices.cast_const(), o.index_capacity)?;
        let spans = self.spans();
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
    pub(crate) fn check_sizes(&self, sizes: &MeshSizes) -> Result<(), Fail> {
        if self.out.vertex_capacity < sizes.vertices {
            return Err(too_small(NLS_MESH_BUFFER_POSITIONS));
        }
        if self.out.face_capacity < sizes.faces {
            return Err(too_small(NLS_MESH_BUFFER_OFFSETS));
        }
        if self.out.index_capacity < sizes.indices {
            return Err(too_small(NLS_MESH_BUFFER_INDICES));
        }
        Ok(())
    }

    /// The five buffers as slices: `(scratch_u32, scratch_points, outputs)`.
    ///
    /// # Safety
    /// [`RawOut::check`] passed and the buffers are writable for their capacities during
    /// `'a`; no other reference to them is alive.
    pub(crate) unsafe fn slices<'a>(&self) -> (&'a mut [u32], &'a mut [Point], MeshOut<'a>) {
        let (s, o) = (&self.scratch, &self.out);
        // SAFETY: checked (NULL, alignment, size) and pairwise disjoint (RawOut::check);
        // writable by the caller's contract.
        unsafe {
            (
                slice_mut(s.u32s, s.u32_capacity),
                slice_mut(s.points.cast::<Point>(), s.point_capacity),
                MeshOut::new(
                    slice_mut(o.positions.cast::<Point>(), o.vertex_capacity),
                    slice_mut(o.offsets, o.face_capacity.saturating_add(1)),
                    slice_mut(o.indices, o.index_capacity),
                ),
            )
        }
    }
}

/// The C sizes of Rust ones.
pub(crate) fn sizes_of(s: &MeshSizes) -> nls_mesh_sizes {
    nls_mesh_sizes {
        vertex_count: s.vertices,
        face_count: s.faces,
        index_count: s.indices,
    }
}

/// The C report of a Rust one.
fn report_of(r: &Report) -> nls_subdivide_report {
    nls_subdivide_report {
        fallbacks: r.fallbacks,
        first_fallback: r.first_fallback,
        first_fallback_level: r.first_fallback_level,
        guarded: r.guarded,
        first_guarded: r.first_guarded,
        first_guarded_level: r.first_guarded_level,
    }
}

/// The one call of the Rust path (`scheme::subdivide`) behind `nls_mesh_subdivide`. On
/// `NLS_STATUS_BUFFER_TOO_SMALL` the plan (computed again, on the error path only) names the
/// first short buffer in the order `scratch_u32`, `scratch_points`, positions, offsets,
/// indices, and `needed` receives the output sizes when the short buffer is an output buffer.
#[allow(clippy::too_many_arguments)] // internal: the buffers of the call, split
fn subdivide_call(
    view: Mesh<'_>,
    (opts, tags, weights): (&Options, &Tags<'_>, Option<VertexWeights<'_>>),
    exec: Option<&HostExecutor>,
    su: &mut [u32],
    sp: &mut [Point],
    out: &mut MeshOut<'_>,
    raw: &RawOut,
    needed: &mut Option<MeshSizes>,
) -> Result<Report, Fail> {
    let scratch = Scratch::new(&mut *su, &mut *sp);
    // The tagged rules run on the calling thread (their passes are not split).
    let x: &dyn Executor = match exec {
        Some(x) if tags.is_empty() => x,
        _ => &Serial,
    };
    let result = scheme::subdivide_weighted(view, opts, tags, weights, scratch, out, x);
    if exec.is_some_and(HostExecutor::fp_refused) {
        // A task found its pool thread's floating-point modes changed and did not run.
        return Err(Status::FpEnvironment.into());
    }
    match result {
        Ok(report) => Ok(report),
        Err(e) if e.status == Status::BufferTooSmall => {
            too_small_buffer(view, (opts, tags, weights), su, sp, raw, needed, e)
        }
        Err(e) => Err(e.into()),
    }
}

/// Which buffer of a call that failed with `BufferTooSmall` (`e`) was short, from the plan.
/// Out of line, so that the plan is not in the frame of every call (`docs/firmware.md`,
/// "Stack").
#[inline(never)]
fn too_small_buffer(
    view: Mesh<'_>,
    (opts, tags, weights): (&Options, &Tags<'_>, Option<VertexWeights<'_>>),
    su: &mut [u32],
    sp: &[Point],
    raw: &RawOut,
    needed: &mut Option<MeshSizes>,
    e: nlsubdiv::Error,
) -> Result<Report, Fail> {
    let plan = scheme::plan_weighted(view, opts, tags, weights, su)?;
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

/// Writes the default options: `NLS_SCHEME_LOOP`, no flags (linear, not strict), 1 level.
///
/// @return `NLS_STATUS_NULL_PARAMETER` or `NLS_STATUS_MISALIGNED_POINTER` for a bad
/// `out_options`, else `NLS_STATUS_OK`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_subdivide_default_options(
    out_options: *mut nls_subdivide_options,
) -> Status {
    run(|| {
        check_ptr(out_options.cast_const(), 1)?;
        // SAFETY: checked above; writable by the caller's contract.
        unsafe {
            store(
                out_options,
                nls_subdivide_options {
                    scheme: NLS_SCHEME_LOOP,
                    flags: 0,
                    levels: 1,
                    linear_weight: 0.0,
                    executor: core::ptr::null(),
                    linear_weights: core::ptr::null(),
                },
            )
        };
        Ok(())
    })
}

/// The `uint32_t` scratch `nls_mesh_plan` (and `nls_differential_plan`) needs for `mesh`: its
/// half-edge topology, `4 * index_count + 3 * vertex_count` entries. Depends on the counts
/// (and the stride rule) only: no array of the mesh is read.
///
/// @param mesh the input mesh.
/// @param out_scratch_u32 receives the number of `uint32_t` entries.
/// @return `NLS_STATUS_SIZE_OVERFLOW` (a count above `UINT32_MAX − 1`),
/// `NLS_STATUS_INVALID_ARGUMENT` (a bad stride), `NLS_STATUS_NULL_PARAMETER`,
/// `NLS_STATUS_MISALIGNED_POINTER`, else `NLS_STATUS_OK`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mesh_plan_scratch_size(
    mesh: *const nls_mesh_view,
    out_scratch_u32: *mut usize,
) -> Status {
    run(|| {
        check_ptr(out_scratch_u32.cast_const(), 1)?;
        // SAFETY: the caller passes NULL or a readable view.
        let mesh = unsafe { RawMesh::read(mesh) }?;
        let need = mesh.topology_need()?;
        // SAFETY: checked above.
        unsafe { store(out_scratch_u32, need) };
        Ok(())
    })
}

/// Validates the mesh and the options and plans `nls_mesh_subdivide`: the exact output sizes
/// and the exact scratch of the call with the same mesh and options. The sizes of every
/// level are exact functions of a few counts of the input, so nothing is subdivided here.
///
/// `scratch_u32` holds `scratch_u32_capacity` entries, at least what
/// `nls_mesh_plan_scratch_size` gives; it must not overlap the mesh and its contents are
/// unspecified afterwards.
///
/// Validation, topology first and before anything else is computed (the first failure wins):
/// `NLS_STATUS_SIZE_OVERFLOW` (a count above `UINT32_MAX − 1`), `NLS_STATUS_BAD_OFFSETS`,
/// `NLS_STATUS_FACE_TOO_SMALL`, `NLS_STATUS_VALENCE_TOO_HIGH` (a face above `nls_max_face_size()` corners),
/// `NLS_STATUS_INDEX_OUT_OF_RANGE`, `NLS_STATUS_REPEATED_VERTEX` (each naming the face),
/// `NLS_STATUS_DUPLICATE_FACE`, `NLS_STATUS_INCONSISTENT_ORIENTATION`,
/// `NLS_STATUS_NON_MANIFOLD_EDGE` (naming the later face on the edge),
/// `NLS_STATUS_NON_MANIFOLD_VERTEX` (bow-tie), `NLS_STATUS_VALENCE_TOO_HIGH` (a vertex above
/// 128 neighbours), `NLS_STATUS_NON_FINITE_INPUT` (each naming the vertex), then, for one or
/// more levels, the scheme's own: `NLS_STATUS_UNSUPPORTED_FACE_TYPE` (Loop and Modified
/// Butterfly accept triangles, Kobbelt quads; naming the face), `NLS_STATUS_FACE_TOO_SMALL`
/// naming an interior valence-2 vertex (dual schemes), `NLS_STATUS_VALENCE_TOO_HIGH` (an
/// output vertex or face above the capacity; no element when a later level would exceed
/// it), `NLS_STATUS_SIZE_OVERFLOW` (a level above `UINT32_MAX − 1` vertices, faces or
/// corners), and for `NLS_SCHEME_SPHERELIKE` `NLS_STATUS_NUMERICAL_FAILURE` for a mesh whose
/// size its squared distances cannot represent (largest bounding-box side below 1e-140, or a
/// coordinate above 1e140).
///
/// @param mesh the input mesh.
/// @param options scheme, flags, levels.
/// @param scratch_u32 `uint32_t` scratch for the validation.
/// @param scratch_u32_capacity entries of `scratch_u32`.
/// @param out_plan receives the plan, on success only.
/// @param out_element may be NULL; otherwise receives, on failure only, the element named
/// above, `NLS_MESH_BUFFER_SCRATCH_U32` on `NLS_STATUS_BUFFER_TOO_SMALL`, or
/// `NLS_NO_ELEMENT`.
/// @return `NLS_STATUS_OK`, a validation error above, `NLS_STATUS_BUFFER_TOO_SMALL`,
/// `NLS_STATUS_INVALID_ARGUMENT` (unknown scheme or flag bits, `NLS_SUBDIVIDE_MOBIUS` with
/// `NLS_SCHEME_SPHERELIKE`, more than `NLS_MAX_LEVELS` levels, a bad stride, a spectrum
/// weight NaN or outside [0, 1]: `linear_weight`, or one of `linear_weights`, which names its
/// vertex, before the mesh is validated),
/// `NLS_STATUS_SCHEME_NOT_BUILT` (the scheme, or with `NLS_SUBDIVIDE_MOBIUS` its Möbius form,
/// is left out of this build of the library by its Cargo features; checked with the options,
/// before the mesh is read), `NLS_STATUS_NULL_PARAMETER`, `NLS_STATUS_MISALIGNED_POINTER`,
/// `NLS_STATUS_ALIASING_BUFFERS` (the scratch overlaps the mesh, or an out-pointer points
/// into a buffer of the call or into the other out-pointer), `NLS_STATUS_FP_ENVIRONMENT`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mesh_plan(
    mesh: *const nls_mesh_view,
    options: *const nls_subdivide_options,
    scratch_u32: *mut u32,
    scratch_u32_capacity: usize,
    out_plan: *mut nls_plan,
    out_element: *mut u32,
) -> Status {
    // SAFETY: forwarded contract (no tags).
    unsafe {
        plan_body(
            mesh,
            options,
            None,
            scratch_u32,
            scratch_u32_capacity,
            out_plan,
            out_element,
        )
    }
}

/// The body of `nls_mesh_plan` and `nls_mesh_plan_tagged`.
///
/// # Safety
/// The contract of `nls_mesh_plan`; `tags` (the tagged export's) is NULL or points to a
/// readable `nls_tags`.
pub(crate) unsafe fn plan_body(
    mesh: *const nls_mesh_view,
    options: *const nls_subdivide_options,
    tags: Option<*const nls_tags>,
    scratch_u32: *mut u32,
    scratch_u32_capacity: usize,
    out_plan: *mut nls_plan,
    out_element: *mut u32,
) -> Status {
    run_with_element(out_element, |element| {
        // SAFETY: the caller passes NULL or readable structs.
        let (mesh_r, tags_r, opts_r) =
            unsafe { (RawMesh::read(mesh), read_tags(tags), read_arg(options)) };
        // SAFETY: the caller passes NULL or a readable view.
        let [a, b, c] = unsafe { RawMesh::named(mesh, &mesh_r) };
        let [d, e, f, g] = named(tags.unwrap_or(null()), &tags_r, tag_raw_spans);
        let w = weight_raw_span(options, &opts_r, &mesh_r);
        let su = Some(Span::raw(scratch_u32.cast_const(), scratch_u32_capacity));
        element.close_unless_clear(&[Span::of_one(out_plan)], &[a, b, c, d, e, f, g, w, su]);
        let (mesh, raw_opts) = (mesh_r?, opts_r?);
        let tags = tags_r?;
        let tags = tags.as_ref();
        check_ptr(out_plan.cast_const(), 1)?;
        check_optional(out_element)?;
        let [a, b, c] = mesh.spans();
        let [d, e, f, g] = tag_spans(tags);
        let w = weight_span(&raw_opts, &mesh);
        let su = Span::checked(scratch_u32.cast_const(), scratch_u32_capacity);
        check_out_pointers(
            &[Span::of_one(out_plan)],
            element,
            &[a, b, c, d, e, f, g, w, su],
        )?;
        let opts = parse_options(&raw_opts)?;
        mesh.check()?;
        check_tags(tags)?;
        check_weights(&raw_opts, &mesh)?;
        check_ptr(scratch_u32.cast_const(), scratch_u32_capacity)?;
        if [a, b, c, d, e, f, g, w].iter().any(|i| su.overlaps(*i)) {
            return Err(Status::AliasingBuffers.into());
        }
        if scratch_u32_capacity < plan_need(&mesh, tags)? {
            return Err(too_small(NLS_MESH_BUFFER_SCRATCH_U32));
        }
        check_fp_env()?;
        // SAFETY: inputs checked; scratch checked and disjoint from them.
        let (view, scratch) =
            unsafe { (mesh.mesh()?, slice_mut(scratch_u32, scratch_u32_capacity)) };
        // SAFETY: the tags and the weights were checked (NULL, alignment, size).
        let (tags, weights) = unsafe { (tags_of(tags)?, weights_of(&raw_opts, &mesh)) };
        let plan = scheme::plan_weighted(view, &opts, &tags, weights, scratch)?;
        let plan = nls_plan {
            output: sizes_of(&plan.output()),
            scratch_u32: plan.scratch.u32s,
            scratch_points: plan.scratch.points,
        };
        // SAFETY: checked above.
        unsafe { store(out_plan, plan) };
        Ok(())
    })
}

/// Subdivides the mesh: `options.levels` levels (0 validates and copies) of
/// `options.scheme`, linear or canonical Möbius (`NLS_SUBDIVIDE_MOBIUS`); the intermediate
/// levels live in the scratch, the last one is written to `out`. The result of `k` levels
/// equals `k` calls of one level, bit for bit. Buffer sizes come from `nls_mesh_plan` with the
/// same mesh and options. No buffer may overlap another one or the input
/// (`NLS_STATUS_ALIASING_BUFFERS`, checked before anything is read): in-place calls are not
/// supported.
///
/// Output order: primal schemes write the old vertices first at the same indices, then the
/// edge points in edge order (edges sorted by their `(min, max)` vertex pair), then the face
/// points in face order; the dual schemes as documented in `docs/mesh-and-linear-schemes.md`.
/// The Möbius version has the connectivity and order of the linear one. Interpolating schemes
/// keep the old vertices bit for bit.
///
/// `NLS_STATUS_BUFFER_TOO_SMALL`: `scratch->u32s` below `nls_mesh_plan_scratch_size` is found
/// before the mesh is validated; after planning, the first short buffer in the order
/// `scratch->u32s`, `scratch->points`, `out->positions`, `out->offsets`, `out->indices`.
/// `*out_element` names it (`NLS_MESH_BUFFER_*`) and, when it is an output buffer,
/// `*out_sizes` receives the exact sizes needed. Nothing is written to the output buffers
/// then. After any other error the contents of the output and scratch buffers are unspecified
/// and `*out_sizes` and `*out_report` are not written.
///
/// @param mesh the input mesh (positions may be strided).
/// @param options scheme, flags, levels.
/// @param scratch at least the scratch of `nls_mesh_plan` (NULL arrays with capacity 0 when
/// that is 0).
/// @param out the output buffers, at least the plan's output sizes.
/// @param out_sizes receives the sizes written (and see `NLS_STATUS_BUFFER_TOO_SMALL`).
/// @param out_report may be NULL; receives the fallbacks (summed over the levels; its
/// `first_fallback` is a vertex of level `first_fallback_level`).
/// @param out_element may be NULL; otherwise receives, on failure only: the element of a
/// validation error (see `nls_mesh_plan`), the output vertex (of the level being computed)
/// for `NLS_STATUS_FALLBACK_IN_STRICT_MODE`, `NLS_STATUS_NUMERICAL_FAILURE` and
/// `NLS_STATUS_DEGENERATE_GEOMETRY` (`NLS_SCHEME_SPHERELIKE`), the buffer for
/// `NLS_STATUS_BUFFER_TOO_SMALL`, else `NLS_NO_ELEMENT`.
/// @return `NLS_STATUS_OK`; the errors of `nls_mesh_plan`; `NLS_STATUS_BUFFER_TOO_SMALL`;
/// `NLS_STATUS_DEGENERATE_GEOMETRY` (`NLS_SCHEME_SPHERELIKE`: coincident points of one
/// circle, or a spike); `NLS_STATUS_FALLBACK_IN_STRICT_MODE` (`NLS_SUBDIVIDE_STRICT`);
/// `NLS_STATUS_NUMERICAL_FAILURE` (an output vertex would not be finite: coordinates near the
/// ends of the double range); `NLS_STATUS_ALIASING_BUFFERS` also when `out_sizes`,
/// `out_report` or `out_element` points into a buffer of the call or into another
/// out-pointer.
///
/// Stack on Cortex-M4F: at most 8,192 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mesh_subdivide(
    mesh: *const nls_mesh_view,
    options: *const nls_subdivide_options,
    scratch: *const nls_scratch,
    out: *const nls_mesh_buffers,
    out_sizes: *mut nls_mesh_sizes,
    out_report: *mut nls_subdivide_report,
    out_element: *mut u32,
) -> Status {
    // SAFETY: forwarded contract (no tags).
    unsafe {
        subdivide_body(
            mesh,
            options,
            None,
            scratch,
            out,
            out_sizes,
            out_report,
            out_element,
        )
    }
}

/// The arguments of `nls_mesh_subdivide` read and checked ([`checked_args`]): what the call
/// itself needs, nothing of the checks.
struct CheckedArgs {
    mesh: RawMesh,
    raw_opts: nls_subdivide_options,
    opts: Options,
    tags: Option<RawTags>,
    raw: RawOut,
    exec: Option<HostExecutor>,
}

/// Reads and checks every argument of [`subdivide_body`] (pointers, sizes, aliasing, options,
/// tags, weights, the plan's `u32` scratch, the FP environment), naming the element of a
/// failure in `element`; `sizes_ok` is set once `out_sizes` may be written. Out of line, so
/// that the checks' arrays of buffer ranges are not in the frame below which the
/// subdivision runs (`docs/firmware.md`, "Stack").
///
/// # Safety
/// The contract of [`subdivide_body`].
#[inline(never)]
#[allow(clippy::too_many_arguments)] // the exports' parameters and the element slot
unsafe fn checked_args(
    mesh: *const nls_mesh_view,
    options: *const nls_subdivide_options,
    tags: Option<*const nls_tags>,
    scratch: *const nls_scratch,
    out: *const nls_mesh_buffers,
    out_sizes: *mut nls_mesh_sizes,
    out_report: *mut nls_subdivide_report,
    out_element: *mut u32,
    element: &mut ElementSlot,
    sizes_ok: &mut bool,
) -> Result<CheckedArgs, Fail> {
    // SAFETY: the caller passes NULL or readable structs.
    let (mesh_r, scratch_r, out_r, tags_r, opts_r) = unsafe {
        (
            RawMesh::read(mesh),
            read_arg(scratch),
            read_arg(out),
            read_tags(tags),
            read_arg(options),
        )
    };
    // SAFETY: the caller passes NULL or a readable view.
    let [a, b, c] = unsafe { RawMesh::named(mesh, &mesh_r) };
    let [d, e] = named(scratch, &scratch_r, scratch_raw_spans);
    let [f, g, h] = named(out, &out_r, out_raw_spans);
    let [i, j, k, l] = named(tags.unwrap_or(null()), &tags_r, tag_raw_spans);
    let m = weight_raw_span(options, &opts_r, &mesh_r);
    element.close_unless_clear(
        &[Span::of_one(out_sizes), Span::of_one(out_report)],
        &[a, b, c, d, e, f, g, h, i, j, k, l, m],
    );
    let (mesh, opts) = (mesh_r?, opts_r?);
    let raw = RawOut {
        scratch: scratch_r?,
        out: out_r?,
    };
    let raw_tags = tags_r?;
    let tags = raw_tags.as_ref();
    check_ptr(out_sizes.cast_const(), 1)?;
    check_optional(out_report)?;
    check_optional(out_element)?;
    let inputs = mesh.spans();
    let [s0, s1, s2, s3, s4] = raw.spans();
    let [i0, i1, i2] = inputs;
    let [t0, t1, t2, t3] = tag_spans(tags);
    let w0 = weight_span(&opts, &mesh);
    check_out_pointers(
        &[Span::of_one(out_sizes), Span::of_one(out_report)],
        element,
        &[i0, i1, i2, t0, t1, t2, t3, w0, s0, s1, s2, s3, s4],
    )?;
    *sizes_ok = true;
    // SAFETY: the caller passes NULL or a readable executor in the options.
    let exec = unsafe { HostExecutor::read(opts.executor) }?;
    let raw_opts = opts;
    let opts = parse_options(&raw_opts)?;
    mesh.check()?;
    check_tags(tags)?;
    check_weights(&raw_opts, &mesh)?;
    raw.check(&[i0, i1, i2, t0, t1, t2, t3, w0])?;
    if raw.scratch.u32_capacity < plan_need(&mesh, tags)? {
        return Err(too_small(NLS_MESH_BUFFER_SCRATCH_U32));
    }
    check_fp_env()?;
    Ok(CheckedArgs {
        mesh,
        raw_opts,
        opts,
        tags: raw_tags,
        raw,
        exec,
    })
}

/// The body of `nls_mesh_subdivide` and `nls_mesh_subdivide_tagged`.
///
/// # Safety
/// The contract of `nls_mesh_subdivide`; `tags` (the tagged export's) is NULL or points to a
/// readable `nls_tags`.
#[allow(clippy::too_many_arguments)] // the two exports' parameters, plus the tags
pub(crate) unsafe fn subdivide_body(
    mesh: *const nls_mesh_view,
    options: *const nls_subdivide_options,
    tags: Option<*const nls_tags>,
    scratch: *const nls_scratch,
    out: *const nls_mesh_buffers,
    out_sizes: *mut nls_mesh_sizes,
    out_report: *mut nls_subdivide_report,
    out_element: *mut u32,
) -> Status {
    let mut needed: Option<MeshSizes> = None;
    let mut sizes_ok = false;
    let status = run_with_element(out_element, |element| {
        // SAFETY: forwarded contract.
        let args = unsafe {
            checked_args(
                mesh,
                options,
                tags,
                scratch,
                out,
                out_sizes,
                out_report,
                out_element,
                element,
                &mut sizes_ok,
            )?
        };
        let CheckedArgs {
            mesh,
            raw_opts,
            opts,
            tags,
            raw,
            exec,
        } = args;
        let tags = tags.as_ref();
        // SAFETY: every buffer was checked (NULL, alignment, size) and the writable ones
        // overlap nothing; the caller guarantees readability and writability.
        let (view, (su, sp, mut out)) = unsafe { (mesh.mesh()?, raw.slices()) };
        // SAFETY: the tags and the weights were checked (NULL, alignment, size).
        let (tags, weights) = unsafe { (tags_of(tags)?, weights_of(&raw_opts, &mesh)) };
        let report = subdivide_call(
            view,
            (&opts, &tags, weights),
            exec.as_ref(),
            su,
            sp,
            &mut out,
            &raw,
            &mut needed,
        )?;
        // SAFETY: checked above.
        unsafe {
            store(out_sizes, sizes_of(&report.sizes));
            if !out_report.is_null() {
                store(out_report, report_of(&report));
            }
        }
        Ok(())
    });
    if let (Status::BufferTooSmall, Some(sizes), true) = (status, needed, sizes_ok) {
        // SAFETY: checked (non-NULL, aligned, outside every buffer) before the sizes were
        // computed.
        unsafe { store(out_sizes, sizes_of(&sizes)) };
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

    fn view(p: &[f64], off: &[u32], idx: &[u32], stride: usize) -> nls_mesh_view {
        let vertex_count = match (p.len() * 8 + stride).checked_sub(24) {
            Some(extent) if stride > 0 => extent / stride,
            _ => p.len() / 3,
        };
        nls_mesh_view {
            positions: p.as_ptr(),
            vertex_count,
            positions_stride: stride,
            offsets: off.as_ptr(),
            face_count: off.len() - 1,
            indices: idx.as_ptr(),
            index_count: idx.len(),
        }
    }

    /// A scheme or Möbius form left out of this build (the ffi crate's Cargo features, which
    /// the core follows) is `NLS_STATUS_SCHEME_NOT_BUILT` from the plan and from the call,
    /// `out_element` is `NLS_NO_ELEMENT` and nothing is written; every scheme built plans.
    /// `scripts/test-features.sh` runs it in builds that leave schemes out.
    #[test]
    fn schemes_left_out_of_the_build_give_scheme_not_built() {
        let feature_on = |code: u32| match code {
            NLS_SCHEME_LOOP => cfg!(feature = "loop"),
            NLS_SCHEME_CATMULL_CLARK => cfg!(feature = "catmull-clark"),
            NLS_SCHEME_MODIFIED_BUTTERFLY => cfg!(feature = "butterfly"),
            NLS_SCHEME_KOBBELT => cfg!(feature = "kobbelt"),
            NLS_SCHEME_DOO_SABIN => cfg!(feature = "doo-sabin"),
            NLS_SCHEME_SIMPLEST => cfg!(feature = "simplest"),
            NLS_SCHEME_DUAL | NLS_SCHEME_VERTEX_INSERTION | NLS_SCHEME_DUAL_TRUNCATION => {
                cfg!(feature = "akleman")
            }
            NLS_SCHEME_SPHERELIKE => cfg!(feature = "spherelike"),
            _ => panic!("a scheme without a feature here: {code}"),
        };
        // The cube, and the octahedron for the triangle schemes, on the unit sphere.
        let cube: Vec<f64> = (0..8)
            .flat_map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
            .map(|x| (2.0 * x - 1.0) / 3f64.sqrt())
            .collect();
        let cube_off = [0u32, 4, 8, 12, 16, 20, 24];
        let cube_idx = [
            0u32, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5,
        ];
        let oct = [
            1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0,
            -1.0,
        ];
        let oct_off = [0u32, 3, 6, 9, 12, 15, 18, 21, 24];
        let oct_idx = [
            0u32, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5,
        ];
        let mut refused = 0;
        for code in 0..=NLS_SCHEME_SPHERELIKE {
            let m = if code == NLS_SCHEME_LOOP || code == NLS_SCHEME_MODIFIED_BUTTERFLY {
                view(&oct, &oct_off, &oct_idx, 0)
            } else {
                view(&cube, &cube_off, &cube_idx, 0)
            };
            for flags in [0, NLS_SUBDIVIDE_MOBIUS] {
                let mobius = flags != 0;
                if mobius && code == NLS_SCHEME_SPHERELIKE {
                    continue;
                }
                let built = feature_on(code) && (!mobius || cfg!(feature = "mobius"));
                let o = nls_subdivide_options {
                    scheme: code,
                    flags,
                    levels: 1,
                    linear_weight: 0.0,
                    executor: core::ptr::null(),
                    linear_weights: core::ptr::null(),
                };
                let mut su0 = 0usize;
                let s = unsafe { nls_mesh_plan_scratch_size(&m, &mut su0) };
                assert_eq!(s, Status::Ok);
                let mut topo = vec![0u32; su0];
                let mut plan = nls_plan::default();
                let mut element = 7u32;
                let s = unsafe {
                    nls_mesh_plan(&m, &o, topo.as_mut_ptr(), su0, &mut plan, &mut element)
                };
                if built {
                    assert_eq!(s, Status::Ok, "scheme {code} flags {flags}");
                    continue;
                }
                refused += 1;
                assert_eq!(s, Status::SchemeNotBuilt, "scheme {code} flags {flags}");
                assert_eq!(element, crate::curve::NLS_NO_ELEMENT);
                assert_eq!(plan, nls_plan::default(), "the plan was written");
                // The call itself, with ample buffers: refused, nothing written.
                let mut u32s = vec![0u32; 4096];
                let mut pts = vec![0.0; 3 * 4096];
                let (mut op, mut oo, mut oi) =
                    (vec![7.0; 3 * 256], vec![7u32; 257], vec![7u32; 1024]);
                let sc = nls_scratch {
                    u32s: u32s.as_mut_ptr(),
                    u32_capacity: 4096,
                    points: pts.as_mut_ptr(),
                    point_capacity: 4096,
                };
                let buf = nls_mesh_buffers {
                    positions: op.as_mut_ptr(),
                    vertex_capacity: 256,
                    offsets: oo.as_mut_ptr(),
                    face_capacity: 256,
                    indices: oi.as_mut_ptr(),
                    index_capacity: 1024,
                };
                let mut sizes = nls_mesh_sizes::default();
                let mut rep = nls_subdivide_report {
                    fallbacks: 9,
                    first_fallback: 9,
                    first_fallback_level: 9,
                    guarded: 9,
                    first_guarded: 9,
                    first_guarded_level: 9,
                };
                element = 7;
                let s = unsafe {
                    nls_mesh_subdivide(&m, &o, &sc, &buf, &mut sizes, &mut rep, &mut element)
                };
                assert_eq!(s, Status::SchemeNotBuilt, "scheme {code} flags {flags}");
                assert_eq!(element, crate::curve::NLS_NO_ELEMENT);
                assert_eq!(sizes, nls_mesh_sizes::default());
                assert_eq!(
                    (rep.fallbacks, rep.guarded),
                    (9, 9),
                    "the report was written"
                );
                assert!(op.iter().all(|&x| x == 7.0) && oo.iter().all(|&x| x == 7));
                assert!(oi.iter().all(|&x| x == 7));
            }
        }
        let text = unsafe { core::ffi::CStr::from_ptr(crate::nls_status_str(35)) };
        assert!(text
            .to_str()
            .unwrap()
            .contains("not compiled into this build"));
        if cfg!(all(
            feature = "loop",
            feature = "catmull-clark",
            feature = "butterfly",
            feature = "kobbelt",
            feature = "doo-sabin",
            feature = "simplest",
            feature = "akleman",
            feature = "spherelike",
            feature = "mobius"
        )) {
            assert_eq!(refused, 0);
        } else {
            assert!(refused > 0);
        }
    }

    /// One quad, Möbius Catmull–Clark, through plan and subdivide; then one face short.
    #[test]
    fn one_quad_through_the_abi() {
        let p: [f64; 12] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0];
        let (off, idx) = ([0u32, 4], [0u32, 1, 2, 3]);
        let m = view(&p, &off, &idx, 0);
        let o = nls_subdivide_options {
            scheme: NLS_SCHEME_CATMULL_CLARK,
            flags: NLS_SUBDIVIDE_MOBIUS,
            levels: 1,
            linear_weight: 0.0,
            executor: core::ptr::null(),
            linear_weights: core::ptr::null(),
        };
        let mut su0 = 0usize;
        assert_eq!(
            unsafe { nls_mesh_plan_scratch_size(&m, &mut su0) },
            Status::Ok
        );
        assert_eq!(su0, 28);
        let mut scratch = vec![0u32; su0];
        let mut plan = nls_plan::default();
        let s = unsafe {
            nls_mesh_plan(
                &m,
                &o,
                scratch.as_mut_ptr(),
                su0,
                &mut plan,
                core::ptr::null_mut(),
            )
        };
        assert_eq!(s, Status::Ok);
        // Points: two candidates per corner (4 corners), and per vertex the kept form's
        // centre (4), then the fold guard's trust and the form's radius per vertex, the
        // candidates' slot per corner and the guard's F4-angle term per edge, room for one
        // per corner (⌈(8 + 4 + 4) / 3⌉ = 6: three values to a point); the star workspace:
        // four arrays of the largest valence (2) for each chunk, at most one per vertex (4).
        // `u32`: the topology (28) and the spoke workspace, four entries per spoke of the
        // largest valence (2) for each chunk (4).
        assert_eq!(
            (plan.scratch_u32, plan.scratch_points),
            (28 + 4 * 2 * 4, 8 + 4 + 6 + 4 * 2 * 4)
        );
        let mut pts = vec![0.0; 3 * plan.scratch_points];
        scratch.resize(plan.scratch_u32, 0);
        let (mut op, mut oo, mut oi) = (vec![0.0; 27], vec![0u32; 5], vec![0u32; 16]);
        let sc = nls_scratch {
            u32s: scratch.as_mut_ptr(),
            u32_capacity: plan.scratch_u32,
            points: pts.as_mut_ptr(),
            point_capacity: plan.scratch_points,
        };
        let mut buf = nls_mesh_buffers {
            positions: op.as_mut_ptr(),
            vertex_capacity: 9,
            offsets: oo.as_mut_ptr(),
            face_capacity: 4,
            indices: oi.as_mut_ptr(),
            index_capacity: 16,
        };
        let mut sizes = nls_mesh_sizes::default();
        let mut rep = nls_subdivide_report {
            fallbacks: 9,
            first_fallback: 9,
            first_fallback_level: 9,
            guarded: 9,
            first_guarded: 9,
            first_guarded_level: 9,
        };
        let mut element = 7u32;
        let s =
            unsafe { nls_mesh_subdivide(&m, &o, &sc, &buf, &mut sizes, &mut rep, &mut element) };
        assert_eq!(s, Status::Ok);
        assert_eq!(sizes, plan.output);
        assert_eq!((sizes.vertex_count, sizes.face_count, element), (9, 4, 7));
        // A face of ears only takes its linear centroid: one fallback, the face point.
        let r = (rep.fallbacks, rep.first_fallback, rep.first_fallback_level);
        assert_eq!(r, (1, 8, 1));
        assert_eq!(&op[24..27], &[0.5, 0.5, 0.0]);
        // One face short: the sizes are given, the element names the buffer.
        buf.face_capacity = 3;
        let lin = nls_subdivide_options { flags: 0, ..o };
        let mut sizes = nls_mesh_sizes::default();
        let s = unsafe {
            nls_mesh_subdivide(
                &m,
                &lin,
                &sc,
                &buf,
                &mut sizes,
                core::ptr::null_mut(),
                &mut element,
            )
        };
        assert_eq!(s, Status::BufferTooSmall);
        assert_eq!((sizes, element), (plan.output, NLS_MESH_BUFFER_OFFSETS));
    }

    /// Strided positions give the bits of packed ones; a stride that is not a multiple of 8
    /// or below 24 is refused.
    #[test]
    fn strided_positions() {
        let p: [f64; 12] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.1, 1.0, 1.0, 0.0, 0.0, 1.0, 0.2];
        let mut wide = Vec::new();
        for q in p.chunks(3) {
            wide.extend_from_slice(q);
            wide.extend_from_slice(&[f64::NAN, 5.0]);
        }
        wide.truncate(wide.len() - 2);
        let (off, idx) = ([0u32, 4], [0u32, 1, 2, 3]);
        let run = |m: &nls_mesh_view| {
            let o = nls_subdivide_options {
                scheme: NLS_SCHEME_CATMULL_CLARK,
                flags: NLS_SUBDIVIDE_MOBIUS,
                levels: 2,
                linear_weight: 0.0,
                executor: core::ptr::null(),
                linear_weights: core::ptr::null(),
            };
            let mut su = vec![0u32; 4096];
            let mut sp = vec![0.0; 3 * 2048];
            let (mut op, mut oo, mut oi) = (vec![0.0; 3 * 64], vec![0u32; 65], vec![0u32; 256]);
            let sc = nls_scratch {
                u32s: su.as_mut_ptr(),
                u32_capacity: su.len(),
                points: sp.as_mut_ptr(),
                point_capacity: 2048,
            };
            let buf = nls_mesh_buffers {
                positions: op.as_mut_ptr(),
                vertex_capacity: 64,
                offsets: oo.as_mut_ptr(),
                face_capacity: 64,
                indices: oi.as_mut_ptr(),
                index_capacity: 256,
            };
            let mut sizes = nls_mesh_sizes::default();
            let s = unsafe {
                nls_mesh_subdivide(
                    m,
                    &o,
                    &sc,
                    &buf,
                    &mut sizes,
                    core::ptr::null_mut(),
                    core::ptr::null_mut(),
                )
            };
            (s, op.iter().map(|x| x.to_bits()).collect::<Vec<_>>(), sizes)
        };
        let packed = run(&view(&p, &off, &idx, 0));
        assert_eq!(packed.0, Status::Ok);
        assert_eq!(packed.2.vertex_count, 25);
        assert_eq!(run(&view(&p, &off, &idx, 24)), packed);
        let strided = view(&wide, &off, &idx, 40);
        assert_eq!(strided.vertex_count, 4);
        assert_eq!(run(&strided), packed);
        for bad in [8, 16, 25, 36] {
            let m = nls_mesh_view {
                positions_stride: bad,
                ..strided
            };
            assert_eq!(run(&m).0, Status::InvalidArgument, "stride {bad}");
        }
    }
}

// Differential-space subdivision (seed 001) shares this module's buffer checks.
#[path = "differential.rs"]
pub mod differential;
