//! Fuzz target `tags`: sharp-feature subdivision through the C ABI
//! (`nls_mesh_plan_scratch_size_tagged`, `nls_mesh_plan_tagged`, `nls_mesh_subdivide_tagged`).
//!
//! Checks the contract of include/nlsubdiv.h, not only "no crash":
//! - the scratch size is the untagged one plus `vertex_count + index_count` with a tag, the
//!   untagged one without, `INVALID_ARGUMENT` for an unknown method;
//! - the plan and the call refuse with the same status and element, and a refusal writes no
//!   sizes, no report and no output; tags (creases first, then corners) name themselves;
//! - tags with a scheme other than Loop, Catmull–Clark, Modified Butterfly or Kobbelt (linear
//!   or Möbius) are `TAGS_NOT_SUPPORTED` on a valid mesh;
//! - on success: the counts are the plan's, every position is finite, a second call gives the
//!   same bits, and with no tags the result is the untagged call's, bit for bit.
//!
//! Input layout (missing bytes read as 0; fuzz/make_corpus.py writes seeds in it):
//! `scheme u8, flags u8, levels u8 (→ 1, 2, 3, 0 by b % 4), method u8 (→ 0, 1, 0, 7 by b % 4),
//!  creases u8 (≤ 16), corners u8 (≤ 8), per crease: a u16, b u16, sharpness u8,
//!  per corner: v u16, sharpness u8, then vertex_count u16, face_count u16, face sizes u8 × F,
//!  indices u16 × Σsizes, positions f64 × 3V`. A sharpness byte picks from
//!  [`SHARPNESS`] (NaN, negative and infinite included); a vertex index is taken modulo
//!  `vertex_count + 2`, so some are out of range.
#![no_main]

#[path = "common.rs"]
mod common;

use common::*;
use libfuzzer_sys::fuzz_target;
use nlsubdiv_ffi::mesh::*;
use nlsubdiv_ffi::tags::*;
use nlsubdiv_ffi::Status;

const LIMITS: Limits = Limits {
    vertices: 200,
    faces: 400,
    indices: 1600,
};
/// Sharpness values a byte picks: smooth, semi-sharp (fractional, non-dyadic), infinitely
/// sharp, above 10, and the invalid ones.
const SHARPNESS: [f64; 12] = [
    0.0,
    0.5,
    1.0,
    1.3,
    2.0,
    2.75,
    10.0,
    1e300,
    f64::NAN,
    -1.0,
    f64::INFINITY,
    -0.0,
];

fn options(scheme: u32, flags: u32, levels: u32) -> nls_subdivide_options {
    let mut o = nls_subdivide_options {
        scheme: 0,
        flags: 0,
        levels: 0,
        linear_weight: 0.0,
        executor: core::ptr::null(),
        linear_weights: core::ptr::null(),
    };
    assert_eq!(unsafe { nls_subdivide_default_options(&mut o) }, Status::Ok);
    o.scheme = scheme;
    o.flags = flags;
    o.levels = levels;
    o
}

/// The tags' arrays.
struct TagData {
    pairs: Vec<u32>,
    crease_s: Vec<f64>,
    corners: Vec<u32>,
    corner_s: Vec<f64>,
    method: u32,
}

impl TagData {
    fn view(&self) -> nls_tags {
        nls_tags {
            crease_vertices: self.pairs.as_ptr(),
            crease_sharpness: self.crease_s.as_ptr(),
            crease_count: self.crease_s.len(),
            corner_vertices: self.corners.as_ptr(),
            corner_sharpness: self.corner_s.as_ptr(),
            corner_count: self.corner_s.len(),
            method: self.method,
        }
    }
    fn is_empty(&self) -> bool {
        self.crease_s.is_empty() && self.corner_s.is_empty()
    }
}

/// One call's results.
struct Call {
    status: Status,
    pos: Vec<f64>,
    off: Vec<u32>,
    idx: Vec<u32>,
    counts: [usize; 3],
    element: u32,
}

