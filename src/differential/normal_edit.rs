//! The normal edit of seed 001 §4.4 ("additional normal … controls", Fig. 11(b)): the caller
//! gives control vertex `i` a direction `u_i`, and the output's surface normal at `i` — the
//! angle-weighted normal of its star, the normal [`dirmag::angle_weighted_normals`] computes —
//! becomes `u_i`.
//!
//! # What §4.4 says and why it is not taken literally (decision)
//!
//! §4.4 reads `δ_i ≈ H_i n_i` and edits "the normal directions of the control mesh": replace
//! `n_i`, so `δ_i ← H_i u_i`. With the combinatorial Laplacian `δ_i = v_i − mean(ring)`, so
//! that edit moves `v_i` off its ring's centroid in the direction `u_i`; the ring itself, and
//! so the plane it spans, stays. The surface normal *at* `v_i` does not turn (its neighbours'
//! do), and where `H_i = 0` (flat regions) the edit is the zero vector and does nothing.
//! Rotating `δ` of the vertex and its ring by the rotation `R_i` that takes the normal to
//! `u_i` does not help either: a field that is `R_i δ` in a patch and `δ` outside is not the
//! Laplacian of any surface, and the least-squares reconstruction spreads the mismatch
//! instead of turning the patch.
//!
//! What is done instead is the rotation of the vertex's neighbourhood *as a surface*, written
//! as a change of the differential coordinates the reconstruction reproduces exactly:
//!
//! 1. the unedited (or curvature-edited) reconstruction `X` is solved first; `m_i` is its
//!    surface normal at `i` and `R_i` the smallest rotation taking `m_i` to `u_i`, as the
//!    rotation vector `ω_i` (axis × angle, [`rotation_vector`]);
//! 2. a rotation field: `ω = ω_i`, centre `c = X_i` on `i` and its 1-ring, `ω = 0` and
//!    `c = X_j` (the vertex's own output position) elsewhere, subdivided to level `k` with
//!    Loop (positive weights, so the field blends smoothly from `ω_i` to 0 over the next
//!    rings). Loop's value at an old vertex and on its star at every later level depends
//!    only on that vertex's 1-ring, so on the star of `i` at level `k`, `ω = ω_i` and
//!    `c = X_i` exactly — provided no other edited vertex shares the 1-ring. The field is
//!    seeded on the control mesh's 1-ring when the nearest other edited vertex is at least
//!    three edges away; otherwise on the 1-ring of level 1 (two edges away) or level 2
//!    (adjacent), where the distance between old vertices has doubled or quadrupled and the
//!    rings are apart ([`seed_level`]); a later seed overwrites what coarser ones left;
//! 3. the displacement `D(x) = R(ω(x)) (x − c(x)) − (x − c(x))` rotates each point about its
//!    centre by its own angle (Rodrigues, [`rotation_displacement`]): on the star of `i` it
//!    is the rigid rotation `R_i` about `X_i`, so the star — and every rotation-equivariant
//!    normal of it — turns by exactly `R_i`, and `m_i` becomes `u_i`;
//! 4. the differential coordinates are edited by `δ ← δ + L_k D` (on the star of `i`:
//!    `L_k (R_i X) = R_i δ`, the differential coordinates rotated with the surface, so the
//!    edited `δ_i` points along `u_i` as §4.4 asks) and the system is solved again, from
//!    `X + D`. `X + D` satisfies the edited normal equations to the accuracy of `X` (the
//!    anchors keep their warm-start values), so this solve only confirms it.
//!
//! Consequences: the edit needs no curvature, so it works on flat regions, and its size is
//! the vertex's own neighbourhood (the control 1-ring, blending out over the next two rings)
//! — the scale of the neighbours; next to another edited vertex, the half or quarter of it
//! that is free. Every edited vertex is met exactly when `k` is at least its seed level (1
//! for edited vertices two edges apart, 2 for adjacent ones); below that a later seed
//! overwrites the shared ring and the normals are a compromise. A large turn can fold the
//! surface; `folds.rs` reports it.

use super::dirmag;
use crate::error::{Error, Result, Status};
use crate::mesh::{get, set, Topology};
use crate::point::{cross, div, dot, norm_unscaled, scale, sub, Point};

/// `u / |u|` for any finite non-zero `u` (scaled by its largest component first, so tiny and
/// huge vectors are directions too); `None` for the zero vector, which means "no edit".
pub(super) fn unit(u: Point) -> Option<Point> {
    let m = u[0].abs().max(u[1].abs()).max(u[2].abs());
    if m == 0.0 || !m.is_finite() {
        return None;
    }
    let s = div(u, m);
    Some(div(s, norm_unscaled(s)))
}

