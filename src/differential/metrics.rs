//! Surface-quality measures of seed 001 §4.3.
//!
//! * [`thin_plate_energy`]: the normalised thin-plate energy `E = ∫(κ₁² + κ₂²) / ∫ 1`, with
//!   the principal curvatures taken from the edge-based curvature tensor of Cohen-Steiner and
//!   Morvan (2003; the paper cites "the curvature tensor proposed in \[39\]"): at vertex `v`,
//!   `T_v = (1/A_v) Σ_{e ∋ v} β(e) (|e|/2) ê êᵀ`, `β(e)` the signed dihedral angle (positive
//!   on convex edges, 0 on boundary edges), `A_v` a third of the area of the incident
//!   triangles. Projected on the tangent plane (angle-weighted normal), the squared
//!   Frobenius norm of `T_v` is `κ₁² + κ₂²` (the tensor's principal directions are swapped,
//!   its eigenvalues are the principal curvatures). `E = Σ_v A_v ‖T_v‖² / Σ_v A_v`. On a
//!   sphere of radius `R` it tends to `2/R²` (tested).
//! * [`level_distance`]: the largest displacement of the vertices two consecutive levels
//!   share (old vertices keep their indices) — a proxy for the Hausdorff distance `h_i` of
//!   §3.3, not the Hausdorff distance itself.

use super::dirmag::normalized;
use crate::error::{Error, Result, Status};
use crate::mesh::{get, Topology, NONE};
use crate::point::{add, cross, div, dot, norm_unscaled, sub, Point};

/// Signed dihedral angle of the edge of half-edge `h` (0 on the boundary).
fn dihedral(topo: &Topology<'_, '_>, h: u32) -> Result<f64> {
    let t = topo.twin(h)?;
    if t == NONE {
        return Ok(0.0);
    }
    let a = topo.position(topo.origin(h)?)?;
    let b = topo.position(topo.dest(h)?)?;
    let c = topo.position(topo.dest(topo.next(h)?)?)?;
    let d = topo.position(topo.dest(topo.next(t)?)?)?;
    let n1 = cross(sub(b, a), sub(c, a));
    let n2 = cross(sub(a, b), sub(d, b));
    let (Some(u1), Some(u2)) = (normalized(n1), normalized(n2)) else {
        return Ok(0.0);
    };
    let ang = libm::atan2(norm_unscaled(cross(u1, u2)), dot(u1, u2));
    Ok(if dot(u1, sub(d, a)) > 0.0 { -ang } else { ang })
}

/// Per vertex `(κ₁² + κ₂², H = (κ₁ + κ₂)/2, A_v)` into `out` (module docs); isolated
/// vertices get zeros.
pub fn vertex_curvatures(topo: &Topology<'_, '_>, out: &mut [[f64; 3]]) -> Result<()> {
    let n = topo.num_vertices();
    let out = out.get_mut(..n).ok_or(Error::too_small(n))?;
    for (v, o) in out.iter_mut().enumerate() {
        let v = v as u32;
        *o = [0.0; 3];
        if topo.is_isolated(v)? {
            continue;
        }
        let (t, area, nsum) = star_tensor(topo, v)?;
        let Some(nrm) = normalized(nsum) else {
            continue;
        };
        if area <= 0.0 {
            continue;
        }
        let pt = tangent_part(&t, nrm)?;
        let mut f2 = 0.0;
        let mut tr = 0.0;
        for (i, row) in pt.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                f2 += x * x;
                if i == j {
                    tr += x;
                }
            }
        }
        let inv = 1.0 / area;
        *o = [f2 * inv * inv, 0.5 * tr * inv, area];
    }
    Ok(())
}

/// A 3×3 matrix, row-major.
type Matrix = [[f64; 3]; 3];

