//! Sharp features in the Möbius schemes: the mesh cut along its sharp edges.
//!
//! Seed 000 (§4.3, "Boundary curves") treats "boundaries (and sharp features in theory ...)
//! as independent curves that are subdivided using curve-based rules". This file makes that
//! literal: one step on a tagged level runs the scheme's Möbius step on the level **cut open
//! along its sharp edges** — every vertex with sharp edges is split into one copy per
//! *sector* (the faces between two consecutive sharp spokes), so each sharp edge becomes two
//! boundary edges — and reads the step's output back onto the uncut level.
//!
//! What follows, with no new rule:
//! * a crease is a boundary loop of the cut mesh on each side, so its edge and vertex points
//!   are the Möbius curve rules of [`super::boundary`] (approximating for Loop and
//!   Catmull–Clark, interpolating for Modified Butterfly and Kobbelt);
//! * the smooth side of a crease vertex gets its candidates from the canonical form of the
//!   part of its star on that side (the sector is an open star, whose canonical form is the
//!   paper's boundary form, §4.2): the faces across a crease do not shape this side, as the
//!   cut mesh refines each side as if the other were absent;
//! * a **corner** — a vertex tagged as one, or where three or more sharp edges (boundary
//!   edges included, counted before darts are given up: the linear rules' classification
//!   for values of at least ½) meet — ends the curves through it: its copies are marked for
//!   the boundary rules, which use the open-curve rules of [`crate::curve::mobius`] next to
//!   it and keep it in place; a corner tag on a vertex of Loop or Catmull–Clark with no cut
//!   edge keeps it in place too, while a corner by three or more sharp edges that were all
//!   given up as darts (below) is a smooth vertex (kept in place inside a smooth surface it
//!   made spikes that folded the faces around it). A smooth edge from a corner to a
//!   non-corner takes the non-corner's candidate alone where it has one (`edges.rs`; Loop,
//!   Catmull–Clark and Butterfly, whose edge points blend two candidates): a corner is no
//!   smooth point, and the canonical form of its sector extrapolates one — on fandisk the
//!   blend with that candidate flipped thin triangles next to the corners of planar faces. In the default mode (the fold guard,
//!   `guard.rs`) Butterfly's such edge moves toward the linear rule where its candidate,
//!   half a stencil doubled (seed 000 §4.3, partial candidates), lands far from its place
//!   on a Möbius-regular star.
//!
//! The cut is combinatorial and the curve and star rules are Möbius-equivariant, so a
//! tagged circle stays a circle and a tagged great circle of a spherical cage stays on the
//! sphere. The exceptions are those of the open curves and of the guard: a crease of one
//! segment between two corners takes its midpoint (a curve of two points, as in
//! [`crate::curve::mobius`]), a face enclosed by sharp edges whose form does not exist takes
//! the linear rule (a fallback), and in the default mode a short crease curve (three
//! points, or four between corners) takes the linear curve rule (`boundary.rs`), and some
//! interior edges at a crease take the linear rule (`guard.rs`, `Driver::trust_edges`),
//! counted as guarded.
//!
//! The report's fallbacks and guarded elements are counted on the cut level: both sides of
//! a crease count, and the first one is renamed to the uncut level's output vertex.
//!
//! Decisions the paper leaves open (docs/creases.md, "Möbius creases"):
//! * **Semi-sharp** values are whole levels: an edge or a corner is sharp at a level when
//!   its sharpness there is at least ½ (after the decay of the crease method), so a
//!   sharpness `s` is sharp for `s` rounded to the nearest level. A fractional blend of the
//!   sharp and smooth results would need a frame to blend in; a combinatorial schedule is
//!   Möbius-equivariant by construction.
//! * **Darts** — a crease ending at a vertex with no other sharp edge — cannot be cut (the
//!   cut would leave a slit whose tip has two coincident neighbours and no canonical form),
//!   so a sharp edge ending at a dart is subdivided smooth, and so, in turn, is a chain
//!   whose far end becomes a dart — through a corner too, when the corner is left with one
//!   sharp edge (a Y of three creases, two of them ending at darts, keeps none): a crease
//!   chain stays sharp when it is closed, or ends at corners with two or more remaining
//!   sharp edges, or on the boundary. A corner tag at the end of a chain does not change
//!   this. An interior vertex whose sharp edges are all given up is no corner (unless
//!   tagged as one), whatever their number.
//!
//! Output bits: an untagged level, and a tagged level with nothing sharp at it and no
//! corner tag (nor a boundary vertex left a corner by peeled darts), run the untagged step
//! itself; in the default mode Modified Butterfly's fold guard there still moves its
//! distrusted edge points toward the linear rule with the level's tags where some edge
//! carries a value (`drivers/butterfly.rs`).

