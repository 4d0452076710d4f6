//! Möbius Kobbelt (seed 000 §4.3, Fig. 11 left; §4.4.3, Fig. 14): old vertices stay
//! (interpolating); the vertex pass gives every spoke the point beyond its centre
//! ([`kobbelt_beyond_in_form`]: virtual points in interior forms, the end extrapolation in
//! boundary forms); an edge point is `F4(r_a, a, b, r_b)` of the points beyond its two ends
//! (boundary edges: along their boundary loop), and a face point the F6 blend of the two
//! grid lines of new edge points through the face.

use super::super::audit::Children;
use super::super::driver::{chunk_fallback, Driver};
use super::super::form::{present, MISSING};
use super::super::guard::{CreaseEdges, EdgeBlend, Outputs};
use super::super::rules::kobbelt_beyond_in_form;
use super::super::slots::slot_of;
use super::super::toward_linear::{no_corner, LinearRules};
use super::super::vertex_pass::{Part, Star};
use super::super::workspace::take;
use crate::blend::{self, f4, f4_hinted};
use crate::error::{Error, Result, Status};
use crate::exec::{pass, Tally};
use crate::mesh::gather::apex;
use crate::mesh::{get, internal, set, Topology, NONE};
use crate::point::{midpoint, Point};
use crate::scheme::carry::copy_old;
use crate::scheme::linear::{kobbelt_edge, kobbelt_face};
use crate::stencil::kobbelt;

/// How far around a distrusted star the fold guard's blend toward the linear rule reaches
/// (`toward_linear.rs`), measured (`docs/folds.md` section 8).
const RINGS: u8 = 1;

pub(in crate::scheme::mobius) fn run(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    copy_old(d.topo, d.pos)?;
    points_beyond(d)?;
    edge_points(d)?;
    face_points(d)?;
    if d.guard {
        fold_guard(d)?;
        // The crease curves (`boundary.rs`), on a level cut along its sharp edges, each
        // crease point judged from both sides of its crease.
        d.guard_curves(
            d.topo.num_vertices(),
            kobbelt::four_point,
            false,
            RINGS,
            true,
        )?;
    }
    Ok(())
}

/// The fold guard (`guard.rs`) on the paper's output of the step: the spread term of every
/// interior star (kept by the vertex pass), the F4-angle term of every interior edge's
/// 4-point blend `F4(r_a, a, b, r_b)`, and the output audit of the corner quads around every
/// interior star (Kobbelt's children are Catmull–Clark's: `(v', e_i, f_i, e_{i+1})`). The
/// stars are not evaluated again in `m_τ`: the old vertices stay, and the points beyond a
/// star only enter the blends, so the blend toward the linear rule (`toward_linear.rs`) is the
/// whole fallback. Spherical stars keep the paper's rules (`trust::sphericity`); a star of
/// valence 3, which gives no evidence of a sphere, is not raised.
#[inline(never)]
fn fold_guard(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    let (nv, ne) = (topo.num_vertices(), topo.num_edges());
    d.trust_edges(EdgeBlend::Beyond, CreaseEdges::Off)?;
    d.audit(Children::Quads {
        edges: nv,
        faces: nv + ne,
        edge_places: true,
    })?;
    d.raise_spherical_quads()?;
    d.curve_terms_into_trust()?;
    if d.trust.iter().all(|&t| t >= 1.0) {
        return Ok(());
    }
    let out = Outputs {
        vertex: false,
        edges: Some(nv),
        faces: Some(nv + ne),
        corners: false,
        boundary_edges: false,
        rings: RINGS,
        vertex_rings: RINGS,
        crease_edge_faces: true,
    };
    let linear = LinearRules {
        vertex: &|_, _, p| Ok(p),
        edge: &kobbelt_edge,
        face: &kobbelt_face,
        corner: &no_corner,
    };
    d.blend_toward_linear(out, linear, false)
}

/// The vertex pass: per half-edge `h = (v → u)`, the point beyond `v` away from `u`, from
/// `v`'s canonical form (regular interior vertices give the actual grid neighbour), kept as
/// `h`'s edge candidate.
fn points_beyond(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    d.vertex_pass(
        false,
        || (),
        |p, star, _| p.with_work(|p, work| beyond_in_workspace(p, star, work)),
    )?;
    Ok(())
}

