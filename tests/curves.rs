//! Properties of the curve schemes (`nlsubdiv::curve`): sizes, circle reproduction, Möbius
//! equivariance, interpolation, seed 001 Eq. (A.1), polynomial precision, bad input.
//!
//! Random inputs come from a fixed-seed SplitMix64, so every run checks the same cases.
//! Measured worst values are printed (`cargo test --test curves -- --nocapture`).

// Test code: panicking on a broken expectation is the point (clippy.toml allows these in
// `#[test]` functions; the helpers here are test code too).
#![allow(clippy::indexing_slicing, clippy::unwrap_used, clippy::panic)]

use nlsubdiv::curve::{self, bspline, circle_blend, differential, four_point, mobius, CurveScheme};
use nlsubdiv::mobius::MobiusMap;
use nlsubdiv::{Point, Status};

// ---------------------------------------------------------------------------------------
// Helpers

struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    fn int(&mut self, lo: usize, hi: usize) -> usize {
        lo + (self.next_u64() % (hi - lo + 1) as u64) as usize
    }
    fn point(&mut self, s: f64) -> Point {
        [self.range(-s, s), self.range(-s, s), self.range(-s, s)]
    }
    fn unit_vector(&mut self) -> Point {
        loop {
            let p = self.point(1.0);
            let l = norm(p);
            if l > 0.1 && l <= 1.0 {
                return scale(p, 1.0 / l);
            }
        }
    }
}