/// The plan: status, output sizes, scratch, element (tagged or, with `tags` None, untagged).
fn plan(
    o: &nls_subdivide_options,
    m: &Mesh,
    tags: Option<&TagData>,
    su: usize,
) -> (Status, [usize; 5], u32) {
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
    let mut e = SENTINEL_ELEMENT;
    let s = match tags {
        Some(t) => unsafe {
            nls_mesh_plan_tagged(
                &view(m),
                o,
                &t.view(),
                scratch.as_mut_ptr(),
                su,
                &mut p,
                &mut e,
            )
        },
        None => unsafe { nls_mesh_plan(&view(m), o, scratch.as_mut_ptr(), su, &mut p, &mut e) },
    };
    let out = p.output;
    (
        s,
        [
            out.vertex_count,
            out.face_count,
            out.index_count,
            p.scratch_u32,
            p.scratch_points,
        ],
        e,
    )
}

/// The call with fresh buffers of the given sizes.
fn call(o: &nls_subdivide_options, m: &Mesh, tags: Option<&TagData>, sizes: [usize; 5]) -> Call {
    let [nv, nf, ni, su, sp] = sizes;
    let mut scratch = vec![0u32; su];
    let mut points = vec![0.0f64; 3 * sp];
    let mut pos = f64_sentinels(3 * nv);
    let mut off = vec![SENTINEL_U32; nf + 1];
    let mut idx = vec![SENTINEL_U32; ni];
    let mut w = nls_mesh_sizes {
        vertex_count: SENTINEL_COUNT,
        face_count: SENTINEL_COUNT,
        index_count: SENTINEL_COUNT,
    };
    let mut e = SENTINEL_ELEMENT;
    let sc = nls_scratch {
        u32s: scratch.as_mut_ptr(),
        u32_capacity: su,
        points: points.as_mut_ptr(),
        point_capacity: sp,
    };
    let b = nls_mesh_buffers {
        positions: pos.as_mut_ptr(),
        vertex_capacity: nv,
        offsets: off.as_mut_ptr(),
        face_capacity: nf,
        indices: idx.as_mut_ptr(),
        index_capacity: ni,
    };
    let status = match tags {
        Some(t) => unsafe {
            nls_mesh_subdivide_tagged(
                &view(m),
                o,
                &t.view(),
                &sc,
                &b,
                &mut w,
                core::ptr::null_mut(),
                &mut e,
            )
        },
        None => unsafe {
            nls_mesh_subdivide(&view(m), o, &sc, &b, &mut w, core::ptr::null_mut(), &mut e)
        },
    };
    Call {
        status,
        pos,
        off,
        idx,
        counts: [w.vertex_count, w.face_count, w.index_count],
        element: e,
    }
}

