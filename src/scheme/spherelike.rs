//! Spherelike interpolating subdivision of polygon meshes (seed 003 §3): the circle-blend
//! curve rule of seed 003 §2 ([`crate::curve::circle_blend`]) applied along the grid lines
//! of the mesh, with Catmull–Clark's connectivity (every n-gon becomes n quads,
//! [`crate::mesh::refine::Pattern::Quads`]).
//!
//! Output order is that of every primal quad scheme: old vertices (kept bit for bit: the
//! scheme is interpolating), then one edge point per edge in edge order, then one face point
//! per face in face order. Evaluation order (fixed, for determinism): old vertices, edge
//! points, face points (face points read the edge points back from the output).
//!
//! # Edge points (seed 003 §3, Figs. 3 and 4)
//!
//! Each edge `V1 V2` is split by the curve rule on `(V0, V1, V2, V3)`
//! ([`circle_blend::blend_point`]). `V0` is the point "beyond" `V1` away from `V2`
//! (`beyond`), `V3` the point beyond `V2` away from `V1`:
//! * valence 4: the straight continuation, the spoke opposite `V1 V2` (Fig. 3a);
//! * even valence `n ≠ 4`: the "most central edge", the spoke `n/2` steps round the star
//!   (Fig. 3b) — at valence 4 this is the same spoke, so one rule serves both;
//! * odd valence: "the vertex which is the furthest away from V1, and belonging to the central
//!   face" (Fig. 3c): the face between spokes `(n−1)/2` and `(n+1)/2` steps round the star
//!   (the face opposite the edge). Ties: see `farthest`.
//!
//! Where the paper is silent (docs/DECISIONS.md, docs/spherelike.md):
//! * **Boundary edges** follow the curve rule along their boundary loop, a closed curve (as
//!   every scheme subdivides its boundary loops, like CGAL's and OpenSubdiv's `EDGE_ONLY`
//!   boundaries): `V0`, `V3` are the other boundary neighbours.
//! * **Open ends**: an interior edge whose endpoint lies on the boundary has no continuation
//!   beyond that endpoint (the star is a half-disk). The grid line ends there, so the edge is
//!   the end segment of an open curve and takes the circle-blend open-end rule: the middle of
//!   its arc on the only circle, through `V1, V2, V3` ([`circle_blend::end_blend_point`]).
//!   With both ends on the boundary, the edge is a two-point curve: its midpoint.
//!   This keeps meridians of an open sphere band on their great circles.
//!
//! # Face points (Figs. 5 and 6)
//!
//! * **Even n-gon** (the regular quad included, Fig. 5 / Fig. 6 left): the average of the
//!   `n/2` curve applications on `(O_i, E_i, E_{i+n/2}, O_{i+n/2})`, `E_i` the new point of
//!   the face's edge `i`, `O_i` the point across edge `i` (`across`). For a quad these are
//!   the two curves "through it" of Fig. 5, on the edge points of the row and the column.
//! * **Odd n-gon** (Fig. 6 right): the average of `n` curve applications, one per corner:
//!   the segment from corner `v_i` to the edge point `E_{i+(n−1)/2}` of the opposite edge,
//!   continued across that edge by `O_{i+(n−1)/2}`. The paper uses "the vertices of the
//!   face" only, so the segment has no point beyond `v_i`: it is the end segment of an open
//!   curve (the open-end rule, circle through `v_i, E, O`), or the midpoint when `O` is
//!   missing too.
//!
//! The point across edge `i` (paper silent beyond the regular quad neighbour):
//! * a **quad neighbour**: the edge point of its opposite edge (the regular case of Fig. 5,
//!   as in Kobbelt's scheme);
//! * an **even m-gon neighbour**: the edge point of the edge `m/2` steps round it (its
//!   opposite edge, as for even valence);
//! * an **odd m-gon neighbour**: its corner opposite the shared edge (an old vertex, as the
//!   odd-valence rule takes a vertex of the central face);
//! * **no neighbour** (a boundary edge: the face lies next to the boundary): none; the row
//!   ends there and the curve takes the open-end rule.
//!
//! # Degenerate geometry
//!
//! The circle rule needs distinct points: two points of one circle that coincide (relative
//! 1e-13), a blended tangent that vanishes or points back along the chord (a spike) give
//! [`Status::DegenerateGeometry`] naming the **output vertex** whose rule failed
//! (`V + e` for edge `e`, `V + E + f` for face `f`). There is no fallback to a linear rule
//! (the scheme has no linear counterpart to fall back to that would keep its circles), and
//! nothing is reported as success with a partial result. There is no Möbius form either
//! ([`super::Scheme::has_mobius_form`]): the circle blend is not Möbius-equivariant.

