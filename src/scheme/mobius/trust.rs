//! The fold guard's criterion: how far the paper's rules can be trusted at one interior
//! vertex star, `τ_v ∈ [0, 1]` (1: the paper's rules; `docs/folds.md` measures why).
//!
//! Seed 000 §7.1 observes that canonical Möbius subdivision can fold non-Delaunay meshes.
//! Traced on real meshes, the folds come from *ill-conditioned canonical forms*: stars with
//! one spoke much shorter or longer than the others, whose canonical ring is far from a
//! circle, so that a stencil lands behind the centre or beyond the neighbour, and the F4
//! blend of two such candidates lands far from both. `τ_v` is the least of three terms, each
//! a ramp from 0 (distrusted) to 1 (trusted):
//!
//! 1. the **radial spread** `σ = max |C_i| / min |C_i|` of the ring's images `C_i` in the
//!    normalised canonical frame (1 for a Möbius-regular star): trust 1 at `σ ≤ 4`, 0 at
//!    `σ ≥ 8`, linear in `ln σ` between; a neighbour sent to infinity gives 0;
//! 2. the **candidate position** `t = ⟨E_j, C_j⟩ / |C_j|²` of each of the star's edge
//!    candidates along its spoke, in the same frame (1/4 to 5/8 on regular stars): trust 1
//!    in `[0.15, 0.85]`, 0 at `t ≤ 0` or `t ≥ 1`;
//! 3. the **F4 angle** `arg ρ ∈ [0°, 180°]` of the cross-ratio `ρ = cr[e_k, v_j, e_j, v_k]`
//!    that the edge blend `F4(v_j, e_j, e_k, v_k)` uses (seed 000 §4.4.3; 0° when the two
//!    candidates agree, 180° on F4's cut): trust 1 at or below 120°, 0 at or above 160°,
//!    lowering both end stars of an edge between two interior stars.
//!
//! **Why `τ_v` is Möbius-invariant**: for a Möbius map `M` of the input, the normalised form
//! of the image star differs from the original's by an orthogonal map (the composite of the
//! two forms with `M` fixes ∞, so it is a similarity, and the centre `c` and radius `r`
//! follow it), so every ratio of lengths and every angle read in that frame (`σ`, `t`) is
//! unchanged; `arg ρ` is a function of `Re ρ` and `|Im ρ|`, which are Möbius invariants of
//! the four points (seed 000 §3.2). A flagged star is flagged on every Möbius image of its
//! neighbourhood (up to rounding at the ramps' ends).
//!
//! Boundary stars are always trusted: their form sends a square corner's diagonal neighbour
//! to infinity by construction (the paper's rule drops that candidate exactly), which a
//! Möbius image brings back by rounding, so a boundary criterion would not be invariant.
//!
//! The thresholds come from the level-1 feature study of `docs/folds.md` (spread 99th
//! percentile 5.9 on bunny against ≥ 9.5 for the folding stars; at most 5.2 on the sphere
//! meshes), not from an optimisation.

use crate::point::{add, cross, dot, sub, Point};

/// Spread at or below which a star is trusted (`ln` of it).
const LN_SPREAD_TRUSTED: f64 = 1.386_294_361_119_890_6; // ln 4
/// Spread at or above which a star is distrusted (`ln` of it).
const LN_SPREAD_DISTRUSTED: f64 = 2.079_441_541_679_835_9; // ln 8
/// Margin of the candidate position `t` inside `[0, 1]` below which trust falls.
const T_MARGIN: f64 = 0.15;
/// `T_MARGIN` and `1 − T_MARGIN` moved inward by a relative 1e-12 ([`position_trust`]).
const T_LOW: f64 = T_MARGIN * (1.0 + 1e-12);
const T_HIGH: f64 = (1.0 - T_MARGIN) * (1.0 - 1e-12);
/// F4 angle (radians) at or below which an edge is trusted: 120°.
const RHO_TRUSTED: f64 = 2.094_395_102_393_195_5;
/// F4 angle (radians) at or above which an edge is distrusted: 160°.
const RHO_DISTRUSTED: f64 = 2.792_526_803_190_927;