/// [`points_beyond`] at one star, its two arrays in the chunk's star workspace
/// (`workspace.rs`).
#[inline(always)]
fn beyond_in_workspace(
    p: &mut Part<'_, '_, '_>,
    star: &mut Star<'_>,
    mut work: &mut [Point],
) -> Result<()> {
    let topo = p.topo;
    // The images of the neighbours and, for a closed star, of the diagonals.
    let n = star.spokes.len();
    let ring = take(&mut work, n)?;
    let diagonals = take(&mut work, if star.boundary { 0 } else { n })?;
    let mut complete = true;
    for (j, s) in star.spokes.iter().enumerate() {
        let form = &mut *star.form;
        let q = form.canon(topo, s.neighbour).unwrap_or(MISSING);
        *ring.get_mut(j).ok_or(internal())? = q;
        complete &= present(&q);
        if !star.boundary {
            let c = apex(topo, s.half_edge)
                .and_then(|a| form.canon(topo, a))
                .unwrap_or(MISSING);
            *diagonals.get_mut(j).ok_or(internal())? = c;
            complete &= present(&c);
        }
    }
    // The guard's spread term, from the ring in the normalised frame (`guard.rs`).
    p.trust_star(star, ring, &[], true)?;
    for j in 0..star.spokes.len() {
        let q = kobbelt_beyond_in_form(ring, diagonals, !star.boundary, complete, j, &*star.form);
        if let (Some(q), true) = (q, star.spokes.get(j).is_some_and(|s| s.half_edge != NONE)) {
            p.set_edge(star, j, q)?;
        }
    }
    Ok(())
}

/// Edge points `F4(r0, a0, a1, r1)` of the points beyond both ends (boundary edges: their
/// boundary loop's neighbours); the linear rule where one is missing or the blend fails.
///
/// The interior edges in edge ranges through the executor, then the boundary edges, which
/// read their boundary loops, on the calling thread: each edge point is computed alone, so
/// the bits do not depend on the order. Every fallback (and fold-guard substitution) is
/// tallied; strict mode then refuses the lowest such output vertex, the one the serial walk
/// over the edges met first. Out of line, as [`face_points`]: the driver's frame holds
/// neither pass's locals (`docs/firmware.md`, "Stack").
#[inline(never)]
fn edge_points(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    let (nv, ne) = (topo.num_vertices(), topo.num_edges());
    let (edge_c, slots): (&[Point], &[f64]) = (d.edge_c, d.slots);
    let out = d.pos.get_mut(nv..nv + ne).ok_or(internal())?;
    let interior = pass(d.exec, out, |first, out, tally| {
        for (i, p) in out.iter_mut().enumerate() {
            let e = (first + i) as u32;
            let h = topo.edge_half_edge(e)?;
            let t = topo.twin(h)?;
            if t == NONE {
                continue;
            }
            let (a0, a1) = (
                topo.position(topo.origin(h)?)?,
                topo.position(topo.dest(h)?)?,
            );
            let hint = topo.position(topo.dest(topo.next(h)?)?)?;
            let q = match (beyond_of(edge_c, slots, h)?, beyond_of(edge_c, slots, t)?) {
                (Some(r0), Some(r1)) => f4_hinted(r0, a0, a1, r1, hint).ok(),
                _ => None,
            };
            *p = match q {
                Some(q) => q,
                None => {
                    tally.add((nv + first + i) as u32);
                    kobbelt_edge(topo, e)?
                }
            };
        }
        Ok(())
    })?;
    let (mut fallbacks, mut guarded) = (interior, Tally::new());
    for e in 0..ne as u32 {
        let h = topo.edge_half_edge(e)?;
        if topo.twin(h)? != NONE {
            continue;
        }
        let (a0, a1) = (
            topo.position(topo.origin(h)?)?,
            topo.position(topo.dest(h)?)?,
        );
        let k = nv + e as usize;
        let (o0, o3) = d.boundary_outer(h)?;
        let (r0, r1) = (topo.position(o0)?, topo.position(o3)?);
        let hint = topo.position(topo.dest(topo.next(h)?)?)?;
        let cut_curve = d.corner_ends(h)? != (false, false);
        if d.short_curve(h)? {
            // A crease curve of three points (`boundary.rs`): the linear 4-point rule.
            guarded.add(k as u32);
            let p = d.boundary_segment(h)?.0;
            set(d.pos, k, kobbelt::four_point(p[0], p[1], p[2], p[3]))?;
            continue;
        }
        let q = if cut_curve {
            // A boundary curve ending at a corner (sharp features): the open-curve rule.
            d.boundary_segment(h)?.1.ok()
        } else {
            f4_hinted(r0, a0, a1, r1, hint).ok()
        };
        let q = match q {
            Some(q) => q,
            None if cut_curve => {
                // The 4-point rule of the open curve (virtual end points past a corner).
                fallbacks.add(k as u32);
                let p = d.boundary_segment(h)?.0;
                kobbelt::four_point(p[0], p[1], p[2], p[3])
            }
            None => {
                fallbacks.add(k as u32);
                kobbelt_edge(topo, e)?
            }
        };
        set(d.pos, k, q)?;
    }
    if d.strict && fallbacks.merge(guarded).count > 0 {
        let first = fallbacks.merge(guarded).first;
        return Err(Error::at(Status::FallbackInStrictMode, first));
    }
    d.add_fallbacks(fallbacks);
    d.add_guarded(guarded);
    Ok(())
}

