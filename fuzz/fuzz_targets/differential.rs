//! Fuzz target `differential`: differential-space subdivision through the C ABI
//! (`nls_differential_default_options`, `nls_mesh_plan_scratch_size`, `_plan`, `_subdivide`; seed 001,
//! docs/differential.md).
//!
//! Contract checked (include/nlsubdiv.h, docs/bad-input-catalogue.md), on every execution:
//! - every writable buffer (scratch, outputs) is allocated with a guard zone past the capacity
//!   passed; the guard keeps its sentinel bits whatever the call returns (no write past a
//!   caller buffer; ASan sees writes past the allocation);
//! - every status is one of the documented set of the function;
//! - `nls_differential_default_options` writes the documented defaults, refuses NULL and
//!   misaligned pointers writing nothing; `nls_mesh_plan_scratch_size` gives `OK` or
//!   `SIZE_OVERFLOW`, writing its count on `OK` only;
//! - options the header calls invalid (unknown scheme, `dirmag_levels` not matching the
//!   scheme, more than `NLS_MAX_LEVELS` levels, a tolerance not finite and ≥ 0) give
//!   `INVALID_ARGUMENT`; NULL options give `NULL_PARAMETER`; an edit array overlapping a
//!   written buffer gives `ALIASING_BUFFERS`;
//! - plan and subdivide agree on every refusal (same status, same element), and a refusal
//!   writes no count, no report and no output;
//! - one buffer shortened by any amount gives `BUFFER_TOO_SMALL` naming it, nothing written to
//!   the outputs or the report; the counts receive the planned sizes (unless the scratch is
//!   below the topology's need, when no size can be computed and none is written);
//! - success: the counts are exactly the planned sizes, every position is finite, the faces
//!   are those of the spatial Loop / Modified Butterfly subdivision (`nls_mesh_subdivide`)
//!   index for index, the report says converged with a residual ≤ the tolerance in at most
//!   `max_iterations` iterations, `out_element` untouched; `NOT_CONVERGED` writes the report
//!   (converged = 0) and no count.
//!
//! Input layout (fuzz/make_corpus.py writes the seeds in it; missing bytes read as 0):
//! `scheme u8 (% 5: Loop, Butterfly, DirMag, two unknown codes), levels u8 (→ 1,1,1,2,0,2,3,17
//!  by b % 8), dirmag u8, iterations u8 (→ 100,0,1,2,5,20,100,250 by b % 8), tolerance u8
//!  (→ 1e-10,0,1e-3,1e-14,0.5,NaN,−1,+∞ by b % 8), edits u8 (bit 0: curvature scales, bit 1:
//!  normals, bits 2–4: mode, see `Mode`), shrink u8, amount u8, tweak u8, tweak_at u16,
//!  vertex_count u16, face_count u16, face sizes u8 × F, indices u16 × Σsizes,
//!  positions f64 × 3V, curvature scales f64 × V (bit 0), normals f64 × 3V (bit 1)`.
#![no_main]

#[path = "common.rs"]
mod common;

use common::*;
use libfuzzer_sys::fuzz_target;
use nlsubdiv_ffi::mesh::differential::*;
use nlsubdiv_ffi::mesh::*;
use nlsubdiv_ffi::Status;

/// Caps that keep one execution short (the solve is iterative).
const LIMITS: Limits = Limits {
    vertices: 200,
    faces: 400,
    indices: 1600,
};
/// The solve runs only when the last level stays below this many vertices.
const MAX_OUT_VERTICES: usize = 3000;
/// Elements of guard zone after every writable buffer.
const GUARD: usize = 16;

const LEVELS: [u32; 8] = [1, 1, 1, 2, 0, 2, 3, NLS_MAX_LEVELS + 1];
const ITERATIONS: [u32; 8] = [100, 0, 1, 2, 5, 20, 100, 250];
const TOLERANCES: [f64; 8] = [1e-10, 0.0, 1e-3, 1e-14, 0.5, f64::NAN, -1.0, f64::INFINITY];

