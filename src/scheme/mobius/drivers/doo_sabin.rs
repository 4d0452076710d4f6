//! Möbius Doo–Sabin (seed 000 §4.3): every corner point is evaluated in the canonical form of
//! its vertex ([`corner_in_form`]: the linear stencil on the face's images, mapped back), an
//! ear's corner in a substitute's form; a corner point that cannot be computed takes the
//! linear rule, counted as a fallback.

use super::super::audit::Children;
use super::super::driver::Driver;
use super::super::form::{present, MapBack, Spokes};
use super::super::guard::Outputs;
use super::super::memo::StarForm;
use super::super::slots::slot_of;
use super::super::toward_linear::LinearRules;
use super::super::workspace::take;
use crate::error::Result;
use crate::exec::pass;
use crate::mesh::{get, internal, set, Topology, NONE};
use crate::point::{self, Point};
use crate::scheme::carry::append_isolated;
use crate::stencil::doo_sabin;

pub(in crate::scheme::mobius) fn run(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    let nh = topo.num_half_edges();
    // One canonical form per vertex: all its corners, kept in the edge candidates' slots
    // (the vertex pass writes slots, split into vertex ranges), then moved to the corners'
    // output points (split into corner ranges).
    d.vertex_pass(
        false,
        || (),
        |p, star, _| {
            // The fold guard's spread term, from the ring's images (`guard.rs`); the form's
            // memo keeps them for the corner rules below. A boundary star's form is kept
            // for the output audit of its E-faces and F-faces (`audit.rs`).
            if p.guard {
                p.with_work(|p, mut work| {
                    let ring = take(&mut work, star.spokes.len())?;
                    star.ring_images(topo, ring)?;
                    p.trust_star(star, ring, &[], true)
                })?;
            }
            for (j, s) in star.spokes.iter().enumerate() {
                if s.face == NONE {
                    continue;
                }
                let i = (s.half_edge - topo.face_half_edges(s.face)?.start) as usize;
                let q = corner_in_form(topo, s.face, i, star.form)?;
                if let Ok(q) = q {
                    p.set_edge(star, j, q)?;
                }
            }
            Ok(())
        },
    )?;
    let (edge_c, slots): (&[Point], &[f64]) = (d.edge_c, d.slots);
    let out = d.pos.get_mut(..nh).ok_or(internal())?;
    pass(d.exec, out, |first, out, _| {
        for (h, o) in (first as u32..).zip(out.iter_mut()) {
            *o = get(edge_c, slot_of(slots, h)?)?;
        }
        Ok(())
    })?;
    // Ears in a substitute's form; anything still missing takes the linear rule.
    missing_corners(d)?;
    if d.guard {
        fold_guard(d)?;
    }
    append_isolated(topo, d.pos, nh)
}

/// How far around a distrusted star the fold guard's blend toward the linear rule reaches
/// (`toward_linear.rs`), measured (`docs/folds.md` section 10).
const RINGS: u8 = 1;

/// The fold guard (`guard.rs`) on the paper's output of the step, as Kobbelt's: the spread
/// term of every interior star (kept by the vertex pass) and the output audit of its V-face,
/// E-faces and F-faces (`audit.rs`, [`Children::Corners`]), and of every boundary star's
/// E-faces and F-faces in its own frame (without them helmet_quad folded at level 3 next to
/// the corners of its open boundary, `docs/folds.md` section 10); spherical stars keep the
/// paper's rules, with the far corners of their faces as further evidence of the sphere; then
/// every corner point within one ring of a distrusted star moves toward the linear Doo–Sabin
/// corner point (`toward_linear.rs`). A star's corner points are all made in its own form
/// and feed no blend, so there is nothing to evaluate again in `m_τ`.
#[inline(never)]
fn fold_guard(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    d.audit(Children::Corners)?;
    d.raise_spherical_quads()?;
    if d.trust.iter().all(|&t| t >= 1.0) {
        return Ok(());
    }
    let out = Outputs {
        vertex: false,
        edges: None,
        faces: None,
        corners: true,
        boundary_edges: false,
        rings: RINGS,
        vertex_rings: RINGS,
        crease_edge_faces: false,
    };
    let linear = LinearRules {
        vertex: &|_, _, p| Ok(p),
        edge: &|_, _| Err(internal()),
        face: &|_, _| Err(internal()),
        corner: &linear_corner,
    };
    d.blend_toward_linear(out, linear, false)
}

