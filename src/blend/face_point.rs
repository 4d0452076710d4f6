//! Face points from candidates: the F4/F6 chain of seed 000 §4.4.3 ("Blending face points").
//!
//! Each corner of a face proposes a face point computed in the canonical form of its own star
//! (a *candidate*). The chain blends them Möbius-invariantly in four named steps:
//!
//! 1. [`Face::new`]: validate the face and index its quadruplets
//!    `(v_i, v_{f,i}, v_{f,i+h}, v_{i+h})`, `h = ⌊d/2⌋`;
//! 2. [`blend_quadruplets`]: `p_l = F4(quadruplet l)` and its noncircularity key;
//! 3. [`sort_by_key`]: a stable sort by ascending key, ties broken by vertex id;
//! 4. [`chain`]: `v_f = p_1`, then `v_f := F6(a_{l−1}, v_f, d_{l−1}, a_l, p_l, d_l)`.
//!
//! The paper leaves the order of ties open, and the F6 chain is not commutative; the rules
//! here make the result independent of where the face's corner list starts and, for generic
//! faces, of the vertex numbering (docs/DECISIONS.md, "Möbius mesh schemes").

use arrayvec::ArrayVec;

use super::f4::{f4_impl, noncircularity};
use super::f6::f6;
use crate::error::{Error, Result, Status};
use crate::point::{self, Point};
use crate::MAX_FACE_SIZE;

/// The face point of a `d`-gon from its vertices `v_i` and the candidates `v_{f,i}` computed
/// in the canonical forms of the vertices' stars (seed 000 §4.4.3, "Blending face points"):
///
/// 1. quadruplets `(v_i, v_{f,i}, v_{f,i+h}, v_{i+h})`, `h = ⌊d/2⌋`, in face order;
/// 2. a stable sort by ascending noncircularity `1 − |Re ρ|/|ρ|` (the `ρ` that F4 uses on the
///    quadruplet; keys rounded to 12 decimals so that rounding noise cannot reorder ties);
/// 3. `p_l = F4(a_l, b_l, c_l, d_l)`;
/// 4. `v_f = p_1`, then `v_f := F6(a_{l−1}, v_f, d_{l−1}, a_l, p_l, d_l)` for `l = 2 … d`.
///
/// Step 4 chains the *opposite vertices* `a`, `d` of the quadruplets. The paper prints
/// `c_{l−1}, c_l` there, which are candidates: with them F6 is singular exactly in the
/// Möbius-regular case (all candidates equal), so we read it as a typo. When all candidates
/// agree (a Möbius-regular neighbourhood) every F4 and F6 returns that point, so `v_f` equals
/// it. In an even face, where quadruplets `i` and `i + h` are the same points reversed, each
/// chain `(a_l, d_l)` is oriented by the face: its start follows the previous chain's start in
/// face order, less than half a turn on (F6 is unchanged when both chains reverse, so this
/// relative orientation is all that enters; docs/DECISIONS.md).
///
/// Evaluation (docs/RESULTS.md, "Möbius arithmetic"): steps 2 and 3 share their cross-ratio
/// (the key is the noncircularity of the `ρ` F4 computes); for an even face quadruplet `i + h`
/// is quadruplet `i` reversed: the one of the pair whose `v_i` has the smaller id (then the
/// earlier in face order) is evaluated and its partner takes its F4 point and key (Lemma 4.1;
/// both are evaluated where F4 is not symmetric); a step onto the reversed partner of the
/// previous quadruplet is F6 with `Y = 1`, `Z = X⁻¹`, evaluated as the F4 it equals.
///
/// Ties of the sort (equal rounded keys) keep face order, as the paper's stable sort does. The
/// F6 chain depends on the order of different quadruplets, which tie in symmetric faces, so
/// the result can depend on which corner the face lists first — by up to 4 % of the face on a
/// regular tetrahedron. Drivers use [`face_point_with_ids`], whose ties go by vertex id and so
/// do not depend on the start.
///
/// # Errors
/// [`Status::InvalidArgument`] when the slices differ in length; [`Status::TooFewPoints`] for
/// fewer than 3 corners; [`Status::ValenceTooHigh`] above [`crate::MAX_FACE_SIZE`];
/// [`Status::NonFiniteInput`] for a non-finite corner or candidate; the errors of
/// [`super::f4()`] and [`super::f6()`] (the caller's degenerate-neighbourhood policy decides
/// what to do). When several quadruplets' F4s fail, the one reported is `NumericalFailure` before
/// `DegenerateGeometry`, so it does not depend on where the face starts.
pub fn face_point(vertices: &[Point], candidates: &[Point]) -> Result<Point> {
    if candidates.len() != vertices.len() {
        return Err(Error::new(Status::InvalidArgument));
    }
    face_point_on_stack(Face::new(&Slices(vertices, candidates), None)?)
}

