//! Fuzz target `mesh`: whole-mesh subdivision through the C ABI (`nls_mesh_*`).
//!
//! Checks the contract of include/nlsubdiv.h, not only "no crash" (docs/bad-input-catalogue.md):
//! - `nls_mesh_plan_scratch_size`, `nls_mesh_plan` and `nls_mesh_subdivide` agree on every
//!   refusal (same status, same element), and a refusal writes no sizes, no report and no
//!   output;
//! - one buffer shortened by any amount gives `BUFFER_TOO_SMALL` naming exactly that buffer,
//!   writes nothing to the outputs, and reports the exact sizes when it is an output buffer;
//! - on success: the counts are the planned sizes, every position is finite, the output
//!   validates again, interpolating schemes keep the old vertices bit for bit, and the report
//!   is consistent;
//! - one call of several levels equals the chain of one-level calls bit for bit (or fails
//!   with the status the chain fails with).
//!
//! Input layout (fuzz/make_corpus.py writes the seeds in it; missing bytes read as 0):
//! `scheme u8, flags u8, levels u8 (→ 1,1,1,1,1,0,2,3 by b % 8), shrink u8, amount u8, tweak u8, tweak_at u16,
//!  vertex_count u16, face_count u16, face sizes u8 × F, indices u16 × Σsizes,
//!  positions f64 × 3V` (little endian). Scheme codes run past the known ones so that new
//! schemes are covered without editing this file; an unknown code must be refused with
//! `INVALID_ARGUMENT`.
#![no_main]

#[path = "common.rs"]
mod common;

use common::*;
use libfuzzer_sys::fuzz_target;
use nlsubdiv_ffi::mesh::*;
use nlsubdiv_ffi::Status;

/// Scheme codes tried: the known ones and a few above (must give `INVALID_ARGUMENT`).
const SCHEME_CODES: u8 = 12;
/// Caps that keep one execution short (the seeds have at most 400 vertices).
const LIMITS: Limits = Limits {
    vertices: 400,
    faces: 800,
    indices: 3200,
};
/// Multi-level comparisons only when the last level stays below this many vertices.
const MAX_LEVEL_VERTICES: usize = 1500;
/// Interpolating schemes (old vertices kept bit for bit), by code.
const INTERPOLATING: [u32; 4] = [
    NLS_SCHEME_MODIFIED_BUTTERFLY,
    NLS_SCHEME_KOBBELT,
    NLS_SCHEME_VERTEX_INSERTION,
    NLS_SCHEME_SPHERELIKE,
];

/// What one `nls_mesh_subdivide` call returned, with its buffers.
struct Call {
    status: Status,
    mesh: Mesh,
    counts: [usize; 3],
    report: nls_subdivide_report,
    element: u32,
}

const REPORT_SENTINEL: nls_subdivide_report = nls_subdivide_report {
    fallbacks: 0xdead,
    first_fallback: 0xdead,
    first_fallback_level: 0xdead,
    guarded: 0xdead,
    first_guarded: 0xdead,
    first_guarded_level: 0xdead,
};

/// Output buffers of the given capacities, filled with sentinels.
fn buffers(caps: [usize; 3]) -> Mesh {
    Mesh {
        pos: f64_sentinels(3 * caps[0]),
        off: vec![SENTINEL_U32; caps[1] + 1],
        idx: vec![SENTINEL_U32; caps[2]],
    }
}

fn options(scheme: u32, flags: u32, levels: u32) -> nls_subdivide_options {
    let mut o = core::mem::MaybeUninit::<nls_subdivide_options>::uninit();
    assert_eq!(
        unsafe { nls_subdivide_default_options(o.as_mut_ptr()) },
        Status::Ok
    );
    let mut o = unsafe { o.assume_init() };
    o.scheme = scheme;
    o.flags = flags;
    o.levels = levels;
    o
}

/// `nls_mesh_plan_scratch_size`.
fn plan_scratch(m: &Mesh) -> (Status, usize) {
    let mut su = SENTINEL_COUNT;
    let s = unsafe { nls_mesh_plan_scratch_size(&view(m), &mut su) };
    (s, su)
}