/// `(x − zero_at) / (one_at − zero_at)` clamped to `[0, 1]`: 0 at `zero_at`, 1 at `one_at`
/// (either order); a NaN `x` gives 0 (distrusted).
pub(super) fn ramp(x: f64, zero_at: f64, one_at: f64) -> f64 {
    let r = (x - zero_at) / (one_at - zero_at);
    if r >= 1.0 {
        1.0
    } else if r > 0.0 {
        r
    } else {
        0.0
    }
}

/// Term 1: the trust of an interior star from the images `ring` of its neighbours in the
/// normalised canonical frame (a non-finite image: a neighbour at infinity, trust 0).
pub(super) fn spread_trust(ring: &[Point]) -> f64 {
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for c in ring {
        let d = dot(*c, *c);
        if !d.is_finite() {
            return 0.0;
        }
        lo = lo.min(d);
        hi = hi.max(d);
    }
    // Squared norms: σ² ≤ 16 is σ ≤ 4, the common case, without a logarithm.
    if hi <= 16.0 * lo {
        return 1.0;
    }
    if lo <= 0.0 {
        return 0.0;
    }
    ramp(
        0.5 * libm::log(hi / lo),
        LN_SPREAD_DISTRUSTED,
        LN_SPREAD_TRUSTED,
    )
}

/// Term 2: the trust of an edge candidate `e` (normalised frame, not mapped back) of the spoke
/// whose neighbour's image is `c`. A candidate or neighbour that is missing gives 1 (no
/// candidate, nothing to distrust; a neighbour at infinity is term 1's).
pub(super) fn position_trust(e: Point, c: Point) -> f64 {
    let cc = dot(c, c);
    let x = dot(e, c);
    // The common case without the division and the ramps: `x` between the margins times
    // `cc`, widened by a relative 1e-12 that covers the rounding of the two products and of
    // `t = x / cc` (each off by at most 2⁻⁵³ relative while `cc` and the products are
    // normal), puts `t` inside `[T_MARGIN, 1 − T_MARGIN]`, where both ramps are exactly 1.
    let (lo, hi) = (T_LOW * cc, T_HIGH * cc);
    if lo >= f64::MIN_POSITIVE && hi.is_finite() && x >= lo && x <= hi {
        return 1.0;
    }
    let t = x / cc;
    // `cc = 0` makes `t` non-finite.
    if !t.is_finite() || !cc.is_finite() {
        return 1.0;
    }
    ramp(t, 0.0, T_MARGIN).min(ramp(t, 1.0, 1.0 - T_MARGIN))
}

/// Term 3: the trust of the edge `(a, b)` from the cross-ratio `ρ = cr[e_b, a, e_a, b]` of its
/// blend `F4(a, e_a, e_b, b)` (seed 000 §4.4.3), without forming `ρ`: with the differences
/// `A = a − e_b`, `B = e_a − a`, `C = b − e_a`, `D = e_b − b` (imaginary quaternions),
/// `ρ = A B⁻¹ C D⁻¹ = A B C D / (|B|² |D|²)`, and for imaginary quaternions
/// `Re(A B C D) = (A·B)(C·D) − (A·C)(B·D) + (A·D)(B·C)` (Binet–Cauchy), `|A B C D| =
/// |A||B||C||D|`: so `cos arg ρ` takes six dot products and no division, and the common case
/// (`arg ρ ≤ 120°`) no square root either. A degenerate blend (a zero difference) gives 1:
/// the blend's own fallback handles it.
pub(super) fn f4_trust(a: Point, ea: Point, eb: Point, b: Point) -> f64 {
    let (qa, qb, qc, qd) = (sub(a, eb), sub(ea, a), sub(b, ea), sub(eb, b));
    let re = dot(qa, qb) * dot(qc, qd) - dot(qa, qc) * dot(qb, qd) + dot(qa, qd) * dot(qb, qc);
    let p2 = dot(qa, qa) * dot(qb, qb) * dot(qc, qc) * dot(qd, qd);
    // arg ρ ≤ 120° iff cos ≥ −½.
    if re >= 0.0 || 4.0 * re * re <= p2 || !(p2 > 0.0 && p2.is_finite()) {
        return 1.0;
    }
    let cos = re / crate::sqrt::sqrt(p2);
    ramp(libm::acos(cos.max(-1.0)), RHO_DISTRUSTED, RHO_TRUSTED)
}

