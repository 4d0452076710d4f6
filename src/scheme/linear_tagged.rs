//! Loop and Catmull–Clark with sharp-feature tags: the position rules of [`super::linear`]
//! combined with the crease rules of [`crate::stencil::crease`] (OpenSubdiv's). Untagged
//! meshes never come here, so their bits and speed are those of [`super::linear`].
//!
//! Face points are unchanged. An edge point is the smooth rule, the midpoint (crease), or
//! their blend by the edge's sharpness when it turns smooth in this step. A vertex point is
//! the rule of its parent sharpness values (smooth or dart: the smooth rule; crease: the
//! cubic B-spline `3/4 v + 1/8 (q_a + q_b)` along its two sharp edges; corner: `v`), blended
//! with the rule of its child values by the fractional weight when the two differ.
//! Boundary edges are infinitely sharp, so an untagged boundary keeps today's rules and a
//! tagged edge meeting the boundary makes a corner there.

use super::interpolating_tagged;
use super::tags::Sharpness;
use super::Scheme;
use crate::error::{Error, Result, Status};
use crate::mesh::gather::{apex, face_sum};
use crate::mesh::{get, internal, set, Topology, NONE};
use crate::point::{add, lin2, midpoint, Point};
use crate::stencil::crease::{self, VertexRule};
use crate::stencil::{catmull_clark, centroid_of_sum, crease_vertex, loop_scheme};
use crate::MAX_VALENCE;
use arrayvec::ArrayVec;

/// Writes the positions of one tagged step of `scheme` (Loop, Catmull–Clark; the
/// interpolating schemes in [`interpolating_tagged`]) on `topo`
/// into `pos`, with the sharpness values `sharp` of this level.
pub(crate) fn positions(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    sharp: &Sharpness<'_>,
    pos: &mut [Point],
) -> Result<()> {
    let nv = topo.num_vertices();
    let ne = topo.num_edges();
    // The arms of the schemes this build contains (`super::built`; the plan refuses the
    // others first): an arm left out has a constant `false` guard, removed by the optimiser.
    match scheme {
        Scheme::CatmullClark if cfg!(feature = "catmull-clark") => {
            // The centroid (`catmull_clark::face_point`), summed as the face is walked.
            for f in 0..topo.num_faces() as u32 {
                let (n, sum) = face_sum(topo, f)?;
                set(pos, nv + ne + f as usize, centroid_of_sum(sum, n)?)?;
            }
        }
        Scheme::Loop if cfg!(feature = "loop") => {}
        Scheme::ModifiedButterfly if cfg!(feature = "butterfly") => {
            return interpolating_tagged::butterfly_positions(topo, sharp, pos)
        }
        Scheme::Kobbelt if cfg!(feature = "kobbelt") => {
            return interpolating_tagged::kobbelt_positions(topo, sharp, pos)
        }
        _ if scheme.takes_tags() => return Err(super::built::not_built()),
        _ => return Err(Error::new(Status::TagsNotSupported)),
    }
    for e in 0..ne as u32 {
        let p = edge_point(scheme, topo, sharp, e, pos)?;
        set(pos, nv + e as usize, p)?;
    }
    let mut parent = ArrayVec::new();
    let mut child = ArrayVec::new();
    for v in 0..nv as u32 {
        let p = vertex_point(scheme, topo, sharp, v, pos, &mut parent, &mut child)?;
        set(pos, v as usize, p)?;
    }
    Ok(())
}

/// The smooth edge rule of `scheme` for interior edge `e` (half-edge `h`, twin `t`); the
/// Catmull–Clark face points are read back from `pos`.
fn smooth_edge(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    h: u32,
    t: u32,
    pos: &[Point],
) -> Result<Point> {
    let a = topo.position(topo.origin(h)?)?;
    let b = topo.position(topo.dest(h)?)?;
    if scheme == Scheme::Loop {
        let c = topo.position(apex(topo, h)?)?;
        let d = topo.position(apex(topo, t)?)?;
        return Ok(loop_scheme::edge_interior(a, b, c, d));
    }
    let base = topo.num_vertices() + topo.num_edges();
    let f0 = get(pos, base + topo.face(h)? as usize)?;
    let f1 = get(pos, base + topo.face(t)? as usize)?;
    Ok(catmull_clark::edge_interior(a, b, f0, f1))
}

/// The value of the child of edge `e` at its end `v` (Chaikin needs the other edges at `v`).
fn child_at(topo: &Topology<'_, '_>, sharp: &Sharpness<'_>, v: u32, e: u32) -> Result<f32> {
    let mut parent = ArrayVec::new();
    let mut child = ArrayVec::new();
    sharp.around(topo, v, &mut parent, &mut child)?;
    let i = topo.star(v).position(|s| s.edge == e).ok_or(internal())?;
    get(&child, i)
}