/// `nls_mesh_plan` with `su` scratch entries: status, output sizes, scratch, element.
fn plan(
    scheme: u32,
    flags: u32,
    levels: u32,
    m: &Mesh,
    su: usize,
) -> (Status, [usize; 3], [usize; 2], u32) {
    let mut scratch = vec![0u32; su];
    let mut p = nls_plan {
        output: nls_mesh_sizes {
            vertex_count: SENTINEL_COUNT,
            face_count: SENTINEL_COUNT,
            index_count: SENTINEL_COUNT,
        },
        scratch_u32: SENTINEL_COUNT,
        scratch_points: SENTINEL_COUNT,
    };
    let mut element = SENTINEL_ELEMENT;
    let o = options(scheme, flags, levels);
    let s = unsafe { nls_mesh_plan(&view(m), &o, scratch.as_mut_ptr(), su, &mut p, &mut element) };
    let out = p.output;
    (
        s,
        [out.vertex_count, out.face_count, out.index_count],
        [p.scratch_u32, p.scratch_points],
        element,
    )
}

/// `nls_mesh_subdivide` with exactly sized fresh buffers (so ASan sees any overrun).
#[allow(clippy::too_many_arguments)]
fn subdivide(
    scheme: u32,
    flags: u32,
    levels: u32,
    m: &Mesh,
    su: usize,
    sp: usize,
    caps: [usize; 3],
) -> Call {
    let mut scratch = vec![0u32; su];
    let mut points = vec![0.0f64; 3 * sp];
    let mut out = buffers(caps);
    let mut sizes = nls_mesh_sizes {
        vertex_count: SENTINEL_COUNT,
        face_count: SENTINEL_COUNT,
        index_count: SENTINEL_COUNT,
    };
    let mut report = REPORT_SENTINEL;
    let mut element = SENTINEL_ELEMENT;
    let o = options(scheme, flags, levels);
    let sc = nls_scratch {
        u32s: scratch.as_mut_ptr(),
        u32_capacity: su,
        points: points.as_mut_ptr(),
        point_capacity: sp,
    };
    let b = nls_mesh_buffers {
        positions: out.pos.as_mut_ptr(),
        vertex_capacity: caps[0],
        offsets: out.off.as_mut_ptr(),
        face_capacity: caps[1],
        indices: out.idx.as_mut_ptr(),
        index_capacity: caps[2],
    };
    let status =
        unsafe { nls_mesh_subdivide(&view(m), &o, &sc, &b, &mut sizes, &mut report, &mut element) };
    Call {
        status,
        mesh: out,
        counts: [sizes.vertex_count, sizes.face_count, sizes.index_count],
        report,
        element,
    }
}

/// Statuses only the computation (not validation or planning) can give.
fn compute_failure(s: Status, flags: u32) -> bool {
    let strict = flags & NLS_SUBDIVIDE_STRICT != 0 && flags & NLS_SUBDIVIDE_MOBIUS != 0;
    matches!(s, Status::NumericalFailure | Status::DegenerateGeometry)
        || (strict && s == Status::FallbackInStrictMode)
}

/// A refused call wrote no count, no report and (validation failures) no output.
fn assert_nothing_written(c: &Call, outputs_too: bool) {
    assert_eq!(
        c.counts, [SENTINEL_COUNT; 3],
        "counts written on {:?}",
        c.status
    );
    assert_eq!(
        c.report, REPORT_SENTINEL,
        "report written on {:?}",
        c.status
    );
    assert_ne!(c.element, SENTINEL_ELEMENT, "no element on {:?}", c.status);
    if outputs_too {
        assert!(
            untouched_f64(&c.mesh.pos),
            "positions written on {:?}",
            c.status
        );
        assert!(
            untouched_u32(&c.mesh.off),
            "offsets written on {:?}",
            c.status
        );
        assert!(
            untouched_u32(&c.mesh.idx),
            "indices written on {:?}",
            c.status
        );
    }
}

/// The written output as a mesh (checked against the counts).
fn written(c: &Call) -> Mesh {
    let [nv, nf, ni] = c.counts;
    Mesh {
        pos: c.mesh.pos[..3 * nv].to_vec(),
        off: c.mesh.off[..nf + 1].to_vec(),
        idx: c.mesh.idx[..ni].to_vec(),
    }
}