use crate::curve::circle_blend;
use crate::error::{Error, Result, Status};
use crate::exec::{pass, Executor};
use crate::mesh::gather::boundary_beyond;
use crate::mesh::{get, internal, Topology, NONE};
use crate::point::Point;

/// Relative tolerance on squared distances under which two candidates of the odd-valence
/// rule count as equally far (`farthest`).
pub const TIE_TOLERANCE: f64 = 1e-12;

/// Writes the positions of one spherelike step: `pos` holds `V + E + F` points
/// (the sizes of [`crate::mesh::refine::Pattern::Quads`]).
///
/// # Errors
/// [`Status::DegenerateGeometry`] and [`Status::NumericalFailure`] naming the output vertex
/// (module docs); internal errors never expected on a built topology.
pub(crate) fn positions(
    topo: &Topology<'_, '_>,
    pos: &mut [Point],
    exec: &dyn Executor,
) -> Result<()> {
    let nv = topo.num_vertices();
    let ne = topo.num_edges();
    let (ve, fpos) = pos.split_at_mut_checked(nv + ne).ok_or(internal())?;
    // Old vertices and edge points (they read the input only), then the face points (they
    // read the edge points back).
    pass(exec, ve, |start, out, _| {
        for (i, o) in (start..).zip(out.iter_mut()) {
            *o = if i < nv {
                topo.position(i as u32)?
            } else {
                edge_point(topo, (i - nv) as u32).map_err(|err| err.with_element(i as u32))?
            };
        }
        Ok(())
    })?;
    let ve: &[Point] = ve;
    pass(exec, fpos, |start, out, _| {
        for (f, o) in (start..).zip(out.iter_mut()) {
            let i = nv + ne + f;
            *o = face_point(topo, ve, f as u32).map_err(|err| err.with_element(i as u32))?;
        }
        Ok(())
    })
    .map(|_| ())
}

/// The circle-blend point of the segment `p1 p2` of a curve whose neighbours `p0` (before
/// `p1`) and `p3` (after `p2`) may be missing (an open end): both present, the blend of
/// seed 003 §2; one missing, the open-end rule (the middle of the arc on the circle through
/// the three points); both missing, the midpoint (a two-point curve).
///
/// # Errors
/// Those of [`circle_blend::blend_point`].
pub fn segment_point(p0: Option<Point>, p1: Point, p2: Point, p3: Option<Point>) -> Result<Point> {
    match (p0, p3) {
        (Some(a), Some(b)) => circle_blend::blend_point(a, p1, p2, b),
        (None, Some(b)) => circle_blend::end_blend_point(p1, p2, b),
        (Some(a), None) => circle_blend::end_blend_point(p2, p1, a),
        (None, None) => Ok(crate::point::midpoint(p1, p2)),
    }
}

/// The new point of edge `e` (module docs, "Edge points").
fn edge_point(topo: &Topology<'_, '_>, e: u32) -> Result<Point> {
    let h = topo.edge_half_edge(e)?;
    let (v1, v2) = (topo.origin(h)?, topo.dest(h)?);
    let (p1, p2) = (topo.position(v1)?, topo.position(v2)?);
    if topo.twin(h)? == NONE {
        let (a, b) = (
            boundary_beyond(topo, v1, v2)?,
            boundary_beyond(topo, v2, v1)?,
        );
        return circle_blend::blend_point(topo.position(a)?, p1, p2, topo.position(b)?);
    }
    segment_point(beyond(topo, v1, v2)?, p1, p2, beyond(topo, v2, v1)?)
}

/// The point `V0` beyond `v` on the grid line from `toward` through `v` (Fig. 3), or `None`
/// when `v` lies on the boundary (an open end, module docs).
fn beyond(topo: &Topology<'_, '_>, v: u32, toward: u32) -> Result<Option<Point>> {
    if topo.is_boundary_vertex(v)? {
        return Ok(None);
    }
    // The star is walked, not gathered: once to find `toward` (spoke j), then to the spoke
    // the rule reads (no array of spokes, so the stack does not grow with the valence).
    let n = topo.valence(v)?;
    let j = topo
        .star(v)
        .position(|s| s.neighbour == toward)
        .ok_or(internal())?;
    let spoke = |k: usize| -> Result<crate::mesh::Spoke> {
        let k = k.checked_rem(n).ok_or(internal())?;
        topo.star(v).nth(k).ok_or(internal())
    };
    if n % 2 == 0 {
        return topo.position(spoke(j + n / 2)?.neighbour).map(Some);
    }
    // The central face lies between spokes j + (n−1)/2 and j + (n+1)/2.
    let s = spoke(j + n.saturating_sub(1) / 2)?;
    let f = s.face;
    if f == NONE {
        return Err(internal());
    }
    farthest(topo, v, f).map(Some)
}

