//! Möbius versions of Akleman's remeshing operators (seed 000 §4.3, "subdivision-like
//! operators"): every face point is the §4.4.3 blend of the face centroids taken in its
//! corners' forms. Dual truncation also moves interior old vertices by the truncation rule in
//! their own forms; the dual's boundary edge points follow the Möbius interpolating curve
//! rule. Layouts are the linear schemes'.

use super::super::audit::Children;
use super::super::driver::Driver;
use super::super::form::{Frame, ORIGIN};
use super::super::guard::Outputs;
use super::super::toward_linear::{face_centroid, no_corner, LinearRules};
use super::super::vertex_pass::{Part, Star};
use super::super::workspace::take;
use super::super::MobiusReport;
use crate::blend::f4;
use crate::error::Result;
use crate::mesh::gather::ring_sum;
use crate::mesh::{set, Topology, NONE};
use crate::point::Point;
use crate::scheme::carry::{append_isolated, boundary_vertices, copy_old};
use crate::stencil::akleman;

/// The face candidates of every corner (the face centroid in the corner's form, ears in a
/// substitute's) blended into face points at `start + f`; the report from before the blends
/// (dual truncation blends again after its guard's re-evaluation, [`dual_truncation`]).
fn face_points(
    d: &mut Driver<'_, '_, '_, '_>,
    start: usize,
    keep_boundary_forms: bool,
) -> Result<MobiusReport> {
    let topo = d.topo;
    d.vertex_pass(
        false,
        || (),
        |p, star, _| {
            p.with_work(|p, mut work| {
                let fc = take(&mut work, star.spokes.len())?;
                if p.guard {
                    // The fold guard's spread term (`guard.rs`), from the ring's images.
                    star.ring_images(topo, fc)?;
                    p.trust_star(star, fc, &[], keep_boundary_forms)?;
                }
                star.face_centroids(topo, fc)?;
                p.keep_face_candidates(star, fc)
            })
        },
    )?;
    d.ear_face_candidates()?;
    let before = d.report;
    d.blend_faces(start)?;
    Ok(before)
}

/// Akleman's dual: face points, then a point on each boundary vertex's outgoing boundary edge
/// (the linear midpoint becomes the Möbius interpolating curve rule), then the boundary
/// vertices themselves, then the isolated vertices (the linear layout).
pub(in crate::scheme::mobius) fn dual(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    face_points(d, 0, true)?;
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
    append_isolated(topo, d.pos, nf + 2 * vb)?;
    if d.guard {
        dual_guard(d)?;
    }
    Ok(())
}

/// How far the dual's blend reaches (`docs/folds.md` section 12): three rings. With two, a
/// face point whose corners' 2-rings were all trusted kept the paper's point between face
/// points that took the centroids, and that seam folded where neither rule folds (cow, level
/// 2: 92.4° against 58.8° for the paper's rules and 82.9° for the centroids on the same
/// level-1 mesh; helmet_quad, level 1: one edge against none).
const DUAL_RINGS: u8 = 3;

/// The fold guard of the dual, as vertex insertion's ([`insertion_guard`]): the audit of each
/// interior vertex's face against its neighbours' faces (`audit.rs`,
/// [`Children::DualFaces`]); the face points around a distrusted star move toward the face
/// centroids, the boundary's edge points and vertices keep the paper's.
#[inline(never)]
fn dual_guard(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    d.audit(Children::DualFaces { faces: 0 })?;
    d.raise_spherical_quads()?;
    if d.trust.iter().all(|&t| t >= 1.0) {
        return Ok(());
    }
    let out = Outputs {
        vertex: false,
        edges: None,
        faces: Some(0),
        corners: false,
        boundary_edges: false,
        rings: DUAL_RINGS,
        vertex_rings: DUAL_RINGS,
        crease_edge_faces: false,
    };
    let linear = LinearRules {
        vertex: &|_, _, p| Ok(p),
        edge: &|_, _| Err(crate::mesh::internal()),
        face: &face_centroid,
        corner: &no_corner,
    };
    d.blend_toward_linear(out, linear, false)
}

/// Akleman's vertex insertion: the old vertices, then the face points; then the fold guard.
pub(in crate::scheme::mobius) fn vertex_insertion(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    copy_old(d.topo, d.pos)?;
    let nv = d.topo.num_vertices();
    face_points(d, nv, false)?;
    if d.guard {
        insertion_guard(d, nv)?;
    }
    Ok(())
}

/// How far around a distrusted star the fold guard's blend toward the linear rule reaches
/// (`toward_linear.rs`), measured (`docs/folds.md` section 12).
const RINGS: u8 = 1;