/// Checks a successful one-level call against its plan.
fn check_success(scheme: u32, flags: u32, input: &Mesh, c: &Call, sizes: [usize; 3]) -> Mesh {
    assert_eq!(c.counts, sizes, "sizes differ from the plan");
    assert_eq!(c.element, SENTINEL_ELEMENT, "element written on success");
    let out = written(c);
    assert!(
        out.pos.iter().all(|x| x.is_finite()),
        "non-finite position with OK"
    );
    assert_eq!(out.off[0], 0);
    assert_eq!(*out.off.last().unwrap() as usize, out.idx.len());
    let r = c.report;
    if flags & NLS_SUBDIVIDE_MOBIUS == 0 || flags & NLS_SUBDIVIDE_STRICT != 0 {
        assert_eq!(
            r.fallbacks, 0,
            "fallbacks reported by a linear or strict call"
        );
    }
    if r.fallbacks == 0 {
        assert_eq!((r.first_fallback, r.first_fallback_level), (u32::MAX, 0));
    } else {
        assert!(r.fallbacks as usize <= sizes[0] && (r.first_fallback as usize) < sizes[0]);
        assert_eq!(r.first_fallback_level, 1);
    }
    if INTERPOLATING.contains(&scheme) {
        assert!(
            same_bits(&out.pos[..input.pos.len()], &input.pos),
            "an interpolating scheme moved an old vertex"
        );
    }
    // The output is a valid mesh again (Catmull–Clark accepts every face size).
    let (s, su) = plan_scratch(&out);
    assert_eq!(s, Status::Ok);
    let (s, _, _, e) = plan(NLS_SCHEME_CATMULL_CLARK, 0, 1, &out, su);
    assert_eq!(s, Status::Ok, "the output does not validate (element {e})");
    out
}

/// One level, with the exact sizes: `Ok(output, report)` or the refusal.
fn one_level(scheme: u32, flags: u32, m: &Mesh) -> Result<(Mesh, nls_subdivide_report), Status> {
    let (s, su0) = plan_scratch(m);
    if s != Status::Ok {
        return Err(s);
    }
    let (s, sizes, [su, sp], _) = plan(scheme, flags, 1, m, su0);
    if s != Status::Ok {
        return Err(s);
    }
    let c = subdivide(scheme, flags, 1, m, su, sp, sizes);
    if c.status != Status::Ok {
        return Err(c.status);
    }
    Ok((check_success(scheme, flags, m, &c, sizes), c.report))
}

