//! DirMag subdivision (seed 001 §3.4, "Direction–magnitude subdivision") and the editing of
//! §4.4, which both work on the separated form `δ_i = H_i n_i`.
//!
//! Separation (§3.4, Case 1): `|H_i| = ‖δ_i‖`; the sign of `H_i` is that of `n̄_i · δ_i`,
//! `n̄_i` the angle-weighted vertex normal (Thürmer–Wüthrich, the paper's \[34\]); then
//! `n_i = δ_i / H_i`. When `H_i = 0` the paper sets `n_i = n̄_i`.
//!
//! Subdivision: normals are points of S² and are "subdivided using weighted sums in S²" by the
//! method of subdivision shading (Alexa & Boubekeur 2008, the paper's \[6\]): the linear stencil
//! applied to the normals, then each result normalised. The magnitudes `H` are subdivided
//! linearly with the same stencil. The refined differential coordinate is `H · n`.
//! Decision: a refined normal shorter than [`MIN_NORMAL`] (opposite normals cancelling) is
//! kept unnormalised, so the refined δ shrinks there instead of jumping; such vertices are
//! counted in [`super::DifferentialReport::dirmag_degenerate`].

use crate::error::Result;
use crate::mesh::{set, Topology};
use crate::point::{add, cross, div, dot, norm_unscaled, sub, Point};

/// Below this length a subdivided normal is not normalised (see the module docs).
pub const MIN_NORMAL: f64 = 1e-12;

/// `a / ‖a‖`, or `None` below [`MIN_NORMAL`].
#[inline]
pub(crate) fn normalized(a: Point) -> Option<Point> {
    let l = norm_unscaled(a);
    if l < MIN_NORMAL || !l.is_finite() {
        None
    } else {
        Some(div(a, l))
    }
}

/// The angle between `a` and `b` (robust `atan2` form).
#[inline]
fn angle(a: Point, b: Point) -> f64 {
    libm::atan2(norm_unscaled(cross(a, b)), dot(a, b))
}

/// Angle-weighted vertex normals of `topo` (Σ over the incident faces of the corner angle
/// times the unit face normal, normalised; zero for isolated vertices and where the sum
/// vanishes). Faces are fan-triangulated from their first corner for the face normal.
pub fn angle_weighted_normals(topo: &Topology<'_, '_>, out: &mut [Point]) -> Result<()> {
    let n = topo.num_vertices();
    for i in 0..n {
        set(out, i, [0.0; 3])?;
    }
    for f in 0..topo.num_faces() as u32 {
        let vs = topo.face_vertices(f)?;
        let m = vs.len();
        let mut fnrm = [0.0; 3];
        let p0 = topo.position(*vs.first().ok_or(crate::mesh::internal())?)?;
        for k in 1..m.saturating_sub(1) {
            let a = topo.position(crate::mesh::get(vs, k)?)?;
            let b = topo.position(crate::mesh::get(vs, k + 1)?)?;
            let c = cross(sub(a, p0), sub(b, p0));
            fnrm = add(fnrm, c);
        }
        let Some(fu) = normalized(fnrm) else { continue };
        for k in 0..m {
            let v = crate::mesh::get(vs, k)?;
            let prev = crate::mesh::get(vs, (k + m - 1) % m)?;
            let next = crate::mesh::get(vs, (k + 1) % m)?;
            let pv = topo.position(v)?;
            let w = angle(sub(topo.position(next)?, pv), sub(topo.position(prev)?, pv));
            let o = out.get_mut(v as usize).ok_or(crate::mesh::internal())?;
            *o = [o[0] + w * fu[0], o[1] + w * fu[1], o[2] + w * fu[2]];
        }
    }
    for o in out.iter_mut().take(n) {
        *o = normalized(*o).unwrap_or([0.0; 3]);
    }
    Ok(())
}

/// Separates `δ` into the signed magnitude `H` and the unit direction `n` (module docs), with
/// `nbar` the angle-weighted normal.
pub fn separate(delta: Point, nbar: Point) -> (f64, Point) {
    let m = norm_unscaled(delta);
    if m == 0.0 || !m.is_finite() {
        return (0.0, nbar);
    }
    let h = if dot(nbar, delta) > 0.0 { m } else { -m };
    (h, div(delta, h))
}