use super::{MobiusOptions, MobiusReport};
use crate::error::{Error, Result, Status};
use crate::exec::Executor;
use crate::mesh::refine::write_pattern;
use crate::mesh::{
    cadd, get, internal, set, topology_scratch_size, Mesh, MeshOut, MeshSizes, Topology, NONE,
};
use crate::point::Point;
use crate::scheme::plan::ScratchSizes;
use crate::scheme::size::step_size;
use crate::scheme::tags::Sharpness;
use crate::scheme::Scheme;

/// The level before the cut, for the cut level's step: its topology (whose half-edge ids are
/// the cut level's, so a half-edge's twin there names a crease's half-edge on the other side)
/// and its sharpness values read in whole levels, as the cut takes them (the fold guard's
/// linear rule with the level's tags, `drivers/butterfly.rs`).
#[derive(Clone, Copy)]
pub(crate) struct Uncut<'a> {
    pub(crate) topo: &'a Topology<'a, 'a>,
    pub(crate) sharp: &'a Sharpness<'a>,
}

/// Whether a sharpness value is sharp at this level (module docs: whole levels).
fn sharp(s: f32) -> bool {
    crate::scheme::tags::whole_level(s) > 0.0
}

/// The scratch of one tagged Möbius step on a level of `vertices` vertices and `corners`
/// corners, `faces` faces, whose child has `next` sizes. The cut level has at most
/// `vertices + corners` vertices (a vertex has at most one copy per face at it) and at most
/// `corners` edges (an edge has a half-edge).
///
/// `u32s`: the cut flags (an edge has a half-edge: `corners`), the sharp-edge count per
/// vertex, per cut vertex its original and its corner mark, the cut level's indices and
/// topology, the cut step's connectivity (that of the child), its spoke workspace. `points`: the cut level's
/// positions, its step's output and its Möbius candidates and star workspace (for a cut
/// level whose valences are at most `max_valence + 1`, `max_valence` bounding the level's,
/// and whose faces have at most `max_face` corners).
pub(crate) fn scratch(
    vertices: usize,
    corners: usize,
    faces: usize,
    next: MeshSizes,
    max_valence: usize,
    max_face: usize,
) -> Result<ScratchSizes> {
    let cut_v = cadd(vertices, corners)?;
    // Cutting a star along its sharp edges splits it into fans of at most one more spoke
    // (a star cut along one edge opens into a fan of all its faces).
    let spokes = super::workspace::spoke_u32s(cadd(max_valence, 1)?, cut_v)?;
    let u32s = [
        corners,
        vertices,
        cut_v,
        cut_v,
        corners,
        topology_scratch_size(cut_v, corners)?,
        next.offsets()?,
        next.indices,
        spokes,
    ]
    .iter()
    .try_fold(0usize, |a, &b| cadd(a, b))?;
    let out = cadd(cadd(cut_v, corners)?, faces)?;
    let work =
        super::workspace::workspace_points(cadd(max_valence, 1)?, max_face, cut_v.max(faces))?;
    let step = cadd(super::candidate_points(cut_v, corners)?, work)?;
    let points = cadd(cadd(cut_v, out)?, step)?;
    Ok(ScratchSizes { u32s, points })
}

/// Takes the first `n` entries off `buf`.
fn take<'a, T>(buf: &mut &'a mut [T], n: usize) -> Result<&'a mut [T]> {
    let (head, tail) = core::mem::take(buf)
        .split_at_mut_checked(n)
        .ok_or(internal())?;
    *buf = tail;
    Ok(head)
}

