//! Tier-1 exports of the Möbius mesh schemes: the rules at one vertex star, for a host mesh
//! library (OpenMesh, CGAL, a CAD kernel) that drives the schemes with its own connectivity.
//! Each export only checks and converts its C arguments and calls the core rule
//! (`nlsubdiv::scheme::mobius::{loop_star, catmull_clark_star, butterfly_star}`), which the
//! driver of `nls_mesh_subdivide` with `NLS_SUBDIVIDE_MOBIUS` evaluates too.
//!
//! Every star rule takes one `nls_star_view`: the centre, its 1-ring and (Catmull–Clark) the
//! corners of its faces. How a host assembles a whole level from them: the docs of
//! `nls_mobius_loop_star`.

use nlsubdiv::scheme::mobius as smobius;
use nlsubdiv::{Point, Status, MAX_VALENCE};

use crate::guard::{
    check_fp_env, check_out, check_ptr, flag, points, points_mut, read_point, write,
};
use crate::primitives::run;

const NAN3: Point = [f64::NAN; 3];

/// A vertex star, read only: the centre `v`, its neighbours and, for
/// `nls_mobius_catmull_clark_star`, the corners of its faces. Plain data; nothing is kept.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct nls_star_view {
    /// The centre: 3 doubles.
    pub v: *const f64,
    /// The neighbours, packed `x, y, z` (`3 * ring_count` doubles). `closed = 1`: an interior
    /// vertex, the neighbours counter-clockwise (seen from outside) as a cycle. `closed = 0`: a
    /// boundary vertex, from one boundary neighbour counter-clockwise to the other.
    pub ring: *const f64,
    /// Number of neighbours.
    pub ring_count: usize,
    /// 1 for an interior vertex, 0 for a boundary vertex.
    pub closed: u32,
    /// `nls_mobius_catmull_clark_star` only (ignored by the triangle rules): face `j` has
    /// the corners `face_offsets[j]` up to `face_offsets[j + 1] - 1` of `face_corners`;
    /// `face_count + 1` entries from 0 to `corner_count`.
    pub face_offsets: *const u32,
    /// Number of faces: `ring_count` for a closed star, `ring_count − 1` for an open one.
    pub face_count: usize,
    /// The positions of the corners of all faces, packed (`3 * corner_count` doubles).
    pub face_corners: *const f64,
    /// Number of face corners.
    pub corner_count: usize,
}

/// Reads a star view.
///
/// # Safety
/// `p` is NULL or points to a readable `nls_star_view`.
unsafe fn read_star(p: *const nls_star_view) -> Result<nls_star_view, Status> {
    check_ptr(p, 1)?;
    // SAFETY: checked non-NULL and aligned; readable by the caller's contract.
    Ok(unsafe { p.read() })
}

/// A byte range `(start, bytes)` of `count` elements of `T` at `p`.
fn bytes<T>(p: *const T, count: usize) -> (usize, usize) {
    (p as usize, count.saturating_mul(core::mem::size_of::<T>()))
}

/// Fails with `AliasingBuffers` when an output range intersects an input or another output
/// (inputs may overlap each other: they are only read).
fn disjoint(outputs: &[(usize, usize)], inputs: &[(usize, usize)]) -> Result<(), Status> {
    let hit = |(a, na): (usize, usize), (b, nb): (usize, usize)| {
        na > 0 && nb > 0 && a < b.saturating_add(nb) && b < a.saturating_add(na)
    };
    for (i, &o) in outputs.iter().enumerate() {
        if inputs
            .iter()
            .chain(outputs.iter().skip(i + 1))
            .any(|&x| hit(o, x))
        {
            return Err(Status::AliasingBuffers);
        }
    }
    Ok(())
}

