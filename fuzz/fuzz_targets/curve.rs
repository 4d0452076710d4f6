//! Fuzz target `curve`: curve subdivision through the C ABI (`nls_curve_*`).
//!
//! Contract checked (include/nlsubdiv.h, docs/bad-input-catalogue.md):
//! - `nls_curve_refined_size`, `nls_curve_scratch_size` and `nls_curve_subdivide` agree on
//!   refusals; a refusal writes no count and no output;
//! - the output or the scratch shortened by any amount gives `BUFFER_TOO_SMALL` with the exact
//!   size of that buffer in `*out_count` and nothing written to the output;
//! - on success: the count is `refined_size`, every point is finite, interpolating schemes keep
//!   the old points bit for bit at indices `2^levels · i`, and `k` levels equal `k` calls of one
//!   level bit for bit.
//!
//! Input layout: `scheme u8, closed u8, levels u8, shrink u8, amount u8, special u8,
//! special_at u8, count u8, points f64 × 3count` (little endian, missing bytes read as 0).
#![no_main]

#[path = "common.rs"]
mod common;

use common::*;
use libfuzzer_sys::fuzz_target;
use nlsubdiv_ffi::curve::*;
use nlsubdiv_ffi::Status;

/// Curve scheme codes tried: the known ones and a few above (`INVALID_ARGUMENT`).
const SCHEME_CODES: u8 = 10;
/// Interpolating curve schemes, by code.
const INTERPOLATING: [u32; 3] = [
    NLS_CURVE_FOUR_POINT,
    NLS_CURVE_MOBIUS_INTERPOLATING,
    NLS_CURVE_CIRCLE_BLEND,
];

struct Call {
    status: Status,
    out: Vec<f64>,
    count: usize,
    element: u32,
}

fn call(
    scheme: u32,
    pts: &[f64],
    closed: u32,
    levels: u32,
    cap: usize,
    scratch_cap: usize,
) -> Call {
    let mut out = f64_sentinels(3 * cap);
    let mut scratch = vec![0.0; 3 * scratch_cap];
    let mut count = SENTINEL_COUNT;
    let mut element = SENTINEL_ELEMENT;
    let status = unsafe {
        nls_curve_subdivide(
            scheme,
            &nls_curve_view {
                points: pts.as_ptr(),
                count: pts.len() / 3,
                closed,
            },
            levels,
            out.as_mut_ptr(),
            cap,
            scratch.as_mut_ptr(),
            scratch_cap,
            &mut count,
            &mut element,
        )
    };
    Call {
        status,
        out,
        count,
        element,
    }
}

/// The sizes: `Ok((out, scratch))` or the first refusal.
fn sizes(scheme: u32, n: usize, closed: u32, levels: u32) -> Result<(usize, usize), Status> {
    let (mut a, mut b) = (SENTINEL_COUNT, SENTINEL_COUNT);
    let s = unsafe { nls_curve_refined_size(n, closed, levels, &mut a) };
    let t = unsafe { nls_curve_scratch_size(scheme, n, closed, levels, &mut b) };
    if s != Status::Ok {
        assert_eq!(a, SENTINEL_COUNT);
    }
    if t != Status::Ok {
        assert_eq!(b, SENTINEL_COUNT);
    }
    // The call checks the scheme code first.
    match (s, t) {
        (Status::Ok, Status::Ok) => Ok((a, b)),
        (_, Status::InvalidArgument) => Err(Status::InvalidArgument),
        (Status::Ok, e) => Err(e),
        (e, _) => Err(e),
    }
}