/// The linear Doo–Sabin corner point of half-edge `h` (its origin's corner in its face),
/// reading the face's positions as it walks.
fn linear_corner(topo: &Topology<'_, '_>, h: u32) -> Result<Point> {
    let f = topo.face(h)?;
    let verts = topo.face_vertices(f)?;
    let i = (h - topo.face_half_edges(f)?.start) as usize;
    let corner = |c: usize| match verts.get(c) {
        Some(&u) => topo.position(u),
        None => Err(internal()),
    };
    doo_sabin::corner_point_by(verts.len(), i, corner)
}

/// The corner point of corner `i` of face `f` in `form` (seed 000 §4.3: the linear rule on
/// the face's images in the form, mapped back), reading the images from the form's memo as
/// the rule walks the face, with no array of the face: the bits of
/// `rules::doo_sabin_corner_in_form` on the face's images. The inner result is the rule's (an
/// image or the map back failing: the caller's fallback); the outer one an error of the
/// topology.
fn corner_in_form(
    topo: &Topology<'_, '_>,
    f: u32,
    i: usize,
    form: &mut StarForm,
) -> Result<Result<Point>> {
    let verts = topo.face_vertices(f)?;
    let mut corner = |c: usize| match verts.get(c) {
        Some(&u) => form.canon(topo, u),
        None => Err(internal()),
    };
    let q = doo_sabin::corner_point_by(verts.len(), i, &mut corner);
    Ok(q.and_then(|q| form.back(q)))
}

/// The corner points the vertex pass left missing: an ear's in a substitute's form, any other
/// by the linear rule, counted as a fallback. Out of line, so that its star form and face
/// arrays are off the stack while the vertex pass runs (docs/firmware.md, "Stack").
#[inline(never)]
fn missing_corners(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    // The substitute forms' tangent polygons in the star workspace (the vertex pass is done).
    let tangents = core::mem::take(&mut d.work);
    let spoke_work = core::mem::take(&mut d.spoke_work);
    let r = missing_corners_into(d, tangents, Spokes::new(&mut *spoke_work));
    d.work = tangents;
    d.spoke_work = spoke_work;
    r
}

/// [`missing_corners`] with the star workspace `tangents` taken out of `d`.
fn missing_corners_into(
    d: &mut Driver<'_, '_, '_, '_>,
    tangents: &mut [Point],
    mut spokes: Spokes<'_>,
) -> Result<()> {
    let topo = d.topo;
    let mut form = StarForm::blank();
    for f in 0..topo.num_faces() as u32 {
        let verts = topo.face_vertices(f)?;
        for (i, h) in topo.face_half_edges(f)?.enumerate() {
            if present(&get(d.pos, h as usize)?) {
                continue;
            }
            let q = if d.is_ear(topo.origin(h)?)? {
                match d.form_vertex(f, i)? {
                    Some(u) if d.local_into(u, &mut form, &mut spokes, tangents)? => {
                        corner_in_form(topo, f, i, &mut form)?.ok()
                    }
                    _ => None,
                }
            } else {
                None
            };
            let q = match q {
                Some(q) if point::is_finite(&q) => q,
                _ => {
                    d.fallback(h as usize)?;
                    // The linear corner point, reading the face's positions as it walks.
                    let corner = |c: usize| match verts.get(c) {
                        Some(&u) => topo.position(u),
                        None => Err(internal()),
                    };
                    doo_sabin::corner_point_by(verts.len(), i, corner)?
                }
            };
            set(d.pos, h as usize, q)?;
        }
    }
    Ok(())
}