/// The rotation vector (unit axis times angle) of the smallest rotation taking the unit
/// vector `m` to the unit vector `u`. Opposite vectors turn by π about an axis perpendicular
/// to `m` (cross product with the coordinate axis along which `m` is smallest).
pub(super) fn rotation_vector(m: Point, u: Point) -> Point {
    let c = dot(m, u);
    let axis = cross(m, u);
    let s = norm_unscaled(axis);
    if s > 0.0 {
        return scale(axis, libm::atan2(s, c) / s);
    }
    if c > 0.0 {
        return [0.0; 3];
    }
    let a = [m[0].abs(), m[1].abs(), m[2].abs()];
    let e = if a[0] <= a[1] && a[0] <= a[2] {
        [1.0, 0.0, 0.0]
    } else if a[1] <= a[2] {
        [0.0, 1.0, 0.0]
    } else {
        [0.0, 0.0, 1.0]
    };
    let p = cross(m, e);
    scale(p, core::f64::consts::PI / norm_unscaled(p))
}

/// `R(ω) v − v`: the displacement of `v` rotated about the origin by the rotation vector `ω`
/// (Rodrigues: `R v = v + sin θ (a × v) + (1 − cos θ) (a (a·v) − v)`, `θ = |ω|`, `a = ω/θ`;
/// `1 − cos θ = 2 sin²(θ/2)` keeps small angles accurate).
pub(super) fn rotation_displacement(omega: Point, v: Point) -> Point {
    let t = norm_unscaled(omega);
    if t == 0.0 || !t.is_finite() {
        return [0.0; 3];
    }
    let a = div(omega, t);
    let (s, h) = (libm::sin(t), libm::sin(0.5 * t));
    let one_minus_cos = 2.0 * h * h;
    let axv = cross(a, v);
    let along = sub(scale(a, dot(a, v)), v);
    [
        s * axv[0] + one_minus_cos * along[0],
        s * axv[1] + one_minus_cos * along[1],
        s * axv[2] + one_minus_cos * along[2],
    ]
}

/// Whether control vertex `v` is edited (its requested normal is not the zero vector).
fn is_edited(normals: &[Point], v: u32) -> Result<bool> {
    Ok(unit(get(normals, v as usize)?).is_some())
}

/// The level at which the rotation of edited vertex `v` is seeded (step 2 of the [module
/// docs](self)): 0 when no other edited vertex is within two edges of `v`, 1 when the nearest
/// is two edges away, 2 when one is adjacent, and never above `k`. Distances between old
/// vertices double with every level, so at the seed level the 1-rings of any two edited
/// vertices are disjoint, and each star is met exactly (when `k` allows it).
fn seed_level(topo0: &Topology<'_, '_>, normals: &[Point], v: u32, k: usize) -> Result<usize> {
    let mut level = 0usize;
    for s in topo0.star(v) {
        if is_edited(normals, s.neighbour)? {
            level = 2;
        }
        for t in topo0.star(s.neighbour) {
            if t.neighbour != v && is_edited(normals, t.neighbour)? {
                level = level.max(1);
            }
        }
    }
    Ok(level.min(k))
}

/// Step 1 of the [module docs](self) for every control vertex of `topo0` that `normals` edits:
/// its rotation vector `ω_v` into `omegas[v]` and its seed level ([`seed_level`]) into
/// `levels[v][0]`, from the surface normals `star_normals` of the result (indexed by output
/// vertex; control vertex `v` is output vertex `v`). Returns the number of edited vertices.
///
/// # Errors
/// [`Status::DegenerateGeometry`] naming an edited vertex whose surface normal is zero (an
/// isolated vertex, a degenerate star): there is no normal to turn.
pub(super) fn rotations(
    topo0: &Topology<'_, '_>,
    normals: &[Point],
    star_normals: &[Point],
    k: usize,
    omegas: &mut [Point],
    levels: &mut [Point],
) -> Result<usize> {
    let mut edited = 0;
    for v in 0..topo0.num_vertices() as u32 {
        let Some(u) = unit(get(normals, v as usize)?) else {
            continue;
        };
        let m = get(star_normals, v as usize)?;
        if m == [0.0; 3] {
            return Err(Error::at(Status::DegenerateGeometry, v));
        }
        set(omegas, v as usize, rotation_vector(m, u))?;
        set(
            levels,
            v as usize,
            [seed_level(topo0, normals, v, k)? as f64, 0.0, 0.0],
        )?;
        edited += 1;
    }
    Ok(edited)
}