/// `Re √ρ` of a curve segment at or above which its turn term trusts it
/// ([`curve_turn_trust`]): a single turn of up to 144° between equal segments (an angle of
/// 36° between them), every turn up to 126° of a circle's equally spaced points.
const TURN_TRUSTED: f64 = 0.9;
/// The same value at or below which it distrusts it: a single turn of 162° (an angle of
/// 18° between the segments).
const TURN_DISTRUSTED: f64 = 0.6;

/// The turn term of a crease or boundary curve segment `(p0, p1, p2, p3)` whose edge point
/// is the blend `F4(p0, p1, p2, p3)` (seed 000 §4.4.1, Eq. (3); the Möbius curve rules of
/// §4.3), from `Re √ρ`, `ρ = cr[p2, p0, p1, p3]`: F4 puts its point where the cross-ratio is
/// `−√ρ`, and `√ρ` reads how the four points sit.
///
/// In order on a line `ρ > 1` is real, so `Re √ρ > 1` (2 equally spaced); on a staircase
/// (turns of ±90°, steps `t` times the treads) `√ρ = 1 + i t`; equally spaced on a circle,
/// turning `θ` at each point, `√ρ = 2 cos(θ/2)`; a single turn `φ` between equal segments
/// gives `√ρ = 2 √cos(φ/2) e^{iφ/4}`. Where the curve turns back on itself (a hairpin at
/// `p1` or `p2`: turns of 150° and more, as the crease curves of a scanned mesh tagged at
/// 30° make), `Re √ρ` falls toward 0 and the circle through the points is small: F4 and
/// the curve's vertex rule put their points on it, off the polyline by most of an edge
/// length (docs/creases.md, "Folds next to corners"), while `arg ρ` (the F4-angle term,
/// [`f4_trust`]) can stay near 50°. A function of `ρ`, so Möbius-invariant: trust 1 at or
/// above [`TURN_TRUSTED`], 0 at or below [`TURN_DISTRUSTED`]. With the differences of
/// [`f4_trust`] (`A = p0 − p2`, `B = p1 − p0`, `C = p3 − p1`, `D = p2 − p3`),
/// `ρ = A B C D / (|B|² |D|²)`, and `Re √ρ = √((|ρ| + Re ρ) / 2)`. A degenerate segment
/// (a zero difference) gives 1: the blend's own fallback handles it.
pub(super) fn curve_turn_trust(p0: Point, p1: Point, p2: Point, p3: Point) -> f64 {
    let (qa, qb, qc, qd) = (sub(p0, p2), sub(p1, p0), sub(p3, p1), sub(p2, p3));
    let re = dot(qa, qb) * dot(qc, qd) - dot(qa, qc) * dot(qb, qd) + dot(qa, qd) * dot(qb, qc);
    let bd = dot(qb, qb) * dot(qd, qd);
    let p2 = dot(qa, qa) * dot(qb, qb) * dot(qc, qc) * dot(qd, qd);
    if !(p2 > 0.0 && p2.is_finite() && bd > 0.0) {
        return 1.0;
    }
    let x = (crate::sqrt::sqrt(p2) + re) / (2.0 * bd);
    if !x.is_finite() {
        return 1.0;
    }
    ramp(crate::sqrt::sqrt(x.max(0.0)), TURN_DISTRUSTED, TURN_TRUSTED)
}