/// The canonical Möbius Loop rules at the vertex star `star` (`v` and `ring[0..ring_count]`,
/// packed `x, y, z`), exactly as `nls_mesh_subdivide` evaluates them for `NLS_SCHEME_LOOP` with
/// `NLS_SUBDIVIDE_MOBIUS`: the star's canonical form (seed 000 §4.2), Loop's stencils on the
/// mapped 1-ring, the results mapped back.
///
/// `closed = 1`: an interior vertex, `ring` its neighbours counter-clockwise (seen from
/// outside) as a cycle. `closed = 0`: a boundary vertex, `ring` from one boundary neighbour
/// counter-clockwise to the other. The faces are triangles: face `j` is `(v, ring[j],
/// ring[j+1])`.
///
/// Writes `out_vertex_point` (the Möbius vertex point; NaN for a boundary vertex, whose
/// vertex point is the boundary curve rule, and when it does not exist) and
/// `out_edge_candidates[3j..3j+3]`, the candidate of the edge to `ring[j]` in this star's form
/// (NaN for the two boundary edges of a boundary star, and when it does not exist); the
/// outputs hold 3 and `3*ring_count` doubles and must not overlap `ring`. Edge points: see
/// `nls_f4_hinted` (the hint `x` of edge `a → b` is the third vertex
/// of the triangle on its left).
///
/// Bit-identical to the driver when `ring` starts at the spoke the driver starts at (the
/// vertex's outgoing half-edge with the lowest corner index); otherwise equal up to rounding.
///
/// One level of a Möbius scheme from the star rules (seed 000 §4.1), as the driver does it:
/// 1. every non-isolated vertex: its star rule (vertex point, edge candidates, and for
///    Catmull–Clark face candidates);
/// 2. every interior edge `a → b` (`a` the smaller index): `nls_f4_hinted(a, e_a, e_b, b, x)`
///    of the candidates of both end points; the one candidate when the other is NaN;
/// 3. every face (Catmull–Clark, Akleman schemes): `nls_face_point_with_ids` of its corners and their
///    stars' face candidates; a boundary vertex with a single face (an *ear*) lends the
///    candidate of the first non-ear corner at offset `h, h+1, h−1, …` (`h = ⌊d/2⌋`);
/// 4. boundary loops as closed curves: edge points `nls_f4(P_{i−1}, P_i, P_{i+1}, P_{i+2})`,
///    vertex points (approximating schemes) `nls_f4(P_{i−1}, E_{i−½}, E_{i+½}, P_{i+1})`;
/// 5. whatever has no value (an error status here, a NaN vertex point of an interior vertex,
///    an edge without candidates) takes the linear rule: what `nls_mesh_subdivide` counts as
///    a fallback.
///
/// Errors: `NLS_STATUS_TOO_FEW_POINTS` (fewer than 2 neighbours),
/// `NLS_STATUS_VALENCE_TOO_HIGH` (more than 128), `NLS_STATUS_NON_FINITE_INPUT`,
/// `NLS_STATUS_DEGENERATE_GEOMETRY` (the star has no canonical form: a neighbour coincides
/// with `v`, or the form sends a neighbour to infinity; the driver then takes the linear rule
/// for everything this star gives), `NLS_STATUS_INVALID_ARGUMENT` (`closed` not 0 or 1),
/// `NLS_STATUS_NULL_PARAMETER`, `NLS_STATUS_MISALIGNED_POINTER`, `NLS_STATUS_SIZE_OVERFLOW`,
/// `NLS_STATUS_ALIASING_BUFFERS`, `NLS_STATUS_FP_ENVIRONMENT`. Nothing is written on error.
///
/// Stack on Cortex-M4F: at most 5,632 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[out_vertex_point;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mobius_loop_star(
    star: *const nls_star_view,
    out_vertex_point: *mut f64,
    out_edge_candidates: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or a readable view whose `v` is NULL or three
        // readable doubles.
        let star = unsafe { read_star(star)? };
        let (ring, ring_count, closed) = (star.ring, star.ring_count, star.closed);
        let v = unsafe { read_point(star.v)? };
        check_ptr(ring.cast::<Point>(), ring_count)?;
        if ring_count > MAX_VALENCE {
            return Err(Status::ValenceTooHigh);
        }
        let closed = flag(closed)?;
        let n3 = ring_count.checked_mul(3).ok_or(Status::SizeOverflow)?;
        check_out(out_vertex_point, 3)?;
        check_out(out_edge_candidates, n3)?;
        disjoint(
            &[
                bytes(out_vertex_point.cast_const(), 3),
                bytes(out_edge_candidates.cast_const(), n3),
            ],
            &[bytes(ring, n3)],
        )?;
        check_fp_env()?;
        // SAFETY: checked above; readable by the caller's contract and disjoint from the
        // outputs.
        // The rule writes its candidates straight to the caller's buffer, and only once it
        // cannot fail (nothing is written on error): no copy of them on the stack.
        // SAFETY: checked above; `ring` is readable by the caller's contract, and the output
        // is writable for `3*ring_count` doubles and disjoint from `ring`.
        let (ring_pts, cands) = unsafe {
            (
                points(ring, ring_count)?,
                points_mut(out_edge_candidates, ring_count),
            )
        };
        let vp = smobius::loop_star(v, ring_pts, closed, cands).map_err(|e| e.status)?;
        // SAFETY: checked above for 3 doubles.
        unsafe { write(out_vertex_point, vp.unwrap_or(NAN3)) };
        Ok(())
    })
}