/// [`face_point`] with ties of the noncircularity sort broken by the vertex ids `ids[i]` of the
/// quadruplets' first corners `v_i` (then by face order, for repeated ids). The quadruplets of
/// a face and their ids are the same whichever corner the face starts at, so the face point
/// is too, bit for bit; ids are untouched by Möbius maps, so Möbius equivariance is kept (a
/// tie-break by coordinates would lose it). This is the rule every Möbius driver uses, with
/// the mesh's vertex indices (docs/DECISIONS.md).
///
/// # Errors
/// Those of [`face_point`]; [`Status::InvalidArgument`] when `ids` differs in length.
pub fn face_point_with_ids(vertices: &[Point], candidates: &[Point], ids: &[u32]) -> Result<Point> {
    if ids.len() != vertices.len() || candidates.len() != vertices.len() {
        return Err(Error::new(Status::InvalidArgument));
    }
    face_point_on_stack(Face::new(&Slices(vertices, candidates), Some(ids))?)
}

/// [`face_point_with_ids`] of a face whose corners and candidates are read in place
/// ([`FaceCorners`]), with the chain's working arrays in `work`: the Möbius drivers read a
/// mesh face's positions and its corners' candidates where they are and lend a part of their
/// star workspace, so nothing sized by the face-size cap is on the stack (`docs/firmware.md`,
/// "Stack"). The same bits as the slice form of the same points. `ids` has
/// [`FaceCorners::len`] entries; `work` at least [`work_points`] of it.
///
/// # Errors
/// Those of [`face_point_with_ids`]; [`Status::BufferTooSmall`] for a short `work`.
pub(crate) fn face_point_in_place<C: FaceCorners + ?Sized>(
    corners: &C,
    ids: &[u32],
    work: &mut [Point],
) -> Result<Point> {
    if ids.len() != corners.len() {
        return Err(Error::new(Status::InvalidArgument));
    }
    let face = Face::new(corners, Some(ids))?;
    let d = face.d;
    let need = work_points(d);
    let (pts, rest) = work.split_at_mut_checked(d).ok_or(Error::too_small(need))?;
    let keys = rest
        .as_flattened_mut()
        .get_mut(..d)
        .ok_or(Error::too_small(need))?;
    face_point_ordered(face, pts, keys)
}

/// The points of the working arrays of a `d`-gon's chain ([`face_point_in_place`]): its
/// F4 points and their sort keys (`f64`, three to a point).
pub(crate) const fn work_points(d: usize) -> usize {
    d + d.div_ceil(3)
}

/// A face's corners `v_i` and the candidates `v_{f,i}` of their stars, read by index
/// `i < len()` (`None` for an index the face does not have, or a value that cannot be read).
pub(crate) trait FaceCorners {
    /// The number of corners `d`.
    fn len(&self) -> usize;
    /// Corner `v_i`.
    fn vertex(&self, i: usize) -> Option<Point>;
    /// Candidate `v_{f,i}`.
    fn candidate(&self, i: usize) -> Option<Point>;
}

/// A face given as two slices of equal length: its corners and their candidates.
struct Slices<'a>(&'a [Point], &'a [Point]);

impl FaceCorners for Slices<'_> {
    fn len(&self) -> usize {
        self.0.len()
    }
    fn vertex(&self, i: usize) -> Option<Point> {
        self.0.get(i).copied()
    }
    fn candidate(&self, i: usize) -> Option<Point> {
        self.1.get(i).copied()
    }
}

/// Quadruplet indices in chain order (`u8`: a face has at most [`MAX_FACE_SIZE`] corners).
type Order = ArrayVec<u8, MAX_FACE_SIZE>;
const _: () = assert!(MAX_FACE_SIZE <= 256);

