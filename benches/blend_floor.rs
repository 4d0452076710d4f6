//! The arithmetic floor of the Möbius schemes against the speed target "Möbius ≤ 2× our own
//! linear time" (issue 5), measured side by side in one run (single thread).
//!
//! `cargo bench --bench blend_floor`
//!
//! Every Möbius scheme of seed 000 §4.1 blends each interior edge with one F4 (Eq. (3); the
//! Butterfly takes the single candidate instead next to irregular vertices, so its count is an
//! upper bound: 182,016 of the 195,840 edges of its row blend, by callgrind); the
//! Catmull–Clark face point of a quad takes three F4 evaluations and one F6 (§4.4.3: the two
//! quadruplets, whose reversed partners reuse them by Lemma 4.1; one F6 step between
//! different quadruplets; one step onto a reversed partner, which is an F4; callgrind counts
//! 307,440 F4 = 122,976 edges + 3 × 61,488 faces on spot_quad). This bench times
//!
//! 1. `blend::f4` and `blend::f6` of the library per call, and
//! 2. the *bare* formulas — Eq. (3) and §4.4.2 written straight out, without a single check
//!    (no coincidence rules, no negative-real case, no range guards, no error paths), with
//!    the products of imaginary quaternions, one reciprocal per inverse and the norms the
//!    roots already have: as little arithmetic as we know to evaluate these rules with in
//!    scalar `f64`,
//!
//! on the same random generic inputs (the bare results are checked against the library's),
//! then multiplies by the number of blends each benchmark row needs (counted from its
//! topology) and sets that beside the row's linear time, measured here too. When even the bare
//! blends of a row take longer than twice its linear subdivision, no implementation of the
//! paper's algorithm in scalar `f64` meets the target on that row: the canonical forms of the
//! vertex stars and the topology still come on top.
#![allow(
    clippy::expect_used,
    clippy::unwrap_used,
    clippy::indexing_slicing,
    dead_code
)]

#[path = "../tests/common/mod.rs"]
mod common;

use std::hint::black_box;
use std::time::Instant;

use common::*;
use nlsubdiv::blend;
use nlsubdiv::scheme::Scheme;
use nlsubdiv::Point;

/// The bare formulas: quaternions as `[w, x, y, z]`, points as imaginary quaternions.
mod bare {
    use nlsubdiv::Point;
    type Q = [f64; 4];