fuzz_target!(|data: &[u8]| {
    let mut r = Reader::new(data);
    let scheme = u32::from(r.u8() % 12);
    let flags = u32::from(r.u8() % 4); // Möbius and strict bits, in any combination
    let levels = [1, 2, 3, 0][usize::from(r.u8() % 4)];
    let method = [
        NLS_CREASE_UNIFORM,
        NLS_CREASE_CHAIKIN,
        NLS_CREASE_UNIFORM,
        7,
    ][usize::from(r.u8() % 4)];
    let nc = usize::from(r.u8() % 17);
    let nk = usize::from(r.u8() % 9);
    let raw_creases: Vec<(u16, u16, u8)> = (0..nc).map(|_| (r.u16(), r.u16(), r.u8())).collect();
    let raw_corners: Vec<(u16, u8)> = (0..nk).map(|_| (r.u16(), r.u8())).collect();
    let m = decode_mesh(&mut r, 0, 0, LIMITS);
    let modulo = m.nv() + 2;
    let idx = |v: u16| (usize::from(v) % modulo) as u32;
    let sharp = |b: u8| SHARPNESS[usize::from(b) % SHARPNESS.len()];
    let tags = TagData {
        pairs: raw_creases
            .iter()
            .flat_map(|&(a, b, _)| [idx(a), idx(b)])
            .collect(),
        crease_s: raw_creases.iter().map(|&(_, _, s)| sharp(s)).collect(),
        corners: raw_corners.iter().map(|&(v, _)| idx(v)).collect(),
        corner_s: raw_corners.iter().map(|&(_, s)| sharp(s)).collect(),
        method,
    };
    let o = options(scheme, flags, levels);

    // 1. The scratch size: untagged + V + I with a tag; unknown method refused.
    let mut su_plain = SENTINEL_COUNT;
    let mut su = SENTINEL_COUNT;
    let sp = unsafe { nls_mesh_plan_scratch_size(&view(&m), &mut su_plain) };
    let st = unsafe { nls_mesh_plan_scratch_size_tagged(&view(&m), &tags.view(), &mut su) };
    assert_eq!(sp, Status::Ok);
    if method == 7 {
        assert_eq!((st, su), (Status::InvalidArgument, SENTINEL_COUNT));
    } else {
        assert_eq!(st, Status::Ok);
        let extra = if tags.is_empty() {
            0
        } else {
            m.nv() + m.idx.len()
        };
        assert_eq!(su, su_plain + extra);
    }
    let su = if method == 7 {
        su_plain + m.nv() + m.idx.len()
    } else {
        su
    };

    // 2. Plan; a refusal is the call's refusal, with nothing written.
    let (s, sizes, element) = plan(&o, &m, Some(&tags), su);
    if s != Status::Ok {
        assert_eq!(sizes, [SENTINEL_COUNT; 5], "plan wrote sizes on {s:?}");
        assert_ne!(element, SENTINEL_ELEMENT);
        let c = call(
            &o,
            &m,
            Some(&tags),
            [
                m.nv() * 4 + 4,
                m.nf() * 4 + 4,
                m.idx.len() * 4 + 4,
                su,
                4 * m.idx.len() + 4,
            ],
        );
        assert_eq!((c.status, c.element), (s, element), "call vs plan");
        assert_eq!(c.counts, [SENTINEL_COUNT; 3]);
        assert!(untouched_f64(&c.pos) && untouched_u32(&c.off) && untouched_u32(&c.idx));
        // A valid mesh with tags and a scheme that takes none: TAGS_NOT_SUPPORTED exactly.
        let tag_scheme = (scheme == NLS_SCHEME_LOOP
            || scheme == NLS_SCHEME_CATMULL_CLARK
            || scheme == NLS_SCHEME_MODIFIED_BUTTERFLY
            || scheme == NLS_SCHEME_KOBBELT);
        let (su0, _, _) = plan(&o, &m, None, su_plain);
        if su0 == Status::Ok && !tags.is_empty() && !tag_scheme && method != 7 && levels > 0 {
            assert_eq!(s, Status::TagsNotSupported);
        }
        if s == Status::TagsNotSupported {
            assert!(
                !tags.is_empty() && !tag_scheme,
                "TAGS_NOT_SUPPORTED without cause"
            );
        }
        if matches!(
            s,
            Status::TagNotAnEdge | Status::RepeatedTag | Status::InvalidSharpness
        ) {
            assert!(
                (element as usize) < nc + nk,
                "{s:?} names tag {element} of {}",
                nc + nk
            );
        }
        return;
    }
    assert!(method != 7, "an unknown method was planned");

    // 3. The call.
    let c = call(&o, &m, Some(&tags), sizes);
    if c.status != Status::Ok {
        assert!(
            matches!(
                c.status,
                Status::NumericalFailure
                    | Status::DegenerateGeometry
                    | Status::FallbackInStrictMode
            ),
            "planned, then {:?}",
            c.status
        );
        assert_eq!(c.counts, [SENTINEL_COUNT; 3]);
        return;
    }
    assert_eq!(
        c.counts,
        [sizes[0], sizes[1], sizes[2]],
        "sizes differ from the plan"
    );
    assert!(
        c.pos.iter().all(|x| x.is_finite()),
        "non-finite output with OK"
    );
    // 4. Deterministic, and with no tags the untagged call exactly.
    let again = call(&o, &m, Some(&tags), sizes);
    assert!(same_bits(&c.pos, &again.pos) && c.off == again.off && c.idx == again.idx);
    if tags.is_empty() {
        let (s0, sizes0, _) = plan(&o, &m, None, su_plain);
        assert_eq!((s0, sizes0), (Status::Ok, sizes));
        let plain = call(&o, &m, None, sizes0);
        assert_eq!(plain.status, Status::Ok);
        assert!(same_bits(&c.pos, &plain.pos) && c.off == plain.off && c.idx == plain.idx);
    }
});