/// One step of the Möbius version of `scheme` on the tagged level `topo` (module docs),
/// with `u32s` and `points` of at least [`scratch`].
///
/// # Errors
/// Those of [`super::step`]; an element named by the cut step (strict mode, a non-finite
/// point) is renamed to the uncut level's output vertex.
#[allow(clippy::too_many_arguments)]
pub(crate) fn step(
    scheme: Scheme,
    topo: &Topology<'_, '_>,
    sh: &Sharpness<'_>,
    out: &mut MeshOut<'_>,
    mut u32s: &mut [u32],
    mut points: &mut [Point],
    opts: MobiusOptions,
    exec: &dyn Executor,
) -> Result<(MeshSizes, MobiusReport)> {
    let (nv, ne, nf) = (topo.num_vertices(), topo.num_edges(), topo.num_faces());
    let nc = topo.num_half_edges();
    let cut_v = cadd(nv, nc)?;
    let cut = take(&mut u32s, ne)?;
    let count = take(&mut u32s, nv)?;
    let copy_of = take(&mut u32s, cut_v)?;
    let corner = take(&mut u32s, cut_v)?;
    // The corners of the uncut level first (`corner[..nv]`), then those of the copies.
    let any = cut_edges(topo, sh, cut, count, corner)?;
    let any_corner = corner.get(..nv).ok_or(internal())?.iter().any(|&c| c != 0);
    if !any && !any_corner {
        // Nothing sharp at this level: the untagged step, bit for bit, but for the fold
        // guard's linear rule where a sharp chain was given up as a dart: that stays the
        // linear rule with the level's tags read in whole levels, as on a cut level
        // (`drivers/butterfly.rs`). The level is its own uncut level.
        let whole = sh.in_whole_levels();
        let dart = sh.edges.iter().any(|&b| sharp(f32::from_bits(b)));
        let uncut = dart.then_some(Uncut {
            topo,
            sharp: &whole,
        });
        let cand = &mut *points;
        return super::step_cut(scheme, topo, out, cand, u32s, opts, exec, &[], uncut);
    }
    let sizes = step_size(scheme, topo)?;
    out.check(&sizes)?;
    let cut_idx = take(&mut u32s, nc)?;
    let n_cut = split_vertices(topo, cut, count, copy_of, cut_idx)?;
    let copy_of = copy_of.get(..n_cut).ok_or(internal())?;
    let corner = corner.get_mut(..n_cut).ok_or(internal())?;
    for c in nv..n_cut {
        let v = get(copy_of, c)? as usize;
        set(corner, c, get(corner, v)?)?;
    }
    let pos = take(&mut points, n_cut)?;
    for (p, &v) in pos.iter_mut().zip(copy_of) {
        *p = topo.position(v)?;
    }
    let cut_idx: &[u32] = cut_idx;
    let cut_mesh = Mesh::new(pos, topo.mesh().offsets, cut_idx);
    let topo_scratch = take(&mut u32s, topology_scratch_size(n_cut, nc)?)?;
    let cut_topo = Topology::build(cut_mesh, topo_scratch)?;
    let cut_sizes = step_size(scheme, &cut_topo)?;
    let c_offs = take(&mut u32s, sizes.offsets()?)?;
    let c_idx = take(&mut u32s, sizes.indices)?;
    let c_pos = take(&mut points, cut_sizes.vertices)?;
    let mut cut_out = MeshOut::new(c_pos, c_offs, c_idx);
    let corner: &[u32] = corner;
    let rename = |e: Error| rename_error(e, topo, &cut_topo, copy_of);
    let (_, mut report) = super::step_cut(
        scheme,
        &cut_topo,
        &mut cut_out,
        points,
        u32s,
        opts,
        exec,
        corner,
        Some(Uncut {
            topo,
            sharp: &sh.in_whole_levels(),
        }),
    )
    .map_err(rename)?;
    // The uncut level's output: its pattern, the first copy's vertex point (the vertex
    // itself), the edge point of each edge's representative half-edge, the face points.
    write_pattern(scheme.pattern(), topo, out.offsets, out.indices)?;
    let dst = out.positions.get_mut(..sizes.vertices).ok_or(internal())?;
    let src: &[Point] = cut_out.positions;
    for v in 0..nv {
        set(dst, v, get(src, v)?)?;
    }
    let cut_ne = cut_topo.num_edges();
    let edge_points = sizes.vertices > nv;
    if edge_points {
        for e in 0..ne as u32 {
            let ce = cut_topo.edge(topo.edge_half_edge(e)?)?;
            set(dst, nv + e as usize, get(src, n_cut + ce as usize)?)?;
        }
    }
    if sizes.vertices == nv + ne + nf {
        for f in 0..nf {
            set(dst, nv + ne + f, get(src, n_cut + cut_ne + f)?)?;
        }
    }
    // A corner of an approximating scheme stays (the boundary rules keep those on a curve;
    // this keeps those in a smooth region: a corner tag there; `cut_edges` unmarks a corner
    // whose sharp edges were all given up as darts).
    if matches!(scheme, Scheme::Loop | Scheme::CatmullClark) {
        for v in 0..nv {
            if get(corner, v)? != 0 {
                set(dst, v, topo.position(v as u32)?)?;
            }
        }
    }
    report.first_fallback = rename_output(report.first_fallback, topo, &cut_topo, copy_of)?;
    report.first_guarded = rename_output(report.first_guarded, topo, &cut_topo, copy_of)?;
    Ok((sizes, report))
}