/// The canonical Möbius Catmull–Clark rules at the vertex star `star` (`v` and
/// `ring[0..ring_count]`), exactly as `nls_mesh_subdivide` evaluates them for `NLS_SCHEME_CATMULL_CLARK` with
/// `NLS_SUBDIVIDE_MOBIUS`. `ring` and `closed` as for `nls_mobius_loop_star`.
///
/// The faces of the star: face `j` lies between the edges to `ring[j]` and `ring[j+1]`
/// (counter-clockwise); `face_count` is `ring_count` for a closed star, `ring_count − 1` for an
/// open one. Face `j` is `face_corners[3*face_offsets[j] .. 3*face_offsets[j+1]]`: the
/// positions of all its corners in face order, `v` included (anywhere in the cycle);
/// `face_offsets` holds `face_count + 1` entries, from 0 to `corner_count`.
///
/// Writes `out_vertex_point` (NaN as for `nls_mobius_loop_star`),
/// `out_edge_candidates[3j..3j+3]` (the candidate of the edge to `ring[j]`; NaN for boundary
/// edges and when it does not exist) and `out_face_candidates[3j..3j+3]` (the centroid of
/// face `j` taken in this star's canonical form; NaN when it does not exist); they hold 3,
/// `3*ring_count` and `3*face_count` doubles and must not overlap the inputs. Face points are
/// `nls_face_point_with_ids` of a face's corners (with the host's vertex indices) and the face candidates of the corners' stars (the
/// Akleman schemes use the same face candidates); edge points as in
/// `nls_f4_hinted` (hint: the corner after `b` in the face on the left
/// of `a → b`).
///
/// Bit-identical to the driver when `ring` starts at the driver's first spoke and each face
/// lists its corners from its first corner in the mesh; otherwise equal up to rounding.
///
/// Errors: those of `nls_mobius_loop_star`, except that a neighbour sent to infinity only
/// removes the rules that use it (NaN), as in the driver; `NLS_STATUS_INVALID_ARGUMENT`
/// (`face_count` does not fit `ring_count` and `closed`, or a face does not contain `v`),
/// `NLS_STATUS_BAD_OFFSETS`, `NLS_STATUS_FACE_TOO_SMALL`, `NLS_STATUS_VALENCE_TOO_HIGH` (a face
/// above `nls_max_face_size()` corners), `NLS_STATUS_NON_FINITE_INPUT` (also a face corner).
///
/// Stack on Cortex-M4F: at most 5,632 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
///
/// cbindgen:ptrs-as-arrays=[[out_vertex_point;3]]
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mobius_catmull_clark_star(
    star: *const nls_star_view,
    out_vertex_point: *mut f64,
    out_edge_candidates: *mut f64,
    out_face_candidates: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or a readable view whose `v` is NULL or three
        // readable doubles.
        let star = unsafe { read_star(star)? };
        let (ring, ring_count, closed) = (star.ring, star.ring_count, star.closed);
        let (face_offsets, face_count) = (star.face_offsets, star.face_count);
        let (face_corners, corner_count) = (star.face_corners, star.corner_count);
        let offsets_len = face_count.checked_add(1).ok_or(Status::SizeOverflow)?;
        // SAFETY: as above.
        let v = unsafe { read_point(star.v)? };
        check_ptr(ring.cast::<Point>(), ring_count)?;
        check_ptr(face_offsets, offsets_len)?;
        check_ptr(face_corners.cast::<Point>(), corner_count)?;
        if ring_count > MAX_VALENCE || face_count > MAX_VALENCE {
            return Err(Status::ValenceTooHigh);
        }
        let closed = flag(closed)?;
        let n3 = ring_count.checked_mul(3).ok_or(Status::SizeOverflow)?;
        let f3 = face_count.checked_mul(3).ok_or(Status::SizeOverflow)?;
        let c3 = corner_count.saturating_mul(3);
        check_out(out_vertex_point, 3)?;
        check_out(out_edge_candidates, n3)?;
        check_out(out_face_candidates, f3)?;
        disjoint(
            &[
                bytes(out_vertex_point.cast_const(), 3),
                bytes(out_edge_candidates.cast_const(), n3),
                bytes(out_face_candidates.cast_const(), f3),
            ],
            &[
                bytes(ring, n3),
                bytes(face_corners, c3),
                bytes(face_offsets, offsets_len),
            ],
        )?;
        check_fp_env()?;
        // The rule writes the outputs only once it cannot fail (nothing is written on
        // error), so they need no copy on the stack.
        // SAFETY: checked above (`face_offsets` is non-NULL since `offsets_len ≥ 1`); the
        // inputs are readable by the caller's contract, the outputs writable for their sizes,
        // pairwise disjoint and disjoint from the inputs.
        let (ring_pts, corners, offs, e, f) = unsafe {
            (
                points(ring, ring_count)?,
                points(face_corners, corner_count)?,
                core::slice::from_raw_parts(face_offsets, offsets_len),
                points_mut(out_edge_candidates, ring_count),
                points_mut(out_face_candidates, face_count),
            )
        };
        let vp = smobius::catmull_clark_star(v, ring_pts, closed, offs, corners, e, f)
            .map_err(|e| e.status)?;
        // SAFETY: checked above for 3 doubles.
        unsafe { write(out_vertex_point, vp.unwrap_or(NAN3)) };
        Ok(())
    })
}