/// [`face_point_ordered`] with the F4 points and keys in this frame (the public, slice
/// forms: `MAX_FACE_SIZE` of each).
fn face_point_on_stack<C: FaceCorners + ?Sized>(face: Face<'_, C>) -> Result<Point> {
    let mut pts = [[0.0; 3]; MAX_FACE_SIZE];
    let mut keys = [0.0; MAX_FACE_SIZE];
    let d = face.d;
    let pts = pts.get_mut(..d).ok_or(Error::new(Status::ValenceTooHigh))?;
    let keys = keys
        .get_mut(..d)
        .ok_or(Error::new(Status::ValenceTooHigh))?;
    face_point_ordered(face, pts, keys)
}

/// The four steps of the chain (module docs), with the F4 points `pts` and the sort keys
/// `keys` of the face's quadruplets (`d` of each) filled in place; each step is out of line,
/// so the frames of F4 (step 2) and of F6 (step 4) are never on the stack together
/// (`docs/firmware.md`, "Stack").
fn face_point_ordered<C: FaceCorners + ?Sized>(
    face: Face<'_, C>,
    pts: &mut [Point],
    keys: &mut [f64],
) -> Result<Point> {
    blend_quadruplets(&face, pts, keys)?;
    let mut order = Order::new();
    sort_by_key(&face, keys, &mut order)?;
    chain(&face, pts, &order)
}

/// A face's corners, their candidates and (optionally) vertex ids, indexed cyclically.
struct Face<'a, C: FaceCorners + ?Sized> {
    corners: &'a C,
    ids: Option<&'a [u32]>,
    /// The number of corners `d`.
    d: usize,
    /// `h = ⌊d/2⌋`: quadruplet `i` joins corner `i` to corner `i + h`.
    h: usize,
}

impl<'a, C: FaceCorners + ?Sized> Face<'a, C> {
    /// Step 1: the face, validated (`ids`, when given, has the length of the face).
    fn new(corners: &'a C, ids: Option<&'a [u32]>) -> Result<Face<'a, C>> {
        let d = corners.len();
        if d < 3 {
            return Err(Error::new(Status::TooFewPoints));
        }
        if d > MAX_FACE_SIZE {
            return Err(Error::new(Status::ValenceTooHigh));
        }
        // A shortcut: a non-finite corner or candidate is `NonFiniteInput` (the ranking of
        // `blend_quadruplets` would report it too, after evaluating every quadruplet).
        let finite = |p: Option<Point>| p.is_some_and(|p| point::is_finite(&p));
        if !(0..d).all(|i| finite(corners.vertex(i)))
            || !(0..d).all(|i| finite(corners.candidate(i)))
        {
            return Err(Error::new(Status::NonFiniteInput));
        }
        Ok(Face {
            corners,
            ids,
            d,
            h: d / 2,
        })
    }

    /// Whether the face has an even number of corners: its quadruplets then come in reversed
    /// pairs `i`, `i + h`.
    fn is_even(&self) -> bool {
        self.d % 2 == 0
    }

    /// Corner `v_{i mod d}`.
    fn vertex(&self, i: usize) -> Result<Point> {
        i.checked_rem(self.d)
            .and_then(|k| self.corners.vertex(k))
            .ok_or(Error::new(Status::InvalidArgument))
    }

    /// Candidate `v_{f, i mod d}`.
    fn candidate(&self, i: usize) -> Result<Point> {
        i.checked_rem(self.d)
            .and_then(|k| self.corners.candidate(k))
            .ok_or(Error::new(Status::InvalidArgument))
    }

    /// Quadruplet `i`: `(v_i, v_{f,i}, v_{f,i+h}, v_{i+h})`.
    fn quad(&self, i: usize) -> Result<[Point; 4]> {
        Ok([
            self.vertex(i)?,
            self.candidate(i)?,
            self.candidate(i + self.h)?,
            self.vertex(i + self.h)?,
        ])
    }

    /// The tie-break of quadruplet `i`: the id of `v_i`, or 0 (face order) without ids.
    fn id(&self, i: usize) -> Result<u32> {
        match self.ids {
            Some(ids) => ids
                .get(i)
                .copied()
                .ok_or(Error::new(Status::InvalidArgument)),
            None => Ok(0),
        }
    }
}