/// What [`Seeds::seed`] reads: the requested normals, the per-vertex rotation vectors and
/// seed levels of [`rotations`], and the result `x` (the centres).
#[derive(Clone, Copy, Debug)]
pub(super) struct Seeds<'a> {
    /// The requested normals (zero: not edited).
    pub(super) normals: &'a [Point],
    /// `ω_v` per control vertex.
    pub(super) omegas: &'a [Point],
    /// The seed level per control vertex (`[level, 0, 0]`).
    pub(super) levels: &'a [Point],
    /// The solved positions; `x[v]` is the centre of `v`'s rotation.
    pub(super) x: &'a [Point],
}

impl Seeds<'_> {
    /// Seeds, at level `j` (topology `topo`), the rotation field `omega` and its centres
    /// `centre` of every edited vertex whose seed level is `j`: `ω_v` and `x_v` on the vertex
    /// and its 1-ring, overwriting what coarser levels left there.
    pub(super) fn seed(
        &self,
        topo: &Topology<'_, '_>,
        j: usize,
        omega: &mut [Point],
        centre: &mut [Point],
    ) -> Result<()> {
        for v in 0..self.normals.len() as u32 {
            if !is_edited(self.normals, v)? || get(self.levels, v as usize)?[0] != j as f64 {
                continue;
            }
            let (w, c) = (get(self.omegas, v as usize)?, get(self.x, v as usize)?);
            set(omega, v as usize, w)?;
            set(centre, v as usize, c)?;
            for s in topo.star(v) {
                set(omega, s.neighbour as usize, w)?;
                set(centre, s.neighbour as usize, c)?;
            }
        }
        Ok(())
    }
}

/// The surface normals of `topo`'s vertices (the angle-weighted normals of their stars).
pub(super) fn star_normals(topo: &Topology<'_, '_>, out: &mut [Point]) -> Result<()> {
    dirmag::angle_weighted_normals(topo, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Point, b: Point, tol: f64) -> bool {
        let d = sub(a, b);
        norm_unscaled(d) <= tol
    }

    #[test]
    fn unit_accepts_every_finite_non_zero_vector_and_refuses_zero() {
        assert_eq!(unit([0.0, -0.0, 0.0]), None);
        for s in [1e-310, 1e-300, 1.0, 1e300, f64::MAX] {
            let u = unit([0.0, 0.75 * s, s]).unwrap_or([0.0; 3]);
            assert!((norm_unscaled(u) - 1.0).abs() < 1e-15, "{s} {u:?}");
            // (0.75 s is rounded to a subnormal's few digits at s = 1e-310.)
            let tol = if s < 1e-300 { 1e-4 } else { 1e-15 };
            assert!(
                (u[1] - 0.6).abs() < tol && (u[2] - 0.8).abs() < tol,
                "{s} {u:?}"
            );
        }
    }

    #[test]
    fn rotation_vector_turns_m_onto_u() {
        let m = [0.0, 0.0, 1.0];
        let cases = [
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.6, 0.8],
            [0.0, 0.0, -1.0],
            [0.0, 0.6, -0.8],
        ];
        for u in cases {
            let w = rotation_vector(m, u);
            // m + D(m) = R m must be u.
            let turned = crate::point::add(m, rotation_displacement(w, m));
            assert!(close(turned, u, 1e-15), "{u:?}: {turned:?}");
            // The smallest rotation: its angle is the angle between m and u, its axis ⊥ both.
            let t = norm_unscaled(w);
            assert!((t - libm::acos(dot(m, u))).abs() < 1e-15, "{u:?}");
            assert!(dot(w, m).abs() < 1e-15 && dot(w, u).abs() < 1e-15, "{u:?}");
        }
        // Opposite vectors along every axis: a half turn about a perpendicular axis.
        for m in [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]] {
            let u = scale(m, -1.0);
            let w = rotation_vector(m, u);
            assert!((norm_unscaled(w) - core::f64::consts::PI).abs() < 1e-15);
            assert!(close(
                crate::point::add(m, rotation_displacement(w, m)),
                u,
                1e-15
            ));
        }
    }

    #[test]
    fn rotation_displacement_is_a_rotation() {
        // A quarter turn about z takes x to y: D = y − x; points on the axis stay.
        let w = [0.0, 0.0, core::f64::consts::FRAC_PI_2];
        assert!(close(
            rotation_displacement(w, [2.0, 0.0, 0.0]),
            [-2.0, 2.0, 0.0],
            1e-15
        ));
        assert_eq!(rotation_displacement(w, [0.0, 0.0, 5.0]), [0.0; 3]);
        assert_eq!(rotation_displacement([0.0; 3], [1.0, 2.0, 3.0]), [0.0; 3]);
        // Lengths are kept.
        let v = [0.3, -1.2, 2.5];
        let r = crate::point::add(v, rotation_displacement([0.4, 0.1, -0.7], v));
        assert!((norm_unscaled(r) - norm_unscaled(v)).abs() < 1e-15);
    }
}
