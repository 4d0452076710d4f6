//! The fold guard's last step (step 7 of `guard.rs`, step 8 of `docs/folds.md` section 8):
//! every output point near a distrusted star moves toward the linear rule's point,
//! `τ² p + (1 − τ²) p_lin`, and these are the points the guard counts in `Report::guarded`.
//!
//! Why: the interpolated form `m_τ` (`spectrum.rs`) ends, at `τ = 0`, in a similarity frame
//! where the stencils are affine but the blends are still the paper's (F4, the face chain,
//! Butterfly's single partial candidate next to an irregular vertex, seed 000 §4.3), so a fully
//! distrusted element can still fold where the linear scheme does not (Loop on epcot's
//! valence-12 stars, Catmull–Clark on polycastle_quad's 90° blocks). This blend is the
//! spectrum toward linear for that element (seed 000 §7.2): at `τ = 0` the point is the linear
//! rule's bit for bit, at `τ = 1` it is untouched, and it is continuous in `τ`.
//!
//! `τ` of a point is the least trust of the stars within `rings` rings of the stars it is made
//! from (its vertex for a vertex point, the two ends for an edge point, the corners for a face
//! point). Moving only the points of the distrusted stars themselves put linear points next
//! to the paper's points, and that seam folded (Loop epcot: 240 folded edges at level 1 with
//! every distrusted point fully linear); reaching two rings further (Loop, Butterfly) or one
//! (Catmull–Clark) spreads the change over the stars around; dual truncation's vertex points
//! reach two rings and its face points one (`Outputs::vertex_rings`), so that a vertex point
//! is no more trusted than the face points around it, and the dual's face points reach three
//! rings (`docs/folds.md` section 12). The weight `τ²` and the rings are measured
//! (`docs/folds.md` section 8). Which points move, and by how much, is decided by `τ` alone,
//! so it stays Möbius-invariant; the blend itself is equivariant under similarities only,
//! like every fallback toward the linear rule. This runs only when some star is distrusted
//! (`Driver::guarded_pass`) or, on a level cut along its sharp edges, a crease vertex's curve
//! terms are below 1 (`Driver::curve_terms_into_trust`), so a mesh that needs nothing pays
//! nothing here.
//!
//! A face point of a quad reads the stars of its four corners, so its `τ` reaches one ring
//! further from an edge's ends than the edge point's. Next to a crease that seam folded:
//! on horse_quad (Kobbelt, 30° tags, level 2) an interior edge point from a crease vertex kept
//! 94 % of the paper's point between face points moved fully to the linear rule, and the
//! next level folded there. So on a level cut along its sharp edges, Kobbelt's interior edge
//! points with an end on a boundary loop also take the least `τ` of their two faces' points
//! (`Outputs::crease_edge_faces`): a function of the trusts and the connectivity, so still
//! Möbius-invariant, and nothing changes on an untagged level.

use super::driver::{chunk_fallback, Driver};
use super::edges::LinearEdge;
use super::guard::Outputs;
use crate::error::Result;
use crate::exec::{pass, Tally};
use crate::mesh::gather::face_sum;
use crate::mesh::{get, internal, Topology, NONE};
use crate::point::{lin2, Point};
use crate::stencil::centroid_of_sum;

/// The linear rule of an interior vertex `v` at `p` (the vertex point of the linear scheme).
pub(super) type LinearVertex<'f> =
    dyn Fn(&Topology<'_, '_>, u32, Point) -> Result<Point> + Sync + 'f;

/// The linear rule of face `f`'s face point.
pub(super) type LinearFace<'f> = dyn Fn(&Topology<'_, '_>, u32) -> Result<Point> + Sync + 'f;

/// The linear rules of a scheme's output points, the ends of the blend toward them.
#[derive(Clone, Copy)]
pub(super) struct LinearRules<'a> {
    /// The interior vertex points (read when [`Outputs::vertex`]).
    pub(super) vertex: &'a LinearVertex<'a>,
    /// The interior edge points.
    pub(super) edge: &'a LinearEdge<'a>,
    /// The face points (read when [`Outputs::faces`] is set).
    pub(super) face: &'a LinearFace<'a>,
    /// The corner point of half-edge `h` (read with [`Outputs::corners`]).
    pub(super) corner: &'a LinearCorner<'a>,
}

/// The linear rule of the corner point of half-edge `h` (Doo–Sabin).
pub(super) type LinearCorner<'f> = dyn Fn(&Topology<'_, '_>, u32) -> Result<Point> + Sync + 'f;