/// The star sums of vertex `v`: the unnormalised tensor `Σ_{e ∋ v} β(e) (|e|/2) ê êᵀ`, the area
/// `A_v` (a third of the incident triangles' area), and the sum of the incident faces' area
/// vectors (the angle-unweighted normal direction).
fn star_tensor(topo: &Topology<'_, '_>, v: u32) -> Result<(Matrix, f64, Point)> {
    let pv = topo.position(v)?;
    let mut t = [[0.0f64; 3]; 3];
    let mut area = 0.0;
    let mut nsum = [0.0; 3];
    for s in topo.star(v) {
        let q = topo.position(s.neighbour)?;
        let e = sub(q, pv);
        let len = norm_unscaled(e);
        if len > 0.0 {
            let h = if s.half_edge != NONE {
                s.half_edge
            } else {
                topo.edge_half_edge(s.edge)?
            };
            let beta = dihedral(topo, h)?;
            let u = div(e, len);
            let w = beta * 0.5 * len;
            for (i, row) in t.iter_mut().enumerate() {
                for (j, x) in row.iter_mut().enumerate() {
                    *x += w * get(&u, i)? * get(&u, j)?;
                }
            }
        }
        if s.face != NONE {
            let vs = topo.face_vertices(s.face)?;
            let p0 = topo.position(get(vs, 0)?)?;
            let c = cross(
                sub(topo.position(get(vs, 1)?)?, p0),
                sub(topo.position(get(vs, 2)?)?, p0),
            );
            area += norm_unscaled(c) / 6.0;
            nsum = add(nsum, c);
        }
    }
    Ok((t, area, nsum))
}

/// `P T P` with `P = I − n nᵀ`: the part of `t` in the tangent plane of the unit normal `n`.
fn tangent_part(t: &Matrix, n: Point) -> Result<Matrix> {
    let mut p = [[0.0f64; 3]; 3];
    for (i, row) in p.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = f64::from(u8::from(i == j)) - get(&n, i)? * get(&n, j)?;
        }
    }
    Ok(mat_mul(&mat_mul(&p, t), &p))
}

/// The matrix product `a b`, each entry summed over `k` in order.
fn mat_mul(a: &Matrix, b: &Matrix) -> Matrix {
    let mut c = [[0.0f64; 3]; 3];
    for (i, row) in c.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            let mut s = 0.0;
            for (k, aik) in a.get(i).into_iter().flatten().enumerate() {
                let bkj = b.get(k).and_then(|r| r.get(j)).copied().unwrap_or(0.0);
                s += aik * bkj;
            }
            *x = s;
        }
    }
    c
}

/// The normalised thin-plate energy of `topo` (module docs); `scratch` holds one entry per
/// vertex.
///
/// # Errors
/// [`Status::BufferTooSmall`]; [`Status::DegenerateGeometry`] when the total area is zero;
/// [`Status::NumericalFailure`].
pub fn thin_plate_energy(topo: &Topology<'_, '_>, scratch: &mut [[f64; 3]]) -> Result<f64> {
    vertex_curvatures(topo, scratch)?;
    let (mut e, mut a) = (0.0, 0.0);
    for c in scratch.iter().take(topo.num_vertices()) {
        e += c[0] * c[2];
        a += c[2];
    }
    if a <= 0.0 {
        return Err(Error::new(Status::DegenerateGeometry));
    }
    let r = e / a;
    if r.is_finite() {
        Ok(r)
    } else {
        Err(Error::new(Status::NumericalFailure))
    }
}

/// `max_{v < coarse.len()} |fine[v] − coarse[v]|` (module docs).
///
/// # Errors
/// [`Status::InvalidArgument`] when `fine` is shorter than `coarse`.
pub fn level_distance(coarse: &[Point], fine: &[Point]) -> Result<f64> {
    if fine.len() < coarse.len() {
        return Err(Error::new(Status::InvalidArgument));
    }
    let mut m = 0.0f64;
    for (a, b) in coarse.iter().zip(fine) {
        m = m.max(norm_unscaled(sub(*a, *b)));
    }
    Ok(m)
}