const REPORT_SENTINEL: nls_differential_report = nls_differential_report {
    iterations: 0xdead,
    converged: 0xdead,
    anchors: 0xdead,
    dirmag_degenerate: 0xdead,
    relative_residual: -7.0,
    initial_residual: -7.0,
    folded_faces: 0xdead,
    first_folded_face: 0xdead,
    folded_edges: 0xdead,
    first_folded_edge: [0xdead; 2],
};

/// The view of a packed mesh.
fn view(m: &Mesh) -> nls_mesh_view {
    nls_mesh_view {
        positions: m.pos.as_ptr(),
        vertex_count: m.nv(),
        positions_stride: 0,
        offsets: m.off.as_ptr(),
        face_count: m.nf(),
        indices: m.idx.as_ptr(),
        index_count: m.idx.len(),
    }
}

/// `nls_plan` filled with sentinels.
const PLAN_SENTINEL: nls_plan = nls_plan {
    output: nls_mesh_sizes {
        vertex_count: SENTINEL_COUNT,
        face_count: SENTINEL_COUNT,
        index_count: SENTINEL_COUNT,
    },
    scratch_u32: SENTINEL_COUNT,
    scratch_points: SENTINEL_COUNT,
};

fn counts_of(s: &nls_mesh_sizes) -> [usize; 3] {
    [s.vertex_count, s.face_count, s.index_count]
}

/// What the `edits` byte's bits 2–4 ask for.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Mode {
    Plain,
    /// A special value planted in an edit array (`NON_FINITE_INPUT` when it is not finite).
    Special,
    /// `curvature_scale` points into a buffer the call writes (plan: scratch; subdivide:
    /// the output positions).
    Alias,
    /// `options` is NULL.
    NullOptions,
    /// `out_report` and `out_element` are NULL (allowed).
    NullOptionalOutputs,
}

fn mode_of(b: u8) -> Mode {
    match (b >> 2) & 7 {
        4 => Mode::Special,
        5 => Mode::Alias,
        6 => Mode::NullOptions,
        7 => Mode::NullOptionalOutputs,
        _ => Mode::Plain,
    }
}

/// A writable buffer of `cap` elements followed by a guard zone, all sentinels.
struct Guarded<T: Copy + PartialEq> {
    v: Vec<T>,
    cap: usize,
    fill: T,
}

impl<T: Copy + PartialEq> Guarded<T> {
    fn new(cap: usize, fill: T) -> Self {
        Guarded {
            v: vec![fill; cap + GUARD],
            cap,
            fill,
        }
    }
    fn ptr(&mut self) -> *mut T {
        self.v.as_mut_ptr()
    }
    fn guard_intact(&self) -> bool {
        self.v[self.cap..].iter().all(|&x| x == self.fill)
    }
    fn untouched(&self) -> bool {
        self.v.iter().all(|&x| x == self.fill)
    }
}

/// f64 buffers compare by bits (the sentinel is a NaN).
#[derive(Clone, Copy)]
struct Bits(f64);
impl PartialEq for Bits {
    fn eq(&self, o: &Bits) -> bool {
        self.0.to_bits() == o.0.to_bits()
    }
}
const SENT: Bits = Bits(f64::from_bits(SENTINEL_F64));

/// The options of the input and their edit arrays (owned here).
struct Opts {
    o: nls_differential_options,
    /// Whether the header calls them invalid (`INVALID_ARGUMENT` expected).
    invalid: bool,
    scale: Option<Vec<f64>>,
    normals: Option<Vec<f64>>,
}

impl Opts {
    /// The options with the edit pointers set to the owned arrays.
    fn raw(&self) -> nls_differential_options {
        let mut o = self.o;
        o.curvature_scale = self
            .scale
            .as_ref()
            .map_or(core::ptr::null(), |s| s.as_ptr());
        o.normals = self
            .normals
            .as_ref()
            .map_or(core::ptr::null(), |s| s.as_ptr());
        o
    }
}

struct Plan {
    status: Status,
    counts: [usize; 3],
    scratch: [usize; 2],
    element: u32,
}