/// For a scheme without corner points (never read).
pub(super) fn no_corner(_: &Topology<'_, '_>, _: u32) -> Result<Point> {
    Err(crate::mesh::internal())
}

/// The centroid of face `f`'s corners, summed as the face is walked (no array of points on
/// the stack): [`crate::stencil::centroid`] of the face's points bit for bit. The linear face
/// point of Catmull–Clark.
pub(super) fn face_centroid(t: &Topology<'_, '_>, f: u32) -> Result<Point> {
    let (n, s) = face_sum(t, f)?;
    centroid_of_sum(s, n)
}

/// `τ² p + (1 − τ²) p_lin`: exactly `p_lin` at `τ ≤ 0` (no signed zero or non-finite `p`
/// leaks through `0 · p`), exactly `p` at `τ ≥ 1`.
pub(super) fn toward_linear(tau: f64, p: Point, p_lin: Point) -> Point {
    if tau >= 1.0 {
        return p;
    }
    if tau <= 0.0 {
        return p_lin;
    }
    let w = tau * tau;
    lin2(w, p, 1.0 - w, p_lin)
}

/// The least trust of the stars within `rings` (0, 1, 2 or 3) rings of `v`, `v` included: its
/// trust, or the minimum [`ring_trust`] kept for it.
fn near_trust(trust: &[f64], ring: &[f64], rings2: &[Point], v: u32, rings: u8) -> Result<f64> {
    match rings {
        0 => get(trust, v as usize),
        1 => get(ring, v as usize),
        2 => Ok(get(rings2, v as usize)?[0]),
        _ => Ok(get(rings2, v as usize)?[1]),
    }
}

/// Keeps, for every vertex `v`, the least trust of its closed 1-ring (`v` and its
/// neighbours) in `ring[v]`, that of its closed 2-ring in the first coordinate of
/// `rings2[v]` and, with `three`, that of its closed 3-ring in the second, each where it is
/// below 1, and 1 elsewhere (a point whose `τ` is 1 or more keeps the paper's point, whatever
/// the value): the closed `k + 1`-ring of `v` is the union of the closed `k`-rings of `v`
/// and its neighbours, so each point's `τ` is one look-up instead of a walk over the rings
/// per point ([`near_trust`]).
///
/// Found by scattering each trust below 1 to its closed 1-ring (and each such 1-ring value to
/// its closed 1-ring, and so on), not by gathering at every vertex: the guard distrusts few
/// stars (on Catmull–Clark spot_quad, 3 levels, about 1 % of the output), so the walks are
/// few. A least value is the same in whatever order its set is walked, so the result is the
/// gathering's for every value below 1, bit for bit; the scatter runs on the calling thread
/// (two stars may share a neighbour).
fn ring_trust(
    topo: &Topology<'_, '_>,
    trust: &[f64],
    ring: &mut [f64],
    rings2: &mut [Point],
    three: bool,
) -> Result<()> {
    ring.fill(1.0);
    rings2.fill([1.0, 1.0, 0.0]);
    // Lowers the value `field` picks in `xs[u]` to `t` for `u` in the closed 1-ring of `v`.
    fn spread<T>(
        topo: &Topology<'_, '_>,
        v: u32,
        t: f64,
        xs: &mut [T],
        field: fn(&mut T) -> &mut f64,
    ) -> Result<()> {
        let mut lower = |u: usize| -> Result<()> {
            let x = field(xs.get_mut(u).ok_or(internal())?);
            *x = x.min(t);
            Ok(())
        };
        lower(v as usize)?;
        for s in topo.star(v) {
            lower(s.neighbour as usize)?;
        }
        Ok(())
    }
    for (v, &t) in (0u32..).zip(trust.iter()) {
        if t < 1.0 {
            spread(topo, v, t, ring, |x| x)?;
        }
    }
    for (v, &t) in (0u32..).zip(ring.iter()) {
        if t < 1.0 {
            spread(topo, v, t, rings2, |r| &mut r[0])?;
        }
    }
    if three {
        for v in 0..rings2.len() as u32 {
            let t = get(rings2, v as usize)?[0];
            if t < 1.0 {
                spread(topo, v, t, rings2, |r| &mut r[1])?;
            }
        }
    }
    Ok(())
}