/// `F4(a, b, c, d)` with its §4.4.3 sort key and [`super::f4::F4Eval::reversible`]: the
/// noncircularity of the cross-ratio F4 uses, rounded to 12 decimals (so that rounding noise
/// cannot reorder ties); when a coincidence rule answered (F4 computed no ρ), that of the input
/// points. A quadruplet whose cross-ratio is undefined (coincident candidates) is as circular
/// as it gets (key 0).
fn f4_keyed(a: Point, b: Point, c: Point, d: Point) -> Result<(Point, i64, bool)> {
    let r = f4_impl(a, b, c, d, None)?;
    let key = match r.noncircularity {
        Some(k) => k,
        None => noncircularity(a, b, c, d).unwrap_or(0.0),
    };
    Ok((r.point, libm::round(key * 1e12) as i64, r.reversible))
}

/// The order in which [`blend_quadruplets`] reports the failures of its quadruplets' F4s
/// (lowest first): a fixed order of statuses, so the report does not depend on evaluation order.
fn failure_rank(status: Status) -> u8 {
    match status {
        Status::NonFiniteInput => 0,
        Status::NumericalFailure => 1,
        Status::DegenerateGeometry => 2,
        // F4 returns none of the other statuses today; they would tie here.
        _ => 3,
    }
}

/// Step 2: `p_l = F4(quadruplet l)` and its rounded sort key ([`f4_keyed`]), per quadruplet in
/// face order.
///
/// The quadruplets are evaluated in face order, so the first failing one depends on where the
/// face starts: every one is evaluated and the failure reported is the one of
/// [`failure_rank`] (then the first), the same for every start.
#[inline(never)]
fn blend_quadruplets<C: FaceCorners + ?Sized>(
    face: &Face<'_, C>,
    pts: &mut [Point],
    keys: &mut [f64],
) -> Result<()> {
    let (d, h) = (face.d, face.h);
    // A key is an integer of at most 10¹² in magnitude (a noncircularity in [0, 1] times
    // 10¹², rounded), exact as an `f64`: the sort compares the same values.
    let mut put = |i: usize, (pt, key): (Point, i64)| -> Result<()> {
        *pts.get_mut(i).ok_or(Error::new(Status::InvalidArgument))? = pt;
        *keys.get_mut(i).ok_or(Error::new(Status::InvalidArgument))? = key as f64;
        Ok(())
    };
    let mut failure: Option<Error> = None;
    let mut eval = |i: usize| -> (Point, i64, bool) {
        match face.quad(i).and_then(|[a, b, c, e]| f4_keyed(a, b, c, e)) {
            Ok(r) => r,
            Err(e) => {
                if failure.is_none_or(|f| failure_rank(e.status) < failure_rank(f.status)) {
                    failure = Some(e);
                }
                ([0.0; 3], 0, false)
            }
        }
    };
    if face.is_even() {
        // Quadruplet i + h is quadruplet i reversed, and F4(a, b, c, d) = F4(d, c, b, a)
        // (Lemma 4.1), noncircularity included: one evaluation serves both. It is the one
        // whose v_i has the smaller id (then the first in face order), so the face point
        // stays independent of the face start bit for bit. Where F4 is not symmetric (a
        // coincidence rule or a negative-real ρ) both are evaluated.
        for i in 0..h {
            let (first, second) = if face.id(i + h)? < face.id(i)? {
                (i + h, i)
            } else {
                (i, i + h)
            };
            let (pt, key, reversible) = eval(first);
            put(first, (pt, key))?;
            if reversible {
                put(second, (pt, key))?;
            } else {
                let (pt2, key2, _) = eval(second);
                put(second, (pt2, key2))?;
            }
        }
    } else {
        for i in 0..d {
            let (pt, key, _) = eval(i);
            put(i, (pt, key))?;
        }
    }
    if let Some(e) = failure {
        return Err(e);
    }
    Ok(())
}