    fn sub(a: Point, b: Point) -> Point {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }
    /// `[0, p]⁻¹ = [0, −p/|p|²]`, one division.
    fn inv(p: Point) -> Point {
        let k = -1.0 / (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        [p[0] * k, p[1] * k, p[2] * k]
    }
    /// `q⁻¹ = q̄/|q|²` with `|q|²` given.
    fn qinv_given(q: Q, norm_sq: f64) -> Q {
        let k = 1.0 / norm_sq;
        [q[0] * k, -q[1] * k, -q[2] * k, -q[3] * k]
    }
    fn qinv(q: Q) -> Q {
        qinv_given(q, q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
    }
    fn mul(a: Q, b: Q) -> Q {
        [
            a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
            a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
            a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
            a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
        ]
    }
    /// The principal square root (`Re ≥ 0` branch, generic inputs) and `|q|`, which is
    /// `|√q|²`.
    fn sqrt(q: Q) -> (Q, f64) {
        let r = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
        let s = (0.5 * (r + q[0])).sqrt();
        let k = 0.5 / s;
        ([s, q[1] * k, q[2] * k, q[3] * k], r)
    }
    /// `[0, a]·[0, b] = [−⟨a, b⟩, a × b]`: the products by zero real parts dropped.
    fn im_im(a: Point, b: Point) -> Q {
        [
            -(a[0] * b[0]) - a[1] * b[1] - a[2] * b[2],
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }
    /// `q·[0, p]`.
    fn q_im(a: Q, p: Point) -> Q {
        [
            -(a[1] * p[0]) - a[2] * p[1] - a[3] * p[2],
            a[0] * p[0] + a[2] * p[2] - a[3] * p[1],
            a[0] * p[1] - a[1] * p[2] + a[3] * p[0],
            a[0] * p[2] + a[1] * p[1] - a[2] * p[0],
        ]
    }
    /// `cr[i, j, k, l] = q_ij q_jk⁻¹ q_kl q_li⁻¹` (seed 000 §3.2) and its prefix `q_ij q_jk⁻¹`.
    fn cr(i: Point, j: Point, k: Point, l: Point) -> (Q, Q) {
        let pre = im_im(sub(j, i), inv(sub(k, j)));
        (q_im(q_im(pre, sub(l, k)), inv(sub(i, l))), pre)
    }
    /// The solution `p` of `cr[e, a, b, p] = χ` with `M = (a − e)(b − a)⁻¹` (the prefix of
    /// the cross-ratios starting `e, a, b`): `e + (M + χ)⁻¹ M (b − e)`.
    fn solve(m: Q, b: Point, e: Point, chi: Q) -> Point {
        let mc = [m[0] + chi[0], m[1] + chi[1], m[2] + chi[2], m[3] + chi[3]];
        let o = mul(qinv(mc), q_im(m, sub(b, e)));
        [e[0] + o[1], e[1] + o[2], e[2] + o[3]]
    }
    /// F4(a, b, c, d), Eq. (3): `cr[c, a, b, p] = χ = −√cr[c, a, b, d]`.
    #[inline(never)]
    pub fn f4(a: Point, b: Point, c: Point, d: Point) -> Point {
        let (rho, m) = cr(c, a, b, d);
        let (s, _) = sqrt(rho);
        solve(m, b, c, [-s[0], -s[1], -s[2], -s[3]])
    }
    /// F6(a, b, c, d, e, f), §4.4.2: `χ = −√X·√r`, `r = (√X)⁻¹ Y (√Z)⁻¹`.
    #[inline(never)]
    pub fn f6(a: Point, b: Point, c: Point, d: Point, e: Point, f: Point) -> Point {
        let (x, m) = cr(e, a, b, d);
        // Y shares the prefix M with X.
        let y = q_im(q_im(m, sub(f, b)), inv(sub(e, f)));
        let (sx, abs_x) = sqrt(x);
        let (sz, abs_z) = sqrt(cr(e, c, b, f).0);
        let (sr, _) = sqrt(mul(mul(qinv_given(sx, abs_x), y), qinv_given(sz, abs_z)));
        let chi = mul(sx, sr);
        solve(m, b, e, [-chi[0], -chi[1], -chi[2], -chi[3]])
    }
}

/// Random generic hexads `a … f` shaped like the blends' inputs: two chains of three points
/// along a unit arc, each perturbed by 0.1.
fn inputs(n: usize) -> Vec<[Point; 6]> {
    let mut s = 0x9E37_79B9_7F4A_7C15u64;
    let mut r = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    (0..n)
        .map(|_| {
            let mut h = [[0.0; 3]; 6];
            for (i, p) in h.iter_mut().enumerate() {
                let t = (i % 3) as f64 / 2.0 * 1.2 - 0.6;
                let z = if i < 3 { 0.0 } else { 0.3 };
                *p = [
                    t.sin() + 0.1 * r(),
                    1.0 - t.cos() + 0.1 * r(),
                    z + 0.1 * r(),
                ];
            }
            h
        })
        .collect()
}

/// Nanoseconds per call of `f` over `hs`, best of `reps` passes.
fn ns_per_call(hs: &[[Point; 6]], reps: usize, f: impl Fn(&[Point; 6]) -> Point) -> f64 {
    let mut best = f64::MAX;
    for _ in 0..reps {
        let t = Instant::now();
        for h in hs {
            black_box(f(black_box(h)));
        }
        best = best.min(t.elapsed().as_secs_f64());
    }
    best / hs.len() as f64 * 1e9
}

/// One multi-level linear call ([`levels_call`]), in milliseconds.
fn linear_once(s: Scheme, m: &OwnedMesh, levels: usize) -> f64 {
    let t = Instant::now();
    black_box(levels_call(s, m, levels, false));
    t.elapsed().as_secs_f64() * 1e3
}

/// `n4` F4 and `n6` F6 evaluations (cycling through `hs`), in milliseconds.
fn blends_once(
    hs: &[[Point; 6]],
    n4: usize,
    n6: usize,
    f4: impl Fn(&[Point; 6]) -> Point,
    f6: impl Fn(&[Point; 6]) -> Point,
) -> f64 {
    let t = Instant::now();
    for h in hs.iter().cycle().take(n4) {
        black_box(f4(black_box(h)));
    }
    for h in hs.iter().cycle().take(n6) {
        black_box(f6(black_box(h)));
    }
    t.elapsed().as_secs_f64() * 1e3
}

/// `(F4, F6)` evaluations of `levels` Möbius steps of `s` on a closed all-triangle or
/// all-quad mesh with `faces` faces of `d` corners: one F4 per edge (at most, for the
/// Butterfly); for Catmull–Clark three F4 and one F6 per quad face point. Every level of both splits keeps the face type, with
/// `F' = 4F` and `E' = 2E + dF`.
fn blend_counts(s: Scheme, d: usize, faces: usize, levels: usize) -> (usize, usize) {
    let (mut f, mut e) = (faces, faces * d / 2);
    let (mut n4, mut n6) = (0, 0);
    for _ in 0..levels {
        n4 += e;
        if s == Scheme::CatmullClark {
            n4 += 3 * f;
            n6 += f;
        }
        e = 2 * e + d * f;
        f *= 4;
    }
    (n4, n6)
}

fn main() {
    let hs = inputs(100_000);
    // The bare formulas compute what the library does (generic inputs: no special case).
    let mut worst = 0.0f64;
    for h in &hs {
        let [a, b, c, d, e, f] = *h;
        for (x, y) in [
            (blend::f4(a, b, c, d).unwrap(), bare::f4(a, b, c, d)),
            (
                blend::f6(a, b, c, d, e, f).unwrap(),
                bare::f6(a, b, c, d, e, f),
            ),
        ] {
            worst = worst.max((0..3).map(|i| (x[i] - y[i]).abs()).fold(0.0, f64::max));
        }
    }
    assert!(
        worst < 1e-9,
        "bare formulas disagree with the library by {worst:e}"
    );
    let reps = 9;
    let f4_lib = ns_per_call(&hs, reps, |h| blend::f4(h[0], h[1], h[2], h[3]).unwrap());
    let f4_bare = ns_per_call(&hs, reps, |h| bare::f4(h[0], h[1], h[2], h[3]));
    let f6_lib = ns_per_call(&hs, reps, |h| {
        blend::f6(h[0], h[1], h[2], h[3], h[4], h[5]).unwrap()
    });
    let f6_bare = ns_per_call(&hs, reps, |h| bare::f6(h[0], h[1], h[2], h[3], h[4], h[5]));
    println!(
        "Per call (ns), {} generic inputs, bare vs library agree to {worst:.1e}:",
        hs.len()
    );
    println!("| blend | library ns | bare ns |\n|---|---|---|");
    println!("| F4 | {f4_lib:.1} | {f4_bare:.1} |");
    println!("| F6 | {f6_lib:.1} | {f6_bare:.1} |");
    println!();

    let dir = shared_meshes_dir();
    println!(
        "| mesh | scheme | levels | F4 | F6 | linear ms | 2 × linear ms | bare blends ms | \
         library blends ms (bench inputs) | bare blends / linear |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    // Doo–Sabin and Kobbelt blend differently (corner points; virtual points): not counted.
    let counted = |s: Scheme| {
        matches!(
            s,
            Scheme::Loop | Scheme::ModifiedButterfly | Scheme::CatmullClark
        )
    };
    for (name, s, levels) in MOBIUS_BENCH_ROWS.into_iter().filter(|r| counted(r.1)) {
        let Ok(m) = read_off(&dir.join(name)) else {
            println!(
                "| {name} | {} | {levels} | SKIP: {} not found |",
                s.name(),
                dir.display()
            );
            continue;
        };
        let sizes: Vec<u32> = m.offsets.windows(2).map(|w| w[1] - w[0]).collect();
        let d = sizes[0] as usize;
        assert!(sizes.iter().all(|&k| k as usize == d) && (d == 3 || d == 4));
        // Closed: every edge in two faces, so E = dF/2 (the counts assume it).
        let mut edges: Vec<(u32, u32)> = m
            .offsets
            .windows(2)
            .flat_map(|w| {
                let f = &m.indices[w[0] as usize..w[1] as usize];
                (0..f.len()).map(move |i| {
                    let (a, b) = (f[i], f[(i + 1) % f.len()]);
                    (a.min(b), a.max(b))
                })
            })
            .collect();
        edges.sort_unstable();
        edges.dedup();
        assert_eq!(2 * edges.len(), d * sizes.len(), "{name} is not closed");
        let (n4, n6) = blend_counts(s, d, sizes.len(), levels);
        // Interleaved, best of `reps` each: the three are timed in the same minutes, so a
        // slow spell of the shared machine does not favour one of them.
        let (mut lin, mut bare_ms, mut lib_ms) = (f64::MAX, f64::MAX, f64::MAX);
        for _ in 0..reps {
            lin = lin.min(linear_once(s, &m, levels));
            bare_ms = bare_ms.min(blends_once(
                &hs,
                n4,
                n6,
                |h| bare::f4(h[0], h[1], h[2], h[3]),
                |h| bare::f6(h[0], h[1], h[2], h[3], h[4], h[5]),
            ));
            lib_ms = lib_ms.min(blends_once(
                &hs,
                n4,
                n6,
                |h| blend::f4(h[0], h[1], h[2], h[3]).unwrap(),
                |h| blend::f6(h[0], h[1], h[2], h[3], h[4], h[5]).unwrap(),
            ));
        }
        println!(
            "| {name} | {} | {levels} | {n4} | {n6} | {lin:.1} | {:.1} | {bare_ms:.1} | \
             {lib_ms:.1} | {:.2} |",
            s.name(),
            2.0 * lin,
            bare_ms / lin
        );
    }
}