impl Driver<'_, '_, '_, '_> {
    /// Moves the points `out` names toward the linear rules `linear` (module docs): the
    /// interior vertex points (when `out.vertex`), the interior edge points (when
    /// `out.edges`), the face points (when `out.faces`), the corner points (when
    /// `out.corners`).
    ///
    /// First it counts in the report every point within reach of a distrusted star (or
    /// refuses the first in strict mode): these include every point step 6 evaluated again.
    /// Then, with `raise_valence_3`, a spherical star of valence 3, which step 6 evaluated on
    /// its sphere (`spectrum.rs`), has its trust raised as the others' were
    /// (`Driver::raise_spherical`), since this blend would leave the sphere (sphere
    /// reproduction, `tests/mesh_mobius.rs`). Then it blends.
    pub(super) fn blend_toward_linear(
        &mut self,
        out: Outputs,
        linear: LinearRules<'_>,
        raise_valence_3: bool,
    ) -> Result<()> {
        let counted = self.each_point(out, false, linear, true)?;
        self.add_guarded(counted);
        let raised = raise_valence_3 && self.raise_spherical(|valence| valence == 3)?;
        // The ring trusts of the count serve the blend unless the raise changed a trust.
        self.each_point(out, true, linear, raised)?;
        Ok(())
    }

    /// Whether an edge with an end on a crease is distrusted (`Driver::trust_edges`).
    pub(super) fn any_crease_edge_term(&self) -> bool {
        self.edge_trust.iter().any(|&t| t < 1.0)
    }

