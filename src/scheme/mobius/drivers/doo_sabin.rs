//! Möbius Doo–Sabin (seed 000 §4.3): every corner point is evaluated in the canonical form of
//! its vertex ([`doo_sabin_corner_in_form`]), an ear's corner in a substitute's form; a
//! corner point that cannot be computed takes the linear rule, counted as a fallback.

use super::super::driver::Driver;
use super::super::form::{present, FacePts, Spokes};
use super::super::memo::StarForm;
use super::super::rules::doo_sabin_corner_in_form;
use super::super::slots::slot_of;
use crate::error::Result;
use crate::exec::pass;
use crate::mesh::gather::face_points_into;
use crate::mesh::{get, internal, set, NONE};
use crate::point::{self, Point};
use crate::scheme::carry::append_isolated;
use crate::stencil::doo_sabin;

pub(in crate::scheme::mobius) fn run(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    let nh = topo.num_half_edges();
    // One canonical form per vertex: all its corners, kept in the edge candidates' slots
    // (the vertex pass writes slots, split into vertex ranges), then moved to the corners'
    // output points (split into corner ranges).
    d.vertex_pass(false, FacePts::new, |p, star, pts| {
        for (j, s) in star.spokes.iter().enumerate() {
            if s.face == NONE {
                continue;
            }
            let i = (s.half_edge - topo.face_half_edges(s.face)?.start) as usize;
            let form = &mut *star.form;
            let q = form
                .face(topo, s.face, pts)
                .and_then(|()| doo_sabin_corner_in_form(pts, i, form));
            if let Ok(q) = q {
                p.set_edge(star, j, q)?;
            }
        }
        Ok(())
    })?;
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
    append_isolated(topo, d.pos, nh)
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
    let mut pts = FacePts::new();
    let mut linear_pts = FacePts::new();
    for f in 0..topo.num_faces() as u32 {
        // The face's own corners only when one of its corner points is missing (rare).
        let mut gathered = false;
        for (i, h) in topo.face_half_edges(f)?.enumerate() {
            if present(&get(d.pos, h as usize)?) {
                continue;
            }
            if !gathered {
                face_points_into(topo, f, &mut linear_pts)?;
                gathered = true;
            }
            let q = if d.is_ear(topo.origin(h)?)? {
                d.form_vertex(f, i)?.and_then(|u| {
                    if !d.local_into(u, &mut form, &mut spokes, tangents).ok()? {
                        return None;
                    }
                    form.face(topo, f, &mut pts).ok()?;
                    doo_sabin_corner_in_form(&pts, i, &form).ok()
                })
            } else {
                None
            };
            let q = match q {
                Some(q) if point::is_finite(&q) => q,
                _ => {
                    d.fallback(h as usize)?;
                    doo_sabin::corner_point(&linear_pts, i)?
                }
            };
            set(d.pos, h as usize, q)?;
        }
    }
    Ok(())
}
