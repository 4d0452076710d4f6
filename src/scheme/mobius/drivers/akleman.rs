//! Möbius versions of Akleman's remeshing operators (seed 000 §4.3, "subdivision-like
//! operators"): every face point is the §4.4.3 blend of the face centroids taken in its
//! corners' forms. Dual truncation also moves interior old vertices by the truncation rule in
//! their own forms; the dual's boundary edge points follow the Möbius interpolating curve
//! rule. Layouts are the linear schemes'.

use super::super::driver::Driver;
use super::super::form::{MapBack, ORIGIN};
use super::super::workspace::take;
use crate::blend::f4;
use crate::error::Result;
use crate::mesh::gather::ring_sum;
use crate::mesh::{set, NONE};
use crate::scheme::carry::{append_isolated, boundary_vertices, copy_old};
use crate::stencil::akleman;

/// The face candidates of every corner (the face centroid in the corner's form, ears in a
/// substitute's) blended into face points at `start + f`.
fn face_points(d: &mut Driver<'_, '_, '_, '_>, start: usize) -> Result<()> {
    let topo = d.topo;
    d.vertex_pass(
        false,
        || (),
        |p, star, _| {
            p.with_work(|p, mut work| {
                let fc = take(&mut work, star.spokes.len())?;
                star.face_centroids(topo, fc)?;
                p.keep_face_candidates(star, fc)
            })
        },
    )?;
    d.ear_face_candidates()?;
    d.blend_faces(start)
}

/// Akleman's dual: face points, then a point on each boundary vertex's outgoing boundary edge
/// (the linear midpoint becomes the Möbius interpolating curve rule), then the boundary
/// vertices themselves, then the isolated vertices (the linear layout).
pub(in crate::scheme::mobius) fn dual(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    face_points(d, 0)?;
    let topo = d.topo;
    let (nf, vb) = (topo.num_faces(), topo.num_boundary_vertices());
    for v in 0..topo.num_vertices() as u32 {
        let r = topo.boundary_vertex_rank(v)?;
        if r == NONE {
            continue;
        }
        let h = topo.vertex_half_edge(v)?;
        let (i0, i3) = d.boundary_outer(h)?;
        let (a, b) = (topo.position(v)?, topo.position(topo.dest(h)?)?);
        let k = nf + r as usize;
        let q = match f4(topo.position(i0)?, a, b, topo.position(i3)?) {
            Ok(q) => q,
            Err(_) => {
                d.fallback(k)?;
                akleman::boundary_edge_point(a, b)
            }
        };
        set(d.pos, k, q)?;
    }
    boundary_vertices(topo, d.pos, nf + vb)?;
    append_isolated(topo, d.pos, nf + 2 * vb)
}

/// Akleman's vertex insertion: the old vertices, then the face points.
pub(in crate::scheme::mobius) fn vertex_insertion(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    copy_old(d.topo, d.pos)?;
    face_points(d, d.topo.num_vertices())
}

/// Akleman's dual truncation: the face points, then every interior old vertex moved by the
/// truncation rule in its own form; boundary vertices stay (as in the linear scheme).
pub(in crate::scheme::mobius) fn dual_truncation(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    face_points(d, topo.num_vertices())?;
    d.clear_vertex_points()?;
    d.vertex_pass(
        true,
        || (),
        |p, star, _| {
            p.with_work(|p, mut work| {
                let ring = take(&mut work, star.spokes.len())?;
                if !star.boundary && star.ring_images(topo, ring)? {
                    let t = akleman::truncated_vertex(ORIGIN, ring);
                    if let Ok(q) = t.and_then(|t| star.form.back(t)) {
                        p.set_vertex(star.v, q)?;
                    }
                }
                Ok(())
            })
        },
    )?;
    d.finish_vertex_points(true, |t, v, p| {
        let (n, ring) = ring_sum(t, v)?;
        akleman::truncated_vertex_sum(p, n, ring)
    })
}