/// Marks in `cut` the edges the step cuts along, counts them per vertex in `count`, marks
/// the corners in `corner` and returns whether there is a cut edge.
///
/// An interior edge is cut when it is sharp at this level, unless it ends at a dart: an
/// interior vertex with one cut edge gives it up, which may leave the vertex at its other
/// end a dart in turn (module docs) — followed along the chain at once, so the result does
/// not depend on the order the vertices are visited in.
///
/// A corner is a vertex tagged as one, or one where three or more sharp edges meet,
/// boundary edges counted, **before** the darts are given up: the classification of the
/// linear rules (OpenSubdiv's), so a vertex that is a corner there is one here, even when a
/// chain through it ends at a dart — unless every chain through it does: an interior vertex
/// left with no cut edge and no corner tag is smooth (module docs).
fn cut_edges(
    topo: &Topology<'_, '_>,
    sh: &Sharpness<'_>,
    cut: &mut [u32],
    count: &mut [u32],
    corner: &mut [u32],
) -> Result<bool> {
    count.fill(0);
    for e in 0..topo.num_edges() as u32 {
        let s = f32::from_bits(get(sh.edges, e as usize)?);
        let c = !topo.is_boundary_edge(e)? && sharp(s);
        set(cut, e as usize, u32::from(c))?;
        if c {
            let (a, b) = topo.edge_vertices(e)?;
            for v in [a, b] {
                set(count, v as usize, get(count, v as usize)? + 1)?;
            }
        }
    }
    for v in 0..topo.num_vertices() as u32 {
        let n = get(count, v as usize)?;
        let meets = n + if topo.is_boundary_vertex(v)? { 2 } else { 0 };
        let ends = n >= 1 && meets >= 3;
        set(corner, v as usize, u32::from(ends || sharp(sh.vertex(v)?)))?;
    }
    for v in 0..topo.num_vertices() as u32 {
        let mut u = v;
        while get(count, u as usize)? == 1 && !topo.is_boundary_vertex(u)? {
            let s = topo
                .star(u)
                .find(|s| get(cut, s.edge as usize) == Ok(1))
                .ok_or(internal())?;
            set(cut, s.edge as usize, 0)?;
            set(count, u as usize, 0)?;
            let w = s.neighbour as usize;
            set(count, w, get(count, w)?.checked_sub(1).ok_or(internal())?)?;
            u = s.neighbour;
        }
    }
    // An interior corner whose sharp edges were all given up (every chain through it ended
    // at a dart) and that carries no corner tag is a smooth vertex: no crease ends there any
    // more, and a vertex kept in place inside a smooth Möbius surface makes a spike that
    // folds the faces around it (module docs).
    for v in 0..topo.num_vertices() as u32 {
        if get(corner, v as usize)? != 0
            && get(count, v as usize)? == 0
            && !sharp(sh.vertex(v)?)
            && !topo.is_boundary_vertex(v)?
        {
            set(corner, v as usize, 0)?;
        }
    }
    Ok(count.iter().any(|&c| c > 0))
}