fn plan(m: &Mesh, o: Option<&nls_differential_options>, su: usize) -> Plan {
    let mut scratch = Guarded::new(su, SENTINEL_U32);
    let mut p = PLAN_SENTINEL;
    let mut element = SENTINEL_ELEMENT;
    let status = unsafe {
        nls_differential_plan(
            &view(m),
            o.map_or(core::ptr::null(), |o| o as *const _),
            scratch.ptr(),
            su,
            &mut p,
            &mut element,
        )
    };
    assert!(
        scratch.guard_intact(),
        "plan wrote past scratch_u32 ({status:?})"
    );
    Plan {
        status,
        counts: counts_of(&p.output),
        scratch: [p.scratch_u32, p.scratch_points],
        element,
    }
}

/// `plan` with `curvature_scale` pointing into the scratch it is given: `ALIASING_BUFFERS`
/// (or `MISALIGNED_POINTER` when the `u32` scratch is not 8-aligned), nothing written.
fn plan_aliased(m: &Mesh, o: &Opts, su: usize) {
    let mut scratch = Guarded::new(su.max(2 * m.nv() + 2), SENTINEL_U32);
    let mut raw = o.raw();
    raw.curvature_scale = scratch.ptr().cast::<f64>().cast_const();
    let mut p = PLAN_SENTINEL;
    let mut element = SENTINEL_ELEMENT;
    let cap = scratch.cap;
    let status =
        unsafe { nls_differential_plan(&view(m), &raw, scratch.ptr(), cap, &mut p, &mut element) };
    let (c, s2) = (counts_of(&p.output), [p.scratch_u32, p.scratch_points]);
    assert!(scratch.guard_intact());
    assert_eq!((c, s2), ([SENTINEL_COUNT; 3], [SENTINEL_COUNT; 2]));
    let want = if (raw.curvature_scale as usize) % core::mem::align_of::<f64>() == 0 {
        Status::AliasingBuffers
    } else {
        Status::MisalignedPointer
    };
    assert_eq!(status, want, "edit array over the scratch");
}

struct Call {
    status: Status,
    counts: [usize; 3],
    report: nls_differential_report,
    element: u32,
    pos: Guarded<Bits>,
    off: Guarded<u32>,
    idx: Guarded<u32>,
    scratch_intact: bool,
}

impl Call {
    fn outputs_untouched(&self) -> bool {
        self.pos.untouched() && self.off.untouched() && self.idx.untouched()
    }
}

/// `nls_differential_subdivide` with the given capacities: `[scratch_u32, scratch_points,
/// vertices, faces, indices]`.
fn subdivide(
    m: &Mesh,
    o: Option<&nls_differential_options>,
    caps: [usize; 5],
    alias: bool,
    null_optional: bool,
) -> Call {
    let mut su = Guarded::new(caps[0], SENTINEL_U32);
    let mut sp = Guarded::new(3 * caps[1], SENT);
    let mut pos = Guarded::new(3 * caps[2], SENT);
    let mut off = Guarded::new(caps[3] + 1, SENTINEL_U32);
    let mut idx = Guarded::new(caps[4], SENTINEL_U32);
    let mut raw = o.copied();
    if alias {
        if let Some(r) = raw.as_mut() {
            r.curvature_scale = pos.ptr().cast_const().cast::<f64>();
        }
    }
    let mut sizes = nls_mesh_sizes {
        vertex_count: SENTINEL_COUNT,
        face_count: SENTINEL_COUNT,
        index_count: SENTINEL_COUNT,
    };
    let mut report = REPORT_SENTINEL;
    let mut element = SENTINEL_ELEMENT;
    let (rep_ptr, el_ptr): (*mut nls_differential_report, *mut u32) = if null_optional {
        (core::ptr::null_mut(), core::ptr::null_mut())
    } else {
        (&mut report, &mut element)
    };
    let scratch = nls_scratch {
        u32s: su.ptr(),
        u32_capacity: caps[0],
        points: sp.ptr().cast::<f64>(),
        point_capacity: caps[1],
    };
    let buffers = nls_mesh_buffers {
        positions: pos.ptr().cast::<f64>(),
        vertex_capacity: caps[2],
        offsets: off.ptr(),
        face_capacity: caps[3],
        indices: idx.ptr(),
        index_capacity: caps[4],
    };
    let status = unsafe {
        nls_differential_subdivide(
            &view(m),
            raw.as_ref().map_or(core::ptr::null(), |o| o as *const _),
            &scratch,
            &buffers,
            &mut sizes,
            rep_ptr,
            el_ptr,
        )
    };
    let counts = counts_of(&sizes);
    let scratch_intact = su.guard_intact() && sp.guard_intact();
    assert!(
        scratch_intact && pos.guard_intact() && off.guard_intact() && idx.guard_intact(),
        "subdivide wrote past a buffer ({status:?})"
    );
    Call {
        status,
        counts,
        report,
        element,
        pos,
        off,
        idx,
        scratch_intact,
    }
}