/// Step 3: the quadruplet starts `i` in chain order, sorted stably by `(rounded key,
/// tie-break)` with an insertion sort (`d` is small, and the sort must be stable and
/// panic-free). The tie-break is the id of `v_i` when given, else 0 (face order).
#[inline(never)]
fn sort_by_key<C: FaceCorners + ?Sized>(
    face: &Face<'_, C>,
    keys: &[f64],
    order: &mut Order,
) -> Result<()> {
    // The sort key of quadruplet `i`: (rounded key, tie-break), compared lexicographically.
    let key = |i: u8| -> Result<(f64, u32)> {
        let k = *keys
            .get(usize::from(i))
            .ok_or(Error::new(Status::InvalidArgument))?;
        Ok((k, face.id(usize::from(i))?))
    };
    order.clear();
    for i in 0..keys.len() {
        let i = u8::try_from(i).map_err(|_| Error::new(Status::ValenceTooHigh))?;
        order
            .try_push(i)
            .map_err(|_| Error::new(Status::ValenceTooHigh))?;
        let mut j = order.len() - 1;
        while j > 0 {
            // Swap through `get_mut` on the pair: `slice::swap` keeps a bounds-check panic.
            match order.get_mut(j - 1..=j) {
                Some([prev, cur]) if key(*prev)? > key(*cur)? => {
                    core::mem::swap(prev, cur);
                    j -= 1;
                }
                _ => break,
            }
        }
    }
    Ok(())
}

/// Step 4: `v_f = p_1`, then `v_f := F6(a_{l−1}, v_f, d_{l−1}, a_l, p_l, d_l)` along `order`,
/// each chain `(a_l, d_l)` of an even face oriented by [`oriented_start`].
#[inline(never)]
fn chain<C: FaceCorners + ?Sized>(face: &Face<'_, C>, p: &[Point], order: &[u8]) -> Result<Point> {
    let h = face.h;
    let point = |i: usize| p.get(i).copied().ok_or(Error::new(Status::InvalidArgument));
    let mut it = order.iter().map(|&i| usize::from(i));
    let first = it.next().ok_or(Error::new(Status::TooFewPoints))?;
    let mut vf = point(first)?;
    let mut prev = first;
    let (mut a_prev, mut d_prev) = (face.vertex(first)?, face.vertex(first + h)?);
    for i in it {
        let p = point(i)?;
        if face.is_even() && h > 0 && i % h == prev % h {
            // The reversed partner of the previous chain: F6(a, b, c, c, e, a), which is
            // F6(a, b, c, a, e, c) too (both are F4(a, b, e, c)), so the step does not depend
            // on how the chain is oriented, and the chain (with `prev`, its start) stays.
            vf = f6_of_reversed_chain(a_prev, vf, d_prev, p)?;
            continue;
        }
        let j = oriented_start(face, i, prev);
        let (a, e) = (face.vertex(j)?, face.vertex(j + h)?);
        vf = f6(a_prev, vf, d_prev, a, p, e)?;
        (a_prev, d_prev, prev) = (a, e, j);
    }
    Ok(vf)
}

/// The start of the chain of quadruplet `i` after a chain that started at `prev`.
///
/// An even face's chain is oriented relative to the previous one by the face alone: of
/// quadruplets `i` and `i + h` (the same F4 point), the one whose start follows the previous
/// start in face order, less than half a turn on. F6 is unchanged when both of its chains are
/// reversed (`F6(a, b, c, d, e, f) = F6(c, b, a, f, e, d)`, to rounding), so only this relative
/// orientation enters, and which member of a reversed pair the sort put first — by vertex id,
/// as they always tie — does not matter: the result does not depend on vertex numbering
/// there. (The other relative orientation is worse conditioned: sphere reproduction on
/// sphere_uv_mixed_pole16 4.3e-10 against < 1e-12; docs/DECISIONS.md.) F6 reads only the
/// chain's ends and the point, so the rule holds where F4 is not symmetric too (a coincidence
/// rule, a negative-real ρ). The identities hold off the negative reals (principal roots:
/// `√(q⁻¹) = (√q)⁻¹` fails there), so on exactly cocircular data the numbering can still
/// enter. An odd face has no reversed pairs: `i` itself.
fn oriented_start<C: FaceCorners + ?Sized>(face: &Face<'_, C>, i: usize, prev: usize) -> usize {
    let (d, h) = (face.d, face.h);
    if face.is_even() && (i + d - prev) % d > h {
        (i + h) % d
    } else {
        i
    }
}