fn add(a: Point, b: Point) -> Point {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn scale(a: Point, s: f64) -> Point {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn dot(a: Point, b: Point) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: Point, b: Point) -> Point {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: Point) -> f64 {
    dot(a, a).sqrt()
}
fn dist(a: Point, b: Point) -> f64 {
    norm(sub(a, b))
}

/// Subdivides with freshly sized buffers.
fn run(
    scheme: CurveScheme,
    p: &[Point],
    closed: bool,
    levels: u32,
) -> nlsubdiv::Result<Vec<Point>> {
    let m = curve::refined_size(p.len(), closed, levels)?;
    let s = curve::scratch_size(scheme, p.len(), closed, levels)?;
    let mut out = vec![[0.0; 3]; m];
    let mut scratch = vec![[0.0; 3]; s];
    let written = curve::subdivide(scheme, p, closed, levels, &mut out, &mut scratch)?;
    assert_eq!(written, m);
    Ok(out)
}

/// A circle: centre, unit normal, two in-plane unit axes, radius.
struct Circle {
    c: Point,
    n: Point,
    e1: Point,
    e2: Point,
    r: f64,
}

impl Circle {
    fn random(rng: &mut Rng) -> Circle {
        let n = rng.unit_vector();
        let mut e1 = cross(n, rng.unit_vector());
        while norm(e1) < 0.1 {
            e1 = cross(n, rng.unit_vector());
        }
        let e1 = scale(e1, 1.0 / norm(e1));
        let e2 = cross(n, e1);
        let r = 10f64.powf(rng.range(-2.0, 2.0));
        let c = rng.point(5.0 * r);
        Circle { c, n, e1, e2, r }
    }
    fn at(&self, t: f64) -> Point {
        add(
            self.c,
            add(
                scale(self.e1, self.r * t.cos()),
                scale(self.e2, self.r * t.sin()),
            ),
        )
    }
    /// Distance from the circle, relative to the radius.
    fn deviation(&self, p: Point) -> f64 {
        let d = sub(p, self.c);
        let z = dot(d, self.n);
        let inplane = norm(sub(d, scale(self.n, z)));
        (z * z + (inplane - self.r) * (inplane - self.r)).sqrt() / self.r
    }
}

/// `n` sorted, unevenly spaced angles: closed curves around the whole circle, open ones on
/// an arc of up to 1.8π.
fn uneven_angles(rng: &mut Rng, n: usize, closed: bool) -> Vec<f64> {
    let span = if closed {
        2.0 * std::f64::consts::PI
    } else {
        rng.range(0.3, 1.8) * std::f64::consts::PI
    };
    let mut w: Vec<f64> = (0..n).map(|_| rng.range(0.3, 1.7)).collect();
    let total: f64 = w.iter().sum::<f64>() + if closed { 0.0 } else { -w[n - 1] };
    let start = rng.range(0.0, 6.0);
    let mut t = start;
    let mut out = Vec::with_capacity(n);
    for wi in w.iter_mut() {
        out.push(t);
        t += *wi / total * span;
    }
    out
}

/// A random smooth space curve (a perturbed trefoil), unevenly sampled.
fn space_curve(rng: &mut Rng, n: usize, closed: bool) -> Vec<Point> {
    let size = 10f64.powf(rng.range(-1.0, 1.0));
    let offset = rng.point(3.0 * size);
    uneven_angles(rng, n, closed)
        .into_iter()
        .map(|t| {
            let p = [
                t.sin() + 2.0 * (2.0 * t).sin(),
                t.cos() - 2.0 * (2.0 * t).cos(),
                -(3.0 * t).sin(),
            ];
            add(offset, add(scale(p, size), rng.point(0.05 * size)))
        })
        .collect()
}

fn diameter(p: &[Point]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for q in p {
        for k in 0..3 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    dist(lo, hi)
}

/// A random Möbius map: an inversion in a sphere whose centre is at least twice the
/// curve's extent away from its centroid, then a rotation, a scaling and a translation.
fn random_mobius(rng: &mut Rng, p: &[Point]) -> MobiusMap {
    let mut centroid = [0.0; 3];
    for q in p {
        centroid = add(centroid, scale(*q, 1.0 / p.len() as f64));
    }
    let d = diameter(p);
    let centre = add(centroid, scale(rng.unit_vector(), d * rng.range(2.0, 4.0)));
    let inv = MobiusMap::inversion(centre, d * rng.range(0.5, 3.0));
    let rot = MobiusMap::rotation(rng.unit_vector(), rng.range(-3.0, 3.0));
    let sc = MobiusMap::scaling(10f64.powf(rng.range(-1.0, 1.0)));
    let tr = MobiusMap::translation(rng.point(5.0));
    tr.compose(&sc).compose(&rot).compose(&inv)
}

fn apply_all(m: &MobiusMap, p: &[Point]) -> Vec<Point> {
    p.iter().map(|q| m.apply(*q).unwrap()).collect()
}

// ---------------------------------------------------------------------------------------
// Sizes

#[test]
fn refined_and_scratch_sizes() {
    assert_eq!(curve::refined_size(4, true, 0).unwrap(), 4);
    assert_eq!(curve::refined_size(4, true, 1).unwrap(), 8);
    assert_eq!(curve::refined_size(4, true, 3).unwrap(), 32);
    assert_eq!(curve::refined_size(4, false, 1).unwrap(), 7);
    assert_eq!(curve::refined_size(4, false, 3).unwrap(), 25);
    assert_eq!(curve::refined_size(2, false, 5).unwrap(), 33);
    for n in 3..20usize {
        for k in 0..8u32 {
            assert_eq!(curve::refined_size(n, true, k).unwrap(), n << k);
            assert_eq!(
                curve::refined_size(n, false, k).unwrap(),
                ((n - 1) << k) + 1
            );
        }
    }
    for (n, closed) in [(0, true), (1, true), (2, true), (0, false), (1, false)] {
        assert_eq!(
            curve::refined_size(n, closed, 2).unwrap_err().status,
            Status::TooFewPoints
        );
    }
    assert_eq!(
        curve::refined_size(3, true, 63).unwrap_err().status,
        Status::SizeOverflow
    );
    assert_eq!(
        curve::refined_size(usize::MAX / 2 + 1, true, 1)
            .unwrap_err()
            .status,
        Status::SizeOverflow
    );
    assert_eq!(
        curve::refined_size(3, false, u32::MAX).unwrap_err().status,
        Status::SizeOverflow
    );
    for s in CurveScheme::ALL {
        let differential = matches!(
            s,
            CurveScheme::DifferentialFourPoint | CurveScheme::DifferentialBSpline
        );
        assert_eq!(curve::scratch_size(s, 5, true, 0).unwrap(), 0);
        assert_eq!(
            curve::scratch_size(s, 5, true, 1).unwrap(),
            if differential { 5 } else { 0 }
        );
        assert_eq!(curve::scratch_size(s, 5, true, 2).unwrap(), 10);
        assert_eq!(curve::scratch_size(s, 5, false, 3).unwrap(), 17);
        assert_eq!(
            curve::scratch_size(s, 5, false, 70).unwrap_err().status,
            Status::SizeOverflow
        );
    }
}

#[test]
fn scheme_codes_and_names_are_stable() {
    let expected = [
        (0, "four-point"),
        (1, "bspline"),
        (2, "mobius-interpolating"),
        (3, "mobius-approximating"),
        (4, "circle-blend"),
        (5, "differential-four-point"),
        (6, "differential-bspline"),
    ];
    for (s, (code, name)) in CurveScheme::ALL.iter().zip(expected) {
        assert_eq!(s.code(), code);
        assert_eq!(s.name(), name);
        assert_eq!(CurveScheme::from_code(code), Some(*s));
        assert_eq!(CurveScheme::from_name(name), Some(*s));
    }
    assert_eq!(CurveScheme::from_code(7), None);
    assert_eq!(
        CurveScheme::from_name("differential"),
        Some(CurveScheme::DifferentialFourPoint)
    );
}

// ---------------------------------------------------------------------------------------
// Circles

#[test]
fn circle_preserving_schemes_keep_circles() {
    let mut rng = Rng(0xC1C1E);
    let mut worst: f64 = 0.0;
    for scheme in CurveScheme::ALL
        .into_iter()
        .filter(|s| s.is_circle_preserving())
    {
        let mut worst_scheme: f64 = 0.0;
        for case in 0..40 {
            let closed = case % 2 == 0;
            let circle = Circle::random(&mut rng);
            // Two points determine no circle (their rule is the midpoint): n ≥ 3.
            let n = rng.int(3, 12);
            let p: Vec<Point> = uneven_angles(&mut rng, n, closed)
                .into_iter()
                .map(|t| circle.at(t))
                .collect();
            for levels in 1..=4 {
                let out = run(scheme, &p, closed, levels).unwrap();
                for q in &out {
                    let dev = circle.deviation(*q);
                    worst_scheme = worst_scheme.max(dev);
                    assert!(
                        dev < 1e-12,
                        "{scheme:?} closed={closed} n={n} levels={levels}: deviation {dev:e}"
                    );
                }
            }
        }
        println!("circle deviation {:>22}: {worst_scheme:.2e}", scheme.name());
        worst = worst.max(worst_scheme);
    }
    println!("worst circle deviation (relative to radius): {worst:.2e}");
}

#[test]
fn circle_points_stay_in_order_on_the_circle() {
    // The new points lie on the arc between their old neighbours: no folds.
    let mut rng = Rng(77);
    for scheme in CurveScheme::ALL
        .into_iter()
        .filter(|s| s.is_circle_preserving())
    {
        let circle = Circle::random(&mut rng);
        let p: Vec<Point> = uneven_angles(&mut rng, 7, true)
            .into_iter()
            .map(|t| circle.at(t))
            .collect();
        let out = run(scheme, &p, true, 3).unwrap();
        let angle = |q: Point| {
            let d = sub(q, circle.c);
            dot(d, circle.e2).atan2(dot(d, circle.e1))
        };
        let mut total = 0.0;
        for i in 0..out.len() {
            let a = angle(out[i]);
            let b = angle(out[(i + 1) % out.len()]);
            let mut step = b - a;
            while step < 0.0 {
                step += 2.0 * std::f64::consts::PI;
            }
            assert!(step < std::f64::consts::PI, "{scheme:?}: step {step}");
            total += step;
        }
        assert!(
            (total - 2.0 * std::f64::consts::PI).abs() < 1e-9,
            "{scheme:?}"
        );
    }
}

// ---------------------------------------------------------------------------------------
// Möbius equivariance

#[test]
fn mobius_schemes_commute_with_mobius_maps() {
    let mut rng = Rng(0x0B1A5);
    let mut worst: f64 = 0.0;
    for scheme in [
        CurveScheme::MobiusInterpolating,
        CurveScheme::MobiusApproximating,
    ] {
        for case in 0..40 {
            let closed = case % 2 == 0;
            let n = rng.int(if closed { 4 } else { 3 }, 14);
            let p = space_curve(&mut rng, n, closed);
            let m = random_mobius(&mut rng, &p);
            let mp = apply_all(&m, &p);
            for levels in 1..=3 {
                let a = run(scheme, &mp, closed, levels).unwrap();
                let b = apply_all(&m, &run(scheme, &p, closed, levels).unwrap());
                let d = diameter(&a);
                let err = a
                    .iter()
                    .zip(&b)
                    .map(|(x, y)| dist(*x, *y))
                    .fold(0.0, f64::max)
                    / d;
                worst = worst.max(err);
                assert!(
                    err < 1e-9,
                    "{scheme:?} closed={closed} n={n} levels={levels}: {err:e}"
                );
            }
        }
    }
    println!("worst Möbius equivariance error (relative to diameter): {worst:.2e}");
}

#[test]
fn linear_schemes_are_not_mobius_equivariant() {
    // Sanity check of the test above: it does detect a non-equivariant scheme.
    let mut rng = Rng(5);
    let p = space_curve(&mut rng, 8, true);
    let m = random_mobius(&mut rng, &p);
    let a = run(CurveScheme::FourPoint, &apply_all(&m, &p), true, 2).unwrap();
    let b = apply_all(&m, &run(CurveScheme::FourPoint, &p, true, 2).unwrap());
    let err = a
        .iter()
        .zip(&b)
        .map(|(x, y)| dist(*x, *y))
        .fold(0.0, f64::max)
        / diameter(&a);
    assert!(err > 1e-6, "{err}");
}

#[test]
fn mobius_schemes_keep_spheres() {
    // Points on a sphere stay on it (F4 is sphere preserving, seed 000 Lemma 4.1).
    let mut rng = Rng(99);
    for scheme in [
        CurveScheme::MobiusInterpolating,
        CurveScheme::MobiusApproximating,
    ] {
        for closed in [true, false] {
            let c = rng.point(3.0);
            let r = rng.range(0.5, 2.0);
            let p: Vec<Point> = (0..9)
                .map(|i| {
                    let t = i as f64 * 0.6 + rng.range(0.0, 0.2);
                    let dir = [
                        t.cos() * (0.3 * t).cos(),
                        t.sin() * (0.3 * t).cos(),
                        (0.3 * t).sin(),
                    ];
                    add(c, scale(dir, r))
                })
                .collect();
            for q in run(scheme, &p, closed, 3).unwrap() {
                let dev = (dist(q, c) - r).abs() / r;
                assert!(dev < 1e-12, "{scheme:?} closed={closed}: {dev:e}");
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// Interpolation, driver

#[test]
fn interpolating_schemes_keep_old_points_bit_exact() {
    let mut rng = Rng(1234);
    for scheme in CurveScheme::ALL
        .into_iter()
        .filter(|s| s.is_interpolating())
    {
        for case in 0..20 {
            let closed = case % 2 == 0;
            let n = rng.int(if closed { 3 } else { 2 }, 12);
            let p = space_curve(&mut rng, n, closed);
            for levels in 0..=3u32 {
                let out = run(scheme, &p, closed, levels).unwrap();
                for (i, q) in p.iter().enumerate() {
                    let o = out[i << levels];
                    assert_eq!(
                        o.map(f64::to_bits),
                        q.map(f64::to_bits),
                        "{scheme:?} closed={closed} levels={levels} point {i}"
                    );
                }
            }
        }
    }
}

#[test]
fn multi_level_equals_repeated_single_levels() {
    type One = fn(&[Point], bool, &mut [Point]) -> nlsubdiv::Result<usize>;
    let rules: [(CurveScheme, One); 5] = [
        (CurveScheme::FourPoint, four_point::refine),
        (CurveScheme::BSpline, bspline::refine),
        (
            CurveScheme::MobiusInterpolating,
            mobius::refine_interpolating,
        ),
        (
            CurveScheme::MobiusApproximating,
            mobius::refine_approximating,
        ),
        (CurveScheme::CircleBlend, circle_blend::refine),
    ];
    let mut rng = Rng(4321);
    for (scheme, one) in rules {
        for closed in [true, false] {
            let p = space_curve(&mut rng, 6, closed);
            for levels in 0..=4u32 {
                let mut cur = p.clone();
                for _ in 0..levels {
                    let mut next =
                        vec![[0.0; 3]; curve::refined_size(cur.len(), closed, 1).unwrap()];
                    assert_eq!(one(&cur, closed, &mut next).unwrap(), next.len());
                    cur = next;
                }
                let all = run(scheme, &p, closed, levels).unwrap();
                assert_eq!(all, cur, "{scheme:?} closed={closed} levels={levels}");
            }
        }
    }
}

#[test]
fn larger_buffers_are_fine_and_untouched_beyond_the_output() {
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.5, 0.0],
        [2.0, 0.0, 1.0],
        [3.0, 1.0, 0.0],
    ];
    for scheme in CurveScheme::ALL {
        for closed in [true, false] {
            let m = curve::refined_size(4, closed, 3).unwrap();
            let s = curve::scratch_size(scheme, 4, closed, 3).unwrap();
            let mut out = vec![[7.0; 3]; m + 5];
            let mut scratch = vec![[7.0; 3]; s + 5];
            let w = curve::subdivide(scheme, &p, closed, 3, &mut out, &mut scratch).unwrap();
            assert_eq!(w, m);
            assert!(out[m..].iter().all(|q| *q == [7.0; 3]));
            assert_eq!(out[..m], run(scheme, &p, closed, 3).unwrap()[..]);
        }
    }
}

#[test]
fn deterministic_bits() {
    let mut rng = Rng(8);
    let p = space_curve(&mut rng, 11, true);
    for scheme in CurveScheme::ALL {
        let a = run(scheme, &p, true, 4).unwrap();
        let b = run(scheme, &p, true, 4).unwrap();
        assert!(a
            .iter()
            .zip(&b)
            .all(|(x, y)| x.map(f64::to_bits) == y.map(f64::to_bits)));
    }
}

// ---------------------------------------------------------------------------------------
// Linear rules against their textbook weights

/// A cubic polynomial per coordinate.
fn cubic(u: f64) -> Point {
    [
        1.0 - 2.0 * u + 0.5 * u * u - 0.125 * u * u * u,
        0.3 + u * u * 0.25 + u * u * u * 0.01,
        -2.0 + 0.75 * u - 0.04 * u * u * u,
    ]
}

#[test]
fn four_point_reproduces_cubics() {
    for n in 4..12usize {
        let p: Vec<Point> = (0..n).map(|i| cubic(i as f64)).collect();
        let out = run(CurveScheme::FourPoint, &p, false, 1).unwrap();
        for i in 1..n - 2 {
            let e = out[2 * i + 1];
            let want = cubic(i as f64 + 0.5);
            assert!(
                dist(e, want) < 1e-13 * (1.0 + norm(want)),
                "{i}: {e:?} {want:?}"
            );
        }
        // The end segments reproduce lines only: 2-point extrapolation.
        let line = |u: f64| [1.0 + 2.0 * u, -u, 0.5 * u];
        let q: Vec<Point> = (0..n).map(|i| line(i as f64)).collect();
        let out = run(CurveScheme::FourPoint, &q, false, 3).unwrap();
        for (j, o) in out.iter().enumerate() {
            assert!(dist(*o, line(j as f64 / 8.0)) < 1e-13 * (1.0 + j as f64));
        }
    }
}

#[test]
fn bspline_of_a_line_stays_on_the_line() {
    let mut rng = Rng(31);
    for closed in [false, true] {
        let a = rng.point(3.0);
        let dir = rng.unit_vector();
        let mut t = 0.0;
        let p: Vec<Point> = (0..9)
            .map(|_| {
                t += rng.range(0.1, 2.0);
                add(a, scale(dir, t))
            })
            .collect();
        for q in run(CurveScheme::BSpline, &p, closed, 4).unwrap() {
            let d = sub(q, a);
            let off = norm(sub(d, scale(dir, dot(d, dir))));
            assert!(off < 1e-13 * (1.0 + norm(d)), "{off:e}");
        }
    }
    // Evenly spaced points stay evenly spaced (linear precision): open, ends kept.
    let p: Vec<Point> = (0..5)
        .map(|i| [i as f64, 2.0 * i as f64, -(i as f64)])
        .collect();
    let out = run(CurveScheme::BSpline, &p, false, 2).unwrap();
    for (j, o) in out.iter().enumerate() {
        let u = j as f64 / 4.0;
        assert!(dist(*o, [u, 2.0 * u, -u]) < 1e-14);
    }
}

#[test]
fn bspline_closed_matches_the_uniform_cubic_bspline() {
    // Vertex points of the closed B-spline rule are the limit stencil's refinement: the
    // level-1 output is (1, 6, 1)/8 and (1, 1)/2 of the input.
    let p = [
        [0.0, 0.0, 0.0],
        [4.0, 0.0, 8.0],
        [4.0, 4.0, 0.0],
        [0.0, 8.0, 16.0],
    ];
    let out = run(CurveScheme::BSpline, &p, true, 1).unwrap();
    for i in 0..4 {
        let (a, b, c) = (p[(i + 3) % 4], p[i], p[(i + 1) % 4]);
        let v = add(scale(b, 0.75), scale(add(a, c), 0.125));
        assert_eq!(out[2 * i], v);
        assert_eq!(out[2 * i + 1], scale(add(b, c), 0.5));
    }
}

// ---------------------------------------------------------------------------------------
// Differential space (seed 001)

/// Δ⁰ from Eq. (8), with the documented open-end extrapolation.
fn delta0(p: &[Point], closed: bool) -> Vec<Point> {
    let n = p.len();
    let d = |a: Point, v: Point, b: Point| sub(v, scale(add(a, b), 0.5));
    if closed {
        return (0..n)
            .map(|i| d(p[(i + n - 1) % n], p[i], p[(i + 1) % n]))
            .collect();
    }
    let mut out = vec![[0.0; 3]; n];
    for i in 1..n - 1 {
        out[i] = d(p[i - 1], p[i], p[i + 1]);
    }
    if n == 3 {
        out[0] = out[1];
        out[2] = out[1];
    } else if n > 3 {
        out[0] = sub(scale(out[1], 2.0), out[2]);
        out[n - 1] = sub(scale(out[n - 2], 2.0), out[n - 3]);
    }
    out
}

#[test]
fn differential_polygon_matches_eq_8() {
    let mut rng = Rng(3);
    for closed in [true, false] {
        for n in [3, 4, 7] {
            let p = space_curve(&mut rng, n, closed);
            let mut out = vec![[0.0; 3]; n];
            differential::differential_polygon(&p, closed, &mut out).unwrap();
            assert_eq!(out, delta0(&p, closed));
        }
    }
}

#[test]
fn differential_scheme_satisfies_eq_a1() {
    let mut rng = Rng(0xA1);
    let mut worst: f64 = 0.0;
    for (scheme, base) in [
        (CurveScheme::DifferentialFourPoint, CurveScheme::FourPoint),
        (CurveScheme::DifferentialBSpline, CurveScheme::BSpline),
    ] {
        for case in 0..20 {
            let closed = case % 2 == 0;
            let n = rng.int(if closed { 3 } else { 2 }, 12);
            let p = space_curve(&mut rng, n, closed);
            for levels in 1..=5u32 {
                let v = run(scheme, &p, closed, levels).unwrap();
                // The subdivided differential polygon Δᵏ, by the public base scheme.
                let dk = run(base, &delta0(&p, closed), closed, levels).unwrap();
                let m = v.len();
                let c = -2.0 * 0.25f64.powi(levels as i32);
                let scale_v = v.iter().map(|q| norm(*q)).fold(0.0, f64::max);
                let range: Vec<usize> = if closed {
                    (0..m).collect()
                } else {
                    (1..m - 1).collect()
                };
                for i in range {
                    let (a, b) = (v[(i + m - 1) % m], v[(i + 1) % m]);
                    let second = add(sub(a, v[i]), sub(b, v[i]));
                    let r = dist(second, scale(dk[i], c)) / scale_v;
                    worst = worst.max(r);
                    assert!(
                        r < 1e-13,
                        "{scheme:?} closed={closed} n={n} k={levels} i={i}: {r:e}"
                    );
                }
                // Fixed vertices.
                assert_eq!(v[0], p[0]);
                if !closed {
                    assert_eq!(v[m - 1], p[n - 1]);
                }
            }
        }
    }
    println!("worst Eq. (A.1) residual (relative to max |v|): {worst:.2e}");
}

#[test]
fn differential_scheme_satisfies_eq_a1_level_to_level() {
    // 4 D_k P_k = S_k D_{k−1} P_{k−1} literally (closed curves, where D is defined
    // everywhere).
    let mut rng = Rng(0xA11);
    for (scheme, base) in [
        (CurveScheme::DifferentialFourPoint, CurveScheme::FourPoint),
        (CurveScheme::DifferentialBSpline, CurveScheme::BSpline),
    ] {
        let p = space_curve(&mut rng, 9, true);
        let second = |v: &[Point]| -> Vec<Point> {
            let m = v.len();
            (0..m)
                .map(|i| add(sub(v[(i + m - 1) % m], v[i]), sub(v[(i + 1) % m], v[i])))
                .collect()
        };
        for k in 1..=4u32 {
            let prev = run(scheme, &p, true, k - 1).unwrap();
            let cur = run(scheme, &p, true, k).unwrap();
            let lhs: Vec<Point> = second(&cur).into_iter().map(|q| scale(q, 4.0)).collect();
            let rhs = run(base, &second(&prev), true, 1).unwrap();
            let s = diameter(&p);
            for (a, b) in lhs.iter().zip(&rhs) {
                assert!(dist(*a, *b) < 1e-12 * s, "{scheme:?} k={k}");
            }
        }
    }
}

#[test]
fn open_differential_scheme_reproduces_cubics() {
    for scheme in [
        CurveScheme::DifferentialFourPoint,
        CurveScheme::DifferentialBSpline,
    ] {
        for n in [3usize, 4, 6, 9] {
            let p: Vec<Point> = (0..n).map(|i| cubic(i as f64)).collect();
            for levels in 1..=4u32 {
                let v = run(scheme, &p, false, levels).unwrap();
                let h = 0.5f64.powi(levels as i32);
                for (j, q) in v.iter().enumerate() {
                    let want = cubic(j as f64 * h);
                    // n = 3 extrapolates δ as a constant: quadratic precision only.
                    if n == 3 {
                        continue;
                    }
                    assert!(
                        dist(*q, want) < 1e-12 * (1.0 + norm(want)),
                        "{scheme:?} n={n} k={levels} j={j}: {q:?} {want:?}"
                    );
                }
            }
        }
        // Quadratics with three points.
        let quad = |u: f64| [u * u, 1.0 - u, 0.5 * u * u - u];
        let p: Vec<Point> = (0..3).map(|i| quad(i as f64)).collect();
        let v = run(scheme, &p, false, 3).unwrap();
        for (j, q) in v.iter().enumerate() {
            assert!(dist(*q, quad(j as f64 / 8.0)) < 1e-13);
        }
    }
}

#[test]
fn differential_two_points_give_the_segment() {
    let p = [[0.0, 0.0, 0.0], [4.0, 8.0, -4.0]];
    for scheme in [
        CurveScheme::DifferentialFourPoint,
        CurveScheme::DifferentialBSpline,
    ] {
        let v = run(scheme, &p, false, 2).unwrap();
        for (j, q) in v.iter().enumerate() {
            assert!(dist(*q, scale(p[1], j as f64 / 4.0)) < 1e-14);
        }
    }
}

// ---------------------------------------------------------------------------------------
// Open ends, coincident points

#[test]
fn two_points_give_the_midpoint_for_every_scheme() {
    let p = [[1.0, 2.0, 3.0], [3.0, -2.0, 5.0]];
    for scheme in CurveScheme::ALL {
        let out = run(scheme, &p, false, 1).unwrap();
        assert_eq!(out[0], p[0]);
        assert_eq!(out[2], p[1]);
        assert!(dist(out[1], [2.0, 0.0, 4.0]) < 1e-15, "{scheme:?}");
    }
}

#[test]
fn mobius_open_end_equals_f4_with_the_virtual_point() {
    let mut rng = Rng(6);
    for _ in 0..50 {
        let p = space_curve(&mut rng, 5, false);
        let out = run(CurveScheme::MobiusInterpolating, &p, false, 1).unwrap();
        let v = mobius::virtual_end_point(p[0], p[1], p[2]).unwrap();
        let e = nlsubdiv::blend::f4(v, p[0], p[1], p[2]).unwrap();
        assert!(dist(out[1], e) < 1e-12 * diameter(&p), "{:?} {e:?}", out[1]);
        let v = mobius::virtual_end_point(p[4], p[3], p[2]).unwrap();
        let e = nlsubdiv::blend::f4(v, p[4], p[3], p[2]).unwrap();
        assert!(dist(out[7], e) < 1e-12 * diameter(&p));
    }
}

#[test]
fn mobius_schemes_reproduce_repeated_points() {
    let (a, b, c, d) = (
        [0.0, 0.0, 0.0],
        [1.0, 0.2, 0.0],
        [2.0, 1.0, 0.5],
        [3.0, 0.0, 1.0],
    );
    for scheme in [
        CurveScheme::MobiusInterpolating,
        CurveScheme::MobiusApproximating,
    ] {
        for closed in [true, false] {
            let p = [a, b, b, c, d];
            let out = run(scheme, &p, closed, 1).unwrap();
            // The edge point of the zero-length segment is the repeated point (b = c → b).
            assert_eq!(out[3], b, "{scheme:?} closed={closed}");
            assert!(out.iter().all(|q| q.iter().all(|x| x.is_finite())));
        }
    }
}

#[test]
fn circle_blend_rejects_repeated_points() {
    let base: Vec<Point> = (0..8)
        .map(|i| {
            let t = i as f64 * 0.7;
            [t.cos(), t.sin(), 0.1 * t]
        })
        .collect();
    for closed in [true, false] {
        let mut p = base.clone();
        p[5] = p[4];
        let e = run(CurveScheme::CircleBlend, &p, closed, 2).unwrap_err();
        assert_eq!(e.status, Status::DegenerateGeometry);
        // The first segment whose circles use the pair P4 = P5 is segment 3 (P2 P3 P4 P5).
        assert_eq!(e.element, 3, "closed={closed}");
        // A hairpin P_{i−1} = P_{i+1}: the circle through two points is undefined.
        let mut p = base.clone();
        p[6] = p[4];
        let e = run(CurveScheme::CircleBlend, &p, closed, 1).unwrap_err();
        assert_eq!(e.status, Status::DegenerateGeometry);
        // Segment 4 (P3 P4 P5 P6) is the first whose circles contain both P4 and P6.
        assert_eq!(e.element, 4);
    }
    // The linear and differential schemes are defined for repeated points.
    let mut p = base.clone();
    p[5] = p[4];
    for scheme in [
        CurveScheme::FourPoint,
        CurveScheme::BSpline,
        CurveScheme::DifferentialFourPoint,
        CurveScheme::DifferentialBSpline,
    ] {
        assert!(run(scheme, &p, true, 2).is_ok());
    }
}

#[test]
fn circle_blend_paper_form_agrees() {
    // S = P1 + cos φ · f · P12 + sin φ · f · N (seed 003 §2, Séquin's f and φ at u = ½)
    // against S = (P1 + P2)/2 + (|P1 P2|/2) tan(θ/2) N (DESIGN.md).
    let mut rng = Rng(2003);
    let mut worst: f64 = 0.0;
    for _ in 0..500 {
        let p: Vec<Point> = (0..4).map(|_| rng.point(2.0)).collect();
        let (p0, p1, p2, p3) = (p[0], p[1], p[2], p[3]);
        let t1 = circle_blend::circle_tangent(p0, p1, p2);
        let t2 = circle_blend::circle_tangent_at_start(p1, p2, p3);
        let t = add(scale(t1, 1.0 / norm(t1)), scale(t2, 1.0 / norm(t2)));
        let Ok(s) = circle_blend::blend_point(p0, p1, p2, p3) else {
            continue;
        };
        let s2 = circle_blend::arc_midpoint(p1, p2, t).unwrap();
        assert!(dist(s, s2) < 1e-12 * dist(p1, p2));
        // Paper form.
        let b = dist(p1, p2);
        let p12 = scale(sub(p2, p1), 1.0 / b);
        let that = scale(t, 1.0 / norm(t));
        let theta = dot(that, p12).clamp(-1.0, 1.0).acos();
        let rot_axis = cross(p12, that);
        if norm(rot_axis) < 1e-6 || theta > 3.0 {
            continue;
        }
        let rot_axis = scale(rot_axis, 1.0 / norm(rot_axis));
        let nn = cross(rot_axis, p12);
        let u = 0.5;
        let f = b * (u * theta).sin() / theta.sin();
        let phi = (1.0 - u) * theta;
        let paper = add(p1, add(scale(p12, phi.cos() * f), scale(nn, phi.sin() * f)));
        let err = dist(paper, s) / b;
        worst = worst.max(err);
        assert!(err < 1e-12, "{err:e}");
        // S is on the arc: equidistant from P1 and P2, on the circle tangent to t at P1.
        assert!((dist(s, p1) - dist(s, p2)).abs() < 1e-12 * b);
    }
    println!("circle blend: tangent form vs paper form, worst {worst:.2e}");
}

// ---------------------------------------------------------------------------------------
// Bad input

#[test]
fn too_few_points() {
    let p = [[0.0; 3], [1.0, 0.0, 0.0]];
    let mut out = vec![[0.0; 3]; 64];
    let mut scratch = vec![[0.0; 3]; 64];
    for scheme in CurveScheme::ALL {
        for (n, closed) in [(0, false), (1, false), (0, true), (1, true), (2, true)] {
            let e =
                curve::subdivide(scheme, &p[..n], closed, 2, &mut out, &mut scratch).unwrap_err();
            assert_eq!(
                e.status,
                Status::TooFewPoints,
                "{scheme:?} n={n} closed={closed}"
            );
        }
        let e = curve::subdivide(scheme, &p[..1], false, 0, &mut out, &mut scratch).unwrap_err();
        assert_eq!(e.status, Status::TooFewPoints);
    }
    for f in [four_point::refine, bspline::refine, circle_blend::refine] {
        assert_eq!(
            f(&p[..1], false, &mut out).unwrap_err().status,
            Status::TooFewPoints
        );
        assert_eq!(
            f(&p, true, &mut out).unwrap_err().status,
            Status::TooFewPoints
        );
    }
}

#[test]
fn non_finite_input_names_the_point() {
    let mut rng = Rng(11);
    let p = space_curve(&mut rng, 7, true);
    let mut out = vec![[0.0; 3]; 1024];
    let mut scratch = vec![[0.0; 3]; 1024];
    for scheme in CurveScheme::ALL {
        for (i, bad) in [(3, f64::NAN), (0, f64::INFINITY), (6, f64::NEG_INFINITY)] {
            for closed in [true, false] {
                let mut q = p.clone();
                q[i][i % 3] = bad;
                for levels in [0, 1, 3] {
                    let e = curve::subdivide(scheme, &q, closed, levels, &mut out, &mut scratch)
                        .unwrap_err();
                    assert_eq!(e.status, Status::NonFiniteInput, "{scheme:?}");
                    assert_eq!(e.element, i as u32);
                }
            }
        }
    }
}

#[test]
fn overflow_in_a_level_is_a_numerical_failure() {
    let big = f64::MAX * 0.75;
    let p = [
        [0.0; 3],
        [big, 0.0, 0.0],
        [big, big, 0.0],
        [0.0, big, 0.0],
        [-big, 0.0, 0.0],
    ];
    for scheme in [CurveScheme::FourPoint, CurveScheme::BSpline] {
        let e = run(scheme, &p, true, 1).unwrap_err();
        assert!(
            matches!(e.status, Status::NumericalFailure),
            "{scheme:?}: {e:?}"
        );
    }
    // Every scheme: never a non-finite output reported as success.
    for scheme in CurveScheme::ALL {
        if let Ok(out) = run(scheme, &p, true, 2) {
            assert!(
                out.iter().all(|q| q.iter().all(|x| x.is_finite())),
                "{scheme:?}"
            );
        }
    }
}

#[test]
fn buffer_too_small_for_every_short_size() {
    let mut rng = Rng(12);
    let p = space_curve(&mut rng, 5, true);
    for scheme in CurveScheme::ALL {
        for closed in [true, false] {
            for levels in 0..=3u32 {
                let m = curve::refined_size(5, closed, levels).unwrap();
                let s = curve::scratch_size(scheme, 5, closed, levels).unwrap();
                let mut scratch = vec![[0.0; 3]; s];
                for short in 0..m {
                    let mut out = vec![[0.0; 3]; short];
                    let e = curve::subdivide(scheme, &p, closed, levels, &mut out, &mut scratch)
                        .unwrap_err();
                    assert_eq!(e.status, Status::BufferTooSmall);
                    assert_eq!(e.needed, m);
                }
                let mut out = vec![[0.0; 3]; m];
                for short in 0..s {
                    let mut scratch = vec![[0.0; 3]; short];
                    let e = curve::subdivide(scheme, &p, closed, levels, &mut out, &mut scratch)
                        .unwrap_err();
                    assert_eq!(e.status, Status::BufferTooSmall);
                    assert_eq!(e.needed, s);
                }
                assert_eq!(
                    curve::subdivide(scheme, &p, closed, levels, &mut out, &mut scratch).unwrap(),
                    m
                );
            }
        }
    }
    // One-level functions.
    type One = fn(&[Point], bool, &mut [Point]) -> nlsubdiv::Result<usize>;
    let ones: [One; 5] = [
        four_point::refine,
        bspline::refine,
        mobius::refine_interpolating,
        mobius::refine_approximating,
        circle_blend::refine,
    ];
    for f in ones {
        for closed in [true, false] {
            let m = curve::refined_size(5, closed, 1).unwrap();
            for short in 0..m {
                let mut out = vec![[0.0; 3]; short];
                let e = f(&p, closed, &mut out).unwrap_err();
                assert_eq!((e.status, e.needed), (Status::BufferTooSmall, m));
            }
        }
    }
    let mut small = [[0.0; 3]; 4];
    let e = differential::differential_polygon(&p, true, &mut small).unwrap_err();
    assert_eq!((e.status, e.needed), (Status::BufferTooSmall, 5));
}

#[test]
fn size_overflow_is_reported_before_buffers() {
    let p = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let mut out = [[0.0; 3]; 4];
    let mut scratch = [[0.0; 3]; 4];
    for scheme in CurveScheme::ALL {
        let e = curve::subdivide(scheme, &p, true, 64, &mut out, &mut scratch).unwrap_err();
        assert_eq!(e.status, Status::SizeOverflow);
    }
}

#[test]
fn differential_reconstruction_does_not_drift() {
    // 500 points 100 units from the origin, 8 levels (128 000 points): the compensated
    // sums keep Eq. (A.1) at the rounding level of the coordinates, wrap-around included.
    let n = 500;
    let p: Vec<Point> = (0..n)
        .map(|i| {
            let t = i as f64 / n as f64 * 2.0 * std::f64::consts::PI;
            [
                100.0 + t.sin() + 2.0 * (2.0 * t).sin(),
                t.cos() - 2.0 * (2.0 * t).cos(),
                -(3.0 * t).sin(),
            ]
        })
        .collect();
    let k = 8;
    let mut worst: f64 = 0.0;
    for closed in [true, false] {
        let v = run(CurveScheme::DifferentialFourPoint, &p, closed, k).unwrap();
        let dk = run(CurveScheme::FourPoint, &delta0(&p, closed), closed, k).unwrap();
        let m = v.len();
        let c = -2.0 * 0.25f64.powi(k as i32);
        let range: Vec<usize> = if closed {
            (0..m).collect()
        } else {
            (1..m - 1).collect()
        };
        for i in range {
            let (a, b) = (v[(i + m - 1) % m], v[(i + 1) % m]);
            let second = add(sub(a, v[i]), sub(b, v[i]));
            worst = worst.max(dist(second, scale(dk[i], c)) / 100.0);
        }
    }
    println!("Eq. (A.1) residual, 128k points at distance 100: {worst:.2e}");
    assert!(worst < 1e-15, "{worst:e}");
}

/// Solves the square system `a x = b` by Gaussian elimination with partial pivoting.
fn dense_solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for col in 0..n {
        let piv = (col..n)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .unwrap();
        a.swap(col, piv);
        b.swap(col, piv);
        let pivot_row = a[col].clone();
        for row in col + 1..n {
            let f = a[row][col] / pivot_row[col];
            for (x, y) in a[row].iter_mut().zip(&pivot_row).skip(col) {
                *x -= f * y;
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = vec![0.0; n];
    for row in (0..n).rev() {
        let s: f64 = (row + 1..n).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - s) / a[row][row];
    }
    x
}

#[test]
fn differential_reconstruction_matches_a_direct_least_squares_solve() {
    // Seed 001 §3.5 step 4: the least-squares solution of [4ᵏ L; anchor rows] V = [Δᵏ; anchors]
    // by the normal equations (AᵀA) V = Aᵀb, dense. Closed: every Laplacian row and v_0 = P_0;
    // open (our boundary condition): the interior rows and v_0 = P_0, v_{m−1} = P_{n−1}.
    let mut rng = Rng(0x501);
    for (scheme, base) in [
        (CurveScheme::DifferentialFourPoint, CurveScheme::FourPoint),
        (CurveScheme::DifferentialBSpline, CurveScheme::BSpline),
    ] {
        for closed in [true, false] {
            let n = 6;
            let k = 2;
            let p = space_curve(&mut rng, n, closed);
            let v = run(scheme, &p, closed, k).unwrap();
            let dk = run(base, &delta0(&p, closed), closed, k).unwrap();
            let m = v.len();
            let w = 4f64.powi(k as i32);
            let mut rows: Vec<(Vec<f64>, Point)> = Vec::new();
            for i in 0..m {
                if !closed && (i == 0 || i == m - 1) {
                    continue;
                }
                let mut r = vec![0.0; m];
                r[i] += w;
                r[(i + m - 1) % m] -= 0.5 * w;
                r[(i + 1) % m] -= 0.5 * w;
                rows.push((r, dk[i]));
            }
            let mut anchor = vec![0.0; m];
            anchor[0] = 1.0;
            rows.push((anchor, p[0]));
            if !closed {
                let mut anchor = vec![0.0; m];
                anchor[m - 1] = 1.0;
                rows.push((anchor, p[n - 1]));
            }
            let ata: Vec<Vec<f64>> = (0..m)
                .map(|i| {
                    (0..m)
                        .map(|j| rows.iter().map(|(r, _)| r[i] * r[j]).sum())
                        .collect()
                })
                .collect();
            let s = diameter(&p);
            for c in 0..3 {
                let atb: Vec<f64> = (0..m)
                    .map(|i| rows.iter().map(|(r, b)| r[i] * b[c]).sum())
                    .collect();
                let x = dense_solve(ata.clone(), atb);
                for i in 0..m {
                    assert!(
                        (x[i] - v[i][c]).abs() < 1e-10 * s,
                        "{scheme:?} closed={closed} i={i}: {} vs {}",
                        x[i],
                        v[i][c]
                    );
                }
            }
        }
    }
}

#[test]
fn circle_preserving_schemes_keep_lines() {
    // A line is the circle through collinear points (reliability catalogue #17): unevenly
    // spaced collinear points stay on their line, in order, with no division by ~0.
    let mut rng = Rng(0x11AE);
    for scheme in CurveScheme::ALL
        .into_iter()
        .filter(|s| s.is_circle_preserving())
    {
        let a = rng.point(3.0);
        let dir = rng.unit_vector();
        let mut t = 0.0;
        let p: Vec<Point> = (0..8)
            .map(|_| {
                t += rng.range(0.2, 2.0);
                add(a, scale(dir, t))
            })
            .collect();
        let out = run(scheme, &p, false, 4).unwrap();
        let mut last = f64::NEG_INFINITY;
        for q in &out {
            let d = sub(*q, a);
            let along = dot(d, dir);
            let off = norm(sub(d, scale(dir, along)));
            assert!(off < 1e-13 * (1.0 + t), "{scheme:?}: {off:e}");
            assert!(along > last, "{scheme:?}: order");
            last = along;
        }
    }
}