    /// One pass over each kind of point `out` names, split into ranges ([`crate::exec`]: a
    /// point depends only on itself and the trust), for every point whose `τ` is below 1:
    /// counts it (strict: refuses it), or with `blend` moves it. With `find_rings` it first
    /// finds each vertex's least trust within one and two rings ([`ring_trust`]); without,
    /// it reads those of the pass before, on the same trusts.
    fn each_point(
        &mut self,
        out: Outputs,
        blend: bool,
        linear: LinearRules<'_>,
        find_rings: bool,
    ) -> Result<Tally> {
        let (linear_vertex, linear_edge, linear_face) = (linear.vertex, linear.edge, linear.face);
        let linear_corner = linear.corner;
        let topo = self.topo;
        let trust: &[f64] = self.trust;
        let (strict, rings) = (self.strict, out.rings);
        // The kept forms' radii and centres are spent after the audit (`audit.rs`): they hold
        // each vertex's least trust of its closed 1-ring and 2-ring for this pass.
        let nv = topo.num_vertices();
        let ring = self.radius.get_mut(..nv).ok_or(internal())?;
        let rings2 = self.centre.get_mut(..nv).ok_or(internal())?;
        let vertex_rings = out.vertex_rings;
        if find_rings && (rings > 0 || (out.vertex && vertex_rings > 0)) {
            let three = rings > 2 || (out.vertex && vertex_rings > 2);
            ring_trust(topo, trust, ring, rings2, three)?;
        }
        let (ring, rings2): (&[f64], &[Point]) = (ring, rings2);
        // Counts the point at `element`, or moves `o` to `toward_linear(τ, o, lin())`.
        let act = |t: &mut Tally,
                   element: usize,
                   tau: f64,
                   o: &mut Point,
                   lin: &dyn Fn() -> Result<Point>| {
            if blend {
                *o = toward_linear(tau, *o, lin()?);
                Ok(())
            } else {
                chunk_fallback(strict, t, element)
            }
        };
        // The least trust within `rings` rings of vertex `v` (`near_trust`).
        let near = |v: u32| near_trust(trust, ring, rings2, v, rings);
        let boundary_edges = out.boundary_edges;
        let crease_edge_faces = out.crease_edge_faces && !self.corners.is_empty();
        let mut tally = Tally::new();
        if out.vertex {
            let nv = topo.num_vertices();
            let pts = self.pos.get_mut(..nv).ok_or(internal())?;
            let t = pass(self.exec, pts, |first, pts, t| {
                for (v, o) in (first as u32..).zip(pts.iter_mut()) {
                    if topo.is_isolated(v)? || topo.is_boundary_vertex(v)? {
                        continue;
                    }
                    let tau = near_trust(trust, ring, rings2, v, vertex_rings)?;
                    if tau < 1.0 {
                        act(t, v as usize, tau, o, &|| {
                            linear_vertex(topo, v, topo.position(v)?)
                        })?;
                    }
                }
                Ok(())
            })?;
            tally = tally.merge(t);
        }
        if let Some(start) = out.edges {
            let ne = topo.num_edges();
            let edge_trust: &[f64] = self.edge_trust;
            let pts = self.pos.get_mut(start..start + ne).ok_or(internal())?;
            let t = pass(self.exec, pts, |first, pts, t| {
                for (e, o) in (first as u32..).zip(pts.iter_mut()) {
                    let h = topo.edge_half_edge(e)?;
                    if topo.twin(h)? == NONE && !boundary_edges {
                        continue;
                    }
                    let (a, b) = (topo.origin(h)?, topo.dest(h)?);
                    let mut tau = near(a)?.min(near(b)?).min(get(edge_trust, e as usize)?);
                    // Kobbelt next to a boundary loop of a cut level: no less trusted than
                    // the face points beside it (module docs).
                    if crease_edge_faces
                        && (topo.is_boundary_vertex(a)? || topo.is_boundary_vertex(b)?)
                    {
                        for g in [h, topo.twin(h)?] {
                            if g == NONE {
                                continue;
                            }
                            for &u in topo.face_vertices(topo.face(g)?)? {
                                tau = tau.min(near(u)?);
                            }
                        }
                    }
                    if tau < 1.0 {
                        act(t, start + e as usize, tau, o, &|| linear_edge(topo, e))?;
                    }
                }
                Ok(())
            })?;
            tally = tally.merge(t);
        }
        if out.corners {
            let nh = topo.num_half_edges();
            let pts = self.pos.get_mut(..nh).ok_or(internal())?;
            let t = pass(self.exec, pts, |first, pts, t| {
                for (h, o) in (first as u32..).zip(pts.iter_mut()) {
                    let tau = near(topo.origin(h)?)?;
                    if tau < 1.0 {
                        act(t, h as usize, tau, o, &|| linear_corner(topo, h))?;
                    }
                }
                Ok(())
            })?;
            tally = tally.merge(t);
        }
        if let Some(start) = out.faces {
            let nf = topo.num_faces();
            let pts = self.pos.get_mut(start..start + nf).ok_or(internal())?;
            let t = pass(self.exec, pts, |first, pts, t| {
                for (f, o) in (first as u32..).zip(pts.iter_mut()) {
                    let mut tau = f64::INFINITY;
                    for &u in topo.face_vertices(f)? {
                        tau = tau.min(near_trust(trust, ring, rings2, u, rings)?);
                    }
                    if tau < 1.0 {
                        act(t, start + f as usize, tau, o, &|| linear_face(topo, f))?;
                    }
                }
                Ok(())
            })?;
            tally = tally.merge(t);
        }
        Ok(tally)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points whose coordinates have both signs and a signed zero: `0 · p + p_lin` would turn
    /// the `-0.0` of `p_lin` into `+0.0` where `p` is positive.
    const P: Point = [3.5, -1.25, 7.0];
    const P_LIN: Point = [-0.75, -0.0, 2.0];

    fn bits(p: Point) -> [u64; 3] {
        p.map(f64::to_bits)
    }

    #[test]
    fn a_fully_distrusted_point_is_the_linear_rule_bit_for_bit() {
        assert_eq!(bits(toward_linear(0.0, P, P_LIN)), bits(P_LIN));
        // Even from a paper's point that is not finite (an F4 near its cut).
        let inf = [f64::INFINITY, f64::NAN, -f64::INFINITY];
        assert_eq!(bits(toward_linear(0.0, inf, P_LIN)), bits(P_LIN));
    }

    #[test]
    fn a_trusted_point_is_the_paper_point_bit_for_bit() {
        assert_eq!(bits(toward_linear(1.0, P, P_LIN)), bits(P));
    }

    #[test]
    fn the_blend_is_continuous_in_the_trust() {
        // Within `2 |τ − τ'| · |p − p_lin|` (the derivative of `τ²` is at most 2) plus
        // rounding, at both ends and between, so no jump at `τ = 0` or `τ = 1`.
        let span = (0..3).map(|i| (P[i] - P_LIN[i]).abs()).fold(0.0, f64::max);
        let h = 1e-9;
        for k in 0..=1000 {
            let t = k as f64 / 1000.0;
            let (a, b) = (toward_linear(t, P, P_LIN), toward_linear(t + h, P, P_LIN));
            for i in 0..3 {
                assert!((a[i] - b[i]).abs() <= 2.0 * h * span + 1e-14, "τ = {t}");
            }
        }
        // And the weight is τ²: halfway in τ is a quarter of the way to the paper's point.
        let q = toward_linear(0.5, P, P_LIN);
        for i in 0..3 {
            assert!((q[i] - (0.25 * P[i] + 0.75 * P_LIN[i])).abs() < 1e-15);
        }
    }
}