/// The weight of the crease rule in the edge point of edge `e` (ends `i0`, `i1`):
/// [`crease::edge_weight`] of its value and its two children's.
pub(super) fn edge_crease_weight(
    topo: &Topology<'_, '_>,
    sharp: &Sharpness<'_>,
    e: u32,
    i0: u32,
    i1: u32,
) -> Result<f64> {
    let s = sharp.edge(topo, e)?;
    let ends = match sharp.method {
        _ if !crease::is_sharp(s) => [0.0; 2],
        crease::CreaseMethod::Uniform => [crease::decrement(s); 2],
        crease::CreaseMethod::Chaikin => {
            [child_at(topo, sharp, i0, e)?, child_at(topo, sharp, i1, e)?]
        }
    };
    Ok(crease::edge_weight(s, ends))
}

fn edge_point(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    sharp: &Sharpness<'_>,
    e: u32,
    pos: &[Point],
) -> Result<Point> {
    let h = topo.edge_half_edge(e)?;
    let (i0, i1) = (topo.origin(h)?, topo.dest(h)?);
    let mid = midpoint(topo.position(i0)?, topo.position(i1)?);
    let t = topo.twin(h)?;
    if t == NONE {
        return Ok(mid);
    }
    let w = edge_crease_weight(topo, sharp, e, i0, i1)?;
    if w == 1.0 {
        return Ok(mid);
    }
    let smooth = smooth_edge(scheme, topo, h, t, pos)?;
    Ok(crease::blend(w, mid, smooth))
}

/// The point of vertex `v` under `rule`, with `edges` the values that decide which two
/// edges a crease follows.
fn rule_point(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    v: u32,
    rule: VertexRule,
    edges: &[f32],
    pos: &[Point],
) -> Result<Point> {
    let p = topo.position(v)?;
    match rule {
        VertexRule::Corner => Ok(p),
        VertexRule::Crease => {
            let mut q = topo
                .star(v)
                .zip(edges)
                .filter(|(_, &s)| crease::is_sharp(s))
                .map(|(s, _)| s.neighbour);
            let (a, b) = (q.next().ok_or(internal())?, q.next().ok_or(internal())?);
            Ok(crease_vertex(p, topo.position(a)?, topo.position(b)?))
        }
        VertexRule::Smooth | VertexRule::Dart => smooth_vertex(scheme, topo, v, pos),
    }
}

/// The smooth rule at an interior vertex (a boundary vertex is never smooth: its boundary
/// edges are sharp). The ring and the face points are summed as the star is walked, in the
/// rules' order (no arrays).
fn smooth_vertex(scheme: Scheme, topo: &Topology<'_, '_>, v: u32, pos: &[Point]) -> Result<Point> {
    let p = topo.position(v)?;
    let mut n = 0;
    let mut ring = [0.0; 3];
    let mut faces = [0.0; 3];
    let base = topo.num_vertices() + topo.num_edges();
    for s in topo.star(v) {
        if s.face == NONE {
            return Err(internal());
        }
        ring = add(ring, topo.position(s.neighbour)?);
        if scheme == Scheme::CatmullClark {
            faces = add(faces, get(pos, base + s.face as usize)?);
        }
        n += 1;
    }
    match scheme {
        Scheme::Loop => loop_scheme::vertex_interior_sum(p, n, ring),
        _ => catmull_clark::vertex_interior_sums(p, n, ring, faces),
    }
}

fn vertex_point(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    sharp: &Sharpness<'_>,
    v: u32,
    pos: &[Point],
    parent: &mut ArrayVec<f32, MAX_VALENCE>,
    child: &mut ArrayVec<f32, MAX_VALENCE>,
) -> Result<Point> {
    let p = topo.position(v)?;
    if topo.is_isolated(v)? {
        return Ok(p);
    }
    sharp.around(topo, v, parent, child)?;
    let pv = sharp.vertex(v)?;
    let p_rule = crease::vertex_rule(pv, parent);
    if matches!(p_rule, VertexRule::Smooth | VertexRule::Dart) {
        return smooth_vertex(scheme, topo, v, pos);
    }
    let sharp_point = rule_point(scheme, topo, v, p_rule, parent, pos)?;
    let cv = crease::decrement(pv);
    let c_rule = crease::vertex_rule(cv, child);
    if c_rule == p_rule {
        return Ok(sharp_point);
    }
    let smooth_point = rule_point(scheme, topo, v, c_rule, child, pos)?;
    let w = f64::from(crease::fractional_weight(
        sharp.method,
        pv,
        cv,
        parent,
        child,
    ));
    // OpenSubdiv combines the masks as `(1 − w) C + w P`.
    Ok(lin2(1.0 - w, smooth_point, w, sharp_point))
}
