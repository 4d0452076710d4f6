//! Fuzz target `primitives`: the point and star primitives of the C ABI (cross-ratio, F4, F6,
//! quaternions, Möbius maps, canonical forms, tangent polygons, star energies, face points,
//! the tier-1 star rules).
//!
//! Contract checked: on `NLS_STATUS_OK` every output is finite (the star rules may give NaN,
//! documented as "does not exist", never ±Inf); on any error the output is untouched.
//!
//! Input layout: `function u8, ring_len u8, option u8, special u8, special_at u8`, then up to
//! 3·(ring_len + 8) + 64 raw little-endian f64 values (missing bytes read as 0).
#![no_main]

#[path = "common.rs"]
mod common;

use common::*;
use libfuzzer_sys::fuzz_target;
use nlsubdiv_ffi::mobius::*;
use nlsubdiv_ffi::primitives::*;
use nlsubdiv_ffi::star::*;
use nlsubdiv_ffi::Status;

const FUNCTIONS: u8 = 23;
/// Ring lengths up to a bit above the valence capacity (128).
const MAX_RING: usize = 140;

/// Checks the outcome of a call whose outputs were sentinel-filled.
fn check(name: &str, s: Status, out: &[f64], nan_ok: bool) {
    if s == Status::Ok {
        for x in out {
            assert!(
                x.is_finite() || (nan_ok && x.is_nan()),
                "{name}: OK with {x}"
            );
        }
    } else {
        assert!(untouched_f64(out), "{name}: output written on {s:?}");
        assert_ne!(s, Status::BufferTooSmall, "{name}");
    }
}

fn mobius_from(v: &[f64]) -> nls_mobius {
    let q = |i: usize| [v[4 * i], v[4 * i + 1], v[4 * i + 2], v[4 * i + 3]];
    nls_mobius {
        a: q(0),
        b: q(1),
        c: q(2),
        d: q(3),
    }
}

fn mobius_sentinel() -> nls_mobius {
    mobius_from(&f64_sentinels(16))
}

fn mobius_flat(m: &nls_mobius) -> Vec<f64> {
    [m.a, m.b, m.c, m.d].concat()
}

fn form_flat(f: &nls_canonical_form) -> Vec<f64> {
    let mut v = [f.v, f.c].concat();
    v.push(f.r);
    v
}