/// Face points: `F6(w2, F4(w1..w4), w3, w6, F4(w5..w8), w7)` over the two grid lines of new
/// edge points through the face (Fig. 14); the linear rule where a blend fails. In face
/// ranges through the executor: a face point reads only the edge points.
#[inline(never)]
fn face_points(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    let (nv, ne, nf) = (topo.num_vertices(), topo.num_edges(), topo.num_faces());
    let strict = d.strict;
    let (pos, rest) = d.pos.split_at_mut_checked(nv + ne).ok_or(internal())?;
    let pos: &[Point] = pos;
    let out = rest.get_mut(..nf).ok_or(internal())?;
    let t = pass(d.exec, out, |first, out, tally| {
        for (i, p) in out.iter_mut().enumerate() {
            let f = (first + i) as u32;
            let r = topo.face_half_edges(f)?;
            let (h0, h1, h2, h3) = lines(topo, r.start)?;
            let line = |hx: u32, hy: u32| -> Result<[Point; 4]> {
                Ok([
                    outer_edge_point(topo, pos, hx, hy)?,
                    edge_point(topo, pos, hx)?,
                    edge_point(topo, pos, hy)?,
                    outer_edge_point(topo, pos, hy, hx)?,
                ])
            };
            let w = line(h0, h2)?;
            let x = line(h1, h3)?;
            let q = f4(w[0], w[1], w[2], w[3])
                .and_then(|pa| {
                    let pb = f4(x[0], x[1], x[2], x[3])?;
                    blend::f6(w[1], pa, w[2], x[1], pb, x[2])
                })
                .ok();
            *p = match q {
                Some(q) => q,
                None => {
                    chunk_fallback(strict, tally, nv + ne + first + i)?;
                    let fa = kobbelt::four_point(w[0], w[1], w[2], w[3]);
                    let fb = kobbelt::four_point(x[0], x[1], x[2], x[3]);
                    midpoint(fa, fb)
                }
            };
        }
        Ok(())
    })?;
    d.add_fallbacks(t);
    Ok(())
}

/// The point beyond the origin of half-edge `h` on the line from its far end, as the vertex
/// pass left it in the candidate slots; `None` when the origin has no form.
fn beyond_of(edge_c: &[Point], slots: &[f64], h: u32) -> Result<Option<Point>> {
    let c = get(edge_c, slot_of(slots, h)?)?;
    Ok(present(&c).then_some(c))
}

/// The new edge point of the edge of half-edge `h` (`pos`: the old vertices, then the edge
/// points).
fn edge_point(topo: &Topology<'_, '_>, pos: &[Point], h: u32) -> Result<Point> {
    get(pos, topo.num_vertices() + topo.edge(h)? as usize)
}

/// The new edge point beyond edge `hx` of a quad, away from its opposite edge `hy`: the
/// edge point of the neighbouring quad's opposite edge, or at the boundary an extrapolation.
fn outer_edge_point(topo: &Topology<'_, '_>, pos: &[Point], hx: u32, hy: u32) -> Result<Point> {
    let t = topo.twin(hx)?;
    if t != NONE {
        return edge_point(topo, pos, topo.next(topo.next(t)?)?);
    }
    // The Möbius-invariant open-end extrapolation of the curve rules
    // (`cr[P_2, P_1, P_0, P_−1] = −1/3`, on the circle through the first three points) along
    // the face's grid line; a strip one face wide has no third point and takes the linear
    // `2e − e'` of the 4-point curve.
    let (e0, e1) = (edge_point(topo, pos, hx)?, edge_point(topo, pos, hy)?);
    let ty = topo.twin(hy)?;
    if ty != NONE {
        let e2 = edge_point(topo, pos, topo.next(topo.next(ty)?)?)?;
        if let Ok(p) = crate::curve::mobius::virtual_end_point(e0, e1, e2) {
            return Ok(p);
        }
    }
    Ok(kobbelt::extrapolate(e0, e1))
}

/// The half-edges `(h0, h1, h2, h3)` of the quad whose first half-edge is `first`, arranged so
/// that Kobbelt's face point `F6(w1, F4(w), w2, x1, F4(x), x2)` over the grid lines `(h0, h2)`
/// and `(h1, h3)` does not depend on where the face starts: F6 is symmetric neither in its two
/// lines nor in their directions, so each line runs from its edge of smaller id, and the line
/// holding the smallest edge id comes first. Edge ids are untouched by Möbius maps, so the
/// rule keeps Möbius equivariance (docs/DECISIONS.md).
fn lines(topo: &Topology<'_, '_>, first: u32) -> Result<(u32, u32, u32, u32)> {
    let edge_of = |h: u32| topo.edge(h).map(|e| (e, h));
    let [p, q, r, t] = [first, first + 1, first + 2, first + 3];
    let (e0, e1, e2, e3) = (edge_of(p)?, edge_of(q)?, edge_of(r)?, edge_of(t)?);
    // Each line from its edge of smaller id; (edge id, half-edge) pairs compare by id first.
    let (a0, a1) = (e0.min(e2), e0.max(e2));
    let (b0, b1) = (e1.min(e3), e1.max(e3));
    Ok(if a0 <= b0 {
        (a0.1, b0.1, a1.1, b1.1)
    } else {
        (b0.1, a0.1, b1.1, a1.1)
    })
}