/// The fold guard (`guard.rs`) of vertex insertion on the paper's output of the step: the
/// spread term of every interior star (kept by the vertex pass) and the output audit of the
/// fan of triangles around it (`audit.rs`, [`Children::Insertion`]); spherical stars keep
/// the paper's rules; then every face point with a corner within one ring of a distrusted
/// star moves toward the face's centroid (the linear face point). The old vertices stay, and
/// a star's face candidates only feed the face blends, so there is no re-evaluation in
/// `m_τ`.
#[inline(never)]
fn insertion_guard(d: &mut Driver<'_, '_, '_, '_>, faces: usize) -> Result<()> {
    d.audit(Children::Insertion { faces })?;
    d.raise_spherical_quads()?;
    if d.trust.iter().all(|&t| t >= 1.0) {
        return Ok(());
    }
    let out = Outputs {
        vertex: false,
        edges: None,
        faces: Some(faces),
        corners: false,
        boundary_edges: false,
        rings: RINGS,
        vertex_rings: RINGS,
        crease_edge_faces: false,
    };
    let linear = LinearRules {
        vertex: &|_, _, p| Ok(p),
        edge: &|_, _| Err(crate::mesh::internal()),
        face: &face_centroid,
        corner: &no_corner,
    };
    d.blend_toward_linear(out, linear, false)
}

/// How far around a distrusted star dual truncation's vertex points move toward the linear
/// rule: two rings, the least trust of the face points around the vertex (each takes the
/// least of its corners' closed 1-rings, [`RINGS`]), measured (`docs/folds.md` section 12).
/// With one ring, a vertex two rings from a distrusted star kept the paper's point while a
/// face point next to it took the linear one, and the child triangle `(v', p_{i−1}, p_i)`
/// between them folded (bunny: 2 / 2 / 1 folded edges at levels 1 / 2 / 3, linear
/// 1 / 0 / 0).
const TRUNCATION_VERTEX_RINGS: u8 = 2;

/// Akleman's dual truncation: the face points, then every interior old vertex moved by the
/// truncation rule in its own form; boundary vertices stay (as in the linear scheme). Then the
/// fold guard.
pub(in crate::scheme::mobius) fn dual_truncation(d: &mut Driver<'_, '_, '_, '_>) -> Result<()> {
    let topo = d.topo;
    let faces = topo.num_vertices();
    let before = face_points(d, faces, true)?;
    d.clear_vertex_points()?;
    d.vertex_pass(true, || (), truncation_star_rule)?;
    let linear_vertex = |t: &Topology<'_, '_>, v: u32, p: Point| -> Result<Point> {
        let (n, ring) = ring_sum(t, v)?;
        akleman::truncated_vertex_sum(p, n, ring)
    };
    let vertex_fallbacks = d.finish_vertex_points_counted(true, linear_vertex)?;
    if !d.guard {
        return Ok(());
    }
    // The fold guard (`guard.rs`), as vertex insertion's ([`insertion_guard`]), on the fan of
    // triangles `(v', p_{i−1}, p_i)` around each moved vertex.
    d.audit(Children::FacePoints { faces })?;
    d.raise_spherical_quads()?;
    if d.trust.iter().all(|&t| t >= 1.0) {
        return Ok(());
    }
    let out = Outputs {
        vertex: true,
        edges: None,
        faces: Some(faces),
        corners: false,
        boundary_edges: false,
        rings: RINGS,
        vertex_rings: TRUNCATION_VERTEX_RINGS,
        crease_edge_faces: false,
    };
    // Step 5 of `guard.rs`: the rules of every distrusted star again in `m_τ` (seed 000
    // §7.2), its face candidates and its vertex point, as Catmull–Clark's, whose vertex
    // point is also made in the star's own form; then the face blends again on the guarded
    // candidates, with the fallbacks of the first blends rewound (the vertex points' stay).
    // Without it, cow folded 21 edges at level 3 against the linear operator's 20 (one at a
    // normal angle of 90.04°, `docs/folds.md` section 12).
    if d.reevaluate(out, || (), truncation_star_rule)? {
        let near = d.rewind_for_blends_again(before);
        d.blend_faces_again(faces, near)?;
        d.add_fallbacks(vertex_fallbacks);
    }
    // Step 7: every point near a distrusted star toward the linear rule, the vertex points
    // within two rings, the face points within one ring of their corners.
    let linear = LinearRules {
        vertex: &linear_vertex,
        edge: &|_, _| Err(crate::mesh::internal()),
        face: &face_centroid,
        corner: &no_corner,
    };
    d.blend_toward_linear(out, linear, false)
}

/// The rules of dual truncation at one star in its frame (the canonical form, or the guard's
/// `m_τ`): the truncation rule `(1 − t) v + t · mean(ring)` on the ring's images, mapped
/// back, for an interior star whose ring the frame maps; in `m_τ` (the guard's
/// re-evaluation, `guard.rs` step 5) also its face candidates, the face centroids in the
/// frame, which the canonical pass kept from [`face_points`].
fn truncation_star_rule<F: Frame>(
    p: &mut Part<'_, '_, '_>,
    star: &mut Star<'_, F>,
    _: &mut (),
) -> Result<()> {
    let topo = p.topo;
    p.with_work(|p, mut work| {
        let n = star.spokes.len();
        if !F::CANONICAL {
            let fc = take(&mut work, n)?;
            star.face_centroids(topo, fc)?;
            p.keep_face_candidates(star, fc)?;
        }
        let ring = take(&mut work, n)?;
        if !star.boundary && star.ring_images(topo, ring)? {
            let t = akleman::truncated_vertex(ORIGIN, ring);
            if let Ok(q) = t.and_then(|t| star.form.back(t)) {
                p.set_vertex(star.v, q)?;
            }
        }
        Ok(())
    })
}