/// Out-of-plane spread of the tangent polygon, over its in-plane spread, at or below which a
/// star counts as spherical, and at or above which it does not; linear between.
const PLANAR: f64 = 1e-6;
const NOT_PLANAR: f64 = 1e-4;

/// The Newell normal (area vector) `Σ T_i × T_{i+1}` of a closed polygon.
pub(super) fn newell(polygon: &[Point]) -> Point {
    let mut n = [0.0; 3];
    for (i, t) in polygon.iter().enumerate() {
        // The next corner, cyclically (no `%`: a division the compiler cannot prove nonzero
        // would link a panic path).
        let u = polygon
            .get(i + 1)
            .or(polygon.first())
            .copied()
            .unwrap_or(*t);
        n = add(n, cross(*t, u));
    }
    n
}

/// How spherical a star is, in `[0, 1]`, from its tangent polygon `T_i` (centre `c`): 1 when
/// the `T_i` lie in one plane, which is exactly when the vertex and its neighbours lie on one
/// sphere or plane (`x ↦ (x − v)⁻¹` sends that sphere to a plane); 0 from an out-of-plane
/// spread of 1e-4 of the in-plane one. The planarity is a ratio of lengths of `T`, which a
/// Möbius map of the input changes by a similarity only (seed 000 Lemma 3.2), so it is
/// Möbius-invariant like the trust. The guard uses it twice (`guard.rs`, `spectrum.rs`):
///
/// * the trust of a spherical star of valence 4 or more is raised to 1: the paper's rules
///   keep its points on its sphere (seed 000 Lemma A.1) and commute with every Möbius map,
///   which no fallback toward the linear rule can, so meshes on a sphere keep sphere
///   reproduction and Möbius equivariance;
/// * three points always lie in a plane, so a valence-3 star gives no such evidence and
///   stays guarded, but its fallback keeps it on its sphere (`spectrum.rs`).
pub(super) fn sphericity(tangents: &[Point], c: Point) -> f64 {
    sphericity_with(tangents, c, &mut core::iter::empty())
}