/// Splits every vertex with cut edges into one copy per sector: copy 0 is the vertex itself,
/// the others are numbered after the level's vertices in vertex order. Writes the original
/// of every cut vertex into `copy_of`, the cut level's corners into `cut_idx`; returns the
/// number of cut vertices.
///
/// The sector of the face after spoke `j` (star order, [`Topology::star`]) is the number of
/// cut spokes among spokes `1..=j`: the faces before the first cut spoke of a closed star
/// join the last sector (modulo the `c` cuts); an open star's first spoke is a boundary
/// edge, so its `c` cuts make `c + 1` sectors.
fn split_vertices(
    topo: &Topology<'_, '_>,
    cut: &[u32],
    count: &[u32],
    copy_of: &mut [u32],
    cut_idx: &mut [u32],
) -> Result<usize> {
    let nv = topo.num_vertices();
    for (d, &s) in cut_idx.iter_mut().zip(topo.mesh().indices) {
        *d = s;
    }
    let mut next = nv;
    for v in 0..nv as u32 {
        set(copy_of, v as usize, v)?;
        let c = get(count, v as usize)?;
        let open = topo.is_boundary_vertex(v)?;
        let sectors = if open { c + 1 } else { c };
        if sectors < 2 {
            continue;
        }
        let base = next;
        for _ in 1..sectors {
            set(copy_of, next, v)?;
            next += 1;
        }
        let mut k: u32 = 0;
        for (j, s) in topo.star(v).enumerate() {
            if j > 0 && get(cut, s.edge as usize)? == 1 {
                k += 1;
            }
            if s.face == NONE {
                continue;
            }
            // `checked_rem`: `c ≥ 2` here (a closed star with fewer cuts has one sector),
            // but the panicking `%` would link a panic path into every export.
            let sector = if open {
                k
            } else {
                k.checked_rem(c).ok_or(internal())?
            };
            let copy = if sector == 0 {
                v
            } else {
                (base + sector as usize - 1) as u32
            };
            set(cut_idx, s.half_edge as usize, copy)?;
        }
    }
    Ok(next)
}

/// The uncut level's output vertex of the cut step's output vertex `i` (vertex copies to
/// their vertex, edge points to their edge's, face points unchanged); [`crate::NO_ELEMENT`]
/// stays.
fn rename_output(
    i: u32,
    topo: &Topology<'_, '_>,
    cut_topo: &Topology<'_, '_>,
    copy_of: &[u32],
) -> Result<u32> {
    if i == crate::error::NO_ELEMENT {
        return Ok(i);
    }
    let i = i as usize;
    let (nv, ne) = (topo.num_vertices(), topo.num_edges());
    let (cv, ce) = (cut_topo.num_vertices(), cut_topo.num_edges());
    let r = if i < cv {
        get(copy_of, i)? as usize
    } else if i < cv + ce {
        let h = cut_topo.edge_half_edge((i - cv) as u32)?;
        nv + topo.edge(h)? as usize
    } else {
        nv + ne + (i - cv - ce)
    };
    Ok(r as u32)
}

/// [`rename_output`] of the element an error of the cut step names, for the errors that
/// name an output vertex ([`Status::FallbackInStrictMode`], [`Status::NumericalFailure`]);
/// other errors keep theirs.
fn rename_error(
    e: Error,
    topo: &Topology<'_, '_>,
    cut_topo: &Topology<'_, '_>,
    copy_of: &[u32],
) -> Error {
    if !matches!(
        e.status,
        Status::FallbackInStrictMode | Status::NumericalFailure
    ) {
        return e;
    }
    match rename_output(e.element, topo, cut_topo, copy_of) {
        Ok(i) => Error { element: i, ..e },
        Err(err) => err,
    }
}