/// Statuses `nls_differential_plan` may return (its doc and that of `nls_mesh_plan` it refers
/// to).
fn plan_status_documented(s: Status) -> bool {
    matches!(
        s,
        Status::Ok
            | Status::SizeOverflow
            | Status::BadOffsets
            | Status::FaceTooSmall
            | Status::ValenceTooHigh
            | Status::IndexOutOfRange
            | Status::RepeatedVertex
            | Status::DuplicateFace
            | Status::InconsistentOrientation
            | Status::NonManifoldEdge
            | Status::NonManifoldVertex
            | Status::NonFiniteInput
            | Status::UnsupportedFaceType
            | Status::InvalidArgument
            | Status::BufferTooSmall
            | Status::NullParameter
            | Status::MisalignedPointer
            | Status::AliasingBuffers
            | Status::FpEnvironment
            // A mesh outside the sizes the normal equations can represent (1e-140 … 1e140).
            | Status::NumericalFailure
    )
}

/// Statuses only the computation of `nls_differential_subdivide` (after the plan) may give:
/// the solver's, a normal edit at a vertex whose surface normal is zero
/// (`DEGENERATE_GEOMETRY`), a fold with `strict` (`FOLDED_SURFACE`).
fn compute_failure(s: Status) -> bool {
    matches!(
        s,
        Status::NotConverged
            | Status::NumericalFailure
            | Status::DegenerateGeometry
            | Status::FoldedSurface
    )
}

/// The spatial subdivision's topology after `levels` levels, when it is computable.
fn spatial(scheme: u32, m: &Mesh, levels: u32) -> Option<(Vec<u32>, Vec<u32>)> {
    let v = view(m);
    let mut su = 0usize;
    if unsafe { nls_mesh_plan_scratch_size(&v, &mut su) } != Status::Ok {
        return None;
    }
    let mut o = core::mem::MaybeUninit::<nls_subdivide_options>::uninit();
    if unsafe { nls_subdivide_default_options(o.as_mut_ptr()) } != Status::Ok {
        return None;
    }
    let mut o = unsafe { o.assume_init() };
    o.scheme = scheme;
    o.levels = levels;
    let mut scratch = vec![0u32; su];
    let mut p = PLAN_SENTINEL;
    let s = unsafe {
        nls_mesh_plan(
            &v,
            &o,
            scratch.as_mut_ptr(),
            su,
            &mut p,
            core::ptr::null_mut(),
        )
    };
    if s != Status::Ok {
        return None;
    }
    let c = counts_of(&p.output);
    let mut scratch = vec![0u32; p.scratch_u32];
    let mut points = vec![0.0f64; 3 * p.scratch_points];
    let mut pos = vec![0.0f64; 3 * c[0]];
    let mut off = vec![0u32; c[1] + 1];
    let mut idx = vec![0u32; c[2]];
    let sc = nls_scratch {
        u32s: scratch.as_mut_ptr(),
        u32_capacity: p.scratch_u32,
        points: points.as_mut_ptr(),
        point_capacity: p.scratch_points,
    };
    let b = nls_mesh_buffers {
        positions: pos.as_mut_ptr(),
        vertex_capacity: c[0],
        offsets: off.as_mut_ptr(),
        face_capacity: c[1],
        indices: idx.as_mut_ptr(),
        index_capacity: c[2],
    };
    let mut w = nls_mesh_sizes::default();
    let s = unsafe {
        nls_mesh_subdivide(
            &v,
            &o,
            &sc,
            &b,
            &mut w,
            core::ptr::null_mut(),
            core::ptr::null_mut(),
        )
    };
    (s == Status::Ok).then_some((off, idx))
}