/// [`sphericity`] with more evidence: `more` are the images `(x − v)⁻¹` of further points
/// near the star (Kobbelt's diagonals), which must lie in the tangent polygon's plane too,
/// that is on the star's sphere. A star of valence 3 then gives evidence (its three
/// neighbours alone always lie on a sphere with the vertex); a non-finite image is none.
pub(super) fn sphericity_with(
    tangents: &[Point],
    c: Point,
    more: &mut dyn Iterator<Item = Option<Point>>,
) -> f64 {
    let n = newell(tangents);
    let nn = dot(n, n);
    if !(nn.is_finite() && nn > 0.0) {
        return 0.0;
    }
    let (mut off, mut spread) = (0.0f64, 0.0f64);
    for t in tangents {
        let d = sub(*t, c);
        let h = dot(d, n);
        off = off.max(h * h / nn);
        spread = spread.max(dot(d, d));
    }
    for t in more {
        let Some(t) = t else {
            return 0.0;
        };
        let d = sub(t, c);
        let h = dot(d, n);
        off = off.max(h * h / nn);
        spread = spread.max(dot(d, d));
    }
    let planarity = crate::sqrt::sqrt(off / spread);
    if planarity <= PLANAR {
        1.0
    } else if planarity < NOT_PLANAR {
        (NOT_PLANAR - planarity) / (NOT_PLANAR - PLANAR)
    } else {
        // Also a NaN planarity (spread 0).
        0.0
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// A reproducible stream in `[-1, 1)` (the audit's tests use it too).
    pub(in crate::scheme::mobius) fn stream(seed: u64) -> impl FnMut() -> f64 {
        let mut x = seed;
        move || {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        }
    }

    #[test]
    fn constants_are_the_documented_thresholds() {
        assert!((LN_SPREAD_TRUSTED - libm::log(4.0)).abs() < 1e-15);
        assert!((LN_SPREAD_DISTRUSTED - libm::log(8.0)).abs() < 1e-15);
        assert!((RHO_TRUSTED - 120f64.to_radians()).abs() < 1e-15);
        assert!((RHO_DISTRUSTED - 160f64.to_radians()).abs() < 1e-15);
    }

    #[test]
    fn spread_ramp() {
        let at = |r: f64| spread_trust(&[[1.0, 0.0, 0.0], [0.0, r, 0.0], [-1.0, 0.0, 0.0]]);
        assert_eq!(at(1.0), 1.0);
        assert_eq!(at(4.0), 1.0);
        assert_eq!(at(8.0), 0.0);
        assert!((at(crate::sqrt::sqrt(32.0)) - 0.5).abs() < 1e-12);
        assert_eq!(at(f64::INFINITY), 0.0);
        assert_eq!(spread_trust(&[[0.0; 3], [1.0, 0.0, 0.0]]), 0.0);
    }

    #[test]
    fn position_ramp() {
        let c = [2.0, 0.0, 0.0];
        let at = |t: f64| position_trust([2.0 * t, 1.0, 0.0], c);
        assert_eq!(at(0.5), 1.0);
        assert_eq!(at(0.15), 1.0);
        assert_eq!(at(0.0), 0.0);
        assert_eq!(at(-1.0), 0.0);
        assert_eq!(at(1.2), 0.0);
        assert!((at(0.075) - 0.5).abs() < 1e-12);
        assert!((at(0.925) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn the_position_bound_gives_the_exact_trust() {
        // The division and the two ramps, as `position_trust` computes them off its bound.
        let exact = |e: Point, c: Point| {
            let cc = dot(c, c);
            let t = dot(e, c) / cc;
            if !t.is_finite() || !cc.is_finite() {
                return 1.0;
            }
            ramp(t, 0.0, T_MARGIN).min(ramp(t, 1.0, 1.0 - T_MARGIN))
        };
        let mut x: u64 = 5;
        let mut rnd = || {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for i in 0..20_000 {
            // `t` at the margins' ends to within a few ulps, or anywhere, on every scale.
            let base = [0.15, 0.85, 0.5, 0.0][i % 4];
            let t = base * (1.0 + 1e-15 * rnd() * (1 << (i % 12)) as f64) + 0.001 * rnd();
            let t = if i % 8 < 4 {
                base * (1.0 + 4e-16 * rnd())
            } else {
                t
            };
            let s = [1e-160, 1e-100, 1.0, 1e100, 1e150][i % 5];
            let c = [s, 0.0, 0.0];
            let e = [t * s, s * rnd(), 0.0];
            assert_eq!(
                position_trust(e, c).to_bits(),
                exact(e, c).to_bits(),
                "{e:?} {c:?}"
            );
        }
    }

    #[test]
    fn f4_angle_matches_the_cross_ratio() {
        use crate::quat::cross_ratio;
        let mut rnd = stream(7);
        let mut seen = [false; 3];
        for _ in 0..2000 {
            let p: [Point; 4] = core::array::from_fn(|_| [rnd(), rnd(), rnd()]);
            let [a, ea, eb, b] = p;
            let rho = cross_ratio(eb, a, ea, b).unwrap();
            let angle = libm::atan2(rho.abs_im(), rho.w);
            let want = ramp(angle, RHO_DISTRUSTED, RHO_TRUSTED);
            let got = f4_trust(a, ea, eb, b);
            assert!((got - want).abs() < 1e-9, "{p:?}: {got} {want}");
            seen[if want == 1.0 {
                0
            } else if want == 0.0 {
                2
            } else {
                1
            }] = true;
        }
        assert_eq!(seen, [true; 3], "every part of the ramp exercised");
        // Agreeing candidates: angle 0.
        assert_eq!(
            f4_trust([0.0; 3], [0.5, 0.0, 0.0], [0.5, 0.0, 0.0], [1.0, 0.0, 0.0]),
            1.0
        );
    }
    /// The turn term against `Re √ρ` of the quaternion cross-ratio itself, on random
    /// quadruplets and on the configurations its documentation names.
    #[test]
    fn the_turn_term_reads_the_root_of_the_cross_ratio() {
        use crate::mobius::MobiusMap;
        use crate::quat::cross_ratio;
        let mut rnd = stream(19);
        let direct = |p: [Point; 4]| {
            let root = cross_ratio(p[2], p[0], p[1], p[3]).unwrap().sqrt().unwrap();
            ramp(root.w, TURN_DISTRUSTED, TURN_TRUSTED)
        };
        let mut seen = [false; 3];
        for _ in 0..4000 {
            let p: [Point; 4] = core::array::from_fn(|_| [rnd(), rnd(), rnd()]);
            let (got, want) = (curve_turn_trust(p[0], p[1], p[2], p[3]), direct(p));
            assert!((got - want).abs() < 1e-9, "{p:?}: {got} {want}");
            seen[if want == 1.0 {
                0
            } else if want == 0.0 {
                2
            } else {
                1
            }] = true;
            // Möbius-invariant: the same on the image under an inversion and a rotation.
            let f = MobiusMap::inversion([3.0 * rnd(), 3.0 * rnd(), 3.0], 1.0 + rnd().abs())
                .compose(&MobiusMap::rotation([rnd(), rnd(), 1.0], 3.0 * rnd()));
            let q = p.map(|x| f.apply(x).unwrap());
            let image = curve_turn_trust(q[0], q[1], q[2], q[3]);
            assert!((image - got).abs() < 1e-7, "{p:?}: {image} {got}");
        }
        assert_eq!(seen, [true; 3], "every part of the ramp exercised");
        // A single turn by `phi` (degrees) at p1 between unit segments, in the plane.
        let turn = |phi: f64| {
            let (c, s) = (libm::cos(phi.to_radians()), libm::sin(phi.to_radians()));
            curve_turn_trust(
                [-1.0, 0.0, 0.0],
                [0.0; 3],
                [c, s, 0.0],
                [2.0 * c, 2.0 * s, 0.0],
            )
        };
        assert_eq!(turn(0.0), 1.0);
        assert_eq!(turn(90.0), 1.0);
        assert_eq!(turn(143.0), 1.0);
        assert!(turn(150.0) > 0.0 && turn(150.0) < 1.0);
        assert_eq!(turn(163.0), 0.0);
        assert_eq!(turn(175.0), 0.0);
        // A staircase (Re √ρ = 1) and a short middle segment on a line (Re √ρ = 1.1):
        // trusted.
        let stair = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 0.4, 0.0],
            [2.0, 0.4, 0.0],
        ];
        assert_eq!(
            curve_turn_trust(stair[0], stair[1], stair[2], stair[3]),
            1.0
        );
        // Equally spaced on a circle, `θ` apart: `√ρ = 2 cos(θ/2)`, trusted up to 126°.
        let circle = |theta: f64| {
            let c = [0.0, 1.0, 2.0, 3.0].map(|k: f64| {
                let a = (theta * k).to_radians();
                [libm::cos(a), libm::sin(a), 0.0]
            });
            curve_turn_trust(c[0], c[1], c[2], c[3])
        };
        assert_eq!(circle(100.0), 1.0);
        assert_eq!(circle(125.0), 1.0);
        assert_eq!(circle(150.0), 0.0);
        let line = [[0.0; 3], [1.0, 0.0, 0.0], [1.1, 0.0, 0.0], [2.1, 0.0, 0.0]];
        assert_eq!(curve_turn_trust(line[0], line[1], line[2], line[3]), 1.0);
        // Degenerate segments are left to the blend's own fallback.
        assert_eq!(
            curve_turn_trust([0.0; 3], [0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]),
            1.0
        );
    }
}