fn check_levels(scheme: u32, flags: u32, m: &Mesh, levels: u32, su_in: usize) {
    let (s, sizes, [su, sp], element) = plan(scheme, flags, levels, m, su_in);
    if s != Status::Ok {
        assert_ne!(s, Status::BufferTooSmall);
        // The multi-level call refuses the same way and writes nothing.
        let c = subdivide(scheme, flags, levels, m, su_in, 0, [0, 0, 0]);
        assert_eq!(
            (c.status, c.element),
            (s, element),
            "levels call vs its size query"
        );
        assert_nothing_written(&c, true);
        return;
    }
    if sizes[0] > MAX_LEVEL_VERTICES {
        return;
    }
    let c = subdivide(scheme, flags, levels, m, su, sp, sizes);
    // The chain of one-level calls.
    let mut cur = m.clone();
    let mut chain = Ok(());
    let mut fallbacks = 0u32;
    let mut first = (u32::MAX, 0u32);
    for level in 1..=levels {
        match one_level(scheme, flags, &cur) {
            Ok((next, r)) => {
                if r.fallbacks > 0 && first.1 == 0 {
                    first = (r.first_fallback, level);
                }
                fallbacks += r.fallbacks;
                cur = next;
            }
            Err(e) => {
                chain = Err(e);
                break;
            }
        }
    }
    match chain {
        Ok(()) => {
            assert_eq!(
                c.status,
                Status::Ok,
                "levels call failed where the chain did not"
            );
            assert_eq!(c.counts, sizes);
            let out = written(&c);
            assert!(
                same_bits(&out.pos, &cur.pos),
                "levels positions differ from the chain"
            );
            assert_eq!(out.off, cur.off, "levels offsets differ from the chain");
            assert_eq!(out.idx, cur.idx, "levels indices differ from the chain");
            let r = c.report;
            assert_eq!(
                (r.fallbacks, r.first_fallback, r.first_fallback_level),
                (fallbacks, first.0, first.1)
            );
        }
        Err(e) => {
            assert_eq!(c.status, e, "levels call vs the chain of one-level calls");
            assert!(
                compute_failure(e, flags),
                "planned OK but the chain was refused: {e:?}"
            );
            assert_nothing_written(&c, false);
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let mut r = Reader::new(data);
    let scheme = u32::from(r.u8() % SCHEME_CODES);
    let flags = u32::from(r.u8() & 7);
    // One level in 5 of 8 inputs; 0, 2 and 3 levels (the multi-level comparison, which runs
    // the chain of one-level calls too) in the other 3.
    let levels = [1, 1, 1, 1, 1, 0, 2, 3][usize::from(r.u8() % 8)];
    let shrink = r.u8() % 6;
    let amount = usize::from(r.u8());
    let tweak = r.u8();
    let tweak_at = r.u16();
    let m = decode_mesh(&mut r, tweak, tweak_at, LIMITS);

    // 1. The plan's scratch depends on the counts only.
    let (s0, su0) = plan_scratch(&m);
    if s0 != Status::Ok {
        assert_eq!(su0, SENTINEL_COUNT);
        assert_eq!(s0, Status::SizeOverflow, "{s0:?}");
        let c = subdivide(scheme, flags, 1, &m, 0, 0, [4, 4, 4]);
        assert!(
            matches!(c.status, Status::InvalidArgument | Status::SizeOverflow),
            "{:?}",
            c.status
        );
        assert_nothing_written(&c, true);
        return;
    }

    // 2. Options and validation: the plan and the call refuse with the same status and element.
    let (s1, plan1, [su, sp], element) = plan(scheme, flags, 1, &m, su0);
    assert_ne!(
        s1,
        Status::BufferTooSmall,
        "scratch of nls_mesh_plan_scratch_size is short"
    );
    if s1 != Status::Ok {
        assert_eq!(plan1, [SENTINEL_COUNT; 3], "sizes written on {s1:?}");
        let caps = [m.nv() * 4, m.nf() * 4, m.idx.len() * 4];
        let c = subdivide(scheme, flags, 1, &m, su0, 4 * m.idx.len(), caps);
        assert_eq!((c.status, c.element), (s1, element), "call vs plan");
        assert_nothing_written(&c, true);
        return;
    }
    assert!(su >= su0, "the call's scratch below the plan's own");
    if shrink == 1 && su0 > 0 {
        let (s, c, _, e) = plan(scheme, flags, 1, &m, su0 - 1 - amount % su0);
        assert_eq!(
            (s, c, e),
            (
                Status::BufferTooSmall,
                [SENTINEL_COUNT; 3],
                NLS_MESH_BUFFER_SCRATCH_U32
            )
        );
    }
    let plan = plan1;

    // 3. One buffer short by any amount: BUFFER_TOO_SMALL naming it, nothing written.
    if shrink > 0 {
        let buffer = u32::from(shrink - 1);
        let (mut su2, mut sp2, mut caps) = (su, sp, plan);
        let need = match buffer {
            NLS_MESH_BUFFER_SCRATCH_U32 => &mut su2,
            NLS_MESH_BUFFER_SCRATCH_POINTS => &mut sp2,
            b => &mut caps[(b - NLS_MESH_BUFFER_POSITIONS) as usize],
        };
        if *need > 0 {
            *need -= 1 + amount % *need;
            let c = subdivide(scheme, flags, 1, &m, su2, sp2, caps);
            assert_eq!((c.status, c.element), (Status::BufferTooSmall, buffer));
            let counts = if buffer >= NLS_MESH_BUFFER_POSITIONS {
                plan
            } else {
                [SENTINEL_COUNT; 3]
            };
            assert_eq!(c.counts, counts, "sizes reported on BUFFER_TOO_SMALL");
            assert_eq!(c.report, REPORT_SENTINEL);
            assert!(
                untouched_f64(&c.mesh.pos)
                    && untouched_u32(&c.mesh.off)
                    && untouched_u32(&c.mesh.idx)
            );
        }
    }

    // 4. The call itself.
    let c = subdivide(scheme, flags, 1, &m, su, sp, plan);
    if c.status != Status::Ok {
        assert!(
            compute_failure(c.status, flags),
            "validated, then {:?}",
            c.status
        );
        assert_nothing_written(&c, false);
    } else {
        check_success(scheme, flags, &m, &c, plan);
    }

    // 5. Several levels (0, 2 or 3) in one call = the chain of one-level calls.
    if levels != 1 {
        check_levels(scheme, flags, &m, levels, su0);
    }
});