fn check_default_options() {
    let mut o = core::mem::MaybeUninit::<nls_differential_options>::zeroed();
    let s = unsafe { nls_differential_default_options(o.as_mut_ptr()) };
    assert_eq!(s, Status::Ok);
    let o = unsafe { o.assume_init() };
    assert_eq!(
        (o.scheme, o.levels, o.dirmag_levels, o.max_iterations),
        (NLS_DIFFERENTIAL_LOOP, 1, 0, 100)
    );
    assert!(o.tolerance == 1e-10 && o.curvature_scale.is_null() && o.normals.is_null());
    assert_eq!(o.strict, 0);
    let s = unsafe { nls_differential_default_options(core::ptr::null_mut()) };
    assert_eq!(s, Status::NullParameter);
    // A misaligned pointer: refused, nothing written.
    let size = core::mem::size_of::<nls_differential_options>();
    let mut bytes = vec![0x5au8; size + 16];
    let p = unsafe { bytes.as_mut_ptr().add(1) }.cast::<nls_differential_options>();
    if (p as usize) % core::mem::align_of::<nls_differential_options>() != 0 {
        let s = unsafe { nls_differential_default_options(p) };
        assert_eq!(s, Status::MisalignedPointer);
        assert!(
            bytes.iter().all(|&b| b == 0x5a),
            "written on MISALIGNED_POINTER"
        );
    }
}

fn decode_options(r: &mut Reader<'_>, m: &Mesh, head: [u8; 5], edits: u8, mode: Mode) -> Opts {
    let code = u32::from(head[0] % 5);
    let levels = LEVELS[usize::from(head[1] % 8)];
    let dirmag = if code == NLS_DIFFERENTIAL_DIRMAG {
        u32::from(head[2] % 4)
    } else {
        u32::from(head[2] >= 240)
    };
    let tolerance = TOLERANCES[usize::from(head[4] % 8)];
    let invalid = code > NLS_DIFFERENTIAL_DIRMAG
        || (code == NLS_DIFFERENTIAL_DIRMAG) != (dirmag > 0)
        || levels > NLS_MAX_LEVELS
        || !(tolerance.is_finite() && tolerance >= 0.0);
    let mut scale = (edits & 1 != 0).then(|| (0..m.nv()).map(|_| r.f64()).collect::<Vec<_>>());
    let mut normals =
        (edits & 2 != 0).then(|| (0..3 * m.nv()).map(|_| r.f64()).collect::<Vec<_>>());
    if mode == Mode::Special {
        let at = usize::from(r.u16());
        let v = SPECIALS[usize::from(r.u8()) % SPECIALS.len()];
        for a in [scale.as_mut(), normals.as_mut()].into_iter().flatten() {
            if !a.is_empty() {
                let k = at % a.len();
                a[k] = v;
            }
        }
    }
    Opts {
        o: nls_differential_options {
            scheme: code,
            levels,
            dirmag_levels: dirmag,
            max_iterations: ITERATIONS[usize::from(head[3] % 8)],
            tolerance,
            curvature_scale: core::ptr::null(),
            normals: core::ptr::null(),
            strict: 0,
        },
        invalid,
        scale,
        normals,
    }
}