/// `F6(a, b, c, c, e, a)`: F6 whose second chain joins the ends of the first in reverse, as
/// the chain of an even face meets when quadruplet `i` or `i + h` follows the chain of its
/// pair (either orientation: `F6(a, b, c, a, e, c)` is `F4(a, b, e, c)` too, off the negative
/// reals).
///
/// There `X = cr[e, a, b, c]`, `Y = cr[e, a, b, a] = q_ea q_ab⁻¹ (−q_ab)(−q_ea)⁻¹ = 1` and
/// `Z = cr[e, c, b, a] = X⁻¹` (the four factors of `X⁻¹` are those of `Z`, each negated), so
/// `r = (√X)⁻¹ (√(X⁻¹))⁻¹ = 1` for the principal root (`√(X⁻¹) = (√X)⁻¹` off the negative
/// reals) and `χ = −√X`: the point with `cr[e, a, b, p] = −√cr[e, a, b, c]`, which is
/// `F4(a, b, e, c)` — one cross-ratio instead of three, and no rounding of `Y` away from 1.
/// Where F4 does not run its formula (a coincidence rule) or `X` is a negative real (where
/// F6 takes `√r = n`, not 1) this is F6 itself.
fn f6_of_reversed_chain(a: Point, b: Point, c: Point, e: Point) -> Result<Point> {
    if b == e {
        // A reused F4 (the step onto the partner of the previous quadruplet): F6's `b = e`
        // rule, before F4's coincidence rule would decline.
        return f6(a, b, c, c, e, a);
    }
    match f4_impl(a, b, e, c, None) {
        Ok(r) if r.reversible => Ok(r.point),
        _ => f6(a, b, c, c, e, a),
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::lcg_points;
    use super::*;
    use crate::point::{distance, norm};

    #[test]
    fn face_point_of_equal_candidates_is_that_candidate() {
        let square = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let c = [0.5, 0.5, 0.0];
        assert_eq!(face_point(&square, &[c; 4]).unwrap(), c);
        let tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let g = [1.0 / 3.0, 1.0 / 3.0, 0.0];
        assert_eq!(face_point(&tri, &[g; 3]).unwrap(), g);
        assert_eq!(
            face_point(&tri, &[g; 2]).unwrap_err().status,
            Status::InvalidArgument
        );
        assert_eq!(
            face_point(&tri[..2], &[g; 2]).unwrap_err().status,
            Status::TooFewPoints
        );
    }

    #[test]
    fn face_point_with_ids_does_not_depend_on_the_face_start() {
        // A regular-looking quad and hexagon with distinct candidates: every rotation of the
        // corner list (ids rotated with it) gives the same bits.
        let quad = [
            [1.02, 0.03, 0.01],
            [-0.04, 0.97, -0.02],
            [-1.01, 0.05, 0.03],
            [0.02, -0.99, -0.01],
        ];
        let qc = [
            [0.01, -0.02, 0.31],
            [-0.015, 0.02, 0.29],
            [0.02, 0.01, 0.305],
            [-0.01, -0.02, 0.295],
        ];
        let hex: [Point; 6] = core::array::from_fn(|i| {
            let t = i as f64 * core::f64::consts::PI / 3.0;
            [libm::cos(t), libm::sin(t), 0.0]
        });
        let hc: [Point; 6] = core::array::from_fn(|i| [0.01 * i as f64, 0.0, 0.5]);
        let ids = [9u32, 4, 7, 1, 30, 2];
        for (v, c) in [(&quad[..], &qc[..]), (&hex[..], &hc[..])] {
            let n = v.len();
            let reference = face_point_with_ids(v, c, &ids[..n]).unwrap();
            for s in 1..n {
                let rot = |a: &[Point]| -> [Point; 6] {
                    core::array::from_fn(|i| if i < n { a[(i + s) % n] } else { [0.0; 3] })
                };
                let (rv, rc) = (rot(v), rot(c));
                let rid: [u32; 6] = core::array::from_fn(|i| ids[(i + s) % n]);
                let p = face_point_with_ids(&rv[..n], &rc[..n], &rid[..n]).unwrap();
                assert_eq!(p, reference, "n = {n}, start {s}");
            }
        }
        assert_eq!(
            face_point_with_ids(&quad, &qc, &ids[..3])
                .unwrap_err()
                .status,
            Status::InvalidArgument
        );
    }

    #[test]
    fn face_point_with_ids_does_not_depend_on_the_numbering_of_generic_faces() {
        // Different quadruplets of a generic face never tie, and the reversed pairs of an
        // even face are oriented by the face, so permuting the ids changes nothing but the
        // rounding of which pair member is evaluated.
        let mut state = 11;
        let mut worst: f64 = 0.0;
        for n in [4usize, 5, 6, 8] {
            for _ in 0..300 {
                let base: [Point; 8] = lcg_points(&mut state);
                let jitter: [Point; 8] = lcg_points(&mut state);
                let v: ArrayVec<Point, 8> = (0..n)
                    .map(|i| {
                        let t = 2.0 * core::f64::consts::PI * i as f64 / n as f64;
                        let j = base.get(i).copied().unwrap_or([0.0; 3]);
                        [
                            libm::cos(t) + 0.2 * j[0],
                            libm::sin(t) + 0.2 * j[1],
                            0.2 * j[2],
                        ]
                    })
                    .collect();
                let c: ArrayVec<Point, 8> = (0..n)
                    .map(|i| {
                        let j = jitter.get(i).copied().unwrap_or([0.0; 3]);
                        [0.1 * j[0], 0.1 * j[1], 0.1 * j[2]]
                    })
                    .collect();
                let ids: ArrayVec<u32, 8> = (0..n as u32).collect();
                let perm: ArrayVec<u32, 8> =
                    (0..n as u32).map(|i| (i * 5 + 3) % n as u32).collect();
                let rev: ArrayVec<u32, 8> = (0..n as u32).rev().collect();
                let (Ok(p), Ok(q), Ok(r)) = (
                    face_point_with_ids(&v, &c, &ids),
                    face_point_with_ids(&v, &c, &perm),
                    face_point_with_ids(&v, &c, &rev),
                ) else {
                    continue;
                };
                worst = worst.max(distance(p, q)).max(distance(p, r));
            }
        }
        // Orienting the chains by ids instead of by the face moves these face points by
        // 1.6e-7.
        assert!(
            worst < 1e-13,
            "renumbering moves a generic face point by {worst:e}"
        );
    }

    #[test]
    fn face_point_failure_does_not_depend_on_the_face_start() {
        // One candidate is NaN and another quadruplet overflows (points f64::MAX apart): the
        // status must be the same from every start (also pinned by
        // fuzz/regressions/primitives/face-point-status-start). Then two finite failures:
        // an overflowing quadruplet and well-behaved ones.
        let m = f64::MAX;
        let verts = [
            [0.9 * m, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-0.9 * m, 0.0, 0.0],
            [0.0, -1.0, 0.0],
        ];
        let mut cands = [
            [0.1, 0.0, 0.0],
            [0.0, 0.1, 0.0],
            [-0.1, 0.0, 0.0],
            [0.0, -0.1, 0.0],
        ];
        let ids = [3u32, 1, 2, 0];
        for (nan, want) in [
            (true, Status::NonFiniteInput),
            (false, Status::NumericalFailure),
        ] {
            if nan {
                cands[1] = [f64::NAN, 0.0, 0.0];
            } else {
                cands[1] = [0.0, 0.1, 0.0];
            }
            for s in 0..4 {
                let rot = |a: &[Point]| -> [Point; 4] { core::array::from_fn(|i| a[(i + s) % 4]) };
                let rid: [u32; 4] = core::array::from_fn(|i| ids[(i + s) % 4]);
                let got = face_point_with_ids(&rot(&verts), &rot(&cands), &rid)
                    .unwrap_err()
                    .status;
                assert_eq!(got, want, "start {s}, NaN candidate: {nan}");
            }
        }
    }

    #[test]
    fn face_point_of_a_spherical_face_is_on_the_sphere() {
        // A pentagon on the unit sphere with distinct candidates on the sphere.
        let s = |th: f64, ph: f64| {
            [
                libm::sin(th) * libm::cos(ph),
                libm::sin(th) * libm::sin(ph),
                libm::cos(th),
            ]
        };
        let verts = [
            s(0.5, 0.0),
            s(0.55, 1.3),
            s(0.45, 2.5),
            s(0.6, 3.8),
            s(0.5, 5.0),
        ];
        let cands = [
            s(0.1, 0.2),
            s(0.12, 1.1),
            s(0.09, 2.0),
            s(0.11, 3.0),
            s(0.1, 4.4),
        ];
        let p = face_point(&verts, &cands).unwrap();
        assert!((norm(p) - 1.0).abs() < 1e-12, "{}", norm(p));
    }
}