fuzz_target!(|data: &[u8]| {
    let mut r = Reader::new(data);
    let function = r.u8() % FUNCTIONS;
    let n = usize::from(r.u8()) % (MAX_RING + 1);
    let option = r.u8();
    let special = r.u8();
    let special_at = usize::from(r.u8());
    let want = 3 * (n + 8) + 64;
    let mut pool: Vec<f64> = (0..want).map(|_| r.f64()).collect();
    if special & 1 == 1 {
        let k = special_at % pool.len();
        pool[k] = SPECIALS[usize::from(special >> 1) % SPECIALS.len()];
    }
    // Fixed slots: points p(0..8) from the front, then the ring, then scalars.
    let p = |i: usize| -> [f64; 3] { [pool[3 * i], pool[3 * i + 1], pool[3 * i + 2]] };
    let ring: Vec<f64> = pool[24..24 + 3 * n].to_vec();
    let scalar = |i: usize| pool[24 + 3 * n + i];
    let (a, b, c, d, e, f) = (p(0), p(1), p(2), p(3), p(4), p(5));
    let quat = |i: usize| -> [f64; 4] {
        [
            pool[4 * i],
            pool[4 * i + 1],
            pool[4 * i + 2],
            pool[4 * i + 3],
        ]
    };
    let closed = u32::from(option % 3); // 2: INVALID_ARGUMENT
    let mut out = f64_sentinels(3 * n.max(4));
    unsafe {
        match function {
            0 => {
                let s = nls_cross_ratio(
                    a.as_ptr(),
                    b.as_ptr(),
                    c.as_ptr(),
                    d.as_ptr(),
                    out.as_mut_ptr(),
                );
                check("cross_ratio", s, &out[..4], false);
            }
            1 => {
                let s = nls_f4(
                    a.as_ptr(),
                    b.as_ptr(),
                    c.as_ptr(),
                    d.as_ptr(),
                    out.as_mut_ptr(),
                );
                check("f4", s, &out[..3], false);
            }
            2 => {
                let s = nls_f4_hinted(
                    a.as_ptr(),
                    b.as_ptr(),
                    c.as_ptr(),
                    d.as_ptr(),
                    e.as_ptr(),
                    out.as_mut_ptr(),
                );
                check("f4_hinted", s, &out[..3], false);
            }
            3 => {
                let s = nls_f6(
                    a.as_ptr(),
                    b.as_ptr(),
                    c.as_ptr(),
                    d.as_ptr(),
                    e.as_ptr(),
                    f.as_ptr(),
                    out.as_mut_ptr(),
                );
                check("f6", s, &out[..3], false);
            }
            4 => {
                let s = nls_noncircularity(
                    a.as_ptr(),
                    b.as_ptr(),
                    c.as_ptr(),
                    d.as_ptr(),
                    out.as_mut_ptr(),
                );
                check("noncircularity", s, &out[..1], false);
            }
            5 => {
                let s = nls_corner_tangent(a.as_ptr(), b.as_ptr(), c.as_ptr(), out.as_mut_ptr());
                check("corner_tangent", s, &out[..3], false);
            }
            6 => {
                let mut o = f64_sentinels(3 * n);
                let s = nls_tangent_polygon(a.as_ptr(), ring.as_ptr(), n, o.as_mut_ptr());
                check("tangent_polygon", s, &o, false);
            }
            7..=11 => {
                let (q1, q2) = (quat(0), quat(1));
                let s = match function {
                    7 => nls_quat_mul(q1.as_ptr(), q2.as_ptr(), out.as_mut_ptr()),
                    8 => nls_quat_inverse(q1.as_ptr(), out.as_mut_ptr()),
                    9 => nls_quat_sqrt(q1.as_ptr(), out.as_mut_ptr()),
                    10 => nls_quat_log(q1.as_ptr(), out.as_mut_ptr()),
                    _ => nls_quat_exp(q1.as_ptr(), out.as_mut_ptr()),
                };
                check("quaternion", s, &out[..4], false);
            }
            12 => {
                let s = nls_star_willmore_energy(
                    a.as_ptr(),
                    ring.as_ptr(),
                    n,
                    closed,
                    out.as_mut_ptr(),
                );
                check("star_willmore_energy", s, &out[..1], false);
            }
            13 => {
                let s = nls_star_mobius_regularity(
                    a.as_ptr(),
                    ring.as_ptr(),
                    n,
                    closed,
                    out.as_mut_ptr(),
                );
                check("star_mobius_regularity", s, &out[..1], false);
            }
            14 => {
                // Vertices and candidates: two halves of the ring.
                let k = n / 2;
                let s = nls_face_point(ring.as_ptr(), ring[3 * k..].as_ptr(), k, out.as_mut_ptr());
                check("face_point", s, &out[..3], false);
                // With distinct vertex ids the face point does not depend on the corner the
                // face starts at, bit for bit (blend::face_point_with_ids).
                let ids: Vec<u32> = (0..k as u32)
                    .map(|i| i.wrapping_mul(2_654_435_761).wrapping_add(n as u32))
                    .collect();
                let (v, c) = (&ring[..3 * k], &ring[3 * k..6 * k]);
                let mut o1 = f64_sentinels(3);
                let s1 = nls_face_point_with_ids(
                    v.as_ptr(),
                    c.as_ptr(),
                    ids.as_ptr(),
                    k,
                    o1.as_mut_ptr(),
                );
                check("face_point_with_ids", s1, &o1, false);
                if k > 0 {
                    let rot = |x: &[f64]| -> Vec<f64> {
                        (0..3 * k).map(|j| x[(j + 3) % (3 * k)]).collect()
                    };
                    let (rv, rc) = (rot(v), rot(c));
                    let rid: Vec<u32> = (0..k).map(|i| ids[(i + 1) % k]).collect();
                    let mut o2 = f64_sentinels(3);
                    let s2 = nls_face_point_with_ids(
                        rv.as_ptr(),
                        rc.as_ptr(),
                        rid.as_ptr(),
                        k,
                        o2.as_mut_ptr(),
                    );
                    assert_eq!(
                        s1, s2,
                        "face_point_with_ids: status depends on the face start"
                    );
                    if s1 == Status::Ok {
                        assert!(
                            o1.iter().zip(&o2).all(|(x, y)| x.to_bits() == y.to_bits()),
                            "face_point_with_ids depends on the face start"
                        );
                    }
                }
            }
            15 => {
                let mut m = mobius_sentinel();
                let s = nls_mobius_similarity(a.as_ptr(), scalar(0), scalar(1), b.as_ptr(), &mut m);
                check("mobius_similarity", s, &mobius_flat(&m), false);
            }
            16 => {
                let mut m = mobius_sentinel();
                let s = nls_mobius_inversion(a.as_ptr(), scalar(0), &mut m);
                check("mobius_inversion", s, &mobius_flat(&m), false);
            }
            17..=19 => {
                let (m1, m2) = (mobius_from(&pool[..16]), mobius_from(&pool[16..32]));
                let mut m = mobius_sentinel();
                let s = match function {
                    17 => nls_mobius_compose(&m1, &m2, &mut m),
                    18 => nls_mobius_invert(&m1, &mut m),
                    _ => {
                        let q = p(11);
                        let s = nls_mobius_apply(&m1, q.as_ptr(), out.as_mut_ptr());
                        check("mobius_apply", s, &out[..3], false);
                        return;
                    }
                };
                check("mobius_compose/invert", s, &mobius_flat(&m), false);
            }
            20 => {
                let kind = u32::from(option % 4); // 3: INVALID_ARGUMENT
                let sentinel = nls_canonical_form {
                    v: [f64::from_bits(SENTINEL_F64); 3],
                    c: [f64::from_bits(SENTINEL_F64); 3],
                    r: f64::from_bits(SENTINEL_F64),
                    kind: SENTINEL_U32,
                };
                let mut cf = sentinel;
                let s = nls_canonical_form_new(a.as_ptr(), ring.as_ptr(), n, kind, &mut cf);
                check("canonical_form_new", s, &form_flat(&cf), false);
                if s != Status::Ok {
                    assert_eq!(cf.kind, SENTINEL_U32);
                    // A malformed form from the pool is refused or mapped, never trusted.
                    cf = nls_canonical_form {
                        v: b,
                        c: c,
                        r: scalar(0),
                        kind: u32::from(option >> 2),
                    };
                }
                let q = p(6);
                let mut o = f64_sentinels(3);
                let s = nls_canonical_form_to_canonical(&cf, q.as_ptr(), o.as_mut_ptr());
                check("canonical_form_to_canonical", s, &o, false);
                let mut o = f64_sentinels(3);
                let s = nls_canonical_form_from_canonical(&cf, q.as_ptr(), o.as_mut_ptr());
                check("canonical_form_from_canonical", s, &o, false);
                let mut m = mobius_sentinel();
                let s = nls_canonical_form_map(&cf, u32::from(option >> 6), &mut m);
                check("canonical_form_map", s, &mobius_flat(&m), false);
            }
            21 => {
                let mut vp = f64_sentinels(3);
                let mut ec = f64_sentinels(3 * n);
                let star = nls_star_view {
                    v: a.as_ptr(),
                    ring: ring.as_ptr(),
                    ring_count: n,
                    closed,
                    face_offsets: core::ptr::null(),
                    face_count: 0,
                    face_corners: core::ptr::null(),
                    corner_count: 0,
                };
                let s = nls_mobius_loop_star(&star, vp.as_mut_ptr(), ec.as_mut_ptr());
                check("mobius_loop_star", s, &[vp, ec].concat(), true);
            }
            _ => {
                // Triangle faces (v, ring[j], ring[j+1]); `option` may break one offset.
                let faces = if closed == 1 { n } else { n.saturating_sub(1) };
                let mut offsets: Vec<u32> = (0..=faces as u32).map(|j| 3 * j).collect();
                let mut corners = Vec::with_capacity(9 * faces);
                for j in 0..faces {
                    let k = (j + 1) % n.max(1);
                    corners.extend_from_slice(&a);
                    corners.extend_from_slice(&ring[3 * j..3 * j + 3]);
                    corners.extend_from_slice(&ring[3 * k..3 * k + 3]);
                }
                if option & 0x80 != 0 {
                    let k = usize::from(option >> 3 & 0xf) % offsets.len();
                    offsets[k] ^= u32::from(special >> 4) + 1;
                }
                let mut vp = f64_sentinels(3);
                let mut ec = f64_sentinels(3 * n);
                let mut fc = f64_sentinels(3 * faces);
                let star = nls_star_view {
                    v: a.as_ptr(),
                    ring: ring.as_ptr(),
                    ring_count: n,
                    closed,
                    face_offsets: offsets.as_ptr(),
                    face_count: faces,
                    face_corners: corners.as_ptr(),
                    corner_count: corners.len() / 3,
                };
                let s = nls_mobius_catmull_clark_star(
                    &star,
                    vp.as_mut_ptr(),
                    ec.as_mut_ptr(),
                    fc.as_mut_ptr(),
                );
                check("mobius_catmull_clark_star", s, &[vp, ec, fc].concat(), true);
            }
        }
    }
});