fuzz_target!(|data: &[u8]| {
    let mut r = Reader::new(data);
    let head = [r.u8(), r.u8(), r.u8(), r.u8(), r.u8()];
    let edits = r.u8();
    let mode = mode_of(edits);
    let shrink = r.u8() % 7;
    let amount = usize::from(r.u8());
    let tweak = r.u8();
    let tweak_at = r.u16();
    let m = decode_mesh(&mut r, tweak, tweak_at, LIMITS);
    let opts = decode_options(&mut r, &m, head, edits, mode);
    let raw = opts.raw();

    // 0. Defaults and the scratch query.
    if tweak & 0x40 != 0 {
        check_default_options();
    }
    let mut topo_need = SENTINEL_COUNT;
    let s = unsafe { nls_mesh_plan_scratch_size(&view(&m), &mut topo_need) };
    assert_eq!(s, Status::Ok, "scratch size of a small mesh");
    assert_ne!(topo_need, SENTINEL_COUNT);
    if tweak & 0x80 != 0 {
        // Counts past the u32 range: SIZE_OVERFLOW, nothing written.
        let mut n = SENTINEL_COUNT;
        let big = usize::from(tweak_at) << 32 | 0xffff_ffff;
        let big_view = nls_mesh_view {
            vertex_count: big,
            ..view(&m)
        };
        let s = unsafe { nls_mesh_plan_scratch_size(&big_view, &mut n) };
        assert_eq!((s, n), (Status::SizeOverflow, SENTINEL_COUNT));
        let s = unsafe { nls_mesh_plan_scratch_size(&view(&m), core::ptr::null_mut()) };
        assert_eq!(s, Status::NullParameter);
    }
    let su0 = topo_need;

    // 1. NULL options.
    if mode == Mode::NullOptions {
        let p = plan(&m, None, su0);
        assert_eq!(p.status, Status::NullParameter);
        assert_eq!(
            (p.counts, p.scratch),
            ([SENTINEL_COUNT; 3], [SENTINEL_COUNT; 2])
        );
        let c = subdivide(&m, None, [su0, 4, 4, 4, 4], false, false);
        assert_eq!(c.status, Status::NullParameter);
        assert_eq!((c.counts, c.report), ([SENTINEL_COUNT; 3], REPORT_SENTINEL));
        assert!(c.outputs_untouched());
        return;
    }

    // 2. The plan: a documented status; invalid options are INVALID_ARGUMENT (the
    // pointers and counts here are all valid, and the options are parsed before the mesh is
    // validated).
    let p = plan(&m, Some(&raw), su0);
    assert!(
        plan_status_documented(p.status),
        "plan: undocumented {:?}",
        p.status
    );
    assert_ne!(
        p.status,
        Status::BufferTooSmall,
        "scratch of nls_mesh_plan_scratch_size is short"
    );
    if opts.invalid {
        assert_eq!(p.status, Status::InvalidArgument, "invalid options");
    }
    if mode == Mode::Alias && opts.scale.is_some() && !opts.invalid && m.nv() > 0 {
        plan_aliased(&m, &opts, su0);
    }
    if p.status != Status::Ok {
        assert_eq!(
            (p.counts, p.scratch),
            ([SENTINEL_COUNT; 3], [SENTINEL_COUNT; 2])
        );
        assert_ne!(p.element, SENTINEL_ELEMENT, "no element on {:?}", p.status);
        // The call refuses the same way and writes nothing.
        let caps = [su0, 4 * m.nv(), 4 * m.nv(), 4 * m.nf(), 4 * m.idx.len()];
        let c = subdivide(&m, Some(&raw), caps, false, false);
        assert_eq!(
            (c.status, c.element),
            (p.status, p.element),
            "subdivide vs plan"
        );
        assert_eq!((c.counts, c.report), ([SENTINEL_COUNT; 3], REPORT_SENTINEL));
        assert!(c.outputs_untouched(), "outputs written on {:?}", c.status);
        return;
    }
    assert_eq!(
        p.element, SENTINEL_ELEMENT,
        "element written by a successful plan"
    );
    let plan_sizes = p.counts;
    let [su, sp] = p.scratch;
    assert!(su >= topo_need, "planned scratch below the topology's need");
    // The plan's sizes are the spatial subdivision's.
    let spatial_scheme = if raw.scheme == NLS_DIFFERENTIAL_LOOP {
        NLS_SCHEME_LOOP
    } else {
        NLS_SCHEME_MODIFIED_BUTTERFLY
    };
    // A scratch shorter than the topology's need: BUFFER_TOO_SMALL naming it.
    if shrink == 6 && su0 > 0 {
        let q = plan(&m, Some(&raw), su0 - 1 - amount % su0);
        assert_eq!(
            (q.status, q.counts, q.element),
            (
                Status::BufferTooSmall,
                [SENTINEL_COUNT; 3],
                NLS_MESH_BUFFER_SCRATCH_U32
            )
        );
    }
    let caps = [su, sp, plan_sizes[0], plan_sizes[1], plan_sizes[2]];

    // 3. An edit array over the output positions.
    if mode == Mode::Alias && opts.scale.is_some() && m.nv() > 0 {
        let c = subdivide(&m, Some(&raw), caps, true, false);
        assert_eq!(
            c.status,
            Status::AliasingBuffers,
            "edit array over the output"
        );
        assert_eq!((c.counts, c.report), ([SENTINEL_COUNT; 3], REPORT_SENTINEL));
        assert!(c.outputs_untouched());
    }

    // 4. One buffer short by any amount.
    if (1..=5).contains(&shrink) {
        let buffer = u32::from(shrink - 1);
        let mut short = caps;
        let k = buffer as usize;
        if short[k] > 0 {
            short[k] -= 1 + amount % short[k];
            let c = subdivide(&m, Some(&raw), short, false, false);
            assert_eq!(
                (c.status, c.element),
                (Status::BufferTooSmall, buffer),
                "short {buffer}"
            );
            let early = buffer == NLS_MESH_BUFFER_SCRATCH_U32 && short[0] < topo_need;
            let want = if early {
                [SENTINEL_COUNT; 3]
            } else {
                plan_sizes
            };
            assert_eq!(c.counts, want, "sizes reported on BUFFER_TOO_SMALL");
            assert_eq!(c.report, REPORT_SENTINEL, "report on BUFFER_TOO_SMALL");
            assert!(c.outputs_untouched(), "outputs written on BUFFER_TOO_SMALL");
        }
    }

    // 5. The call itself.
    if plan_sizes[0] > MAX_OUT_VERTICES {
        return;
    }
    let null_optional = mode == Mode::NullOptionalOutputs;
    let c = subdivide(&m, Some(&raw), caps, false, null_optional);
    assert!(c.scratch_intact);
    match c.status {
        Status::Ok => {
            assert_eq!(c.counts, plan_sizes, "counts differ from the plan");
            let [nv, nf, ni] = plan_sizes;
            let pos: Vec<f64> = c.pos.v[..3 * nv].iter().map(|b| b.0).collect();
            assert!(
                pos.iter().all(|x| x.is_finite()),
                "non-finite position with OK"
            );
            let off = c.off.v[..nf + 1].to_vec();
            let idx = c.idx.v[..ni].to_vec();
            assert_eq!(off[0], 0);
            assert_eq!(off[nf] as usize, ni);
            if !null_optional {
                assert_eq!(c.element, SENTINEL_ELEMENT, "element written on success");
                let rep = c.report;
                assert_eq!(rep.converged, 1, "OK without convergence: {rep:?}");
                assert!(rep.iterations <= raw.max_iterations, "{rep:?}");
                assert!(rep.relative_residual <= raw.tolerance, "{rep:?}");
                // Counted over the DirMag levels (each level at most `nv` outputs).
                let dm = raw.dirmag_levels.min(raw.levels) as usize;
                assert!(rep.dirmag_degenerate as usize <= nv * dm, "{rep:?}");
            }
            match spatial(spatial_scheme, &m, raw.levels) {
                Some((soff, sidx)) => {
                    assert_eq!(off, soff, "offsets differ from the spatial subdivision");
                    assert_eq!(idx, sidx, "indices differ from the spatial subdivision");
                }
                None => panic!("differential planned and succeeded, spatial refused"),
            }
        }
        s => {
            assert!(compute_failure(s), "planned OK, then {s:?}");
            assert_eq!(c.counts, [SENTINEL_COUNT; 3], "counts written on {s:?}");
            if !null_optional {
                assert_ne!(c.element, SENTINEL_ELEMENT, "no element on {s:?}");
                if s == Status::NotConverged {
                    assert_ne!(c.report, REPORT_SENTINEL, "no report on NOT_CONVERGED");
                    assert_eq!(c.report.converged, 0);
                } else if s == Status::FoldedSurface {
                    assert!(c.report.folded_faces + c.report.folded_edges > 0, "{:?}", c.report);
                } else {
                    assert_eq!(c.report, REPORT_SENTINEL, "report written on {s:?}");
                }
            }
        }
    }
});