/// The canonical Möbius Modified Butterfly rules at the vertex star `star` (`v` and
/// `ring[0..ring_count]`; `ring` and `closed` as for `nls_mobius_loop_star`; triangles), as `nls_mesh_subdivide`
/// evaluates them for `NLS_SCHEME_MODIFIED_BUTTERFLY` with `NLS_SUBDIVIDE_MOBIUS` (seed 000
/// §4.3, "partial candidates"): the star's canonical form, then for each interior spoke `j`
/// the candidate of the edge to `ring[j]`:
/// * `v` interior and irregular (valence ≠ 6): Zorin's stencil of `v`, ring from `ring[j]`;
/// * else, when `irregular_neighbours[j]` is 1 (`ring[j]` is an interior vertex of valence
///   ≠ 6): no candidate from this star (only the singular ring contributes);
/// * else `v`'s half of the 8-point stencil, doubled (`v`, `ring[j]` ½; `ring[j ± 1]` ⅛;
///   the wings `ring[j ± 2]` −⅛, reflected as `u + w − z` across a boundary edge, as OpenMesh
///   does), all in the canonical form, the result mapped back.
///
/// `irregular_neighbours` holds `ring_count` flags (0 or 1), or is NULL (no neighbour is
/// irregular). Writes `out_edge_candidates[3j..3j+3]` (NaN for boundary spokes, the skipped
/// spokes, a rule that needs a point the form sends to infinity, and every spoke of an *ear*,
/// a boundary star of one face, to which the driver gives no form). Interior old vertices
/// keep their positions (the scheme interpolates); edge points are
/// `nls_f4_hinted(a, e_a, e_b, b, x)` of both end points' candidates (hint: the third vertex
/// of the triangle on the left of `a → b`, `a` the smaller index), the one candidate when
/// the other is NaN; boundary edges `nls_f4(P_{i−1}, P_i, P_{i+1}, P_{i+2})`; what has no
/// value takes the linear rule (the driver's fallback).
///
/// Bit-identical to the driver when `ring` starts at the driver's first spoke (any start
/// gives the same values here: each spoke's rule reads the ring relative to that spoke).
///
/// Errors: those of `nls_mobius_loop_star` (including `NLS_STATUS_DEGENERATE_GEOMETRY` when
/// the star has no canonical form); `NLS_STATUS_INVALID_ARGUMENT` also for a flag not 0 or 1;
/// `NLS_STATUS_TOO_FEW_POINTS` for fewer than 2 neighbours. Nothing is written on error.
///
/// Stack on Cortex-M4F: at most 5,632 bytes in a firmware build
/// (`NLSUBDIV_MAX_CHUNKS=1`: `docs/firmware.md`, "Stack").
#[unsafe(no_mangle)]
pub unsafe extern "C" fn nls_mobius_butterfly_star(
    star: *const nls_star_view,
    irregular_neighbours: *const u32,
    out_edge_candidates: *mut f64,
) -> Status {
    run(|| {
        // SAFETY: the caller passes NULL or a readable view whose `v` is NULL or three
        // readable doubles.
        let star = unsafe { read_star(star)? };
        let (ring, ring_count, closed) = (star.ring, star.ring_count, star.closed);
        let v = unsafe { read_point(star.v)? };
        check_ptr(ring.cast::<Point>(), ring_count)?;
        if ring_count > MAX_VALENCE {
            return Err(Status::ValenceTooHigh);
        }
        let closed = flag(closed)?;
        let n3 = ring_count.checked_mul(3).ok_or(Status::SizeOverflow)?;
        let flags_len = if irregular_neighbours.is_null() {
            0
        } else {
            ring_count
        };
        check_ptr(irregular_neighbours, flags_len)?;
        check_out(out_edge_candidates, n3)?;
        disjoint(
            &[bytes(out_edge_candidates.cast_const(), n3)],
            &[bytes(ring, n3), bytes(irregular_neighbours, flags_len)],
        )?;
        check_fp_env()?;
        // SAFETY: checked above; readable by the caller's contract and disjoint from the
        // output.
        let (ring_pts, flags) = unsafe {
            (
                points(ring, ring_count)?,
                if flags_len == 0 {
                    &[][..]
                } else {
                    core::slice::from_raw_parts(irregular_neighbours, flags_len)
                },
            )
        };
        let mut irregular = [false; MAX_VALENCE];
        for (slot, &f) in irregular.iter_mut().zip(flags) {
            *slot = flag(f)?;
        }
        let irregular = irregular.get(..flags_len).ok_or(Status::ValenceTooHigh)?;
        // SAFETY: checked above for `3*ring_count` writable doubles, disjoint from the
        // inputs; the rule writes it only once it cannot fail (nothing is written on error).
        let c = unsafe { points_mut(out_edge_candidates, ring_count) };
        smobius::butterfly_star(v, ring_pts, closed, irregular, c).map_err(|e| e.status)?;
        Ok(())
    })
}
