//! Möbius Doo–Sabin (seed 000 §4.3): every corner point is evaluated in the canonical form of
//! its vertex ([`doo_sabin_corner_in_form`]), an ear's corner in a substitute's form; a
//! corner point that cannot be computed takes the linear rule, counted as a fallback.

use super::super::driver::Driver;
use super::super::form::{present, FacePts, Spokes, MISSING};
use super::super::memo::StarForm;
use super::super::rules::doo_sabin_corner_in_form;
use crate::error::Result;
use crate::mesh::gather::face_points_into;
use crate::mesh::{get, set, NONE};
use crate::point;
use crate::scheme::carry::append_isolated;
use crate::stencil::doo_sabin;

pub(in crate::scheme::mobius) fn run(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    let nh = topo.num_half_edges();
    for p in d.pos.iter_mut().take(nh) {
        *p = MISSING;
    }
    // One canonical form per vertex: all its corners.
    let mut pts = FacePts::new();
    d.vertex_pass(|d, star| {
        for s in star.spokes.iter() {
            if s.face == NONE {
                continue;
            }
            let i = (s.half_edge - topo.face_half_edges(s.face)?.start) as usize;
            let form = &mut *star.form;
            let q = form
                .face(topo, s.face, &mut pts)
                .and_then(|()| doo_sabin_corner_in_form(&pts, i, form));
            if let Ok(q) = q {
                set(d.pos, s.half_edge as usize, q)?;
            }
        }
        Ok(())
    })?;
    // Ears in a substitute's form; anything still missing takes the linear rule.
    let mut form = StarForm::blank();
    let mut spokes = Spokes::new();
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
                    if !d.local_into(u, &mut form, &mut spokes).ok()? {
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
    append_isolated(topo, d.pos, nh)
}