fuzz_target!(|data: &[u8]| {
    let mut r = Reader::new(data);
    let scheme = u32::from(r.u8() % SCHEME_CODES);
    let closed = u32::from(r.u8() % 3); // 2 is not a flag: INVALID_ARGUMENT
    let levels = u32::from(r.u8() % 6);
    let shrink = r.u8() % 3;
    let amount = usize::from(r.u8());
    let special = r.u8();
    let special_at = usize::from(r.u8());
    let n = usize::from(r.u8());
    let mut pts: Vec<f64> = (0..3 * n).map(|_| r.f64()).collect();
    if special & 1 == 1 && !pts.is_empty() {
        let k = special_at % pts.len();
        pts[k] = SPECIALS[usize::from(special >> 1) % SPECIALS.len()];
    }

    let (need, need_scratch) = match sizes(scheme, n, closed, levels) {
        Ok(s) => s,
        Err(e) => {
            // The call refuses the same way (argument errors come before the sizes).
            let c = call(scheme, &pts, closed, levels, 4 * n + 1, 4 * n + 1);
            if e == Status::InvalidArgument || e == Status::TooFewPoints {
                assert_eq!(c.status, e, "call vs size queries");
            } else {
                assert_ne!(c.status, Status::Ok);
            }
            assert_eq!(c.count, SENTINEL_COUNT, "count written on {:?}", c.status);
            assert!(untouched_f64(&c.out), "output written on {:?}", c.status);
            return;
        }
    };
    if need > 1 << 16 {
        return;
    }

    // A short buffer: BUFFER_TOO_SMALL, the exact size, nothing written.
    if shrink > 0 {
        let (mut cap, mut scap) = (need, need_scratch);
        let short = if shrink == 1 { &mut cap } else { &mut scap };
        let full = *short;
        if *short > 0 {
            *short -= 1 + amount % *short;
            let c = call(scheme, &pts, closed, levels, cap, scap);
            assert_eq!(c.status, Status::BufferTooSmall);
            // The output is checked first: its size is reported when it is short.
            let reported = if cap < need { need } else { full };
            assert_eq!(c.count, reported, "size reported on BUFFER_TOO_SMALL");
            assert!(untouched_f64(&c.out), "output written on BUFFER_TOO_SMALL");
        }
    }

    let c = call(scheme, &pts, closed, levels, need, need_scratch);
    if c.status != Status::Ok {
        assert!(
            matches!(
                c.status,
                Status::NonFiniteInput | Status::NumericalFailure | Status::DegenerateGeometry
            ),
            "sizes OK, then {:?}",
            c.status
        );
        assert_eq!(c.count, SENTINEL_COUNT, "count written on {:?}", c.status);
        assert_ne!(c.element, SENTINEL_ELEMENT);
        return;
    }
    assert_eq!(c.count, need);
    assert_eq!(c.element, SENTINEL_ELEMENT, "element written on success");
    assert!(
        c.out.iter().all(|x| x.is_finite()),
        "non-finite point with OK"
    );
    if INTERPOLATING.contains(&scheme) {
        let step = 3usize << levels;
        for (i, p) in pts.chunks_exact(3).enumerate() {
            assert!(
                same_bits(&c.out[i * step..i * step + 3], p),
                "old point {i} moved"
            );
        }
    }
    // k levels = k one-level calls, for the local schemes. The differential schemes are
    // global (seed 001 §3.5: subdivide Δ k times, then reconstruct once): k levels at once
    // and k single levels agree only up to rounding, so they are not compared bit for bit
    // (fuzz/regressions/curve/differential-levels is the input that showed it).
    let local = !matches!(
        scheme,
        NLS_CURVE_DIFFERENTIAL_FOUR_POINT | NLS_CURVE_DIFFERENTIAL_BSPLINE
    );
    if levels > 1 && local {
        let mut cur = pts.clone();
        for _ in 0..levels {
            let (a, b) = sizes(scheme, cur.len() / 3, closed, 1).expect("sizes of a finer level");
            let step = call(scheme, &cur, closed, 1, a, b);
            if step.status != Status::Ok {
                panic!("levels at once OK, one level at a time {:?}", step.status);
            }
            cur = step.out;
        }
        assert!(
            same_bits(&cur, &c.out),
            "levels at once differ from one level at a time"
        );
    }
});