/// The corner of face `f` farthest from its corner `v` (the odd-valence rule of Fig. 3c).
/// Candidates whose squared distances lie within [`TIE_TOLERANCE`] (relative) of the largest
/// are ties; the tie goes to the first of them counter-clockwise after `v` in the face — a
/// fixed, orientation-based choice, so the result never depends on vertex numbering.
fn farthest(topo: &Topology<'_, '_>, v: u32, f: u32) -> Result<Point> {
    let pv = topo.position(v)?;
    let corners = topo.face_vertices(f)?;
    let k = corners.iter().position(|&c| c == v).ok_or(internal())?;
    let m = corners.len();
    // The candidates counter-clockwise after `v`, walked twice (the largest squared
    // distance, then the first within the tolerance of it) rather than held in an array.
    let candidates = || {
        (1..m).map(move |i| -> Result<(f64, Point)> {
            let c = get(corners, (k + i).checked_rem(m).ok_or(internal())?)?;
            let p = topo.position(c)?;
            let d = [p[0] - pv[0], p[1] - pv[1], p[2] - pv[2]];
            Ok((d[0] * d[0] + d[1] * d[1] + d[2] * d[2], p))
        })
    };
    let mut max = 0.0_f64;
    for c in candidates() {
        max = max.max(c?.0);
    }
    for c in candidates() {
        let (d, p) = c?;
        if d >= max - TIE_TOLERANCE * max {
            return Ok(p);
        }
    }
    Err(Error::new(Status::DegenerateGeometry))
}

/// The edge point of the edge of half-edge `h`, read back from the output.
fn ep(topo: &Topology<'_, '_>, pos: &[Point], h: u32) -> Result<Point> {
    get(pos, topo.num_vertices() + topo.edge(h)? as usize)
}

/// The point across edge `h` of a face, continuing its grid line into the neighbour face
/// (module docs, "The point across edge i"), or `None` on the boundary.
fn across(topo: &Topology<'_, '_>, pos: &[Point], h: u32) -> Result<Option<Point>> {
    let t = topo.twin(h)?;
    if t == NONE {
        return Ok(None);
    }
    let m = topo.face_size(topo.face(t)?)?;
    let mut g = t;
    if m % 2 == 0 {
        for _ in 0..m / 2 {
            g = topo.next(g)?;
        }
        ep(topo, pos, g).map(Some)
    } else {
        for _ in 0..m.div_ceil(2) {
            g = topo.next(g)?;
        }
        topo.position(topo.origin(g)?).map(Some)
    }
}

/// The new point of face `f` (module docs, "Face points").
fn face_point(topo: &Topology<'_, '_>, pos: &[Point], f: u32) -> Result<Point> {
    let hs = topo.face_half_edges(f)?;
    let n = hs.len();
    let first = hs.start;
    // `checked_rem`, not `%`: the core has no panic paths, not even unreachable ones.
    let he = |i: usize| -> Result<u32> {
        let k = i.checked_rem(n).ok_or(internal())?;
        first.checked_add(k as u32).ok_or(internal())
    };
    let mut sum = [0.0_f64; 3];
    let count;
    if n % 2 == 0 {
        count = n / 2;
        for i in 0..count {
            let (a, b) = (he(i)?, he(i + n / 2)?);
            let p = segment_point(
                across(topo, pos, a)?,
                ep(topo, pos, a)?,
                ep(topo, pos, b)?,
                across(topo, pos, b)?,
            )?;
            sum = [sum[0] + p[0], sum[1] + p[1], sum[2] + p[2]];
        }
    } else {
        count = n;
        for (i, &v) in topo.face_vertices(f)?.iter().enumerate() {
            let c = topo.position(v)?;
            let b = he(i + n.saturating_sub(1) / 2)?;
            let p = segment_point(None, c, ep(topo, pos, b)?, across(topo, pos, b)?)?;
            sum = [sum[0] + p[0], sum[1] + p[1], sum[2] + p[2]];
        }
    }
    let s = 1.0 / count as f64;
    let p = [sum[0] * s, sum[1] * s, sum[2] * s];
    if crate::point::is_finite(&p) {
        Ok(p)
    } else {
        Err(Error::new(Status::NumericalFailure))
    }
}
